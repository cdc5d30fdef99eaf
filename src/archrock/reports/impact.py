"""The impact law that ran, in words: shared by the four-link and contact engine reports."""

from __future__ import annotations


def impact_law_line(law) -> str:
    """The impact law that ran, in words: where the paper's law could not be used on this arch
    (``law.fallback``) the law used instead and why, never the law asked for."""
    rates = (f"rate ratio l->r {law.l_to_r:.4f}, r->l {law.r_to_l:.4f} "
             f"(energy ratio {law.energy_l_to_r:.4f}, {law.energy_r_to_l:.4f})")
    if not law.fallback:
        return f"impact: {law.model}; {rates}"
    why = law.fallback
    tail = f"; {law.model} law used"
    if why.endswith(tail):  # the note ends by naming the law, which this line names first
        why = why[:-len(tail)]
    return (f"impact law: {law.model} (the paper's law cannot be used on this arch: {why}); "
            f"{rates}")
