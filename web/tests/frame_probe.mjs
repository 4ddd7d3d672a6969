// What one frame of the page costs with no worker computing: after the
// landscape, the optimum and the diagnostics, it prints the browser's own
// requestAnimationFrame interval when idle, the time per frame with each
// part of the window left out in turn (frames back to back), the app's
// time per frame while the pointer moves over the central panel, and the
// trace slices (Chromium's tracing over CDP) that took the most time, per
// process. Measured here (docs/browser.md): a frame takes ~125 ms, the
// renderer waiting in GLES2::ReadPixels for the GPU process to run the
// frame's WebGL commands on SwiftShader, where every pixel egui fills runs
// its whole shader (both sides of its texture-filtering branch).
// TRACE_CATS sets the trace's categories, TRACE_DUMP=file writes the
// trace's events there (and skips the parts).
//
// Usage: web/build.sh --testing && (cd web/tests && node frame_probe.mjs)
import { serve, launch } from "./serve.mjs";
import { mkdtemp, rm } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const { server, url } = await serve(join(here, "..", "dist"));
const profile = await mkdtemp(join(tmpdir(), "dmpscope-probe-"));
const context = await launch(profile);
try {
  const page = context.pages()[0] ?? (await context.newPage());
  const state = () => page.evaluate(() => (window.dmpscope_state ? JSON.parse(window.dmpscope_state()) : null));
  await page.goto(url);
  const start = Date.now();
  for (;;) {
    const hooked = await page.evaluate(() => typeof window.dmpscope_state === "function");
    if (!hooked && Date.now() - start > 20000) {
      throw new Error("no window.dmpscope_state after 20 s: build with web/build.sh --testing");
    }
    const s = hooked ? await state() : null;
    if (s && s.landscape?.total > 0 && s.landscape.done === s.landscape.total && s.optimum && s.diagnostics && s.diagnostics.done === s.diagnostics.total) break;
    if (Date.now() - start > 60000) throw new Error("no landscape after 60 s");
    await page.waitForTimeout(50);
  }
  await page.waitForTimeout(1000);
  const raf = await page.evaluate(() => new Promise((done) => {
    const t = [];
    const tick = (ts) => { t.push(ts); if (t.length < 30) requestAnimationFrame(tick); else done(t); };
    requestAnimationFrame(tick);
  }));
  const gaps = raf.slice(1).map((v, i) => v - raf[i]).sort((a, b) => a - b);
  console.log(`requestAnimationFrame when the app draws nothing: median ${gaps[gaps.length >> 1].toFixed(1)} ms`);
  // What each part of the frame costs: frames drawn back to back (the
  // app asks for the next at once) over five seconds with that part left
  // out (window.dmpscope_hide's bits: app/src/gui/app.rs, mod part).
  const CONTINUOUS = 1 << 7;
  const perFrame = async () => {
    const f0 = (await state()).frames;
    const t0 = Date.now();
    await page.waitForTimeout(5000);
    return (Date.now() - t0) / Math.max(1, (await state()).frames - f0);
  };
  const panels = ["the top bar", "the side panel", "the plots panel", "the table panel", "the central panel"];
  const parts = [
    ["nothing left out", 0],
    ...panels.map((p, i) => [p, 1 << i]),
    ["the 3D view's drawing", (1 << 8) | (1 << 6)],
    ["nothing left out (3D view back)", 1 << 8],
    ["every panel's content", 31],
    ["every panel (a label only)", 1 << 5],
  ];
  for (const [name, mask] of process.env.TRACE_DUMP ? [] : parts) {
    await page.evaluate((m) => window.dmpscope_hide(m), mask | CONTINUOUS);
    await page.waitForTimeout(300);
    console.log(`ms per frame, ${name.startsWith("nothing") ? name : `without ${name}`}: ${(await perFrame()).toFixed(0)}`);
  }
  await page.evaluate(() => window.dmpscope_hide(0));
  const client = await context.newCDPSession(page);
  const events = [];
  client.on("Tracing.dataCollected", (e) => events.push(...e.value));
  const traced = new Promise((r) => client.once("Tracing.tracingComplete", r));
  await client.send("Tracing.start", { categories: process.env.TRACE_CATS ?? "gpu,viz,cc,toplevel,benchmark", transferMode: "ReportEvents" });
  const f0 = (await state()).frames;
  const t0 = Date.now();
  for (let i = 0; i < 60; i++) {
    await page.mouse.move(600 + (i % 20) * 5, 400 + (i % 7) * 3);
    await page.waitForTimeout(16);
  }
  const frames = (await state()).frames - f0;
  const ms = Date.now() - t0;
  await client.send("Tracing.end");
  await traced;
  console.log(`app frames while the pointer moves: ${frames} in ${ms} ms, ${(ms / Math.max(1, frames)).toFixed(0)} ms per frame`);
  const total = new Map();
  for (const e of events) {
    if (e.ph === "X" && e.dur) total.set(`${e.name} (pid ${e.pid})`, (total.get(`${e.name} (pid ${e.pid})`) ?? 0) + e.dur);
  }
  if (process.env.TRACE_DUMP) { (await import("node:fs")).writeFileSync(process.env.TRACE_DUMP, JSON.stringify(events)); }
  console.log("trace slices with the most time (nested slices count in their parents too):");
  for (const [name, us] of [...total.entries()].sort((a, b) => b[1] - a[1]).slice(0, 15)) {
    console.log(`${(us / 1000).toFixed(0).padStart(8)} ms  ${name}`);
  }
} finally {
  await context.close();
  server.close();
  await rm(profile, { recursive: true, force: true });
}
