"""Report of a Monte Carlo ensemble of random arches (from its JSON-ready summary)."""

from __future__ import annotations

__all__ = ["format_ensemble"]


def _num(x, spec: str) -> str:
    """A summary number; '-' for None (no sample to take it over)."""
    return "-" if x is None else format(x, spec)


def format_ensemble(summary: dict, arch_name: str) -> str:
    """Readable report of ``EnsembleResult.summary()`` for random arches around ``arch_name``:
    multipliers, distance from the paper's random arches, hinge patterns, P(collapse), timing."""
    sp = summary["spreads"]
    lines = [f"{summary['samples']} random arches around {arch_name} (seed {summary['seed']}, "
             f"spreads {sp['span']:g}/{sp['thickness']:g}/{sp['radius']:g})",
             f"nominal: k_l = {summary['nominal']['k_l']:.4f}, "
             f"k_r = {summary['nominal']['k_r']:.4f}"]
    for name in ("k_l", "k_r"):
        s = summary[name]
        if s["mean"] is not None:
            lines.append(f"{name}: mean {s['mean']:.4f}, std {_num(s['std'], '.4f')}, 5-95% "
                         f"[{s['q05']:.4f}, {s['q95']:.4f}]")
    for name, far in summary["as_far_as"].items():
        f3 = {k: _num(far[k], ".3f") for k in ("k_l", "k_r", "either", "asymmetry")}
        lines.append(f"as far from nominal as {name}: k_l {f3['k_l']}, k_r {f3['k_r']}, "
                     f"either {f3['either']}, asymmetry |k_l-k_r| {f3['asymmetry']}")
    for m, counts in summary["hinge_patterns"].items():
        lines.append(f"{m} hinges: " + ", ".join(f"{k} {v}" for k, v in list(counts.items())[:4]))
    pc = summary["p_collapse"]
    if pc is not None:
        lines.append(f"P(collapse) = {pc['p']:.4f} [{pc['low']:.4f}, {pc['high']:.4f}] "
                     f"({pc['collapses']}/{pc['trials']}, {pc['confidence']:.0%} Wilson)")
    if summary["failed"]["count"]:
        lines.append(f"failed samples: {summary['failed']['count']} "
                     + "; ".join(f"{k}: {v}" for k, v in summary["failed"]["reasons"].items()))
    t = summary["timing"]
    lines.append(f"time: {t['wall_s']:.1f} s ({t['executor']}; {len(t['computed_batches'])} "
                 f"batches computed, {len(t['loaded_batches'])} loaded)")
    return "\n".join(lines)
