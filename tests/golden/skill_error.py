"""Independent reference of docs/method.md section 11: the skill error E (modes frame,
per-axis, none), E's depth, and the acceptable region of J.

Written from the method text on method.py (sections 1-4) and generalise.py (section 10's
maps and skill), not from the Rust sources. E is computed the direct way: at each gain pair
every demo's forcing term is fitted, the skill is their mapped mean (generalise.skill_dmp),
and it is rolled out to each demo's own start and goal with generalise.rollout_unit.
"""
import math

import numpy as np

import generalise as gz
import method as m

MODES = ("frame", "per-axis", "none")
FLAT = 0.02


def _scaling(mode):
    return {"frame": "frame", "per-axis": "paper"}.get(mode)


def skill_errors(preps, D, K, mode):
    """e_i of every demo at (D, K): the one skill of all demos mapped back to demo i's own
    start and goal, against the demo's raw path (absolute), trapezoid over unit time."""
    dmps = [gz.demo_dmp(p, D, K) for p in preps]
    scaling = _scaling(mode)
    if scaling is None:
        f = np.mean(np.stack([q["f"] for q in dmps]), axis=0)
        v0 = np.mean(np.stack([q["v0"] for q in dmps]), axis=0)
        d_bar = None
    else:
        sk = gz.skill_dmp(dmps, scaling)       # raises for a frame skill without direction
        f, v0, d_bar = sk["f"], sk["v0"], sk["d"]
    out = []
    for p, q in zip(preps, dmps):
        Q = np.eye(3) if scaling is None else gz.scaling_map(d_bar, q["d"], scaling)
        y, _, _ = gz.rollout_unit(D, K, q["y0"], q["g"], gz.apply_q(Q, f), gz.apply_q(Q, v0))
        target = p["p0"] + p["y_raw"]
        out.append(m.trapz_unit(np.linalg.norm(y - target, axis=1)))
    return out


def depth_of_grid_min(E):
    """Section 9's depth on E with E's grid minimum as the reference."""
    edge = np.concatenate([E[0, :], E[-1, :], E[:, 0], E[:, -1]])
    return max(0.0, float(np.min(edge)) / float(np.min(E)) - 1.0)


def acceptable(J, j_star, Dg, Kg, eps=0.02):
    """The grid points with J <= (1 + eps) J*: fraction, and D/M, K/M, zeta ranges."""
    inside = J <= (1.0 + eps) * j_star
    idx = np.argwhere(inside)
    if idx.size == 0:
        return dict(eps=eps, fraction=0.0, dm=None, km=None, zeta=None)
    D = np.array([Dg[i] for i, _ in idx])
    K = np.array([Kg[j] for _, j in idx])
    z = D / (2.0 * np.sqrt(K))
    return dict(eps=eps, fraction=float(inside.sum()) / inside.size,
                dm=[float(D.min()), float(D.max())], km=[float(K.min()), float(K.max())],
                zeta=[float(z.min()), float(z.max())])


def selfcheck(preps):
    """One demo: E = d; mode none with identical displacements equals frame."""
    for D, K in [(10.73, 20.71), (25.0, 156.25)]:
        e = skill_errors(preps[:1], D, K, "frame")[0]
        d = m.eval_demo(preps[0], D, K)["d"]
        assert abs(e - d) <= 1e-12 * max(d, 1e-12), (e, d)
    print("skill_error selfcheck ok")
