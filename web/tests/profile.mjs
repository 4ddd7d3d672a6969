// Profiles the page's main thread while the landscape computes: Chromium's
// CPU profiler over CDP, self time aggregated by function (wasm functions
// keep their names). A tool for finding where the page's frames go, not a
// test: `web/build.sh --testing && (cd web/tests && node profile.mjs)`.
// It then lists the longest stretches the page's thread was busy (breaks
// shorter than GAP_MS, default 4, joined; IDLE lists the profiler's nodes
// counted as idle, default "(idle),(program),(garbage collector)") and, for
// stretch PICK (default 0, the longest), self time and stacks DEPTH deep.
import { serve, launch } from "./serve.mjs";
import { mkdtemp } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const dist = join(here, "..", "dist");
const { server, url } = await serve(dist);
const profileDir = await mkdtemp(join(tmpdir(), "dmpscope-profile-"));
const context = await launch(profileDir);
const page = context.pages()[0] ?? (await context.newPage());
const cdp = await context.newCDPSession(page);
await cdp.send("Profiler.enable");
await cdp.send("Profiler.setSamplingInterval", { interval: 200 });
await cdp.send("Profiler.start");
await page.goto(url);
const state = () => page.evaluate(() => (window.dmpscope_state ? JSON.parse(window.dmpscope_state()) : null));
for (let i = 0; i < 600; i++) {
  const s = await state();
  if (s && s.landscape.total > 0 && s.landscape.done === s.landscape.total && s.optimum) break;
  await page.waitForTimeout(20);
}
const { profile } = await cdp.send("Profiler.stop");
const byId = new Map(profile.nodes.map((n) => [n.id, n]));
const self = new Map();
const dt = profile.timeDeltas;
profile.samples.forEach((id, i) => {
  const n = byId.get(id);
  const name = n.callFrame.functionName || `(${n.callFrame.url.split("/").pop()}:${n.callFrame.lineNumber})`;
  self.set(name, (self.get(name) ?? 0) + (dt[i] ?? 0) / 1000);
});
const top = [...self.entries()].sort((a, b) => b[1] - a[1]).slice(0, Number(process.env.TOP ?? 40));
for (const [name, ms] of top) console.log(`${ms.toFixed(1).padStart(9)} ms  ${name.slice(0, 140)}`);

// The longest stretch the page's thread was busy without a break of GAP_MS
// (default 4 ms) or more (what makes the longest frame), by self time and by the
// outermost wasm function on the stack (what the app was doing).
const parent = new Map();
for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
const idle = new Set((process.env.IDLE ?? "(idle),(program),(garbage collector)").split(","));
let t = profile.startTime;
const times = dt.map((d) => (t += d));
const name = (id) => byId.get(id).callFrame.functionName;
const gapUs = Number(process.env.GAP_MS ?? 4) * 1000;
const stretches = [];
let start = -1;
for (let i = 0; i < profile.samples.length; i++) {
  const busy = !idle.has(name(profile.samples[i]));
  if (busy && start < 0) start = i;
  const gapAhead = i + 1 < times.length ? times[i + 1] - times[i] : Infinity;
  if (start >= 0 && (!busy || gapAhead >= gapUs)) {
    stretches.push([start, busy ? i : i - 1]);
    start = -1;
  }
}
const span = ([a, b]) => times[b] - times[a];
stretches.sort((x, y) => span(y) - span(x));
console.log("\nthe longest busy stretches (ms, and s after the profile started):");
for (const s of stretches.slice(0, 6))
  console.log(`  ${(span(s) / 1000).toFixed(1)} ms at ${((times[s[0]] - profile.startTime) / 1e6).toFixed(3)} s`);
const best = stretches[Number(process.env.PICK ?? 0)] ?? [0, 0];
const [b0, b1] = best;
console.log(`\nlongest busy stretch: ${((times[b1] - times[b0]) / 1000).toFixed(1)} ms, ` +
  `${((times[b0] - profile.startTime) / 1e6).toFixed(3)} s after the profile started`);
const selfIn = new Map(), outer = new Map();
for (let i = b0; i <= b1; i++) {
  const id = profile.samples[i];
  const ms = (dt[i + 1] ?? 0) / 1000;
  selfIn.set(name(id) || "(anonymous)", (selfIn.get(name(id) || "(anonymous)") ?? 0) + ms);
  // The stack from the root: the first few named frames below the event loop.
  const stack = [];
  for (let p = id; p !== undefined; p = parent.get(p)) stack.push(name(p));
  const path = stack.reverse().filter((f) => f && !idle.has(f) && f !== "(root)").slice(0, Number(process.env.DEPTH ?? 6)).join(" > ");
  outer.set(path, (outer.get(path) ?? 0) + ms);
}
console.log("by self time:");
for (const [n, ms] of [...selfIn.entries()].sort((a, b) => b[1] - a[1]).slice(0, 20))
  console.log(`${ms.toFixed(1).padStart(9)} ms  ${n.slice(0, 140)}`);
console.log("by stack (outermost frames):");
for (const [n, ms] of [...outer.entries()].sort((a, b) => b[1] - a[1]).slice(0, 20))
  console.log(`${ms.toFixed(1).padStart(9)} ms  ${n.slice(0, 200)}`);
await context.close();
server.close();
