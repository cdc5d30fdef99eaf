"""Check: how much a GPU's rounding (fused multiply-adds) moves the batch's answers, measured on the CPU.

A GPU contracts ``a * b + c`` into one fused operation (one rounding instead of two) wherever
its compiler can; the CPU build of numba does not.  This script builds the batch kernels (the
four-hinge search, the four-link loop, the response) a second time for the CPU from their own
source with ``fastmath={"contract"}`` -- LLVM may then fuse exactly as NVVM does, on a CPU with
FMA -- and runs both builds on the same irregular arches around Oppenheim's under the paper's
pulse (c_v 0.8754 fixed, early stop).  It prints the outcomes that differ and the largest
differences of k, the four-link vectors (relative), the peak rotation [rad] and the times [s]:
the size of the differences to expect between ``device="cpu"`` and ``device="gpu"``.

Usage: python benchmarks/gpu_rounding.py [--samples 20000] [--json FILE]
"""

from __future__ import annotations

import time

import numpy as np

from _common import finish, parser


def _contracted_loops():
    """The three CPU loops rebuilt with FMA contraction (serial: one arch after another)."""
    import numba

    from archrock._device import builder
    from archrock.dynamics import batch, batchsim
    from archrock.statics import kinematic

    build = builder(numba.njit(fastmath={"contract"}))
    return (build(kinematic._numba_kernel), build(batch._prepare_loop_py),
            build(batchsim._simulate_loop_py))


def _answers(pb, res) -> dict:
    return {"k_l": pb.k_l, "k_r": pb.k_r, "geo_l": pb.geo_l, "geo_r": pb.geo_r,
            "status": res["status"], "peak": res["peak"], "t_collapse": res["t_collapse"],
            "t_unstable": res["t_unstable"], "n_impacts": res["n_impacts"]}


def main() -> dict:
    ap = parser(__doc__, samples=20_000)
    args = ap.parse_args()
    from archrock.dynamics import batch, batchsim
    from archrock.dynamics.batch import prepare_batch, simulate_batch
    from archrock.dynamics.impact import ImpactSpec
    from archrock.geometry import oppenheim_arch
    from archrock.geometry.sampling import ArchSampler
    from archrock.groundmotion import oppenheim_pulse
    from archrock.statics import kinematic

    nom = oppenheim_arch()
    spans, thick, radii = ArchSampler(nom, seed=0).draw(0, args.samples)
    motion = oppenheim_pulse(-1.0, 0.2)
    impact = ImpactSpec.fixed(0.8754)

    def once():
        pb = prepare_batch(spans, radii, thick, nom.density, impact=impact, parallel=False)
        return pb, simulate_batch(pb, motion, early_stop=True, parallel=False)

    t0 = time.perf_counter()
    plain = _answers(*once())
    t1 = time.perf_counter()
    saved = (kinematic._numba_kernel, batch._prepare_loop, batchsim._simulate_loop_serial)
    (kinematic._numba_kernel, batch._prepare_loop,
     batchsim._simulate_loop_serial) = _contracted_loops()
    try:
        fused = _answers(*once())
    finally:
        (kinematic._numba_kernel, batch._prepare_loop, batchsim._simulate_loop_serial) = saved
    t2 = time.perf_counter()
    out = {"samples": args.samples, "plain_s": t1 - t0, "fused_s": t2 - t1,
           "outcomes_differ": int(np.sum(plain["status"] != fused["status"])),
           "impact_counts_differ": int(np.sum(plain["n_impacts"] != fused["n_impacts"])),
           "collapsed": int(np.sum(plain["status"] == 1))}
    for k in ("k_l", "k_r", "geo_l", "geo_r", "peak", "t_collapse", "t_unstable"):
        a, b = plain[k], fused[k]
        fin = np.isfinite(a) & np.isfinite(b)
        rel = np.abs(a[fin] - b[fin]) / np.maximum(1.0, np.abs(a[fin]))
        out[k] = float(rel.max()) if rel.size else 0.0
        out[k + "_nan_differ"] = int(np.sum(np.isnan(a) != np.isnan(b)))
    print(f"gpu_rounding: {args.samples:,} arches, plain CPU build {t1 - t0:.1f} s, "
          f"fused multiply-adds {t2 - t1:.1f} s (compilation included)")
    print(f"  outcomes that differ: {out['outcomes_differ']} of {args.samples:,} "
          f"({out['collapsed']:,} collapse); impact counts that differ: "
          f"{out['impact_counts_differ']}")
    print("  largest differences (relative to max(1, |value|)): " + ", ".join(
        f"{k} {out[k]:.2g}" for k in ("k_l", "k_r", "geo_l", "geo_r", "peak", "t_collapse",
                                      "t_unstable")))
    return finish(out, args.json)


if __name__ == "__main__":
    main()
