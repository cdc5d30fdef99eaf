"""The contact engine's settings that change its answers, as one frozen, serialisable object."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields

from ..errors import ArchInputError

__all__ = ["EngineSettings", "DEFAULT_FRICTION"]

#: Coulomb coefficient of every contact unless --friction says otherwise: well above what the
#: thrust of ordinary arches needs, so that the default run is Heyman's no-sliding masonry.
DEFAULT_FRICTION = 0.8


def _num(name, value, lo, hi, allowed, integer=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ArchInputError(f"{name}: expected a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v) or not lo <= v <= hi or (integer and v != int(v)):
        raise ArchInputError(f"{name}: {value!r} is out of range; allowed {allowed}")
    return int(v) if integer else v


@dataclass(frozen=True)
class EngineSettings:
    """Settings of the rigid-body contact engine (pymunk / Chipmunk2D), all scale-free so that an
    arch a hundred times larger runs the same numbers of steps:

    steps_per_T: time steps per T = sqrt(size / g) (the arch's time scale; 1 s for R = 9.8 m);
    iterations: impulse-solver iterations per step;
    slop: contact overlap allowed without correction, as a fraction of the arch's size;
    bias: fraction of the remaining overlap corrected per step (Chipmunk's collision_bias is set
    to (1 - bias)^(1/dt));
    rounding: corner radius of the contact shapes, as a fraction of the size (their cores are
    inset by it, so that flush joints are not degenerate for the contact search);
    friction: Coulomb coefficient of every contact (voussoir-voussoir and voussoir-abutment);
    restitution: coefficient of restitution of every contact (0: no bounce).
    Defaults are those of the convergence study in docs/verification.md.
    """

    steps_per_T: float = 400.0
    iterations: int = 40
    slop: float = 1e-5
    bias: float = 0.1
    rounding: float = 1e-5
    friction: float = DEFAULT_FRICTION
    restitution: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "steps_per_T", _num("steps_per_T", self.steps_per_T, 10, 1e6,
                                                     "10 <= steps_per_T <= 1e6"))
        object.__setattr__(self, "iterations", _num("iterations", self.iterations, 1, 10000,
                                                    "an integer 1..10000", integer=True))
        object.__setattr__(self, "slop", _num("slop", self.slop, 0.0, 0.1, "0 <= slop <= 0.1"))
        object.__setattr__(self, "rounding", _num("rounding", self.rounding, 0.0, 0.01,
                                                  "0 <= rounding <= 0.01"))
        object.__setattr__(self, "bias", _num("bias", self.bias, 0.0, 1.0, "0 <= bias <= 1"))
        object.__setattr__(self, "friction", _num("friction", self.friction, 0.0, 100.0,
                                                  "0 <= friction (MU) <= 100"))
        object.__setattr__(self, "restitution", _num("restitution", self.restitution, 0.0, 1.0,
                                                     "0 <= restitution <= 1"))

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, data) -> "EngineSettings":
        names = {f.name for f in fields(cls)}
        if not isinstance(data, dict) or set(data) - names:
            extra = sorted(set(data) - names) if isinstance(data, dict) else data
            raise ArchInputError(f"engine settings: unknown fields {extra!r}; allowed "
                                 f"{sorted(names)}")
        return cls(**data)

    def replace(self, **changes) -> "EngineSettings":
        return EngineSettings.from_dict({**self.to_dict(), **changes})
