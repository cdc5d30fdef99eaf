"""Text and JSON reports of the contact engine (``archrock dem``) beside the four-link model."""

from __future__ import annotations

import numpy as np

from ..geometry.blocks import block_counts, block_names, describe_blocks

__all__ = ["ramp_dict", "format_ramp", "engine_response_dict", "format_engine_response",
           "blocks_words", "blocks_count", "blocks_names", "four_link_label"]


def _found_piers(arch) -> tuple:
    """The pier blocks of an arch that does not name its kinds (a geometry file such as
    tests/data/heavy_piers.json): its heavy end blocks on level foundations
    (:func:`archrock.dynamics.piers.pier_blocks`); () where the arch names them or has none."""
    if getattr(arch, "block_kinds", None):
        return ()
    from ..dynamics.piers import pier_blocks

    return tuple(pier_blocks(arch)[0])


def blocks_words(arch) -> str:
    """The blocks of ``arch`` by kind (:func:`archrock.geometry.blocks.describe_blocks`); on a
    file without kinds whose end blocks are piers, "12 voussoirs on two piers (found by their
    geometry)": an arch of 12 voussoirs on two piers is not an arch of 14 voussoirs."""
    piers = _found_piers(arch)
    if not piers:
        return describe_blocks(arch)
    nv = arch.n - len(piers)
    two = "two piers" if len(piers) == 2 else "a pier"
    return f"{nv} voussoir{'s' if nv != 1 else ''} on {two} (found by their geometry)"


def blocks_names(arch) -> tuple:
    """Every block's name (:func:`archrock.geometry.blocks.block_names`), the found piers of a
    file without kinds named "left pier" / "right pier" and the voussoirs counted from 0."""
    piers = _found_piers(arch)
    if not piers:
        return block_names(arch)
    names, v = [], 0
    for i in range(arch.n):
        if i in piers:
            names.append("left pier" if i == 0 else "right pier")
        else:
            names.append(f"voussoir {v}")
            v += 1
    return tuple(names)


def blocks_count(arch) -> dict:
    """:func:`archrock.geometry.blocks.block_counts`, the piers of a file without kinds
    counted as piers (:func:`blocks_words`)."""
    counts = block_counts(arch)
    piers = _found_piers(arch)
    if piers:
        counts.update(voussoirs=arch.n - len(piers), pier_blocks=len(piers), piers=len(piers))
    return counts


def _limit_hinges(limit, d):
    return [h.joint for h in sorted(limit.mechanism(d).hinges, key=lambda h: h.joint)]


def _reference(limit, friction, d):
    """(k, what) the engine's ramp is compared with in direction ``d``: the limit analysis at
    the engine's friction -- the friction analysis's multiplier where sliding governs (it is
    then below the no-sliding k), else the no-sliding k."""
    k = getattr(limit, f"k_{d}")
    if friction is not None:
        fd = friction.direction(d)
        if fd.sliding_governs and fd.multiplier < k:
            return fd.multiplier, "friction LP"
    return k, "no sliding"


def ramp_dict(result, limit, friction=None) -> dict:
    """--json of ``archrock dem --ramp``: the engine's k_l, k_r, hinges_l, hinges_r (joints from
    the left springing) beside archrock's limit analysis; ``relative_error`` against the limit
    analysis at the engine's friction (``friction``: its friction analysis; where sliding
    governs, its multiplier), named in ``compared_with``."""
    d = result.to_dict()
    d["limit"] = {"k_l": limit.k_l, "k_r": limit.k_r, "hinges_l": _limit_hinges(limit, "l"),
                  "hinges_r": _limit_hinges(limit, "r"),
                  "mechanism_l": limit.mechanism("l").label,
                  "mechanism_r": limit.mechanism("r").label}
    refs = {dd: _reference(limit, friction, dd) for dd in ("l", "r")}
    d["relative_error"] = {f"k_{dd}": getattr(result, f"k_{dd}") / refs[dd][0] - 1.0
                           for dd in ("l", "r")}
    d["compared_with"] = {f"k_{dd}": {"k": refs[dd][0], "analysis": refs[dd][1]}
                          for dd in ("l", "r")}
    return d


def _range_line(opts: dict) -> list[str]:
    """The ramp's range per direction (``lambda_start`` .. ``lambda_max``), when recorded."""
    top, start = opts.get("lambda_max"), opts.get("lambda_start") or {}
    if not isinstance(top, dict):
        return []
    return ["  ramp range |xg''|/g: " + ", ".join(
        f"M_{d} {start.get(d, 0.0):.3g} to {top[d]:.3g}" for d in ("l", "r") if d in top)
        + " (default max(2, 1.5 k); --ramp-max)"]


def format_ramp(result, limit, arch, friction=None) -> str:
    """``archrock dem --ramp``'s table: each direction's engine multiplier and bracket beside the
    limit analysis at the engine's friction (``friction``: its friction analysis, whose
    multiplier is the reference where sliding governs) and the limit mechanism."""
    s = result.settings
    lines = [f"Contact engine ramp: {arch.name}, {describe_blocks(arch)}, friction MU = {s.friction:g}",
             f"  engine: {s.describe()}",
             *_range_line(result.ramp),
             f"  {'':3} {'engine':>9} {'bracket':>19} {'limit k':>9} {'error':>8}  "
             f"{'engine hinges':<22} limit hinges"]
    notes = []
    for d in ("l", "r"):
        r = getattr(result, d)
        k, what = _reference(limit, friction, d)
        if what != "no sliding":
            notes.append(f"  M_{d}: the joints slide first at mu = {s.friction:g}: the limit k "
                         f"is the friction analysis's, {k:.4f} (no sliding: "
                         f"{getattr(limit, f'k_{d}'):.4f})")
        hinges = ("-".join(f"{j}{e[0]}" for j, e in zip(r.hinges, r.edges))
                  if r.mode == "rocking" else "sliding at " + ",".join(map(str, r.sliding_joints)))
        lines.append(f"  M_{d} {r.multiplier:9.4f} [{r.lower:.4f}, {r.upper:.4f}] {k:9.4f} "
                     f"{100 * (r.multiplier / k - 1):+7.2f}%  {hinges:<22} "
                     f"{limit.mechanism(d).label}")
    return "\n".join(lines + notes)


def engine_response_dict(res, four_link=None, choice=None) -> dict:
    """``archrock dem --json`` of a response: the engine's run, the four-link run beside it
    and, with ``choice``, the routing ("dynamics") and whether the four-link model holds."""
    d = res.to_dict()
    if four_link is not None:
        d["four_link"] = four_link.to_dict(samples=False)
    if choice is not None:
        d["dynamics"] = choice.to_dict()
        if four_link is not None:
            d["four_link"]["valid_here"] = not choice.engine
            d["four_link"]["label"] = four_link_label(choice)
    return d


def four_link_label(choice, short: bool = False) -> str:
    """The four-link column beside the engine: "four-link", or "four-link (not valid here:
    <why>)" where the routing (``choice``, a DynamicsChoice of "auto") sends this arch to the
    engine; ``short``: without the why (a figure's legend)."""
    if choice is None or not choice.engine:
        return "four-link"
    if short:
        return "four-link (not valid here)"
    why = choice.reason.split(": ", 1)[-1] if choice.reason.startswith("one degree") else \
        choice.reason
    return f"four-link (not valid here: {why})"


def format_engine_response(res, four_link, arch, motion, choice=None) -> str:
    """``archrock dem``'s text: the engine's run, the four-link run beside it (labelled not
    valid here where ``choice``, the routing of "auto", says so) and the sliding."""
    s = res.settings
    lines = [f"Contact engine: {arch.name}, {blocks_words(arch)}, {motion.name}, friction MU = "
             f"{s.friction:g}, restitution {s.restitution:g}"]
    if choice is not None:
        lines.append(f"  governing model (--dynamics auto of respond and the studies): "
                     f"{'contact engine' if choice.engine else 'four-link model'} "
                     f"({choice.reason})")
    lines += [f"  engine   : {res.status}"
             + (f" at t = {res.t_collapse:.3f} s (a block dropped by "
                f"{res.run['collapse_drop']:g} x size)" if res.collapsed else "")
             + f", peak equivalent phi {res.peak:.4f} rad, run to {res.t_final:.2f} s"]
    if four_link is not None:
        label = four_link_label(choice)
        if label != "four-link":  # a model the output calls invalid: its numbers under the label
            lines.append(f"  {label}:")
            label = "  four-link outcome (not valid here)"
        lines.append(f"  {label}: {four_link.status}"
                     + (f" at t = {four_link.t_collapse:.3f} s" if four_link.collapsed else "")
                     + f", peak phi {four_link.peak:.4f} rad, impacts "
                     + ", ".join(f"{t:.3f}" for t in four_link.impacts[:6]))
        if four_link.model.impact.fallback:  # the law named is the law that ran
            from .impact import impact_law_line

            lines.append(f"    four-link {impact_law_line(four_link.model.impact)}")
    ms = res.max_sliding
    j = int(np.argmax(ms))
    lines.append(f"  max sliding: {ms.max() * 1e3:.2f} mm at joint {j} (per joint, mm: "
                 + " ".join(f"{v * 1e3:.2f}" for v in ms) + ")")
    return "\n".join(lines)
