"""Irregular family and surveyed arches prepared as arrays: the ensemble's batch path for any
family and for a surveyed polygon arch (:mod:`archrock.geometry.surveybatch`).

:func:`prepare_family_batch` does what ``prepare_batch(sampler.arches(start, count))`` does
(:mod:`archrock.dynamics.batch`) without an arch object per sample: the draws' polylines, validity
checks, mass properties and joint contact segments come from the compiled
:func:`archrock.geometry.batchdraw.batch_properties`, the limit analysis sums are stacked from
them with :func:`archrock.statics.limit.arch_sums`'s arithmetic, and the enumeration, the four-link
loop and the impact laws are those of ``prepare_batch``.  Each row is that of the arch-object
path to the last bit; a draw the compiled checks do not certify (a check of
:class:`~archrock.geometry.PolygonArch` near its threshold, an arch far from the origin) is
built as its object, as are the rows whose lift-off or least-loss treatment needs one.

It falls back to the arch-object path without numba (the compiled drawing would run as slow
Python), for nominals with loads or fill (a surveyed arch: loads), and above
:data:`archrock.statics.limit.ENUMERATION_MAX_VOUSSOIRS` voussoirs (the guided search works on arch
objects).
"""

from __future__ import annotations

import time

import numpy as np

from ...dynamics.batch import (PreparedBatch, _finish, _lift_off_errors, _limit_errors,
                               _multipliers, _spec, prepare_batch)
from ...errors import InvalidSampleError
from ...geometry import power_of_two_near
from ..._device import resolve_device
from ..._jit import HAVE_NUMBA
from ...geometry.batchdraw import OK, REFUSED, batch_properties, compiled_drawing, family_plan, \
    refusal_message
from ...geometry.surveybatch import survey_plan, survey_properties, survey_refusal, \
    survey_supported
from ...statics.kinematic import ENUMERATION_MAX_VOUSSOIRS, _check_method, _full_enumeration
from ...statics.sums import arch_sums

__all__ = ["prepare_family_batch"]


def _row_error(exc) -> str:
    """A refused draw's reason (an invalid draw, :class:`~archrock.leftout.LeftOut`) as
    ``prepare_batch`` words an InvalidSampleError entry."""
    from ...leftout import LeftOut

    why = " ".join(str(exc).split())
    return LeftOut("invalid_draw", why if why.startswith("geometry:") else "geometry: " + why)


def prepare_family_batch(sampler, start: int, count: int, impact=None, cv=None, *,
                         nominal=None, parallel: bool = True,
                         device: str = "cpu") -> PreparedBatch:
    """``prepare_batch(sampler.arches(start, count), impact, cv, nominal=..., parallel=...,
    device=...)`` for a sampler around a family arch, computed as arrays (module docstring):
    the same PreparedBatch, row for row.  ``device``: where the four-hinge search and the
    four-link loop run ('cpu', 'gpu' or 'auto'; the drawing stays on the CPU)."""
    n = sampler.nominal.n
    survey = HAVE_NUMBA and survey_supported(sampler.nominal)
    if not (compiled_drawing(sampler) or survey) or n > ENUMERATION_MAX_VOUSSOIRS:
        return prepare_batch(sampler.arches(start, count), impact=impact, cv=cv,
                             nominal=nominal, parallel=parallel, device=device)
    t0 = time.perf_counter()
    spec = _spec(impact, cv, nominal)
    B = int(count)
    device = resolve_device(device, B)
    plan, bp = _draw(sampler, start, B, survey, parallel)
    areas, cen, polar, jp = bp["areas"], bp["centroids"], bp["polar"], bp["joint_points"]
    size = bp["size"].copy()
    # far from the origin, arch_sums would shift its moments: such rows go as objects
    far = (bp["state"] == OK) & ~(np.max(np.abs(jp), axis=(1, 2, 3)) <= 8.0 * size)
    state = np.where(far, -1, bp["state"])
    error, objects = _refused_and_objects(sampler, start, bp, state, survey)
    certified = state == OK
    ref = np.ones(B)
    ref[certified] = power_of_two_near(size[certified])
    sums = _stacked_sums(bp, certified, ref)
    mass = plan.density * areas
    inert = plan.density * polar
    for b, arch in objects.items():
        for k, arr in enumerate(arch_sums(arch)):
            sums[k][b] = arr[0]
        jp[b] = arch.joint_points
        mass[b], cen[b], inert[b] = arch.masses, arch.centroids, arch.inertias
        ref[b] = arch.reference_length
    sums = [np.ascontiguousarray(a) for a in sums]

    def arch_of(b):
        return objects[b] if b in objects else sampler.arch(int(start + b))

    k_l, k_r, cand_l, cand_r = _limit_rows(n, B, sums, error, arch_of, parallel, device)
    t1 = time.perf_counter()
    _fill_unusable(error == "", n, jp, mass, cen, inert, ref)
    px = np.ascontiguousarray(jp[..., 0])
    py = np.ascontiguousarray(jp[..., 1])
    return _finish(n, px, py, np.ascontiguousarray(mass), np.ascontiguousarray(cen),
                   np.ascontiguousarray(inert), ref, k_l, k_r, cand_l, cand_r, error, spec,
                   arch_of, t0, t1, parallel, device)


def _draw(sampler, start: int, B: int, survey: bool, parallel: bool) -> tuple:
    """(plan, properties) of the B arches drawn from ``start``: by the survey's compiled
    drawing where it applies, else by the family's."""
    if survey:
        plan = survey_plan(sampler.nominal)
        return plan, survey_properties(plan, sampler.uniforms(start, B), sampler.spreads,
                                       parallel)
    plan = family_plan(sampler.nominal)
    return plan, batch_properties(plan, sampler.uniforms(start, B), sampler.spreads, parallel)


def _refused_and_objects(sampler, start: int, bp: dict, state, survey: bool) -> tuple:
    """(error per row, {row: arch object}): a refused draw gets its reason; the other rows
    the arrays cannot take (state not OK) are built as objects (or refused by the sampler)."""
    error = np.full(len(state), "", dtype=object)
    objects = {}
    for b in np.flatnonzero(state != OK):
        if state[b] == REFUSED:
            why = survey_refusal(bp["index"][b]) if survey else \
                refusal_message(bp["code"][b], bp["index"][b], bp["side"][b])
            error[b] = _row_error(InvalidSampleError(f"not a valid arch: {why}"))
            continue
        try:
            objects[b] = sampler.arch(int(start + b))
        except InvalidSampleError as exc:
            error[b] = _row_error(exc)
    return error, objects


def _stacked_sums(bp: dict, certified, ref) -> list:
    """arch_sums of every row, stacked: weights per unit total area and their moments, and
    the joints' points, in units of ``ref``."""
    areas, cen, jp = bp["areas"], bp["centroids"], bp["joint_points"]
    B = len(ref)
    with np.errstate(all="ignore"):
        w = areas / np.where(certified, bp["area_sum"], 1.0)[:, None]
        g = cen / ref[:, None, None]
        zero = np.zeros((B, 1))
        return [np.concatenate([zero, np.cumsum(w, axis=1)], axis=1),
                np.concatenate([zero, np.cumsum(w * g[..., 0], axis=1)], axis=1),
                np.concatenate([zero, np.cumsum(w * g[..., 1], axis=1)], axis=1),
                jp[..., 0] / ref[:, None, None], jp[..., 1] / ref[:, None, None]]


def _limit_rows(n: int, B: int, sums: list, error, arch_of, parallel: bool,
                device: str = "cpu") -> tuple:
    """(k_l, k_r, cand_l, cand_r) of the rows without an error, by full enumeration (on
    ``device``, 'cpu' or 'gpu'); the rows whose limit analysis or lift-off check fails get
    their reason in ``error``."""
    ok = error == ""
    rows = np.flatnonzero(ok)
    max_seconds = _check_method("auto", None)
    k_l, k_r, cand_l, cand_r = _multipliers(
        B, ok, lambda: _full_enumeration(
            lambda s, e: tuple(np.ascontiguousarray(a[rows[s:e]]) for a in sums), rows.size, n,
            None, max_seconds, parallel=parallel, device=device))
    _limit_errors(k_l, k_r, ok, error, arch_of)
    _lift_off_errors(n, lambda r: tuple(np.ascontiguousarray(a[r]) for a in sums), arch_of,
                     k_l, k_r, cand_l, cand_r, error)
    return k_l, k_r, cand_l, cand_r


def _fill_unusable(ok, n: int, jp, mass, cen, inert, ref) -> None:
    """The rows not ``ok`` take a usable row's geometry (or the circular stand-in of
    prepare_batch when none is), so that the compiled preparation runs on every row."""
    if ok.any():
        safe = np.flatnonzero(ok)[0]
        fill = (jp[safe], mass[safe], cen[safe], inert[safe], ref[safe])
    else:  # nothing to prepare: the harmless circular stand-in of prepare_batch
        from ...geometry import nominal_arch

        a = nominal_arch(10.0, 157.5, 1.5, n)
        fill = (a.joint_points, a.masses, a.centroids, a.inertias, a.reference_length)
    bad = ~ok
    jp[bad], mass[bad], cen[bad], inert[bad], ref[bad] = fill
