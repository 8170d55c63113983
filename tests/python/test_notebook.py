"""clearsim in a Jupyter notebook, run headless (nbclient, a fresh ipykernel) from
tests/data/notebook_display.ipynb: runs shorter than the progress bar's delay create no widget
(a tqdm notebook bar is eleven widget models: 30 short runs once left 330), a long run's bar
closes every model it opened, without ipywidgets the bar falls back to text without a warning,
and clearsim's figures (``m.plot()``, ``res.plot_mechanism(t)``, ``plots.plot_journal_orbits``)
and a Mechanism show as PNG pictures although matplotlib.pyplot is never imported."""

from __future__ import annotations

from pathlib import Path
from typing import Any, List, Tuple

import nbformat
from nbclient import NotebookClient

NOTEBOOK = Path(__file__).resolve().parents[1] / "data" / "notebook_display.ipynb"
#: Widget models of one tqdm notebook bar: an HBox, a progress bar and two HTML labels, with
#: their layout and style models.
MODELS_PER_BAR = 11


def _run(first_cell: str = "") -> Tuple[Any, int]:
    """The notebook executed in a fresh kernel (``first_cell`` run before it) and the number of
    widget models it stored."""
    nb = nbformat.read(NOTEBOOK, as_version=4)
    if first_cell:
        nb.cells.insert(1, nbformat.v4.new_code_cell(first_cell))
    NotebookClient(nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(NOTEBOOK.parent)}}).execute()
    state = nb.metadata.get("widgets", {}).get("application/vnd.jupyter.widget-state+json", {}).get("state", {})
    return nb, len(state)


def _outputs(nb: Any, source_start: str) -> List[Any]:
    """The outputs of the code cell whose source is ``source_start`` or starts with it."""
    cells = [c for c in nb.cells if c.cell_type == "code"]
    cell = next((c for c in cells if c.source == source_start), None) or next(c for c in cells if c.source.startswith(source_start))
    return list(cell.outputs)


def _text(nb: Any) -> str:
    return "\n".join(str(o.get("text", "")) + str(o.get("data", {}).get("text/plain", "")) for c in nb.cells if c.cell_type == "code" for o in c.outputs)


def test_a_notebook_shows_figures_as_pictures_and_keeps_no_idle_progress_widgets() -> None:
    nb, models = _run()
    for start in ("m.plot()", "r.plot_mechanism", "e = r.eccentricity", "m"):
        results = [o for o in _outputs(nb, start) if o.output_type == "execute_result"]
        assert results and "image/png" in results[0].data, (start, [list(o.get("data", {})) for o in results])
        assert results[0].data["image/png"], start
    text = _text(nb)
    assert "pyplot imported: False" in text  # a fresh kernel: pyplot's display of figures never registered
    # 30 short runs and one long one: only the long run's bar, and that bar closed all it opened.
    assert 0 < models <= MODELS_PER_BAR, models
    assert "live widgets: 0" in text, text[-500:]
    assert "Warning" not in text


def test_without_ipywidgets_the_bar_is_text_and_says_nothing_else() -> None:
    nb, models = _run("import sys\nsys.modules['ipywidgets'] = None  # as if ipywidgets were not installed")
    assert models == 0
    long_run = "".join(str(o.get("text", "")) for o in _outputs(nb, "progress.DELAY") if o.output_type == "stream")
    assert "simulating" in long_run, long_run  # the text bar of the long run
    text = _text(nb)
    assert "TqdmWarning" not in text and "IProgress" not in text and "Warning" not in text, text[-800:]
