"""The report's time-history verification: records chosen and scaled for the site spectrum
(:mod:`archrock.studies.selection`), each run on the arch by the model that holds for it, each
record's effect measured against the capacity of the nonlinear kinematic check, and the
verdict by the codes' rule for time-history analysis (NTC 2018 par. 7.3.5, EN 1998-1
par. 4.3.3.4.3), beside the kinematic check's verdict (docs/assess.md, Time-history
verification).

The effect of record i is E_i = d*(phi_peak,i) / d_u*: its peak rotation [rad] mapped to the
spectral displacement d* [m] by the same mechanism's capacity curve that the code check draws
(:func:`archrock.studies.codecheck.kinematic_check`: the same four-link kinematics, the same
control point), over the check's ultimate displacement d_u* = 0.4 d_0*.  A record that
collapses the arch has an unbounded effect, E_i = inf.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from .assessment_blocks import Figure, Paragraph, Section, Table, titled
from .assessment_context import Context

__all__ = ["section_timehistory", "code_rule", "peak_effect", "record_effects",
           "MEAN_RULE_RECORDS", "LEAST_RECORDS", "TITLE"]

TITLE = "Time-history verification (NTC 2018 par. 7.3.5, EN 1998-1 par. 4.3.3.4.3)"
#: with this many records or more the codes take the mean of the effects
MEAN_RULE_RECORDS = 7
#: the least number of records the codes accept (then the largest effect governs)
LEAST_RECORDS = 3
#: output step [s] of each record's sampled response, read only for the peak's direction
_DT_OUT = 0.01
#: sampled response kept this long [s] after the record ends (the free rocking after it)
_AFTER = 5.0


# ---------------------------------------------------------------------------- the rule
def code_rule(effects) -> dict:
    """The codes' verdict on the effects E_i (demand / capacity, inf for a collapse): with 7 or
    more records their mean E = (1/n) sum E_i, with 3 to 6 the largest, and E <= 1 passes.
    Returns {"n", "rule", "formula", "value", "passed", "collapsed", "unbounded"}."""
    e = np.asarray(effects, float).ravel()
    n = int(e.size)
    if n < LEAST_RECORDS:
        raise ArchInputError(f"records: {n}; allowed at least {LEAST_RECORDS} records for a "
                             f"time-history verification (NTC 2018 par. 7.3.5)")
    if np.any(np.isnan(e)) or np.any(e < 0):
        raise ArchInputError("effects: allowed numbers >= 0 or inf (a collapse)")
    mean_rule = n >= MEAN_RULE_RECORDS
    value = float(e.mean()) if mean_rule else float(e.max())
    formula = ("E = (1/n) sum_i E_i <= 1 (n >= 7: the mean of the effects)" if mean_rule
               else "E = max_i E_i <= 1 (3 <= n <= 6: the largest effect)")
    return {"n": n, "rule": "mean" if mean_rule else "max", "formula": formula,
            "value": value, "passed": bool(value <= 1.0),
            "collapsed": int(np.sum(np.isinf(e))), "unbounded": not math.isfinite(value)}


# ---------------------------------------------------------------------------- effects
def peak_effect(checks, peaks: dict) -> dict:
    """The effect of one run that did not collapse: for each direction d of ``checks`` (the
    code check's :class:`~archrock.studies.codecheck.DirectionCheck`\\ s), its peak rotation
    ``peaks[d]`` [rad] mapped by the check's capacity curve to d* [m] (beyond the unstable
    rotation: d_0*), over d_u*; the effect is the larger of the two directions'.
    Returns {"effect", "direction", "d_star", "du_star"}."""
    best = None
    for c in checks:
        phi = float(peaks.get(c.direction, 0.0))
        d_star = float(np.interp(phi, c.curve_rotation, c.curve_d_star))
        e = d_star / c.du_star
        if best is None or e > best["effect"]:
            best = {"effect": e, "direction": c.direction, "d_star": d_star,
                    "du_star": float(c.du_star)}
    return best


def _direction_peaks(res) -> dict:
    """Peak rotation [rad] in each direction of one response: the exact peak (the integrator's
    max phi) in the direction whose sampled response reaches further, the sampled peak in the
    other (+phi is M_l, -phi is M_r)."""
    r = np.asarray(res.response, float)
    r = r[np.isfinite(r)]
    pl = float(r.max(initial=0.0))
    pr = float((-r).max(initial=0.0))
    return {"l": float(res.peak), "r": pr} if pl >= pr else {"l": pl, "r": float(res.peak)}


def record_effects(model, motions, checks) -> list:
    """Each motion run on the four-link ``model`` (:func:`archrock.dynamics.response.respond`):
    per record {"name", "outcome", "peak_rad", "effect", "direction", "d_star"}; a collapse has
    effect inf."""
    from ..dynamics.response import respond

    out = []
    for m in motions:
        res = respond(model, m, t_end=float(m.times[-1]) + _AFTER, dt_out=_DT_OUT)
        row = {"name": m.name, "outcome": res.status, "peak_rad": float(res.peak),
               "t_collapse": res.t_collapse}
        if res.collapsed:
            row.update(effect=math.inf, direction=None, d_star=None)
        else:
            eff = peak_effect(checks, _direction_peaks(res))
            row.update(effect=eff["effect"], direction=eff["direction"], d_star=eff["d_star"])
        out.append(row)
    return out


# ---------------------------------------------------------------------------- the section
def _skip(why: str, data: dict | None = None, head: str = "not computed") -> Section:
    return Section("timehistory", TITLE, (Paragraph(f"Skipped: {why}."),),
                   {"skipped": True, "reason": why, **(data or {})},
                   (("time-history verification", head),))


def _no_records_reason() -> str:
    from ..groundmotion.p695 import EXTRA_HINT, extra_available

    if extra_available():
        return ("no records were given: pass --records FILE|DIR|SUITE (the command line takes "
                "the FEMA P695 far-field set, p695-far-field, by default with a site spectrum)")
    return (f"no records were given, and the FEMA P695 record sets are not installed: "
            f"{EXTRA_HINT}, or --records FILE|DIR")


@titled("timehistory", TITLE)
def section_timehistory(ctx: Context) -> Section:
    """The selection for the site spectrum, the records run on the arch, the codes' verdict on
    their effects and the kinematic check's verdict beside it (module doc)."""
    from .codecheck import code_check

    cfg = ctx.config
    spec = cfg.codecheck.spectrum
    if spec is None:
        return _skip("no site spectrum was given (--spectrum FILE, or --ag --f0 --tc-star "
                     "--soil, or --ec8-type): the records are chosen and scaled for it")
    if not cfg.records:
        return _skip(_no_records_reason())
    motions, count = ctx.records, cfg.selection.count
    if count < LEAST_RECORDS:
        return _skip(f"the selection asks for {count} record(s); the codes verify by time "
                     f"history with at least {LEAST_RECORDS} (the mean of the effects from "
                     f"{MEAN_RULE_RECORDS} on)")
    if len(motions) < count:
        return _skip(f"{len(motions)} record(s) given, the selection asks for {count} "
                     f"(--count N, at least {LEAST_RECORDS}; with fewer than "
                     f"{MEAN_RULE_RECORDS} the largest effect governs)")
    sel = _select(spec, motions, cfg.selection)
    sel_block = _selection_blocks(sel, motions, spec)
    cc = ctx.once("codecheck", lambda: code_check(ctx.arch, ctx.limit, cfg.codecheck))
    choice = ctx.dynamics
    data = {"selection": sel.to_dict(), "dynamics": choice.to_dict()}
    if choice.engine:
        why = (f"the four-link model is not valid here ({choice.reason}), and the report does "
               f"not run the contact engine over the selected records (minutes per record): "
               f"no time-history verdict is given rather than the four-link model's")
        return Section("timehistory", TITLE, sel_block + (Paragraph(f"Not run: {why}."),),
                       {**data, "skipped": True, "reason": why},
                       (("time-history verification", "not run (contact engine needed)"),))
    from .selection import scaled_motions

    runs = record_effects(ctx.model, scaled_motions(sel, motions), cc.directions)
    for row, f in zip(runs, sel.factors):
        row["factor"] = float(f)
    rule = code_rule([r["effect"] for r in runs])
    kin = _kinematic_verdict(cc)
    blocks = sel_block + (
        Paragraph(_method_text(ctx.model)),
        Table(("record", "scale factor", "outcome", "peak rotation [rad]", "d* [m]",
               "E_i = d* / d_u*"), tuple(_run_row(r) for r in runs),
              "Each scaled record on the arch (four-link model)."),
        Paragraph(_rule_text(rule)),
        Table(("method", "verdict", "governing figure (demand / capacity)", "rests on"),
              (_th_row(rule), _kin_row(kin)),
              "The time history and the simplified kinematic check (which governs: below)."),
    )
    governs = bool(sel.rules_hold)
    blocks += (Paragraph(_governing_text(rule, kin, governs, sel)),)
    data.update(records=runs, rule=rule, kinematic=kin, governs=governs,
                capacity={c.direction: {"du_star": float(c.du_star), "d0_star": float(c.d0_star)}
                          for c in cc.directions})
    head = (("time-history verification",
             f"{'pass' if rule['passed'] else 'FAIL'}, E = {_e(rule['value'])} "
             f"({rule['rule']} of {rule['n']} records)"),)
    return Section("timehistory", TITLE, blocks, data, head)


def _select(spec, motions, config):
    """The selection for the site spectrum (:func:`archrock.studies.selection.select_for_site`)."""
    from .selection import select_for_site

    return select_for_site(spec, motions, config)


def _selection_blocks(sel, motions, spec) -> tuple:
    """The selection's paragraph, its table and its figure (the figure draws the spectra beyond
    the period range from the motions it was made from and the target)."""
    pool = len(motions)
    rows = tuple((n, f"{f:.3f}", f"{p:.3f}") for n, f, p in zip(sel.names, sel.factors, sel.pga_g))
    lo, hi = sel.period_range
    text = (f"{sel.count} of {pool} records chosen and scaled for the site spectrum, as NTC "
            f"2018 par. 3.2.3.6 and EN 1998-1 par. 3.2.3.1.2 ask: the mean of their 5%-damped "
            f"spectra is nowhere below {sel.lower:g} x the target over {lo:g}-{hi:g} s (least "
            f"mean/target {sel.ratio_min:.3f} at {sel.ratio_period:.3g} s), scale factors "
            f"within {sel.scale_bounds[0]:g}-{sel.scale_bounds[1]:g}, mean PGA of the scaled "
            f"set {sel.pga_mean_g:.3f} g"
            + (f" (site: {sel.pga_min_g:.3f} g)" if sel.pga_min_g is not None else "") + ".")
    return (Paragraph(text),
            Table(("record", "scale factor", "scaled PGA [g]"), rows, "The selection."),
            Figure("selection", "Spectra of the scaled records, their mean, the target and "
                                "the period range.", (sel, motions, spec)))


def _method_text(model) -> str:
    extra = (" The impact law opens mechanisms other than M_l and M_r after some impacts; "
             "their rotations are mapped by the curve of the limit mechanism of the same "
             "direction (an approximation)." if model.extra else "")
    return ("Each scaled record runs on the four-link model (the model that holds for this "
            "arch, section Governing answer), from rest, through the record and the free "
            "rocking after it. Its effect is E_i = d*(phi_peak) / d_u*: the peak rotation mapped "
            "to the spectral displacement d* by the capacity curve of the code check (same "
            "mechanism, same control point), over the ultimate displacement d_u* of the "
            "nonlinear kinematic check; the direction of the peak is read from the response "
            f"sampled every {_DT_OUT:g} s. A record that collapses the arch has an unbounded "
            "effect (E_i = inf). FC does not enter: the rigid-block model has no material "
            "strength to divide." + extra)


def _e(x) -> str:
    return "inf" if x is None or not math.isfinite(x) else f"{x:.3g}"


def _run_row(r: dict) -> tuple:
    col = r["outcome"] == "collapsed"
    return (r["name"], f"{r['factor']:.3f}",
            f"collapse at {r['t_collapse']:.2f} s" if col else r["outcome"],
            f"{r['peak_rad']:.4f}", "-" if r["d_star"] is None else f"{r['d_star']:.4f}",
            "inf (collapse)" if col else f"{r['effect']:.3f}")


def _rule_text(rule: dict) -> str:
    word = "passes" if rule["passed"] else "FAILS"
    txt = (f"The codes' rule (NTC 2018 par. 7.3.5, EN 1998-1 par. 4.3.3.4.3): {rule['formula']}. "
           f"Here E = {_e(rule['value'])} over {rule['n']} records: the arch {word}.")
    if rule["collapsed"]:
        txt += (f" {rule['collapsed']} record(s) collapse the arch: a collapse is an unbounded "
                f"effect, so the " + ("mean" if rule["rule"] == "mean" else "largest")
                + " effect is unbounded and the verification fails.")
    return txt


def _kinematic_verdict(cc) -> dict:
    """The code check's verdict and its governing check as demand / capacity."""
    worst = None
    for c in cc.directions:
        for name, chk in c.checks.items():
            if isinstance(chk, dict) and "ratio" in chk:
                dc = 1.0 / chk["ratio"] if chk["ratio"] > 0 else math.inf
                # rounded: on a symmetric arch the directions tie and M_l is named
                if worst is None or round(dc, 9) > round(worst[0], 9):
                    worst = (dc, name, c.direction)
    if worst is None:
        return {"passed": None, "value": None, "check": None, "direction": None}
    return {"passed": cc.passed, "value": worst[0], "check": worst[1], "direction": worst[2]}


def _th_row(rule: dict) -> tuple:
    return ("time history (records scaled to the spectrum)", "pass" if rule["passed"] else "FAIL",
            f"E = {_e(rule['value'])} ({rule['rule']} of {rule['n']} records of d*_peak / d_u*)",
            "rigid rocking (four-link model) with its impact law, no viscous damping; the "
            "records' spectral shape")


def _kin_row(kin: dict) -> tuple:
    label = {"linear": "(Se(0)/q) / a_0*", "nonlinear": "S_De(T_s) / d_u*"}
    fig = ("-" if kin["value"] is None else
           f"{label.get(kin['check'], kin['check'])} = {_e(kin['value'])} "
           f"(M_{kin['direction']}, {kin['check']})")
    verdict = "-" if kin["passed"] is None else ("pass" if kin["passed"] else "FAIL")
    return ("kinematic check (NTC 2018 par. 8.7.1, Circolare 2019 C8.7.1.2)", verdict, fig,
            "an equivalent elastic oscillator of secant period T_s on the 5%-damped site "
            "spectrum; FC on the capacity")


def _governing_text(rule: dict, kin: dict, governs: bool, sel) -> str:
    """Which verdict is the report's and why: the time history where its records meet the
    codes' selection rules (the refined analysis the codes admit, on the arch's own rocking),
    else the kinematic check; where the two differ, why they may."""
    th = "passes" if rule["passed"] else "fails"
    if not governs:
        broken = "; ".join(r[0] for r in sel.rules if not r[1])
        return (f"The time history {th}, but its records do not meet the codes' selection "
                f"rules ({broken}): it is shown, and the report's verdict is the kinematic "
                f"check's.")
    text = (f"The time history governs the report's verdict: its records meet the codes' "
            f"selection rules, and it follows the arch's own nonlinear rocking (energy lost "
            f"only at the impacts) under them, where the kinematic check replaces the arch by "
            f"an elastic oscillator at the secant period T_s with the spectrum's 5% damping "
            f"and divides its strength by FC, a simplified check.")
    if kin["passed"] is not None and kin["passed"] != rule["passed"]:
        kc = "passes" if kin["passed"] else "fails"
        text += (f" The two differ here: the time history {th}, the simplified kinematic check "
                 f"{kc}; the kinematic check's result is shown as the simplified check's, not "
                 f"as the answer.")
    return text
