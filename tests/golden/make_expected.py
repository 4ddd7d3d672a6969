#!/usr/bin/env python3
"""Read input.json, run the reference implementation (method.py), write expected.json."""
import json
import math
import os

import numpy as np
import scipy

import method as m

HERE = os.path.dirname(os.path.abspath(__file__))
IDX = [0, 1, 2, 5, 10, 11, 50, 100, 250, 500, 750, 900, 990, 995, 998, 999, 1000]
POINTS = [(10.73, 20.71), (25.0, 156.25), (10.0, 200.0), (100.0, 20.0), (4.0, 4.0),
          (0.1, 0.1), (1000.0, 1000.0), (0.1, 1000.0), (1000.0, 0.1), (3.3, 47.0)]
K = m.K_WEIGHT


def fl(a):
    """numpy array / scalar -> plain Python floats (nested lists)."""
    return np.asarray(a, dtype=np.float64).tolist()


def main():
    with open(os.path.join(HERE, "input.json")) as fh:
        demos = json.load(fh)["demos"]
    preps = [m.prepare_demo(d["stamps_ns"], d["positions"], d["name"]) for d in demos]

    prepared = []
    for p in preps:
        prepared.append(dict(
            name=p["name"], n_raw=p["n_raw"], T=p["T"], h=p["h"], n0=p["n0"], h_prime=p["hp"],
            g=fl(p["g"]), p0=fl(p["p0"]), idx=IDX,
            y_raw=fl(p["y_raw"][IDX]), y=fl(p["y"][IDX]), yd=fl(p["yd"][IDX]), ydd=fl(p["ydd"][IDX])))

    p = preps[0]
    n0 = p["n0"]
    sidx = [0, 1, 5, 9, 10, 11, 20, n0 // 2, n0 - 11, n0 - 10, n0 - 2, n0 - 1]
    savgol = dict(demo=p["name"], axis="x", n0=n0, h_prime=p["hp"], indices=sidx,
                  t=fl(p["grid"][sidx]),
                  raw=fl(p["p_resampled"][sidx, 0]),
                  pos=fl(p["p_smooth"][sidx, 0]), vel=fl(p["v_smooth"][sidx, 0]),
                  acc=fl(p["a_smooth"][sidx, 0]))

    points = []
    for D, Kg in POINTS:
        evs = [m.eval_demo(q, D, Kg) for q in preps]
        S = m.similarity(preps, D, Kg)
        ds = [e["d"] for e in evs]
        w0x = evs[0]["w"][:, 0]
        points.append(dict(
            dm=D, km=Kg, zeta=D / (2.0 * math.sqrt(Kg)),
            d=ds, a_peak=[e["a_peak"] for e in evs], s=S, d_sum=float(sum(ds)),
            j=S + K * float(sum(ds)),
            weights_demo0_x_first5=fl(w0x[:5]), weights_demo0_x_last5=fl(w0x[-5:]),
            f_fit_demo0_x=fl(evs[0]["f"][IDX, 0]), idx=IDX))

    G = np.geomspace(0.1, 1000.0, 16)
    S, dsum, J = m.landscape(preps, G, G, K)
    i, j = np.unravel_index(int(np.argmin(J)), J.shape)
    DD, KK = np.meshgrid(G, G, indexing="ij")
    landscape = dict(k=K, dm_axis=fl(G), km_axis=fl(G), dm=fl(DD), km=fl(KK),
                     d_sum=fl(dsum), s=fl(S), j=fl(J),
                     grid_min=dict(i_dm=int(i), i_km=int(j), dm=float(G[i]), km=float(G[j]),
                                   j=float(J[i, j])))

    opt = m.refine(preps, G, G, J, K)
    optimum = dict(dm=opt["dm"], km=opt["km"], j=opt["j"], s=opt["s"], d_sum=opt["d_sum"],
                   on_edge=opt["on_edge"], zeta=opt["dm"] / (2.0 * math.sqrt(opt["km"])),
                   log_dm=opt["log_dm"], log_km=opt["log_km"],
                   initial_simplex_log=opt["initial_simplex"], nit=opt["nit"], nfev=opt["nfev"],
                   final_simplex_span_log=opt["simplex_span"])

    e0 = m.eval_demo(preps[0], 10.73, 20.71)
    single = dict(dm=10.73, km=20.71, s=m.similarity(preps[:1], 10.73, 20.71), d=e0["d"],
                  j=m.similarity(preps[:1], 10.73, 20.71) + K * e0["d"])

    out = dict(meta=dict(numpy=np.__version__, scipy=scipy.__version__, k=K, n_grid=m.N_GRID,
                         B=m.B, savgol_window=m.SG_WINDOW, savgol_order=m.SG_ORDER,
                         note="g is relative (y_raw(1) = p(T) - p0); p0, savgol.raw/pos are absolute"),
               prepared=prepared, savgol=savgol, points=points, landscape=landscape,
               optimum=optimum, single_demo=single)
    path = os.path.join(HERE, "expected.json")
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
    print("wrote", path, os.path.getsize(path), "bytes")


if __name__ == "__main__":
    main()
