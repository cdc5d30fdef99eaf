"""The impact specification: which impact law a computation uses, as one serialisable object.

An :class:`ImpactSpec` says

* ``model``: ``"paper"`` (De Lorenzis et al. 2007, the paper's), ``"momentum"`` (energy-consistent
  projection), ``"fixed"`` (a given coefficient of restitution ``cv``) or ``"least-loss"``
  (momentum law, each impact opening the mechanism that keeps the most energy; Bisegna et al.
  2023);
* ``cv``: the coefficient of restitution of the fixed model, 0 <= cv <= 1;
* ``literal``: a fixed c_v multiplies the rates (the paper's wording) instead of the kinetic
  energy by cv^2 (energy-consistent, the default);
* ``on``: ``"arch"`` evaluates the model on every arch analysed; ``"nominal"`` evaluates it once
  on the study's nominal arch and applies the resulting c_v to every arch as a fixed coefficient
  (the paper's practice, section 5.1: "as a first approximation").  When one arch is analysed
  alone it is its own nominal arch, so ``"nominal"`` then means the model on that arch;
* ``fallback``: with the ``"paper"`` model only, ``"momentum"`` or None: on an arch where the
  paper's equations cannot be used (they would create energy, give a negative rate ratio or are
  singular) the momentum law is used for that arch instead of refusing it, and the law says so
  (``ImpactLaw.fallback``; a spec resolved on such a nominal arch carries it as ``note``);
* ``note``: why a resolved fixed c_v is what it is (set by :meth:`ImpactSpec.resolved` when the
  nominal arch fell back; None otherwise).

:data:`PAPER_PRACTICE` (the paper model on the nominal arch, falling back to the momentum law
where the paper model cannot be used on it) is the default of every command and study;
``prepare(arch)`` alone uses it on ``arch``, which is the same thing.  A spec written out
(``"paper"``, ``ImpactSpec("paper", on="nominal")``, ``--impact paper``) has no fallback: it
refuses such an arch with :class:`~archrock.errors.ImpactModelError`.  In a dict
(:meth:`ImpactSpec.to_dict`) ``fallback`` is written only where it differs from the implied
value (``"momentum"`` for the paper model on the nominal arch, the default's form; None
otherwise), so the dicts of 0.4's specs, and of manifests written by it, read as before.
"""

from __future__ import annotations

import dataclasses
import json
import math
import warnings
from dataclasses import dataclass

from ...errors import ArchInputError, ImpactModelError
from .laws import IMPACT_MODELS, impact_law

__all__ = ["ImpactSpec", "PAPER_PRACTICE", "IMPACT_MODELS", "FALLBACK_MODELS", "nominal_cv"]

_ON = ("arch", "nominal")
#: What the paper model may fall back to where it cannot be used (ImpactSpec.fallback).
FALLBACK_MODELS = ("momentum",)
_FIELDS = ("model", "cv", "literal", "on", "fallback", "note")
#: Old spellings still accepted by :meth:`ImpactSpec.parse` (scripts of archrock 0.1.0).
_ALIASES = {"nominal-paper": ("paper", "nominal")}


@dataclass(frozen=True)
class ImpactSpec:
    """Which impact law to use (module docstring).  Frozen; ``to_dict``/``from_dict`` round trip."""

    model: str = "paper"
    cv: float | None = None
    literal: bool = False
    on: str = "arch"
    fallback: str | None = None
    note: str | None = None

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
                    math.isfinite(cv) and 0.0 <= cv <= 1.0):
                raise ArchInputError(f"cv: {cv!r}; allowed 0 <= cv <= 1 (0: every impact stops the arch)")
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
        if self.fallback is not None and (self.model != "paper"
                                          or self.fallback not in FALLBACK_MODELS):
            raise ArchInputError(f"fallback: {self.fallback!r}; allowed None, or "
                                 f"{', '.join(map(repr, FALLBACK_MODELS))} with the 'paper' model "
                                 f"(got model {self.model!r})")
        if self.note is not None and not (isinstance(self.note, str) and self.model == "fixed"):
            raise ArchInputError(f"note: {self.note!r}; allowed None, or a text with the 'fixed' "
                                 f"model (why a resolved c_v is what it is)")

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
            spec = dataclasses.replace(spec, literal=True)
        return spec

    # ------------------------------------------------------------------ use
    def resolved(self, nominal=None) -> "ImpactSpec":
        """The spec to apply to each arch: with ``on='nominal'`` and a nominal arch given, the
        fixed c_v of this model on that arch (:func:`nominal_cv`); otherwise itself."""
        if self.on != "nominal" or nominal is None:
            return self
        cv, note = _nominal(nominal, self.model, self.fallback)
        if note is not None:
            note = f"on the nominal arch, {note} (c_v = {cv:.6g})"
        return ImpactSpec("fixed", cv=cv, literal=self.literal, note=note)

    def describe(self) -> str:
        """One line for reports."""
        if self.model == "fixed":
            return (f"fixed c_v = {self.cv:.4f}"
                    + (" on the rates (literal)" if self.literal else " (energy x c_v^2)")
                    + (f"; {self.note}" if self.note else ""))
        where = "evaluated on the nominal arch, applied to every arch" if self.on == "nominal" \
            else "on each arch"
        return (f"{self.model} model {where}" + (" (literal)" if self.literal else "")
                + (f" ({self.fallback} law where the paper model cannot be used)"
                   if self.fallback else ""))

    def to_dict(self) -> dict:
        """JSON-ready dict; ``fallback`` only where it differs from the implied value, ``note``
        only when set (module docstring), so the dicts of 0.4's specs are unchanged."""
        d = {"model": self.model, "cv": self.cv, "literal": self.literal, "on": self.on}
        if self.fallback != _implied_fallback(self.model, self.on):
            d["fallback"] = self.fallback
        if self.note is not None:
            d["note"] = self.note
        return d

    @classmethod
    def from_dict(cls, data) -> "ImpactSpec":
        if not isinstance(data, dict):
            raise ArchInputError(f"impact: {data!r}; allowed an object with model, cv, literal, on")
        unknown = set(data) - set(_FIELDS)
        if unknown:
            raise ArchInputError(f"impact: unknown field(s) {sorted(unknown)}; allowed "
                                 f"{', '.join(_FIELDS)}")
        model, on = data.get("model", "paper"), data.get("on", "arch")
        return cls(model, data.get("cv"), data.get("literal", False), on,
                   data.get("fallback", _implied_fallback(model, on)), data.get("note"))


def _implied_fallback(model, on) -> str | None:
    """The fallback a dict without one means: the default's (the paper model on the nominal
    arch falls back to momentum), None for every other spec."""
    return "momentum" if (model, on) == ("paper", "nominal") else None


#: The paper's practice and archrock's default: the paper model on the nominal arch, the
#: momentum law where the paper model cannot be used on it (it would create energy).
PAPER_PRACTICE = ImpactSpec("paper", on="nominal", fallback="momentum")


def nominal_cv(nominal, model: str = "paper", fallback: str | None = None) -> float:
    """The c_v of ``model`` on the arch ``nominal`` (0.8754 for Oppenheim's arch with the paper
    model): the rate ratio on a symmetric arch; for an asymmetric one the c_v with the same mean
    kinetic-energy loss as its two directions (``ImpactLaw.equivalent_cv``).  Raises
    EnergyGainError where the paper model creates energy on it, unless ``fallback`` names the
    model to use there instead (``ImpactSpec.resolved`` says when it was used)."""
    return _nominal(nominal, model, fallback)[0]


def _nominal(nominal, model: str, fallback: str | None) -> tuple[float, str | None]:
    """(c_v, fallback note or None) of ``model`` on ``nominal`` (:func:`nominal_cv`)."""
    if model not in ("paper", "momentum"):
        raise ArchInputError(f"impact model: {model!r} on the nominal arch; allowed 'paper' or "
                             f"'momentum' (a model that gives one c_v)")
    key = (json.dumps(nominal.to_dict(), sort_keys=True), model, fallback)
    if key not in _NOMINAL_CV:
        _NOMINAL_CV[key] = _evaluate_cv(nominal, model, fallback)
    return _NOMINAL_CV[key]


# (nominal geometry JSON, model, fallback) -> (c_v, note): studies ask for it per arch
_NOMINAL_CV: dict = {}


def _evaluate_cv(arch, model: str, fallback: str | None) -> tuple[float, str | None]:
    from ...statics.limit import limit_analysis
    from ..fourlink import four_link

    lim = limit_analysis(arch, verify=False)
    # Where a joint of the nominal arch lifts off, its own mechanism has no four-link model; the
    # c_v given to the random arches (those that do rock as four-hinge chains) is that of the
    # nominal arch's best four-hinge mechanisms, and the note says so.
    mechs, lifted = [], []
    for d in ("l", "r"):
        m = lim.mechanism(d)
        if not m.is_four_hinge:
            lifted.append(lim.not_four_hinge(d))
            m = lim.four_hinge_l if d == "l" else lim.four_hinge_r
        if m is None:
            raise ImpactModelError(
                f"impact: the {model} model's c_v is evaluated on the nominal arch, where no "
                f"four-hinge mechanism loads direction {d!r} ({lim.not_four_hinge(d)}); give a "
                f"fixed c_v (ImpactSpec cv; --cv), or the momentum law (ImpactSpec model "
                f"'momentum'; --impact momentum), evaluated on each arch")
        mechs.append(m)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        law = impact_law(four_link(arch, mechs[0]), four_link(arch, mechs[1]), model,
                         fallback=fallback)
    notes = [f"{'; '.join(lifted)}: c_v of its best four-hinge mechanisms"] if lifted else []
    notes += [law.fallback] if law.fallback else []
    return float(law.equivalent_cv), "; ".join(notes) or None
