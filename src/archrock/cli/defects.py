"""``archrock defects``: the defect map of one arch (which voussoir or joint, if damaged,
costs the most capacity)."""

from __future__ import annotations


from .fourlinkonly import add_fourlink_dynamics_option, check_fourlink
from .runsettings import run_settings
from ._parser import emit_json, finite_float, positive_float
from .options import (add_geometry_options, add_impact_options, add_output_options,
                      add_scan_options, arch_from_args, figure_arg)


def add_defects_parser(subparsers):
    p = subparsers.add_parser(
        "defects", help="defect map: the capacity lost when each voussoir (or joint) in turn "
                        "is damaged",
        description="Apply one defect to each voussoir (thickness) or joint (tilt, mortar) in "
                    "turn: k_l, k_r and the hinges of each damaged arch, the capacity lost "
                    "(drop of min(k_l, k_r)) and, with --pulse-duration, the first collapse "
                    "amplitude of a pulse (docs/defects.md).")
    add_geometry_options(p)
    g = p.add_argument_group("defect", "the defect applied to each voussoir or joint in turn")
    g.add_argument("--kind", choices=("thickness", "tilt", "mortar"), default="thickness",
                   help="thickness: a voussoir keeps --value of its thickness; tilt: a joint "
                        "turns by --value degrees; mortar: a joint has no mortar over --value "
                        "of its contact (default thickness)")
    g.add_argument("--value", type=finite_float, default=None, metavar="X",
                   help="thickness: remaining fraction, 0 < X < 1 (default 0.7); tilt: degrees, "
                        "-45 < X < 45 (default 5); mortar: missing fraction, 0 < X < 1 "
                        "(default 0.3)")
    g.add_argument("--side", choices=("centreline", "intrados", "extrados"), default=None,
                   help="thickness: where the masonry is lost (default centreline); mortar: the "
                        "face the missing depth is measured from (default intrados)")
    # the 0.5 spellings of --side, one per kind
    g.add_argument("--at", choices=("centreline", "intrados", "extrados"), default=None,
                   help="thickness: the old name of --side")
    g.add_argument("--from", dest="from_", choices=("intrados", "extrados"), default=None,
                   help="mortar: the old name of --side")
    m = p.add_argument_group("pulse", "with --pulse-duration: the first collapse amplitude of "
                                      "each damaged arch (archrock curves' scan and bisection)")
    m.add_argument("--pulse-duration", type=positive_float, default=None, metavar="S",
                   help="pulse duration t_p [s] (e.g. 0.2, the paper's)")
    add_scan_options(
        m, sign_choices=(-1, 0, 1), n_scan=60, tol_help="bisection tolerance [g] (default 0.001)",
        sign_help="sign of the amplitude: -1 (opens M_l; default), +1 (opens M_r) or 0 (both: "
                  "the smaller first collapse amplitude of the two)")
    add_impact_options(p)
    add_output_options(
        p, plot="write the arch coloured by the capacity lost at each voussoir or joint",
        progress="no progress lines on stderr")
    add_fourlink_dynamics_option(p)
    p.set_defaults(func=run_defects)
    return p


def run_defects(args) -> int:
    from ..studies.defectmap import defect_map
    from ..reports.defects import defects_summary, format_defects
    from ._parser import CLIError
    from .options import impact_spec_from_args

    plot = figure_arg(args.plot)
    if args.at is not None and args.kind != "thickness":
        raise CLIError("--at: applies to --kind thickness")
    if args.from_ is not None and args.kind != "mortar":
        raise CLIError("--from: applies to --kind mortar")
    if args.n_scan < 2:
        raise CLIError(f"--n-scan: {args.n_scan}; allowed an integer >= 2")
    arch = arch_from_args(args)
    if args.pulse_duration is not None:  # the multipliers alone need no dynamics
        check_fourlink(arch, args, "defects")
    impact = impact_spec_from_args(args)
    given = [v for v in (args.side, args.at, args.from_) if v is not None]
    if len(given) > 1:
        raise CLIError("--side: given more than once (--at and --from are its old names)")
    if args.kind == "tilt" and given:
        raise CLIError("--side: a tilted joint has no side; allowed with --kind thickness or "
                       "mortar")
    side = given[0] if given else ""
    dmap = defect_map(arch, args.kind, args.value, side, pulse_duration=args.pulse_duration,
                      pulse_kind=args.pulse, sign=args.sign, impact=impact, a_max=args.a_max,
                      n_scan=args.n_scan, tol=args.tol,
                      settings=run_settings(args, progress=args.pulse_duration is not None))
    if plot:
        from ..reports.plots import plot_defect_map

        plot_defect_map(dmap, plot)
    if args.json:
        emit_json(defects_summary(dmap, impact))
        return 0
    print(format_defects(dmap))
    if plot:
        print(f"wrote {plot}")
    return 0
