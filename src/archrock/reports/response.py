"""Report of one rocking response: the arch, the motion, the impact law and the outcome."""

from __future__ import annotations

__all__ = ["format_response"]


def format_response(result, model, motion) -> str:
    """Readable summary of a ResponseResult of ``model`` under ``motion``."""
    imp = result.impacts
    law = model.impact
    # the collapse time is the last passage of the unstable position; the limit is where the
    # integration stopped (it moves with the limit factor, the collapse time does not)
    outcome = (f"COLLAPSED at t = {result.t_collapse:.3f} s (last passage of the unstable "
               f"position; rotation limit reached at {result.t_limit:.3f} s)" if result.collapsed else
               ("at rest" if result.status == "rest" else "still rocking at the end of the run"))
    lines = [
        f"arch: {model.arch.name}; k_l = {model.k_l:.4f}, k_r = {model.k_r:.4f}",
        f"ground motion: {motion.name} (duration {motion.duration:g} s, PGA {motion.pga_g:.3f} g)",
        f"impact: {law.model}; rate ratio l->r {law.l_to_r:.4f}, r->l {law.r_to_l:.4f} "
        f"(energy ratio {law.energy_l_to_r:.4f}, {law.energy_r_to_l:.4f})",
        *([f"impact law fallback: {law.fallback}"] if law.fallback else []),
        f"outcome: {outcome}; peak rotation {result.peak:.4f} rad; {len(imp)} impacts"
        + (f" (first at {imp[0]:.3f} s)" if imp else "")
        + (f"; first passed the unstable position at {result.t_unstable:.3f} s"
           if result.t_unstable is not None else ""),
    ]
    opened = result.mechanisms_opened()
    if opened:
        # distinct mechanisms in order of first opening; rows 0/1 are the limit mechanisms
        first = list(dict.fromkeys((row, lab) for _, row, lab in opened))
        names = [f"{('M_l', 'M_r')[row]} {lab}" if row < 2 else
                 f"{lab} ({model.mechanism(row).direction})" for row, lab in first]
        lines.append(f"mechanisms opened ({len(opened)} times, {len(first)} distinct): {names[0]}"
                     + (", then " + ", ".join(names[1:]) if len(names) > 1 else ""))
    return "\n".join(lines)
