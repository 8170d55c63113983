"""Cost against mechanism size: one right-hand side on pendulum chains of 8 to 1 024 links,
ideal and with two dry clearance joints (``benches/chain.rs``), and one RADAU5 step on chains of
20 to 320 links with a lubricated joint at every 4th (``benches/chain_steps.rs``).

Runs ``cargo bench --bench chain`` (about a minute; ``--no-run`` reuses the last results) and
``cargo bench --bench chain_steps`` (about a minute; ``--no-run``: the last ``docs/scaling_steps.csv``;
``--steps-binary <path>``: an already built ``chain_steps`` binary), and writes
``docs/scaling.csv``, ``docs/scaling_steps.csv`` and ``docs/scaling.png``: the time per
right-hand side and per RADAU5 step against the number of bodies, log-log, each with the line
that linear growth would follow. Usage: ``python benches/scaling.py [--no-run] [--steps-only] [--steps-binary PATH]``
(``--steps-only``: re-measure the RADAU5 steps only, the right-hand sides from ``docs/scaling.csv``).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import re
import subprocess
from pathlib import Path
from typing import List, Optional, Tuple

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
SIZES = [8, 16, 32, 64, 128, 256, 512, 1024]
GROUPS = {"chain_ideal": "ideal revolute joints", "chain_dry": "two dry clearance joints"}
STEP_SIZES = [20, 40, 80, 160, 320]


def criterion_dir() -> Path:
    target = os.environ.get("CARGO_TARGET_DIR")
    return Path(target) / "criterion" if target else ROOT / "target" / "criterion"


def read_estimates() -> dict[str, list[float]]:
    """Mean time per right-hand side [s] for each group and size."""
    out: dict[str, list[float]] = {}
    for group in GROUPS:
        times = []
        for n in SIZES:
            path = criterion_dir() / group / str(n) / "new" / "estimates.json"
            if not path.exists():
                raise SystemExit(f"{path} is missing: run `cargo bench --bench chain` first")
            times.append(json.loads(path.read_text())["mean"]["point_estimate"] * 1e-9)
        out[group] = times
    return out


def read_steps(binary: Optional[str]) -> List[Tuple[int, float, float]]:
    """(links, right-hand sides per step, CPU µs per RADAU5 step) from ``chain_steps``."""
    if binary:
        cmd = [binary, "radau", *map(str, STEP_SIZES)]
    else:
        cmd = ["cargo", "bench", "--bench", "chain_steps", "--", "radau", *map(str, STEP_SIZES)]
    text = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    rows = []
    for line in text.splitlines():
        m = re.match(r"\s*(\d+)\s+\d+\s+\d+\s+([\d.]+)\s+[\d.]+\s+([\d.]+)", line)
        if m:
            rows.append((int(m.group(1)), float(m.group(2)), float(m.group(3))))
    return rows


def plot(est: dict[str, list[float]], steps: List[Tuple[int, float, float]], path: Path) -> None:
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11.0, 4.4), constrained_layout=True)
    for (group, label), marker in zip(GROUPS.items(), ("o", "s")):
        ax.loglog(SIZES, [t * 1e6 for t in est[group]], marker=marker, label=label)
    ref = est["chain_ideal"][SIZES.index(32)] * 1e6
    ax.loglog(SIZES, [ref * n / 32 for n in SIZES], "k--", lw=1, label="linear growth from 32 bodies")
    ax.set_xlabel("bodies in the chain")
    ax.set_ylabel("one right-hand side [µs]")
    ax.set_xticks(SIZES, [str(n) for n in SIZES])
    ax.set_title("Cost per right-hand side grows linearly with size\n(sparse KKT solve, pendulum chains)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    n, us = [r[0] for r in steps], [r[2] for r in steps]
    bx.loglog(n, us, marker="o", color="C2", label="RADAU5, lifted sparse Newton matrices")
    bx.loglog(n, [us[0] * k / n[0] for k in n], "k--", lw=1, label=f"linear growth from {n[0]} links")
    bx.set_xlabel("links in the chain (a lubricated joint at every 4th)")
    bx.set_ylabel("one RADAU5 step, CPU [µs]")
    bx.set_xticks(n, [str(k) for k in n])
    bx.set_title("Cost per implicit step grows linearly with size\n(benches/chain_steps.rs, 20 ms of the chain's fall)")
    bx.grid(True, which="both", alpha=0.3)
    bx.legend()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-run", action="store_true", help="reuse the last criterion results and docs/scaling_steps.csv")
    ap.add_argument("--steps-binary", help="a built chain_steps binary to run instead of cargo bench")
    ap.add_argument("--steps-only", action="store_true", help="measure the RADAU5 steps only; the right-hand sides from docs/scaling.csv")
    args = ap.parse_args()
    if args.steps_only:
        with open(DOCS / "scaling.csv") as f:
            rows = list(csv.DictReader(f))
        est = {"chain_ideal": [float(r["rhs_ideal_us"]) * 1e-6 for r in rows], "chain_dry": [float(r["rhs_two_dry_us"]) * 1e-6 for r in rows]}
    else:
        if not args.no_run:
            subprocess.run(["cargo", "bench", "--bench", "chain"], cwd=ROOT, check=True)
        est = read_estimates()
    steps_csv = DOCS / "scaling_steps.csv"
    if args.no_run and steps_csv.exists():
        with open(steps_csv) as f:
            steps = [(int(r["links"]), float(r["rhs_per_step"]), float(r["radau_step_us"])) for r in csv.DictReader(f)]
    else:
        steps = read_steps(args.steps_binary)
        with open(steps_csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["links", "rhs_per_step", "radau_step_us"])
            w.writerows(steps)
    DOCS.mkdir(exist_ok=True)
    if not args.steps_only:
        with open(DOCS / "scaling.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["bodies", "constraint_rows_ideal", "rhs_ideal_us", "rhs_two_dry_us"])
            for k, n in enumerate(SIZES):
                w.writerow([n, 2 * n, f"{est['chain_ideal'][k] * 1e6:.3f}", f"{est['chain_dry'][k] * 1e6:.3f}"])
    plot(est, steps, DOCS / "scaling.png")
    t32, t1024 = est["chain_ideal"][SIZES.index(32)], est["chain_ideal"][-1]
    print(f"1024 bodies: {t1024 * 1e6:.1f} µs = {t1024 / (32 * t32):.2f} × the linear extrapolation from 32 bodies")
    (n0, _, s0), (n1, _, s1) = steps[0], steps[-1]
    print(f"RADAU5 step, {n1} links: {s1:.0f} µs = {s1 / s0:.1f} × the {n0}-link step ({n1 / n0:.0f} × the size)")


if __name__ == "__main__":
    main()
