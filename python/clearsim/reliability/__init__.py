"""Dynamic-accuracy reliability of a mechanism output (docs/physics.md §6, paper section 4).

The study of one output with random inputs::

    from clearsim import reliability as rel
    study = rel.Study(build, inputs={"clearance": rel.Normal(0.5e-3, 0.02e-3), "viscosity": 0.4},
                      output=rel.Output(body="slider9", component="y", quantity="displacement"),
                      limit=1e-3, omega=-5 * np.pi, cycles=1.0)
    study.monte_carlo(n)   study.form()   study.importance_sampling(cov=0.1)   study.subset()
    study.sobol(n)         study.tolerance("clearance", reliability=0.999)      study.fosm()
    study.ak_mcs(max_runs=150)   study.ak_is(max_runs=150)      (few runs: Kriging surrogates)
    res = study.life(cycles=[0, 1e5, 2e5], n=200); res.life_at(0.999)  (Archard wear fed back)

Several failure modes (a series system)::

    study = rel.Study(build, inputs, output=[rel.Output(body="slider9", component="y"),
                                             rel.Output(joint="B", quantity="film_thickness")],
                      limit=[1e-3, rel.Limit.below(2e-6)], omega=-5 * np.pi)

Rooms, each importing only those above it: :mod:`.distributions` (random inputs on
``scipy.stats``), :mod:`.fosm` (the paper's first-order second-moment method, Eqs. P27–P32, and
FOSM from monitor bins), :mod:`.estimates` (Monte Carlo statistics), :mod:`.outputs`
(:class:`Output`, :class:`Limit`), :mod:`.runs` (batches of runs and their monitors),
:mod:`.bridge` (OpenTURNS' view of a model), :mod:`.form` (FORM on noisy limit states, series
systems), :mod:`.sampling` (importance sampling, subset simulation), :mod:`.sobol` (Sobol
indices by sampling or polynomial chaos), :mod:`.tolerance` (tolerance design), :mod:`.akmcs` (AK-MCS,
AK-IS), :mod:`.uq` (all of these in one import), :mod:`.model` (what the methods need of a model and every method on it;
:class:`LimitState` for any function), :mod:`.study` (:class:`Study`, the simulation model and
the one Monte Carlo sample loop), :mod:`.binned` (``clearsim.monte_carlo``: per-bin Monte
Carlo of one body coordinate's errors on that loop), :mod:`.life` and :mod:`.life_plot` (reliability over life by
cycle jumping), :mod:`.report` (``clearsim reliability``; the ``[study]`` table it reads is
:mod:`clearsim.scene.study`).
Methods on OpenTURNS need ``pip install clearsim[uq]``; docs/reliability.md says which to use.
"""

from .distributions import Distribution, Fixed, LogNormal, Normal, Scipy, Shifted, TruncatedNormal, Uniform, as_distribution, sample_inputs
from .estimates import Estimate, MonteCarloBins, compare_fosm_mc, failure_reasons, first_passage_probability, mc_bin_reliability, wilson_interval
from .fosm import PAPER_ALLOWABLE, FosmResult, allowable_statistics, fosm, normal_cdf, normal_ppf, reliability_index
from .form import FormResult, SystemFormResult
from .life import LifeModel, LifeResult
from .model import LimitState, ReliabilityModel
from .outputs import Limit, Output
from .sampling import SamplingResult
from .sobol import SobolResult
from .study import Evaluation, ModeEstimate, MonteCarloEstimate, Study
from .tolerance import ToleranceResult
from . import uq

__all__ = [
    "PAPER_ALLOWABLE",
    "Distribution",
    "Estimate",
    "Evaluation",
    "Fixed",
    "FormResult",
    "FosmResult",
    "LifeModel",
    "LifeResult",
    "Limit",
    "LimitState",
    "LogNormal",
    "ModeEstimate",
    "MonteCarloBins",
    "MonteCarloEstimate",
    "Normal",
    "Output",
    "ReliabilityModel",
    "SamplingResult",
    "Scipy",
    "Shifted",
    "SobolResult",
    "Study",
    "SystemFormResult",
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
