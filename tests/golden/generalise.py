"""Independent reference of docs/method.md section 10 (a new start, goal and duration;
one skill from many demos), with R and the integration as docs/export.md spells them out.

Sections 1-4 (preparation, LWR fit, forcing term, section 4's Euler) come from method.py;
everything here is written from the two documents, not from the Rust sources.

Conventions (see README.md, "Conventions in expected_generalise.json"):
- a demo's DMP is absolute: start y0 = p0, goal g = p0 + g_rel, d = g - y0 (float difference
  of the absolute vectors), duration T, forcing f (n, 3) and initial velocity v0 = y'(0) in
  unit time;
- Q maps d to d' = g' - y0'; f' = Q f, v0' = Q v0; the integration is section 4's semi-implicit
  Euler in the variable z = y - g', the output y_0 = y0' exactly and y_k = z_k + g' after.
"""
import math

import numpy as np

import method as m

SMALL_AXIS = 1e-9          # |d_a| below this: per-axis factor left at 1; |d| below: frame refused
PARALLEL_SIN = 1e-15       # sin below this with cos > 0: parallel (identity)
OPPOSITE_SIN = 1e-6        # sin below this with cos <= 0: opposite (pi turn)


# ---- the map Q -------------------------------------------------------------
def _norm(v):
    return math.sqrt(float(v[0]) ** 2 + float(v[1]) ** 2 + float(v[2]) ** 2)


def _cross(a, b):
    return np.array([a[1] * b[2] - a[2] * b[1],
                     a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]], dtype=np.float64)


def rodrigues(k, S, V):
    """export.md's matrix for unit axis k, S = sin(theta), V = 1 - cos(theta)."""
    kx, ky, kz = (float(c) for c in k)
    return np.array([
        [1 - V * (ky * ky + kz * kz), V * kx * ky - S * kz, V * kx * kz + S * ky],
        [V * kx * ky + S * kz, 1 - V * (kx * kx + kz * kz), V * ky * kz - S * kx],
        [V * kx * kz - S * ky, V * ky * kz + S * kx, 1 - V * (kx * kx + ky * ky)],
    ], dtype=np.float64)


def smallest_rotation(e, ep):
    """The smallest rotation taking unit e to unit e' (export.md)."""
    k = _cross(e, ep)
    sin = _norm(k)
    cos = float(e @ ep)
    if sin < PARALLEL_SIN and cos > 0:
        return np.eye(3)
    if sin < OPPOSITE_SIN and cos <= 0:
        # opposite: pi about e x c / |e x c|, c the axis of |e|'s smallest component (first)
        c = np.zeros(3)
        c[int(np.argmin(np.abs(e)))] = 1.0
        ax = _cross(e, c)
        ax = ax / _norm(ax)
        return rodrigues(ax, 0.0, 2.0)           # theta = pi: S = 0, V = 2 exactly
    k = k / sin
    theta = math.atan2(sin, cos)
    return rodrigues(k, math.sin(theta), 1.0 - math.cos(theta))


def scaling_map(d, dp, mode):
    """Q from d to d' (3 x 3)."""
    d = np.asarray(d, dtype=np.float64)
    dp = np.asarray(dp, dtype=np.float64)
    if not (np.all(np.isfinite(d)) and np.all(np.isfinite(dp))):
        raise ValueError("non-finite displacement")
    if np.all(dp == d):
        return np.eye(3)
    if mode == "paper":
        q = np.ones(3)
        for a in range(3):
            if abs(d[a]) >= SMALL_AXIS:
                q[a] = dp[a] / d[a]
        return np.diag(q)
    if mode == "frame":
        nd = _norm(d)
        if nd < SMALL_AXIS:
            raise ValueError("frame-independent scaling needs |g - y0| >= 1e-9 "
                             "(the motion ends where it starts)")
        ndp = _norm(dp)
        R = smallest_rotation(d / nd, dp / ndp)
        return (ndp / nd) * R
    raise ValueError(f"unknown scaling mode {mode!r}")


def apply_q(Q, f):
    """Q applied to each row of f (n, 3) or to a vector (3,)."""
    f = np.asarray(f, dtype=np.float64)
    return f @ Q.T if f.ndim == 2 else Q @ f


# ---- section 10's integration -----------------------------------------------
def rollout_unit(D, K, start, goal, f, v0):
    """Semi-implicit Euler of section 4 in z = y - goal, unit time.
    Returns y (n,3) absolute, v (n,3), a (n,3) in unit time; y[0] = start exactly."""
    start = np.asarray(start, dtype=np.float64)
    goal = np.asarray(goal, dtype=np.float64)
    n = f.shape[0]
    y = np.empty((n, 3)); v = np.empty((n, 3)); a = np.empty((n, 3))
    zk = start - goal
    vk = np.array(v0, dtype=np.float64)
    for k in range(n):
        y[k] = start if k == 0 else zk + goal
        v[k] = vk
        ak = -D * vk - K * zk + f[k]
        a[k] = ak
        if k < n - 1:
            vk = vk + ak * m.DT
            zk = zk + vk * m.DT
    return y, v, a


def real_time(y, v, a, tau):
    n = y.shape[0]
    t = np.array([tau * k / (n - 1) for k in range(n)])
    return dict(t=t, y=y, v=v / tau, a=a / (tau * tau))


def check_target(start, goal, tau):
    for nm, val in (("start", start), ("goal", goal)):
        if not np.all(np.isfinite(val)):
            raise ValueError(f"{nm} is not finite")
    if np.all(np.asarray(goal) == np.asarray(start)):
        raise ValueError("goal equals the start")
    if not (isinstance(tau, (int, float)) and math.isfinite(tau) and tau > 0):
        raise ValueError("duration must be a positive finite number")


# ---- a demo's DMP --------------------------------------------------------------
def demo_dmp(prep, D, K):
    """The fitted DMP of one prepared demo (method.py), absolute positions."""
    w = m.lwr_weights(m.f_target(prep, D, K))
    f = m.forcing(w)
    y0 = prep["p0"].copy()                      # y_raw(0) = 0, so the start is p0
    g = prep["p0"] + prep["g"]
    return dict(y0=y0, g=g, d=g - y0, T=float(prep["T"]), f=f, w=w, v0=prep["yd"][0].copy())


def generalise(dmp, D, K, mode, start=None, goal=None, duration=None):
    """Roll a DMP (demo_dmp or skill) out to (start', goal', T'); None = its own."""
    sp = dmp["y0"] if start is None else np.asarray(start, dtype=np.float64)
    gp = dmp["g"] if goal is None else np.asarray(goal, dtype=np.float64)
    tau = dmp["T"] if duration is None else float(duration)
    check_target(sp, gp, tau)
    dp = dmp["d"] if (start is None and goal is None) else gp - sp
    Q = scaling_map(dmp["d"], dp, mode)
    y, v, a = rollout_unit(D, K, sp, gp, apply_q(Q, dmp["f"]), apply_q(Q, dmp["v0"]))
    out = real_time(y, v, a, tau)
    out.update(Q=Q, start=sp, goal=gp, tau=tau, y_unit=y, v_unit=v, a_unit=a)
    return out


# ---- one skill from many demos ---------------------------------------------------
def skill_dmp(dmps, mode):
    N = len(dmps)
    d_bar = np.mean(np.stack([q["d"] for q in dmps]), axis=0)
    if mode == "frame" and _norm(d_bar) < SMALL_AXIS:
        raise ValueError("frame-independent skill needs |d_bar| >= 1e-9")
    Qs = [scaling_map(q["d"], d_bar, mode) for q in dmps]
    fs = np.stack([apply_q(Qi, q["f"]) for Qi, q in zip(Qs, dmps)])        # (N, n, 3)
    vs = np.stack([apply_q(Qi, q["v0"]) for Qi, q in zip(Qs, dmps)])       # (N, 3)
    ws = np.stack([apply_q(Qi, q["w"]) for Qi, q in zip(Qs, dmps)])        # (N, B, 3)
    start = np.mean(np.stack([q["y0"] for q in dmps]), axis=0)
    sd = fs.std(axis=0, ddof=1) if N > 1 else np.zeros_like(fs[0])
    return dict(y0=start, g=start + d_bar, d=d_bar, T=float(np.mean([q["T"] for q in dmps])),
                f=fs.mean(axis=0), v0=vs.mean(axis=0), w=ws.mean(axis=0), forcing_sd=sd,
                Q_members=Qs, member_f=fs, member_v0=vs, N=N)


def generalise_skill(sk, D, K, mode, start=None, goal=None, duration=None):
    out = generalise(sk, D, K, mode, start, goal, duration)
    Q = out["Q"]
    ys = []
    for fi, vi in zip(sk["member_f"], sk["member_v0"]):
        yi, _, _ = rollout_unit(D, K, out["start"], out["goal"], apply_q(Q, fi), apply_q(Q, vi))
        ys.append(yi)
    ys = np.stack(ys)
    out["band"] = ys.std(axis=0, ddof=1) if sk["N"] > 1 else np.zeros_like(ys[0])
    out["member_y"] = ys
    return out


# ---- self-checks ---------------------------------------------------------------------
def rot_z(theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def selfcheck(preps):
    """Returns a list of (name, max abs error) and prints them."""
    res = []
    # case 4: own target = section 4's regenerate (+ p0)
    p = preps[0]; D, K = 4.0, 4.0
    dm = demo_dmp(p, D, K)
    o = generalise(dm, D, K, "paper")
    y, v, a = m.regenerate(D, K, p["g"], dm["f"], p["y_raw"][0], p["yd"][0])
    res.append(("case4 y vs regenerate + p0", float(np.max(np.abs(o["y"] - (y + p["p0"]))))))
    res.append(("case4 v*T vs regenerate", float(np.max(np.abs(o["v_unit"] - v)))))
    res.append(("case4 a*T^2 vs regenerate", float(np.max(np.abs(o["a_unit"] - a)))))
    res.append(("case4 Q == I", float(np.max(np.abs(o["Q"] - np.eye(3))))))
    # case 2: linearity, y' = start' + Q (y_own - y0) with Q = 0.7 R (R the smallest rotation)
    p = preps[1]; D, K = 25.0, 156.25
    dm = demo_dmp(p, D, K)
    own = generalise(dm, D, K, "frame")
    R0 = rot_z(0.9)
    goal = dm["y0"] + 0.7 * (R0 @ dm["d"])
    o = generalise(dm, D, K, "frame", start=dm["y0"], goal=goal, duration=0.8)
    Q = o["Q"]
    res.append(("case2 y vs start + Q (own - start)",
                float(np.max(np.abs(o["y"] - (dm["y0"] + apply_q(Q, own["y"] - dm["y0"])))))))
    res.append(("case2 Q d vs d'", float(np.max(np.abs(Q @ dm["d"] - (goal - dm["y0"]))))))
    res.append(("case2 Q/0.7 orthogonal, det 1",
                float(max(np.max(np.abs((Q / 0.7) @ (Q / 0.7).T - np.eye(3))),
                          abs(np.linalg.det(Q / 0.7) - 1.0)))))
    res.append(("case2 (info) |Q - 0.7 R0| (R0 = rot_z(0.9); equal only if d is in the xy plane)",
                float(np.max(np.abs(Q - 0.7 * R0)))))
    res.append(("case2 (info) y vs start + 0.7 R0 (own - start)",
                float(np.max(np.abs(o["y"] - (dm["y0"] + apply_q(0.7 * R0, own["y"] - dm["y0"])))))))
    # a demo whose d lies in the xy plane: then the smallest rotation is R0 itself
    dflat = dm.copy(); dflat["g"] = dm["y0"] + np.array([dm["d"][0], dm["d"][1], 0.0])
    dflat["d"] = dflat["g"] - dflat["y0"]
    goal = dflat["y0"] + 0.7 * (R0 @ dflat["d"])
    of = generalise(dflat, D, K, "frame", start=dflat["y0"], goal=goal)
    ownf = generalise(dflat, D, K, "frame")
    res.append(("xy-plane d: Q vs 0.7 R0", float(np.max(np.abs(of["Q"] - 0.7 * R0)))))
    res.append(("xy-plane d: y vs start + 0.7 R0 (own - start)",
                float(np.max(np.abs(of["y"] - (dflat["y0"] + apply_q(0.7 * R0, ownf["y"] - dflat["y0"])))))))
    # case 3: opposite direction, pi turn: R d = -d, y' = start + R (own - start)
    p = preps[2]; D, K = 10.73, 20.71
    dm = demo_dmp(p, D, K)
    own = generalise(dm, D, K, "frame")
    o = generalise(dm, D, K, "frame", goal=dm["y0"] - dm["d"])
    res.append(("case3 Q d vs -d", float(np.max(np.abs(o["Q"] @ dm["d"] + dm["d"])))))
    res.append(("case3 y vs start + Q (own - start)",
                float(np.max(np.abs(o["y"] - (dm["y0"] + apply_q(o["Q"], own["y"] - dm["y0"])))))))
    # skill: the rollout is the mean of the members' rollouts; f_bar = forcing(mean Q_i w_i)
    dms = [demo_dmp(q, D, K) for q in preps]
    for mode in ("paper", "frame"):
        sk = skill_dmp(dms, mode)
        o = generalise_skill(sk, D, K, mode, start=[0.1, 0.2, 0.3], goal=[0.4, 0.6, 0.1], duration=3.0)
        res.append((f"skill {mode}: y vs mean of members", float(np.max(np.abs(o["y"] - o["member_y"].mean(axis=0))))))
        res.append((f"skill {mode}: f_bar vs forcing(mean Q_i w_i)", float(np.max(np.abs(sk["f"] - m.forcing(sk["w"]))))))
        res.append((f"skill {mode}: Q_i d_i vs d_bar",
                    float(max(np.max(np.abs(Qi @ q["d"] - sk["d"])) for Qi, q in zip(sk["Q_members"], dms)))))
    for name, err in res:
        print(f"  {err:10.3e}  {name}")
    return res


if __name__ == "__main__":
    import json
    import os
    import time
    t0 = time.time()
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "input.json")) as fh:
        demos = json.load(fh)["demos"]
    preps = [m.prepare_demo(d["stamps_ns"], d["positions"], d["name"]) for d in demos]
    selfcheck(preps)
    print(f"  {time.time() - t0:.2f} s")
