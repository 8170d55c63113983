"""Monte Carlo throughput and memory of reliability.Study on the nine-bar.

    python benches/study_throughput.py            # samples/s per core, dry and lubricated, 1 cycle
    python benches/study_throughput.py memory N   # max RSS after N dry samples of 0.05 cycle
"""

import math
import resource
import sys
import time

import clearsim
from clearsim import reliability as rel


def study(kind, cycles):
    def build(cA, cB):
        return clearsim.models.nine_bar(kind, {"A": cA, "B": cB})

    return rel.Study(
        build, inputs={"cA": rel.Normal(0.5e-3, 0.02e-3), "cB": rel.Normal(0.5e-3, 0.02e-3)},
        output=rel.Output(body="slider9", component="y", quantity="acceleration"), limit=1000.0,
        omega=-5 * math.pi, cycles=cycles, progress=False,
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


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "memory":
        memory(int(sys.argv[2]))
    else:
        throughput()
