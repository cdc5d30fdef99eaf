"""The least-loss post-impact mechanism (Bisegna, Coccia, Como, Nodargi 2023).

At an impact the closing mechanism's joints shut; instead of opening the opposite limit-analysis
mechanism (the paper's alternation), the arch may open whichever admissible four-hinge mechanism
of the other direction keeps the most kinetic energy under the momentum (projection) law.
"""

from __future__ import annotations

from dataclasses import dataclass
from ...statics.hinges import Mechanism
from ..fourlink import FourLink, candidate_four_links
from .laws import _m0, momentum_rate_ratio

__all__ = ["LeastLoss", "least_loss_mechanism"]


@dataclass(frozen=True)
class LeastLoss:
    """The post-impact mechanism that keeps the most kinetic energy (Bisegna, Coccia, Como,
    Nodargi 2023), among all admissible four-hinge mechanisms opening in the other direction,
    with the momentum (projection) impact law.

    mechanism: its hinges; rate_ratio, energy_ratio: its c and kinetic-energy ratio; limit_*:
    the same for the limit-analysis mechanism archrock opens by default; candidates: how many
    mechanisms were compared.
    """

    closing: str
    mechanism: object
    rate_ratio: float
    energy_ratio: float
    limit_rate_ratio: float
    limit_energy_ratio: float
    candidates: int

    @property
    def is_limit_mechanism(self) -> bool:
        return self.energy_ratio <= self.limit_energy_ratio * (1 + 1e-12)

    def to_dict(self) -> dict:
        return {"closing": self.closing, "mechanism": self.mechanism.to_dict(),
                "rate_ratio": self.rate_ratio, "energy_ratio": self.energy_ratio,
                "limit_rate_ratio": self.limit_rate_ratio,
                "limit_energy_ratio": self.limit_energy_ratio,
                "is_limit_mechanism": self.is_limit_mechanism, "candidates": self.candidates}


def least_loss_mechanism(old: FourLink, limit_new: FourLink) -> LeastLoss:
    """Compare the limit-analysis post-impact mechanism ``limit_new`` with every admissible
    four-hinge mechanism of its direction; return the one with the largest energy ratio.

    Beyond the paper, after Bisegna et al. (2023): the dynamics keep opening ``limit_new``; this
    says how much less energy another mechanism would lose at the same impact.
    """
    arch = old.arch
    direction = limit_new.direction
    m_old = _m0(old)

    def energy(fl):
        c = momentum_rate_ratio(old, fl)
        return c, c * c * _m0(fl) / m_old

    c_lim, e_lim = energy(limit_new)
    best = (e_lim, c_lim, limit_new.mechanism)
    count = 0
    for mech, fl in candidate_four_links(arch, direction):
        count += 1
        c, e = energy(fl)
        if e > best[0] * (1 + 1e-12):
            # its own activation multiplier (virtual work), for the record
            best = (e, c, Mechanism(direction, mech.hinges, abs(fl.static_multiplier())))
    return LeastLoss("l" if direction == "r" else "r", best[2], best[1], best[0], c_lim, e_lim, count)
