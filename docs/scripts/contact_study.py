"""The contact engine's convergence and the verification study of docs/verification.md.

Writes docs/figures/contact_convergence.json, docs/figures/verify_<arch>.json and
docs/figures/verify_contact.png (first-collapse amplitudes of Oppenheim's arch and of the 2 m
arch of the same proportions), and prints the markdown tables.

The published convergence table, pulse figure and verification grid were computed with the
fine cut (every outline vertex, ``outline_tol = 0``, the engine before issue 21), which stays
this script's default (``--cut fine``); ``--cut simplified`` runs them with the default
``EngineSettings`` (outline within 2e-3 x size), written beside them with the suffix
``_simplified``.  ``--activation`` prints the activation table (four arches, both directions)
for the chosen cut.

Usage: PYTHONPATH=src python docs/scripts/contact_study.py [--quick] [--skip-convergence]
       [--cut fine|simplified] [--activation]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]
FIG = HERE / "figures"
#: "fine" (outline_tol = 0, the published figures) or "simplified" (the default settings)
CUT = {"cut": "fine"}


def base_settings():
    from archrock.contact import FINE_CUT, EngineSettings

    return FINE_CUT if CUT["cut"] == "fine" else EngineSettings()


def _suffix() -> str:
    return "" if CUT["cut"] == "fine" else "_simplified"


def activation():
    """The activation table of docs/verification.md: engine ramp beside the limit analysis."""
    from archrock.contact import ContactArch, ramp
    from archrock.geometry import family_arch, oppenheim_arch, random_arch
    from archrock.statics.limit import limit_analysis

    s = base_settings()
    cases = [("Oppenheim", oppenheim_arch()),
             ("pointed S 10, F 7, t 1 m, 9 voussoirs", family_arch("pointed", 10.0, 7.0, 1.0, 9)),
             ("irregular circular (random_arch(seed=3))", random_arch(seed=3)),
             ("irregular pointed (seed 1, tilt 5 deg)",
              random_arch(family_arch("pointed", 10.0, 7.0, 1.0, 9), seed=1, spread_tilt_deg=5.0)),
             ("pointed S 10, F 7, t 1 m, 12 voussoirs (docs/geometry.md)",
              family_arch("pointed", 10.0, 7.0, 1.0, 12))]
    rows = []
    for name, arch in cases:
        lim = limit_analysis(arch)
        pieces = max(len(p) for p in ContactArch(arch, s).pieces)
        t0 = time.perf_counter()
        r = ramp(arch, s, limit=lim)
        rows.append({"arch": name, "pieces": pieces, "seconds": time.perf_counter() - t0,
                     "k_l": r.k_l, "k_r": r.k_r, "limit_k_l": lim.k_l, "limit_k_r": lim.k_r,
                     "hinges_l": list(r.l.hinges), "hinges_r": list(r.r.hinges),
                     "edges_l": list(r.l.edges), "edges_r": list(r.r.edges)})
        print(rows[-1], file=sys.stderr, flush=True)
    (FIG / f"contact_activation{_suffix()}.json").write_text(json.dumps(
        {"engine": s.to_dict(), "rows": rows}, indent=1))
    out = ["| arch | pieces a voussoir | engine k_l, k_r | limit analysis k_l, k_r | error | "
           "engine hinges (M_l; M_r) | ramp [s] |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['arch']} | {r['pieces']} | {r['k_l']:.4f}, {r['k_r']:.4f} | "
                   f"{r['limit_k_l']:.4f}, {r['limit_k_r']:.4f} | "
                   f"{100 * (r['k_l'] / r['limit_k_l'] - 1):+.1f}%, "
                   f"{100 * (r['k_r'] / r['limit_k_r'] - 1):+.1f}% | "
                   f"{'-'.join(map(str, r['hinges_l']))}; {'-'.join(map(str, r['hinges_r']))} | "
                   f"{r['seconds']:.1f} |")
    return "\n".join(out)


def convergence():
    from archrock.contact import EngineSettings, engine_respond, ramp_direction
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse
    from archrock.dynamics.response import prepare

    arch = oppenheim_arch()
    model = prepare(arch)
    base = base_settings()
    rows = []
    variants = [("steps_per_T", v) for v in (100, 200, 400, 800)] + \
               [("iterations", v) for v in (10, 20, 80)] + \
               [("rounding", v) for v in (1e-6, 1e-4)] + [("slop", v) for v in (1e-6, 1e-4)]
    for field, value in variants:
        s = base.replace(**{field: value})
        t0 = time.perf_counter()
        r = ramp_direction(arch, "l", s)
        t1 = time.perf_counter()
        e = engine_respond(arch, oppenheim_pulse(-1.0, 0.2), s, model=model, t_end=1.0)
        t2 = time.perf_counter()
        rows.append({"field": field, "value": value, "k_l": r.multiplier, "lower": r.lower,
                     "upper": r.upper, "hinges": list(r.hinges), "peak": e.peak,
                     "status": e.status, "ramp_seconds": t1 - t0, "pulse_seconds": t2 - t1,
                     "simulated": e.t_final})
        print(rows[-1], file=sys.stderr, flush=True)
    (FIG / f"contact_convergence{_suffix()}.json").write_text(json.dumps(rows, indent=1))
    return rows


def convergence_markdown(rows):
    out = ["| setting | value | k_l (engine) | error vs 0.370010 | hinges | peak phi, -1 g pulse [rad] |",
           "|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['field']} | {r['value']:g} | {r['k_l']:.4f} | "
                   f"{100 * (r['k_l'] / 0.370010 - 1):+.2f}% | "
                   f"{'-'.join(map(str, r['hinges']))} | {r['peak']:.4f} |")
    return "\n".join(out)


def pulse_figure():
    """The paper's pulse on Oppenheim's arch: engine beside the four-link model (paper c_v)."""
    from archrock.contact import engine_respond
    from archrock.reports.contactplots import save_engine_figure
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse
    from archrock.dynamics.response import prepare, respond

    arch, motion = oppenheim_arch(), oppenheim_pulse(-1.0, 0.2)
    model = prepare(arch)
    e = engine_respond(arch, motion, base_settings(), model=model, t_end=6.0)
    f = respond(model, motion, t_end=6.0)
    save_engine_figure(e, f, FIG / f"dem_oppenheim_pulse{_suffix()}.png")
    i = [int(t / e.run["dt_out"]) for t in (0.1, 0.2, 0.3)]
    print(f"engine: {e.status}, peak {e.peak:.4f}, max sliding "
          f"{[round(v * 1e3, 2) for v in e.max_sliding]} mm; four-link: {f.status}, peak "
          f"{f.peak:.4f}, impacts {[round(t, 3) for t in f.impacts[:4]]}")
    for k in i:
        print(f"t = {e.time[k]:.2f} s: joint rotations {[round(v, 4) for v in e.joint_rotations[k]]}")


def study(quick=False):
    from archrock.reports.contactplots import save_verify_figure
    from archrock.geometry import oppenheim_arch
    from archrock.reports.plots import new_figure, save_figure
    from archrock.reports.verification import format_verify, verify_markdown
    from archrock.studies.verification import verify
    from archrock.studies.runner import RunSettings

    amps = [-0.4, -0.5, -0.75, -1.0, -1.25, -1.5, -2.0, -2.5, -3.0, -4.0, -5.0, -6.0, -8.0]
    if quick:
        amps = [-1.0, -2.0, -4.0]
    opp = oppenheim_arch()
    small = opp.scaled(0.2)
    small = dataclasses.replace(small, name="2 m arch (Oppenheim x 0.2)")
    cases = [(opp, [0.1, 0.15, 0.2, 0.3, 0.4]), (small, [0.05, 0.075, 0.1, 0.15, 0.2])]
    fig, axes = new_figure(1, 2, figsize=(11.0, 4.4))
    texts = []
    for k, (arch, durs) in enumerate(cases):
        said = RunSettings(progress=lambda m: print(m, file=sys.stderr, flush=True))
        res = verify(arch, amps, durs, settings=base_settings(), run_settings=said)
        tag = "oppenheim" if k == 0 else "2m"
        (FIG / f"verify_{tag}{_suffix()}.json").write_text(json.dumps(res.to_dict(), indent=1))
        save_verify_figure(res, None, ax=axes[0][k])
        texts.append(format_verify(res) + "\n\n" + verify_markdown(res))
    save_figure(fig, FIG / f"verify_contact{_suffix()}.png")
    return texts


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--skip-convergence", action="store_true")
    ap.add_argument("--skip-study", action="store_true")
    ap.add_argument("--skip-pulse", action="store_true")
    ap.add_argument("--cut", choices=("fine", "simplified"), default="fine",
                    help="the voussoirs' outline cut (default fine: the published figures)")
    ap.add_argument("--activation", action="store_true",
                    help="print the activation table for the cut")
    a = ap.parse_args()
    CUT["cut"] = a.cut
    if a.activation:
        print(activation())
    if not a.skip_convergence:
        print(convergence_markdown(convergence()))
    if not a.skip_pulse:
        pulse_figure()
    if not a.skip_study:
        for t in study(a.quick):
            print(t)
            print()
