"""Dynamic-accuracy reliability of a mechanism output (docs/physics.md §6, paper section 4).

The study of one output with random inputs::

    from clearsim import reliability as rel
    study = rel.Study(build, inputs={"clearance": rel.Normal(0.5e-3, 0.02e-3), "viscosity": 0.4},
                      output=rel.Output(body="slider9", component="y", quantity="displacement"),
                      limit=1e-3, omega=-5 * np.pi, cycles=1.0)
    study.monte_carlo(n)   study.form()   study.importance_sampling(cov=0.1)   study.subset()
    study.sobol(n)         study.tolerance("clearance", reliability=0.999)      study.fosm()

Rooms: :mod:`.distributions` (random inputs on ``scipy.stats``), :mod:`.fosm` (the paper's
first-order second-moment method, Eqs. P27–P32), :mod:`.estimates` (Monte Carlo statistics),
:mod:`.model` (what the methods need of a model; :class:`LimitState` for any function),
:mod:`.study` (:class:`Study`, the simulation model), :mod:`.uq` (FORM, importance sampling,
subset simulation, Sobol indices and tolerance design on OpenTURNS, ``pip install clearsim[uq]``).
"""

from .distributions import Distribution, Fixed, LogNormal, Normal, Scipy, Shifted, TruncatedNormal, Uniform, as_distribution, sample_inputs
from .estimates import Estimate, MonteCarloBins, compare_fosm_mc, failure_reasons, first_passage_probability, mc_bin_reliability, wilson_interval
from .fosm import PAPER_ALLOWABLE, FosmResult, allowable_statistics, fosm, normal_cdf, normal_ppf, reliability_index
from .model import LimitState, Model
from .study import Evaluation, MonteCarloEstimate, Output, Study
from .uq import FormResult, SamplingResult, SobolResult, ToleranceResult

__all__ = [
    "PAPER_ALLOWABLE",
    "Distribution",
    "Estimate",
    "Evaluation",
    "Fixed",
    "FormResult",
    "FosmResult",
    "LimitState",
    "LogNormal",
    "Model",
    "MonteCarloBins",
    "MonteCarloEstimate",
    "Normal",
    "Output",
    "SamplingResult",
    "Scipy",
    "Shifted",
    "SobolResult",
    "Study",
    "ToleranceResult",
    "TruncatedNormal",
    "Uniform",
    "allowable_statistics",
    "as_distribution",
    "compare_fosm_mc",
    "failure_reasons",
    "first_passage_probability",
    "fosm",
    "mc_bin_reliability",
    "normal_cdf",
    "normal_ppf",
    "reliability_index",
    "sample_inputs",
    "wilson_interval",
]
