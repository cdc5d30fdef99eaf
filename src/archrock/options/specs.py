"""Option values -> the specs of the other choices: the spreads of random arches, the ground
motion (PulseSpec / RecordSpec) and the impact law (ImpactSpec).  ``args`` as in
:mod:`archrock.options.arch`."""

from __future__ import annotations

from .arch import arch_from_args
from .errors import OptionError
from .fields import flag_message, values


def spreads(args):
    """The :class:`~archrock.geometry.sampling.Spreads` of :func:`add_spread_options`."""
    from ..errors import ArchInputError
    from ..geometry.sampling import Spreads

    try:  # a command without --spread-tilt (or the pier spreads): none of it
        return Spreads(**values(args, "Spreads"))
    except ArchInputError as exc:  # the flag's name, not the field's
        worded = flag_message(str(exc), "Spreads")
        if worded is not None:
            raise ArchInputError(worded) from None
        raise


def motion_spec_from_args(args):
    """The PulseSpec / RecordSpec described by :func:`add_motion_options`, or None if none was
    given (a record's file is read and checksummed)."""
    from ..groundmotion import PulseSpec, RecordSpec

    has_pulse = any(getattr(args, f, None) is not None for f in ("pulse", "amplitude", "pulse_duration"))
    if getattr(args, "record", None):
        if has_pulse:
            raise OptionError("--record: cannot be combined with --pulse/--amplitude/--pulse-duration")
        return RecordSpec.from_file(**values(args, "RecordSpec"))
    for flag, given in (("--units", args.units is not None), ("--scale", args.scale != 1.0)):
        if given and has_pulse:
            raise OptionError(f"{flag}: applies to --record only; a pulse's amplitude is in g")
    if not has_pulse:
        if getattr(args, "_motion_required", False):
            raise OptionError("ground motion: give --pulse KIND --amplitude A_G --pulse-duration S "
                              "or --record FILE")
        return None
    if args.amplitude is None or args.pulse_duration is None:
        raise OptionError("--amplitude and --pulse-duration: both are needed with a pulse "
                          "(e.g. --pulse oppenheim --amplitude -1 --pulse-duration 0.2)")
    kw = values(args, "PulseSpec")
    return PulseSpec(**{**kw, "kind": kw.get("kind") or "oppenheim"})


def motion_from_args(args):
    """The GroundMotion described by :func:`add_motion_options`, or None if none was given."""
    spec = motion_spec_from_args(args)
    return None if spec is None else spec.build()


def impact_spec_from_args(args):
    """The :class:`~archrock.dynamics.impact.ImpactSpec` of the impact options (the same in every
    command)."""
    from ..dynamics.impact import PAPER_PRACTICE, ImpactSpec

    if args.cv is not None and args.impact is not None:
        raise OptionError("--cv: cannot be combined with --impact; choose one")
    on = getattr(args, "impact_on", None)
    if args.cv is not None:
        if on is not None:
            raise OptionError("--impact-on: applies to --impact MODEL; a given --cv is the same on "
                              "every arch")
        return ImpactSpec.fixed(args.cv, literal=args.literal_cv)
    if args.impact is None:
        if on is not None:
            raise OptionError("--impact-on: needs --impact MODEL")
        return ImpactSpec.parse(PAPER_PRACTICE, literal=args.literal_cv)
    spec = ImpactSpec.parse(args.impact)
    if on is not None:
        if args.impact == "nominal-paper" and on != "nominal":
            raise OptionError("--impact-on: nominal-paper is evaluated on the nominal arch")
        spec = ImpactSpec(spec.model, on=on)
    if args.literal_cv:
        if spec.on != "nominal":
            raise OptionError("--literal-cv: applies to a fixed c_v (--cv, or a model evaluated on "
                              "the nominal arch); cannot be combined with --impact on each arch")
        spec = ImpactSpec(spec.model, literal=True, on="nominal")
    return spec


def model_from_args(args, arch=None):
    """The prepared DynamicModel (limit analysis, mechanisms, impact law) of one arch."""
    from ..dynamics.response import prepare

    arch = arch_from_args(args) if arch is None else arch
    return prepare(arch, impact_spec_from_args(args))
