"""A displaced arch's open joints (docs/supports.md): which of them a mechanism closes again, the
arch re-closed on its moved supports (the arch every command analyses), its point contacts, and
the gap a closing mechanism must close.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import ArchInputError
from ..geometry import VoussoirArch
from ..geometry.displaced import DisplacedArch, SupportMovement
from .displacement import displace

__all__ = ["closing_hinges", "reclosed", "on_moved_supports", "point_contacts", "GapClosing",
           "gap_closing"]


def closing_hinges(arch: DisplacedArch, mechanism) -> tuple[int, ...]:
    """The open joints of a displaced arch that ``mechanism`` (e.g. of
    :func:`archrock.statics.limit.limit_analysis` on it) turns back toward closing: it hinges
    there about the other edge's label (the same point, the opposite relative rotation).  Such
    a mechanism moves only until that joint's gap closes (a rotation of the order of the hinge's
    rotation so far), then the joint bears on its whole face again: limit analysis on the
    displaced configuration counts it, though it is not a collapse of the arch as a whole."""
    if not isinstance(arch, DisplacedArch):
        return ()
    opened = {h.joint: h.edge for h in arch.hinges}
    return tuple(h.joint for h in mechanism.hinges
                 if h.joint in opened and h.edge != opened[h.joint])


def reclosed(arch: DisplacedArch) -> DisplacedArch:
    """The displaced geometry with every open joint bearing on a whole face again: its contact
    segment is the face of the voussoir on its right as that voussoir now lies (at the right
    springing, the last voussoir's).  Limit analysis on it gives the effect of the changed
    geometry alone, without the point contacts (docs/supports.md): the open joints' gaps are
    small at small movements, and a mechanism that turns them back closes them at once."""
    if not isinstance(arch, DisplacedArch):
        raise ArchInputError(f"arch: expected a DisplacedArch, got {type(arch).__name__}")
    if not arch.point_joints:
        return arch
    return DisplacedArch(arch.base, tuple(arch.angles), tuple(arch.origins), tuple(arch.images),
                         (), arch.movement, arch.hinges, f"{arch.name} (joints re-closed)",
                         contacts=arch.point_joints)


def on_moved_supports(arch: VoussoirArch, movement: SupportMovement) -> VoussoirArch:
    """``arch`` as every analysis takes it after ``movement`` (docs/supports.md, "One answer:
    the re-closed arch"): the displaced arch of :func:`displace`, :func:`reclosed`; ``arch``
    itself at zero movement.  CannotStandError where it cannot stand there."""
    moved = displace(arch, movement).arch
    return reclosed(moved) if isinstance(moved, DisplacedArch) else moved


def point_contacts(arch: DisplacedArch) -> DisplacedArch:
    """The inverse of :func:`reclosed`: the displaced arch with its open joints as the point
    contacts they were (``arch`` itself if it has none to restore)."""
    if not isinstance(arch, DisplacedArch):
        raise ArchInputError(f"arch: expected a DisplacedArch, got {type(arch).__name__}")
    if arch.point_joints or not arch.contacts:
        return arch
    return DisplacedArch(arch.base, tuple(arch.angles), tuple(arch.origins), tuple(arch.images),
                         arch.contacts, arch.movement, arch.hinges, arch.base.name + " (displaced)")


@dataclass(frozen=True)
class GapClosing:
    """What the point contacts of a displaced arch's open joints allow before its collapse
    multipliers are reached: limit analysis of the point-contact geometry (``k_l``, ``k_r``,
    mechanisms) where it is lower than the re-closed arch's.  Such a mechanism turns open joints
    (``closing_l``, ``closing_r``) back toward closing, so it moves only until their gaps close,
    a rotation of the order of the hinges' rotation so far: a bounded motion, not a collapse
    (docs/supports.md, "One answer: the re-closed arch")."""

    k_l: float
    k_r: float
    closing_l: tuple
    closing_r: tuple

    def to_dict(self) -> dict:
        return {"k_l": self.k_l, "k_r": self.k_r, "closing_l": list(self.closing_l),
                "closing_r": list(self.closing_r)}


def gap_closing(arch: DisplacedArch) -> GapClosing | None:
    """:class:`GapClosing` of a (re-closed) displaced arch, or None when the point contacts
    allow nothing below the re-closed arch's multipliers or the arch has no open joint."""
    from .limit import limit_analysis

    pc = point_contacts(arch)
    if not pc.point_joints:
        return None
    # a point contact has no segment to spread a stress block on: the gaps' closing is
    # Heyman's (the re-closed arch's own analysis takes the finite f_c)
    r = limit_analysis(pc.with_fc(None), verify=False)
    shut_l, shut_r = closing_hinges(pc, r.mechanism_l), closing_hinges(pc, r.mechanism_r)
    if not (shut_l or shut_r):
        return None
    return GapClosing(r.k_l, r.k_r, shut_l, shut_r)
