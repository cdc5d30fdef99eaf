"""Many arches at once: batch preparation (limit analysis -> four-link models -> impact law) and a
parallel loop of the single-response kernel :func:`archrock.dynamics.kernel.simulate_chain`.

* the random arches themselves come from :class:`archrock.geometry.sampling.ArchSampler`.
* :func:`prepare_batch` does for a whole batch what :func:`archrock.dynamics.response.prepare` does for one
  arch: limit analysis of all arches at once (:func:`archrock.statics.limit.kinematic_multipliers_batch`),
  then, per arch, the flat four-link vectors ``geo`` of M_l and M_r (the same numbers as
  ``four_link(arch, mechanism).geo``), the unstable rotations, the rotation limits
  (``FourLink.default_limit``), ``v_rest`` and the impact law.  The geometric part is compiled by
  numba (about 0.1 ms per arch instead of about 4 ms through ``prepare``); the per-geometry impact
  models "paper" and "momentum" go through :func:`archrock.dynamics.impact.impact_law` arch by arch, and
  "least-loss" builds each arch's chain of mechanisms with :func:`archrock.dynamics.response.prepare`.
  Every arch carries its chain (padded to the batch's longest; the paper's alternation is the
  two rows M_l, M_r).  Arches that cannot be used (invalid geometry, no mechanism, an impact
  model that creates energy) are not dropped: their ``error`` holds the reason.
* :func:`simulate_batch` (:mod:`archrock.dynamics.batchsim`) integrates one ground motion for
  every prepared arch with a numba ``prange`` loop over arches (no output samples,
  ``n_out = 1``), returning per-arch summaries: status, peak, t_collapse (the last upward
  passage of phi_u before the rotation limit), t_limit (when the limit, a numerical stop, was
  reached), t_unstable (the first passage of phi_u), number of impacts and of activations, and
  whether the event table overflowed (``events_truncated``: the outcome and the counts of impacts
  and activations are still complete).  Without numba the same loop runs in Python.
"""

from __future__ import annotations

import math
import time

import numpy as np

from .._device import check_device, resolve_device
from .._jit import HAVE_NUMBA, maybe_njit, numba
from ..errors import ArchInputError, ArchrockError
from ..leftout import LeftOut
from .impact import ImpactSpec, fallback_note
from ..geometry import Arch, power_of_two_near, sector_properties
from ..groundmotion import G
from ..statics.hinges import _mechanism_from_candidate, candidate_hinges
from ..statics.kinematic import kinematic_multipliers_arches, kinematic_multipliers_batch
from ..statics.liftoff import LIFT_OFF_REASON, certify_candidates
from ..statics.lp import static_multiplier
from ..statics.sums import _batch_sums, arch_sums
from .chain import pack_chains
from .prepared import PreparedBatch
from .finite import any_finite
# the batch's response loop is a module of its own; its names stay importable from here
from .batchsim import MAX_EVENTS, ST_NOT_RUN, STATUS_NAMES, simulate_batch
from .fourbar import (GEO_ERRORS, GEO_SIZE, coefficients, dead_point, mechanism_geo,
                      rest_rate, rotation_limit, table_range, unstable_rotation)

__all__ = ["PreparedBatch", "check_geometries", "prepare_batch", "simulate_batch",
           "mechanism_label", "STATUS_NAMES", "ST_NOT_RUN", "MAX_EVENTS"]


# ---------------------------------------------------------------------------- random geometry


def check_geometries(spans, radii, thick) -> np.ndarray:
    """Per-arch reason why the geometry is invalid ('' when valid), object array (B,)."""
    B = spans.shape[0]
    err = np.full(B, "", dtype=object)
    ri, ro = radii - thick / 2, radii + thick / 2
    bad_span = np.any(~(spans > 0), axis=1)
    bad_t = np.any(~((thick > 0) & (thick < 2 * radii)), axis=1)
    no_overlap = np.any(np.maximum(ri[:, :-1], ri[:, 1:]) >= np.minimum(ro[:, :-1], ro[:, 1:]), axis=1)
    for b in np.flatnonzero(bad_span | bad_t | no_overlap):
        if bad_span[b]:
            err[b] = LeftOut("invalid_draw", "geometry: a voussoir span is <= 0")
        elif bad_t[b]:
            err[b] = LeftOut("invalid_draw", "geometry: a thickness is outside 0 < t < 2 R")
        else:
            err[b] = LeftOut("invalid_draw", "geometry: two neighbouring voussoirs do not overlap "
                                             "radially")
    return err


def mechanism_label(n: int, candidate: int) -> str:
    """Compact label of a kinematic candidate: joints from the left springing with their edge,
    e.g. '0i-3e-5i-7e' (i = intrados, e = extrados): :attr:`archrock.statics.limit.Mechanism.label`."""
    return _mechanism_from_candidate(n, candidate, "l", math.nan).label


# ---------------------------------------------------------------------------- compiled geometry


@maybe_njit
def _prepare_one(b, px, py, mass, cen, inert, jl, el, jr, er, geo_l, geo_r, phu_l, phu_r, lim_l,
                 lim_r, m0_l, m0_r, v_rest, err_l, err_r, tab_l, tab_r):
    """Four-link vectors, unstable rotations, limits, table ranges and v_rest of arch b."""
    err_l[b] = mechanism_geo(px[b], py[b], mass[b], cen[b], inert[b], jl[b], el[b], False,
                             geo_l[b])
    err_r[b] = mechanism_geo(px[b], py[b], mass[b], cen[b], inert[b], jr[b], er[b], True,
                             geo_r[b])
    if err_l[b] != 0 or err_r[b] != 0:
        return
    for side in range(2):
        geo = geo_l[b] if side == 0 else geo_r[b]
        dead = dead_point(geo)
        phu = unstable_rotation(geo, dead)
        lim = rotation_limit(phu, dead)
        start, top = table_range(geo, lim, dead)
        M0 = coefficients(0.0, geo)[0]
        if side == 0:
            phu_l[b], lim_l[b], m0_l[b] = phu, lim, M0
            tab_l[b, 0], tab_l[b, 1] = start, top
        else:
            phu_r[b], lim_r[b], m0_r[b] = phu, lim, M0
            tab_r[b, 0], tab_r[b, 1] = start, top
    v_rest[b] = rest_rate(geo_l[b], phu_l[b], phu_r[b], G)


def _prepare_loop_py(px, py, mass, cen, inert, jl, el, jr, er, ok, geo_l, geo_r, phu_l, phu_r,
                     lim_l, lim_r, m0_l, m0_r, v_rest, err_l, err_r, tab_l, tab_r):
    for b in range(px.shape[0]):
        if ok[b]:
            _prepare_one(b, px, py, mass, cen, inert, jl, el, jr, er, geo_l, geo_r, phu_l, phu_r,
                         lim_l, lim_r, m0_l, m0_r, v_rest, err_l, err_r, tab_l, tab_r)


if HAVE_NUMBA:
    @maybe_njit(parallel=True)
    def _prepare_loop_nb(px, py, mass, cen, inert, jl, el, jr, er, ok, geo_l, geo_r, phu_l,
                         phu_r, lim_l, lim_r, m0_l, m0_r, v_rest, err_l, err_r, tab_l, tab_r):
        for b in numba.prange(px.shape[0]):
            if ok[b]:
                _prepare_one(b, px, py, mass, cen, inert, jl, el, jr, er, geo_l, geo_r, phu_l,
                             phu_r, lim_l, lim_r, m0_l, m0_r, v_rest, err_l, err_r, tab_l, tab_r)

    _prepare_loop = maybe_njit(_prepare_loop_py)
else:  # pragma: no cover - without numba
    _prepare_loop = _prepare_loop_py
    _prepare_loop_nb = None


# ---------------------------------------------------------------------------- preparation
_NOT_CIRCULAR = ("the array form takes circular arches only, as arrays (B, n) of spans, radii "
                 "and thicknesses; give arches of any shape as one sequence of VoussoirArch "
                 "objects alone: prepare_batch(arches)")


def _circular_rows(name: str, values) -> np.ndarray:
    """``values`` as a contiguous float array (B, n); anything else (arch objects, polylines of
    polygon voussoirs) is refused with a clear message instead of a numpy error."""
    from ..geometry import VoussoirArch

    items = values if isinstance(values, (list, tuple)) else [values]
    if any(isinstance(v, VoussoirArch) for v in items):
        raise ArchInputError(f"{name}: got an arch object; {_NOT_CIRCULAR}")
    try:
        arr = np.ascontiguousarray(np.atleast_2d(values), dtype=float)
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: expected numbers; {_NOT_CIRCULAR}") from None
    if arr.ndim != 2:
        raise ArchInputError(f"{name}: shape {arr.shape} (points of polygon voussoirs?); "
                             f"{_NOT_CIRCULAR}")
    return arr


def _is_arch_sequence(values) -> bool:
    from ..geometry import VoussoirArch

    if isinstance(values, VoussoirArch):
        return True
    return isinstance(values, (list, tuple)) and len(values) > 0 and all(
        isinstance(v, (VoussoirArch, ArchrockError)) for v in values)


def prepare_batch(spans, radii=None, thicknesses=None, density: float = 2000.0, impact=None,
                  cv: float | None = None, *, nominal=None, parallel: bool = True,
                  device: str = "cpu") -> PreparedBatch:
    """Limit analysis, four-link models, rotation limits and impact law of a batch of arches.

    Either spans [rad], radii [m], thicknesses [m]: arrays (B, n) with the same n (circular
    arches), or ``spans`` alone a sequence of B arches of any shape (:class:`VoussoirArch`) with
    the same n: an entry may be an :class:`~archrock.errors.ArchrockError` instead (e.g. the
    ``InvalidSampleError`` of :meth:`archrock.geometry.sampling.ArchSampler.arches`), which becomes that
    row's error.  Arches are analysed by :func:`archrock.statics.limit.kinematic_multipliers_arches`
    (the enumeration over their stacked sums, or the guided search above 40 voussoirs); their
    joint points, masses, centroids and inertias (with loads) feed the same compiled four-link
    loop, and ``density`` is then unused (each arch has its own).  impact: an
    :class:`~archrock.dynamics.impact.ImpactSpec` or what ``ImpactSpec.parse`` reads (with ``cv``), as
    for :func:`archrock.dynamics.response.prepare`: a fixed c_v (applied energy-consistently, c = cv
    sqrt(M_old(0)/M_new(0)), or to the rates with ``literal``, docs/method.md, Impact), "paper" or
    "momentum" (per geometry, compiled for the whole batch by
    :func:`archrock.dynamics.impact.compiled.rate_ratios_batch`, the numbers of
    :func:`archrock.dynamics.impact.impact_law`; a geometry on which "paper" creates energy gets an error
    instead of a law, or the momentum law under a spec with ``fallback``, as the default's: its
    ``impact_fallback`` says why), or "least-loss" (each arch's chain of mechanisms from
    ``archrock.dynamics.response.prepare(arch, "least-loss")``, arch by arch in Python: about 0.1 s
    each).  A spec evaluated on the nominal arch needs ``nominal`` (an Arch).
    ``parallel``: the limit analysis, the four-link loop and the impact laws spread the arches
    over the numba threads (the results do not depend on it); False for process-pool or Dask
    workers, which run one batch each.
    ``device``: 'cpu', 'gpu' or 'auto' (:func:`archrock._device.resolve_device`): on 'gpu' the
    four-hinge search and the four-link loop run one arch per GPU thread
    (:mod:`archrock.dynamics.gpubatch`); the lift-off check, the impact laws and the rows with
    an error stay on the CPU.  Arches of finite strength are prepared on the CPU.
    Arch objects together with radii/thicknesses arrays, or polylines as arrays, are refused with
    an :class:`~archrock.errors.ArchInputError`.
    """
    t0 = time.perf_counter()
    check_device(device)
    if radii is None and thicknesses is None and _is_arch_sequence(spans):
        return _prepare_arches(spans, impact, cv, nominal, t0, parallel, device)
    if radii is None or thicknesses is None:
        raise ArchInputError(f"radii, thicknesses: needed with arrays of spans; {_NOT_CIRCULAR}")
    spans, radii, thick = (_circular_rows(name, v) for name, v in (
        ("spans", spans), ("radii", radii), ("thicknesses", thicknesses)))
    spec = _spec(impact, cv, nominal)
    B, n = spans.shape
    device = resolve_device(device, B)
    error = check_geometries(spans, radii, thick)
    ok = error == ""
    k_l, k_r, cand_l, cand_r = _multipliers(
        B, ok, lambda: kinematic_multipliers_batch(spans[ok], radii[ok], thick[ok],
                                                   parallel=parallel, fallback=False,
                                                   device=device))
    _limit_errors(k_l, k_r, ok, error, lambda b: Arch(spans[b], radii[b], thick[b], density))
    _lift_off_errors(n, lambda rows: _batch_sums(spans[rows], radii[rows], thick[rows])[:5],
                     lambda b: Arch(spans[b], radii[b], thick[b], density), k_l, k_r, cand_l,
                     cand_r, error)
    ok = error == ""
    t1 = time.perf_counter()
    # geometry of the voussoirs (invalid rows replaced by a harmless copy of a valid one)
    safe = np.flatnonzero(ok)[0] if ok.any() else None
    s_, r_, t_ = spans.copy(), radii.copy(), thick.copy()
    if safe is not None:
        s_[~ok], r_[~ok], t_[~ok] = spans[safe], radii[safe], thick[safe]
    else:
        s_[:], r_[:], t_[:] = 1.0 / n, 1.0, 0.1
    p = sector_properties(s_, r_, t_)
    rr = np.stack([p["r_in"], p["r_out"]], axis=-1)
    px = np.ascontiguousarray(rr * np.cos(p["psi"])[..., None])
    py = np.ascontiguousarray(rr * np.sin(p["psi"])[..., None])
    mass = np.ascontiguousarray(density * p["area"])
    cen = np.ascontiguousarray(p["centroid"])
    inert = np.ascontiguousarray(density * p["polar"])
    # Arch.reference_length of each row: the power of two nearest its mean radius
    ref = np.asarray(power_of_two_near(np.mean(r_, axis=1)), float).reshape(B)
    return _finish(n, px, py, mass, cen, inert, ref, k_l, k_r, cand_l, cand_r, error, spec,
                   lambda b: Arch(spans[b], radii[b], thick[b], density), t0, t1, parallel,
                   device)


def _spec(impact, cv, nominal):
    spec = ImpactSpec.parse(impact, cv=cv).resolved(nominal)
    if spec.on == "nominal":
        raise ArchInputError("nominal: the impact is evaluated on the nominal arch; give it "
                             "(nominal=Arch) or resolve the spec first")
    return spec


def _multipliers(B: int, ok, compute):
    """(k_l, k_r, candidate_l, candidate_r), each (B,): ``compute()`` gives them for the usable
    rows ``ok`` (NaN and 0 elsewhere)."""
    k_l = np.full(B, np.nan)
    k_r = np.full(B, np.nan)
    cand_l = np.zeros(B, dtype=np.int64)
    cand_r = np.zeros(B, dtype=np.int64)
    if ok.any():
        kl, kr, il, ir = compute()
        k_l[ok], k_r[ok], cand_l[ok], cand_r[ok] = kl, kr, il, ir
    return k_l, k_r, cand_l, cand_r


def _limit_errors(k_l, k_r, ok, error, arch_of):
    """Rows whose multipliers say the arch has no four-hinge mechanism (+inf) or cannot stand
    (k <= 0; -inf from the static-guided search: no line of thrust at any horizontal load).
    An inf row whose static LP is bounded in that direction is governed by a mechanism with
    lift-off (:data:`~archrock.statics.limit.LIFT_OFF_REASON`, its k the LP's); unbounded, nothing
    loads that direction."""
    for b in np.flatnonzero(ok & ((k_l == np.inf) | (k_r == np.inf))):
        error[b] = LeftOut("no_mechanism", "limit analysis: no admissible four-hinge mechanism")
        arch = arch_of(b)
        lift = False
        for d, k in (("l", k_l), ("r", k_r)):
            if k[b] == np.inf:
                try:
                    lam = static_multiplier(arch, d)[0]
                except ArchrockError:  # unbounded or infeasible: the message above stands
                    continue
                k[b], lift = lam, True
        if lift:
            error[b] = LeftOut("lift_off", LIFT_OFF_REASON)
    for b in np.flatnonzero(ok & (k_l < np.inf) & (k_r < np.inf) & ((k_l <= 0) | (k_r <= 0))):
        error[b] = LeftOut("cannot_stand", f"limit analysis: the arch cannot stand "
                                           f"(k_l = {k_l[b]:.4g}, k_r = {k_r[b]:.4g})")


def _lift_off_errors(n: int, sums_of, arch_of, k_l, k_r, cand_l, cand_r, error) -> None:
    """Rows whose best four-hinge mechanism does not govern (the line of thrust through its
    hinges leaves the arch: a mechanism with lift-off has a smaller multiplier) get
    :data:`~archrock.statics.limit.LIFT_OFF_REASON` (the four-link model is not integrated for them)
    and, in k_l / k_r, the Heyman multiplier of that direction (the static LP's optimum, one
    linear program per such row and direction).  ``sums_of(rows)``: the
    :func:`~archrock.statics.limit.arch_sums` of those rows, stacked; ``arch_of(b)``: row b's arch."""
    rows = np.flatnonzero(error == "")
    if rows.size == 0:
        return
    gov_l, gov_r = certify_candidates(sums_of(rows), n, cand_l[rows], cand_r[rows])
    for b, gl, gr in zip(rows, gov_l, gov_r):
        if gl and gr:
            continue
        error[b] = LeftOut("lift_off", LIFT_OFF_REASON)
        arch = arch_of(b)
        for d, governs, k in (("l", gl, k_l), ("r", gr, k_r)):
            if not governs:
                try:
                    k[b] = static_multiplier(arch, d)[0]
                except ArchrockError:  # the error row says why; the k is then not known
                    k[b] = np.nan


def _prepare_arches(arches, impact, cv, nominal, t0, parallel=True,
                    device="cpu") -> PreparedBatch:
    """prepare_batch of a sequence of arches of any shape (see there)."""
    from ..geometry import VoussoirArch

    items = [arches] if isinstance(arches, VoussoirArch) else list(arches)
    spec = _spec(impact, cv, nominal)
    if any_finite(items):  # finite strength: the conic statics, arch by arch (dynamics.finite)
        return _prepare_finite(items, spec, t0)
    B = len(items)
    device = resolve_device(device, B)
    good = [b for b, a in enumerate(items) if isinstance(a, VoussoirArch)]
    if not good:
        n = 3
    else:
        n = items[good[0]].n
        if any(items[b].n != n for b in good):
            raise ArchInputError("arches: different numbers of voussoirs; allowed one n per batch")
    error = np.full(B, "", dtype=object)
    for b, a in enumerate(items):
        if not isinstance(a, VoussoirArch):
            why = " ".join(str(a).split())
            # an arch refused before the batch (a draw, or one that cannot stand on moved
            # supports): its own reason, worded as a geometry
            error[b] = LeftOut.read(why if why.startswith("geometry:") else "geometry: " + why)
    ok = error == ""
    k_l, k_r, cand_l, cand_r = _multipliers(
        B, ok, lambda: kinematic_multipliers_arches([items[b] for b in good], parallel=parallel,
                                                    fallback=False, device=device))
    _limit_errors(k_l, k_r, ok, error, lambda b: items[b])
    _lift_off_errors(n, lambda rows: tuple(np.concatenate(parts) for parts in zip(
        *(arch_sums(items[b]) for b in rows))), lambda b: items[b], k_l, k_r, cand_l, cand_r,
        error)
    ok = error == ""
    t1 = time.perf_counter()
    safe = np.flatnonzero(ok)[0] if ok.any() else None
    if safe is None:  # nothing to prepare: a harmless circular stand-in for the loop's shapes
        from ..geometry import nominal_arch

        stand_in = nominal_arch(10.0, 157.5, 1.5, n)
    else:
        stand_in = items[safe]
    rows = [items[b] if ok[b] else stand_in for b in range(B)]
    jp = np.stack([np.asarray(a.joint_points, float) for a in rows])
    px = np.ascontiguousarray(jp[..., 0])
    py = np.ascontiguousarray(jp[..., 1])
    mass = np.ascontiguousarray(np.stack([np.asarray(a.masses, float) for a in rows]))
    cen = np.ascontiguousarray(np.stack([np.asarray(a.centroids, float) for a in rows]))
    inert = np.ascontiguousarray(np.stack([np.asarray(a.inertias, float) for a in rows]))
    ref = np.array([a.reference_length for a in rows], dtype=float)
    return _finish(n, px, py, mass, cen, inert, ref, k_l, k_r, cand_l, cand_r, error, spec,
                   lambda b: items[b], t0, t1, parallel, device)


def _hinge_arrays(n, cand):
    """Joints and edges (B, 4) of candidates ``cand`` (B,), and their compact labels (B,):
    unranked once per distinct candidate (a batch has a few dozen), then gathered."""
    uniq, inv = np.unique(cand, return_inverse=True)
    inv = inv.reshape(-1)
    joints = np.empty((uniq.size, 4), dtype=np.int64)
    edges = np.empty((uniq.size, 4), dtype=np.int64)
    labels = np.empty(uniq.size, dtype=object)
    for u, c in enumerate(uniq.tolist()):
        joints[u], edges[u] = candidate_hinges(n, c)
        labels[u] = mechanism_label(n, c)
    return joints[inv], edges[inv], labels[inv]


def _finish(n, px, py, mass, cen, inert, ref, k_l, k_r, cand_l, cand_r, error, spec, arch_of, t0,
            t1, parallel=True, device="cpu") -> PreparedBatch:
    """The four-link models, rotation limits, tables and impact law of a batch whose limit
    analysis is done (both paths); ``arch_of(b)`` the arch object of row b (least-loss only),
    ``ref`` (B,) each arch's reference length [m]."""
    impact, cv = spec.model, spec.cv
    B = error.size
    ok = error == ""
    # hinges of each arch's two mechanisms, unranked from the candidate indices (the candidate
    # list itself is never built: 14 C(n+1, 4) entries)
    jl, el, lab_l = _hinge_arrays(n, cand_l)
    jr, er, lab_r = _hinge_arrays(n, cand_r)
    geo_l = np.full((B, GEO_SIZE), np.nan)
    geo_r = np.full((B, GEO_SIZE), np.nan)
    out = {name: np.full(B, np.nan) for name in
           ("phu_l", "phu_r", "lim_l", "lim_r", "m0_l", "m0_r", "v_rest")}
    err_l = np.zeros(B, dtype=np.int64)
    err_r = np.zeros(B, dtype=np.int64)
    tab_l = np.full((B, 2), np.nan)
    tab_r = np.full((B, 2), np.nan)
    loop_args = (px, py, mass, cen, inert, jl, el, jr, er)
    outs = (geo_l, geo_r, out["phu_l"], out["phu_r"], out["lim_l"], out["lim_r"], out["m0_l"],
            out["m0_r"], out["v_rest"], err_l, err_r, tab_l, tab_r)
    try:
        if device == "gpu" or (parallel and _prepare_loop_nb is not None):
            try:
                if device == "gpu":
                    from .gpubatch import prepare_gpu

                    prepare_gpu(_prepare_one, loop_args, ok, outs)
                else:
                    _prepare_loop_nb(*loop_args, ok, *outs)
            except (ZeroDivisionError, FloatingPointError, SystemError):
                # an exception inside prange may surface as SystemError ("returned a result
                # with an exception set"): the serial per-arch pass below finds the culprits
                # (and re-raises anything else)
                raise ZeroDivisionError from None
            # inside prange (or a GPU thread) a division by zero gives inf/nan instead of
            # ZeroDivisionError: the
            # rows with a non-finite result are redone by the serial loop, which raises as the
            # one-arch path does (and is the reference for every row anyway)
            done = ok & (err_l == 0) & (err_r == 0)
            finite = (np.isfinite(geo_l).all(axis=1) & np.isfinite(geo_r).all(axis=1)
                      & np.isfinite(tab_l).all(axis=1) & np.isfinite(tab_r).all(axis=1))
            for v in out.values():
                finite &= np.isfinite(v)
            redo = done & ~finite
            if redo.any():
                _prepare_loop(*loop_args, redo, *outs)
        else:
            _prepare_loop(*loop_args, ok, *outs)
    except (ZeroDivisionError, FloatingPointError):
        # a degenerate four-bar somewhere: redo arch by arch and record the culprits
        for b in np.flatnonzero(ok):
            only = np.zeros(B, dtype=bool)
            only[b] = True
            try:
                _prepare_loop(*loop_args, only, *outs)
            except (ZeroDivisionError, FloatingPointError):
                error[b] = LeftOut("four_link_not_applicable",
                                   "four-link model: degenerate four-bar (division by zero)")
        ok = error == ""
    mech_l = np.where(ok, lab_l, "").astype(object)
    mech_r = np.where(ok, lab_r, "").astype(object)
    for b in np.flatnonzero(ok & ((err_l != 0) | (err_r != 0))):
        code, m = (err_l[b], "M_l " + mech_l[b]) if err_l[b] != 0 else (err_r[b], "M_r " + mech_r[b])
        error[b] = LeftOut("four_link_not_applicable", GEO_ERRORS[int(code)].format(m=m))
    ok = error == ""
    t2 = time.perf_counter()
    c_lr = np.full(B, np.nan)
    c_rl = np.full(B, np.nan)
    # why a row's law is the fallback's ('' where it is the law asked for): a fixed c_v
    # resolved on a nominal arch that fell back carries its note to every row
    fallback = np.full(B, spec.note or "", dtype=object)
    if impact == "fixed" and spec.literal:
        c_lr[ok] = c_rl[ok] = cv
    elif impact == "fixed":
        ratio = np.sqrt(out["m0_l"] / out["m0_r"])
        c_lr[ok] = cv * ratio[ok]
        c_rl[ok] = cv / ratio[ok]
    elif impact != "least-loss":
        before = error.copy()
        _impact_batch(impact, px, py, mass, cen, inert, ref, jl, el, jr, er, geo_l, geo_r,
                      out["m0_l"], out["m0_r"], ok, c_lr, c_rl, error, parallel)
        # the default spec: a row the paper model refuses gets the momentum law instead (the
        # law and note of impact_law(..., fallback=...) on the same arch)
        fell = ok & (error != before) if spec.fallback is not None else np.zeros(B, bool)
        if fell.any():
            for b in np.flatnonzero(fell):
                fallback[b] = fallback_note(error[b], spec.fallback)
                error[b] = ""
            f_lr, f_rl = np.full(B, np.nan), np.full(B, np.nan)
            _impact_batch(spec.fallback, px, py, mass, cen, inert, ref, jl, el, jr, er, geo_l,
                          geo_r, out["m0_l"], out["m0_r"], fell, f_lr, f_rl, error, parallel)
            c_lr[fell], c_rl[fell] = f_lr[fell], f_rl[fell]
        ok = error == ""
    chain = {}
    if impact == "least-loss":
        chain = _least_loss_per_arch(arch_of, B, ok, c_lr, c_rl, out["v_rest"],
                                     error)
    fallback[error != ""] = ""
    t3 = time.perf_counter()
    return PreparedBatch(k_l, k_r, mech_l, mech_r, geo_l, geo_r, out["phu_l"], out["phu_r"],
                         out["lim_l"], out["lim_r"], c_lr, c_rl, out["v_rest"], error,
                         tab_l, tab_r, {"limit": t1 - t0, "four_link": t2 - t1, "impact": t3 - t2},
                         **chain, impact_fallback=fallback)


def _impact_batch(model, px, py, mass, cen, inert, ref, jl, el, jr, er, geo_l, geo_r, m0_l, m0_r,
                  ok, c_lr, c_rl, error, parallel):
    """'paper' / 'momentum' rate ratios of the usable rows, compiled over the batch; the checks
    and messages of :func:`archrock.dynamics.impact.impact_law` (only the failing rows are worded)."""
    from .impact.compiled import SINGULAR, rate_ratios_batch
    from .impact.laws import OR_FIXED_CV, USE_MOMENTUM

    mref = np.asarray(power_of_two_near(np.sum(mass, axis=1)), float).reshape(-1)
    lr, rl, code_lr, code_rl = rate_ratios_batch(model, ok, px, py, mass, cen, inert, jl, el, jr,
                                                 er, geo_l, geo_r, ref, mref, parallel)
    if model == "paper":
        singular = ok & ((code_lr == SINGULAR) | (code_rl == SINGULAR))
        for b in np.flatnonzero(singular):
            error[b] = LeftOut("impact_not_applicable", "impact: the 'paper' model's momentum "
                               "equations are singular for this geometry; " + USE_MOMENTUM)
        with np.errstate(invalid="ignore"):
            e_lr = lr**2 * m0_r / m0_l
            e_rl = rl**2 * m0_l / m0_r
            bad = ok & ~singular & ((e_lr > 1.0 + 1e-9) | (lr < 0) | (e_rl > 1.0 + 1e-9) | (rl < 0))
        for b in np.flatnonzero(bad):
            for name, e, c in (("l_to_r", e_lr[b], lr[b]), ("r_to_l", e_rl[b], rl[b])):
                if e > 1.0 + 1e-9:
                    error[b] = LeftOut("impact_not_applicable", (
                        f"impact {name}: the 'paper' model creates energy on this geometry "
                        f"(kinetic energy ratio {e:.4f} > 1, rate ratio {c:.4f}); "
                        + USE_MOMENTUM + OR_FIXED_CV))
                    break
                if c < 0:
                    error[b] = LeftOut("impact_not_applicable", (
                        f"impact {name}: the 'paper' model gives a negative rate ratio "
                        f"{c:.4f} on this geometry; " + USE_MOMENTUM))
                    break
    use = error == ""
    c_lr[use] = lr[use]
    c_rl[use] = rl[use]


def _least_loss_per_arch(arch_of, B, ok, c_lr, c_rl, v_rest, error) -> dict:
    """Chain arrays of the least-loss law, arch by arch through response.prepare (the same chain,
    four-link vectors, limits and v_rest as the one-arch path); failures recorded in ``error``."""
    import warnings

    from .response import prepare

    chains = {}
    for b in np.flatnonzero(ok):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                model = prepare(arch_of(b), "least-loss")
        except (ArchrockError, ZeroDivisionError, FloatingPointError) as exc:
            error[b] = LeftOut("impact_not_applicable",
                               "least-loss chain: " + " ".join(str(exc).split()))
            continue
        chains[b] = model.chain
        c_lr[b], c_rl[b] = model.impact.l_to_r, model.impact.r_to_l
        v_rest[b] = model.v_rest
    c = pack_chains(chains, size=B, fill=np.nan, width=GEO_SIZE)
    R = c["rows"].shape[1]
    arr = {"chain_geo": c["rows"], "chain_limit": c["limit"], "chain_unstable": c["unstable"],
           "chain_direction": c["direction"], "chain_next": c["next"], "chain_ratio": c["ratio"],
           "chain_table": np.full((B, R, 2), np.nan), "n_mechanisms": c["n_rows"]}
    for b, (mechs, lims, _) in chains.items():
        for j, (fl, lim) in enumerate(zip(mechs, lims)):
            # the range of FourLink.tabulated(lim), which the one-arch fast integrator reads
            arr["chain_table"][b, j] = table_range(fl.geo, lim, fl.phi_dead)
    return arr


def _prepare_finite(arches, spec, t0: float):
    """A :class:`~archrock.dynamics.batch.PreparedBatch` of ``arches`` (entries may be
    errors) through :func:`~archrock.dynamics.response.prepare`, one arch at a time, with the
    resolved impact ``spec``: the path for arches of finite strength (module docstring).  An
    arch without an answer keeps its reason in ``error``, as the compiled path words it."""
    import warnings

    from ..errors import GeometryOutcome, ImpactModelError
    from .response import prepare

    B = len(arches)
    error = np.full(B, "", dtype=object)
    nan = lambda: np.full(B, np.nan)  # noqa: E731 - a fresh column each call
    k_l, k_r, phu_l, phu_r, lim_l, lim_r, c_lr, c_rl, v_rest = (nan() for _ in range(9))
    mech_l = np.full(B, "", dtype=object)
    mech_r = np.full(B, "", dtype=object)
    fallback = np.full(B, spec.note or "", dtype=object)
    chains = {}
    for b, arch in enumerate(arches):
        if isinstance(arch, Exception):
            why = " ".join(str(arch).split())
            error[b] = LeftOut.read(why if why.startswith("geometry:") else "geometry: " + why)
            continue
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                model = prepare(arch, spec)
        except (GeometryOutcome, ImpactModelError) as exc:
            error[b] = _finite_reason(exc)
            continue
        except (ArchrockError, ZeroDivisionError, FloatingPointError) as exc:
            error[b] = LeftOut("four_link_not_applicable",
                               "four-link model: " + " ".join(str(exc).split()))
            continue
        chains[b] = model.chain
        k_l[b], k_r[b] = model.k_l, model.k_r
        mech_l[b], mech_r[b] = model.mech_l.mechanism.label, model.mech_r.mechanism.label
        phu_l[b], phu_r[b] = model.phi_unstable_l, model.phi_unstable_r
        lim_l[b], lim_r[b] = model.phi_limit_l, model.phi_limit_r
        c_lr[b], c_rl[b] = model.impact.l_to_r, model.impact.r_to_l
        v_rest[b] = model.v_rest
        if getattr(model.impact, "fallback", None):
            fallback[b] = model.impact.fallback
    c = pack_chains(chains, size=B, fill=np.nan, width=GEO_SIZE)
    R = c["rows"].shape[1]
    table = np.full((B, R, 2), np.nan)
    for b, (mechs, lims, _) in chains.items():
        for j, (fl, lim) in enumerate(zip(mechs, lims)):
            table[b, j] = table_range(fl.geo, lim, fl.phi_dead)
    fallback[error != ""] = ""
    return PreparedBatch(k_l, k_r, mech_l, mech_r, c["rows"][:, 0].copy(),
                         c["rows"][:, 1].copy(), phu_l, phu_r, lim_l, lim_r, c_lr, c_rl, v_rest,
                         error, table[:, 0].copy(), table[:, 1].copy(),
                         {"limit": time.perf_counter() - t0, "four_link": 0.0, "impact": 0.0},
                         chain_geo=c["rows"], chain_limit=c["limit"],
                         chain_unstable=c["unstable"], chain_direction=c["direction"],
                         chain_next=c["next"], chain_ratio=c["ratio"], chain_table=table,
                         n_mechanisms=c["n_rows"], impact_fallback=fallback)


def _finite_reason(exc) -> str:
    """An outcome as a LeftOut: its reason by its type, its message as it was raised."""
    from ..errors import (CannotStandError, ImpactModelError, InvalidSampleError,
                          NoMechanismError, NotFourHingeError)

    msg = " ".join(str(exc).split()) or type(exc).__name__
    for kind, reason in ((InvalidSampleError, "invalid_draw"), (CannotStandError, "cannot_stand"),
                         (NoMechanismError, "no_mechanism"), (NotFourHingeError, "lift_off"),
                         (ImpactModelError, "impact_not_applicable")):
        if isinstance(exc, kind):
            return LeftOut(reason, msg)
    return LeftOut.read(msg)
