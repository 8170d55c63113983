"""Report figures, one room a subject: :mod:`.paper` (error histories, journal orbits),
:mod:`.reliability` (reliability curves, FOSM against Monte Carlo), :mod:`.wear` (wear depth),
:mod:`.pressure` (a bearing's film pressure),
:mod:`.benchmark` (work–precision), :mod:`.dynamics` (Poincaré sections, phase portraits,
bifurcation diagrams, Lyapunov exponents, spectra), all in the look of :mod:`.theme` (palette, rcParams,
series styles, :func:`save`).

Every function takes plain numpy arrays and labels (no simulation objects), returns a
:class:`matplotlib.figure.Figure` and leaves no pyplot state behind: figures are built with
``Figure(...)`` directly, so nothing is registered with pyplot and nothing needs closing unless
you created it through pyplot yourself. Save with :func:`save` (PNG, 150 dpi).
"""

from .benchmark import plot_work_precision
from .dynamics import plot_bifurcation, plot_lyapunov, plot_phase_portrait, plot_poincare, plot_poincare_panels, plot_spectrum
from .paper import plot_error_histories, plot_journal_orbits
from .pressure import plot_film_pressure
from .reliability import plot_fosm_vs_mc, plot_reliability, plot_reliability_panels
from .theme import OKABE_ITO, QUANTITIES, RC, new_figure, save, series_style, style, suptitle
from .wear import plot_wear

__all__ = [
    "OKABE_ITO",
    "QUANTITIES",
    "RC",
    "new_figure",
    "plot_bifurcation",
    "plot_lyapunov",
    "plot_phase_portrait",
    "plot_poincare",
    "plot_poincare_panels",
    "plot_spectrum",
    "plot_error_histories",
    "plot_film_pressure",
    "plot_fosm_vs_mc",
    "plot_journal_orbits",
    "plot_reliability",
    "plot_reliability_panels",
    "plot_wear",
    "plot_work_precision",
    "save",
    "series_style",
    "style",
    "suptitle",
]
