"""The ``[study]`` table of a scene file, read and checked, and the :class:`Study` it sets up
(``clearsim reliability``; ``[reliability]`` is its short form, :mod:`.alias`): random inputs of
the mechanism (by path, ``element.field``), one output with its limit or several (a series
system), and the methods to run.

::

    [study]                            # clearsim reliability scene.toml
    body = "slider9"                   # the output: a body coordinate's error against the
    component = "y"                    #   reference motion (x | y | theta) ...
    # point = [0.05, 0.0]              # ... or a point's on the body (body frame [m];
                                       #   component x | y | magnitude)
    # joint = "B"                      # ... or a clearance joint's quantity
    quantity = "displacement"          # displacement | velocity | acceleration;
                                       #   joint: eccentricity | force | contact_force | film_force
    limit = 1.1e-3                     # required: largest acceptable peak, in the quantity's unit
    cycles = 1.0                       # analysed crank turns after skip_cycles turns
    skip_cycles = 0.0
    # omega = -15.708                  # rad/s (default: the first constant-speed driver)
    # reference = "nominal"            # errors against: own_ideal (default: each sample's ideal
                                       #   twin, what the clearances add) | nominal (the nominal
                                       #   design's ideal motion: every tolerance counts)
    methods = ["form", "importance_sampling", "sobol"]
                                       # of monte_carlo, form, importance_sampling, subset, sobol,
                                       #   fosm, ak_mcs, ak_is (active-learning Kriging)
    # max_runs = 150                   # ak_mcs / ak_is: most model runs (AK-IS: FORM's included)
    samples = 1000                     # monte_carlo samples; subset runs per level; Sobol base
                                       #   size (× (d + 2) runs)
    cov = 0.1                          # importance sampling target coefficient of variation
    seed = 0
    # sobol_method = "saltelli"        # saltelli (n × (d + 2) runs) | pce (polynomial chaos, n runs)
    # step = 0.05                      # FORM's gradient step in u (default: from the measured noise)

    # Several outputs (a series system: it fails when any output passes its limit), instead of
    # body/component/joint/quantity/limit above:
    # [[study.output]]
    # body = "slider9"
    # component = "y"
    # quantity = "displacement"
    # limit = 1.1e-3
    # [[study.output]]
    # joint = "B"
    # quantity = "film_thickness"      # smallest gap c (1 − ε_max) [m]
    # limit = 2e-6
    # side = "below"                   # fails when it falls below the limit (default "above")

    [[study.input]]                    # one per random input
    path = "B.clearance"               # element.field of the mechanism, SI units, or
    # parameter = "rod"                #   a name of [parameters] (clearsim.scene.parameters): each
                                       #   sample rebuilds the mechanism with it (a link length)
    distribution = "normal"            # normal | lognormal (mean, std) | uniform (low, high)
    mean = 0.5e-3                      #   | truncated_normal (mean, std, low, high)
    std = 0.05e-3

    [study.life]                       # optional: p_f against operating cycles, Archard wear fed
    cycles = [0, 1e5, 2e5, 5e5]        #   back (the worn joints need wear = {..., feedback = true})
    samples = 100                      # samples run through their life (default: study.samples)
    reliability = 0.999                # report the cycles at which R falls to this (optional)
    # max_growth = 0.02                # cycle jumping: deepest bin's growth per jump / clearance
    # max_jump = 1e4                   # and at most this many cycles a jump

    [study.tolerance]                  # optional: the largest mean of one input that still
    input = "B.clearance"              #   meets a reliability
    reliability = 0.9999
    # bracket = [0.3e-3, 0.6e-3]
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Tuple, Union

from ..errors import InputError
from ..reliability.distributions import Distribution, LogNormal, Normal, TruncatedNormal, Uniform
from ..reliability.fosm import BIN_WIDTH
from ..reliability.life import MAX_BLOCKS
from ..reliability.outputs import BODY_QUANTITIES, JOINT_QUANTITIES, SIDES, Limit, Modes, Output
from ..reliability.sobol import SOBOL_METHODS
from ..reliability.study import Study
from ..schema import COMPONENTS, POINT_MONITOR_COMPONENTS, REFERENCES

# Extension point: a method is a name here (and in report.METHOD_RUNNERS); a method with
# settings of its own reads them from a sub-table [study.<name>] listed in STUDY_KEYS.
METHODS = ("monte_carlo", "form", "importance_sampling", "subset", "sobol", "fosm", "ak_mcs", "ak_is")
OUTPUT_KEYS = ("body", "component", "point", "joint", "quantity", "limit", "side")
#: The keys of [study] (the loader checks them before parse_study reads the table).
STUDY_KEYS = (*OUTPUT_KEYS, "cycles", "skip_cycles", "omega", "methods", "samples", "cov", "seed", "bin_width", "input", "tolerance", "output", "sobol_method", "step", "max_runs", "life", "reference")
INPUT_KEYS = ("path", "parameter", "distribution", "mean", "std", "low", "high")
TOLERANCE_KEYS = ("input", "reliability", "bracket")
LIFE_KEYS = ("cycles", "samples", "reliability", "max_growth", "max_jump", "settle", "max_blocks")
DISTRIBUTIONS = ("normal", "lognormal", "uniform", "truncated_normal")


@dataclass
class LifeSettings:
    """The ``[study.life]`` table: the cycle counts, the samples and what to report."""

    cycles: List[float]
    samples: int
    reliability: Optional[float] = None
    max_growth: float = 0.02
    max_jump: Optional[float] = None
    settle: Optional[float] = None
    max_blocks: int = MAX_BLOCKS  # blocks a sample may take (Study.life's max_blocks)


@dataclass
class StudySettings(Modes):
    """The ``[study]`` table, checked: ``outputs`` and their ``limits`` (one each, or several:
    a series system)."""

    outputs: List[Output]
    limits: List[Limit]
    omega: float
    inputs: Dict[str, Distribution]
    cycles: float = 1.0
    skip_cycles: float = 0.0
    methods: List[str] = field(default_factory=lambda: ["form", "importance_sampling"])
    samples: int = 1000
    cov: float = 0.1
    seed: int = 0
    bin_width: float = BIN_WIDTH
    tolerance: Optional[Tuple[str, float, Optional[Tuple[float, float]]]] = None
    sobol_method: str = "saltelli"
    step: Union[float, str] = "auto"
    max_runs: int = 150
    life: Optional[LifeSettings] = None
    #: Each output's allowable range (Δv, Δu) for FOSM (``None``: (0, limit)); set by [reliability].
    allowable: Optional[List[Tuple[float, float]]] = None
    #: Runs start here [s] (``[simulation].t0``; [reliability] only); crank angles count from t = 0 all the same (docs/physics.md §6).
    t0: float = 0.0
    #: What body and point errors are measured against (:data:`clearsim.schema.REFERENCES`).
    reference: str = "own_ideal"


def _output(t: Any, mech: Any, where: str) -> Tuple[Output, Limit]:
    """One output and its limit from the keys of ``t`` (``[study]`` or a ``[[study.output]]``)."""
    joint = t.string("joint", None, choices=mech.clearance_joint_names) if "joint" in t else None
    if joint is not None:
        if "body" in t or "component" in t or "point" in t:
            raise t.error("joint", f"invalid {where}: give either joint or body (with component), not both")
        quantity = t.string("quantity", choices=JOINT_QUANTITIES)
        output = Output(joint=joint, quantity=quantity)
    else:
        if "body" not in t:
            raise t.error(None, f"missing key 'body' (with component) or 'joint' in {where}: the analysed output")
        body = t.string("body", choices=mech.body_names)
        point = tuple(t.numbers("point", length=2)) if "point" in t else None
        component = t.string("component", choices=POINT_MONITOR_COMPONENTS if point is not None else COMPONENTS)
        output = Output(body=body, component=component, quantity=t.string("quantity", choices=BODY_QUANTITIES), point=point)
        if point is not None:  # in mm or in the global frame: a warning located at its line
            mech.warn_output_point(body, point, f"{where}.point", lambda msg: str(t.error("point", msg)))
    side = t.string("side", "below" if output.quantity == "film_thickness" else "above", choices=SIDES)
    if "limit" not in t:
        what = "largest acceptable" if side == "above" else "smallest acceptable"
        raise t.error(None, f"missing key 'limit' in {where}: the {what} {output.label} [{output.unit}] (there is no default)")
    limit = t.number("limit")
    if side == "above" and not limit > 0:
        raise t.error("limit", f"invalid {where}.limit = {limit!r}: must be positive [{output.unit}]", limit)
    if side == "below" and limit == 0:
        raise t.error("limit", f"invalid {where}.limit = 0: a lower limit must be non-zero [{output.unit}]", limit)
    if output.quantity == "film_thickness" and side != "below":
        raise t.error("side", f"invalid {where}.side = 'above': a film thickness fails by getting thin (side = \"below\")", side)
    return output, Limit(limit, side)


def _input_name(it: Any, mech: Any) -> Tuple[str, str]:
    """A ``[[study.input]]``'s name and the key that gives it: ``path`` (``element.field`` of the
    mechanism) or ``parameter`` (a name of ``[parameters]``: each sample rebuilds the scene with
    it; a name has no dot, so the two never meet)."""
    if "parameter" in it:
        if "path" in it:
            raise it.error("parameter", "invalid [[study.input]]: give path (element.field) or parameter (a [parameters] name), not both")
        name = it.string("parameter")
        known = it.src.parameters
        if name not in known:
            raise it.error("parameter", f"invalid study.input parameter {name!r}: no such parameter (known: {', '.join(known) or 'none: no [parameters] table'})", name)
        return name, "parameter"
    if "path" not in it:
        raise it.error(None, "missing key 'path' (element.field of the mechanism) or 'parameter' (a name of [parameters]) in [[study.input]]")
    path = it.string("path")
    if "." not in path and path in it.src.parameters:
        raise it.error("path", f"invalid study.input path {path!r}: a parameter is randomised by parameter = {path!r}", path)
    try:
        mech.value(path)
    except Exception as err:  # an InputError naming the path
        raise it.error("path", str(err), path) from None
    return path, "path"


def parse_study(t: Any, mech: Any, omega_default: Optional[float]) -> StudySettings:
    """Read the ``[study]`` table ``t`` (a scene ``_Table``: errors point at the key's line)."""
    tables = t.array_of_tables("output", OUTPUT_KEYS)
    if tables:
        extra = [k for k in OUTPUT_KEYS if k in t]
        if extra:
            raise t.error(extra[0], f"invalid [study]: give the outputs either as [[study.output]] tables or by {', '.join(OUTPUT_KEYS)} in [study], not both")
        pairs = [_output(o, mech, f"study.output[{k}]") for k, o in enumerate(tables)]
    else:
        pairs = [_output(t, mech, "[study]")]
    omega = t.number("omega", omega_default)
    if omega is None or omega == 0:
        raise t.error("omega", "missing key 'omega' in [study]: the drive speed [rad/s] (no constant-speed driver to take it from)", omega)
    inputs: Dict[str, Distribution] = {}
    for it in t.array_of_tables("input", INPUT_KEYS):
        path, key = _input_name(it, mech)
        kind = it.string("distribution", choices=DISTRIBUTIONS)
        try:
            if kind == "normal":
                d: Distribution = Normal(it.number("mean"), it.number("std"))
            elif kind == "lognormal":
                d = LogNormal(it.number("mean"), it.number("std"))
            elif kind == "uniform":
                d = Uniform(it.number("low"), it.number("high"))
            else:
                d = TruncatedNormal(it.number("mean"), it.number("std"), it.number("low"), it.number("high"))
        except Exception as err:
            if hasattr(err, "line") and getattr(err, "line", None):
                raise
            raise it.error(getattr(err, "field", None) and str(getattr(err, "field")).split(".")[-1], str(err)) from None
        if path in inputs:
            raise it.error(key, f"invalid study.input {key} {path!r}: given twice", path)
        inputs[path] = d
    if not inputs:
        raise t.error(None, "missing [[study.input]]: give at least one random input (path, distribution, parameters)")
    methods = t.strings("methods", ["form", "importance_sampling"], choices=METHODS)
    samples = t.integer("samples", 1000)
    if samples < 2:
        raise t.error("samples", f"invalid study.samples = {samples!r}: must be at least 2", samples)
    tol = None
    tt = t.table("tolerance", TOLERANCE_KEYS)
    if tt is not None:
        name = tt.string("input", choices=list(inputs))
        r = tt.number("reliability")
        if not 0 < r < 1:
            raise tt.error("reliability", f"invalid study.tolerance.reliability = {r!r}: must lie in (0, 1)", r)
        bracket = tt.numbers("bracket", None, length=2)
        tol = (name, r, tuple(bracket) if bracket else None)
    life = None
    lt = t.table("life", LIFE_KEYS)
    if lt is not None:
        cycles = lt.numbers("cycles")
        if not cycles or any(not (c >= 0) for c in cycles):
            raise lt.error("cycles", f"invalid study.life.cycles = {cycles!r}: give one or more cycle counts ≥ 0", cycles)
        r_life = lt.number("reliability", None)
        if r_life is not None and not 0 < r_life < 1:
            raise lt.error("reliability", f"invalid study.life.reliability = {r_life!r}: must lie in (0, 1)", r_life)
        values = {"samples": lt.integer("samples", samples), "max_growth": lt.number("max_growth", 0.02), "max_jump": lt.number("max_jump", None), "settle": lt.number("settle", None)}
        for key, v in values.items():
            if v is not None and not (v >= 0 if key == "settle" else v > 0):
                raise lt.error(key, f"invalid study.life.{key} = {v!r}: must be {'≥ 0' if key == 'settle' else 'positive'}", v)
        max_blocks = lt.integer("max_blocks", MAX_BLOCKS)
        if not max_blocks >= 1:
            raise lt.error("max_blocks", f"invalid study.life.max_blocks = {max_blocks!r}: must be at least 1", max_blocks)
        life = LifeSettings([float(c) for c in cycles], int(values["samples"]), r_life, float(values["max_growth"]), values["max_jump"], values["settle"], max_blocks)
    max_runs = t.integer("max_runs", 150)
    if max_runs < 2:
        raise t.error("max_runs", f"invalid study.max_runs = {max_runs!r}: must be at least 2", max_runs)
    # the window and the estimators' settings, checked here so that a mistake names its line
    window = {"cycles": t.number("cycles", 1.0), "skip_cycles": t.number("skip_cycles", 0.0), "cov": t.number("cov", 0.1), "bin_width": t.number("bin_width", BIN_WIDTH)}
    for key, v in window.items():
        if not (math.isfinite(v) and (v >= 0 if key == "skip_cycles" else v > 0)):
            raise t.error(key, f"invalid study.{key} = {v!r}: must be {'finite and ≥ 0' if key == 'skip_cycles' else 'finite and positive'}", v)
    step: Union[float, str] = "auto"
    if "step" in t:
        fixed = float(t.number("step"))
        if not fixed > 0:
            raise t.error("step", f"invalid study.step = {fixed!r}: FORM's gradient step in the standard normal space must be positive", fixed)
        step = fixed
    return StudySettings(
        outputs=[p[0] for p in pairs], limits=[p[1] for p in pairs], omega=float(omega), sobol_method=t.string("sobol_method", "saltelli", choices=SOBOL_METHODS), step=step, inputs=inputs, cycles=window["cycles"], skip_cycles=window["skip_cycles"],
        methods=methods, samples=samples, cov=window["cov"], seed=t.integer("seed", 0), bin_width=window["bin_width"], tolerance=tol,
        max_runs=max_runs, life=life, reference=t.string("reference", "own_ideal", choices=REFERENCES),
    )  # fmt: skip


def scene_study(scene: Any, progress: bool = True) -> Study:
    """The :class:`Study` of a scene's ``[study]`` table: its mechanism with the random inputs
    set by path (:meth:`clearsim.Mechanism.with_values`) or, for ``[parameters]``, rebuilt with
    them, run with the scene's integrator settings."""
    return study_of(scene.study, scene.mechanism, scene.simulation, progress, rebuild=getattr(scene, "_rebuild", None))


#: The name of the one fixed input of a study without inputs ([reliability]'s nominal run):
#: :class:`Study` asks for at least one; this one changes nothing.
NOMINAL = "nominal"


def study_of(s: StudySettings, mech: Any, sim: Any, progress: bool = True, rebuild: Optional[Callable[[Mapping[str, float]], Any]] = None) -> Study:
    """The :class:`Study` of the settings ``s`` on ``mech``, run with the integrator settings of
    ``sim`` (a :class:`~clearsim.scene.SimulationSettings`: integrator, tolerances, step, step
    bounds, step budget) from ``s.t0``. ``rebuild({parameter: value})`` makes the mechanism with
    ``[parameters]`` changed (inputs named without a dot; paths have one)."""
    parameters = [k for k in s.inputs if "." not in k]
    if parameters and rebuild is None:
        raise InputError(f"invalid inputs {parameters!r}: [parameters] inputs need the scene to rebuild the mechanism (Scene.study_model)", field="inputs", value=parameters)

    def build(**values: float) -> Any:
        changed = {k: v for k, v in values.items() if k in parameters}
        base = rebuild(changed) if (changed and rebuild is not None) else mech
        return base.with_values({k: v for k, v in values.items() if k in s.inputs and k not in parameters})

    opts: Dict[str, Any] = dict(integrator=sim.integrator, rtol=sim.rtol, atol=sim.atol)
    if sim.max_steps is not None:
        opts["max_steps"] = sim.max_steps
    outputs: Any = s.outputs if len(s.outputs) > 1 else s.outputs[0]
    limits: Any = s.limits if len(s.limits) > 1 else s.limits[0]
    inputs: Dict[str, Any] = dict(s.inputs) or {NOMINAL: 0.0}
    study = Study(build, inputs, outputs, limits, omega=s.omega, cycles=s.cycles, skip_cycles=s.skip_cycles, bin_width=s.bin_width, reference=s.reference, progress=progress, **opts)
    # Run options Study's signature does not take: rk4's fixed step, the step bounds, the start time.
    study.run_options.update({k: v for k, v in (("step", sim.step), ("h_max", sim.h_max), ("h_min", sim.h_min)) if v is not None})
    if s.t0 != 0.0:
        study.run_options["t0"] = s.t0
    return study
