"""Benchmark: where an ensemble's time goes, how it scales with threads, and 10^6 arches.

Oppenheim's arch (spreads 0.1/0.1/0.05), the paper's pulse (a = -1 g, t_p = 0.2 s), the paper's
practice for the impact (c_v = 0.8754 fixed), batches of 500 through ``run_ensemble``
in-process.  For 1 numba thread and for all of them, with and without early stop, it prints
the seconds in preparation (limit analysis, four-link tables, impact law; ``prepare_s``) and in
the response (``response_s``), the wall time and arches per second, and the serial fraction:
the share of the single-thread wall time spent outside the compiled parallel loops (the numba
``prange`` kernels of the limit enumeration, the four-link loop, the impact laws and the
response, timed here by wrapping them).  Amdahl's law with that fraction s bounds the speed-up
on N threads by 1 / (s + (1 - s) / N).  After a warm-up ensemble, each configuration runs
REPEATS times; the run of median wall time is shown, with the serial fractions of all the
single-thread runs.

``--million``: 10^6 arches (batches of 10,000) through limit analysis and the paper's pulse
with early stop, batch by batch through ``run_batch`` keeping only the counts, so memory stays
that of one batch; prints the wall time, arches per second and the peak resident memory
(``resource.getrusage(RUSAGE_SELF).ru_maxrss``).

Usage: python benchmarks/bench_scale.py [--samples 10000] [--million] [--json FILE]
"""

from __future__ import annotations

import os
import platform
import resource
import time

from _common import finish, parser, speed_record


#: runs per configuration in the scaling table (the median is shown)
REPEATS = 3


def _config(samples, early_stop=False, batch_size=500, seed=0):
    from archrock.studies.ensemble import EnsembleConfig
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import PulseSpec
    from archrock.dynamics.impact import ImpactSpec

    return EnsembleConfig.from_arch(oppenheim_arch(), samples=samples, seed=seed,
                                    batch_size=batch_size,
                                    motion=PulseSpec("oppenheim", -1.0, 0.2),
                                    impact=ImpactSpec.fixed(0.8754), early_stop=early_stop)


class KernelClock:
    """Wraps the compiled parallel loops of the package and adds up the seconds spent in them."""

    def __init__(self):
        from archrock.dynamics import batch, batchsim
        from archrock.statics import kinematic
        from archrock.dynamics.impact import compiled

        self.seconds = 0.0
        self._saved = []
        for mod, name in ((batch, "_prepare_loop_nb"), (batchsim, "_simulate_loop_nb"),
                          (kinematic, "_numba_kernel_par"), (compiled, "_loop_nb")):
            fn = getattr(mod, name)
            if fn is None:
                continue
            self._saved.append((mod, name, fn))
            setattr(mod, name, self._wrap(fn))

    def _wrap(self, fn):
        def timed(*args):
            t0 = time.perf_counter()
            try:
                return fn(*args)
            finally:
                self.seconds += time.perf_counter() - t0
        return timed

    def restore(self):
        for mod, name, fn in self._saved:
            setattr(mod, name, fn)


def _run(cfg, threads):
    import numba

    from archrock.studies.ensemble import run_ensemble

    numba.set_num_threads(threads)
    clock = KernelClock()
    try:
        t0 = time.perf_counter()
        res = run_ensemble(cfg)
        wall = time.perf_counter() - t0
    finally:
        clock.restore()
    return res, {"threads": threads, "wall_s": wall, "arches_per_s": cfg.samples / wall,
                 "prepare_s": res.timing["prepare_s"], "response_s": res.timing["response_s"],
                 "kernel_s": clock.seconds, "outside_kernels_s": wall - clock.seconds,
                 "collapsed": int(res.frame["collapsed"].sum())}


def scaling(samples):
    import numba
    import numpy as np

    all_threads = numba.config.NUMBA_NUM_THREADS
    out = {}
    frames = {}
    # steady state: the first ensemble of a process also loads the compiled kernels from the
    # cache and pays pandas' first conversions, which would count as serial time
    _run(_config(1000), all_threads)
    _run(_config(1000, True), all_threads)
    for early in (False, True):
        cfg = _config(samples, early)
        key = "early_stop" if early else "full"
        rows = {}
        fractions = []
        for threads in (1, all_threads):
            # three runs each, the one of median wall time kept: the serial part is a few
            # hundredths of a second, within the noise of a shared machine
            runs = sorted((_run(cfg, threads) for _ in range(REPEATS)),
                          key=lambda r: r[1]["wall_s"])
            res, row = runs[len(runs) // 2]
            frames[(key, threads)] = res.frame
            rows[threads] = row
            if threads == 1:
                fractions = sorted(r["outside_kernels_s"] / r["wall_s"] for _, r in runs)
        one, many = rows[1], rows[all_threads]
        s = one["outside_kernels_s"] / one["wall_s"]
        out[key] = {"threads_1": one, f"threads_{all_threads}": many,
                    "serial_fraction": s, "speedup": one["wall_s"] / many["wall_s"],
                    "amdahl_bound": 1.0 / (s + (1.0 - s) / all_threads)}
        for row in (one, many):
            print(f"{key:10s} {row['threads']:2d} thread(s): wall {row['wall_s']:6.2f} s  "
                  f"{row['arches_per_s']:7.0f} arches/s  prepare {row['prepare_s']:5.2f} s  "
                  f"response {row['response_s']:6.2f} s  outside the parallel kernels "
                  f"{row['outside_kernels_s']:5.2f} s  ({row['collapsed']} collapsed)")
        out[key]["serial_fraction_runs"] = fractions
        print(f"{key:10s} serial fraction {100 * s:.2f}% of the 1-thread time (runs: "
              f"{', '.join(f'{100 * f:.2f}%' for f in fractions)}); speed-up "
              f"x{out[key]['speedup']:.2f} on {all_threads} threads (Amdahl bound "
              f"x{out[key]['amdahl_bound']:.2f})")
    numba.set_num_threads(all_threads)
    full, early = frames[("full", all_threads)], frames[("early_stop", all_threads)]
    same = {"collapsed": bool(np.array_equal(full["collapsed"], early["collapsed"])),
            "peak": bool(np.array_equal(full["peak"].to_numpy(), early["peak"].to_numpy(),
                                        equal_nan=True)),
            "stopped": int(early["early_stopped"].sum())}
    threads_same = all(frames[(k, 1)].equals(frames[(k, all_threads)]) for k in ("full", "early_stop"))
    out["early_stop_same_outcome"] = same
    out["threads_identical"] = bool(threads_same)
    out["early_stop_speedup"] = (out["full"][f"threads_{all_threads}"]["wall_s"]
                                 / out["early_stop"][f"threads_{all_threads}"]["wall_s"])
    print(f"early stop: {same['stopped']} of {samples} arches stopped; collapse identical "
          f"{same['collapsed']}, peak identical {same['peak']}; x{out['early_stop_speedup']:.2f} "
          f"faster on {all_threads} threads; 1 thread = {all_threads} threads, bit for bit: "
          f"{threads_same}")
    return out


def million(samples=1_000_000, batch_size=10_000):
    """samples arches batch by batch (only counts kept): wall, arches/s, peak RSS."""
    import numba

    from archrock.studies.ensemble import run_batch

    cfg = _config(samples, early_stop=True, batch_size=batch_size)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    counts = {"collapsed": 0, "stopped": 0, "failed": 0}
    prep = resp = 0.0
    t0 = time.perf_counter()
    for b in range(cfg.n_batches):
        df, timing = run_batch(cfg, b)
        counts["collapsed"] += int(df["collapsed"].sum())
        counts["stopped"] += int(df["early_stopped"].sum())
        counts["failed"] += int((df["error"] != "").sum())
        prep += timing["prepare_s"]
        resp += timing["response_s"]
        del df
        if (b + 1) % 10 == 0:
            el = time.perf_counter() - t0
            print(f"  {(b + 1) * batch_size:>9,d} arches  {el:6.1f} s", flush=True)
    wall = time.perf_counter() - t0
    rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # kB on Linux
    out = speed_record(samples, wall, prep, resp, batch_size=batch_size, peak_rss_mb=rss_mb,
                       **counts)
    print(f"10^6 arches (early stop): {wall:.1f} s, {samples / wall:.0f} arches/s (prepare "
          f"{prep:.1f} s, response {resp:.1f} s), {counts['collapsed']} collapsed, peak resident "
          f"memory {rss_mb:.0f} MB")
    return out


def main(argv=None):
    ap = parser(__doc__, samples=10000)
    ap.add_argument("--million", action="store_true",
                    help="also 10^6 arches with early stop, printing the peak resident memory")
    args = ap.parse_args(argv)

    import numba

    _run(_config(20), 1)  # compile / load the numba caches
    _run(_config(20, True), 1)
    out = {"samples": args.samples, "cpus": os.cpu_count(), "python": platform.python_version(),
           "numba_threads": numba.config.NUMBA_NUM_THREADS,
           "load_average": os.getloadavg()}
    print(f"{args.samples} arches, {out['numba_threads']} numba threads, load average "
          f"{out['load_average'][0]:.2f} (a shared machine inflates every figure)")
    out["scaling"] = scaling(args.samples)
    if args.million:
        out["million"] = million()
    return finish(out, args.json)


if __name__ == "__main__":
    main()
