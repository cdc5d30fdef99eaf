"""Many responses in one parallel call: arches x ground motions x scale factors.

A study that searches for a collapse boundary (IDA's first collapse, multiple stripes, the
collapse-acceleration curves) runs thousands of responses whose only outputs are the outcome and
a few numbers.  :func:`sweep` runs a list of *items*, each a triple (arch index, motion index,
scale factor), in one numba ``prange`` loop over the items: item k integrates
``motions[m].scaled(scale)`` on arch b with the RK4 state machine of
:func:`archrock.dynamics.kernel.simulate_chain`, the very function :func:`archrock.dynamics.response.respond`
calls.

Exactness.  :meth:`SweepArches.from_models` packs prepared :class:`~archrock.dynamics.response.DynamicModel`
objects with the numbers ``respond`` reads, through the same packer
(:func:`archrock.dynamics.chain.pack_chains`): the same chain (four-link vectors, rotation limits,
unstable rotations, successors and rate ratios), the same tables (``model.tables``, built
once per arch instead of once per item), ``v_rest``, k_l, k_r, and per arch the step ``dt`` and
free-motion cap ``t_free`` of :func:`archrock.dynamics.response.default_steps`.  The scaled acceleration is
``accel * scale`` as :meth:`GroundMotion.scaled` computes it, and the output sampling does not
enter the dynamics.  An item therefore has bit for bit the outcome, peak and times of
``respond(model, motion.scaled(scale))``; tests/dynamics/test_sweep.py checks this.  (An arch prepared by
:func:`archrock.dynamics.batch.prepare_batch` agrees with ``prepare`` only to about 1e-13, so
:meth:`SweepArches.from_batch` is offered for speed, not for identity.)

On a GPU (``device="gpu"``) the items run one per GPU thread (:mod:`archrock.dynamics.gpusweep`)
through the same per-item body, :func:`sweep_item`, which allocates nothing: the CPU loops give
it buffers of their own per item, the GPU kernel per-thread scratch.  The outcomes are the
CPU's; rotations and times may differ in their last bits where the GPU fuses a multiply and
an add (docs/gpu.md).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from . import kernel as K
from .._device import resolve_device
from .._jit import HAVE_NUMBA, maybe_njit, numba
from ..errors import ArchInputError, LimitExceededError
from ..groundmotion import G, GroundMotion
from .chain import pack_chains
from .fourlink import build_table, check_table_intervals, init_table, table_size
from .kernel import ST_COLLAPSED as K_ST_COLLAPSED
from .kernel import run_chain as K_run_chain

__all__ = ["SweepArches", "SweepMotions", "sweep", "sweep_item", "SWEEP_EVENTS"]

#: rows of the event table of each item: the sweep needs the outcome only (the kernel keeps
#: integrating past the table and still counts the events, so a run beyond ``max_events`` of
#: ``respond`` is still detected).
SWEEP_EVENTS = 64


@dataclass(frozen=True, eq=False)
class SweepArches:
    """B arches packed for :func:`sweep`: per arch its chain of R rows (padded), each row the
    four-link vector with its tables (``rows`` (B, R, S)), rotation limits and unstable
    rotations [rad], directions (+1 l, -1 r), successor rows and rate ratios, the number of rows
    used, k_l, k_r, v_rest [rad/s] and the RK4 step ``dt`` and free-motion cap ``t_free`` [s]."""

    rows: np.ndarray
    n_rows: np.ndarray
    limits: np.ndarray
    unstable: np.ndarray
    directions: np.ndarray
    nexts: np.ndarray
    ratios: np.ndarray
    k_l: np.ndarray
    k_r: np.ndarray
    v_rest: np.ndarray
    dt: np.ndarray
    t_free: np.ndarray

    def __len__(self) -> int:
        return int(self.k_l.size)

    def arrays(self) -> dict:
        """The fields as a dict of arrays (what a worker process receives)."""
        return {k: getattr(self, k) for k in self.__dataclass_fields__}

    @classmethod
    def from_arrays(cls, d: dict) -> "SweepArches":
        return cls(**d)

    @classmethod
    def from_models(cls, models, dt: float | None = None, t_free: float | None = None,
                    tabulate: bool = True) -> "SweepArches":
        """Pack prepared models (module doc: the numbers ``respond`` reads).  dt, t_free [s]:
        as ``respond``'s (None: :func:`~archrock.dynamics.response.default_steps` of each arch)."""
        from .response import DynamicModel, default_steps

        ms = list(models)
        if not ms or not all(isinstance(m, DynamicModel) for m in ms):
            raise ArchInputError("models: allowed a non-empty list of DynamicModel")
        B = len(ms)
        c = pack_chains([m.chain for m in ms], rows=[m.tables for m in ms] if tabulate else None)
        dts = np.zeros(B)
        frees = np.zeros(B)
        for b, m in enumerate(ms):
            d0, f0 = default_steps(m.arch)
            dts[b] = d0 if dt is None else dt
            frees[b] = f0 if t_free is None else t_free
        return cls(c["rows"], c["n_rows"], c["limit"], c["unstable"], c["direction"], c["next"],
                   c["ratio"], np.array([m.k_l for m in ms], float),
                   np.array([m.k_r for m in ms], float), np.array([m.v_rest for m in ms], float),
                   dts, frees)

    @classmethod
    def from_batch(cls, prepared, dt: float = 2e-3, t_free: float = 60.0,
                   tabulate: bool = True, table_intervals: int = 600) -> "SweepArches":
        """Pack the usable arches of a :class:`archrock.dynamics.batch.PreparedBatch` (in order; the
        unusable ones are dropped, so index i is the i-th usable arch), with one ``dt`` and
        ``t_free`` [s] as :func:`archrock.dynamics.batch.simulate_batch` takes them."""
        ok = np.flatnonzero(prepared.ok & (prepared.n_mechanisms >= 2))
        if ok.size == 0:
            raise ArchInputError("prepared: no usable arch in the batch")
        R = int(prepared.n_mechanisms[ok].max())
        geo = np.ascontiguousarray(prepared.chain_geo[ok, :R], dtype=float)
        if tabulate:
            n = check_table_intervals(table_intervals)
            rows = np.zeros((ok.size, R, table_size(n)))
            _tables(geo, np.ascontiguousarray(prepared.chain_table[ok, :R], dtype=float),
                    prepared.n_mechanisms[ok].astype(np.int64), n, rows)
        else:
            rows = geo
        B = ok.size
        return cls(rows, prepared.n_mechanisms[ok].astype(np.int64),
                   np.ascontiguousarray(prepared.chain_limit[ok, :R], dtype=float),
                   np.ascontiguousarray(prepared.chain_unstable[ok, :R], dtype=float),
                   np.ascontiguousarray(prepared.chain_direction[ok, :R], dtype=float),
                   np.ascontiguousarray(prepared.chain_next[ok, :R], dtype=np.int64),
                   np.ascontiguousarray(prepared.chain_ratio[ok, :R], dtype=float),
                   prepared.k_l[ok].astype(float), prepared.k_r[ok].astype(float),
                   prepared.v_rest[ok].astype(float), np.full(B, float(dt)),
                   np.full(B, float(t_free)))


@maybe_njit
def _tables(geo, ranges, n_rows, n, out):
    for b in range(geo.shape[0]):
        for j in range(n_rows[b]):
            init_table(out[b, j], geo[b, j], ranges[b, j, 0], ranges[b, j, 1], n)
            build_table(out[b, j])


@dataclass(frozen=True, eq=False)
class SweepMotions:
    """Ground motions packed end to end: motion m is ``times[offsets[m]:offsets[m + 1]]`` [s]
    and ``accel[...]`` [m/s^2], read once and shared by every item (and every worker)."""

    times: np.ndarray
    accel: np.ndarray
    offsets: np.ndarray
    names: tuple = ()

    def __len__(self) -> int:
        return int(self.offsets.size - 1)

    @classmethod
    def of(cls, motions) -> "SweepMotions":
        ms = [motions] if isinstance(motions, GroundMotion) else list(motions)
        if not ms or not all(isinstance(m, GroundMotion) for m in ms):
            raise ArchInputError("motions: allowed a non-empty list of GroundMotion")
        off = np.zeros(len(ms) + 1, dtype=np.int64)
        off[1:] = np.cumsum([m.times.size for m in ms])
        return cls(np.ascontiguousarray(np.concatenate([m.times for m in ms]), dtype=float),
                   np.ascontiguousarray(np.concatenate([m.accel for m in ms]), dtype=float),
                   off, tuple(m.name for m in ms))

    def arrays(self) -> dict:
        return {"times": self.times, "accel": self.accel, "offsets": self.offsets,
                "names": self.names}


# ---------------------------------------------------------------------------- kernel
#: whether the kernel offers the early stop of a run that can no longer collapse
#: (``kernel.run_chain``: after the ground motion, at an impact from which the energy is below
#: every mechanism's barrier under an impact law that never adds energy); always, since 0.5
HAVE_EARLY_STOP = True


@maybe_njit
def sweep_item(k, accel_buf, out, ev, arch, motion, scale, rows, n_rows, lims, phus, dirs,
               modes, ratios, k_l, k_r, v_rest, dts, t_frees, m_times, m_accel, m_off, g,
               max_events, early_stop, status, peak, t_col, t_uns, t_lim, n_ev):
    """Integrate item k and write its summary into the output arrays, allocating nothing: the
    one per-item body of the CPU loops and of the GPU kernel (:mod:`.gpusweep`).  Scratch:
    ``accel_buf`` (at least the item's motion's length) receives the scaled acceleration,
    ``out`` (1,) and ``ev`` (rows, 6) are run_chain's.  ``modes``: the chain's next rows + 1
    (kernel modes, 0 = rest), computed once by the host.  ``rows`` are shared by every item of
    an arch and only read (their tables are built by the host; an interval the kernel lacked
    would be built in place with the same numbers by whichever item reaches it)."""
    b = arch[k]
    m = motion[k]
    R = n_rows[b]
    lo = m_off[m]
    n = m_off[m + 1] - lo
    s = scale[k]
    # exactly GroundMotion.scaled (accel * factor), element by element: no array is made
    for q in range(n):
        accel_buf[q] = m_accel[lo + q] * s
    _, ne, st, tf, pk, tc, tu, _, _ = K_run_chain(
        out, ev, rows[b, :R], lims[b, :R], phus[b, :R], dirs[b, :R], modes[b, :R],
        ratios[b, :R], k_l[b], k_r[b], v_rest[b], m_times[lo:lo + n], accel_buf[:n], g, 1.0,
        dts[b], t_frees[b], max_events, early_stop)
    status[k] = st
    peak[k] = pk
    t_col[k] = tc
    t_uns[k] = tu
    t_lim[k] = tf if st == K_ST_COLLAPSED else -1.0
    n_ev[k] = ne


@maybe_njit
def _sweep_one(k, arch, motion, scale, rows, n_rows, lims, phus, dirs, modes, ratios, k_l, k_r,
               v_rest, dts, t_frees, m_times, m_accel, m_off, g, max_events, early_stop, status,
               peak, t_col, t_uns, t_lim, n_ev):
    """:func:`sweep_item` with buffers of its own (the CPU loops): those
    ``kernel.simulate_chain_stop`` gave it before, so the same bits."""
    m = motion[k]
    sweep_item(k, np.empty(m_off[m + 1] - m_off[m]), np.zeros(1),
               np.zeros((min(max_events, K.EVENT_ROWS), 6)), arch, motion, scale, rows, n_rows,
               lims, phus, dirs, modes, ratios, k_l, k_r, v_rest, dts, t_frees, m_times,
               m_accel, m_off, g, max_events, early_stop, status, peak, t_col, t_uns, t_lim,
               n_ev)


def _sweep_loop_py(arch, motion, scale, rows, n_rows, lims, phus, dirs, modes, ratios, k_l, k_r,
                   v_rest, dts, t_frees, m_times, m_accel, m_off, g, max_events, early_stop,
                   status, peak, t_col, t_uns, t_lim, n_ev):
    for k in range(arch.size):
        _sweep_one(k, arch, motion, scale, rows, n_rows, lims, phus, dirs, modes, ratios, k_l,
                   k_r, v_rest, dts, t_frees, m_times, m_accel, m_off, g, max_events, early_stop,
                   status, peak, t_col, t_uns, t_lim, n_ev)


if HAVE_NUMBA:
    @maybe_njit(parallel=True)
    def _sweep_loop_nb(arch, motion, scale, rows, n_rows, lims, phus, dirs, modes, ratios, k_l,
                       k_r, v_rest, dts, t_frees, m_times, m_accel, m_off, g, max_events, early_stop,
                       status, peak, t_col, t_uns, t_lim, n_ev):
        for k in numba.prange(arch.size):
            _sweep_one(k, arch, motion, scale, rows, n_rows, lims, phus, dirs, modes, ratios,
                       k_l, k_r, v_rest, dts, t_frees, m_times, m_accel, m_off, g, max_events,
                       early_stop, status, peak, t_col, t_uns, t_lim, n_ev)

    _sweep_loop_serial = maybe_njit(_sweep_loop_py)
else:  # pragma: no cover - without numba
    _sweep_loop_nb = _sweep_loop_serial = None


def sweep(arches: SweepArches, motions: SweepMotions, arch_index, motion_index, scales, *,
          parallel: bool = True, max_events: int | None = None, early_stop: bool = False,
          device: str = "cpu") -> dict:
    """Responses of the items (arch_index[k], motion_index[k], scales[k]) (module doc).

    Returns a dict of arrays (N,): status (0 rest, 1 collapsed, 2 still moving, 3 stopped
    early), peak [rad],
    t_collapse, t_unstable, t_limit [s] (NaN if never), n_events; plus 'seconds', 'device'
    (where it ran) and, on a GPU, 'gpu' (:func:`archrock.dynamics.gpusweep.sweep_gpu`'s split
    of the time).
    max_events: as ``respond``'s: an item with more events raises LimitExceededError, as
    ``respond`` does (None: no bound; an early-stopped item has counted fewer events than the
    full run would).  early_stop: end an item once it can no longer collapse (status 3, see
    :data:`HAVE_EARLY_STOP`; ignored where the kernel lacks it): its outcome is final, its
    peak, times to rest and event count are not.  parallel: the numba prange loop (all numba threads);
    otherwise a serial compiled loop (one worker process = one core); Python without numba.
    device: 'cpu', 'gpu' or 'auto' (:func:`archrock._device.resolve_device`, on the number of
    items): on 'gpu' one item per GPU thread (:mod:`archrock.dynamics.gpusweep`), the same
    per-item source (:func:`sweep_item`).
    """
    t0 = time.perf_counter()
    a = np.ascontiguousarray(arch_index, dtype=np.int64).ravel()
    m = np.ascontiguousarray(motion_index, dtype=np.int64).ravel()
    s = np.ascontiguousarray(scales, dtype=float).ravel()
    if not (a.size == m.size == s.size):
        raise ArchInputError(f"arch_index, motion_index, scales: lengths {a.size}, {m.size}, "
                             f"{s.size}; allowed equal lengths")
    if a.size and (a.min() < 0 or a.max() >= len(arches)):
        raise ArchInputError(f"arch_index: allowed 0..{len(arches) - 1}")
    if m.size and (m.min() < 0 or m.max() >= len(motions)):
        raise ArchInputError(f"motion_index: allowed 0..{len(motions) - 1}")
    if not np.all(np.isfinite(s)):
        raise ArchInputError("scales: allowed finite numbers")
    N = a.size
    res = {"status": np.zeros(N, dtype=np.int64), "peak": np.zeros(N),
           "t_collapse": np.zeros(N), "t_unstable": np.zeros(N), "t_limit": np.zeros(N),
           "n_events": np.zeros(N, dtype=np.int64)}
    p = arches
    # the kernel builds table intervals it lacks in place (none are lacking in packed tables,
    # but a compiled writer needs a writable array: Dask hands read-only buffers)
    rows = p.rows if p.rows.flags.writeable else p.rows.copy()
    ran_on = resolve_device(device, N)
    # kernel modes (next row + 1, 0 = rest): once per call, not once per item
    modes = np.ascontiguousarray(p.nexts + 1, dtype=np.int64)
    args = (a, m, s, rows, p.n_rows, p.limits, p.unstable, p.directions, modes, p.ratios,
            p.k_l, p.k_r, p.v_rest, p.dt, p.t_free, motions.times, motions.accel,
            motions.offsets, G, SWEEP_EVENTS, bool(early_stop), res["status"], res["peak"],
            res["t_collapse"], res["t_unstable"], res["t_limit"], res["n_events"])
    if N:
        if ran_on == "gpu":
            from .gpusweep import sweep_gpu

            res["gpu"] = sweep_gpu(args, sweep_item)
        elif HAVE_NUMBA:
            (_sweep_loop_nb if parallel else _sweep_loop_serial)(*args)
        else:
            _sweep_loop_py(*args)
    if max_events is not None and N and res["n_events"].max() > max_events:
        raise LimitExceededError(f"max_events: more than {max_events} events; raise max_events")
    for key in ("t_collapse", "t_limit", "t_unstable"):
        res[key][res[key] < 0] = np.nan
    res["device"] = ran_on
    res["seconds"] = time.perf_counter() - t0
    return res
