"""FORM on an impact-driven limit state against crude Monte Carlo (issue 31, item 1).

An offset slider-crank compressor: crank 25 mm, rod 90 mm, piston offset 5 mm, 1 500 rpm; the
crank pin is a lubricated clearance joint (c = 20 µm, L = 20 mm, R_j = 8 mm), the wrist pin a
dry one (c = 50 µm, R_j = 5 mm). Random: both clearances and the viscosity, normal with 5 % CoV.
Output: the piston's peak |x error| over the first turn; the dry wrist pin's
impacts make it noisy at small scales. Prints FORM (β, p_f, the measured noise σ_g, the step it
chose, runs, time) and crude Monte Carlo (p_f with its 95 % interval, runs, time), and whether
FORM's p_f lies in the Monte Carlo interval.

    python benches/compressor_form.py [limit_um] [n_mc]
"""

import math
import sys
import time
import warnings

import clearsim
from clearsim import reliability as rel

RPM = 1500.0
OMEGA = RPM * 2 * math.pi / 60


def compressor(c_crank: float, c_wrist: float, viscosity: float) -> clearsim.Mechanism:
    r, l, e = 0.025, 0.09, 0.005
    # Assembled pose at θ = 0: crank along x, piston at x = sqrt((r + l)² − e²)... solved by
    # the assembly from an approximate rod angle.
    phi = math.asin(e / l)
    xp = r + l * math.cos(phi)
    m = clearsim.Mechanism()
    m.add_body("crank", mass=0.4, inertia=2e-4, position=(r / 2, 0.0))
    m.add_body("rod", mass=0.25, inertia=2e-4, position=(r + 0.5 * l * math.cos(phi), 0.5 * e), angle=phi)
    m.add_body("piston", mass=0.3, inertia=1e-4, position=(xp, e))
    m.revolute("ground", (0.0, 0.0), "crank", (-r / 2, 0.0), name="main")
    m.clearance_joint("crank-pin", "rod", (-l / 2, 0.0), "crank", (r / 2, 0.0), journal_radius=8e-3, clearance=c_crank,
                      model=clearsim.Lubricated(viscosity=viscosity, length=0.02))
    m.clearance_joint("wrist-pin", "piston", (0.0, 0.0), "rod", (l / 2, 0.0), journal_radius=5e-3, clearance=c_wrist, model=clearsim.Dry())
    m.prismatic("ground", (0.0, e), "piston", (0.0, 0.0), axis=(1.0, 0.0), name="cylinder")
    m.driver("crank", omega=OMEGA, angle0=0.0, name="drive")
    return m


def main() -> None:
    args = sys.argv[1:]
    limit = float(args[0]) * 1e-6 if args else 75e-6
    n_mc = int(args[1]) if len(args) > 1 else 400
    study = rel.Study(
        compressor, {"c_crank": rel.Normal(20e-6, 1e-6), "c_wrist": rel.Normal(50e-6, 2.5e-6), "viscosity": rel.Normal(0.05, 0.0025)},
        output=rel.Output(body="piston", component="x"), limit=limit, omega=OMEGA, cycles=1.0, progress=False,
    )  # fmt: skip
    print(study)
    t = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            fr = study.form()
        except clearsim.ReliabilityError as err:
            print(f"FORM raised ReliabilityError: {err}")
            fr = None
    for w in caught:
        print(f"  warning: {w.message}")
    if fr is not None:
        print(f"FORM  beta = {fr.beta:.3f}  p_f = {fr.pf:.4g}  noise sigma_g = {fr.noise:.2g}  step = {fr.step:.3g}  "
              f"beta +- {fr.beta_noise:.2g}  runs = {fr.n_runs}  {time.perf_counter() - t:.1f} s")
    t = time.perf_counter()
    mc = study.monte_carlo(n_mc, seed=0)
    print(f"MC    p_f = {mc.pf:.4g}  95 % [{mc.interval[0]:.4g}, {mc.interval[1]:.4g}]  runs = {mc.n_runs}  failed = {len(mc.failures)}  {time.perf_counter() - t:.1f} s")
    if fr is not None:
        print(f"FORM in the MC interval: {mc.interval[0] <= fr.pf <= mc.interval[1]}")


if __name__ == "__main__":
    main()
