"""What the compiled draws of a nominal family arch share (:mod:`~archrock.geometry.batchdraw`):
the draw states, the refusal codes and their messages, and :class:`FamilyPlan` (the centreline's
pieces, their arc-length tables, the nominal division points), built once in Python and kept
for the nominals seen lately (:func:`family_plan`).
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import HAVE_NUMBA
from ..errors import ArchInputError
from .centreline import _catenary_parameter, circular_radius, three_centred_radii
from .faces import _vertical_joints_that_cut

__all__ = ["FamilyPlan", "supported", "family_plan", "cached_plan", "compiled_drawing",
           "refusal_message", "OK", "REFUSED", "UNCERTIFIED"]

OK, REFUSED, UNCERTIFIED = 0, 1, 2
ARC, ELLIPSE, PARABOLA, CATENARY = 0, 1, 2, 3
# refusals of perturb_family (code): 1 a length <= 0, 2 an offset beyond half the thickness,
# 3 joints that do not cut a line in order
LENGTH, OFFSET, ORDER = 1, 2, 3


def refusal_message(code: int, index: int, side: int) -> str:
    """The ArchInputError message of ``perturb_family`` for a refused draw."""
    if code == LENGTH:
        return "geometry: a voussoir length is <= 0"
    if code == OFFSET:
        return f"geometry: voussoir {index}'s offset exceeds half its thickness"
    return (f"geometry: voussoir {index}'s joints do not cut its "
            f"{'intrados' if side < 0 else 'extrados'} in order")


def supported(nominal) -> bool:
    """Whether ``nominal`` is drawn by this module: a family arch (with a recipe) without
    loads or fill."""
    r = getattr(nominal, "recipe", None)
    return r is not None and r["fill"] is None and not r["loads"] and not nominal.loads


# ---------------------------------------------------------------------------- the plan
class FamilyPlan:
    """The per-nominal data of the compiled drawing (module docstring): built from the family's
    recipe with the expressions of :func:`~archrock.geometry.centreline.centreline`, its tables
    taken from the nominal's own centreline."""

    def __init__(self, nominal):
        if not supported(nominal):
            raise ArchInputError("nominal: the batch drawing takes family arches without loads "
                                 "or fill")
        r = nominal.recipe
        line, _ = nominal._frame
        shape, span, rise = r["shape"], r["span"], r["rise"]
        self.nominal = nominal
        a, f = span / 2, rise
        pieces = []  # (type, parameters)
        if shape == "circular":
            rr, yc = circular_radius(span, rise)
            th0 = math.atan2(-yc, -a)
            if th0 < 0:
                th0 += 2 * math.pi
            pieces.append(_arc_par(0.0, yc, rr, th0, math.pi - th0))
        elif shape == "pointed":
            c = (a * a - f * f) / span
            rho = a - c
            phi = math.atan2(f, -c)
            pieces += [_arc_par(-c, 0.0, rho, math.pi, math.pi - phi),
                       _arc_par(c, 0.0, rho, phi, 0.0)]
        elif shape == "elliptical":
            pieces.append((ELLIPSE, [-a, f, math.pi, math.pi * a, math.pi * f]))
        elif shape == "three-centred":
            r1, r2 = three_centred_radii(span, rise)
            c1 = a - r1
            yc2 = f - r2
            gamma = math.atan2(-yc2, -c1)
            pieces += [_arc_par(-c1, 0.0, r1, math.pi, gamma),
                       _arc_par(0.0, yc2, r2, gamma, math.pi - gamma),
                       _arc_par(c1, 0.0, r1, math.pi - gamma, 0.0)]
        elif shape == "parabolic":
            pieces.append((PARABOLA, [-a, 2 * a, f, a, -2 * f, a ** 2]))
        elif shape == "catenary":
            big_a = _catenary_parameter(a, f)
            pieces.append((CATENARY, [-a, 2 * a, f + big_a, big_a]))
        else:  # pragma: no cover - family_arch checks the shape
            raise ArchInputError(f"shape: {shape!r}")
        if len(pieces) != len(line.pieces):  # pragma: no cover - the two constructions agree
            raise ArchInputError("nominal: centreline pieces differ from the family's")
        P = len(pieces)
        grid = max(len(p._u) for p in line.pieces)
        self.ptype = np.array([t for t, _ in pieces], dtype=np.int64)
        self.ppar = np.zeros((P, 8))
        for j, (_, par) in enumerate(pieces):
            self.ppar[j, :len(par)] = par
        self.plen = np.array([p.length for p in line.pieces])
        # 1: an arc (u = s / length), 0: the Hermite table, 2: the table and a Newton step
        self.pmode = np.array([1 if p.constant_speed else (2 if p.newton else 0)
                               for p in line.pieces], dtype=np.int64)
        self.tab_u = np.zeros((P, grid))
        self.tab_s = np.zeros((P, grid))
        self.tab_n = np.array([len(p._u) for p in line.pieces], dtype=np.int64)
        self.tab_v = np.ones((P, grid))
        for j, p in enumerate(line.pieces):
            self.tab_u[j, :len(p._u)] = p._u
            self.tab_s[j, :len(p._s)] = p._s
            self.tab_v[j, :len(p._v)] = p._v
        self.bounds = np.asarray(line.bounds, float).copy()
        big_l = line.length
        base = big_l * np.arange(r["voussoirs"] + 1) / r["voussoirs"]
        if r["joints"] == "vertical":
            _, thick = nominal._frame
            base = _vertical_joints_that_cut(line, thick, base)
        self.base_len = np.ascontiguousarray(np.diff(base))
        self.n = len(base) - 1
        t0 = r["thickness"]
        tc = t0 if r["thickness_crown"] is None else r["thickness_crown"]
        pc = (span * span / 4 - rise * rise) / span  # _pointed_crown's centre and radius
        # scalars: L, kink, vertical, t0, tc - t0, ppr, crown centre c, crown radius rho
        self.scal = np.array([big_l, float(line.kink), float(r["joints"] == "vertical"), t0,
                              tc - t0, r["points_per_rad"], pc, span / 2 - pc])
        self.density = r["density"]

    def args(self):
        """The plan's arrays in the order the kernels take them."""
        return (self.ptype, self.ppar, self.plen, self.pmode, self.tab_u, self.tab_s,
                self.tab_v, self.tab_n, self.bounds, self.base_len, self.scal)


# the plans of the nominals seen lately (a study has one nominal)
_PLANS: list = []


def cached_plan(cache: list, nominal, build):
    """The plan in ``cache`` built for this very ``nominal`` object, or ``build(nominal)`` kept
    there (the last four nominals: a study has one)."""
    for plan in cache:
        if plan.nominal is nominal:
            return plan
    plan = build(nominal)
    cache.insert(0, plan)
    del cache[4:]
    return plan


def family_plan(nominal) -> "FamilyPlan":
    """The :class:`FamilyPlan` of ``nominal``, kept for reuse (:func:`cached_plan`)."""
    return cached_plan(_PLANS, nominal, FamilyPlan)


def compiled_drawing(sampler) -> bool:
    """Whether a sampler's family draws go through this module (numba present, a supported
    family nominal): :class:`~archrock.geometry.sampling.ArchSampler` and the ensemble's
    batches."""
    return HAVE_NUMBA and not sampler.circular and supported(sampler.nominal)


def _arc_par(cx, cy, r, th0, th1):
    """Parameters of an arc piece as :func:`~archrock.geometry.centreline._arc` evaluates them."""
    return (ARC, [cx, cy, r, th0, th1 - th0, -(th1 - th0) * r, (th1 - th0) * r])
