"""``archrock verify``: the contact engine against the four-link model on a grid of pulses."""

from __future__ import annotations


from .runsettings import run_settings
from ._parser import CLIError, _int, emit_json, finite_float, non_negative_int
from .dem import add_engine_options, engine_settings_from_args
from .options import (add_geometry_options, add_spread_options, arch_from_args, figure_arg,
                      spreads_for)


DEFAULT_AMPLITUDES = [-0.5, -0.75, -1.0, -1.25, -1.5, -2.0, -2.5, -3.0]
DEFAULT_DURATIONS = [0.1, 0.2, 0.4]


def _numbers(name: str, signed: bool):
    """argparse type of a number list, in every command's grammar (studies.curves.parse_range)."""
    import argparse

    def parse(text):
        from ..errors import ArchInputError
        from ..studies.curves import parse_range

        try:
            return [float(v) for v in parse_range(text, name, signed=signed)]
        except ArchInputError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
    return parse


def add_verify_parser(subparsers):
    p = subparsers.add_parser(
        "verify", help="contact engine vs four-link model on a grid of pulses",
        description="Runs the contact engine (pymunk) and the four-link model with the paper's "
                    "and the momentum impact laws on every pulse of a grid, tabulates their "
                    "collapse decisions and each model's first-collapse amplitude per duration. "
                    "With --samples N: the engine's activation and hinges against the four-link "
                    "model's mechanism (limit analysis) on N random arches around the given one, "
                    "arch by arch, with the disagreement rate and where it occurs.")
    add_geometry_options(p)
    add_engine_options(p)
    p.add_argument("--pulse", default="oppenheim", metavar="KIND",
                   help="pulse kind (default oppenheim: a for t_p, -a/2 for 2 t_p)")
    p.add_argument("--amplitudes", type=_numbers("amplitudes", signed=True), metavar="A1,A2,...",
                   default=list(DEFAULT_AMPLITUDES),
                   help="pulse amplitudes [g], signed (default -0.5,...,-3)")
    p.add_argument("--durations", type=_numbers("durations", signed=False), metavar="T1,T2,...",
                   default=list(DEFAULT_DURATIONS),
                   help="pulse durations [s] (default 0.1,0.2,0.4)")
    g = p.add_argument_group("over an ensemble", "--samples N: random arches around the given "
                                                 "one instead of the pulse grid")
    g.add_argument("--samples", type=non_negative_int, default=0, metavar="N",
                   help="random arches to check (default 0: the pulse grid on the arch itself)")
    g.add_argument("--seed", type=non_negative_int, default=0, help="random seed (default 0)")
    g.add_argument("--workers", type=_int, default=1, metavar="N",
                   help="processes, one arch per task (default 1)")
    g.add_argument("--k-tol", type=finite_float, default=None, metavar="F",
                   help="relative difference of the multipliers that counts as a disagreement, "
                        "0 < F < 1 (default 0.05)")
    g.add_argument("--ramp-tol", type=finite_float, default=None, metavar="F",
                   help="relative width of the ramp's final bracket (default 0.005)")
    add_spread_options(g, tilt=True)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="figure of the first-collapse amplitudes")
    p.set_defaults(func=run_verify)
    return p


def _run_ensemble(args) -> int:
    from ..contact import require_engine
    from ..geometry.sampling import ArchSampler
    from ..reports.verification import format_verify_ensemble
    from ..studies.verification import DEFAULT_K_TOL, verify_ensemble

    if args.plot:
        raise CLIError("--plot: the pulse grid's figure; not with --samples")
    for flag, value, default in (("--amplitudes", args.amplitudes, DEFAULT_AMPLITUDES),
                                 ("--durations", args.durations, DEFAULT_DURATIONS),
                                 ("--pulse", args.pulse, "oppenheim")):
        if value != default:
            raise CLIError(f"{flag}: the pulse grid's; not with --samples (the ensemble is "
                           f"checked by the engine's ramp)")
    nominal = arch_from_args(args)
    sampler = ArchSampler(nominal, spreads_for(args, nominal), args.seed)
    require_engine(engine_settings_from_args(args))
    # progress goes to stderr even with --json (stdout holds only the JSON), as in ensemble
    opts = {} if args.ramp_tol is None else {"tol": args.ramp_tol}
    res = verify_ensemble(sampler, args.samples, settings=engine_settings_from_args(args),
                          k_tol=DEFAULT_K_TOL if args.k_tol is None else args.k_tol,
                          ramp_options=opts, run_settings=run_settings(args))
    if args.json:
        emit_json(res.to_dict())
    else:
        print(format_verify_ensemble(res))
    return 0


def run_verify(args) -> int:
    from ..contact import require_engine
    from ..reports.verification import format_verify
    from ..studies.verification import verify

    if args.samples:
        return _run_ensemble(args)
    for flag, given in (("--workers", args.workers != 1), ("--k-tol", args.k_tol is not None),
                        ("--ramp-tol", args.ramp_tol is not None)):
        if given:
            raise CLIError(f"{flag}: applies with --samples N (N >= 1) only")
    plot = figure_arg(args.plot)
    if any(a == 0 for a in args.amplitudes):
        raise CLIError("--amplitudes: allowed nonzero amplitudes [g]")
    if any(d <= 0 for d in args.durations):
        raise CLIError("--durations: allowed durations > 0 s")
    arch = arch_from_args(args)
    require_engine(engine_settings_from_args(args))
    # progress goes to stderr even with --json (stdout holds only the JSON), as in ensemble
    res = verify(arch, args.amplitudes, args.durations, pulse=args.pulse,
                 settings=engine_settings_from_args(args),
                 run_settings=run_settings(args, workers=False))
    if plot:
        from ..reports.contactplots import save_verify_figure

        plot = save_verify_figure(res, plot)
    if args.json:
        emit_json(res.to_dict())
        return 0
    print(format_verify(res))
    if plot:
        print(f"wrote {plot}")
    return 0
