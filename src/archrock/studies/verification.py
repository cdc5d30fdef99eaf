"""The verification study: the contact engine against the four-link model on a grid of pulses.

For one arch and a grid of pulse amplitudes (in g, signed) and durations (s), run the contact
engine (:func:`archrock.contact.engine_respond`) and the four-link model (:func:`respond`) with
the paper's impact law and with the momentum one (:class:`~archrock.dynamics.impact.ImpactSpec`), record
each model's collapse decision, their agreement, and each model's first-collapse amplitude at
each duration (the smallest |amplitude| of the grid that collapses the arch).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..contact import EngineSettings, engine_respond
from ..errors import ArchInputError
from ..geometry import VoussoirArch
from ..groundmotion import PulseSpec
from ..dynamics.impact import ImpactSpec
from ..dynamics.response import prepare, respond

__all__ = ["VerifyResult", "verify", "MODELS"]

#: the compared models, in table order
MODELS = ("engine", "paper", "momentum")


@dataclass(frozen=True, eq=False)
class VerifyResult:
    """Collapse decisions ``collapsed[model]`` (len(durations), len(amplitudes)) bool of each of
    :data:`MODELS`; ``peak[model]`` [rad] the peak (equivalent) rotation; ``cv`` the four-link
    laws' restitution (l_to_r); ``first[model][i]`` the first-collapse |amplitude| [g] at
    duration i (NaN when none of the grid collapses)."""

    arch_name: str
    pulse: str
    amplitudes: np.ndarray
    durations: np.ndarray
    collapsed: dict = field(repr=False)
    peak: dict = field(repr=False)
    cv: dict
    settings: EngineSettings

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def first(self) -> dict:
        out = {}
        order = np.argsort(np.abs(self.amplitudes))
        for m in MODELS:
            row = []
            for i in range(len(self.durations)):
                hit = [abs(self.amplitudes[j]) for j in order if self.collapsed[m][i, j]]
                row.append(hit[0] if hit else float("nan"))
            out[m] = np.array(row)
        return out

    def agreement(self, other: str) -> float:
        """Fraction of the grid where the engine and the four-link ``other`` model agree."""
        return float((self.collapsed["engine"] == self.collapsed[other]).mean())

    def to_dict(self) -> dict:
        first = self.first
        return {"arch": self.arch_name, "pulse": self.pulse,
                "amplitudes": self.amplitudes.tolist(), "durations": self.durations.tolist(),
                "collapsed": {m: self.collapsed[m].tolist() for m in MODELS},
                "peak": {m: self.peak[m].tolist() for m in MODELS},
                "first_collapse": {m: [None if np.isnan(v) else float(v) for v in first[m]]
                                   for m in MODELS},
                "agreement": {m: self.agreement(m) for m in MODELS[1:]},
                "cv": dict(self.cv), "engine": self.settings.to_dict()}


def verify(arch: VoussoirArch, amplitudes, durations, *, pulse: str = "oppenheim",
           settings: EngineSettings | None = None, t_free: float = 20.0,
           progress=None) -> VerifyResult:
    """Run the engine and the two four-link models on every (duration, amplitude) of the grid."""
    amps = np.asarray(amplitudes, float).ravel()
    durs = np.asarray(durations, float).ravel()
    if amps.size == 0 or durs.size == 0 or not np.all(np.isfinite(amps)) or np.any(amps == 0):
        raise ArchInputError("amplitudes: expected a list of finite nonzero numbers [g]")
    if not np.all(np.isfinite(durs)) or np.any(durs <= 0):
        raise ArchInputError("durations: expected a list of finite numbers > 0 [s]")
    settings = settings or EngineSettings()
    models = {"paper": prepare(arch, ImpactSpec("paper")),
              "momentum": prepare(arch, ImpactSpec("momentum"))}
    col = {m: np.zeros((durs.size, amps.size), bool) for m in MODELS}
    peak = {m: np.zeros((durs.size, amps.size)) for m in MODELS}
    total = durs.size * amps.size
    for i, d in enumerate(durs):
        for j, a in enumerate(amps):
            motion = PulseSpec(pulse, float(a), float(d)).build()
            t_end = float(motion.times[-1]) + 0.1
            for m, model in models.items():
                r = respond(model, motion, t_end=t_end, dt_out=min(0.01, t_end))
                col[m][i, j], peak[m][i, j] = r.collapsed, r.peak
            e = engine_respond(arch, motion, settings, model=models["paper"], t_end=t_end,
                               dt_out=min(0.01, t_end), t_free=t_free)
            col["engine"][i, j], peak["engine"][i, j] = e.collapsed, e.peak
            if progress:
                progress(f"{i * amps.size + j + 1}/{total}: t_p = {d:g} s, a = {a:g} g: engine "
                         f"{'collapse' if e.collapsed else e.status}, paper "
                         f"{'collapse' if col['paper'][i, j] else 'stands'}, momentum "
                         f"{'collapse' if col['momentum'][i, j] else 'stands'}")
    cv = {m: float(models[m].impact.l_to_r) for m in models}
    return VerifyResult(arch.name, pulse, amps, durs, col, peak, cv, settings)
