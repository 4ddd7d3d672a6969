"""Independent reference of method.md section 12: the orientation (quaternion) DMP.

Written from /work/shared/method.md (section 12 on sections 2-4) with docs/method.md section 12
read for the points the shared text leaves open; not from the Rust sources. Sections 2-4 for the
grid, Savitzky-Golay, basis, LWR and forcing term come from method.py. `python3 orientation.py`
runs the self-checks (prints only; they read ../../assets/planted8.mcap through
make_orientation.py's decoder).

Quaternions are (x, y, z, w) arrays in the last axis; `*` is the Hamilton product.

Choices where the shared method.md is open (also listed in README.md):
 1. Order: every sample's quaternion is normalised on reading (file order); the samples are then
    sorted and de-duplicated exactly as the positions (method.sort_dedupe's rule: stable sort on
    the integer-ns stamp, the first in file order of equal stamps kept), and sign continuity runs
    over that time order, sequentially: q_k is compared with the already-corrected q_{k-1}; a
    dot product of exactly 0 flips nothing. A quaternion that is not finite or has norm below
    1e-6 is an error (shared text: "zero"; docs/method.md's threshold for unusable).
 2. Slerp onto section 2's uniform grid linspace(0, T, n0), over the same knots and with the
    same interval choice as np.interp (j = the last knot <= t, clipped to [0, n-2];
    u = (t - t_j) / (t_{j+1} - t_j)). Slerp(a, b, u) = (sin((1-u) O) a + sin(u O) b) / sin O with
    O = 2 atan2(|a - b|, |a + b|) (the angle between a and b as 4-vectors, accurate at small O);
    O < 1e-12: (1-u) a + u b. The result is renormalised (a change of ~1e-16).
 3. q_raw on the 1001-point unit-time grid: slerped from the uniform grid (knots linspace(0, 1,
    n0), the same interval rule; docs/method.md section 12 step 4 says slerp), not linearly
    interpolated as section 2.6 would have it for positions: a component-wise interpolation is
    not unit and acos turns its norm deficit into a spurious angle (on planted8 d_rot grows
    1.6-5.1 times). Linear interpolation renormalised (nlerp) agrees with slerp to 7e-9 in d_rot.
    The goal is q_g = q_raw(1) (= the last sorted sample), as g = y_raw(1) for positions
    (shared text: q_g undefined; docs/method.md: "The goal is q_g = q_raw(1)").
 4. q, q', q'': savgol_filter(window 21, order 3, deriv 0/1/2, delta = h', mode "interp") on each
    of the four components of the slerped uniform-grid quaternions, derivatives times T and
    T^2, then linearly interpolated onto the 1001 grid like y, y', y'' (section 2.6); q is
    renormalised after that interpolation (on the 1001 grid); q' and q'' are not touched.
 5. w = 2 vec(q' * conj(q)), w' = 2 vec(q'' * conj(q)) with the renormalised q.
 6. f_o is fitted as F0 + D F1 + K F2 with F0 = f(lwr(w')), F1 = f(lwr(w)),
    F2 = f(lwr(-2 log(q_g * conj(q)))), f(.) = method.forcing; evaluated as
    (F0 + D F1) + K F2. Fitting f_o directly at the gains is the same up to rounding
    (d_rot within 4e-10 relative, self-check (c)).
 7. The rollout renormalises q_{k+1} after each step (the shared text does not say;
    docs/method.md and docs/export.md do). Without it |q| - 1 drifts to ~4e-15, which is harmless
    for q but not for theta = 2 acos(|dot|): near dot = 1 acos turns an error e in the dot into
    ~4 e / theta, so d_rot moves by up to 8e-8 relative on planted8 (self-check (c)). The same
    conditioning limits any comparison of d_rot to ~1e-7 relative: fitting f_o directly instead
    of F0 + D F1 + K F2 (a rounding-level change of f) moves d_rot by up to 4e-10 relative.
 8. alpha_peak = max over all n grid points k = 0..n-1, a_{n-1} computed from the final state,
    as a_peak in section 4.
"""
import os
import sys
import time

import numpy as np
from scipy.signal import savgol_filter

import method as m

N = m.N_GRID
DT = m.DT
QUAT_MIN_NORM = 1e-6
SLERP_SMALL = 1e-12


# ---- quaternion algebra (x, y, z, w), vectorised over leading axes ---------
def qmul(a, b):
    av, aw = a[..., :3], a[..., 3:]
    bv, bw = b[..., :3], b[..., 3:]
    v = aw * bv + bw * av + np.cross(av, bv)
    w = aw * bw - np.sum(av * bv, axis=-1, keepdims=True)
    return np.concatenate([v, w], axis=-1)


def conj(q):
    return np.concatenate([-q[..., :3], q[..., 3:]], axis=-1)


def vnorm(v):
    return np.sqrt(np.sum(v * v, axis=-1))


def qlog(q):
    """log of a unit quaternion (v, w): atan2(|v|, w) v / |v|, 0 when v = 0 (no hemisphere flip)."""
    v = q[..., :3]
    n = vnorm(v)
    ang = np.arctan2(n, q[..., 3])
    safe = np.where(n > 0.0, n, 1.0)
    return np.where((n > 0.0)[..., None], (ang / safe)[..., None] * v, 0.0)


def qexp(u):
    """exp of a 3-vector: (sin|u| u/|u|, cos|u|)."""
    n = vnorm(u)
    safe = np.where(n > 0.0, n, 1.0)
    v = np.where((n > 0.0)[..., None], (np.sin(n) / safe)[..., None] * u, 0.0)
    return np.concatenate([v, np.cos(n)[..., None]], axis=-1)


def qnormalise(q):
    return q / vnorm(q)[..., None]


def slerp(a, b, u):
    """Slerp between rows of a and b (..., 4) at fractions u (...)."""
    u = np.asarray(u, dtype=np.float64)[..., None]
    om = 2.0 * np.arctan2(vnorm(a - b), vnorm(a + b))[..., None]
    so = np.sin(om)
    small = om < SLERP_SMALL
    sso = np.where(small, 1.0, so)
    out = np.where(small, (1.0 - u) * a + u * b,
                   (np.sin((1.0 - u) * om) * a + np.sin(u * om) * b) / sso)
    return qnormalise(out)


def slerp_onto(knots, qk, x):
    """Slerp the unit quaternions qk (n, 4) given at increasing knots (n,) onto x (m,), with
    np.interp's choice of interval."""
    j = np.clip(np.searchsorted(knots, x, side="right") - 1, 0, len(knots) - 2)
    u = (x - knots[j]) / (knots[j + 1] - knots[j])
    out = slerp(qk[j], qk[j + 1], u)
    exact_lo = x == knots[j]
    exact_hi = x == knots[j + 1]
    out[exact_lo] = qk[j[exact_lo]]          # slerp(a, b, 0) = a, kept bit-exact
    out[exact_hi] = qk[j[exact_hi] + 1]
    return out


# ---- section 12 preparation ------------------------------------------------
def read_quaternions(quats, name="demo"):
    q = np.asarray(quats, dtype=np.float64)
    if q.ndim != 2 or q.shape[1] != 4:
        raise ValueError(f"{name}: quaternions must be (n, 4)")
    bad = np.nonzero(~np.all(np.isfinite(q), axis=1))[0]
    if bad.size:
        raise ValueError(f"{name}: non-finite quaternion at sample index {int(bad[0])} (file order)")
    nr = vnorm(q)
    bad = np.nonzero(nr < QUAT_MIN_NORM)[0]
    if bad.size:
        raise ValueError(f"{name}: zero quaternion at sample index {int(bad[0])} (file order)")
    return q / nr[:, None]


def sort_keep(stamps_ns):
    """Indices (file order) of the samples kept, in time order: method.sort_dedupe's rule."""
    st = np.asarray([int(s) for s in stamps_ns], dtype=np.int64)
    order = np.argsort(st, kind="stable")
    sst = st[order]
    keep = np.ones(sst.shape[0], dtype=bool)
    keep[1:] = sst[1:] != sst[:-1]
    return order[keep]


def sign_continuous(q):
    q = q.copy()
    for k in range(1, q.shape[0]):
        if float(np.dot(q[k], q[k - 1])) < 0.0:
            q[k] = -q[k]
    return q


def prepare_orientation(stamps_ns, positions, quats, name="demo"):
    """Section 12's preparation on section 2's grid (positions give T, h, n0, h')."""
    pp = m.prepare_demo(stamps_ns, positions, name)
    qr = read_quaternions(quats, name)
    sel = sort_keep(stamps_ns)
    assert np.array_equal(m.sort_dedupe(stamps_ns, positions)[1], np.asarray(positions)[sel])
    qs = sign_continuous(qr[sel])
    t = pp["t"]
    T, n0, hp = pp["T"], pp["n0"], pp["hp"]
    grid = pp["grid"]
    q_uni = slerp_onto(t, qs, grid)                                      # (n0, 4)
    sg = [savgol_filter(q_uni, m.SG_WINDOW, m.SG_ORDER, deriv=d, delta=hp, axis=0, mode="interp")
          for d in (0, 1, 2)]
    s0 = np.linspace(0.0, 1.0, n0)
    s = np.linspace(0.0, 1.0, N)

    def rs(arr):
        return np.stack([np.interp(s, s0, arr[:, c]) for c in range(4)], axis=1)

    q = qnormalise(rs(sg[0]))
    qd = rs(T * sg[1])
    qdd = rs(T * T * sg[2])
    q_raw = slerp_onto(s0, q_uni, s)
    goal = q_raw[-1].copy()
    w = 2.0 * qmul(qd, conj(q))[:, :3]
    wd = 2.0 * qmul(qdd, conj(q))[:, :3]
    glog = 2.0 * qlog(qmul(np.broadcast_to(goal, q.shape), conj(q)))     # 2 log(q_g * conj(q))
    F0 = m.forcing(m.lwr_weights(wd))
    F1 = m.forcing(m.lwr_weights(w))
    F2 = m.forcing(m.lwr_weights(-glog))
    return dict(name=name, T=T, n0=n0, hp=hp, n_samples=int(sel.shape[0]), q_sorted=qs,
                q_uniform=q_uni, q_raw=q_raw, q=q, qd=qd, qdd=qdd, w=w, wd=wd, goal=goal,
                glog=glog, F0=F0, F1=F1, F2=F2)


def forcing_o(prep, D, K):
    return (prep["F0"] + D * prep["F1"]) + K * prep["F2"]


def f_target_o(prep, D, K):
    return prep["wd"] + D * prep["w"] - K * prep["glog"]


# ---- section 12 rollout (section 4's order), vectorised over a batch ------
def rollout(D, K, f, q0, w0, goal, renormalise=True):
    """D, K (P,), f (P, n, 3), q0 (P, 4), w0 (P, 3), goal (P, 4).
    Returns q (P, n, 4), w (P, n, 3), a (P, n, 3); a[:, -1] from the final state."""
    D = np.asarray(D, dtype=np.float64)[:, None]
    K = np.asarray(K, dtype=np.float64)[:, None]
    P, n, _ = f.shape
    qs = np.empty((P, n, 4)); ws = np.empty((P, n, 3)); acc = np.empty((P, n, 3))
    qk = np.array(q0, dtype=np.float64); wk = np.array(w0, dtype=np.float64)
    for k in range(n):
        qs[:, k] = qk; ws[:, k] = wk
        ak = -D * wk + K * (2.0 * qlog(qmul(goal, conj(qk)))) + f[:, k]
        acc[:, k] = ak
        if k < n - 1:
            wk = wk + ak * DT
            qk = qmul(qexp(wk * (DT / 2.0)), qk)
            if renormalise:
                qk = qnormalise(qk)
    return qs, ws, acc


def errors(q_new, q_raw, acc):
    """theta (P, n), d_rot (P,), alpha_peak (P,)."""
    dot = np.abs(np.sum(q_new * q_raw, axis=-1))
    theta = 2.0 * np.arccos(np.minimum(1.0, dot))
    d_rot = np.trapezoid(theta, dx=DT, axis=-1)
    alpha = np.max(vnorm(acc), axis=-1)
    return theta, d_rot, alpha


def evaluate(preps, pairs, renormalise=True, f_override=None):
    """Every demo at every gain pair in one batch. Returns dict of arrays indexed
    [pair, demo]: d_rot, alpha_peak, q (regenerated, (n, 4)), a."""
    pairs = np.asarray(pairs, dtype=np.float64).reshape(-1, 2)
    P, M = pairs.shape[0], len(preps)
    D = np.repeat(pairs[:, 0], M); K = np.repeat(pairs[:, 1], M)
    f = np.empty((P * M, N, 3))
    for i in range(P):
        for j, p in enumerate(preps):
            f[i * M + j] = (forcing_o(p, pairs[i, 0], pairs[i, 1]) if f_override is None
                            else f_override(p, pairs[i, 0], pairs[i, 1]))
    q0 = np.tile(np.stack([p["q"][0] for p in preps]), (P, 1))
    w0 = np.tile(np.stack([p["w"][0] for p in preps]), (P, 1))
    goal = np.tile(np.stack([p["goal"] for p in preps]), (P, 1))
    q_raw = np.tile(np.stack([p["q_raw"] for p in preps]), (P, 1, 1))
    qn, wn, acc = rollout(D, K, f, q0, w0, goal, renormalise)
    theta, d_rot, alpha = errors(qn, q_raw, acc)
    return dict(d_rot=d_rot.reshape(P, M), alpha_peak=alpha.reshape(P, M),
                q=qn.reshape(P, M, N, 4), w=wn.reshape(P, M, N, 3), a=acc.reshape(P, M, N, 3),
                theta=theta.reshape(P, M, N))


def d_rot_grid(preps, dm, km, chunk=48):
    """sum over demos of d_rot on the grid [i_dm][i_km] (batched in chunks of gain pairs)."""
    pairs = np.array([(D, K) for D in dm for K in km])
    out = np.empty(len(pairs))
    for c in range(0, len(pairs), chunk):
        r = evaluate(preps, pairs[c:c + chunk])
        out[c:c + chunk] = r["d_rot"].sum(axis=1)
    return out.reshape(len(dm), len(km))


# ---- self-checks -----------------------------------------------------------
def _synthetic_dmp_demo(D, K, T=2.0, rate=100.0, substeps=20, angle=1.2,
                        axis=(1.0, 1.0, 0.3)):
    """A demo produced by integrating the orientation DMP itself at gains (D, K): its forcing
    term is the LWR fit (section 3's basis, on a fine grid) of the one a minimum-jerk turn by
    `angle` about `axis` needs; integrated in section 4's order from q0 with w = 0, with
    `substeps` steps per grid step, then sampled at `rate` Hz over T seconds."""
    ax = np.asarray(axis, dtype=np.float64)
    ax = ax / np.linalg.norm(ax)
    q0 = qexp(np.array([0.1, -0.2, 0.3]))
    qg = qmul(qexp(0.5 * angle * ax), q0)
    nf = (N - 1) * substeps + 1
    sf = np.linspace(0.0, 1.0, nf)
    mj = sf ** 3 * (10 - 15 * sf + 6 * sf ** 2)
    mjd = 30 * sf ** 2 * (1 - sf) ** 2
    mjdd = 60 * sf * (1 - sf) * (1 - 2 * sf)
    q_nom = qmul(qexp(0.5 * angle * mj[:, None] * ax), q0)
    w_nom = angle * mjd[:, None] * ax
    wd_nom = angle * mjdd[:, None] * ax
    f_nom = wd_nom + D * w_nom - K * 2.0 * qlog(qmul(np.broadcast_to(qg, q_nom.shape), conj(q_nom)))
    xf = m.phase(sf)
    psi = m.psi_matrix(xf)
    W = np.einsum("k,ki,ka->ia", xf, psi, f_nom) / ((xf ** 2)[:, None] * psi).sum(axis=0)[:, None]
    ff = xf[:, None] * (psi @ W) / psi.sum(axis=1)[:, None]
    dt = 1.0 / (nf - 1)
    qk, wk = q0.copy(), np.zeros(3)
    qf = np.empty((nf, 4))
    for k in range(nf):
        qf[k] = qk
        ak = -D * wk + K * 2.0 * qlog(qmul(qg, conj(qk))) + ff[k]
        wk = wk + ak * dt
        qk = qnormalise(qmul(qexp(wk * dt / 2.0), qk))
    n_s = int(round(T * rate)) + 1
    ts = np.arange(n_s) / rate
    qs = slerp_onto(sf, qf, ts / T)
    stamps = [1_700_000_000_000_000_000 + int(round(k * 1e9 / rate)) for k in range(n_s)]
    pos = np.stack([0.3 * ts / T, 0.1 * np.sin(ts), 0.05 * ts * ts], axis=1)
    return stamps, pos, qs, (sf, qf)


def _constant_rate_demo(T=1.5, rate=90.0, omega=(0.6, -0.3, 0.9)):
    """Rotation at a constant rate (rad/s, space frame) from a fixed start."""
    n_s = int(round(T * rate)) + 1
    ts = np.arange(n_s) / rate
    q0 = qexp(np.array([-0.3, 0.2, 0.5]))
    om = np.asarray(omega)
    qs = np.stack([qmul(qexp(om * t / 2.0), q0) for t in ts])
    stamps = [1_700_000_000_000_000_000 + int(round(k * 1e9 / rate)) for k in range(n_s)]
    pos = np.stack([0.2 * ts, 0.0 * ts, 0.1 * ts], axis=1)
    return stamps, pos, qs


def selfcheck(demos):
    t0 = time.time()
    ok = True

    def report(label, val, tol):
        nonlocal ok
        good = val <= tol
        ok &= good
        print(f"  {'ok  ' if good else 'FAIL'} {label}: {val:.3e} (tol {tol:.0e})")

    print("(0) algebra")
    rng = np.random.default_rng(1)
    u = rng.normal(size=(200, 3)) * 1.2
    report("log(exp(u)) = u for |u| < pi/2", float(np.max(np.abs(qlog(qexp(u * 0.5)) - u * 0.5))),
           1e-14)
    a = qnormalise(rng.normal(size=(200, 4))); b = qnormalise(rng.normal(size=(200, 4)))
    b = np.where((np.sum(a * b, axis=1) < 0)[:, None], -b, b)
    mid = slerp(a, b, 0.5)
    dev = np.abs(2 * np.arccos(np.minimum(1, np.abs(np.sum(a * mid, 1))))
                 - 2 * np.arccos(np.minimum(1, np.abs(np.sum(b * mid, 1)))))
    report("slerp midpoint equidistant", float(np.max(dev)), 1e-7)
    # slerp(a, b, u) = a * (conj(a) * b)^u via log/exp
    uu = rng.uniform(size=200)
    ref = qmul(a, qexp(uu[:, None] * qlog(qmul(conj(a), b))))
    report("slerp = a (a^-1 b)^u", float(np.max(np.abs(slerp(a, b, uu) - ref))), 1e-14)

    print("(a) regenerating demos the DMP could have produced")
    # Full pipeline: limited by section 3's LWR (100 phase bases; its error is largest near
    # x = 1), Savitzky-Golay and the 100/90 Hz sampling: ~0.05 deg at most. With the exact
    # target forcing term in place of the LWR fit only the smoothing and Euler errors remain.
    D, K = 25.0, 156.25
    deg = np.degrees
    stamps, pos, qs, _ = _synthetic_dmp_demo(D, K)
    p = prepare_orientation(stamps, pos, qs, "synthetic_dmp")
    r = evaluate([p], [(D, K), (10.73, 20.71)])
    print(f"  synthetic DMP demo (1.2 rad turn, T 2 s, 100 Hz) at 25/156.25: d_rot "
          f"{r['d_rot'][0, 0]:.3e} rad; at 10.73/20.71: {r['d_rot'][1, 0]:.3e} rad")
    report("synthetic DMP demo: d_rot at its gains (deg)", float(deg(r["d_rot"][0, 0])), 0.05)
    report("synthetic DMP demo: max theta at its gains (deg)", float(deg(r["theta"][0, 0].max())), 0.1)
    r2 = evaluate([p], [(D, K)], f_override=f_target_o)
    report("synthetic DMP demo, exact f_target: max theta (deg)", float(deg(r2["theta"][0, 0].max())),
           0.02)
    stamps, pos, qs = _constant_rate_demo()
    p = prepare_orientation(stamps, pos, qs, "constant_rate")
    wu = np.array([0.6, -0.3, 0.9]) * p["T"]
    report("constant rate: |w - omega T| / |omega T| (prepared)",
           float(np.max(vnorm(p["w"] - wu)) / np.linalg.norm(wu)), 1e-4)
    report("constant rate: |w'| / |omega T|^2 (prepared, exact 0)",
           float(np.max(vnorm(p["wd"]))) / float(wu @ wu), 1e-3)
    r = evaluate([p], [(D, K), (10.73, 20.71)])
    print(f"  constant-rate demo (1.12 rad/s, 1.5 s, 90 Hz): d_rot {r['d_rot'][0, 0]:.3e} (25/156.25), "
          f"{r['d_rot'][1, 0]:.3e} (10.73/20.71) rad")
    for i, (D_, K_) in enumerate([(D, K), (10.73, 20.71)]):
        report(f"constant rate: max theta at {D_}/{K_} (deg)", float(deg(r["theta"][i, 0].max())), 0.1)
    r2 = evaluate([p], [(D, K)], f_override=f_target_o)
    report("constant rate, exact f_target: max theta (deg)", float(deg(r2["theta"][0, 0].max())), 1e-3)

    print("(b) sign flips change nothing (planted8)")
    pairs = [(10.73, 20.71), (25.0, 156.25), (2.0, 900.0), (0.1, 1000.0)]
    preps = [prepare_orientation(d["stamps_ns"], d["positions"], d["orientations"], d["name"])
             for d in demos]
    base = evaluate(preps, pairs)
    rng = np.random.default_rng(11)
    flipped = []
    for i, d in enumerate(demos):
        q = np.array(d["orientations"], dtype=np.float64)
        if i % 3 == 0:
            q = -q                                          # whole demo (between demos)
        if i % 2 == 0:
            q[rng.random(q.shape[0]) < 0.3] *= -1.0         # random samples within a demo
        if i == 1:
            q[0] *= -1.0                                    # its first sample too
        flipped.append(prepare_orientation(d["stamps_ns"], d["positions"], q, d["name"]))
    alt = evaluate(flipped, pairs)
    for key in ("d_rot", "alpha_peak"):
        report(f"flips: max |diff| {key}", float(np.max(np.abs(alt[key] - base[key]))), 0.0)
    # the regenerated q may be negated as a whole (a demo flipped at its start); compare up to sign
    sgn = np.sign(np.sum(alt["q"][:, :, :1] * base["q"][:, :, :1], axis=-1))[..., None]
    report("flips: max |diff| regenerated q (up to a demo's overall sign)",
           float(np.max(np.abs(alt["q"] * sgn - base["q"]))), 0.0)
    dm = np.logspace(-1, 3, 4)
    g1 = d_rot_grid(preps, dm, dm); g2 = d_rot_grid(flipped, dm, dm)
    report("flips: max |diff| d_rot_sum on a 4 x 4 grid", float(np.max(np.abs(g1 - g2))), 0.0)

    print("(c) the quaternion stays unit")
    big = evaluate(preps, [(D_, K_) for D_ in np.logspace(-1, 3, 5) for K_ in np.logspace(-1, 3, 5)])
    report("max ||q_new| - 1| over 8 demos x 25 gain pairs", float(np.max(np.abs(vnorm(big["q"]) - 1))),
           1e-13)
    report("max ||q| - 1| prepared q, q_raw", max(float(np.max(np.abs(vnorm(p_["q"]) - 1))) for p_ in preps)
           + max(float(np.max(np.abs(vnorm(p_["q_raw"]) - 1))) for p_ in preps), 1e-15)
    raw = evaluate(preps, pairs, renormalise=False)
    report("max ||q_new| - 1| without per-step renormalisation",
           float(np.max(np.abs(vnorm(raw["q"]) - 1))), 1e-13)
    report("without per-step renormalisation: max |diff| d_rot (rel; acos's conditioning)",
           float(np.max(np.abs(raw["d_rot"] - base["d_rot"]) / base["d_rot"])), 1e-6)
    # direct fit of f_o at the gains equals F0 + D F1 + K F2
    fd = evaluate(preps, pairs, f_override=lambda p_, D_, K_: m.forcing(m.lwr_weights(f_target_o(p_, D_, K_))))
    rel = np.abs(fd["d_rot"] - base["d_rot"]) / base["d_rot"]
    report("direct f_o fit vs F0 + D F1 + K F2: max |diff| d_rot (rel)", float(np.max(rel)), 1e-7)
    print("    per pair:", ", ".join(f"{D_}/{K_}: {float(np.max(rel[i])):.1e}"
                                     for i, (D_, K_) in enumerate(pairs)))
    # scalar rollout of one demo at one pair equals the batch
    one = evaluate(preps[2:3], pairs[1:2])
    report("batch vs single rollout d_rot (rel)",
           abs(float(one["d_rot"][0, 0]) - float(base["d_rot"][1, 2])) / float(base["d_rot"][1, 2]), 1e-14)
    print(f"selfcheck {'ok' if ok else 'FAILED'} ({time.time() - t0:.1f} s)")
    return ok


if __name__ == "__main__":
    import make_orientation as mo
    demos, _ = mo.read(os.path.join(mo.ASSETS, "planted8.mcap"))
    sys.exit(0 if selfcheck(demos) else 1)
