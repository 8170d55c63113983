"""Every sampling method on the dry-pin compressor of benches/compressor_form.py (issue 31's
"dry-pin case"): importance sampling around FORM's design point, subset simulation and AK-MCS,
each with its p_f, interval, model runs and wall time. Crude Monte Carlo and FORM:
``python benches/compressor_form.py 63``.

    python benches/compressor_methods.py [limit_um]        (about half a minute on 2 cores)
"""

import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import compressor_form as cf  # noqa: E402

from clearsim import reliability as rel  # noqa: E402


def main() -> None:
    limit = float(sys.argv[1]) * 1e-6 if len(sys.argv) > 1 else 63e-6
    study = rel.Study(
        cf.compressor, {"c_crank": rel.Normal(20e-6, 1e-6), "c_wrist": rel.Normal(50e-6, 2.5e-6), "viscosity": rel.Normal(0.05, 0.0025)},
        output=rel.Output(body="piston", component="x"), limit=limit, omega=cf.OMEGA, cycles=1.0, progress=False,
    )  # fmt: skip
    print(study)
    warnings.simplefilter("ignore")
    methods = [
        ("IS", lambda: study.importance_sampling(cov=0.1)),
        ("subset", lambda: study.subset(n_per_level=200)),
        ("AK-MCS", lambda: study.ak_mcs(max_runs=150)),
    ]
    for name, run in methods:
        t = time.perf_counter()
        r = run()
        lo, hi = r.interval
        print(f"{name:7s} p_f = {r.pf:.4g}  95 % [{lo:.4g}, {hi:.4g}]  runs = {r.n_runs}  {time.perf_counter() - t:.1f} s")


if __name__ == "__main__":
    main()
