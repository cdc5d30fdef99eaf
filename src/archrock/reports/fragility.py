"""Reports of a fragility study: IDA curves, multiple stripes and their lognormal fits."""

from __future__ import annotations

from ..groundmotion.intensity import im_label, im_units
from ..studies.wording import fit_line, level_off_note, range_tried_line
from ._common import format_ci, format_failed, format_left_out, impact_summary

__all__ = ["fragility_summary", "format_fragility", "engine_fragility_summary",
           "format_engine_fragility"]


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


def engine_fragility_summary(result, *, arch_name: str, suite=None, unused=()) -> dict:
    """JSON-ready summary of an :class:`archrock.studies.engineida.EngineIDAResult` (the
    ``archrock fragility --json`` object on the contact engine's path): "model" "engine", the
    "dynamics" choice, the IDA by the engine; "stripes" None (not run on this path)."""
    return {"arch": arch_name, "model": "engine", "dynamics": result.dynamics,
            "records": list(result.records), "n_arches": 1, "im": result.im,
            "im_units": im_units(result.im),
            "record_files": None if suite is None else suite.to_dict(),
            "ida": result.to_dict(), "stripes": None,
            "not_run": "multiple stripes and random arches: the contact engine's fragility is "
                       "the IDA of the nominal arch",
            "unused_options": list(unused)}


def format_engine_fragility(result, *, arch_name: str, friction: str) -> str:
    """Readable report of an engine IDA: the model and why, each record's first collapse on
    the grid, the fit; the four-link report's lines where they mean the same."""
    im = result.im
    u = "" if im == "scale" else " " + im_units(im)
    dyn = result.dynamics or {}
    st = result.run.settings
    lines = [f"dynamics: contact engine ({dyn.get('reason', 'asked for')})",
             f"{arch_name}: {len(result.records)} record(s) x 1 arch (nominal); IM = "
             f"{im_label(im)}; {result.scales.size} scale factors, each (record, scale) one "
             f"engine run ({st.steps_per_T:g} steps per T, restitution {st.restitution:g}, "
             f"{result.run.t_free:g} T of free motion); {friction}",
             "first collapse: the smallest collapsing scale of the grid (not bisected)"]
    ida = result.as_ida()
    for c in ida.curves:
        fc = "never" if c.first_im is None else f"{c.first_im:.4f}{u} (scale {c.first_scale:.4g})"
        sa = ", ".join(f"{s:g}" for s in c.survivals_above) or "-"
        lines.append(f"  {c.record[:40]:<40} first collapse {fc}; survives above at scales {sa}")
    rng = range_tried_line(ida)
    if rng is not None:
        lines.append(f"IDA: {rng}")
    if result.fit is None:
        lines.append(f"IDA (contact engine): no fit ({result.fit_error})")
    else:
        lines.append(f"IDA (contact engine): {fit_line(result.fit, im)}{format_ci(result.fit)}")
        note = level_off_note(result.fit)
        if note:
            lines.append(f"  {note}")
    failed = sum(st_ == "failed" for row in result.status for st_ in row)
    if failed:
        lines.append(f"{failed} engine run(s) failed (counted as no collapse; see the JSON)")
    lines.append("stripes: not run on the contact engine's path (the IDA's fit is the "
                 "fragility)")
    return "\n".join(lines)
