"""The figures of docs/defects.md: defect maps of Oppenheim's arch and of a semicircle on piers
(run from the repository root: ``python docs/scripts/defect_map.py``; about a minute, most of it
the pulse map)."""

import time

from archrock.studies.defectmap import defect_map
from archrock.reports.plots import plot_defect_map
from archrock.geometry import oppenheim_arch
from archrock.reports.defects import format_defects

arch = oppenheim_arch()
for kind, value, side in (("thickness", 0.7, "centreline"), ("thickness", 0.7, "intrados"),
                          ("thickness", 0.7, "extrados"), ("tilt", 5.0, ""), ("tilt", -5.0, ""),
                          ("mortar", 0.3, "intrados"), ("mortar", 0.3, "extrados")):
    t0 = time.perf_counter()
    m = defect_map(arch, kind, value, side)
    print(format_defects(m))
    print(f"[{time.perf_counter() - t0:.1f} s]\n")

for sign in (-1, 0):  # the paper's sign, then both signs (the smaller amplitude)
    t0 = time.perf_counter()
    m = defect_map(arch, "thickness", 0.7, pulse_duration=0.2, sign=sign, n_scan=150)
    print(format_defects(m))
    print(f"[{time.perf_counter() - t0:.1f} s]\n")
plot_defect_map(m, "docs/figures/defect_map_oppenheim.png")
print("wrote docs/figures/defect_map_oppenheim.png")

# on piers (docs/defects.md, On piers): voussoirs and pier courses apart
from archrock.geometry import nominal_arch, with_piers  # noqa: E402

piers = with_piers(nominal_arch(5.0, 180.0, 0.8, 9), 4.0, 2.0)
m = defect_map(piers)
print(format_defects(m))
plot_defect_map(m, "docs/figures/defect_map_piers.png")
print("wrote docs/figures/defect_map_piers.png")
