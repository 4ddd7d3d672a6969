"""Bad input, notices, progress, Ctrl+C and panics at the boundary."""

from __future__ import annotations

import ast
import os
import signal
import threading
import warnings
from pathlib import Path

import pytest

import dmpscope
from conftest import PLANTED


def test_a_missing_file_is_file_not_found():
    with pytest.raises(FileNotFoundError, match="no_such_recording.mcap"):
        dmpscope.load(["no_such_recording.mcap"])


def test_a_bad_file_names_the_file(tmp_path):
    bad = tmp_path / "broken.mcap"
    bad.write_bytes(b"\x89MCAP0\r\n" + b"\x00" * 64)
    with pytest.raises(dmpscope.DmpscopeError, match="broken.mcap"):
        dmpscope.load([bad])


def test_a_bad_csv_row_names_the_file_topic_and_sample(tmp_path):
    bad = tmp_path / "hand.csv"
    bad.write_text("t,x,y,z\n0.0,0,0,0\n0.01,0.1,0,0\n0.02,oops,0,0\n")
    with pytest.raises(dmpscope.DmpscopeError) as raised:
        dmpscope.load(bad)
    message = str(raised.value)
    assert "hand.csv" in message and "topic csv" in message and "sample 2" in message
    # It is a ValueError too, and dmpscope.Error.
    assert isinstance(raised.value, ValueError)
    assert isinstance(raised.value, dmpscope.Error)


@pytest.mark.parametrize(
    "kw, words",
    [
        ({"demos": "segments"}, "topic, file or segment"),
        ({"units": "inch"}, "m, cm or mm"),
        ({"segments": "middle"}, "segment number from 1"),
        ({"gaps": "bridge"}, "split or keep"),
        ({"cut": "half"}, "none or farthest"),
    ],
)
def test_unknown_load_options_are_refused(kw, words):
    with pytest.raises(dmpscope.DmpscopeError, match=words):
        dmpscope.load(PLANTED, **kw)


@pytest.mark.parametrize(
    "kw, words",
    [
        ({"skill_mode": "paper"}, "frame, per-axis or none"),
        ({"pick": "best"}, "optimum, compliant, critical or smooth"),
        ({"k": -1}, "k must be finite"),
        ({"accept_eps": 0}, "eps must be a fraction above 0"),
        ({"grid": 1}, "2 to 4096"),
        ({"dm_range": (5, 1)}, "0 < lo < hi"),
        ({"a_peak_limit": -3}, "a-peak-limit"),
        ({"unusable": "drop"}, "skip or fail"),
    ],
)
def test_unknown_options_are_refused(planted, kw, words):
    with pytest.raises(ValueError, match=words):
        dmpscope.extract(planted, **kw)


def test_bad_targets_are_refused(planted):
    with pytest.raises(dmpscope.DmpscopeError, match="positive"):
        dmpscope.regen(planted, -1, 10, demo=0)
    with pytest.raises(dmpscope.DmpscopeError, match="duration"):
        dmpscope.regen(planted, 10, 10, demo=0, duration=0)
    with pytest.raises(dmpscope.DmpscopeError, match="between 0 and 7"):
        dmpscope.regen(planted, 10, 10, demo=8)
    with pytest.raises(dmpscope.DmpscopeError, match="no demo is named"):
        dmpscope.regen(planted, 10, 10, demo="nope")
    with pytest.raises(dmpscope.DmpscopeError, match="must be a rotation"):
        dmpscope.regen(planted, 10, 10, demo=0, goal_orientation=(0, 0, 0, 0))
    with pytest.raises(dmpscope.DmpscopeError, match="one DMP"):
        dmpscope.export(planted, 10, 10)


def test_loading_notices_are_warnings():
    with pytest.warns(dmpscope.DmpscopeNote, match="rest at their ends"):
        dmpscope.load(PLANTED)
    with pytest.warns(dmpscope.DmpscopeWarning, match="--segments first applies only"):
        dmpscope.load(PLANTED, segments="first")


def test_a_non_unit_quaternion_gets_a_note(planted):
    with pytest.warns(dmpscope.DmpscopeNote, match="normalised to unit"):
        dmpscope.regen(planted, 20, 100, demo=0, goal_orientation=(0, 0, 0, 2))


def test_an_edge_optimum_warns(planted):
    with pytest.warns(dmpscope.DmpscopeWarning, match="edge of the gain box"):
        dmpscope.landscape(planted, grid=6, dm_range=(0.1, 0.5), km_range=(0.1, 0.5))


def test_progress_is_reported(planted):
    seen = []
    dmpscope.extract(planted, grid=40, bootstrap=8, diag_grid=8, progress=lambda d, t: seen.append((d, t)))
    landscape = [s for s in seen if s[1] == 1600]
    assert landscape and landscape[-1] == (1600, 1600)
    assert all(b[0] >= a[0] for a, b in zip(landscape, landscape[1:]))
    # Then the diagnostics: 8 leave-one-out and 8 bootstrap extractions.
    assert seen[-1] == (16, 16)


def test_an_exception_in_progress_stops_the_work(planted):
    class Stop(Exception):
        pass

    calls = []

    def progress(done, total):
        calls.append(done)
        raise Stop("enough")

    with pytest.raises(Stop):
        dmpscope.landscape(planted, grid=64, progress=progress)
    assert len(calls) == 1


def test_ctrl_c_interrupts_a_landscape(planted):
    if os.name != "posix":
        pytest.skip("signals to the own process")
    done = []
    timers = []

    def progress(d, t):
        # Once the landscape runs, Ctrl+C arrives from elsewhere.
        if not done:
            timers.append(threading.Timer(0.05, lambda: os.kill(os.getpid(), signal.SIGINT)))
            timers[0].start()
        done.append(d)

    try:
        with pytest.raises(KeyboardInterrupt):
            dmpscope.landscape(planted, grid=512, progress=progress)
    finally:
        for timer in timers:
            timer.cancel()
    assert done and done[-1] < 512 * 512


def test_a_panic_is_an_exception_not_a_crash():
    with pytest.raises(dmpscope.DmpscopeError, match="internal error.*boom"):
        dmpscope._core._panic_for_test("boom")


def test_a_landscape_refuses_other_settings(planted):
    land = dmpscope.landscape(planted, grid=8)
    with pytest.raises(dmpscope.DmpscopeError, match="already has its grid"):
        dmpscope.extract(land, grid=16)


def test_the_stub_states_the_defaults():
    """Every default the stub writes is the core's (dmpscope.defaults())."""
    stub = Path(dmpscope.__file__).with_name("_core.pyi")
    tree = ast.parse(stub.read_text())
    defaults = dmpscope.defaults()
    checked = 0
    for fn in [n for n in tree.body if isinstance(n, ast.FunctionDef)]:
        names = [a.arg for a in fn.args.kwonlyargs]
        for name, value in zip(names, fn.args.kw_defaults):
            if name in defaults and value is not None:
                stated = ast.literal_eval(value)
                want = defaults[name]
                assert stated == (tuple(want) if isinstance(want, (list, tuple)) else want), (
                    fn.name,
                    name,
                )
                checked += 1
    assert checked > 20


def test_warnings_point_at_the_caller():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        dmpscope.load(PLANTED)
    assert caught and all(w.filename == __file__ for w in caught)
