"""Loading a scene file: :func:`load_scene_file` reads every table into a :class:`Scene` (the
mechanism with its run, output and reliability settings) and :meth:`Scene.run` runs it, the
ideal mechanism and the ``[reliability]`` FOSM with it (format: :mod:`clearsim.scene`)."""

from __future__ import annotations

import copy
import dataclasses
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from functools import partial
from typing import Any, Callable, Dict, Iterator, List, Mapping, Optional, Tuple, Union

import numpy as np

from .. import _core, display
from ..errors import InputError, PlausibilityWarning, SimulationError
from ..mechanism import Mechanism
from ..reliability.study import Study
from ..result import Result
from .alias import ReliabilitySettings, read_reliability, scene_fosm
from .builder import _Builder
from .study import STUDY_KEYS, StudySettings, parse_study, study_of
from .sweep import SWEEP_KEYS, SweepSettings, parse_sweep
from .settings import _CHANNEL_OF, ERROR_QUANTITIES, OutputSettings, SimulationSettings, _drive_speed, _outputs, _simulation
from ..schema import INPUT_UNITS
from .parameters import parameter_units, read_parameters
from .toml_reader import Source, Table, read_toml

PathLike = Union[str, Path]


@dataclass
class SceneRun:
    """The runs of a scene: the clearance run, the ideal run (if made) and the errors.

    ``errors[(body, quantity)]`` (quantity ``displacement``, ``velocity``, ``acceleration``) is
    the (N, 3) error clearance − ideal [SI] of :meth:`Result.error` (common part of both runs),
    ``errors[(point, quantity)]`` the (N, 2) error of a named point of ``[outputs] points``;
    ``reliability[quantity]`` the :class:`clearsim.reliability.FosmResult`.
    ``failure`` is the :class:`SimulationError` that stopped the clearance run early, if any
    (``result`` then holds the partial result); ``reliability_failure`` says why a scene's
    ``[reliability]`` gave no numbers (the run failed, or its nominal FOSM run did).
    """

    scene: "Scene"
    result: Result
    ideal: Optional[Result] = None
    errors: Dict[Tuple[str, str], np.ndarray] = field(default_factory=dict)
    reliability: Dict[str, Any] = field(default_factory=dict)
    failure: Optional[SimulationError] = None
    reliability_failure: Optional[str] = None

    def __repr__(self) -> str:
        return display.text(self, "result", "ideal", "errors", "reliability", "failure", "reliability_failure")


@dataclass
class Scene:
    """A mechanism with the run, output and reliability settings of a scene file."""

    mechanism: Mechanism
    simulation: SimulationSettings
    outputs: OutputSettings
    reliability: Optional[ReliabilitySettings] = None
    #: The ``[study]`` table (random inputs, one output and its limit; ``clearsim reliability``):
    #: a :class:`clearsim.scene.study.StudySettings`.
    study: Optional[StudySettings] = None
    #: The ``[sweep]`` table (a bifurcation diagram; ``clearsim sweep``): :class:`clearsim.scene.sweep.SweepSettings`.
    sweep: Optional[SweepSettings] = None
    name: str = ""
    description: str = ""
    path: Optional[Path] = None
    #: The values of the ``[parameters]`` table (named numbers the scene's fields may use).
    parameters: Dict[str, float] = field(default_factory=dict)
    #: The unit of each parameter, from the fields that use it (``"m"`` for a length;
    #: :func:`clearsim.scene.parameters.parameter_units`; absent where none is clear).
    parameter_units: Dict[str, str] = field(default_factory=dict)
    _ideal: Optional[Mechanism] = field(default=None, repr=False, compare=False)
    #: ``rebuild({parameter: value})``: the mechanism with those parameters changed (a
    #: ``[[study.input]]`` may randomise a parameter).
    _rebuild: Optional[Callable[[Mapping[str, float]], Mechanism]] = field(default=None, repr=False, compare=False)

    def with_overrides(self, *, t_end: Optional[float] = None, integrator: Optional[str] = None) -> "Scene":
        """A copy with another ``t_end`` [s] and/or integrator (validated)."""
        sim = dataclasses.replace(
            self.simulation,
            t_end=self.simulation.t_end if t_end is None else float(t_end),
            integrator=self.simulation.integrator if integrator is None else integrator,
        )
        _core.check_settings(self.mechanism.run_settings(sim.t_end, **sim.kwargs()))  # raises InputError if invalid (the core's checks)
        return dataclasses.replace(self, simulation=sim)

    def study_settings(self) -> Optional[StudySettings]:
        """The study ``clearsim reliability`` runs: the ``[study]`` table, else the one
        ``[reliability]`` is the short form of (:func:`~clearsim.scene.alias.alias_study`: FOSM
        per quantity of the nominal mechanism); ``None`` if the scene has neither."""
        if self.study is not None:
            return self.study
        return self.reliability.study(self.simulation) if self.reliability is not None else None

    def study_model(self, progress: bool = True) -> Study:
        """The :class:`~clearsim.reliability.Study` of :meth:`study_settings` (``clearsim
        reliability``); :class:`InputError` if the scene has neither table."""
        settings = self.study_settings()
        if settings is None:
            raise InputError(f"{self.path or 'the scene'} has no [study] table (random inputs, output and limit) nor [reliability]", field="study", value=None)
        return study_of(settings, self.mechanism, self.simulation, progress, rebuild=self._rebuild)

    def simulate(self) -> Result:
        """Run the mechanism with the scene's settings."""
        return self.mechanism.simulate(self.simulation.t_end, **self.simulation.kwargs())

    def ideal_mechanism(self) -> Mechanism:
        """The ideal counterpart of the mechanism (clearance joints → revolute joints)."""
        if self._ideal is None:
            self._ideal = self.mechanism.idealized()
        return self._ideal

    def run(self, ideal: Optional[bool] = None, progress: bool = False) -> SceneRun:
        """Run the scene: the ideal mechanism first (if ``ideal``, default from ``[outputs]``,
        or if ``[reliability]`` names a body), then the mechanism (with its bearing summary,
        ``bearings=True``, and with ``[outputs] reactions`` its joints' and drivers' peak
        reactions tracked at every step, ``extremes``, which the run's summary prints); errors; the FOSM reliability
        of ``[reliability]`` from the monitored nominal run (:func:`~clearsim.scene.alias.scene_fosm`).

        A :class:`SimulationError` of the clearance run is kept in ``SceneRun.failure`` with
        the partial result, not raised (the errors cover the part that was computed); one of the
        ideal run is raised. ``progress`` shows a bar (:mod:`clearsim.progress`) when more than one run is made.
        """
        has_clearance = bool(self.mechanism.clearance_joint_names)
        want_ideal = has_clearance and ((self.outputs.ideal if ideal is None else ideal) or self.reliability is not None)
        jobs: List[Tuple[str, Mechanism]] = [("ideal", self.ideal_mechanism())] if want_ideal else []
        jobs.append(("clearance" if has_clearance else "run", self.mechanism))
        results: Dict[str, Result] = {}
        failure: Optional[SimulationError] = None
        desc = self.path.stem if self.path is not None else "clearsim"
        for label, mech in _progress(jobs, progress, desc=desc):
            try:
                # The run's summary prints the bearing summary and, with [outputs] reactions, the
                # peak joint forces and driver torques (clearsim run): ask for them, tracked.
                tracked = label != "ideal"
                peaks = mech.clearance_joint_names + [n for n, _ in mech.held_reactions()] if tracked and self.outputs.reactions else []
                results[label] = mech.simulate(self.simulation.t_end, progress=progress, bearings=tracked, extremes=peaks or False, **self.simulation.kwargs())
            except SimulationError as err:
                if label == "ideal" or err.result is None:
                    raise
                results[label], failure = err.result, err
        for res in results.values():
            res.tracked_points = list(self.outputs.points)
        run = SceneRun(self, results[jobs[-1][0]], results.get("ideal"), failure=failure)
        if run.ideal is not None and len(run.result.t):
            bodies = set(self.outputs.bodies) | ({self.reliability.body} if self.reliability else set())
            for body in sorted(bodies):
                for quantity, error in ERROR_QUANTITIES.items():
                    if _CHANNEL_OF[quantity] in self.simulation.outputs:
                        run.errors[(body, error)] = run.result.error(run.ideal, body, error)
            for p in self.outputs.points:
                for quantity in self.outputs.quantities:
                    run.errors[(p.name, ERROR_QUANTITIES[quantity])] = run.result.error(run.ideal, p.body, ERROR_QUANTITIES[quantity], point=p.point)
        if self.reliability is not None:
            self._fosm(run, progress)
        return run

    def _fosm(self, run: SceneRun, progress: bool) -> None:
        """``run.reliability`` of ``[reliability]`` through Study.fosm (:func:`scene_fosm`), or
        why there is none in ``run.reliability_failure``."""
        assert self.reliability is not None
        if run.failure is not None:
            run.reliability_failure = f"FOSM not computed: the run failed ({run.failure.reason})"
            return
        try:
            run.reliability = scene_fosm(self.reliability, self.mechanism, self.simulation, progress)
        except SimulationError as err:
            run.reliability_failure = f"FOSM not computed: {err.reason}"
        except InputError as err:  # a run shorter than a crank turn
            run.reliability_failure = f"FOSM not computed: {err.reason}"


def _progress(items: List[Any], enabled: bool, desc: str) -> Iterator[Any]:
    """``items``, with a progress bar when enabled and there is more than one."""
    from ..progress import bar

    with bar(len(items), desc, "run", enabled=enabled and len(items) > 1) as b:
        for item in items:
            b.set_postfix_str(item[0] if isinstance(item, tuple) else str(item))
            yield item
            b.update(1)

# ====================================================================== reading a scene
_TOP_KEYS = (
    "parameters", "mechanism", "body", "joint", "driver", "clearance_joint", "force", "simulation", "outputs", "reliability", "study", "sweep",
)  # fmt: skip


def _needed_channels(outputs: OutputSettings, reliability: Optional[ReliabilitySettings]) -> List[str]:
    needed = ["violation"]
    if outputs.bodies or outputs.points:
        needed += [_CHANNEL_OF[q] for q in outputs.quantities]
    if outputs.points:
        needed.append("states")  # a point's velocity and acceleration read the body's pose and rate
    if outputs.reactions:
        needed.append("reactions")
    if outputs.joints:
        needed.append("joints")
    if reliability is not None:
        needed += [_CHANNEL_OF[b] for b, e in ERROR_QUANTITIES.items() if e in reliability.allowable]
    return needed


def load_scene_file(path: PathLike) -> Scene:
    """Read a scene file: the mechanism and its run, output and reliability settings.

    Raises :class:`InputError` ``"FILE:LINE: message"`` (attributes ``file``, ``line``,
    ``field``, ``value``) for invalid TOML, unknown keys, wrong types, missing keys and values
    the mechanism builder or the Rust core rejects.
    """
    path = Path(path)
    src, data = read_toml(path)
    builder, mech = _located_build(src, data)
    name = builder.mechanism_table.string("name", path.stem)
    description = builder.mechanism_table.string("description", "")
    outputs = _outputs(builder, mech)
    reliability = read_reliability(builder, mech)
    sim = _simulation(builder, mech, _needed_channels(outputs, reliability))
    study = None
    if "study" in builder.top:
        study = parse_study(builder.top.table("study", STUDY_KEYS), mech, _drive_speed(mech, builder.drivers))
    sweep = None
    if "sweep" in builder.top:
        table = builder.top.table("sweep", SWEEP_KEYS)
        assert table is not None
        sweep = parse_sweep(table, mech)
    return Scene(mech, sim, outputs, reliability, study=study, sweep=sweep, name=name, description=description, path=path,
                 parameters=dict(src.parameters), parameter_units=parameter_units(data, INPUT_UNITS), _ideal=mech.idealized(),
                 _rebuild=partial(_rebuilt, src, data))  # fmt: skip


def _located_build(src: Source, data: Dict[str, Any], overrides: Optional[Mapping[str, float]] = None) -> Tuple[_Builder, Mechanism]:
    """The scene's mechanism built from its tables ``data`` with the ``[parameters]`` (each of
    ``overrides`` replacing its definition), and the builder that located it: errors and
    plausibility warnings name the file and the line. The nominal build (no ``overrides``) is
    also compiled (the Rust core's checks, located in the file)."""
    if overrides is not None:
        src = copy.copy(src)  # its own parameters; the text and its lines shared
    top = Table(src, (), data, _TOP_KEYS)
    src.parameters = read_parameters(top, overrides)
    builder = _Builder(src, top)

    def emit(caught: List[warnings.WarningMessage]) -> None:
        for w in caught:  # a plausibility warning located in the file, like an error
            if isinstance(w.message, PlausibilityWarning):
                where = builder.relocate(InputError(str(w.message), field=getattr(w.message, "field", "")), None)
                warnings.warn(PlausibilityWarning(str(where)), stacklevel=4)
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)

    failed: Optional[InputError] = None
    refused: Optional[InputError] = None  # an element refused as it was added (located already)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            mech = builder.build()
        except InputError as err:
            refused = err
        if refused is None and overrides is None:
            try:
                # The Rust core's checks, located in the file; the compiled model is cached on the
                # mechanism, so the scene's own run does not compile it again (Mechanism.copy()
                # leaves it out of copies).
                mech.compile()
            except InputError as err:
                failed = err
    # The warnings first: a unit slip they name (a journal radius in mm) is often the cause
    # of the error that follows (an L/D outside the finite film's table).
    emit(caught)
    if refused is not None:
        raise refused
    if failed is not None:
        raise builder.relocate(failed, None) from None
    return builder, mech


def _rebuilt(src: Source, data: Dict[str, Any], values: Mapping[str, float]) -> Mechanism:
    """The scene's mechanism with the ``[parameters]`` named in ``values`` set to them (a
    ``[[study.input]]`` that randomises a parameter: Scene.study_model's build)."""
    return _located_build(src, data, values)[1]


def load_scene(path: PathLike) -> Mechanism:
    """The :class:`Mechanism` of a scene file (see :func:`load_scene_file` and the module
    docstring for the format)."""
    return load_scene_file(path).mechanism
