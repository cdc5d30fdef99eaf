"""The sweep on the CPU and on its GPU build under numba's CUDA simulator, for the tests.

``python tests/dynamics/gpu_sweep_compare.py`` (run with NUMBA_ENABLE_CUDASIM=1) sweeps a few
small irregular arches x two motions (the paper's pulse and a short band-limited noise record)
x two scale factors both ways, early stop off and on, and prints one JSON line per early-stop
setting: the items whose status or event count differ, the largest absolute differences of the
rotations and times, the outcomes seen, where each ran and the GPU's launches; then one line
of multiple stripes run through the studies' runner on either device.
"""

import json
import sys

import numpy as np

#: arches, scale factors: 2 x 2 motions x 2 = 8 items per sweep (the simulator: ~0.5 s each)
N_ARCHES = 2
SCALES = (0.6, 2.5)


def items():
    from archrock.dynamics.sweep import SweepArches, SweepMotions
    from archrock.geometry import nominal_arch
    from archrock.groundmotion import band_limited_noise, oppenheim_pulse
    from archrock.studies.ida import random_models

    models = random_models(nominal_arch(radius=2.0, thickness=0.3), N_ARCHES, 0)
    motions = [oppenheim_pulse(-0.5, 0.25), band_limited_noise(1.5, 0.01, (0.5, 5.0), seed=3,
                                                               pga_g=0.3)]
    ai, mi, si = (x.ravel() for x in np.meshgrid(np.arange(N_ARCHES), np.arange(2), SCALES,
                                                  indexing="ij"))
    return SweepArches.from_models(models.models), SweepMotions.of(motions), ai, mi, si


def compare(early_stop: bool) -> dict:
    from archrock.dynamics.sweep import sweep

    A, M, ai, mi, si = items()
    cpu = sweep(A, M, ai, mi, si, early_stop=early_stop)
    gpu = sweep(A, M, ai, mi, si, early_stop=early_stop, device="gpu")
    out = {"early_stop": early_stop, "items": int(ai.size), "cpu_device": cpu["device"],
           "gpu_device": gpu["device"], "launches": gpu["gpu"]["launches"],
           "status": [int(x) for x in cpu["status"]]}
    for k in ("status", "n_events"):
        out[k + "_differ"] = int(np.sum(cpu[k] != gpu[k]))
    for k in ("peak", "t_collapse", "t_unstable", "t_limit"):
        a, b = cpu[k], gpu[k]
        if not np.array_equal(np.isnan(a), np.isnan(b)):
            out[k] = float("inf")
        else:
            out[k] = float(np.nanmax(np.abs(a - b))) if np.isfinite(a).any() else 0.0
    return out


def stripes() -> dict:
    """Multiple stripes (the studies' SweepRunner) with the run settings' device: the outcomes
    of the CPU's and of the GPU's, which ran where."""
    from archrock.geometry import nominal_arch
    from archrock.groundmotion import oppenheim_pulse
    from archrock.studies.ida import msa, random_models

    models = random_models(nominal_arch(radius=2.0, thickness=0.3), N_ARCHES, 0)
    recs = [oppenheim_pulse(-0.5, 0.25)]
    from archrock.dynamics import gpusweep

    launches = []
    real = gpusweep.sweep_gpu

    def counted(*args, **kw):  # what ran on the (simulated) GPU
        out = real(*args, **kw)
        launches.append(out["launches"])
        return out

    gpusweep.sweep_gpu = counted
    cpu = msa(recs, models, [0.3, 1.25])
    cpu_launches = len(launches)
    gpu = msa(recs, models, [0.3, 1.25], settings={"device": "gpu"})
    return {"stripes": cpu.outcomes.astype(int).ravel().tolist(),
            "stripes_gpu": gpu.outcomes.astype(int).ravel().tolist(),
            "same_dict": cpu.to_dict() == gpu.to_dict(), "cpu_gpu_calls": cpu_launches,
            "gpu_launches": sum(launches)}


if __name__ == "__main__":
    for stop in (False, True):
        print(json.dumps(compare(stop)), flush=True)
    print(json.dumps(stripes()), flush=True)
    sys.exit(0)
