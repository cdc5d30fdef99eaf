"""Report of a record selection (:mod:`archrock.groundmotion.selection`): the table of the
chosen records, the rules with their outcome, the CSV of the selection and the figure of the
spectra (matplotlib, optional)."""

from __future__ import annotations

import csv
import io

import numpy as np

__all__ = ["format_selection", "selection_json", "selection_csv", "event_names",
           "selection_figure", "DISPLAY_RANGE"]

#: the figure shows the spectra from lo / DISPLAY_RANGE to hi x DISPLAY_RANGE of the range
DISPLAY_RANGE = 2.0


def event_names(selection) -> tuple:
    """Each chosen record's event as the FEMA P695 metadata names it ('Northridge 1994,
    Beverly Hills - Mulhol'), else the record's event key (its name)."""
    from ..errors import ArchInputError
    from ..groundmotion.p695 import is_suite_ref, parse_ref, suite_records

    out = []
    for name, key in zip(selection.names, selection.events):
        text = key
        if is_suite_ref(name):
            try:
                suite, record, comp = parse_ref(name)
                r = next(r for r in suite_records(suite)
                         if r.record == record and r.component == comp)
                text = f"{r.event} {r.year}, {r.station}"
            except (ArchInputError, StopIteration):  # the extra is not installed
                pass
        out.append(text)
    return tuple(out)


def format_selection(selection) -> str:
    """The selection as text: the target, the records with their factors and scaled PGAs, the
    least mean/target ratio and each rule with pass or fail."""
    s = selection
    lo, hi = s.period_range
    events = event_names(s)
    per_event = "one component per station" if s.one_per_station else "components chosen freely"
    lines = [f"records scaled for: {s.description or 'the target spectrum given'}",
             f"{s.count} of {s.candidates} candidate records ({per_event}), "
             f"{100 * s.damping:g}%-damped spectra over {lo:g}-{hi:g} s, factors within "
             f"{s.scale_bounds[0]:g}-{s.scale_bounds[1]:g}",
             f"{'#':>3}  {'record':28s} {'event':44s} {'factor':>7} {'PGA g':>7}"]
    for k, (name, event, f, pga) in enumerate(zip(s.names, events, s.factors, s.pga_g), 1):
        lines.append(f"{k:>3}  {name[:28]:28s} {event[:44]:44s} {f:7.3f} {pga:7.3f}")
    site = "" if s.pga_min_g is None else f" (site a_g S {s.pga_min_g:.4g} g)"
    lines += [f"mean/target: least {s.ratio_min:.3f} at {s.ratio_period:.3g} s (the rule: >= "
              f"{s.lower:g} over {lo:g}-{hi:g} s); common adjustment {s.adjustment:.3f} of "
              f"each record's own factor",
              f"mean PGA of the scaled set: {s.pga_mean_g:.4g} g{site}",
              "rules (NTC 2018 3.2.3.6, EN 1998-1 3.2.3.1.2):"]
    for rule, ok, found in s.rules:
        lines.append(f"  [{'pass' if ok else 'FAIL'}] {rule}" + (f": {found}" if found else ""))
    lines.append("the rules hold" if s.rules_hold else
                 "the rules do not all hold: see FAIL above")
    return "\n".join(lines)


def selection_json(selection) -> dict:
    """The selection's JSON with each record's event (:func:`event_names`)."""
    d = selection.to_dict()
    for row, event in zip(d["records"], event_names(selection)):
        row["event_name"] = event
    return d


def selection_csv(selection) -> str:
    """One row per chosen record: index, name, event, factor, PGA of the scaled record [g]."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["index", "name", "event", "factor", "pga_scaled_g"])
    for i, name, event, f, pga in zip(selection.indices, selection.names,
                                      event_names(selection), selection.factors,
                                      selection.pga_g):
        w.writerow([i, name, event, f"{f:.6g}", f"{pga:.6g}"])
    return buf.getvalue()


def _display(selection, motions, spectrum):
    """Periods, scaled spectra and target to draw: wider than the range when the motions and
    the spectrum are given, else the selection's own grid."""
    s = selection
    if motions is None or spectrum is None:
        return s.periods, s.spectra, s.target
    from ..groundmotion.spectra import response_spectrum

    lo, hi = s.period_range
    top = min(hi * DISPLAY_RANGE, spectrum.t_max)
    periods = np.union1d(np.geomspace(lo / DISPLAY_RANGE, top, 80), s.periods)
    spectra = np.array([f * response_spectrum(motions[i], periods, s.damping)
                        for i, f in zip(s.indices, s.factors)])
    return periods, spectra, np.asarray(spectrum.se(periods), float)


def selection_figure(selection, path=None, motions=None, spectrum=None, dpi: int = 150):
    """The figure of a selection: each scaled spectrum (thin grey), their mean (thick), the
    target, ``lower`` x target (dashed), the period range shaded; log period axis.  With the
    ``motions`` the selection was made from and the target ``spectrum`` (an object with
    ``se(T)`` and ``t_max``), the spectra are drawn beyond the range too.  Saved to ``path``
    when given; returns the figure."""
    from .drawing import new_figure, save_figure

    s = selection
    periods, spectra, target = _display(s, motions, spectrum)
    fig, axes = new_figure(figsize=(7.0, 4.6))
    ax = axes[0, 0]
    ax.axvspan(*s.period_range, color="#f0e6c8", zorder=0,
               label=f"period range {s.period_range[0]:g}-{s.period_range[1]:g} s")
    for k, row in enumerate(spectra):
        ax.plot(periods, row, color="#9a9a9a", lw=0.7, label="scaled records" if k == 0 else None)
    ax.plot(periods, spectra.mean(axis=0), color="#1f4e9c", lw=2.2,
            label=f"mean of {s.count}")
    ax.plot(periods, target, color="#c0392b", lw=1.6, label="target")
    ax.plot(periods, s.lower * target, color="#c0392b", lw=1.2, ls="--",
            label=f"{s.lower:g} x target")
    ax.plot([s.ratio_period], [s.ratio_min * np.interp(s.ratio_period, s.periods, s.target)],
            "o", color="#1f4e9c", ms=5,
            label=f"least mean/target {s.ratio_min:.3f} at {s.ratio_period:.3g} s")
    ax.set_xscale("log")
    ax.set_xlabel("period T [s]")
    ax.set_ylabel(f"Sa(T, {100 * s.damping:g}%) [g]")
    ax.set_title("records scaled for the site spectrum", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    if path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig
