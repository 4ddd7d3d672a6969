// A dmpscope worker: its own instance of the app's wasm module, computing
// landscape tiles, the diagnostics' resampled extractions and RL runs for
// the page (app/src/web/transport.rs is the page's side of the messages,
// the session's workers.rs what hands the pieces out, app/src/web/worker.rs
// what this calls). The page's first message hands
// over its compiled WebAssembly.Module, so nothing is fetched or compiled
// twice; every later message waits for that instance.
import init, * as dmpscope from "./dmpscope.js";

let ready = null;

// Tiles and parts wait in a queue and are computed one per task, so that a
// message that comes while they wait is seen between two of them: a
// "forget" drops the queued pieces of its generation (the page hands out
// many at once so that the worker keeps computing while the page draws).
const queue = [];
const pump_channel = new MessageChannel();
let pumping = false;

function schedule() {
  if (!pumping && queue.length > 0) {
    pumping = true;
    pump_channel.port2.postMessage(null);
  }
}

pump_channel.port1.onmessage = () => {
  pumping = false;
  const m = queue.shift();
  if (m !== undefined) {
    try {
      const values = m.kind === "tile"
        ? dmpscope.dmpscope_worker_tile(m.generation, m.payload)
        : dmpscope.dmpscope_worker_part(m.generation, m.payload);
      self.postMessage({ kind: "answer", generation: m.generation, piece: m.piece, values }, [values.buffer]);
    } catch (e) {
      self.postMessage({ kind: "error", generation: m.generation, piece: m.piece, error: String(e) });
    }
  }
  schedule();
};

// Trains an RL run in ~20 ms slices, letting messages (tiles, forget) in
// between; posts an update after every iteration and the last one.
function pump(generation, piece) {
  let out;
  try {
    out = dmpscope.dmpscope_worker_run_step(generation, piece, 20);
  } catch (e) {
    self.postMessage({ kind: "error", generation, piece, error: String(e) });
    return;
  }
  if (out === undefined) return; // the page forgot this generation
  if (out !== "") {
    const last = out[0] === "L";
    self.postMessage({ kind: last ? "answer" : "progress", generation, piece, json: out.slice(1) });
    if (last) return;
  }
  setTimeout(() => pump(generation, piece), 0);
}

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
        dmpscope.dmpscope_worker_model(m.model, m.bytes);
        break;
      case "grid":
        dmpscope.dmpscope_worker_grid(m.generation, m.model, m.grid);
        break;
      case "diag":
        dmpscope.dmpscope_worker_diag(m.generation, m.model, m.grid, m.k);
        break;
      case "rl":
        dmpscope.dmpscope_worker_rl(m.generation, m.model, m.request);
        break;
      case "run":
        pump(m.generation, m.piece);
        break;
      case "forget":
        for (let i = queue.length - 1; i >= 0; i--) {
          if (queue[i].generation === m.generation) queue.splice(i, 1);
        }
        dmpscope.dmpscope_worker_forget(m.generation);
        break;
      case "tile":
      case "part":
        queue.push(m);
        schedule();
        break;
      default:
        throw new Error("unknown message " + m.kind);
    }
  } catch (e) {
    self.postMessage({ kind: "error", generation: m.generation, piece: m.piece, error: String(e) });
  }
};
