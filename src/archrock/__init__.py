"""archrock: seismic rocking assessment of masonry arches.

The Python API in one namespace, in the order data flows (docs/architecture.md):

* geometry: :class:`VoussoirArch` (every arch), :class:`Arch` (circular), :class:`PolygonArch`
  (any shape), :func:`family_arch` (pointed, elliptical, ...), :class:`Load`,
  :func:`nominal_arch`, :func:`oppenheim_arch`, :func:`random_arch`;
  irregular arches of a study: :class:`ArchSampler`, :class:`Spreads`;
* limit analysis: :func:`limit_analysis` (the Heyman optimum and its mechanism),
  :func:`general_mechanisms`, :func:`minimum_thickness`, :func:`thrust_range` (least and
  greatest thrust under self-weight); with Coulomb friction at
  the joints: :func:`friction_analysis`, :func:`friction_needed`,
  :func:`friction_minimum_thickness`;
* ground motion: :class:`GroundMotion`, :func:`pulse`, :func:`oppenheim_pulse`,
  :func:`load_record`, :class:`PulseSpec`, :class:`RecordSpec`;
* impacts: :class:`ImpactSpec`, :data:`PAPER_PRACTICE`;
* dynamics: :func:`prepare`, :func:`respond`, :func:`prepare_many`;
* studies: :func:`collapse_curve`, :func:`ensemble_curve`, :class:`EnsembleConfig`,
  :func:`run_ensemble` (incremental dynamic analysis: :mod:`archrock.studies.ida`, whose function
  ``ida`` shares the module's name and so is not lifted here);
* errors: :class:`ArchrockError` and its subclasses.

Names are imported on first use, so ``import archrock`` stays cheap and the optional extras
(pandas, matplotlib, ...) are only needed by what uses them.
"""

from importlib import import_module

_EXPORTS = {
    "errors": ("ArchrockError", "ArchInputError", "GeometryOutcome", "CannotStandError",
               "NoMechanismError", "NotFourHingeError", "InvalidSampleError", "ImpactModelError",
               "EnergyGainError", "FitError", "LimitExceededError"),
    "geometry": ("Arch", "PolygonArch", "VoussoirArch", "Load", "family_arch", "nominal_arch",
                 "oppenheim_arch", "random_arch", "as_polygon", "arch_from_dict", "Defect",
                 "apply_defect"),
    "geometry.sampling": ("ArchSampler", "Spreads"),
    "statics.limit": ("limit_analysis", "minimum_thickness", "general_mechanisms"),
    "statics.thrust": ("thrust_range",),
    "statics.friction": ("friction_analysis", "friction_needed", "friction_minimum_thickness"),
    "groundmotion": ("GroundMotion", "pulse", "oppenheim_pulse", "load_record", "PulseSpec",
                     "RecordSpec"),
    "dynamics.impact": ("ImpactSpec", "PAPER_PRACTICE"),
    "dynamics.response": ("prepare", "respond"),
    "dynamics.population": ("prepare_many",),
    "studies.curves": ("collapse_curve", "ensemble_curve"),
    "studies.ensemble": ("EnsembleConfig", "run_ensemble"),
    "studies.defectmap": ("defect_map",),
    "studies.sensitivity": ("sobol_indices",),
}
_OWNER = {name: module for module, names in _EXPORTS.items() for name in names}

__all__ = sorted(_OWNER)


def __getattr__(name):
    module = _OWNER.get(name)
    if module is None:
        raise AttributeError(f"module 'archrock' has no attribute {name!r}")
    value = getattr(import_module(f".{module}", __name__), name)
    globals()[name] = value  # later lookups skip this function
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
