// Chromium's trace of the app computing its landscape: the long events of
// every process (the page, the GPU process), in time order, as
// `ms from the first event | duration ms | thread | event | args`. A tool
// for finding where the frames go, not a test:
// `web/build.sh --testing && (cd web/tests && node trace.mjs)`; MIN_MS
// (default 30) is the shortest event listed, ALL=1 lists every event name,
// not only the WebGL flushes, read-backs and frames.
import { serve, launch } from "./serve.mjs";
import { mkdtemp } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const { server, url } = await serve(join(here, "..", "dist"));
const profile = await mkdtemp(join(tmpdir(), "trace-"));
const context = await launch(profile);
const page = context.pages()[0] ?? (await context.newPage());
const cdp = await context.newCDPSession(page);
const events = [];
cdp.on("Tracing.dataCollected", (e) => events.push(...e.value));
const done = new Promise((r) => cdp.on("Tracing.tracingComplete", r));
await cdp.send("Tracing.start", { categories: "gpu,gpu.service,viz,cc,toplevel,blink,renderer.scheduler,disabled-by-default-gpu.service,disabled-by-default-devtools.timeline,v8.execute", transferMode: "ReportEvents" });
const state = () => page.evaluate(() => (window.dmpscope_state ? JSON.parse(window.dmpscope_state()) : null));
await page.goto(url);
let moving = true;
const pointer = (async () => { for (let i = 0; moving; i++) await page.mouse.move(900 + (i % 2) * 30, 500); })();
for (let i = 0; i < 1500; i++) {
  const s = await state();
  if (s && s.landscape.total > 0 && s.landscape.done === s.landscape.total && s.optimum) break;
  await page.waitForTimeout(20);
}
moving = false; await pointer.catch(() => {});
await cdp.send("Tracing.end");
await done;
const names = new Map();
for (const e of events) if (e.ph === "M" && e.name === "thread_name") names.set(`${e.pid}:${e.tid}`, e.args.name);
const t0 = Math.min(...events.filter((e) => e.ts > 0).map((e) => e.ts));
const minUs = Number(process.env.MIN_MS ?? 30) * 1000;
const shown = (e) => process.env.ALL === "1" || ["WebGL", "GLES2::ReadPixels", "ProxyMain::BeginMainFrame"].includes(e.name);
const long = events.filter((e) => e.ph === "X" && e.dur > minUs && shown(e))
  .map((e) => [((e.ts - t0) / 1000) | 0, (e.dur / 1000) | 0, names.get(`${e.pid}:${e.tid}`) ?? `${e.pid}:${e.tid}`, e.name, JSON.stringify(e.args ?? {}).slice(0, 120)]);
long.sort((a, b) => a[0] - b[0]);
for (const l of long) console.log(l.join(" | "));
await context.close(); server.close();
