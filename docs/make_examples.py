"""Draw every example scene at t = 0 into docs/examples/<scene>.png (the pictures of
docs/examples.md).

    MPLBACKEND=Agg python docs/make_examples.py
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt

import clearsim

ROOT = Path(__file__).resolve().parent.parent


def main() -> None:
    out = ROOT / "docs" / "examples"
    out.mkdir(exist_ok=True)
    for path in sorted((ROOT / "scenes").glob("*.toml")):
        m = clearsim.load_scene(path)
        fig, ax = plt.subplots(figsize=(5.0, 3.6), dpi=90)
        m.plot(0.0, ax=ax)
        ax.set_title(path.stem, fontsize=10)
        fig.savefig(out / f"{path.stem}.png", bbox_inches="tight")
        plt.close(fig)
        print(out / f"{path.stem}.png")


if __name__ == "__main__":
    main()
