"""The batch's response: one ground motion integrated for every arch of a
:class:`~archrock.dynamics.batch.PreparedBatch` by a numba ``prange`` loop over the arches of the
single-response kernel :func:`archrock.dynamics.kernel.simulate_chain_stop` (no output samples),
returning per-arch summaries (:func:`simulate_batch`, importable from
:mod:`archrock.dynamics.batch` as ever).  Without numba the same loop runs in Python.
"""

from __future__ import annotations

import time

import numpy as np

from . import kernel as K
from .._device import resolve_device
from .._jit import HAVE_NUMBA, maybe_njit, numba
from ..errors import ArchInputError
from ..groundmotion import G, GroundMotion
from .kernel import ST_COLLAPSED as K_ST_COLLAPSED
from .kernel import run_chain as K_run_chain
from .tables import check_table_intervals, init_table, table_size

__all__ = ["simulate_batch", "STATUS_NAMES", "ST_NOT_RUN", "MAX_EVENTS"]

#: status codes of :func:`simulate_batch` (those of the kernel, plus -1 not run / failed).
STATUS_NAMES = {K.ST_REST: "rest", K.ST_COLLAPSED: "collapsed", K.ST_MOVING: "moving",
                K.ST_STOPPED: "stopped"}
ST_NOT_RUN = -1
#: event-table size per response in the batch kernel (the paper's pulse needs about 100).  The
#: kernel keeps integrating past it (status, peak, times and the counts of impacts and
#: activations stay exact); ``events_truncated`` says the table itself was cut.
MAX_EVENTS = 4096


@maybe_njit
def chain_rows(b, rows, geos, tabs, n_rows, n_tab):
    """Write arch b's chain into ``rows`` (at least n_rows[b] rows): empty tables of
    ``n_tab`` intervals, built interval by interval as the motion reaches them
    (mechanism.init_table), or with ``n_tab`` 0 the four-link vectors themselves."""
    for j in range(n_rows[b]):
        if n_tab > 0:
            init_table(rows[j], geos[b, j], tabs[b, j, 0], tabs[b, j, 1], n_tab)
        else:
            for q in range(geos.shape[2]):
                rows[j, q] = geos[b, j, q]


@maybe_njit
def summary_one(b, rows, out, ev, n_rows, k_l, k_r, lims, phus, dirs, modes, ratios, v_rest,
                times, accel, g, dt, t_free, max_events, status, peak, t_col, t_uns, t_lim,
                n_imp, n_act, n_ev, early_stop):
    """Integrate arch b over its chain ``rows`` (:func:`chain_rows`) and write its summary into
    the output arrays; ``out`` (1,) and ``ev`` (k, 6) are its scratch buffers.  The one
    per-arch body of both builds: the CPU loops and the GPU kernel
    (:mod:`archrock.dynamics.gpubatch`).  ``modes``: the chain's next rows + 1 (kernel modes,
    0 = rest)."""
    R = n_rows[b]
    _, ne, st, tf, pk, tc, tu, ni, na = K_run_chain(
        out, ev, rows[:R], lims[b, :R], phus[b, :R], dirs[b, :R], modes[b, :R],
        ratios[b, :R], k_l[b], k_r[b], v_rest[b], times, accel, g, 1.0, dt, t_free,
        max_events, early_stop)
    status[b] = st  # complete even when the event table overflowed (ne > max_events)
    peak[b] = pk
    t_col[b] = tc
    t_uns[b] = tu
    t_lim[b] = tf if st == K_ST_COLLAPSED else -1.0
    n_imp[b] = ni
    n_act[b] = na
    n_ev[b] = ne


@maybe_njit
def _simulate_one(b, geos, tabs, n_rows, n_tab, k_l, k_r, lims, phus, dirs, modes, ratios,
                  v_rest, times, accel, g, dt, t_free, max_events, status, peak, t_col, t_uns,
                  t_lim, n_imp, n_act, n_ev, early_stop):
    """:func:`summary_one` of arch b with buffers of its own (the CPU loops)."""
    R = n_rows[b]
    rows = np.empty((R, table_size(n_tab) if n_tab > 0 else geos.shape[2]))
    chain_rows(b, rows, geos, tabs, n_rows, n_tab)
    ev = np.zeros((min(max_events, K.EVENT_ROWS), 6))
    summary_one(b, rows, np.zeros(1), ev, n_rows, k_l, k_r, lims, phus,
                dirs, modes, ratios, v_rest, times, accel, g, dt, t_free, max_events, status,
                peak, t_col, t_uns, t_lim, n_imp, n_act, n_ev, early_stop)


def _simulate_loop_py(geos, tabs, n_rows, n_tab, k_l, k_r, lims, phus, dirs, nexts, ratios,
                      v_rest, run, times, accel, g, dt, t_free, max_events, status, peak, t_col,
                      t_uns, t_lim, n_imp, n_act, n_ev, early_stop):
    for b in range(geos.shape[0]):
        if run[b]:
            _simulate_one(b, geos, tabs, n_rows, n_tab, k_l, k_r, lims, phus, dirs, nexts, ratios,
                          v_rest, times, accel, g, dt, t_free, max_events, status, peak, t_col,
                          t_uns, t_lim, n_imp, n_act, n_ev, early_stop)


if HAVE_NUMBA:
    @maybe_njit(parallel=True)
    def _simulate_loop_nb(geos, tabs, n_rows, n_tab, k_l, k_r, lims, phus, dirs, nexts, ratios,
                          v_rest, run, times, accel, g, dt, t_free, max_events, status, peak,
                          t_col, t_uns, t_lim, n_imp, n_act, n_ev, early_stop):
        for b in numba.prange(geos.shape[0]):
            if run[b]:
                _simulate_one(b, geos, tabs, n_rows, n_tab, k_l, k_r, lims, phus, dirs, nexts,
                              ratios, v_rest, times, accel, g, dt, t_free, max_events, status,
                              peak, t_col, t_uns, t_lim, n_imp, n_act, n_ev, early_stop)

    _simulate_loop_serial = maybe_njit(_simulate_loop_py)
else:  # pragma: no cover - without numba
    _simulate_loop_nb = _simulate_loop_serial = None


def simulate_batch(prepared, motion: GroundMotion, *, dt: float = 2e-3,
                   t_free: float = 60.0, max_events: int = MAX_EVENTS, parallel: bool = True,
                   tabulate: bool = True, table_intervals: int = 600,
                   early_stop: bool = False, device: str = "cpu") -> dict:
    """Response of every usable arch of ``prepared`` (a ``PreparedBatch``) to ``motion`` (RK4
    kernel, step ``dt`` [s], free motion after the record at most ``t_free`` [s]).

    Returns a dict of arrays (B,): status (0 rest, 1 collapsed, 2 still moving, -1 not run:
    unusable arch), peak [rad], t_collapse [s] (the last upward passage of the unstable position
    before the rotation limit, independent of the limit), t_limit [s] (when the limit, a
    numerical stop, was reached), t_unstable [s] (its first passage) (each NaN if never), n_impacts,
    n_activations, events_truncated (more than ``max_events`` events: status, peak and times are
    still exact, and so are n_impacts and n_activations, counted as they happen); plus 'seconds',
    'device' (where it ran) and, on a GPU, 'gpu' (:func:`archrock.dynamics.gpubatch.simulate_gpu`'s
    split of the time).
    ``tabulate``: the kernel reads phi'' from tables of ``table_intervals`` intervals (as
    ``respond(..., tabulate=True)``, relative error ~2e-9), each interval built inside the loop
    when the arch's motion first reaches it; otherwise the exact loop closure.
    ``parallel`` uses the numba prange loop (all numba threads); otherwise a serial compiled loop
    (for process-pool or Dask workers); a Python loop when numba is absent.
    ``early_stop``: an arch is no longer followed from the first impact after the ground motion
    from which it can neither collapse nor exceed its peak (:func:`archrock.dynamics.kernel.cannot_collapse`:
    energy below every reachable mechanism's barrier under impacts that never add energy); its
    status is then 3 ("stopped", ``early_stopped`` True): not collapsed, peak and t_unstable
    final, n_impacts / n_activations only those before the stop, no time of rest.  Status,
    collapse and peak of every arch are those of the full run.
    ``device``: 'cpu', 'gpu' or 'auto' (:func:`archrock._device.resolve_device`): on 'gpu' one
    arch per GPU thread (:mod:`archrock.dynamics.gpubatch`), the same source; outcomes equal,
    rotations and times to the tolerance of docs/gpu.md.
    """
    if not isinstance(motion, GroundMotion):
        raise ArchInputError(f"motion: expected a GroundMotion, got {type(motion).__name__}")
    t0 = time.perf_counter()
    B = len(prepared)
    run = np.ascontiguousarray(prepared.ok)
    res = {"status": np.full(B, ST_NOT_RUN, dtype=np.int64), "peak": np.full(B, np.nan),
           "t_collapse": np.full(B, np.nan), "t_limit": np.full(B, np.nan),
           "t_unstable": np.full(B, np.nan),
           "n_impacts": np.zeros(B, dtype=np.int64), "n_activations": np.zeros(B, dtype=np.int64),
           "n_events": np.zeros(B, dtype=np.int64)}
    times = np.ascontiguousarray(motion.times, dtype=float)
    accel = np.ascontiguousarray(motion.accel, dtype=float)
    p = prepared
    run = run & (p.n_mechanisms >= 2)
    args = (np.ascontiguousarray(p.chain_geo, dtype=float),
            np.ascontiguousarray(p.chain_table, dtype=float), p.n_mechanisms.astype(np.int64),
            check_table_intervals(table_intervals) if tabulate else 0, p.k_l, p.k_r,
            np.ascontiguousarray(p.chain_limit, dtype=float),
            np.ascontiguousarray(p.chain_unstable, dtype=float),
            np.ascontiguousarray(p.chain_direction, dtype=float),
            np.ascontiguousarray(p.chain_next + 1, dtype=np.int64),
            np.ascontiguousarray(p.chain_ratio, dtype=float), p.v_rest, run, times, accel, G,
            float(dt), float(t_free), int(max_events), res["status"], res["peak"],
            res["t_collapse"], res["t_unstable"], res["t_limit"], res["n_impacts"],
            res["n_activations"], res["n_events"], bool(early_stop))
    ran_on = resolve_device(device, int(run.sum()))
    if ran_on == "gpu":
        from .gpubatch import simulate_gpu

        res["gpu"] = simulate_gpu(args, chain_rows, summary_one)
    elif HAVE_NUMBA:
        (_simulate_loop_nb if parallel else _simulate_loop_serial)(*args)
    else:
        _simulate_loop_py(*args)
    for key in ("t_collapse", "t_limit", "t_unstable"):
        res[key][res[key] < 0] = np.nan
    res["events_truncated"] = res.pop("n_events") > int(max_events)
    res["early_stopped"] = res["status"] == K.ST_STOPPED
    res["device"] = ran_on
    res["seconds"] = time.perf_counter() - t0
    return res
