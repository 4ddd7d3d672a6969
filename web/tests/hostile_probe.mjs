// Where the time of a hostile file dropped on the page goes: a tool, not a
// test. With the bundled sample loaded and its landscape done, it drops
// each file of a folder (`dmpscope gen-sample --hostile DIR`) on the page
// and logs, on the page's clock, every animation frame from the drop to
// the frame whose state first names the file: when each frame's callback
// started, how long it took, and what the state said after it.
//
// Usage: web/build.sh --testing && (cd web/tests && node hostile_probe.mjs DIR [NAME...])
// (PRELOAD=FILE opens FILE with Open… first, as large.mjs opens its take.)
import { serve, launch } from "./serve.mjs";
import { fileInPage, stateOf, until as untilOn } from "./poll.mjs";
import { readdir, mkdtemp, rm } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const [dir, ...only] = process.argv.slice(2);
if (!dir) throw new Error("usage: node hostile_probe.mjs DIR [NAME...]");
const { server, url } = await serve(join(here, "..", "dist"));
const profile = await mkdtemp(join(tmpdir(), "dmpscope-hostile-"));
const context = await launch(profile);
try {
  const page = context.pages()[0] ?? (await context.newPage());
  // PROBE lines the page logs (temporary instrumentation), page clock first.
  let probes = [];
  page.on("console", (m) => { if (m.text().startsWith("PROBE ")) probes.push(m.text().slice(6)); });
  await page.addInitScript(() => {
    window.__frames = [];
    const raf = window.requestAnimationFrame.bind(window);
    window.requestAnimationFrame = (cb) => raf((ts) => {
      const t = performance.now();
      cb(ts);
      const s = window.dmpscope_state ? window.dmpscope_state() : "{}";
      window.__frames.push([t, performance.now() - t, s]);
      if (window.__frames.length > 400) window.__frames.shift();
    });
  });
  const state = () => stateOf(page);
  const until = (predicate, ms) => untilOn(page, predicate, ms, 50);
  await page.goto(url);
  await until((s) => s.landscape.total > 0 && s.landscape.done === s.landscape.total, 60000);
  if (process.env.PRELOAD) {
    // A recording opened first with Open… (as large.mjs opens its take).
    const chooser = page.waitForEvent("filechooser", { timeout: 15000 }).then((c) => ["chooser", c]);
    const overlay = page.waitForSelector("#rfd-input", { state: "attached", timeout: 15000 }).then(() => ["overlay"]);
    await page.mouse.move(105, 12);
    await page.waitForTimeout(300);
    await page.mouse.down();
    await page.mouse.up();
    const [how, fc] = await Promise.race([chooser, overlay]);
    if (how === "chooser") await fc.setFiles(process.env.PRELOAD);
    else {
      await page.setInputFiles("#rfd-input", process.env.PRELOAD);
      await page.click("button.rfd-button >> text=Ok");
    }
    chooser.catch(() => {});
    overlay.catch(() => {});
    await until((s) => !s.loading && s.raw_demos.length > 0 && s.landscape.total > 0 && s.landscape.done === s.landscape.total, 600000);
  }
  const names = (await readdir(dir)).sort().filter((n) => only.length === 0 || only.includes(n));
  for (const name of names) {
    await fileInPage(page, join(dir, name));
    const seen = (await state()).messages.length;
    probes = [];
    const dropped = await page.evaluate(() => {
      window.__frames = [];
      const dt = new DataTransfer();
      dt.items.add(window.__hostile);
      const target = document.getElementById("dmpscope_canvas");
      const t = performance.now();
      for (const type of ["dragenter", "dragover", "drop"]) {
        target.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
      }
      return t;
    });
    await until((s) => !s.loading && s.messages.slice(seen).some((m) => m.includes(name)), 20000);
    await page.waitForTimeout(300);
    const frames = await page.evaluate(() => window.__frames.map(([t, d, s]) => [t, d, JSON.parse(s)]));
    console.log(`\n${name}: dropped at ${dropped.toFixed(0)} ms`);
    for (const [t, d, s] of frames) {
      const said = s.messages.slice(seen).find((m) => m.includes(name));
      console.log(`  frame ${s.frames} at +${(t - dropped).toFixed(0)} ms, ${d.toFixed(0)} ms: loading ${s.loading}, repaint causes ${JSON.stringify(s.repaint_causes)}${said ? `, says ${said.slice(0, 80)}` : ""}`);
      if (said) break;
    }
    for (const p of probes) {
      const [t, ...rest] = p.split(" ");
      console.log(`  page +${(Number(t) - dropped).toFixed(0)} ms: ${rest.join(" ")}`);
    }
  }
} finally {
  await context.close();
  server.close();
  await rm(profile, { recursive: true, force: true });
}
