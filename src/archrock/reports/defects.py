"""Report of a defect map (:class:`archrock.studies.defectmap.DefectMap`): the ``archrock defects
--json`` object and the readable table."""

from __future__ import annotations

import math

from ..studies.defectmap import names_text

__all__ = ["defects_summary", "format_defects"]


def defects_summary(dmap, impact=None) -> dict:
    """JSON-ready summary of a DefectMap (with the run's ImpactSpec when it has a pulse)."""
    out = dmap.to_dict()
    if dmap.pulse is not None and impact is not None:
        out["impact"] = {**impact.to_dict(), "description": impact.describe()}
    return out


def _num(x, spec=".4f") -> str:
    return "n/a" if x is None or not math.isfinite(x) else format(x, spec)


def _table(dmap, d, rows) -> list[str]:
    t = dmap.target
    # the place column on piers only: elsewhere the index is the voussoir's (or joint's) own
    wide = max([len(d["rows"][m]["place"]) for m in rows] + [5]) if dmap.on_piers else 0
    head = (f"{t:>8} {'place' if wide else '':<{wide}}{' ' if wide else ''}{'k_l':>8} {'k_r':>8} {'lost [g]':>9} {'lost':>7}  "
            f"{'M_l':<13} {'M_r':<13}")
    if dmap.pulse:
        head += f" {'a_first':>8} {'lost [g]':>9}"
    lines = [head]
    amp_loss = dmap.amplitude_loss
    for m in rows:
        row = d["rows"][m]
        mark = "*" if row["hinges_changed"] else " "
        place = f"{row['place']:<{wide}} " if wide else ""
        line = (f"{row[t]:>8} {place}{_num(row['k_l']):>8} "
                f"{_num(row['k_r']):>8} {_num(row['loss']):>9} {row['relative_loss']:>7.1%} "
                f"{mark}{row['hinges_l'] or '-':<13} {row['hinges_r'] or '-':<13}")
        if dmap.pulse:
            line += f" {_num(row['amplitude_g']):>8} {_num(float(amp_loss[m])):>9}"
        if row.get("note"):
            line += f"  ({row['note']})"
        lines.append(line)
    return lines


def _worst_line(dmap, label: str, w: dict) -> str:
    return (f"{label}: {names_text(w['places'])}: min(k_l, k_r) {dmap.k0:.4f} -> {w['k']:.4f} g, "
            f"-{w['loss']:.4f} g ({w['relative_loss']:.1%})")


def format_defects(dmap) -> str:
    """Readable table: k_l, k_r, the capacity lost and the hinges of each damaged arch; on
    piers the arch's voussoirs (or joints) and the piers' courses (or joints) in two tables,
    each with its worst defect (a thinned pier is a pier defect, not a voussoir's)."""
    d = dmap.to_dict()
    lines = [f"{d['arch']}: {d['description']}",
             f"undamaged: k_l = {dmap.k_l0:.4f}, k_r = {dmap.k_r0:.4f} g; hinges M_l "
             f"{dmap.hinges_l0}, M_r {dmap.hinges_r0}"
             + (f"; first collapse {_num(dmap.amplitude0)} g" if dmap.pulse else "")]
    if dmap.pulse:
        p = dmap.pulse
        sgn = "both signs (the smaller amplitude)" if p["sign"] == 0 else f"sign {p['sign']:+d}"
        lines.append(f"pulse: {p['kind']}, t_p = {p['duration']:g} s, {sgn}")
    groups = [g for g in ("arch", "piers") if g in dmap.groups]
    if dmap.on_piers:
        lines.append(f"{d['numbering']}; hinges in chain numbering")
    what = {"voussoir": ("voussoirs", "pier courses (a pier course keeps that share of its "
                                      "width)"),
            "joint": ("arch joints", "pier joints (foundations and bed joints)")}[dmap.target]
    for g in groups:
        rows = [m for m, gg in enumerate(dmap.groups) if gg == g]
        if dmap.on_piers:
            lines.append(f"{what[0] if g == 'arch' else what[1]}:")
        lines.extend(_table(dmap, d, rows))
    if dmap.on_piers and "worst_pier" in d:
        lines.append(_worst_line(dmap, f"worst {what[0][:-1]} defect", d["worst"]))
        lines.append(_worst_line(dmap, "worst pier defect", d["worst_pier"]))
        lines.append("* = other hinges than the undamaged arch's")
    else:
        lines.append(_worst_line(dmap, "worst", d["worst"])
                     + "; * = other hinges than the undamaged arch's")
    return "\n".join(lines)
