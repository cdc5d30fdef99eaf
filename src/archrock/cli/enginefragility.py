"""``archrock fragility`` on an arch one degree of freedom cannot follow (issue 31): the IDA by
the contact engine (:func:`archrock.studies.engineida.engine_ida`) instead of a refusal; the
model and the reason are stated, the JSON carries "dynamics"."""

from __future__ import annotations

import sys

from ..errors import ArchInputError
from ._parser import EXIT_INTERRUPTED, PROG, emit_json
from .fragilityfigure import fragility_figure


def _unused(args) -> list:
    """The four-link options given on a run the engine answers (said, not silently dropped)."""
    given = [("--levels", args.levels), ("--impact", args.impact),
             ("--impact-on", args.impact_on), ("--cv", args.cv),
             ("--literal-cv", args.literal_cv or None),
             ("--engine", None if args.engine == "batch" else args.engine),
             ("--early-stop", args.early_stop or None)]
    return [flag for flag, v in given if v is not None]


def _refuse_what_cannot_run(args) -> None:
    if args.samples > 0:
        raise ArchInputError(
            f"samples: {args.samples}; the contact engine's fragility, which this arch needs "
            f"(piers that rock or joints that slide: --dynamics), runs the nominal arch only; "
            f"allowed 0, or `archrock ensemble --dynamics auto` for random arches by the engine")
    if args.out is not None:
        raise ArchInputError("out: a folder of finished four-link responses; the contact "
                             "engine's fragility keeps none; allowed without --out")


def run_engine_fragility(args, nominal, choice, plot) -> int:
    """The engine's IDA of ``nominal`` over ``--records`` x ``--scales`` (``choice``: the
    DynamicsChoice that sent it here)."""
    from ..groundmotion.intensity import parse_im
    from ..groundmotion.suite import read_records
    from ..reports.fragility import engine_fragility_summary, format_engine_fragility
    from ..studies.curves import parse_range
    from ..studies.engineida import engine_ida
    from ..studies.enginestudy import EngineRun
    from ..studies.runner import RunSettings
    from .options import friction_words
    from .respond import _engine_settings

    run = EngineRun(settings=_engine_settings(args, choice))  # --friction none: refused
    _refuse_what_cannot_run(args)
    if args.workers < 1:  # before any records are read
        raise ArchInputError(f"workers: {args.workers}; allowed an integer >= 1")
    im = parse_im(args.im)
    suite = read_records(args.records, units=args.units)
    scales = parse_range(args.scales, "scales")
    sink = (None if args.no_progress or args.json
            else lambda line: print(line, file=sys.stderr, flush=True))
    try:
        res = engine_ida(nominal, list(suite.records), scales, im=im, run=run,
                         n_boot=args.bootstrap, seed=args.seed, dynamics=choice,
                         settings=RunSettings(workers=args.workers, scheduler=args.scheduler,
                                              progress=sink))
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted; nothing was kept (the contact engine's fragility keeps "
              f"no folder of finished runs)", file=sys.stderr)
        return EXIT_INTERRUPTED
    unused = _unused(args)
    if args.json:
        emit_json(engine_fragility_summary(res, arch_name=nominal.name, suite=suite,
                                           unused=unused))
    else:
        print(format_engine_fragility(res, arch_name=nominal.name,
                                      friction=friction_words(args)))
        if unused:
            print(f"not used by the contact engine (four-link options): {', '.join(unused)}")
    sys.stdout.flush()
    if plot:
        if fragility_figure(res.as_ida(), None, plot) and not args.json:
            print(f"wrote {plot}", file=sys.stderr)
    return 0
