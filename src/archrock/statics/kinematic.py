"""The four-hinge search: the best four-hinge mechanism of each direction, and the governing one.

Up to ENUMERATION_MAX_VOUSSOIRS voussoirs every candidate of :mod:`archrock.statics.hinges` is
enumerated (vectorised numpy in cache-sized blocks, or the compiled numba kernel: identical
results; ARCHROCK_NO_NUMBA=1 for numpy only), after estimating its work (LimitExceededError
beyond ``max_seconds``; progress lines through :func:`limit_progress`).  Above it the
static-guided search reads the hinges where the static optimum's line of thrust touches the
edges and accepts the mechanism whose kinematic multiplier equals the static one.
:func:`_governing` then certifies the best four-hinge mechanism by its line of thrust, or takes
the mechanism with lift-off from the LP's dual (:mod:`archrock.statics.liftoff`).  Multipliers
are horizontal loads per unit weight; 'l' loads toward +x, 'r' toward -x; inf where no
mechanism loads a direction.

Module switches (tests patch them here, the only place they live): ``_NUMBA_ENABLED``
(:func:`_disable_numba`), ``_BLOCK_ELEMENTS``, ``_PROGRESS_SECONDS``, ``_CONFIRM_RTOL``.
"""

from __future__ import annotations

import math
import time
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

import numpy as np

from .._device import resolve_device
from .._jit import HAVE_NUMBA, maybe_njit, numba
from .._progress import check_progress
from ..errors import ArchInputError, CannotStandError, LimitExceededError, NoMechanismError
from ..geometry import Arch, VoussoirArch
from .hinges import (_EDGE_SIGN, _PATTERNS, DIRECTIONS, Mechanism, _active_candidates,
                     _candidate_index, _mechanism_from_candidate, quadruples)
from .liftoff import (_DUAL_CONFIRM, GENERAL_MAX_VOUSSOIRS, _certify_arch, _lp_mechanism,
                      general_mechanisms)
from .lp import ThrustLine, _radial, _stands, static_multiplier
from .overload import cannot_stand_message
from .sums import _batch_sums, _enumerate_sums, _virtual_work, arch_sums, signed_work

__all__ = ["kinematic_mechanisms", "kinematic_multipliers_batch", "kinematic_multipliers_arches",
           "limit_progress", "enumeration_estimate", "SEARCH_CHOICES",
           "ENUMERATION_MAX_VOUSSOIRS", "MAX_ENUMERATION_SECONDS"]


# Optional compiled kernel (the "fast" extra).  The same arithmetic as _enumerate_sums, candidate
# by candidate, keeping the first minimum in candidate order (as numpy's argmin does).
_NUMBA_ENABLED = False
_numba_kernel = _numba_kernel_par = None
if HAVE_NUMBA:  # one switch for the whole package: ARCHROCK_NO_NUMBA=1 (see archrock._jit)
    _NUMBA_ENABLED = True

    @maybe_njit(nogil=True)
    def _numba_kernel(cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0):
        """Nested loops over joint quadruples a < b < c < d and the 14 hinge-edge patterns
        that can be admissible, in the order of _candidates(n) (candidate index = rank of
        the quadruple * 16 + pattern): no candidate list is built, so memory stays O(n).
        Only first joints ja0 <= a < ja1 (rank0: rank of the first such quadruple), starting
        from the best values already in k_*, i_*: calls over consecutive ranges of a give the
        result of one call over all, and a long enumeration can report its progress."""
        for b in range(cw.shape[0]):
            _numba_arch(b, cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0)

    @maybe_njit(parallel=True)
    def _numba_kernel_par(cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0):
        """:func:`_numba_kernel` with the arches spread over the numba threads (each arch's
        enumeration is the same sequential loop, so the results are the serial ones, bit for
        bit)."""
        for b in numba.prange(cw.shape[0]):
            _numba_arch(b, cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0)

    _signed_work_jit = maybe_njit(nogil=True)(signed_work)

    @maybe_njit(nogil=True)
    def _numba_arch(b, cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0):
        """The enumeration of arch b (see :func:`_numba_kernel`)."""
        m = cw.shape[1]
        tol = 1e-9
        tiny = 1e-14
        best_l = k_l[b]
        best_r = k_r[b]
        arg_l = i_l[b]
        arg_r = i_r[b]
        rank = rank0 - 1
        for ja in range(ja0, ja1):
            for jb in range(ja + 1, m):
                W1 = cw[b, jb] - cw[b, ja]
                X1 = cwx[b, jb] - cwx[b, ja]
                Y1 = cwy[b, jb] - cwy[b, ja]
                for jc in range(jb + 1, m):
                    W2 = cw[b, jc] - cw[b, jb]
                    X2 = cwx[b, jc] - cwx[b, jb]
                    Y2 = cwy[b, jc] - cwy[b, jb]
                    for jd in range(jc + 1, m):
                        rank += 1
                        W3 = cw[b, jd] - cw[b, jc]
                        X3 = cwx[b, jd] - cwx[b, jc]
                        Y3 = cwy[b, jd] - cwy[b, jc]
                        for pat in range(1, 15):
                            ea = (pat >> 3) & 1
                            eb = (pat >> 2) & 1
                            ec = (pat >> 1) & 1
                            ed = pat & 1
                            Ax = pxf[b, 2 * ja + ea]
                            Ay = pyf[b, 2 * ja + ea]
                            Bx = pxf[b, 2 * jb + eb]
                            By = pyf[b, 2 * jb + eb]
                            Cx = pxf[b, 2 * jc + ec]
                            Cy = pyf[b, 2 * jc + ec]
                            Dx = pxf[b, 2 * jd + ed]
                            Dy = pyf[b, 2 * jd + ed]
                            u2x = Cx - Bx
                            u2y = Cy - By
                            u3x = Dx - Cx
                            u3y = Dy - Cy
                            rx = Ax - Bx
                            ry = Ay - By
                            det = u2x * u3y - u2y * u3x
                            scale = (max(abs(u2x) + abs(u2y), 1e-300)
                                     * max(abs(u3x) + abs(u3y), 1e-300))
                            if not abs(det) > 1e-12 * scale:
                                continue
                            w2 = (rx * u3y - ry * u3x) / det
                            w3 = (u2x * ry - u2y * rx) / det
                            q0 = _EDGE_SIGN[ea] * 1.0
                            q1 = _EDGE_SIGN[eb] * (w2 - 1.0)
                            q2 = _EDGE_SIGN[ec] * (w3 - w2)
                            q3 = _EDGE_SIGN[ed] * (-w3)
                            qmag = max(max(abs(q0), abs(q1)), max(abs(q2), abs(q3)))
                            thr = tol * qmag
                            if q0 > thr and q1 > thr and q2 > thr and q3 > thr:
                                sigma = 1.0
                            elif q0 < -thr and q1 < -thr and q2 < -thr and q3 < -thr:
                                sigma = -1.0
                            else:
                                continue
                            work_x, work_y = _signed_work_jit(
                                sigma, W1, X1, Y1, W2, X2, Y2, W3, X3, Y3, Ax, Ay, Bx, By, Dx,
                                Dy, w2, w3)
                            if work_x > tiny:
                                lam = work_y / work_x
                                if lam < best_l:
                                    best_l = lam
                                    arg_l = rank * 16 + pat
                            elif work_x < -tiny:
                                lam = work_y / (-work_x)
                                if lam < best_r:
                                    best_r = lam
                                    arg_r = rank * 16 + pat
        k_l[b] = best_l
        k_r[b] = best_r
        i_l[b] = arg_l
        i_r[b] = arg_r


def _circular_sums_of(spans, radii, thick):
    """``sums_of`` for :func:`_full_enumeration` from the circular parameters (B, n)."""
    return lambda s, e: _batch_sums(spans[s:e], radii[s:e], thick[s:e])[:5]


def _validate_batch(spans, radii, thick):
    spans = np.atleast_2d(np.asarray(spans, float))
    radii = np.atleast_2d(np.asarray(radii, float))
    thick = np.atleast_2d(np.asarray(thick, float))
    if not (spans.shape == radii.shape == thick.shape):
        raise ArchInputError(f"spans, radii, thicknesses: shapes differ {spans.shape}, {radii.shape}, {thick.shape}")
    if spans.shape[1] < 3:
        raise ArchInputError(f"voussoirs: {spans.shape[1]}; allowed >= 3")
    for name, arr in (("spans", spans), ("radii", radii), ("thicknesses", thick)):
        if not np.all(np.isfinite(arr)):
            raise ArchInputError(f"{name}: every value must be finite")
    if np.any(spans <= 0) or np.any(radii <= 0) or np.any(thick <= 0) or np.any(thick >= 2 * radii):
        raise ArchInputError("voussoirs: spans > 0, radii > 0 and 0 < thickness < 2 radius required")
    return spans, radii, thick


def _disable_numba() -> None:
    global _NUMBA_ENABLED
    _NUMBA_ENABLED = False


# Elements per block of the numpy enumeration: blocks that stay in cache are several times
# faster than one big block (measured: ~10x at n = 7 against 4e6-element blocks).
_BLOCK_ELEMENTS = 16_384
# The numpy enumeration keeps index arrays of all candidates (14 C(n+1, 4)): 2 GB at n = 60.
_NUMPY_MAX_VOUSSOIRS = 48
# ... about this many bytes per candidate (cached candidate list and gather indices).
_NUMPY_BYTES_PER_CANDIDATE = 170

#: Up to this many voussoirs, ``method="auto"`` enumerates every candidate (0.1.0's results,
#: bit for bit); above it, the static-guided search.  Measured on one core: the numba
#: enumeration takes 3 ms per arch at n = 30, 10 ms at 40, 41 ms at 48 and grows as n^4 (50 s
#: at 300); the guided search takes about 5 ms at n = 40 (two LPs), 20 ms at 100.  Above 40 the
#: search is faster with numba; without numba it is faster from n ~ 20, but one threshold for
#: both keeps the two paths' results identical.
ENUMERATION_MAX_VOUSSOIRS = 40
#: Ways of finding the mechanisms: "auto" (enumeration up to ENUMERATION_MAX_VOUSSOIRS, the
#: guided search above), "enumeration" (every candidate, with a work estimate), "guided".
SEARCH_CHOICES = ("auto", "enumeration", "guided")
#: Default bound [s] on the estimated time of a full enumeration; beyond it LimitExceededError.
MAX_ENUMERATION_SECONDS = 300.0
# Candidates per second of the enumeration on one core (measured 1.0-1.4e8 with numba for
# n >= 20, 1.1-1.5e7 with numpy), rounded down so that estimates err on the long side.
_ENUMERATION_RATE = {"numba": 8e7, "numpy": 1e7}
# Seconds per arch of the guided search: a + b n (measured ~4 ms at n = 40, ~0.1 s at 1000).
_GUIDED_SECONDS = (5e-3, 1e-4)
# Work estimated above this many seconds prints progress lines on stderr.
_PROGRESS_SECONDS = 5.0
# A joint touches the line of thrust when its gap to an edge is below this fraction of its
# contact width: HiGHS's vertex puts the active joints at ~1e-12, while the neighbours of a
# hinge on a 1000-voussoir arch are ~1e-5 away.
_TOUCH_TOL = 1e-7
# The chosen mechanism's multiplier must equal the static one to this, relative (|lambda| >= 1)
# or absolute (|lambda| < 1): the two limit theorems bracket the collapse multiplier.
_CONFIRM_RTOL = 1e-9
# Neighbourhoods tried after the touching joints alone: every joint within k of a contact,
# hinges at both edges.
_WIDEN = (1, 2, 4)
# A neighbourhood with more candidates than this goes to the full enumeration instead.
_GUIDED_MAX_CANDIDATES = 2_000_000


def _check_method(method, max_seconds):
    if method not in SEARCH_CHOICES:
        raise ArchInputError(f"method: {method!r}; allowed "
                             f"{', '.join(map(repr, SEARCH_CHOICES))}")
    if max_seconds is not None:
        try:
            ok = float(max_seconds) > 0 and math.isfinite(float(max_seconds))
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise ArchInputError(f"max_seconds: {max_seconds!r}; allowed a number > 0 (seconds)")
    return MAX_ENUMERATION_SECONDS if max_seconds is None else float(max_seconds)


def enumeration_estimate(n: int, arches: int = 1) -> dict:
    """Work of the full enumeration of ``arches`` arches of ``n`` voussoirs: candidates,
    estimated seconds on one core with the current backend, and memory for numpy [bytes]."""
    per_arch = 14 * math.comb(n + 1, 4)
    backend = "numba" if _NUMBA_ENABLED else "numpy"
    return {"candidates": per_arch * arches, "seconds": per_arch * arches / _ENUMERATION_RATE[backend],
            "backend": backend, "bytes": per_arch * _NUMPY_BYTES_PER_CANDIDATE if backend == "numpy" else 0}


def _seconds(x: float) -> str:
    return f"{x:.0f}" if x >= 10 else f"{x:.2g}"


# Where the progress lines of long enumerations go: a callable given one line of text, set for
# a block of code by :func:`limit_progress` (the CLI prints them on stderr); the library itself
# never prints.  A context variable, so threads and nested calls each see their own.
_PROGRESS_SINK: ContextVar = ContextVar("archrock_limit_progress", default=None)


@contextmanager
def limit_progress(progress):
    """Within the block, the progress lines of long limit analyses (a full enumeration above
    about 5 s, a batch of guided searches) go to ``progress`` (a callable given one line of text;
    None: silent, the default)."""
    token = _PROGRESS_SINK.set(check_progress(progress))
    try:
        yield
    finally:
        _PROGRESS_SINK.reset(token)


def _say(msg: str) -> None:
    sink = _PROGRESS_SINK.get()
    if sink is not None:
        sink(f"archrock limit analysis: {msg}")


def _full_enumeration(sums_of, B, n, chunk, max_seconds, why="", parallel=False, device="cpu"):
    """Every candidate of B arches of n voussoirs, after estimating the work: refused beyond
    ``max_seconds``, with progress lines on stderr when it will take a while.  ``sums_of(s, e)``
    gives the prefix sums and joint points (cw, cwx, cwy, px, py) of arches s..e-1: from the
    circular parameters (:func:`_batch_sums`) or from any arch (:func:`arch_sums`)."""
    est = enumeration_estimate(n, B)
    what = (f"{est['candidates']:.3g} candidate mechanisms ({B} arch{'es' if B > 1 else ''} "
            f"of {n} voussoirs)")
    if est["backend"] == "numpy" and n > _NUMPY_MAX_VOUSSOIRS:
        raise LimitExceededError(
            f"limit analysis: {why}the full enumeration without numba holds every candidate in "
            f"memory: {what}, about {est['bytes'] / 1e9:.1f} GB (allowed n <= {_NUMPY_MAX_VOUSSOIRS}); "
            "install the 'fast' extra (numba), or use method='auto' (the static-guided search)")
    if est["seconds"] > max_seconds:
        raise LimitExceededError(
            f"limit analysis: {why}the full enumeration of {what} would take about "
            f"{_seconds(est['seconds'])} s with {est['backend']} (bound {max_seconds:g} s); pass "
            f"max_seconds={math.ceil(2 * est['seconds'])} to run it anyway, or use method='auto' "
            "(the static-guided search)")
    progress = est["seconds"] > _PROGRESS_SECONDS
    if progress:
        _say(f"{why}full enumeration of {what}, about {_seconds(est['seconds'])} s with {est['backend']}")
    t0 = time.perf_counter()
    if device == "gpu":  # one arch per GPU thread; its errors are the caller's, never hidden
        from .gpusearch import four_hinge_gpu

        cw, cwx, cwy, px, py = sums_of(0, B)
        return four_hinge_gpu(cw, cwx, cwy, px.reshape(B, -1), py.reshape(B, -1), _numba_arch)
    if _NUMBA_ENABLED:
        try:
            out = _enumerate_numba(sums_of, B, n, progress, t0, parallel)
        except Exception:  # noqa: BLE001 - a kernel that cannot compile here: use numpy
            _disable_numba()
            return _full_enumeration(sums_of, B, n, chunk, max_seconds, why, parallel)
    else:
        out = _enumerate_numpy(sums_of, B, n, chunk, progress, t0)
    if progress:
        _say(f"full enumeration done in {time.perf_counter() - t0:.1f} s")
    return out


def _enumerate_numba(sums_of, B, n, progress, t0, parallel=False):
    m = n + 1
    k_l = np.full(B, np.inf)
    k_r = np.full(B, np.inf)
    i_l = np.zeros(B, dtype=np.int64)
    i_r = np.zeros(B, dtype=np.int64)
    cw, cwx, cwy, px, py = sums_of(0, B)
    pxf = np.ascontiguousarray(px.reshape(B, -1))
    pyf = np.ascontiguousarray(py.reshape(B, -1))
    if not progress:
        # arches over the numba threads (no Python per arch); one arch alone stays serial
        kernel = _numba_kernel_par if parallel and B > 1 else _numba_kernel
        kernel(cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, 0, m, 0)
        return k_l, k_r, i_l, i_r
    # one arch at a time, the first joints in ranges of about a tenth of the work each
    total = math.comb(m, 4)
    for b in range(B):
        sl = slice(b, b + 1)
        ja = 0
        while ja < m - 3:
            done = total - math.comb(m - ja, 4)  # rank of the first quadruple with joint ja
            end = ja + 1
            while end < m - 3 and total - math.comb(m - end, 4) - done < total / 10:
                end += 1
            _numba_kernel(cw[sl], cwx[sl], cwy[sl], pxf[sl], pyf[sl], k_l[sl], k_r[sl],
                          i_l[sl], i_r[sl], ja, end, done)
            ja = end
            frac = (b + (total - math.comb(m - ja, 4)) / total) / B
            _say(f"full enumeration {100 * frac:.0f}% ({time.perf_counter() - t0:.0f} s)")
    return k_l, k_r, i_l, i_r


def _enumerate_numpy(sums_of, B, n, chunk, progress, t0):
    k_l = np.empty(B)
    k_r = np.empty(B)
    i_l = np.empty(B, dtype=np.int64)
    i_r = np.empty(B, dtype=np.int64)
    idx, pt, pair, sign = _active_candidates(n)
    K = len(idx)
    if chunk is None:
        chunk = max(1, _BLOCK_ELEMENTS // K)
    # candidates per sub-block when a single arch already exceeds the block size
    cstep = K if chunk > 1 else max(_BLOCK_ELEMENTS // 2, 1)
    last = t0
    for s in range(0, B, chunk):
        e = min(B, s + chunk)
        cw, cwx, cwy, px, py = sums_of(s, e)
        rows = np.arange(e - s)
        best_l = np.full(e - s, np.inf)
        best_r = np.full(e - s, np.inf)
        arg_l = np.zeros(e - s, dtype=np.int64)
        arg_r = np.zeros(e - s, dtype=np.int64)
        for c0 in range(0, K, cstep):
            c1 = min(K, c0 + cstep)
            lam_l, lam_r = _enumerate_sums(cw, cwx, cwy, px, py,
                                           None if (c0 == 0 and c1 == K) else slice(c0, c1))
            a_l = np.argmin(lam_l, axis=1)
            a_r = np.argmin(lam_r, axis=1)
            v_l = lam_l[rows, a_l]
            v_r = lam_r[rows, a_r]
            better_l = v_l < best_l  # strict: the first minimum in candidate order wins
            better_r = v_r < best_r
            best_l = np.where(better_l, v_l, best_l)
            best_r = np.where(better_r, v_r, best_r)
            arg_l = np.where(better_l, a_l + c0, arg_l)
            arg_r = np.where(better_r, a_r + c0, arg_r)
            if progress and time.perf_counter() - last > 0.1 * _PROGRESS_SECONDS:
                last = time.perf_counter()
                frac = (s + (e - s) * c1 / K) / B
                _say(f"full enumeration {100 * frac:.0f}% ({last - t0:.0f} s)")
        k_l[s:e] = best_l
        k_r[s:e] = best_r
        i_l[s:e] = np.where(np.isfinite(best_l), idx[arg_l], 0)
        i_r[s:e] = np.where(np.isfinite(best_r), idx[arg_r], 0)
    return k_l, k_r, i_l, i_r


def kinematic_multipliers_batch(spans, radii, thicknesses, chunk: int | None = None,
                                method: str = "auto", max_seconds: float | None = None, *,
                                parallel: bool = False, fallback: bool = True,
                                device: str = "cpu"):
    """Collapse multipliers of a batch of arches with the same number of voussoirs.

    spans [rad], radii [m], thicknesses [m]: arrays (B, n). Returns (k_l, k_r, cand_l, cand_r)
    where cand_* index into the candidate list of :func:`_candidates` (joint quadruple, edges).
    ``method``: one of :data:`SEARCH_CHOICES`; "auto" enumerates every candidate up to
    :data:`ENUMERATION_MAX_VOUSSOIRS` voussoirs and runs the static-guided search above.
    ``max_seconds``: bound on the estimated time of a full enumeration (default
    :data:`MAX_ENUMERATION_SECONDS`), beyond which it raises LimitExceededError.
    ``chunk``: arches per block of the vectorised (numpy) enumeration (default: sized to stay in
    cache); it does not change the results.  ``parallel``: the compiled enumeration spreads
    the arches over the numba threads (the same numbers, bit for bit).  ``fallback``: where the
    guided search confirms no four-hinge mechanism (a mechanism with lift-off governs), run the
    full enumeration for the best four-hinge one (default) or give inf there (the batch engine,
    which leaves such arches out anyway: a full enumeration of 200 voussoirs takes minutes).
    A multiplier is inf where no mechanism loads that direction, and -inf (both directions)
    where the guided search finds no line of thrust at any horizontal load (cannot stand).
    ``device``: 'cpu', 'gpu' or 'auto' (:func:`archrock._device.resolve_device`) for the full
    enumeration (:mod:`archrock.statics.gpusearch`); the guided search runs on the CPU.
    """
    spans, radii, thick = _validate_batch(spans, radii, thicknesses)
    max_seconds = _check_method(method, max_seconds)
    B, n = spans.shape
    if method == "enumeration" or (method == "auto" and n <= ENUMERATION_MAX_VOUSSOIRS):
        return _full_enumeration(_circular_sums_of(spans, radii, thick), B, n, chunk, max_seconds,
                                 parallel=parallel, device=resolve_device(device, B))
    k_l = np.empty(B)
    k_r = np.empty(B)
    i_l = np.empty(B, dtype=np.int64)
    i_r = np.empty(B, dtype=np.int64)
    estimate = B * (_GUIDED_SECONDS[0] + _GUIDED_SECONDS[1] * n)
    progress = estimate > _PROGRESS_SECONDS
    if progress:
        _say(f"static-guided search on {B} arches of {n} voussoirs, about {_seconds(estimate)} s")
    t0 = last = time.perf_counter()
    for b in range(B):
        k_l[b], k_r[b], i_l[b], i_r[b] = _guided_arch(spans[b], radii[b], thick[b], max_seconds,
                                                      fallback)
        if progress and time.perf_counter() - last > 0.1 * _PROGRESS_SECONDS:
            last = time.perf_counter()
            _say(f"static-guided search {b + 1}/{B} arches ({last - t0:.0f} s)")
    return k_l, k_r, i_l, i_r


def kinematic_multipliers_arches(arches, method: str = "auto", max_seconds: float | None = None,
                                 *, parallel: bool = False, fallback: bool = True,
                                 device: str = "cpu"):
    """:func:`kinematic_multipliers_batch` for arches of any shape with the same number of
    voussoirs (a sequence of :class:`VoussoirArch`): their :func:`arch_sums` stacked into one
    enumeration (n <= :data:`ENUMERATION_MAX_VOUSSOIRS` with "auto"), or arch by arch the
    static-guided search of :func:`kinematic_mechanisms`.  Each row is that arch's
    ``kinematic_mechanisms`` result, bit for bit.  Returns (k_l, k_r, cand_l, cand_r)."""
    max_seconds = _check_method(method, max_seconds)
    arches = list(arches)
    if not arches or not all(isinstance(a, VoussoirArch) for a in arches):
        raise ArchInputError("arches: expected a non-empty sequence of VoussoirArch objects")
    n = arches[0].n
    if any(a.n != n for a in arches):
        raise ArchInputError("arches: different numbers of voussoirs; allowed one n per batch")
    B = len(arches)
    sums = [arch_sums(a) for a in arches]
    if method == "enumeration" or (method == "auto" and n <= ENUMERATION_MAX_VOUSSOIRS):
        stacked = tuple(np.ascontiguousarray(np.concatenate([sm[k] for sm in sums]))
                        for k in range(5))
        return _full_enumeration(lambda s, e: tuple(a[s:e] for a in stacked), B, n, None,
                                 max_seconds, parallel=parallel,
                                 device=resolve_device(device, B))
    k_l = np.empty(B)
    k_r = np.empty(B)
    i_l = np.empty(B, dtype=np.int64)
    i_r = np.empty(B, dtype=np.int64)
    for b, (arch, sm) in enumerate(zip(arches, sums)):
        k_l[b], k_r[b], i_l[b], i_r[b] = _guided(arch, sm, (lambda why, sm=sm: _full_enumeration(
            lambda s, e: sm, 1, n, None, max_seconds, why)) if fallback else None)
    return k_l, k_r, i_l, i_r


def _best_in_pool(sums, n: int, allowed: np.ndarray, direction: str):
    """Smallest multiplier, and its candidate index, over every candidate whose four hinges are
    allowed ((n+1, 2) bool over joints and edges); ties go to the first candidate in the
    enumeration's order, as there.  None when no candidate is admissible or there are too many."""
    pool = np.flatnonzero(allowed.any(axis=1))
    if pool.size < 4 or math.comb(pool.size, 4) * 16 > _GUIDED_MAX_CANDIDATES:
        return None
    quads = quadruples(pool)  # the order of four_hinge_sets, restricted to the pool
    # the 14 edge patterns that can be admissible, each hinge at an allowed edge
    ok = np.all(allowed[quads[:, None, :], _PATTERNS[None, :, :]], axis=-1)
    ok[:, [0, 15]] = False
    qi, pi = np.nonzero(ok)
    jq, eq = quads[qi], _PATTERNS[pi]
    cw, cwx, cwy, px, py = (a[0] for a in sums)
    points = [(px[jq[:, h], eq[:, h]], py[jq[:, h], eq[:, h]]) for h in range(4)]
    links = [(cw[jq[:, k + 1]] - cw[jq[:, k]], cwx[jq[:, k + 1]] - cwx[jq[:, k]],
              cwy[jq[:, k + 1]] - cwy[jq[:, k]]) for k in range(3)]
    lam_l, lam_r = _virtual_work(points, links, _EDGE_SIGN[eq].T)
    lam = lam_l if direction == "l" else lam_r
    if lam.size == 0 or not np.isfinite(lam.min()):
        return None
    best = np.flatnonzero(lam == lam.min())
    idx = _candidate_index(n, jq[best], eq[best])
    return float(lam[best[0]]), int(idx.min())


def _search(arch: VoussoirArch, sums, direction: str, lam: float, thrust: ThrustLine):
    """The mechanism of the static solution: candidates from the joints where its line of
    thrust touches an edge, then from wider neighbourhoods, until one's kinematic multiplier
    equals the static one.  Returns (multiplier, candidate index) or None."""
    if _radial(arch):
        # 0.1.0's arithmetic, so that the touching joints are decided on the same numbers
        width = arch.contact_outer - arch.contact_inner
        gap = np.column_stack([(thrust.radii - arch.contact_inner) / width,
                               (arch.contact_outer - thrust.radii) / width])  # intrados, extrados
    else:
        gap = np.column_stack([thrust.fractions, 1.0 - thrust.fractions])
    touch = gap <= _TOUCH_TOL
    tol = _CONFIRM_RTOL * max(1.0, abs(lam))
    contacts = np.flatnonzero(touch.any(axis=1))
    pools = [touch]
    for k in _WIDEN:
        near = np.zeros(arch.n + 1, dtype=bool)
        for j in contacts:
            near[max(0, j - k):j + k + 1] = True
        pools.append(np.column_stack([near, near]))
    for allowed in pools:
        found = _best_in_pool(sums, arch.n, allowed, direction)
        # by the kinematic theorem found[0] >= the collapse multiplier >= lam (static theorem),
        # so equality confirms it is the collapse mechanism
        if found is not None and abs(found[0] - lam) <= tol:
            return found
    return None


def _guided_arch(spans, radii, thick, max_seconds, fallback=True):
    """(k_l, k_r, cand_l, cand_r) of one circular arch (its parameters (n,)) by the
    static-guided search, the full enumeration (within ``max_seconds``) where the search cannot
    confirm its mechanism (``fallback=False``: inf there; a mechanism with lift-off governs)."""
    arch = Arch(spans, radii, thick)
    sums_of = _circular_sums_of(spans[None], radii[None], thick[None])
    return _guided(arch, sums_of(0, 1), (lambda why: _full_enumeration(
        sums_of, 1, arch.n, None, max_seconds, why)) if fallback else None)


def _guided(arch: VoussoirArch, sums, full):
    """(k_l, k_r, cand_l, cand_r) of any arch given its sums (a batch of one) by the
    static-guided search; ``full(why)`` runs the full enumeration where it cannot confirm
    (``full=None``: inf there, the four-hinge family does not attain the static optimum)."""
    lp = {}
    for d in DIRECTIONS:
        try:
            # a joint with no force across it (N = M = 0: the springing lifts off) has no
            # crossing radius (NaN): it touches no edge, and no mechanism can be confirmed
            with np.errstate(invalid="ignore", divide="ignore"):
                lp[d] = static_multiplier(arch, d)
        except CannotStandError:
            lp[d] = None
    if lp["l"] is None and lp["r"] is None and not _stands(arch):
        # no line of thrust at any horizontal load: the arch cannot stand, and there is no
        # static multiplier to confirm a mechanism with
        return -np.inf, -np.inf, 0, 0
    out, enumerated = [], None
    for d in DIRECTIONS:
        if lp[d] is None:
            # the LP is feasible (it stands, or the other direction solved) but unbounded: by
            # duality no admissible mechanism loads this direction
            out.append((np.inf, 0))
            continue
        found = _search(arch, sums, d, *lp[d])
        if found is None and full is None:
            # no four-hinge mechanism attains the static optimum: one with lift-off governs
            found = (np.inf, 0)
        if found is None:
            if enumerated is None:
                enumerated = full(
                    f"the static-guided search could not confirm the mechanism ({d}); ")
            e = enumerated
            found = (e[0][0], e[2][0]) if d == "l" else (e[1][0], e[3][0])
        out.append(found)
    return out[0][0], out[1][0], out[0][1], out[1][1]


def _four_hinge_search(arch: VoussoirArch, method: str, max_seconds: float):
    """(sums, k_l, k_r, cand_l, cand_r): the best four-hinge mechanism per direction (inf where
    none loads it; -inf when the arch cannot stand), by the enumeration or, above
    :data:`ENUMERATION_MAX_VOUSSOIRS` voussoirs with "auto", the static-guided search (which
    never falls back to the full enumeration here: where it cannot confirm a four-hinge
    mechanism, one with lift-off governs and the LP's dual gives it)."""
    n = arch.n
    sums = arch_sums(arch)
    if method == "enumeration" or (method == "auto" and n <= ENUMERATION_MAX_VOUSSOIRS):
        (k_l,), (k_r,), (i_l,), (i_r,) = _full_enumeration(lambda s, e: sums, 1, n, None,
                                                           max_seconds)
    else:
        k_l, k_r, i_l, i_r = _guided(arch, sums, None)
    return sums, k_l, k_r, i_l, i_r


@dataclass(frozen=True)
class _Governing:
    """One direction's answer: the governing mechanism, the best four-hinge mechanism (None
    where none loads that direction), the LP optimum and line of thrust (None where not
    solved) and how the mechanism was found."""

    mechanism: Mechanism
    four_hinge: Mechanism | None
    static: float | None
    thrust: ThrustLine | None
    how: str


def _governing(arch: VoussoirArch, method: str = "auto", max_seconds: float | None = None,
               static: bool = True) -> dict:
    """The Heyman collapse mechanism of each direction ({'l': _Governing, 'r': ...}).

    The best four-hinge mechanism governs when the line of thrust through its hinges fits
    (:func:`certify_four_hinge`); otherwise the static LP's optimum does, with the mechanism
    read from its dual and confirmed by its own virtual work.  ``static``: solve the LP also
    where the four-hinge mechanism is certified (the cross-check)."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    max_seconds = _check_method(method, max_seconds)
    n = arch.n
    sums, k_l, k_r, i_l, i_r = _four_hinge_search(arch, method, max_seconds)
    if k_l == -np.inf:
        raise CannotStandError(cannot_stand_message(
            arch, "(no line of thrust fits inside it under any horizontal load)"))
    if k_l <= 0 or k_r <= 0:
        # a four-hinge mechanism opens under its own weight (kinematic theorem: the Heyman
        # multiplier is at most this one)
        raise CannotStandError(cannot_stand_message(arch, f"(k_l = {k_l:.4g}, k_r = {k_r:.4g})"))
    out = {}
    for d, k, i in (("l", k_l, i_l), ("r", k_r, i_r)):
        four = _mechanism_from_candidate(n, int(i), d, k) if np.isfinite(k) else None
        if four is not None and _certify_arch(arch, four):
            lp = static_multiplier(arch, d) if static else (None, None)
            out[d] = _Governing(four, four, lp[0], lp[1], "four-hinge")
            continue
        lam_s, thrust, mech = _lp_mechanism(arch, d)
        if lam_s == math.inf:
            raise NoMechanismError(
                f"arch: no mechanism opens under horizontal forces toward "
                f"{'+x' if d == 'l' else '-x'} (the arch is too flat or too thick to hinge or "
                f"lift off); sliding or crushing governs, which limit analysis under Heyman's "
                f"hypotheses does not cover")
        how = "lp-dual"
        if mech is None and n <= GENERAL_MAX_VOUSSOIRS:
            mech = general_mechanisms(arch, d)
            how = "general-enumeration"
            if abs(mech.multiplier - lam_s) > _DUAL_CONFIRM * max(1.0, abs(lam_s)):
                mech = None
        if mech is None:
            raise LimitExceededError(
                f"limit analysis: the static optimum ({lam_s:.6g}, direction {d!r}) is attained "
                f"by no mechanism archrock can confirm by virtual work (a degenerate linear "
                f"program); the multiplier is not reported")
        out[d] = _Governing(mech, four, lam_s, thrust, how)
    for d in DIRECTIONS:
        if out[d].mechanism.multiplier <= 0:
            raise CannotStandError(cannot_stand_message(
                arch, f"(k_l = {out['l'].mechanism.multiplier:.4g}, k_r = "
                      f"{out['r'].mechanism.multiplier:.4g})"))
    return out


def kinematic_mechanisms(arch: VoussoirArch, method: str = "auto",
                         max_seconds: float | None = None) -> tuple[Mechanism, Mechanism]:
    """The governing (Heyman) mechanisms (M_l, M_r) of any arch: the best four-hinge mechanism
    (enumeration, or the static-guided search for many voussoirs: ``method``, ``max_seconds``,
    see :func:`kinematic_multipliers_batch`) where the line of thrust through its hinges fits
    the arch, otherwise the mechanism with lift-off that the static LP's dual gives, confirmed
    by its virtual work (``Mechanism.kind``).  Works on :func:`arch_sums` (weights with loads)."""
    g = _governing(arch, method, max_seconds, static=False)
    return g["l"].mechanism, g["r"].mechanism
