#!/usr/bin/env python3
"""Write input.json: 3 synthetic hand-tracker demos of one 3-D point-to-point reach.

Deterministic: numpy default_rng(7). Stamps are integer nanoseconds at a large
epoch (~1.7e18 ns); ~90 Hz with ~1 ms Gaussian jitter; durations 1.0-1.5 s;
reach 0.3-0.5 m with a small arc (minimum-jerk profile), ~0.5 mm noise, rest at
both ends.

Edge cases planted on purpose:
  * demo_b: one duplicated stamp (the second message, later in file order,
    has a different position; the method keeps the FIRST in file order).
  * demo_c: two adjacent samples swapped in the list (stable sort by time
    restores them).
"""
import json
import os

import numpy as np

EPOCH_NS = 1_700_000_000_123_456_789


def min_jerk(tau):
    tau = np.clip(tau, 0.0, 1.0)
    return 10 * tau**3 - 15 * tau**4 + 6 * tau**5


def make_demo(rng, epoch_ns, start, goal, arc_dir):
    duration = rng.uniform(1.0, 1.5)              # total incl. rests
    rest0 = rng.uniform(0.08, 0.15)
    rest1 = rng.uniform(0.08, 0.15)
    move = duration - rest0 - rest1
    n = int(np.floor(duration * 90.0)) + 1
    nominal = np.arange(n) / 90.0
    jitter = np.clip(rng.normal(0.0, 1e-3, n), -3e-3, 3e-3)
    jitter[0] = 0.0
    t = nominal + jitter                          # strictly increasing (|jitter| <= 3 ms)
    stamps = [epoch_ns + int(round(tk * 1e9)) for tk in t]
    arc_amp = rng.uniform(0.02, 0.05)
    warp = rng.uniform(-0.08, 0.08)               # small per-demo time warp
    tau = np.clip((t - rest0) / move, 0.0, 1.0)
    tau = np.clip(tau + warp * tau * (1 - tau), 0.0, 1.0)
    s = min_jerk(tau)
    pos = start[None, :] + s[:, None] * (goal - start)[None, :] \
        + (arc_amp * np.sin(np.pi * s))[:, None] * arc_dir[None, :]
    pos = pos + rng.normal(0.0, 0.5e-3, pos.shape)
    return stamps, pos


def main():
    rng = np.random.default_rng(7)
    start_nom = np.array([0.42, -0.18, 0.25])
    direction = rng.normal(size=3)
    direction /= np.linalg.norm(direction)
    arc_dir = np.cross(direction, [0.0, 0.0, 1.0])
    arc_dir /= np.linalg.norm(arc_dir)
    demos = []
    offsets_ns = [0, 7_345_678_901, 15_987_654_321]
    for i, name in enumerate(["demo_a", "demo_b", "demo_c"]):
        reach = rng.uniform(0.3, 0.5)
        start = start_nom + rng.normal(0.0, 0.01, 3)
        d = direction + rng.normal(0.0, 0.05, 3)
        d /= np.linalg.norm(d)
        goal = start + reach * d
        stamps, pos = make_demo(rng, EPOCH_NS + offsets_ns[i], start, goal, arc_dir)
        stamps = list(stamps)
        pos = [list(map(float, p)) for p in pos]
        if name == "demo_b":
            k = 45  # duplicate stamp, inserted right after sample k, different position
            dup = [p + 3e-3 + float(rng.normal(0.0, 0.5e-3)) for p in pos[k]]
            stamps.insert(k + 1, stamps[k])
            pos.insert(k + 1, dup)
        if name == "demo_c":
            k = 55  # swap two adjacent samples in the list (mid-motion)
            stamps[k], stamps[k + 1] = stamps[k + 1], stamps[k]
            pos[k], pos[k + 1] = pos[k + 1], pos[k]
        demos.append({"name": name, "stamps_ns": [int(s) for s in stamps], "positions": pos})
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "input.json")
    with open(out, "w") as fh:
        json.dump({"demos": demos}, fh)
    print("wrote", out)


if __name__ == "__main__":
    main()
