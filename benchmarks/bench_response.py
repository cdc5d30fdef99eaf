"""Benchmark of the response integrators (prints figures; never fails).

Usage: python benchmarks/bench_response.py [--quick]

(a) the paper's case (Oppenheim's arch, Oppenheim's pulse a = -1 g, t_p = 0.2 s, t_end 3 s),
(b) a 20 s synthetic record (band-limited noise, dt = 0.01 s, fixed seed, scaled to make the
arch rock), fast kernel vs scipy reference, responses per second and their ratio;
(c) random irregular 7-voussoir arches, single core: responses of 3 s per second with the arch
prepared once (respond many) and with prepare included.
Targets: fast >= 100x reference; >= 500 responses of 3 s per second per core.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ[_v] = "1"

import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from archrock import geometry, groundmotion as gm  # noqa: E402
from archrock.dynamics.response import prepare, respond  # noqa: E402


def rate(fn, min_time=1.0, min_reps=3):
    """Calls per second of fn (repeated for at least min_time seconds)."""
    n, t0 = 0, time.perf_counter()
    while True:
        fn()
        n += 1
        dt = time.perf_counter() - t0
        if n >= min_reps and dt >= min_time:
            return n / dt


def synthetic_record(k, seed=20240601, duration=20.0, dt=0.01):
    """Band-limited (0.5-5 Hz) Gaussian noise with a smooth envelope, PGA = 2.5 k g."""
    rng = np.random.default_rng(seed)
    n = int(round(duration / dt)) + 1
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, dt)
    spec[(f < 0.5) | (f > 5.0)] = 0.0
    x = np.fft.irfft(spec, n)
    t = np.arange(n) * dt
    env = np.minimum(1.0, t / 2.0) * np.minimum(1.0, (duration - t) / 4.0)
    x = x * env
    x *= 2.5 * k / np.max(np.abs(x))
    return gm.from_samples(x, dt, units="g", name="synthetic noise")


def main(quick=False):
    mt = 0.3 if quick else 1.5
    print(f"archrock response benchmark (single thread, numba compile excluded){' [quick]' if quick else ''}")
    nominal = prepare(geometry.oppenheim_arch(), "paper")
    paper = gm.oppenheim_pulse(-1.0, 0.2)
    rec = synthetic_record(min(nominal.k_l, nominal.k_r))
    # warm up (numba compile / cache load)
    respond(nominal, paper)
    respond(nominal, rec, t_end=20.0)

    ratios = {}
    for label, motion, t_end in (("paper's case (3 s)", paper, 3.0),
                                 ("synthetic 20 s record", rec, 20.0)):
        f = respond(nominal, motion, t_end=t_end)
        r = respond(nominal, motion, t_end=t_end, integrator="reference")
        rf = rate(lambda: respond(nominal, motion, t_end=t_end), mt)
        rr = rate(lambda: respond(nominal, motion, t_end=t_end, integrator="reference"), mt, 2)
        ratios[label] = rf / rr
        print(f"\n{label}: status {f.status} (reference {r.status}), impacts {len(f.impacts)} "
              f"(reference {len(r.impacts)}), peak {f.peak:.5f} rad, run ends at {f.t_final:.2f} s")
        print(f"  fast      {rf:10.1f} responses/s   ({1e3 / rf:8.3f} ms each)")
        print(f"  reference {rr:10.2f} responses/s   ({1e3 / rr:8.1f} ms each)")
        print(f"  ratio fast/reference {rf / rr:8.1f}x   target >= 100x: "
              f"{'met' if rf / rr >= 100 else 'NOT met'}")

    # random irregular arches, 3 s responses to pulses that make them rock
    rng = np.random.default_rng(7)
    n_arch = 20 if quick else 60
    arches = [geometry.random_arch(seed=int(s)) for s in rng.integers(0, 2**31, n_arch)]
    t0 = time.perf_counter()
    models = [prepare(a, "momentum") for a in arches]
    t_prep = (time.perf_counter() - t0) / n_arch
    motions = [gm.oppenheim_pulse(-1.0, tp) for tp in (0.1, 0.15, 0.2, 0.25)]
    status = {"rest": 0, "collapsed": 0, "moving": 0}

    def respond_all():
        for m in models:
            for mo in motions:
                status[respond(m, mo, t_end=3.0).status] += 1

    t0 = time.perf_counter()
    reps = 0
    while True:
        respond_all()
        reps += 1
        if time.perf_counter() - t0 >= mt:
            break
    per_resp = (time.perf_counter() - t0) / (reps * n_arch * len(motions))
    rate_many = 1.0 / per_resp
    rate_incl = len(motions) / (t_prep + len(motions) * per_resp)
    rate_single = 1.0 / (t_prep + per_resp)
    print(f"\nrandom 7-voussoir arches ({n_arch} arches x {len(motions)} Oppenheim pulses, "
          f"momentum impacts), single core:")
    print(f"  outcomes per pass: {dict((k, v // reps) for k, v in status.items())}")
    print(f"  prepare once, respond many: {rate_many:10.1f} responses of 3 s /s   target >= 500: "
          f"{'met' if rate_many >= 500 else 'NOT met'}")
    print(f"  prepare time per arch:      {1e3 * t_prep:10.2f} ms")
    print(f"  including prepare ({len(motions)} motions per arch): {rate_incl:8.1f} responses/s")
    print(f"  including prepare (1 motion per arch): {rate_single:8.1f} responses/s")
    print("\nsummary: ratio fast/reference "
          + ", ".join(f"{k}: {v:.0f}x" for k, v in ratios.items())
          + f"; {rate_many:.0f} responses/s/core (prepared)")
    # the last line, for machines (docs/scripts/doc_numbers_registry.py reads the ratios)
    print("json: " + json.dumps({"paper_ratio": round(ratios["paper's case (3 s)"], 1),
                                 "record_ratio": round(ratios["synthetic 20 s record"], 1),
                                 "prepared_per_s": round(rate_many, 1)}))


if __name__ == "__main__":
    main(quick="--quick" in sys.argv[1:])
