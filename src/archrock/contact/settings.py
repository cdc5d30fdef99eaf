"""The contact engine's settings that change its answers, as one frozen, serialisable object."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields

from ..errors import ArchInputError
from ..statics.friction import check_friction
from ..units import G

__all__ = ["EngineSettings", "EngineScales", "engine_scales", "DEFAULT_FRICTION",
           "DEFAULT_OUTLINE_TOL", "FINE_CUT"]

#: Coulomb coefficient of every contact unless --friction says otherwise: the package's one
#: default (archrock.statics.friction.DEFAULT_FRICTION), so that the engine and the limit analysis
#: with friction assume the same joints.
from ..statics.friction import DEFAULT_FRICTION  # noqa: E402

#: How far the contact shapes' outline may deviate from a voussoir's, as a fraction of the arch's
#: size (0: the fine cut, every outline vertex kept).
DEFAULT_OUTLINE_TOL = 2e-3

#: The engines: archrock's own nonsmooth contact dynamics (:mod:`archrock.contact.nscd`), and
#: pymunk (soft contacts), kept as a cross-check (``pip install "archrock[dem]"``).
ENGINES = ("archrock", "pymunk")


def _num(name, value, lo, hi, allowed, integer=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ArchInputError(f"{name}: expected a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v) or not lo <= v <= hi or (integer and v != int(v)):
        raise ArchInputError(f"{name}: {value!r} is out of range; allowed {allowed}")
    return int(v) if integer else v


@dataclass(frozen=True)
class EngineSettings:
    """Settings of the rigid-block contact engine, all scale-free so that an arch a hundred
    times larger runs the same numbers of steps:

    engine: "archrock" (default), archrock's own nonsmooth contact dynamics
    (:mod:`archrock.contact.nscd`: exact unilateral contacts and Coulomb friction at the joints'
    ends, Moreau-Jean steps), or "pymunk", the soft-contact game engine kept as a cross-check;
    steps_per_T: time steps per T = sqrt(size / g) (the arch's time scale; 1 s for R = 9.8 m);
    friction: Coulomb coefficient of every contact (voussoir-voussoir and voussoir-abutment),
    finite and > 0 as in the limit analysis (:func:`archrock.statics.friction.check_friction`);
    restitution: Newton's coefficient of every contact (0: no bounce);
    tolerance: archrock's solver stops when its residuals are below tolerance x g x dt [m/s];
    max_rounds: archrock's solver's most rounds of De Saxce's friction shift in one step (a step
    left unconverged is counted, :meth:`~archrock.contact.rigid.RigidBlocks.solver_stats`);
    pymunk only -- iterations: impulse-solver iterations per step; slop: contact overlap allowed
    without correction, as a fraction of the arch's size; bias: fraction of the remaining overlap
    corrected per step (Chipmunk's collision_bias is set to (1 - bias)^(1/dt)); rounding: corner
    radius of the contact shapes, as a fraction of the size; outline_tol: the contact shapes'
    outline may deviate from the voussoir's by this fraction of the size
    (:func:`~archrock.contact.convex.simplify_outline`; 0: the fine cut).
    Defaults are those of the convergence studies in docs/verification.md; how they become
    seconds and metres on a given arch is :func:`engine_scales`.
    """

    steps_per_T: float = 400.0
    iterations: int = 40
    slop: float = 1e-5
    bias: float = 0.1
    rounding: float = 1e-5
    friction: float = DEFAULT_FRICTION
    restitution: float = 0.0
    outline_tol: float = DEFAULT_OUTLINE_TOL
    engine: str = "archrock"
    tolerance: float = 1e-6
    max_rounds: int = 200

    def __post_init__(self):
        if self.engine not in ENGINES:
            raise ArchInputError(f"engine: {self.engine!r}; allowed one of {', '.join(ENGINES)}")
        object.__setattr__(self, "tolerance", _num("tolerance", self.tolerance, 1e-12, 1e-2,
                                                   "1e-12 <= tolerance <= 1e-2"))
        object.__setattr__(self, "max_rounds", _num("max_rounds", self.max_rounds, 1, 10000,
                                                    "an integer 1..10000", integer=True))
        object.__setattr__(self, "steps_per_T", _num("steps_per_T", self.steps_per_T, 10, 1e6,
                                                     "10 <= steps_per_T <= 1e6"))
        object.__setattr__(self, "iterations", _num("iterations", self.iterations, 1, 10000,
                                                    "an integer 1..10000", integer=True))
        object.__setattr__(self, "slop", _num("slop", self.slop, 0.0, 0.1, "0 <= slop <= 0.1"))
        object.__setattr__(self, "rounding", _num("rounding", self.rounding, 0.0, 0.01,
                                                  "0 <= rounding <= 0.01"))
        object.__setattr__(self, "bias", _num("bias", self.bias, 0.0, 1.0, "0 <= bias <= 1"))
        if isinstance(self.friction, bool):
            raise ArchInputError(f"friction: expected a number, got {self.friction!r}")
        # one friction field, one range, in the limit analysis and the engine alike
        object.__setattr__(self, "friction", check_friction(self.friction))
        object.__setattr__(self, "restitution", _num("restitution", self.restitution, 0.0, 1.0,
                                                     "0 <= restitution <= 1"))
        object.__setattr__(self, "outline_tol", _num("outline_tol", self.outline_tol, 0.0, 0.01,
                                                     "0 <= outline_tol <= 0.01 (fraction of the "
                                                     "size; 0: the fine cut)"))

    def to_dict(self) -> dict:
        return asdict(self)

    def describe(self) -> str:
        """The settings that make this engine's answer, in one line (without the friction and
        restitution, which the reports state once)."""
        if self.engine == "archrock":
            return (f"archrock's nonsmooth contact dynamics, {self.steps_per_T:g} steps per T, "
                    f"solver tolerance {self.tolerance:g} x g dt")
        return (f"pymunk (soft contacts), {self.steps_per_T:g} steps per T, {self.iterations} "
                f"iterations, slop {self.slop:g}, rounding {self.rounding:g}, outline_tol "
                f"{self.outline_tol:g} (x size)")

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


@dataclass(frozen=True)
class EngineScales:
    """The engine settings made concrete for one arch (:func:`engine_scales`).

    size [m]: the arch's size; time_scale T = sqrt(size/g) [s]: its characteristic period (a
    pendulum of length ``size`` swings with period 2 pi T, and the four-link rocking frequency p
    of geometrically similar arches scales as 1/T); dt = T / steps_per_T [s]: the time step;
    slop, rounding, outline_tol [m]: the settings' fractions of the size."""

    size: float
    time_scale: float
    dt: float
    slop: float
    rounding: float
    outline_tol: float

    def to_dict(self) -> dict:
        return asdict(self)


def engine_scales(arch, settings: EngineSettings | None = None) -> EngineScales:
    """How ``settings`` (default :class:`EngineSettings`) are chosen for ``arch``: every length
    is a fraction of ``arch.size`` and every duration a fraction of T = sqrt(size/g), so an arch
    a hundred times larger runs with a ten times longer step and the same number of steps per
    rocking period, and contact tolerances a hundred times larger."""
    settings = settings or EngineSettings()
    size = float(arch.size)
    if not math.isfinite(size) or size <= 0:
        raise ArchInputError(f"arch size: {size!r} m; allowed a finite length > 0")
    t = math.sqrt(size / G)
    return EngineScales(size, t, t / settings.steps_per_T, settings.slop * size,
                        settings.rounding * size, settings.outline_tol * size)


#: The fine cut of pymunk's engine: every vertex of each voussoir's outline kept (pymunk before
#: issue 21).
FINE_CUT = EngineSettings(outline_tol=0.0, engine="pymunk")
