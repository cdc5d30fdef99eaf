"""``archrock ensemble``: Monte Carlo over random arches (multipliers, hinges, P(collapse))."""

from __future__ import annotations

from ..errors import ArchInputError
from ._parser import CLIError, _int, emit_json, finite_float
from .options import (add_geometry_options, add_motion_options, add_spread_options,
                      arch_from_args, motion_from_args, spreads)


def add_ensemble_parser(subparsers):
    p = subparsers.add_parser(
        "ensemble", help="Monte Carlo over random arches around a nominal one: k_l, k_r, hinge "
                         "patterns and, under a ground motion, the probability of collapse",
        description="Random arches (spans, thicknesses, radii uniform around the nominal arch) in "
                    "batches with independent random streams (numpy SeedSequence), so results "
                    "depend on --seed and --batch-size only, never on --workers. With --out DIR "
                    "every finished batch is kept (Parquet + manifest.json) and a re-run resumes.")
    add_geometry_options(p)
    p.add_argument("--samples", type=_int, default=1000, metavar="N",
                   help="number of random arches, >= 1 (default 1000)")
    p.add_argument("--seed", type=_int, default=0, help="random seed, integer >= 0 (default 0)")
    add_spread_options(p)
    p.add_argument("--batch-size", type=_int, default=500, metavar="B",
                   help="samples per batch and random stream, >= 1 (default 500)")
    p.add_argument("--workers", type=_int, default=1, metavar="N",
                   help="1: in-process (numba threads, default); N > 1: local process pool")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the batches on an existing Dask cluster (needs archrock[dask])")
    p.add_argument("--out", metavar="DIR",
                   help="folder for batches/*.parquet and manifest.json; resumes if it exists")
    add_motion_options(p)
    # the ensemble's own impact choices: its default applies the nominal arch's c_v to every sample
    g = p.add_argument_group("impact", "coefficient of restitution at each impact")
    g.add_argument("--impact", choices=("nominal-paper", "paper", "momentum"), default=None,
                   help="nominal-paper (default, the paper's choice): c_v of the nominal arch with "
                        "the 'paper' model, applied to every sample; paper / momentum: per "
                        "geometry ('paper' geometries that gain energy are reported as failed)")
    g.add_argument("--cv", type=finite_float, default=None, metavar="CV",
                   help="fixed coefficient of restitution, 0 < cv <= 1 (kinetic energy x cv^2)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="histograms of k_l and k_r")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run_ensemble_cmd)
    return p


def _ensemble_motion(args):
    from ..ensemble import pulse_description, record_description

    motion = motion_from_args(args)  # validates the options (one-line errors)
    if motion is None:
        return None
    if args.record:
        return record_description(args.record, args.units, args.scale)
    return pulse_description(args.pulse or "oppenheim", args.amplitude, args.pulse_duration)


def run_ensemble_cmd(args) -> int:
    from ..ensemble import PAPER_RANDOM_ARCHES, EnsembleConfig, run_ensemble
    from ..reports.ensemble import format_ensemble

    if args.workers < 1:
        raise ArchInputError(f"workers: {args.workers}; allowed an integer >= 1")
    if args.cv is not None and args.impact is not None:
        raise CLIError("--cv: cannot be combined with --impact; choose one")
    nominal = arch_from_args(args)
    impact = {"impact": "fixed", "cv": args.cv} if args.cv is not None else \
        {"impact": args.impact or "nominal-paper"}
    config = EnsembleConfig.from_arch(nominal, samples=args.samples, seed=args.seed,
                                      batch_size=args.batch_size, motion=_ensemble_motion(args),
                                      **spreads(args), **impact)
    result = run_ensemble(config, out_dir=args.out, workers=args.workers,
                          scheduler=args.scheduler, progress=not args.no_progress)
    summary = result.summary()
    if args.plot:
        from ..plots import plot_multiplier_histograms

        ref = {"nominal": (summary["nominal"]["k_l"], summary["nominal"]["k_r"]),
               **PAPER_RANDOM_ARCHES}
        plot_multiplier_histograms(result.frame, args.plot, reference=ref)
    if args.json:
        emit_json(summary)
        return 0
    print(format_ensemble(summary, nominal.name))
    if args.out:
        print(f"results in {args.out}")
    if args.plot:
        print(f"wrote {args.plot}")
    return 0
