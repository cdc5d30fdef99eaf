"""The four-hinge search on an NVIDIA GPU: one arch per GPU thread, the enumeration of
:func:`archrock.statics.kinematic._numba_arch` compiled from its own source for numba's CUDA
target (:mod:`archrock._device`).  Every candidate is visited in the same order with the same
arithmetic as on the CPU; the GPU may fuse a multiply and an add (one rounding instead of two),
so a multiplier can differ from the CPU's in its last bits and, between two candidates equal to
rounding, the index of the one kept."""

from __future__ import annotations

import numpy as np

from .._device import cuda_module, device_kernel

__all__ = ["four_hinge_gpu", "THREADS_PER_BLOCK"]

#: GPU threads per block of the batch kernels (each thread's loop is long and register-heavy)
THREADS_PER_BLOCK = 64


def _four_hinge_kernel(cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, m):
    b = cuda.grid(1)  # noqa: F821 - numba.cuda, put in the kernel's globals by device_kernel
    if b < cw.shape[0]:
        # _numba_arch: given to device_kernel (it exists only where numba does)
        _numba_arch(b, cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, 0, m, 0)  # noqa: F821


def four_hinge_gpu(cw, cwx, cwy, pxf, pyf, arch_search):
    """(k_l, k_r, cand_l, cand_r) of the arches whose prefix sums (B, n+1) and flattened joint
    points (B, 2(n+1)) are given, each arch one GPU thread (see the module docstring);
    ``arch_search``: the CPU's per-arch enumeration (kinematic._numba_arch), whose source the
    GPU build compiles."""
    cuda = cuda_module()
    B, m = cw.shape
    kernel = device_kernel(_four_hinge_kernel, _numba_arch=arch_search)
    arrays = [cuda.to_device(np.ascontiguousarray(a, dtype=float))
              for a in (cw, cwx, cwy, pxf, pyf)]
    k_l = cuda.to_device(np.full(B, np.inf))
    k_r = cuda.to_device(np.full(B, np.inf))
    i_l = cuda.to_device(np.zeros(B, dtype=np.int64))
    i_r = cuda.to_device(np.zeros(B, dtype=np.int64))
    blocks = (B + THREADS_PER_BLOCK - 1) // THREADS_PER_BLOCK
    kernel[blocks, THREADS_PER_BLOCK](*arrays, k_l, k_r, i_l, i_r, m)
    return k_l.copy_to_host(), k_r.copy_to_host(), i_l.copy_to_host(), i_r.copy_to_host()
