"""Pieces shared by the reports of several studies (curves, fragility)."""

from __future__ import annotations


def impact_summary(impact, cv: float | None = None) -> dict:
    """JSON form of a study's ImpactSpec, with ``cv``: the fixed c_v it applies to the random
    arches (None for a per-arch law)."""
    return {**impact.to_dict(), "applied_cv": cv, "description": impact.describe()}


def format_failed(failed, n_requested: int) -> list[str]:
    """Lines listing the random arches that could not be analysed (none when all could)."""
    if not failed:
        return []
    return [f"{len(failed)} of {n_requested} random arches left out (unusable):",
            *(f"  sample {i}: {why}" for i, why in failed)]
