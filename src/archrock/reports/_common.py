"""Pieces shared by the reports of several studies (curves, fragility)."""

from __future__ import annotations


def impact_summary(impact, literal_cv: bool = False):
    """JSON form of a study's impact spec: the model name, or the fixed c_v and how it applies."""
    if isinstance(impact, str):
        return impact
    return {"model": "fixed", "cv": impact, "literal": literal_cv}


def format_failed(failed, n_requested: int) -> list[str]:
    """Lines listing the random arches that could not be analysed (none when all could)."""
    if not failed:
        return []
    return [f"{len(failed)} of {n_requested} random arches left out (unusable):",
            *(f"  sample {i}: {why}" for i, why in failed)]
