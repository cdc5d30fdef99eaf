"""Irregular arches around a surveyed polygon arch (a PolygonArch without a family recipe, e.g.
read from a DXF drawing): the surveyed joints stay where they were measured, and each voussoir's
thickness and the offset of its centreline vary, as the family arches' do.

Voussoir i, between joints i and i + 1 (each joint the segment from its intrados end to its
extrados end), draws U1_i and U2_i on [-1, 1] (rows 1 and 2 of the sampler's draws; row 0, the
span, is not used: a surveyed joint is not moved along the arch).  Every point of its intrados
and extrados moves along the direction d(s) that turns at a constant rate from d_i to d_i+1
(d_j the unit vector of joint j from intrados to extrados, s the point's arc-length fraction
along its face; on a circular arc d(s) is the radial direction) by

    extrados: (s_t U1_i / 2 + s_R U2_i) t(s),    intrados: (-s_t U1_i / 2 + s_R U2_i) t(s),

t(s) = (1 - s) t_i + s t_i+1 (t_j the surveyed length of joint j): the thickness becomes
t (1 + s_t U1_i) and the centreline moves by s_R U2_i t along the joints, the family arch's
s_t and s_R.  A face's end moves along its own joint, so neighbouring voussoirs still meet on
the surveyed joint lines.  Loads stay where they are.  A joint tilt or a span spread is refused
for a surveyed arch (its joints are data, not a family's construction).
"""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError
from .polygon import PolygonArch

__all__ = ["perturb_survey", "is_survey"]


def is_survey(arch) -> bool:
    """A polygon arch with no family recipe: perturbed by :func:`perturb_survey`."""
    return isinstance(arch, PolygonArch) and getattr(arch, "recipe", None) is None


def _joints(nominal: PolygonArch):
    """Intrados and extrados ends (n + 1, 2) of the surveyed joints, left to right."""
    n = nominal.n
    ends_i = np.array([nominal.intrados[i][0] for i in range(n)] + [nominal.intrados[-1][-1]])
    ends_e = np.array([nominal.extrados[i][0] for i in range(n)] + [nominal.extrados[-1][-1]])
    return ends_i, ends_e


def joint_frames(nominal: PolygonArch):
    """(t, d, a0, turn) of the surveyed joints: lengths t_j [m], unit vectors d_j from intrados
    to extrados, their angles [rad], and the turn from each joint to the next [rad] (module
    docstring); ArchInputError for a joint of zero length."""
    ends_i, ends_e = _joints(nominal)
    vec = ends_e - ends_i
    t = np.hypot(*vec.T)
    if np.any(t <= 0):
        raise ArchInputError("nominal: a joint of the surveyed arch has zero length")
    d = vec / t[:, None]
    # d(s) turns at a constant rate from d_i to d_i+1 (the radial direction of a circular arc,
    # whose arc length is proportional to its angle)
    a0 = np.arctan2(d[:, 1], d[:, 0])
    turn = np.angle(np.exp(1j * (a0[1:] - a0[:-1])))
    return t, d, a0, turn


def _fractions(line: np.ndarray) -> np.ndarray:
    seg = np.hypot(*np.diff(line, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    return s / s[-1]


def perturb_survey(nominal: PolygonArch, u, spread_thickness: float, spread_offset: float,
                   name: str = "arch") -> PolygonArch:
    """An irregular arch around the surveyed arch ``nominal`` from uniform draws ``u`` (shape
    (3, n) or (4, n), each on [-1, 1]; rows 1 and 2 used, module docstring).  Raises
    ArchInputError when the draw is not a valid arch (a voussoir thinner than nothing, crossing
    faces)."""
    if not is_survey(nominal):
        raise ArchInputError("nominal: perturb_survey takes a polygon arch without a family "
                             "recipe (a surveyed arch)")
    n = nominal.n
    u = np.asarray(u, float)
    if u.ndim != 2 or u.shape[0] not in (3, 4) or u.shape[1] != n:
        raise ArchInputError(f"u: shape {u.shape}; allowed (3, {n}) or (4, {n})")
    t, d, a0, turn = joint_frames(nominal)
    intr, extr = [], []
    for i in range(n):
        half = 0.5 * spread_thickness * u[1, i]
        off = spread_offset * u[2, i]
        if 2.0 * abs(off) >= 1.0 + 2.0 * half or 1.0 + 2.0 * half <= 0.0:
            raise ArchInputError(f"geometry: voussoir {i}'s offset exceeds half its thickness")
        for line, amount, out in ((nominal.intrados[i], off - half, intr),
                                  (nominal.extrados[i], off + half, extr)):
            s = _fractions(line)
            ang = a0[i] + s * turn[i]
            direc = np.column_stack([np.cos(ang), np.sin(ang)])
            direc[0], direc[-1] = d[i], d[i + 1]  # a face's ends move along their own joints
            tt = (1.0 - s) * t[i] + s * t[i + 1]
            out.append(line + (amount * tt)[:, None] * direc)
    return PolygonArch(tuple(intr), tuple(extr), nominal.density, name, nominal.loads)
