// Where the page's frames go while the landscape computes: a tool, not a
// test. Loads the page as browser.mjs does (the pointer moving, so every
// move asks for a frame), waits for the full landscape, and prints per
// frame while computing the app's own `ui` time split into its phases (the
// app's `test_hooks::mark`s: the session's update, each panel, the maps,
// the 3D view) and each heat map image made, RUNS times (default 3).
// TRACE=1 also records Chromium's trace and prints the page's
// animation-frame callbacks while the landscape computes (between the
// app's marks), each one's wall and thread (CPU) time: the whole callback
// (the app's `ui`, egui's tessellation and the WebGL calls), and the
// page's garbage collections over 1 ms.
//
// Usage: web/build.sh --testing && (cd web/tests && node phases_probe.mjs)
import { serve, launch } from "./serve.mjs";
import { until as untilOn } from "./poll.mjs";
import { mkdtemp, rm } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const { server, url } = await serve(join(here, "..", "dist"));
for (let run = 0; run < Number(process.env.RUNS ?? 3); run++) {
  const profileDir = await mkdtemp(join(tmpdir(), "dmpscope-phases-"));
  const context = await launch(profileDir, []);
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    const until = (predicate, ms) => untilOn(page, predicate, ms);
    const trace = process.env.TRACE ? await startTrace(context, page) : null;
    await page.goto(url);
    await until((s) => s.frames >= 1, 20000);
    let moving = true;
    const pointer = (async () => {
      for (let i = 0; moving; i++) await page.mouse.move(900 + (i % 2) * 30, 500);
    })();
    const done = await until((s) => s.landscape.total > 0 && s.landscape.done === s.landscape.total && s.optimum !== null, 60000);
    moving = false;
    await pointer.catch(() => {});
    console.log(`run ${run}: work ms ${JSON.stringify(done.page_frame_work_ms.map((v) => Math.round(v * 10) / 10))}, model frames ${JSON.stringify(done.page_frame_model_ms.map(Math.round))}`);
    console.log(`  heat map images made, ms: ${JSON.stringify(done.page_frame_phases.heatmap_build_ms.map((v) => Math.round(v * 10) / 10))}`);
    if (trace) await printTrace(page, trace);
    for (const marks of done.page_frame_phases.phases_ms) {
      let last = 0;
      const parts = marks.map(([name, m]) => { const d = m - last; last = m; return `${name} ${d.toFixed(1)}`; });
      console.log(`  ${parts.join(", ")}`);
    }
  } finally {
    await context.close();
    await rm(profileDir, { recursive: true, force: true });
  }
}
server.close();

/** Starts Chromium's trace of `page` (the timeline, V8's GC, user marks). */
async function startTrace(context, page) {
  const cdp = await context.newCDPSession(page);
  const events = [];
  cdp.on("Tracing.dataCollected", (e) => events.push(...e.value));
  await cdp.send("Tracing.start", {
    categories: "devtools.timeline,disabled-by-default-devtools.timeline,v8,blink.user_timing",
    transferMode: "ReportEvents",
  });
  return { cdp, events };
}

/** Ends the trace and prints the frames between the model's first frame
 * (a mark the page is asked to make now is the end) and the GCs. */
async function printTrace(page, { cdp, events }) {
  await page.evaluate(() => performance.mark("dmpscope-probe-done"));
  const ended = new Promise((r) => cdp.once("Tracing.tracingComplete", r));
  await cdp.send("Tracing.end");
  await ended;
  const main = events.find((e) => e.ph === "M" && e.name === "thread_name" && e.args?.name === "CrRendererMain" &&
    events.some((f) => f.pid === e.pid && f.tid === e.tid && f.name === "FireAnimationFrame"));
  if (!main) return console.log("  no page thread in the trace");
  const on = (e) => e.pid === main.pid && e.tid === main.tid;
  const frames = events.filter((e) => on(e) && e.name === "FireAnimationFrame" && e.ph === "X");
  const gcs = events.filter((e) => on(e) && e.ph === "X" && /^(MinorGC|MajorGC)$/.test(e.name) && e.dur > 1000);
  // The app's marks (test_hooks.rs): the frames that ran while the
  // landscape computed, from the one that started it.
  const mark = (name) => events.find((e) => on(e) && e.name === name)?.ts;
  const [from, to] = [mark("dmpscope-landscape-start"), mark("dmpscope-landscape-end")];
  if (from === undefined || to === undefined) return console.log("  the landscape's marks are not in the trace");
  const ms = (us) => (us / 1000).toFixed(1);
  // A mark is made at the start of the first frame that sees the change:
  // the frames counted are the one before the start's (it started the
  // landscape) to the one before the end's, as the app's `work_ms`.
  const first = frames.findIndex((f) => f.ts + f.dur >= from);
  const end = frames.findIndex((f) => f.ts + f.dur >= to);
  const during = frames.slice(Math.max(0, first - 1), end);
  console.log(`  frame callbacks while computing, wall / thread ms: ${during.map((f) => `${ms(f.dur)}/${ms(f.tdur ?? 0)}`).join(", ")}`);
  if (process.env.TRACE === "2") {
    for (const f of frames.slice(Math.max(0, first - 3), end + 2)) {
      const has = [from, to].map((t) => (t >= f.ts && t <= f.ts + f.dur ? "mark" : "")).join(" ");
      console.log(`    frame at ${ms(f.ts - from)} ms: ${ms(f.dur)}/${ms(f.tdur ?? 0)} ${has}`);
    }
  }
  console.log(`  GCs over 1 ms then: ${gcs.filter((g) => g.ts >= from && g.ts <= to).map((g) => `${g.name} ${ms(g.dur)}`).join(", ") || "none"}`);
}
