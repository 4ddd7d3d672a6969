// Profiles the page's main thread while the landscape computes: Chromium's
// CPU profiler over CDP, self time aggregated by function (wasm functions
// keep their names). A tool for finding where the page's frames go, not a
// test: `web/build.sh --testing && (cd web/tests && node profile.mjs)`.
import { chromium } from "playwright-core";
import { serve } from "./serve.mjs";
import { mkdtemp } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const dist = join(here, "..", "dist");
const { server, url } = await serve(dist);
const profileDir = await mkdtemp(join(tmpdir(), "dmpscope-profile-"));
const context = await chromium.launchPersistentContext(profileDir, {
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  headless: true,
  viewport: { width: 1280, height: 800 },
  args: ["--no-sandbox", "--disable-background-networking", "--disable-component-update",
    "--disable-sync", "--disable-quic", "--no-first-run"],
});
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
await context.close();
server.close();
