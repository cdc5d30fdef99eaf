"""Irregular arches around a surveyed polygon arch, drawn as arrays for a whole batch.

:func:`~archrock.geometry.survey.perturb_survey` moves every point of voussoir i's faces along a
direction d fixed by the surveyed joints, by an amount that depends on the draw only through two
numbers (its thickness and offset draws): point = line + (amount * t) * d, with the line, the
length t and the direction d the nominal's.  :class:`SurveyPlan` keeps line, t and d of every face
once; :func:`survey_properties` applies the draws of a batch and computes each arch's checks,
mass properties and joint segments with the compiled checks of
:func:`archrock.geometry.batchpolygon._arch_arrays` (those of ``PolygonArch``, with margins), no
Python per arch.  The arithmetic is perturb_survey's, operation for operation, so each certified
row is that of the arch object to the last bit; a draw the compiled checks do not certify goes
back to the arch object (:mod:`archrock.studies.ensemble.familybatch`).
"""

from __future__ import annotations

import numpy as np

from .._jit import HAVE_NUMBA, maybe_njit, numba
from ..errors import ArchInputError
from .batchplan import OK, REFUSED, UNCERTIFIED, cached_plan
from .batchpolygon import _arch_arrays
from .survey import _fractions, is_survey, joint_frames

__all__ = ["SurveyPlan", "survey_supported", "survey_plan", "survey_properties",
           "survey_refusal"]


def survey_supported(nominal) -> bool:
    """Whether ``nominal`` is drawn by this module: a surveyed polygon arch without loads."""
    return is_survey(nominal) and not nominal.loads


def survey_refusal(index: int) -> str:
    """perturb_survey's refusal of voussoir ``index`` (its ArchInputError's words)."""
    return f"geometry: voussoir {index}'s offset exceeds half its thickness"


class SurveyPlan:
    """Each face's nominal points, lengths t and directions d (module docstring), as flat
    arrays: face 2 i is voussoir i's intrados, 2 i + 1 its extrados, points start[f] to
    start[f + 1] - 1."""

    def __init__(self, nominal):
        if not survey_supported(nominal):
            raise ArchInputError("nominal: the batch drawing of surveyed arches takes a polygon "
                                 "arch without a family recipe and without loads")
        self.nominal = nominal
        n = self.n = nominal.n
        t, d, a0, turn = joint_frames(nominal)
        base, thick, direc, start = [], [], [], [0]
        for i in range(n):
            for line in (nominal.intrados[i], nominal.extrados[i]):
                s = _fractions(line)
                ang = a0[i] + s * turn[i]
                dd = np.column_stack([np.cos(ang), np.sin(ang)])
                dd[0], dd[-1] = d[i], d[i + 1]
                base.append(line)
                thick.append((1.0 - s) * t[i] + s * t[i + 1])
                direc.append(dd)
                start.append(start[-1] + len(line))
        self.base = np.ascontiguousarray(np.vstack(base))
        self.thick = np.ascontiguousarray(np.concatenate(thick))
        self.direc = np.ascontiguousarray(np.vstack(direc))
        self.start = np.array(start, dtype=np.int64)
        pts = np.vstack(base)
        # the margin scale of the compiled simplicity check: the drawing's extent
        self.scale = float(np.max(np.ptp(pts, axis=0)))
        self.density = nominal.density

    def args(self):
        return self.base, self.thick, self.direc, self.start, self.scale


_PLANS: list = []


def survey_plan(nominal) -> SurveyPlan:
    """The :class:`SurveyPlan` of ``nominal``, kept for reuse (batchdraw.cached_plan)."""
    return cached_plan(_PLANS, nominal, SurveyPlan)


@maybe_njit
def _draw(u, st, so, base, thick, direc, start):
    """One draw: (refused voussoir or -1, the 2 n face polylines)."""
    n = (start.size - 1) // 2
    lines = [np.empty((0, 2)) for _ in range(0)]
    for i in range(n):
        half = 0.5 * st * u[1, i]
        off = so * u[2, i]
        if 2.0 * abs(off) >= 1.0 + 2.0 * half or 1.0 + 2.0 * half <= 0.0:
            return i, lines
        for f, amount in ((2 * i, off - half), (2 * i + 1, off + half)):
            a, b = start[f], start[f + 1]
            line = np.empty((b - a, 2))
            for q in range(a, b):
                w = amount * thick[q]
                line[q - a, 0] = base[q, 0] + w * direc[q, 0]
                line[q - a, 1] = base[q, 1] + w * direc[q, 1]
            lines.append(line)
    return -1, lines


@maybe_njit
def _one(b, U, st, so, base, thick, direc, start, scale, state, index, areas, cen, polar, jp,
         size, asum):
    i, lines = _draw(U[b], st, so, base, thick, direc, start)
    if i >= 0:
        state[b], index[b] = REFUSED, i
        return
    n = (start.size - 1) // 2
    ok, sz, tot = _arch_arrays(lines, n, scale, areas[b], cen[b], polar[b], jp[b])
    if ok:
        state[b], size[b], asum[b] = OK, sz, tot
    else:
        state[b] = UNCERTIFIED


def _loop_py(U, st, so, base, thick, direc, start, scale, state, index, areas, cen, polar, jp,
             size, asum):
    for b in range(U.shape[0]):
        _one(b, U, st, so, base, thick, direc, start, scale, state, index, areas, cen, polar, jp,
             size, asum)


if HAVE_NUMBA:
    @maybe_njit(parallel=True)
    def _loop_nb(U, st, so, base, thick, direc, start, scale, state, index, areas, cen, polar,
                 jp, size, asum):
        for b in numba.prange(U.shape[0]):
            _one(b, U, st, so, base, thick, direc, start, scale, state, index, areas, cen,
                 polar, jp, size, asum)

    _loop_serial = maybe_njit(_loop_py)
else:  # pragma: no cover - without numba
    _loop_nb = _loop_serial = _loop_py


def survey_lines(plan: SurveyPlan, u, spreads):
    """One draw's (intrados, extrados) polylines, or perturb_survey's ArchInputError."""
    u = np.ascontiguousarray(u, dtype=float)
    if u.ndim != 2 or u.shape[0] not in (3, 4) or u.shape[1] != plan.n:
        raise ArchInputError(f"u: shape {u.shape}; allowed (3, {plan.n}) or (4, {plan.n})")
    i, lines = _draw(u, float(spreads.thickness), float(spreads.radius), *plan.args()[:4])
    if i >= 0:
        return ArchInputError(survey_refusal(i))
    lines = list(lines)
    return tuple(lines[0::2]), tuple(lines[1::2])


def survey_properties(plan: SurveyPlan, U, spreads, parallel: bool = True) -> dict:
    """Draws ``U`` (B, rows, n) around the plan's surveyed arch with ``spreads`` (thickness and
    radius used), as :func:`archrock.geometry.batchdraw.batch_properties` gives them for a
    family: state (B,), the refused voussoir in ``index``, areas, centroids, polar,
    joint_points, size and area_sum (rows not in state OK hold garbage there).  With pier
    spreads every row is UNCERTIFIED: its arch is drawn as an object."""
    U = np.ascontiguousarray(U, dtype=float)
    B, n = U.shape[0], plan.n
    out = {"state": np.full(B, UNCERTIFIED, dtype=np.int64), "index": np.zeros(B, np.int64),
           "areas": np.zeros((B, n)), "centroids": np.zeros((B, n, 2)), "polar": np.zeros((B, n)),
           "joint_points": np.zeros((B, n + 1, 2, 2)), "size": np.zeros(B),
           "area_sum": np.zeros(B)}
    if getattr(spreads, "piers", False):
        # irregular piers (a lean, a width ...) are drawn on the arch objects
        # (ArchSampler.arch): every row is left uncertified and goes back to them
        return out
    loop = (_loop_nb if parallel else _loop_serial) if HAVE_NUMBA else _loop_py
    loop(U, float(spreads.thickness), float(spreads.radius), *plan.args(), out["state"],
         out["index"], out["areas"], out["centroids"], out["polar"], out["joint_points"],
         out["size"], out["area_sum"])
    return out
