"""Crossings into the core, description builds and copies, and assemblies per request.

    python benches/crossings.py

One ``Mechanism.simulate`` (on a compiled mechanism, and on a fresh one with its compile), one
``simulate_with_ideal`` and one Study sample (dry slider-crank, random clearance, errors against
each sample's own ideal twin; one more sample, and per sample of a batch of 32): the calls into
``clearsim._core`` (each ``_core`` function and each compiled model's method counted by wrapping
them), the builds of a mechanism's plain description (``Mechanism._description``) and its deep
copies, and the poses the core assembled (``_core.assembly_count``). docs/performance.md, "One
request, one crossing", gives the figures before and after.
"""

from __future__ import annotations

import copy
import math
from typing import Any, Callable, Dict

import numpy as np

from clearsim import _core, mechanism, models
from clearsim.reliability import Normal, Output, Study

calls: Dict[str, int] = {}


def count(name: str) -> None:
    calls[name] = calls.get(name, 0) + 1


class Counted:
    """A compiled model whose method calls are counted."""

    def __init__(self, inner: Any) -> None:
        self._inner = inner

    def __getattr__(self, name: str) -> Any:
        attr = getattr(self._inner, name)
        if not callable(attr):
            return attr

        def crossing(*args: Any, **kwargs: Any) -> Any:
            count(f"CompiledModel.{name}")
            return attr(*args, **kwargs)

        return crossing


def wrap() -> None:
    for name in ("compile", "idealize", "run_batch", "check_element", "check_settings", "resolve", "findings"):
        real = getattr(_core, name, None)
        if real is None:
            continue

        def counted(*args: Any, _real: Any = real, _name: str = name, **kwargs: Any) -> Any:
            count(f"_core.{_name}")
            out = _real(*args, **kwargs)
            return Counted(out) if _name == "compile" else out

        setattr(_core, name, counted)
    build = mechanism.Mechanism._description

    def built(self: Any) -> Any:
        if self._plain is None:
            count("description built")
        return build(self)

    mechanism.Mechanism._description = built  # type: ignore[method-assign]
    deep = copy.deepcopy

    def copied(x: Any, *args: Any, **kwargs: Any) -> Any:
        if isinstance(x, dict) and "bodies" in x:
            count("description copied")
        return deep(x, *args, **kwargs)

    mechanism.copy.deepcopy = copied  # type: ignore[attr-defined]


def measure(label: str, fn: Callable[[], Any], per: int = 1) -> None:
    calls.clear()
    a0 = _core.assembly_count()
    fn()
    assembled = _core.assembly_count() - a0
    crossings = {k: v for k, v in calls.items() if k.startswith(("_core", "CompiledModel"))}
    print(f"{label}: crossings {sum(crossings.values()) / per:g} {crossings}; description built "
          f"{calls.get('description built', 0) / per:g}, copied {calls.get('description copied', 0) / per:g}; "
          f"assemblies {assembled / per:g}")  # fmt: skip


def main() -> None:
    wrap()
    m = models.slider_crank("dry", clearance=0.5e-3)
    m.compile()
    measure("simulate (compiled mechanism)", lambda: m.simulate(0.002, dt_out=1e-4, progress=False))
    fresh = models.slider_crank("dry", clearance=0.5e-3)
    measure("simulate (fresh mechanism, compile included)", lambda: fresh.simulate(0.002, dt_out=1e-4, progress=False))
    pair = models.slider_crank("dry", clearance=0.5e-3)
    measure("simulate_with_ideal (fresh)", lambda: pair.simulate_with_ideal(0.002, dt_out=1e-4, progress=False))
    omega = 5000 * 2 * math.pi / 60
    study = Study(lambda c: models.slider_crank("dry", clearance=c), {"c": Normal(0.5e-3, 0.01e-3)},
                  Output(body="slider", component="x", quantity="displacement"), 1e-3, omega=omega, cycles=0.25, progress=False)  # fmt: skip
    study.run_samples({"c": np.array([0.5e-3])})  # the first sample's pose check
    measure("Study sample (one more)", lambda: study.run_samples({"c": np.array([0.51e-3])}))
    measure("Study sample (per sample of 32)", lambda: study.run_samples({"c": np.linspace(0.49e-3, 0.51e-3, 32)}), per=32)


if __name__ == "__main__":
    main()
