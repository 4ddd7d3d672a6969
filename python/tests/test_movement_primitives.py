"""dmpscope's gains in movement_primitives' DMP: alpha_y = D/M, beta_y = K/D.

Skipped when movement_primitives (with pytransform3d) is not installed.
"""

from __future__ import annotations

import numpy as np
import pytest

import dmpscope

mp_dmp = pytest.importorskip("movement_primitives.dmp")
mp_module = pytest.importorskip("movement_primitives.dmp._dmp")


def test_the_conversion_is_movement_primitives_convention():
    """mp's transformation system at alpha_y, beta_y, in unit time, is dmpscope's."""
    dm, km, tau = 14.0, 70.0, 2.5
    gains = dmpscope.movement_primitives_gains(dm, km)
    assert gains == {"alpha_y": dm, "beta_y": km / dm}
    rng = np.random.default_rng(3)
    y, v, g = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    zero = np.zeros(3)
    ydd = mp_module._dmp_acc(
        y, v, zero, np.full(3, gains["alpha_y"]), np.full(3, gains["beta_y"]), g, zero,
        zero, zero, 1.0, tau, zero, None, 0.0, False,
    )
    # Unit time u = t / tau: y_u = tau v, y_uu = tau^2 ydd.
    unit = tau**2 * ydd
    assert np.allclose(unit, -dm * (tau * v) - km * (y - g), rtol=1e-12, atol=1e-12)


def test_a_dmp_fitted_at_the_picked_gains_reproduces_the_demo(planted):
    report = dmpscope.extract(planted, grid=24, diagnostics=False)
    dm, km = report.pick.dm, report.pick.km
    demo = planted[0]
    t, y = demo.t, demo.positions
    tau = float(t[-1])
    dmp = mp_dmp.DMP(
        n_dims=3, execution_time=tau, dt=tau / (len(t) - 1), n_weights_per_dim=50,
        **dmpscope.movement_primitives_gains(dm, km),
    )
    dmp.imitate(t, y)
    dmp.configure(start_y=y[0], goal_y=y[-1])
    t_mp, y_mp = dmp.open_loop(step_function="euler")
    ours = dmpscope.regen(planted, dm, km, demo=0)
    # Both DMPs reproduce the demo at these gains: on dmpscope's time grid
    # they agree to a few millimetres, and both end at the goal.
    mp_on_ours = np.column_stack([np.interp(ours.t, t_mp, y_mp[:, a]) for a in range(3)])
    rms = np.sqrt(np.mean(np.sum((mp_on_ours - ours.positions) ** 2, axis=1)))
    assert rms < 0.01, rms
    assert np.linalg.norm(y_mp[-1] - y[-1]) < 0.01
    assert ours.final_error < 0.01
