"""Reports of collapse-acceleration curves (nominal arch, with quantile bands over random arches)."""

from __future__ import annotations

import math

from ..studies.wording import resolution_line
from ._common import format_failed, format_left_out, impact_summary

__all__ = ["curves_summary", "format_curves", "format_resolution"]


def curves_summary(curve, band=None, *, arch_name: str, pulse: str, sign: int, impact,
                   cv: float | None = None, note: str | None = None) -> dict:
    """JSON-ready summary (the ``archrock curves --json`` object) of a CollapseCurve and, if
    given, its EnsembleCurve band; impact: the ImpactSpec of the run; cv: the fixed c_v it
    applies to the random arches (None for a per-arch law)."""
    out = {"arch": arch_name, "pulse": pulse, "sign": sign,
           "impact": impact_summary(impact, cv, note), "curve": curve.to_dict()}
    if band is not None:
        b = band.to_dict()
        b.pop("nominal")  # already under "curve"
        out["ensemble"] = b
    return out


def _fmt_windows(ws) -> str:
    return ", ".join(f"{lo:.3f}-{hi:.3f}" for lo, hi in ws) or "-"


def format_resolution(curve) -> str:
    """The line that says at which resolution the windows were searched (worded once, in
    :func:`archrock.studies.wording.resolution_line`, for this and the assess report)."""
    return resolution_line(curve)


def format_curves(curve, band=None, *, arch_name: str, pulse: str, sign: int, impact,
                  cv: float | None = None, note: str | None = None) -> str:
    """Readable table: first collapse amplitude, band quantiles, mode and survival windows per t_p."""
    imp = impact.describe() if cv is None else f"c_v = {cv:.4f}"
    literal = " (literal, on the rates)" if cv is not None and impact.literal else ""
    lines = [f"{arch_name}: k_l = {curve.k_l:.4f}, k_r = {curve.k_r:.4f}; {pulse} pulse, "
             f"sign {sign:+d}; impact {imp}{literal}"]
    if note:
        lines.append(f"impact law fallback: {note}")
    head = f"{'t_p [s]':>8} {'a_first [g]':>12}  {'mode':<22} survival windows above [g]"
    if band is not None:
        head = head.replace("  mode", "  " + " ".join(f"q{q:g}".rjust(7) for q in band.quantiles)
                            + "  mode")
    lines.append(head)
    for i, p in enumerate(curve.points):
        a = "none" if p.amplitude is None else f"{p.amplitude:.4f}"
        qs = ""
        if band is not None:
            qs = " ".join(("n/a" if math.isnan(v) else "inf" if not math.isfinite(v)
                           else f"{v:.3f}").rjust(7) for v in band.bands[:, i]) + " "
        lines.append(f"{p.duration:8.3f} {a:>12}  {qs}{(p.mode or '-'):<22} {_fmt_windows(p.windows)}")
    lines.append(format_resolution(curve))
    if band is not None:
        lines.append(format_left_out(band.to_dict()["left_out"], "quantiles (inf: no collapse "
                                     "up to a_max)"))
        if band.band_note:
            lines.append(f"quantile bands: n/a ({band.band_note})")
        lines += format_failed(band.failed, band.n_requested)
    return "\n".join(lines)
