"""IDA of the heavy-pier arch by the contact engine (issue 31: 10 records x 12 scales in under
5 minutes on 2 cores).

tests/data/heavy_piers.json (12 voussoirs on two free piers, one degree of freedom cannot follow
it) under RECORDS synthetic records, each one engine run per scale
(:func:`archrock.studies.engineida.engine_ida`, default engine settings: 400 steps per T,
mu = 0.8, e = 0, 30 T of free motion at most):

* ``--kind noise`` (default): band-limited white noise, 0.3-3 Hz (2nd-order Butterworth), under a
  sin^2 envelope, DURATION s at 0.01 s, seeds 0 .. RECORDS - 1, normalised to a PGA of 1 g;
* ``--kind sine``: one-sine pulses of 1 g, periods spread geometrically over 0.5-3 s.

Scale factors: SCALES geometric from 0.1 to 1.5 (PGA 0.1-1.5 g: from below the arch's activation,
0.113 g, to twice its engine first collapse under Oppenheim's pulse, about 0.7 g).  Prints the
wall time, the engine runs per second and the collapse matrix.  Usage:

    PYTHONPATH=src python benchmarks/bench_engine_ida.py [--records 10] [--scales 12]
        [--workers 2] [--kind noise|sine] [--duration 10]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

HEAVY = Path(__file__).resolve().parent.parent / "tests" / "data" / "heavy_piers.json"


def noise_record(seed: int, duration: float, dt: float = 0.01):
    """Seeded band-limited noise (0.3-3 Hz) under a sin^2 envelope, PGA 1 g."""
    from scipy.signal import butter, sosfilt

    from archrock.groundmotion import from_samples

    rng = np.random.default_rng(seed)
    n = int(round(duration / dt))
    x = sosfilt(butter(2, [0.3, 3.0], btype="band", fs=1 / dt, output="sos"),
                rng.standard_normal(n))
    x *= np.sin(np.pi * np.arange(n) * dt / duration) ** 2
    return from_samples(x / np.max(np.abs(x)), dt, name=f"noise {seed}")


def sine_record(period: float):
    """One full sine of ``period`` [s], 1 g."""
    from archrock.groundmotion import G, GroundMotion

    t = np.linspace(0.0, period, 401)
    return GroundMotion(t, G * np.sin(2 * np.pi * t / period), name=f"sine {period:.2f} s")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--records", type=int, default=10)
    ap.add_argument("--scales", type=int, default=12)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--kind", choices=("noise", "sine"), default="noise")
    ap.add_argument("--duration", type=float, default=10.0, help="noise records [s]")
    args = ap.parse_args(argv)

    from archrock.geometry.files import read_arch
    from archrock.studies.engineida import engine_ida
    from archrock.studies.enginestudy import choose_dynamics
    from archrock.studies.runner import RunSettings

    arch = read_arch(HEAVY)
    recs = ([noise_record(i, args.duration) for i in range(args.records)]
            if args.kind == "noise" else
            [sine_record(p) for p in np.geomspace(0.5, 3.0, args.records)])
    scales = np.geomspace(0.1, 1.5, args.scales)
    # compile (or load the cache) outside the timing: one short run
    engine_ida(arch, recs[:1], scales[:1])
    t0 = time.perf_counter()
    res = engine_ida(arch, recs, scales, dynamics=choose_dynamics(arch),
                     settings=RunSettings(workers=args.workers,
                                          progress=lambda line: print(line, flush=True)))
    wall = time.perf_counter() - t0
    runs = len(recs) * scales.size
    print(f"cpus {os.cpu_count()}, executor {res.timing['workers']}")
    print("collapse matrix (records x scales):")
    for name, row in zip(res.records, res.collapsed):
        print(f"  {name:<14} {''.join('X' if c else '.' for c in row)}")
    fit = ("no fit: " + str(res.fit_error)) if res.fit is None else \
        f"theta {res.fit.theta:.3f} g, beta {res.fit.beta:.3f} ({res.fit.method})"
    print(f"fit: {fit}")
    print(f"engine ida heavy piers: {len(recs)} {args.kind} records x {scales.size} scales = "
          f"{runs} runs in {wall:.1f} s, {runs / wall:.2f} runs/s, workers={args.workers} "
          f"(estimate {res.timing['estimate_s']:.0f} s)")


if __name__ == "__main__":
    main()
