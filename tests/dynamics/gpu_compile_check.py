"""Compile the batch's and the sweep's GPU kernels to PTX for an NVIDIA H100/H200 (sm_90) without a GPU.

Run as a script (``python tests/dynamics/gpu_compile_check.py``) where numba's CUDA target and
NVVM are installed (the ``gpu`` extra); it prints one JSON line: the PTX size of each kernel.
The launches of :mod:`archrock.statics.gpusearch`, :mod:`archrock.dynamics.gpubatch` and
:mod:`archrock.dynamics.gpusweep` go
through a stand-in for ``numba.cuda`` whose kernels compile instead of running (nothing is
computed), so the host code's arguments and the device builds' typing and lowering are the
ones a GPU would get.  numba asks the driver for the compute capability of nested device
functions; that one call is answered with (9, 0).
"""

import json
import sys
import types

import numpy as np


def main() -> int:
    import numba
    from numba import cuda
    import numba.cuda.dispatcher as dispatcher

    if cuda.__name__ != "numba.cuda" or getattr(numba.config, "ENABLE_CUDASIM", 0):
        print(json.dumps({"skipped": "the CUDA simulator is on"}))
        return 0
    dispatcher.get_current_device = lambda: types.SimpleNamespace(compute_capability=(9, 0))
    compiled = {}

    class Host(np.ndarray):
        """A host array standing for a device array."""

        def copy_to_host(self, out=None):
            if out is not None:
                out[...] = self
                return out
            return np.array(self)

    class Launch:
        def __init__(self, fn):
            self.fn = fn
            fn.__globals__["cuda"] = cuda  # the real target, not this stand-in

        def __getitem__(self, config):
            return self

        def __call__(self, *args):
            if self.fn.__name__ in compiled:
                return
            sig = tuple(numba.typeof(np.asarray(a) if isinstance(a, Host) else a) for a in args)
            ptx, _ = cuda.compile_ptx(self.fn, sig, cc=(9, 0))
            compiled[self.fn.__name__] = {"ptx_bytes": len(ptx), "fma": ptx.count("fma.rn")}

    def jit(fn=None, device=False):
        if device:
            return cuda.jit(device=True)
        return Launch(fn)

    ctx = types.SimpleNamespace(get_memory_info=lambda: (2**34, 2**34))
    shim = types.SimpleNamespace(
        jit=jit, grid=cuda.grid, current_context=lambda: ctx, synchronize=lambda: None,
        to_device=lambda a: np.ascontiguousarray(a).view(Host),
        device_array=lambda shape, dtype=float: np.zeros(shape, dtype).view(Host))

    import archrock._device as D
    from archrock.dynamics import batch, batchsim, gpubatch, gpusweep, sweep
    from archrock.statics import gpusearch, kinematic

    D.cuda_module = gpubatch.cuda_module = gpusearch.cuda_module = lambda: shim
    gpusweep.cuda_module = lambda: shim
    for mod in (batch, batchsim, kinematic, sweep):
        mod.resolve_device = lambda device, n=0: "gpu"
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse

    nom = oppenheim_arch()
    rng = np.random.default_rng(0)
    spans = nom.spans * (1 + 0.05 * rng.uniform(-1, 1, (4, nom.n)))
    spans *= nom.embrace / spans.sum(axis=1, keepdims=True)
    radii = np.tile(nom.radii, (4, 1))
    thick = np.tile(nom.thicknesses, (4, 1))
    pb = batch.prepare_batch(spans, radii, thick, nom.density, nominal=nom, device="gpu")
    pb_cpu = batch.prepare_batch(spans, radii, thick, nom.density, nominal=nom)
    batchsim.simulate_batch(pb_cpu, oppenheim_pulse(-1.0, 0.25), device="gpu", early_stop=True)
    from archrock.dynamics.response import prepare

    # packed on the CPU (under the stand-in the batch's preparation computes nothing)
    arches = sweep.SweepArches.from_models([prepare(nom)] * 2)
    motions = sweep.SweepMotions.of([oppenheim_pulse(-1.0, 0.25)])
    n = len(arches)
    sweep.sweep(arches, motions, np.arange(n), np.zeros(n), np.full(n, 0.5), device="gpu",
                early_stop=True)
    print(json.dumps(compiled, sort_keys=True))
    return 0 if len(compiled) == 4 and pb.k_l.size == 4 else 1


if __name__ == "__main__":
    sys.exit(main())
