"""Docs that agree (issue 28 item 11): a measured figure lives in one place and the others link
to it; the scene format's help documents every table and key a scene file accepts."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

import clearsim
from clearsim import _core, scene
from clearsim.scene.sweep import SWEEP_KEYS
from clearsim.scene import alias, settings
from clearsim.scene import builder as scene_builder
from clearsim.scene import study as study_scene

ROOT = Path(__file__).resolve().parents[2]
PHYSICS = (ROOT / "docs" / "physics.md").read_text(encoding="utf-8")


def _sommerfeld(film: str, l_over_d: float, eps: float, squeeze: bool) -> float:
    """Sommerfeld number of a film force (as benches/finite_bearing.py computes it)."""
    mu, r, c = 0.4, 0.01, 5e-4
    length = 2 * r * l_over_d
    f = _core.film_force(film, mu, r, c, length, eps, 2.0 if squeeze else 0.0, 0.0 if squeeze else 50.0)
    return math.hypot(*f) * (c / r) ** 2 / (length * 2 * r * mu * (2.0 if squeeze else 50.0))


def test_the_long_films_error_at_l_over_d_1_is_the_benchs():
    """docs/physics.md §4 holds the closed forms' errors against the finite bearing (was +190 %
    there and +250 % in Lubricated's docstring); the docstring links to it."""
    m = re.search(r"the long form is \+(\d+) % \| \+(\d+) % at L/D = 1,", PHYSICS)
    assert m, "docs/physics.md: the long form's error at L/D = 1 is missing"
    rotation = 100 * (_sommerfeld("long", 1.0, 0.5, False) / _sommerfeld("finite", 1.0, 0.5, False) - 1)
    squeeze = 100 * (_sommerfeld("long", 1.0, 0.5, True) / _sommerfeld("finite", 1.0, 0.5, True) - 1)
    assert float(m.group(1)) == pytest.approx(rotation, abs=1.0) and float(m.group(2)) == pytest.approx(squeeze, abs=1.0)
    doc = clearsim.Lubricated.__doc__ or ""
    assert not re.search(r"[+−-]\d+ %", doc) and "docs/physics.md §4" in doc  # no error figure of its own


def test_radau5s_lead_lives_in_the_readme():
    doc = clearsim.Mechanism.simulate.__doc__ or ""
    assert not re.search(r"\d\s*×", doc) and "Choosing an integrator" in doc
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "## Choosing an integrator" in readme and re.search(r"RADAU5 is [\d.]+–[\d.]+× faster than RK45", readme)


def test_the_scene_help_documents_every_table_and_key():
    """``pydoc clearsim.scene`` lists every table and key the reader accepts, [study] too."""
    doc = scene.__doc__ or ""
    tables = {"mechanism", "body", "joint", "driver", "clearance_joint", "force", "simulation", "outputs", "reliability", "study", "sweep"}
    for table in tables:
        assert re.search(rf"\[\[?{table}\]\]?", doc), table
    for sub in ("study.input", "study.tolerance", "reliability.allowable", "clearance_joint.dry", "clearance_joint.lubricated"):
        assert f"[{sub}]" in doc or f"[[{sub}]]" in doc, sub
    b = scene_builder
    keys = {*b._MECHANISM_KEYS, *b._BODY_KEYS, *b._DRIVER_KEYS, *b._CLEARANCE_KEYS, *b._PRISMATIC_CLEARANCE_KEYS,
            *(k for ks in b._JOINT_KEYS.values() for k in ks), *(k for ks in b._FORCE_KEYS.values() for k in ks),
            *settings._SIM_KEYS, *settings._OUTPUT_KEYS, *alias._RELIABILITY_KEYS, *study_scene.STUDY_KEYS,
            *study_scene.INPUT_KEYS, *study_scene.TOLERANCE_KEYS, *study_scene.OUTPUT_KEYS, *SWEEP_KEYS}  # fmt: skip
    missing = sorted(k for k in keys if not re.search(rf"\b{k}\b", doc))
    assert not missing, f"keys a scene accepts but pydoc clearsim.scene does not name: {missing}"
