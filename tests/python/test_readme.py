"""Every Python example in the README runs."""

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"
BLOCKS = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)


@pytest.mark.parametrize("code", BLOCKS, ids=[f"block{k}" for k in range(len(BLOCKS))])
def test_readme_example_runs(code):
    exec(compile(code, str(README), "exec"), {"__name__": "readme_example"})


def test_readme_has_examples():
    assert BLOCKS


EXAMPLES = README.parent / "docs" / "examples.md"


def test_examples_page_runs_and_every_scene_is_on_it(tmp_path, monkeypatch):
    """docs/examples.md: its Python blocks run in order (one session, in a scratch directory),
    and every scene in scenes/ is listed with its picture."""
    text = EXAMPLES.read_text(encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "examples_page"}
    for code in re.findall(r"```python\n(.*?)```", text, flags=re.S):
        exec(compile(code, str(EXAMPLES), "exec"), namespace)
    assert (tmp_path / "slider_crank.gif").stat().st_size > 0 and (tmp_path / "run.nc").stat().st_size > 0
    for scene in sorted((README.parent / "scenes").glob("*.toml")):
        assert f"`{scene.name}`" in text and f"examples/{scene.stem}.png" in text, scene.name
        assert (EXAMPLES.parent / "examples" / f"{scene.stem}.png").exists(), scene.stem
