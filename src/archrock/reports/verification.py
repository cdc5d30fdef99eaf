"""Text report of the verification study (``archrock verify``)."""

from __future__ import annotations

import numpy as np

__all__ = ["format_verify", "verify_markdown", "format_verify_ensemble"]


def _cell(res, i, j) -> str:
    return "".join("C" if res.collapsed[m][i, j] else "." for m in ("engine", "paper", "momentum"))


def format_verify(res) -> str:
    amps = res.amplitudes
    lines = [f"Verification: {res.arch_name}, {res.pulse} pulses, engine MU = "
             f"{res.settings.friction:g}; four-link c_v paper {res.cv['paper']:.5f}, momentum "
             f"{res.cv['momentum']:.5f}",
             "  cells: engine/paper/momentum, C = collapse, . = stands",
             "  t_p [s] | " + " ".join(f"{a:>6g}" for a in amps) + "   (amplitude [g])"]
    for i, d in enumerate(res.durations):
        lines.append(f"  {d:7g} | " + " ".join(f"{_cell(res, i, j):>6}" for j in range(len(amps))))
    first = res.first
    lines.append("  first-collapse |amplitude| [g] per t_p: " + "; ".join(
        f"{m} " + ", ".join("-" if np.isnan(v) else f"{v:g}" for v in first[m])
        for m in ("engine", "paper", "momentum")))
    lines.append(f"  agreement of the collapse decisions: engine-paper "
                 f"{100 * res.agreement('paper'):.0f}%, engine-momentum "
                 f"{100 * res.agreement('momentum'):.0f}%")
    return "\n".join(lines)


def verify_markdown(res) -> str:
    """The decision table as a markdown table (docs)."""
    amps = res.amplitudes
    head = "| t_p [s] | " + " | ".join(f"{a:g} g" for a in amps) + " |"
    rows = [head, "|" + "---|" * (len(amps) + 1)]
    for i, d in enumerate(res.durations):
        rows.append(f"| {d:g} | " + " | ".join(_cell(res, i, j) for j in range(len(amps))) + " |")
    return "\n".join(rows)


def _hinges(h) -> str:
    return "-".join(map(str, h)) or "-"


def format_verify_ensemble(res) -> str:
    """The table of :func:`~archrock.studies.verification.verify_ensemble`: per arch and
    direction the four-link (limit analysis) and engine multipliers and hinges, and what
    differs; then the disagreement rate and where."""
    s = res.settings
    lines = [f"Verification over {res.n} arches: engine (MU = {s.friction:g}, "
             f"{s.describe()}) against the four-link model's mechanism (limit analysis); "
             f"k within {100 * res.k_tol:g}%",
             f"  {'arch':>4} {'dir':>3} | {'k 4-link':>8} {'k engine':>8} {'error':>7} | "
             f"{'4-link hinges':<14} {'engine hinges':<14} | differs"]
    for a in res.arches:
        for d in (a.l, a.r):
            ke = "-" if np.isnan(d.k_engine) else f"{d.k_engine:.4f}"
            err = "-" if np.isnan(d.k_error) else f"{100 * d.k_error:+.1f}%"
            lines.append(f"  {a.index:>4} {d.direction:>3} | {d.k_four_link:8.4f} {ke:>8} "
                         f"{err:>7} | {_hinges(d.hinges_four_link):<14} "
                         f"{_hinges(d.hinges_engine):<14} | "
                         f"{'; '.join(d.differences) if not d.agree else 'agree'}")
    lines.append(f"  disagreement rate: {100 * res.disagreement_rate:.0f}% of the arches "
                 f"({sum(not a.agree for a in res.arches)} of {res.n})")
    for d, w in sorted(res.where.items()):
        parts = []
        if w["missing"]:
            parts.append("hinge not opened at joint " + ", ".join(
                f"{j} ({c}x)" for j, c in sorted(w["missing"].items())))
        if w["extra"]:
            parts.append("extra hinge at joint " + ", ".join(
                f"{j} ({c}x)" for j, c in sorted(w["extra"].items())))
        for key, what in (("sliding", "slides first"), ("rests", "no motion in range"),
                          ("k", f"k beyond {100 * res.k_tol:g}%")):
            if w[key]:
                parts.append(f"{what} ({w[key]}x)")
        lines.append(f"  where, M_{d}: " + "; ".join(parts))
    return "\n".join(lines)
