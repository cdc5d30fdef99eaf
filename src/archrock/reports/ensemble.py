"""Report of a Monte Carlo ensemble of random arches (from its JSON-ready summary)."""

from __future__ import annotations

__all__ = ["format_ensemble"]


def _num(x, spec: str) -> str:
    """A summary number; '-' for None (no sample to take it over)."""
    return "-" if x is None else format(x, spec)


_OUTCOME_TEXT = {"invalid_draw": "invalid draw", "cannot_stand": "cannot stand",
                 "no_mechanism": "no mechanism",
                 "four_link_not_applicable": "four-link model not applicable",
                 "impact_not_applicable": "impact model not applicable", "other": "other",
                 "integrated": "integrated", "limit_only": "limit analysis only"}


def _p_line(name: str, pc: dict, counts: str) -> str:
    if pc["p"] is None:
        return f"{name} = n/a ({pc['note']})"
    return (f"{name} = {pc['p']:.4f} [{pc['low']:.4f}, {pc['high']:.4f}] "
            f"({counts} of {pc['trials']}, {pc['confidence']:.0%} Wilson)")


def _outcome_lines(oc: dict) -> list[str]:
    """One line per outcome that occurred (all samples; shares of all)."""
    n = oc["samples"]
    lines = [f"outcomes of all {n} samples (each sample has one):"]
    for key, count in oc["counts"].items():
        if count or key in ("cannot_stand", "integrated"):
            extra = ""
            if key == "integrated":
                extra = " (" + ", ".join(f"{k} {v}" for k, v in oc["integrated"].items()) + ")"
            share = "-" if oc["shares"][key] is None else f"{oc['shares'][key]:.1%}"
            lines.append(f"  {_OUTCOME_TEXT.get(key, key)}: {count} ({share}){extra}")
    return lines


def format_ensemble(summary: dict, arch_name: str) -> str:
    """Readable report of ``EnsembleResult.summary()`` for random arches around ``arch_name``:
    multipliers, distance from the paper's random arches, hinge patterns, P(collapse), timing."""
    sp = summary["spreads"]
    lines = [f"{summary['samples']} random arches around {arch_name} (seed {summary['seed']}, "
             f"spreads {sp['span']:g}/{sp['thickness']:g}/{sp['radius']:g}"
             + (f", joint tilt {sp['tilt_deg']:g} deg" if sp.get("tilt_deg") else "") + ")",
             f"nominal: k_l = {summary['nominal']['k_l']:.4f}, "
             f"k_r = {summary['nominal']['k_r']:.4f}"
             + (f" at f_c = {summary['nominal']['fc']:g} MPa"
                + (f" (each arch's f_c spread by {sp['fc']:g})" if sp.get("fc") else "")
                if summary["nominal"].get("fc") is not None else "")]
    sd = summary["nominal"].get("single_dof")
    if sd is not None and not sd["valid"] and summary.get("p_collapse") is not None:
        lines.append(f"WARNING single degree of freedom not valid on the nominal arch: "
                     f"{sd['reason']}; P(collapse) below is the four-link model's")
    imp = summary.get("impact")
    if imp and summary.get("p_collapse") is not None:
        lines.append(f"impact: {imp['description']}")
        note = (imp.get("applied") or {}).get("note")
        if note:
            lines.append(f"impact law fallback: {note}")
    oc = summary.get("outcomes")
    if oc is not None:
        lines += _outcome_lines(oc)
    for name in ("k_l", "k_r"):
        s = summary[name]
        if s["mean"] is not None:
            rng = ("n/a (one sample)" if s["q05"] is None
                   else f"[{s['q05']:.4f}, {s['q95']:.4f}]")
            lines.append(f"{name} (standing arches, n = {s['count']}): mean {s['mean']:.4f}, "
                         f"std {'n/a (one sample)' if s['std'] is None else format(s['std'], '.4f')}"
                         f", 5-95% {rng}")
    for name, far in summary["as_far_as"].items():
        f3 = {k: _num(far[k], ".3f") for k in ("k_l", "k_r", "either", "asymmetry")}
        lines.append(f"as far from nominal as {name}: k_l {f3['k_l']}, k_r {f3['k_r']}, "
                     f"either {f3['either']}, asymmetry |k_l-k_r| {f3['asymmetry']}")
    for m, counts in summary["hinge_patterns"].items():
        lines.append(f"{m} hinges: " + ", ".join(f"{k} {v}" for k, v in list(counts.items())[:4]))
    pc = summary["p_collapse"]
    if pc is not None:
        lines.append(_p_line("P(collapse | integrated)", pc, f"{pc['collapses']} collapsed")
                     + "; conditional: arches without a response left out")
    pf = summary.get("p_failure")
    if pf is not None:
        lines.append(_p_line("P(failure), cannot stand counted as failed", pf,
                             f"{pf['cannot_stand']} cannot stand + {pf['collapses']} collapsed")
                     + "; invalid draws, no mechanism, model not applicable left out")
    if summary["failed"]["count"]:
        lines.append(f"failed samples: {summary['failed']['count']} "
                     + "; ".join(f"{k}: {v}" for k, v in summary["failed"]["reasons"].items()))
    t = summary["timing"]
    on = f", {t['device']}" if t.get("device") else ""  # the device that ran (0.8)
    lines.append(f"time: {t['wall_s']:.1f} s ({t['executor']}{on}; {len(t['computed_batches'])} "
                 f"batches computed, {len(t['loaded_batches'])} loaded)")
    return "\n".join(lines)
