"""Pieces shared by the reports of several studies (curves, fragility)."""

from __future__ import annotations


def impact_summary(impact, cv: float | None = None, note: str | None = None) -> dict:
    """JSON form of a study's ImpactSpec, with ``cv``: the fixed c_v it applies to the random
    arches (None for a per-arch law), and ``note``: why that c_v is another law's (the default
    falls back to momentum where the paper's equations cannot be used on the nominal arch)."""
    return {**impact.to_dict(), "applied_cv": cv, "applied_note": note,
            "description": impact.describe()}


def format_left_out(left_out: dict, what: str) -> str:
    """One line: what a study's statistics are over, and the arches left out by reason (the
    ``left_out`` dict of a result's JSON)."""
    from ..dynamics.population import LEFT_OUT

    why = ", ".join(f"{LEFT_OUT[k].split(' (')[0]} {v}" for k, v in left_out["by_reason"].items()
                    if v)
    n = left_out["usable"]
    line = f"{what} over the {n} usable arch{'es' if n != 1 else ''} only"
    if left_out["count"]:
        line += (f"; {left_out['count']} left out ({why}), not counted: an arch that cannot "
                 f"stand is not counted as a collapse")
    return line


def format_ci(fit) -> str:
    """The bootstrap intervals of a FragilityFit: '' without bootstrap, 'n/a (why)' when they
    cannot be estimated."""
    if fit.theta_ci is None and fit.beta_ci is None:
        return "" if fit.ci_note is None else f", CI n/a ({fit.ci_note})"
    part = []
    for name, ci, spec in (("theta", fit.theta_ci, ".3f"), ("beta", fit.beta_ci, ".2f")):
        part.append(f"{name} CI n/a" if ci is None else
                    f"{name} CI [{ci[0]:{spec}}, {ci[1]:{spec}}]")
    note = "" if fit.ci_note is None else f"; {fit.ci_note}"
    return f", {fit.confidence:.0%} bootstrap: " + ", ".join(part) + note


def format_failed(failed, n_requested: int) -> list[str]:
    """Lines listing the random arches that could not be analysed (none when all could)."""
    if not failed:
        return []
    return [f"{len(failed)} of {n_requested} random arches left out (unusable):",
            *(f"  sample {i}: {why}" for i, why in failed)]
