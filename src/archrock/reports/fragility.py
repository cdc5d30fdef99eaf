"""Reports of a fragility study: IDA curves, multiple stripes and their lognormal fits."""

from __future__ import annotations

from ..groundmotion.intensity import im_label, im_units
from ..studies.wording import fit_line, level_off_note, range_tried_line
from ._common import format_ci, format_failed, format_left_out, impact_summary

__all__ = ["fragility_summary", "format_fragility"]


def fragility_summary(ida_result, stripes, *, arch_name: str, records, n_arches: int, impact,
                      cv: float | None = None, suite=None, engine: dict | None = None,
                      note: str | None = None) -> dict:
    """JSON-ready summary (the ``archrock fragility --json`` object) of an IDAResult and a
    StripeResult over ``records`` (GroundMotion) and ``n_arches`` analysed arches; ``suite``
    (:class:`archrock.groundmotion.suite.RecordSuite`): the files read, with their sha256;
    ``engine``: how the responses were run."""
    return {"arch": arch_name, "records": [r.name for r in records],
            "n_arches": n_arches, "im": ida_result.im,
            "im_units": im_units(ida_result.im),
            "record_files": None if suite is None else suite.to_dict(),
            "impact": impact_summary(impact, cv, note),
            **({} if engine is None else {"engine": engine}),
            "ida": ida_result.to_dict(),
            "stripes": stripes.to_dict()}


def format_fragility(ida_result, stripes, *, arch_name: str, n_records: int, n_arches: int,
                     n_requested: int) -> str:
    """Readable report: first collapse per record and arch, both fits, stripe counts.
    n_requested: random arches asked for (for the line on those left out)."""
    im = ida_result.im
    u = "" if im == "scale" else " " + im_units(im)
    lines = [f"{arch_name}: {n_records} record(s) x {n_arches} arch(es); IM = {im_label(im)}"]
    lines += format_failed(ida_result.failed, n_requested)
    for c in ida_result.curves:
        fc = "never" if c.first_im is None else f"{c.first_im:.4f}{u} (scale {c.first_scale:.4f})"
        sa = ", ".join(f"{s:g}" for s in c.survivals_above) or "-"
        lines.append(f"  arch {c.arch} {c.record[:40]:<40} first collapse {fc}; "
                     f"survives above at scales {sa}")
        if c.note:
            lines.append(f"    ({c.note})")
    lines.append(format_left_out(ida_result.to_dict()["left_out"], "IDA, stripes and fits"))
    rng = range_tried_line(ida_result)
    if rng is not None:
        lines.append(f"IDA: {rng}")
    for name, r in (("IDA", ida_result), ("stripes", stripes)):
        if r.fit is None:
            lines.append(f"{name}: no fit ({r.fit_error})")
            continue
        lines.append(f"{name}: {fit_line(r.fit, im)}{format_ci(r.fit)}")
        note = level_off_note(r.fit)
        if note:
            lines.append(f"  {note}")
    lines.append("stripes: " + ", ".join(f"{x:.3f}{u} {z}/{n}" for x, z, n in
                                         zip(stripes.levels, stripes.collapses, stripes.trials)))
    return "\n".join(lines)
