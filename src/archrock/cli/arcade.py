"""``archrock arcade``: several arches on shared piers (a graph of blocks): the static LP's k and
mechanism in each direction, optionally the contact engine's ramp beside it (--ramp) or its
response to a pulse or record, and a figure of the mechanism (docs/arcades.md)."""

from __future__ import annotations

import sys

from ._parser import CLIError, _int, emit_json, finite_float, positive_float
from .options import add_motion_options, figure_arg, motion_spec_from_args, say_written

#: the library's field -> the flag that gives it (ArchInputError messages start with the field)
_FLAGS = (("heights", "--pier-height"), ("widths", "--pier-width"),
          ("courses", "--pier-courses"))


def add_arcade_parser(subparsers):
    from ..geometry import SHAPES

    p = subparsers.add_parser(
        "arcade", help="several arches on shared piers: k, the mechanism (graph LP), the "
                       "contact engine",
        description="An arcade: n arches on n + 1 piers (semicircles of --spans by default, "
                    "arches of a family with --shape/--rises, or geometry files), analysed by "
                    "the static LP on the graph of blocks (equilibrium of every block, no "
                    "tension, --friction for Coulomb rows); the mechanism is read from its dual "
                    "and confirmed by its own virtual work. --ramp adds the contact engine's "
                    "activation; --pulse/--record its response (docs/arcades.md).")
    g = p.add_argument_group("arches", "one value for every span, or one per span")
    g.add_argument("--spans", type=finite_float, nargs="+", metavar="S",
                   help="span of each arch's centreline [m], > 0 (1 to 50 spans; default "
                        "semicircles of radius S/2)")
    g.add_argument("--shape", choices=SHAPES, metavar="SHAPE",
                   help=f"arch family of every span: {', '.join(SHAPES)} (with --rises)")
    g.add_argument("--rises", type=finite_float, nargs="+", metavar="F",
                   help="with --shape: rise of each arch's centreline [m]")
    g.add_argument("--thickness", type=finite_float, nargs="+", metavar="T",
                   help="thickness of each arch [m] (default 1/10 of the span)")
    g.add_argument("--voussoirs", type=_int, nargs="+", metavar="N",
                   help="voussoirs of each arch, 3 to 2000 (default 9)")
    g.add_argument("--density", type=finite_float, metavar="RHO",
                   help="density [kg/m^3] of the arches and piers, 1e-8 to 1e8 (default "
                        "2000)")
    g.add_argument("--geometry", nargs="+", metavar="FILE",
                   help="an arch geometry file per span (or one, with --repeat); excludes "
                        "the flags above")
    g.add_argument("--repeat", type=_int, metavar="N",
                   help="with one --geometry FILE: that arch on N spans, 1 to 50")
    g.add_argument("--arcade", metavar="FILE",
                   help="an arcade document (blocks and their contacts, docs/arcades.md); "
                        "excludes every arch and pier flag")
    q = p.add_argument_group("piers", "one value for every pier, or one per pier (n + 1, "
                                      "from the left)")
    q.add_argument("--pier-height", type=finite_float, nargs="+", metavar="H",
                   help="height of each pier from its foundation to the springing [m], > 0")
    q.add_argument("--pier-width", type=finite_float, nargs="+", metavar="W",
                   help="width of each pier [m]: an end pier's outward of its intrados "
                        "springing, an inner pier's between the two intrados springings")
    q.add_argument("--pier-courses", type=_int, nargs="+", metavar="N",
                   help="courses of each pier, 1 to 200 (default 1: monolithic)")
    s = p.add_argument_group("strength", "finite compressive strength (default: infinite, "
                                         "Heyman's hypothesis)")
    s.add_argument("--fc", type=finite_float, metavar="MPA",
                   help="compressive strength f_c of every block [MPa], 0.1 to 1000 (default: "
                        "the arches' own, a file's \"fc\"); a contact takes its weaker block's")
    s.add_argument("--pier-fc", type=finite_float, metavar="MPA",
                   help="compressive strength of the piers' courses [MPa], 0.1 to 1000 "
                        "(default: --fc)")
    p.add_argument("--friction", type=positive_float, default=None, metavar="MU",
                   help="Coulomb friction at every contact in the LP (default: no sliding) "
                        "and in the engine (default 0.8)")
    p.add_argument("--write", metavar="FILE.json",
                   help="write the arcade as an arcade document (blocks and contacts)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png",
                   help="figure: the blocks, the hinges and the blocks' velocities of the "
                        "mechanism in each direction")
    e = p.add_argument_group("contact engine")
    e.add_argument("--ramp", action="store_true",
                   help="the contact engine's ramp in each direction beside the LP")
    e.add_argument("--ramp-tol", type=positive_float, default=0.005, metavar="TOL",
                   help="--ramp: relative width of the final bracket (default 0.005)")
    e.add_argument("--t-end", type=positive_float, default=3.0, metavar="S",
                   help="with a ground motion: output window [s] (default 3); the run goes on "
                        "to rest or collapse")
    add_motion_options(p)
    from .rings import add_ring_options

    add_ring_options(p)
    p.set_defaults(func=run_arcade)
    return p


def _renamed(exc, extra: str = ""):
    from ..errors import ArchInputError

    msg = str(exc)
    for field, flag in _FLAGS:
        if msg.startswith(field):
            rest = msg[len(field):]
            if rest.startswith("["):
                idx, _, rest = rest[1:].partition("]")
                return ArchInputError(f"{flag}: value {int(idx) + 1} (pier {int(idx) + 1})"
                                      f"{rest}")
            return ArchInputError(f"{flag}{rest}")
    return ArchInputError(f"{extra}{msg}")


def _per_span(args, name, flag, n, default):
    vals = getattr(args, name)
    if vals is None:
        return [default(s) for s in range(n)]
    if len(vals) == 1:
        return vals * n
    if len(vals) != n:
        raise CLIError(f"{flag}: {len(vals)} values for {n} spans; allowed one for all, or one "
                       f"per span")
    return list(vals)


def _arches_from_files(args, arch_flags, max_spans):
    """The arches of --geometry FILE... (and --repeat), each file read once."""
    given = [f for f, v in arch_flags if v is not None]
    if given:
        raise CLIError(f"--geometry: cannot be combined with {', '.join(given)}; each file "
                       f"holds its arch")
    from ..geometry.files import read_arch

    files = list(args.geometry)
    if args.repeat is not None:
        if len(files) != 1:
            raise CLIError("--repeat: applies to one --geometry FILE; give one file")
        if not 1 <= args.repeat <= max_spans:
            raise CLIError(f"--repeat: {args.repeat} is out of range; allowed 1 to "
                           f"{max_spans}")
        files = files * args.repeat
    cache = {}
    arches = []
    for f in files:
        if f not in cache:
            cache[f] = read_arch(f)
        arches.append(cache[f])
    return arches


def _check_spans(args, max_spans) -> int:
    """Check --spans, --shape and --rises (no --repeat without --geometry): the span count."""
    if args.repeat is not None:
        raise CLIError("--repeat: applies to --geometry FILE only")
    if args.spans is None:
        raise CLIError("--spans: needed (the span of each arch's centreline, in metres), or "
                       "--geometry FILE... or --arcade FILE")
    n = len(args.spans)
    if not 1 <= n <= max_spans:
        raise CLIError(f"--spans: {n} spans; allowed 1 to {max_spans}")
    for i, s in enumerate(args.spans):
        if not 1e-8 <= s <= 1e8:
            raise CLIError(f"--spans: {s:g} (span {i + 1}) is out of range; allowed 1e-8 "
                           f"to 1e8 m")
    if args.rises is not None and args.shape is None:
        raise CLIError("--rises: needs --shape (the family of the arches)")
    if args.shape is not None and args.rises is None:
        raise CLIError("--rises: needed with --shape (the rise of each arch's centreline, "
                       "in metres)")
    return n


def _span_arch(args, s, thickness, voussoirs, rise, density):
    """The arch of span s (0-based): a semicircle, or of --shape; its errors name the flag."""
    from ..errors import ArchInputError
    from ..geometry import family_arch, nominal_arch

    try:
        if args.shape is None:
            return nominal_arch(radius=args.spans[s] / 2, embrace_deg=180.0,
                                thickness=thickness, voussoirs=voussoirs, density=density,
                                name=f"span {s + 1}")
        return family_arch(args.shape, args.spans[s], rise, thickness, voussoirs,
                           density=density, name=f"span {s + 1}")
    except ArchInputError as exc:
        msg = str(exc)
        for field in ("thickness", "voussoirs", "rise", "span", "density"):
            if msg.startswith(field):
                flag = {"rise": "--rises", "span": "--spans"}.get(field, f"--{field}")
                raise ArchInputError(f"{flag} (span {s + 1}){msg[len(field):]}") from None
        raise ArchInputError(f"span {s + 1}: {msg}") from None


def _arches_from_spans(args, max_spans):
    """The arches of --spans (with --shape, --rises, --thickness, --voussoirs, --density)."""
    n = _check_spans(args, max_spans)
    t = _per_span(args, "thickness", "--thickness", n, lambda s: args.spans[s] / 10)
    nv = _per_span(args, "voussoirs", "--voussoirs", n, lambda s: 9)
    rises = _per_span(args, "rises", "--rises", n, lambda s: None)
    density = 2000.0 if args.density is None else args.density
    arches, cache = [], {}
    for s in range(n):
        key = (args.spans[s], t[s], nv[s], rises[s])
        if key not in cache:  # equal spans share one arch (written as polygons once)
            cache[key] = _span_arch(args, s, t[s], nv[s], rises[s], density)
        arches.append(cache[key])
    return arches


def _on_piers(args, arches, pier_flags):
    """The arcade of ``arches`` on the piers of the options, its work checked first."""
    from ..errors import ArchInputError
    from ..geometry.arcade import arcade

    for flag, v in pier_flags[:2]:
        if v is None:
            raise CLIError(f"{flag}: needed (one value for every pier, or {len(arches) + 1}, "
                           f"in metres)")
    # courses are checked by arcade(); only a plausible count enters the estimate
    courses = [c for c in (args.pier_courses or [1]) if isinstance(c, int) and 0 < c <= 10**6]
    n_piers = len(arches) + 1
    pier_blocks = (courses[0] * n_piers if len(courses) == 1 else sum(courses)) if courses else 0
    _check_work(args, sum(a.n for a in arches) + pier_blocks)
    try:
        return arcade(arches, list(args.pier_height), list(args.pier_width),
                      courses=list(args.pier_courses or [1]),
                      fc=None if args.fc is None else _check_fc_flag(args.fc))
    except ArchInputError as exc:
        if str(exc).startswith("arches: compressive strengths"):
            raise ArchInputError(f"--geometry: {str(exc)[8:].split(';')[0]}; allowed files "
                                 f"of one fc, or --fc for all") from None
        raise _renamed(exc) from None


def _check_fc_flag(value, flag: str = "--fc") -> float:
    from ..errors import ArchInputError
    from ..geometry.base import _check_fc

    try:
        return _check_fc(value, flag)
    except ArchInputError as exc:
        raise ArchInputError(str(exc)) from None


def _with_strength(args, arc):
    """``arc`` with --fc (every block) and --pier-fc (the piers) over its own strengths."""
    if args.fc is None and args.pier_fc is None:
        return arc
    fc = dict(arc.fc)
    if args.fc is not None:  # the kinds the arcade has (its document names no others)
        fc = {k: _check_fc_flag(args.fc) for k in dict.fromkeys(arc.kinds)}
    if args.pier_fc is not None:
        fc["pier"] = _check_fc_flag(args.pier_fc, "--pier-fc")
    return arc.with_fc(fc)


def arcade_from_args(args):
    """The Arcade of the options (the arches on their piers, or an arcade document)."""
    from ..geometry.arcade import MAX_SPANS

    arch_flags = [("--spans", args.spans), ("--shape", args.shape), ("--rises", args.rises),
                  ("--thickness", args.thickness), ("--voussoirs", args.voussoirs),
                  ("--density", args.density)]
    pier_flags = [("--pier-height", args.pier_height), ("--pier-width", args.pier_width),
                  ("--pier-courses", args.pier_courses)]
    from .rings import ringed_from_args, wants_rings

    if wants_rings(args):
        return _with_strength(args, ringed_from_args(args))
    if args.arcade:
        given = [f for f, v in arch_flags + pier_flags + [("--geometry", args.geometry),
                                                          ("--repeat", args.repeat)]
                 if v is not None]
        if given:
            raise CLIError(f"--arcade: cannot be combined with {', '.join(given)}; the file "
                           f"holds the whole arcade")
        from ..geometry.files import read_arcade

        return _with_strength(args, read_arcade(args.arcade,
                                                on_size=lambda n: _check_work(args, n)))
    if args.geometry:
        arches = _arches_from_files(args, arch_flags, MAX_SPANS)
    else:
        arches = _arches_from_spans(args, MAX_SPANS)
    return _with_strength(args, _on_piers(args, arches, pier_flags))


def _check_work(args, n_blocks: int) -> float:
    """The estimated seconds of the static program on ``n_blocks`` blocks (both directions);
    refused past the work bound (ARCHROCK_MAX_WORK_S), a warning past a minute, which also
    turns on one progress line per direction (``args._say_progress``)."""
    from ..statics.graph import graph_limit_cost_s
    from ..studies.work import WARN_WORK_S, check_work

    est = check_work("arcade", n_blocks, "blocks", graph_limit_cost_s(n_blocks) / max(1, n_blocks),
                     "fewer voussoirs (--voussoirs), courses (--pier-courses) or spans: the "
                     "static program's time grows as the square of the number of blocks",
                     kernel=False)
    args._say_progress = est > WARN_WORK_S
    return est


def _check_engine_work(args, arc, settings, results, motion) -> float:
    """The estimated seconds of the contact engine's part (--ramp: both directions' ramp and
    holds; a motion: the response run to the end of its free motion, an upper estimate), at
    :data:`~archrock.studies.enginestudy.ENGINE_STEP_S` per step and contact piece (about 3
    per block); refused past the work bound, a warning past a minute."""
    import math

    from ..contact.ramp import ramp_range
    from ..studies.enginestudy import ARCHROCK_STEP_S, ENGINE_STEP_S
    from ..units import G
    from ..studies.work import check_work

    spt = settings.steps_per_T
    if args.ramp:  # the ramp up to the motion, then about log2(1/tol) + 4 holds
        holds = math.log2(1.0 / args.ramp_tol) + 4.0
        steps = sum(min(1.2 * g.k if g.k > 0 else ramp_range(None)[1], ramp_range(g.k)[1])
                    / 0.05 * spt + holds * 4.0 * spt for g in results.values())
    else:  # the motion, then up to 20 T of free motion
        t_scale = math.sqrt(arc.size / G)
        steps = (float(motion.times[-1]) / t_scale + 20.0) * spt
    if settings.engine == "archrock":  # a + b m^2, m = 4 (contacts): studies.enginestudy
        m = 4 * len(arc.contacts)
        each = ARCHROCK_STEP_S[0] + ARCHROCK_STEP_S[1] * m * m
    else:
        each = (3 * arc.n_blocks + 2) * ENGINE_STEP_S * settings.iterations / 40.0
    return check_work("arcade engine", steps, "engine steps", each,
                      "leave out --ramp / the motion (the static program's k and mechanism "
                      "need no engine), or use fewer blocks", kernel=False)


def _progress(msg):
    print(msg, file=sys.stderr, flush=True)


def format_result(arc, results, ramp=None, response=None, engine_ref=None) -> str:
    """The report; ``engine_ref``: the LP results the engine's ramp is compared with (Heyman's,
    where the arcade has a finite strength the engine does not model), default ``results``."""
    from ..geometry.blocks import describe_arcade

    counts = describe_arcade(arc)  # piers counted as piers, not as their courses
    spans = f"{len(arc.spans)} span{'s' if len(arc.spans) != 1 else ''}, " if arc.spans else ""
    lines = [f"{arc.name}: {spans}{arc.n_blocks} blocks ({counts}), "
             f"{len(arc.contacts)} contacts, {arc.masses.sum():.6g} kg/m"]
    present = [k for k in dict.fromkeys(arc.kinds)]
    if any(k in arc.fc for k in present):
        kinds = ", ".join(f"{k} {arc.fc[k]:g} MPa" if k in arc.fc else f"{k} infinite"
                          for k in present)
        lines.append(f"compressive strength f_c: {kinds} (a contact takes its weaker "
                     f"block's)")
    from .rings import ring_lines

    for d, g in results.items():
        m = g.mechanism
        lines.append(f"k_{d} = {g.k:.6f} (static LP, HiGHS; the mechanism's virtual work "
                     f"{g.k_virtual_work:.6f}, |diff| {abs(g.k_virtual_work - g.k):.1e}; "
                     f"{m.dof} degree{'s' if m.dof != 1 else ''} of freedom, "
                     f"{len(m.moving)} blocks move)")
        if abs(g.k_virtual_work - g.k) > 1e-6 * max(1.0, abs(g.k)):
            # k stands on the static program (its bracket); the motion read from its dual
            # does not confirm it (crushing with sliding and many degrees of freedom)
            lines.append(f"  note: the mechanism read from the dual is approximate (its "
                         f"virtual work {g.k_virtual_work:.6f} is not k): k is the static "
                         f"program's, a multiplier the structure carries; the motion drawn "
                         f"is indicative only")
        rings = ring_lines(arc, m)
        if rings:  # a brick arch: hundreds of joints, summed by ring
            lines += rings
            if g.k_bounds is not None:
                lines.append(f"  bracket of the static optimum: [{g.k_bounds[0]:.9f}, "
                             f"{g.k_bounds[1]:.9f}] (k is its lower bound)")
            continue
        lines.append(f"  hinges: {'; '.join(h.place for h in m.hinges) or '-'}")
        if g.k_bounds is not None:
            lines.append(f"  bracket of the static optimum: [{g.k_bounds[0]:.9f}, "
                         f"{g.k_bounds[1]:.9f}] (k is its lower bound)")
            z = "; ".join(f"{arc.contacts[h.contact].label} {g.zones[h.contact] * 1e3:.1f} mm"
                          for h in m.hinges if g.zones[h.contact] > 0)
            lines.append(f"  stress blocks at the hinges (depth N / f_c): {z or '-'}")
        if m.lift_off:
            lines.append(f"  lift off: {'; '.join(arc.contacts[c].label for c in m.lift_off)}")
        if m.sliding:
            lines.append(f"  sliding: {'; '.join(arc.contacts[c].label for c in m.sliding)}")
    neg = [d for d, g in results.items() if g.k < 0]
    if neg:  # the signed loads that hold it form [-k_r, k_l]: 0 outside it
        lines.append(f"the arcade cannot stand under its own weight: k_{neg[0]} < 0 (it needs a "
                     f"horizontal load toward {'-x' if neg[0] == 'l' else '+x'} to stand)")
    if arc.fc and (ramp is not None or response is not None):
        lines.append("the contact engine's blocks do not crush (rigid corners, infinite f_c): "
                     "its ramp is compared with the LP at infinite f_c")
    if ramp is not None:
        lines.append("contact engine ramp (pymunk):")
        lines.append("  dir  LP k      engine k  [bracket]             engine/LP - 1  hinges")
        for d, g in (engine_ref or results).items():
            r = getattr(ramp, d)
            same = sorted(r.hinges) == sorted((h.contact, h.end) for h in g.hinges)
            lines.append(f"  {d}    {g.k:.6f}  {r.multiplier:.6f}  [{r.lower:.6f}, "
                         f"{r.upper:.6f}]  {r.multiplier / g.k - 1:+.4f}        "
                         f"{'the LP hinges' if same else '; '.join(r.places)}"
                         f"{'' if r.mode == 'rocking' else ' (sliding)'}")
    if response is not None:
        rs = response
        what = (f"collapsed at t = {rs.t_collapse:.3f} s" if rs.collapsed else
                f"{'at rest' if rs.status == 'rest' else 'still moving'} at t = "
                f"{rs.t_final:.2f} s")
        lines.append(f"contact engine under {rs.run['motion']}: {what}; peak block rotation "
                     f"{rs.peak_rotation:.4g} rad; {len(rs.moved)} blocks turned by more "
                     f"than 1e-3 rad")
    return "\n".join(lines)


def plot_arcade(arc, results, path) -> str:
    """The blocks (piers grey, voussoirs stone), each direction's hinges (dots) and the blocks'
    velocities (arrows at the mass centres), one panel per direction."""
    from ..reports.plots import STYLE, new_figure, save_figure
    from matplotlib.patches import Polygon
    import numpy as np

    fig, axes = new_figure(len(results), 1, figsize=(9.0, 3.4 * len(results)))
    axes = np.asarray(axes).ravel()
    ext = arc.extent
    for ax, (d, g) in zip(axes, results.items()):
        v = g.mechanism.velocities
        speed = np.hypot(v[:, 0], v[:, 1])
        scale = 0.12 * ext / max(float(speed.max()), 1e-300)
        for i, b in enumerate(arc.blocks):
            face = STYLE.get(f"{b.kind}_face", STYLE["voussoir_face"])
            ax.add_patch(Polygon(b.outline, closed=True, facecolor=face,
                                 edgecolor=STYLE["voussoir_edge"], linewidth=0.5))
        c = arc.centroids
        moving = list(g.mechanism.moving)
        ax.quiver(c[moving, 0], c[moving, 1], v[moving, 0] * scale, v[moving, 1] * scale,
                  angles="xy", scale_units="xy", scale=1.0, color=STYLE["thrust"], width=0.003,
                  label="block velocity (mass centre)")
        if g.zones is not None:  # each contact's stress block about the thrust's crossing
            _draw_zones(ax, arc, g)
        hp = np.array([arc.contacts[h.contact].points[h.end] if h.point is None else h.point
                       for h in g.hinges])
        if len(hp):
            ax.plot(hp[:, 0], hp[:, 1], "o", color=STYLE["hinge"], markersize=6,
                    label="hinge")
        feet = [ct.points for ct in arc.contacts if ct.a == -1]
        for f in feet:
            ax.plot(f[:, 0], f[:, 1], "-", color=STYLE["ground"], linewidth=3)
        ax.set_aspect("equal")
        ax.autoscale_view()
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi + 0.3 * (hi - lo))  # room for the legend above the arches
        arrow = "+x" if d == "l" else "-x"
        ax.set_title(f"loads toward {arrow}: k_{d} = {g.k:.4f}, {len(g.hinges)} hinges, "
                     f"{g.mechanism.dof} dof", fontsize=9)
        ax.legend(loc="upper right", fontsize=7, ncol=2)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
    return str(save_figure(fig, path))


def _draw_zones(ax, arc, g) -> None:
    """The compressed zone of every contact of finite strength: a thick segment of the zone's
    depth along the joint, centred where the thrust crosses it."""
    import numpy as np

    first = True
    for c, ct in enumerate(arc.contacts):
        depth = float(g.zones[c])
        n0, n1 = g.forces[c, 0], g.forces[c, 1]
        if depth <= 0 or n0 + n1 <= 0:
            continue
        p0, p1 = ct.points
        u = (p1 - p0) / max(float(np.hypot(*(p1 - p0))), 1e-300)
        mid = p0 + n1 / (n0 + n1) * (p1 - p0)
        seg = np.array([mid - 0.5 * depth * u, mid + 0.5 * depth * u])
        ax.plot(seg[:, 0], seg[:, 1], "-", color="tab:red", linewidth=3, solid_capstyle="butt",
                zorder=5,
                label="compressed zone (N / f_c)" if first else None)
        first = False


def run_arcade(args) -> int:
    plot = figure_arg(args.plot)
    spec = motion_spec_from_args(args)
    if args.ramp and spec is not None:
        raise CLIError("--ramp: cannot be combined with a ground motion; give one")
    arc = arcade_from_args(args)
    if (args.ramp or spec is not None) and any(c.friction is not None for c in arc.contacts):
        raise CLIError("--arcade: its contacts carry their own friction (a brick arch's ring "
                       "interfaces), which the contact engine does not model; leave out --ramp "
                       "and the ground motion")
    from ..statics.graph import graph_limit

    results = {}
    for d in ("l", "r"):
        if getattr(args, "_say_progress", False):
            _progress(f"arcade: static program in direction {d!r} ({arc.n_blocks} blocks) ...")
        results[d] = graph_limit(arc, d, friction=args.friction)
    ramp = response = None
    engine_ref = results
    progress = None if args.json else _progress
    if args.ramp or spec is not None:
        from ..contact import EngineSettings
        from ..contact.settings import DEFAULT_FRICTION

        settings = EngineSettings(friction=args.friction or DEFAULT_FRICTION)
        if arc.fc:  # the engine does not crush: its ramp's range and reference are Heyman's
            plain = arc.with_fc(None)
            engine_ref = {d: graph_limit(plain, d, friction=args.friction) for d in ("l", "r")}
        motion = None if spec is None else spec.build()
        _check_engine_work(args, arc, settings, engine_ref, motion)
        if args.ramp:
            from ..contact.arcade import arcade_ramp

            ramp = arcade_ramp(arc, settings, progress, k_l=engine_ref["l"].k,
                               k_r=engine_ref["r"].k, tol=args.ramp_tol)
        else:
            from ..contact.arcade import arcade_respond

            response = arcade_respond(arc, motion, settings, t_end=args.t_end)
    written = None
    if args.write:
        from ..geometry.files import write_arcade

        written = write_arcade(arc, args.write)
    if plot:
        from .rings import plot_rings
        from ..geometry.rings import interface_contacts

        plot = (plot_rings if interface_contacts(arc) else plot_arcade)(arc, results, plot)
    if args.json:
        from ..geometry.blocks import arcade_counts

        out = {"arcade": {"name": arc.name, "blocks": arc.n_blocks,
                          "counts": arcade_counts(arc),
                          "contacts": len(arc.contacts), "spans": [list(s) for s in arc.spans],
                          "piers": [list(p) for p in arc.piers], "kinds": list(arc.kinds),
                          "labels": [c.label for c in arc.contacts],
                          **({"fc": dict(arc.fc)} if arc.fc else {})},
               "k_l": results["l"].k, "k_r": results["r"].k,
               "l": results["l"].to_dict(), "r": results["r"].to_dict()}
        from ..geometry.rings import interface_contacts

        if interface_contacts(arc):  # a brick arch: how its rings separate
            from .rings import ring_summary

            out["rings"] = {d: ring_summary(arc, g.mechanism) for d, g in results.items()}
        if ramp is not None:
            out["ramp"] = ramp.to_dict()
        if response is not None:
            out["engine_response"] = response.to_dict()
        emit_json(out)
        return 0
    print(format_result(arc, results, ramp, response, engine_ref))
    say_written(written, plot)
    return 0
