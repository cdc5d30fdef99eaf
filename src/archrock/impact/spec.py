"""The impact specification: which impact law a computation uses, as one serialisable object.

An :class:`ImpactSpec` says

* ``model``: ``"paper"`` (De Lorenzis et al. 2007, the paper's), ``"momentum"`` (energy-consistent
  projection), ``"fixed"`` (a given coefficient of restitution ``cv``) or ``"least-loss"``
  (momentum law, each impact opening the mechanism that keeps the most energy; Bisegna et al.
  2023);
* ``cv``: the coefficient of restitution of the fixed model, 0 < cv <= 1;
* ``literal``: a fixed c_v multiplies the rates (the paper's wording) instead of the kinetic
  energy by cv^2 (energy-consistent, the default);
* ``on``: ``"arch"`` evaluates the model on every arch analysed; ``"nominal"`` evaluates it once
  on the study's nominal arch and applies the resulting c_v to every arch as a fixed coefficient
  (the paper's practice, section 5.1: "as a first approximation").  When one arch is analysed
  alone it is its own nominal arch, so ``"nominal"`` then means the model on that arch.

:data:`PAPER_PRACTICE` (the paper model on the nominal arch) is the default of every command and
study; ``prepare(arch)`` alone uses the paper model on ``arch``, which is the same thing.
"""

from __future__ import annotations

import json
import math
import warnings
from dataclasses import dataclass

from ..errors import ArchInputError

__all__ = ["ImpactSpec", "PAPER_PRACTICE", "IMPACT_MODELS", "nominal_cv"]

#: The impact models an ImpactSpec can name.
IMPACT_MODELS = ("paper", "momentum", "fixed", "least-loss")
_ON = ("arch", "nominal")
#: Old spellings still accepted by :meth:`ImpactSpec.parse` (scripts of archrock 0.1.0).
_ALIASES = {"nominal-paper": ("paper", "nominal")}


@dataclass(frozen=True)
class ImpactSpec:
    """Which impact law to use (module docstring).  Frozen; ``to_dict``/``from_dict`` round trip."""

    model: str = "paper"
    cv: float | None = None
    literal: bool = False
    on: str = "arch"

    def __post_init__(self):
        if self.model not in IMPACT_MODELS:
            raise ArchInputError(f"impact model: {self.model!r}; allowed {', '.join(IMPACT_MODELS)}")
        if self.on not in _ON:
            raise ArchInputError(f"impact on: {self.on!r}; allowed 'arch' or 'nominal'")
        if not isinstance(self.literal, bool):
            raise ArchInputError(f"literal: {self.literal!r}; allowed true or false")
        if self.model == "fixed":
            cv = self.cv
            if isinstance(cv, bool) or not isinstance(cv, (int, float)) or not (
                    math.isfinite(cv) and 0.0 < cv <= 1.0):
                raise ArchInputError(f"cv: {cv!r}; allowed 0 < cv <= 1")
            object.__setattr__(self, "cv", float(cv))
            object.__setattr__(self, "on", "arch")  # a given c_v is the same on every arch
        elif self.cv is not None:
            raise ArchInputError(f"cv: {self.cv!r}; only with the 'fixed' impact model "
                                 f"(got model {self.model!r})")
        if self.model == "least-loss" and self.on == "nominal":
            raise ArchInputError("impact on: 'nominal' gives every arch one c_v; the least-loss "
                                 "law chooses each arch's own post-impact mechanisms, allowed "
                                 "only on 'arch'")
        if self.literal and not (self.model == "fixed" or self.on == "nominal"):
            raise ArchInputError("literal: applies to a fixed c_v (model 'fixed', or a model "
                                 "evaluated on the nominal arch); not to a per-arch "
                                 f"{self.model!r} law")

    # ------------------------------------------------------------------ constructors
    @classmethod
    def fixed(cls, cv: float, literal: bool = False) -> "ImpactSpec":
        return cls("fixed", cv=cv, literal=literal)

    @classmethod
    def parse(cls, value=None, *, cv: float | None = None, literal: bool = False,
              default: "ImpactSpec | None" = None) -> "ImpactSpec":
        """An ImpactSpec from what users write: None (``default``, else :data:`PAPER_PRACTICE`),
        a model name (also 0.1.0's 'nominal-paper'), a number (a fixed c_v), a dict
        (:meth:`from_dict`) or an ImpactSpec.  ``cv``/``literal`` complete a name or None:
        ``parse(None, cv=0.8)`` and ``parse("fixed", cv=0.8)`` are the fixed law."""
        if isinstance(value, ImpactSpec):
            spec = value
        elif isinstance(value, dict):
            spec = cls.from_dict(value)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            if cv is not None:
                raise ArchInputError("cv: given twice (as the impact and as cv); give one")
            return cls("fixed", cv=float(value), literal=literal)
        elif value is None and cv is not None:
            return cls("fixed", cv=cv, literal=literal)
        elif value is None:
            spec = default if default is not None else PAPER_PRACTICE
        elif isinstance(value, str):
            model, on = _ALIASES.get(value, (value, "arch"))
            if model == "fixed":
                return cls("fixed", cv=cv, literal=literal)
            if cv is not None:
                raise ArchInputError(f"cv: {cv!r}; only with the 'fixed' impact model (got {value!r})")
            return cls(model, literal=literal, on=on)
        else:
            raise ArchInputError(f"impact: {value!r}; allowed a model name "
                                 f"({', '.join(IMPACT_MODELS)}), a c_v number or an ImpactSpec")
        if cv is not None or literal:
            if cv is not None:
                raise ArchInputError("cv: give it in the impact specification, not beside it")
            spec = cls(spec.model, spec.cv, True, spec.on)
        return spec

    # ------------------------------------------------------------------ use
    def resolved(self, nominal=None) -> "ImpactSpec":
        """The spec to apply to each arch: with ``on='nominal'`` and a nominal arch given, the
        fixed c_v of this model on that arch (:func:`nominal_cv`); otherwise itself."""
        if self.on != "nominal" or nominal is None:
            return self
        return ImpactSpec("fixed", cv=nominal_cv(nominal, self.model), literal=self.literal)

    def describe(self) -> str:
        """One line for reports."""
        if self.model == "fixed":
            return (f"fixed c_v = {self.cv:.4f}"
                    + (" on the rates (literal)" if self.literal else " (energy x c_v^2)"))
        where = "evaluated on the nominal arch, applied to every arch" if self.on == "nominal" \
            else "on each arch"
        return f"{self.model} model {where}" + (" (literal)" if self.literal else "")

    def to_dict(self) -> dict:
        return {"model": self.model, "cv": self.cv, "literal": self.literal, "on": self.on}

    @classmethod
    def from_dict(cls, data) -> "ImpactSpec":
        if not isinstance(data, dict):
            raise ArchInputError(f"impact: {data!r}; allowed an object with model, cv, literal, on")
        unknown = set(data) - {"model", "cv", "literal", "on"}
        if unknown:
            raise ArchInputError(f"impact: unknown field(s) {sorted(unknown)}; allowed model, cv, "
                                 f"literal, on")
        return cls(data.get("model", "paper"), data.get("cv"), data.get("literal", False),
                   data.get("on", "arch"))


#: The paper's practice and archrock's default: the paper model on the nominal arch.
PAPER_PRACTICE = ImpactSpec("paper", on="nominal")


def nominal_cv(nominal, model: str = "paper") -> float:
    """The c_v of ``model`` on the arch ``nominal`` (0.8754 for Oppenheim's arch with the paper
    model): the rate ratio on a symmetric arch; for an asymmetric one the c_v with the same mean
    kinetic-energy loss as its two directions (``ImpactLaw.equivalent_cv``).  Raises
    EnergyGainError where the paper model creates energy on it."""
    if model not in ("paper", "momentum"):
        raise ArchInputError(f"impact model: {model!r} on the nominal arch; allowed 'paper' or "
                             f"'momentum' (a model that gives one c_v)")
    key = (json.dumps(nominal.to_dict(), sort_keys=True), model)
    if key not in _NOMINAL_CV:
        _NOMINAL_CV[key] = _evaluate_cv(nominal, model)
    return _NOMINAL_CV[key]


_NOMINAL_CV: dict = {}  # (nominal geometry JSON, model) -> c_v: studies ask for it per arch


def _evaluate_cv(arch, model: str) -> float:
    from ..limit import limit_analysis
    from ..mechanism import four_link
    from .laws import impact_law

    lim = limit_analysis(arch, verify=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        law = impact_law(four_link(arch, lim.mechanism_l), four_link(arch, lim.mechanism_r), model)
    return float(law.equivalent_cv)
