"""The roller-chain drive example (``scenes/roller_chain.toml``): writes the scene and measures
what a step of it costs.

``python benches/roller_chain.py --write`` regenerates the scene file from the dimensions below
(60 links and pins, 62 bodies: too many to keep consistent by hand). Without arguments it runs the
scene with its own settings, three times, and prints the steps, the right-hand sides and Newton
matrices per step and the CPU time per step (the best run), with the same for the RADAU5 run
through the dense Newton matrices of ``main`` when ``--compare <python>`` names another
environment's interpreter.

The drive: an ANSI 40 (ISO 08A) roller chain, pitch 12.7 mm, 60 links, on two 20-tooth sprockets
(pitch radius 40.6 mm) 254 mm apart, so each span is 20 pitches and each sprocket carries 10
links. Every pin is a lubricated clearance joint, as a chain engineer would have it: oil in a
25 µm radial clearance between the 3.96 mm pin and its bushing, 7.85 mm long (the inner width;
L/D ≈ 2, the long-bearing film), 0.04 Pa s (an SAE 30 oil warm). The driver sprocket is started
from rest with a jerk-limited law θ = 1e6 t³ rad (75 rad/s after 5 ms) against a load torque of
5 N m on the driven one; the tight span is the upper one.

The sprockets have no teeth in this model: the rollers on them are seated, every other one, by
an ideal revolute joint to the sprocket at its tooth gap (seating each would close a loop of
two revolutes on one link, which the ideal counterpart and the assembly reject as redundant);
the pins between them hold the rest. Engagement is therefore fixed: the model holds while the
sprockets turn by less than one tooth (18°), which the 5 ms run (7°) respects. What it shows is
the start-up: the load taken up through 60 lubricated pin clearances, the tight span's pins
pulled to their walls, the slack span's squeezing films.
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "scenes" / "roller_chain.toml"

PITCH = 12.7e-3  # m
TEETH = 20
SPAN = 20  # pitches per straight span
LINK_MASS = 7.8e-3  # kg (0.61 kg/m)
LINK_INERTIA = 2.0e-7  # kg m², about the centroid
SPROCKET_MASS = 0.35  # kg (steel disc, 45 mm radius, 7 mm thick)
SPROCKET_INERTIA = 3.5e-4  # kg m²
PIN_RADIUS = 1.98e-3  # m
CLEARANCE = 25e-6  # m, radial
BUSH_LENGTH = 7.85e-3  # m
VISCOSITY = 0.04  # Pa s
JERK_LAW = 1.0e6  # θ = JERK_LAW t³ [rad]
LOAD = -5.0  # N m on the driven sprocket (counter-clockwise positive)


def pins() -> list[tuple[float, float]]:
    """The pin centres, in chain order: the upper span from the driver's top to the driven one's,
    round the driven sprocket, the lower span back, round the driver."""
    r = PITCH / (2 * math.sin(math.pi / TEETH))
    c = SPAN * PITCH
    step = 2 * math.pi / TEETH
    half = TEETH // 2
    out = [(k * PITCH, r) for k in range(SPAN)]
    out += [(c + r * math.cos(math.pi / 2 - k * step), r * math.sin(math.pi / 2 - k * step)) for k in range(half)]
    out += [(c - k * PITCH, -r) for k in range(SPAN)]
    out += [(r * math.cos(-math.pi / 2 - k * step), r * math.sin(-math.pi / 2 - k * step)) for k in range(half)]
    return out


def seats() -> list[tuple[int, str]]:
    """The pins seated on a sprocket (every other one round each wrap, its tangent pins included)."""
    half = TEETH // 2
    driven = [(SPAN + k, "sprocket-driven") for k in range(0, half + 1, 2)]
    driver = [((2 * SPAN + half + k) % (2 * SPAN + TEETH), "sprocket-driver") for k in range(0, half + 1, 2)]
    return driven + driver


def f(x: float) -> str:
    return repr(round(x, 12))


def scene_text() -> str:
    p = pins()
    n = len(p)
    centre = {"sprocket-driver": (0.0, 0.0), "sprocket-driven": (SPAN * PITCH, 0.0)}
    lines = [
        "# A roller-chain drive: ANSI 40 chain (pitch 12.7 mm), 60 links on two 20-tooth sprockets 254 mm",
        "# apart, a lubricated clearance at every pin (25 µm, 0.04 Pa s), the driver started from rest",
        "# (θ = 1e6 t³ rad: 75 rad/s at 5 ms) against 5 N m on the driven sprocket. The rollers on the",
        "# sprockets sit every other one in a tooth gap (an ideal revolute), so engagement is fixed: valid",
        "# while the sprockets turn less than a tooth (18°; 7° here). Written by",
        "# `python benches/roller_chain.py --write`, which says more; docs/examples.md. SI units.",
        "",
        "[mechanism]",
        'name = "roller-chain drive, 60 lubricated pins"',
        "",
    ]
    for name, (x, y) in centre.items():
        lines += ["[[body]]", f'name = "{name}"', f"mass = {SPROCKET_MASS}", f"inertia = {SPROCKET_INERTIA}", f"position = [{f(x)}, {f(y)}]", ""]
    for k in range(n):
        a, b = p[k], p[(k + 1) % n]
        lines += ["[[body]]", f'name = "link{k:02d}"', f"mass = {LINK_MASS}", f"inertia = {LINK_INERTIA}", f"ends = [[{f(a[0])}, {f(a[1])}], [{f(b[0])}, {f(b[1])}]]", ""]
    for name, (x, y) in centre.items():
        lines += ["[[joint]]", 'type = "revolute"', f'name = "{name}-shaft"', f'bodies = ["ground", "{name}"]', f"points = [[{f(x)}, {f(y)}], [0.0, 0.0]]", ""]
    for k, sprocket in seats():
        cx, cy = centre[sprocket]
        lines += [
            "[[joint]]",
            'type = "revolute"',
            f'name = "seat{k:02d}"                   # roller {k} in its tooth gap',
            f'bodies = ["{sprocket}", "link{k:02d}"]',
            f"points = [[{f(p[k][0] - cx)}, {f(p[k][1] - cy)}], [{f(-PITCH / 2)}, 0.0]]",
            "",
        ]
    lines += ["[[driver]]", 'name = "drive"', 'body = "sprocket-driver"', f"polynomial = [0.0, 0.0, 0.0, {JERK_LAW}]   # θ = 1e6 t³ [rad]", ""]
    lines += ["[[force]]", 'type = "torque"', 'name = "load"', 'body = "sprocket-driven"', f"value = {LOAD}                        # N m, against the drive", ""]
    for k in range(n):
        lines += [
            "[[clearance_joint]]",
            f'name = "pin{k:02d}"',
            f'bearing_body = "link{(k - 1) % n:02d}"           # the bushing',
            f"bearing_point = [{f(PITCH / 2)}, 0.0]",
            f'journal_body = "link{k:02d}"           # the pin',
            f"journal_point = [{f(-PITCH / 2)}, 0.0]",
            f"journal_radius = {PIN_RADIUS}",
            f"clearance = {CLEARANCE}",
            'model = "lubricated"',
            "[clearance_joint.lubricated]",
            f"viscosity = {VISCOSITY}",
            f"length = {BUSH_LENGTH}",
            "",
        ]
    lines += [
        "[simulation]",
        "t_end = 0.005",
        'integrator = "auto"                   # radau: the pins are lubricated',
        "rtol = 1e-6",
        "atol = 1e-9",
        "dt_out = 1e-5",
        "",
        "[outputs]",
        'bodies = ["sprocket-driven"]',
        'quantities = ["position", "velocity"]',
        'components = ["theta"]',
        'joints = ["pin00", "pin10", "pin19", "pin40"]   # tight span (driver end, middle, driven end), slack span',
        'joint_quantities = ["eccentricity", "force"]',
        "ideal = false                         # its spans are free chains of ideal pins: nothing to compare",
        "",
    ]
    return "\n".join(lines)


def measure(runs: int) -> None:
    from clearsim.scene import load_scene_file

    scene = load_scene_file(SCENE)
    best, stats = math.inf, {}
    for _ in range(runs):
        t0 = time.thread_time()
        res = scene.mechanism.simulate(scene.simulation.t_end, progress=False, **scene.simulation.kwargs())
        best = min(best, time.thread_time() - t0)
        stats = res.stats
    steps = stats["steps"] + stats["rejected_steps"]
    print(
        f"roller chain ({stats.get('integrator', '?')}): {stats['steps']} steps, {stats['rejected_steps']} rejected, "
        f"{stats['rhs_evaluations'] / steps:.1f} right-hand sides and {stats['jacobians'] / steps:.2f} Newton matrices per step, "
        f"{best / steps * 1e6:.0f} µs CPU per step, {best:.2f} s per run (best of {runs})"
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="regenerate scenes/roller_chain.toml")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--compare", help="another environment's python (e.g. main's) to run the same measurement")
    ap.add_argument("--json", help="write the scene's mechanism description here, for `cargo bench --bench chain_steps -- radau <file>`")
    args = ap.parse_args()
    if args.write:
        SCENE.write_text(scene_text())
        print(f"wrote {SCENE}")
        return
    if args.json:
        import json

        import clearsim

        Path(args.json).write_text(json.dumps(clearsim.load_scene(SCENE).description()))
        print(f"wrote {args.json}")
        return
    measure(args.runs)
    if args.compare:
        subprocess.run([args.compare, __file__, "--runs", str(args.runs)], check=True)


if __name__ == "__main__":
    sys.exit(main())
