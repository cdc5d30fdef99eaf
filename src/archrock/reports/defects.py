"""Report of a defect map (:class:`archrock.studies.defectmap.DefectMap`): the ``archrock defects
--json`` object and the readable table."""

from __future__ import annotations

import math

__all__ = ["defects_summary", "format_defects"]


def defects_summary(dmap, impact=None) -> dict:
    """JSON-ready summary of a DefectMap (with the run's ImpactSpec when it has a pulse)."""
    out = dmap.to_dict()
    if dmap.pulse is not None and impact is not None:
        out["impact"] = {**impact.to_dict(), "description": impact.describe()}
    return out


def _num(x, spec=".4f") -> str:
    return "n/a" if x is None or not math.isfinite(x) else format(x, spec)


def format_defects(dmap) -> str:
    """Readable table: k_l, k_r, the capacity lost and the hinges of each damaged arch."""
    d = dmap.to_dict()
    t = dmap.target
    lines = [f"{d['arch']}: {d['description']}",
             f"undamaged: k_l = {dmap.k_l0:.4f}, k_r = {dmap.k_r0:.4f} g; hinges M_l "
             f"{dmap.hinges_l0}, M_r {dmap.hinges_r0}"
             + (f"; first collapse {_num(dmap.amplitude0)} g" if dmap.pulse else "")]
    if dmap.pulse:
        p = dmap.pulse
        sgn = "both signs (the smaller amplitude)" if p["sign"] == 0 else f"sign {p['sign']:+d}"
        lines.append(f"pulse: {p['kind']}, t_p = {p['duration']:g} s, {sgn}")
    head = f"{t:>8} {'k_l':>8} {'k_r':>8} {'lost [g]':>9} {'lost':>7}  {'M_l':<13} {'M_r':<13}"
    if dmap.pulse:
        head += f" {'a_first':>8} {'lost [g]':>9}"
    lines.append(head)
    amp_loss = dmap.amplitude_loss
    for m, row in enumerate(d["rows"]):
        mark = "*" if row["hinges_changed"] else " "
        line = (f"{row[t]:>8} {_num(row['k_l']):>8} {_num(row['k_r']):>8} "
                f"{_num(row['loss']):>9} {row['relative_loss']:>7.1%} {mark}"
                f"{row['hinges_l'] or '-':<13} {row['hinges_r'] or '-':<13}")
        if dmap.pulse:
            line += f" {_num(row['amplitude_g']):>8} {_num(float(amp_loss[m])):>9}"
        if row.get("note"):
            line += f"  ({row['note']})"
        lines.append(line)
    w = d["worst"]
    ties = w["ties"]
    which = f"{t} {ties[0]}" if len(ties) == 1 else f"{t}s {', '.join(map(str, ties))} (tied)"
    lines.append(f"worst: {which}: min(k_l, k_r) {dmap.k0:.4f} -> {w['k']:.4f} g, "
                 f"-{w['loss']:.4f} g ({w['relative_loss']:.1%}); * = other hinges than the "
                 f"undamaged arch's")
    return "\n".join(lines)
