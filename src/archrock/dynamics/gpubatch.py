"""The batch's compiled stages on an NVIDIA GPU: one arch per GPU thread.

The four-link preparation (:func:`archrock.dynamics.batch._prepare_one`: mechanisms, dead
points, unstable rotations, limits, table ranges, v_rest) and the response
(:func:`archrock.dynamics.batchsim.summary_one`: the RK4 state machine with impacts, mechanism
switching and early stop) run from the same Python source as on the CPU, compiled for numba's
CUDA target by :mod:`archrock._device`; the four-hinge search is
:mod:`archrock.statics.gpusearch`.  The ground motion and the batch's arrays are copied to the
GPU once per call; each arch's tables (``tabulate``) live in a scratch block of device memory
reused chunk after chunk, so a batch of any size runs in the memory it is given.  Only the
per-arch summaries come back.

The GPU may contract a multiply and an add into one fused operation, so rotations and times
differ from the CPU's in their last bits (docs/gpu.md states the tolerance and the largest
difference measured); outcomes are the CPU's.
"""

from __future__ import annotations

import time

import numpy as np

from .._device import cuda_module, device_kernel, simulator
from ..statics.gpusearch import THREADS_PER_BLOCK
from .tables import table_size

__all__ = ["prepare_gpu", "simulate_gpu", "chunk_arches", "run_launches", "SCRATCH_FRACTION"]

#: fraction of the GPU's free memory the response's scratch (tables, buffers) may take
SCRATCH_FRACTION = 0.5
#: rows of each GPU thread's event table: the counts are kept whatever its size, so one row
EVENT_ROWS_GPU = 1
#: arches per chunk under numba's simulator (pure Python): small, so that tests stay quick
SIMULATOR_CHUNK = 256


def _prepare_kernel(px, py, mass, cen, inert, jl, el, jr, er, ok, geo_l, geo_r, phu_l, phu_r,
                    lim_l, lim_r, m0_l, m0_r, v_rest, err_l, err_r, tab_l, tab_r):
    b = cuda.grid(1)  # noqa: F821 - numba.cuda, put in the kernel's globals by device_kernel
    if b < px.shape[0] and ok[b]:
        _prepare_one(b, px, py, mass, cen, inert, jl, el, jr, er, geo_l, geo_r,  # noqa: F821
                     phu_l, phu_r, lim_l, lim_r, m0_l, m0_r, v_rest, err_l, err_r, tab_l, tab_r)


def prepare_gpu(prepare_one, loop_args, ok, outs) -> None:
    """The four-link loop of :func:`archrock.dynamics.batch.prepare_batch` on the GPU: the same
    arguments as its CPU loops (inputs ``loop_args``, rows ``ok``, outputs ``outs`` written in
    place).  A division by zero gives inf or NaN there, as in numba's parallel loop: the caller
    redoes such rows on the CPU, which says why.  ``prepare_one``: the CPU's per-arch body
    (batch._prepare_one), whose source the GPU build compiles."""
    cuda = cuda_module()
    kernel = device_kernel(_prepare_kernel, _prepare_one=prepare_one)
    B = ok.shape[0]
    d_in = [cuda.to_device(np.ascontiguousarray(a)) for a in (*loop_args, ok)]
    d_out = [cuda.to_device(a) for a in outs]
    blocks = (B + THREADS_PER_BLOCK - 1) // THREADS_PER_BLOCK
    kernel[blocks, THREADS_PER_BLOCK](*d_in, *d_out)
    for host, dev in zip(outs, d_out):
        dev.copy_to_host(host)


def _simulate_kernel(work, outs, evs, base, geos, tabs, n_rows, n_tab, k_l, k_r, lims, phus,
                     dirs, modes, ratios, v_rest, run, times, accel, g, dt, t_free, max_events,
                     status, peak, t_col, t_uns, t_lim, n_imp, n_act, n_ev, early_stop):
    i = cuda.grid(1)  # noqa: F821 - numba.cuda, put in the kernel's globals by device_kernel
    b = base + i
    if i < work.shape[0] and b < geos.shape[0] and run[b]:
        rows = work[i]
        chain_rows(b, rows, geos, tabs, n_rows, n_tab)  # noqa: F821 - given to device_kernel
        summary_one(b, rows, outs[i], evs[i], n_rows, k_l, k_r, lims,  # noqa: F821
                    phus, dirs, modes, ratios, v_rest, times, accel, g, dt, t_free, max_events,
                    status, peak, t_col, t_uns, t_lim, n_imp, n_act, n_ev, early_stop)


def chunk_arches(B: int, row_floats: int, rows: int, free_bytes: int | None = None) -> int:
    """Arches per launch of the response kernel: all B where their scratch (``rows`` chain rows
    of ``row_floats`` float64 each, per arch) fits in :data:`SCRATCH_FRACTION` of the free
    device memory, else as many as fit (at least one block)."""
    per_arch = 8 * (rows * row_floats + 1 + 6 * EVENT_ROWS_GPU)
    if free_bytes is None:
        free_bytes = cuda_module().current_context().get_memory_info()[0]
    fit = int(SCRATCH_FRACTION * free_bytes) // per_arch
    return max(THREADS_PER_BLOCK, min(B, fit))


def simulate_gpu(args, chain_rows, summary_one, chunk: int | None = None) -> dict:
    """The response loop of :func:`archrock.dynamics.batchsim.simulate_batch` on the GPU: the
    same arguments as its CPU loops, the outputs written in place.  ``chunk``: arches per
    launch (default: :func:`chunk_arches`, or :data:`SIMULATOR_CHUNK` under the simulator).
    ``chain_rows``, ``summary_one``: the CPU's per-arch bodies (:mod:`.batchsim`), whose
    source the GPU build compiles.
    Returns where the time went: {"chunk", "launches", "scratch_bytes", "to_device_s",
    "kernel_s", "to_host_s"}."""
    cuda = cuda_module()
    (geos, tabs, n_rows, n_tab, k_l, k_r, lims, phus, dirs, modes, ratios, v_rest, run, times,
     accel, g, dt, t_free, max_events, status, peak, t_col, t_uns, t_lim, n_imp, n_act, n_ev,
     early_stop) = args
    B, R = geos.shape[0], geos.shape[1]
    width = table_size(n_tab) if n_tab > 0 else geos.shape[2]
    if chunk is None:
        chunk = min(B, SIMULATOR_CHUNK) if simulator() else chunk_arches(B, width, R)
    chunk = max(1, min(int(chunk), B))
    kernel = device_kernel(_simulate_kernel, chain_rows=chain_rows, summary_one=summary_one)
    t0 = time.perf_counter()
    d_in = [cuda.to_device(np.ascontiguousarray(a)) for a in
            (geos, tabs, n_rows)] + [n_tab] + [
        cuda.to_device(np.ascontiguousarray(a)) for a in
        (k_l, k_r, lims, phus, dirs, modes, ratios, v_rest, run, times, accel)]
    outputs = (status, peak, t_col, t_uns, t_lim, n_imp, n_act, n_ev)
    d_out = [cuda.to_device(a) for a in outputs]
    work = cuda.device_array((chunk, R, width))
    outs = cuda.device_array((chunk, 1))
    evs = cuda.device_array((chunk, EVENT_ROWS_GPU, 6))
    blocks = (chunk + THREADS_PER_BLOCK - 1) // THREADS_PER_BLOCK

    def launch(base):
        kernel[blocks, THREADS_PER_BLOCK](work, outs, evs, base, *d_in, g, dt, t_free,
                                          max_events, *d_out, early_stop)
    return run_launches(launch, B, chunk, outputs, d_out, (work, outs, evs), t0)


def run_launches(launch, total: int, chunk: int, outputs, d_out, scratch, t0: float) -> dict:
    """``launch(base)`` for base = 0, chunk, ... below ``total``, then the device outputs
    ``d_out`` copied into the host arrays ``outputs``.  Returns where the time went since
    ``t0`` (copies to the device before, the kernels, the copies back) with the chunk, the
    number of launches and the bytes of the ``scratch`` arrays."""
    cuda = cuda_module()
    cuda.synchronize()
    t1 = time.perf_counter()
    launches = 0
    for base in range(0, total, chunk):
        launch(base)
        launches += 1
    cuda.synchronize()
    t2 = time.perf_counter()
    for host, dev in zip(outputs, d_out):
        dev.copy_to_host(host)
    return {"chunk": chunk, "launches": launches,
            "scratch_bytes": int(sum(a.nbytes for a in scratch)),
            "to_device_s": t1 - t0, "kernel_s": t2 - t1, "to_host_s": time.perf_counter() - t2}
