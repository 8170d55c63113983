"""Finite-length bearing (film="finite") against Butenschön's tables (B/D = 1/8) and the long
and short closed forms across L/D.

    python benches/finite_bearing.py
"""

import csv
import math
import time
from pathlib import Path

from clearsim import _core

MU, R, C = 0.4, 0.01, 5e-4
DATA = Path(__file__).resolve().parents[1] / "tests" / "data"


def load(name):
    with open(DATA / name) as f:
        return [r for r in csv.reader(line for line in f if not line.startswith("#"))][1:]


def sommerfeld(film, l_over_d, eps, kind):
    length = 2 * R * l_over_d
    if kind == "rotation":
        f = _core.film_force(film, MU, R, C, length, eps, 0.0, 50.0)
        rate = 50.0
    else:
        f = _core.film_force(film, MU, R, C, length, abs(eps), math.copysign(2.0, eps), 0.0)
        rate = 2.0
    so = math.hypot(*f) * (C / R) ** 2 / (length * 2 * R * MU * rate)
    return so, math.degrees(math.atan2(abs(f[1]), -f[0]))


def main():
    t = time.perf_counter()
    sommerfeld("finite", 1 / 8, 0.5, "rotation")
    print(f"table for B/D = 1/8 built in {time.perf_counter() - t:.2f} s")
    t = time.perf_counter()
    sommerfeld("finite", 2.5, 0.5, "rotation")
    print(f"table for L/D = 2.5 built in {time.perf_counter() - t:.2f} s")
    worst = [0.0, 0.0, 0.0]
    print("\nButenschön B/D = 1/8, rotation: eps, So (table), So (finite), error, beta (table), beta (finite)")
    for _, eps, so_b, beta_b in load("butenschoen_rotation_BD1_8.csv"):
        so, beta = sommerfeld("finite", 1 / 8, float(eps), "rotation")
        err = so / float(so_b) - 1
        worst[0] = max(worst[0], abs(err))
        worst[1] = max(worst[1], abs(beta - float(beta_b)))
        print(f"  {float(eps):.2f}  {float(so_b):9.4f}  {so:9.4f}  {100 * err:+5.1f} %  {float(beta_b):6.2f}  {beta:6.2f}")
    print("Butenschön B/D = 1/8, squeeze: eps (signed), So (table), So (finite), error")
    for _, eps, so_b in load("butenschoen_squeeze_BD1_8.csv"):
        so, _ = sommerfeld("finite", 1 / 8, float(eps), "squeeze")
        err = so / float(so_b) - 1
        if float(eps) != -0.95:
            worst[2] = max(worst[2], abs(err))
        print(f"  {float(eps):+.2f}  {float(so_b):10.4f}  {so:10.4f}  {100 * err:+5.1f} %" + ("  (table glitch)" if float(eps) == -0.95 else ""))
    print(f"worst: rotation So {100 * worst[0]:.2f} %, attitude {worst[1]:.2f}°, squeeze So {100 * worst[2]:.2f} %")
    print("\nClosed forms against the finite bearing (Sommerfeld number and attitude), pure rotation | approaching squeeze")
    for ld in (0.25, 0.5, 1.0, 2.0, 2.5, 4.0, 8.0):
        for eps in (0.3, 0.5, 0.8):
            fin = sommerfeld("finite", ld, eps, "rotation")
            lo = sommerfeld("long", ld, eps, "rotation")
            sh = sommerfeld("short", ld, eps, "rotation")
            fs = sommerfeld("finite", ld, eps, "squeeze")
            ls = sommerfeld("long", ld, eps, "squeeze")
            ss = sommerfeld("short", ld, eps, "squeeze")
            print(f"  L/D {ld:4}  eps {eps}: long {100 * (lo[0] / fin[0] - 1):+6.0f} % {lo[1] - fin[1]:+4.0f}°   short {100 * (sh[0] / fin[0] - 1):+6.0f} % {sh[1] - fin[1]:+4.0f}°"
                  f"  | long {100 * (ls[0] / fs[0] - 1):+6.0f} %  short {100 * (ss[0] / fs[0] - 1):+6.0f} %")
    # Right-hand-side cost of one film evaluation (Python call overhead included, for comparison).
    for film in ("long", "short", "finite"):
        t = time.perf_counter()
        for k in range(20000):
            _core.film_force(film, MU, R, C, 0.05, 0.3 + 0.6 * k / 20000, 0.5, 40.0)
        print(f"film_force {film:6s}: {1e6 * (time.perf_counter() - t) / 20000:.2f} µs per call (from Python)")


if __name__ == "__main__":
    main()
