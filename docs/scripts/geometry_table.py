"""The per-family table and figure of docs/geometry.md: limit analysis, minimum thickness and the
momentum c_v of each arch family at one span, rise and thickness (run from the repository root:
``python docs/scripts/geometry_table.py``; about half a minute)."""

import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archrock.geometry.families import family_arch  # noqa: E402
from archrock.statics.limit import limit_analysis, minimum_thickness  # noqa: E402
from archrock.reports.plots import plot_limit  # noqa: E402
from archrock.dynamics.response import prepare  # noqa: E402

S, T, N = 10.0, 1.0, 12
CASES = [("circular", 2.5, "circular (segmental)"), ("circular", 5.0, "circular (semicircle)"),
         ("pointed", 7.0, "pointed"), ("elliptical", 4.0, "elliptical"),
         ("three-centred", 3.5, "three-centred"), ("parabolic", 5.0, "parabolic"),
         ("catenary", 5.0, "catenary")]

rows = []
fig, axes = plt.subplots(4, 2, figsize=(11, 13))
for ax, (shape, rise, label) in zip(axes.flat, CASES):
    t0 = time.perf_counter()
    arch = family_arch(shape, S, rise, T, N)
    res = limit_analysis(arch)
    mt = minimum_thickness(arch)
    cv = prepare(arch, "momentum", limit=res).impact.l_to_r
    rows.append(f"| {label} (F = {rise:g} m) | {res.k_l:.4f} / {res.k_r:.4f} | "
                f"{res.mechanism_l.label} | {mt.factor * T:.4f} m ({mt.factor:.4f} t) | "
                f"{cv:.4f} | {res.discrepancy:.1e} |")
    plot_limit(res, "l", ax=ax)
    ax.set_title(f"{label}, F = {rise:g} m: k = {res.k:.4f}")
    print(rows[-1], f"({time.perf_counter() - t0:.1f} s)")
axes.flat[-1].axis("off")
fig.tight_layout()
fig.savefig("docs/figures/families_limit.png", dpi=90)
print("| family (S = 10 m, t = 1 m, n = 12, normal joints) | k_l / k_r | M_l hinges | "
      "minimum thickness | momentum c_v | static - kinematic |")
print("|---|---|---|---|---|---|")
print("\n".join(rows))
