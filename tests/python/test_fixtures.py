"""The JSON fixtures the Rust tests and benches load (tests/data/*.json) must equal the current
Python models, so the two sides cannot drift. Regenerate with ``python benches/fixtures.py``."""

import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("clearsim_bench_fixtures", ROOT / "benches" / "fixtures.py")
fixtures = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(fixtures)


@pytest.mark.parametrize("name", sorted(fixtures.MODELS))
def test_fixture_equals_current_model(name):
    path = fixtures.fixture_path(name)
    assert path.exists(), f"missing {path}: run python benches/fixtures.py"
    stored = json.loads(path.read_text())
    current = fixtures.plain(fixtures.MODELS[name]().description())
    assert stored == current, f"{path.name} is stale: run python benches/fixtures.py"
