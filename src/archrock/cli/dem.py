"""``archrock dem``: the arch as rigid voussoirs in a contact engine (pymunk), beside the
four-link model: activation by a ramp (--ramp) or the response to a pulse or record."""

from __future__ import annotations

import sys

from ._parser import CLIError, emit_json, finite_float, positive_float
from .options import (add_geometry_options, add_impact_options, add_motion_options,
                      add_output_options, add_window_options, animation_arg, arch_from_args,
                      figure_arg, impact_spec_from_args, motion_spec_from_args, say_written)


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
    g.add_argument("--engine", choices=("archrock", "pymunk"), default="archrock",
                   help="archrock: archrock's own nonsmooth contact dynamics (default); pymunk: "
                        "the soft-contact game engine, kept as a cross-check (pip install "
                        "'archrock[dem]')")
    g.add_argument("--steps-per-T", type=positive_float, default=None, metavar="N",
                   help="time steps per T = sqrt(size/g) (default 400)")
    g.add_argument("--iterations", type=int, default=None, metavar="N",
                   help="--engine pymunk: impulse-solver iterations per step (default 40)")
    g.add_argument("--outline-tol", type=finite_float, default=None, metavar="F",
                   help="--engine pymunk: largest deviation of the contact shapes from a "
                        "voussoir's outline, as a "
                        "fraction of the size, 0..0.01 (default 2e-3; 0: the fine cut)")
    return p


def engine_settings_from_args(args):
    from ..contact import EngineSettings

    kw = {"friction": args.friction, "restitution": args.restitution,
          "engine": getattr(args, "engine", None) or "archrock"}
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
                    "and the equivalent four-link rotation beside `respond`; --push: a "
                    "support moved slowly (spread, settlement, close). Needs pymunk "
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
    p.add_argument("--push", choices=("spread", "settlement", "close", "rotate"), default=None,
                   help="move a support slowly (a kinematic abutment): the thrust on it, the "
                        "hinges and the displacement capacity (docs/supports-engine.md)")
    p.add_argument("--push-side", choices=("right", "left", "both"), default="right",
                   help="--push: the support that moves (both: each by half a spread, or both "
                        "settle; default right)")
    p.add_argument("--push-rate", type=positive_float, default=0.005, metavar="R",
                   help="--push: support speed in sizes per T = sqrt(size/g) (default 0.005)")
    p.add_argument("--push-max", type=positive_float, default=None, metavar="M",
                   help="--push: the largest displacement tried [m] (default half the size)")
    add_window_options(p, "the run goes on to rest or collapse")
    add_output_options(
        p, progress="no progress on stderr (the engine's run, the animation's frames)",
        plot="figure: the engine's equivalent rotation over the four-link phi(t), every "
             "voussoir's rotation and the sliding at each joint",
        animate="animation of the engine's run beside the four-link one")
    p.set_defaults(func=run_dem)
    return p


def _progress(msg):
    print(msg, file=sys.stderr, flush=True)


def format_push(res, arch) -> str:
    """The push's result for people: thrust, hinges, capacity, cost."""
    from ..statics.thrust import thrust_range

    tr = thrust_range(arch)
    kind = {"spread": "spreads", "close": "closes", "settlement": "settles",
            "rotate": "turns outward about its foot (d = rotation x size)"}[res.movement]
    side = "both supports" if res.side == "both" else f"the {res.side} support"
    lines = [f"contact engine: {side} {kind} at {res.run['speed']:.4g} m/s "
             f"(rate {res.run['rate']:g} size per T)",
             f"  thrust at rest {res.thrust_rest:.6g} N/m; thrust range (LP) "
             f"{tr.thrust_min:.6g} .. {tr.thrust_max:.6g} N/m"]
    if res.thrust_start is not None:
        lines.append(f"  thrust once the hinges open (at d = 0) {res.thrust_start:.6g} N/m")
    if res.hinges:
        lines.append(f"  hinges at the first opening (d = {res.opening_displacement:.4g} m): "
                     f"{'-'.join(res.hinges)}")
    if res.collapsed:
        lo, hi = res.capacity_bracket
        if res.movement == "rotate":
            lines.append(f"  rotation capacity {res.capacity / res.run['size']:.4g} rad")
        lines.append(f"  displacement capacity {res.capacity:.4g} m (held: rests at "
                     f"{lo:.4g}, moves on at {hi:.4g}; by {res.collapse_by}); collapse hinges "
                     f"{'-'.join(res.collapse_hinges) or '-'}")
    else:
        lines.append(f"  stands up to d = {res.run['max_displacement']:.4g} m (--push-max)")
    lines.append(f"  crown drop at the end {res.crown_drop[-1]:.4g} m; KE/dPE at most "
                 f"{res.ke_ratio if res.ke_ratio is not None else float('nan'):.3g} "
                 f"({'quasi-static' if res.quasi_static else 'check the rate'})")
    lines.append(f"  simulated {res.simulated_seconds:.1f} s, wall {res.wall_seconds:.1f} s")
    return "\n".join(lines)


def _run_push(args) -> int:
    from ..contact import push_support, require_engine

    settings = engine_settings_from_args(args)
    arch = arch_from_args(args)
    # a moved support runs on pymunk's kinematic bodies (archrock's engine has fixed supports)
    settings = settings.replace(engine="pymunk")
    require_engine(settings)
    res = push_support(arch, args.push, args.push_side, settings, rate=args.push_rate,
                       max_displacement=args.push_max,
                       progress=None if args.json or args.no_progress else _progress,
                       pivot_depth=getattr(args, "pivot_depth", None) or 0.0)
    if args.json:
        emit_json(res.to_dict())
    else:
        print(format_push(res, arch))
    return 0


def run_dem(args) -> int:
    from ..contact import require_engine
    from ..errors import ArchrockError, ImpactModelError, NotFourHingeError

    plot, animation = figure_arg(args.plot), animation_arg(args.animate)
    spec = motion_spec_from_args(args)
    if args.push is not None:
        if args.ramp or spec is not None or plot or animation:
            raise CLIError("--push: cannot be combined with --ramp, a ground motion, --plot or "
                           "--animate; give one")
        return _run_push(args)
    if args.ramp and spec is not None:
        raise CLIError("--ramp: cannot be combined with a ground motion; give one")
    if not args.ramp and spec is None:
        raise CLIError("dem: give --ramp or a ground motion (--pulse KIND --amplitude A_G "
                       "--pulse-duration S, or --record FILE|SUITE/ID)")
    if args.ramp and (plot or animation):
        raise CLIError("--plot/--animate: apply to a ground motion, not to --ramp")
    settings = engine_settings_from_args(args)
    arch = arch_from_args(args)
    require_engine(settings)
    if arch.fc is not None:  # never a silent answer without the strength asked for
        print(f"archrock: note: the contact engine's blocks are rigid and do not crush: "
              f"f_c = {arch.fc:g} MPa is not in its answer; the limit analysis and the "
              f"four-link model with f_c are (archrock limit --fc, archrock respond --fc; "
              f"docs/crushing-dynamics.md)", file=sys.stderr)
    quiet = args.json or args.no_progress
    progress = None if quiet else _progress
    if args.ramp:
        from ..contact import ramp
        from ..statics.limit import limit_analysis
        from ..reports.contact import format_ramp, ramp_dict

        from ..statics.friction import friction_analysis

        limit = limit_analysis(arch)
        res = ramp(arch, settings, progress=progress, limit=limit, lambda_max=args.ramp_max,
                   tol=args.ramp_tol, hold=args.ramp_hold)
        try:  # the reference where the joints slide first; the table states which it is
            friction = friction_analysis(arch, settings.friction)
        except ArchrockError:
            friction = None
        if args.json:
            emit_json(ramp_dict(res, limit, friction))
        else:
            print(format_ramp(res, limit, arch, friction))
        return 0
    from ..contact import engine_respond
    from ..reports.contact import engine_response_dict, format_engine_response, four_link_label
    from ..dynamics.response import prepare, respond
    from ..studies.enginestudy import choose_dynamics

    # the routing respond and the studies apply at this friction: where it sends the arch to
    # the engine, the four-link run beside it is labelled not valid here
    choice = choose_dynamics(arch, "auto", friction=settings.friction)

    motion = spec.build()
    # the engine uses no impact law; the four-link run beside it does: the impact options are
    # for that run only, and an impact law that cannot apply to this arch leaves it out (with
    # the reason) instead of stopping the engine's run
    fl, fl_note = None, None
    try:
        model = prepare(arch, impact_spec_from_args(args))
    except NotFourHingeError as exc:  # lift-off governs: the engine alone follows the arch
        model = None
        fl_note = f"four-link model not run: {' '.join(str(exc).split())}"
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

        from ..reports.contact import blocks_names

        plot = save_engine_figure(res, fl, plot, names=blocks_names(arch),
                                  four_link_label=four_link_label(choice, short=True))
        if progress:
            progress(f"figure: wrote {plot} (100%)")
    if animation:
        from ..reports.contactplots import animate_engine

        animation = animate_engine(res, fl, arch, animation, progress=progress,
                                   four_link_label=four_link_label(choice, short=True))
    if args.json:
        d = engine_response_dict(res, fl, choice)
        if fl_note:
            d["four_link_note"] = fl_note
        emit_json(d)
        return 0
    print(format_engine_response(res, fl, arch, motion, choice))
    if fl_note:
        print(f"  {fl_note}")
    say_written(plot, animation)
    return 0
