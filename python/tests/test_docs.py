"""docs/python.md's API reference is the stub's (python/api_doc.py)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_the_api_reference_is_current():
    spec = importlib.util.spec_from_file_location("api_doc", ROOT / "python" / "api_doc.py")
    if spec is None or spec.loader is None:
        pytest.fail("python/api_doc.py cannot be loaded")
    api_doc = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(api_doc)
    doc = (ROOT / "docs" / "python.md").read_text()
    assert api_doc.documented(doc) == api_doc.reference(), (
        "docs/python.md's API reference is stale: run python3 python/api_doc.py --write"
    )
