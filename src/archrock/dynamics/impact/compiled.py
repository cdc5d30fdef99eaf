"""The 'paper' and 'momentum' rate ratios of a whole batch of arches, compiled.

:func:`archrock.dynamics.impact.laws.paper_rate_ratio` and :func:`~archrock.dynamics.impact.laws.momentum_rate_ratio`
work on :class:`~archrock.dynamics.fourlink.FourLink` objects, one arch at a time in Python (about 2.4 ms
and 0.6 ms per arch: more than the arch's whole response).  The functions here do the same
arithmetic from the flat arrays of a batch (joint points, voussoir masses, centroids, inertias,
the hinges of M_l and M_r and their four-link vectors ``geo``), one arch per numba thread, with
no Python per arch.  The sums are taken in numpy's order (pairwise over a row, sequential down a
column: :func:`np_sum`), so the rate ratios are those of the one-arch functions to the last bit
or, where the 5 x 5 solve of the 'paper' model goes through another LAPACK build, to ~1e-16.
Without numba the same functions run as Python (and the solve is numpy's).

Returned codes per direction (l_to_r, r_to_l): 0 a ratio, :data:`SINGULAR` the 'paper' model's
momentum equations are singular (the one-arch path raises ImpactModelError); the checks on
energy gain and sign are left to the caller, which words the messages as
:func:`archrock.dynamics.impact.laws.impact_law` does.
"""

from __future__ import annotations

import numpy as np

from ..._jit import HAVE_NUMBA, maybe_njit, numba
from ..._pairwise import _pairwise, np_sum
from ..fourlink import rates

__all__ = ["np_sum", "rate_ratios_batch", "MOMENTUM", "PAPER", "SINGULAR"]

MOMENTUM, PAPER = 0, 1
SINGULAR = 1


@maybe_njit
def _links(joints, is_r):
    """(first, end) voussoir of links 1, 2, 3 of a mechanism (FourLink.link_voussoirs):
    from the leading side, so reversed for M_r."""
    out = np.empty((3, 2), dtype=np.int64)
    for k in range(3):
        src = 2 - k if is_r else k
        out[k, 0] = joints[src]
        out[k, 1] = joints[src + 1]
    return out


@maybe_njit
def _field(cen, geo, links, v, w):
    """FourLink.voussoir_field at phi = 0 into v (n, 2), w (n,): zero outside the mechanism."""
    t1, t2, t3, _, _, _ = rates(0.0, geo)
    ax, ay = geo[0], geo[1]
    bx, by = geo[2], geo[3]
    dx, dy = geo[6], geo[7]
    v[:, :] = 0.0
    w[:] = 0.0
    for k in range(3):
        if k == 0:
            th, rx0, ry0 = t1, ax, ay
        elif k == 1:
            th, rx0, ry0 = t2, bx, by
        else:
            th, rx0, ry0 = t3, dx, dy
        for i in range(links[k, 0], links[k, 1]):
            rx = cen[i, 0] - rx0
            ry = cen[i, 1] - ry0
            vx = th * (-ry)
            vy = th * rx
            if k == 1:  # link 2 moves with B's velocity plus its own rotation about B
                vx = vx + t1 * (-(by - ay))
                vy = vy + t1 * (bx - ax)
            v[i, 0] = vx
            v[i, 1] = vy
            w[i] = th


@maybe_njit
def _momentum(mass, inert, v, w, vn, wn, tmp):
    """projection_ratio: c = max(0, -sum(m v'.v + I w' w) / sum(m |v'|^2 + I w'^2))."""
    n = mass.size
    for i in range(n):
        tmp[i] = mass[i] * (vn[i, 0] * v[i, 0] + vn[i, 1] * v[i, 1]) + inert[i] * wn[i] * w[i]
    s = np_sum(tmp)
    for i in range(n):
        tmp[i] = mass[i] * (vn[i, 0] * vn[i, 0] + vn[i, 1] * vn[i, 1]) + inert[i] * wn[i] * wn[i]
    m_new = np_sum(tmp)
    return max(0.0, -s / m_new)


@maybe_njit
def _ang(lo, hi, qx, qy, g, m, inertia, vel, om, tmp):
    """Angular momentum about q of voussoirs lo..hi-1 (paper_rate_ratio's ``ang``)."""
    k = hi - lo
    for j in range(k):
        i = lo + j
        rx = g[i, 0] - qx
        ry = g[i, 1] - qy
        tmp[j] = inertia[i] * om[i] + m[i] * (rx * vel[i, 1] - ry * vel[i, 0])
    return _pairwise(tmp, 0, k)


@maybe_njit
def _paper(px, py, mass, cen, inert, joints, edges, is_r, links, ref, mref, v, w, vn, wn,
           tmp):
    """paper_rate_ratio(old, new) (De Lorenzis et al.'s five equations on the old links) from
    the old mechanism's hinges (joints, edges from the left springing; leading side first for
    M_r through ``links``) and both velocity fields.  Returns (c, singular)."""
    # nondimensional, exactly as the one-arch function
    vs = v / ref
    vns = vn / ref
    m = mass / mref
    inertia = inert / (mref * ref * ref)
    g = cen / ref
    # closing points A*, B*, C*, D*: the opposite edge of each old hinge's joint, leading first
    sx = np.empty(4)
    sy = np.empty(4)
    for k in range(4):
        kk = 3 - k if is_r else k
        e = 1 - edges[kk]
        sx[k] = px[joints[kk], e] / ref
        sy[k] = py[joints[kk], e] / ref
    pre = -1.0
    A = np.zeros((5, 5))
    b = np.zeros(5)
    l1a, l1b = links[0, 0], links[0, 1]
    l2a, l2b = links[1, 0], links[1, 1]
    l3a, l3b = links[2, 0], links[2, 1]
    # L1 about A*
    A[0, 0] = _ang(l1a, l1b, sx[0], sy[0], g, m, inertia, vns, wn, tmp)
    rx, ry = sx[1] - sx[0], sy[1] - sy[0]
    A[0, 1] = -ry
    A[0, 2] = rx
    b[0] = pre * _ang(l1a, l1b, sx[0], sy[0], g, m, inertia, vs, w, tmp)
    # L3 about D*
    A[1, 0] = _ang(l3a, l3b, sx[3], sy[3], g, m, inertia, vns, wn, tmp)
    rx, ry = sx[2] - sx[3], sy[2] - sy[3]
    A[1, 3] = -(-ry)
    A[1, 4] = -rx
    b[1] = pre * _ang(l3a, l3b, sx[3], sy[3], g, m, inertia, vs, w, tmp)
    # L2 linear: sums down the column, in order (numpy's axis-0 sum)
    pnx = m[l2a] * vns[l2a, 0]
    pny = m[l2a] * vns[l2a, 1]
    pox = m[l2a] * vs[l2a, 0]
    poy = m[l2a] * vs[l2a, 1]
    for i in range(l2a + 1, l2b):
        pnx += m[i] * vns[i, 0]
        pny += m[i] * vns[i, 1]
        pox += m[i] * vs[i, 0]
        poy += m[i] * vs[i, 1]
    A[2, 0] = pnx
    A[3, 0] = pny
    A[2, 1] = -1.0
    A[3, 2] = -1.0
    A[2, 3] = 1.0
    A[3, 4] = 1.0
    b[2] = pre * pox
    b[3] = pre * poy
    # L2 about B*
    A[4, 0] = _ang(l2a, l2b, sx[1], sy[1], g, m, inertia, vns, wn, tmp)
    rx, ry = sx[2] - sx[1], sy[2] - sy[1]
    A[4, 3] = -ry
    A[4, 4] = rx
    b[4] = pre * _ang(l2a, l2b, sx[1], sy[1], g, m, inertia, vs, w, tmp)
    return _solve_first(A, b)


def _solve_first_py(A, b):
    try:
        return float(np.linalg.solve(A, b)[0]), 0
    except np.linalg.LinAlgError:
        return np.nan, SINGULAR


if HAVE_NUMBA:
    @maybe_njit
    def _solve_first(A, b):
        """x[0] of A x = b (LAPACK gesv, as numpy's solve), or (nan, SINGULAR)."""
        try:
            x = np.linalg.solve(A, b)
        except Exception:  # noqa: BLE001 - numba raises LinAlgError-like errors
            return np.nan, SINGULAR
        return x[0], 0
else:  # pragma: no cover - without numba
    _solve_first = _solve_first_py


@maybe_njit
def _one(b, model, px, py, mass, cen, inert, jl, el, jr, er, geo_l, geo_r, ref, mref, c_lr,
         c_rl, code_lr, code_rl):
    n = mass.shape[1]
    v_l = np.zeros((n, 2))
    w_l = np.zeros(n)
    v_r = np.zeros((n, 2))
    w_r = np.zeros(n)
    tmp = np.zeros(n)
    links_l = _links(jl[b], False)
    links_r = _links(jr[b], True)
    _field(cen[b], geo_l[b], links_l, v_l, w_l)
    _field(cen[b], geo_r[b], links_r, v_r, w_r)
    if model == MOMENTUM:
        c_lr[b] = _momentum(mass[b], inert[b], v_l, w_l, v_r, w_r, tmp)
        c_rl[b] = _momentum(mass[b], inert[b], v_r, w_r, v_l, w_l, tmp)
    else:
        c, k = _paper(px[b], py[b], mass[b], cen[b], inert[b], jl[b], el[b], False, links_l, ref[b],
                      mref[b], v_l, w_l, v_r, w_r, tmp)
        c_lr[b], code_lr[b] = c, k
        c, k = _paper(px[b], py[b], mass[b], cen[b], inert[b], jr[b], er[b], True, links_r, ref[b],
                      mref[b], v_r, w_r, v_l, w_l, tmp)
        c_rl[b], code_rl[b] = c, k


def _loop_py(run, *args):
    for b in range(run.size):
        if run[b]:
            _one(b, *args)


if HAVE_NUMBA:
    @maybe_njit(parallel=True)
    def _loop_nb(run, model, px, py, mass, cen, inert, jl, el, jr, er, geo_l, geo_r, ref, mref,
                 c_lr, c_rl, code_lr, code_rl):
        for b in numba.prange(run.size):
            if run[b]:
                _one(b, model, px, py, mass, cen, inert, jl, el, jr, er, geo_l, geo_r, ref, mref,
                     c_lr, c_rl, code_lr, code_rl)

    _loop_serial = maybe_njit(_loop_py)
else:  # pragma: no cover - without numba
    _loop_nb = _loop_serial = None


def rate_ratios_batch(model: str, run, px, py, mass, cen, inert, jl, el, jr, er, geo_l, geo_r,
                      ref, mref, parallel: bool = True):
    """Rate ratios (c_l_to_r, c_r_to_l) and codes of the 'paper' or 'momentum' model for the
    arches ``run`` (bool (B,)) of a batch: joint points px, py (B, n+1, 2) [m], masses (B, n)
    [kg], centroids (B, n, 2) [m], inertias (B, n) [kg m^2], hinges jl, el, jr, er (B, 4) from
    the left springing, four-link vectors geo_l, geo_r (B, 21); ``ref`` (B,) the reference
    length [m] and ``mref`` (B,) the power of two nearest the total mass that the 'paper' model
    divides by.  Rows not run are NaN."""
    B = run.size
    c_lr = np.full(B, np.nan)
    c_rl = np.full(B, np.nan)
    code_lr = np.zeros(B, dtype=np.int64)
    code_rl = np.zeros(B, dtype=np.int64)
    args = (np.ascontiguousarray(run, dtype=np.bool_), MOMENTUM if model == "momentum" else PAPER,
            *(np.ascontiguousarray(a, dtype=float) for a in (px, py, mass, cen, inert)),
            *(np.ascontiguousarray(a, dtype=np.int64) for a in (jl, el, jr, er)),
            *(np.ascontiguousarray(a, dtype=float) for a in (geo_l, geo_r, ref, mref)),
            c_lr, c_rl, code_lr, code_rl)
    if not HAVE_NUMBA:
        _loop_py(*args)
    elif parallel:
        _loop_nb(*args)
    else:
        _loop_serial(*args)
    return c_lr, c_rl, code_lr, code_rl
