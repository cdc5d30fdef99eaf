"""What an assessment computes (:class:`AssessConfig`, frozen and serialisable) and what its
sections share (:class:`Context`: the arch, the configuration and the results computed once).
Below the sections (assessment_statics.py, assessment_dynamics.py), which read the context, and
below :mod:`archrock.studies.assessment`, which runs them in order."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..dynamics.impact import PAPER_PRACTICE, ImpactSpec
from ..errors import ArchInputError, ArchrockError
from ..geometry import VoussoirArch
from ..geometry.sampling import Spreads
from ..statics.friction import DEFAULT_FRICTION, check_friction
from .codecheck import CodeCheckConfig
from .selection import SelectionConfig

__all__ = ["AssessConfig", "Context"]


# ---------------------------------------------------------------------------- configuration
@dataclass(frozen=True)
class AssessConfig:
    """What the assessment computes, frozen and serialisable.

    impact: the impact law (:class:`ImpactSpec`); pulse_amplitude [g], pulse_duration [s]: the
    paper's Oppenheim pulse (-1 g, 0.2 s); t_end [s]: the response window;
    durations [s]: pulse durations of the collapse-acceleration curve; n_scan: its amplitude grid;
    samples, seed, spreads: the irregular arches of the band (and of the fragility, if records);
    records: accelerogram files (none: no fragility section); record_units; scales: IDA scale
    factors; bootstrap: fragility resamples; codecheck: the code check's configuration;
    friction: the joints' Coulomb coefficient, one for the whole report (the friction analysis,
    the governing decision, the routing of the dynamics and the contact engine); default the
    package's DEFAULT_FRICTION; None: sliding excluded by the user (Heyman's hypothesis);
    selection: how the time-history verification chooses and scales the records for the code
    check's site spectrum (:class:`~archrock.studies.selection.SelectionConfig`).
    """

    impact: ImpactSpec = field(default_factory=lambda: ImpactSpec.parse(PAPER_PRACTICE))
    pulse_amplitude: float = -1.0
    pulse_duration: float = 0.2
    t_end: float = 3.0
    durations: tuple = (0.1, 0.2, 0.3, 0.5, 0.7, 1.0)
    n_scan: int = 60
    samples: int = 12
    seed: int = 0
    spreads: Spreads = field(default_factory=Spreads)
    records: tuple = ()
    record_units: str | None = None
    scales: tuple = tuple(np.round(np.linspace(0.2, 3.0, 15), 6))
    bootstrap: int = 0
    codecheck: CodeCheckConfig = field(default_factory=CodeCheckConfig)
    friction: float | None = DEFAULT_FRICTION
    selection: SelectionConfig = field(default_factory=SelectionConfig)

    def __post_init__(self):
        if self.friction is not None:
            if isinstance(self.friction, bool):
                raise ArchInputError(f"friction: {self.friction!r}; allowed a finite friction "
                                     f"coefficient > 0, or None (sliding excluded)")
            object.__setattr__(self, "friction", check_friction(self.friction))
        for name in ("pulse_amplitude", "pulse_duration", "t_end"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ArchInputError(f"{name}: {v!r}; allowed a finite number")
        if self.pulse_duration <= 0 or self.t_end <= 0:
            raise ArchInputError("pulse_duration, t_end: allowed > 0 s")
        if self.pulse_amplitude == 0:
            raise ArchInputError("pulse_amplitude: 0; allowed a nonzero amplitude in g")
        d = tuple(float(x) for x in self.durations)
        if not d or any(not (math.isfinite(x) and x > 0) for x in d):
            raise ArchInputError(f"durations: {self.durations!r}; allowed positive periods in s")
        object.__setattr__(self, "durations", d)
        object.__setattr__(self, "scales", tuple(float(x) for x in self.scales))
        object.__setattr__(self, "records", tuple(str(r) for r in self.records))
        for name, lo in (("n_scan", 2), ("samples", 0), ("seed", 0), ("bootstrap", 0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
                raise ArchInputError(f"{name}: {v!r}; allowed an integer >= {lo}")
        if self.bootstrap == 1:
            raise ArchInputError("bootstrap: 1; allowed 0 or an integer >= 2")
        if isinstance(self.spreads, dict):
            object.__setattr__(self, "spreads", Spreads.from_dict(self.spreads))
        if isinstance(self.selection, dict):
            object.__setattr__(self, "selection", SelectionConfig.from_dict(self.selection))
        if not isinstance(self.selection, SelectionConfig):
            raise ArchInputError(f"selection: {type(self.selection).__name__}; allowed a "
                                 f"SelectionConfig")

    def to_dict(self) -> dict:
        return {"impact": self.impact.to_dict(), "pulse_amplitude": self.pulse_amplitude,
                "pulse_duration": self.pulse_duration, "t_end": self.t_end,
                "durations": list(self.durations), "n_scan": self.n_scan, "samples": self.samples,
                "seed": self.seed, "spreads": self.spreads.to_dict(), "records": list(self.records),
                "record_units": self.record_units, "scales": list(self.scales),
                "bootstrap": self.bootstrap, "codecheck": self.codecheck.to_dict(),
                "friction": self.friction, "selection": self.selection.to_dict()}

    @classmethod
    def from_dict(cls, d: dict) -> "AssessConfig":
        d = dict(d)
        d["impact"] = ImpactSpec.from_dict(d["impact"])
        d["spreads"] = Spreads.from_dict(d["spreads"])
        d["codecheck"] = CodeCheckConfig.from_dict(d["codecheck"])
        if "selection" in d:  # a 0.7 report's configuration has none: the default
            d["selection"] = SelectionConfig.from_dict(d["selection"])
        for k in ("durations", "records", "scales"):
            d[k] = tuple(d[k])
        return cls(**d)


# ---------------------------------------------------------------------------- context
@dataclass(frozen=True)
class _Failed:
    exc: Exception


@dataclass
class Context:
    """What the sections share: the arch, the configuration, a progress callback and a cache of
    results computed once (the limit analysis, the dynamic model)."""

    arch: VoussoirArch
    config: AssessConfig
    progress: Callable[[str], None] = lambda msg: None
    cache: dict = field(default_factory=dict)
    #: whether the governing decision ramps the contact engine: where the report has its
    #: contact section (the app's fast report leaves both out)
    engine: bool = True

    def once(self, key: str, compute: Callable):
        """compute() the first time; its result, or the error it raised, every time after (a
        failed limit analysis is not run again by each section that needs it)."""
        if key not in self.cache:
            try:
                self.cache[key] = compute()
            except Exception as exc:  # noqa: BLE001 - kept and raised again, not swallowed
                self.cache[key] = _Failed(exc)
        value = self.cache[key]
        if isinstance(value, _Failed):
            raise value.exc
        return value

    @property
    def limit(self):
        from ..statics.limit import limit_analysis

        return self.once("limit", lambda: limit_analysis(self.arch, verify=True))

    @property
    def records(self) -> list:
        """The accelerograms of the configuration, read once."""
        from ..groundmotion import load_record

        return self.once("records", lambda: [load_record(f, units=self.config.record_units)
                                             for f in self.config.records])

    @property
    def model(self):
        from ..dynamics.response import prepare

        return self.once("model", lambda: prepare(self.arch, self.config.impact, limit=self.limit))

    @property
    def friction(self) -> dict | None:
        """What friction does to k at the report's friction, computed once: {"needed": {"l":
        mu or None, "r": ...} (None: no finite friction suffices), "mu": the report's friction
        (None: sliding excluded by the user), "with_mu": {"l": k, "r": k} or None,
        "with_mu_error": why not, or None, "sliding_governs"}; None when
        archrock.statics.friction does not import."""
        return self.once("friction", self._friction)

    def _friction(self):
        try:
            from ..statics.friction import friction_analysis, friction_needed
        except ImportError:
            return None
        mu = self.config.friction
        if getattr(self.arch, "fc", None) is not None:
            return self._friction_with_crushing(mu)
        out = {"needed": friction_needed(self.arch), "mu": mu, "with_mu": None,
               "with_mu_error": None, "sliding_governs": None}
        if mu is None:  # sliding excluded by the user: no friction analysis
            return out
        try:
            fa = friction_analysis(self.arch, mu)
        except ArchrockError as exc:  # e.g. the joints slide under self-weight at this mu
            out["with_mu_error"] = " ".join(str(exc).split())
        else:
            out["with_mu"] = {d: fa.direction(d).multiplier for d in ("l", "r")}
            out["sliding_governs"] = {d: fa.direction(d).sliding_governs for d in ("l", "r")}
        return out

    def _friction_with_crushing(self, mu):
        """:meth:`_friction` with a finite f_c: Heyman's friction analyses assume no crushing,
        so the friction needed is read on the finite-strength collapse's own thrust line (its
        static state is unique where four hinges form) and the multipliers at mu are friction
        and crushing in one program (studies.governing, on the graph of blocks)."""
        from ..statics.friction import thrust_friction
        from .governing import friction_with_crushing

        lim = self.limit
        needed = thrust_friction(self.arch, {"l": lim.thrust_l, "r": lim.thrust_r})
        out = {"needed": needed, "mu": mu, "with_mu": None, "with_mu_error": None,
               "sliding_governs": None, "with_crushing": self.arch.fc}
        if mu is None:
            return out
        cap = friction_with_crushing(self.arch, mu)
        if "error" in cap.details:
            out["with_mu_error"] = cap.details["error"]
        else:
            out["with_mu"] = {d: cap.k(d) for d in ("l", "r")}
            out["sliding_governs"] = {d: cap.why[d] == "sliding governs" for d in ("l", "r")}
        return out

    @property
    def governing(self):
        """The governing capacity at the report's friction (studies.governing), with the
        contact engine where the report has its section and pymunk imports, computed once."""
        from .governing import governing_capacity

        return self.once("governing", lambda: governing_capacity(
            self.arch, self.config.friction, engine=self.engine, limit=self.limit,
            progress=self.progress, engine_left_out="the contact-engine section is not part "
                                                    "of this report"))

    @property
    def dynamics(self):
        """The dynamic model that holds for the arch at the report's friction
        (enginestudy.choose_dynamics, "auto"), computed once."""
        from .enginestudy import choose_dynamics

        return self.once("dynamics", lambda: choose_dynamics(self.arch, "auto",
                                                             friction=self.config.friction))
