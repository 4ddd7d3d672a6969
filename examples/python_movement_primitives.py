#!/usr/bin/env python3
"""Fit movement_primitives' DMP with gains dmpscope picked from the demos.

    pip install ./python movement_primitives pytransform3d
    python examples/python_movement_primitives.py

movement_primitives' transformation system is
``tau^2 y'' = alpha_y (beta_y (g - y) - tau y') + f`` with ``tau`` the
execution time. In unit time (the motion lasts 1) it is dmpscope's
``y'' = -D/M y' - K/M (y - g) + f`` with ``alpha_y = D/M`` and
``beta_y = K/D = (K/M) / (D/M)``: ``dmpscope.movement_primitives_gains``
does this, and ``execution_time`` is the demo's duration in seconds.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

import dmpscope

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    try:
        from movement_primitives.dmp import DMP
    except ImportError:
        raise SystemExit("needs movement_primitives: pip install movement_primitives pytransform3d")
    warnings.simplefilter("ignore", dmpscope.DmpscopeNote)
    demos = dmpscope.load(ROOT / "assets" / "planted8.mcap")
    report = dmpscope.extract(demos, diagnostics=False)
    pick = report.pick
    gains = dmpscope.movement_primitives_gains(pick.dm, pick.km)
    print(f"{pick}  ->  movement_primitives: alpha_y {gains['alpha_y']:.4f}, beta_y {gains['beta_y']:.4f}")

    demo = demos[0]
    tau = float(demo.t[-1])
    dmp = DMP(n_dims=3, execution_time=tau, dt=tau / (len(demo.t) - 1), n_weights_per_dim=50, **gains)
    dmp.imitate(demo.t, demo.positions)

    # The demo's own start and goal, then a goal 10 cm further along x.
    for name, goal in [("own goal", demo.positions[-1]), ("goal + 10 cm x", demo.positions[-1] + [0.1, 0, 0])]:
        dmp.configure(start_y=demo.positions[0], goal_y=goal)
        t, y = dmp.open_loop(step_function="euler")
        ours = dmpscope.regen(demos, pick.dm, pick.km, demo=0, goal=tuple(goal))
        on_ours = np.column_stack([np.interp(ours.t, t, y[:, a]) for a in range(3)])
        gap = np.linalg.norm(on_ours - ours.positions, axis=1)
        print(
            f"{name}: movement_primitives ends {1e3 * np.linalg.norm(y[-1] - goal):.2f} mm from "
            f"the goal; its path is {1e3 * gap.mean():.2f} mm (mean) from dmpscope's regen"
        )


if __name__ == "__main__":
    main()
