"""Report of Sobol indices (:class:`archrock.studies.sensitivity.SobolResult`): the ``archrock
sensitivity --json`` object and the readable table."""

from __future__ import annotations

import math

__all__ = ["sensitivity_summary", "format_sensitivity"]


def sensitivity_summary(result) -> dict:
    """JSON-ready summary of a SobolResult."""
    return result.to_dict()


def _pm(v, c) -> str:
    if not math.isfinite(v):
        return "n/a".rjust(13)
    return f"{v:6.3f} ±{c:5.3f}"


def format_sensitivity(result) -> str:
    """Readable table: S1 and ST with their intervals, per output and group; sum(S1) against
    the R^2 of a linear model."""
    r = result
    s = r.spreads
    lines = [f"{r.nominal}: Sobol indices over random arches (spreads span {s.span:g}, "
             f"thickness {s.thickness:g}, radius {s.radius:g}"
             + (f", tilt {s.tilt:g} deg" if s.tilt else "") + f"), by {r.by}",
             f"{r.samples} base samples, {r.runs} arches"
             + (f" ({r.unusable} unusable: counted k = 0, collapsed)" if r.unusable else "")
             + f"; ± = half-width of the {r.conf_level:.0%} bootstrap interval"]
    if r.motion:
        lines.append(f"collapse: under {r.motion['description']}; impact "
                     f"{r.impact['description']}")
    width = max(12, max(len(g) for g in r.groups) + 1)
    for o, out in enumerate(r.outputs):
        lines.append("")
        if not r.variance[o] > 0:
            # constant up to rounding: there is no variance to share out
            lines.append(f"{out}: mean {r.mean[o]:.4f}, std 0 (the same on every arch): no "
                         f"indices")
            continue
        lines.append(f"{out}: mean {r.mean[o]:.4f}, std {math.sqrt(r.variance[o]):.4f}; "
                     f"sum S1 = {r.sum_S1[o]:.3f}, sum ST = {r.sum_ST[o]:.3f}, linear R^2 = "
                     f"{r.r2_linear[o]:.3f}")
        lines.append(f"  {'group':<{width}} {'S1':>13} {'ST':>13}")
        for k, g in enumerate(r.groups):
            lines.append(f"  {g:<{width}} {_pm(r.S1[o, k], r.S1_conf[o, k])} "
                         f"{_pm(r.ST[o, k], r.ST_conf[o, k])}")
    return "\n".join(lines)
