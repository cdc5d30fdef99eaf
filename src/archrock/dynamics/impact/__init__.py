"""Impacts of the rocking arch: what happens when an open mechanism closes at phi = 0.

* :mod:`~archrock.dynamics.impact.laws` -- the impact laws (paper, momentum, fixed c_v) as rate ratios;
* :mod:`~archrock.dynamics.impact.least_loss` -- the post-impact mechanism that keeps the most energy;
* :mod:`~archrock.dynamics.impact.spec` -- :class:`ImpactSpec`, the one object that names the choice.
"""

from .laws import (EnergyGainWarning, ImpactLaw, fallback_note, impact_law, momentum_rate_ratio,
                   paper_rate_ratio, projection_ratio)
from .least_loss import LeastLoss, least_loss_mechanism
from .spec import IMPACT_MODELS, PAPER_PRACTICE, ImpactSpec, nominal_cv

__all__ = ["ImpactLaw", "impact_law", "paper_rate_ratio", "momentum_rate_ratio",
           "EnergyGainWarning", "projection_ratio", "LeastLoss", "least_loss_mechanism",
           "ImpactSpec", "PAPER_PRACTICE", "IMPACT_MODELS", "nominal_cv", "fallback_note"]
