"""dmpscope: DMP gains from recorded hand-motion demos.

The core of dmpscope (the code the ``dmpscope`` CLI and app run) with NumPy
arrays in and out:

>>> import dmpscope
>>> demos = dmpscope.load(["assets/planted8.mcap"])        # doctest: +SKIP
>>> report = dmpscope.extract(demos)                        # doctest: +SKIP
>>> print(report.pick)                                      # doctest: +SKIP
picked by optimum: D/M ..., K/M ... (zeta ...)

- ``load(paths, ...)`` reads recordings (MCAP, ROS 1 bags, rosbag2
  folders, CSV) into ``Demo`` objects; ``Demo(t, positions,
  orientations=None, name=None)`` makes one from arrays.
- ``landscape(demos, ...)`` maps sum d, S, J, a_peak, E and d_rot over a
  grid of gain pairs (D/M, K/M) and finds J's optimum.
- ``extract(demos or landscape, ...)`` adds the diagnostics, what the
  demos determine, the pick for the robot and Table I (``Report``).
- ``regen(demos, dm, km, ...)`` runs the DMPs at a gain pair, at their own
  or a new start, goal and duration (``Rollout``); ``export(...)`` writes
  the DMP document a controller runs (docs/export.md).
- ``movement_primitives_gains(dm, km)`` converts a gain pair to
  movement_primitives' ``alpha_y``, ``beta_y``.

Every number equals the CLI's to the bit. Errors are ``DmpscopeError`` (a
``ValueError``; also ``Error``) in the CLI's words, or
``FileNotFoundError``; notices are warnings of category
``DmpscopeWarning`` (notes: ``DmpscopeNote``). See docs/python.md.
"""

from __future__ import annotations

from ._core import (
    Demo,
    DmpscopeError,
    DmpscopeNote,
    DmpscopeWarning,
    Landscape,
    Pick,
    Report,
    Rollout,
    defaults,
    export,
    extract,
    landscape,
    load,
    regen,
)

#: The package's exception: the same class as ``DmpscopeError``.
Error = DmpscopeError

__all__ = [
    "Demo",
    "DmpscopeError",
    "DmpscopeNote",
    "DmpscopeWarning",
    "Error",
    "Landscape",
    "Pick",
    "Report",
    "Rollout",
    "defaults",
    "export",
    "extract",
    "landscape",
    "load",
    "movement_primitives_gains",
    "regen",
]


def movement_primitives_gains(dm: float, km: float) -> dict[str, float]:
    """dmpscope's gains as movement_primitives' ``DMP(alpha_y=, beta_y=)``.

    movement_primitives' transformation system is
    ``tau^2 y'' = alpha_y (beta_y (g - y) - tau y') + f`` with ``tau`` the
    execution time; in unit time ``u = t / tau`` that is
    ``y_uu = -alpha_y y_u - alpha_y beta_y (y - g) + f``, dmpscope's
    ``y_uu = -D/M y_u - K/M (y - g) + f``. So ``alpha_y = D/M`` and
    ``beta_y = (K/M) / (D/M) = K/D``, with ``execution_time`` the demo's
    duration in seconds.

    Parameters
    ----------
    dm : float
        D/M, per unit time (> 0).
    km : float
        K/M, per unit time squared (> 0).

    Returns
    -------
    dict
        ``{"alpha_y": dm, "beta_y": km / dm}``.
    """
    if not (dm > 0 and km > 0):
        raise ValueError(f"dm and km must be positive numbers, got {dm}, {km}")
    return {"alpha_y": float(dm), "beta_y": float(km) / float(dm)}
