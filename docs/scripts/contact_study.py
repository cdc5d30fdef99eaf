"""The contact engine's convergence and the verification study of docs/verification.md.

Writes docs/figures/contact_convergence.json, docs/figures/verify_<arch>.json and
docs/figures/verify_contact.png (first-collapse amplitudes of Oppenheim's arch and of the 2 m
arch of the same proportions), and prints the markdown tables.

Usage: PYTHONPATH=src python docs/scripts/contact_study.py [--quick] [--skip-convergence]
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


def convergence():
    from archrock.contact import EngineSettings, engine_respond, ramp_direction
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse
    from archrock.dynamics.response import prepare

    arch = oppenheim_arch()
    model = prepare(arch)
    base = EngineSettings()
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
    (FIG / "contact_convergence.json").write_text(json.dumps(rows, indent=1))
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
    e = engine_respond(arch, motion, model=model, t_end=6.0)
    f = respond(model, motion, t_end=6.0)
    save_engine_figure(e, f, FIG / "dem_oppenheim_pulse.png")
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
        res = verify(arch, amps, durs, progress=lambda m: print(m, file=sys.stderr, flush=True))
        tag = "oppenheim" if k == 0 else "2m"
        (FIG / f"verify_{tag}.json").write_text(json.dumps(res.to_dict(), indent=1))
        save_verify_figure(res, None, ax=axes[0][k])
        texts.append(format_verify(res) + "\n\n" + verify_markdown(res))
    save_figure(fig, FIG / "verify_contact.png")
    return texts


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--skip-convergence", action="store_true")
    ap.add_argument("--skip-study", action="store_true")
    ap.add_argument("--skip-pulse", action="store_true")
    a = ap.parse_args()
    if not a.skip_convergence:
        print(convergence_markdown(convergence()))
    if not a.skip_pulse:
        pulse_figure()
    if not a.skip_study:
        for t in study(a.quick):
            print(t)
            print()
