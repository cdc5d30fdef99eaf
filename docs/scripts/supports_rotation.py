"""Rotation of a pier or abutment (docs/supports.md): the hinges, thrust and crown drop at a
few outward rotations, and the capacity in rotation, of Oppenheim's arch on rigid abutments
(the foot 0 and 3 m below the springing's outer end), on 4 m x 2 m piers (the pier's outer
foot) and of a 16-voussoir semicircle (R = 10 m, t = 2 m).

Usage: PYTHONPATH=src python docs/scripts/supports_rotation.py
"""

from __future__ import annotations

import time

from archrock.geometry import nominal_arch, with_piers
from archrock.geometry.displaced import SupportMovement
from archrock.statics.limit import limit_analysis
from archrock.statics.supports import displace, displacement_capacity, reclosed

ARCHES = {"Oppenheim": (nominal_arch(), 0.0), "Oppenheim, foot 3 m down": (nominal_arch(), 3.0),
          "Oppenheim on piers": (with_piers(nominal_arch(), 4.0, 2.0), 0.0),
          "semicircle t/R 0.2, 16": (nominal_arch(radius=10.0, embrace_deg=180, thickness=2.0,
                                                   voussoirs=16), 0.0)}


def lab(hs):
    return ", ".join(f"{h.joint}{h.edge[0]}" for h in hs)


for name, (arch, depth) in ARCHES.items():
    t0 = time.perf_counter()
    cap = displacement_capacity(arch, "rotation", pivot_depth=depth)
    print(f"{name}: capacity {cap.capacity:.5g} rad ({cap.reason}; onset {lab(cap.hinges)}, "
          f"mechanism {lab(cap.mechanism)}), H {cap.curve[0, 1] / 1e3:.4g} -> "
          f"{cap.curve[-1, 1] / 1e3:.4g} kN/m, crown drop {cap.curve[-1, 4]:.4g} m "
          f"[{time.perf_counter() - t0:.1f} s]")
    for r in (0.005, 0.01, 0.02):
        if r >= cap.capacity:
            continue
        st = displace(arch, SupportMovement(rotation=r, pivot_depth=depth))
        lim = limit_analysis(reclosed(st.arch))
        print(f"   {r:g} rad: hinges {lab(st.hinges)}, H {st.thrust / 1e3:.5g} kN/m, crown drop "
              f"{st.crown_drop:.4g} m, k_l {lim.k_l:.4f}, k_r {lim.k_r:.4f}")
