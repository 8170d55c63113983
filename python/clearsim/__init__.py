"""clearsim: planar mechanisms with dry and lubricated revolute clearance joints.

The Rust core (``clearsim._core``) integrates; this package describes mechanisms, runs them and
analyses the results. SI units throughout.
"""

from . import _core
from .errors import AssemblyError, ClearsimError, ClusterError, InputError, InterruptedRun, PlausibilityWarning, ReliabilityError, SimulationError
from .joints import Archard, Dry, Lubricated, Thermal, Vogel
from .forces import Harmonic
from .mechanism import GROUND, Mechanism
from .result import Result
from . import models, reliability
from .montecarlo import monte_carlo
from .scene import load_scene
from .progress import set_progress

__version__ = _core.__version__

__all__ = [
    "Archard",
    "AssemblyError",
    "ClearsimError",
    "ClusterError",
    "Dry",
    "GROUND",
    "Harmonic",
    "InputError",
    "InterruptedRun",
    "Lubricated",
    "Mechanism",
    "ReliabilityError",
    "PlausibilityWarning",
    "Result",
    "load_scene",
    "SimulationError",
    "models",
    "monte_carlo",
    "reliability",
    "set_progress",
    "Thermal",
    "Vogel",
]
