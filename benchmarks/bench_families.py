"""Benchmark: irregular arches of every family per second, each against the circular arch.

Each family arch (S = 10 m, t = 1 m, 12 voussoirs, spreads 0.1/0.1/0.05) and Oppenheim's circular
arch go through ``run_ensemble``: draw, kinematic limit analysis, four-link models, fixed
c_v = 0.8754, and the response to Oppenheim's pulse (a = -1 g, t_p = 0.2 s), in-process on all
numba threads.  One warm-up ensemble per family first (numba caches, plans).  Prints arches per
second, the split (prepare / response) and the ratio of each family's time to the circular
arch's.  ``--legacy`` also times the arch-object path (``prepare_batch(sampler.arches(...))``
with ``perturb_family``, as before the compiled drawing) on ``--legacy-samples`` arches.

A surveyed polygon arch (Oppenheim's as a polygon without a family, thickness and offset
spreads only, docs/geometry.md) and Oppenheim's arch on two piers 4 m x 2 m (perturbed by the
same rule, piers included) run last, drawn as arrays (geometry.surveybatch) since 0.7.

Usage: python benchmarks/bench_families.py [--samples 10000] [--legacy] [--json FILE]
"""

from __future__ import annotations

import os
import platform
import time

from _common import ensemble_record, finish, parser

FAMILIES = (("pointed", 7.0), ("elliptical", 4.0), ("three-centred", 3.0), ("parabolic", 4.0),
            ("catenary", 5.0), ("circular", 3.0))


def _config(nominal, samples, spreads=None):
    from archrock.dynamics.impact import ImpactSpec
    from archrock.groundmotion import PulseSpec
    from archrock.studies.ensemble import EnsembleConfig

    return EnsembleConfig.from_arch(nominal, samples=samples, seed=0, batch_size=500,
                                    motion=PulseSpec("oppenheim", -1.0, 0.2),
                                    impact=ImpactSpec.fixed(0.8754),
                                    **({"spreads": spreads} if spreads is not None else {}))


def _run(nominal, samples, spreads=None):
    from archrock.studies.ensemble import run_ensemble

    run_ensemble(_config(nominal, min(samples, 50), spreads))  # warm-up
    t0 = time.perf_counter()
    res = run_ensemble(_config(nominal, samples, spreads))
    wall = time.perf_counter() - t0
    return ensemble_record(res, samples, wall)


def _legacy(nominal, samples):
    """The arch-object path: perturb_family per arch, PolygonArch, prepare_batch, response."""
    import numpy as np

    from archrock.dynamics.batch import prepare_batch, simulate_batch
    from archrock.errors import ArchInputError, InvalidSampleError
    from archrock.geometry.irregular import perturb_family
    from archrock.geometry.sampling import ArchSampler
    from archrock.groundmotion import PulseSpec

    s = ArchSampler(nominal, seed=0)
    sp = s.spreads
    t0 = time.perf_counter()
    arches = []
    for i, u in enumerate(s.uniforms(0, samples)):
        try:
            arches.append(perturb_family(nominal, u, sp.span, sp.thickness, sp.radius, sp.tilt,
                                         name=f"sample {i}"))
        except ArchInputError as exc:
            arches.append(InvalidSampleError(f"not a valid arch: {exc}"))
    t_draw = time.perf_counter() - t0
    pb = prepare_batch(arches, impact=0.8754)
    res = simulate_batch(pb, PulseSpec("oppenheim", -1.0, 0.2).build())
    wall = time.perf_counter() - t0
    return {"samples": samples, "wall_s": wall, "arches_per_s": samples / wall,
            "draw_s": t_draw, "collapsed": int(np.sum(res["status"] == 1))}


def main(argv=None):
    ap = parser(__doc__, samples=10000)
    ap.add_argument("--families",
                    default=",".join([f for f, _ in FAMILIES] + ["surveyed", "piers"]),
                    help="comma-separated families, 'surveyed' for a surveyed polygon arch, "
                         "'piers' for an arch on piers (default: all)")
    ap.add_argument("--legacy", action="store_true", help="also time the arch-object path")
    ap.add_argument("--legacy-samples", type=int, default=500)
    args = ap.parse_args(argv)

    from archrock._jit import HAVE_NUMBA, numba
    from archrock.geometry import family_arch, oppenheim_arch

    out = {"samples": args.samples, "cpus": os.cpu_count(), "python": platform.python_version(),
           "numba": HAVE_NUMBA, "numba_threads": numba.get_num_threads() if HAVE_NUMBA else 0,
           "families": {}}
    base = _run(oppenheim_arch(), args.samples)
    out["circular (Oppenheim, exact sectors)"] = base
    print(f"{'arch':34s} {'s':>7s} {'arches/s':>9s} {'prepare':>8s} {'response':>8s} "
          f"{'x circular':>10s}")
    print(f"{'circular (Oppenheim, sectors)':34s} {base['wall_s']:7.2f} "
          f"{base['arches_per_s']:9.0f} {base['prepare_s']:8.2f} {base['response_s']:8.2f} "
          f"{1.0:10.2f}")
    wanted = args.families.split(",")
    for shape, rise in FAMILIES:
        if shape not in wanted:
            continue
        nom = family_arch(shape, 10.0, rise, 1.0, 12, exact=False)
        r = _run(nom, args.samples)
        r["ratio_to_circular"] = r["wall_s"] / base["wall_s"]
        name = f"{shape} S=10 F={rise:g} (polygon)"
        print(f"{name:34s} {r['wall_s']:7.2f} {r['arches_per_s']:9.0f} {r['prepare_s']:8.2f} "
              f"{r['response_s']:8.2f} {r['ratio_to_circular']:10.2f}   ({r['left_out']} left "
              f"out, {r['collapsed']} collapsed)", flush=True)
        if args.legacy:
            lg = _legacy(nom, args.legacy_samples)
            lg["ratio_to_circular"] = base["arches_per_s"] / lg["arches_per_s"]
            r["legacy"] = lg
            print(f"{'  arch-object path (before)':34s} {lg['wall_s']:7.2f} "
                  f"{lg['arches_per_s']:9.0f} {'':8s} {'':8s} {lg['ratio_to_circular']:10.2f}"
                  f"   (on {lg['samples']} arches; drawing {lg['draw_s']:.2f} s)", flush=True)
        out["families"][shape] = r
    # a surveyed arch (Oppenheim's as a polygon without a family, joints kept: span spread 0)
    # and Oppenheim's arch on two piers 4 m x 2 m, perturbed by the same rule (piers included)
    from archrock.geometry import as_polygon, with_piers
    from archrock.geometry.sampling import Spreads

    for key, name, build in (
            ("surveyed", "surveyed polygon (Oppenheim, n=7)",
             lambda: as_polygon(oppenheim_arch())),
            ("piers", "on piers 4 x 2 m (Oppenheim, n=9)",
             lambda: with_piers(oppenheim_arch(), 4.0, 2.0))):
        if key not in wanted:
            continue
        r = _run(build(), args.samples, Spreads(0.0, 0.1, 0.05))
        r["ratio_to_circular"] = r["wall_s"] / base["wall_s"]
        print(f"{name:34s} {r['wall_s']:7.2f} {r['arches_per_s']:9.0f} {r['prepare_s']:8.2f} "
              f"{r['response_s']:8.2f} {r['ratio_to_circular']:10.2f}   ({r['left_out']} left "
              f"out, {r['collapsed']} collapsed)", flush=True)
        out["families"][key] = r
    return finish(out, args.json)


if __name__ == "__main__":
    main()
