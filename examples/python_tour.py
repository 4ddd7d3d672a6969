#!/usr/bin/env python3
"""A tour of dmpscope in Python: load the bundled sample, map J, pick gains,
regenerate a demo at them.

    pip install ./python            # or: cd python && maturin develop
    python examples/python_tour.py  # writes tour_j.png when matplotlib is there

Every number is the CLI's: `dmpscope extract assets/planted8.mcap` prints
the same pick.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np

import dmpscope

ROOT = Path(__file__).resolve().parents[1]


def main(out: Path) -> None:
    # Loading notices (rests at the demos' ends, a skipped topic) are
    # warnings of category dmpscope.DmpscopeWarning; show each once.
    warnings.simplefilter("once", dmpscope.DmpscopeWarning)
    demos = dmpscope.load([ROOT / "assets" / "planted8.mcap"])
    print(f"{len(demos)} demos, e.g. {demos[0]!r}")

    # The landscape over the CLI's default grid (128 x 128, D/M and K/M from
    # 0.1 to 1000), on all cores, with a progress line.
    def progress(done: int, total: int) -> None:
        print(f"\r  {done}/{total} points", end="" if done < total else "\n", flush=True)

    land = dmpscope.landscape(demos, progress=progress)
    opt = land.optimum
    print(f"J's optimum: D/M {opt['dm']:.3f}, K/M {opt['km']:.3f} (zeta {opt['zeta']:.3f})")

    # The extraction reuses the landscape: diagnostics, what the demos
    # determine, the pick for the robot and Table I.
    report = dmpscope.extract(land, progress=lambda d, t: None)
    pick = report.pick
    print(pick)  # the line `dmpscope extract` prints
    print("J flat:", report.verdict["j_flat"], "| acceptable region:", report.acceptable["fraction"])

    # Regenerate the first demo at the picked gains, in real time.
    run = dmpscope.regen(demos, pick.dm, pick.km, demo=0)
    demo = demos[0]
    at_run = np.column_stack([np.interp(run.t, demo.t, demo.positions[:, a]) for a in range(3)])
    error = np.linalg.norm(run.positions - at_run, axis=1)
    print(
        f"{run.name}: {len(run.t)} points over {run.duration:.2f} s, mean distance from the demo "
        f"{1e3 * error.mean():.2f} mm, peak speed {run.peak_speed:.3f} m/s"
    )

    plot(land, pick, out)


def plot(land: dmpscope.Landscape, pick: dmpscope.Pick, out: Path) -> None:
    """J over the grid (log axes), the optimum and the pick marked."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure (pip install matplotlib)")
        return
    fig, ax = plt.subplots(figsize=(6, 5))
    # land.j is [len(dm), len(km)]: rows over D/M, so K/M is the x axis.
    mesh = ax.pcolormesh(land.km, land.dm, np.log10(land.j), shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="log10 J")
    opt = land.optimum
    ax.plot(opt["km"], opt["dm"], "w*", markersize=14, label="J's optimum")
    ax.plot(pick.km, pick.dm, "ro", markersize=8, label=f"pick ({pick.rule})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("K/M [1/unit time^2]")
    ax.set_ylabel("D/M [1/unit time]")
    ax.set_title("J = S + k sum d over the gains")
    ax.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("tour_j.png"))
