// A dmpscope worker: its own instance of the app's wasm module, computing
// landscape tiles for the page (app/src/web/pool.rs is the page's side,
// app/src/web/worker.rs what this calls). The page's first message hands
// over its compiled WebAssembly.Module, so nothing is fetched or compiled
// twice; every later message waits for that instance.
import init, * as dmpscope from "./dmpscope.js";

let ready = null;

self.onmessage = async (event) => {
  const m = event.data;
  if (m.kind === "init") {
    ready = init({ module_or_path: m.module });
  }
  try {
    await ready;
  } catch (e) {
    self.postMessage({ kind: "dead", error: "the module did not start: " + e });
    return;
  }
  try {
    switch (m.kind) {
      case "init":
        break;
      case "model":
        dmpscope.dmpscope_worker_model(m.model, m.json);
        break;
      case "grid":
        dmpscope.dmpscope_worker_grid(m.generation, m.model, m.grid);
        break;
      case "forget":
        dmpscope.dmpscope_worker_forget(m.generation);
        break;
      case "tile": {
        const values = dmpscope.dmpscope_worker_tile(m.generation, m.points);
        self.postMessage({ kind: "tile", generation: m.generation, tile: m.tile, values }, [values.buffer]);
        break;
      }
      default:
        throw new Error("unknown message " + m.kind);
    }
  } catch (e) {
    self.postMessage({ kind: "error", generation: m.generation, tile: m.tile, error: String(e) });
  }
};
