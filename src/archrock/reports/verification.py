"""Text report of the verification study (``archrock verify``)."""

from __future__ import annotations

import numpy as np

__all__ = ["format_verify", "verify_markdown"]


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
