"""``archrock respond``: the response of one arch to one ground motion, by the model that
holds for it (issue 30): the four-link model where one degree of freedom follows the arch, the
contact engine otherwise (:func:`archrock.studies.enginestudy.choose_dynamics`)."""

from __future__ import annotations

import sys

from ..errors import ArchInputError, GeometryOutcome, NotFourHingeError
from ._parser import emit_json, finite_float
from ._friction import add_friction_option
from .options import (add_dynamics_option, add_geometry_options, add_impact_options,
                      add_motion_options, add_output_options, add_window_options, animation_arg,
                      arch_from_args, figure_arg, friction_mu, friction_words, model_from_args,
                      motion_from_args, say_written)


def add_respond_parser(subparsers):
    p = subparsers.add_parser(
        "respond", help="response of an arch to a ground motion (four-link mechanism, or the "
                        "contact engine where one degree of freedom cannot follow the arch)",
        description="Four-link model: activation by the paper's eq. (1), motion in M_l / M_r, "
                    "impacts, rest or collapse; signed response +phi in M_l, -phi in M_r. "
                    "Where it does not hold (piers that rock with the arch, joints that slide "
                    "at --friction) the contact engine answers (--dynamics; needs pymunk: "
                    "pip install 'archrock[dem]').")
    add_geometry_options(p)
    add_motion_options(p, required=True)
    add_impact_options(p)
    add_dynamics_option(p)
    add_friction_option(p, "the routing of the dynamics (the joints slide where the four-link "
                           "collapse needs more) and the contact engine")
    add_window_options(p, "the outcome covers the whole ground motion and the free motion "
                          "after it")
    p.add_argument("--integrator", choices=("fast", "reference"), default="fast",
                   help="fast: RK4 + events (numba); reference: scipy DOP853 (default fast)")
    p.add_argument("--limit-factor", type=finite_float, default=None, metavar="F",
                   help="rotation limit as a multiple of the unstable rotation (> 1): where the "
                        "integration of a collapse stops (t_limit); the collapse time, the last "
                        "passage of the unstable rotation, does not depend on it")
    add_output_options(
        p, progress="no progress on stderr (the engine's run, the animation's frames)",
        plot="write a figure of the motion and response; it runs to --t-end or, when the run "
                "ends later (at rest, or at the rotation limit after a collapse), to that end "
                "plus 5%%, but at most to 2 x --t-end or 10 s after the ground motion, "
                "whichever is later",
        animate="write an animation of the mechanism (same time span as --plot)")
    p.set_defaults(func=run_respond)
    return p


def _progress(args):
    """The progress sink of the command: lines on stderr, or None (--no-progress, --json)."""
    if args.no_progress or args.json:
        return None
    return lambda line: print(line, file=sys.stderr, flush=True)


def run_respond(args) -> int:
    from ..studies.enginestudy import choose_dynamics

    plot, animation = figure_arg(args.plot), animation_arg(args.animate)
    motion = motion_from_args(args)
    arch = arch_from_args(args)
    choice = choose_dynamics(arch, args.dynamics, friction=friction_mu(args))
    if choice.engine:
        return _run_engine(args, arch, motion, choice, plot, animation)
    return _run_fourlink(args, arch, motion, choice, plot, animation)


def _run_fourlink(args, arch, motion, choice, plot, animation) -> int:
    """The four-link model's answer; where it does not hold (asked for by name) under the
    heading "four-link model: not valid here (...)", never as an outcome line alone."""
    from ..reports.response import format_response, not_valid_reason
    from ..dynamics.response import prepare, respond

    model = model_from_args(args, arch)
    if args.limit_factor is not None:
        model = prepare(model.arch, model.impact, limit_factor=args.limit_factor, limit=model.limit)
    res = respond(model, motion, t_end=args.t_end, dt_out=args.dt_out, integrator=args.integrator)
    why_not = not_valid_reason(choice)
    if why_not is None and not res.single_dof_valid:  # the model's own check, as before
        why_not = f"single degree of freedom not valid: {res.single_dof.reason}"
    shown = res
    if plot or animation:
        from ..reports.plots import figure_t_end

        # the figures show the run to rest or collapse, also past --t-end (capped); the JSON and
        # the report keep --t-end.  The run itself does not depend on the output window.
        t_fig = figure_t_end(res, args.t_end)
        if t_fig > res.time[-1]:
            shown = respond(model, motion, t_end=t_fig, dt_out=args.dt_out,
                            integrator=args.integrator)
    label = model.arch.name + ("" if why_not is None else " (four-link: not valid here)")
    if plot:
        from ..reports.plots import save_response_figure

        plot = save_response_figure([shown], plot, labels=[label])
    if animation:
        from ..reports.animate import animate_response

        animation = animate_response(shown, animation, progress=_progress(args))
    if args.json:
        from ..reports.contact import blocks_count

        d = {"model": "fourlink", "dynamics": choice.to_dict(),
             "blocks": blocks_count(arch), **res.to_dict()}
        d["valid_here"] = why_not is None
        d["not_valid_reason"] = why_not
        emit_json(d)
        return 0
    text = format_response(res, model, motion)
    head = [f"dynamics: four-link model ({choice.reason})", friction_words(args)]
    if why_not is None:
        # the report as before, then the model that gave it and the friction it assumed
        print("\n".join([text] + head))
    else:
        # issue 30: a model the same output calls invalid gives no bare answer line
        print(f"four-link model: not valid here ({why_not})")
        if choice.requested == "fourlink":  # its reason repeats the heading's
            head[0] = "dynamics: four-link model, asked for by name (--dynamics fourlink)"
        body = [("four-link outcome (not valid here):" + line[len("outcome:"):])
                if line.startswith("outcome:") else line for line in text.splitlines()]
        print("\n".join("  " + line for line in head + body))
        print("  (the governing answer on this arch is the contact engine's: --dynamics auto)")
    say_written(plot, animation)
    return 0


def _four_link_options(args) -> list:
    """The four-link model's options given on a run the engine answers (said, not silently
    dropped)."""
    given = [("--impact", args.impact), ("--impact-on", args.impact_on), ("--cv", args.cv),
             ("--literal-cv", args.literal_cv or None), ("--limit-factor", args.limit_factor),
             ("--integrator", None if args.integrator == "fast" else args.integrator)]
    return [flag for flag, v in given if v is not None]


def _engine_settings(args, choice):
    """The engine's settings at the command's one friction; --friction none cannot be run."""
    from ..contact import EngineSettings

    if friction_mu(args) is None:
        raise ArchInputError(
            f"friction: none (sliding excluded) cannot be modelled by the contact engine, which "
            f"this arch needs ({choice.reason}); allowed a finite number > 0 (a large one, e.g. "
            f"--friction 10, for joints that hardly slide), or --dynamics fourlink for the "
            f"four-link answer, labelled not valid here")
    return EngineSettings(friction=friction_mu(args))


def _run_engine(args, arch, motion, choice, plot, animation) -> int:
    """The contact engine's answer (the model that holds where one degree of freedom cannot
    follow the arch, or asked for by name); no four-link number beside it."""
    from ..contact import require_engine
    from ..contact.motion import engine_respond
    from ..dynamics.response import prepare
    from ..reports.response import format_engine_outcome
    from ..studies.enginestudy import EngineRun

    settings = _engine_settings(args, choice)
    try:
        require_engine(settings)
    except ImportError:
        raise GeometryOutcome(
            f"respond: this arch needs the contact engine ({choice.reason}), which needs "
            f"pymunk: pip install 'archrock[dem]'; or give --dynamics fourlink for the "
            f"four-link answer, labelled not valid here") from None
    run = EngineRun(settings=settings)  # the studies' free motion and collapse criterion
    try:
        model = prepare(arch, "momentum")  # its limit mechanisms give the equivalent rotation
    except NotFourHingeError:  # lift-off governs: the engine reports its largest rotation
        model = None
    res = engine_respond(arch, motion, settings, model=model, t_end=args.t_end,
                         dt_out=args.dt_out, t_free=run.t_free,
                         collapse_drop=run.collapse_drop, progress=_progress(args))
    if plot:
        from ..reports.contactplots import save_engine_figure

        from ..reports.contact import blocks_names

        plot = save_engine_figure(res, None, plot, names=blocks_names(arch))
    if animation:
        from ..reports.contactplots import animate_engine

        animation = animate_engine(res, None, arch, animation, progress=_progress(args))
    unused = _four_link_options(args)
    if args.json:
        from ..reports.contact import blocks_count

        emit_json({"model": "engine", "dynamics": choice.to_dict(), "arch": arch.name,
                   "blocks": blocks_count(arch), "engine_run": run.to_dict(),
                   "unused_options": unused, **res.to_dict()})
        return 0
    print(format_engine_outcome(res, arch, motion, choice, friction_words(args)))
    if unused:
        print(f"not used by the contact engine (four-link options): {', '.join(unused)}")
    say_written(plot, animation)
    return 0
