"""Demos as NumPy arrays: in, out, and refused when bad."""

from __future__ import annotations

import re

import numpy as np
import pytest

import dmpscope
from conftest import GRID


def rebuilt(demos):
    return [dmpscope.Demo(d.t, d.positions, d.orientations, name=d.name) for d in demos]


def test_a_demo_rebuilt_from_its_arrays_gives_the_same_landscape(planted):
    first = dmpscope.landscape(planted, grid=GRID)
    again = dmpscope.landscape(rebuilt(planted), grid=GRID)
    for key in ["d_sum", "s", "j", "a_peak", "e_sum", "d_rot_sum"]:
        assert getattr(first, key).tobytes() == getattr(again, key).tobytes(), key
    assert first.optimum == again.optimum
    assert first.demos == again.demos


def test_a_rebuilt_demo_extracts_the_same_pick(planted):
    a = dmpscope.extract(planted, grid=GRID, diagnostics=False)
    b = dmpscope.extract(rebuilt(planted), grid=GRID, diagnostics=False)
    assert a.pick.to_dict() == b.pick.to_dict()
    assert a.table == b.table


def test_demo_arrays(planted):
    d = planted[0]
    n = len(d)
    assert d.t.shape == (n,) and d.t[0] == 0.0 and np.all(np.diff(d.t) > 0)
    assert d.positions.shape == (n, 3)
    assert d.orientations.shape == (n, 4)
    assert np.allclose(np.linalg.norm(d.orientations, axis=1), 1.0)
    assert d.name == "planted8.mcap:/demo_01"
    assert d.units == "m" and d.frame_id == "world"
    assert abs(d.duration - d.t[-1]) < 1e-9


def make(n=50, dims=3):
    t = np.linspace(0.0, 1.0, n)
    p = np.zeros((n, dims))
    p[:, 0] = 0.3 * (10 * t**3 - 15 * t**4 + 6 * t**5)
    return t, p


def test_lists_and_ints_are_accepted():
    t, p = make()
    d = dmpscope.Demo(t.tolist(), p.tolist(), name="mine")
    assert d.name == "mine" and d.orientations is None and d.file == ""
    assert d.positions.tobytes() == p.tobytes()


@pytest.mark.parametrize(
    "change, words",
    [
        (lambda t, p: (t[:, None], p), "one-dimensional"),
        (lambda t, p: (t, p[:, :2]), "shape (N, 3)"),
        (lambda t, p: (t, p[:-1]), "shape (N, 3)"),
        (lambda t, p: (np.where(np.arange(len(t)) == 4, np.nan, t), p), "t[4]"),
        (lambda t, p: (t, np.where(np.arange(p.size).reshape(p.shape) == 7, np.nan, p)),
         "positions[2, 1]"),
        (lambda t, p: (t[::-1], p), "increase strictly"),
        (lambda t, p: (np.concatenate([t[:3], t[2:3], t[4:]]), p), "increase strictly"),
        (lambda t, p: (t[:1], p[:1]), "at least 2"),
        (lambda t, p: (["a"] * len(t), p), "array of numbers"),
    ],
)
def test_bad_arrays_are_refused(change, words):
    t, p = change(*make())
    with pytest.raises(ValueError, match=re.escape(words)):
        dmpscope.Demo(t, p)


def test_bad_orientations_are_refused():
    t, p = make()
    q = np.tile([0.0, 0.0, 0.0, 1.0], (len(t), 1))
    q[5] = 0.0
    with pytest.raises(ValueError, match=r"orientations\[5\]"):
        dmpscope.Demo(t, p, q)
    with pytest.raises(ValueError, match=r"shape \(N, 4\)"):
        dmpscope.Demo(t, p, q[:, :3])


def test_non_unit_orientations_are_normalised():
    t, p = make()
    q = np.tile([0.0, 0.0, 0.0, 2.0], (len(t), 1))
    d = dmpscope.Demo(t, p, q)
    assert np.array_equal(d.orientations, np.tile([0.0, 0.0, 0.0, 1.0], (len(t), 1)))


def test_an_empty_list_of_demos_is_refused():
    with pytest.raises(dmpscope.DmpscopeError, match="no usable demonstration"):
        dmpscope.landscape([], grid=8)


def test_not_demos_are_a_type_error():
    with pytest.raises(TypeError, match="dmpscope.Demo"):
        dmpscope.landscape([1, 2], grid=8)


def test_arrays_make_a_full_run():
    t, p = make(120)
    demos = []
    for i in range(3):
        pi = p.copy()
        pi[:, 1] = 0.05 * i * t
        demos.append(dmpscope.Demo(t * (1 + 0.1 * i), pi))
    report = dmpscope.extract(demos, grid=10, bootstrap=5, diag_grid=6)
    assert report.pick is not None
    # Unnamed demos get unique names.
    assert [d["name"] for d in report.demos] == ["demo", "demo (2)", "demo (3)"]
    run = dmpscope.regen(demos, report.pick.dm, report.pick.km, demo=1)
    assert run.positions.shape == (len(run.t), 3)


def test_landscape_arrays_are_read_only(planted):
    land = dmpscope.landscape(planted, grid=8)
    with pytest.raises(ValueError):
        land.j[0, 0] = 0.0
