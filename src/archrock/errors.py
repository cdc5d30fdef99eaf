"""The errors archrock raises, one class per kind of problem.

* :class:`ArchInputError` -- the input is wrong (a field out of range, a malformed file): the
  message names the field and the allowed range.  Fix the input.
* :class:`GeometryOutcome` -- the input is valid but the arch has no answer of the kind asked:
  it cannot stand under its own weight (:class:`CannotStandError`), no four-hinge mechanism can
  open (:class:`NoMechanismError`: sliding or crushing governs), a joint lifts off before any
  four-hinge mechanism opens (:class:`NotFourHingeError`: the four-link model does not hold), or
  a drawn random arch is not a
  valid arch (:class:`InvalidSampleError`).  A physical outcome, reported as such.
* :class:`ImpactModelError` -- an impact model cannot be used on this geometry (it would create
  energy: :class:`EnergyGainError`; its equations are singular).
* :class:`FitError` -- a fragility curve cannot be identified from the data.
* :class:`LimitExceededError` -- a computation would exceed a limit (events, samples, memory).
* :class:`NoSelectionError` -- valid records and a valid target spectrum of which no set meets
  the codes' rules for time-history analysis within the scale bounds (an outcome, like a
  :class:`GeometryOutcome`, but not the arch's: a study does not leave an arch out on it).

Studies over random arches leave out an arch only on a :class:`GeometryOutcome` or an
:class:`ImpactModelError` (both depend on the drawn geometry) and report it; any other error stops
the study.  Every class derives from :class:`ArchrockError`.
"""

__all__ = ["ArchrockError", "ArchInputError", "GeometryOutcome", "CannotStandError",
           "NoMechanismError", "NotFourHingeError", "InvalidSampleError", "ImpactModelError", "EnergyGainError",
           "FitError", "LimitExceededError", "NoSelectionError", "OUTCOMES", "UNUSABLE_ARCH"]


class ArchrockError(Exception):
    """Base class of every error archrock raises on purpose."""


class ArchInputError(ArchrockError, ValueError):
    """Invalid user input (geometry, ground motion, options). The message names the field."""


class GeometryOutcome(ArchrockError):
    """A valid input whose arch has no answer of the kind asked (a physical outcome)."""


class CannotStandError(GeometryOutcome):
    """The arch cannot stand under its own weight (no thrust line inside the arch)."""


class NoMechanismError(GeometryOutcome):
    """No admissible four-hinge mechanism opens under horizontal forces: the arch fails by
    sliding or crushing, which Heyman's hypotheses exclude."""


class NotFourHingeError(GeometryOutcome):
    """The arch's governing (Heyman) mechanism is not a four-hinge chain: a joint lifts off
    (opens at both ends) at a lower multiplier than any four-hinge mechanism.  Oppenheim's
    four-link model does not describe it; the contact engine (``archrock dem``) does."""


class InvalidSampleError(GeometryOutcome):
    """A random arch drawn around a nominal one is not a valid arch (e.g. neighbouring voussoirs
    do not overlap): the spreads are too wide for this sample."""


class ImpactModelError(ArchrockError):
    """An impact model cannot be applied to this geometry."""


class EnergyGainError(ImpactModelError):
    """An impact model would create kinetic energy on this geometry."""


class FitError(ArchrockError):
    """A fragility fit cannot be identified from the data."""


class LimitExceededError(ArchrockError):
    """A computation would exceed a limit (events, samples, memory); the message gives it."""


class NoSelectionError(ArchrockError):
    """No set of the records given meets the codes' rules for a target spectrum within the
    scale bounds; the message says by how much the best set fails."""


#: Valid inputs with no answer of the kind asked: the command line says "outcome" (exit 3).
OUTCOMES = (GeometryOutcome, NoSelectionError)

#: What a study over random arches catches to leave one arch out (and report why).
UNUSABLE_ARCH = (GeometryOutcome, ImpactModelError)
