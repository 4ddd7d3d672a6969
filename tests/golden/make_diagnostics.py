#!/usr/bin/env python3
"""Read input.json, compute the diagnostics of method.md section 9 with
diagnostics.py on the 16 x 16 grid of expected.json, write
expected_diagnostics.json."""
import json
import os

import numpy as np

import diagnostics as dg
import method as m

HERE = os.path.dirname(os.path.abspath(__file__))
K = m.K_WEIGHT
# Fixed gain pairs for the quantities that are exact functions of the gains.
POINTS = [(10.73, 20.71), (25.0, 156.25), (3.3, 47.0)]
# A fixed bootstrap resample list (demo indices; repeats allowed).
RESAMPLES = [[0, 0, 1], [2, 1, 2], [0, 1, 2], [1, 1, 1], [2, 2, 0]]


def main():
    with open(os.path.join(HERE, "input.json")) as fh:
        demos = json.load(fh)["demos"]
    preps = [m.prepare_demo(d["stamps_ns"], d["positions"], d["name"]) for d in demos]
    G = np.geomspace(0.1, 1000.0, 16)
    per_demo_d = dg.d_grids(preps, G, G)
    dsum = per_demo_d.sum(axis=0)
    S = dg.s_grid(preps, G, G)
    J = S + K * dsum
    opt = dg.refine_of(lambda D, Kk: m.objective(preps, D, Kk, K)["j"], G, G, J)
    at_opt = m.objective(preps, opt["dm"], opt["km"], K)
    s_min = dg.refine_of(lambda D, Kk: m.similarity(preps, D, Kk), G, G, S)
    points = []
    for D, Kk in POINTS:
        o = m.objective(preps, D, Kk, K)
        points.append(dict(dm=D, km=Kk, s_share=dg.s_shares(preps, D, Kk),
                           k_ratio=K * o["d_sum"] / o["s"]))
    loo = [dg.optimum_of(preps, [j for j in range(len(preps)) if j != i], per_demo_d, G, G)
           for i in range(len(preps))]
    boot = [dg.optimum_of(preps, r, per_demo_d, G, G) for r in RESAMPLES]
    dm = [b["dm"] for b in boot]
    km = [b["km"] for b in boot]
    out = dict(
        grid=dict(lo=0.1, hi=1000.0, n=16), k=K,
        optimum=dict(dm=opt["dm"], km=opt["km"], j=opt["value"], on_edge=opt["on_edge"]),
        depth=dg.depth(J, opt["value"]),
        k_ratio_at_optimum=K * at_opt["d_sum"] / at_opt["s"],
        balanced_k=dg.balanced_k(S, dsum),
        s_share_at_optimum=dg.s_shares(preps, opt["dm"], opt["km"]),
        s_minimum=dict(dm=s_min["dm"], km=s_min["km"], s=s_min["value"]),
        points=points,
        loo=loo,
        resamples=RESAMPLES,
        bootstrap=dict(optima=boot,
                       dm=np.percentile(dm, [5, 50, 95]).tolist(),
                       km=np.percentile(km, [5, 50, 95]).tolist(),
                       on_edge_fraction=sum(b["on_edge"] for b in boot) / len(boot)),
    )
    path = os.path.join(HERE, "expected_diagnostics.json")
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
    print("wrote", path, os.path.getsize(path), "bytes")


if __name__ == "__main__":
    main()
