"""Finite compressive strength in the rocking dynamics (docs/crushing-dynamics.md).

Where an arch has a finite strength f_c (``arch.fc`` [MPa]), the statics put each hinge of the
collapse mechanism not at the joint's edge but at the centre of its compressed zone: half the
depth N / f_c of the rectangular stress block in from the edge (Heyman 1982, The Masonry Arch;
Gilbert 2007, "Limit analysis applied to masonry arch bridges", ARCH'07, and the RING theory
manual).  The four-link model of such an arch is Oppenheim's on those inset hinge points:
:func:`inset_joint_points` moves the four hinge points of a mechanism inward along their joints
by the zone depths of :attr:`~archrock.statics.limit.LimitResult.zones_l` / ``zones_r`` at
collapse, and :func:`collapse_zones` picks those zones out of a limit analysis (None where f_c
is infinite: the edge hinges, to the bit).

The inset is frozen at the force the statics give at the onset of collapse: while the arch rocks
the normal forces change, and with them the zones; the model keeps the onset's.  The inset is
small (a few millimetres at 5 MPa for a 10 m bridge arch), so its effect on the rocking is the
change in the activation multiplier and in the links' lever arms.  Mechanisms opened after
impacts that the statics never met (the least-loss chain's extra rows) and the impact law's
closing points keep the edges: no force is known for them.

With more arches at once (:func:`archrock.dynamics.batch.prepare_batch`) every arch goes through
:func:`~archrock.dynamics.response.prepare` (the conic statics and the inset four-links one
arch at a time): the compiled batch path of :mod:`archrock.dynamics.batch` assumes Heyman's
infinite strength and is never used for such arches.
"""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError

__all__ = ["arch_fc", "collapse_zones", "inset_joint_points", "any_finite"]


def arch_fc(arch) -> float | None:
    """The arch's compressive strength [MPa], or None (infinite: Heyman's hypothesis)."""
    fc = getattr(arch, "fc", None)
    return None if fc is None else float(fc)


def any_finite(arches) -> bool:
    """Whether any arch of ``arches`` (entries may be errors) has a finite strength."""
    return any(arch_fc(a) is not None for a in arches)


def collapse_zones(limit, direction: str):
    """Depths [m] (n+1,) of the compressed zones at the joints at collapse in ``direction``
    ('l' or 'r') of a limit analysis, or None where the arch's strength is infinite.  A finite
    strength whose statics gave no zones is refused: edge hinges would start rocking at a
    multiplier that is not the statics' (a silent wrong answer)."""
    if arch_fc(limit.arch) is None:
        return None
    zones = getattr(limit, "zones_l" if direction == "l" else "zones_r", None)
    if zones is None:
        raise ArchInputError(f"limit: the analysis of an arch of f_c = {arch_fc(limit.arch):g} "
                             f"MPa gives no compressed zones for M_{direction}; allowed the "
                             f"finite-strength limit analysis (limit_analysis(arch))")
    return np.asarray(zones, float)


def inset_joint_points(arch, mechanism, zones) -> np.ndarray:
    """``arch.joint_points`` (n+1, 2, 2) [m] with each hinge point of ``mechanism`` moved along
    its joint, toward the other edge, by half the compressed zone depth ``zones[joint]`` [m]:
    the centre of the stress block, where the finite-strength statics put the hinge."""
    pts = np.array(arch.joint_points, dtype=float)
    zones = np.asarray(zones, float)
    if zones.shape != (arch.n + 1,):
        raise ArchInputError(f"zones: shape {zones.shape}; allowed ({arch.n + 1},) (one depth "
                             f"per joint)")
    for h in mechanism.hinges:
        j, e = int(h.joint), 0 if h.edge == "intrados" else 1
        z = float(zones[j])
        if not z > 0.0:
            continue
        edge, other = pts[j, e].copy(), pts[j, 1 - e]
        length = float(np.hypot(*(other - edge)))
        if z >= length:  # the whole joint crushed: no inset can describe it
            raise ArchInputError(f"zones[{j}]: {z:g} m; allowed below the joint's length "
                                 f"{length:g} m")
        pts[j, e] = edge + 0.5 * z * (other - edge) / length
    return pts
