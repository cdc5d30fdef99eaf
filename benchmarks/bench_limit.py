"""Throughput of the limit analysis: production path against a plain loop of linprog.

Run:  python benchmarks/bench_limit.py [--arches N] [--lp-arches N] [--no-numba]

For random arches (default spreads s_a = 0.1, s_t = 0.1, s_R = 0.05 around a nominal arch with
R = 10 m, embrace 157.5 deg, t = 1.5 m) with n = 7 and n = 20 voussoirs it measures, on one core:

* the production path: ``limit.kinematic_multipliers_batch`` on the whole batch (arches/s);
* the one-arch-at-a-time path: ``limit.kinematic_mechanisms`` in a Python loop;
* the static linear program (``limit.static_multiplier``, scipy HiGHS) for 'l' and 'r' per arch,
  on the first arches of the same batch, measured in the same run;

then prints the rates, the speed-up ratios and the largest |kinematic - static| difference.
Target: >= 5000 arches/s at n = 7 through the production path.

Polygon and family arches (``--polygon-arches``, default 200): ``limit.limit_analysis`` one arch
at a time of the circular arches (Oppenheim's, and random arches at n = 7) against the same arches
as polygons (``geometry.as_polygon(arch, 20)``: 20 points per intrados and extrados line), and of a
pointed family arch (n = 12); arches/s and the polygon/circular ratio in the same run (target: the
polygon path within a factor 2 of the circular one).  Each timed call gets a fresh arch object, so
cached joints and mass properties are paid for.

Many voussoirs (``--large``, default 100 200 500 1000): ``limit.limit_analysis`` of the nominal
arch (the static-guided search above ``limit.ENUMERATION_MAX_VOUSSOIRS``), its kinematic part
alone, and the full enumeration (``method="enumeration"``) where its estimate is below
``--enum-max-seconds`` (default 60), as ratios in the same run; static = kinematic is checked.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

if "--no-numba" in sys.argv:
    os.environ["ARCHROCK_NO_NUMBA"] = "1"

import numpy as np  # noqa: E402

from archrock.statics import kinematic, limit  # noqa: E402
from archrock.geometry import (Arch, as_polygon, family_arch, nominal_arch,  # noqa: E402
                               oppenheim_arch, random_spans_thicknesses_radii)

TARGET_POLYGON_RATIO = 2.0

TARGET_N7 = 5000.0


def make_batch(n: int, count: int, seed: int):
    """``count`` random arches around the nominal n-voussoir arch, as (B, n) arrays."""
    nom = nominal_arch(10.0, 157.5, 1.5, n)
    rng = np.random.default_rng(seed)
    spans, radii, thick = (np.empty((count, n)) for _ in range(3))
    for b in range(count):
        u = rng.uniform(-1.0, 1.0, size=(3, n))
        spans[b], thick[b], radii[b] = random_spans_thicknesses_radii(nom, u, 0.1, 0.1, 0.05)
    return spans, radii, thick


def best_rate(fn, count: int, repeat: int) -> float:
    """Best of ``repeat`` timings, as items per second."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return count / best


def bench(n: int, n_batch: int, n_single: int, n_lp: int, seed: int) -> dict:
    spans, radii, thick = make_batch(n, n_batch, seed)
    arches = [Arch(spans[b], radii[b], thick[b]) for b in range(max(n_single, n_lp))]
    # warm-up (compilation of the optional kernel, candidate tables)
    limit.kinematic_multipliers_batch(spans[:4], radii[:4], thick[:4])
    limit.kinematic_mechanisms(arches[0])

    out = {}

    def batch():
        out["batch"] = limit.kinematic_multipliers_batch(spans, radii, thick)

    rate_batch = best_rate(batch, n_batch, 3)

    def single():
        out["single"] = [limit.kinematic_mechanisms(a) for a in arches[:n_single]]

    rate_single = best_rate(single, n_single, 2)

    def lp():
        out["lp"] = [(limit.static_multiplier(a, "l")[0], limit.static_multiplier(a, "r")[0])
                     for a in arches[:n_lp]]

    rate_lp = best_rate(lp, n_lp, 1)

    k_l, k_r = out["batch"][0], out["batch"][1]
    lp_arr = np.array(out["lp"])
    diff_lp = float(np.max(np.abs(np.column_stack([k_l[:n_lp], k_r[:n_lp]]) - lp_arr)))
    single_arr = np.array([(m_l.multiplier, m_r.multiplier) for m_l, m_r in out["single"]])
    diff_single = float(np.max(np.abs(np.column_stack([k_l[:n_single], k_r[:n_single]]) - single_arr)))
    return {"n": n, "batch": rate_batch, "single": rate_single, "lp": rate_lp,
            "diff_lp": diff_lp, "diff_single": diff_single, "n_batch": n_batch,
            "n_single": n_single, "n_lp": n_lp,
            "candidates": len(limit._candidates(n)[0])}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--arches", type=int, default=20000, help="batch size at n = 7 (default 20000)")
    ap.add_argument("--lp-arches", type=int, default=300, help="arches through linprog (default 300)")
    ap.add_argument("--no-numba", action="store_true", help="use the numpy enumeration only")
    ap.add_argument("--seed", type=int, default=2017)
    ap.add_argument("--polygon-arches", type=int, default=200,
                    help="arches per polygon/family timing (default 200; 0: skip)")
    ap.add_argument("--large", type=int, nargs="*", default=[100, 200, 500, 1000],
                    help="voussoir counts of the many-voussoir timings (none: skip them)")
    ap.add_argument("--enum-max-seconds", type=float, default=60.0,
                    help="run the full enumeration where its estimate is below this (s)")
    args = ap.parse_args(argv)

    backend = "numba kernel" if kinematic._NUMBA_ENABLED else "numpy (vectorised, blocked)"
    print(f"archrock limit-analysis benchmark; kinematic backend: {backend}; threads = 1")
    rows = []
    for n, n_batch in ((7, args.arches), (20, max(200, args.arches // 50))):
        n_single = min(n_batch, 2000 if n == 7 else 200)
        n_lp = min(n_batch, args.lp_arches)
        r = bench(n, n_batch, n_single, n_lp, args.seed + n)
        rows.append(r)
        print(f"\nn = {n:2d}  ({r['candidates']} candidate mechanisms per arch)")
        print(f"  production, kinematic_multipliers_batch ({r['n_batch']} arches): {r['batch']:10.0f} arches/s")
        print(f"  one arch at a time, kinematic_mechanisms ({r['n_single']} arches): {r['single']:10.0f} arches/s")
        print(f"  linprog loop, static_multiplier l + r ({r['n_lp']} arches):      {r['lp']:10.1f} arches/s")
        print(f"  speed-up batch / linprog:  {r['batch'] / r['lp']:8.1f} x")
        print(f"  speed-up single / linprog: {r['single'] / r['lp']:8.1f} x")
        print(f"  max |kinematic - static LP| = {r['diff_lp']:.2e}; "
              f"max |batch - single| = {r['diff_single']:.2e}")
    ok = rows[0]["batch"] >= TARGET_N7
    print(f"\ntarget >= {TARGET_N7:.0f} arches/s at n = 7: {'met' if ok else 'NOT met'} "
          f"({rows[0]['batch']:.0f} arches/s)")
    agree = all(r["diff_lp"] < 1e-6 and r["diff_single"] == 0.0 for r in rows)
    print(f"kinematic and static agree within 1e-6: {'yes' if agree else 'NO'}")
    if args.polygon_arches:
        agree &= bench_polygon(args.polygon_arches, args.seed)
    if args.large:
        agree &= bench_large(args.large, args.enum_max_seconds)
    return 0 if agree else 1


def _rate_fresh(make, count: int, repeat: int = 3, built: bool = False) -> tuple[float, list]:
    """limit_analysis of ``count`` fresh arches from ``make(b)`` (built before the clock
    starts, or inside it with ``built``), best of ``repeat``: arches/s, and the results of the
    last pass."""
    best, res = np.inf, None
    for _ in range(repeat):
        arches = list(range(count)) if built else [make(b) for b in range(count)]
        t0 = time.perf_counter()
        res = [limit.limit_analysis(make(a) if built else a) for a in arches]
        best = min(best, time.perf_counter() - t0)
    return count / best, res


def bench_polygon(count: int, seed: int) -> bool:
    """One arch at a time: circular arches against the same arches as polygons; a family arch."""
    print(f"\npolygon arches: limit_analysis one arch at a time ({count} fresh arches per "
          f"timing), circular Arch against as_polygon(arch, 20)")
    opp = oppenheim_arch()
    spans, radii, thick = make_batch(7, count, seed + 101)
    rand = [Arch(spans[b], radii[b], thick[b]) for b in range(count)]
    cases = [("Oppenheim (n = 7)", lambda b: Arch(opp.spans, opp.radii, opp.thicknesses),
              lambda b: as_polygon(opp, 20)),
             ("random, n = 7", lambda b: Arch(rand[b].spans, rand[b].radii, rand[b].thicknesses),
              lambda b: as_polygon(rand[b], 20))]
    limit.limit_analysis(as_polygon(opp, 20))  # warm-up
    ok = True
    print(f"{'arches':>20} {'circular':>12} {'polygon':>12} {'circ/poly':>10} "
          f"{'+ as_polygon':>13} {'circ/poly':>10} {'max |dk|':>10}")
    for label, circ, poly in cases:
        rc, res_c = _rate_fresh(circ, count)
        rp, res_p = _rate_fresh(poly, count)
        rpb, _ = _rate_fresh(poly, count, built=True)
        dk = max(max(abs(a.k_l - b.k_l), abs(a.k_r - b.k_r)) for a, b in zip(res_c, res_p))
        ratio = rc / rp
        ok &= ratio <= TARGET_POLYGON_RATIO
        print(f"{label:>20} {rc:8.0f} /s {rp:8.0f} /s {ratio:9.2f}x {rpb:9.0f} /s "
              f"{rc / rpb:9.2f}x {dk:10.1e}")
    print("  (polygon: the arch built before the clock; + as_polygon: built inside it, with the "
          "checks of its outlines; dk: the 20-point polygons against the exact sectors)")
    pointed = family_arch("pointed", 10.0, 7.0, 1.0, 12)
    fam = pointed.to_dict()
    from archrock.geometry import PolygonArch

    rf, _ = _rate_fresh(lambda b: PolygonArch.from_dict(fam), count)
    rb, _ = _rate_fresh(lambda b: family_arch("pointed", 10.0, 7.0, 1.0, 12), max(count // 10, 5), 1)
    n_pts = len(pointed.outline(0))
    print(f"  pointed family arch (S = 10, F = 7, t = 1 m, n = 12; {n_pts} outline points per "
          f"voussoir): {rf:.0f} arches/s; with family_arch's construction: {rb:.1f} arches/s")
    print(f"polygon path within {TARGET_POLYGON_RATIO:g}x of the circular one: "
          f"{'yes' if ok else 'NO'}")
    return ok


def bench_large(counts, enum_max_seconds: float) -> bool:
    """Many voussoirs: static-guided search against the full enumeration, same run."""
    print(f"\nmany voussoirs (R = 10 m, 157.5 deg, t = 1.5 m); the guided search above "
          f"n = {limit.ENUMERATION_MAX_VOUSSOIRS}")
    print(f"{'n':>6} {'limit_analysis':>15} {'kinematic':>10} {'enumeration':>14} "
          f"{'enum/kin':>9} {'|kin-static|':>13}  mechanism M_l")
    ok = True
    for n in counts:
        arch = nominal_arch(10.0, 157.5, 1.5, n)
        limit.limit_analysis(arch)  # warm-up
        t_la = 1.0 / best_rate(lambda: limit.limit_analysis(arch), 1, 3)
        t_kin = 1.0 / best_rate(lambda: limit.kinematic_mechanisms(arch), 1, 3)
        res = limit.limit_analysis(arch)
        diff = max(abs(res.k_l - res.static_k_l), abs(res.k_r - res.static_k_r))
        ok &= diff <= 1e-9
        est = limit.enumeration_estimate(n)
        if est["seconds"] <= enum_max_seconds and (kinematic._NUMBA_ENABLED or n <= kinematic._NUMPY_MAX_VOUSSOIRS):
            t0 = time.perf_counter()
            full = limit.kinematic_mechanisms(arch, method="enumeration", max_seconds=enum_max_seconds * 2)
            t_en = time.perf_counter() - t0
            same = full == (res.mechanism_l, res.mechanism_r)
            ok &= same
            enum = f"{t_en:10.2f} s" + ("" if same else " DIFFERENT")
            ratio = f"{t_en / t_kin:8.0f}x"
        else:
            enum = f"~{est['seconds']:8.0f} s*"
            ratio = f"~{est['seconds'] / t_kin:7.0f}x"
        print(f"{n:6d} {t_la * 1e3:12.1f} ms {t_kin * 1e3:7.1f} ms {enum:>14} {ratio:>9} "
              f"{diff:13.1e}  {res.mechanism_l.label}")
    print("  * estimated (enumeration_estimate), not run")
    print(f"static = kinematic (1e-9) and guided = enumerated where run: {'yes' if ok else 'NO'}")
    return ok


if __name__ == "__main__":
    sys.exit(main())
