// Where the page's frames go while the landscape computes: a tool, not a
// test. Loads the page as browser.mjs does (the pointer moving, so every
// move asks for a frame), waits for the full landscape, and prints per
// frame while computing the app's own `ui` time split into its phases (the
// app's `test_hooks::mark`s: the session's update, each panel, the maps,
// the 3D view) and each heat map image made, RUNS times (default 3).
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
