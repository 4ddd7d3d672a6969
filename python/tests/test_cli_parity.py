"""The package's numbers equal the CLI's to the bit.

Both JSON documents are parsed with ``json`` (shortest round-trip floats:
parsing gives the exact doubles) and compared equal; CSV fields likewise.
"""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

import dmpscope
from conftest import DIAG, GRID, PLANTED, REACH


def as_array(rows) -> np.ndarray:
    """JSON rows (None for NaN) as a float array."""
    return np.array([[np.nan if v is None else v for v in row] for row in rows], dtype=float)


def test_landscape_equals_the_cli(cli, cli_json, planted, tmp_path):
    out = tmp_path / "land.json"
    cli("landscape", PLANTED, "--grid", str(GRID), "-o", str(out))
    expected = json.loads(out.read_text())
    land = dmpscope.landscape(planted, grid=GRID)
    assert land.to_dict() == expected
    for key in ["d_sum", "s", "j", "a_peak", "e_sum", "d_rot_sum"]:
        got = getattr(land, key)
        assert got.shape == (GRID, GRID)
        want = as_array(expected[key])
        # Same bits: the bytes of the arrays are equal.
        assert got.tobytes() == want.tobytes(), key
    assert land.dm.tolist() == expected["dm"]
    assert land.km.tolist() == expected["km"]
    assert land.optimum == expected["optimum"]


def test_landscape_options_equal_the_cli(cli, reach, tmp_path):
    out = tmp_path / "land.json"
    args = ["--grid", "12", "--dm-range", "1", "60", "--km-range", "2", "400", "--linear"]
    args += ["--k", "5", "--sg-window", "15", "--basis", "40", "--skill-mode", "per-axis"]
    cli("landscape", REACH, *args, "-o", str(out))
    land = dmpscope.landscape(
        reach,
        grid=12,
        dm_range=(1, 60),
        km_range=(2, 400),
        linear=True,
        k=5,
        sg_window=15,
        basis=40,
        skill_mode="per-axis",
    )
    assert land.to_dict() == json.loads(out.read_text())


def test_extract_equals_the_cli(cli, cli_json, planted):
    expected = cli_json("extract", PLANTED, "--grid", str(GRID), *DIAG, "--json")
    report = dmpscope.extract(planted, grid=GRID, bootstrap=12, diag_grid=10)
    assert report.to_dict() == expected
    assert report.optimum == expected["optimum"]
    assert report.table == expected["table"]
    assert report.diagnostics == expected["diagnostics"]
    assert report.acceptable == expected["acceptable"]
    assert report.pick.to_dict() == expected["pick"]
    assert (report.pick.dm, report.pick.km) == (expected["pick"]["dm"], expected["pick"]["km"])
    assert report.verdict["j_flat"] == expected["j_flat"]
    assert report.loading == expected["loading"]


def test_extract_text_equals_the_cli(cli, planted):
    text, _ = cli("extract", PLANTED, "--grid", str(GRID), *DIAG)
    report = dmpscope.extract(planted, grid=GRID, bootstrap=12, diag_grid=10)
    assert report.text() == text
    # The pick's line is the one the CLI prints.
    assert str(report.pick) in text


def test_extract_of_a_landscape_equals_the_cli(cli_json, planted):
    expected = cli_json(
        "extract", PLANTED, "--grid", str(GRID), "--no-diagnostics", "--pick", "compliant",
        "--a-peak-limit", "40", "--settle-within", "0.8", "--json",
    )
    land = dmpscope.landscape(planted, grid=GRID)
    report = dmpscope.extract(
        land, diagnostics=False, pick="compliant", a_peak_limit=40, settle_within=0.8
    )
    assert report.to_dict() == expected
    assert report.diagnostics is None


def test_extract_with_loading_options_equals_the_cli(cli_json):
    args = ["--trim-rest", "--units", "m", "--grid", "12", "--no-diagnostics", "--json"]
    expected = cli_json("extract", PLANTED, *args)
    demos = dmpscope.load(PLANTED, trim_rest=True, units="m")
    report = dmpscope.extract(demos, grid=12, diagnostics=False)
    assert report.to_dict() == expected


def regen_csv(cli, tmp_path, *args):
    out = tmp_path / "paths.csv"
    cli("regen", PLANTED, *args, "-o", str(out))
    rows = list(csv.DictReader(io.StringIO(out.read_text())))
    by_demo: dict[str, list[dict]] = {}
    for row in rows:
        by_demo.setdefault(row["demo"], []).append(row)
    return by_demo


def columns(rows, names):
    return np.array([[float(r[n]) for n in names] for r in rows])


def assert_rollout_equals_csv(run, rows):
    assert run.t.tolist() == [float(r["t_s"]) for r in rows]
    assert run.positions.tobytes() == columns(rows, ["x", "y", "z"]).tobytes()
    assert run.velocities.tobytes() == columns(rows, ["vx", "vy", "vz"]).tobytes()
    assert run.accelerations.tobytes() == columns(rows, ["ax", "ay", "az"]).tobytes()
    if run.band is not None:
        assert run.band.tobytes() == columns(rows, ["sd_x", "sd_y", "sd_z"]).tobytes()


def test_regen_equals_the_cli(cli, planted, tmp_path):
    by_demo = regen_csv(cli, tmp_path, "--dm", "18.5", "--km", "95", "--demo", "3")
    (name, rows), = by_demo.items()
    run = dmpscope.regen(planted, 18.5, 95, demo=2)
    assert run.name == name
    assert_rollout_equals_csv(run, rows)
    assert run.orientations is not None and run.orientations.shape == (len(rows), 4)
    # By name, the same run.
    again = dmpscope.regen(planted, 18.5, 95, demo=name)
    assert again.positions.tobytes() == run.positions.tobytes()


def test_regen_every_demo_equals_the_cli(cli, planted, tmp_path):
    by_demo = regen_csv(cli, tmp_path, "--dm", "30", "--km", "200")
    runs = dmpscope.regen(planted, 30, 200)
    assert [r.name for r in runs] == list(by_demo)
    for run in runs:
        assert_rollout_equals_csv(run, by_demo[run.name])


def test_regen_at_a_new_target_equals_the_cli(cli, planted, tmp_path):
    target = ["--goal", "0.6", "0.1", "1.2", "--start", "0.3", "-0.2", "0.9"]
    target += ["--duration", "3.5", "--scaling", "frame"]
    by_demo = regen_csv(cli, tmp_path, "--dm", "25", "--km", "150", "--demo", "1", *target)
    (rows,) = by_demo.values()
    run = dmpscope.regen(
        planted, 25, 150, demo=0, goal=(0.6, 0.1, 1.2), start=(0.3, -0.2, 0.9),
        duration=3.5, scaling="frame",
    )
    assert_rollout_equals_csv(run, rows)
    assert run.duration == 3.5


def test_regen_skill_equals_the_cli(cli, planted, tmp_path):
    by_demo = regen_csv(cli, tmp_path, "--dm", "25", "--km", "150", "--skill")
    (rows,) = by_demo.values()
    run = dmpscope.regen(planted, 25, 150, skill=True)
    assert run.source == "skill" and run.band is not None
    assert_rollout_equals_csv(run, rows)


@pytest.mark.parametrize(
    "which, kw",
    [
        (["--demo", "2", "--goal-orientation", "0", "0", "0.6", "0.8"],
         {"demo": 1, "goal_orientation": (0, 0, 0.6, 0.8)}),
        (["--skill", "--goal", "0.6", "0.1", "1.2"], {"skill": True, "goal": (0.6, 0.1, 1.2)}),
    ],
)
def test_export_equals_the_cli(cli, planted, tmp_path, which, kw):
    cli_out = tmp_path / "cli.json"
    cli("regen", PLANTED, "--dm", "22", "--km", "130", *which, "-o", str(cli_out))
    mine = tmp_path / "mine.json"
    doc = dmpscope.export(planted, 22, 130, mine, **kw)
    assert mine.read_bytes() == cli_out.read_bytes()
    assert doc == json.loads(cli_out.read_text())
