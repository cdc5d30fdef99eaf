"""How an ensemble's samples lose energy at impact: the configuration's ``impact`` choice resolved
to the law that :func:`archrock.batch.prepare_batch` applies to every sample."""

from __future__ import annotations

import json
from functools import lru_cache
from typing import TYPE_CHECKING

from ..geometry import Arch

if TYPE_CHECKING:
    from .config import EnsembleConfig

__all__ = ["IMPACT_CHOICES", "resolve_impact"]

IMPACT_CHOICES = ("nominal-paper", "paper", "momentum", "fixed")


@lru_cache(maxsize=16)
def _nominal_paper_cv(nominal_json: str) -> float:
    import warnings

    from ..response import nominal_cv

    arch = Arch.from_dict(json.loads(nominal_json), name="nominal")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return nominal_cv(arch)  # raises EnergyGainError if it creates energy


def resolve_impact(config: EnsembleConfig) -> dict:
    """{'model': 'fixed' | 'paper' | 'momentum', 'cv': float or None, 'source': ...}."""
    if config.impact == "nominal-paper":
        cv = _nominal_paper_cv(json.dumps(config.nominal, sort_keys=True))
        return {"model": "fixed", "cv": cv,
                "source": "c_v of the nominal arch with the 'paper' model, applied as a fixed c_v "
                          "(kinetic energy after impact = c_v^2 x before)"}
    if config.impact == "fixed":
        return {"model": "fixed", "cv": config.cv, "source": "user-given c_v (energy-consistent)"}
    return {"model": config.impact, "cv": None, "source": "per-geometry impact law"}

