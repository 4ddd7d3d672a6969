#!/usr/bin/env python3
"""Read input.json, roll demos and skills out to new targets with generalise.py
(docs/method.md section 10, docs/export.md), write expected_generalise.json."""
import json
import os

import numpy as np

import generalise as gz
import method as m

HERE = os.path.dirname(os.path.abspath(__file__))
IDX = list(range(0, m.N_GRID, 10))          # 0, 10, ..., 1000


def fl(a):
    return np.asarray(a, dtype=np.float64).tolist()


def vec(a):
    return None if a is None else fl(a)


def main():
    with open(os.path.join(HERE, "input.json")) as fh:
        demos = json.load(fh)["demos"]
    preps = [m.prepare_demo(d["stamps_ns"], d["positions"], d["name"]) for d in demos]

    def dmp(i, D, K):
        return gz.demo_dmp(preps[i], D, K)

    def skill(D, K, mode):
        return gz.skill_dmp([dmp(i, D, K) for i in range(len(preps))], mode)

    R0 = gz.rot_z(0.9)
    cases = []

    # 1. demo_a, paper, shifted start and goal, 2.5 s
    d0 = dmp(0, 10.73, 20.71)
    cases.append(dict(name="demo_a paper shifted", source="demo", demo=0, dm=10.73, km=20.71,
                      scaling="paper", start=d0["y0"] + np.array([0.05, -0.02, 0.01]),
                      goal=d0["g"] + np.array([0.10, 0.05, -0.03]), duration=2.5))
    # 2. demo_b, frame, goal = start + 0.7 R0 d, 0.8 s
    d1 = dmp(1, 25.0, 156.25)
    cases.append(dict(name="demo_b frame rotated 0.9 rad about z, scale 0.7", source="demo", demo=1,
                      dm=25.0, km=156.25, scaling="frame", start=d1["y0"].copy(),
                      goal=d1["y0"] + 0.7 * (R0 @ d1["d"]), duration=0.8))
    # 3. demo_c, frame, opposite direction (own start), own duration
    d2 = dmp(2, 10.73, 20.71)
    cases.append(dict(name="demo_c frame opposite", source="demo", demo=2, dm=10.73, km=20.71,
                      scaling="frame", start=None, goal=d2["y0"] - d2["d"], duration=None))
    # 4. demo_a, own target (= section 4's regenerate + p0)
    cases.append(dict(name="demo_a own target", source="demo", demo=0, dm=4.0, km=4.0,
                      scaling="paper", start=None, goal=None, duration=None))
    # 5. skill, paper
    sk = skill(10.73, 20.71, "paper")
    s5 = sk["y0"] + np.array([0.02, 0.02, 0.0])
    cases.append(dict(name="skill paper", source="skill", demo=None, dm=10.73, km=20.71,
                      scaling="paper", start=s5, goal=s5 + np.array([0.3, -0.1, 0.2]), duration=1.7))
    # 6. skill, frame, own target
    cases.append(dict(name="skill frame own target", source="skill", demo=None, dm=10.73, km=20.71,
                      scaling="frame", start=None, goal=None, duration=None))
    # 7. skill, frame, absolute target
    cases.append(dict(name="skill frame absolute target", source="skill", demo=None, dm=25.0,
                      km=156.25, scaling="frame", start=np.array([0.1, 0.2, 0.3]),
                      goal=np.array([0.4, 0.6, 0.1]), duration=3.0))

    out_cases = []
    for c in cases:
        D, K = c["dm"], c["km"]
        if c["source"] == "demo":
            src = dmp(c["demo"], D, K)
            o = gz.generalise(src, D, K, c["scaling"], c["start"], c["goal"], c["duration"])
        else:
            src = skill(D, K, c["scaling"])
            o = gz.generalise_skill(src, D, K, c["scaling"], c["start"], c["goal"], c["duration"])
        row = dict(name=c["name"], source=c["source"], demo=c["demo"], dm=D, km=K,
                   scaling=c["scaling"], start=vec(c["start"]), goal=vec(c["goal"]),
                   duration=c["duration"],
                   start_used=fl(o["start"]), goal_used=fl(o["goal"]), duration_used=o["tau"],
                   Q=fl(o["Q"]), idx=IDX,
                   t=fl(o["t"][IDX]), y=fl(o["y"][IDX]), v=fl(o["v"][IDX]), a=fl(o["a"][IDX]))
        if c["source"] == "skill":
            row.update(skill_start=fl(src["y0"]), skill_goal=fl(src["g"]),
                       skill_duration=src["T"], Q_members=[fl(q) for q in src["Q_members"]],
                       band=fl(o["band"][IDX]), forcing_sd=fl(src["forcing_sd"][IDX]))
        out_cases.append(row)

    out = dict(meta=dict(numpy=np.__version__, n_grid=m.N_GRID, B=m.B,
                         demos=[p["name"] for p in preps],
                         note="positions absolute (metres); v m/s, a m/s^2 (real time, tau = "
                              "duration_used); t = tau k / (n - 1); y[0] = start_used exactly"),
               cases=out_cases)
    path = os.path.join(HERE, "expected_generalise.json")
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
    print("wrote", path, os.path.getsize(path), "bytes")


if __name__ == "__main__":
    main()
