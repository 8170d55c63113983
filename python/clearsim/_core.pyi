"""Type stub of the native module ``clearsim._core`` (Rust, pyo3). Use the ``clearsim`` facade."""

from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
JOINT_COLUMNS: List[str]
ENERGY_COLUMNS: List[str]

class CompiledModel:
    """A validated, compiled mechanism."""

    @property
    def state_dim(self) -> int: ...
    @property
    def constraint_rows(self) -> int: ...
    @property
    def dof(self) -> int: ...
    @property
    def contact_stiffness(self) -> List[float]: ...
    def initial_state(self, t0: float) -> npt.NDArray[np.float64]: ...
    def rhs(self, t: float, y: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def jacobian(self, t: float, y: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def simulate(self, settings: Dict[str, Any], progress: Optional[Callable[[float], None]] = None) -> Dict[str, Any]: ...
    def idealized(self) -> "CompiledModel": ...

def compile(description: Union[str, Dict[str, Any]]) -> CompiledModel:
    """Validate and compile a description (plain data or its JSON text), read by serde."""

def run_batch(
    descriptions: List[Union[str, Dict[str, Any]]],
    settings: Union[Dict[str, Any], List[Dict[str, Any]]],
    threads: int = 0,
) -> List[Union[Dict[str, Any], BaseException]]: ...

run_batch_py = run_batch

def film_force(
    film: str, viscosity: float, journal_radius: float, clearance: float, length: float, eps: float, eps_dot: float, wedge: float
) -> Tuple[float, float]:
    """Film force (F_ξ, F_η) [N] on the journal (docs/physics.md §4); film one of long, short,
    long_paper, finite; SI units, ε̇ [1/s], wedge speed [rad/s]."""
