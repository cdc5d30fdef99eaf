"""Benchmark: random arches per second through limit analysis + response to the paper's pulse.

Each arch: draw (spreads 0.1/0.1/0.05 around Oppenheim's arch), kinematic limit analysis, four-link
models, rotation limits, fixed c_v = 0.8754, then the response to Oppenheim's pulse (a = -1 g,
t_p = 0.2 s) integrated to rest or collapse (RK4, dt = 2 ms; the free motion after the pulse
lasts several seconds for the arches that recover).

Modes:
  serial     in-process, one numba thread
  threads    in-process, all numba threads (the default of run_ensemble / archrock ensemble)
  workers=2  local process pool of 2 workers (spawned; includes their start-up)
  naive      response.prepare + response.respond(integrator="fast") arch by arch (a sample)

  pointed    with --pointed N: N irregular pointed arches (S = 10 m, F = 7 m, t = 1 m, 12
             voussoirs, spreads 0.1/0.1/0.05) drawn through their family recipe, the general
             prepare_batch and the paper's pulse, in-process (all threads)

Usage: python benchmarks/bench_ensemble.py [--samples 10000] [--naive 200] [--pointed 10000]
       [--json FILE]
"""

from __future__ import annotations

import os
import platform
import time

import numpy as np

from _common import ensemble_record, finish, parser


def _config(samples, seed=0):
    from archrock.studies.ensemble import EnsembleConfig
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import PulseSpec
    from archrock.dynamics.impact import ImpactSpec

    return EnsembleConfig.from_arch(oppenheim_arch(), samples=samples, seed=seed, batch_size=500,
                                    motion=PulseSpec("oppenheim", -1.0, 0.2),
                                    impact=ImpactSpec.fixed(0.8754))


def _timed(config, **kw):
    from archrock.studies.ensemble import run_ensemble

    t0 = time.perf_counter()
    res = run_ensemble(config, **kw)
    wall = time.perf_counter() - t0
    return res, wall


def naive(config, n):
    """prepare + respond arch by arch for the first n samples; returns (seconds, rows)."""
    from archrock.studies.ensemble import sample_arch
    from archrock.dynamics.response import prepare, respond

    motion = config.motion.build()
    arches = [sample_arch(config, i) for i in range(n)]
    # warm-up: the single-arch kernel compiles (or loads from numba's cache) on its first call
    respond(prepare(arches[0], 0.8754), motion, integrator="fast")
    rows = []
    t0 = time.perf_counter()
    t_prep = 0.0
    for a in arches:
        ta = time.perf_counter()
        m = prepare(a, 0.8754)
        t_prep += time.perf_counter() - ta
        r = respond(m, motion, integrator="fast")
        rows.append((r.status, r.peak))
    return time.perf_counter() - t0, t_prep, rows


def pointed(samples):
    """Irregular pointed arches through limit analysis and the paper's pulse (fixed c_v)."""
    from archrock.studies.ensemble import EnsembleConfig
    from archrock.geometry import family_arch
    from archrock.groundmotion import PulseSpec
    from archrock.dynamics.impact import ImpactSpec

    nom = family_arch("pointed", 10.0, 7.0, 1.0, 12, exact=False)
    cfg = EnsembleConfig.from_arch(nom, samples=samples, seed=0, batch_size=500,
                                   motion=PulseSpec("oppenheim", -1.0, 0.2),
                                   impact=ImpactSpec.fixed(0.8754))
    res, wall = _timed(cfg)
    out = ensemble_record(res, samples, wall)
    print(f"pointed (irregular, {samples}): {wall:7.2f} s  {samples / wall:7.1f} arches/s  "
          f"(prepare {out['prepare_s']:.2f} s, response {out['response_s']:.2f} s; "
          f"{out['collapsed']} collapsed, {out['left_out']} left out)")
    return out


def main(argv=None):
    ap = parser(__doc__, samples=10000)
    ap.add_argument("--naive", type=int, default=200, help="arches for the naive loop")
    ap.add_argument("--pointed", type=int, default=0,
                    help="irregular pointed arches through the general batch path (0: skipped)")
    args = ap.parse_args(argv)

    import numba

    from archrock._jit import HAVE_NUMBA

    cfg = _config(args.samples)
    _timed(_config(20))  # compile / load the numba caches
    out = {"samples": args.samples, "cpus": os.cpu_count(), "python": platform.python_version(),
           "numba": HAVE_NUMBA, "numba_threads": numba.get_num_threads() if HAVE_NUMBA else 0}

    n_threads = numba.get_num_threads()
    numba.set_num_threads(1)
    res1, wall = _timed(cfg)
    numba.set_num_threads(n_threads)
    out["serial"] = {"wall_s": wall, "arches_per_s": args.samples / wall,
                     "prepare_s": res1.timing["prepare_s"], "response_s": res1.timing["response_s"]}
    print(f"serial (1 thread):      {wall:7.2f} s  {args.samples / wall:7.1f} arches/s  "
          f"(prepare {res1.timing['prepare_s']:.2f} s, response {res1.timing['response_s']:.2f} s)")

    res_t, wall = _timed(cfg)
    out["threads"] = {"wall_s": wall, "arches_per_s": args.samples / wall, "threads": n_threads}
    print(f"in-process ({n_threads} threads): {wall:7.2f} s  {args.samples / wall:7.1f} arches/s")

    from archrock.studies.runner import RunSettings

    res2, wall = _timed(cfg, settings=RunSettings(workers=2))
    out["workers_2"] = {"wall_s": wall, "arches_per_s": args.samples / wall}
    print(f"process pool (2):       {wall:7.2f} s  {args.samples / wall:7.1f} arches/s")

    same = all(res1.frame.equals(r.frame) for r in (res_t, res2))
    out["identical_results"] = bool(same)
    print(f"identical results in the three modes: {same}")

    secs, t_prep, rows = naive(cfg, args.naive)
    rate = args.naive / secs
    out["naive"] = {"arches": args.naive, "wall_s": secs, "arches_per_s": rate,
                    "prepare_ms_per_arch": 1e3 * t_prep / args.naive,
                    "respond_ms_per_arch": 1e3 * (secs - t_prep) / args.naive}
    df = res1.frame.iloc[:args.naive]
    agree = sum(s == st for (s, _), st in zip(rows, df["status"]))
    peak_err = float(np.max(np.abs(np.array([p for _, p in rows]) - df["peak"].to_numpy())))
    out["naive"]["same_outcome"] = f"{agree}/{args.naive}"
    out["naive"]["max_peak_difference_rad"] = peak_err
    out["speedup_vs_naive"] = {"serial": out["serial"]["arches_per_s"] / rate,
                               "threads": out["threads"]["arches_per_s"] / rate,
                               "workers_2": out["workers_2"]["arches_per_s"] / rate}
    print(f"naive prepare+respond:  {rate:7.1f} arches/s on {args.naive} arches "
          f"(prepare {out['naive']['prepare_ms_per_arch']:.2f} ms, respond "
          f"{out['naive']['respond_ms_per_arch']:.2f} ms per arch); same outcome {agree}/{args.naive}, "
          f"max |peak difference| {peak_err:.1e} rad")
    print("speed-up vs naive: " + ", ".join(f"{k} x{v:.1f}" for k, v in out["speedup_vs_naive"].items()))
    if args.pointed:
        out["pointed"] = pointed(args.pointed)
    return finish(out, args.json)


if __name__ == "__main__":
    main()
