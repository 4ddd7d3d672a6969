"""Shared fixtures: the repository's samples and the CLI to compare with.

The CLI is ``$DMPSCOPE_BIN`` (default ``target/debug/dmpscope`` at the
repository's root); ``python/ci.sh`` builds it when it is missing.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
ASSETS = ROOT / "assets"
PLANTED = str(ASSETS / "planted8.mcap")
REACH = str(ASSETS / "reach10.mcap")

# A small grid keeps the suite quick on a debug build; the numbers are the
# CLI's at any size.
GRID = 20
DIAG = ["--bootstrap", "12", "--diag-grid", "10"]


def cli_path() -> Path:
    return Path(os.environ.get("DMPSCOPE_BIN", ROOT / "target" / "debug" / "dmpscope"))


@pytest.fixture(scope="session")
def cli():
    """Runs the CLI from the repository's root; returns (stdout, stderr)."""
    path = cli_path()
    if not path.exists():
        pytest.fail(
            f"the dmpscope CLI is not at {path}: build it (cargo build -p dmpscope --bin "
            "dmpscope) or set DMPSCOPE_BIN"
        )

    def run(*args: str) -> tuple[str, str]:
        done = subprocess.run(
            [str(path), *args], cwd=ROOT, capture_output=True, text=True, timeout=900
        )
        if done.returncode != 0:
            raise AssertionError(f"dmpscope {' '.join(args)} failed: {done.stderr}")
        return done.stdout, done.stderr

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    def run(*args: str):
        out, _ = cli(*args)
        return json.loads(out)

    return run


@pytest.fixture(scope="session")
def planted():
    import dmpscope

    return dmpscope.load([PLANTED])


@pytest.fixture(scope="session")
def reach():
    import dmpscope

    return dmpscope.load(REACH)
