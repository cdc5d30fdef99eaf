"""The report's section on crushing: what a finite compressive strength f_c does to the arch.

Left out where the arch's strength is infinite (``arch.fc`` None: Heyman's hypothesis, every
other section as before).  Otherwise it sets the limit analysis with f_c beside Heyman's (the
same arch with f_c = infinity), lists the compressed zones at the collapse hinges (the stress
block of depth a = N / f_c on a 1 m depth, its share of the joint, the normal force N and the
mean stress N / t over the joint), and says which answer governs: the finite-strength one
wherever it is lower, and the contact engine's rigid blocks (which cannot crush) never above
it (Heyman 1982, The Masonry Arch; Gilbert 2007, ARCH'07, and the RING theory manual;
docs/crushing-dynamics.md).
"""

from __future__ import annotations

import numpy as np

from .assessment_blocks import Paragraph, Section, Table, _f

__all__ = ["section_crushing", "hinge_zones"]

MPA = 1e6  # Pa per MPa
DIRS = ("l", "r")


def hinge_zones(arch, lim, direction: str) -> list[dict]:
    """At each hinge of the collapse mechanism in ``direction``: joint, edge, joint length t
    [m], zone depth a [m], a / t, normal force N = a f_c [N/m] (1 m depth), mean stress N / t
    [MPa] and the hinge's inset a / 2 [m]."""
    zones = getattr(lim, f"zones_{direction}", None)
    fc = float(arch.fc)
    jp = np.asarray(arch.joint_points, float)
    out = []
    for h in sorted(lim.mechanism(direction).hinges, key=lambda h: h.joint):
        t = float(np.hypot(*(jp[h.joint, 1] - jp[h.joint, 0])))
        a = float(zones[h.joint]) if zones is not None else float("nan")
        n = a * fc * MPA
        out.append({"joint": int(h.joint), "edge": h.edge, "t": t, "zone": a, "ratio": a / t,
                    "N": n, "mean_stress": n / t / MPA, "inset": 0.5 * a})
    return out


def _heyman(ctx):
    """The limit analysis of the same arch with infinite strength (computed once)."""
    from ..statics.limit import limit_analysis

    return ctx.once("limit_heyman", lambda: limit_analysis(ctx.arch.with_fc(None),
                                                           verify=False))


def section_crushing(ctx) -> Section | None:
    """k with and without the finite strength, the compressed zones at collapse, and which
    governs; None (left out) where f_c is infinite."""
    arch = ctx.arch
    fc = getattr(arch, "fc", None)
    if fc is None:
        return None
    from ..errors import ArchrockError

    lim = ctx.limit
    try:
        hey = _heyman(ctx)
        k_hey = {d: float(getattr(hey, f"k_{d}")) for d in DIRS}
    except ArchrockError as exc:  # e.g. a flat arch with no Heyman mechanism (unbounded LP)
        hey, k_hey = None, {d: None for d in DIRS}
        why_none = " ".join(str(exc).split())
    k_fc = {d: float(getattr(lim, f"k_{d}")) for d in DIRS}
    rows, zones = [], {}
    for d in DIRS:
        kh = k_hey[d]
        drop = "-" if kh is None else f"{100 * (k_fc[d] / kh - 1):+.1f}%"
        bounds = getattr(lim, f"k_bounds_{d}", None)
        br = "-" if bounds is None else f"{bounds[0]:.6f} .. {bounds[1]:.6f}"
        rows.append((f"M_{d}", _f(k_fc[d], ".6f"), br, "none" if kh is None else f"{kh:.6f}",
                     drop))
        zones[d] = hinge_zones(arch, lim, d)
    zrows = tuple((f"M_{d}", f"{z['joint']} {z['edge']}", f"{z['t']:.4g}",
                   f"{1e3 * z['zone']:.4g}", f"{z['ratio']:.4f}", f"{z['N'] / 1e3:.4g}",
                   f"{z['mean_stress']:.4g}") for d in DIRS for z in zones[d])
    worst = max((z["ratio"] for d in DIRS for z in zones[d]), default=float("nan"))
    k_min, low = min(k_fc.values()), min(k_fc, key=k_fc.get)
    if hey is None:
        verdict = (f"Without crushing the arch has no mechanism ({why_none}); with f_c = "
                   f"{fc:g} MPa it carries k = {k_min:.6f} g (M_{low}): the finite strength "
                   f"governs, and it is the only answer.")
    else:
        k_h = min(k_hey.values())
        verdict = (f"With f_c = {fc:g} MPa the arch carries k = {k_min:.6f} g against Heyman's "
                   f"{k_h:.6f} g ({100 * (k_min / k_h - 1):+.1f}%): the finite strength "
                   f"governs wherever it is lower.")
    blocks = (
        Paragraph(f"Masonry of compressive strength f_c = {fc:g} MPa on a rectangular stress "
                  f"block, 1 m deep: at a joint of length t under a normal force N the "
                  f"compressed zone is a = N / f_c deep and the hinge sits at its centre, a / 2 "
                  f"in from the edge (Heyman 1982; Gilbert 2007, the RING theory manual). "
                  + verdict + " The four-link model of this report rocks about those inset "
                  "hinges (frozen at the collapse forces); the contact engine's rigid blocks "
                  "cannot crush, so its answer does not govern above the finite-strength "
                  "limit."),
        Table(("mechanism", f"k with f_c = {fc:g} MPa", "bracket (static)", "k, Heyman",
               "change"), tuple(rows)),
        Table(("mechanism", "hinge", "t [m]", "zone a [mm]", "a / t", "N [kN/m]",
               "N / t [MPa]"), zrows,
              "The compressed zones at the collapse hinges; the stress in each block is f_c."),
    )
    data = {"fc": float(fc), "k_l": k_fc["l"], "k_r": k_fc["r"],
            "heyman_k_l": k_hey["l"], "heyman_k_r": k_hey["r"],
            "k_bounds_l": _pair(getattr(lim, "k_bounds_l", None)),
            "k_bounds_r": _pair(getattr(lim, "k_bounds_r", None)),
            "zones": zones, "largest_zone_ratio": worst,
            "governs": "finite strength" if hey is None or k_min < min(k_hey.values())
            else "Heyman (equal)",
            "units": {"fc": "MPa", "k": "g", "t": "m", "zone": "m", "N": "N/m",
                      "mean_stress": "MPa"}}
    head = (("f_c [MPa]", f"{fc:g}"),
            ("k with f_c [g]", f"{k_min:.6f}" + ("" if hey is None else
                                                f" (Heyman {min(k_hey.values()):.6f})")),
            ("largest zone a / t", f"{worst:.4f}"))
    return Section("crushing", "Crushing (finite compressive strength)", blocks, data, head)


def _pair(bounds):
    return None if bounds is None else [float(bounds[0]), float(bounds[1])]
