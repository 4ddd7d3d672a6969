#!/usr/bin/env python3
"""Write expected_orientation.json: method.md section 12 (the orientation DMP) on
assets/planted8.mcap with orientation.py: per demo the prepared orientation at idx and the goal;
per gain pair each demo's d_rot, alpha_peak and regenerated q at idx; the d_rot_sum grid
(12 x 12, np.logspace(-1, 3, 12) on both axes). The MCAP is decoded by hand (ROS 2
geometry_msgs/PoseStamped in little-endian CDR) as make_samples_input.py does, here with the
orientation too."""
import hashlib
import json
import os
import struct
import sys
import time

import numpy as np
import scipy

import method as m
import orientation as o

HERE = os.path.dirname(os.path.abspath(__file__))
ASSETS = os.path.join(HERE, "..", "..", "assets")
IDX = [0, 1, 2, 100, 500, 999, 1000]
PAIRS = [(10.73, 20.71), (25.0, 156.25), (2.0, 900.0)]
GRID = np.logspace(-1, 3, 12)


def pose_stamped(data):
    """(stamp_ns, [x, y, z], [qx, qy, qz, qw]) of a CDR PoseStamped (little-endian)."""
    if data[1] != 1:
        raise ValueError("expected little-endian CDR")
    body = data[4:]
    sec, nsec, n = struct.unpack_from("<iII", body, 0)
    off = 12 + n
    off += (-off) % 8
    x, y, z, qx, qy, qz, qw = struct.unpack_from("<7d", body, off)
    return sec * 1_000_000_000 + nsec, [x, y, z], [qx, qy, qz, qw]


def read(path):
    """Demos in the order of their topics sorted by name; and the file's sha256."""
    from mcap.reader import make_reader
    demos = {}
    with open(path, "rb") as fh:
        for _, channel, message in make_reader(fh).iter_messages(log_time_order=False):
            stamp, pos, quat = pose_stamped(message.data)
            d = demos.setdefault(channel.topic, dict(name=channel.topic, stamps_ns=[], log_ns=[],
                                                     positions=[], orientations=[]))
            d["stamps_ns"].append(stamp)
            d["log_ns"].append(int(message.log_time))
            d["positions"].append(pos)
            d["orientations"].append(quat)
    for d in demos.values():
        # method.md 2.1: all stamps zero -> the whole demo uses the MCAP log time
        if all(s == 0 for s in d["stamps_ns"]):
            d["stamps_ns"] = d["log_ns"]
    with open(path, "rb") as fh:
        sha = hashlib.sha256(fh.read()).hexdigest()
    return [demos[t] for t in sorted(demos)], sha


def at(arr):
    return [arr[k].tolist() for k in IDX]


def main():
    t0 = time.time()
    path = os.path.join(ASSETS, "planted8.mcap")
    demos, sha = read(path)
    preps = [o.prepare_orientation(d["stamps_ns"], d["positions"], d["orientations"], d["name"])
             for d in demos]
    t_prep = time.time() - t0
    demo_out = [dict(name=p["name"], n_samples=p["n_samples"], T=p["T"], n0=p["n0"],
                     q_raw=at(p["q_raw"]), q=at(p["q"]), w=at(p["w"]), wd=at(p["wd"]),
                     goal=p["goal"].tolist()) for p in preps]
    r = o.evaluate(preps, PAIRS)
    points = []
    for i, (D, K) in enumerate(PAIRS):
        points.append(dict(dm=D, km=K, demos=[
            dict(name=p["name"], d_rot=float(r["d_rot"][i, j]), alpha_peak=float(r["alpha_peak"][i, j]),
                 q=at(r["q"][i, j])) for j, p in enumerate(preps)]))
    t1 = time.time()
    grid = o.d_rot_grid(preps, GRID, GRID)
    t_grid = time.time() - t1
    out = dict(
        meta=dict(input="assets/planted8.mcap", sha256=sha, numpy=np.__version__,
                  scipy=scipy.__version__, python=sys.version.split()[0],
                  n_grid=m.N_GRID, sg_window=m.SG_WINDOW, sg_order=m.SG_ORDER, basis=m.B,
                  idx=IDX, quaternion_order="x, y, z, w",
                  units=dict(q="unit quaternion", w="rad per unit time (space frame)",
                             wd="rad per unit time^2", d_rot="rad", alpha_peak="rad per unit time^2"),
                  rollout_renormalised=True),
        demos=demo_out,
        points=points,
        grid=dict(dm=GRID.tolist(), km=GRID.tolist(), d_rot_sum=grid.tolist(),
                  note="np.logspace(-1, 3, 12) on both axes; d_rot_sum[i_dm][i_km], radians"),
    )
    out_path = os.path.join(HERE, "expected_orientation.json")
    with open(out_path, "w") as fh:
        json.dump(out, fh, indent=1)
    print("wrote", out_path, os.path.getsize(out_path), "bytes")
    print(f"time: read+prepare {t_prep:.2f} s, grid {t_grid:.2f} s, total {time.time() - t0:.2f} s")
    for pt in points:
        print(f"  D/M {pt['dm']}, K/M {pt['km']}:")
        for d in pt["demos"]:
            print(f"    {d['name']}: d_rot {d['d_rot']:.6e} rad ({np.degrees(d['d_rot']):.5f} deg),"
                  f" alpha_peak {d['alpha_peak']:.6e}")
    i, j = np.unravel_index(np.argmin(grid), grid.shape)
    k, l = np.unravel_index(np.argmax(grid), grid.shape)
    print(f"  d_rot_sum grid: min {grid.min():.6e} at D {GRID[i]:.4g}, K {GRID[j]:.4g};"
          f" max {grid.max():.6e} at D {GRID[k]:.4g}, K {GRID[l]:.4g}")


if __name__ == "__main__":
    main()
