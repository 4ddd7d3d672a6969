// The app's state as the tools read it (`window.dmpscope_state`, the
// build's `testing` feature), and a wait for it: shared by the tools
// slow_frame.mjs and hostile_probe.mjs.

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
