#!/usr/bin/env python3
"""Vectorised NumPy landscape of method.md sections 1-6, for speed comparison.

    python3 landscape_speed.py [--set reach10|planted8] [--grid N] [--out F.json] [--check]

Same numbers as method.py's `landscape` (to rounding), computed over all gain pairs at once:

- demos of input_samples.json prepared by method.prepare_demo (file order of the set);
- f_target = ydd + D yd + K (y - g) is linear in (D, K), so are the LWR weights and the fitted
  forcing term: per demo F0, F1, F2 = method.forcing(method.lwr_weights(.)) of ydd, yd, y - g
  (fitted once), f(D, K) = F0 + D F1 + K F2;
- regeneration: method.regenerate's semi-implicit Euler, same order of operations, on state
  arrays (3, rows, nK) of gain pairs (D along rows, K along columns, broadcast), one Python
  loop over demos and the 1001 time steps; d = trapezoid (np.trapezoid, dx = DT) of
  |y_k - y_raw_k|, a_peak = max_k |a_k|;
- S: method.similarity's formula (per demo and axis population mean/SD over the grid,
  standardised, 0 where SD < 1e-12; sample SD over demos; trapezoid of the norm over axes)
  on blocks of gain pairs, arrays (N, n, 3, pairs);
- J = S + k sum d, k = 20.
Grid rows are processed in chunks (--chunk rows) so memory stays bounded (~0.4 GB at 128 x 128).

Timing: "prepare+fit" is method.prepare_demo of every demo plus the three LWR fits per demo;
"grid" is the regeneration, d, a_peak, S and J over all pairs; the total is their sum (JSON
reading, output writing and --check are not timed).
--check compares 5 spread grid points with method.objective (s, each d, d_sum, j) and
method.eval_demo (each a_peak) and prints the largest relative difference.
"""
import argparse
import json
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import method as m  # noqa: E402

DT = m.DT
N_GRID = m.N_GRID
S_BLOCK = 256          # gain pairs per block in S: (N, 1001, 3, 256) float64 = 61 MB for N = 10


def fit_demo(prep):
    """The fitted forcing term's three parts, each (n, 3): f(D, K) = F0 + D F1 + K F2."""
    yg = prep["y"] - prep["g"][None, :]
    F0 = m.forcing(m.lwr_weights(prep["ydd"]))
    F1 = m.forcing(m.lwr_weights(prep["yd"]))
    F2 = m.forcing(m.lwr_weights(yg))
    return dict(F0=F0, F1=F1, F2=F2, yg=yg)


def regenerate_grid(prep, fit, Dr, Kc, nbuf):
    """Section 4 on all pairs of Dr (rows) x Kc (columns); returns d, a_peak (rows, nK).
    nbuf: scratch (n, rows, nK) for d's integrand.

    Mirrors method.regenerate: a_k = -D v_k - K (y_k - g) + f(x_k); v += a dt; y += v dt.
    """
    R, C = Dr.shape[0], Kc.shape[0]
    D = Dr[None, :, None]                      # (1, R, 1)
    K = Kc[None, None, :]                      # (1, 1, C)
    negD = -D
    g = prep["g"][:, None, None]               # (3, 1, 1)
    F0, F1, F2 = fit["F0"], fit["F1"], fit["F2"]
    y_raw = prep["y_raw"]
    y = np.empty((3, R, C)); y[...] = prep["y_raw"][0][:, None, None]
    v = np.empty((3, R, C)); v[...] = prep["yd"][0][:, None, None]
    a = np.empty((3, R, C)); e = np.empty((3, R, C)); f = np.empty((3, R, C))
    a2 = np.empty((R, C)); a2max = np.zeros((R, C))
    n = N_GRID
    for k in range(n):
        # d's integrand at y_k
        np.subtract(y, y_raw[k][:, None, None], out=e)
        np.multiply(e, e, out=e)
        np.sum(e, axis=0, out=nbuf[k])
        np.sqrt(nbuf[k], out=nbuf[k])
        # f(x_k) = F0 + D F1 + K F2 (small (3,R,1) and (3,1,C) parts, one full add)
        np.add(F0[k][:, None, None] + D * F1[k][:, None, None],
               K * F2[k][:, None, None], out=f)
        # a_k = -D v_k - K (y_k - g) + f(x_k)
        np.multiply(negD, v, out=a)
        np.subtract(y, g, out=e)
        np.multiply(K, e, out=e)
        np.subtract(a, e, out=a)
        np.add(a, f, out=a)
        # a_peak: running max of |a_k|^2 (sqrt at the end; sqrt is monotone)
        np.multiply(a, a, out=e)
        np.sum(e, axis=0, out=a2)
        np.maximum(a2max, a2, out=a2max)
        if k < n - 1:
            np.multiply(a, DT, out=e)
            np.add(v, e, out=v)
            np.multiply(v, DT, out=e)
            np.add(y, e, out=y)
    d = np.trapezoid(nbuf, dx=DT, axis=0)
    return d, np.sqrt(a2max)


def similarity_grid(preps, fits, Dp, Kp):
    """method.similarity for the pairs (Dp[j], Kp[j]), flat arrays; returns S (pairs,)."""
    N = len(preps)
    P = Dp.shape[0]
    if N < 2:
        return np.zeros(P)
    ydd = np.stack([p["ydd"] for p in preps])[..., None]      # (N, n, 3, 1)
    yd = np.stack([p["yd"] for p in preps])[..., None]
    yg = np.stack([f["yg"] for f in fits])[..., None]
    out = np.empty(P)
    for j0 in range(0, P, S_BLOCK):
        Db = Dp[j0:j0 + S_BLOCK]; Kb = Kp[j0:j0 + S_BLOCK]
        ft = ydd + yd * Db + yg * Kb                           # (N, n, 3, b): f_target
        mu = ft.mean(axis=1, keepdims=True)
        sd = ft.std(axis=1, ddof=0, keepdims=True)
        ok = sd >= 1e-12
        ft -= mu
        ft /= np.where(ok, sd, 1.0)
        ft *= ok                                               # f_stand, 0 where sd < 1e-12
        sig = ft.std(axis=0, ddof=1)                           # (n, 3, b)
        out[j0:j0 + S_BLOCK] = np.trapezoid(np.sqrt((sig ** 2).sum(axis=1)), dx=DT, axis=0)
    return out


def landscape_grid(preps, fits, G, chunk_rows, k=m.K_WEIGHT):
    nD = nK = G.shape[0]
    N = len(preps)
    dsum = np.zeros((nD, nK)); s = np.empty((nD, nK))
    a_peak = np.empty((N, nD, nK)); d_all = np.empty((N, nD, nK))
    nbuf = np.empty((N_GRID, min(chunk_rows, nD), nK))
    for r0 in range(0, nD, chunk_rows):
        Dr = G[r0:r0 + chunk_rows]
        R = Dr.shape[0]
        buf = nbuf if R == nbuf.shape[1] else np.empty((N_GRID, R, nK))
        for i, (p, fit) in enumerate(zip(preps, fits)):
            d, ap = regenerate_grid(p, fit, Dr, G, buf)
            d_all[i, r0:r0 + R] = d
            a_peak[i, r0:r0 + R] = ap
        Dp = np.repeat(Dr, nK); Kp = np.tile(G, R)
        s[r0:r0 + R] = similarity_grid(preps, fits, Dp, Kp).reshape(R, nK)
    for i in range(N):                         # sum in demo order, as method.objective
        dsum += d_all[i]
    return dict(s=s, d_sum=dsum, j=s + k * dsum, d=d_all, a_peak=a_peak,
                a_peak_max=a_peak.max(axis=0))


def check(preps, G, res, n_points=5):
    nG = G.shape[0]
    idx = np.linspace(0, nG - 1, n_points).round().astype(int)
    pts = [(int(idx[t]), int(idx[(t * 2 + 1) % n_points])) for t in range(n_points)]
    worst = 0.0
    for i, j in pts:
        D, K = float(G[i]), float(G[j])
        o = m.objective(preps, D, K)
        aps = [m.eval_demo(p, D, K)["a_peak"] for p in preps]
        pairs = [(o["s"], res["s"][i, j]), (o["d_sum"], res["d_sum"][i, j]),
                 (o["j"], res["j"][i, j]), (max(aps), res["a_peak_max"][i, j])]
        pairs += [(o["d"][q], res["d"][q, i, j]) for q in range(len(preps))]
        pairs += [(aps[q], res["a_peak"][q, i, j]) for q in range(len(preps))]
        rel = max(abs(b - a) / max(abs(a), 1e-300) for a, b in pairs)
        worst = max(worst, rel)
        print(f"check D={D:.6g} K={K:.6g}: J={o['j']:.12g} max rel diff {rel:.3e}")
    print(f"check: largest relative difference {worst:.3e} "
          f"({'ok' if worst < 1e-9 else 'FAIL'}, limit 1e-9)")
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--set", default="reach10", choices=["reach10", "planted8"])
    ap.add_argument("--grid", type=int, default=128)
    ap.add_argument("--out")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--chunk", type=int, default=128, help="grid rows (D values) per chunk")
    args = ap.parse_args()
    with open(os.path.join(HERE, "input_samples.json")) as fh:
        demos = json.load(fh)["sets"][args.set]
    G = np.geomspace(0.1, 1000.0, args.grid)

    t0 = time.perf_counter()
    preps = [m.prepare_demo(d["stamps_ns"], d["positions"], d["name"]) for d in demos]
    fits = [fit_demo(p) for p in preps]
    t1 = time.perf_counter()
    res = landscape_grid(preps, fits, G, max(1, args.chunk))
    t2 = time.perf_counter()
    print(f"numpy landscape {args.set} {args.grid}x{args.grid}: {t2 - t0:.3f} s "
          f"(prepare+fit {t1 - t0:.3f} s, grid {t2 - t1:.3f} s)", flush=True)

    if args.out:
        DM, KM = np.meshgrid(G, G, indexing="ij")
        out = dict(set=args.set, n=args.grid, k=m.K_WEIGHT, dm=DM.tolist(), km=KM.tolist(),
                   d_sum=res["d_sum"].tolist(), s=res["s"].tolist(), j=res["j"].tolist(),
                   a_peak_max=res["a_peak_max"].tolist())
        with open(args.out, "w") as fh:
            json.dump(out, fh)
    if args.check:
        worst = check(preps, G, res)
        if worst >= 1e-9:
            sys.exit(1)


if __name__ == "__main__":
    main()
