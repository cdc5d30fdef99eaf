"""The paper's study, end to end (``archrock paper --out DIR``).

Steps: the limit analysis of Oppenheim's arch (paper section 3, Fig. 3); the coefficient of
restitution (paper section 5.1: c_v = 0.8754); the responses to Oppenheim's pulse a = -1 g,
t_p = 0.2 s over 0..3 s (Fig. 4): the nominal arch, a random arch that recovers (RA-1 type) and
one that fails in the second half cycle after an impact (RA-2 type).  The random arches are
found by seed among arches drawn with the default spreads (0.1, 0.1, 0.05), choosing those whose
(k_l, k_r) are nearest the paper's RA-1 and RA-2; as in the paper, the nominal arch's c_v is
applied to them.  Each step writes its files into ``out_dir`` and adds an entry to the summary;
``summary.json`` and ``table.md`` (the paper's figures beside ours) are written last.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import Callable

from .. import published
from ..errors import ArchInputError
from .runner import RunSettings

__all__ = ["run_paper_study", "PAPER_K_OPPENHEIM", "FIG3_NAME", "FIG4_NAME", "find_random_arches",
           "PAPER_RA1", "PAPER_RA2", "PAPER_CV"]

PAPER_K_OPPENHEIM = published.K_OPPENHEIM
FIG3_NAME = "fig3_oppenheim_limit.png"
FIG4_NAME = "fig4_responses.png"
PAPER_RA1 = published.RANDOM_ARCHES["RA-1"]
PAPER_RA2 = published.RANDOM_ARCHES["RA-2"]
PAPER_CV = published.CV_OPPENHEIM
SPREADS = published.DEFAULT_SPREADS


def find_random_arches(cv: float, n_seeds: int = 1000, t_window: float = 3.0,
                       near: float = 0.02):
    """Seeds of a recovering arch (at least two impacts within ``t_window``) nearest RA-1 and of
    an arch failing in the second half cycle (collapse in M_r after exactly one impact, falling
    to the rotation limit within ``t_window``, so that Fig. 4 shows the fall) nearest RA-2,
    distances measured in the (k_l, k_r) plane.

    Also counts, for the arches within ``near`` of RA-1's and of RA-2's (k_l, k_r), how many
    collapse: the paper's geometries are unpublished, so this says how typical its outcomes are.
    Returns {"RA-1": (seed, model, response) or None, "RA-2": ..., "searched": n,
    "failing": m, "near": {"RA-1": [collapsing, total], "RA-2": [...]}}.
    """
    from ..geometry import oppenheim_arch, random_arch
    from ..groundmotion import oppenheim_pulse
    from ..dynamics.response import prepare, respond

    motion = oppenheim_pulse(-1.0, 0.2)
    nominal = oppenheim_arch()
    best = {"RA-1": (math.inf, None), "RA-2": (math.inf, None)}
    counts = {"RA-1": [0, 0], "RA-2": [0, 0]}
    failing = 0
    for seed in range(n_seeds):
        model = prepare(random_arch(nominal, seed=seed, **SPREADS), cv)
        res = respond(model, motion, t_end=t_window)
        failing += res.collapsed
        for key, (kl, kr) in (("RA-1", PAPER_RA1), ("RA-2", PAPER_RA2)):
            if math.hypot(model.k_l - kl, model.k_r - kr) <= near:
                counts[key][0] += res.collapsed
                counts[key][1] += 1
        impacts = [e for e in res.events if e.kind == "impact" and e.time < (res.t_collapse or math.inf)]
        # the fall itself must be within the figure's window: the limit reached, not only the
        # collapse (the last passage of phi_u) begun
        second_half = (res.collapsed and len(impacts) == 1 and res.events[-1].before == "r"
                       and res.t_limit <= t_window)
        if res.collapsed and not second_half:
            continue
        # RA-1 type: recovers "after subsequent impacts" (paper 5.2), seen within the window
        if not res.collapsed and sum(t <= t_window for t in res.impacts) < 2:
            continue
        target, key = (PAPER_RA2, "RA-2") if second_half else (PAPER_RA1, "RA-1")
        d = math.hypot(model.k_l - target[0], model.k_r - target[1])
        if d < best[key][0]:
            best[key] = (d, (seed, model, res))
    return {"RA-1": best["RA-1"][1], "RA-2": best["RA-2"][1], "searched": n_seeds,
            "failing": failing, "near": counts, "near_radius": near}


def _dynamics_step(out: Path, progress: Callable[[str], None], draw) -> dict:
    """Section 5: c_v of the nominal arch, Fig. 4 (a)-(d) (drawn by ``draw`` when given)."""
    from ..geometry import oppenheim_arch
    from ..groundmotion import oppenheim_pulse
    from ..dynamics.impact import least_loss_mechanism
    from ..dynamics.response import prepare, respond

    nominal = prepare(oppenheim_arch(), "paper")
    cv = nominal.impact.equivalent_cv  # = the rate ratio: Oppenheim's arch is symmetric
    momentum = prepare(oppenheim_arch(), "momentum").impact.l_to_r
    # beyond the paper: the post-impact mechanism that would lose the least energy
    least = least_loss_mechanism(nominal.mech_l, nominal.mech_r)
    progress(f"coefficient of restitution of Oppenheim's arch: paper model c_v = {cv:.4f} "
             f"(paper: {PAPER_CV}); energy-consistent momentum model {momentum:.4f}")
    motion = oppenheim_pulse(-1.0, 0.2)
    res_nom = respond(nominal, motion, t_end=3.0)
    res_ref = respond(nominal, motion, t_end=3.0, integrator="reference")
    progress(f"nominal arch: {'collapses' if res_nom.collapsed else 'recovers'}; first impact at "
             f"{res_nom.impacts[0]:.3f} s, peak {res_nom.peak:.4f} rad "
             f"(reference integrator: peak {res_ref.peak:.4f} rad)")
    found = find_random_arches(cv)
    responses, labels = [res_nom], ["Oppenheim's arch"]
    rows = _random_rows(out, progress, found, responses, labels)
    if draw is not None:
        progress(f"wrote {draw(responses, out / FIG4_NAME, labels=labels)}")
    return {
        "cv_paper_model": cv, "cv_momentum_model": momentum, "paper_cv": PAPER_CV,
        "least_loss_after_M_l": least.to_dict(),
        "nominal": {"collapsed": res_nom.collapsed, "status": res_nom.status, "peak": res_nom.peak,
                    "impacts": res_nom.impacts[:5], "reference_peak": res_ref.peak,
                    "reference_impacts": res_ref.impacts[:5]},
        "random": rows,
        "random_search": {"seeds": found["searched"], "collapsing": found["failing"],
                          "spreads": SPREADS, "near_radius": found["near_radius"],
                          "near_collapsing": found["near"]},
        "figure": FIG4_NAME if draw is not None else None,
    }


def _random_rows(out: Path, progress: Callable[[str], None], found: dict, responses: list,
                 labels: list) -> dict:
    """The summary rows of the RA-1 and RA-2 type arches found (their geometry written to
    ``out``; their responses and labels appended for Fig. 4)."""
    rows = {}
    for key in ("RA-1", "RA-2"):
        if found[key] is None:
            progress(f"{key}: no arch of that type among {found['searched']} seeds")
            continue
        seed, model, res = found[key]
        progress(f"{key} type: seed {seed}, k_l = {model.k_l:.4f}, k_r = {model.k_r:.4f}; "
                 + (f"collapses at {res.t_collapse:.2f} s (last passage of the unstable position; "
                    f"rotation limit at {res.t_limit:.2f} s) after {len(res.impacts)} impact(s)"
                    if res.collapsed else f"recovers ({len(res.impacts)} impacts)"))
        (out / f"{key.lower()}_geometry.json").write_text(
            json.dumps(model.arch.to_dict(), indent=2) + "\n", encoding="utf-8")
        responses.append(res)
        labels.append(f"{key} type (seed {seed})")
        rows[key] = {"seed": seed, "k_l": model.k_l, "k_r": model.k_r, "collapsed": res.collapsed,
                     "t_collapse": res.t_collapse, "t_limit": res.t_limit,
                     "t_unstable": res.t_unstable, "impacts": res.impacts[:5], "peak": res.peak,
                     "mechanism_l": model.limit.mechanism_l.to_dict(),
                     "mechanism_r": model.limit.mechanism_r.to_dict(),
                     "restitution": model.impact.to_dict(),
                     "geometry": f"{key.lower()}_geometry.json"}
    return rows


def _table(summary: dict) -> str:
    lim, dyn = summary["limit_oppenheim"], summary["dynamics"]
    ra = dyn["random"]
    lines = ["| quantity | paper | archrock |", "|---|---|---|",
             f"| k of Oppenheim's arch | {PAPER_K_OPPENHEIM:.4f} | {lim['k_l']:.4f} (k_l), {lim['k_r']:.4f} (k_r) |",
             f"| c_v of Oppenheim's arch | {PAPER_CV:.4f} | {dyn['cv_paper_model']:.4f} (paper model); "
             f"{dyn['cv_momentum_model']:.4f} (momentum model) |",
             f"| Oppenheim's arch, a = -1 g, t_p = 0.2 s | recovers | "
             f"{'collapses' if dyn['nominal']['collapsed'] else 'recovers'} (peak {dyn['nominal']['peak']:.4f} rad) |"]
    for key, (kl, kr), fate in (("RA-1", PAPER_RA1, "recovers"),
                                ("RA-2", PAPER_RA2, "fails in the second half cycle after an impact")):
        if key in ra:
            r = ra[key]
            ours = ("collapses at %.2f s after %d impact(s) (last passage of the unstable "
                    "position; the rotation limit, a numerical stop, at %.2f s)"
                    % (r["t_collapse"], len(r["impacts"]), r["t_limit"])
                    if r["collapsed"] else "recovers")
            lines.append(f"| {key}: k_l, k_r; response | {kl:.4f}, {kr:.4f}; {fate} | "
                         f"{r['k_l']:.4f}, {r['k_r']:.4f} (seed {r['seed']}); {ours} |")
    ll = dyn["least_loss_after_M_l"]
    hinges = "-".join(f"{h['joint']}{h['edge'][0]}" for h in ll["mechanism"]["hinges"])
    lines.append(f"| post-impact mechanism keeping the most energy (momentum law; Bisegna et al. "
                 f"2023) | not studied | {hinges}: {ll['energy_ratio']:.3f} of the kinetic energy, "
                 f"against {ll['limit_energy_ratio']:.3f} for M_r (archrock opens M_r, as the paper) |")
    search = dyn["random_search"]
    lines.append(f"| random arches collapsing under the paper's pulse | not given | "
                 f"{search['collapsing']} of {search['seeds']} |")
    for key, fate in (("RA-1", "recovers"), ("RA-2", "collapses")):
        c, n = search["near_collapsing"][key]
        lines.append(f"| arches within {search['near_radius']} of {key}'s (k_l, k_r) | {fate} | "
                     f"{c} of {n} collapse |")
    return "\n".join(lines) + "\n"


def _limit_step(out: Path, progress: Callable[[str], None], draw) -> dict:
    """Fig. 3: Oppenheim's arch, collapse hinges and line of thrust (drawn by ``draw``)."""
    from ..geometry import oppenheim_arch
    from ..statics.limit import limit_analysis

    result = limit_analysis(oppenheim_arch(), verify=True)
    progress(f"Oppenheim's arch: k_l = {result.k_l:.4f}, k_r = {result.k_r:.4f} "
             f"(paper: k = {PAPER_K_OPPENHEIM:.4f}); kinematic vs static LP differ by "
             f"{result.discrepancy:.1e}")
    if draw is not None:
        progress(f"wrote {draw(result, out / FIG3_NAME, directions=('l', 'r'))}")
    return {
        "arch": result.arch.name,
        "geometry": result.arch.to_dict(),
        "k_l": result.k_l,
        "k_r": result.k_r,
        "k": result.k,
        "paper_k": PAPER_K_OPPENHEIM,
        "matches_paper_4_decimals": round(result.k, 4) == PAPER_K_OPPENHEIM,
        "static_k_l": result.static_k_l,
        "static_k_r": result.static_k_r,
        "discrepancy": result.discrepancy,
        "hinges": {d: [{"label": lab, **h.to_dict()} for lab, h in result.mechanism(d).labelled()]
                   for d in ("l", "r")},
        "figure": FIG3_NAME if draw is not None else None,
    }


def _silent(msg: str) -> None:
    """The default progress of the library: it does not print."""


def run_paper_study(figures: dict | None = None, *, settings=None) -> dict:
    """Run the paper's study into the folder ``settings.out`` (a
    :class:`~archrock.studies.runner.RunSettings`; created if needed); returns the summary
    dict, also written to ``summary.json`` there.  The settings' ``progress`` receives
    one-line messages (:mod:`archrock._progress`; None: silent).  ``figures``: {"fig3": draw(limit_result, path,
    directions), "fig4": draw(responses, path, labels)} returning the path written (the CLI
    passes :data:`archrock.reports.plots.PAPER_FIGURES`); None writes no figure (studies do
    not draw: reports sit a layer above)."""
    settings = RunSettings.from_dict(settings).only("run_paper_study", "out")
    if settings.out is None:
        raise ArchInputError("out: None; the paper's study writes its summary (and figures) "
                             "into a folder; allowed a folder path (RunSettings(out=...))")
    progress = settings.sink or _silent
    out = settings.out
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ArchInputError(f"--out: cannot create the folder {str(out)!r} ({exc.strerror or exc})") from None
    t0 = time.perf_counter()
    summary: dict = {"paper": "Effect of geometric irregularities on the dynamic response of "
                              "masonry arches (EURODYN 2017)",
                     "files": []}
    figures = figures or {}
    limit = _limit_step(out, progress, figures.get("fig3"))
    summary["limit_oppenheim"] = limit
    dyn = _dynamics_step(out, progress, figures.get("fig4"))
    summary["dynamics"] = dyn
    summary["files"] += [f for f in (limit["figure"], dyn["figure"]) if f is not None]
    summary["files"] += [r["geometry"] for r in dyn["random"].values()]
    table = _table(summary)
    (out / "table.md").write_text(table, encoding="utf-8")
    summary["files"].append("table.md")
    progress("the paper's figures beside ours:\n" + table)
    summary["elapsed_s"] = round(time.perf_counter() - t0, 3)
    summary["files"].append("summary.json")
    path = out / "summary.json"
    # strict JSON: a NaN here would be a bug, not a value to write
    path.write_text(json.dumps(summary, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    progress(f"wrote {path}")
    return summary
