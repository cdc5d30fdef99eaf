"""The arches of a study, prepared for dynamics: "prepare many", with those left out and why.

A study over random arches (collapse curves, fragility) draws its arches with one
:class:`~archrock.geometry.sampling.ArchSampler` and prepares each with :func:`archrock.dynamics.response.prepare`
under one :class:`~archrock.dynamics.impact.ImpactSpec`, evaluated on the sampler's nominal arch where the
spec says so.  An arch is left out only when it has no answer under the chosen model
(:data:`archrock.errors.UNUSABLE_ARCH`: it cannot stand, no mechanism opens, the draw is not a
valid arch, the impact model cannot be applied to it); the study lists it with the reason.  Any
other error is a real error and stops the study.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import UNUSABLE_ARCH, ArchInputError
from ..geometry import Arch
from ..leftout import REASONS, LeftOut, count_reasons
from .impact import ImpactSpec
from .response import DynamicModel, prepare
from ..geometry.sampling import ArchSampler

__all__ = ["PreparedArches", "prepare_many", "prepare_sample", "LEFT_OUT", "left_out_outcome",
           "count_left_out", "left_out_summary", "LeftOut"]

#: Why an arch of a study has no response, in report order (keys of every summary's counts):
#: :data:`archrock.leftout.REASONS`.
LEFT_OUT = REASONS


def left_out_outcome(reason) -> str:
    """The key of :data:`LEFT_OUT` of a reason: a :class:`~archrock.leftout.LeftOut`'s own, or
    that of a message (:meth:`LeftOut.read`)."""
    return LeftOut.read(reason).reason


def count_left_out(reasons) -> dict:
    """{key of :data:`LEFT_OUT`: count} over reasons (LeftOut or messages) or (index, reason)
    pairs."""
    return count_reasons(r if isinstance(r, str) else r[1] for r in reasons)


def left_out_summary(failed, usable: int, what: str) -> dict:
    """JSON statement of the arches a study left out: count, counts by reason, and the rule
    that ``what`` (e.g. "quantiles") is over the ``usable`` arches only."""
    return {"count": len(failed), "by_reason": count_left_out(failed), "usable": int(usable),
            "rule": f"{what} over the {usable} usable arch{'es' if usable != 1 else ''} only; the "
                    f"{len(failed)} left out are "
                    f"not counted (an arch that cannot stand under its own weight is not counted "
                    f"as a collapse)"}


@dataclass(frozen=True, eq=False)
class PreparedArches:
    """Prepared arches of a study: ``models[i]`` is sample ``indices[i]``; ``failed`` lists
    (sample index, :class:`~archrock.leftout.LeftOut`) of the arches left out; ``requested`` how many were asked for;
    ``impact`` the spec as given.  Iterates and indexes like the tuple of models."""

    models: tuple
    indices: tuple
    failed: tuple
    requested: int
    impact: ImpactSpec

    def __len__(self) -> int:
        return len(self.models)

    def __iter__(self):
        return iter(self.models)

    def __getitem__(self, i):
        return self.models[i]


def prepare_sample(sampler: ArchSampler, index: int, impact: ImpactSpec):
    """(model, None) for sample ``index``, or (None, :class:`~archrock.leftout.LeftOut`) when it
    is unusable."""
    try:
        arch = sampler.arch(index)
        return prepare(arch, impact, nominal=sampler.nominal), None
    except UNUSABLE_ARCH as exc:
        return None, LeftOut.of(exc)


def prepare_many(source, samples: int | None = None, impact=None, *,
                 nominal: Arch | None = None) -> PreparedArches:
    """Prepare the arches of a study.

    source: an :class:`ArchSampler` (with ``samples``: arches 0 .. samples - 1) or a sequence of
    Arch / DynamicModel (used as they are; ``nominal`` is then the arch a spec with
    ``on='nominal'`` is evaluated on).  impact: an ImpactSpec or what ``ImpactSpec.parse`` reads
    (default: the paper's practice).  Raises the first reason when no arch is usable.
    """
    spec = ImpactSpec.parse(impact)
    models, kept, failed = [], [], []
    if isinstance(source, ArchSampler):
        if isinstance(samples, bool) or not isinstance(samples, int) or samples < 1:
            raise ArchInputError(f"samples: {samples!r}; allowed an integer >= 1")
        for i in range(samples):
            model, why = prepare_sample(source, i, spec)
            if model is None:
                failed.append((i, why))
            else:
                models.append(model)
                kept.append(i)
        requested = samples
    else:
        items = [source] if isinstance(source, (Arch, DynamicModel)) else list(source)
        if not items:
            raise ArchInputError("arches: empty; allowed at least one arch")
        for i, item in enumerate(items):
            if isinstance(item, DynamicModel):
                models.append(item)
                kept.append(i)
                continue
            if not isinstance(item, Arch):
                raise ArchInputError(f"arches[{i}]: {type(item).__name__}; allowed Arch or "
                                     f"DynamicModel objects")
            try:
                models.append(prepare(item, spec, nominal=nominal))
                kept.append(i)
            except UNUSABLE_ARCH as exc:
                failed.append((i, LeftOut.of(exc)))
        requested = len(items)
    if not models:
        i, why = failed[0]
        # none usable: a statement about the study's inputs (spreads, impact model), not one arch
        raise ArchInputError(
            f"samples: none of the {requested} {'random ' if isinstance(source, ArchSampler) else ''}"
            f"arches is usable (sample {i}: {why}); allowed "
            f"spreads that give arches able to stand")
    return PreparedArches(tuple(models), tuple(kept), tuple(failed), requested, spec)

