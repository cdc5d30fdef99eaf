"""Text and JSON reports of the contact engine (``archrock dem``) beside the four-link model."""

from __future__ import annotations

import numpy as np

__all__ = ["ramp_dict", "format_ramp", "engine_response_dict", "format_engine_response",
           "block_counts", "block_kinds_count", "four_link_label"]


def block_kinds_count(arch) -> dict:
    """{"voussoirs": n, "piers": m, "buttresses": b} (kinds present only) of ``arch``: kinds
    from ``block_kinds`` where the arch has them, else the piers a geometry file's end blocks
    are (:func:`archrock.dynamics.piers.pier_blocks`)."""
    from ..dynamics.piers import pier_blocks

    kinds = list(getattr(arch, "block_kinds", None) or ("voussoir",) * arch.n)
    if "pier" not in kinds and "buttress" not in kinds:
        for i in pier_blocks(arch)[0]:
            kinds[i] = "pier"
    counts = {plural: kinds.count(kind) for kind, plural in
              (("voussoir", "voussoirs"), ("pier", "piers"), ("buttress", "buttresses"))}
    return {k: v for k, v in counts.items() if v}


def block_counts(arch) -> str:
    """The blocks of ``arch`` counted by kind ("12 voussoirs, 2 piers"): an arch of 12
    voussoirs on two piers is not an arch of 14 voussoirs."""
    one = {"voussoirs": "voussoir", "piers": "pier", "buttresses": "buttress"}
    return ", ".join(f"{n} {plural if n != 1 else one[plural]}"
                     for plural, n in block_kinds_count(arch).items())


def _limit_hinges(limit, d):
    return [h.joint for h in sorted(limit.mechanism(d).hinges, key=lambda h: h.joint)]


def ramp_dict(result, limit) -> dict:
    """--json of ``archrock dem --ramp``: the engine's k_l, k_r, hinges_l, hinges_r (joints from
    the left springing) beside archrock's limit analysis."""
    d = result.to_dict()
    d["limit"] = {"k_l": limit.k_l, "k_r": limit.k_r, "hinges_l": _limit_hinges(limit, "l"),
                  "hinges_r": _limit_hinges(limit, "r"),
                  "mechanism_l": limit.mechanism("l").label,
                  "mechanism_r": limit.mechanism("r").label}
    d["relative_error"] = {"k_l": result.k_l / limit.k_l - 1.0, "k_r": result.k_r / limit.k_r - 1.0}
    return d


def _range_line(opts: dict) -> list[str]:
    """The ramp's range per direction (``lambda_start`` .. ``lambda_max``), when recorded."""
    top, start = opts.get("lambda_max"), opts.get("lambda_start") or {}
    if not isinstance(top, dict):
        return []
    return ["  ramp range |xg''|/g: " + ", ".join(
        f"M_{d} {start.get(d, 0.0):.3g} to {top[d]:.3g}" for d in ("l", "r") if d in top)
        + " (default max(2, 1.5 k); --ramp-max)"]


def format_ramp(result, limit, arch) -> str:
    s = result.settings
    lines = [f"Contact engine ramp: {arch.name}, {arch.n} voussoirs, friction MU = {s.friction:g}",
             f"  engine: {s.steps_per_T:g} steps per T, {s.iterations} iterations, "
             f"slop {s.slop:g}, rounding {s.rounding:g} (x size)",
             *_range_line(result.ramp),
             f"  {'':3} {'engine':>9} {'bracket':>19} {'limit k':>9} {'error':>8}  "
             f"{'engine hinges':<22} limit hinges"]
    for d in ("l", "r"):
        r = getattr(result, d)
        k = getattr(limit, f"k_{d}")
        hinges = ("-".join(f"{j}{e[0]}" for j, e in zip(r.hinges, r.edges))
                  if r.mode == "rocking" else "sliding at " + ",".join(map(str, r.sliding_joints)))
        lines.append(f"  M_{d} {r.multiplier:9.4f} [{r.lower:.4f}, {r.upper:.4f}] {k:9.4f} "
                     f"{100 * (r.multiplier / k - 1):+7.2f}%  {hinges:<22} "
                     f"{limit.mechanism(d).label}")
    return "\n".join(lines)


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
    lines = [f"Contact engine: {arch.name}, {block_counts(arch)}, {motion.name}, friction MU = "
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
            from .response import impact_law_line

            lines.append(f"    four-link {impact_law_line(four_link.model.impact)}")
    ms = res.max_sliding
    j = int(np.argmax(ms))
    lines.append(f"  max sliding: {ms.max() * 1e3:.2f} mm at joint {j} (per joint, mm: "
                 + " ".join(f"{v * 1e3:.2f}" for v in ms) + ")")
    return "\n".join(lines)
