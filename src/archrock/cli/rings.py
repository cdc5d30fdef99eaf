"""``archrock arcade --rings N``: a brick arch of several rings (docs/rings.md), its flags, their
checks and the lines and drawing that show the rings' separation."""

from __future__ import annotations

import math

from ._parser import CLIError, _int, finite_float, positive_float

#: the library's field -> the flag that gives it (ArchInputError messages start with the field)
_RING_FLAGS = (("ring_thicknesses", "--ring-thickness"), ("rings", "--rings"),
               ("brick", "--brick"), ("friction", "--ring-friction"),
               ("thickness", "--thickness"), ("radius", "--spans"), ("density", "--density"),
               ("embrace", "--rises"), ("headers", "--headers"))


def add_ring_options(p) -> None:
    from ..geometry.rings import DEFAULT_RING_FRICTION, MAX_RINGS

    g = p.add_argument_group("rings", "a brick arch of several rings on the ground (one span, "
                                      "a semicircle or --shape circular --rises F)")
    g.add_argument("--rings", type=_int, metavar="N",
                   help=f"rings of bricks, 1 to {MAX_RINGS}, from the intrados out (default: "
                        f"as many as --ring-thickness values)")
    g.add_argument("--ring-thickness", type=finite_float, nargs="+", metavar="T",
                   help="thickness of each ring [m], intrados first, adding up to --thickness "
                        "(default: --thickness split equally)")
    g.add_argument("--brick", type=finite_float, metavar="L",
                   help="length of a brick along the arch's centreline [m], > 0 (default "
                        "0.1025: a header in a rowlock ring)")
    g.add_argument("--ring-friction", type=positive_float, metavar="MU",
                   help=f"Coulomb friction of the ring interfaces, > 0 (default "
                        f"{DEFAULT_RING_FRICTION:g})")
    g.add_argument("--ring-cohesion", type=finite_float, metavar="KPA",
                   help="cohesion of the ring interfaces [kPa], >= 0 (default 0)")
    g.add_argument("--headers", type=_int, metavar="M",
                   help="a header course through every ring every M bricks from each "
                        "springing toward the crown, 2 or more (default: none)")
    g.add_argument("--aligned-joints", action="store_true",
                   help="every ring's radial joints on the same radial lines (default: "
                        "bonded, every other ring's joints half a brick along)")


def wants_rings(args) -> bool:
    return args.aligned_joints or any(
        getattr(args, k) is not None for k in ("rings", "ring_thickness", "brick",
                                              "ring_friction", "ring_cohesion", "headers"))


def _renamed(exc):
    from ..errors import ArchInputError

    msg = str(exc)
    for field, flag in _RING_FLAGS:
        if msg.startswith(field):
            rest = msg[len(field):]
            if rest.startswith("["):
                idx, _, rest = rest[1:].partition("]")
                return ArchInputError(f"{flag}: value {int(idx) + 1}{rest}")
            return ArchInputError(f"{flag}{rest}")
    if msg.startswith("cohesion"):
        return ArchInputError(f"--ring-cohesion{msg[len('cohesion'):]}")
    return ArchInputError(msg)


def _check_ring_flags(args) -> None:
    """The flags that a ringed arch cannot take, and the spans it can."""
    other = [f for f, v in (("--arcade", args.arcade), ("--geometry", args.geometry),
                            ("--repeat", args.repeat), ("--voussoirs", args.voussoirs),
                            ("--pier-height", args.pier_height),
                            ("--pier-width", args.pier_width),
                            ("--pier-courses", args.pier_courses)) if v is not None]
    if other:
        raise CLIError(f"--rings: cannot be combined with {', '.join(other)}; a brick arch "
                       f"stands on the ground, its bricks set by --brick")
    if args.ramp or getattr(args, "pulse", None) is not None or \
            getattr(args, "record", None) is not None:
        raise CLIError("--rings: the contact engine (--ramp, a ground motion) does not model "
                       "the ring interfaces' own friction; leave it out")
    if args.spans is None or len(args.spans) != 1:
        raise CLIError("--spans: one span with --rings (the span of the arch's centreline "
                       "[m])")
    if args.shape not in (None, "circular"):
        raise CLIError(f"--shape: {args.shape!r} with --rings; allowed circular (or none: a "
                       f"semicircle)")
    for flag, v in (("--thickness", args.thickness), ("--rises", args.rises)):
        if v is not None and len(v) != 1:
            raise CLIError(f"{flag}: {len(v)} values with --rings; allowed one")


def _circle(span: float, rise: float | None):
    """(centreline radius [m], embrace [deg]) of a circular arch of ``span`` and ``rise``
    (None: a semicircle)."""
    if not 1e-8 <= span <= 1e8:
        raise CLIError(f"--spans: {span:g} is out of range; allowed 1e-8 to 1e8 m")
    if rise is None:
        return span / 2, 180.0
    if not 0 < rise < 1e8:
        raise CLIError(f"--rises: {rise:g} is out of range; allowed > 0 m")
    R = (span * span / 4 + rise * rise) / (2 * rise)
    half = math.asin(min(1.0, span / (2 * R)))
    if rise > span / 2:  # more than a semicircle
        half = math.pi - half
    return R, math.degrees(2 * half)


def ringed_from_args(args):
    """The ringed arch of the options (an Arcade); every error names its flag."""
    from ..errors import ArchInputError
    from ..geometry.rings import DEFAULT_RING_FRICTION, ringed_arch

    _check_ring_flags(args)
    R, embrace = _circle(args.spans[0], None if args.rises is None else args.rises[0])
    ts = args.ring_thickness
    rings = args.rings if args.rings is not None else (len(ts) if ts else None)
    if rings is None:
        raise CLIError("--rings: needed (how many rings of bricks), or --ring-thickness T...")
    if args.thickness is not None:
        t = args.thickness[0]
    elif ts:
        t = sum(ts)
    else:
        t = args.spans[0] / 10
    coh = args.ring_cohesion
    if coh is not None and not 0 <= coh <= 1e6:
        raise CLIError(f"--ring-cohesion: {coh:g} kPa is out of range; allowed 0 to 1e6 kPa")
    try:
        return ringed_arch(R, t, rings, ts, 0.1025 if args.brick is None else args.brick,
                           embrace, 2000.0 if args.density is None else args.density,
                           args.ring_friction or DEFAULT_RING_FRICTION,
                           1e3 * (coh or 0.0), not args.aligned_joints, args.headers or 0,
                           name=f"{rings}-ring brick arch")
    except ArchInputError as exc:
        raise _renamed(exc) from None


def ring_summary(arc, mech) -> dict:
    """The rings' separation in a mechanism, for the JSON: the interface contacts, those that
    open and those that slide (contact indices), and the hinges by ring."""
    from ..geometry.rings import interface_contacts, ring_of

    faces = interface_contacts(arc)
    fs = set(faces)
    opened = sorted({c for c in mech.lift_off if c in fs} | {h.contact for h in mech.hinges
                                                            if h.contact in fs})
    hinges = {}
    for h in mech.hinges:
        r = ring_of(arc.contacts[h.contact].label)
        if h.contact not in fs and r is not None:
            hinges[str(r)] = hinges.get(str(r), 0) + 1
    return {"interfaces": len(faces), "open": opened,
            "sliding": sorted(c for c in mech.sliding if c in fs), "hinges_by_ring": hinges}


def ring_lines(arc, mech) -> list:
    """The lines that say how the rings separate in a mechanism: the interfaces that open or
    slide, and the hinges by ring."""
    from ..geometry.rings import interface_contacts, ring_of

    faces = interface_contacts(arc)
    if not faces:
        return []
    fs = set(faces)
    opened = [c for c in mech.lift_off if c in fs] + [h.contact for h in mech.hinges
                                                      if h.contact in fs]
    slid = [c for c in mech.sliding if c in fs]
    by_ring = {}
    for h in mech.hinges:
        if h.contact in fs:
            continue
        r = ring_of(arc.contacts[h.contact].label)  # "ring 2 joint 5": a header's side too
        if r is not None:
            by_ring[r] = by_ring.get(r, 0) + 1
    hinge_words = ", ".join(f"ring {r}: {k}" for r, k in sorted(by_ring.items()))
    sep = (f"the rings separate: {len(opened)} of {len(faces)} interface contacts open, "
           f"{len(slid)} slide" if opened or slid else "the rings do not separate")
    return [f"  {sep}", f"  hinges in the rings' radial joints: {hinge_words or '-'}"]


def plot_rings(arc, results, path) -> str:
    """The brick arch's mechanism in each direction: the bricks at rest (outlines), the bricks
    moved along the mechanism (a small multiple of its velocities, so that gaps show where the
    rings separate), the hinges (dots) and the ring interfaces that open or slide (lines)."""
    from matplotlib.patches import Polygon
    import numpy as np

    from ..geometry.rings import interface_contacts
    from ..reports.plots import STYLE, new_figure, save_figure

    fig, axes = new_figure(len(results), 1, figsize=(8.0, 3.6 * len(results)))
    axes = np.asarray(axes).ravel()
    faces = set(interface_contacts(arc))
    c = arc.centroids
    for ax, (d, g) in zip(axes, results.items()):
        v = g.mechanism.velocities
        reach = max(float(np.max(np.hypot(
            v[i, 0] - v[i, 2] * (b.outline[:, 1] - c[i, 1]),
            v[i, 1] + v[i, 2] * (b.outline[:, 0] - c[i, 0])))) for i, b in enumerate(arc.blocks))
        s = 0.04 * arc.extent / max(reach, 1e-300)  # the largest point moves 4 % of the extent
        for i, b in enumerate(arc.blocks):
            o = np.asarray(b.outline, float)
            ax.add_patch(Polygon(o, closed=True, fill=False, edgecolor="0.75", linewidth=0.4))
            moved = o + s * np.column_stack([v[i, 0] - v[i, 2] * (o[:, 1] - c[i, 1]),
                                             v[i, 1] + v[i, 2] * (o[:, 0] - c[i, 0])])
            ax.add_patch(Polygon(moved, closed=True, facecolor=STYLE["voussoir_face"],
                                 edgecolor=STYLE["voussoir_edge"], linewidth=0.4, alpha=0.9))
        m = g.mechanism
        shown = {"open": (set(m.lift_off) | {h.contact for h in m.hinges}) & faces,
                 "slide": set(m.sliding) & faces}
        for what, colour in (("open", STYLE["thrust"]), ("slide", STYLE["hinge"])):
            for k, cc in enumerate(sorted(shown[what])):
                p = arc.contacts[cc].points
                ax.plot(p[:, 0], p[:, 1], "-", color=colour,
                        linewidth=0.9 if what == "open" else 2.5,
                        label=(f"ring interface that {'opens' if what == 'open' else 'slides'}"
                               if k == 0 else None))
        hp = np.array([arc.contacts[h.contact].points[h.end] for h in m.hinges
                       if h.contact not in faces]).reshape(-1, 2)
        if len(hp):
            ax.plot(hp[:, 0], hp[:, 1], "o", color="k", markersize=2.5, label="hinge")
        for ct in arc.contacts:
            if ct.a == -1:
                ax.plot(ct.points[:, 0], ct.points[:, 1], "-", color=STYLE["ground"],
                        linewidth=3)
        ax.set_aspect("equal")
        ax.autoscale_view()
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi + 0.3 * (hi - lo))
        ax.set_title(f"loads toward {'+x' if d == 'l' else '-x'}: k_{d} = {g.k:.4f}; "
                     f"{len(shown['open'])} interface contacts open, {len(shown['slide'])} "
                     f"slide (bricks moved along the mechanism)", fontsize=8)
        ax.legend(loc="upper right", fontsize=7, ncol=3)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
    return str(save_figure(fig, path))
