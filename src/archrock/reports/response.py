"""Report of one rocking response: the arch, the motion, the impact law and the outcome."""

from __future__ import annotations

from .impact import impact_law_line

__all__ = ["format_response", "impact_law_line", "format_engine_outcome", "not_valid_reason"]


def not_valid_reason(choice) -> str | None:
    """Why the four-link model asked for by name does not hold here (the WARNING parts of
    ``choice.reason``, :func:`archrock.studies.enginestudy.choose_dynamics`), or None where it
    holds."""
    parts = choice.reason.split("; WARNING ")[1:]
    if not parts:
        return None
    return "; ".join(p[len("not valid here: "):] if p.startswith("not valid here: ") else p
                     for p in parts)


def format_engine_outcome(res, arch, motion, choice, friction_line: str) -> str:
    """The contact engine's response (:class:`archrock.contact.motion.ContactResponse`) of
    ``arch`` to ``motion`` as the governing answer: outcome, peak, sliding, and why the engine
    ran (``choice``, a DynamicsChoice); no four-link number."""
    from .contact import blocks_words

    s = res.settings
    outcome = (f"COLLAPSED at t = {res.t_collapse:.3f} s (a block's mass centre dropped by "
               f"{res.run['collapse_drop']:g} x size)" if res.collapsed else
               {"rest": "at rest", "moving": "still moving when the free motion ran out "
                "(counted as not collapsed)"}.get(res.status, res.status))
    ms = res.max_sliding
    j = int(ms.argmax())
    return "\n".join([
        f"arch: {arch.name} ({blocks_words(arch)})",
        f"dynamics: contact engine ({choice.reason})",
        friction_line + f"; restitution {s.restitution:g}",
        f"ground motion: {motion.name} (duration {motion.duration:g} s, PGA {motion.pga_g:.3f} g)",
        "impact: none (the engine's contacts resolve each impact; no impact law)",
        f"outcome (contact engine): {outcome}; peak equivalent rotation {res.peak:.4f} rad; run "
        f"to {res.t_final:.2f} s",
        f"max sliding: {ms.max() * 1e3:.2f} mm at joint {j}",
    ])


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
        impact_law_line(law),
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
    fc = getattr(model.arch, "fc", None)
    if fc is not None:  # the four-link model rocks about the statics' inset hinges
        lines.append(f"strength: f_c = {fc:g} MPa; M_l and M_r rock about hinges half a stress "
                     f"block in from the edges (the blocks at collapse: "
                     f"{_zone_words(model.limit)})")
    return "\n".join(lines)


def _zone_words(lim) -> str:
    """The compressed zones [mm] at the hinges of M_l and M_r at collapse, in words."""
    parts = []
    for d in ("l", "r"):
        zones = getattr(lim, f"zones_{d}", None)
        if zones is None:
            continue
        hs = sorted(lim.mechanism(d).hinges, key=lambda h: h.joint)
        parts.append(f"M_{d} " + ", ".join(f"{1e3 * float(zones[h.joint]):.3g}" for h in hs)
                     + " mm")
    return "; ".join(parts) or "not given"
