"""What the page draws of an arch: its blocks' outlines, joints and ground, shared by the
statics, four-link and engine endpoints (:mod:`archrock.app.api`, :mod:`archrock.app.engine`)."""

from __future__ import annotations

from .fields import xy


def block_counts(arch) -> tuple[int, int]:
    """(voussoirs, pier courses) of an arch: the blocks of its piers are not voussoirs."""
    p = len(getattr(arch, "pier_blocks", ()))
    return int(arch.n) - p, p


def arch_drawing(arch) -> dict:
    """What the page draws of an arch: ``n`` blocks (``voussoirs`` and ``pier_courses``, the
    blocks of both piers), each block's closed outline [[x, y], ...] [m], each
    joint's contact segment (intrados end, extrados end) [m] and the ground level [m]."""
    from ..reports.plots import springing_level, voussoir_outline

    outlines = [xy(voussoir_outline(arch, i, points_per_rad=30.0)) for i in range(arch.n)]
    v, p = block_counts(arch)
    return {"name": arch.name, "n": int(arch.n), "voussoirs": v, "pier_courses": p,
            "outlines": outlines,
            "joints": xy(arch.joint_points), "ground": springing_level(arch),
            "kind": type(arch).__name__}
