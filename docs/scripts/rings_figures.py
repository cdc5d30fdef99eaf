"""The figure and table of docs/rings.md: a semicircle of centreline span 5 m, 0.43 m deep, in
one ring of 77 voussoirs and in two rings of 0.215 m headers (0.1025 m), at several interface
frictions, a cohesion and header courses; the two-ring mechanisms drawn.  Run from the repository root:
``PYTHONPATH=src python docs/scripts/rings_figures.py`` (about a minute)."""

from archrock.cli.rings import plot_rings, ring_lines
from archrock.geometry.rings import ringed_arch
from archrock.statics.graph import graph_limit

R, T = 2.5, 0.43
CASES = {"one ring": dict(rings=1),
         "two rings, mu 2": dict(rings=2, friction=2.0),
         "two rings, mu 0.8": dict(rings=2),
         "two rings, mu 0.5": dict(rings=2, friction=0.5),
         "two rings, mu 0.8, c 10 kPa": dict(rings=2, cohesion=1e4),
         "two rings, a header every 8 bricks": dict(rings=2, headers=8)}
print("| build | blocks | k_l | k_r | virtual work - LP | dof |")
print("|---|---|---|---|---|---|")
for what, kw in CASES.items():
    a = ringed_arch(R, T, **kw)
    g = {d: graph_limit(a, d) for d in "lr"}
    diff = max(abs(g[d].k_virtual_work - g[d].k) for d in "lr")
    print(f"| {what} | {a.n_blocks} | {g['l'].k:.6f} | {g['r'].k:.6f} | {diff:.1e} | "
          f"{g['l'].mechanism.dof} |")
    for line in ring_lines(a, g["l"].mechanism):
        print(line)
    if what == "two rings, mu 0.8":
        plot_rings(a, g, "docs/figures/rings_separation.png")
    if what == "two rings, a header every 8 bricks":
        plot_rings(a, g, "docs/figures/rings_headers.png")
