"""Text and JSON reports of the contact engine (``archrock dem``) beside the four-link model."""

from __future__ import annotations

import numpy as np

from ..geometry.blocks import describe_blocks

__all__ = ["ramp_dict", "format_ramp", "engine_response_dict", "format_engine_response"]


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
    lines = [f"Contact engine ramp: {arch.name}, {describe_blocks(arch)}, friction MU = {s.friction:g}",
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


def engine_response_dict(res, four_link=None) -> dict:
    d = res.to_dict()
    if four_link is not None:
        d["four_link"] = four_link.to_dict(samples=False)
    return d


def format_engine_response(res, four_link, arch, motion) -> str:
    s = res.settings
    lines = [f"Contact engine: {arch.name}, {describe_blocks(arch)}, {motion.name}, friction MU = "
             f"{s.friction:g}, restitution {s.restitution:g}",
             f"  engine   : {res.status}"
             + (f" at t = {res.t_collapse:.3f} s (a voussoir dropped by "
                f"{res.run['collapse_drop']:g} x size)" if res.collapsed else "")
             + f", peak equivalent phi {res.peak:.4f} rad, run to {res.t_final:.2f} s"]
    if four_link is not None:
        lines.append(f"  four-link: {four_link.status}"
                     + (f" at t = {four_link.t_collapse:.3f} s" if four_link.collapsed else "")
                     + f", peak phi {four_link.peak:.4f} rad, impacts "
                     + ", ".join(f"{t:.3f}" for t in four_link.impacts[:6]))
    ms = res.max_sliding
    j = int(np.argmax(ms))
    lines.append(f"  max sliding: {ms.max() * 1e3:.2f} mm at joint {j} (per joint, mm: "
                 + " ".join(f"{v * 1e3:.2f}" for v in ms) + ")")
    return "\n".join(lines)
