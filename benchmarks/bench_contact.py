"""Benchmark: seconds of computation per simulated second, contact engine vs four-link kernel.

Oppenheim's arch under the paper's pulse (a = -1 g, t_p = 0.2 s) for a fixed simulated window:
* engine: archrock.contact.ContactArch (pymunk), the default EngineSettings (and the coarse
  ones of the default test suite), stepped through the window without the early stop at rest;
* four-link: archrock.dynamics.response.respond(integrator="fast"), RK4 at dt = 2 ms (numba when
  installed), run to rest as archrock does (its simulated span is the response's t_final);
* the outline cut (issue 21): the engine at the default settings with the fine cut (every
  outline vertex, outline_tol = 0) and the simplified one (outline_tol = 2e-3 of the size, the default), in
  seconds per simulated second, and ``ramp`` (both directions) on the pointed arch of
  docs/geometry.md (S = 10 m, F = 7 m, t = 1 m, 12 voussoirs) with each cut, with the ratios.

Usage: python benchmarks/bench_contact.py [--window 6] [--repeat 3] [--no-ramp] [--json FILE]
"""

from __future__ import annotations

import platform
import time

from _common import finish, parser


def _engine(arch, motion, settings, window):
    from archrock.contact import ContactArch

    ca = ContactArch(arch, settings)
    ca.settle()
    steps = int(round(window / ca.dt))
    t0 = time.perf_counter()
    for _ in range(steps):
        ca.step(float(motion(ca.time + 0.5 * ca.dt)), 1)
    return time.perf_counter() - t0, steps * ca.dt, steps


def _ramps():
    from archrock.contact import ContactArch, EngineSettings, ramp
    from archrock.geometry import family_arch
    from archrock.statics.limit import limit_analysis

    arch = family_arch("pointed", 10.0, 7.0, 1.0, 12)
    lim = limit_analysis(arch)
    out = {"limit": {"k_l": lim.k_l, "k_r": lim.k_r}}
    for name, s in (("fine", EngineSettings(outline_tol=0.0)), ("simplified", EngineSettings())):
        pieces = max(len(p) for p in ContactArch(arch, s).pieces)
        t0 = time.perf_counter()
        r = ramp(arch, s, limit=lim)
        out[name] = {"seconds": time.perf_counter() - t0, "pieces": pieces, "k_l": r.k_l,
                     "k_r": r.k_r, "hinges_l": list(r.l.hinges), "hinges_r": list(r.r.hinges),
                     "outline_tol": s.outline_tol}
    out["speedup"] = out["fine"]["seconds"] / out["simplified"]["seconds"]
    out["k_diff_l"] = out["simplified"]["k_l"] / out["fine"]["k_l"] - 1
    out["k_diff_r"] = out["simplified"]["k_r"] / out["fine"]["k_r"] - 1
    return out


def main(argv=None):
    from archrock._jit import HAVE_NUMBA
    from archrock.contact import EngineSettings
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse
    from archrock.dynamics.response import prepare, respond

    ap = parser(__doc__)
    ap.add_argument("--window", type=float, default=6.0, help="simulated seconds (default 6)")
    ap.add_argument("--repeat", type=int, default=3, help="repeats; the best is kept")
    ap.add_argument("--no-ramp", action="store_true", help="skip the ramps on the pointed arch")
    args = ap.parse_args(argv)
    arch = oppenheim_arch()
    motion = oppenheim_pulse(-1.0, 0.2)
    model = prepare(arch)
    respond(model, motion, t_end=args.window)  # compile
    best = float("inf")
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        r = respond(model, motion, t_end=args.window)
        best = min(best, time.perf_counter() - t0)
    four = {"seconds": best, "simulated": r.t_final, "per_sim_second": best / r.t_final}
    out = {"python": platform.python_version(), "numba": HAVE_NUMBA, "four_link": four}
    for name, s in (("engine_default", EngineSettings()),
                    ("engine_fine_cut", EngineSettings(outline_tol=0.0)),
                    ("engine_coarse", EngineSettings(steps_per_T=150, iterations=20))):
        runs = [_engine(arch, motion, s, args.window) for _ in range(args.repeat)]
        sec, sim, steps = min(runs)
        out[name] = {"seconds": sec, "simulated": sim, "steps": steps,
                     "per_sim_second": sec / sim, "settings": s.to_dict(),
                     "ratio_to_four_link": (sec / sim) / four["per_sim_second"]}
    print(f"Oppenheim's arch, paper pulse; best of {args.repeat}")
    print(f"  four-link kernel ({'numba' if HAVE_NUMBA else 'pure Python'}): "
          f"{four['per_sim_second']:.3g} s per simulated s ({r.t_final:.2f} s simulated)")
    for name in ("engine_fine_cut", "engine_default", "engine_coarse"):
        e = out[name]
        print(f"  {name:15s}: {e['per_sim_second']:.3g} s per simulated s "
              f"({e['steps']} steps of {e['simulated'] / e['steps'] * 1e3:.2f} ms), "
              f"{e['ratio_to_four_link']:.0f}x the four-link kernel")
    cut = out["engine_fine_cut"]["per_sim_second"] / out["engine_default"]["per_sim_second"]
    out["cut_speedup"] = cut
    print(f"  outline cut: fine {out['engine_fine_cut']['per_sim_second']:.3g} -> simplified "
          f"{out['engine_default']['per_sim_second']:.3g} s per simulated s ({cut:.1f}x faster)")
    if not args.no_ramp:
        out["ramp_pointed"] = _ramps()
        r = out["ramp_pointed"]
        print(f"Pointed arch (S 10 m, F 7 m, t 1 m, 12 voussoirs), ramp in both directions:")
        for name in ("fine", "simplified"):
            e = r[name]
            print(f"  {name:10s} cut ({e['pieces']} pieces a voussoir): {e['seconds']:.2f} s, "
                  f"k_l {e['k_l']:.4f} k_r {e['k_r']:.4f}, hinges {e['hinges_l']} / "
                  f"{e['hinges_r']}")
        print(f"  ramp {r['speedup']:.1f}x faster; activation simplified / fine - 1: M_l "
              f"{100 * r['k_diff_l']:+.2f}%, M_r {100 * r['k_diff_r']:+.2f}%")
    return finish(out, args.json)


if __name__ == "__main__":
    main()
