// A lab-size recording in the browser: the test writes a 2 GB take (a
// tracker's poses beside a 640x480 camera, zstd chunks of 4 MiB) with the
// native `dmpscope gen-sample --lab`, opens it with Open… in headless
// Chromium and checks that its demos equal the native build's, that the
// page reads it in slices (the wasm heap and Chromium's processes grow by
// less than 512 MiB), that frames keep coming while it reads, and that
// each hostile file (`gen-sample --hostile`) dropped on the page ends in a
// message naming it within a second. Figures go to
// web/tests/out/large.json.
//
// Usage: web/build.sh --testing && cargo build && (cd web/tests && node large.mjs)
// (DMPSCOPE_BIN names the native binary; LARGE_SECONDS the take's length.)
import { serve, launch, chromiumPath } from "./serve.mjs";
import { fileInPage } from "./poll.mjs";
import { readdir, mkdtemp, mkdir, writeFile, rm, stat } from "node:fs/promises";
import { existsSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";
import { execFileSync } from "node:child_process";

const here = dirname(fileURLToPath(import.meta.url));
const repo = join(here, "..", "..");
const dist = join(here, "..", "dist");
const out = join(here, "out");
const bin = process.env.DMPSCOPE_BIN ?? join(repo, "target", "debug", "dmpscope");
const seconds = Number(process.env.LARGE_SECONDS ?? 94);
function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exitCode = 1;
  throw new Error(message);
}
function check(ok, message) {
  if (!ok) fail(message);
  console.log(`ok: ${message}`);
}
if (!existsSync(join(dist, "dmpscope_bg.wasm"))) fail(`no build in ${dist}: run web/build.sh --testing`);
if (!existsSync(bin)) fail(`no native dmpscope at ${bin}: cargo build (or DMPSCOPE_BIN)`);

// Chromium's processes' resident memory, bytes (those of this profile).
function chromiumRss(profile) {
  let total = 0;
  for (const line of execFileSync("ps", ["-eo", "rss=,args="]).toString().split("\n")) {
    if (line.includes(profile) || (line.includes("chromium") && line.includes("--type="))) {
      total += Number(line.trim().split(/\s+/)[0]) * 1024;
    }
  }
  return total;
}

const work = await mkdtemp(join(tmpdir(), "dmpscope-large-"));
const take = join(work, "take.mcap");
const hostile = join(work, "hostile");
const figures = {};
let t = Date.now();
execFileSync(bin, ["gen-sample", "--lab", String(seconds), "-o", take], { stdio: "inherit" });
const size = (await stat(take)).size;
figures.file_gb = size / 1e9;
figures.generate_s = (Date.now() - t) / 1000;
execFileSync(bin, ["gen-sample", "--hostile", hostile], { stdio: "inherit" });
t = Date.now();
const native = JSON.parse(execFileSync(bin, ["info", take, "--json"], { maxBuffer: 1 << 26 }).toString());
figures.native_read_s = (Date.now() - t) / 1000;

const { server, url } = await serve(dist);
const profile = await mkdtemp(join(tmpdir(), "dmpscope-chromium-"));
const context = await launch(profile);
try {
  const page = context.pages()[0] ?? (await context.newPage());
  // The page's clock for the hostile files: after each animation-frame
  // callback (the app's frame), whether its state answers the file the
  // test dropped last (`window.__watch`): a message naming it, or its
  // demos, with nothing loading. The first such frame's end is the answer.
  await page.addInitScript(() => {
    const raf = window.requestAnimationFrame.bind(window);
    window.requestAnimationFrame = (cb) => raf((ts) => {
      cb(ts);
      const w = window.__watch;
      if (!w || w.at !== undefined || !window.dmpscope_state) return;
      const raw = window.dmpscope_state();
      if (!raw.includes(w.name)) return;
      const s = JSON.parse(raw);
      if (!s.loading && (s.messages.slice(w.seen).some((m) => m.includes(w.name))
        || s.raw_demos.some((d) => d.name.startsWith(w.name)))) w.at = performance.now();
    });
  });
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  const state = () => page.evaluate(() => (window.dmpscope_state ? JSON.parse(window.dmpscope_state()) : null));
  async function until(what, predicate, timeoutMs, every = 20) {
    const start = Date.now();
    for (;;) {
      const s = await state();
      if (s && predicate(s)) return s;
      if (Date.now() - start > timeoutMs) fail(`timed out waiting for ${what}: ${JSON.stringify(s)?.slice(0, 400)}`);
      await page.waitForTimeout(every);
    }
  }
  async function click(x, y) {
    await page.mouse.move(x, y);
    await page.waitForTimeout(300);
    await page.mouse.down();
    await page.mouse.up();
  }
  await page.goto(url);
  await until("the sample", (s) => s.raw_demos.length > 0 && !s.loading, 60000);
  const rssBefore = chromiumRss(profile);
  const before = await state();

  // Open… the take.
  t = Date.now();
  const chooser = page.waitForEvent("filechooser", { timeout: 15000 }).then((c) => ["chooser", c]);
  const overlay = page.waitForSelector("#rfd-input", { state: "attached", timeout: 15000 }).then(() => ["overlay"]);
  await click(105, 12);
  const [how, fc] = await Promise.race([chooser, overlay]);
  if (how === "chooser") {
    await fc.setFiles(take);
  } else {
    await page.setInputFiles("#rfd-input", take);
    await page.click("button.rfd-button >> text=Ok");
  }
  chooser.catch(() => {});
  overlay.catch(() => {});
  let wasmMax = 0, heapMax = 0, rssMax = 0, sawProgress = false;
  const framesAtStart = before.frames;
  const loaded = await until("the take's demos", (s) => {
    wasmMax = Math.max(wasmMax, s.wasm_memory_bytes);
    rssMax = Math.max(rssMax, chromiumRss(profile));
    sawProgress ||= s.reading.some((r) => r.size === size && r.read > 0);
    return s.raw_demos.some((d) => d.name.startsWith("take.mcap")) && !s.loading;
  }, 600000, 250);
  heapMax = await page.evaluate(() => performance.memory?.usedJSHeapSize ?? 0);
  figures.browser_read_s = (Date.now() - t) / 1000;
  figures.wasm_memory_mb = wasmMax / 1e6;
  figures.js_heap_mb = heapMax / 1e6;
  figures.chromium_rss_growth_mb = (rssMax - rssBefore) / 1e6;
  figures.frames_while_reading = loaded.frames - framesAtStart;
  check(sawProgress, "the page shows how much of the file it has read");
  check(figures.frames_while_reading > 5, `frames keep coming while it reads (${figures.frames_while_reading})`);
  check(wasmMax < 512e6, `the wasm heap stays under 512 MiB (${figures.wasm_memory_mb.toFixed(0)} MB)`);
  check(rssMax - rssBefore < 512e6, `Chromium's processes grow by less than 512 MiB (${figures.chromium_rss_growth_mb.toFixed(0)} MB)`);
  const mine = loaded.raw_demos.filter((d) => d.name.startsWith("take.mcap"));
  check(mine.length === native.length, `as many demos as natively (${mine.length})`);
  for (const [k, d] of mine.entries()) {
    const n = native[k];
    check(d.name.endsWith(n.name.split(":").slice(1).join(":")) && d.samples === n.n_samples
      && JSON.stringify(d.first) === JSON.stringify(n.start) && JSON.stringify(d.last) === JSON.stringify(n.goal),
      `${d.name}: ${d.samples} samples, the same first and last positions as natively`);
  }

  // Each hostile file dropped on the page (once the take's landscape is
  // done: the page idle): a message naming it within a second.
  await until("the take's landscape", (s) => s.landscape.total > 0 && s.landscape.done === s.landscape.total, 300000, 250);
  const names = (await readdir(hostile)).sort();
  figures.hostile_s = {};
  // Answered later than a second after the drop on the page's clock: the
  // test fails.
  const slow = [];
  for (const name of names) {
    await fileInPage(page, join(hostile, name));
    const seen = (await state()).messages.length;
    const start = Date.now();
    await page.evaluate(([name, seen]) => {
      window.__watch = { name, seen, dropped: performance.now() };
      const dt = new DataTransfer();
      dt.items.add(window.__hostile);
      const target = document.getElementById("dmpscope_canvas");
      for (const type of ["dragenter", "dragover", "drop"]) {
        target.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
      }
    }, [name, seen]);
    const s = await until(`${name} answered`, (s) => !s.loading && (s.messages.slice(seen).some((m) => m.includes(name))
      || s.raw_demos.some((d) => d.name.startsWith(name))), 20000);
    const polled = (Date.now() - start) / 1000;
    // The page's clock: from the drop to the end of the frame that
    // answered (the test's own polls wait for the page's frames, 150-250 ms
    // each under SwiftShader, so `polled` is an upper bound).
    const secs = await page.evaluate(() => (window.__watch.at - window.__watch.dropped) / 1000);
    figures.hostile_s[name] = secs;
    figures.hostile_polled_s ??= {};
    figures.hostile_polled_s[name] = polled;
    const said = s.messages.slice(seen).find((m) => m.includes(name)) ?? "its demos";
    console.log(`${secs < 1.0 ? "ok" : "SLOW"}: ${name}: ${said.slice(0, 100)} (${secs.toFixed(2)} s; the test's polls saw it at ${polled.toFixed(2)} s)`);
    if (!(secs < 1.0)) slow.push(`${name} ${secs.toFixed(2)} s`);
  }
  check(errors.length === 0, `no page errors (${errors.join("; ").slice(0, 300)})`);
  await mkdir(out, { recursive: true });
  await writeFile(join(out, "large.json"), JSON.stringify(figures, null, 2));
  console.log(JSON.stringify(figures, null, 2));
  check(slow.length === 0, `every hostile file answered within 1 s of its drop${slow.length ? `; not: ${slow.join(", ")}` : ""}`);
} finally {
  await context.close();
  server.close();
  await rm(profile, { recursive: true, force: true });
  await rm(work, { recursive: true, force: true });
}
