"""Cost of one right-hand side against mechanism size: pendulum chains of 8 to 1 024 links,
ideal and with two dry clearance joints (``benches/chain.rs``).

Runs ``cargo bench --bench chain`` (about a minute; ``--no-run`` reuses the last results),
reads criterion's estimates, and writes ``docs/scaling.csv`` and ``docs/scaling.png``: the
time per right-hand side against the number of bodies, log-log, with the line through the
32-body point that linear growth would follow. Usage: ``python benches/scaling.py [--no-run]``.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
SIZES = [8, 16, 32, 64, 128, 256, 512, 1024]
GROUPS = {"chain_ideal": "ideal revolute joints", "chain_dry": "two dry clearance joints"}


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


def plot(est: dict[str, list[float]], path: Path) -> None:
    fig, ax = plt.subplots(figsize=(6.4, 4.4), constrained_layout=True)
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
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-run", action="store_true", help="reuse the last criterion results")
    args = ap.parse_args()
    if not args.no_run:
        subprocess.run(["cargo", "bench", "--bench", "chain"], cwd=ROOT, check=True)
    est = read_estimates()
    DOCS.mkdir(exist_ok=True)
    with open(DOCS / "scaling.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["bodies", "constraint_rows_ideal", "rhs_ideal_us", "rhs_two_dry_us"])
        for k, n in enumerate(SIZES):
            w.writerow([n, 2 * n, f"{est['chain_ideal'][k] * 1e6:.3f}", f"{est['chain_dry'][k] * 1e6:.3f}"])
    plot(est, DOCS / "scaling.png")
    t32, t1024 = est["chain_ideal"][SIZES.index(32)], est["chain_ideal"][-1]
    print(f"1024 bodies: {t1024 * 1e6:.1f} µs = {t1024 / (32 * t32):.2f} × the linear extrapolation from 32 bodies")


if __name__ == "__main__":
    main()
