#!/usr/bin/env bash
# The Python package's CI step: python/ci.sh VENV
#
# Makes VENV (a virtual environment) if it is not one, installs maturin,
# NumPy and pytest from PyPI (movement_primitives too, when it installs: its
# test is skipped without it), builds the wheel (maturin, debug: the same
# bits as a release build, built faster), installs it, and runs the pytest
# suite, which compares every number with the CLI's ($DMPSCOPE_BIN, default
# target/debug/dmpscope, built here when missing).
set -euo pipefail
venv=${1:?usage: python/ci.sh VENV}
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")

[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
venv=$(cd "$venv" && pwd)
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet "maturin>=1.16,<2" numpy pytest
"$venv/bin/python" -m pip install --quiet movement_primitives pytransform3d ||
  echo "note: movement_primitives did not install: its test is skipped"

export DMPSCOPE_BIN=${DMPSCOPE_BIN:-$root/target/debug/dmpscope}
if [ ! -x "$DMPSCOPE_BIN" ]; then
  (cd "$root" && cargo build -p dmpscope --bin dmpscope)
fi

wheels=$(mktemp -d)
(cd "$here" && "$venv/bin/maturin" build --interpreter "$venv/bin/python" --out "$wheels")
"$venv/bin/python" -m pip install --quiet --force-reinstall --no-deps "$wheels"/dmpscope-*.whl
rm -rf "$wheels"

# Run from the tests' folder against the installed wheel (not the sources).
cd "$here/tests"
"$venv/bin/python" -m pytest -q -p no:cacheprovider .
