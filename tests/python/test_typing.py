"""The package type-checks: mypy (settings in pyproject.toml: every function annotated, no
type errors) over python/clearsim. Skipped where mypy is not installed (it is in the ``test``
extra, so CI runs it)."""

import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_mypy_finds_no_type_errors():
    pytest.importorskip("mypy")
    if not (ROOT / "pyproject.toml").is_file() or not (ROOT / "python" / "clearsim").is_dir():
        pytest.skip("not run from a source tree")
    out = subprocess.run(
        [sys.executable, "-m", "mypy", "--config-file", str(ROOT / "pyproject.toml"), "--cache-dir", "/dev/null"],
        cwd=ROOT, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert out.returncode == 0, out.stdout[-4000:] + out.stderr[-2000:]
