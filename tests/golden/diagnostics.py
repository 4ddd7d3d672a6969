"""Independent reference of the diagnostics of docs/method.md section 9.

Built on method.py (sections 1-6); NumPy + SciPy only, written from the
method text. Per-demo d over a grid does not depend on which other demos
are in a set, so subsets (leave-one-out, bootstrap resamples with repeats)
reuse each demo's d grid and recompute only S.
"""
import math

import numpy as np
from scipy.optimize import minimize

import method as m

FLAT_DEPTH = 0.02


def d_grids(preps, Dg, Kg):
    """d of every demo at every grid point: (N, nd, nk)."""
    out = np.empty((len(preps), len(Dg), len(Kg)))
    for n, p in enumerate(preps):
        for i, D in enumerate(Dg):
            for j, K in enumerate(Kg):
                out[n, i, j] = m.eval_demo(p, float(D), float(K))["d"]
    return out


def s_grid(preps, Dg, Kg):
    S = np.empty((len(Dg), len(Kg)))
    for i, D in enumerate(Dg):
        for j, K in enumerate(Kg):
            S[i, j] = m.similarity(preps, float(D), float(K))
    return S


def depth(J, j_star):
    """max(0, min(J over the first and last rows and columns) / J* - 1)."""
    edge = np.concatenate([J[0, :], J[-1, :], J[:, 0], J[:, -1]])
    return max(0.0, float(np.min(edge)) / j_star - 1.0)


def balanced_k(S, dsum):
    return float(np.median(S)) / float(np.median(dsum))


def s_shares(preps, D, K):
    """q_i = integral sum_axes (f_stand(i) - mean_j f_stand(j))^2, shares q_i / sum q."""
    fs = m.standardised(preps, D, K)
    mean = fs.mean(axis=0)
    q = np.array([m.trapz_unit(((f - mean) ** 2).sum(axis=1)) for f in fs])
    return (q / q.sum()).tolist()


def refine_of(value, Dg, Kg, grid):
    """Section 6's refinement of any quantity: grid minimum of `grid`, scipy
    Nelder-Mead in (ln D, ln K) from the grid step simplex (inward at an
    edge), every point clipped into the box."""
    lo_d, hi_d = math.log(Dg[0]), math.log(Dg[-1])
    lo_k, hi_k = math.log(Kg[0]), math.log(Kg[-1])
    i, j = np.unravel_index(int(np.argmin(grid)), grid.shape)
    lD, lK = np.log(Dg), np.log(Kg)
    si = 1 if i < len(Dg) - 1 else -1
    sj = 1 if j < len(Kg) - 1 else -1
    simplex = np.array([[lD[i], lK[j]], [lD[i + si], lK[j]], [lD[i], lK[j + sj]]])

    def clip(u):
        return np.array([min(max(u[0], lo_d), hi_d), min(max(u[1], lo_k), hi_k)])

    def fun(u):
        c = clip(u)
        return value(math.exp(c[0]), math.exp(c[1]))

    res = minimize(fun, simplex[0], method="Nelder-Mead",
                   options=dict(initial_simplex=simplex, xatol=1e-7, fatol=1e-12,
                                maxiter=20000, maxfev=20000))
    c = clip(res.x)
    best = float(grid[i, j])
    D, K = math.exp(c[0]), math.exp(c[1])
    v = value(D, K)
    if not v <= best:          # the grid point stays when nothing better was found
        D, K, v, c = float(Dg[i]), float(Kg[j]), best, np.array([lD[i], lK[j]])
    on_edge = bool(min(abs(c[0] - lo_d), abs(c[0] - hi_d), abs(c[1] - lo_k), abs(c[1] - hi_k)) <= 1e-6)
    return dict(dm=D, km=K, value=v, on_edge=on_edge)


def optimum_of(preps, idx, dg, Dg, Kg, k=m.K_WEIGHT):
    """The extraction on the demos at `idx` (repeats allowed), reusing the
    per-demo d grids `dg`."""
    sub = [preps[i] for i in idx]
    dsum = dg[list(idx)].sum(axis=0)
    J = s_grid(sub, Dg, Kg) + k * dsum
    r = refine_of(lambda D, K: m.objective(sub, D, K, k)["j"], Dg, Kg, J)
    return dict(dm=r["dm"], km=r["km"], j=r["value"], on_edge=r["on_edge"])
