"""What the documentation's figure scripts share: the folder they write to, a --samples option,
and the start and finish of one matplotlib figure (Agg, no display needed)."""

from __future__ import annotations

import argparse
from pathlib import Path

#: docs/figures/, where every figure and its JSON of numbers is written
FIGURES = Path(__file__).resolve().parents[1] / "figures"


def samples_arg(doc: str, default: int, argv=None) -> int:
    """The --samples N of a script whose docstring is ``doc`` (its first line: the help)."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--samples", type=int, default=default)
    return ap.parse_args(argv).samples


def new_axes(figsize: tuple[float, float]):
    """A figure and its axes, ``figsize`` in inches, drawn off-screen."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(figsize=figsize)


def save_axes(fig, ax, name: str, **grid) -> Path:
    """Finish the one-axes figure (a light grid, ``grid`` overriding its style; the legend) and
    write it to docs/figures/``name`` at 110 dpi; the path written."""
    ax.grid(**({"alpha": 0.3} | grid))
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = FIGURES / name
    fig.savefig(path, dpi=110)
    return path
