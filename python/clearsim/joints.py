"""Clearance-joint models: the parameters of a dry or lubricated revolute clearance (docs/physics.md §3–§4).

All quantities in SI units. The parameters' defaults are the core's (``_core.DEFAULTS``, the serde
defaults of ``rust/description.rs``), and so are the checks of their values: a model is checked by
the core as it is made (``_core.check_element``, the checks of ``rust/compile/validate.rs``), so a
bad value is an :class:`~clearsim.InputError` at the call that gives it. The classes here check
only what must be known to write the plain data (the type of a nested model, a number's type).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, Optional, Tuple, Union

from . import _core
from .errors import InputError, check_choice, check_finite

NORMAL_LAWS = ("lankarani_nikravesh", "hertz", "hunt_crossley", "flores")
#: Dry contact stiffness forms (docs/physics.md §3): point contacts, or a pin as a line contact.
STIFFNESS_FORMS = ("internal", "paper_printed", "cylindrical")


def _numbers(model: Any, fields: Tuple[str, ...], optional: Tuple[str, ...] = ()) -> None:
    """Each of ``fields`` of ``model`` (and each of ``optional`` that is not ``None``) made a
    float, or an :class:`InputError` naming the field if it is not a finite number: checked where it is given, because
    inside a joint's model the core names a value's field for its range, not for its type
    (serde's path stops at the model)."""
    for name in fields + tuple(o for o in optional if getattr(model, o) is not None):
        object.__setattr__(model, name, check_finite(name, getattr(model, name)))  # a float, as the core reads it


#: The core's defaults of a dry law and of a lubricated joint's film (rust/description.rs).
_DRY: Dict[str, Any] = _core.DEFAULTS["dry"]
_FILM: Dict[str, Any] = _core.DEFAULTS["lubricated"]
FILM_MODELS = ("long", "short", "long_paper", "finite")
#: Where the finite film's pressure is ambient (docs/physics.md §4, finite bearing).
FILM_SUPPLIES = ("widest_gap", "none")
#: R_j/c from which a lubricated joint counts as a µm film: a long-bearing film there can crawl in
#: a whirl near the centre, and a journal released at rest against the wall can stall at once
#: (measured at R_j = 9.5 mm: docs/hard_cases.md, *µm films*; the core's, which words the hint
#: of a run that stalls there).
MICROMETRE_FILM_RATIO: float = float(_core.MICROMETRE_FILM_RATIO)


@dataclass(frozen=True)
class Archard:
    """Archard wear at a dry revolute clearance contact (docs/physics.md §12): worn volume
    V = k ∫ F_N |v_slip| dt / H, laid down as a depth around the bearing and the journal where
    they touch (see :meth:`Result.wear`).

    Parameters
    ----------
    coefficient:
        Dimensionless wear coefficient k (e.g. 1e-4 … 1e-3 for unlubricated steel on steel).
    hardness:
        Hardness H of the worn surface [Pa] (e.g. 2e9 Pa for a soft steel).
    length:
        Bearing length L [m], over which the volume spreads axially.
    feedback:
        ``True`` feeds the worn depth back into the contact: the penetration is measured from
        the worn surfaces (bearing and journal depth where they touch, updated after every
        accepted step), so the clearance grows where it wears. Default ``False``: wear is only
        booked. Contact onsets are still located at the unworn surface; with wear depths far
        below the clearance this shifts an impact by less than depth / approach speed.
    initial_bearing, initial_journal:
        Depths [m] already worn when the run starts, in the :data:`WEAR_BINS` 1° bins of
        :meth:`Result.wear` around the bearing and the journal (each in its body's frame);
        ``None`` (default): unworn. A run can so continue from an earlier one's worn state
        (``Result.wear(joint)[1]``), as reliability over life does; :meth:`Result.wear` then
        includes them, ``Result.wear_volume`` counts only what the run wears.
    """

    coefficient: float
    hardness: float
    length: float
    feedback: bool = False
    initial_bearing: Optional[Tuple[float, ...]] = field(default=None, repr=False)
    initial_journal: Optional[Tuple[float, ...]] = field(default=None, repr=False)

    def __post_init__(self) -> None:
        for name in ("coefficient", "hardness", "length"):  # numbers (written as floats); the core checks their signs
            check_finite(f"wear.{name}", getattr(self, name))
        if not isinstance(self.feedback, bool):
            raise InputError(f"invalid wear.feedback = {self.feedback!r}: must be True or False", field="wear.feedback", value=self.feedback)
        for name in ("initial_bearing", "initial_journal"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _depths(f"wear.{name}", value))

    def _as_dict(self) -> Dict[str, Any]:
        out: Dict[str, Any] = {"coefficient": float(self.coefficient), "hardness": float(self.hardness), "length": float(self.length), "feedback": bool(self.feedback)}
        for name in ("initial_bearing", "initial_journal"):
            if getattr(self, name) is not None:
                out[name] = list(getattr(self, name))
        return out


#: Bins around each worn surface (1° each, docs/physics.md §12).
WEAR_BINS = 360


def _depths(field: str, value: Any) -> Tuple[float, ...]:
    """A worn-depth profile as floats [m] (the core checks that it has :data:`WEAR_BINS` depths ≥ 0)."""
    try:
        return tuple(float(v) for v in value)
    except (TypeError, ValueError):
        raise InputError(f"invalid {field} = {value!r}: must be {WEAR_BINS} depths [m]", field=field, value=value) from None


@dataclass(frozen=True)
class Dry:
    """Dry clearance: impact with a continuous contact law and modified Coulomb friction.

    Parameters
    ----------
    normal_law:
        ``"lankarani_nikravesh"`` (default, P3), ``"hertz"`` (no damping), ``"hunt_crossley"``
        or ``"flores"`` (Flores et al. 2011).
    youngs_modulus, poisson_ratio:
        E [Pa] and ν [-] of the bearing; the journal's default to the same unless
        ``journal_youngs_modulus`` / ``journal_poisson_ratio`` are given.
    restitution:
        Coefficient of restitution c_e in (0, 1].
    exponent:
        n in K δⁿ (1.5, Hertzian).
    stiffness:
        Contact stiffness K [N/m^n]; ``None`` computes it from the materials (P4).
    stiffness_form:
        ``"internal"`` (default: a point contact of effective radius R_b R_j / (R_b − R_j), journal
        inside bearing, docs/physics.md erratum), ``"paper_printed"`` (R_b R_j / (R_b + R_j), as
        printed in the paper's Eq. 4) or ``"cylindrical"`` (a pin of ``length`` L in its bore as a
        line contact, Johnson's law for cylinders, docs/physics.md §3: the penetration falls
        nearly as 1/L; revolute clearance joints only, with ``stiffness=None`` and
        ``exponent=1.5``).
    length:
        Pin (contact) length L [m] of ``stiffness_form="cylindrical"``; ``None`` otherwise.
    friction:
        Sliding friction coefficient c_f [-].
    v0, v1:
        Modified-Coulomb slip-speed limits [m/s] (P5), v0 < v1.
    impact_speed_floor:
        Floor for the recorded impact speed δ̇⁽⁻⁾ [m/s], guarding resting contact.
    wear:
        :class:`Archard` to accumulate wear (revolute clearance joints), or ``None``.
    """

    normal_law: str = _DRY["normal_law"]
    youngs_modulus: float = _DRY["youngs_modulus"]
    poisson_ratio: float = _DRY["poisson_ratio"]
    journal_youngs_modulus: Optional[float] = None
    journal_poisson_ratio: Optional[float] = None
    restitution: float = _DRY["restitution"]
    exponent: float = _DRY["exponent"]
    stiffness: Optional[float] = _DRY["stiffness"]
    stiffness_form: str = "internal"
    friction: float = _DRY["friction"]
    v0: float = _DRY["v0"]
    v1: float = _DRY["v1"]
    impact_speed_floor: float = _DRY["impact_speed_floor"]
    wear: Optional[Archard] = None
    length: Optional[float] = None

    def __post_init__(self) -> None:
        if self.wear is not None and not isinstance(self.wear, Archard):
            raise InputError(f"invalid wear = {self.wear!r}: must be clearsim.Archard(...) or None", field="wear", value=self.wear)
        _numbers(self, ("youngs_modulus", "poisson_ratio", "restitution", "exponent", "friction", "v0", "v1", "impact_speed_floor"),
                 ("journal_youngs_modulus", "journal_poisson_ratio", "stiffness", "length"))  # fmt: skip
        check_choice("stiffness_form", self.stiffness_form, STIFFNESS_FORMS)
        _core.check_element("dry", self._as_dict())  # the values' ranges and what goes with what

    def _as_dict(self) -> Dict[str, Any]:
        e_j = self.youngs_modulus if self.journal_youngs_modulus is None else self.journal_youngs_modulus
        nu_j = self.poisson_ratio if self.journal_poisson_ratio is None else self.journal_poisson_ratio
        return {
            "kind": "dry",
            "normal_law": self.normal_law,
            "youngs_modulus": self.youngs_modulus,
            "journal_youngs_modulus": e_j,
            "poisson_ratio": self.poisson_ratio,
            "journal_poisson_ratio": nu_j,
            "restitution": self.restitution,
            "exponent": self.exponent,
            "stiffness": self.stiffness,
            "stiffness_form": self.stiffness_form,
            "length": None if self.length is None else float(self.length),
            "friction": self.friction,
            "v0": self.v0,
            "v1": self.v1,
            "impact_speed_floor": self.impact_speed_floor,
            "wear": None if self.wear is None else self.wear._as_dict(),
        }


@dataclass(frozen=True)
class Vogel:
    """Vogel's viscosity law of the oil temperature, μ(T) = a·exp(b/(T − c)) (Vogel 1921; the
    core's ``rust/laws/viscosity.rs``, docs/physics.md §4, *Heat*), for ``Lubricated(viscosity=…)``
    with ``thermal``. Valid for T > c.

    Parameters
    ----------
    a:
        Viscosity scale [Pa s] (> 0): μ as T → ∞.
    b:
        Temperature scale [K] (≥ 0).
    c:
        Temperature [K] at which the law's viscosity becomes infinite (below the oil's).
    """

    a: float
    b: float
    c: float

    def __post_init__(self) -> None:
        for name in ("a", "b", "c"):  # numbers (written as floats); the core checks a > 0, b ≥ 0
            check_finite(f"viscosity.vogel.{name}", getattr(self, name))

    def viscosity(self, temperature: float) -> float:
        """μ [Pa s] at ``temperature`` [K] (> c)."""
        t = check_finite("temperature", temperature)
        if t <= self.c:
            raise InputError(f"invalid temperature = {temperature!r}: Vogel's law holds above c = {self.c:g} K", field="temperature", value=temperature)
        return float(self.a * math.exp(self.b / (t - self.c)))


@dataclass(frozen=True)
class Thermal:
    """One effective oil temperature T per lubricated joint (docs/physics.md §4, *Heat*):
    C dT/dt = P_loss − hA (T − T_ambient), the film's power loss heating the oil and the parts
    that follow its temperature, the ambient cooling them; with ``Lubricated(viscosity=Vogel(…))``
    the film is evaluated at μ(T). Read back with :meth:`Result.temperature`.

    Parameters
    ----------
    ambient:
        Ambient temperature T_ambient [K].
    heat_capacity:
        Heat capacity C [J/K] of the oil and the parts at its temperature.
    heat_transfer:
        Heat transfer coefficient times area hA [W/K] to the ambient. The time constant C/hA [s]
        sets how fast the oil settles.
    initial:
        Oil temperature at the start [K]; ``None`` (default): the ambient.
    """

    ambient: float
    heat_capacity: float
    heat_transfer: float
    initial: Optional[float] = None

    def __post_init__(self) -> None:
        for name in ("ambient", "heat_capacity", "heat_transfer", "initial"):  # numbers; the core checks their signs
            if getattr(self, name) is not None:
                check_finite(f"thermal.{name}", getattr(self, name))

    def _as_dict(self) -> Dict[str, Any]:
        d: Dict[str, Any] = {"ambient": float(self.ambient), "heat_capacity": float(self.heat_capacity), "heat_transfer": float(self.heat_transfer)}
        if self.initial is not None:
            d["initial"] = float(self.initial)
        return d


@dataclass(frozen=True)
class Lubricated:
    """Lubricated clearance: a hydrodynamic journal bearing with the transition to dry contact.

    Parameters
    ----------
    viscosity:
        Dynamic viscosity μ [Pa s], or :class:`Vogel`'s law μ(T) of the oil temperature (with
        ``thermal``: the film is evaluated at μ(T) along the run).
    length:
        Bearing length L [m].
    film:
        ``"long"`` (default: Pinkus–Sternlicht long bearing, Gümbel condition, quadrature of the
        positive pressure; the paper's model), ``"short"`` (Ocvirk short bearing), ``"finite"``
        (any 1/16 ≤ L/D ≤ 16: the Reynolds equation with the Reynolds cavitation condition, solved
        once per L/D into a table, a few seconds the first time on a machine, then read from the
        user cache directory; within 1 % of Butenschön's tables, see ``supply``) or
        ``"long_paper"`` (the paper's printed closed forms P13–P14, wrong for a receding journal;
        for comparison only, and they can stall the integrator). Neither closed form is accurate
        between L/D ≈ 1/2 and 8: use ``"finite"`` there (how far each is off, measured against the
        finite bearing across L/D and ε: docs/physics.md §4, *Validity of the closed forms*).
        Also for clearances of a few µm: a journal whirling at half the shaft speed meets a
        negative squeeze damping in the long bearing's half-Sommerfeld film, and in the finite film
        with its supply line, and the run can crawl, where the periodic finite film
        (``supply="none"``) damps; a journal released at rest against the wall with the drive at
        speed leaves it at default settings only above a clearance that depends on the film
        (measured: docs/hard_cases.md, *µm films*): start µm films centred.
    eps0, m:
        Below ε0 both film components are scaled by (ε/ε0)^m (P15–P16, made continuous at
        ε0: docs/physics.md §4).
    e0:
        Width of the film-to-contact transition band [m] (P18); ``None`` = 5 % of the clearance.
    eps_max:
        The film is evaluated at min(ε, ε_max) inside the band (it is singular at ε = 1).
    dry:
        The dry law that takes over beyond e = c.
    cavitation:
        How the finite film ruptures and reforms (``film="finite"`` only): ``"reynolds"``
        (default: p ≥ 0 with the Reynolds condition, from the tables) or ``"jfo"``
        (mass-conserving, Jakobsson–Floberg–Olsson in Elrod–Adams' film-content form: the oil
        content over the bearing is carried from step to step, the pressure solved at every
        evaluation; needs ``supply="widest_gap"``, where the oil comes in). Costlier (a
        complementarity problem on a 90 × 8 grid each evaluation); docs/physics.md §4,
        *Mass-conserving cavitation*.
    supply:
        Where the finite film's pressure is ambient (``film="finite"`` only):
        ``"widest_gap"`` (default: on the axial line of the widest gap, where a bearing is fed, as
        Butenschön's rotation table, the Raimondi–Boyd charts, DIN 31652 and the paper's
        long-bearing pressure P12 take it) or ``"none"`` (a film periodic around the bearing,
        ambient only at its ends, as Butenschön's squeeze table). docs/physics.md §4 compares both.
    roughness:
        Composite RMS roughness σ = √(σ₁² + σ₂²) of journal and bearing [m] (``None``, the
        default: smooth surfaces). Where the film is thinner than 4σ the asperities carry load by
        Greenwood & Tripp's law (σηβ = 0.04, σ/β = 10⁻³, the modulus of the ``dry`` law's
        materials), with ``boundary_friction`` on that load; this replaces the film-to-contact
        band ``e0`` (P18), and the dry law acts only where the mean surfaces overlap (e > c).
        docs/physics.md §4, *Roughness and mixed lubrication*. Must be below c/4.
    boundary_friction:
        Friction coefficient μ_b on the asperity load (with ``roughness``; default: the ``dry``
        law's ``friction``).
    boundary_slip:
        Slip speed [m/s] over which the boundary friction rises from 0 at standstill to μ_b (with
        ``roughness``; default 1e-4 m/s): its own regularisation, so that the friction coefficient
        tends to μ_b × (asperity share) as the journal slows down (the dry law's v0, v1 ramp
        impacts, not the asperities).
    thermal:
        :class:`Thermal`: the joint's effective oil temperature, heated by its power loss and
        cooled to the ambient (docs/physics.md §4, *Heat*; :meth:`Result.temperature`). Needed by
        a :class:`Vogel` viscosity; with a constant one the temperature is an output only.
    """

    viscosity: Union[float, Vogel] = 0.4  # the two values the core's description requires: defaults of this API only
    length: float = 0.05
    film: str = _FILM["film"]
    eps0: float = _FILM["eps0"]
    m: float = _FILM["m"]
    e0: Optional[float] = _FILM["e0"]
    eps_max: float = _FILM["eps_max"]
    dry: Dry = field(default_factory=Dry)
    supply: str = _FILM["supply"]
    roughness: Optional[float] = None
    boundary_friction: Optional[float] = None
    thermal: Optional[Thermal] = None
    boundary_slip: Optional[float] = None
    cavitation: str = "reynolds"

    def __post_init__(self) -> None:
        # The nested models must be these classes (they write themselves as plain data). The
        # values' ranges, the choices of film and supply and what goes with what are the core's checks.
        if self.thermal is not None and not isinstance(self.thermal, Thermal):
            raise InputError(f"invalid thermal = {self.thermal!r}: must be clearsim.Thermal(...) or None", field="thermal", value=self.thermal)
        if not isinstance(self.dry, Dry):
            raise InputError(f"invalid dry = {self.dry!r}: must be clearsim.Dry(...)", field="dry", value=self.dry)
        _numbers(self, ("length", "eps0", "m", "eps_max") + (() if isinstance(self.viscosity, Vogel) else ("viscosity",)), ("e0", "roughness", "boundary_friction", "boundary_slip"))
        _core.check_element("lubricated", self._as_dict())  # the values' ranges and what goes with what

    def _as_dict(self) -> Dict[str, Any]:
        d: Dict[str, Any] = {
            "kind": "lubricated",
            "film": self.film,
            "supply": self.supply,
            "viscosity": {"vogel": [float(self.viscosity.a), float(self.viscosity.b), float(self.viscosity.c)]} if isinstance(self.viscosity, Vogel) else self.viscosity,
            "length": self.length,
            "eps0": self.eps0,
            "m": self.m,
            "eps_max": self.eps_max,
            "dry": self.dry._as_dict(),
        }
        if self.e0 is not None:
            d["e0"] = self.e0
        if self.roughness is not None:
            d["roughness"] = self.roughness
        if self.boundary_friction is not None:
            d["boundary_friction"] = self.boundary_friction
        if self.boundary_slip is not None:
            d["boundary_slip"] = self.boundary_slip
        if self.cavitation != "reynolds":
            d["cavitation"] = self.cavitation
        if self.thermal is not None:
            d["thermal"] = self.thermal._as_dict()
        return d
