"""Arch options -> an arch: the nominal geometry (circular, a family's, or a geometry file),
its defects, its piers and a support movement.  ``args`` is anything with the options as
attributes (argparse's Namespace of the command line, or the one the app builds from a request's
fields); an option absent or None is not given."""

from __future__ import annotations

from .errors import OptionError
from .fields import FLAGS, flag_message, values

#: Defaults of the nominal-geometry flags: Oppenheim's arch (R [m], embrace [deg], t [m], n, kg/m^3).
#: Spelled out rather than taken from archrock.geometry so that --help needs no numpy.
GEOMETRY_DEFAULTS = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7,
                     "density": 2000.0}
#: The arch families and joint kinds (archrock.geometry.SHAPES / JOINTS, spelled out for --help
#: without numpy; tests/test_cli.py checks they agree).
SHAPES = ("circular", "pointed", "elliptical", "three-centred", "parabolic", "catenary")
JOINTS = ("normal", "vertical")


def arch_from_args(args):
    """The arch described by the options of :func:`add_geometry_options`: a circular
    :class:`~archrock.geometry.Arch`, or a family's (the exact Arch for a circular one with
    normal joints and constant thickness, else a FamilyArch), with the --defect defects applied
    (archrock.geometry.apply_defect), on the piers of --pier-height/--pier-width (an
    ArchOnPiers, archrock.geometry.with_piers), with the compressive strength of --fc (applied
    last, on whatever the other options built; None keeps the arch's own, a file's "fc");
    raises ArchInputError / OptionError on bad input."""
    arch = undamaged_arch_from_args(args)
    specs = list(getattr(args, "defect", None) or ())
    # a pier tilt turns a pier: applied once the arch stands on its piers; the others number
    # the arch's own voussoirs and joints, so they come first
    tilts = [d for d in specs if isinstance(d, str) and "pier-tilt" in d]
    from ..geometry import apply_defects

    if len(tilts) < len(specs):
        arch = apply_defects(arch, [d for d in specs if d not in tilts])
    arch = piers_from_args(args, arch)
    if tilts:
        arch = apply_defects(arch, tilts)
    return fc_from_args(args, supports_from_args(args, arch))


def fc_from_args(args, arch):
    """``arch`` with the compressive strength of --fc [MPa] (``args.fc``), or ``arch`` itself
    when it is not given; a value out of range is refused naming --fc."""
    fc = getattr(args, "fc", None)
    if fc is None:
        return arch
    from ..errors import ArchInputError

    try:
        return arch.with_fc(fc)
    except ArchInputError as exc:
        msg = str(exc)
        raise ArchInputError("--fc" + msg[2:] if msg.startswith("fc:") else msg) from None


def piers_from_args(args, arch):
    """``arch`` on the piers of --pier-height/--pier-width/--pier-courses (the defects, which
    number the arch's own voussoirs and joints, are applied first), or ``arch`` without them.
    The flags are read through the one table of :mod:`archrock.options.fields`."""
    given = values(args, "with_piers")  # {field: value} of the flags given, in the table's order
    flag = FLAGS["with_piers"]
    if "steps" in given or "steps_right" in given:
        return _stepped_from_args(arch, given)
    if not given:
        return arch
    if "height" not in given or "width" not in given:
        missing = " and ".join(flag[f] for f in ("height", "width") if f not in given)
        raise OptionError(f"{missing}: needed with {flag[next(iter(given))]} (the piers' height "
                          f"and width, in metres)")
    from ..errors import ArchInputError
    from ..geometry import with_piers

    try:
        return with_piers(arch, given.pop("height"), given.pop("width"), **given)
    except ArchInputError as exc:
        worded = flag_message(str(exc), "with_piers")
        if worded is not None:
            raise ArchInputError(worded) from None
        raise


def _stepped_from_args(arch, given):
    """``arch`` on the stepped buttresses of --pier-steps/--right-pier-steps (docs/piers.md)."""
    from ..errors import ArchInputError
    from ..geometry import with_piers
    from ..geometry.piers import parse_steps

    flag = FLAGS["with_piers"]
    why = "(stepped piers take their heights and widths from the steps)"
    if "steps" not in given:
        raise OptionError(f"--pier-steps: needed with --right-pier-steps {why}")
    others = [f for f in given if f not in ("steps", "steps_right")]
    if others:
        raise OptionError(f"{flag[others[0]]}: given with --pier-steps {why}")
    sl = parse_steps(given["steps"], "--pier-steps")
    sr = None if "steps_right" not in given else parse_steps(given["steps_right"],
                                                             "--right-pier-steps")
    try:
        return with_piers(arch, None, None, steps=sl, steps_right=sr)
    except ArchInputError as exc:
        msg = str(exc)
        for field, fl in (("steps_right", "--right-pier-steps"), ("steps", "--pier-steps"),
                          ("width_right:", "--right-pier-steps: top step"),
                          ("width:", "--pier-steps: top step")):
            if msg.startswith(field):
                raise ArchInputError(fl + msg[len(field):]) from None
        raise


def undamaged_arch_from_args(args):
    from ..geometry import nominal_arch

    circ = ("radius", "embrace")
    fam = ("shape", "span", "rise", "thickness_crown", "joints")
    common = ("thickness", "voussoirs", "density")
    flags = circ + fam + common
    given = [f for f in flags if getattr(args, f, None) is not None]
    flag = {f: "--" + f.replace("_", "-") for f in flags}
    if getattr(args, "geometry", None):
        if given:
            raise OptionError(f"--geometry: cannot be combined with "
                              f"{', '.join(flag[f] for f in given)}; the file holds the whole geometry")
        from ..geometry.files import read_arch

        return read_arch(args.geometry)
    family = [f for f in fam if f in given]
    if family:
        both = [f for f in circ if f in given]
        if both:
            raise OptionError(f"{flag[both[0]]}: cannot be combined with {flag[family[0]]}; give "
                              f"--radius/--embrace (circular) or --shape/--span/--rise")
        shape = getattr(args, "shape", None) or "circular"
        missing = [flag[f] for f in ("span", "rise") if getattr(args, f, None) is None]
        if missing:
            raise OptionError(f"{' and '.join(missing)}: needed with {flag[family[0]]} (the span "
                              f"and rise of the {shape} arch's centreline, in metres)")
        from ..geometry import family_arch

        val = {f: getattr(args, f) if getattr(args, f, None) is not None else GEOMETRY_DEFAULTS[f]
               for f in common}
        return family_arch(shape, args.span, args.rise, val["thickness"], val["voussoirs"],
                           thickness_crown=args.thickness_crown, joints=args.joints or "normal",
                           density=val["density"], name=shape)
    vals = {f: (getattr(args, f, None) if getattr(args, f, None) is not None else GEOMETRY_DEFAULTS[f])
            for f in circ + common}
    is_oppenheim = not given or all(vals[f] == GEOMETRY_DEFAULTS[f] for f in circ + common)
    return nominal_arch(radius=vals["radius"], embrace_deg=vals["embrace"], thickness=vals["thickness"],
                        voussoirs=vals["voussoirs"], density=vals["density"],
                        name="Oppenheim" if is_oppenheim else "nominal")


def supports_from_args(args, arch):
    """``arch`` after the movement of --spread/--settlement/--support-side (the displaced arch
    of archrock.statics.supports.displace, re-closed; the arch itself at zero movement)."""
    given = values(args, "SupportMovement")
    if not {"spread", "settlement", "rotation"} & set(given):
        capacity = getattr(args, "capacity", None)
        if "side" in given and capacity is None:
            raise OptionError("--support-side: needs --spread, --settlement or --rotation (the "
                              "movement)")
        if "pivot_depth" in given and capacity != "rotation":
            raise OptionError("--pivot-depth: needs --rotation or --capacity rotation")
        return arch
    from ..errors import ArchInputError
    from ..geometry.displaced import SupportMovement
    from ..statics.supports import on_moved_supports

    try:
        mv = SupportMovement(**{"spread": 0.0, "settlement": 0.0, "side": "right", **given})
        # the analyses take the displaced geometry with its open joints bearing on whole faces:
        # a mechanism that turns an open joint back only closes its gap (docs/supports.md, "One
        # answer: the re-closed arch"); limit reports that bounded motion beside it.  A
        # movement the arch cannot follow is refused here too, by its flag.
        return on_moved_supports(arch, mv)  # the arch itself at zero movement
    except ArchInputError as exc:
        worded = flag_message(str(exc), "SupportMovement")
        if worded is not None:
            raise ArchInputError(worded) from None
        raise
