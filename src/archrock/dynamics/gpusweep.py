"""The sweep on an NVIDIA GPU: one item (arch, motion, scale) per GPU thread.

:func:`archrock.dynamics.sweep.sweep_item` (the scaled motion, then the RK4 state machine
:func:`archrock.dynamics.kernel.run_chain`) runs from the same Python source as on the CPU,
compiled for numba's CUDA target by :mod:`archrock._device`.  The packed arches (chains and
their tables, shared by every item of an arch and only read), the motions and the items are
copied to the GPU once per call; each thread's scratch (its scaled motion, as long as the
longest motion, and run_chain's two small buffers) lives in blocks of device memory reused
launch after launch, so a call of any size runs in the memory it is given.  Only the items'
summaries come back.

As in :mod:`archrock.dynamics.gpubatch`, the GPU may fuse a multiply and an add, so rotations
and times may differ from the CPU's in their last bits (docs/gpu.md); under numba's simulator
the device source runs as Python and gives the CPU's bits.
"""

from __future__ import annotations

import time

import numpy as np

from .._device import cuda_module, device_kernel, simulator
from ..statics.gpusearch import THREADS_PER_BLOCK
from .gpubatch import EVENT_ROWS_GPU, SCRATCH_FRACTION, run_launches

__all__ = ["sweep_gpu", "chunk_items", "SIMULATOR_CHUNK"]

#: items per launch under numba's simulator (pure Python, ~0.5 s per response): small, so that a
#: test's few items go through several launches
SIMULATOR_CHUNK = 4


def _sweep_kernel(accels, outs, evs, base, arch, motion, scale, rows, n_rows, lims, phus, dirs,
                  modes, ratios, k_l, k_r, v_rest, dts, t_frees, m_times, m_accel, m_off, g,
                  max_events, early_stop, status, peak, t_col, t_uns, t_lim, n_ev):
    i = cuda.grid(1)  # noqa: F821 - numba.cuda, put in the kernel's globals by device_kernel
    k = base + i
    if i < accels.shape[0] and k < arch.shape[0]:
        sweep_item(k, accels[i], outs[i], evs[i], arch, motion, scale, rows,  # noqa: F821
                   n_rows, lims, phus, dirs, modes, ratios, k_l, k_r, v_rest, dts, t_frees,
                   m_times, m_accel, m_off, g, max_events, early_stop, status, peak, t_col,
                   t_uns, t_lim, n_ev)


def chunk_items(N: int, longest: int, free_bytes: int | None = None) -> int:
    """Items per launch: all N where their scratch (a motion of ``longest`` samples, run_chain's
    output sample and event row, float64, per item) fits in :data:`SCRATCH_FRACTION` of the
    free device memory, else as many as fit (at least one block)."""
    per_item = 8 * (longest + 1 + 6 * EVENT_ROWS_GPU)
    if free_bytes is None:
        free_bytes = cuda_module().current_context().get_memory_info()[0]
    fit = int(SCRATCH_FRACTION * free_bytes) // per_item
    return max(THREADS_PER_BLOCK, min(N, fit))


def sweep_gpu(args, sweep_item, chunk: int | None = None) -> dict:
    """The item loop of :func:`archrock.dynamics.sweep.sweep` on the GPU: the same arguments as
    its CPU loops, the outputs written in place.  ``chunk``: items per launch (default:
    :func:`chunk_items`, or :data:`SIMULATOR_CHUNK` under the simulator).  ``sweep_item``: the
    CPU's per-item body, whose source the GPU build compiles (passed in: no import back into
    :mod:`.sweep`).
    Returns where the time went: {"chunk", "launches", "scratch_bytes", "to_device_s",
    "kernel_s", "to_host_s"}."""
    cuda = cuda_module()
    (arch, motion, scale, rows, n_rows, lims, phus, dirs, modes, ratios, k_l, k_r, v_rest, dts,
     t_frees, m_times, m_accel, m_off, g, max_events, early_stop, status, peak, t_col, t_uns,
     t_lim, n_ev) = args
    N = arch.shape[0]
    longest = max(1, int(np.max(np.diff(m_off))))
    if chunk is None:
        chunk = min(N, SIMULATOR_CHUNK) if simulator() else chunk_items(N, longest)
    chunk = max(1, min(int(chunk), N))
    kernel = device_kernel(_sweep_kernel, sweep_item=sweep_item)
    t0 = time.perf_counter()
    d_in = [cuda.to_device(np.ascontiguousarray(x)) for x in
            (arch, motion, scale, rows, n_rows, lims, phus, dirs, modes, ratios, k_l, k_r,
             v_rest, dts, t_frees, m_times, m_accel, m_off)]
    outputs = (status, peak, t_col, t_uns, t_lim, n_ev)
    d_out = [cuda.to_device(x) for x in outputs]
    accels = cuda.device_array((chunk, longest))
    outs = cuda.device_array((chunk, 1))
    evs = cuda.device_array((chunk, EVENT_ROWS_GPU, 6))
    threads = min(THREADS_PER_BLOCK, chunk)
    blocks = (chunk + threads - 1) // threads

    def launch(base):
        kernel[blocks, threads](accels, outs, evs, base, *d_in, g, max_events, early_stop,
                                *d_out)
    return run_launches(launch, N, chunk, outputs, d_out, (accels, outs, evs), t0)
