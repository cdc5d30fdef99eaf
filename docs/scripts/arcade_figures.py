"""The figures and tables of docs/arcades.md: the reference semicircle (R = 5 m, t = 0.8 m, 9
voussoirs) as one, two and three spans on 8 m piers (end piers 2.5 m, inner piers 1.8 m): the
graph LP's k and mechanism, the contact engine's ramp beside it, the first collapse under
Oppenheim's pulse (t_p = 0.2 s) by the engine, and the mechanism figure.  Run from the
repository root: ``PYTHONPATH=src python docs/scripts/arcade_figures.py`` (a few minutes; the
ramps dominate)."""

import sys
import time

from archrock.cli.arcade import plot_arcade
from archrock.contact import EngineSettings
from archrock.contact.arcade import arcade_ramp, arcade_respond
from archrock.geometry import nominal_arch
from archrock.geometry.arcade import arcade
from archrock.groundmotion import PulseSpec
from archrock.statics.graph import graph_limit

ARCH = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
CASES = {1: arcade([ARCH], 8.0, 2.5), 2: arcade([ARCH] * 2, 8.0, [2.5, 1.8, 2.5]),
         3: arcade([ARCH] * 3, 8.0, [2.5, 1.8, 1.8, 2.5])}
skip_engine = "--no-engine" in sys.argv

res = {n: {d: graph_limit(a, d) for d in "lr"} for n, a in CASES.items()}
plot_arcade(CASES[3], res[3], "docs/figures/arcade_mechanism.png")
print("| spans | blocks | contacts | k_l | k_r | virtual work - LP | dof | hinges (l) |")
print("|---|---|---|---|---|---|---|---|")
for n, a in CASES.items():
    g = res[n]
    diff = max(abs(g[d].k_virtual_work - g[d].k) for d in "lr")
    print(f"| {n} | {a.n_blocks} | {len(a.contacts)} | {g['l'].k:.6f} | {g['r'].k:.6f} | "
          f"{diff:.1e} | {g['l'].mechanism.dof} | "
          f"{'; '.join(h.place for h in g['l'].hinges)} |")
if skip_engine:
    sys.exit(0)

print("\n| spans | dir | LP k | engine k | bracket | engine / LP - 1 | hinges | wall [s] |")
print("|---|---|---|---|---|---|---|---|")
for n, a in CASES.items():
    t0 = time.perf_counter()
    r = arcade_ramp(a, EngineSettings(), k_l=res[n]["l"].k, k_r=res[n]["r"].k)
    wall = time.perf_counter() - t0
    for d in "lr":
        rd, g = getattr(r, d), res[n][d]
        same = sorted(rd.hinges) == sorted((h.contact, h.end) for h in g.hinges)
        print(f"| {n} | {d} | {g.k:.6f} | {rd.multiplier:.6f} | [{rd.lower:.6f}, "
              f"{rd.upper:.6f}] | {rd.multiplier / g.k - 1:+.4f} | "
              f"{'the LP hinges' if same else '; '.join(rd.places)} | {wall:.0f} |")

print("\n| spans | amplitude [g] | engine | t_collapse [s] | peak block rotation [rad] |")
print("|---|---|---|---|---|")
for n, a in CASES.items():
    for amp in (-0.1, -0.15, -0.2, -0.25, -0.3, -0.4):
        rs = arcade_respond(a, PulseSpec("oppenheim", amp, 0.2).build(), t_end=1.0)
        tc = f"{rs.t_collapse:.3f}" if rs.collapsed else "-"
        print(f"| {n} | {amp:g} | {rs.status} | {tc} | {rs.peak_rotation:.4g} |", flush=True)

# the first collapse amplitude, bisected between the last rest and the first collapse above
print("\n| spans | first collapse [g] (bracket) | piers turning > 1e-3 rad at collapse | "
      "blocks turning |")
print("|---|---|---|---|")
for n, a in CASES.items():
    lo, hi = 0.25, 0.30
    last = None
    while hi - lo > 0.0025:
        mid = 0.5 * (lo + hi)
        rs = arcade_respond(a, PulseSpec("oppenheim", -mid, 0.2).build(), t_end=1.0)
        if rs.collapsed:
            hi, last = mid, rs
        else:
            lo = mid
    if last is None:
        last = arcade_respond(a, PulseSpec("oppenheim", -hi, 0.2).build(), t_end=1.0)
    piers = [p + 1 for p, blocks in enumerate(a.piers) if set(blocks) & set(last.moved)]
    print(f"| {n} | {0.5 * (lo + hi):.4f} ({lo:.4f}, {hi:.4f}) | {piers} | "
          f"{len(last.moved)} of {a.n_blocks} |", flush=True)
