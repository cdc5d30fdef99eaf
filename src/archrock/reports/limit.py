"""Reports of a limit analysis: the ``archrock limit --json`` object and the readable table.

Circular arches are described by their voussoirs' spans, radii and thicknesses; any other arch
(a :class:`~archrock.geometry.PolygonArch`, a family) by each voussoir's area, mass and mass
centre.  Loads attached to voussoirs are listed for both.
"""

from __future__ import annotations

import math

import numpy as np

from ..geometry import Arch, ArchOnPiers
from ..geometry.piers import hinge_place
from ..geometry.blocks import block_counts, block_name, describe_blocks

__all__ = ["limit_summary", "format_limit_table", "friction_summary", "friction_lines",
           "thrust_range_line", "min_pier_width_line", "friction_only_summary",
           "format_friction_only", "format_governing"]


def _on_piers(arch) -> bool:
    return isinstance(arch, ArchOnPiers) and bool(arch.pier_blocks)


def _voussoir_properties(arch) -> list[dict]:
    """Area [m^2] of each voussoir's masonry, mass [kg/m] and mass centre [m] with its loads;
    on piers, each block's kind ("pier", "buttress" or "voussoir") too."""
    kinds = arch.block_kinds if _on_piers(arch) else None
    return [{**({"kind": kinds[i]} if kinds else {}),
             "area": float(a), "mass": float(m), "centroid": [float(c[0]), float(c[1])]}
            for i, (a, m, c) in enumerate(zip(arch.areas, arch.masses, arch.centroids))]


def _place(arch, h) -> dict:
    """{"place": ...} naming a hinge on the drawing, for an arch on piers (else nothing)."""
    return {"place": hinge_place(arch, h.joint, h.edge)} if _on_piers(arch) else {}


def limit_summary(result, min_thickness=None, needed=None, friction=None,
                  min_thickness_friction=None, thrust=None, min_pier_width=None) -> dict:
    """JSON-ready summary of a LimitResult (the ``archrock limit --json`` object); ``needed``
    ({"l", "r"}, :func:`archrock.statics.friction.friction_needed`) and ``friction`` (a
    :class:`~archrock.statics.friction.FrictionResult`) add the keys of :func:`friction_summary`;
    ``min_thickness_friction``: the friction coefficient ``min_thickness`` was found with;
    ``thrust`` (a :class:`~archrock.statics.thrust.ThrustRange`) adds ``thrust_min`` and ``thrust_max``
    (each ``H`` [N/m], ``hinges`` [{joint, edge}], ``points`` [[x, y]] [m]);
    ``min_pier_width`` (a :class:`~archrock.statics.buttress.MinimumPierWidth`) adds
    ``min_pier_width``."""
    arch = result.arch
    d = result.to_dict()
    d.pop("arch", None)
    if isinstance(arch, Arch):
        units = {"k": "g (horizontal load / weight)", "span_deg": "deg", "radius": "m",
                 "thickness": "m", "density": "kg/m^3"}
    else:
        units = {"k": "g (horizontal load / weight)", "intrados": "m", "extrados": "m",
                 "density": "kg/m^3", "area": "m^2", "mass": "kg/m", "centroid": "m"}
    if arch.loads:
        units.update({"load mass": "kg/m", "load at": "m"})
    out = {
        "arch": arch.name,
        "k": result.k,
        **d,
        "hinge_labels": {
            # A..D from the mechanism's leading side (A leftmost for M_l, rightmost for M_r)
            dirn: [{"label": lab, **h.to_dict(), **_place(arch, h)}
                   for lab, h in result.mechanism(dirn).labelled()]
            for dirn in ("l", "r")
        },
        # the four-link model (respond, studies) holds only where four-hinge mechanisms govern
        "four_link_holds": result.four_hinge,
        "geometry": arch.to_dict(),
        "blocks": block_counts(arch),
        **({} if isinstance(arch, Arch) else {"voussoirs": _voussoir_properties(arch)}),
        **({"block_kinds": list(arch.block_kinds)} if _on_piers(arch) else {}),
        "units": units,
    }
    if min_thickness is not None:
        t = min_thickness.thicknesses
        out["min_thickness"] = {
            "factor": min_thickness.factor,
            "ratio_t_over_R": min_thickness.ratio,
            "thicknesses": None if t is None else [float(x) for x in t],
            "friction": min_thickness_friction,
        }
    if needed is not None or friction is not None:
        out.update(friction_summary(needed, friction))
    if thrust is not None:
        td = thrust.to_dict()
        out["thrust_min"], out["thrust_max"] = td["thrust_min"], td["thrust_max"]
        out["units"]["H"] = "N/m (horizontal thrust per metre of depth)"
    if min_pier_width is not None:
        out["min_pier_width"] = min_pier_width.to_dict()
    return out


def min_pier_width_line(mpw) -> str:
    """One line of a :class:`~archrock.statics.buttress.MinimumPierWidth`."""
    if mpw.governed_by == "springing":
        why = ("the narrowest pier the springing joint allows already stands: the width does "
               "not limit the arch")
    else:
        H, V = mpw.springing_force
        why = (f"the thrust (H = {H / 1e3:.4g} kN/m, V = {V / 1e3:.4g} kN/m at the pier top) "
               f"through the pier's outer foot corner")
    return (f"minimum pier width under self-weight, piers {mpw.height:g} m high: "
            f"{mpw.width:.4f} m ({why})")


def friction_summary(needed=None, friction=None) -> dict:
    """JSON keys of a friction analysis: ``friction_needed_l``/``_r`` (the friction the
    no-sliding collapse needs); with a FrictionResult ``friction_mu``, ``friction_k_l``/``_r``
    (multipliers with friction), ``sliding_governs_l``/``_r``, ``friction_joints_l``/``_r``
    (joints where the thrust needs the most friction) and ``friction`` (the full record)."""
    out = {}
    if needed is None and friction is not None:
        needed = {d: friction.direction(d).friction_needed for d in ("l", "r")}
    if needed is not None:
        reasons = _needed_reasons(needed, friction)
        out["friction_needed_l"] = needed["l"]
        out["friction_needed_r"] = needed["r"]
        # null above: why (no mechanism, or no finite friction: archrock.statics.friction.MU_CAP)
        out["friction_needed_reason_l"] = reasons["l"]
        out["friction_needed_reason_r"] = reasons["r"]
    if friction is not None:
        out["friction_mu"] = friction.mu
        for d in ("l", "r"):
            fd = friction.direction(d)
            out[f"friction_k_{d}"] = fd.multiplier
            out[f"sliding_governs_{d}"] = fd.sliding_governs
            out[f"friction_joints_{d}"] = list(fd.joints)
        out["friction"] = friction.to_dict()
    return out


def _needed_reasons(needed, friction) -> dict:
    """Why a friction needed is None: ``needed.reasons`` (archrock.statics.friction.FrictionNeeded) or
    the FrictionResult's ``friction_needed_reason``; None where unknown or a number."""
    reasons = getattr(needed, "reasons", None)
    if reasons is None and friction is not None:
        reasons = {d: friction.direction(d).friction_needed_reason for d in ("l", "r")}
    return {d: (reasons or {}).get(d) for d in ("l", "r")}


def _needing_friction(fd) -> str:
    """The joints of one direction's friction analysis that need the most friction, with |T|/N."""
    return ", ".join(f"{j} ({fd.ratios[j]:.4f})" for j in fd.joints)


def _friction_rows(friction, frictionless: bool) -> list[str]:
    """One table row a direction: k with friction, k without it (when ``frictionless``),
    whether sliding governs, and the joints needing most friction."""
    rows = []
    for d in ("l", "r"):
        fd = friction.direction(d)
        free = f"{fd.frictionless:15.4f}  " if frictionless else ""
        rows.append(f"  M_{d}        {fd.multiplier:12.4f}  {free}"
                    f"{'yes' if fd.sliding_governs else 'no':>15}  {_needing_friction(fd)}")
    return rows


def friction_lines(needed=None, friction=None) -> list[str]:
    """Readable lines of a friction analysis (see :func:`friction_summary`)."""
    if needed is None and friction is None:
        return []
    if needed is None:
        needed = {d: friction.direction(d).friction_needed for d in ("l", "r")}
    reasons = _needed_reasons(needed, friction)
    # None: the reason's first words ("no finite friction", "no mechanism"), the reason below
    fmt = {d: (f"{needed[d]:.4f}" if needed[d] is not None else
               (reasons[d] or "-").split(":")[0]) for d in ("l", "r")}
    lines = ["", "Friction (Coulomb |T| <= mu N at every joint; associative: docs/friction.md)",
             f"  friction the no-sliding collapse needs (largest |T|/N on its thrust line): "
             f"M_l {fmt['l']}, M_r {fmt['r']}"]
    lines += [f"  M_{d}: {reasons[d]}" for d in ("l", "r") if needed[d] is None and reasons[d]]
    if friction is None:
        return lines
    lines += [f"  with mu = {friction.mu:g}:",
              "  mechanism  k (friction)  k (no friction)  sliding governs  "
              "joints needing most friction (|T|/N)"]
    lines += _friction_rows(friction, frictionless=True)
    lines.append(f"  k with friction = {friction.k:.4f}")
    return lines


def _circular_lines(arch) -> list[str]:
    lines = [f"Arch: {arch.name}, {arch.n} voussoirs, embrace {math.degrees(arch.embrace):.4f} deg, "
             f"density {arch.density:g} kg/m^3"]
    # relative to the arch's size: the wording must not depend on the units
    ref = float(np.mean(arch.radii))
    uniform = (np.ptp(arch.spans) < 1e-12 and np.ptp(arch.radii) < 1e-12 * ref
               and np.ptp(arch.thicknesses) < 1e-12 * ref)
    if uniform:
        lines.append(f"  regular: R = {arch.radii[0]:g} m, t = {arch.thicknesses[0]:g} m, "
                     f"span = {math.degrees(arch.spans[0]):.4f} deg each")
    else:
        lines.append("  voussoir  span [deg]  radius [m]  thickness [m]")
        for i, (a, r, t) in enumerate(zip(arch.spans, arch.radii, arch.thicknesses)):
            lines.append(f"  {i:8d}  {math.degrees(a):10.4f}  {r:10.4f}  {t:13.4f}")
    return lines


def _piers_lines(arch) -> list[str]:
    """The blocks of an arch on piers, each with its kind (chain order: left pier from its
    foot up, the voussoirs, right pier from its top down; docs/piers.md)."""
    kinds = arch.block_kinds
    lines = [f"Arch: {arch.name}, {arch.n} blocks: {describe_blocks(arch)}; "
             f"{type(arch).__name__}, size {arch.size:.6g} m, density {arch.density:g} kg/m^3",
             "  block  kind        area [m^2]  mass [kg/m]  mass centre x [m]  y [m]"
             + ("  (mass and centre with loads)" if arch.loads else "")]
    cents = np.where(np.abs(arch.centroids) < 1e-12 * arch.size, 0.0, arch.centroids)
    for i, (k, a, m, c) in enumerate(zip(kinds, arch.areas, arch.masses, cents)):
        lines.append(f"  {i:5d}  {k:<8s}  {a:11.5g}  {m:11.5g}  {c[0]:17.6g}  {c[1]:.6g}")
    return lines


def _general_lines(arch) -> list[str]:
    if _on_piers(arch):
        return _piers_lines(arch)
    lines = [f"Arch: {arch.name}, {arch.n} voussoirs ({type(arch).__name__}), "
             f"size {arch.size:.6g} m, density {arch.density:g} kg/m^3",
             "  voussoir   area [m^2]  mass [kg/m]  mass centre x [m]  y [m]"
             + ("  (mass and centre with loads)" if arch.loads else "")]
    # rounding noise (1e-15 of the size) on a symmetric arch's axis prints as 0
    cents = np.where(np.abs(arch.centroids) < 1e-12 * arch.size, 0.0, arch.centroids)
    for i, (a, m, c) in enumerate(zip(arch.areas, arch.masses, cents)):
        lines.append(f"  {i:8d}  {a:11.5g}  {m:11.5g}  {c[0]:17.6g}  {c[1]:.6g}")
    return lines


def thrust_range_line(thrust) -> str:
    """One line of a :class:`~archrock.statics.thrust.ThrustRange`: H_min and H_max [kN/m] and the
    hinges (joint edge) of each line of thrust."""
    def part(name, H, hinges):
        if not math.isfinite(H):
            return f"{name} unbounded"
        where = ", ".join(f"{h.joint} {h.edge}" for h in hinges) or "none"
        return f"{name} = {H / 1e3:.4f} kN/m (hinges {where})"

    return (f"thrust range under self-weight: "
            f"{part('H_min', thrust.thrust_min, thrust.hinges_min)}, "
            f"{part('H_max', thrust.thrust_max, thrust.hinges_max)}")


def format_limit_table(result, min_thickness=None, needed=None, friction=None,
                       min_thickness_friction=None, thrust=None, min_pier_width=None) -> str:
    """Readable report of a LimitResult: geometry, k_l / k_r, hinges, LP check; friction
    (:func:`friction_lines`) where given."""
    arch = result.arch
    lines = _circular_lines(arch) if isinstance(arch, Arch) else _general_lines(arch)
    for ld in arch.loads:
        on = (f"block {ld.voussoir} ({block_name(arch, ld.voussoir)})" if _on_piers(arch)
              else f"voussoir {ld.voussoir}")  # on piers the index is the chain's
        lines.append(f"  load: {ld.mass:g} kg/m on {on} at "
                     f"({ld.at[0]:g}, {ld.at[1]:g}) m")
    fc = getattr(arch, "fc", None)
    hyp = "Heyman's hypotheses" if fc is None else f"compressive strength f_c = {fc:g} MPa"
    lines += ["", f"Limit analysis (horizontal forces = multiplier x weight; {hyp})",
              "  mechanism  k (kinematic)  k (static LP)  hinges A-D (joint edge)"]
    for dirn in ("l", "r"):
        mech = result.mechanism(dirn)
        k = result.k_l if dirn == "l" else result.k_r
        ks = result.static_k_l if dirn == "l" else result.static_k_r
        kss = f"{ks:13.4f}" if ks is not None else f"{'-':>13}"
        hinges = ", ".join(f"{lab}: {h.joint} {h.edge}" for lab, h in mech.labelled())
        if mech.lift_off:
            hinges = (f"hinges {', '.join(f'{h.joint} {h.edge}' for h in mech.hinges)}; "
                      f"lifts off at joint {', '.join(map(str, mech.lift_off))}")
        if mech.crushed:
            hinges = (f"hinges {', '.join(f'{h.joint} {h.edge}' for h in mech.hinges)}; "
                      f"crushed through at joint {', '.join(map(str, mech.crushed))}")
        lines.append(f"  M_{dirn}        {k:13.4f}  {kss}  {hinges}")
    if _on_piers(arch):
        # where each hinge is on the drawing (joints numbered along the chain: docs/piers.md)
        for dirn in ("l", "r"):
            mech = result.mechanism(dirn)
            lines.append(f"  M_{dirn} hinges: " + "; ".join(
                f"{lab} = {h.joint}{h.edge[0]} ({hinge_place(arch, h.joint, h.edge)})"
                for lab, h in mech.labelled()))
    if fc is not None:
        lines += crushing_lines(result)
    else:
        lines.append(f"  k = min(k_l, k_r) = {result.k:.4f} (Heyman's collapse multiplier)")
    if result.discrepancy is not None and fc is None:
        # the kinematic value is that of the mechanism attaining the LP's optimum: they agree by
        # construction (limit_analysis refuses to report a multiplier otherwise)
        lines.append(f"  LP check: max |kinematic - static| = {result.discrepancy:.2e} (agree)")
    for dirn in ("l", "r"):
        why = result.not_four_hinge(dirn)
        if why is not None:
            lines.append(f"  {why}: the four-link model does not hold for this arch; the "
                         f"contact engine follows it (archrock dem)")
    lines += _extras(arch, min_thickness, min_thickness_friction, thrust, min_pier_width)
    lines.append("  (M_l: activated by xg''/g <= -k_l, forces toward +x; "
                 "M_r: by xg''/g >= k_r, forces toward -x)")
    lines += friction_lines(needed, friction)
    return "\n".join(lines)


def _sliding_mechanism(fd) -> str:
    """The friction collapse of one direction in words: the joints that slide (or need most
    friction where sliding does not govern)."""
    joints = ", ".join(str(j) for j in fd.joints)
    what = "sliding at joint" if fd.sliding_governs else "most friction at joint"
    return f"{what}{'s' if len(fd.joints) != 1 else ''} {joints}"


def friction_only_summary(arch, why: str, min_thickness=None, friction=None,
                          min_thickness_friction=None, thrust=None, min_pier_width=None) -> dict:
    """The ``archrock limit --friction --json`` object of an arch that no frictionless mechanism
    brings down (``why``: the limit analysis's reason): ``k``, ``k_l``, ``k_r`` are the
    multipliers with friction, ``frictionless_mechanism`` is false, ``mechanism_l``/``_r`` name
    the sliding joints; the friction keys of :func:`friction_summary` follow."""
    units = {"k": "g (horizontal load / weight)"}
    fr = friction
    out = {"arch": arch.name, "k": None if fr is None else fr.k,
           "k_l": None if fr is None else fr.l.multiplier,
           "k_r": None if fr is None else fr.r.multiplier, "frictionless_mechanism": False,
           "no_frictionless_mechanism": why,
           "mechanism_l": None if fr is None else _sliding_mechanism(fr.l),
           "mechanism_r": None if fr is None else _sliding_mechanism(fr.r),
           "four_link_holds": False, "geometry": arch.to_dict(), "blocks": block_counts(arch),
           **({} if isinstance(arch, Arch) else {"voussoirs": _voussoir_properties(arch)}),
           "units": units}
    if fr is not None:
        out.update(friction_summary(None, fr))
    if min_thickness is not None:
        t = min_thickness.thicknesses
        out["min_thickness"] = {"factor": min_thickness.factor,
                                "ratio_t_over_R": min_thickness.ratio,
                                "thicknesses": None if t is None else [float(x) for x in t],
                                "friction": min_thickness_friction}
    if thrust is not None:
        td = thrust.to_dict()
        out["thrust_min"], out["thrust_max"] = td["thrust_min"], td["thrust_max"]
        units["H"] = "N/m (horizontal thrust per metre of depth)"
    if min_pier_width is not None:
        out["min_pier_width"] = min_pier_width.to_dict()
    return out


def format_friction_only(arch, why: str, min_thickness=None, friction=None,
                         min_thickness_friction=None, thrust=None, min_pier_width=None) -> str:
    """Readable report of an arch with no frictionless mechanism: the friction analysis is the
    answer (the joints slide at k_l, k_r); without friction, only the lines of the other
    results (the capacity's follow)."""
    lines = _circular_lines(arch) if isinstance(arch, Arch) else _general_lines(arch)
    lines += ["", f"No frictionless mechanism: {why.removeprefix('arch: ')}"]
    if friction is None:
        lines += _extras(arch, min_thickness, min_thickness_friction, thrust, min_pier_width)
        return "\n".join(lines)
    lines += [f"Limit analysis with friction mu = {friction.mu:g} (Coulomb |T| <= mu N at every "
              f"joint; associative: docs/friction.md)",
              "  mechanism  k (friction)  sliding governs  joints needing most friction (|T|/N)"]
    lines += _friction_rows(friction, frictionless=False)
    lines.append(f"  k = min(k_l, k_r) with friction = {friction.k:.4f} (joints slide; the "
                 f"four-link model does not hold)")
    lines += _extras(arch, min_thickness, min_thickness_friction, thrust, min_pier_width)
    lines.append("  (M_l: activated by xg''/g <= -k_l, forces toward +x; "
                 "M_r: by xg''/g >= k_r, forces toward -x)")
    return "\n".join(lines)


def _extras(arch, min_thickness, min_thickness_friction, thrust, min_pier_width) -> list[str]:
    """The lines of --min-thickness, --thrust-range and --min-pier-width."""
    lines = []
    if min_thickness is not None:
        ratio = ("" if min_thickness.ratio is None
                 else f", mean t/R = {min_thickness.ratio:.4f}" if isinstance(arch, Arch)
                 else f", mean t / size = {min_thickness.ratio:.4f}")
        with_mu = ("" if min_thickness_friction is None
                   else f" with friction {min_thickness_friction:g}")
        lines.append(f"  minimum thickness under self-weight{with_mu}: factor "
                     f"{min_thickness.factor:.4f} of the given thicknesses{ratio}")
    if thrust is not None:
        lines.append(f"  {thrust_range_line(thrust)}")
    if min_pier_width is not None:
        lines.append(f"  {min_pier_width_line(min_pier_width)}")
    return lines


def format_governing(gov, stated: str) -> str:
    """The governing answer of ``archrock limit`` (a
    :class:`~archrock.studies.governing.GoverningCapacity`): its friction stated once, the
    governing line, what was left out and why."""
    lines = ["", f"Governing capacity, friction {stated}", "  " + gov.line()]
    for name, why in gov.left_out:
        lines.append(f"  left out: {name}: {why}")
    return "\n".join(lines)


def crushing_lines(result) -> list[str]:
    """The lines of a finite-strength result (:mod:`archrock.statics.crushing`): k, each
    direction's static bracket, the compressed zones at the hinges and how it was found."""
    fc = result.arch.fc
    lines = [f"  k = min(k_l, k_r) = {result.k:.4f} (collapse multiplier with f_c = {fc:g} MPa)"]
    for dirn in ("l", "r"):
        lo, hi = getattr(result, f"k_bounds_{dirn}")
        zones = getattr(result, f"zones_{dirn}")
        mech = result.mechanism(dirn)
        at = ", ".join(f"{lab} {zones[h.joint]:.4g} m" for lab, h in mech.labelled())
        at += "".join(f", joint {j} {zones[j]:.4g} m (crushed through)" for j in mech.crushed)
        lines.append(f"  M_{dirn}: static bracket [{lo:.7f}, {hi:.7f}]; compressed zones "
                     f"(depth N / f_c) at the hinges: {at}")
    if result.discrepancy is not None:
        lines.append(f"  check: max |kinematic - static| = {result.discrepancy:.2e} "
                     f"({result.method})")
    else:
        lines.append(f"  method: {result.method}")
    return lines
