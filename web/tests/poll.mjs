// The app's state as the tools read it (`window.dmpscope_state`, the
// build's `testing` feature), a wait for it, and a file made in the page to
// drop on it: shared by slow_frame.mjs, hostile_probe.mjs and large.mjs.
import { readFile } from "node:fs/promises";
import { basename } from "node:path";

/** The app's state on `page` (null before its first frame). */
export function stateOf(page) {
  return page.evaluate(() => (window.dmpscope_state ? JSON.parse(window.dmpscope_state()) : null));
}

/** Polls `page`'s state every `every` ms until `predicate` holds (then
 * returns the state), throwing after `ms`. */
export async function until(page, predicate, ms, every = 10) {
  const start = Date.now();
  for (;;) {
    const s = await stateOf(page);
    if (s && predicate(s)) return s;
    if (Date.now() - start > ms) throw new Error("timed out");
    await page.waitForTimeout(every);
  }
}

/** Makes the file at `path` in `page` as `window.__hostile` (a `File`),
 * and reads it once there, so that the browser holds its bytes (a blob
 * made in the page reaches the browser's process in the background) as it
 * holds a file dropped from the disk: a drop's clock then counts the app,
 * not the copy of the bytes into the page. */
export async function fileInPage(page, path) {
  const b64 = (await readFile(path)).toString("base64");
  await page.evaluate(async ([b64, name]) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    window.__hostile = new File([bytes], name);
    await window.__hostile.arrayBuffer();
  }, [b64, basename(path)]);
}
