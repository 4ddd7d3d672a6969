// dmpscope in headless Chromium (Debian's, WebGL2 on SwiftShader), driven
// with playwright-core on a page served from 127.0.0.1. Asserts what a user
// sees: the page loads without console errors, the first frame appears, the
// sample's demos are listed, a drag on the J map moves the operating point
// and the regenerated paths and Table I follow, a dropped file is loaded,
// the screenshot is not blank. Prints the figures of issue 5 and writes them
// to web/tests/out/figures.json with the screenshot.
//
// Usage: web/build.sh --testing && (cd web/tests && npm ci && node browser.mjs)
import { serve, launch, chromiumPath } from "./serve.mjs";
import { readFile, mkdtemp, mkdir, writeFile, rm } from "node:fs/promises";
import { existsSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";
import { gzipSync } from "node:zlib";
import { execFileSync } from "node:child_process";

const here = dirname(fileURLToPath(import.meta.url));
const dist = join(here, "..", "dist");
const out = join(here, "out");
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
if (!existsSync(chromiumPath)) fail(`no Chromium at ${chromiumPath}: apt install chromium`);

const { server, url } = await serve(dist);

const profile = await mkdtemp(join(tmpdir(), "dmpscope-chromium-"));
const context = await launch(profile);
const figures = {};
try {
  const page = context.pages()[0] ?? (await context.newPage());
  const errors = [];
  page.on("console", (m) => { if (process.env.VERBOSE) console.log(`console.${m.type()}: ${m.text()}`); if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", (e) => errors.push(String(e)));

  const state = () => page.evaluate(() => (window.dmpscope_state ? JSON.parse(window.dmpscope_state()) : null));
  async function until(what, predicate, timeoutMs) {
    const start = Date.now();
    for (;;) {
      const s = await state();
      if (s && predicate(s)) return s;
      if (Date.now() - start > timeoutMs) fail(`timed out waiting for ${what}: ${JSON.stringify(s)?.slice(0, 400)}`);
      await page.waitForTimeout(20);
    }
  }

  // Long tasks (> 50 ms on the main thread) are what a user feels as a
  // frozen page; the observer keeps each one's start and duration.
  await page.addInitScript(() => {
    window.__longtasks = [];
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) window.__longtasks.push([e.startTime, e.duration]);
    }).observe({ type: "longtask", buffered: true });
  });
  // A click egui sees for sure: the pointer first hovers for two frames,
  // then press and release arrive together, so they land in one frame
  // (egui measures a click's duration in frame time, and a frame under
  // SwiftShader can take longer than egui's 0.8 s click limit on a busy
  // machine).
  async function click(x, y) {
    const before = (await state()).frames;
    await page.mouse.move(x, y);
    await until("a frame", (s) => s.frames >= before + 2, 10000);
    await Promise.all([page.mouse.down(), page.mouse.up()]);
    const pressed = (await state()).frames;
    await until("a frame", (s) => s.frames >= pressed + 2, 10000);
  }

  const t0 = Date.now();
  await page.goto(url);
  await until("the first frame", (s) => s.frames >= 1, 20000);
  figures.first_frame_s = (Date.now() - t0) / 1000;
  // A user's pointer moving over the window while the landscape computes:
  // every move asks for a frame, so the frame intervals while computing are
  // what the page can draw, not only the frames the progress asks for.
  let moving = true;
  const pointer = (async () => {
    for (let i = 0; moving; i++) await page.mouse.move(900 + (i % 2) * 30, 500);
  })();
  let listed, computing, startedAt, full, finishedAt;
  try {
    listed = await until("the sample's demos", (s) => s.demos?.length > 0 && !s.loading, 20000);
    check(listed.demos.length === 8, `the planted sample's 8 demos are listed (${listed.demos[0]} ...)`);
    computing = await until("the landscape to start", (s) => s.landscape.total > 0, 20000);
    startedAt = await page.evaluate(() => performance.now());
    full = await until("the full landscape", (s) => s.landscape.total > 0 && s.landscape.done === s.landscape.total, 60000);
    finishedAt = await page.evaluate(() => performance.now());
  } finally {
    moving = false;
    await pointer.catch(() => {});
  }
  // The browser's own first paint of the canvas, from navigation (recorded
  // once the frame is presented, so read now), beside the first frame the
  // test's poll saw.
  figures.first_paint_s = await page.evaluate(
    () => (performance.getEntriesByName("first-contentful-paint")[0]?.startTime ?? NaN) / 1000);
  // The app's own clock, from the landscape's job created (the demos
  // loaded) to the last tile stored on the page; the test's polls see the
  // start and the end late (each waits for the page's thread, which waits
  // for SwiftShader's frames).
  figures.full_landscape_s = full.landscape.elapsed_ms / 1000;
  figures.full_landscape_seen_by_polls_s = (finishedAt - startedAt) / 1000;
  figures.full_landscape_from_navigation_s = (Date.now() - t0) / 1000;
  const tasks = await page.evaluate(([a, b]) => window.__longtasks.filter(([t, d]) => t + d >= a && t <= b), [startedAt, finishedAt]);
  figures.long_tasks_while_computing = tasks.length;
  figures.longest_task_ms_while_computing = Math.max(0, ...tasks.map(([, d]) => d));
  figures.longest_slice_ms = full.longest_slice_ms;
  figures.landscape_compute_s = full.compute_ms / 1000;
  figures.frames_while_computing = full.frames - computing.frames;
  void computing;
  figures.landscape_points = full.landscape.total;
  const done = await until("the optimum", (s) => s.optimum !== null, 30000);
  figures.longest_frame_interval_ms_while_computing = done.longest_frame_ms_computing;
  figures.longest_frame_interval_at = `frame ${done.longest_frame_at}, after: ${done.longest_frame_after}`;
  figures.longest_frame_cpu_ms_while_computing = done.longest_frame_cpu_ms;
  figures.longest_frame_cpu_at = done.longest_frame_cpu_after;
  // [interval before the frame, egui CPU of the frame before (logic and painting), the app's own ui time of the frame before], ms.
  figures.frame_log_while_computing = done.frame_log_computing.map((r) => r.map((v) => Math.round(v * 10) / 10));
  // The page's own main-thread work per frame while the landscape computes,
  // from the frame that starts it: the app's time inside its frame
  // callbacks (its ui, wall time), not the wait for SwiftShader.
  const work = [...done.page_frame_work_ms].sort((a, b) => a - b);
  figures.page_frame_work_frames = work.length;
  figures.page_frame_work_ms_p95 = work.length ? work[Math.min(work.length - 1, Math.floor(0.95 * work.length))] : 0;
  figures.page_frame_work_ms_max = work.length ? work[work.length - 1] : 0;
  // Of those, the frame that started the landscape (its job made: the
  // workers are given the model in the slice after that frame).
  figures.page_frame_work_start_ms = done.page_frame_work_start_ms;
  // The frame that first drew the model (before the landscape starts).
  figures.page_frame_model_ms = done.page_frame_model_ms;
  // Where each of those frames' time went (after the start frame): each
  // phase's time, ms (the app's `test_hooks::mark`s).
  figures.page_frame_phases_ms = done.page_frame_phases.phases_ms.map((r) => {
    let last = 0;
    return Object.fromEntries(r.map(([name, end]) => { const d = end - last; last = end; return [name, Math.round(d * 10) / 10]; }));
  });
  check(work.length > 0, `frames were timed while computing (${work.length})`);
  console.log(`page frame work while computing: p95 ${figures.page_frame_work_ms_p95.toFixed(1)} ms, max ${figures.page_frame_work_ms_max.toFixed(1)} ms; the frames that first drew a model: ${JSON.stringify(figures.page_frame_model_ms.map((v) => Math.round(v * 10) / 10))} ms`);
  console.log(`optimum ${JSON.stringify(done.optimum)}`);
  // The same numbers as the native build (DMPSCOPE_BIN, else target/{debug,release}).
  const repo = join(here, "..", "..");
  const bin = process.env.DMPSCOPE_BIN ??
    [join(repo, "target", "debug", "dmpscope"), join(repo, "target", "release", "dmpscope")].find(existsSync);
  if (!bin) fail("no native dmpscope binary to compare with (cargo build first)");
  const report = JSON.parse(execFileSync(bin, ["extract", join(repo, "assets", "planted8.mcap"), "--json"],
    { stdio: ["ignore", "pipe", "ignore"] }).toString());
  const native = report.optimum;
  const rel = (a, b) => Math.abs(a - b) / Math.max(Math.abs(b), 1e-300);
  const worst = Math.max(rel(done.optimum.dm, native.dm), rel(done.optimum.km, native.km), rel(done.optimum.j, native.j));
  figures.optimum_vs_native_rel = worst;
  check(worst === 0, `the browser's optimum equals the native one (relative difference ${worst.toExponential(2)})`);
  // What the demos allow (E computed in the workers): the same verdict,
  // pick and E's depth as the native CLI.
  const allowed = (await until("the verdict and the pick", (s) => s.allowed && s.allowed.pick, 30000)).allowed;
  const pickWorst = Math.max(rel(allowed.pick.dm, report.pick.dm), rel(allowed.pick.km, report.pick.km),
    rel(allowed.pick.e_sum, report.pick.e_sum), rel(allowed.e_depth + 1, report.e_depth + 1),
    rel(allowed.acceptable.fraction + 1, report.acceptable.fraction + 1));
  figures.pick_vs_native_rel = pickWorst;
  check(allowed.pick.rule === report.pick.rule && allowed.skill_mode === report.skill_mode && pickWorst === 0,
    `the browser's pick (${allowed.pick.rule}), E at it and E's depth equal the native ones (${pickWorst.toExponential(2)})`);
  // The orientation DMP (method.md section 12), integrated on the page's
  // thread for Table I: each demo's d_rot and alpha_peak at the fixed
  // gains of the paper's rows equal the native CLI's (the kernel's
  // polynomials and libm are the same code on both).
  const pageRows = (await state()).rows;
  let rotWorst = 0;
  let rotCompared = 0;
  let rotWhere = "";
  const paperRows = report.table.filter((r) => r.name === "Ours" || r.name.startsWith("Hrstc"));
  const rotExpected = paperRows.reduce((n, r) => n + r.d_rot.length + r.alpha_peak.length, 0);
  for (const nat of paperRows) {
    const here = pageRows.find((r) => r.name === nat.name);
    if (!here) fail(`Table I has no row ${nat.name} in the browser`);
    for (const key of ["d_rot", "alpha_peak"]) {
      nat[key].forEach((v, i) => {
        const r = rel(here[key][i], v);
        if (r > rotWorst) rotWhere = `${nat.name} ${key}[${i}]: ${here[key][i]} against ${v}`;
        rotWorst = Math.max(rotWorst, r);
        rotCompared++;
      });
    }
  }
  figures.orientation_vs_native_rel = rotWorst;
  check(paperRows.length === 5 && rotExpected === 5 * 2 * 8 && rotCompared === rotExpected && rotWorst === 0,
    `the browser's d_rot and alpha_peak in Table I equal the native ones (${rotCompared} values, relative difference ${rotWorst.toExponential(2)}${rotWorst > 0 ? `, largest at ${rotWhere}` : ""})`);
  // Issue 15: the landscape is computed by Web Workers, none of it on the
  // page's thread (which only moves tiles and draws).
  const cores = await page.evaluate(() => navigator.hardwareConcurrency);
  figures.workers = full.workers;
  figures.hardware_concurrency = cores;
  check(full.workers && full.workers.workers === Math.min(8, Math.max(2, cores)) && full.workers.alive === full.workers.workers,
    `${full.workers?.workers} workers for ${cores} cores, all alive`);
  check(full.workers.tiles_from_workers >= Math.ceil(full.landscape.total / 128) && full.landscape_points_here === 0,
    `the workers computed all ${full.workers.tiles_from_workers} tiles, the page none of the ${full.landscape.total} points`);

  // The diagnostics, their resampled extractions in the workers: the same
  // numbers as the native `extract --json`.
  const diagStart = Date.now();
  const framesBefore = (await state()).frames;
  const diag = await until("the diagnostics", (s) => s.diagnostics && s.diagnostics.done === s.diagnostics.total && s.diagnostics.values.bootstrap, 180000);
  figures.diagnostics_s = (Date.now() - diagStart) / 1000;
  figures.diagnostics_compute_s = diag.diagnostics.compute_ms / 1000;
  figures.diagnostics_longest_slice_ms = diag.diagnostics.longest_slice_ms;
  figures.frames_while_diagnosing = diag.frames - framesBefore;
  console.log(`repaint causes at the end of the diagnostics: ${diag.repaint_causes.join("; ")}`);
  const nd = report.diagnostics, bd = diag.diagnostics.values;
  // To the bit, values and gains alike: every transcendental function the
  // numbers go through is the same code natively and in the browser
  // (core::portable), so even the simplex's path is the same.
  const worstOf = (pairs) => Math.max(...pairs.map(([a, b]) => (a === b ? 0 : rel(a, b))));
  const values = [[bd.depth, nd.depth], [bd.k_ratio, nd.k_ratio], [bd.balanced_k, nd.balanced_k],
    [bd.s_minimum.s, nd.s_minimum.s],
    ...bd.demos.flatMap((d, i) => [[d.s_share, nd.demos[i].s_share], [d.loo.j, nd.demos[i].loo.j]])];
  const gains = [[bd.s_minimum.dm, nd.s_minimum.dm], [bd.s_minimum.km, nd.s_minimum.km],
    ...bd.demos.flatMap((d, i) => [[d.loo.dm, nd.demos[i].loo.dm], [d.loo.km, nd.demos[i].loo.km]]),
    ...[0, 1, 2].flatMap((i) => [[bd.bootstrap.dm[i], nd.bootstrap.dm[i]], [bd.bootstrap.km[i], nd.bootstrap.km[i]]])];
  const diagWorst = worstOf(values), gainWorst = worstOf(gains);
  figures.diagnostics_values_vs_native_rel = diagWorst;
  figures.diagnostics_gains_vs_native_rel = gainWorst;
  figures.diagnostics_parts_from_workers = diag.workers.parts_from_workers;
  check(diag.workers.parts_from_workers >= diag.diagnostics.total && diag.workers.alive === diag.workers.workers,
    `the workers computed the ${diag.diagnostics.total} resampled extractions (${diag.diagnostics.compute_ms.toFixed(0)} ms on the page's thread)`);
  check(bd.flat === nd.flat && bd.flat === false, "the browser says the planted sample determines the gains, as the CLI");
  check(diagWorst === 0, `the browser's diagnostic values equal the native ones (relative difference ${diagWorst.toExponential(2)})`);
  check(gainWorst === 0, `the browser's diagnostic gains equal the native ones (relative difference ${gainWorst.toExponential(2)})`);
  check(bd.bootstrap.on_edge_fraction === nd.bootstrap.on_edge_fraction && bd.bootstrap.n === nd.bootstrap.n, "the same bootstrap edge fraction");

  // RL training in a worker, as the RL panel's Train does: the same
  // learning curve as the native CLI for the same gains and seed (RL's
  // transcendental functions are portable, core::rl::math).
  const rlSteps = 2000;
  const rlStart = Date.now();
  await page.evaluate((n) => window.dmpscope_train(n, 1), rlSteps);
  const trained = await until("RL training", (s) => s.rl && s.rl.done, 120000);
  figures.rl_train_s = (Date.now() - rlStart) / 1000;
  check(!trained.rl.stopped && trained.rl.decisions === rlSteps && trained.workers.runs_from_workers >= 1,
    `a worker trained ${trained.rl.decisions} decisions (runs from workers: ${trained.workers.runs_from_workers})`);
  const rlJson = join(profile, "rl_native.json");
  execFileSync(bin, ["rl", join(repo, "assets", "planted8.mcap"), "--demo", "1", "--dm", String(trained.rl.dm),
    "--km", String(trained.rl.km), "--steps", String(rlSteps), "--seed", "1", "--out", rlJson], { stdio: "ignore" });
  const nativeRl = JSON.parse(await readFile(rlJson, "utf8"));
  const curveWorst = worstOf(trained.rl.returns.map((r, i) => [r, nativeRl.returns[i]]));
  figures.rl_returns_vs_native_rel = curveWorst;
  // PPO's transcendentals and the DMP's fit under the task are portable
  // (core::portable), so the curve is the same to the bit.
  const finalRel = rel(trained.rl.final_error, nativeRl.final_error_m);
  figures.rl_final_error_vs_native_rel = finalRel;
  check(trained.rl.returns.length === nativeRl.returns.length && curveWorst === 0,
    `the browser's learning curve equals the native one (${trained.rl.returns.length} iterations, relative difference ${curveWorst.toExponential(2)})`);
  check(finalRel === 0, `the same final error (${trained.rl.final_error} m, relative difference ${finalRel.toExponential(2)})`);

  // A new grid while the landscape computes cancels it: the workers' tiles
  // of the old grid never reach the new one, and the 128 x 128 landscape
  // computed again in the workers gives the native optimum again.
  const tilesBefore = (await state()).workers.tiles_from_workers;
  await page.evaluate(() => window.dmpscope_grid(96));
  await until("the 96 x 96 landscape to start", (s) => s.landscape.total === 96 * 96 && s.landscape.done > 0, 20000);
  await page.evaluate(() => window.dmpscope_grid(128));
  const regrid = await until("the 128 x 128 landscape again", (s) => s.landscape.total === 16384 && s.landscape.done === 16384, 60000);
  const reopt = await until("its optimum", (s) => s.optimum !== null, 30000);
  const regridWorst = Math.max(rel(reopt.optimum.dm, native.dm), rel(reopt.optimum.km, native.km), rel(reopt.optimum.j, native.j));
  check(regrid.workers.tiles_from_workers - tilesBefore >= 128 && regrid.landscape_points_here === 0 && regridWorst === 0,
    `a new grid cancelled the landscape; the workers computed the next one (${regrid.workers.tiles_from_workers - tilesBefore} tiles) and its optimum equals the native one (${regridWorst.toExponential(2)})`);

  // A drag on the J map (at 1280x800 it spans about x 382..556, y 55..230).
  const before = await state();
  await page.mouse.move(470, 150);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) {
    await page.mouse.move(470 + 5 * i, 150 - 6 * i);
    await page.waitForTimeout(30);
  }
  await page.mouse.up();
  await page.waitForTimeout(200);
  const after = await state();
  check(JSON.stringify(after.op) !== JSON.stringify(before.op), `the drag moved the operating point ${JSON.stringify(before.op)} -> ${JSON.stringify(after.op)}`);
  check(after.regen_checksum !== before.regen_checksum, "the regenerated paths followed");
  const row = (s) => s.rows.find((r) => r.name === "Operating point");
  check(row(after).dm === after.op[0] && row(after).j !== row(before).j, "Table I's operating-point row followed");

  // Playback (issue 44): the space bar plays, the cursor moves by the
  // frames' real time, the space bar pauses.
  const still = (await state()).playback;
  check(!still.playing, "playback starts paused");
  await page.keyboard.press("Space");
  const playing = await until("the playback", (s) => s.playback.playing && s.playback.t !== still.t, 10000);
  await page.waitForTimeout(700);
  const later = (await state()).playback;
  check(later.playing && later.t !== playing.playback.t,
    `the cursor moves while playing (${still.t.toFixed(3)} -> ${playing.playback.t.toFixed(3)} -> ${later.t.toFixed(3)})`);
  await page.keyboard.press("Space");
  const paused = await until("the pause", (s) => !s.playback.playing, 10000);
  await page.waitForTimeout(400);
  check((await state()).playback.t === paused.playback.t, "the space bar pauses it");

  // Compare gain sets (issue 45): two pinned sets, each drawn in the 3D
  // view for every demo and overlaid on the plots, at the gains of the
  // Table I row they name.
  await page.evaluate(() => { window.dmpscope_pin("Hrstc4"); window.dmpscope_pin("40:400"); });
  const pinned = await until("two pinned sets drawn",
    (s) => s.pins.length === 2 && s.pins.every((p) => p.paths_3d > 0) && s.plot_pin_lines > 0, 20000);
  const hrstc4 = pinned.rows.find((r) => r.name === "Hrstc4");
  check(pinned.pins[0].name === "Hrstc4" && pinned.pins[0].dm === hrstc4.dm && pinned.pins[0].km === hrstc4.km
    && pinned.pins[1].dm === 40 && pinned.pins[1].km === 400,
    `two sets pinned: ${pinned.pins.map((p) => `${p.name} (${p.dm}, ${p.km})`).join(", ")}`);
  check(pinned.pins.every((p) => p.paths_3d === pinned.pins[0].paths_3d) && pinned.plot_pin_lines >= 2,
    `their overlays drawn: ${pinned.pins.map((p) => p.paths_3d).join(" and ")} paths in the 3D view, ${pinned.plot_pin_lines} lines in the plots`);
  figures.pinned_paths_3d = pinned.pins.map((p) => p.paths_3d);

  // A file dropped on the page (the sample again, as a second file).
  const sample = (await readFile(join(here, "..", "..", "assets", "reach10.mcap"))).toString("base64");
  await page.evaluate((b64) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const dt = new DataTransfer();
    dt.items.add(new File([bytes], "dropped.mcap"));
    const target = document.getElementById("dmpscope_canvas");
    for (const type of ["dragenter", "dragover", "drop"]) {
      target.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
    }
  }, sample);
  const dropped = await until("the dropped file's demos", (s) => s.demos.length === 18 && !s.loading, 20000);
  check(dropped.demos.some((d) => d.startsWith("dropped.mcap")), "a dropped file is loaded");

  // Open… (the top bar's second button): with the click's user activation
  // rfd opens the browser's file chooser at once; the picked file's bytes
  // are loaded.
  // rfd clicks its hidden file input when the click's user activation is
  // still active (a file chooser), else it shows its own dialog (the input
  // and an Ok button): either way the picked file's bytes are loaded.
  const file = {
    name: "picked.mcap",
    mimeType: "application/octet-stream",
    buffer: await readFile(join(here, "..", "..", "assets", "reach10.mcap")),
  };
  await until("the landscape of the 18 demos", (s) => s.landscape.total > 0 && s.landscape.done === s.landscape.total && s.optimum !== null, 60000);
  const chooser = page.waitForEvent("filechooser", { timeout: 15000 }).then((c) => ["chooser", c]);
  const overlay = page.waitForSelector("#rfd-input", { state: "attached", timeout: 15000 }).then(() => ["overlay"]);
  await click(105, 12);
  const [how, fc] = await Promise.race([chooser, overlay]);
  if (how === "chooser") {
    await fc.setFiles(file);
  } else {
    await page.setInputFiles("#rfd-input", file);
    await page.click("button.rfd-button >> text=Ok");
  }
  console.log(`Open… answered with ${how === "chooser" ? "the browser's file chooser" : "rfd's dialog"}`);
  chooser.catch(() => {});
  overlay.catch(() => {});
  const picked = await until("the picked file's demos", (s) => s.demos.length === 28 && !s.loading, 20000);
  check(picked.demos.some((d) => d.startsWith("picked.mcap")), "a file picked with Open… is loaded");

  await mkdir(out, { recursive: true });
  const shot = await page.screenshot({ path: join(out, "screenshot.png") });
  const stats = await page.evaluate(async (b64) => {
    const blob = await (await fetch(`data:image/png;base64,${b64}`)).blob();
    const bitmap = await createImageBitmap(blob);
    const c = new OffscreenCanvas(bitmap.width, bitmap.height);
    const g = c.getContext("2d");
    g.drawImage(bitmap, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    const colours = new Set();
    let sum = 0, sum2 = 0;
    for (let i = 0; i < d.length; i += 4 * 7) {
      const v = d[i] + d[i + 1] + d[i + 2];
      sum += v; sum2 += v * v;
      colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
    }
    const n = d.length / (4 * 7);
    return { variance: sum2 / n - (sum / n) ** 2, colours: colours.size };
  }, shot.toString("base64"));
  check(stats.colours > 200 && stats.variance > 100, `the screenshot is not blank (${stats.colours} colours)`);
  check(errors.length === 0, `no console errors${errors.length ? ": " + errors.join(" | ") : ""}`);

  // The New target tab (right panel) and its "Run the DMP at a new target"
  // box: the selected demo runs at its own target, ending at its goal.
  const centre = ([x, y, w, h]) => [x + w / 2, y + h / 2];
  await click(...centre((await state()).buttons["New target"]));
  const tab = await until("the New target tab", (s) => s.buttons["Run at a new target"], 10000);
  await click(...centre(tab.buttons["Run at a new target"]));
  const moved = await until("the run at a new target", (s) => s.generalised?.name, 10000);
  check(!moved.generalised.error && moved.generalised.final_error < 0.01,
    `the run at a new target ends at its goal (${JSON.stringify(moved.generalised)})`);
  await page.screenshot({ path: join(out, "new_target.png") });
  // The box again (it moves to the top of the tab once on): off.
  await page.waitForTimeout(300);
  await click(...centre((await state()).buttons["Run at a new target"]));
  await until("the run switched off", (s) => s.generalised === null, 10000);

  // Settings persist in the browser's storage: a preset chosen, the page
  // reloaded, the operating point is still there.
  // "Hrstc4" in the side panel, where the app drew it last frame.
  const [bx, by, bw, bh] = (await state()).buttons.Hrstc4;
  await click(bx + bw / 2, by + bh / 2);
  await until("the Hrstc4 button's effect", (s) => s.op[0] === 4 && s.op[1] === 4, 10000);
  // The reloaded page reports 5 cores: 4 workers (one core is left to the
  // page; on this machine's 2), answering in another order, and the same
  // optimum.
  await page.addInitScript(() => Object.defineProperty(navigator, "hardwareConcurrency", { get: () => 5 }));
  await page.reload();
  const reloaded = await until("the reloaded app", (s) => s.demos?.length === 8 && !s.loading, 20000);
  check(reloaded.op[0] === 4 && reloaded.op[1] === 4, `settings survive a reload (operating point ${JSON.stringify(reloaded.op)})`);
  const five = await until("the landscape and optimum with 5 cores reported",
    (s) => s.landscape?.total === 16384 && s.landscape.done === 16384 && s.optimum, 60000);
  const fiveWorst = Math.max(rel(five.optimum.dm, native.dm), rel(five.optimum.km, native.km), rel(five.optimum.j, native.j));
  figures.optimum_5_workers_vs_native_rel = fiveWorst;
  check(five.workers.workers === 4 && five.workers.alive === 4 && five.landscape_points_here === 0 && fiveWorst === 0,
    `with ${five.workers.workers} workers the optimum equals the native one too (${fiveWorst.toExponential(2)})`);

  // A host that does not serve worker.js: every worker fails, the user is
  // told, and the page computes the landscape itself, with the same optimum.
  await page.route("**/worker.js", (route) => route.fulfill({ status: 404, body: "" }));
  await page.reload();
  const alone = await until("the landscape computed on the page",
    (s) => s.landscape?.total === 16384 && s.landscape.done === 16384 && s.optimum, 90000);
  const aloneWorst = Math.max(rel(alone.optimum.dm, native.dm), rel(alone.optimum.km, native.km), rel(alone.optimum.j, native.j));
  const told = alone.messages.filter((m) => m.includes("Web Worker"));
  figures.optimum_no_workers_vs_native_rel = aloneWorst;
  check(alone.workers.alive === 0 && alone.landscape_points_here > 0 && told.length > 0 && aloneWorst === 0,
    `without worker.js the page computes (${alone.landscape_points_here} points), says so ("${told[told.length - 1]}") and gives the same optimum (${aloneWorst.toExponential(2)})`);
  await page.unroute("**/worker.js");

  // ROS 1 bags dropped on the page: one named .bag (lz4 chunks), one
  // without a name that says what it is (bz2 chunks, known by its first
  // bytes); each gives its pose topics and names the custom type it skips.
  const bags = join(here, "..", "..", "core", "tests", "bags", "reach");
  for (const [file, name, total] of [["reach_3.bag", "vive.bag", 10], ["reach_2.bag", "upload", 12]]) {
    const b64 = (await readFile(join(bags, file))).toString("base64");
    await page.evaluate(([b64, name]) => {
      const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
      const dt = new DataTransfer();
      dt.items.add(new File([bytes], name));
      const target = document.getElementById("dmpscope_canvas");
      for (const type of ["dragenter", "dragover", "drop"]) {
        target.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
      }
    }, [b64, name]);
    const got = await until(`the dropped bag ${name}'s demos`, (s) => s.demos.length === total && !s.loading, 20000);
    check(got.demos.includes(`${name}:/vive/controller`) && got.messages.some((m) => m.includes("my_msgs/Button")),
      `a ROS 1 bag dropped on the page (${file} as ${name}) is read`);
  }

  const wasm = await readFile(join(dist, "dmpscope_bg.wasm"));
  figures.wasm_mb = wasm.length / 1e6;
  figures.wasm_gzip_mb = gzipSync(wasm, { level: 9 }).length / 1e6;
  await writeFile(join(out, "figures.json"), JSON.stringify(figures, null, 2));
  console.log(JSON.stringify(figures, null, 2));
} finally {
  await context.close();
  server.close();
  await rm(profile, { recursive: true, force: true });
}
