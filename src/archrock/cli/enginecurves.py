"""``archrock curves`` on an arch that one degree of freedom cannot follow (issue 19): the
first-collapse amplitudes by the contact engine (:func:`archrock.studies.enginestudy.
engine_collapse_curve`), with the reason."""

from __future__ import annotations

import sys

from ._parser import CLIError, emit_json

#: The engine curve's relative bisection tolerance (each step is an engine run of seconds).
ENGINE_RTOL = 0.01


def run_engine_curves(args, nominal, durations, choice, plot) -> int:
    """The engine's collapse-acceleration curve of ``nominal`` (no random arches: --samples
    is refused), printed or as JSON; the figure with --plot."""
    from ..contact import EngineSettings
    from ..studies.enginestudy import EngineRun, engine_collapse_curve
    from .options import friction_mu

    if args.samples > 0:
        raise CLIError("--samples: the engine curve is of the nominal arch only (an engine run "
                       "takes seconds); for random arches run archrock ensemble (it routes to "
                       "the engine too), or give --dynamics fourlink")
    if friction_mu(args) is None:
        raise CLIError(f"--friction: none (sliding excluded) cannot be modelled by the contact "
                       f"engine, which this arch needs ({choice.reason}); give a finite MU > 0 "
                       f"(a large one, e.g. 10, for joints that hardly slide) or --dynamics "
                       f"fourlink")
    run = EngineRun(settings=EngineSettings(friction=friction_mu(args)))  # the one friction
    progress = None if args.no_progress else (lambda line: print(line, file=sys.stderr,
                                                                  flush=True))
    curve = engine_collapse_curve(nominal, durations, args.pulse, args.sign, a_max=args.a_max,
                                  rtol=ENGINE_RTOL, run=run, progress=progress)
    if plot:
        from ..reports.plots import plot_collapse_curve

        plot_collapse_curve(curve, plot, title=f"{nominal.name}: {args.pulse} pulse, sign "
                                               f"{args.sign:+d}, contact engine")
    if args.json:
        emit_json({"how": "contact engine", "dynamics": choice.to_dict(),
                   "curve": curve.to_dict()})
        return 0
    k = curve.k_l if args.sign < 0 else curve.k_r
    lines = [f"{nominal.name}: first collapse of the {args.pulse} pulse (sign {args.sign:+d}) "
             f"by the contact engine, bisected to {ENGINE_RTOL:g} of the amplitude",
             f"why the engine: {choice.reason}",
             f"friction: mu = {friction_mu(args):g} (the engine's and the routing's; --friction)",
             f"activation threshold k = {k:.4f} g",
             f"{'t_p [s]':>8}  {'first collapse |a| [g]':>22}  {'bracket [g]':>17}  runs  "
             f"seconds"]
    for p in curve.points:
        a = ("none up to a_max" if p.amplitude is None else f"{p.amplitude:.4f}")
        br = "-" if p.bracket is None else f"{p.bracket[0]:.4f}-{p.bracket[1]:.4f}"
        lines.append(f"{p.duration:8.3g}  {a:>22}  {br:>17}  {p.n_responses:4d}  "
                     f"{p.seconds:7.1f}")
    print("\n".join(lines))
    if plot:
        print(f"wrote {plot}", file=sys.stderr)
    return 0
