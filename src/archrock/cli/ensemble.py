"""``archrock ensemble``: Monte Carlo over random arches (multipliers, hinges, P(collapse))."""

from __future__ import annotations

import sys
from pathlib import Path

from ._parser import EXIT_INTERRUPTED, PROG, CLIError, _int, emit_json
from .runsettings import run_settings
from ._friction import add_friction_option
from .options import (DEVICE_HELP, add_dynamics_option, add_geometry_options, add_impact_options,
                      add_motion_options, add_output_options, add_run_options, add_spread_options,
                      arch_from_args, figure_arg, folder_arg, friction_mu, friction_words,
                      impact_spec_from_args, motion_spec_from_args, spreads_for)


def add_ensemble_parser(subparsers):
    p = subparsers.add_parser(
        "ensemble", help="Monte Carlo over random arches around a nominal one: k_l, k_r, hinge "
                         "patterns and, under a ground motion, the probability of collapse",
        description="Random arches (spans, thicknesses, radii uniform around the nominal arch): "
                    "sample i depends on the nominal arch, the spreads and --seed only (never on "
                    "--batch-size or --workers) and is sample i of curves and fragility too. "
                    "With --out DIR every finished batch is kept (Parquet + manifest.json) and a "
                    "re-run resumes.")
    add_geometry_options(p)
    p.add_argument("--samples", type=_int, default=1000, metavar="N",
                   help="number of random arches, >= 1 (default 1000)")
    p.add_argument("--seed", type=_int, default=0, help="random seed, integer >= 0 (default 0)")
    add_spread_options(p, tilt=True, piers=True, strength=True)
    p.add_argument("--batch-size", type=_int, default=500, metavar="B",
                   help="samples per batch: the unit of work and of resumption, >= 1 "
                        "(default 500)")
    add_run_options(p, workers="1: in-process (numba threads, default); N > 1: local process pool",
                    scheduler="run the batches on an existing Dask cluster (needs archrock[dask])",
                    out="folder for batches/*.parquet and manifest.json; resumes if it exists "
                        "(on either device)",
                    device=DEVICE_HELP)
    add_motion_options(p)
    add_impact_options(p)
    p.add_argument("--support-draw", choices=("fixed", "uniform"), default="fixed",
                   help="with --spread/--settlement: every arch takes the whole movement "
                        "(fixed, default) or a fraction U uniform on [0, 1] of it drawn per arch "
                        "(uniform; docs/supports.md)")
    p.add_argument("--early-stop", action="store_true",
                   help="stop following an arch once, after the ground motion, its energy is "
                        "below every mechanism's barrier under an impact law that adds no energy: "
                        "collapse and peak as in the full run, impacts and rest not followed "
                        "(status 'stopped', column early_stopped)")
    p.add_argument("--low-memory", action="store_true",
                   help="keep no per-sample table in memory (needs --out; not with --plot): each "
                        "batch is written and dropped and the summary is read back from the "
                        "stored batches, exactly (for 10^7 arches and more)")
    add_dynamics_option(p, "under a motion, each response")
    add_friction_option(p, "the routing of the dynamics and, where it runs, the contact "
                           "engine")
    add_output_options(p, json="print the summary as one JSON object",
                       plot="histograms of k_l and k_r", progress="no progress bar on stderr")
    p.set_defaults(func=run_ensemble_cmd)
    return p


def _kept(out, n_batches: int) -> str:
    """What an interrupted run leaves: the finished batches in --out, which a re-run resumes."""
    if out is None:
        return "nothing was kept (give --out DIR to keep finished batches and resume)"
    kept = len(list((Path(out) / "batches").glob("*.parquet")))
    return (f"{kept} of {n_batches} batches kept in {out}; the same command resumes from them")


def _engine_run(args, motion, choice):
    """The engine's run at the command's one friction where the routing (``choice``) sends the
    arches to the engine; None elsewhere.  --friction none (sliding excluded) is refused there:
    the engine cannot exclude sliding."""
    if motion is None or not choice.engine:
        return None
    if friction_mu(args) is None:
        raise CLIError(f"--friction: none (sliding excluded) cannot be modelled by the contact "
                       f"engine, which this arch needs ({choice.reason}); give a finite MU > 0 "
                       f"(a large one, e.g. 10, for joints that hardly slide) or --dynamics "
                       f"fourlink")
    from ..contact.settings import EngineSettings
    from ..studies.enginestudy import EngineRun

    return EngineRun(settings=EngineSettings(friction=friction_mu(args)))


def _choice(config, args):
    """The routing (choose_dynamics) of the nominal arch at --friction, as run_ensemble makes
    it: said in the text and JSON."""
    from ..studies.enginestudy import choose_dynamics

    return choose_dynamics(config.analysed_nominal, args.dynamics, friction=friction_mu(args))


def run_ensemble_cmd(args) -> int:
    from ..geometry.displaced import DisplacedArch
    from ..studies.ensemble import PAPER_RANDOM_ARCHES, EnsembleConfig, run_ensemble
    from ..reports.ensemble import format_ensemble

    out, plot = folder_arg(args.out), figure_arg(args.plot)
    settings = run_settings(args, out=out)
    nominal = arch_from_args(args)
    support = None
    if isinstance(nominal, DisplacedArch):  # --spread/--settlement: every sample's supports move
        support, nominal = nominal.movement, nominal.base
    if args.support_draw != "fixed" and support is None:
        raise CLIError("--support-draw: needs --spread or --settlement (the movement drawn per "
                       "arch, in metres)")
    motion = motion_spec_from_args(args)
    given = [f for f, v in (("--cv", args.cv), ("--impact", args.impact),
                            ("--impact-on", args.impact_on),
                            ("--literal-cv", args.literal_cv or None)) if v is not None]
    if args.low_memory and (out is None or plot):
        raise CLIError("--low-memory: needs --out DIR (the summary is read from the stored "
                       "batches) and cannot draw --plot (the histograms need every sample)")
    if args.early_stop and motion is None:
        raise CLIError("--early-stop: unused without a ground motion; give --pulse ... or "
                       "--record FILE|SUITE/ID, or drop --early-stop")
    if motion is None and given:
        # without a motion nothing impacts: the option would be silently ignored
        raise CLIError(f"{given[0]}: unused without a ground motion (the ensemble is then limit "
                       f"analysis only); give --pulse ... or --record FILE|SUITE/ID, or drop "
                       f"{given[0]}")
    config = EnsembleConfig.from_arch(nominal, samples=args.samples, seed=args.seed,
                                      batch_size=args.batch_size,
                                      motion=motion, spreads=spreads_for(args, nominal),
                                      impact=impact_spec_from_args(args),
                                      early_stop=bool(args.early_stop), support=support,
                                      support_draw=args.support_draw)
    choice = _choice(config, args) if motion is not None else None
    engine = _engine_run(args, motion, choice)
    try:
        result = run_ensemble(config, keep_frame=not args.low_memory, settings=settings,
                              dynamics=args.dynamics, engine=engine, friction=friction_mu(args))
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted; " + _kept(out, config.n_batches), file=sys.stderr)
        return EXIT_INTERRUPTED
    summary = result.summary()
    if motion is not None:  # the routing of the dynamics that ran, at the command's friction
        summary["dynamics"] = choice.to_dict()
    if summary.get("how") == "contact engine":  # the engine's result (studies/enginestudy.py)
        if args.json:
            emit_json(summary)
            return 0
        from ..reports.engineensemble import format_engine_ensemble

        print(format_engine_ensemble(summary, nominal.name))
        for flag, given in (("--out", out), ("--plot", plot)):
            if given:
                print(f"{flag}: not used by the engine ensemble (nothing stored or drawn)")
        return 0
    if plot:
        from ..reports.plots import plot_multiplier_histograms

        ref = {"nominal": (summary["nominal"]["k_l"], summary["nominal"]["k_r"]),
               **PAPER_RANDOM_ARCHES}
        plot = plot_multiplier_histograms(result.frame, plot, reference=ref)
    if args.json:
        emit_json(summary)
        return 0
    if motion is not None:
        print(f"dynamics: four-link model: {summary['dynamics']['reason']}; "
              f"{friction_words(args)}")
    print(format_ensemble(summary, nominal.name))
    if out:
        print(f"results in {out}")
    if plot:
        print(f"wrote {plot}")
    return 0
