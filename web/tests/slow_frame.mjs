// Where the page's slowest frame goes while the landscape computes: a tool,
// not a test. It moves the pointer over the window (every move asks for a
// frame, as in browser.mjs), times every requestAnimationFrame callback and
// every WebGL2 call, and profiles the page's thread (Chromium's CPU
// profiler over CDP) and records Chromium's trace (CDP Tracing). For every
// callback over 100 ms it prints the WebGL calls over 3 ms and the
// profile's samples inside it by function and by stack (what the page's
// work was); then, from the trace, every task of the page's main thread
// over 100 ms with its wall time and its thread time (the CPU the thread
// got): a task of 170 ms wall and 50 ms thread time waited for a core
// (docs/browser.md).
//
// Usage: web/build.sh --testing && (cd web/tests && node slow_frame.mjs)
// HIDE=mask leaves parts of the window out from the first frame
// (window.dmpscope_hide's bits, app/src/gui/app.rs `part`); JSFLAGS passes
// V8 flags (e.g. --no-wasm-lazy-compilation); DEPTH sets the stacks' depth;
// INCL=pattern lists the functions matching it by total time; SLOW_MS sets
// the callbacks looked into (over 100 ms).
import { serve, launch } from "./serve.mjs";
import { until as untilOn } from "./poll.mjs";
import { mkdtemp, rm } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const { server, url } = await serve(join(here, "..", "dist"));
const profileDir = await mkdtemp(join(tmpdir(), "dmpscope-slow-frame-"));
const context = await launch(profileDir, process.env.JSFLAGS ? [`--js-flags=${process.env.JSFLAGS}`] : []);
try {
  const page = context.pages()[0] ?? (await context.newPage());

  // Every WebGL2 call over 3 ms, and every animation-frame callback over
  // 100 ms, each followed by a call of __SLOW_MARK, a 3 ms busy wait the
  // profile shows by name: the anchor of that callback's window.
  await page.addInitScript((SLOW_MS) => {
    window.__gl_slow = [];
    window.__slow_frames = [];
    const proto = WebGL2RenderingContext.prototype;
    for (const name of Object.getOwnPropertyNames(proto)) {
      const d = Object.getOwnPropertyDescriptor(proto, name);
      if (!d || typeof d.value !== "function") continue;
      const f = d.value;
      proto[name] = function (...args) {
        const t = performance.now();
        const r = f.apply(this, args);
        const dt = performance.now() - t;
        if (dt > 3) window.__gl_slow.push([Math.round(t), name, Math.round(dt)]);
        return r;
      };
    }
    window.__SLOW_MARK = function __SLOW_MARK() {
      const t = performance.now();
      while (performance.now() - t < 3) { /* the profile's anchor */ }
    };
    const raf = window.requestAnimationFrame.bind(window);
    window.requestAnimationFrame = (cb) => raf((ts) => {
      const t = performance.now();
      cb(ts);
      const dt = performance.now() - t;
      if (dt > SLOW_MS) {
        window.__slow_frames.push([t, dt]);
        window.__SLOW_MARK();
      }
    });
  }, Number(process.env.SLOW_MS ?? 100));

  const cdp = await context.newCDPSession(page);
  await cdp.send("Profiler.enable");
  await cdp.send("Profiler.setSamplingInterval", { interval: 200 });
  await cdp.send("Profiler.start");
  const events = [];
  cdp.on("Tracing.dataCollected", (e) => events.push(...e.value));
  const traced = new Promise((r) => cdp.once("Tracing.tracingComplete", r));
  await cdp.send("Tracing.start", { categories: "toplevel,disabled-by-default-devtools.timeline", transferMode: "ReportEvents" });
  const until = (predicate, ms) => untilOn(page, predicate, ms);
  await page.goto(url);
  await until((s) => s.frames >= 1, 20000);
  const hide = Number(process.env.HIDE ?? 0);
  if (hide) await page.evaluate((m) => window.dmpscope_hide(m), hide);
  let moving = true;
  const pointer = (async () => {
    for (let i = 0; moving; i++) await page.mouse.move(900 + (i % 2) * 30, 500);
  })();
  await until((s) => s.landscape.total > 0 && s.landscape.done === s.landscape.total, 60000);
  moving = false;
  await pointer.catch(() => {});
  const done = await until((s) => s.optimum !== null, 30000);
  const pageSide = await page.evaluate(() => ({ frames: window.__slow_frames, gl: window.__gl_slow }));
  const { profile } = await cdp.send("Profiler.stop");
  await cdp.send("Tracing.end");
  await traced;

  const byId = new Map(profile.nodes.map((n) => [n.id, n]));
  const parent = new Map();
  for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
  let clock = profile.startTime;
  const times = profile.timeDeltas.map((d) => (clock += d));
  const name = (id) => byId.get(id)?.callFrame.functionName || "(anonymous)";
  // Whether a sample is inside __SLOW_MARK (anywhere in its stack: a
  // sample may land in the performance.now it calls).
  const marked = (id) => {
    for (let x = id; x !== undefined; x = parent.get(x)) if (name(x) === "__SLOW_MARK") return true;
    return false;
  };
  // The first sample of each run of marks, one run per slow callback.
  const marks = [];
  profile.samples.forEach((id, i) => {
    if (marked(id) && (i === 0 || !marked(profile.samples[i - 1]))) marks.push(i);
  });
  // The profiler's nominal interval (0.2 ms) per sample.
  const ms = (count) => count * 0.2;
  const top = (m, k) => [...m.entries()].sort((a, b) => b[1] - a[1]).slice(0, k);

  console.log(`landscape ${done.landscape.elapsed_ms / 1000} s, longest frame interval while computing ${Math.round(done.longest_frame_ms_computing)} ms`);
  console.log(`frames while computing [interval, egui CPU, app ui] ms: ${JSON.stringify(done.frame_log_computing.slice(0, 8).map((r) => r.map(Math.round)))}`);
  if (marks.length !== pageSide.frames.length) {
    console.log(`${pageSide.frames.length} slow callbacks but ${marks.length} marks in the profile: no attribution`);
  }
  pageSide.frames.forEach(([at, wall], f) => {
    console.log(`\nanimation-frame callback of ${wall.toFixed(1)} ms at ${Math.round(at)} ms from navigation`);
    const gl = pageSide.gl.filter(([t]) => t >= at && t <= at + wall);
    console.log(`  WebGL calls over 3 ms inside it: ${JSON.stringify(gl)}`);
    if (marks.length !== pageSide.frames.length) return;
    const end = times[marks[f]];
    const start = end - wall * 1000;
    const self = new Map();
    const stacks = new Map();
    const incl = new Map();
    let n = 0;
    for (let i = 0; i < profile.samples.length; i++) {
      if (times[i] < start || times[i] >= end) continue;
      n++;
      const id = profile.samples[i];
      self.set(name(id), (self.get(name(id)) ?? 0) + 1);
      const stack = [];
      for (let x = id; x !== undefined; x = parent.get(x)) stack.push(name(x));
      for (const fn of new Set(stack)) incl.set(fn, (incl.get(fn) ?? 0) + 1);
      const key = stack.reverse()
        .filter((fn) => fn !== "(root)" && !fn.startsWith("wasm_bindgen"))
        .slice(0, Number(process.env.DEPTH ?? 12)).join(" > ");
      stacks.set(key, (stacks.get(key) ?? 0) + 1);
    }
    console.log(`  samples inside it: ${ms(n).toFixed(1)} ms of ${wall.toFixed(1)} ms wall (at the profiler's nominal 0.2 ms a sample; the trace's thread time below is the CPU it got)`);
    console.log("  by self time:");
    for (const [k, v] of top(self, 12)) console.log(`    ${ms(v).toFixed(1).padStart(6)} ms  ${k.slice(0, 140)}`);
    // INCL: a pattern; the functions matching it by total time (their
    // callees included).
    if (process.env.INCL) {
      const re = new RegExp(process.env.INCL);
      console.log(`  by total time (${process.env.INCL}):`);
      for (const [k, v] of top(new Map([...incl].filter(([k]) => re.test(k))), 40)) console.log(`    ${ms(v).toFixed(1).padStart(6)} ms  ${k.slice(0, 140)}`);
    }
    console.log("  by stack (innermost frames shown):");
    for (const [k, v] of top(stacks, 6)) console.log(`    ${ms(v).toFixed(1).padStart(6)} ms  ${k.slice(-240)}`);
  });
  // The page's main thread in the trace, and its tasks over 100 ms: wall
  // time against thread time.
  // (Each renderer has one; the page's is the one with long tasks.)
  const mains = events.filter((e) => e.ph === "M" && e.name === "thread_name" && e.args?.name === "CrRendererMain");
  console.log("\nmain-thread tasks over 100 ms (trace), wall ms / thread ms:");
  for (const m of mains) {
    const tasks = events.filter((e) => e.pid === m.pid && e.tid === m.tid && e.ph === "X" &&
      e.name === "ThreadControllerImpl::RunTask" && e.dur > 100_000);
    if (tasks.length === 0) continue;
    const fmt = (us) => (us === undefined ? "?" : (us / 1000).toFixed(1));
    console.log(`  renderer ${m.pid}: ${tasks.map((t) => `${fmt(t.dur)} / ${fmt(t.tdur)}`).join(", ")}`);
  }
} finally {
  await context.close();
  server.close();
  await rm(profileDir, { recursive: true, force: true });
}
