"""Reports of a limit analysis: the ``archrock limit --json`` object and the readable table."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["limit_summary", "format_limit_table"]


def limit_summary(result, min_thickness=None) -> dict:
    """JSON-ready summary of a LimitResult (the ``archrock limit --json`` object)."""
    d = result.to_dict()
    d.pop("arch", None)
    out = {
        "arch": result.arch.name,
        "k": result.k,
        **d,
        "hinge_labels": {
            # A..D from the mechanism's leading side (A leftmost for M_l, rightmost for M_r)
            dirn: [{"label": lab, **h.to_dict()} for lab, h in result.mechanism(dirn).labelled()]
            for dirn in ("l", "r")
        },
        "geometry": result.arch.to_dict(),
        "units": {"k": "g (horizontal load / weight)", "span_deg": "deg", "radius": "m",
                  "thickness": "m", "density": "kg/m^3"},
    }
    if min_thickness is not None:
        out["min_thickness"] = {
            "factor": min_thickness.factor,
            "ratio_t_over_R": min_thickness.ratio,
            "thicknesses": [float(t) for t in min_thickness.thicknesses],
        }
    return out


def format_limit_table(result, min_thickness=None) -> str:
    """Readable report of a LimitResult: geometry, k_l / k_r, hinges, LP check."""
    arch = result.arch
    lines = [f"Arch: {arch.name}, {arch.n} voussoirs, embrace {math.degrees(arch.embrace):.4f} deg, "
             f"density {arch.density:g} kg/m^3"]
    # relative to the arch's size: the wording must not depend on the units
    ref = float(np.mean(arch.radii))
    uniform = (np.ptp(arch.spans) < 1e-12 and np.ptp(arch.radii) < 1e-12 * ref
               and np.ptp(arch.thicknesses) < 1e-12 * ref)
    if uniform:
        lines.append(f"  regular: R = {arch.radii[0]:g} m, t = {arch.thicknesses[0]:g} m, "
                     f"span = {math.degrees(arch.spans[0]):.4f} deg each")
    else:
        lines.append("  voussoir  span [deg]  radius [m]  thickness [m]")
        for i, (a, r, t) in enumerate(zip(arch.spans, arch.radii, arch.thicknesses)):
            lines.append(f"  {i:8d}  {math.degrees(a):10.4f}  {r:10.4f}  {t:13.4f}")
    lines += ["", "Limit analysis (horizontal forces = multiplier x weight; Heyman's hypotheses)",
              "  mechanism  k (kinematic)  k (static LP)  hinges A-D (joint edge)"]
    for dirn in ("l", "r"):
        mech = result.mechanism(dirn)
        k = result.k_l if dirn == "l" else result.k_r
        ks = result.static_k_l if dirn == "l" else result.static_k_r
        kss = f"{ks:13.4f}" if ks is not None else f"{'-':>13}"
        hinges = ", ".join(f"{lab}: {h.joint} {h.edge}" for lab, h in mech.labelled())
        lines.append(f"  M_{dirn}        {k:13.4f}  {kss}  {hinges}")
    lines.append(f"  k = min(k_l, k_r) = {result.k:.4f}")
    if result.discrepancy is not None:
        verdict = "agree" if result.discrepancy < 1e-6 else "DISAGREE"
        lines.append(f"  LP check: max |kinematic - static| = {result.discrepancy:.2e} ({verdict})")
    if min_thickness is not None:
        lines.append(f"  minimum thickness under self-weight: factor {min_thickness.factor:.4f} "
                     f"of the given thicknesses, mean t/R = {min_thickness.ratio:.4f}")
    lines.append("  (M_l: activated by xg''/g <= -k_l, forces toward +x; "
                 "M_r: by xg''/g >= k_r, forces toward -x)")
    return "\n".join(lines)
