#!/usr/bin/env python3
"""Self-checks of the reference implementation (prints a report; writes nothing)."""
import json
import math
import os

import numpy as np
from scipy.optimize import minimize

import method as m

HERE = os.path.dirname(os.path.abspath(__file__))
demos = json.load(open(os.path.join(HERE, "input.json")))["demos"]
preps = [m.prepare_demo(d["stamps_ns"], d["positions"], d["name"]) for d in demos]
exp = json.load(open(os.path.join(HERE, "expected.json")))


def rel(a, b):
    a = np.asarray(a, float); b = np.asarray(b, float)
    return float(np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-300)))


# (a) Savitzky-Golay edges/interior == explicit cubic least-squares fits
print("(a) savgol vs explicit cubic fits (np.polyfit), all demos, all axes")
worst = [0.0, 0.0, 0.0]
for p in preps:
    t = p["grid"]; n0 = p["n0"]
    for ax in range(3):
        y = p["p_resampled"][:, ax]
        windows = [(0, range(0, 11)), (n0 - 21, range(n0 - 11, n0))]
        windows += [(k - 10, [k]) for k in range(10, n0 - 10)]
        for start, ks in windows:
            tt = t[start:start + 21]; tc = tt[10]
            c = np.polyfit(tt - tc, y[start:start + 21], 3)
            for k in ks:
                x = t[k] - tc
                val = np.polyval(c, x); d1 = np.polyval(np.polyder(c, 1), x); d2 = np.polyval(np.polyder(c, 2), x)
                for q, (ref, got) in enumerate([(val, p["p_smooth"][k, ax]), (d1, p["v_smooth"][k, ax]),
                                                 (d2, p["a_smooth"][k, ax])]):
                    scale = [np.max(np.abs(p["p_smooth"][:, ax])), np.max(np.abs(p["v_smooth"][:, ax])),
                             np.max(np.abs(p["a_smooth"][:, ax]))][q]
                    worst[q] = max(worst[q], abs(ref - got) / scale)
print("    max |diff|/max|signal|  pos %.2e  vel %.2e  acc %.2e" % tuple(worst))

# (b) regeneration with exact per-sample f_target as f (instead of the LWR fit)
print("(b) regeneration with exact f_target as f (instead of LWR fit)")
from scipy.integrate import solve_ivp
s = np.linspace(0.0, 1.0, m.N_GRID)
mj = 10 * s**3 - 15 * s**4 + 6 * s**5
mjd = 30 * s**2 - 60 * s**3 + 30 * s**4
mjdd = 60 * s - 180 * s**2 + 120 * s**3
r = np.array([0.2, 0.3, -0.1])
ana = dict(y=mj[:, None] * r, yd=mjd[:, None] * r, ydd=mjdd[:, None] * r, y_raw=mj[:, None] * r, g=r.copy())
for D, K in [(10.73, 20.71), (25.0, 156.25), (100.0, 20.0), (4.0, 4.0), (1000.0, 1000.0)]:
    ft = m.f_target(ana, D, K)
    e = m.eval_demo(ana, D, K, f_override=ft)
    ea = np.max(np.linalg.norm(e["y"] - ana["y"], axis=1))
    errs = []; errs_ode = []
    for p in preps:
        ft = m.f_target(p, D, K)
        e = m.eval_demo(p, D, K, f_override=ft)
        errs.append(np.max(np.linalg.norm(e["y"] - p["y"], axis=1)))
        if p is preps[0]:
            def rhs(tt, z):
                f = np.array([np.interp(tt, p["s"], ft[:, a]) for a in range(3)])
                return np.concatenate([z[3:], -D * z[3:] - K * (z[:3] - p["g"]) + f])
            sol = solve_ivp(rhs, (0, 1), np.concatenate([p["y_raw"][0], p["yd"][0]]), t_eval=p["s"],
                            rtol=1e-10, atol=1e-12, method="Radau" if D >= 100 else "DOP853", max_step=1e-3)
            errs_ode.append(np.max(np.linalg.norm(e["y"] - sol.y[:3].T, axis=1)))
    print("    D=%-7g K=%-7g analytic min-jerk target: max||y_regen - y|| = %.2e m (reach 0.37 m);"
          " demo_a Euler vs accurate ODE %.2e m; demos vs smoothed y %.2e m"
          % (D, K, ea, errs_ode[0], max(errs)))
print("    (the mm-level demo residual is the inconsistency of the Savitzky-Golay y, y', y''"
      " -- the SG derivative is not the derivative of the SG-smoothed curve -- not integrator error)")

# (c) S = 0 for scaled + shifted (space and time) copies of one demo
print("(c) S for scaled+shifted copies of demo_a")
d0 = demos[0]
st = np.array(d0["stamps_ns"], dtype=object); P = np.array(d0["positions"])
first = min(d0["stamps_ns"])
copies = [
    (d0["stamps_ns"], P),
    ([s + 123_456_789_012 for s in d0["stamps_ns"]], P * np.array([1.7, 0.6, 2.3]) + np.array([0.1, -0.3, 0.5])),
    ([1_600_000_000_000_000_001 + 2 * (s - first) for s in d0["stamps_ns"]], P * 0.8 - 0.2),
]
cp = [m.prepare_demo(s, q, "copy%d" % i) for i, (s, q) in enumerate(copies)]
for D, K in [(10.73, 20.71), (0.1, 1000.0), (1000.0, 0.1)]:
    print("    D=%-7g K=%-7g S = %.3e   (the 3 real demos: S = %.4f)" % (D, K, m.similarity(cp, D, K), m.similarity(preps, D, K)))
print("    single demo S =", m.similarity(preps[:1], 10.73, 20.71))

# (d) landscape consistent with points and with direct evaluation
print("(d) landscape vs direct evaluation")
L = exp["landscape"]
G = np.array(L["dm_axis"])
for (i, j) in [(0, 0), (5, 9), (10, 10), (15, 0), (15, 15), (3, 12)]:
    o = m.objective(preps, float(G[i]), float(G[j]))
    print("    [%2d][%2d] D=%-10.5g K=%-10.5g rel diff  j %.1e  s %.1e  d_sum %.1e"
          % (i, j, G[i], G[j], rel(o["j"], L["j"][i][j]), rel(o["s"], L["s"][i][j]), rel(o["d_sum"], L["d_sum"][i][j])))
# grid point (0,0) is D=K=0.1, which is also a "points" entry; (15,15) is (1000,1000)
for (i, j, pi) in [(0, 0, 5), (15, 15, 6)]:
    pt = exp["points"][pi]
    print("    landscape[%d][%d] vs points (%g,%g): rel diff j %.1e" % (i, j, pt["dm"], pt["km"], rel(L["j"][i][j], pt["j"])))
o5 = m.objective(preps, float(G[4]), float(G[7]), k=5.0)
print("    recombination with k=5 at [4][7]: rel diff %.1e" % rel(L["s"][4][7] + 5.0 * L["d_sum"][4][7], o5["j"]))
gm = L["grid_min"]
print("    grid_min", gm, " argmin check:", int(np.argmin(np.array(L["j"]))) == gm["i_dm"] * 16 + gm["i_km"])

# (e) optimum cross-check: independent polish (restart NM with a tiny simplex + Powell)
print("(e) optimum cross-check")
O = exp["optimum"]
u = np.array([O["log_dm"], O["log_km"]])
f = lambda v: m.objective(preps, math.exp(v[0]), math.exp(v[1]))["j"]
r1 = minimize(f, u, method="Nelder-Mead", options=dict(initial_simplex=[u, u + [1e-3, 0], u + [0, 1e-3]],
                                                       xatol=1e-9, fatol=1e-15))
r2 = minimize(f, u + [0.05, -0.05], method="Powell", options=dict(xtol=1e-10, ftol=1e-15))
print("    expected: log D %.9f log K %.9f j %.15g" % (u[0], u[1], O["j"]))
print("    NM restart: log D %.9f log K %.9f j %.15g" % (r1.x[0], r1.x[1], r1.fun))
print("    Powell    : log D %.9f log K %.9f j %.15g" % (r2.x[0], r2.x[1], r2.fun))

# (f) sensitivity: does the test data discriminate the planted edge cases, and how much
#     do harmless implementation variants move the results?
print("(f) sensitivity")
def variant_d(stamps, pos, D=10.73, K=20.71):
    p = m.prepare_demo(stamps, pos, "v")
    return m.eval_demo(p, D, K)["d"], p
b = demos[1]
k = [i for i in range(1, len(b["stamps_ns"])) if b["stamps_ns"][i] == b["stamps_ns"][i - 1]][0]
st_last = b["stamps_ns"][:k - 1] + b["stamps_ns"][k:]; pos_last = b["positions"][:k - 1] + b["positions"][k:]
dl, _ = variant_d(st_last, pos_last)
print("    demo_b keep-LAST instead of first: d rel change %.1e" % rel(dl, exp["points"][0]["d"][1]))
# h from integer-ns median instead of float-second differences
for di, dd in enumerate(demos):
    stt, _ = m.sort_dedupe(dd["stamps_ns"], dd["positions"])
    h_int = float(np.median(np.diff(stt))) * 1e-9
    print("    %s: h(float diffs) %.17g  h(int diffs)*1e-9 %.17g  rel %.1e  T/h = %.6f"
          % (dd["name"], preps[di]["h"], h_int, rel(h_int, preps[di]["h"]), preps[di]["T"] / preps[di]["h"]))
# perturb y/yd/ydd by 1 ulp-ish relative noise and see how results move (conditioning)
rng = np.random.default_rng(1)
for D, K in [(10.73, 20.71), (0.1, 1000.0), (1000.0, 0.1), (1000.0, 1000.0), (0.1, 0.1)]:
    base = [m.eval_demo(p, D, K) for p in preps]
    Sb = m.similarity(preps, D, K)
    pert = []
    for p in preps:
        q = dict(p)
        for key in ("y", "yd", "ydd", "y_raw"):
            q[key] = p[key] * (1 + 4e-16 * rng.standard_normal(p[key].shape))
        pert.append(q)
    pe = [m.eval_demo(q, D, K) for q in pert]
    print("    D=%-6g K=%-6g ulp-perturbation -> rel change d %.1e  a_peak %.1e  S %.1e"
          % (D, K, max(rel(a["d"], b_["d"]) for a, b_ in zip(pe, base)),
             max(rel(a["a_peak"], b_["a_peak"]) for a, b_ in zip(pe, base)),
             rel(m.similarity(pert, D, K), Sb)))
