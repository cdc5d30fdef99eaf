"""Irregular arches: random voussoir-by-voussoir perturbations of a nominal arch, circular
(:func:`~archrock.geometry.perturb_voussoirs`, exact sectors) or of a family
(:func:`perturb_family`: lengths along the centreline, thicknesses, offsets and joint tilts),
and :func:`random_arch`, one such arch from a seed.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from .base import VoussoirArch, _check_scalar
from .circular import Arch, _check_spread, oppenheim_arch, random_spans_thicknesses_radii
from .displaced import refuse_moved_supports
from .faces import (_CrownOffsetCrossed, _fill, _pointed_crown, _sample_offset,
                    _vertical_joints_that_cut, cut_polyline)
from .families import FamilyArch
from .polygon import PolygonArch

__all__ = ["random_arch", "perturb_family"]


def random_arch(nominal: VoussoirArch | None = None, seed=None, spread_span: float = 0.1,
                spread_thickness: float = 0.1, spread_radius: float = 0.05,
                rng: np.random.Generator | None = None, spread_tilt_deg: float = 0.0):
    """An irregular arch drawn around ``nominal`` (default: Oppenheim's arch).

    Each voussoir's span (its length along the centreline), thickness and radius (a normal
    offset of its centreline) are independent uniform perturbations (widths ``spread_*``,
    dimensionless, see :func:`random_spans_thicknesses_radii`); for an arch of
    :func:`~archrock.geometry.family_arch` also each interior joint's tilt, +-``spread_tilt_deg``
    degrees (:func:`~archrock.geometry.irregular.perturb_family`).  Reproducible from ``seed``
    (an int or a numpy SeedSequence) or a given ``rng``.  A circular :class:`Arch` gives an
    ``Arch``, a family arch a :class:`~archrock.geometry.PolygonArch`.
    """
    nominal = oppenheim_arch() if nominal is None else nominal
    s_a = _check_spread("spread_span", spread_span, 1.0)
    s_t = _check_spread("spread_thickness", spread_thickness, 1.0)
    s_r = _check_spread("spread_radius", spread_radius, 1.0)
    tilt = _check_scalar("spread_tilt_deg", spread_tilt_deg, 0.0, 45.0, lo_open=False,
                         allowed="0 <= tilt < 45 deg")
    rng = np.random.default_rng(seed) if rng is None else rng
    label = f"random (seed {seed})" if seed is not None else "random"
    if isinstance(nominal, Arch):
        if tilt:
            raise ArchInputError("spread_tilt_deg: the joints of a circular Arch stay radial; "
                                 "tilt joints on family_arch('circular', ..., exact=False)")
        u = rng.uniform(-1.0, 1.0, size=(3, nominal.n))
        spans, thick, radii = random_spans_thicknesses_radii(nominal, u, s_a, s_t, s_r)
        return Arch(spans, radii, thick, nominal.density, name=label)
    if not isinstance(nominal, FamilyArch) or nominal.recipe is None:
        refuse_moved_supports(nominal)
        raise ArchInputError(f"nominal: a {type(nominal).__name__} without a family recipe (e.g. "
                             f"a surveyed arch) cannot be perturbed; allowed a circular Arch or "
                             f"an arch of family_arch")
    u = rng.uniform(-1.0, 1.0, size=(4 if tilt else 3, nominal.n))
    return perturb_family(nominal, u, s_a, s_t, s_r, tilt, name=label)


def perturb_family(nominal: "FamilyArch", u, spread_length: float, spread_thickness: float,
                   spread_offset: float, tilt_deg: float = 0.0, name: str = "arch"):
    """An irregular arch around a family arch, from uniform draws ``u`` (shape (3, n), or
    (4, n) with a tilt), each on [-1, 1]; the family's counterpart of
    :func:`~archrock.geometry.perturb_voussoirs`.

    Voussoir i covers the centreline's arc length [s_i, s_i+1] with lengths
    l_i = l0_i (1 + s_a U0_i) rescaled to the total L (l0_i the nominal's: L/n, or, with
    vertical joints that would miss the intrados near the springings, the nominal's longer
    springing voussoirs and equal ones between); its thickness is t(s)(1 + s_t U1_i) and
    its own centreline is offset along the normal by s_R U2_i t(s) (t(s): the nominal
    thickness, the circular family's R_i = R + s_R t U).  Joint j (1..n-1) is the nominal
    family's joint line at s_j (normal to the centreline, or vertical) rotated about the
    centreline point by U3_(j-1) x ``tilt_deg``; the springing faces stay normal.  Each
    voussoir's intrados and extrados are its offset lines (sampled as the family's) cut by its
    two joint lines, so neighbours' faces lie on one line.  A fill is recomputed over the new
    extrados; user loads stay where they are.

    Returns a :class:`PolygonArch` (no recipe: it is not a member of the family); raises
    :class:`~archrock.errors.ArchInputError` when the draw is not a valid arch.
    """
    r = nominal.recipe
    if r is None:
        raise ArchInputError("nominal: a polygon arch without a family recipe (e.g. a surveyed "
                             "arch) cannot be perturbed; allowed a circular Arch or an arch of "
                             "family_arch")
    line, thick = nominal._frame
    lengths, s_div = _drawn_divisions(line, thick, r, u, spread_length)
    u = np.asarray(u, float)
    n = len(lengths)
    c, d = _joint_lines(line, s_div, r["joints"], tilt_deg, u)
    fac = 1.0 + spread_thickness * u[1]
    off = spread_offset * u[2]
    intr, extr = [], []
    for i in range(n):
        lines = {side: _face_line(line, thick, r, lengths, s_div, c, d, i,
                                  fac[i] + 2.0 * side * off[i], side)
                 for side in (-1, 1)}
        intr.append(lines[-1])
        extr.append(lines[1])
    loads = tuple(r["loads"])
    if r["fill"] is not None:
        loads = loads + _fill(extr, r["fill"])[1]
    return PolygonArch(tuple(intr), tuple(extr), r["density"], name, loads)


def _drawn_divisions(line, thick, r, u, spread_length):
    """(lengths, s_div) [m]: the drawn voussoirs' lengths along the centreline and their
    division points, from the nominal's (with vertical joints: longer springing voussoirs where
    an equal division's vertical would miss the intrados)."""
    big_l = line.length
    base = big_l * np.arange(r["voussoirs"] + 1) / r["voussoirs"]
    if r["joints"] == "vertical":
        base = _vertical_joints_that_cut(line, thick, base)
    n = len(base) - 1
    u = np.asarray(u, float)
    if u.ndim != 2 or u.shape[0] not in (3, 4) or u.shape[1] != n:
        raise ArchInputError(f"u: shape {u.shape}; allowed (3, {n}) or (4, {n})")
    lengths = np.diff(base) * (1.0 + spread_length * u[0])
    lengths = lengths * (big_l / lengths.sum())
    if np.any(lengths <= 0):
        raise ArchInputError("geometry: a voussoir length is <= 0")
    s_div = np.concatenate([[0.0], np.cumsum(lengths)])
    s_div[-1] = big_l
    return lengths, s_div


def _joint_lines(line, s_div, joints: str, tilt_deg: float, u):
    """(c, d): each joint line's centreline point c_j [m] and unit direction d_j (intrados ->
    extrados): normal to the centreline or vertical, interior joints turned by U3 x tilt."""
    big_l, n = line.length, len(s_div) - 1
    tilt = np.zeros(n + 1)
    if tilt_deg and u.shape[0] == 4:
        tilt[1:n] = math.radians(tilt_deg) * u[3, :n - 1]
    c, tang = line.eval(s_div)
    d = np.column_stack([-tang[:, 1], tang[:, 0]])
    for j in range(1, n):
        if joints == "vertical" or (line.kink and abs(s_div[j] - big_l / 2) <= 1e-12 * big_l):
            d[j] = (0.0, 1.0)
    cs, sn = np.cos(tilt), np.sin(tilt)
    d = np.column_stack([cs * d[:, 0] - sn * d[:, 1], sn * d[:, 0] + cs * d[:, 1]])
    return c, d


def _face_line(line, thick, r, lengths, s_div, c, d, i: int, k: float, side: int):
    """Voussoir i's intrados (side -1) or extrados (+1): its offset line at k times the nominal
    half thickness, sampled as the family's and cut by its two joint lines."""
    big_l, n, ppr = line.length, len(lengths), r["points_per_rad"]
    span, rise = r["span"], r["rise"]
    if k <= 0:
        raise ArchInputError(f"geometry: voussoir {i}'s offset exceeds half its thickness")

    def te(s, k=k):
        return thick(s) * k
    t_mid = float(te(big_l / 2))

    def crown(sd, t_mid=t_mid):
        return _pointed_crown(span, rise, t_mid, sd)
    piece = None
    for widen in (False, True):
        lo = 0.0 if i == 0 else (0.0 if widen else max(0.0, s_div[i] - 0.5 * min(
            lengths[i - 1], lengths[i])))
        hi = big_l if i == n - 1 else (big_l if widen else min(big_l, s_div[i + 1] + 0.5 * min(
            lengths[i], lengths[i + 1])))
        try:
            pts = _sample_offset(line, te, lo, hi, side, ppr, crown)
        except _CrownOffsetCrossed:  # a range ending just past a pointed crown: widen it
            continue
        left = (0, pts[0]) if i == 0 else cut_polyline(pts, c[i], d[i], c[i] + side * d[i])
        right = (len(pts) - 2, pts[-1]) if i == n - 1 else \
            cut_polyline(pts, c[i + 1], d[i + 1], c[i + 1] + side * d[i + 1])
        if left is not None and right is not None and left[0] <= right[0]:
            piece = (pts, left, right)
            break
    if piece is None:
        raise ArchInputError(f"geometry: voussoir {i}'s joints do not cut its "
                             f"{'intrados' if side < 0 else 'extrados'} in order")
    pts, (kl, ql), (kr, qr) = piece
    mid = pts[kl + 1:kr + 1]
    tol = 1e-9 * big_l
    if len(mid):
        mid = mid[(np.hypot(*(mid - ql).T) > tol) & (np.hypot(*(mid - qr).T) > tol)]
    return np.vstack([ql, mid, qr])
