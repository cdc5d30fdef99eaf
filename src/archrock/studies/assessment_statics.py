"""The report's statics sections: geometry, limit analysis, supports, piers, friction and the
governing answer (:mod:`archrock.studies.assessment` orders them)."""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchrockError
from ..geometry import Arch, PolygonArch, VoussoirArch
from .assessment_context import Context
from .assessment_blocks import Figure, Paragraph, Section, Table, _f, _optional_missing, titled


def arch_extent(arch: VoussoirArch) -> tuple[float, float, float, float]:
    """(x_min, x_max, y_min, y_max) of the masonry [m]: of the voussoirs' outlines, so that the
    height is the extrados crown's (the crown is inside a voussoir when n is odd, above the
    corners of the joints).  A circular :class:`Arch`'s arcs are taken exactly (their highest
    point is the extrados radius where an arc crosses the vertical through the centre)."""
    jp = np.asarray(arch.joint_points, float).reshape(-1, 2)
    pts = [jp] + [np.asarray(arch.outline(i), float) for i in range(arch.n)]
    allp = np.vstack(pts)
    x0, x1 = float(allp[:, 0].min()), float(allp[:, 0].max())
    y0, y1 = float(allp[:, 1].min()), float(allp[:, 1].max())
    if isinstance(arch, Arch):
        psi = np.asarray(arch.joint_angles, float)
        ro = np.asarray(arch.extrados_radii, float)
        for i in range(arch.n):  # exact extremes of each extrados arc (centre at the origin)
            a, b = sorted((psi[i], psi[i + 1]))
            for ang, fx, fy in ((0.5 * math.pi, 0, 1), (0.0, 1, 0), (math.pi, -1, 0)):
                if a <= ang <= b:
                    x0, x1 = min(x0, fx * ro[i]), max(x1, fx * ro[i])
                    y1 = max(y1, fy * ro[i])
    return x0, x1, y0, y1


def _shape_lines(arch: VoussoirArch) -> tuple[str, dict]:
    """The arch's defining dimensions as a sentence and a dict: R, t, t/R and the embrace of a
    circular arch; shape, span, rise, rise/span and thickness of a family's."""
    if isinstance(arch, Arch):
        R, t = np.asarray(arch.radii, float), np.asarray(arch.thicknesses, float)
        emb = math.degrees(float(np.sum(arch.spans)))
        d = {"radius": float(R.mean()), "thickness": float(t.mean()),
             "t_over_R": float((t / R).mean()), "embrace_deg": emb}
        if np.ptp(R) <= 1e-12 * R.mean() and np.ptp(t) <= 1e-12 * t.mean():
            txt = (f"mean radius R = {R[0]:g} m, thickness t = {t[0]:g} m, t/R = "
                   f"{t[0] / R[0]:.4f}, embrace {emb:g} deg")
        else:
            d.update(radius_range=[float(R.min()), float(R.max())],
                     thickness_range=[float(t.min()), float(t.max())])
            txt = (f"mean radius R = {R.mean():.4g} m ({R.min():.4g}-{R.max():.4g}), thickness "
                   f"t = {t.mean():.4g} m ({t.min():.4g}-{t.max():.4g}), mean t/R = "
                   f"{d['t_over_R']:.4f}, embrace {emb:.4g} deg")
        return txt, d
    recipe = getattr(arch, "recipe", None)
    if recipe:
        S, F, t = recipe["span"], recipe["rise"], recipe["thickness"]
        tc = recipe.get("thickness_crown")
        d = {"shape": recipe["shape"], "span": S, "rise": F, "rise_over_span": F / S,
             "thickness": t, "thickness_crown": tc, "t_over_span": t / S,
             "joints": recipe.get("joints")}
        txt = (f"{recipe['shape']} family: centreline span S = {S:g} m, rise F = {F:g} m, "
               f"F/S = {F / S:.4f}, thickness t = {t:g} m"
               + (f" (crown {tc:g} m)" if tc is not None else "")
               + f", t/S = {t / S:.4f}, {recipe.get('joints', 'normal')} joints")
        return txt, d
    return "a polygon arch (surveyed or drawn): its dimensions are those measured below", {}


@titled('geometry', 'Geometry')
def section_geometry(ctx) -> Section:
    arch = ctx.arch
    jp = np.asarray(arch.joint_points, float)
    x0, x1, y0, y1 = arch_extent(arch)
    span, rise = x1 - x0, y1 - y0
    shape_txt, shape = _shape_lines(arch)
    masses = np.asarray(arch.masses, float)
    from ..geometry.blocks import arch_phrase, block_counts, block_name, describe_blocks

    counts = block_counts(arch)
    piers = counts["piers"] > 0
    # on piers each block named by kind (voussoirs in the arch's own numbering)
    rows = tuple((f"{i} ({block_name(arch, i)})" if piers else i, f"{m:.1f}", f"{c[0]:.3f}",
                  f"{c[1]:.3f}", f"{math.hypot(*(jp[i, 1] - jp[i, 0])):.3f}")
                 for i, (m, c) in enumerate(zip(masses, arch.centroids)))
    kind = "circular (exact sectors)" if isinstance(arch, Arch) else type(arch).__name__

    # blocks by kind: "an arch of 9 voussoirs on two piers", never "of 11 voussoirs"
    adjective = {"Arch": "circular (exact sectors)", "PolygonArch": "polygon",
                 "FamilyArch": "family"}.get(type(arch).__name__, "")
    blocks = [Paragraph(f"{arch.name}: {arch_phrase(arch, adjective)}; {shape_txt}."),
              Paragraph(f"Measured on the masonry: overall span {span:.3f} m (outside to outside), "
                        f"height {rise:.3f} m (from the lowest point of the springings to the top "
                        f"of the extrados at the crown), mass {masses.sum():.1f} kg per metre of "
                        f"depth" + (f", {len(arch.loads)} attached load(s)" if arch.loads else "")
                        + "."),
              Figure("arch", f"{arch.name}: {'blocks' if piers else 'voussoirs'} and joints "
                             f"(joint 0 at the left {'pier foot' if piers else 'springing'}).",
                     arch),
              Table(("block" if piers else "voussoir", "mass [kg/m]", "x_G [m]", "y_G [m]",
                     "joint i contact length [m]"), rows,
                    ("Each block (piers and voussoirs, in chain order from the left pier's foot)"
                     if piers else "Each voussoir") + " with its loads; joint i is its left face.")]
    data = {"name": arch.name, "kind": kind, "voussoirs": counts["voussoirs"], "blocks": counts,
            "span": span, "height": rise,
            "mass": float(masses.sum()), "dimensions": shape, "geometry": arch.to_dict(),
            "units": {"span": "m", "height": "m", "mass": "kg/m", "radius": "m",
                      "thickness": "m", "embrace_deg": "deg", "rise": "m"}}
    head = [("arch", shape_txt), ("blocks", describe_blocks(arch)),
            ("span x height [m]", f"{span:.3f} x {rise:.3f}"),
            ("mass [kg/m]", f"{masses.sum():.1f}")]
    return Section("geometry", "Geometry", tuple(blocks), data, tuple(head))


@titled('limit', 'Limit analysis (both directions)')
def section_limit(ctx: Context) -> Section:
    lim = ctx.limit
    rows = []
    for d in ("l", "r"):
        m = lim.mechanism(d)
        hinges = ", ".join(f"{lab}: joint {h.joint} {h.edge}" for lab, h in m.labelled())
        st = lim.static_k_l if d == "l" else lim.static_k_r
        rows.append((f"M_{d}", _f(m.multiplier, ".6f"), _f(st, ".6f"), m.label, hinges))
    blocks = (
        Paragraph("Horizontal forces proportional to the weight, toward +x (M_l) or -x (M_r), "
                  + ("with Heyman's hypotheses" if ctx.arch.fc is None else
                     f"with no tension, no sliding and a compressive strength f_c = "
                     f"{ctx.arch.fc:g} MPa (hinges at the stress blocks' centres; section "
                     f"Crushing)")
                  + "; k is the smallest multiplier of the weight that "
                  "opens a four-hinge mechanism (kinematic enumeration), checked by the static "
                  f"theorem (a linear program): they differ by {_f(lim.discrepancy, '.1e')}. "
                  "The arch rocks when the ground acceleration reaches -k_l g (M_l) or +k_r g (M_r)."),
        Table(("mechanism", "k (kinematic)", "k (static LP)", "hinges", "A..D from the leading side"),
              tuple(rows)),
        Figure("limit", "Collapse mechanisms and lines of thrust at the collapse multipliers "
                        "(as the paper's Fig. 3), both directions.", lim),
    )
    data = {"k_l": lim.k_l, "k_r": lim.k_r, "k": lim.k, "static_k_l": lim.static_k_l,
            "static_k_r": lim.static_k_r, "discrepancy": lim.discrepancy, "method": lim.method,
            "mechanism_l": lim.mechanism_l.to_dict(), "mechanism_r": lim.mechanism_r.to_dict(),
            "units": {"k": "g"}}
    try:
        fr = ctx.friction
    except Exception:  # noqa: BLE001 - the friction section says why; k stands without it
        fr = None
    notes = {d: friction_note(fr, d) for d in ("l", "r")}
    if fr is not None:
        data["friction"] = {"mu": fr["mu"], "needed": fr["needed"], "k_with_mu": fr["with_mu"],
                            "with_mu_error": fr["with_mu_error"], "notes": notes,
                            "caveat": friction_caveat(fr)}
        if any(notes.values()):
            blocks = blocks + (Paragraph("Friction: " + " ".join(
                f"M_{d}: {notes[d]}." for d in ("l", "r") if notes[d])),)
    head = tuple((f"k_{d} [g]", f"{getattr(lim, f'k_{d}'):.6f}"
                  + (f" - {notes[d]}" if notes[d] else "")) for d in ("l", "r"))
    return Section("limit", "Limit analysis (both directions)", blocks, data, head)


def _support_capacity(arch, base, mv, blocks: list, data: dict, head: list) -> None:
    """The capacity that remains along the movement's direction (and the gaps that close
    first), into ``blocks``, ``data`` and ``head`` of the supports section."""
    from ..statics.supports import gap_closing, movement_capacity, movement_size

    cap = movement_capacity(base, mv)
    mag = movement_size(base, mv)  # in the capacity's units: rad for a turn alone, else m
    unit = "rad" if cap.fraction is None else "m"
    left = cap.capacity - mag
    mech = ", ".join(f"{h.joint}{h.edge[0]}" for h in cap.mechanism)
    span = "" if cap.fraction is None else f"{100 * cap.fraction:.3g}% of the span; "
    blocks.append(Paragraph(
        f"Pushed further the same way, the arch stands up to {cap.capacity:.4g} {unit} of "
        f"this movement ({span}{cap.reason}, hinges {mech}): {left:.4g} {unit} remain, "
        f"{cap.capacity / mag:.3g} times the movement so far"
        + (f" (a turn with a translation is measured as hypot(spread, settlement, rotation x "
           f"{base.size:.4g} m), docs/supports.md)" if mv.rotation and unit == "m" else "")
        + "."))
    data["capacity"] = {k: v for k, v in cap.to_dict().items() if k != "curve"}
    data["capacity_remaining"] = left
    data["units"]["capacity"] = unit
    head.append((f"support capacity remaining [{unit}]",
                 f"{left:.4g} ({cap.capacity / mag:.3g} x the movement)"))
    gc = gap_closing(arch)
    if gc is not None:
        shut = sorted(set(gc.closing_l) | set(gc.closing_r))
        blocks.append(Paragraph(
            f"Before those multipliers, the open joints' point contacts let the arch rock "
            f"from k_l = {gc.k_l:.4g}, k_r = {gc.k_r:.4g} g, turning joint(s) "
            f"{', '.join(map(str, shut))} back until their gaps close: a bounded motion, "
            f"not a collapse."))
        data["gap_closing"] = gc.to_dict()


@titled('supports', 'Supports that have moved')
def section_supports(ctx: Context) -> Section | None:
    """The arch on moved supports (docs/supports.md): the movement, the hinges it opened, the
    multipliers on the displaced arch beside those on fixed supports, and the capacity that
    remains along the movement's direction.  None (left out) on fixed supports."""
    from ..statics.limit import limit_analysis
    from ..statics.supports import displace, moved_parts

    base, mv = moved_parts(ctx.arch)
    if mv is None:
        return None
    lim, fixed = ctx.limit, limit_analysis(base, verify=False)
    st = displace(base, mv)
    labels = ", ".join(f"{h.joint}{h.edge[0]}" for h in st.hinges) or "none (a rigid move)"
    rows = [("k_l [g]", f"{fixed.k_l:.6f}", f"{lim.k_l:.6f}"),
            ("k_r [g]", f"{fixed.k_r:.6f}", f"{lim.k_r:.6f}")]
    data = {"movement": mv.to_dict(), "hinges": [h.to_dict() for h in st.hinges],
            "points": st.points.tolist(), "fixed": {"k_l": fixed.k_l, "k_r": fixed.k_r},
            "moved": {"k_l": lim.k_l, "k_r": lim.k_r}, "units": {"k": "g", "H": "N/m",
                                                                 "movement": "m"}}
    text = (f"The supports have moved: {mv.describe()}. Hinges {labels} opened; the arch is "
            f"analysed on the displaced geometry with those joints bearing on whole faces again "
            f"(re-closed, docs/supports.md), as every other section of this report takes it.")
    if st.hinges:
        rows.append(("thrust H [kN/m]", "-", f"{st.thrust / 1e3:.4g}"))
        rows.append(("crown drop [m]", "0", f"{st.crown_drop:.4g}"))
        data.update(H=st.thrust, crown_drop=st.crown_drop)
    head = [("support movement", mv.describe())]
    blocks = [Paragraph(text)]
    if np.any(mv.relative) or mv.rotation:
        _support_capacity(ctx.arch, base, mv, blocks, data, head)
    blocks += [Table(("", "fixed supports", "moved supports"), tuple(rows)),
               Figure("arch", f"{ctx.arch.name}: the arch on its moved supports.", ctx.arch)]
    return Section("supports", "Supports that have moved", tuple(blocks), data, tuple(head))
def _piers_of(arch):
    """(the arch on piers, a sentence when its piers were guessed) of the report's arch, or
    (None, "") on rigid ground.  A geometry file that names no kinds: the end blocks the
    single-DOF check takes for piers (heavy, rising as columns from level foundations), if any."""
    from ..geometry.piers import ArchOnPiers

    if isinstance(arch, ArchOnPiers) and arch.pier_blocks:
        return arch, ""
    from ..dynamics.piers import pier_blocks

    found, how = pier_blocks(arch) if isinstance(arch, PolygonArch) else ((), "none")
    if how != "geometry":
        return None, ""
    kinds = tuple("pier" if i in found else "voussoir" for i in range(arch.n))
    piers = ArchOnPiers(arch.intrados, arch.extrados, arch.density, arch.name, arch.loads,
                        block_kinds=kinds)
    return piers, (f" The geometry names no block kinds: block(s) "
                   f"{', '.join(map(str, found))} are taken for piers (heavy end blocks rising "
                   f"as columns from level foundations; kinds in the file would say so).")


def _pier_sizes(sizes: dict, guessed: str) -> tuple[str, list]:
    """Each pier's size in words, and the paragraph and table that give them."""
    rows = tuple((side, sz["kind"], sz["blocks"], f"{sz['height']:.3f}",
                  f"{sz['width_top']:.3f}" if math.isfinite(sz["width_top"]) else "-",
                  f"{sz['width_foot']:.3f}",
                  f"{sz['lean_deg']:.3f}") for side, sz in sizes.items())
    words = "; ".join(f"{side} {sz['kind']} {sz['height']:.3g} m high, "
                      f"{sz['width_top']:.3g} m wide at its top and {sz['width_foot']:.3g} m at "
                      f"its foot, {sz['blocks']} block(s)"
                      + (f", {abs(sz['lean_deg']):.3g} deg out of plumb "
                         f"{'outward' if sz['lean_deg'] > 0 else 'inward'}"
                         if abs(sz["lean_deg"]) > 1e-9 else "") for side, sz in sizes.items())
    return words, [Paragraph(f"The arch stands on piers ({words}). Blocks are numbered from the "
                             f"left pier's foot; hinges are named where they are on the drawing."
                             + guessed),
                   Table(("pier", "kind", "blocks", "height [m]", "width at top [m]",
                          "width at foot [m]", "lean [deg, outward +]"), rows,
                         "Sizes in each pier's own frame (turned back by its lean).")]


def _pier_hinges(arch, lim) -> tuple[list, list]:
    """The rows (mechanism, hinge, joint, where) of the limit mechanisms' hinges, and those
    that lie in the piers, in words."""
    from ..geometry.piers import hinge_place

    hinge_rows, at_piers = [], []
    for d in ("l", "r"):
        for lab, h in lim.mechanism(d).labelled():
            place = hinge_place(arch, h.joint, h.edge)
            hinge_rows.append((f"M_{d}", lab, f"{h.joint}{h.edge[0]}", place))
            if "pier" in place or "buttress" in place:
                at_piers.append(f"M_{d} {lab}: {place}")
    return hinge_rows, at_piers


def _least_pier_widths(arch, sizes: dict) -> tuple[list, Paragraph]:
    """The buttress question: the least width of rectangular piers of each pier's height with
    which the arch stands (statics.buttress), as data and in words."""
    from ..geometry.piers import arch_without_piers
    from ..statics.buttress import minimum_pier_width

    mins = {}
    for h in sorted({round(sz["height"], 9) for sz in sizes.values()}):
        try:
            mw = minimum_pier_width(arch_without_piers(arch), h, tol=1e-6)
            mins[h] = {"width": mw.width, "governed_by": mw.governed_by}
        except ArchrockError as exc:
            mins[h] = {"width": None, "error": " ".join(str(exc).split())}
    txt = []
    for side, sz in sizes.items():
        m = mins[round(sz["height"], 9)]
        if m["width"] is None:
            txt.append(f"{side}: not computed ({m['error']})")
        else:
            ratio = sz["width_top"] / m["width"] if math.isfinite(sz["width_top"]) else math.nan
            txt.append(f"{side}: {m['width']:.4f} m for piers {sz['height']:.3g} m high "
                       f"(this pier {sz['width_top']:.3g} m, {ratio:.2f} x"
                       + (", the springing joint's own width governs" if m["governed_by"] ==
                          "springing" else "") + ")")
    return [{"height": h, **v} for h, v in mins.items()], Paragraph(
        "The least width of two rectangular monolithic piers of this height with which the "
        "arch stands under its own weight (a line of thrust inside arch and piers; Heyman "
        "1995, Ochsendorf 2002): " + "; ".join(txt) + ".")


def _single_dof(ctx, data: dict, blocks: list, head: list) -> None:
    """One degree of freedom or more (docs/piers-dynamics.md): the check into ``data``, and a
    warning into ``blocks`` and ``head`` where the four-link model cannot follow the piers."""
    try:
        from ..dynamics.piers import single_dof_check

        chk = single_dof_check(ctx.model)
        data["single_dof"] = chk.to_dict()
        if not chk.valid:
            blocks.append(Paragraph(
                f"WARNING single degree of freedom not valid: {chk.reason}. The four-link "
                f"model's figures would be unconservative here (docs/piers-dynamics.md): the "
                f"response and the curves of this report are the contact engine's (section "
                f"Governing answer), the four-link model's appear nowhere."))
            head.append(("four-link model on piers", "not valid: a pier rocks with the arch "
                         "(figures can be unconservative)"))
    except ArchrockError as exc:
        data["single_dof"] = {"error": " ".join(str(exc).split())}


@titled('piers', 'The piers')
def section_piers(ctx: Context) -> Section | None:
    """An arch on piers (docs/piers.md): each pier's size, where the mechanisms' hinges are
    (named as ``archrock limit`` names them), the least width of rectangular piers of that
    height that carry the arch (statics.buttress), and whether the four-link model (one
    degree of freedom) can follow the structure (dynamics.piers).  None (left out) on rigid
    ground."""
    from ..geometry.piers import pier_sizes

    arch, guessed = _piers_of(ctx.arch)
    if arch is None:
        return None
    sizes = pier_sizes(arch)
    words, blocks = _pier_sizes(sizes, guessed)
    hinge_rows, at_piers = _pier_hinges(arch, ctx.limit)
    blocks.append(Table(("mechanism", "hinge", "joint", "where"), tuple(hinge_rows),
                        "The hinges of the limit mechanisms, named as archrock limit names "
                        "them."))
    data = {"piers": sizes, "hinges": [dict(zip(("mechanism", "hinge", "joint", "place"), r))
                                       for r in hinge_rows],
            "units": {"height": "m", "width_top": "m", "width_foot": "m", "foot_level": "m",
                      "lean_deg": "deg"}}
    head = [("piers", words)]
    if at_piers:
        blocks.append(Paragraph("Hinges in the piers: " + "; ".join(at_piers) + "."))
    data["minimum_pier_width"], least = _least_pier_widths(arch, sizes)
    blocks.append(least)
    _single_dof(ctx, data, blocks, head)
    return Section("piers", "The piers", tuple(blocks), data, tuple(head))


def _mu(x) -> str:
    return "no finite friction" if x is None else f"{x:.3f}"


def friction_note(fr: dict | None, d: str) -> str:
    """'' where the report's friction (AssessConfig.friction) is enough for k in direction
    ``d``, or where sliding is excluded by the user (mu None); else what k needs and the
    multiplier with that friction (or why there is none)."""
    if fr is None or fr["mu"] is None:
        return ""
    need = fr["needed"][d]
    mu = fr["mu"]
    if need is not None and need <= mu:
        return ""
    what = ("needs more friction than any finite coefficient (no finite friction)"
            if need is None else f"needs friction mu >= {need:.3f}")
    head = f"{what}, more than the report's mu = {mu:g}; "
    if fr["with_mu"] is not None:
        return head + f"with mu = {mu:g} the joints slide first, at k_{d} = {fr['with_mu'][d]:.4f}"
    return head + f"with mu = {mu:g} no multiplier ({fr['with_mu_error']})"


def friction_caveat(fr: dict | None) -> str:
    """One sentence for the verdict where k needs more friction than the report's mu ('' where
    it does not): both directions at once when they need the same."""
    if fr is None:
        return ""
    short = [d for d in ("l", "r") if friction_note(fr, d)]
    if not short:
        return ""
    need, wm = fr["needed"], fr["with_mu"]
    same = (len(short) == 2 and (need["l"] is None) == (need["r"] is None)
            and (need["l"] is None or math.isclose(need["l"], need["r"], rel_tol=1e-6))
            and (wm is None or math.isclose(wm["l"], wm["r"], rel_tol=1e-6)))
    if same:
        note = friction_note(fr, "l").replace("k_l =", "k =")
        return f"k (both directions) {note}"
    return "; ".join(f"k_{d} {friction_note(fr, d)}" for d in short)


@titled('friction', 'Friction the thrust needs')
def section_friction(ctx: Context) -> Section:
    """OPTIONAL: the friction coefficient the thrust needs (archrock.statics.friction), and the
    multipliers at the report's friction (AssessConfig.friction)."""
    title = "Friction the thrust needs"
    fr = ctx.friction
    if fr is None:
        return _optional_missing("friction", title, "statics.friction",
                                 "The friction the limit thrust needs at the joints")
    need, mu = fr["needed"], fr["mu"]  # need: {"l": mu or None (no finite friction), "r": ...}
    lim = ctx.limit
    rows = []
    for d in ("l", "r"):
        k_mu = ("-" if fr["with_mu"] is None else f"{fr['with_mu'][d]:.4f}")
        gov = ("-" if fr["sliding_governs"] is None else
               "sliding" if fr["sliding_governs"][d] else "hinges (no sliding)")
        rows.append((f"M_{d}", _mu(need[d]), f"{getattr(lim, f'k_{d}'):.4f}", k_mu, gov))
    intro = ("The smallest Coulomb friction coefficient at the joints with which the thrust at "
             "collapse needs no sliding (Heyman's no-sliding hypothesis made explicit; static "
             "LP, docs/friction.md). ")
    if fr.get("with_crushing") is not None:
        intro += (f"With the masonry's f_c = {fr['with_crushing']:g} MPa it is read on the "
                  "finite-strength collapse's thrust line, and the multipliers with friction "
                  "solve friction and crushing together (docs/crushing.md). ")
    data = {"available": True, "friction_needed_l": need["l"], "friction_needed_r": need["r"],
            "no_finite_friction": {d: need[d] is None for d in ("l", "r")}, "mu": mu,
            "k_with_mu": fr["with_mu"], "sliding_governs": fr["sliding_governs"],
            "with_mu_error": fr["with_mu_error"]}
    if mu is None:
        data["left_out"] = "sliding excluded by the user (--friction none)"
        return Section("friction", title, (
            Paragraph(intro + "Sliding is excluded by the user (--friction none, Heyman's "
                      "hypothesis): the analysis with friction is left out, and k stands on "
                      "that hypothesis; the table says how much friction it takes."),
            Table(("mechanism", "friction coefficient needed", "k, no sliding [g]"),
                  tuple(r[:3] for r in rows))), data)
    notes = [f"M_{d}: {friction_note(fr, d)}." for d in ("l", "r") if friction_note(fr, d)]
    verdict = (" ".join(notes) if notes else
               f"The report's friction mu = {mu:g} is enough for the multipliers above in both "
               f"directions: the joints do not slide before the hinges form.")
    if fr["with_mu_error"] and not notes:
        verdict += f" With mu = {mu:g}: {fr['with_mu_error']}."
    return Section("friction", title, (
        Paragraph(intro + f"Beside it, the multipliers with the report's friction mu = {mu:g} "
                  "(one coefficient for the whole report: this analysis, the governing answer, "
                  "the routing of the dynamics and the contact engine; `archrock assess "
                  "--friction MU|none` sets it; EN 1996-1-1's 0.4 gives a conservative check). "
                  "Joints with less friction than needed slide before the hinge mechanism "
                  "forms. " + verdict),
        Table(("mechanism", "friction coefficient needed", "k, no sliding [g]",
               f"k with mu = {mu:g} [g]", f"at mu = {mu:g} governs"), tuple(rows))), data)


@titled('governing', 'Governing answer')
def section_governing(ctx: Context) -> Section:
    """Which capacity governs and why (studies.governing, with the contact engine where it
    imports), and which dynamic model governs and why (enginestudy.choose_dynamics)."""
    gov, choice = ctx.governing, ctx.dynamics
    g = gov.governing
    if g is None:
        cap_txt = f"No governing capacity: {gov.why_none}."
        head = [("governing capacity [g]", f"none ({gov.why_none})")]
    else:
        cap_txt = (f"The governing capacity is k = {g.value:.6f} g, {g.directions}, from the "
                   f"{g.analysis} (mechanism: {g.mechanism}; hypotheses: "
                   f"{'; '.join(g.hypotheses)}): {g.why}.")
        head = [("governing capacity [g]", f"{g.value:.6f} ({g.analysis}, {g.directions}, "
                                           f"{'; '.join(g.hypotheses)})")]
    rows = []
    for a in gov.analyses:  # one row per analysis and direction
        for d in ("l", "r"):
            k = a.k(d)
            rows.append((a.name, f"M_{d}", "-" if k is None else f"{k:.4f}", a.mechanism(d),
                         "holds" if a.holds[d] else "does not hold", a.why[d]))
    used = "the contact engine" if choice.engine else "the four-link model"
    dyn_txt = (f"Dynamics: {used} governs the response, the curves and the fragility of this "
               f"report ({choice.reason}).")
    head.append(("dynamics", f"{used} ({choice.reason})"))
    blocks = [Paragraph(f"One friction for the whole report: {gov.friction_words}. " + cap_txt),
              Table(("analysis", "direction", "k [g]", "mechanism", "its hypotheses",
                     "why"), tuple(rows), "Every analysis that ran, and whether its hypotheses "
                                          "hold in each direction.")]
    if gov.findings:
        blocks.append(Paragraph("Finding: " + " ".join(gov.findings)))
    if gov.left_out:
        blocks.append(Paragraph("Left out: " + "; ".join(f"{n}: {w}" for n, w in gov.left_out)
                                + "."))
    blocks.append(Paragraph(dyn_txt))
    data = {**gov.to_dict(), "dynamics": choice.to_dict()}
    return Section("governing", "Governing answer", tuple(blocks), data, tuple(head))
