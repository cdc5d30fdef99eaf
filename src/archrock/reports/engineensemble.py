"""Report of an ensemble run in the contact engine (from its JSON-ready summary)."""

from __future__ import annotations

__all__ = ["format_engine_ensemble"]


def format_engine_ensemble(summary: dict, arch_name: str) -> str:
    """Readable report of ``EngineEnsembleResult.summary()`` for random arches around
    ``arch_name``: why the engine, the outcomes, P(collapse) with its Wilson interval, the
    engine's settings and the time taken."""
    sp = summary["spreads"]
    dyn = summary.get("dynamics") or {}
    oc = summary["outcomes"]
    lines = [f"{summary['samples']} random arches around {arch_name} (seed {summary['seed']}, "
             f"spreads {sp['span']:g}/{sp['thickness']:g}/"
             f"{sp['radius']:g})",
             f"computed by the contact engine: {dyn.get('reason', 'asked for')}"]
    nom = summary.get("nominal") or {}
    if nom.get("k_l") is not None:
        lines.append(f"nominal: k_l = {nom['k_l']:.4f}, k_r = {nom['k_r']:.4f}")
    st = oc["status"]
    lines.append(f"outcomes: {oc['integrated']} run to the end (rest {st['rest']}, collapsed "
                 f"{st['collapsed']}, still moving {st['moving']}), {oc['failed']} failed"
                 + "".join(f"; {k}: {v}" for k, v in oc["failed_reasons"].items()))
    pc = summary["p_collapse"]
    if pc["p"] is None:
        lines.append(f"P(collapse | run) = n/a ({pc['note']})")
    else:
        lines.append(f"P(collapse | run) = {pc['p']:.4f} [{pc['low']:.4f}, {pc['high']:.4f}] "
                     f"({pc['collapses']} collapsed of {pc['trials']}, "
                     f"{pc['confidence']:.0%} Wilson)")
    e = summary["engine"]
    s = e["settings"]
    from ..contact.settings import EngineSettings

    lines.append(f"engine: {EngineSettings.from_dict(s).describe()}, "
                 f"friction {s['friction']:g}, restitution {s['restitution']:g}, free motion "
                 f"{e['t_free']:g} T, collapse at a drop of {e['collapse_drop']:g} x size")
    t = summary["timing"]
    lines.append(f"time: {t['wall_s']:.1f} s ({t['seconds_per_arch']:.2f} s an arch; "
                 f"estimated beforehand {t['estimate_s']:.0f} s)")
    return "\n".join(lines)
