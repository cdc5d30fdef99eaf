"""The tables and figure of docs/friction.md: the friction-limited minimum thickness of a
semicircle against the friction coefficient (archrock's weights and Cocchetti and Rizzi's
centreline weights), and the friction the no-sliding collapse needs on three arches (run from
the repository root: ``python docs/scripts/friction_table.py``; about a minute)."""

import math
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from archrock.errors import CannotStandError  # noqa: E402
from archrock.statics.friction import (friction_analysis, friction_minimum_thickness,  # noqa: E402
                               friction_needed)
from archrock.geometry import Arch, Load, family_arch, nominal_arch, oppenheim_arch  # noqa: E402
from archrock.statics.limit import limit_analysis, minimum_thickness  # noqa: E402


def centreline_semicircle(n, t_over_r=0.2):
    """Weight on the centreline (Cocchetti and Rizzi's convention): nearly massless masonry and a
    point mass at the centroid of each voussoir's arc of the mean radius (1e-9 of the weight off)."""
    a = nominal_arch(1.0, 180.0, t_over_r, n)
    psi = a.joint_angles
    mid, half = 0.5 * (psi[:-1] + psi[1:]), 0.5 * a.spans
    rc = np.sin(half) / half
    loads = tuple(Load(i, 1e9 * a.spans[i], (rc[i] * math.cos(mid[i]), rc[i] * math.sin(mid[i])))
                  for i in range(n))
    return Arch(a.spans, a.radii, a.thicknesses, 1.0, "centreline semicircle", loads)


def min_t(arch, mu):
    try:
        return friction_minimum_thickness(arch, mu).ratio
    except CannotStandError:
        return None


MUS = [1.0, 0.5, 0.396, 0.39, 0.38, 0.37, 0.36, 0.35, 0.34, 0.33, 0.32, 0.315, 0.31, 0.3095,
       0.3093, 0.309, 0.305, 0.30]
ARCHES = {"true weights, n = 60": nominal_arch(10.0, 180.0, 1.0, 60),
          "true weights, n = 360": nominal_arch(10.0, 180.0, 1.0, 360),
          "centreline weights, n = 360": centreline_semicircle(360)}

t0 = time.perf_counter()
table = {name: [min_t(a, mu) for mu in MUS] for name, a in ARCHES.items()}
print(f"semicircle table ({time.perf_counter() - t0:.1f} s)")
print("| mu | " + " | ".join(f"t/R, {name}" for name in ARCHES) + " |")
print("|---|" + "---|" * len(ARCHES))
for i, mu in enumerate(MUS):
    cells = ["no thickness" if table[k][i] is None else f"{table[k][i]:.6f}" for k in ARCHES]
    print(f"| {mu:g} | " + " | ".join(cells) + " |")

print()
for name, a in ARCHES.items():
    mt = minimum_thickness(a)
    need = friction_needed(a.with_thickness_factor(mt.factor))
    print(f"{name}: frictionless t/R = {mt.ratio:.6f}, friction its collapse needs "
          f"{need['l']:.6f}")

print()
print("| arch | k_l | friction needed M_l / M_r | joints | k_l with mu = 0.8 x needed |")
print("|---|---|---|---|---|")
for label, a in [("Oppenheim's (R = 10 m, 157.5 deg, t = 1.5 m, 7 voussoirs)", oppenheim_arch()),
                 ("pointed (S = 10 m, F = 7 m, t = 1 m, 12 voussoirs)",
                  family_arch("pointed", 10.0, 7.0, 1.0, 12)),
                 ("pointed (S = 10 m, F = 7 m, t = 1 m, 40 voussoirs)",
                  family_arch("pointed", 10.0, 7.0, 1.0, 40)),
                 ("semicircle (R = 10 m, t = 1.5 m, 12 voussoirs)", nominal_arch(10.0, 180.0, 1.5, 12)),
                 ("semicircle (R = 10 m, t = 1.5 m, 60 voussoirs)", nominal_arch(10.0, 180.0, 1.5, 60))]:
    res = limit_analysis(a)
    need = friction_needed(a)
    fr = friction_analysis(a, 0.8 * min(need.values()))
    print(f"| {label} | {res.k_l:.4f} | {need['l']:.4f} / {need['r']:.4f} | "
          f"M_l {friction_analysis(a, 1.01 * need['l']).l.joints} | {fr.l.multiplier:.4f} "
          f"(sliding at {fr.l.joints}) |")

fig, ax = plt.subplots(figsize=(6.5, 4.2))
for name, style in zip(ARCHES, ("o-", "s--", "-")):
    pts = [(mu, t) for mu, t in zip(MUS, table[name]) if t is not None and mu <= 0.45]
    ax.plot(*zip(*pts), style, label=name, ms=3)
ax.axvline(0.309215, color="0.5", lw=0.8)
ax.axvline(0.395832, color="0.5", lw=0.8)
ax.set_xlabel("friction coefficient mu")
ax.set_ylabel("least thickness t/R")
ax.set_title("Semicircle under self-weight: least thickness with friction")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig("docs/figures/friction_semicircle.png", dpi=90)
print("wrote docs/figures/friction_semicircle.png")
