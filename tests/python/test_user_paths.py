"""The user-path matrix (issue 28 item 2): every shipped model and example scene, started at
t0 ∈ {0, T/4, 2.5 T}, through every public path — ``simulate``, ``simulate_with_ideal``,
``Study.monte_carlo`` (and ``clearsim.monte_carlo``) skipping the same start-up, ``clearsim run``
and ``clearsim reliability`` on its scene — with every joint kind (ideal, dry, lubricated, and dry
+ lubricated in one mechanism). Each cell runs, or fails with the clearsim error and the reason
written in :data:`EXPECTED_FAILURES`. A failure names its cell in the test id, e.g.
``test_scene_path[compressor-mixed-T/4-clearsim run]``.

The defects of issue 28 this class of test catches: a start after t = 0 failing the assembly
(every path at T/4 and 2.5 T), ``clearsim run`` dying in a figure with a dry and a lubricated
joint (the mixed cells, figures drawn at T/4), a ``[study] skip_cycles`` scene failing in
``clearsim reliability``, and a Monte Carlo or FOSM window shorter than a turn failing on its
empty crank-angle bins (``cycles`` = 0.05 here).

Kept fast: each run covers 5 % of a turn at loose tolerances, the studies run 2 samples, figures
are drawn only at t0 = T/4 for each scene as shipped and each mixed variant (:func:`drawn`; the
t0 = 0 figures of every scene are drawn by test_examples.py).
"""

from __future__ import annotations

import copy
import json
import math
import re
import sys
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import pytest

import clearsim
from clearsim import models
from clearsim.cli import main
from clearsim.reliability import Normal, Output, Study
from clearsim.scene.study import scene_study
from clearsim.scene import load_scene_file

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

SCENES = Path(__file__).resolve().parents[2] / "scenes"
T0_TURNS = {"0": 0.0, "T/4": 0.25, "2.5T": 2.5}
SPAN = 0.05  # turns simulated (and analysed by the studies) after t0
LOOSE = dict(rtol=1e-5, atol=1e-8)
PYTHON_PATHS = ("simulate", "simulate_with_ideal", "Study.monte_carlo", "clearsim.monte_carlo")
SCENE_PATHS = ("simulate", "simulate_with_ideal", "Study.monte_carlo", "clearsim run", "clearsim reliability")
KINDS = ("ideal", "dry", "lubricated", "mixed")

#: model → (turn T [s], drive speed ω [rad/s], analysed body, component)
MODELS: Dict[str, Tuple[float, float, str, str]] = {
    "slider_crank": (60.0 / 5000.0, 5000.0 * 2 * math.pi / 60.0, "slider", "x"),
    "nine_bar": (0.4, -5.0 * math.pi, "slider9", "y"),
}
#: scene → (turn T [s], driver whose angle at t0 is checked or None, analysed body, component)
#: for scenes without a [study] of their own, the study this test adds. The engine has no
#: driver: its motor's no-load speed 314.16 rad/s sets its nominal turn.
SCENE_TABLE: Dict[str, Tuple[float, Optional[str], str, str]] = {
    "compressor": (0.04, "motor", "piston", "x"),
    "engine": (2 * math.pi / 314.16, None, "slider", "x"),
    "four_bar_spring": (0.5, "drive", "rocker", "theta"),
    "nine_bar": (0.4, "drive1", "slider9", "y"),
    "nine_bar_lubricated": (0.4, "drive1", "slider9", "y"),
    "nine_bar_reliability": (0.4, "drive1", "slider9", "y"),
    "press_workpiece": (0.4, "drive1", "slider9", "y"),
    "slider_crank": (60.0 / 5000.0, "crank-drive", "slider", "x"),
    "slider_crank_guide_clearance": (0.03, "crank-drive", "slider", "y"),
}
#: The nine-bar scenes with a [study] or a film of their own are the nine-bar with other joint
#: kinds, which scenes/nine_bar.toml's variants cover: they run as shipped only.
SHIPPED_ONLY = {"nine_bar_lubricated", "nine_bar_reliability"}

#: Cells that must fail, with the named error, words of its message and the documented reason.
#: (subject, kind, path) with "*" for any path. On the command line the error is one line on
#: stderr, ``clearsim: error: ...``, and exit code 2 (a clearsim error, no traceback).
EXPECTED_FAILURES: Dict[Tuple[str, str, str], Tuple[type, str, str]] = {
    ("slider_crank_guide_clearance", "lubricated", "*"): (
        clearsim.InputError,
        r"clearance_joint\[0\]\.model = 'lubricated': must be one of dry",
        "a prismatic clearance joint is dry only (docs/physics.md §11; pydoc clearsim.scene: [clearance_joint.dry])",
    ),
}
EXIT_ERROR = 2  # clearsim.cli.EXIT_ERROR: a clearsim error, one line on stderr
#: The point every scene cell tracks on its analysed body ([outputs] points), body frame [m].
TRACKED, TRACKED_POINT = "tracked", (0.01, 0.005)


def _check_point(res: Any, body: str) -> None:
    """A body point stays at its distance from the centroid, and (0, 0) is the centroid."""
    offset = res.point(body, TRACKED_POINT) - res.position(body)[:, :2]
    np.testing.assert_allclose(np.hypot(*offset.T), math.hypot(*TRACKED_POINT), rtol=1e-12)
    np.testing.assert_array_equal(res.point(body, (0, 0), "velocity"), res.velocity(body)[:, :2])


class CommandFailed(Exception):
    """A ``clearsim`` command that exited non-zero: its exit code and stderr."""

    def __init__(self, code: int, err: str) -> None:
        super().__init__(f"exit {code}: {err}")
        self.code, self.err = code, err


# ---------------------------------------------------------------------- scene variants
def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"no TOML for {v!r}")


def _toml_table(path: List[str], table: Dict[str, Any], lines: List[str], array: bool = False) -> None:
    def is_tables(v: Any) -> bool:
        return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)

    if path:
        lines.append(f"[[{'.'.join(path)}]]" if array else f"[{'.'.join(path)}]")
    nested = {k: v for k, v in table.items() if isinstance(v, dict) or is_tables(v)}
    lines += [f"{json.dumps(k)} = {_toml_value(v)}" for k, v in table.items() if k not in nested]
    for k, v in nested.items():
        for item in [v] if isinstance(v, dict) else v:
            _toml_table(path + [k], item, lines, array=not isinstance(v, dict))


def to_toml(data: Dict[str, Any]) -> str:
    """TOML text of a scene's tables (inline tables written as sub-tables: the same data)."""
    lines: List[str] = []
    _toml_table([], data, lines)
    return "\n".join(lines) + "\n"


def test_the_toml_writer_gives_back_every_scene():
    for path in sorted(SCENES.glob("*.toml")):
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        assert tomllib.loads(to_toml(data)) == data, path.name


def _lubricated_table(cj: Dict[str, Any]) -> Dict[str, Any]:
    # Ocvirk's short bearing at L/D = 0.6: no finite-film table to build on a first run.
    table = dict(cj.get("lubricated") or {"viscosity": 0.05, "length": 1.2 * cj["journal_radius"], "film": "short"})
    if "dry" in cj:
        table["dry"] = cj["dry"]
    return table


def _dry_table(cj: Dict[str, Any]) -> Optional[Dict[str, Any]]:
    return cj.get("dry") or (cj.get("lubricated") or {}).get("dry")


def scene_kind(data: Dict[str, Any]) -> str:
    """ideal, dry, lubricated or mixed: the models of a scene's clearance joints."""
    kinds = {cj.get("model", "dry") for cj in data.get("clearance_joint", [])}
    return "ideal" if not kinds else "mixed" if len(kinds) > 1 else kinds.pop()


def variant(data: Dict[str, Any], kind: str) -> Optional[Dict[str, Any]]:
    """The scene with its clearance joints made ``kind`` (None if the scene cannot have it: a
    mixed one needs two revolute clearance joints). ``ideal`` turns them into ideal joints, as
    Mechanism.idealized() does, and drops what needs a clearance ([reliability], joint outputs)."""
    d = copy.deepcopy(data)
    joints = d.get("clearance_joint", [])
    revolute = [cj for cj in joints if cj.get("type", "revolute") == "revolute"]
    if kind == scene_kind(data):
        return d
    if kind == "ideal":
        for cj in joints:
            if cj.get("type", "revolute") == "revolute":
                ideal = {"type": "revolute", "name": cj["name"], "bodies": [cj["bearing_body"], cj["journal_body"]],
                         "points": [cj["bearing_point"], cj["journal_point"]]}  # fmt: skip
            else:
                ideal = {"type": "prismatic", "name": cj["name"], "bodies": [cj["guide_body"], cj["slider_body"]],
                         "points": [cj["guide_point"], [0.0, 0.0]], "axis": cj["axis"]}  # fmt: skip
            d.setdefault("joint", []).append(ideal)
        d.pop("clearance_joint", None)
        d.pop("reliability", None)
        for key in ("joints", "joint_quantities", "ideal"):
            d.get("outputs", {}).pop(key, None)
        return d
    if kind == "mixed" and len(revolute) < 2:
        return None
    # A film is stiff: RK45 crawls through it (100× the steps of RADAU5 on the short film here).
    d["simulation"]["integrator"] = "auto"
    for k, cj in enumerate(joints):
        model = kind if kind != "mixed" else ("dry" if k == 0 else "lubricated")
        if cj.get("type", "revolute") == "prismatic":
            cj["model"] = model  # a prismatic clearance is dry only: lubricated is the documented error
            continue
        dry, lub = _dry_table(cj), _lubricated_table(cj)
        cj.pop("dry", None)
        cj.pop("lubricated", None)
        cj["model"] = model
        if model == "dry" and dry is not None:
            cj["dry"] = dry
        elif model == "lubricated":
            cj["lubricated"] = lub
    return d


def short_scene(name: str, kind: str, t0_turns: float) -> Optional[Dict[str, Any]]:
    """Scene ``name`` with joints of ``kind``, run from t0 = t0_turns · T for SPAN turns at loose
    tolerances, with a two-sample Monte Carlo [study] (and FOSM) skipping t0_turns turns."""
    turn, _, body, component = SCENE_TABLE[name]
    data = variant(tomllib.loads((SCENES / f"{name}.toml").read_text(encoding="utf-8")), kind)
    if data is None:
        return None
    sim = data["simulation"]
    for key in ("cycles", "period", "t_end"):
        sim.pop(key, None)
    sim.update(t0=t0_turns * turn, t_end=(t0_turns + SPAN) * turn, outputs=["states"], **LOOSE)
    study = data.get("study")
    if study is None or kind == "ideal":
        # An ideal mechanism has no clearance to vary: a mass in its place (the error against
        # the ideal counterpart, itself, is then zero).
        first = (data.get("clearance_joint") or [None])[0]
        random = (
            {"path": f"{first['name']}.clearance", "mean": first["clearance"], "std": 0.05 * first["clearance"]}
            if first is not None
            else {"path": f"{body}.mass", "mean": 0.5, "std": 0.01}
        )
        study = data["study"] = {"body": body, "component": component, "quantity": "displacement", "limit": 1.0,
                                 "input": [dict(random, distribution="normal")]}  # fmt: skip
        if name == "engine":
            study["omega"] = 314.16
    study.pop("tolerance", None)
    study.update(skip_cycles=t0_turns, cycles=SPAN, methods=["monte_carlo", "fosm"], samples=2)
    if t0_turns == T0_TURNS["T/4"]:  # errors against the nominal design's motion (issue 36 item 3)
        study["reference"] = "nominal"
    # a tracked point on the analysed body (issue 36 item 2): its columns in clearsim run's files
    data.setdefault("outputs", {})["points"] = [{"name": TRACKED, "body": body, "point": list(TRACKED_POINT)}]
    return data


# ---------------------------------------------------------------------- the cells
def drawn(name: str, kind: str) -> bool:
    """Whether the cell's ``clearsim run`` / ``clearsim reliability`` at T/4 draws its figures
    (about 2 s each): each scene as shipped and every mixed variant, where a figure met a dry
    and a lubricated joint together (issue 28: KeyError in plot_journal_orbits)."""
    return kind == "mixed" or name in SHIPPED_ONLY or kind == scene_kind(tomllib.loads((SCENES / f"{name}.toml").read_text(encoding="utf-8")))


def _expected(subject: str, kind: str, path: str) -> Optional[Tuple[type, str, str]]:
    return EXPECTED_FAILURES.get((subject, kind, path)) or EXPECTED_FAILURES.get((subject, kind, "*"))


def _scene_cells() -> List[Any]:
    cells = []
    for name in SCENE_TABLE:
        data = tomllib.loads((SCENES / f"{name}.toml").read_text(encoding="utf-8"))
        kinds = [scene_kind(data)] if name in SHIPPED_ONLY else [k for k in KINDS if variant(data, k) is not None]
        for kind in kinds:
            for t0 in T0_TURNS:
                for path in SCENE_PATHS:
                    cells.append(pytest.param(name, kind, t0, path, id=f"{name}-{kind}-{t0}-{path}"))
    return cells


def _check_result(res: Any, t0: float, t_end: float) -> None:
    # The dt_out grid ends at its last point ≤ t_end (the run itself reaches t_end).
    assert res.completed and res.t[0] == pytest.approx(t0, abs=1e-12) and res.stats["t_reached"] == pytest.approx(t_end)
    assert t_end - res.t[-1] < max(np.diff(res.t), default=1.0) * (1 + 1e-9)
    for body in res.body_names:
        assert np.all(np.isfinite(res.position(body))), body


def _driver_angle(scene: Any, driver: str, t: float) -> float:
    """θ(t) = angle0 + ω t of a constant-speed driver [rad] (the closed form the pose at t0 must meet;
    angle0 not given: the driven body's angle as drawn)."""
    desc = scene.mechanism.description()
    d = next(d for d in desc["drivers"] if d["name"] == driver)
    law = d["law"]
    angle0 = law["angle0"] if law["angle0"] is not None else next(b.get("angle", 0.0) for b in desc["bodies"] if b["name"] == d["body"])
    return float(angle0 + law["omega"] * t)


def _run_scene_path(tmp_path: Path, capsys: Any, name: str, kind: str, t0: str, path: str) -> None:
    data = short_scene(name, kind, T0_TURNS[t0])
    assert data is not None
    file = tmp_path / f"{name}-{kind}.toml"
    file.write_text(to_toml(data), encoding="utf-8")
    turn, driver, body, _ = SCENE_TABLE[name]
    if path in ("clearsim run", "clearsim reliability"):
        command = "run" if path == "clearsim run" else "reliability"
        out = tmp_path / command
        plots = [] if t0 == "T/4" and drawn(name, kind) else ["--no-plots"]
        code = main([command, str(file), "-o", str(out), "-q", *plots])
        err = capsys.readouterr().err
        if code != 0:
            raise CommandFailed(code, err.strip())
        assert err == "", err
        if command == "run":
            summary = json.loads((out / "summary.json").read_text())
            assert summary["run"]["failure"] is None and "not_written" not in summary
            assert summary["run"]["t_reached"] == pytest.approx(data["simulation"]["t_end"])
            header = (out / "bodies.csv").read_text().splitlines()[0].split(",")
            # its x and/or y of each quantity, as [outputs] components and quantities say
            units = {"position": "m", "velocity": "m/s", "acceleration": "m/s^2"}
            named = [h for h in header if h.startswith(f"{TRACKED}.")]
            assert named and all(re.fullmatch(rf"{TRACKED}\.(\w+)\.[xy] \[(.+)\]", h) and units[h.split(".")[1]] == h.split("[")[1][:-1] for h in named), header
            if data.get("clearance_joint") and data["outputs"].get("ideal", True):  # against the ideal twin
                assert f"{TRACKED}.displacement_error." in (out / "errors.csv").read_text().splitlines()[0]
            if not plots and data.get("clearance_joint"):
                assert (out / "orbits.png").stat().st_size > 10_000
        else:
            report = (out / "report.md").read_text(encoding="utf-8")
            assert "monte_carlo" in report and (out / "samples.csv").is_file() and (out / "fosm.csv").is_file()
            if data["study"].get("reference") == "nominal" and "body" in data["study"]:
                assert '`reference = "nominal"`' in report
        return
    scene = load_scene_file(file)
    sim = scene.simulation
    if path == "simulate":
        res = scene.simulate()
        _check_result(res, sim.t0, sim.t_end)
        _check_point(res, body)
        if driver is not None:  # the pose at t0 follows the driver (closed form)
            driven = next(d["body"] for d in scene.mechanism.description()["drivers"] if d["name"] == driver)
            theta = res.position(driven)[0, 2]
            assert math.remainder(theta - _driver_angle(scene, driver, sim.t0), 2 * math.pi) == pytest.approx(0.0, abs=1e-6)
    elif path == "simulate_with_ideal":
        res, ideal = scene.mechanism.simulate_with_ideal(sim.t_end, progress=False, **sim.kwargs())
        _check_result(res, sim.t0, sim.t_end)
        _check_result(ideal, sim.t0, sim.t_end)
        if not scene.mechanism.clearance_joint_names:
            assert np.array_equal(res.position(body), ideal.position(body))  # the ideal counterpart of an ideal mechanism
        err = res.error(ideal, body, "displacement", point=TRACKED_POINT)
        assert err.shape == (len(res.t), 2) and np.all(np.isfinite(err))
    else:  # Study.monte_carlo
        est = scene_study(scene, progress=False).monte_carlo(2)
        assert est.n_runs == 2 and not est.failures, est.failures
        assert np.all(np.isfinite(est.peaks))
        if not scene.mechanism.clearance_joint_names:  # against itself: zero to the reference's accuracy
            assert np.all(est.peaks < 1e-4) and est.pf == 0.0  # rtol 1e-5 against a reference at 1e-6


@pytest.mark.parametrize("name, kind, t0, path", _scene_cells())
def test_scene_path(tmp_path, capsys, name, kind, t0, path):
    expected = _expected(name, kind, path)
    if expected is None:
        _run_scene_path(tmp_path, capsys, name, kind, t0, path)
        return
    error, words, _reason = expected
    if path.startswith("clearsim "):
        with pytest.raises(CommandFailed) as info:
            _run_scene_path(tmp_path, capsys, name, kind, t0, path)
        assert info.value.code == EXIT_ERROR and len(info.value.err.splitlines()) == 1, info.value.err
        assert re.search(words, info.value.err) and info.value.err.startswith("clearsim: error: "), info.value.err
        return
    with pytest.raises(error, match=words):
        _run_scene_path(tmp_path, capsys, name, kind, t0, path)


def _model(name: str, kind: str, **kw: Any) -> clearsim.Mechanism:
    build = getattr(models, name)
    return build(kind, **kw) if kind != "ideal" else build("ideal")


def _model_cells() -> List[Any]:
    return [
        pytest.param(name, kind, t0, path, id=f"{name}-{kind}-{t0}-{path}")
        for name in MODELS
        for kind in ("ideal", "dry", "lubricated")
        for t0 in T0_TURNS
        for path in PYTHON_PATHS
    ]


@pytest.mark.parametrize("name, kind, t0, path", _model_cells())
def test_model_path(name, kind, t0, path):
    """The shipped models (no model mixes kinds: the mixed cells are the scenes' above)."""
    turn, omega, body, component = MODELS[name]
    start = T0_TURNS[t0] * turn
    end = start + SPAN * turn
    m = _model(name, kind)
    if path == "simulate":
        res = m.simulate(end, t0=start, progress=False, **LOOSE)
        _check_result(res, start, end)
        driven = "crank" if name == "slider_crank" else "crank1"
        theta = res.position(driven)[0, 2]
        assert math.remainder(theta - omega * start, 2 * math.pi) == pytest.approx(0.0, abs=1e-6)
        # the crank tip (a body point: the crank's centroid is at mid-length) moves at |ω| r
        r = 0.05 if name == "slider_crank" else 0.10
        speed = np.hypot(*res.point(driven, (r / 2, 0.0), "velocity").T)
        np.testing.assert_allclose(speed, abs(omega) * r, rtol=1e-4)
    elif path == "simulate_with_ideal":
        res, ideal = m.simulate_with_ideal(end, t0=start, progress=False, **LOOSE)
        _check_result(res, start, end)
        _check_result(ideal, start, end)
    elif path == "Study.monte_carlo":
        inputs: Dict[str, Any] = {"c": Normal(0.5e-3, 0.02e-3)}
        study = Study(lambda c: _model(name, kind, clearance=c), inputs, Output(body=body, component=component, quantity="displacement"),
                      1.0, omega=omega, cycles=SPAN, skip_cycles=T0_TURNS[t0], progress=False, **LOOSE)  # fmt: skip
        est = study.monte_carlo(2)
        assert est.n_runs == 2 and not est.failures and np.all(np.isfinite(est.peaks))
        assert (est.pf == 0.0) if kind == "ideal" else True
        # A point on the analysed body against the nominal design's motion (issue 36 items 2, 3).
        point = Output(body=body, point=TRACKED_POINT, component="magnitude", quantity="displacement")
        nominal = Study(lambda c: _model(name, kind, clearance=c), inputs, point, 1.0, omega=omega, cycles=SPAN, skip_cycles=T0_TURNS[t0],
                        reference="nominal", progress=False, **LOOSE)  # fmt: skip
        est = nominal.monte_carlo(2)
        assert est.n_runs == 2 and not est.failures and np.all(np.isfinite(est.peaks))
        if kind == "ideal":  # a clearance that is not there moves nothing: zero to the reference's accuracy
            assert np.all(est.peaks < 1e-4)
    else:  # clearsim.monte_carlo: per-bin reliability and FOSM over a window shorter than a turn
        mc = clearsim.monte_carlo(lambda c: _model(name, kind, clearance=c), {"c": Normal(0.5e-3, 0.02e-3)}, 2, omega=omega,
                                  cycles=SPAN, skip_cycles=T0_TURNS[t0], body=body, component=component,
                                  allowable={"displacement": (0.0, 1.0)}, progress=False, **LOOSE)  # fmt: skip
        assert mc.completed == 2 if hasattr(mc, "completed") else not mc.failures
        bins = mc.bins["displacement"]
        seen = np.isfinite(bins.reliability)
        # the window covers SPAN × 360° = 18°: one bin of 18° (two if it straddles an edge)
        assert 1 <= seen.sum() <= 2 and np.all(bins.reliability[seen] == 1.0)
        assert np.isfinite(bins.fosm.min_reliability)


# ---------------------------------------------------------------------- walk 5: a six-bar of our own
#: tests/data/scenes/feeder_six_bar.toml: a Stephenson III six-bar feeder arm whose finger tip is
#: the output (a tool point, not a centroid); link lengths and a pivot are [parameters].
FEEDER = Path(__file__).resolve().parents[1] / "data" / "scenes" / "feeder_six_bar.toml"
FEEDER_NOMINAL = dict(r2=0.030, r3=0.100, r4=0.080, l5=0.110, l6=0.100, o6x=-0.090, o6y=0.160)
FEEDER_O4, FEEDER_C, FEEDER_ARM_HALF, FINGER = (0.100, 0.0), (0.0, 0.040), 0.075, (0.075, -0.015)
FEEDER_OMEGA = 240.0 * 2 * math.pi / 60  # rad/s


def _circles(p: Tuple[float, float], rp: float, q: Tuple[float, float], rq: float, side: int) -> Tuple[float, float]:
    """The intersection of the circles about p (radius rp) and q (rq) on the ``side`` of p → q."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    d = math.hypot(dx, dy)
    a = (rp**2 - rq**2 + d**2) / (2 * d)
    h = math.sqrt(rp**2 - a**2)
    return (p[0] + (a * dx - side * h * dy) / d, p[1] + (a * dy + side * h * dx) / d)


def feeder_pose(theta: float, r2: float, r3: float, r4: float, l5: float, l6: float, o6x: float, o6y: float) -> Dict[str, Any]:
    """The six-bar's pins at crank angle ``theta`` [rad] by its loop closure (closed form) and the
    arm's angle [rad]."""
    a = (r2 * math.cos(theta), r2 * math.sin(theta))
    b = _circles(a, r3, FEEDER_O4, r4, +1)
    ex, ey = (b[0] - a[0]) / r3, (b[1] - a[1]) / r3
    c = ((a[0] + b[0]) / 2 - FEEDER_C[1] * ey, (a[1] + b[1]) / 2 + FEEDER_C[1] * ex)
    d = _circles(c, l5, (o6x, o6y), l6, -1)
    return {"A": a, "B": b, "C": c, "D": d, "arm": math.atan2(d[1] - o6y, d[0] - o6x)}


def finger_closed_form(theta: float, **lengths: float) -> np.ndarray:
    """The finger tip's global position [m] at crank angle ``theta`` with ideal joints."""
    g = {**FEEDER_NOMINAL, **lengths}
    phi = feeder_pose(theta, **g)["arm"]
    x, y = FEEDER_ARM_HALF + FINGER[0], FINGER[1]
    return np.array([g["o6x"] + x * math.cos(phi) - y * math.sin(phi), g["o6y"] + x * math.sin(phi) + y * math.cos(phi)])


def feeder(joints: str = "clearance", cA: float = 15e-6, cD: float = 50e-6, cO6: float = 30e-6, **lengths: float) -> clearsim.Mechanism:
    """The scene's mechanism written in Python (a build function, its pose from the closed form):
    the crank pin A lubricated, the arm's pins D and O6 dry; ``joints="ideal"`` pins them all."""
    g = {**FEEDER_NOMINAL, **lengths}
    p = feeder_pose(0.0, **g)
    a, b, c, d, phi = p["A"], p["B"], p["C"], p["D"], p["arm"]
    m = clearsim.Mechanism(gravity=(0.0, -9.81))
    m.add_body("crank", mass=0.10, inertia=2.0e-5, ends=((0.0, 0.0), a))
    m.add_body("coupler", mass=0.25, inertia=2.1e-4, ends=(a, b))
    m.add_body("rocker", mass=0.12, inertia=6.4e-5, ends=(FEEDER_O4, b))
    m.add_body("link5", mass=0.10, inertia=1.0e-4, ends=(c, d))
    arm_centre = (g["o6x"] + FEEDER_ARM_HALF * math.cos(phi), g["o6y"] + FEEDER_ARM_HALF * math.sin(phi))
    m.add_body("arm", mass=0.30, inertia=5.6e-4, position=arm_centre, angle=phi)
    m.revolute("ground", (0.0, 0.0), "crank", (-g["r2"] / 2, 0.0), name="O2")
    m.revolute("ground", FEEDER_O4, "rocker", (-g["r4"] / 2, 0.0), name="O4")
    m.revolute("coupler", (g["r3"] / 2, 0.0), "rocker", (g["r4"] / 2, 0.0), name="B")
    m.revolute("coupler", FEEDER_C, "link5", (-g["l5"] / 2, 0.0), name="C")
    m.driver("crank", omega=FEEDER_OMEGA, name="motor")
    pins = {"A": ("coupler", (-g["r3"] / 2, 0.0), "crank", (g["r2"] / 2, 0.0)), "D": ("arm", (g["l6"] - FEEDER_ARM_HALF, 0.0), "link5", (g["l5"] / 2, 0.0)),
            "O6": ("arm", (-FEEDER_ARM_HALF, 0.0), "ground", (g["o6x"], g["o6y"]))}  # fmt: skip
    if joints == "ideal":
        for name, (body_a, point_a, body_b, point_b) in pins.items():
            m.revolute(body_a, point_a, body_b, point_b, name=name)
    else:
        dry = clearsim.Dry(restitution=0.7, friction=0.12)
        m.clearance_joint("A", *pins["A"], journal_radius=6e-3, clearance=cA, model=clearsim.Lubricated(viscosity=0.05, length=10e-3))
        m.clearance_joint("D", *pins["D"], journal_radius=4e-3, clearance=cD, model=dry)
        m.clearance_joint("O6", *pins["O6"], journal_radius=6e-3, clearance=cO6, model=dry)
    angle = [0.0, 0.5, 0.7, 2.3, 2.5, 2 * math.pi]
    m.force("arm", FINGER, {"driver": "motor", "angle": angle, "fx": [0.0, 0.0, -40.0, -40.0, 0.0, 0.0], "period": 2 * math.pi}, name="product")
    return m


def test_the_feeder_six_bar_walk(tmp_path, capsys):
    """Walk 5: a mechanism of our own (a Stephenson III six-bar feeder: lubricated crank pin, dry
    arm pins, link lengths and a pivot as [parameters], the finger tip as the output point) through
    a build function and its scene, both studied against the nominal design, and both commands.

    The ideal finger follows the six-bar's loop closure (closed form); a Study sample's peak
    finger error against the nominal design is its own run against the nominal ideal run (a
    second method); with ideal joints and a random l5 it is the closed form's
    max |P(l5) − P(l5₀)|; the scene and the build function are the same mechanism."""
    from clearsim.scene.study import scene_study

    turn = 2 * math.pi / FEEDER_OMEGA
    grid = dict(dt_out=turn / 400, progress=False, rtol=1e-9, atol=1e-12)
    ideal = feeder("ideal").simulate(0.25 * turn, **grid)
    closed = np.array([finger_closed_form(FEEDER_OMEGA * t) for t in ideal.t])
    np.testing.assert_allclose(ideal.point("arm", FINGER), closed, rtol=0, atol=1e-9)
    # the scene is the same mechanism: its [parameters] and rounded pose assemble to the same run
    scene = load_scene_file(FEEDER)
    short = dict(dt_out=turn / 400, progress=False, rtol=1e-7, atol=1e-10)
    by_scene = scene.mechanism.simulate(0.05 * turn, **short)
    by_build = feeder().simulate(0.05 * turn, extremes=[("arm", FINGER)], bearings=True, **short)
    np.testing.assert_allclose(by_scene.point("arm", FINGER), by_build.point("arm", FINGER), rtol=0, atol=1e-9)
    # the finger's peak speed, tracked at every step, and the crank pin's film beside it
    # (bearing_summary raised KeyError: 'coordinate' when a point was tracked)
    speed = np.hypot(*by_build.point("arm", FINGER, "velocity").T)
    assert speed.max() <= by_build.extremes("arm", "velocity", "magnitude", point=FINGER).max <= speed.max() * 1.01
    assert 0 < by_build.bearing_summary()["A"]["min_film_thickness"] < 15e-6

    # a random connecting link, ideal joints, against the nominal design: the closed form
    window = dict(skip_cycles=0.25, cycles=0.125, rtol=1e-7, atol=1e-10, progress=False)
    out = Output(body="arm", point=FINGER, component="magnitude", quantity="displacement")
    study = Study(lambda l5: feeder("ideal", l5=l5), {"l5": Normal(0.110, 0.1e-3)}, out, 0.2e-3, reference="nominal", **window)
    est = study.monte_carlo(3, seed=2)
    angles = FEEDER_OMEGA * turn * np.linspace(0.25, 0.375, 721)
    for k, l5 in enumerate(est.inputs["l5"]):
        expected = max(np.hypot(*(finger_closed_form(a, l5=float(l5)) - finger_closed_form(a))) for a in angles)
        assert est.peaks[k] == pytest.approx(expected, rel=2e-4), (k, l5)
    assert est.pf == float(np.mean(est.peaks > 0.2e-3))

    # the scene's own [study] (clearances, l5, l6 and O6 random), shortened: each sample alone
    text = FEEDER.read_text(encoding="utf-8").replace("skip_cycles = 1.0", "skip_cycles = 0.25").replace("\ncycles = 1.0", "\ncycles = 0.125")
    short_scene = tmp_path / "feeder.toml"
    short_scene.write_text(text, encoding="utf-8")
    sc = load_scene_file(short_scene)
    st = scene_study(sc, progress=False)
    assert st.reference == "nominal"
    mc = st.monte_carlo(2, seed=0)
    assert not mc.failures
    sim = sc.simulation
    end = 0.375 * turn
    fine = dict(dt_out=turn / 4000, progress=False, integrator=sim.integrator, rtol=sim.rtol, atol=sim.atol)
    nominal = feeder("ideal").simulate(end, **{**fine, "rtol": sim.rtol / 10, "atol": sim.atol / 10})
    names = {"A.clearance": "cA", "D.clearance": "cD", "O6.clearance": "cO6"}
    for k in range(2):
        x = {names.get(name, name): float(v[k]) for name, v in mc.inputs.items()}
        alone = feeder(**x).simulate(end, **fine)
        keep = alone.t >= 0.25 * turn - 1e-12
        e = np.hypot(*(alone.point("arm", FINGER) - nominal.point("arm", FINGER)).T)[keep]
        assert mc.peaks[k] == pytest.approx(e.max(), rel=2e-3), (k, x)

    # both commands on the shortened scene: the finger's columns, the nominal reference named
    out_dir = tmp_path / "run"
    assert main(["run", str(short_scene), "-o", str(out_dir), "-q", "--no-plots"]) == 0
    assert "finger.position.x [m]" in (out_dir / "bodies.csv").read_text().splitlines()[0]
    assert "finger.displacement_error.y [m]" in (out_dir / "errors.csv").read_text().splitlines()[0]
    rel_dir = tmp_path / "rel"
    assert main(["reliability", str(short_scene), "-o", str(rel_dir), "-q", "--no-plots", "--methods", "monte_carlo", "--samples", "2"]) == 0
    assert '`reference = "nominal"`' in (rel_dir / "report.md").read_text(encoding="utf-8")
    assert capsys.readouterr().err == ""


PLUNGER_PUMP = Path(__file__).resolve().parents[1] / "data" / "scenes" / "plunger_pump.toml"


def _plunger_work_per_turn(r: float = 0.040, rod: float = 0.160, n: int = 200_001) -> float:
    """The work [J] the drive does on the fluid in a turn of the pump's crank: −∮ F_x(θ) dx_p,
    with the plunger at x_p = r cos θ + √(l² − r² sin² θ) (closed form) and F_x the scene's
    table, by the trapezoidal rule on ``n`` angles."""
    area = math.pi / 4 * 0.030**2
    ramp = math.radians(10)
    theta = np.linspace(0.0, 2 * math.pi, n)
    fx = np.interp(theta, [0.0, math.pi, math.pi + ramp, 2 * math.pi - ramp, 2 * math.pi], [0.5e5 * area, 0.5e5 * area, -100e5 * area, -100e5 * area, 0.5e5 * area])
    xp = r * np.cos(theta) + np.sqrt(rod**2 - (r * np.sin(theta)) ** 2)
    return float(-np.sum(0.5 * (fx[1:] + fx[:-1]) * np.diff(xp)))


def test_the_plunger_pump_walk(tmp_path, capsys):
    """Walk 6: a plunger pump of our own (crank and flywheel, rod, plunger under a 100 bar load
    table over the crank angle; lubricated finite-film big end, dry wrist pin) read as a bearing
    engineer reads it, against hand calculations:

    - the ideal pump's mean driver torque over a turn is the fluid's work per turn (closed-form
      plunger kinematics) over 2π: 90.0 N m;
    - over the periodic second turn the big end's mean film force equals the ideal pump's mean
      reaction in that joint (the load balance; the journal's own inertia averages out);
    - the film's Couette friction torque is −2πμR³L(θ̇_j − θ̇_b)/(c√(1 − ε²)) at the recorded
      eccentricity and body speeds;
    - the side leakage is of the order of Ocvirk's R c L ρ, ρ = |(Wε, 2ε̇)| from the recorded
      motion (the finite film at L/D = 0.6 leaks somewhat less);
    - the minimum film, tracked at every step, lies below every stored c − |e| and at the crank
      angle the driver had then;
    then the scene through both commands (its CSV headers with units, its [study] against the
    nominal design)."""
    scene = load_scene_file(PLUNGER_PUMP)
    m = scene.mechanism
    omega, turn = 1500 * 2 * math.pi / 60, 0.04
    grid = dict(dt_out=turn / 720, progress=False)
    ideal = m.idealized().simulate(turn, outputs=["states", "reactions"], rtol=1e-9, atol=1e-12, **grid)
    tq = ideal.driver_torque("motor")
    mean_torque = float(np.sum(0.5 * (tq[1:] + tq[:-1]) * np.diff(ideal.t)) / turn)
    assert mean_torque == pytest.approx(_plunger_work_per_turn() / (2 * math.pi), rel=1e-3)

    res, nominal = m.simulate_with_ideal(2 * turn, outputs=["states", "joints", "reactions", "film"], bearings=True, extremes_from=turn, dt_out=turn / 360, progress=False)
    last = res.t >= turn - 1e-12

    def mean(v: np.ndarray) -> np.ndarray:
        t = res.t[last]
        return np.sum(0.5 * (v[last][1:] + v[last][:-1]) * np.diff(t)[:, None], axis=0) / (t[-1] - t[0])

    film, reaction = mean(res.joint_force("big-end")), mean(nominal.joint_force("big-end"))
    assert np.hypot(*(film - reaction)) < 0.005 * np.hypot(*reaction), (film, reaction)  # 3.4 kN mean

    mu, radius, length, c = 0.02, 0.020, 0.024, 30e-6
    e, e_dot = res.eccentricity("big-end"), res.eccentricity_rate("big-end")
    eps = np.hypot(*e.T) / c
    w_j, w_b = res.velocity("crank")[:, 2], res.velocity("rod")[:, 2]
    couette = -2 * math.pi * mu * radius**3 * length * (w_j - w_b) / (c * np.sqrt(1 - eps**2))
    np.testing.assert_allclose(res.friction_torque("big-end", part="couette"), couette, rtol=1e-6)

    whirl = (e[:, 0] * e_dot[:, 1] - e[:, 1] * e_dot[:, 0]) / np.maximum(np.hypot(*e.T) ** 2, 1e-30)
    eps_dot = np.sum(e * e_dot, axis=1) / np.maximum(np.hypot(*e.T), 1e-30) / c
    ocvirk = radius * c * length * np.hypot((w_j + w_b - 2 * whirl) * eps, 2 * eps_dot)
    leak = res.flow("big-end")[:, 0]
    assert 0.5 < leak[last].mean() / ocvirk[last].mean() < 1.0, (leak[last].mean(), ocvirk[last].mean())  # 1.98 vs 2.38 cm³/s
    np.testing.assert_array_equal(res.flow("big-end")[:, 1], leak)  # the Reynolds film: supply = side leakage

    b = res.bearing_summary()["big-end"]
    stored = c - np.hypot(*e[last].T)
    assert 0 < b["min_film_thickness"] <= stored.min() and b["min_film_thickness"] == pytest.approx(stored.min(), rel=0.02)
    crank = math.degrees(np.interp(b["t_min_film"], res.t, res.position("crank")[:, 2])) % 360
    assert b["min_film_crank_angle_deg"] == pytest.approx(crank, abs=1e-6)
    assert 180 < b["min_film_crank_angle_deg"] < 360  # under the discharge stroke

    # both commands on the scene, shortened: a quarter turn, the study's windows within it
    text = PLUNGER_PUMP.read_text(encoding="utf-8").replace("cycles = 2 ", "cycles = 0.25 ").replace("skip_cycles = 1.0 ", "skip_cycles = 0.125 ")
    text = text.replace("\ncycles = 1.0", "\ncycles = 0.125").replace("dt_out = 1e-4 ", "dt_out = 2e-4 ")
    short = tmp_path / "plunger_pump.toml"
    short.write_text(text, encoding="utf-8")
    out = tmp_path / "run"
    assert main(["run", str(short), "-o", str(out), "-q", "--no-plots"]) == 0
    header = (out / "joints.csv").read_text().splitlines()[0]
    for column in ("big-end.side_leakage [m^3/s]", "big-end.peak_pressure [Pa]", "big-end.film_thickness [m]", "wrist-pin.eps [1]"):
        assert column in header, header
    assert "rod-mid.displacement_error.x [m]" in (out / "errors.csv").read_text().splitlines()[0]
    rel_dir = tmp_path / "rel"
    assert main(["reliability", str(short), "-o", str(rel_dir), "-q", "--no-plots", "--methods", "monte_carlo", "--samples", "2"]) == 0
    assert "big-end.viscosity [Pa s]" in (rel_dir / "samples.csv").read_text().splitlines()[0]
    assert '`reference = "nominal"`' in (rel_dir / "report.md").read_text(encoding="utf-8")
    assert capsys.readouterr().err == ""
