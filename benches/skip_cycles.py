"""How a study's peaks settle with ``skip_cycles`` (docs/reliability.md, "The start-up
transient"): the peak slider acceleration error [m/s²] over one turn of the shipped lubricated
slider-crank (x) and nine-bar (slider9 y) at clearances 0.3, 0.5 and 0.7 mm, and whether the study
warned that its peaks sit at the window's start. Usage: ``python benches/skip_cycles.py sc|nb 0,0.5,1,2``.
"""

from __future__ import annotations

import math
import sys
import time
import warnings

import numpy as np

from clearsim import models
from clearsim.reliability import Normal, Output, Study


def main() -> None:
    kind = sys.argv[1] if len(sys.argv) > 1 else "sc"
    skips = [float(x) for x in (sys.argv[2] if len(sys.argv) > 2 else "0,0.25,0.5,1,2").split(",")]

    def build(clearance: float) -> object:
        return models.slider_crank("lubricated", clearance=clearance) if kind == "sc" else models.nine_bar("lubricated", clearance=clearance, omega=-5 * math.pi)

    body, component = ("slider", "x") if kind == "sc" else ("slider9", "y")
    for skip in skips:
        study = Study(build, {"clearance": Normal(0.5e-3, 0.05e-3)}, Output(body=body, component=component, quantity="acceleration"), 1e9, skip_cycles=skip, progress=False)
        start = time.perf_counter()
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            ev, _ = study.run_samples({"clearance": np.array([0.3e-3, 0.5e-3, 0.7e-3])})
        print(f"{kind} skip_cycles {skip:g}: peaks {' / '.join(f'{p:.1f}' for p in ev.peaks)} m/s², warned: {bool(seen)} ({time.perf_counter() - start:.1f} s)", flush=True)


if __name__ == "__main__":
    main()
