"""Command-line interface: ``archrock <subcommand> ...`` (argparse, stdlib only).

Adding a subcommand: write ``add_<name>_parser(subparsers)`` that creates the parser with
``subparsers.add_parser(...)``, adds its options (use :func:`add_geometry_options` for the arch
and :func:`finite_float` / :func:`positive_float` as argparse ``type=`` to refuse NaN/inf),
sets ``parser.set_defaults(func=run_<name>)`` and returns the parser; decorate it with
``@subcommand("<name>")``. ``run_<name>(args) -> int`` does the work; raising
:class:`~archrock.errors.ArchInputError` (or :class:`CLIError`) gives the one-line
``archrock: error: ...`` message and exit status 2.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from typing import Callable

from .errors import ArchInputError

__all__ = [
    "main", "build_parser", "subcommand", "SUBCOMMANDS", "CLIError",
    "add_geometry_options", "arch_from_args", "finite_float", "positive_float",
    "non_negative_int", "emit_json", "GEOMETRY_DEFAULTS",
    "add_motion_options", "motion_from_args", "add_impact_options", "model_from_args",
    "add_spread_options",
]

PROG = "archrock"
EXIT_USAGE = 2  # bad input: same status as argparse's own errors
_OPTIONAL_MODULES = {"matplotlib", "PIL", "pandas", "pyarrow", "tqdm", "numba", "dask", "distributed"}

#: Defaults of the nominal-geometry flags: Oppenheim's arch (R [m], embrace [deg], t [m], n, kg/m^3).
GEOMETRY_DEFAULTS = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7,
                     "density": 2000.0}

#: name -> add_<name>_parser(subparsers); filled by @subcommand, in the order shown by --help.
SUBCOMMANDS: dict[str, Callable] = {}


class CLIError(Exception):
    """A command-line problem that is not an arch-input problem (e.g. conflicting options)."""


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors read ``archrock: error: <message>`` (exit status 2)."""

    def error(self, message):  # noqa: D401 - argparse API
        self.print_usage(sys.stderr)
        self.exit(EXIT_USAGE, f"{PROG}: error: {message}\n")


def subcommand(name: str):
    """Decorator registering ``add_<name>_parser(subparsers)`` under ``name``."""
    def register(add_parser: Callable) -> Callable:
        SUBCOMMANDS[name] = add_parser
        return add_parser
    return register


# ---------------------------------------------------------------------------- argparse types
def finite_float(text: str) -> float:
    """argparse type: a finite number (NaN and infinities refused)."""
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(v):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text!r}")
    return v


def positive_float(text: str) -> float:
    """argparse type: a finite number > 0."""
    v = finite_float(text)
    if v <= 0:
        raise argparse.ArgumentTypeError(f"{text!r} is out of range; allowed > 0")
    return v


def non_negative_int(text: str) -> int:
    """argparse type: an integer >= 0 (e.g. a random seed)."""
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None
    if v < 0:
        raise argparse.ArgumentTypeError(f"{text!r} is out of range; allowed an integer >= 0")
    return v


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None


# ---------------------------------------------------------------------------- shared options
def add_geometry_options(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Add the arch options: --radius --embrace --thickness --voussoirs --density (a nominal
    arch; defaults: Oppenheim's arch) or --geometry FILE (a JSON geometry file)."""
    d = GEOMETRY_DEFAULTS
    g = parser.add_argument_group(
        "arch geometry", "a nominal arch (defaults: Oppenheim's arch) or --geometry FILE")
    # Defaults are None so that arch_from_args can tell given flags from defaults.
    g.add_argument("--radius", type=finite_float, metavar="R",
                   help=f"mean radius [m], > 0 (default {d['radius']:g})")
    g.add_argument("--embrace", type=finite_float, metavar="DEG",
                   help=f"angle of embrace [deg], 0 < embrace < 360 (default {d['embrace']:g})")
    g.add_argument("--thickness", type=finite_float, metavar="T",
                   help=f"thickness [m], 0 < t < 2 R (default {d['thickness']:g})")
    g.add_argument("--voussoirs", type=_int, metavar="N",
                   help=f"number of voussoirs, >= 3 (default {d['voussoirs']})")
    g.add_argument("--density", type=finite_float, metavar="RHO",
                   help=f"density [kg/m^3], > 0 (default {d['density']:g}; cancels from k)")
    g.add_argument("--geometry", metavar="FILE",
                   help="JSON geometry file (voussoirs from the left springing); "
                        "excludes the flags above")
    return parser


def add_spread_options(p: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Add --spread-span, --spread-thickness, --spread-radius (METHOD section 1 widths)."""
    p.add_argument("--spread-span", type=finite_float, default=0.1, metavar="S_A",
                   help="relative half-width of the spans, 0 <= s_a < 1 (default 0.1)")
    p.add_argument("--spread-thickness", type=finite_float, default=0.1, metavar="S_T",
                   help="relative half-width of the thicknesses, 0 <= s_t < 1 (default 0.1)")
    p.add_argument("--spread-radius", type=finite_float, default=0.05, metavar="S_R",
                   help="half-width of the radii as a fraction of t, 0 <= s_R < 1 (default 0.05)")
    return p


def arch_from_args(args: argparse.Namespace):
    """The :class:`~archrock.geometry.Arch` described by the options of
    :func:`add_geometry_options` (raises ArchInputError / CLIError on bad input)."""
    from .geometry import nominal_arch

    flags = ("radius", "embrace", "thickness", "voussoirs", "density")
    given = [f for f in flags if getattr(args, f, None) is not None]
    if getattr(args, "geometry", None):
        if given:
            raise CLIError(f"--geometry: cannot be combined with "
                           f"{', '.join('--' + f for f in given)}; the file holds the whole geometry")
        from .files import read_arch

        return read_arch(args.geometry)
    vals = {f: (getattr(args, f, None) if getattr(args, f, None) is not None else GEOMETRY_DEFAULTS[f])
            for f in flags}
    is_oppenheim = not given or all(vals[f] == GEOMETRY_DEFAULTS[f] for f in flags)
    return nominal_arch(radius=vals["radius"], embrace_deg=vals["embrace"], thickness=vals["thickness"],
                        voussoirs=vals["voussoirs"], density=vals["density"],
                        name="Oppenheim" if is_oppenheim else "nominal")


def emit_json(obj, out=None) -> None:
    """Print ``obj`` as one JSON document (strict: NaN/inf refused) on stdout."""
    out = sys.stdout if out is None else out
    out.write(json.dumps(obj, indent=2, allow_nan=False) + "\n")


def _write_text(path: str, text: str) -> Path:
    p = Path(path)
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise CLIError(f"--out: cannot write {str(p)!r} ({exc.strerror or exc})") from None
    return p


# ---------------------------------------------------------------------------- limit
def limit_summary(result, min_thickness=None) -> dict:
    """JSON-ready summary of a LimitResult (the ``archrock limit --json`` object)."""
    d = result.to_dict()
    d.pop("arch", None)
    out = {
        "arch": result.arch.name,
        "k": result.k,
        **d,
        "hinge_labels": {
            # A..D from the mechanism's leading side (A leftmost for M_l, rightmost for M_r)
            dirn: [{"label": lab, **h.to_dict()} for lab, h in _labelled(result.mechanism(dirn))]
            for dirn in ("l", "r")
        },
        "geometry": result.arch.to_dict(),
        "units": {"k": "g (horizontal load / weight)", "span_deg": "deg", "radius": "m",
                  "thickness": "m", "density": "kg/m^3"},
    }
    if min_thickness is not None:
        out["min_thickness"] = {
            "factor": min_thickness.factor,
            "ratio_t_over_R": min_thickness.ratio,
            "thicknesses": [float(t) for t in min_thickness.thicknesses],
        }
    return out


def _labelled(mechanism):
    # plots imports matplotlib only inside its drawing functions, so this stays light
    from .plots import hinge_labels

    return hinge_labels(mechanism)


def format_limit_table(result, min_thickness=None) -> str:
    """Readable report of a LimitResult: geometry, k_l / k_r, hinges, LP check."""
    import numpy as np

    arch = result.arch
    lines = [f"Arch: {arch.name}, {arch.n} voussoirs, embrace {math.degrees(arch.embrace):.4f} deg, "
             f"density {arch.density:g} kg/m^3"]
    uniform = (np.ptp(arch.spans) < 1e-12 and np.ptp(arch.radii) < 1e-12
               and np.ptp(arch.thicknesses) < 1e-12)
    if uniform:
        lines.append(f"  regular: R = {arch.radii[0]:g} m, t = {arch.thicknesses[0]:g} m, "
                     f"span = {math.degrees(arch.spans[0]):.4f} deg each")
    else:
        lines.append("  voussoir  span [deg]  radius [m]  thickness [m]")
        for i, (a, r, t) in enumerate(zip(arch.spans, arch.radii, arch.thicknesses)):
            lines.append(f"  {i:8d}  {math.degrees(a):10.4f}  {r:10.4f}  {t:13.4f}")
    lines += ["", "Limit analysis (horizontal forces = multiplier x weight; Heyman's hypotheses)",
              "  mechanism  k (kinematic)  k (static LP)  hinges A-D (joint edge)"]
    for dirn in ("l", "r"):
        mech = result.mechanism(dirn)
        k = result.k_l if dirn == "l" else result.k_r
        ks = result.static_k_l if dirn == "l" else result.static_k_r
        kss = f"{ks:13.4f}" if ks is not None else f"{'-':>13}"
        hinges = ", ".join(f"{lab}: {h.joint} {h.edge}" for lab, h in _labelled(mech))
        lines.append(f"  M_{dirn}        {k:13.4f}  {kss}  {hinges}")
    lines.append(f"  k = min(k_l, k_r) = {result.k:.4f}")
    if result.discrepancy is not None:
        verdict = "agree" if result.discrepancy < 1e-6 else "DISAGREE"
        lines.append(f"  LP check: max |kinematic - static| = {result.discrepancy:.2e} ({verdict})")
    if min_thickness is not None:
        lines.append(f"  minimum thickness under self-weight: factor {min_thickness.factor:.4f} "
                     f"of the given thicknesses, mean t/R = {min_thickness.ratio:.4f}")
    lines.append("  (M_l: activated by xg''/g <= -k_l, forces toward +x; "
                 "M_r: by xg''/g >= k_r, forces toward -x)")
    return "\n".join(lines)


@subcommand("limit")
def add_limit_parser(subparsers):
    p = subparsers.add_parser(
        "limit", help="collapse multipliers k_l, k_r and mechanisms (limit analysis)",
        description="Limit analysis under horizontal forces proportional to the weight: "
                    "kinematic enumeration of four-hinge mechanisms, checked by a static LP.")
    add_geometry_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a table")
    p.add_argument("--min-thickness", action="store_true",
                   help="also compute the minimum thickness under self-weight (bisection)")
    p.set_defaults(func=run_limit)
    return p


def run_limit(args) -> int:
    from .limit import limit_analysis, minimum_thickness

    arch = arch_from_args(args)
    result = limit_analysis(arch, verify=True)
    mt = minimum_thickness(arch) if args.min_thickness else None
    if args.json:
        emit_json(limit_summary(result, mt))
    else:
        print(format_limit_table(result, mt))
    return 0


# ---------------------------------------------------------------------------- random-arch
@subcommand("random-arch")
def add_random_arch_parser(subparsers):
    p = subparsers.add_parser(
        "random-arch", help="draw an irregular arch around a nominal one; write its geometry file",
        description="span_i = (alpha/n)(1 + s_a U), t_i = t (1 + s_t U), R_i = R + s_R t U, "
                    "U uniform on [-1, 1], spans rescaled to the nominal embrace.")
    add_geometry_options(p)
    p.add_argument("--seed", type=non_negative_int, default=None,
                   help="random seed (integer >= 0); omit for a fresh draw")
    add_spread_options(p)
    p.add_argument("--out", metavar="FILE", help="geometry file to write (default: stdout)")
    p.set_defaults(func=run_random_arch)
    return p


def run_random_arch(args) -> int:
    from .geometry import random_arch

    nominal = arch_from_args(args)
    arch = random_arch(nominal, seed=args.seed, spread_span=args.spread_span,
                       spread_thickness=args.spread_thickness, spread_radius=args.spread_radius)
    meta = {"generator": "archrock random-arch", "seed": args.seed, "nominal": nominal.name,
            "spread_span": args.spread_span, "spread_thickness": args.spread_thickness,
            "spread_radius": args.spread_radius}
    if args.out:
        from .files import write_arch

        try:
            Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise CLIError(f"--out: cannot create the folder of {args.out!r} ({exc.strerror})") from None
        write_arch(arch, args.out, metadata=meta)
        print(f"wrote {args.out}", file=sys.stderr)
    else:
        emit_json({**arch.to_dict(), "metadata": meta})
    return 0


# ---------------------------------------------------------------------------- plot-limit
@subcommand("plot-limit")
def add_plot_limit_parser(subparsers):
    p = subparsers.add_parser(
        "plot-limit", help="figure of the collapse mechanism and line of thrust (paper Fig. 3)")
    add_geometry_options(p)
    p.add_argument("--out", metavar="FILE.png", default="limit.png",
                   help="image to write (default limit.png)")
    p.add_argument("--direction", choices=("l", "r", "both"), default="both",
                   help="mechanism M_l, M_r or both panels (default both)")
    p.add_argument("--dpi", type=positive_float, default=150, help="resolution (default 150)")
    p.set_defaults(func=run_plot_limit)
    return p


def run_plot_limit(args) -> int:
    from .limit import limit_analysis
    from .plots import save_limit_figure

    arch = arch_from_args(args)
    result = limit_analysis(arch, verify=True)
    dirs = ("l", "r") if args.direction == "both" else (args.direction,)
    path = save_limit_figure(result, args.out, directions=dirs, dpi=int(args.dpi))
    print(f"k_l = {result.k_l:.4f}, k_r = {result.k_r:.4f}; wrote {path}")
    return 0


# ---------------------------------------------------------------------------- ground motion / impact
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


def motion_from_args(args: argparse.Namespace):
    """The GroundMotion described by :func:`add_motion_options`, or None if none was given."""
    from .groundmotion import load_record, pulse

    has_pulse = any(getattr(args, f, None) is not None for f in ("pulse", "amplitude", "pulse_duration"))
    if getattr(args, "record", None):
        if has_pulse:
            raise CLIError("--record: cannot be combined with --pulse/--amplitude/--pulse-duration")
        motion = load_record(args.record, units=args.units)
        return motion.scaled(args.scale) if args.scale != 1.0 else motion
    for flag, given in (("--units", args.units is not None), ("--scale", args.scale != 1.0)):
        if given and has_pulse:
            raise CLIError(f"{flag}: applies to --record only; a pulse's amplitude is in g")
    if not has_pulse:
        if getattr(args, "_motion_required", False):
            raise CLIError("ground motion: give --pulse KIND --amplitude A_G --pulse-duration S "
                           "or --record FILE")
        return None
    kind = args.pulse or "oppenheim"
    if args.amplitude is None or args.pulse_duration is None:
        raise CLIError("--amplitude and --pulse-duration: both are needed with a pulse "
                       "(e.g. --pulse oppenheim --amplitude -1 --pulse-duration 0.2)")
    return pulse(kind, args.amplitude, args.pulse_duration)


def add_impact_options(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """Add --impact paper|momentum and --cv X (a fixed coefficient of restitution)."""
    g = parser.add_argument_group("impact", "coefficient of restitution at each impact")
    g.add_argument("--impact", choices=("paper", "momentum", "least-loss"), default=None,
                   help="paper: De Lorenzis et al.'s five equations on this geometry (refused if "
                        "it creates energy); momentum: energy-consistent projection; least-loss: "
                        "momentum, opening the mechanism that keeps the most energy (Bisegna et "
                        "al. 2023) (default: paper)")
    g.add_argument("--cv", type=finite_float, default=None, metavar="CV",
                   help="fixed coefficient of restitution, 0 < cv <= 1 (kinetic energy x cv^2)")
    g.add_argument("--literal-cv", action="store_true",
                   help="apply --cv to the rates literally (may gain energy on irregular arches)")
    return parser


def model_from_args(args: argparse.Namespace, arch=None):
    """The prepared DynamicModel (limit analysis, mechanisms, impact law) for the options."""
    from .response import prepare

    arch = arch_from_args(args) if arch is None else arch
    if args.cv is not None and args.impact is not None:
        raise CLIError("--cv: cannot be combined with --impact; choose one")
    if args.cv is not None:
        return prepare(arch, "fixed", cv=args.cv, literal_cv=args.literal_cv)
    return prepare(arch, args.impact or "paper")


# ---------------------------------------------------------------------------- respond
@subcommand("respond")
def add_respond_parser(subparsers):
    p = subparsers.add_parser(
        "respond", help="rocking response of an arch to a ground motion (four-link mechanism)",
        description="Activation by the paper's eq. (1), motion in M_l / M_r, impacts, rest or "
                    "collapse; signed response +phi in M_l, -phi in M_r.")
    add_geometry_options(p)
    add_motion_options(p, required=True)
    add_impact_options(p)
    p.add_argument("--t-end", type=positive_float, default=3.0, metavar="S",
                   help="end of the output window [s] (default 3); the outcome covers the whole "
                        "ground motion and the free motion after it")
    p.add_argument("--dt-out", type=positive_float, default=0.005, metavar="S",
                   help="output sampling [s] (default 0.005)")
    p.add_argument("--integrator", choices=("fast", "reference"), default="fast",
                   help="fast: RK4 + events (numba); reference: scipy DOP853 (default fast)")
    p.add_argument("--limit-factor", type=finite_float, default=None, metavar="F",
                   help="collapse rotation limit as a multiple of the unstable rotation (> 1)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="write a figure of the motion and response")
    p.add_argument("--animate", metavar="FILE.gif", help="write an animation of the mechanism")
    p.set_defaults(func=run_respond)
    return p


def run_respond(args) -> int:
    from .response import prepare, respond

    motion = motion_from_args(args)
    model = model_from_args(args)
    if args.limit_factor is not None:
        model = prepare(model.arch, model.impact, limit_factor=args.limit_factor, limit=model.limit)
    res = respond(model, motion, t_end=args.t_end, dt_out=args.dt_out, integrator=args.integrator)
    if args.plot:
        from .plots import save_response_figure

        save_response_figure([res], args.plot, labels=[model.arch.name])
    if args.animate:
        from .animate import animate_response

        animate_response(res, args.animate)
    if args.json:
        emit_json(res.to_dict())
        return 0
    imp = res.impacts
    print(f"arch: {model.arch.name}; k_l = {model.k_l:.4f}, k_r = {model.k_r:.4f}")
    print(f"ground motion: {motion.name} (duration {motion.duration:g} s, PGA {motion.pga_g:.3f} g)")
    law = model.impact
    print(f"impact: {law.model}; rate ratio l->r {law.l_to_r:.4f}, r->l {law.r_to_l:.4f} "
          f"(energy ratio {law.energy_l_to_r:.4f}, {law.energy_r_to_l:.4f})")
    outcome = (f"COLLAPSED at t = {res.t_collapse:.3f} s" if res.collapsed else
               ("at rest" if res.status == "rest" else "still rocking at the end of the run"))
    print(f"outcome: {outcome}; peak rotation {res.peak:.4f} rad; {len(imp)} impacts"
          + (f" (first at {imp[0]:.3f} s)" if imp else "")
          + (f"; passed the unstable position at {res.t_unstable:.3f} s" if res.t_unstable else ""))
    opened = res.mechanisms_opened()
    if opened:
        # distinct mechanisms in order of first opening; rows 0/1 are the limit mechanisms
        first = list(dict.fromkeys((row, lab) for _, row, lab in opened))
        names = [f"{('M_l', 'M_r')[row]} {lab}" if row < 2 else
                 f"{lab} ({model.mechanism(row).direction})" for row, lab in first]
        print(f"mechanisms opened ({len(opened)} times, {len(first)} distinct): {names[0]}"
              + (", then " + ", ".join(names[1:]) if len(names) > 1 else ""))
    for f in (args.plot, args.animate):
        if f:
            print(f"wrote {f}")
    return 0


# ---------------------------------------------------------------------------- curves
def _spreads(args) -> dict:
    return {"spread_span": args.spread_span, "spread_thickness": args.spread_thickness,
            "spread_radius": args.spread_radius}


def _impact_spec(args, nominal):
    """The impact law of curves/fragility: --cv X, --impact NAME, or (default) the paper's fixed
    c_v computed once on the nominal arch with the "paper" model.  --literal-cv (args.literal_cv,
    passed on by the callers) applies that fixed c_v to the rates literally."""
    from .curves import default_cv

    if args.cv is not None and args.impact is not None:
        raise CLIError("--cv: cannot be combined with --impact; choose one")
    if args.literal_cv and args.impact is not None:
        raise CLIError("--literal-cv: applies to a fixed c_v (--cv, or the default paper c_v); "
                       "cannot be combined with --impact")
    if args.cv is not None:
        if not 0.0 < args.cv <= 1.0:
            raise ArchInputError(f"cv: {args.cv!r}; allowed 0 < cv <= 1")
        return args.cv
    return args.impact or default_cv(nominal)


@subcommand("curves")
def add_curves_parser(subparsers):
    p = subparsers.add_parser(
        "curves", help="collapse-acceleration curves: first collapse amplitude against pulse duration",
        description="For each pulse duration t_p, scan the amplitude from the activation threshold "
                    "k to --a-max, bisect the first collapse to --tol, and report the survival "
                    "windows above it (collapse is not monotonic in the amplitude).")
    add_geometry_options(p)
    p.add_argument("--durations", default="0.1:1.0:10", metavar="LO:HI:N|A,B,...",
                   help="pulse durations t_p [s] (default 0.1:1.0:10)")
    p.add_argument("--pulse", default="oppenheim", metavar="KIND",
                   help="oppenheim (default), rectangular, half-sine, one-sine or ricker")
    p.add_argument("--sign", type=_int, choices=(-1, 1), default=-1,
                   help="sign of the amplitude (main lobe): -1 (xg'' < 0, opens M_l; default) or "
                        "+1; the first push except for ricker, whose first lobe is -0.446 a")
    p.add_argument("--a-max", type=positive_float, default=10.0, metavar="G",
                   help="top of the amplitude scan [g] (default 10)")
    p.add_argument("--n-scan", type=_int, default=150, metavar="N",
                   help="amplitude grid points (geometric, default 150)")
    p.add_argument("--tol", type=positive_float, default=1e-3, metavar="G",
                   help="bisection tolerance [g] (default 0.001)")
    p.add_argument("--samples", type=non_negative_int, default=0, metavar="N",
                   help="random arches for quantile bands (0 = nominal only, default)")
    p.add_argument("--seed", type=non_negative_int, default=0, help="random seed (default 0)")
    add_spread_options(p)
    p.add_argument("--workers", type=_int, default=1, metavar="N", help="processes (default 1)")
    add_impact_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="write the curve (with bands) to a figure")
    p.set_defaults(func=run_curves)
    return p


def _fmt_windows(ws) -> str:
    return ", ".join(f"{lo:.3f}-{hi:.3f}" for lo, hi in ws) or "-"


def _print_failed(failed, n_requested: int) -> None:
    """The random arches of curves/fragility that could not be analysed, one line each."""
    if failed:
        print(f"{len(failed)} of {n_requested} random arches left out (unusable):")
        for i, why in failed:
            print(f"  sample {i}: {why}")


def run_curves(args) -> int:
    from .curves import collapse_curve, ensemble_curve, parse_range
    from .response import prepare

    nominal = arch_from_args(args)
    durations = parse_range(args.durations, "durations")
    if args.n_scan < 2:
        raise ArchInputError(f"n_scan: {args.n_scan}; allowed an integer >= 2")
    if args.workers < 1:
        raise ArchInputError(f"workers: {args.workers}; allowed an integer >= 1")
    impact = _impact_spec(args, nominal)
    kw = dict(kind=args.pulse, sign=args.sign, a_max=args.a_max, n_scan=args.n_scan, tol=args.tol)
    band = None
    if args.samples > 0:
        band = ensemble_curve(nominal, args.samples, args.seed, _spreads(args), durations,
                              impact=impact, literal_cv=args.literal_cv, workers=args.workers, **kw)
        curve = band.nominal
    else:
        curve = collapse_curve(prepare(nominal, impact, literal_cv=args.literal_cv), durations, **kw)
    if args.plot:
        from .plots import plot_collapse_curve

        plot_collapse_curve(curve, args.plot, band=band,
                            title=f"{nominal.name}: {args.pulse} pulse, sign {args.sign:+d}")
    if args.json:
        out = {"arch": nominal.name, "pulse": args.pulse, "sign": args.sign,
               "impact": impact if isinstance(impact, str) else {"model": "fixed", "cv": impact,
                                                                 "literal": args.literal_cv},
               "curve": curve.to_dict()}
        if band is not None:
            b = band.to_dict()
            b.pop("nominal")
            out["ensemble"] = b
        emit_json(out)
        return 0
    print(f"{nominal.name}: k_l = {curve.k_l:.4f}, k_r = {curve.k_r:.4f}; {args.pulse} pulse, "
          f"sign {args.sign:+d}; impact {impact if isinstance(impact, str) else f'c_v = {impact:.4f}'}"
          f"{' (literal, on the rates)' if args.literal_cv else ''}")
    head = f"{'t_p [s]':>8} {'a_first [g]':>12}  {'mode':<22} survival windows above [g]"
    if band is not None:
        head = head.replace("  mode", "  " + " ".join(f"q{q:g}".rjust(7) for q in band.quantiles)
                            + "  mode")
    print(head)
    for i, p in enumerate(curve.points):
        a = "none" if p.amplitude is None else f"{p.amplitude:.4f}"
        qs = ""
        if band is not None:
            qs = " ".join(("inf" if not math.isfinite(v) else f"{v:.3f}").rjust(7)
                          for v in band.bands[:, i]) + " "
        print(f"{p.duration:8.3f} {a:>12}  {qs}{(p.mode or '-'):<22} {_fmt_windows(p.windows)}")
    if band is not None:
        _print_failed(band.failed, band.n_requested)
    if args.plot:
        print(f"wrote {args.plot}", file=sys.stderr)
    return 0


# ---------------------------------------------------------------------------- fragility
@subcommand("fragility")
def add_fragility_parser(subparsers):
    p = subparsers.add_parser(
        "fragility", help="IDA and multiple-stripe fragility over accelerograms (and random arches)",
        description="IM = PGA of the scaled record [g]. IDA: per record (and arch), scan the scale "
                    "factors, bisect the first collapse, report survivals above it; lognormal fit "
                    "by moments (censored MLE when some never collapse). Multiple stripes at "
                    "--levels (default: 8 levels spanning the IDA first collapses): binomial MLE.")
    add_geometry_options(p)
    p.add_argument("--records", nargs="+", required=True, metavar="FILE",
                   help="accelerograms: PEER .AT2 (g) or two-column 'time accel' files (g)")
    p.add_argument("--units", choices=("g", "m/s2", "cm/s2"), default=None,
                   help="units of two-column records (default g)")
    p.add_argument("--scales", default="0.1:3:30", metavar="LO:HI:N|A,B,...",
                   help="IDA scale factors (default 0.1:3:30)")
    p.add_argument("--levels", default=None, metavar="LO:HI:N|A,B,...",
                   help="stripe PGA levels [g] (default: 8 levels around the IDA first collapses)")
    p.add_argument("--samples", type=non_negative_int, default=0, metavar="N",
                   help="random arches (0 = the nominal arch only, default)")
    p.add_argument("--seed", type=non_negative_int, default=0, help="random seed (default 0)")
    add_spread_options(p)
    add_impact_options(p)
    p.add_argument("--bootstrap", type=non_negative_int, default=200, metavar="N",
                   help="bootstrap resamples for confidence bands (0 = none, or >= 2; default 200)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="write the fragility curves to a figure")
    p.set_defaults(func=run_fragility)
    return p


def run_fragility(args) -> int:
    import numpy as np

    from .curves import parse_range
    from .groundmotion import load_record
    from .ida import ida, msa, random_models
    from .response import prepare

    if args.bootstrap == 1:
        raise ArchInputError("bootstrap: 1; allowed 0 (no confidence bands) or an integer >= 2")
    nominal = arch_from_args(args)
    records = [load_record(f, units=args.units) for f in args.records]
    scales = parse_range(args.scales, "scales")
    impact = _impact_spec(args, nominal)
    models = (random_models(nominal, args.samples, args.seed, _spreads(args), impact,
                            literal_cv=args.literal_cv)
              if args.samples > 0 else [prepare(nominal, impact, literal_cv=args.literal_cv)])
    boot = args.bootstrap
    res_ida = ida(records, models, scales, n_boot=boot, seed=args.seed)
    if args.levels:
        levels = parse_range(args.levels, "levels")
    else:
        f = res_ida.first_ims
        f = f[np.isfinite(f)]
        lo = 0.6 * f.min() if f.size else float(scales[0] * min(r.pga_g for r in records))
        hi = 1.4 * f.max() if f.size else float(scales[-1] * max(r.pga_g for r in records))
        levels = np.geomspace(lo, hi, 8)
    res_msa = msa(records, models, levels, n_boot=boot, seed=args.seed)
    if args.plot:
        from .plots import plot_fragility

        plot_fragility(res_msa.fit if res_msa.fit is not None else res_ida.fit, res_msa, args.plot,
                       ida=res_ida)
    if args.json:
        emit_json({"arch": nominal.name, "records": [r.name for r in records],
                   "n_arches": len(models), "im": "pga_g",
                   "impact": impact if isinstance(impact, str) else {"model": "fixed", "cv": impact,
                                                                     "literal": args.literal_cv},
                   "ida": res_ida.to_dict(),
                   "stripes": res_msa.to_dict()})
        return 0
    print(f"{nominal.name}: {len(records)} record(s) x {len(models)} arch(es); IM = PGA [g]")
    _print_failed(res_ida.failed, args.samples)
    for c in res_ida.curves:
        fc = "never" if c.first_im is None else f"{c.first_im:.4f} g (scale {c.first_scale:.4f})"
        sa = ", ".join(f"{s:g}" for s in c.survivals_above) or "-"
        print(f"  arch {c.arch} {c.record[:40]:<40} first collapse {fc}; survives above at scales {sa}")
        if c.note:
            print(f"    ({c.note})")
    for name, r in (("IDA", res_ida), ("stripes", res_msa)):
        if r.fit is None or r.fit_error:
            print(f"{name}: {'no fit' if r.fit is None else 'note'} ({r.fit_error})")
        if r.fit is not None:
            ci = "" if r.fit.theta_ci is None else (
                f" [{r.fit.theta_ci[0]:.3f}, {r.fit.theta_ci[1]:.3f}], beta CI "
                f"[{r.fit.beta_ci[0]:.2f}, {r.fit.beta_ci[1]:.2f}]")
            print(f"{name}: {r.fit.method} theta = {r.fit.theta:.4f} g{ci}, beta = {r.fit.beta:.3f}")
    print("stripes: " + ", ".join(f"{x:.3f} g {z}/{n}" for x, z, n in
                                  zip(res_msa.levels, res_msa.collapses, res_msa.trials)))
    if args.plot:
        print(f"wrote {args.plot}", file=sys.stderr)
    return 0


# ---------------------------------------------------------------------------- ensemble
@subcommand("ensemble")
def add_ensemble_parser(subparsers):
    p = subparsers.add_parser(
        "ensemble", help="Monte Carlo over random arches around a nominal one: k_l, k_r, hinge "
                         "patterns and, under a ground motion, the probability of collapse",
        description="Random arches (spans, thicknesses, radii uniform around the nominal arch) in "
                    "batches with independent random streams (numpy SeedSequence), so results "
                    "depend on --seed and --batch-size only, never on --workers. With --out DIR "
                    "every finished batch is kept (Parquet + manifest.json) and a re-run resumes.")
    add_geometry_options(p)
    p.add_argument("--samples", type=_int, default=1000, metavar="N",
                   help="number of random arches, >= 1 (default 1000)")
    p.add_argument("--seed", type=_int, default=0, help="random seed, integer >= 0 (default 0)")
    add_spread_options(p)
    p.add_argument("--batch-size", type=_int, default=500, metavar="B",
                   help="samples per batch and random stream, >= 1 (default 500)")
    p.add_argument("--workers", type=_int, default=1, metavar="N",
                   help="1: in-process (numba threads, default); N > 1: local process pool")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the batches on an existing Dask cluster (needs archrock[dask])")
    p.add_argument("--out", metavar="DIR",
                   help="folder for batches/*.parquet and manifest.json; resumes if it exists")
    add_motion_options(p)
    g = p.add_argument_group("impact", "coefficient of restitution at each impact")
    g.add_argument("--impact", choices=("nominal-paper", "paper", "momentum"), default=None,
                   help="nominal-paper (default, the paper's choice): c_v of the nominal arch with "
                        "the 'paper' model, applied to every sample; paper / momentum: per "
                        "geometry ('paper' geometries that gain energy are reported as failed)")
    g.add_argument("--cv", type=finite_float, default=None, metavar="CV",
                   help="fixed coefficient of restitution, 0 < cv <= 1 (kinetic energy x cv^2)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="histograms of k_l and k_r")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run_ensemble_cmd)
    return p


def _ensemble_motion(args):
    from .ensemble import pulse_description, record_description

    motion = motion_from_args(args)  # validates the options (one-line errors)
    if motion is None:
        return None
    if args.record:
        return record_description(args.record, args.units, args.scale)
    return pulse_description(args.pulse or "oppenheim", args.amplitude, args.pulse_duration)


def _ensemble_num(x, spec: str) -> str:
    """A summary number for the text output; '-' for None (no sample to take it over)."""
    return "-" if x is None else format(x, spec)


def run_ensemble_cmd(args) -> int:
    from .ensemble import PAPER_RANDOM_ARCHES, EnsembleConfig, run_ensemble

    if args.workers < 1:
        raise ArchInputError(f"workers: {args.workers}; allowed an integer >= 1")
    if args.cv is not None and args.impact is not None:
        raise CLIError("--cv: cannot be combined with --impact; choose one")
    nominal = arch_from_args(args)
    impact = {"impact": "fixed", "cv": args.cv} if args.cv is not None else \
        {"impact": args.impact or "nominal-paper"}
    config = EnsembleConfig.from_arch(nominal, samples=args.samples, seed=args.seed,
                                      batch_size=args.batch_size, motion=_ensemble_motion(args),
                                      **_spreads(args), **impact)
    result = run_ensemble(config, out_dir=args.out, workers=args.workers,
                          scheduler=args.scheduler, progress=not args.no_progress)
    summary = result.summary()
    if args.plot:
        from .plots import plot_multiplier_histograms

        ref = {"nominal": (summary["nominal"]["k_l"], summary["nominal"]["k_r"]),
               **PAPER_RANDOM_ARCHES}
        plot_multiplier_histograms(result.frame, args.plot, reference=ref)
    if args.json:
        emit_json(summary)
        return 0
    kl, kr = summary["k_l"], summary["k_r"]
    print(f"{summary['samples']} random arches around {nominal.name} (seed {args.seed}, spreads "
          f"{args.spread_span:g}/{args.spread_thickness:g}/{args.spread_radius:g})")
    print(f"nominal: k_l = {summary['nominal']['k_l']:.4f}, k_r = {summary['nominal']['k_r']:.4f}")
    for name, s in (("k_l", kl), ("k_r", kr)):
        if s["mean"] is not None:
            print(f"{name}: mean {s['mean']:.4f}, std {_ensemble_num(s['std'], '.4f')}, 5-95% "
                  f"[{s['q05']:.4f}, {s['q95']:.4f}]")
    for name, far in summary["as_far_as"].items():
        f3 = {k: _ensemble_num(far[k], ".3f") for k in ("k_l", "k_r", "either", "asymmetry")}
        print(f"as far from nominal as {name}: k_l {f3['k_l']}, k_r {f3['k_r']}, "
              f"either {f3['either']}, asymmetry |k_l-k_r| {f3['asymmetry']}")
    for m, counts in summary["hinge_patterns"].items():
        print(f"{m} hinges: " + ", ".join(f"{k} {v}" for k, v in list(counts.items())[:4]))
    pc = summary["p_collapse"]
    if pc is not None:
        print(f"P(collapse) = {pc['p']:.4f} [{pc['low']:.4f}, {pc['high']:.4f}] "
              f"({pc['collapses']}/{pc['trials']}, {pc['confidence']:.0%} Wilson)")
    if summary["failed"]["count"]:
        print(f"failed samples: {summary['failed']['count']} "
              + "; ".join(f"{k}: {v}" for k, v in summary["failed"]["reasons"].items()))
    t = summary["timing"]
    print(f"time: {t['wall_s']:.1f} s ({t['executor']}; {len(t['computed_batches'])} batches "
          f"computed, {len(t['loaded_batches'])} loaded)")
    if args.out:
        print(f"results in {args.out}")
    if args.plot:
        print(f"wrote {args.plot}")
    return 0


# ---------------------------------------------------------------------------- paper
@subcommand("paper")
def add_paper_parser(subparsers):
    p = subparsers.add_parser(
        "paper", help="reproduce the paper's results into a folder (figures + summary.json)")
    p.add_argument("--out", metavar="DIR", default="paper-out",
                   help="output folder (default paper-out)")
    p.set_defaults(func=run_paper)
    return p


def run_paper(args) -> int:
    from .study import run_paper_study

    run_paper_study(args.out, progress=print)
    return 0


# ---------------------------------------------------------------------------- main
def _version() -> str:
    try:
        from importlib.metadata import version

        return version("archrock")
    except Exception:  # not installed (running from a source tree)
        return "unknown"


def build_parser() -> argparse.ArgumentParser:
    """The top-level parser with every registered subcommand."""
    parser = _Parser(prog=PROG, description="Seismic rocking assessment of masonry arches: "
                                            "limit analysis, rocking dynamics, ensembles.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = parser.add_subparsers(dest="command", metavar="<command>", parser_class=_Parser)
    sub.required = True
    for add_parser in SUBCOMMANDS.values():
        add_parser(sub)
    return parser


def main(argv=None) -> int:
    """Run the CLI; returns the exit status (0 ok, 2 bad input, 1 missing optional dependency)."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse: --help/--version (0) or a usage error (2)
        return int(exc.code) if isinstance(exc.code, int) else (0 if exc.code is None else EXIT_USAGE)
    try:
        return int(args.func(args) or 0)
    except (ArchInputError, CLIError) as exc:
        # one line, no traceback: the message names the field and the allowed range
        msg = " ".join(str(exc).split())
        print(f"{PROG}: error: {msg}", file=sys.stderr)
        return EXIT_USAGE
    except ImportError as exc:
        # only a missing optional extra is a user-facing condition; anything else is a bug
        root = (getattr(exc, "name", None) or "").split(".")[0]
        if root not in _OPTIONAL_MODULES and "pip install" not in str(exc):
            raise
        print(f"{PROG}: error: {exc} (install the extras: pip install 'archrock[all]')",
              file=sys.stderr)
        return 1
    except BrokenPipeError:  # e.g. `archrock limit --json | head`
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
