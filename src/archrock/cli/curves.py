"""``archrock curves``: collapse-acceleration curves of pulses against their duration."""

from __future__ import annotations

import sys

from ..errors import ArchInputError
from ._parser import emit_json, interrupted_study
from .runsettings import cpu_only, gpu_ready, run_settings
from ._friction import add_friction_option
from .options import (PROGRESS_ESTIMATED, add_dynamics_option, add_geometry_options,
                      add_impact_options, add_output_options, add_random_arches_options,
                      add_run_options, add_scan_options, arch_from_args, figure_arg, folder_arg,
                      friction_mu, friction_words, impact_spec_from_args, spreads_for)


def add_curves_parser(subparsers):
    p = subparsers.add_parser(
        "curves", help="collapse-acceleration curves: first collapse amplitude against pulse duration",
        description="For each pulse duration t_p, scan the amplitude from the activation threshold "
                    "k to --a-max, bisect the first collapse to --tol, and report the survival "
                    "windows above it (collapse is not monotonic in the amplitude).")
    add_geometry_options(p)
    p.add_argument("--durations", default="0.1:1.0:10", metavar="LO:HI:N|A,B,...",
                   help="pulse durations t_p [s] (default 0.1:1.0:10)")
    add_scan_options(
        p, sign_choices=(-1, 1), n_scan=150,
        sign_help="sign of the amplitude (main lobe): -1 (xg'' < 0, opens M_l; default) or +1; "
                  "the first push except for ricker, whose first lobe is -0.446 a",
        tol_help="bisection tolerance on the collapse amplitude [g], 1e-9 to 0.1 (default 0.001)")
    add_random_arches_options(p, "random arches for quantile bands (0 = nominal only, default)")
    p.add_argument("--engine", choices=("batch", "respond"), default="batch",
                   help="batch (default): the scans and bisection steps of every arch and "
                        "duration in one parallel call each; respond: arch after arch (0.1.0's "
                        "path); the results are identical")
    add_run_options(
        p, workers="1: in-process (numba threads, default); N > 1: a local process pool (of the "
                   "batch engine's items, or of --engine respond's arches)",
        scheduler="batch engine: run on an existing Dask cluster (needs archrock[dask])",
        out="batch engine: keep every finished response in DIR (Parquet + manifest.json); the "
            "same command after an interruption resumes",
        device="cpu (default), gpu (the batch engine's sweeps, one response per GPU thread, "
               "in this process) or auto (the GPU where one is present and a round is large "
               "enough); docs/gpu.md")
    add_impact_options(p)
    add_dynamics_option(p, "each response")
    add_friction_option(p, "the routing of the dynamics and, where it runs, the contact "
                           "engine")
    add_output_options(p, progress=PROGRESS_ESTIMATED,
                       plot="write the curve (with bands) to a figure")
    p.set_defaults(func=run_curves)
    return p


def run_curves(args) -> int:
    from ..studies.curves import collapse_curve, ensemble_curve, parse_range
    from ..reports.curves import curves_summary, format_curves
    from ..dynamics.response import prepare

    gpu_ready(args)  # before any work
    plot = figure_arg(args.plot)
    nominal = arch_from_args(args)
    durations = parse_range(args.durations, "durations")
    if args.n_scan < 2:
        raise ArchInputError(f"n_scan: {args.n_scan}; allowed an integer >= 2")
    impact = impact_spec_from_args(args)
    from ..studies.enginestudy import choose_dynamics

    # the routing of respond, ensemble and assess at the command's one friction
    choice = choose_dynamics(nominal, args.dynamics, friction=friction_mu(args))
    if choice.engine:  # issue 19: one degree of freedom cannot follow this arch
        cpu_only(args, "curves by the contact engine")
        from .enginecurves import run_engine_curves

        return run_engine_curves(args, nominal, durations, choice, plot)
    out = folder_arg(args.out)
    settings = run_settings(args, out=out)
    if args.engine == "respond":
        if args.scheduler:
            raise ArchInputError("scheduler: run by the batch engine; allowed --scheduler with "
                                 "--engine batch")
        if out is not None:
            raise ArchInputError("out: kept by the batch engine; allowed --out with --engine "
                                 "batch")
    kw = dict(kind=args.pulse, sign=args.sign, a_max=args.a_max, n_scan=args.n_scan, tol=args.tol,
              engine=args.engine)
    band = None
    try:
        if args.samples > 0:
            band = ensemble_curve(nominal, args.samples, args.seed,
                                  spreads_for(args, nominal), durations, impact=impact,
                                  settings=settings, **kw)
            curve = band.nominal
        else:
            # one curve: arch after arch has no pool (the respond engine runs here)
            curve = collapse_curve(prepare(nominal, impact), durations, settings=(
                settings if args.engine == "batch" else settings.replace(workers=None)), **kw)
    except KeyboardInterrupt:
        return interrupted_study(out)
    if plot:
        from ..reports.plots import plot_collapse_curve

        plot_collapse_curve(curve, plot, band=band,
                            title=f"{nominal.name}: {args.pulse} pulse, sign {args.sign:+d}")
    applied = impact.resolved(nominal)
    about = dict(arch_name=nominal.name, pulse=args.pulse, sign=args.sign,
                 impact=impact, cv=applied.cv, note=applied.note)
    if args.json:
        emit_json({**curves_summary(curve, band, **about), "dynamics": choice.to_dict()})
        return 0
    print(format_curves(curve, band, **about))
    print(f"dynamics: four-link model ({choice.reason}); {friction_words(args)}")
    if plot:
        print(f"wrote {plot}", file=sys.stderr)
    return 0
