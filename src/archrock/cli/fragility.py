"""``archrock fragility``: IDA and multiple-stripe fragility over accelerograms."""

from __future__ import annotations

import sys

from ..errors import ArchInputError
from ._parser import emit_json, interrupted_study, non_negative_int
from .fragilityfigure import fragility_figure
from .fourlinkonly import add_fourlink_dynamics_option, check_fourlink
from .runsettings import cpu_only, gpu_ready, run_settings
from .options import (PROGRESS_ESTIMATED, RECORDS_HELP, RECORDS_METAVAR, add_geometry_options,
                      add_impact_options, add_output_options, add_random_arches_options,
                      add_run_options, arch_from_args, figure_arg, folder_arg,
                      impact_spec_from_args, spreads_for)


def add_fragility_parser(subparsers):
    p = subparsers.add_parser(
        "fragility", help="IDA and multiple-stripe fragility over accelerograms (and random arches)",
        description="IM = PGA of the scaled record [g] (--im: PGV, Sa(T), Arias). IDA: per record (and arch), scan the scale "
                    "factors, bisect the first collapse, report survivals above it; lognormal fit "
                    "by moments (censored MLE when some never collapse). Multiple stripes at "
                    "--levels (default: 8 levels spanning the IDA first collapses): binomial MLE.")
    add_geometry_options(p)
    p.add_argument("--records", nargs="+", required=True, metavar=RECORDS_METAVAR,
                   help=RECORDS_HELP + "; each read once, its sha256 in the JSON")
    p.add_argument("--im", default="pga", metavar="pga|pgv|sa:T|arias|scale",
                   help="intensity measure of the fits, levels and plot: PGA [g] (default), PGV "
                        "[m/s], Sa(T, 5%%) [g] at period T [s], Arias intensity [m/s], or the "
                        "scale factor")
    p.add_argument("--units", choices=("g", "m/s2", "cm/s2"), default=None,
                   help="units of two-column records (default g)")
    p.add_argument("--scales", default="0.1:3:30", metavar="LO:HI:N|A,B,...",
                   help="IDA scale factors (default 0.1:3:30)")
    p.add_argument("--levels", default=None, metavar="LO:HI:N|A,B,...",
                   help="stripe IM levels (--im units; default: 8 levels around the IDA first "
                        "collapses)")
    add_random_arches_options(p, "random arches (0 = the nominal arch only, default)")
    add_impact_options(p)
    p.add_argument("--bootstrap", type=non_negative_int, default=200, metavar="N",
                   help="bootstrap resamples for confidence bands (0 = none, or >= 2; default 200)")
    p.add_argument("--engine", choices=("batch", "respond"), default="batch",
                   help="batch (default): every arch x record x scale of a search step in one "
                        "parallel call; respond: response after response (0.1.0's path); the "
                        "results are identical")
    add_run_options(p, workers="1: in-process (numba threads, default); N > 1: local process pool",
                    scheduler="run on an existing Dask cluster (needs archrock[dask])",
                    device="cpu (default), gpu (the batch engine's IDA and stripe sweeps, one "
                           "response per GPU thread, in this process) or auto (the GPU where "
                           "one is present and a round is large enough); docs/gpu.md")
    p.add_argument("--early-stop", action="store_true",
                   help="batch engine: end a response once the record is over and the arch's "
                        "energy is below every mechanism it can open (same collapse decisions "
                        "and peaks; impacts and time to rest are not followed)")
    p.add_argument("--out", metavar="DIR",
                   help="keep every finished response in DIR (Parquet + manifest.json); the same "
                        "command after an interruption resumes (batch engine)")
    add_output_options(p, progress=PROGRESS_ESTIMATED,
                       plot="write the fragility curves to a figure")
    add_fourlink_dynamics_option(
        p, help="auto (default): the four-link model where one degree of freedom follows the "
                "arch; the contact engine's IDA (no stripes, the nominal arch only) where it "
                "does not: piers that rock with the arch, joints that slide at --friction "
                "(docs/piers-dynamics.md); fourlink: the four-link model anyway, with a "
                "warning")
    p.set_defaults(func=run_fragility)
    return p


def run_fragility(args) -> int:
    from ..studies.curves import parse_range
    from ..groundmotion.intensity import parse_im
    from ..groundmotion.suite import read_records
    from ..studies.ida import default_stripe_levels, ida, msa, random_models
    from ..reports.fragility import format_fragility, fragility_summary
    from ..dynamics.response import prepare

    if args.bootstrap == 1:
        raise ArchInputError("bootstrap: 1; allowed 0 (no confidence bands) or an integer >= 2")
    gpu_ready(args)  # before any work
    plot = figure_arg(args.plot)
    nominal = arch_from_args(args)
    choice = check_fourlink(nominal, args, "fragility", engine_runs=True)
    if choice.engine:  # one degree of freedom cannot follow it: the IDA by the contact engine
        cpu_only(args, "fragility by the contact engine")
        from .enginefragility import run_engine_fragility

        return run_engine_fragility(args, nominal, choice, plot)
    if args.workers < 1:  # before any records are read
        raise ArchInputError(f"workers: {args.workers}; allowed an integer >= 1")
    if args.engine == "respond" and (args.workers > 1 or args.scheduler):
        raise ArchInputError("engine: 'respond' runs in this process only; allowed --workers "
                             "and --scheduler with --engine batch")
    im = parse_im(args.im)
    suite = read_records(args.records, units=args.units)
    records = list(suite.records)
    scales = parse_range(args.scales, "scales")
    impact = impact_spec_from_args(args)
    models = (random_models(nominal, args.samples, args.seed, spreads_for(args, nominal), impact)
              if args.samples > 0 else [prepare(nominal, impact)])
    boot = args.bootstrap
    out = folder_arg(args.out)
    if out is not None and args.engine == "respond":
        raise ArchInputError("out: kept by the batch engine; allowed --out with --engine batch")
    if args.early_stop and args.engine == "respond":
        raise ArchInputError("early-stop: a batch-engine option; allowed with --engine batch")
    run = dict(engine=args.engine, settings=run_settings(args, out=out))
    if args.engine == "batch":
        run.update(early_stop=args.early_stop)
    try:
        res_ida = ida(records, models, scales, im=im, n_boot=boot, seed=args.seed, **run)
        levels = (parse_range(args.levels, "levels") if args.levels
                  else default_stripe_levels(res_ida, scales, records))
        res_msa = msa(records, models, levels, im=im, n_boot=boot, seed=args.seed, **run)
    except KeyboardInterrupt:
        return interrupted_study(out)
    # the results first, on stdout, then the figure: a figure that fails loses nothing
    if args.json:
        emit_json(fragility_summary(res_ida, res_msa, arch_name=nominal.name, records=records,
                                    n_arches=len(models), impact=impact,
                                    cv=impact.resolved(nominal).cv, suite=suite,
                                    note=impact.resolved(nominal).note))
    else:
        print(format_fragility(res_ida, res_msa, arch_name=nominal.name, n_records=len(records),
                               n_arches=len(models), n_requested=args.samples))
    sys.stdout.flush()
    if plot and fragility_figure(res_ida, res_msa, plot) and not args.json:
        print(f"wrote {plot}", file=sys.stderr)
    return 0
