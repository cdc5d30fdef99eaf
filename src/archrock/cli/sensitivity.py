"""``archrock sensitivity``: Sobol indices of k_l, k_r and the collapse over random arches."""

from __future__ import annotations


from .fourlinkonly import add_fourlink_dynamics_option, check_fourlink
from .runsettings import run_settings
from ._parser import _int, emit_json, non_negative_int
from .options import (add_geometry_options, add_impact_options, add_motion_options,
                      add_output_options, add_spread_options, arch_from_args,
                      impact_spec_from_args, motion_spec_from_args, spreads_for)


def add_sensitivity_parser(subparsers):
    p = subparsers.add_parser(
        "sensitivity", help="Sobol indices: which irregularity drives the spread of k_l, k_r "
                            "and the collapse (SALib)",
        description="Saltelli's scheme on a Sobol sequence over the random arches' draws "
                    "(span, thickness, radius of each voussoir, joint tilt), grouped by kind, "
                    "voussoir or input, run on the batch engine; first-order and total indices "
                    "with bootstrap intervals (docs/ensemble.md). Needs the extra "
                    "'sensitivity' (SALib).")
    add_geometry_options(p)
    add_spread_options(p, tilt=True, strength=True)
    p.add_argument("--samples", type=_int, default=1024, metavar="N",
                   help="base samples, a power of two >= 16 (N x (groups + 2) arches; default "
                        "1024)")
    p.add_argument("--seed", type=non_negative_int, default=0,
                   help="seed of the scrambled Sobol sequence and the bootstrap (default 0)")
    p.add_argument("--by", choices=("kind", "voussoir", "input"), default="kind",
                   help="groups of inputs: each kind of irregularity (default), each voussoir, "
                        "or each draw alone")
    add_motion_options(p)
    p.add_argument("--limit-only", action="store_true",
                   help="k_l, k_r and k only (no ground motion; default: also the collapse under "
                        "the paper's pulse, a = -1 g, t_p = 0.2 s, or the motion given)")
    add_impact_options(p)
    add_output_options(p, progress="no progress lines on stderr")
    add_fourlink_dynamics_option(p)
    p.set_defaults(func=run_sensitivity)
    return p


def run_sensitivity(args) -> int:
    from ..reports.sensitivity import format_sensitivity, sensitivity_summary
    from ..studies.sensitivity import PAPER_PULSE, sobol_indices
    from ._parser import CLIError

    motion = motion_spec_from_args(args)
    if args.limit_only and motion is not None:
        raise CLIError("--limit-only: cannot be combined with a ground motion")
    if motion is None and not args.limit_only:
        motion = PAPER_PULSE
    nominal = arch_from_args(args)
    if not args.limit_only:  # the multipliers alone need no dynamics
        check_fourlink(nominal, args, "sensitivity")
    res = sobol_indices(nominal, spreads_for(args, nominal), args.samples, by=args.by,
                        motion=None if args.limit_only else motion,
                        impact=impact_spec_from_args(args), seed=args.seed,
                        settings=run_settings(args))
    if args.json:
        emit_json(sensitivity_summary(res))
    else:
        print(format_sensitivity(res))
    return 0
