"""Type stub of dmpscope's extension module (the Rust side, ``dmpscope._core``).

Units: positions in metres (z up), time in seconds, gains D/M per unit time
and K/M per unit time squared (the motion's duration is one unit), a_peak
in m/s^2 of the unit-time motion, angles in degrees where named ``d_rot``.
Every default is the CLI's (``dmpscope.defaults()`` lists them; a keyword
whose default is ``None`` takes the core's default, as the CLI's flag).
"""

from __future__ import annotations

import os
from typing import Any, Callable, Iterable, Literal, Optional, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

PathLike = Union[str, "os.PathLike[str]"]
Demos = Union[Sequence["Demo"], "Demo"]
Progress = Callable[[int, int], Any]
FloatArray = npt.NDArray[np.float64]

class DmpscopeError(ValueError):
    """An error of dmpscope's core, in the CLI's words (file, topic, sample, setting)."""

class DmpscopeWarning(UserWarning):
    """A notice: a topic or demo left out, a file cut short, an optimum on the edge."""

class DmpscopeNote(DmpscopeWarning):
    """A notice where nothing was lost (the CLI's ``note:`` lines)."""

class Demo:
    """One demonstration: time stamps, positions and (optionally) orientations.

    ``Demo(t, positions, orientations=None, name=None)``: ``t`` seconds (N,
    strictly increasing, by 1 ns or more), ``positions`` metres (N x 3, z
    up), ``orientations`` quaternions ``[x, y, z, w]`` (N x 4, normalised
    when not unit). NaN, infinities, a wrong shape, fewer than 2 samples or
    a non-increasing ``t`` raise ``ValueError`` naming the element.
    """

    def __init__(
        self,
        t: npt.ArrayLike,
        positions: npt.ArrayLike,
        orientations: Optional[npt.ArrayLike] = None,
        name: Optional[str] = None,
    ) -> None: ...
    @property
    def name(self) -> str:
        """``file:topic`` for a loaded demo; ``demo`` when not given."""
    @property
    def file(self) -> str:
        """The file it was loaded from ("" for one built from arrays)."""
    @property
    def topic(self) -> str:
        """The topic (and key) it was read from ("" for one built from arrays)."""
    @property
    def t(self) -> FloatArray:
        """Seconds from the first sample, in time order (N,)."""
    @property
    def positions(self) -> FloatArray:
        """Positions, metres (N x 3), in time order."""
    @property
    def orientations(self) -> Optional[FloatArray]:
        """Unit quaternions ``[x, y, z, w]`` (N x 4), or None."""
    @property
    def units(self) -> Literal["m", "cm", "mm"]:
        """The unit the recording was in (converted to metres at loading)."""
    @property
    def frame_id(self) -> str:
        """The fixed frame asked for at loading, or ``world``."""
    @property
    def duration(self) -> float:
        """Last stamp minus first, seconds."""
    @property
    def n_samples(self) -> int:
        """Samples as recorded, equal stamps included (``len(demo)`` counts them once)."""
    def __len__(self) -> int: ...

class Landscape:
    """Every quantity over the gain grid, shape ``(len(dm), len(km))``, read-only.

    ``to_dict()`` is ``dmpscope landscape``'s JSON (NaN as None).
    """

    k: float
    dm: FloatArray
    km: FloatArray
    d_sum: FloatArray
    s: FloatArray
    j: FloatArray
    a_peak: FloatArray
    e_sum: FloatArray
    d_rot_sum: FloatArray
    @property
    def optimum(self) -> dict[str, Any]:
        """J's optimum: dm, km, zeta, j, s, d_sum, on_edge, edge, grid_min_j, iterations, converged."""
    @property
    def demos(self) -> list[str]:
        """The model's demos, by name."""
    @property
    def grid(self) -> dict[str, Any]:
        """``{"dm": {"lo", "hi", "n", "scale"}, "km": {...}}``."""
    def to_dict(self) -> dict[str, Any]: ...

class Pick:
    """The gains picked for the robot; ``str(pick)`` is the CLI's line."""

    @property
    def rule(self) -> Literal["optimum", "compliant", "critical", "smooth"]: ...
    @property
    def dm(self) -> float: ...
    @property
    def km(self) -> float: ...
    @property
    def zeta(self) -> float: ...
    @property
    def j(self) -> float: ...
    @property
    def why(self) -> str: ...
    @property
    def on_edge(self) -> bool: ...
    def to_dict(self) -> dict[str, Any]:
        """Every field: also s, d_sum, e_sum, a_peak_max, settling, edge, robot."""

class Report:
    """An extraction: ``to_dict()`` is ``dmpscope extract --json``, ``text()`` its text."""

    landscape: Landscape
    @property
    def k(self) -> float: ...
    @property
    def demos(self) -> list[dict[str, Any]]: ...
    @property
    def optimum(self) -> dict[str, Any]: ...
    @property
    def table(self) -> list[dict[str, Any]]:
        """Table I: Extracted, Picked (rule), the paper's presets."""
    @property
    def diagnostics(self) -> Optional[dict[str, Any]]: ...
    @property
    def diagnostics_about(self) -> Optional[dict[str, Any]]: ...
    @property
    def constrained(self) -> Optional[dict[str, Any]]: ...
    @property
    def loading(self) -> Optional[dict[str, Any]]: ...
    @property
    def verdict(self) -> dict[str, Any]:
        """skill_mode, j_depth, j_flat, e_depth, e_flat, e_range, e_excess, e_note."""
    @property
    def acceptable(self) -> dict[str, Any]: ...
    @property
    def pick(self) -> Optional[Pick]: ...
    @property
    def pick_failure(self) -> Optional[str]: ...
    @property
    def optimum_robot(self) -> dict[str, Any]: ...
    def to_dict(self) -> dict[str, Any]: ...
    def text(self) -> str: ...

class Rollout:
    """A DMP run at a target, in real time."""

    name: str
    source: Literal["demo", "skill"]
    dm: float
    km: float
    t: FloatArray
    positions: FloatArray
    velocities: FloatArray
    accelerations: FloatArray
    orientations: Optional[FloatArray]
    angular_velocities: Optional[FloatArray]
    band: Optional[FloatArray]
    start: tuple[float, float, float]
    goal: tuple[float, float, float]
    duration: float
    peak_speed: float
    a_peak: float
    a_peak_unit: float
    final_error: float

def load(
    paths: Union[PathLike, Iterable[PathLike]],
    *,
    topic: Union[str, Sequence[str], None] = None,
    demos: Literal["topic", "file", "segment"] = "topic",
    units: Literal["m", "cm", "mm"] = "m",
    segments: str = "all",
    trim_rest: bool = False,
    exclude: Union[str, Sequence[str], None] = None,
    frame: Union[str, Sequence[str], None] = None,
    fixed_frame: Optional[str] = None,
    min_extent: float = 0.01,
    y_up: bool = False,
    rest_speed: float = 0.05,
    min_rest: float = 0.2,
    min_demo: float = 0.4,
    gaps: Literal["split", "keep"] = "split",
    cut: Literal["none", "farthest"] = "none",
    drop_bad_orientation: bool = False,
) -> list[Demo]:
    """The demonstrations in recordings, as ``dmpscope extract FILES`` loads them.

    ``paths``: MCAP, ROS 1 bag, CSV files or folders (rosbag2, or any folder
    of recordings). The keywords are the CLI's loading flags: ``topic``
    (``--topic`` globs), ``exclude``, ``frame`` (TF child frames or pose
    indices), ``fixed_frame``, ``min_extent`` (m), ``y_up``, ``demos``,
    ``rest_speed`` (m/s), ``min_rest`` and ``min_demo`` (s), ``gaps``,
    ``units``, ``trim_rest``, ``segments`` (all, first, last, out, back or a
    number from 1), ``drop_bad_orientation``, ``cut``. Notices are warnings
    (``DmpscopeWarning``); a missing file raises ``FileNotFoundError``, an
    unreadable one ``DmpscopeError`` naming the file, topic and sample.
    """

def landscape(
    demos: Demos,
    *,
    grid: Optional[int] = 128,
    dm_range: Optional[tuple[float, float]] = (0.1, 1000.0),
    km_range: Optional[tuple[float, float]] = (0.1, 1000.0),
    linear: bool = False,
    k: Optional[float] = 20.0,
    sg_window: Optional[int] = 21,
    sg_order: Optional[int] = 3,
    sg_seconds: Optional[float] = None,
    basis: Optional[int] = 100,
    skill_mode: Optional[Literal["frame", "per-axis", "none"]] = "frame",
    unusable: Optional[Literal["skip", "fail"]] = "skip",
    axis_sd_floor: Optional[float] = 0.0,
    k_rot: Optional[float] = 0.0,
    orientation_gains: Optional[tuple[float, float]] = None,
    progress: Optional[Progress] = None,
) -> Landscape:
    """sum d, S, J, a_peak, E and d_rot over the gain grid, and J's optimum.

    As ``dmpscope landscape``: ``grid`` points per axis, ``dm_range`` and
    ``km_range`` (lo, hi), geometric unless ``linear``, J = S + k sum d.
    The model keywords are the CLI's (``--sg-window`` ...). Runs on all
    cores with the GIL released; ``progress(done, total)`` is called
    between tiles and Ctrl+C stops it (``KeyboardInterrupt``).
    """

def extract(
    demos: Union[Demos, Landscape],
    *,
    pick: Optional[Literal["optimum", "compliant", "critical", "smooth"]] = None,
    accept_eps: float = 0.02,
    diagnostics: bool = True,
    bootstrap: int = 100,
    bootstrap_seed: int = 1,
    diag_grid: int = 32,
    a_peak_limit: Optional[float] = None,
    settle_within: Optional[float] = None,
    grid: Optional[int] = 128,
    dm_range: Optional[tuple[float, float]] = (0.1, 1000.0),
    km_range: Optional[tuple[float, float]] = (0.1, 1000.0),
    linear: bool = False,
    k: Optional[float] = 20.0,
    sg_window: Optional[int] = 21,
    sg_order: Optional[int] = 3,
    sg_seconds: Optional[float] = None,
    basis: Optional[int] = 100,
    skill_mode: Optional[Literal["frame", "per-axis", "none"]] = "frame",
    unusable: Optional[Literal["skip", "fail"]] = "skip",
    axis_sd_floor: Optional[float] = 0.0,
    k_rot: Optional[float] = 0.0,
    orientation_gains: Optional[tuple[float, float]] = None,
    progress: Optional[Progress] = None,
) -> Report:
    """The extraction, as ``dmpscope extract``: ``to_dict()`` equals its ``--json``.

    ``demos`` may be a computed ``Landscape`` (then no grid or model keyword
    may be given). ``pick`` (None: optimum when J is not flat, compliant
    when it is), ``accept_eps`` (the acceptable region's fraction),
    ``diagnostics`` (False: ``--no-diagnostics``), ``bootstrap``,
    ``bootstrap_seed``, ``diag_grid``, ``a_peak_limit`` (m/s^2),
    ``settle_within`` (unit times). ``progress(done, total)`` is called for
    the landscape, then for the diagnostics (done restarts from 0).
    """

@overload
def regen(
    demos: Union[Demos, Landscape],
    dm: float,
    km: float,
    *,
    demo: Union[int, str],
    skill: Literal[False] = False,
    start: Optional[Sequence[float]] = None,
    goal: Optional[Sequence[float]] = None,
    duration: Optional[float] = None,
    scaling: Literal["paper", "frame"] = "paper",
    goal_orientation: Optional[Sequence[float]] = None,
    start_orientation: Optional[Sequence[float]] = None,
    **model: Any,
) -> Rollout: ...
@overload
def regen(
    demos: Union[Demos, Landscape],
    dm: float,
    km: float,
    *,
    demo: None = None,
    skill: Literal[True],
    start: Optional[Sequence[float]] = None,
    goal: Optional[Sequence[float]] = None,
    duration: Optional[float] = None,
    scaling: Literal["paper", "frame"] = "paper",
    goal_orientation: Optional[Sequence[float]] = None,
    start_orientation: Optional[Sequence[float]] = None,
    **model: Any,
) -> Rollout: ...
@overload
def regen(
    demos: Union[Demos, Landscape],
    dm: float,
    km: float,
    *,
    demo: None = None,
    skill: Literal[False] = False,
    start: Optional[Sequence[float]] = None,
    goal: Optional[Sequence[float]] = None,
    duration: Optional[float] = None,
    scaling: Literal["paper", "frame"] = "paper",
    goal_orientation: Optional[Sequence[float]] = None,
    start_orientation: Optional[Sequence[float]] = None,
    **model: Any,
) -> list[Rollout]:
    """The DMPs at gains (dm, km), as ``dmpscope regen``.

    ``demo``: one demo, by its index in ``demos`` (0-based: the CLI's
    ``--demo N`` is ``demo=N-1``) or its name -> a ``Rollout``; ``skill``:
    the skill of all demos -> a ``Rollout``; neither: every demo -> a list.
    ``start``, ``goal`` (metres), ``duration`` (s), ``scaling``,
    ``goal_orientation``, ``start_orientation`` (``[x, y, z, w]``, made
    unit with a note) default to each demo's own. The model keywords are
    ``landscape``'s.
    """

def export(
    demos: Union[Demos, Landscape],
    dm: float,
    km: float,
    path: Optional[PathLike] = None,
    *,
    demo: Union[int, str, None] = None,
    skill: bool = False,
    start: Optional[Sequence[float]] = None,
    goal: Optional[Sequence[float]] = None,
    duration: Optional[float] = None,
    scaling: Literal["paper", "frame"] = "paper",
    goal_orientation: Optional[Sequence[float]] = None,
    start_orientation: Optional[Sequence[float]] = None,
    frame_id: Optional[str] = None,
    **model: Any,
) -> dict[str, Any]:
    """The DMP document a controller runs (docs/export.md), for one demo or the skill.

    Written to ``path`` when given, the bytes ``dmpscope regen --out
    F.json`` writes; returned as a dict either way. ``frame_id`` defaults to
    the demos' fixed frame, else ``world``.
    """

def defaults() -> dict[str, Any]:
    """The defaults of every keyword (the core's, the CLI's)."""

def _panic_for_test(message: str) -> None: ...
