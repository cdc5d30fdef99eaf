"""Spreading capacity of semicircles against t/R by the two methods (docs/supports.md).

The exact displaced arch (statics.supports.displacement_capacity) at t/R from 0.11 to 0.32, for
16 and 36 radial voussoirs (centreline radius R = 10 m, the right support spreading), beside the
contact engine's capacities stored by docs/scripts/supports_engine.py
(docs/figures/supports_engine.json).  Writes docs/figures/supports_capacity.png and prints the
exact values.

Usage: PYTHONPATH=src python docs/scripts/supports_capacity.py
"""

from __future__ import annotations

import json
import numpy as np
from _figures import FIGURES, new_axes, save_axes

from archrock.errors import ArchrockError
from archrock.geometry import nominal_arch
from archrock.statics.supports import displacement_capacity


def main():
    engine = json.loads((FIGURES / "supports_engine.json").read_text())["semicircles"]
    fig, ax = new_axes((6.4, 3.8))
    for n, colour in ((16, "tab:blue"), (36, "tab:red")):
        tr = np.round(np.arange(0.11, 0.3201, 0.01), 2)
        cap = []
        for t in tr:
            try:
                c = displacement_capacity(nominal_arch(radius=10.0, embrace_deg=180.0,
                                                       thickness=10.0 * t, voussoirs=n),
                                          "spread", "right").capacity / 10.0
            except ArchrockError:  # below the minimum thickness: no capacity
                c = np.nan
            cap.append(c)
            print(f"n={n} t/R={t:.2f} capacity/R={c:.4f}", flush=True)
        ax.plot(tr, cap, "-", color=colour, label=f"exact displaced arch, {n} voussoirs")
        pts = [(r["t_over_r"], r["capacity"] / 10.0) for r in engine
               if r.get("n") == n and r.get("movement") == "spread" and r.get("capacity")]
        if pts:
            x, y = zip(*pts)
            ax.plot(x, y, "o", color=colour, mfc="none", label=f"contact engine, {n} voussoirs")
    ax.set_xlabel("t / R (R: centreline radius)")
    ax.set_ylabel("spreading capacity / R")
    ax.set_title("Semicircle, right support spreading: capacity by two methods", fontsize=9)
    save_axes(fig, ax, "supports_capacity.png")


if __name__ == "__main__":
    main()
