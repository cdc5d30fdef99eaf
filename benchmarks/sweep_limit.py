"""Limit analysis over a random sweep of arches of every family: counts by outcome, the worst
time per arch and the worst |kinematic - static| (the figures of issue 17's closing note).

    python benchmarks/sweep_limit.py [--arches 400] [--seed 0] [--max-n 200] [--friction] [--fc MPA]

Families with rise/span 0.05-1, t/span 0.02-0.3, 3 to max-n voussoirs, normal and vertical
joints, half of them with a point load of half the arch's weight above a voussoir.  Up to 10
voussoirs the kinematic enumeration of every mechanism with lift-off
(:func:`archrock.statics.limit.general_mechanisms`) is compared with the LP as well.  ``--friction``
also times :func:`archrock.statics.friction.friction_analysis` at mu = 0.5 on every arch that stands.
``--fc MPA`` analyses every arch that has no mechanism under Heyman's hypotheses again with
that compressive strength (docs/crushing.md) and counts those that get a finite k.
"""

from __future__ import annotations

import argparse
import time
from collections import Counter

import numpy as np

from archrock.statics import limit
from archrock.errors import ArchrockError, CannotStandError, GeometryOutcome
from archrock.geometry import Load, family_arch

SHAPES = ("circular", "pointed", "elliptical", "three-centred", "parabolic", "catenary")
RISE = {"circular": (0.05, 0.5), "three-centred": (0.1, 0.5), "pointed": (0.52, 1.0)}


def draw(rng, max_n):
    shape = SHAPES[rng.integers(len(SHAPES))]
    lo, hi = RISE.get(shape, (0.05, 1.0))
    return (shape, 10.0 * rng.uniform(lo, hi), 10.0 * rng.uniform(0.02, 0.3),
            int(rng.integers(3, max_n + 1)), ("normal", "vertical")[rng.integers(2)],
            bool(rng.integers(2)))


def build(shape, rise, thick, n, joints, loaded):
    arch = family_arch(shape, 10.0, rise, thick, n, joints=joints)
    if loaded:
        c = np.asarray(arch.centroids)[n // 3]
        arch = family_arch(shape, 10.0, rise, thick, n, joints=joints,
                           loads=[Load(n // 3, 0.5 * float(np.sum(arch.masses)),
                                       (float(c[0]), float(c[1]) + thick))])
    return arch


def _with_fc(arch, fc) -> str:
    """The outcome of an arch without a mechanism, analysed again with compressive strength fc."""
    try:
        k = limit.limit_analysis(arch.with_fc(fc)).k
    except GeometryOutcome as exc:
        return type(exc).__name__
    return "finite k" if np.isfinite(k) and k > 0 else "k not finite"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--arches", type=int, default=400)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--max-n", type=int, default=200)
    ap.add_argument("--friction", action="store_true")
    ap.add_argument("--fc", type=float, default=None)
    args = ap.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    outcomes, worst_t, worst_d, worst_gen = Counter(), (0.0, None), 0.0, 0.0
    with_fc = Counter()
    worst_f = (0.0, None)
    for _ in range(args.arches):
        case = draw(rng, args.max_n)
        try:
            arch = build(*case)
        except ArchrockError:
            outcomes["family refuses"] += 1
            continue
        t0 = time.perf_counter()
        try:
            res = limit.limit_analysis(arch)
        except CannotStandError:
            outcomes["cannot stand"] += 1
            res = None
        except GeometryOutcome:
            outcomes["no mechanism (LP unbounded)"] += 1
            res = None
            if args.fc is not None:
                with_fc[_with_fc(arch, args.fc)] += 1
        dt = time.perf_counter() - t0
        if dt > worst_t[0]:
            worst_t = (dt, case)
        if res is None:
            continue
        outcomes["four-hinge" if res.four_hinge else "lift-off"] += 1
        worst_d = max(worst_d, res.discrepancy / max(1.0, res.k))
        if arch.n <= 10:
            for d in "lr":
                g = limit.general_mechanisms(arch, d).multiplier
                worst_gen = max(worst_gen, abs(g - res.mechanism(d).multiplier) / max(1.0, abs(g)))
        if args.friction:
            from archrock.statics.friction import friction_analysis

            t0 = time.perf_counter()
            friction_analysis(arch, 0.5)
            dt = time.perf_counter() - t0
            if dt > worst_f[0]:
                worst_f = (dt, case)
    total = sum(outcomes.values())
    print(f"arches tried: {total} (seed {args.seed}, 3-{args.max_n} voussoirs)")
    for k, v in sorted(outcomes.items(), key=lambda kv: -kv[1]):
        print(f"  {k:30s} {v:5d}")
    for k, v in sorted(with_fc.items(), key=lambda kv: -kv[1]):
        print(f"    with f_c = {args.fc:g} MPa: {k:19s} {v:5d}")
    print(f"worst limit-analysis time: {worst_t[0]:.3f} s ({worst_t[1]})")
    print(f"worst |kinematic - static| / max(1, k): {worst_d:.2e}")
    print(f"worst |general enumeration - governing| / max(1, k) (n <= 10): {worst_gen:.2e}")
    if args.friction:
        print(f"worst friction-analysis time: {worst_f[0]:.3f} s ({worst_f[1]})")


if __name__ == "__main__":
    main()
