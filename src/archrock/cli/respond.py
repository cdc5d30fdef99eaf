"""``archrock respond``: the rocking response of one arch to one ground motion."""

from __future__ import annotations

from ._parser import emit_json, finite_float, positive_float
from .options import (add_geometry_options, add_impact_options, add_motion_options,
                      animation_arg, figure_arg, model_from_args, motion_from_args)


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
                   help="rotation limit as a multiple of the unstable rotation (> 1): where the "
                        "integration of a collapse stops (t_limit); the collapse time, the last "
                        "passage of the unstable rotation, does not depend on it")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png",
                   help="write a figure of the motion and response; it runs to --t-end or, when "
                        "the run ends later (at rest, or at the rotation limit after a collapse), "
                        "to that end plus 5%%, but at most to 2 x --t-end or 10 s after the ground "
                        "motion, whichever is later")
    p.add_argument("--animate", metavar="FILE.gif",
                   help="write an animation of the mechanism (same time span as --plot)")
    p.set_defaults(func=run_respond)
    return p


def run_respond(args) -> int:
    from ..reports.response import format_response
    from ..dynamics.response import prepare, respond

    plot, animation = figure_arg(args.plot), animation_arg(args.animate)
    motion = motion_from_args(args)
    model = model_from_args(args)
    if args.limit_factor is not None:
        model = prepare(model.arch, model.impact, limit_factor=args.limit_factor, limit=model.limit)
    res = respond(model, motion, t_end=args.t_end, dt_out=args.dt_out, integrator=args.integrator)
    shown = res
    if plot or animation:
        from ..reports.plots import figure_t_end

        # the figures show the run to rest or collapse, also past --t-end (capped); the JSON and
        # the report keep --t-end.  The run itself does not depend on the output window.
        t_fig = figure_t_end(res, args.t_end)
        if t_fig > res.time[-1]:
            shown = respond(model, motion, t_end=t_fig, dt_out=args.dt_out,
                            integrator=args.integrator)
    if plot:
        from ..reports.plots import save_response_figure

        plot = save_response_figure([shown], plot, labels=[model.arch.name])
    if animation:
        from ..reports.animate import animate_response

        animation = animate_response(shown, animation)
    if args.json:
        emit_json(res.to_dict())
        return 0
    print(format_response(res, model, motion))
    if not res.single_dof_valid:
        # issue 19: the number above is the four-link model's, which cannot follow this arch
        print(f"WARNING single degree of freedom not valid: {res.single_dof.reason}")
    for f in (plot, animation):
        if f:
            print(f"wrote {f}")
    return 0
