"""Each description is compiled once (issue 29, criterion 3): a scene file is checked by the core
when it loads, and its run uses that compiled model instead of compiling it a second time. One
request, one crossing (issue 38, item 1): ``simulate`` is one core call once compiled, the pose
given is assembled once per compiled model, the description built once per change."""

from __future__ import annotations

from pathlib import Path
from typing import Any, List

import numpy as np
import pytest

from clearsim import Mechanism, _core, models, running
from clearsim.scene import load_scene_file

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def test_a_scene_compiles_its_mechanism_once(monkeypatch: pytest.MonkeyPatch) -> None:
    calls: List[Any] = []
    real = running._core.compile

    def counting(description: Any, *args: Any) -> Any:
        calls.append(description)
        return real(description, *args)

    monkeypatch.setattr(running._core, "compile", counting)
    scene = load_scene_file(SCENES / "slider_crank.toml").with_overrides(t_end=0.01)
    assert len(calls) == 1  # the load's check
    scene.run(ideal=False)
    assert len(calls) == 1  # the run reused it


# ---------------------------------------------------------------- one request, one crossing (issue 38 item 1)
class _Counted:
    """A compiled model whose method calls are counted (each is a crossing into the core)."""

    def __init__(self, inner: Any, calls: List[str]) -> None:
        self._inner, self._calls = inner, calls

    def __getattr__(self, name: str) -> Any:
        attr = getattr(self._inner, name)
        if not callable(attr):
            return attr

        def crossing(*args: Any, **kwargs: Any) -> Any:
            self._calls.append(f"CompiledModel.{name}")
            return attr(*args, **kwargs)

        return crossing


@pytest.fixture
def crossings(monkeypatch: pytest.MonkeyPatch) -> List[str]:
    """Every call into the core from the running layer (compile and the compiled model's
    methods), and every build of a mechanism's description."""
    calls: List[str] = []
    real_compile = running._core.compile

    def compile_counted(*args: Any, **kwargs: Any) -> Any:
        calls.append("_core.compile")
        return _Counted(real_compile(*args, **kwargs), calls)

    monkeypatch.setattr(running._core, "compile", compile_counted)
    real_description = Mechanism._description

    def description_counted(self: Mechanism) -> Any:
        if self._plain is None:
            calls.append("description built")
        return real_description(self)

    monkeypatch.setattr(Mechanism, "_description", description_counted)
    return calls


def test_simulate_is_one_core_call_and_assembles_once(crossings: List[str]) -> None:
    """``simulate`` on a compiled mechanism crosses into the core once (its run) and neither
    assembles nor describes the mechanism again; a fresh one adds its compile, one description
    build and one assembly (the pose given, assembled when it compiles: the pose check, the
    springs' free lengths and every run start from it). Before: three crossings (compile, the
    pose check's initial_state, simulate), two or three assemblies and four description copies."""
    m = models.slider_crank("dry", clearance=0.5e-3)
    before = _core.assembly_count()
    m.simulate(0.002, dt_out=1e-4, progress=False)
    assert crossings == ["description built", "_core.compile", "CompiledModel.simulate"]
    assert _core.assembly_count() - before == 1
    crossings.clear()
    m.simulate(0.002, dt_out=1e-4, progress=False, t0=0.001)  # from t0 ≠ 0: the drivers followed from the same start
    assert crossings == ["CompiledModel.simulate"] and _core.assembly_count() - before == 1


def test_a_spring_without_free_length_assembles_once(crossings: List[str]) -> None:
    """A spring whose free length is the assembled distance: the compile's assembly gives it,
    and the run starts from the same assembly (it assembled twice, the pose check a third time)."""
    m = models.slider_crank("dry", clearance=0.5e-3)
    m.spring("ground", (0.0, 0.1), "crank", (0.0, 0.0), stiffness=100.0)
    before = _core.assembly_count()
    res = m.simulate(0.002, dt_out=1e-4, progress=False)
    assert res.completed and _core.assembly_count() - before == 1
    assert crossings.count("_core.compile") == 1 and crossings.count("CompiledModel.simulate") == 1


def test_simulate_with_ideal_assembles_each_mechanism_once(crossings: List[str]) -> None:
    """The run and its ideal twin: the compiled mechanism runs as compiled (its pose assembled
    once, at the compile) beside the twin, compiled in the core: two assemblies, one a mechanism,
    and the numbers of the two descriptions run by the core's batch (the path before, which
    compiled and assembled the mechanism a second time: three assemblies)."""
    m = models.slider_crank("dry", clearance=0.5e-3)
    before = _core.assembly_count()
    res, ideal = m.simulate_with_ideal(0.002, dt_out=1e-4, progress=False)
    assert _core.assembly_count() - before == 2
    assert crossings.count("_core.compile") == 1 and crossings.count("CompiledModel.simulate_with_ideal") == 1
    twin = m.idealized()
    raws = _core.run_batch([m.description(), twin.description()], [m.run_settings(0.002, dt_out=1e-4), twin.run_settings(0.002, dt_out=1e-4)], 1)
    for got, raw in zip((res, ideal), raws):
        for key in ("t", "q", "qd", "qdd", "joints"):
            assert np.array_equal(got._raw[key], raw[key]), key
        assert got._raw["stats"]["steps"] == raw["stats"]["steps"]


def test_a_batch_run_assembles_once() -> None:
    """A run of the core's batch (a Study's sample) compiles and assembles its description once."""
    m = models.slider_crank("dry", clearance=0.5e-3)
    m.spring("ground", (0.0, 0.1), "crank", (0.0, 0.0), stiffness=100.0)
    before = _core.assembly_count()
    (raw,) = _core.run_batch([m.description()], m.run_settings(0.002, dt_out=1e-4), 1)
    assert raw["error"] is None and _core.assembly_count() - before == 1


def test_a_study_sample_is_described_once_and_assembled_once(crossings: List[str], monkeypatch: pytest.MonkeyPatch) -> None:
    """Eight dry Study samples (random clearance, errors against each sample's own ideal twin):
    one core batch, each sample's mechanism described once and not copied, not compiled on the
    Python side, assembled once in the batch, and one reference run for all eight (their ideal
    twins are the same mechanism: rust/batch.rs runs it once). Before: each sample called
    ``_core.idealize`` and copied its description five times."""
    import math

    import numpy as np

    from clearsim.reliability import Normal, Output, Study

    batches: List[int] = []
    real_batch = _core.run_batch

    def batch_counted(descriptions: Any, *args: Any, **kwargs: Any) -> Any:
        batches.append(len(descriptions))
        return real_batch(descriptions, *args, **kwargs)

    monkeypatch.setattr(_core, "run_batch", batch_counted)
    copies: List[str] = []
    real_copy = Mechanism.description
    monkeypatch.setattr(Mechanism, "description", lambda self: copies.append("copy") or real_copy(self))
    study = Study(lambda c: models.slider_crank("dry", clearance=c), {"c": Normal(0.5e-3, 0.01e-3)},
                  Output(body="slider", component="x"), 1e-3, omega=500 * math.pi / 3, cycles=0.25, progress=False)  # fmt: skip
    study.run_samples({"c": np.array([0.5e-3])})  # the first sample's pose check (a compile)
    crossings.clear(), batches.clear(), copies.clear()
    before = _core.assembly_count()
    study.run_samples({"c": np.linspace(0.49e-3, 0.51e-3, 8)})
    assert batches == [8] and copies == []
    assert crossings.count("description built") == 8 and "_core.compile" not in crossings
    assert _core.assembly_count() - before == 8 + 1  # each sample, and their one ideal reference
