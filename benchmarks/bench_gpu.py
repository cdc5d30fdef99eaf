"""Benchmark: 10^7 irregular arches through limit analysis and the paper's pulse on a GPU, and the CPU at every thread count.

Oppenheim's arch with the default spreads (0.1/0.1/0.05), the paper's pulse (a = -1 g,
t_p = 0.2 s), the paper's practice for the impact (c_v = 0.8754 fixed), early stop: the
ensemble's own batch path (``ArchSampler.draw`` -> ``prepare_batch`` -> ``simulate_batch``), batch
after batch, keeping the counts only, so the host's memory stays that of one batch.

* GPU (``device="gpu"``): ``--arches`` arches in batches of ``--batch``; the time split between
  the stages (drawing the arches, limit analysis, four-link models, impact law, response, and
  inside the response the copies to the device, the kernel and the copy back), the arches per
  second, the peak resident memory of the process and the GPU's scratch memory per launch.
* CPU (``device="cpu"``): the first ``--cpu-arches`` of the same arches at every thread count
  (1, 2, 4, ... and all of the machine's), arches per second and the GPU's speed-up over each.
* The CPU's and the GPU's answers on those arches compared: outcomes that differ (must be 0)
  and the largest differences of k, peak and times (the GPU fuses multiply-adds).

Without a GPU the GPU part says so and the rest runs; ``--simulator`` (with
NUMBA_ENABLE_CUDASIM=1 set before the run) runs the GPU part on numba's simulator, for a
check of the script itself on a few arches (the simulator takes seconds per arch):
``NUMBA_ENABLE_CUDASIM=1 python benchmarks/bench_gpu.py --simulator --arches 8 --batch 4
--cpu-arches 8 --threads 1``.

Usage: python benchmarks/bench_gpu.py [--arches 10000000] [--batch 1048576]
       [--cpu-arches 200000] [--threads 1,2,4,16] [--json FILE]
"""

from __future__ import annotations

import os
import platform
import resource
import time

import numpy as np

from _common import finish, parser

CV = 0.8754


def _setup():
    from archrock.dynamics.impact import ImpactSpec
    from archrock.geometry import oppenheim_arch
    from archrock.geometry.sampling import ArchSampler
    from archrock.groundmotion import oppenheim_pulse

    nom = oppenheim_arch()
    return nom, ArchSampler(nom, seed=0), oppenheim_pulse(-1.0, 0.2), ImpactSpec.fixed(CV)


def run(sampler, nom, motion, impact, start: int, count: int, batch: int, device: str,
        keep: bool = False) -> dict:
    """Arches start .. start + count - 1 on ``device``, batch by batch: seconds per stage,
    counts of outcomes and (``keep``) the per-arch answers."""
    from archrock.dynamics.batch import prepare_batch, simulate_batch

    sec = dict.fromkeys(("draw", "limit", "four_link", "impact", "response", "to_device",
                         "kernel", "to_host"), 0.0)
    counts = {"collapsed": 0, "rest": 0, "stopped": 0, "moving": 0, "left_out": 0}
    kept = {k: [] for k in ("k_l", "k_r", "status", "peak", "t_collapse", "t_unstable")}
    scratch = 0
    t_all = time.perf_counter()
    for lo in range(start, start + count, batch):
        n = min(batch, start + count - lo)
        t0 = time.perf_counter()
        spans, thick, radii = sampler.draw(lo, n)
        sec["draw"] += time.perf_counter() - t0
        pb = prepare_batch(spans, radii, thick, nom.density, impact=impact, device=device)
        for k in ("limit", "four_link", "impact"):
            sec[k] += pb.seconds[k]
        res = simulate_batch(pb, motion, early_stop=True, device=device)
        sec["response"] += res["seconds"]
        for k, v in res.get("gpu", {}).items():
            if k.endswith("_s"):
                sec[k[:-2]] += v
        scratch = max(scratch, res.get("gpu", {}).get("scratch_bytes", 0))
        st = res["status"]
        for name, code in (("rest", 0), ("collapsed", 1), ("moving", 2), ("stopped", 3),
                           ("left_out", -1)):
            counts[name] += int(np.sum(st == code))
        if keep:
            for k in ("k_l", "k_r"):
                kept[k].append(getattr(pb, k))
            for k in ("status", "peak", "t_collapse", "t_unstable"):
                kept[k].append(res[k])
    wall = time.perf_counter() - t_all
    out = {"device": device, "arches": count, "wall_s": wall, "arches_per_s": count / wall,
           "seconds": sec, "counts": counts, "scratch_bytes": scratch,
           "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}
    if keep:
        out["answers"] = {k: np.concatenate(v) for k, v in kept.items()}
    return out


def compare(cpu: dict, gpu: dict) -> dict:
    """Outcomes that differ and the largest absolute differences between two runs' answers."""
    a, b = cpu["answers"], gpu["answers"]
    out = {"outcomes_differ": int(np.sum(a["status"] != b["status"]))}
    for k in ("k_l", "k_r", "peak", "t_collapse", "t_unstable"):
        x, y = a[k], b[k]
        same = np.array_equal(np.isnan(x), np.isnan(y))
        fin = np.isfinite(x) & np.isfinite(y)
        out[k] = float(np.max(np.abs(x[fin] - y[fin]))) if same and fin.any() else (
            0.0 if same else float("inf"))
    return out


def _threads(spec: str | None) -> list[int]:
    import numba

    top = numba.config.NUMBA_NUM_THREADS
    if spec:
        return [t for t in (int(x) for x in spec.split(",")) if 1 <= t <= top]
    counts = [1]
    while counts[-1] * 2 < top:
        counts.append(counts[-1] * 2)
    return counts + [top] if top > 1 else counts


def _show(r: dict) -> None:
    s = r["seconds"]
    split = ", ".join(f"{k} {v:.1f} s" for k, v in s.items() if v > 0)
    print(f"  {r['device']}: {r['arches']:,} arches in {r['wall_s']:.1f} s = "
          f"{r['arches_per_s']:,.0f} arches/s ({split}); peak RSS {r['peak_rss_mb']:.0f} MB"
          + (f", GPU scratch {r['scratch_bytes'] / 2**30:.1f} GiB" if r["scratch_bytes"] else ""))
    print(f"    outcomes: {r['counts']}")


def main() -> dict:
    ap = parser(__doc__)
    ap.add_argument("--arches", type=int, default=10_000_000)
    ap.add_argument("--batch", type=int, default=1 << 20)
    ap.add_argument("--cpu-arches", type=int, default=200_000)
    ap.add_argument("--threads", help="CPU thread counts, e.g. 1,2,4,16 (default: powers of "
                                      "two up to all)")
    ap.add_argument("--simulator", action="store_true",
                    help="run the GPU part on numba's CUDA simulator (NUMBA_ENABLE_CUDASIM=1)")
    args = ap.parse_args()
    import numba

    from archrock._device import gpu_note, gpu_present, simulator

    nom, sampler, motion, impact = _setup()
    have_gpu = gpu_present() or (args.simulator and simulator())
    print(f"bench_gpu: {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} CPUs, numba {numba.__version__}; GPU: {gpu_note()}")
    out = {"gpu_note": gpu_note(), "cpus": os.cpu_count()}
    cpu_n = min(args.cpu_arches, args.arches)
    # compile both builds on a few arches before timing anything (the simulator runs Python
    # thread by thread: seconds per arch)
    warm = 4 if simulator() else 64
    run(sampler, nom, motion, impact, 0, warm, warm, "cpu")
    if have_gpu:
        run(sampler, nom, motion, impact, 0, warm, warm, "gpu")
        print(f"GPU, {args.arches:,} arches:")
        gpu = run(sampler, nom, motion, impact, 0, args.arches, args.batch, "gpu")
        _show(gpu)
        gpu_head = run(sampler, nom, motion, impact, 0, cpu_n, args.batch, "gpu", keep=True)
        out["gpu"] = {k: v for k, v in gpu.items() if k != "answers"}
    else:
        print("GPU: none here (gpu_present() is False); the GPU part is skipped. On a machine "
              "with one: pip install '.[gpu]' and run this command again.")
        gpu = gpu_head = None
    print(f"CPU, the first {cpu_n:,} of those arches, by numba threads:")
    out["cpu"] = []
    for t in _threads(args.threads):
        numba.set_num_threads(t)
        r = run(sampler, nom, motion, impact, 0, cpu_n, min(args.batch, 100_000), "cpu",
                keep=(t == 1))
        r["threads"] = t
        _show(r)
        if gpu is not None:
            r["gpu_speedup"] = gpu["arches_per_s"] / r["arches_per_s"]
            print(f"    GPU / CPU ({t} threads): {r['gpu_speedup']:.1f}x")
        if t == 1 and gpu_head is not None:
            out["agreement"] = compare(r, gpu_head)
            print(f"    CPU vs GPU on these arches: {out['agreement']}")
        out["cpu"].append({k: v for k, v in r.items() if k != "answers"})
    if gpu is not None:
        minute = gpu["arches_per_s"] * 60
        print(f"GPU: {minute:,.0f} arches per minute (aim: 10,000,000)")
    return finish(out, args.json)


if __name__ == "__main__":
    main()
