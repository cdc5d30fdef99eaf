"""Option groups shared by several subcommands (argparse), and the output-file options.

Their conversion to library objects lives one layer down, in :mod:`archrock.options`, which the
web app shares; it is re-exported here under its old names (``archrock.cli.options.arch_from_args``
and the rest keep working)."""

from __future__ import annotations

import argparse
import sys

from ..options import (GEOMETRY_DEFAULTS, JOINTS, SHAPES, arch_from_args,  # noqa: F401
                       impact_spec_from_args, model_from_args, motion_from_args,
                       motion_spec_from_args, piers_from_args, spreads, supports_from_args,
                       undamaged_arch_from_args)
from ._parser import PROG, CLIError, _int, finite_float, non_negative_int, positive_float

# the old private names of the builders (archrock <= 0.6.0 imported them from here)
_piers_from_args = piers_from_args
_supports_from_args = supports_from_args
_undamaged_arch_from_args = undamaged_arch_from_args


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


def say_written(*paths) -> None:
    """One 'wrote PATH' line on stdout for each file a command wrote (None: not asked for)."""
    for path in paths:
        if path:
            print(f"wrote {path}")


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
    g.add_argument("--fill-level", type=finite_float, metavar="Y",
                   help="with --shape: a fill over the extrados up to y = Y [m] above the "
                        "centreline's springings, carried as weight and horizontal inertia by "
                        "the voussoir beneath (docs/fill.md)")
    g.add_argument("--fill-density", type=finite_float, metavar="RHO",
                   help="with --fill-level: the fill's density [kg/m^3] (default 1800)")
    g.add_argument("--voussoirs", type=_int, metavar="N",
                   help=f"number of voussoirs, 3 to 2000 (default {d['voussoirs']})")
    g.add_argument("--density", type=finite_float, metavar="RHO",
                   help=f"density [kg/m^3], 1e-8 to 1e8 (default {d['density']:g}; cancels from k)")
    g.add_argument("--fc", type=finite_float, metavar="MPA",
                   help="the masonry's compressive strength f_c [MPa], 0.1 to 1000 (default: "
                        "infinite, Heyman's no-crushing hypothesis); with --geometry it "
                        "replaces the file's \"fc\" (docs/crushing.md)")
    g.add_argument("--geometry", metavar="FILE",
                   help="JSON geometry file, circular or polygon voussoirs (from the left "
                        "springing); excludes the flags above but --fc")
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


# ---------------------------------------------------------------------------- random arches
def add_spread_options(p: argparse.ArgumentParser, tilt: bool = False,
                       piers: bool = False, strength: bool = False) -> argparse.ArgumentParser:
    """Add --spread-span, --spread-thickness, --spread-radius (docs/method.md, Geometry widths),
    with ``tilt`` --spread-tilt (joint tilt of family arches, degrees), with ``piers`` the
    pier spreads --spread-pier-lean/-width/-height/-course (docs/piers.md, Irregular piers),
    with ``strength`` --spread-fc (each arch's f_c, docs/crushing-dynamics.md)."""
    p.add_argument("--spread-span", type=finite_float, default=None, metavar="S_A",
                   help="relative half-width of the spans, 0 <= s_a < 1 (default 0.1; 0 for an "
                        "arch whose joints stay where drawn: on piers, or a polygon without a "
                        "family)")
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
    if strength:
        p.add_argument("--spread-fc", type=finite_float, default=0.0, metavar="S",
                       help="with --fc: each arch's compressive strength is f_c (1 + U s), U "
                            "uniform on [-1, 1], 0 <= s < 1 (default 0)")
    return p


def resolve_spread_span(args, nominal) -> None:
    """Set an omitted --spread-span to its default for ``nominal``: 0.1, or 0 where its joints
    stay where they are drawn (an arch on piers, a surveyed polygon: the span spread does not
    apply), saying so in one line on stderr so the run states the spreads it applied."""
    if getattr(args, "spread_span", 0.0) is not None:
        return
    from ..geometry.sampling import DEFAULT_SPREADS, fixed_joints

    why = fixed_joints(getattr(nominal, "base", nominal))  # a moved arch: its own blocks
    args.spread_span = DEFAULT_SPREADS.span if why is None else 0.0
    if why is not None:
        tilt = getattr(args, "spread_tilt", 0.0) or 0.0
        print(f"{PROG}: spreads applied: span 0 (default for {nominal.name!r}, {why}, whose "
              f"joints stay where drawn), thickness {args.spread_thickness:g}, radius "
              f"{args.spread_radius:g}, tilt {tilt:g}", file=sys.stderr)


def spreads_for(args, nominal):
    """:func:`spreads` of ``args`` with --spread-span's default chosen for ``nominal``
    (:func:`resolve_spread_span`)."""
    resolve_spread_span(args, nominal)
    return spreads(args)


def add_random_arches_options(p: argparse.ArgumentParser,
                              samples_help: str) -> argparse.ArgumentParser:
    """--samples N (0: the nominal arch only), --seed and the spreads with tilt: the random arches
    of a study (curves, fragility)."""
    p.add_argument("--samples", type=non_negative_int, default=0, metavar="N", help=samples_help)
    p.add_argument("--seed", type=non_negative_int, default=0, help="random seed (default 0)")
    return add_spread_options(p, tilt=True, piers=True, strength=True)


# ---------------------------------------------------------------------------- ground motion
#: the built-in suites in a help text, one spelling in every command (extra ``records``)
_SUITES_HELP = ("the 'records' extra: pip install 'archrock[records]'; archrock records lists "
                "them")
#: --record of every command that takes one record
RECORD_HELP = ("accelerogram: PEER .AT2 (g) or two-column 'time accel' text file, or a built-in "
               "suite's record SUITE/ID (p695-far-field/1a: record 1, component a; "
               + _SUITES_HELP + ")")
RECORD_METAVAR = "FILE|SUITE/ID"
#: --records of every command that takes a list of records
RECORDS_HELP = ("accelerograms: PEER .AT2 (g) or two-column 'time accel' files, folders of .AT2 "
                "files, built-in suites (p695-far-field, p695-near-field-pulse, "
                "p695-near-field-no-pulse, each also NAME-normalized) or their records "
                "SUITE/ID (" + _SUITES_HELP + ")")
RECORDS_METAVAR = "FILE|DIR|SUITE"


def add_motion_options(parser: argparse.ArgumentParser, required: bool = False) -> argparse.ArgumentParser:
    """Add the ground-motion options: --pulse KIND --amplitude A_G --pulse-duration S, or
    --record FILE|SUITE/ID [--units U] [--scale F]."""
    g = parser.add_argument_group(
        "ground motion", "an idealised pulse (amplitude in g, positive toward +x) or a record")
    g.add_argument("--pulse", metavar="KIND",
                   help="oppenheim (a for t_p, -a/2 for 2 t_p: the paper's), rectangular, "
                        "half-sine, one-sine or ricker")
    g.add_argument("--amplitude", type=finite_float, metavar="A_G", default=None,
                   help="pulse amplitude [g], sign = direction (paper: -1)")
    g.add_argument("--pulse-duration", type=finite_float, metavar="S", default=None,
                   help="pulse duration t_p [s] (ricker: its period) (paper: 0.2)")
    g.add_argument("--record", metavar=RECORD_METAVAR, help=RECORD_HELP)
    g.add_argument("--units", choices=("g", "m/s2", "cm/s2"), default=None,
                   help="units of a two-column record (default g)")
    g.add_argument("--scale", type=finite_float, default=1.0, metavar="F",
                   help="scale factor applied to the record (default 1)")
    parser.set_defaults(_motion_required=required)
    return parser


# ---------------------------------------------------------------------------- dynamics
def friction_mu(args):
    """The command's one friction coefficient from ``--friction MU|none``
    (:mod:`archrock.cli._friction`): MU, None (sliding excluded) or the package's default."""
    from ._friction import NOT_GIVEN, resolve_friction

    return resolve_friction(getattr(args, "friction", NOT_GIVEN))[0]


def add_dynamics_option(parser, what: str = "the response"):
    """--dynamics auto|fourlink|engine, as the studies route it (docs/piers-dynamics.md)."""
    from ..studies.enginestudy import DYNAMICS

    parser.add_argument(
        "--dynamics", choices=DYNAMICS, default="auto",
        help=f"auto (default): {what} by the four-link model where one degree of freedom "
             f"follows the arch (no piers or still piers, and the joints' friction carries the "
             f"collapse without sliding), else by the contact engine (docs/piers-dynamics.md); "
             f"fourlink or engine as asked (fourlink where it is not valid: labelled so)")


def friction_words(args) -> str:
    """The friction a command ran with, in words, stated once in its output."""
    from ._friction import NOT_GIVEN, resolve_friction

    return "friction: " + resolve_friction(getattr(args, "friction", NOT_GIVEN))[1]


# ---------------------------------------------------------------------------- output and runs
#: --no-progress of the studies that say how long they will take
PROGRESS_ESTIMATED = "no progress on stderr (shown for runs estimated above a few seconds)"


def add_output_options(parser, *, json: str = "print one JSON object", progress: str | None = None,
                       plot: str | None = None, animate: str | None = None):
    """--json, and each of --no-progress, --plot FILE.png and --animate FILE.gif whose help is
    given: the output options of the commands, one spelling in all."""
    parser.add_argument("--json", action="store_true", help=json)
    if progress:
        parser.add_argument("--no-progress", action="store_true", help=progress)
    if plot:
        parser.add_argument("--plot", metavar="FILE.png", help=plot)
    if animate:
        parser.add_argument("--animate", metavar="FILE.gif", help=animate)
    return parser


def add_window_options(parser, after: str):
    """--t-end S and --dt-out S: the output window of one response; ``after`` says what the run
    covers past the window."""
    parser.add_argument("--t-end", type=positive_float, default=3.0, metavar="S",
                        help=f"end of the output window [s] (default 3); {after}")
    parser.add_argument("--dt-out", type=positive_float, default=0.005, metavar="S",
                        help="output sampling [s] (default 0.005)")
    return parser


#: --device's help where the command's kernels have a GPU build (the ensemble's)
DEVICE_HELP = ("where the batch kernels run: cpu (default), gpu (an NVIDIA GPU through numba's "
               "CUDA target, in-process only: not with --workers > 1 or --scheduler) or auto "
               "(the GPU where one is present and the run has enough arches, else the CPU); "
               "results agree to rounding (docs/gpu.md)")


def add_run_options(parser, *, workers: str, scheduler: str, out: str | None = None,
                    device: str | None = None):
    """--workers N, --scheduler ADDRESS and (where ``out`` is given) --out DIR: where a study
    runs and keeps its finished work, with each command's own help; with ``device`` also
    --device cpu|gpu|auto (a run setting, never part of a study's configuration)."""
    from .._device import DEVICES

    parser.add_argument("--workers", type=_int, default=1, metavar="N", help=workers)
    parser.add_argument("--scheduler", metavar="ADDRESS", help=scheduler)
    if out:
        parser.add_argument("--out", metavar="DIR", help=out)
    if device:
        parser.add_argument("--device", choices=DEVICES, default="cpu", help=device)
    return parser


def add_scan_options(group, *, sign_choices: tuple, sign_help: str, n_scan: int,
                     tol_help: str):
    """The amplitude scan of a collapse-amplitude search (curves, defects): --pulse KIND,
    --sign, --a-max G, --n-scan N and --tol G."""
    group.add_argument("--pulse", default="oppenheim", metavar="KIND",
                       help="oppenheim (default), rectangular, half-sine, one-sine or ricker")
    group.add_argument("--sign", type=_int, choices=sign_choices, default=-1, help=sign_help)
    group.add_argument("--a-max", type=positive_float, default=10.0, metavar="G",
                       help="top of the amplitude scan [g] (default 10)")
    group.add_argument("--n-scan", type=_int, default=n_scan, metavar="N",
                       help=f"amplitude grid points (geometric, default {n_scan})")
    group.add_argument("--tol", type=positive_float, default=1e-3, metavar="G", help=tol_help)
    return group


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
    g.add_argument("--rotation", type=finite_float, metavar="RAD",
                   help="rotation of the support (abutment or pier) about its foot [rad]: > 0 "
                        "outward, |RAD| <= 0.5 (default 0)")
    g.add_argument("--pivot-depth", type=finite_float, metavar="M",
                   help="with --rotation or limit --capacity rotation: the foot is the outer end "
                        "of the springing joint (an arch on piers: the pier's outer foot) lowered "
                        "by M [m] (default 0)")
    g.add_argument("--support-side", choices=("right", "left", "both"), default=None,
                   help="which support moves: right (default), left, or both by half "
                        "(symmetric)")
    return parser
