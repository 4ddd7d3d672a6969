#!/usr/bin/env python3
"""Write expected_skill_error.json: the skill error E of method.md section 11 in its three
modes (per-demo e at fixed gains, the E grid, E's depth), J's refined optimum and the
acceptable region, for input.json's demos (16 x 16 grid) and the bundled samples of
input_samples.json (10 x 10 grid), with skill_error.py (~3 min)."""
import json
import os

import numpy as np

import diagnostics as dg
import method as m
import skill_error as se

HERE = os.path.dirname(os.path.abspath(__file__))
K = m.K_WEIGHT
POINTS = [(10.73, 20.71), (25.0, 156.25)]


def one_set(demos, n):
    preps = [m.prepare_demo(d["stamps_ns"], d["positions"], d["name"]) for d in demos]
    G = np.geomspace(0.1, 1000.0, n)
    S = np.empty((n, n)); dsum = np.empty((n, n))
    E = {mode: np.empty((n, n)) for mode in se.MODES}
    for i, D in enumerate(G):
        for j, Kk in enumerate(G):
            o = m.objective(preps, float(D), float(Kk), K)
            S[i, j], dsum[i, j] = o["s"], o["d_sum"]
            for mode in se.MODES:
                E[mode][i, j] = sum(se.skill_errors(preps, float(D), float(Kk), mode))
    J = S + K * dsum
    opt = dg.refine_of(lambda D, Kk: m.objective(preps, D, Kk, K)["j"], G, G, J)
    modes = {}
    for mode in se.MODES:
        modes[mode] = dict(
            e_sum=E[mode].tolist(),
            e_depth=se.depth_of_grid_min(E[mode]),
            points=[dict(dm=D, km=Kk, e=se.skill_errors(preps, D, Kk, mode)) for D, Kk in POINTS],
        )
    return dict(demos=[p["name"] for p in preps], grid=dict(lo=0.1, hi=1000.0, n=n),
                optimum=dict(dm=opt["dm"], km=opt["km"], j=opt["value"]),
                acceptable=se.acceptable(J, opt["value"], G, G, 0.02), modes=modes)


def main():
    with open(os.path.join(HERE, "input.json")) as fh:
        golden = json.load(fh)["demos"]
    with open(os.path.join(HERE, "input_samples.json")) as fh:
        samples = json.load(fh)["sets"]
    se.selfcheck([m.prepare_demo(d["stamps_ns"], d["positions"], d["name"]) for d in golden])
    sets = {"input": one_set(golden, 16)}
    for name in ("reach10", "planted8"):
        sets[name] = one_set(samples[name], 10)
        print(name, "done", flush=True)
    out = dict(meta=dict(numpy=np.__version__, k=K, eps=0.02, modes=list(se.MODES)), sets=sets)
    path = os.path.join(HERE, "expected_skill_error.json")
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
    print("wrote", path, os.path.getsize(path), "bytes")


if __name__ == "__main__":
    main()
