"""The figures and tables of docs/piers.md, parts 2 and 3 of issue 19: the reference semicircle
(R = 5 m, t = 0.8 m, 9 voussoirs) on piers: k against the piers' height (2 m wide), the minimum
pier width against the height, and the mechanism figure of the arch on piers with courses and a
battered pier (run from the repository root: ``PYTHONPATH=src python
docs/scripts/piers_figures.py``; about 30 s)."""

import time

import numpy as np

from archrock.geometry import nominal_arch, with_piers
from archrock.reports.plots import plot_k_against_pier_height, save_limit_figure
from archrock.statics.buttress import k_against_pier_height, minimum_pier_width
from archrock.statics.limit import limit_analysis

ARCH = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)

t0 = time.perf_counter()
table = k_against_pier_height(ARCH, 2.0, np.linspace(0.0, 3 * 9.2, 25))
plot_k_against_pier_height(table, "docs/figures/k_pier_height.png")
print("| H [m] | H / span | k | mechanism | hinge D |")
print("|---|---|---|---|---|")
for r in table.rows()[::2]:
    print(f"| {r['height']:.2f} | {r['height_over_span']:.3f} | {r['k_l']:.4f} | "
          f"{r['mechanism_l']} | {r['hinge_d_l']} |")
print(f"({time.perf_counter() - t0:.1f} s)")

print("\n| H [m] | min width [m] | iterations | H_thrust [kN/m] | V [kN/m] | governed by |")
print("|---|---|---|---|---|---|")
for h in (0.05, 1.0, 2.0, 4.0, 8.0, 16.0):
    t = time.perf_counter()
    m = minimum_pier_width(ARCH, h)
    print(f"| {h:g} | {m.width:.6f} | {m.iterations} | {m.springing_force[0] / 1e3:.3f} | "
          f"{m.springing_force[1] / 1e3:.3f} | {m.governed_by} | ({time.perf_counter() - t:.2f} s)")
for b in (0.05, 0.1, 0.2):
    m = minimum_pier_width(ARCH, 4.0, batter=b)
    print(f"batter {b}: min top width {m.width:.6f} m, base {m.width + b * 4.0:.6f} m")

ap = with_piers(ARCH, 4.0, 2.0, courses=3, batter=0.0, batter_right=0.0)
save_limit_figure(limit_analysis(ap), "docs/figures/piers_mechanism.png")
