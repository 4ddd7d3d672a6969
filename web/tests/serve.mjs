// Serves web/dist on 127.0.0.1 for the browser scripts (browser.mjs, the
// tests; profile.mjs, trace.mjs, frame_probe.mjs and slow_frame.mjs, the
// tools): `const { server, url } = await serve(dist)`; and starts the
// headless Chromium they all drive: `const context = await launch(dir)`.
import { chromium } from "playwright-core";
import { createServer } from "node:http";
import { readFile } from "node:fs/promises";
import { join, extname } from "node:path";

const TYPES = {
  ".html": "text/html", ".js": "text/javascript", ".wasm": "application/wasm",
  ".png": "image/png", ".json": "application/json",
};

export async function serve(dist) {
  const server = createServer(async (req, res) => {
    const path = join(dist, decodeURIComponent(new URL(req.url, "http://x").pathname).replace(/\/$/, "/index.html"));
    try {
      const body = await readFile(path);
      res.writeHead(200, { "content-type": TYPES[extname(path)] ?? "application/octet-stream" });
      res.end(body);
    } catch {
      res.writeHead(404);
      res.end();
    }
  });
  await new Promise((r) => server.listen(0, "127.0.0.1", r));
  return { server, url: `http://127.0.0.1:${server.address().port}/` };
}

// The Chromium the scripts drive: Debian's, unless CHROMIUM names another.
export const chromiumPath = process.env.CHROMIUM ?? "/usr/bin/chromium";

// That Chromium, headless, 1280 x 800, with a fresh profile in
// `profileDir` and no background traffic; `extraArgs` are added to its
// command line.
export function launch(profileDir, extraArgs = []) {
  return chromium.launchPersistentContext(profileDir, {
    executablePath: chromiumPath,
    headless: true,
    viewport: { width: 1280, height: 800 },
    args: ["--no-sandbox", "--disable-background-networking", "--disable-component-update",
      "--disable-sync", "--disable-quic", "--no-first-run", ...extraArgs],
  });
}
