"""Monte Carlo throughput and memory of reliability.Study on the nine-bar.

    python benches/study_throughput.py            # samples/s per core, dry and lubricated, 1 cycle
    python benches/study_throughput.py memory N   # max RSS after N dry samples of 0.05 cycle
    python benches/study_throughput.py tolerance  # dry peaks at rtol 1e-6 against 1e-7, 128 samples
    python benches/study_throughput.py tolerance lubricated  # the same for the lubricated nine-bar, rtol 1e-4 … 1e-7
"""

import math
import resource
import sys
import time

import clearsim
from clearsim import reliability as rel


def study(kind, cycles, **tolerances):
    def build(cA, cB):
        return clearsim.models.nine_bar(kind, {"A": cA, "B": cB})

    return rel.Study(
        build, inputs={"cA": rel.Normal(0.5e-3, 0.02e-3), "cB": rel.Normal(0.5e-3, 0.02e-3)},
        output=rel.Output(body="slider9", component="y", quantity="acceleration"), limit=1000.0,
        omega=-5 * math.pi, cycles=cycles, progress=False, **tolerances,
    )  # fmt: skip


def throughput():
    for kind in ("dry", "lubricated"):
        st = study(kind, 1.0)
        st.evaluate({"cA": [5e-4], "cB": [5e-4]})  # the ideal reference, once
        t = time.perf_counter()
        build = [st.build(cA=5e-4, cB=5e-4).description() for _ in range(128)]
        t_build = time.perf_counter() - t
        t = time.perf_counter()
        mc = st.monte_carlo(128, seed=1)
        dt = time.perf_counter() - t
        print(f"{kind}: {128 / dt:.1f} samples/s on 2 cores ({128 / dt / 2:.1f} per core); building the 128 descriptions in Python: "
              f"{t_build:.2f} s of {dt:.2f} s; failures {len(mc.failures)}")
        del build


def memory(n):
    st = study("dry", 0.05)
    t = time.perf_counter()
    mc = st.monte_carlo(n, seed=0)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"{n} samples in {time.perf_counter() - t:.1f} s; max RSS {rss:.0f} MB; p_f {mc.pf:.3f}")


def tolerance(n=128, kind="dry"):
    """One dry sample's peak is sensitive to the tolerance (impact sequences); the distribution
    of the peaks is not. A lubricated sample's peak hardly moves with the tolerance."""
    import numpy as np

    peaks, times = {}, {}
    for rtol in (1e-7, 1e-6, 1e-5) if kind == "dry" else (1e-7, 1e-6, 1e-5, 1e-4):
        st = study(kind, 1.0, rtol=rtol, atol=rtol * 1e-3)
        t = time.perf_counter()
        peaks[rtol] = st.monte_carlo(n, seed=5).peaks
        times[rtol] = time.perf_counter() - t
    for rtol in list(peaks)[1:]:
        d = np.abs(peaks[rtol] - peaks[1e-7]) / peaks[1e-7]
        print(f"one sample's peak, rtol {rtol:g} against 1e-7: median {np.median(d):.2%}, 90 % {np.quantile(d, 0.9):.2%}, max {d.max():.2%}")
    # Dry: the limits of docs/physics.md's study; lubricated: the tight run's 50 and 90 % quantiles.
    limits = (1500.0, 2000.0, 2500.0) if kind == "dry" else tuple(np.quantile(peaks[1e-7], [0.5, 0.9]))
    for rtol, p in peaks.items():
        q = np.quantile(p, [0.1, 0.5, 0.9])
        ex = [float(np.mean(p > a)) for a in limits]
        print(f"rtol {rtol:g}: quantiles 10/50/90 % {q.round(2)} m/s²; exceedance of {np.round(limits, 2)} m/s²: {ex}; {times[rtol]:.1f} s")


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "tolerance":
        tolerance(kind=sys.argv[2] if len(sys.argv) > 2 else "dry")
    elif len(sys.argv) > 2 and sys.argv[1] == "memory":
        memory(int(sys.argv[2]))
    else:
        throughput()
