"""``archrock limit``, ``random-arch`` and ``plot-limit``: one arch, no ground motion."""

from __future__ import annotations

import sys
from pathlib import Path

from ._friction import NOT_GIVEN, friction_or_none, resolve_friction
from ._parser import (CLIError, emit_json, finite_float, non_negative_int, out_of_range,
                      positive_float)
from ..statics.friction import DEFAULT_FRICTION
from .options import (add_geometry_options, add_spread_options, arch_from_args, figure_arg,
                      folder_arg)


# ---------------------------------------------------------------------------- limit
def add_limit_parser(subparsers):
    p = subparsers.add_parser(
        "limit", help="collapse multipliers k_l, k_r and mechanisms (limit analysis)",
        description="Limit analysis under horizontal forces proportional to the weight: "
                    "kinematic enumeration of four-hinge mechanisms, checked by a static LP.")
    add_geometry_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a table")
    p.add_argument("--min-thickness", action="store_true",
                   help="also compute the minimum thickness under self-weight (bisection); "
                        "with --friction, the friction-limited one")
    p.add_argument("--friction", type=friction_or_none, metavar="MU|none", default=NOT_GIVEN,
                   help="Coulomb friction coefficient at every joint (finite, > 0): multipliers "
                        "with friction, whether sliding governs, the joints needing most "
                        "friction, and the governing capacity at it; 'none': sliding excluded "
                        "(Heyman's hypothesis); left out, the governing capacity is at the "
                        f"default mu = {DEFAULT_FRICTION:g} and no friction table is printed")
    p.add_argument("--thrust-range", action="store_true",
                   help="also compute the least and greatest horizontal thrust under self-weight "
                        "(supports spreading or closing) and their hinges (docs/thrust.md)")
    p.add_argument("--min-pier-width", type=positive_float, metavar="H", default=None,
                   help="also compute the least width [m] of two equal monolithic piers H m "
                        "high with which the arch stands under self-weight (bisection; "
                        "docs/piers.md); the arch is given without --pier-* options")
    p.add_argument("--capacity", choices=("spread", "closure", "settlement", "rotation"),
                   default=None,
                   help="also compute the support movement at which the arch can no longer "
                        "stand: spreading, closing or settlement of --support-side (default the "
                        "right support; docs/supports.md)")
    p.add_argument("--supports-plot", metavar="FILE.png", default=None,
                   help="with --spread/--settlement and/or --capacity: figure of the displaced "
                        "arch with its line of thrust and/or of the capacity curve")
    p.add_argument("--fill-pressure", type=_kappa, metavar="KAPPA", default=None,
                   help="also compute k with the fill's mobilised passive pressure on the "
                        "extrados where the arch sways into it: KAPPA (0 to 1000) times "
                        "Rankine's full passive pressure K_p gamma z; needs a fill "
                        "(--fill-level, or a geometry file whose family has one; docs/fill.md)")
    p.add_argument("--fill-friction-angle", type=finite_float, metavar="DEG", default=None,
                   help="with --fill-pressure: the fill's friction angle [deg], 0 to 89, for "
                        "K_p = (1 + sin phi) / (1 - sin phi) (default 30: K_p = 3)")
    p.set_defaults(func=run_limit)
    return p


def _kappa(text):
    """argparse type of --fill-pressure: a finite number >= 0."""
    v = finite_float(text)
    if v < 0:
        raise out_of_range(text, ">= 0 (a fraction of the full passive pressure)")
    return v


def _check_fill_flags(args, arch):
    """--fill-pressure and --fill-friction-angle checked before any work: refused, naming the
    flags, where the arch has no fill of its own (docs/fill.md)."""
    if args.fill_pressure is None:
        if args.fill_friction_angle is not None:
            raise CLIError("--fill-friction-angle: needs --fill-pressure KAPPA")
        return
    if getattr(arch, "fc", None) is not None:
        raise CLIError("--fill-pressure: computed under Heyman's hypotheses (infinite "
                       "compressive strength); leave out --fc (or the geometry file's \"fc\")")
    if not (getattr(arch, "recipe", None) or {}).get("fill"):
        raise CLIError("--fill-pressure: the arch has no fill; give one with --fill-level Y "
                       "[--fill-density RHO] and --shape/--span/--rise, or a geometry file whose "
                       "family has a fill (on the arch alone: no piers, defects or support "
                       "movement)")


def _fill_pressure(args, arch, result):
    """The FillResult of --fill-pressure (None without it; docs/fill.md)."""
    phi, kappa = args.fill_friction_angle, args.fill_pressure
    if kappa is None:
        return None
    from ..errors import ArchInputError
    from ..statics.fill import DEFAULT_FILL_FRICTION_DEG, fill_pressure_analysis

    try:
        return fill_pressure_analysis(arch, kappa, DEFAULT_FILL_FRICTION_DEG if phi is None
                                      else phi, base=result)
    except ArchInputError as exc:
        msg = str(exc)
        for field, flag in (("kappa:", "--fill-pressure:"), ("phi:", "--fill-friction-angle:")):
            if msg.startswith(field):
                raise ArchInputError(flag + msg[len(field):]) from None
        raise


def _min_pier_width(args, arch):
    """The minimum pier width of --min-pier-width H (None without it); refused with --pier-*."""
    if getattr(args, "min_pier_width", None) is None:
        return None
    from ..geometry import ArchOnPiers
    from ..statics.buttress import minimum_pier_width

    if isinstance(arch, ArchOnPiers) and arch.pier_blocks:
        raise CLIError("--min-pier-width: cannot be combined with an arch on piers (--pier-* "
                       "options or a geometry file with pier blocks); give the arch alone")
    from ..errors import ArchInputError

    try:
        return minimum_pier_width(arch, args.min_pier_width)
    except ArchInputError as exc:  # the library names its argument; the user typed the flag
        msg = str(exc)
        if msg.startswith("height:"):
            raise ArchInputError("--min-pier-width:" + msg[len("height:"):]) from None
        raise


def _supports_extra(args, arch, result):
    """(lines, json, capacity) for a displaced arch and --capacity (docs/supports.md)."""
    from ..geometry.displaced import DisplacedArch
    from ..reports.supports import (displaced_summary, format_capacity, format_displaced,
                                    format_gap_closing)
    from ..statics.supports import displacement_capacity, gap_closing

    lines, out, cap = [], {}, None
    if isinstance(arch, DisplacedArch):
        lines.append(format_displaced(arch))
        out["support_movement"] = displaced_summary(arch)
        gc = gap_closing(arch)
        if gc is not None:
            lines.append(format_gap_closing(gc))
        out["support_movement"]["gap_closing"] = None if gc is None else gc.to_dict()
    if args.capacity is not None:
        cap = displacement_capacity(arch, args.capacity, args.support_side or "right",
                                    getattr(args, "pivot_depth", None) or 0.0)
        lines.append(format_capacity(cap))
        out["capacity"] = cap.to_dict()
    return lines, out, cap


def _frictionless(arch, args):
    """(LimitResult, None), or (None, why) where no frictionless mechanism opens but another
    question has an answer: with --friction the friction analysis (docs/friction.md), with
    --capacity the support movement's (docs/supports.md)."""
    from ..errors import NoMechanismError
    from ..statics.limit import limit_analysis

    mu = args.friction
    try:
        return limit_analysis(arch, verify=True), None
    except NoMechanismError as exc:
        if mu is None and args.capacity is None:  # name what gives an answer
            raise NoMechanismError(f"{exc}; --friction MU gives the multipliers at which its "
                                   f"joints slide") from None
        return None, str(exc)


def _crushing_friction(arch, result):
    """The friction the finite-strength collapse needs, on its own thrust line (its state is
    unique where four hinges form), where no friction coefficient was given; else None."""
    from ..statics.friction import FrictionNeeded, thrust_friction

    if result is None:
        return None
    return FrictionNeeded(thrust_friction(arch, {"l": result.thrust_l, "r": result.thrust_r}),
                          {})


def run_limit(args) -> int:
    from ..errors import CannotStandError
    from ..statics.friction import friction_analysis, friction_minimum_thickness, friction_needed
    from ..statics.limit import minimum_thickness
    from ..reports.limit import (format_friction_only, format_governing, format_limit_table,
                                 friction_only_summary, limit_summary)

    plot = figure_arg(args.supports_plot)
    if args.capacity is not None and (args.spread or args.settlement
                                      or getattr(args, "rotation", None)):  # 0: the arch
        raise CLIError("--capacity: computed on the arch as built; leave out --spread and "
                       "--settlement (the capacity's curve gives every movement up to it)")
    arch = arch_from_args(args)
    _check_fill_flags(args, arch)
    # the governing answer's friction (stated); the friction table only where --friction MU
    gov_mu, gov_stated = resolve_friction(args.friction)
    if args.friction is NOT_GIVEN:
        args.friction = None
    mpw = _min_pier_width(args, arch)
    result, no_mech = _frictionless(arch, args)
    sup_lines, sup_json, cap = _supports_extra(args, arch, result)
    mu = args.friction
    mt = None
    if args.min_thickness and mu is not None and arch.fc is not None:
        # the friction-limited minimum thickness is Heyman's (no crushing): with both it would
        # answer a question that was not asked
        raise CLIError("--min-thickness: with --friction and --fc together is not computed "
                       "(friction and crushing at once); give one of them")
    if args.min_thickness:
        # first: where no thickness stands with this friction, that is the answer
        mt = minimum_thickness(arch) if mu is None else friction_minimum_thickness(arch, mu)
    # Heyman's friction table and the friction his collapse needs assume no crushing: with a
    # finite f_c friction is in the governing capacity alone (both on the graph of blocks)
    heyman = arch.fc is None
    try:
        fr = friction_analysis(arch, mu) if mu is not None and heyman else None
    except CannotStandError as exc:
        if mt is None:
            raise
        raise CannotStandError(f"{exc}; with friction {mu:g} the minimum thickness is "
                               f"{_thickness_words(arch, mt)}") from None
    needed = (None if fr is not None or no_mech is not None
              else friction_needed(arch) if heyman else _crushing_friction(arch, result))
    extra = {"needed": needed, "friction": fr, "min_thickness_friction": mu}
    if mpw is not None:
        extra["min_pier_width"] = mpw
    if args.thrust_range:
        from ..statics.thrust import thrust_range

        extra["thrust"] = thrust_range(arch)
    if plot is not None:
        from ..geometry.displaced import DisplacedArch
        from ..reports.supports import save_supports_figure

        state = None
        if isinstance(arch, DisplacedArch):
            from ..statics.supports import displace

            state = displace(arch.base, arch.movement)
        if state is None and cap is None:
            raise CLIError("--supports-plot: needs --spread/--settlement or --capacity")
        path = save_supports_figure(plot, state=state, capacity=cap)
        print(f"wrote {path}", file=sys.stderr)
    if no_mech is not None:
        # no frictionless mechanism: friction's result and/or the capacity are the answer
        extra.pop("needed")
        gov = None if fr is None else _governing(arch, None, gov_mu)
        if args.json:
            emit_json({**friction_only_summary(arch, no_mech, mt, **extra), **sup_json,
                       **({} if gov is None else
                          {"governing": {**gov.to_dict(), "friction_stated": gov_stated}})})
        else:
            print(format_friction_only(arch, no_mech, mt, **extra))
            for line in sup_lines:
                print(line)
            if gov is not None:
                print(format_governing(gov, gov_stated))
            if args.fill_pressure is not None:  # the soil only resists
                print("Fill's passive pressure: no frictionless mechanism opens without it, "
                      "nor with it (a resistance only)")
        return 0
    gov = _governing(arch, result, gov_mu)
    fp = _fill_pressure(args, arch, result)
    if args.json:
        emit_json({**limit_summary(result, mt, **extra), **sup_json,
                   "governing": {**gov.to_dict(), "friction_stated": gov_stated},
                   **({} if fp is None else {"fill_pressure": fp.to_dict()})})
    else:
        print(format_limit_table(result, mt, **extra))
        for line in sup_lines:
            print(line)
        print(format_governing(gov, gov_stated))
        if fp is not None:
            from ..reports.limit import format_fill_pressure

            print(format_fill_pressure(fp))
    return 0


def _governing(arch, result, mu):
    """The governing capacity at ``mu`` (studies.governing), without the engine."""
    from ..studies.governing import governing_capacity

    return governing_capacity(arch, mu, engine=False, limit=result,
                              engine_left_out="not run by limit: archrock dem --ramp")


def _thickness_words(arch, mt) -> str:
    from ..geometry import Arch

    what = "t/R" if isinstance(arch, Arch) else "t / size"
    ratio = "" if mt.ratio is None else f", mean {what} = {mt.ratio:.4f}"
    return f"factor {mt.factor:.4f} of the given thicknesses{ratio}"


# ---------------------------------------------------------------------------- random-arch
def add_random_arch_parser(subparsers):
    p = subparsers.add_parser(
        "random-arch", help="draw an irregular arch around a nominal one; write its geometry file",
        description="span_i = (alpha/n)(1 + s_a U), t_i = t (1 + s_t U), R_i = R + s_R t U, "
                    "U uniform on [-1, 1], spans rescaled to the nominal embrace.")
    add_geometry_options(p)
    p.add_argument("--seed", type=non_negative_int, default=None,
                   help="random seed (integer >= 0); omit for a fresh draw")
    add_spread_options(p, tilt=True)
    p.add_argument("--out", metavar="FILE", help="geometry file to write (default: stdout)")
    p.set_defaults(func=run_random_arch)
    return p


def run_random_arch(args) -> int:
    from ..geometry import random_arch
    from ..geometry.sampling import DEFAULT_SPREADS

    out = folder_arg(args.out, "--out", "a file name (omit --out for stdout)")
    nominal = arch_from_args(args)
    if args.spread_span is None:  # random_arch draws circular and family arches only
        args.spread_span = DEFAULT_SPREADS.span
    arch = random_arch(nominal, seed=args.seed, spread_span=args.spread_span,
                       spread_thickness=args.spread_thickness, spread_radius=args.spread_radius,
                       spread_tilt_deg=args.spread_tilt)
    meta = {"generator": "archrock random-arch", "seed": args.seed, "nominal": nominal.name,
            "spread_span": args.spread_span, "spread_thickness": args.spread_thickness,
            "spread_radius": args.spread_radius,
            **({"spread_tilt_deg": args.spread_tilt} if args.spread_tilt else {})}
    if out:
        from ..geometry.files import write_arch

        try:
            Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise CLIError(f"--out: cannot create the folder of {args.out!r} ({exc.strerror})") from None
        write_arch(arch, args.out, metadata=meta)
        print(f"wrote {args.out}", file=sys.stderr)
    else:
        emit_json({**arch.to_dict(), "metadata": meta})
    return 0


# ---------------------------------------------------------------------------- plot-limit
def add_plot_limit_parser(subparsers):
    p = subparsers.add_parser(
        "plot-limit", help="figure of the collapse mechanism and line of thrust (paper Fig. 3)")
    add_geometry_options(p)
    p.add_argument("--out", metavar="FILE.png", default="limit.png",
                   help="image to write (default limit.png)")
    p.add_argument("--direction", choices=("l", "r", "both"), default="both",
                   help="mechanism M_l, M_r or both panels (default both)")
    p.add_argument("--dpi", type=positive_float, default=150,
                   help="resolution, dots per inch (default 150; at most 50 million pixels)")
    p.set_defaults(func=run_plot_limit)
    return p


def run_plot_limit(args) -> int:
    from ..statics.limit import limit_analysis
    from ..reports.plots import save_limit_figure

    out = figure_arg(args.out)
    arch = arch_from_args(args)
    result = limit_analysis(arch, verify=True)
    dirs = ("l", "r") if args.direction == "both" else (args.direction,)
    path = save_limit_figure(result, out, directions=dirs, dpi=args.dpi)
    print(f"k_l = {result.k_l:.4f}, k_r = {result.k_r:.4f}; wrote {path}")
    return 0
