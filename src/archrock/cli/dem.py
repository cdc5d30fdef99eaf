"""``archrock dem``: the arch as rigid voussoirs in a contact engine (pymunk), beside the
four-link model: activation by a ramp (--ramp) or the response to a pulse or record."""

from __future__ import annotations

import sys

from ._parser import CLIError, emit_json, finite_float, positive_float
from .options import (add_geometry_options, add_impact_options, add_motion_options,
                      animation_arg, arch_from_args, figure_arg, impact_spec_from_args,
                      motion_spec_from_args)


def add_engine_options(p):
    """--friction, --restitution and the engine settings that change answers."""
    from ..contact.settings import DEFAULT_FRICTION

    g = p.add_argument_group("contact engine", "settings of the rigid-body engine (defaults: "
                                                "the convergence study of docs/verification.md)")
    g.add_argument("--friction", type=positive_float, default=DEFAULT_FRICTION, metavar="MU",
                   help=f"Coulomb friction coefficient of every joint and springing (finite, "
                        f"> 0, as limit --friction; default {DEFAULT_FRICTION:g})")
    g.add_argument("--restitution", type=finite_float, default=0.0, metavar="E",
                   help="coefficient of restitution of every contact, 0..1 (default 0)")
    g.add_argument("--steps-per-T", type=positive_float, default=None, metavar="N",
                   help="time steps per T = sqrt(size/g) (default 400)")
    g.add_argument("--iterations", type=int, default=None, metavar="N",
                   help="impulse-solver iterations per step (default 40)")
    g.add_argument("--outline-tol", type=finite_float, default=None, metavar="F",
                   help="largest deviation of the contact shapes from a voussoir's outline, as a "
                        "fraction of the size, 0..0.01 (default 2e-3; 0: the fine cut)")
    return p


def engine_settings_from_args(args):
    from ..contact import EngineSettings

    kw = {"friction": args.friction, "restitution": args.restitution}
    if args.steps_per_T is not None:
        kw["steps_per_T"] = args.steps_per_T
    if args.iterations is not None:
        kw["iterations"] = args.iterations
    if getattr(args, "outline_tol", None) is not None:
        kw["outline_tol"] = args.outline_tol
    return EngineSettings(**kw)


def add_dem_parser(subparsers):
    p = subparsers.add_parser(
        "dem", help="the arch as rigid voussoirs in a contact engine (pymunk), beside the "
                    "four-link model",
        description="--ramp: activation multiplier and hinges in each direction beside the "
                    "limit analysis; or a pulse/record: collapse, voussoir rotations, sliding "
                    "and the equivalent four-link rotation beside `respond`. Needs pymunk "
                    "(pip install 'archrock[dem]').")
    add_geometry_options(p)
    add_motion_options(p)
    add_impact_options(p)  # for the four-link run beside the engine's only (the engine has none)
    add_engine_options(p)
    p.add_argument("--ramp", action="store_true",
                   help="slowly increasing ground acceleration in each direction: activation "
                        "multipliers and hinges")
    p.add_argument("--ramp-tol", type=positive_float, default=0.005, metavar="TOL",
                   help="--ramp: relative width of the final bracket of the multiplier "
                        "(default 0.005)")
    p.add_argument("--ramp-max", type=positive_float, default=None, metavar="LAMBDA",
                   help="--ramp: the largest |xg''|/g the ramp tries before it gives up "
                        "(default max(2, 1.5 k) per direction, k from the limit analysis; at "
                        "most 100)")
    p.add_argument("--ramp-hold", type=positive_float, default=4.0, metavar="T",
                   help="--ramp: duration of each constant-acceleration hold, in units of "
                        "T = sqrt(size/g) (default 4)")
    p.add_argument("--t-end", type=positive_float, default=3.0, metavar="S",
                   help="end of the output window [s] (default 3); the run goes on to rest or "
                        "collapse")
    p.add_argument("--dt-out", type=positive_float, default=0.005, metavar="S",
                   help="output sampling [s] (default 0.005)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png",
                   help="figure: the engine's equivalent rotation over the four-link phi(t), "
                        "every voussoir's rotation and the sliding at each joint")
    p.add_argument("--animate", metavar="FILE.gif",
                   help="animation of the engine's run beside the four-link one")
    p.set_defaults(func=run_dem)
    return p


def _progress(msg):
    print(msg, file=sys.stderr, flush=True)


def run_dem(args) -> int:
    from ..contact import import_pymunk
    from ..errors import ImpactModelError

    plot, animation = figure_arg(args.plot), animation_arg(args.animate)
    spec = motion_spec_from_args(args)
    if args.ramp and spec is not None:
        raise CLIError("--ramp: cannot be combined with a ground motion; give one")
    if not args.ramp and spec is None:
        raise CLIError("dem: give --ramp or a ground motion (--pulse KIND --amplitude A_G "
                       "--pulse-duration S, or --record FILE)")
    if args.ramp and (plot or animation):
        raise CLIError("--plot/--animate: apply to a ground motion, not to --ramp")
    settings = engine_settings_from_args(args)
    arch = arch_from_args(args)
    import_pymunk()
    quiet = args.json
    progress = None if quiet else _progress
    if args.ramp:
        from ..contact import ramp
        from ..statics.limit import limit_analysis
        from ..reports.contact import format_ramp, ramp_dict

        limit = limit_analysis(arch)
        res = ramp(arch, settings, progress=progress, limit=limit, lambda_max=args.ramp_max,
                   tol=args.ramp_tol, hold=args.ramp_hold)
        if args.json:
            emit_json(ramp_dict(res, limit))
        else:
            print(format_ramp(res, limit, arch))
        return 0
    from ..contact import engine_respond
    from ..reports.contact import engine_response_dict, format_engine_response
    from ..dynamics.response import prepare, respond

    motion = spec.build()
    # the engine uses no impact law; the four-link run beside it does: the impact options are
    # for that run only, and an impact law that cannot apply to this arch leaves it out (with
    # the reason) instead of stopping the engine's run
    fl, fl_note = None, None
    try:
        model = prepare(arch, impact_spec_from_args(args))
    except ImpactModelError as exc:
        why = " ".join(str(exc).split())
        model = prepare(arch, "momentum")  # its mechanisms give the equivalent rotation
        if args.impact is None and args.cv is None:  # the default law: the energy-consistent one
            fl_note = f"four-link model with the momentum impact law ({why})"
        else:
            fl_note = f"four-link model not run: {why}"
    res = engine_respond(arch, motion, settings, model=model, t_end=args.t_end,
                         dt_out=args.dt_out, progress=progress)
    if fl_note is None or fl_note.startswith("four-link model with"):
        fl = respond(model, motion, t_end=args.t_end, dt_out=args.dt_out)
    if plot:
        from ..reports.contactplots import save_engine_figure

        plot = save_engine_figure(res, fl, plot)
    if animation:
        from ..reports.contactplots import animate_engine

        animation = animate_engine(res, fl, arch, animation)
    if args.json:
        d = engine_response_dict(res, fl)
        if fl_note:
            d["four_link_note"] = fl_note
        emit_json(d)
        return 0
    print(format_engine_response(res, fl, arch, motion))
    if fl_note:
        print(f"  {fl_note}")
    for f in (plot, animation):
        if f:
            print(f"wrote {f}")
    return 0
