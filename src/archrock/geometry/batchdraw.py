"""Irregular family arches drawn for a whole batch, compiled: no Python per arch.

:func:`~archrock.geometry.irregular.perturb_family` draws one irregular arch of a family in numpy
(arc-length inversion, offset lines, joint cuts) and :class:`~archrock.geometry.PolygonArch`
checks it and computes its mass properties: 6-20 ms per arch.  This module does the same
arithmetic, operation for operation, in scalar loops that numba compiles (or that run as Python
without it), for one arch or a batch of them over the numba threads:

* :class:`FamilyPlan`: what a nominal family arch's draws share (its centreline's pieces, their
  arc-length tables, the nominal division points), built once in Python;
* :func:`draw_lines`: one draw's intrados and extrados polylines, the numbers of
  ``perturb_family`` (its sums in numpy's pairwise order, ``math.dist`` as CPython computes it);
* :func:`batch_properties`: for a batch of draws, without building polylines in Python: whether
  each is a valid polygon arch (the checks of ``PolygonArch``), and its voussoirs' areas [m^2],
  centroids [m], polar moments [m^4], joint contact segments [m] and size [m], the numbers of
  ``PolygonArch`` built from the same polylines.

A draw is reported in one of three states (``state``): 0 a valid arch whose arrays are given, 1
the draw itself is refused (``perturb_family`` would raise: the reason is in ``code``, ``index``,
``side``), 2 not certified (a check of ``PolygonArch`` fails or lies near its threshold): the
caller builds the ``PolygonArch`` from :func:`draw_lines` and lets it decide.

The parts: :mod:`~archrock.geometry.batchplan` (the plan, states, refusals),
:mod:`~archrock.geometry.batchlines` (one draw's polylines) and
:mod:`~archrock.geometry.batchpolygon` (the polygon checks and mass properties); this module runs
them over a batch.

Nominals supported: a :class:`~archrock.geometry.FamilyArch` without loads and without fill
(:func:`supported`); other nominals go through ``perturb_family`` arch by arch.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import HAVE_NUMBA, maybe_njit, numba
from ..errors import ArchInputError
from .batchlines import _draw
from .batchplan import (OK, REFUSED, UNCERTIFIED, FamilyPlan, cached_plan, compiled_drawing,
                        family_plan, refusal_message, supported)
from .batchpolygon import _arch_arrays

__all__ = ["FamilyPlan", "supported", "family_plan", "cached_plan", "compiled_drawing",
           "draw_lines", "batch_properties", "refusal_message", "OK", "REFUSED", "UNCERTIFIED"]


@maybe_njit
def _batch_one(b, U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n,
               bounds, base_len, scal, state, code, where, side, areas, cen, polar, jp, size,
               asum):
    n = base_len.size
    c, i, sd, lines = _draw(U[b], sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s,
                            tab_v, tab_n, bounds, base_len, scal)
    if c != 0:
        state[b], code[b], where[b], side[b] = REFUSED, c, i, sd
        return
    ok, sz, tot = _arch_arrays(lines, n, scal[0], areas[b], cen[b], polar[b], jp[b])
    if ok:
        state[b], size[b], asum[b] = OK, sz, tot
    else:
        state[b] = UNCERTIFIED


def _batch_loop_py(U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n,
                   bounds, base_len, scal, state, code, where, side, areas, cen, polar, jp, size,
                   asum):
    for b in range(U.shape[0]):
        _batch_one(b, U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n,
                   bounds, base_len, scal, state, code, where, side, areas, cen, polar, jp, size,
                   asum)


if HAVE_NUMBA:
    @maybe_njit(parallel=True)
    def _batch_loop_nb(U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s,
                       tab_v, tab_n, bounds, base_len, scal, state, code, where, side, areas,
                       cen, polar, jp, size, asum):
        for b in numba.prange(U.shape[0]):
            _batch_one(b, U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v,
                       tab_n, bounds, base_len, scal, state, code, where, side, areas, cen,
                       polar, jp, size, asum)

    _batch_loop_serial = maybe_njit(_batch_loop_py)
else:  # pragma: no cover - without numba
    _batch_loop_nb = _batch_loop_serial = _batch_loop_py


# ---------------------------------------------------------------------------- entry points
def _spread_args(u, spreads):
    u = np.ascontiguousarray(u, dtype=float)
    return u, float(spreads.span), float(spreads.thickness), float(spreads.radius), \
        (math.radians(spreads.tilt) if spreads.tilt else 0.0)


def draw_lines(plan: FamilyPlan, u, spreads):
    """One draw: (intrados, extrados) tuples of polylines (k, 2) [m] of ``perturb_family(
    plan.nominal, u, ...)``, or the :class:`~archrock.errors.ArchInputError` it would raise.
    ``u``: (3, n) or (4, n) uniforms; ``spreads``: a
    :class:`~archrock.geometry.sampling.Spreads`."""
    u, sa, st, sr, tilt = _spread_args(u, spreads)
    n = plan.n
    if u.ndim != 2 or u.shape[0] not in (3, 4) or u.shape[1] != n:
        raise ArchInputError(f"u: shape {u.shape}; allowed (3, {n}) or (4, {n})")
    c, i, sd, lines = _draw(u, sa, st, sr, tilt, *plan.args())
    if c != 0:
        return ArchInputError(refusal_message(c, i, sd))
    lines = list(lines)
    return tuple(lines[0::2]), tuple(lines[1::2])


def batch_properties(plan: FamilyPlan, U, spreads, parallel: bool = True) -> dict:
    """Draws ``U`` (B, rows, n) of the plan's nominal with ``spreads``, as arrays (module
    docstring): state (B,), code / index / side of refused draws, areas (B, n) [m^2],
    centroids (B, n, 2) [m], polar (B, n) [m^4], joint_points (B, n + 1, 2, 2) [m], size (B,)
    [m] and area_sum (B,) [m^2] (numpy's sum of the row's areas); rows not in state 0 hold
    garbage there.  ``parallel``: over the numba threads (the same numbers)."""
    U, sa, st, sr, tilt = _spread_args(U, spreads)
    B, n = U.shape[0], plan.n
    out = {"state": np.full(B, UNCERTIFIED, dtype=np.int64), "code": np.zeros(B, np.int64),
           "index": np.zeros(B, np.int64), "side": np.zeros(B, np.int64),
           "areas": np.zeros((B, n)), "centroids": np.zeros((B, n, 2)), "polar": np.zeros((B, n)),
           "joint_points": np.zeros((B, n + 1, 2, 2)), "size": np.zeros(B),
           "area_sum": np.zeros(B)}
    loop = (_batch_loop_nb if parallel else _batch_loop_serial) if HAVE_NUMBA else _batch_loop_py
    loop(U, sa, st, sr, tilt, *plan.args(), out["state"], out["code"], out["index"], out["side"],
         out["areas"], out["centroids"], out["polar"], out["joint_points"], out["size"],
         out["area_sum"])
    return out
