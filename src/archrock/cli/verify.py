"""``archrock verify``: the contact engine against the four-link model on a grid of pulses."""

from __future__ import annotations

import sys

from ._parser import CLIError, emit_json
from .dem import add_engine_options, engine_settings_from_args
from .options import add_geometry_options, arch_from_args, figure_arg


def _floats(text):
    import argparse

    try:
        vals = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text!r}") from None
    if not vals:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text!r}")
    return vals


def add_verify_parser(subparsers):
    p = subparsers.add_parser(
        "verify", help="contact engine vs four-link model on a grid of pulses",
        description="Runs the contact engine (pymunk) and the four-link model with the paper's "
                    "and the momentum impact laws on every pulse of a grid, tabulates their "
                    "collapse decisions and each model's first-collapse amplitude per duration.")
    add_geometry_options(p)
    add_engine_options(p)
    p.add_argument("--pulse", default="oppenheim", metavar="KIND",
                   help="pulse kind (default oppenheim: a for t_p, -a/2 for 2 t_p)")
    p.add_argument("--amplitudes", type=_floats, metavar="A1,A2,...",
                   default=[-0.5, -0.75, -1.0, -1.25, -1.5, -2.0, -2.5, -3.0],
                   help="pulse amplitudes [g], signed (default -0.5,...,-3)")
    p.add_argument("--durations", type=_floats, metavar="T1,T2,...", default=[0.1, 0.2, 0.4],
                   help="pulse durations [s] (default 0.1,0.2,0.4)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="figure of the first-collapse amplitudes")
    p.set_defaults(func=run_verify)
    return p


def run_verify(args) -> int:
    from ..contact import import_pymunk
    from ..reports.verification import format_verify
    from ..studies.verification import verify

    plot = figure_arg(args.plot)
    if any(a == 0 for a in args.amplitudes):
        raise CLIError("--amplitudes: allowed nonzero amplitudes [g]")
    if any(d <= 0 for d in args.durations):
        raise CLIError("--durations: allowed durations > 0 s")
    arch = arch_from_args(args)
    import_pymunk()
    progress = None if args.json else (lambda m: print(m, file=sys.stderr, flush=True))
    res = verify(arch, args.amplitudes, args.durations, pulse=args.pulse,
                 settings=engine_settings_from_args(args), progress=progress)
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
