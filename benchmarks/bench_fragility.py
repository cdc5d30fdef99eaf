"""Fragility (IDA to first collapse) on the batch engine against the arch-by-arch path.

``archrock fragility``'s IDA on ARCHES irregular arches (samples 0.. of ArchSampler around
Oppenheim's arch, the paper's spreads and impact practice) x RECORDS synthetic records: seeded
band-limited noise (0.2-2.5 Hz, a sin^2 envelope, 20 s at 0.01 s, PGA 0.4 g), scale factors
0.1:4:30, first collapse bisected to a relative 1e-3.  In one run it times

* the arch-by-arch path (``engine="respond"``: one ``respond`` per scale, curve after curve; on
  a subset of the arches, scaled to all of them, unless --full-reference),
* the batch path (``engine="batch"``) in-process with 1 and all numba threads, and with a
  process pool of 2 workers,

checks that every first-collapse scale (and bracket, survivals, flags) is identical between the
paths on the arches both ran, and prints the ratios.  Usage:

    PYTHONPATH=src python benchmarks/bench_fragility.py [--arches 200] [--records 10]
        [--reference-arches 20] [--full-reference] [--early-stop]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np


def synthetic_record(seed: int, duration=20.0, dt=0.01, pga_g=0.4):
    from archrock.groundmotion import band_limited_noise

    return band_limited_noise(duration, dt, (0.2, 2.5), seed, pga_g, name=f"synthetic {seed}")


def _same(a, b) -> bool:
    return [c.to_dict() for c in a] == [c.to_dict() for c in b]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--arches", type=int, default=200)
    ap.add_argument("--records", type=int, default=10)
    ap.add_argument("--reference-arches", type=int, default=20,
                    help="arches run arch by arch (the time is scaled to --arches)")
    ap.add_argument("--full-reference", action="store_true",
                    help="run every arch arch by arch (slow: about 50 ms per arch and record "
                         "per scale scan)")
    ap.add_argument("--early-stop", action="store_true",
                    help="also time the batch path with the kernel's early stop")
    args = ap.parse_args(argv)

    from archrock._jit import HAVE_NUMBA, numba
    from archrock.geometry import nominal_arch
    from archrock.studies.ida import ida, random_models
    from archrock.studies.runner import RunSettings
    from archrock.dynamics.sweep import HAVE_EARLY_STOP

    threads = numba.get_num_threads() if HAVE_NUMBA else 1
    print(f"machine: {os.cpu_count()} cores, numba {'on' if HAVE_NUMBA else 'off'} "
          f"({threads} threads); shared with other jobs: timings are inflated by the load")
    nominal = nominal_arch()
    t0 = time.perf_counter()
    models = random_models(nominal, args.arches, 0)
    t_prep = time.perf_counter() - t0
    records = [synthetic_record(s) for s in range(args.records)]
    scales = np.linspace(0.1, 4.0, 30)
    print(f"{len(models)} arches ({len(models.failed)} left out) x {len(records)} records, "
          f"{scales.size} scales 0.1..4, tol 1e-3; preparation {t_prep:.2f} s (prepare, "
          f"arch by arch; shared by both paths)")
    # compile and warm both paths on one pair
    ida(records[:1], models[:1], scales, engine="batch")
    ida(records[:1], models[:1], scales, engine="respond")

    n_ref = len(models) if args.full_reference else min(args.reference_arches, len(models))
    ref_models = models.models[:n_ref]
    t0 = time.perf_counter()
    ref = ida(records, ref_models, scales, engine="respond")
    t_ref = (time.perf_counter() - t0) * len(models) / n_ref
    per_pair = t_ref / (len(models) * len(records))
    print(f"arch by arch (respond): {t_ref:8.2f} s{'' if n_ref == len(models) else f' (measured on {n_ref} arches, scaled)'}"
          f"  {1e3 * per_pair:.1f} ms per arch and record")

    rows = []
    if HAVE_NUMBA:
        numba.set_num_threads(1)
        t0 = time.perf_counter()
        one = ida(records, models, scales, engine="batch")
        rows.append(("batch, 1 thread", time.perf_counter() - t0, one))
        numba.set_num_threads(threads)
    t0 = time.perf_counter()
    res = ida(records, models, scales, engine="batch")
    rows.append((f"batch, {threads} threads", time.perf_counter() - t0, res))
    t0 = time.perf_counter()
    pool = ida(records, models, scales, engine="batch", settings=RunSettings(workers=2))
    rows.append(("batch, 2 worker processes", time.perf_counter() - t0, pool))
    if args.early_stop and HAVE_EARLY_STOP:
        t0 = time.perf_counter()
        es = ida(records, models, scales, engine="batch", early_stop=True)
        rows.append((f"batch + early stop, {threads} threads", time.perf_counter() - t0, es))
    n_pairs = len(models) * len(records)
    for name, t, r in rows:
        same = _same(r.curves[:n_ref * len(records)], ref.curves)
        same_all = _same(r.curves, res.curves)
        print(f"{name:34s} {t:8.2f} s  {1e3 * t / n_pairs:6.2f} ms per arch and record  "
              f"speed-up {t_ref / t:5.2f}x  identical to respond: {same}  to batch: {same_all}")
    first = np.array([np.nan if c.first_scale is None else c.first_scale for c in res.curves])
    print(f"first collapses: {np.isfinite(first).sum()} of {first.size} curves, median scale "
          f"{np.nanmedian(first):.3f}; fit theta {res.fit.theta:.3f} g beta {res.fit.beta:.3f}")


if __name__ == "__main__":
    main()
