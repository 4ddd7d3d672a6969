#!/usr/bin/env python3
"""A peer's implementation as the check of docs/method.md section 12 (the orientation DMP):
fit movement_primitives' CartesianDMP (PyPI `movement_primitives`, Ude et al. 2014) to one
synthetic demo at alpha_y 25, beta_y 6.25 (D/M 25 and K/M 156.25 in unit time) and write its
regenerated orientation path with the demo (input and output in
expected_orientation_peer.json). dmpscope fits and regenerates the same demo at the same gains
in core/tests/golden_orientation.rs and compares the two paths."""
import json
import os

import numpy as np
from movement_primitives.dmp import CartesianDMP

HERE = os.path.dirname(os.path.abspath(__file__))
T = 2.0
RATE = 100.0
AXIS = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
ANGLE = 1.4


def qmul(a, b):
    """Hamilton product of (x, y, z, w) quaternions."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array([aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw,
                     aw * bw - ax * bx - ay * by - az * bz])


def qexp(u):
    n = np.linalg.norm(u)
    if n == 0.0:
        return np.array([0.0, 0.0, 0.0, 1.0])
    return np.concatenate([np.sin(n) * u / n, [np.cos(n)]])


START = qexp(np.array([0.1, -0.2, 0.3]))


def demo(t):
    """Minimum-jerk turn by ANGLE about AXIS from START, and a straight reach."""
    u = t / T
    s = u ** 3 * (10 - 15 * u + 6 * u * u)
    q = qmul(qexp(0.5 * ANGLE * s * AXIS), START)
    return np.array([0.3 * s, 0.1 * s, 0.05 * s]), q / np.linalg.norm(q)


def main():
    n = int(T * RATE) + 1
    t = np.arange(n) / RATE
    stamps = [1_700_000_000_000_000_000 + k * 10_000_000 for k in range(n)]
    pos, quat = zip(*(demo(tk) for tk in t))
    pos, quat = np.array(pos), np.array(quat)
    wxyz = quat[:, [3, 0, 1, 2]]
    dmp = CartesianDMP(execution_time=T, dt=0.01, n_weights_per_dim=50, int_dt=0.001,
                       alpha_y=25.0, beta_y=6.25)
    dmp.imitate(t, np.hstack([pos, wxyz]))
    t_out, y_out = dmp.open_loop()
    peer = y_out[:, [4, 5, 6, 3]]                       # back to (x, y, z, w)
    out = dict(
        meta=dict(peer="movement_primitives CartesianDMP", alpha_y=25.0, beta_y=6.25,
                  n_weights_per_dim=50, dt=0.01, int_dt=0.001, T=T,
                  note="quaternions (x, y, z, w); peer path at t_out"),
        demo=dict(stamps_ns=stamps, positions=pos.tolist(), orientations=quat.tolist()),
        t_out=t_out.tolist(), peer=peer.tolist(),
        demo_at_t_out=[demo(tk)[1].tolist() for tk in t_out],
    )
    path = os.path.join(HERE, "expected_orientation_peer.json")
    with open(path, "w") as fh:
        json.dump(out, fh)
    ang = [2 * np.arccos(min(1.0, abs(float(np.dot(a, b))))) for a, b in
           zip(peer, out["demo_at_t_out"])]
    print("wrote", path, "peer vs demo: max %.4f deg" % np.degrees(max(ang)))


if __name__ == "__main__":
    main()
