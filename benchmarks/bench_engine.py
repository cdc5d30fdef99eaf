"""Benchmark: archrock's own rigid-block engine against pymunk and the four-link kernel.

In one run, on this machine, with the project's own functions:

* response: Oppenheim's arch under the paper's pulse (a = -1 g, t_p = 0.2 s), each model run as
  the studies run it -- the four-link model by ``respond`` (RK4, numba when installed), the
  engines by ``EngineRun().respond`` (to rest or collapse, samples every 0.01 s) -- seconds per
  run (best of ``--repeat``) and the ratios engine / four-link and pymunk / archrock;
* ramp: the activation multipliers of Oppenheim's arch and of the flat bridge arch (span 10 m,
  rise 1.5 m, t 0.5 m, 15 voussoirs) in both engines, beside the limit analysis, with the time
  of each ramp and the ratio;
* first collapse: the heavy-pier arch (tests/data/heavy_piers.json) under Oppenheim's pulse
  (t_p = 0.2 s, amplitude toward +x), archrock's engine (pymunk's takes minutes: --pymunk).

Usage: python benchmarks/bench_engine.py [--repeat 3] [--no-ramp] [--pymunk] [--json FILE]
pymunk is optional (``pip install "archrock[dem]"``): without it its columns are skipped.
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path


def _best(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _have_pymunk() -> bool:
    try:
        import pymunk  # noqa: F401
    except ImportError:
        return False
    return True


def response(repeat: int, pymunk: bool) -> dict:
    from archrock.contact import EngineSettings
    from archrock.dynamics.response import prepare, respond
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse
    from archrock.studies.enginestudy import EngineRun

    arch = oppenheim_arch()
    model = prepare(arch, "momentum")
    motion = oppenheim_pulse(-1.0, 0.2)
    respond(model, motion)  # compile
    t4, r4 = _best(lambda: respond(model, motion), repeat)
    out = {"fourlink": {"seconds": t4, "status": r4.status, "peak": r4.peak}}
    engines = ["archrock"] + (["pymunk"] if pymunk else [])
    for name in engines:
        run = EngineRun(settings=EngineSettings(engine=name))
        run.respond(arch, motion, model)  # compile / warm up
        t, r = _best(lambda: run.respond(arch, motion, model), repeat)
        out[name] = {"seconds": t, "status": r.status, "peak": r.peak, "t_final": r.t_final}
    out["archrock_over_fourlink"] = out["archrock"]["seconds"] / t4
    if pymunk:
        out["pymunk_over_archrock"] = out["pymunk"]["seconds"] / out["archrock"]["seconds"]
    return out


def ramps(pymunk: bool) -> dict:
    from archrock.contact import EngineSettings, ramp
    from archrock.geometry import family_arch, oppenheim_arch
    from archrock.statics.limit import limit_analysis

    out = {}
    for label, arch in (("oppenheim", oppenheim_arch()),
                        ("flat bridge arch", family_arch("circular", 10.0, 1.5, 0.5, 15))):
        lim = limit_analysis(arch)
        row = {"limit": lim.k_l}
        for name in ["archrock"] + (["pymunk"] if pymunk else []):
            t0 = time.perf_counter()
            r = ramp(arch, EngineSettings(engine=name), limit=lim)
            row[name] = {"seconds": time.perf_counter() - t0, "k_l": r.k_l, "k_r": r.k_r,
                         "err_l": r.k_l / lim.k_l - 1, "err_r": r.k_r / lim.k_r - 1,
                         "hinges_l": list(r.l.hinges), "hinges_r": list(r.r.hinges)}
        if pymunk:
            row["pymunk_over_archrock"] = row["pymunk"]["seconds"] / row["archrock"]["seconds"]
        out[label] = row
    return out


def heavy_piers(pymunk: bool) -> dict:
    from archrock.contact import EngineSettings
    from archrock.geometry.files import read_arch
    from archrock.studies.enginestudy import EngineRun, engine_first_collapse

    arch = read_arch(Path(__file__).resolve().parents[1] / "tests" / "data" / "heavy_piers.json")
    out = {}
    for name in ["archrock"] + (["pymunk"] if pymunk else []):
        t0 = time.perf_counter()
        r = engine_first_collapse(arch, 0.2, rtol=0.01,
                                  run=EngineRun(settings=EngineSettings(engine=name)))
        out[name] = {"seconds": time.perf_counter() - t0, "amplitude_g": r.amplitude,
                     "bracket": list(r.bracket) if r.bracket else None, "runs": r.n_responses}
    return out


def main(argv=None):
    from archrock._jit import HAVE_NUMBA

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-ramp", action="store_true")
    ap.add_argument("--pymunk", action="store_true",
                    help="also pymunk's first collapse on heavy piers (minutes)")
    ap.add_argument("--json", metavar="FILE")
    args = ap.parse_args(argv)
    have = _have_pymunk()
    res = {"machine": platform.processor() or platform.machine(), "numba": HAVE_NUMBA,
           "pymunk": have, "response": response(args.repeat, have)}
    r = res["response"]
    print(f"Oppenheim, paper's pulse (numba {HAVE_NUMBA}):")
    print(f"  four-link {1e3 * r['fourlink']['seconds']:8.1f} ms  ({r['fourlink']['status']})")
    print(f"  archrock  {1e3 * r['archrock']['seconds']:8.1f} ms  ({r['archrock']['status']}, "
          f"{r['archrock_over_fourlink']:.1f}x the four-link)")
    if have:
        print(f"  pymunk    {1e3 * r['pymunk']['seconds']:8.1f} ms  ({r['pymunk']['status']}, "
              f"{r['pymunk_over_archrock']:.1f}x archrock)")
    if not args.no_ramp:
        res["ramp"] = ramps(have)
        for label, row in res["ramp"].items():
            print(f"ramp, {label}: limit k = {row['limit']:.4f}")
            for name in ("archrock", "pymunk"):
                if name in row:
                    e = row[name]
                    print(f"  {name:8s} k_l {e['k_l']:.4f} ({100 * e['err_l']:+.2f}%)  k_r "
                          f"{e['k_r']:.4f} ({100 * e['err_r']:+.2f}%)  {e['seconds']:6.1f} s")
            if "pymunk_over_archrock" in row:
                print(f"  pymunk / archrock time: {row['pymunk_over_archrock']:.1f}x")
    res["heavy_piers"] = heavy_piers(args.pymunk and have)
    for name, e in res["heavy_piers"].items():
        print(f"heavy piers, first collapse (t_p 0.2 s), {name}: {e['amplitude_g']:.4f} g "
              f"in {e['seconds']:.1f} s ({e['runs']} runs)")
    if args.json:
        Path(args.json).write_text(json.dumps(res, indent=1))
    return res


if __name__ == "__main__":
    main()
