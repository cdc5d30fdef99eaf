"""Option groups shared by several subcommands, and their conversion to library objects."""

from __future__ import annotations

import argparse

from ._parser import CLIError, _int, finite_float, non_negative_int

#: Defaults of the nominal-geometry flags: Oppenheim's arch (R [m], embrace [deg], t [m], n, kg/m^3).
#: Spelled out rather than taken from archrock.geometry so that --help needs no numpy.
GEOMETRY_DEFAULTS = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7,
                     "density": 2000.0}
#: The arch families and joint kinds (archrock.geometry.SHAPES / JOINTS, spelled out for --help
#: without numpy; tests/test_cli.py checks they agree).
SHAPES = ("circular", "pointed", "elliptical", "three-centred", "parabolic", "catenary")
JOINTS = ("normal", "vertical")


# ---------------------------------------------------------------------------- output files
def figure_arg(path):
    """The file a --plot/--out figure option will write (None if not given), checked before
    any work: a format matplotlib writes, not a folder ('.png' added without an extension)."""
    if path is None:
        return None
    from ..reports.plots import figure_path

    return figure_path(path)


def animation_arg(path):
    """The file of --animate (None if not given), checked before any work (.gif or .mp4)."""
    if path is None:
        return None
    from ..reports.animate import animation_path

    return animation_path(path)


def folder_arg(path, flag: str = "--out", what: str = "a folder name"):
    """An output folder (or file) option: None if not given; an empty name is refused (it
    would silently mean the current folder, or nothing, depending on the command)."""
    if path is None:
        return None
    if not path.strip():
        raise CLIError(f"{flag}: {path!r}; allowed {what}")
    return path


# ---------------------------------------------------------------------------- arch
def add_geometry_options(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Add the arch options: a circular arch (--radius --embrace), an arch of a family
    (--shape --span --rise, --thickness-crown, --joints), both with --thickness --voussoirs
    --density (defaults: Oppenheim's arch), or --geometry FILE (a JSON geometry file)."""
    d = GEOMETRY_DEFAULTS
    g = parser.add_argument_group(
        "arch geometry", "a circular arch (defaults: Oppenheim's arch), an arch of a family "
                         "(--shape, --span, --rise of the centreline) or --geometry FILE")
    # Defaults are None so that arch_from_args can tell given flags from defaults.
    g.add_argument("--radius", type=finite_float, metavar="R",
                   help=f"mean radius [m], 1e-8 to 1e8 (default {d['radius']:g})")
    g.add_argument("--embrace", type=finite_float, metavar="DEG",
                   help=f"angle of embrace [deg], 0 < embrace < 360 (default {d['embrace']:g})")
    g.add_argument("--shape", choices=SHAPES, metavar="SHAPE",
                   help=f"arch family: {', '.join(SHAPES)} (with --span and --rise; "
                        f"docs/geometry.md)")
    g.add_argument("--span", type=finite_float, metavar="S",
                   help="span of the centreline between its springings [m], 1e-8 to 1e8")
    g.add_argument("--rise", type=finite_float, metavar="F",
                   help="rise of the centreline's crown above its springings [m] (circular: "
                        "0 < F <= S; pointed: F > S/2; three-centred: F <= S/2)")
    g.add_argument("--thickness", type=finite_float, metavar="T",
                   help=f"thickness [m], 0 < t < 2 R (default {d['thickness']:g}); "
                        f"with --shape: normal to the centreline, at the springings")
    g.add_argument("--thickness-crown", type=finite_float, metavar="T_C",
                   help="with --shape: thickness at the crown [m] (linear from --thickness at "
                        "the springings; default: constant)")
    g.add_argument("--joints", choices=JOINTS,
                   help="with --shape: joints normal to the centreline (default) or vertical")
    g.add_argument("--voussoirs", type=_int, metavar="N",
                   help=f"number of voussoirs, 3 to 2000 (default {d['voussoirs']})")
    g.add_argument("--density", type=finite_float, metavar="RHO",
                   help=f"density [kg/m^3], > 0 (default {d['density']:g}; cancels from k)")
    g.add_argument("--geometry", metavar="FILE",
                   help="JSON geometry file, circular or polygon voussoirs (from the left "
                        "springing); excludes the flags above")
    g.add_argument("--defect", action="append", metavar="SPEC",
                   help="a defect applied to the arch, repeatable: VOUSSOIR:thickness=F"
                        "[,side=intrados|extrados] (keeps F of its thickness, 0 < F < 1), "
                        "JOINT:tilt=DEG (-45 < DEG < 45) or JOINT:mortar=F[,side=extrados] "
                        "(no mortar over F of the contact); on piers pier-tilt=DEG"
                        "[,side=left|right] (out of plumb, outward positive, |DEG| <= 15; "
                        "docs/piers.md); docs/defects.md")
    g.add_argument("--pier-height", type=finite_float, metavar="H",
                   help="the arch on two piers: height [m] of each pier from its foundation to "
                        "the springing, > 0 (with --pier-width; docs/piers.md)")
    g.add_argument("--pier-width", type=finite_float, metavar="W",
                   help="width [m] of each pier, outward of the intrados springing, > 0 and at "
                        "least the springing joint's width (with --pier-height)")
    g.add_argument("--pier-courses", type=_int, metavar="N",
                   help="courses (blocks between horizontal bed joints) of each pier, 1 to 200 "
                        "(default 1: monolithic; with --pier-height)")
    g.add_argument("--pier-batter", type=finite_float, metavar="B",
                   help="batter of each pier's outer face: horizontal run per unit of height, "
                        "0 to 10 (default 0: rectangular; > 0: a buttress W + B H wide at its "
                        "foundation; with --pier-height)")
    for what, flag in (("height", "H"), ("width", "W"), ("courses", "N"), ("batter", "B")):
        g.add_argument(f"--right-pier-{what}", type=_int if what == "courses" else finite_float,
                       metavar=flag, help=f"the right pier's {what} where it differs from the "
                                          f"left one's (default: --pier-{what})")
    g.add_argument("--pier-steps", metavar="H:W,...",
                   help="both piers as stepped buttresses: HEIGHT:WIDTH [m] per step from the "
                        "foot up, widths not growing upward (instead of --pier-height and "
                        "--pier-width; docs/piers.md)")
    g.add_argument("--right-pier-steps", metavar="H:W,...",
                   help="the right pier's steps where they differ (with --pier-steps)")
    add_support_options(parser)
    return parser


def arch_from_args(args: argparse.Namespace):
    """The arch described by the options of :func:`add_geometry_options`: a circular
    :class:`~archrock.geometry.Arch`, or a family's (the exact Arch for a circular one with
    normal joints and constant thickness, else a FamilyArch), with the --defect defects applied
    (archrock.geometry.apply_defect), on the piers of --pier-height/--pier-width (an
    ArchOnPiers, archrock.geometry.with_piers); raises ArchInputError / CLIError on bad input."""
    arch = _undamaged_arch_from_args(args)
    specs = list(getattr(args, "defect", None) or ())
    # a pier tilt turns a pier: applied once the arch stands on its piers
    tilts = [d for d in specs if isinstance(d, str) and "pier-tilt" in d]
    if len(tilts) < len(specs):
        from ..geometry import apply_defects

        arch = apply_defects(arch, [d for d in specs if d not in tilts])
    arch = _piers_from_args(args, arch)
    if tilts:
        from ..geometry import apply_defects

        arch = apply_defects(arch, tilts)
    return _supports_from_args(args, arch)


def _piers_from_args(args: argparse.Namespace, arch):
    """``arch`` on the piers of --pier-height/--pier-width/--pier-courses (the defects, which
    number the arch's own voussoirs and joints, are applied first), or ``arch`` without them."""
    h = getattr(args, "pier_height", None)
    w = getattr(args, "pier_width", None)
    c = getattr(args, "pier_courses", None)
    b = getattr(args, "pier_batter", None)
    right = {k: getattr(args, f"right_pier_{k}", None)
             for k in ("height", "width", "courses", "batter")}
    others = [("--pier-courses", c), ("--pier-batter", b)] + \
        [(f"--right-pier-{k}", v) for k, v in right.items()]
    st, st_r = getattr(args, "pier_steps", None), getattr(args, "right_pier_steps", None)
    if st is not None or st_r is not None:
        return _stepped_from_args(arch, h, w, others, st, st_r)
    if h is None and w is None and all(v is None for _, v in others):
        return arch
    if h is None or w is None:
        given = "--pier-height" if h is not None else ("--pier-width" if w is not None else
                                                          next(f for f, v in others if v is not None))
        missing = " and ".join(f for f, v in (("--pier-height", h), ("--pier-width", w))
                               if v is None)
        raise CLIError(f"{missing}: needed with {given} (the piers' height and width, in metres)")
    from ..geometry import with_piers

    from ..errors import ArchInputError

    try:
        return with_piers(arch, h, w, courses=1 if c is None else c,
                          batter=0.0 if b is None else b, height_right=right["height"],
                          width_right=right["width"], courses_right=right["courses"],
                          batter_right=right["batter"])
    except ArchInputError as exc:
        msg = str(exc)
        for field, flag in (("height:", "--pier-height:"), ("width:", "--pier-width:"),
                            ("courses:", "--pier-courses:"), ("batter:", "--pier-batter:"),
                            ("height_right:", "--right-pier-height:"),
                            ("width_right:", "--right-pier-width:"),
                            ("courses_right:", "--right-pier-courses:"),
                            ("batter_right:", "--right-pier-batter:")):
            if msg.startswith(field):
                raise ArchInputError(flag + msg[len(field):]) from None
        raise


def _stepped_from_args(arch, h, w, others, steps, steps_right):
    """``arch`` on the stepped buttresses of --pier-steps/--right-pier-steps (docs/piers.md)."""
    from ..errors import ArchInputError
    from ..geometry import with_piers
    from ..geometry.piers import parse_steps

    given = [f for f, v in [("--pier-height", h), ("--pier-width", w)] + others if v is not None]
    why = "(stepped piers take their heights and widths from the steps)"
    if steps is None:
        raise CLIError(f"--pier-steps: needed with --right-pier-steps {why}")
    if given:
        raise CLIError(f"{given[0]}: given with --pier-steps {why}")
    sl = parse_steps(steps, "--pier-steps")
    sr = None if steps_right is None else parse_steps(steps_right, "--right-pier-steps")
    try:
        return with_piers(arch, None, None, steps=sl, steps_right=sr)
    except ArchInputError as exc:
        msg = str(exc)
        for field, flag in (("steps_right", "--right-pier-steps"), ("steps", "--pier-steps"),
                            ("width_right:", "--right-pier-steps: top step"),
                            ("width:", "--pier-steps: top step")):
            if msg.startswith(field):
                raise ArchInputError(flag + msg[len(field):]) from None
        raise


def _undamaged_arch_from_args(args: argparse.Namespace):
    from ..geometry import nominal_arch

    circ = ("radius", "embrace")
    fam = ("shape", "span", "rise", "thickness_crown", "joints")
    common = ("thickness", "voussoirs", "density")
    flags = circ + fam + common
    given = [f for f in flags if getattr(args, f, None) is not None]
    flag = {f: "--" + f.replace("_", "-") for f in flags}
    if getattr(args, "geometry", None):
        if given:
            raise CLIError(f"--geometry: cannot be combined with "
                           f"{', '.join(flag[f] for f in given)}; the file holds the whole geometry")
        from ..geometry.files import read_arch

        return read_arch(args.geometry)
    family = [f for f in fam if f in given]
    if family:
        both = [f for f in circ if f in given]
        if both:
            raise CLIError(f"{flag[both[0]]}: cannot be combined with {flag[family[0]]}; give "
                           f"--radius/--embrace (circular) or --shape/--span/--rise")
        shape = getattr(args, "shape", None) or "circular"
        missing = [flag[f] for f in ("span", "rise") if getattr(args, f, None) is None]
        if missing:
            raise CLIError(f"{' and '.join(missing)}: needed with {flag[family[0]]} (the span "
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


# ---------------------------------------------------------------------------- random arches
def add_spread_options(p: argparse.ArgumentParser, tilt: bool = False,
                       piers: bool = False) -> argparse.ArgumentParser:
    """Add --spread-span, --spread-thickness, --spread-radius (docs/method.md, Geometry widths),
    with ``tilt`` --spread-tilt (joint tilt of family arches, degrees), with ``piers`` the
    pier spreads --spread-pier-lean/-width/-height/-course (docs/piers.md, Irregular piers)."""
    p.add_argument("--spread-span", type=finite_float, default=0.1, metavar="S_A",
                   help="relative half-width of the spans, 0 <= s_a < 1 (default 0.1)")
    p.add_argument("--spread-thickness", type=finite_float, default=0.1, metavar="S_T",
                   help="relative half-width of the thicknesses, 0 <= s_t < 1 (default 0.1)")
    p.add_argument("--spread-radius", type=finite_float, default=0.05, metavar="S_R",
                   help="half-width of the radii as a fraction of t, 0 <= s_R < 1 (default 0.05)")
    if tilt:
        p.add_argument("--spread-tilt", type=finite_float, default=0.0, metavar="DEG",
                       help="half-width of the tilt of each interior joint [deg] about its "
                            "centreline point, 0 <= tilt < 45 (default 0); an arch of a family "
                            "(--shape ...) other than the exact circular Arch")
    if piers:  # an arch on piers: each pier drawn on its own (geometry.sampling.PIER_SPREADS)
        from ..geometry.sampling import PIER_SPREADS

        for name, hi, closed, what in PIER_SPREADS:
            p.add_argument("--spread-" + name.replace("_", "-"), type=finite_float, default=0.0,
                           metavar="S", help=f"on piers: {what}, 0 <= s {'<=' if closed else '<'}"
                                             f" {hi:g} (default 0)")
    return p


def add_random_arches_options(p: argparse.ArgumentParser,
                              samples_help: str) -> argparse.ArgumentParser:
    """--samples N (0: the nominal arch only), --seed and the spreads with tilt: the random arches
    of a study (curves, fragility)."""
    p.add_argument("--samples", type=non_negative_int, default=0, metavar="N", help=samples_help)
    p.add_argument("--seed", type=non_negative_int, default=0, help="random seed (default 0)")
    return add_spread_options(p, tilt=True, piers=True)


def spreads(args: argparse.Namespace):
    """The :class:`~archrock.geometry.sampling.Spreads` of :func:`add_spread_options`."""
    from ..errors import ArchInputError
    from ..geometry.sampling import PIER_SPREADS, Spreads

    pier = {name: getattr(args, "spread_" + name, 0.0) for name, *_ in PIER_SPREADS}
    try:
        return Spreads(args.spread_span, args.spread_thickness, args.spread_radius,
                       getattr(args, "spread_tilt", 0.0), **pier)
    except ArchInputError as exc:  # the flag's name, not the field's
        msg = str(exc)
        for name, *_ in PIER_SPREADS:
            if msg.startswith(name + ":"):
                raise ArchInputError("--spread-" + name.replace("_", "-") + msg[len(name):]) \
                    from None
        raise


# ---------------------------------------------------------------------------- ground motion
def add_motion_options(parser: argparse.ArgumentParser, required: bool = False) -> argparse.ArgumentParser:
    """Add the ground-motion options: --pulse KIND --amplitude A_G --pulse-duration S, or
    --record FILE [--units U] [--scale F]."""
    g = parser.add_argument_group(
        "ground motion", "an idealised pulse (amplitude in g, positive toward +x) or a record")
    g.add_argument("--pulse", metavar="KIND",
                   help="oppenheim (a for t_p, -a/2 for 2 t_p: the paper's), rectangular, "
                        "half-sine, one-sine or ricker")
    g.add_argument("--amplitude", type=finite_float, metavar="A_G", default=None,
                   help="pulse amplitude [g], sign = direction (paper: -1)")
    g.add_argument("--pulse-duration", type=finite_float, metavar="S", default=None,
                   help="pulse duration t_p [s] (ricker: its period) (paper: 0.2)")
    g.add_argument("--record", metavar="FILE",
                   help="accelerogram: PEER .AT2 (g) or two-column 'time accel' text file")
    g.add_argument("--units", choices=("g", "m/s2", "cm/s2"), default=None,
                   help="units of a two-column record (default g)")
    g.add_argument("--scale", type=finite_float, default=1.0, metavar="F",
                   help="scale factor applied to the record (default 1)")
    parser.set_defaults(_motion_required=required)
    return parser


def motion_spec_from_args(args: argparse.Namespace):
    """The PulseSpec / RecordSpec described by :func:`add_motion_options`, or None if none was
    given (a record's file is read and checksummed)."""
    from ..groundmotion import PulseSpec, RecordSpec

    has_pulse = any(getattr(args, f, None) is not None for f in ("pulse", "amplitude", "pulse_duration"))
    if getattr(args, "record", None):
        if has_pulse:
            raise CLIError("--record: cannot be combined with --pulse/--amplitude/--pulse-duration")
        return RecordSpec.from_file(args.record, args.units, args.scale)
    for flag, given in (("--units", args.units is not None), ("--scale", args.scale != 1.0)):
        if given and has_pulse:
            raise CLIError(f"{flag}: applies to --record only; a pulse's amplitude is in g")
    if not has_pulse:
        if getattr(args, "_motion_required", False):
            raise CLIError("ground motion: give --pulse KIND --amplitude A_G --pulse-duration S "
                           "or --record FILE")
        return None
    if args.amplitude is None or args.pulse_duration is None:
        raise CLIError("--amplitude and --pulse-duration: both are needed with a pulse "
                       "(e.g. --pulse oppenheim --amplitude -1 --pulse-duration 0.2)")
    return PulseSpec(args.pulse or "oppenheim", args.amplitude, args.pulse_duration)


def motion_from_args(args: argparse.Namespace):
    """The GroundMotion described by :func:`add_motion_options`, or None if none was given."""
    spec = motion_spec_from_args(args)
    return None if spec is None else spec.build()


# ---------------------------------------------------------------------------- impact
def add_impact_options(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Add the impact group, with one meaning in every command (archrock.dynamics.impact.ImpactSpec):
    --impact MODEL, --cv X, --literal-cv, --impact-on arch|nominal."""
    g = parser.add_argument_group(
        "impact", "the impact law at each closing of the mechanism. Default: the paper's practice, "
                  "the 'paper' model on the nominal arch and its c_v fixed on every random arch "
                  "(one arch alone: the 'paper' model on it)")
    g.add_argument("--impact", choices=("paper", "momentum", "least-loss", "nominal-paper"),
                   default=None,
                   help="paper: De Lorenzis et al.'s five equations (refused where they create "
                        "energy); momentum: energy-consistent projection; least-loss: momentum, "
                        "opening the mechanism that keeps the most energy (Bisegna et al. 2023); "
                        "evaluated on each arch unless --impact-on nominal (nominal-paper: "
                        "archrock 0.1.0's name for --impact paper --impact-on nominal)")
    g.add_argument("--impact-on", choices=("arch", "nominal"), default=None,
                   help="evaluate --impact on each arch (default when --impact is given) or once "
                        "on the nominal arch, its c_v then fixed on every arch")
    g.add_argument("--cv", type=finite_float, default=None, metavar="CV",
                   help="fixed coefficient of restitution, 0 <= cv <= 1 (kinetic energy x cv^2; 0 stops the arch at the first impact)")
    g.add_argument("--literal-cv", action="store_true",
                   help="apply the fixed c_v (--cv, or the nominal arch's) to the rates "
                        "literally (may gain energy on irregular arches)")
    return parser


def impact_spec_from_args(args: argparse.Namespace):
    """The :class:`~archrock.dynamics.impact.ImpactSpec` of the impact options (the same in every
    command)."""
    from ..dynamics.impact import PAPER_PRACTICE, ImpactSpec

    if args.cv is not None and args.impact is not None:
        raise CLIError("--cv: cannot be combined with --impact; choose one")
    on = getattr(args, "impact_on", None)
    if args.cv is not None:
        if on is not None:
            raise CLIError("--impact-on: applies to --impact MODEL; a given --cv is the same on "
                           "every arch")
        return ImpactSpec.fixed(args.cv, literal=args.literal_cv)
    if args.impact is None:
        if on is not None:
            raise CLIError("--impact-on: needs --impact MODEL")
        return ImpactSpec.parse(PAPER_PRACTICE, literal=args.literal_cv)
    spec = ImpactSpec.parse(args.impact)
    if on is not None:
        if args.impact == "nominal-paper" and on != "nominal":
            raise CLIError("--impact-on: nominal-paper is evaluated on the nominal arch")
        spec = ImpactSpec(spec.model, on=on)
    if args.literal_cv:
        if spec.on != "nominal":
            raise CLIError("--literal-cv: applies to a fixed c_v (--cv, or a model evaluated on "
                           "the nominal arch); cannot be combined with --impact on each arch")
        spec = ImpactSpec(spec.model, literal=True, on="nominal")
    return spec


def model_from_args(args: argparse.Namespace, arch=None):
    """The prepared DynamicModel (limit analysis, mechanisms, impact law) of one arch."""
    from ..dynamics.response import prepare

    arch = arch_from_args(args) if arch is None else arch
    return prepare(arch, impact_spec_from_args(args))


# ---------------------------------------------------------------------------- support movements
def add_support_options(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Add the support-movement options (docs/supports.md): the arch after a prescribed
    movement of its springings, hinged and displaced exactly."""
    g = parser.add_argument_group(
        "support movement", "the arch after its supports have moved (docs/supports.md): three "
                            "hinges open and the arch is displaced exactly")
    g.add_argument("--spread", type=finite_float, metavar="D",
                   help="horizontal movement of the support [m]: > 0 opens the span, < 0 "
                        "closes it (default 0)")
    g.add_argument("--settlement", type=finite_float, metavar="S",
                   help="vertical movement of the support [m]: > 0 down, < 0 up (default 0)")
    g.add_argument("--support-side", choices=("right", "left", "both"), default=None,
                   help="which support moves: right (default), left, or both by half "
                        "(symmetric)")
    return parser


def _supports_from_args(args: argparse.Namespace, arch):
    """``arch`` after the movement of --spread/--settlement/--support-side (the displaced arch
    of archrock.statics.supports.displace, re-closed; the arch itself at zero movement)."""
    s = getattr(args, "spread", None)
    v = getattr(args, "settlement", None)
    side = getattr(args, "support_side", None)
    if s is None and v is None:
        if side is not None:
            raise CLIError("--support-side: needs --spread or --settlement (the movement, in "
                           "metres)")
        return arch
    from ..errors import ArchInputError
    from ..geometry.displaced import SupportMovement
    from ..statics.supports import on_moved_supports

    try:
        mv = SupportMovement(0.0 if s is None else s, 0.0 if v is None else v,
                             side or "right")
    except ArchInputError as exc:
        msg = str(exc)
        for field, flag in (("spread:", "--spread:"), ("settlement:", "--settlement:")):
            if msg.startswith(field):
                raise ArchInputError(flag + msg[len(field):]) from None
        raise
    # the analyses take the displaced geometry with its open joints bearing on whole faces: a
    # mechanism that turns an open joint back only closes its gap (docs/supports.md, "One
    # answer: the re-closed arch"); limit reports that bounded motion beside it
    return on_moved_supports(arch, mv)  # the arch itself at zero movement
