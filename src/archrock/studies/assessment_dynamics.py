"""The report's dynamics sections and its closing ones: impact laws, the response to the
paper's pulse, the collapse curves, defects, fragility, the contact engine, the code check and
the assumptions (:mod:`archrock.studies.assessment` orders them)."""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError, ArchrockError
from ..geometry import VoussoirArch
from .assessment_context import Context
from .assessment_blocks import (REFERENCES, Figure, Paragraph, Section, Table, _f,
                                _optional_missing, titled)


@titled('impact', 'Impact coefficients by model')
def section_impact(ctx: Context) -> Section:
    from ..dynamics.impact import least_loss_mechanism
    from ..dynamics.response import prepare

    lim = ctx.limit
    rows, data = [], {}
    for model in ("paper", "momentum"):
        try:
            law = prepare(ctx.arch, model, limit=lim).impact
        except ArchrockError as exc:
            rows.append((model, "-", "-", f"not applicable: {exc}"))
            data[model] = {"error": str(exc)}
            continue
        rows.append((model, f"{law.l_to_r:.5f}", f"{law.r_to_l:.5f}", f"{law.equivalent_cv:.5f}"))
        data[model] = law.to_dict()
    try:
        m = ctx.model
        ll = least_loss_mechanism(m.mech_l, m.mech_r)
        data["least_loss_after_M_l"] = ll.to_dict()
        ll_txt = (f"After an impact closing M_l, the post-impact mechanism that keeps the most "
                  f"kinetic energy under the momentum law keeps {ll.energy_ratio:.3f} of it, "
                  f"against {ll.limit_energy_ratio:.3f} for M_r (Bisegna et al. 2023).")
    except ArchrockError as exc:
        ll_txt = f"Least-loss mechanism: not found ({exc})."
    used = ctx.config.impact
    blocks = (Paragraph("At each impact the mechanism closes and the other opens; the rate of "
                        "the new mechanism is c times the old (kinetic energy times c^2 on a "
                        "symmetric arch). 'paper': De Lorenzis et al.'s five equations as the "
                        "paper applies them; 'momentum': the energy-consistent projection of the "
                        "momentum balance on the new motion."),
              Table(("model", "c (M_l -> M_r)", "c (M_r -> M_l)", "equivalent c_v"), tuple(rows)),
              Paragraph(ll_txt),
              Paragraph(_law_that_ran(ctx, used, data)))
    data["used"] = used.to_dict()
    head = ()
    if "paper" in data and "l_to_r" in data["paper"]:
        head = (("c_v (paper model)", f"{data['paper']['l_to_r']:.5f}"),)
    return Section("impact", "Impact coefficients by model", blocks, data, head)


def _law_that_ran(ctx, used, data: dict) -> str:
    """'The response and the curves below use: <the law that ran>', from the prepared model's
    law (its fallback and reason where the law asked for could not be used); the law and the
    reason go to ``data["ran"]``."""
    where = f"evaluated on the {'nominal arch' if used.on == 'nominal' else 'arch'}"
    try:
        law = ctx.model.impact
    except ArchrockError as exc:
        data["ran"] = {"error": " ".join(str(exc).split())}
        return (f"The response and the curves below use: none: the law asked for ({used.model}) "
                f"cannot be used on this arch ({data['ran']['error']}).")
    c = (f"c = {law.l_to_r:.5f} closing M_l, {law.r_to_l:.5f} closing M_r")
    data["ran"] = {"model": law.model, "asked": used.model, "fallback": law.fallback,
                   "l_to_r": law.l_to_r, "r_to_l": law.r_to_l}
    if law.fallback:
        txt = (f"{law.model} ({c}), because the {used.model} law could not be used: "
               f"{law.fallback}")
    else:
        txt = f"{law.model} ({c}" + (f", c_v {used.cv:g}" if used.cv else "") + ")"
    engine = ""
    try:
        if ctx.dynamics.engine:
            engine = (" Here the contact engine governs the dynamics (section Governing "
                      "answer): its contacts need no impact law; the law applies only where "
                      "the four-link model is asked for by name.")
    except ArchrockError:
        pass
    return f"The response and the curves below use: {txt}, {where}.{engine}"


@titled('response', "Response to the paper's pulse")
def section_response(ctx: Context) -> Section:
    from ..groundmotion import oppenheim_pulse
    from ..dynamics.response import respond

    cfg = ctx.config
    motion = oppenheim_pulse(cfg.pulse_amplitude, cfg.pulse_duration)
    choice = ctx.dynamics
    if choice.engine:  # the four-link model is not valid here: its answer is never printed
        return _engine_response(ctx, choice, motion)
    res = respond(ctx.model, motion, t_end=cfg.t_end)
    impacts = res.impacts
    outcome = (f"collapses (last passage of the unstable position at {res.t_collapse:.3f} s)"
               if res.collapsed else f"does not collapse ({res.status})")
    blocks = (Paragraph(f"Oppenheim's pulse: a = {cfg.pulse_amplitude:g} g for t_p = "
                        f"{cfg.pulse_duration:g} s, then -a/2 for 2 t_p (the paper's forcing). "
                        f"The arch {outcome}; peak rotation {res.peak:.4f} rad; "
                        f"{len(impacts)} impact(s)"
                        + (f", the first at {', '.join(f'{t:.4f}' for t in impacts[:3])} s"
                           if impacts else "") + "."),
              Figure("response", "Ground acceleration and the signed response (+phi in M_l, "
                                 "-phi in M_r).", res))
    data = res.to_dict(samples=False)
    data["pulse"] = {"kind": "oppenheim", "amplitude_g": cfg.pulse_amplitude,
                     "duration_s": cfg.pulse_duration}
    data["dynamics"] = choice.to_dict()
    return Section("response", "Response to the paper's pulse", blocks, data,
                   (("paper pulse", "collapse" if res.collapsed else f"survives, peak {res.peak:.4f} rad"),))


def _engine_response(ctx, choice, motion) -> Section:
    """The response to the pulse by the contact engine, at the report's friction (a friction
    high enough not to slide where the user excluded sliding)."""
    from .enginestudy import EngineRun
    from .governing import engine_friction

    cfg, title = ctx.config, "Response to the paper's pulse"
    pulse = {"kind": "oppenheim", "amplitude_g": cfg.pulse_amplitude,
             "duration_s": cfg.pulse_duration}
    why = (f"The four-link model is not valid here ({choice.reason}): the contact engine "
           f"(rigid blocks, contact and Coulomb friction, archrock.contact) gives the response.")
    try:
        from ..contact import EngineSettings, require_engine

        require_engine()
    except ImportError:
        return Section("response", title, (Paragraph(
            why + " The engine is needed and is not installed: pip install 'archrock[dem]'. "
            "No four-link answer is given in its place."),),
            {"engine_needed": True, "pulse": pulse, "dynamics": choice.to_dict()},
            (("paper pulse", "not computed: the contact engine is needed (pip install "
                             "'archrock[dem]')"),))
    fr = ctx.friction
    mu, note = engine_friction(cfg.friction, None if fr is None else fr["needed"])
    res = EngineRun(settings=EngineSettings(friction=mu)).respond(ctx.arch, motion)
    if res.collapsed:
        outcome, head = (f"collapses (a block has dropped by the collapse threshold at "
                         f"t = {res.t_collapse:.3f} s)"), f"collapse at t = {res.t_collapse:.3f} s"
    else:
        outcome = f"does not collapse ({res.status} at t = {res.t_final:.3f} s)"
        head = f"no collapse ({res.status}), peak {res.peak:.4f} rad"
    text = (why + f" Oppenheim's pulse: a = {cfg.pulse_amplitude:g} g for t_p = "
            f"{cfg.pulse_duration:g} s, then -a/2 for 2 t_p. At mu = {mu:g}"
            + (f" ({note})" if note else "") + f", the arch {outcome}; peak equivalent "
            f"rotation {res.peak:.4f} rad, largest sliding {float(res.max_sliding.max()):.3g} m.")
    data = {**res.to_dict(samples=False), "pulse": pulse, "how": "contact engine",
            "dynamics": choice.to_dict()}
    return Section("response", title, (Paragraph(text),), data,
                   (("paper pulse (contact engine)", head),))


@titled('curves', 'Collapse-acceleration curve and its band over irregular arches')
def section_curves(ctx: Context) -> Section:
    from .curves import collapse_curve, ensemble_curve
    from .enginestudy import engine_curves_section
    from .wording import resolution_line

    choice = ctx.dynamics  # at the report's friction: where one degree of freedom cannot follow
    if choice.engine:
        return engine_curves_section(ctx, choice)
    cfg = ctx.config
    kw = dict(kind="oppenheim", sign=-1, n_scan=cfg.n_scan)
    band = None
    if cfg.samples > 0 and isinstance(ctx.arch, VoussoirArch):
        try:
            band = ensemble_curve(ctx.arch, cfg.samples, cfg.seed, cfg.spreads, cfg.durations,
                                  impact=cfg.impact, **kw)
        except ArchInputError as exc:  # an arch that cannot be perturbed: nominal curve only
            ctx.progress(f"  band over irregular arches left out: {exc}")
    curve = band.nominal if band is not None else collapse_curve(ctx.model, cfg.durations, **kw)
    rows = tuple((f"{p.duration:g}", _f(float(a), ".4f"), p.mode or "-", _windows(p.windows))
                 for p, a in zip(curve.points, curve.amplitudes))
    s = cfg.spreads
    band_txt = (f"The band spans the quantiles of {band.n_samples} irregular arches (seed "
                f"{cfg.seed}; spreads: span {s.span:g}, thickness {s.thickness:g}, radius "
                f"{s.radius:g} t" + (f", joint tilt {s.tilt:g} deg" if s.tilt else "")
                + ")." if band is not None else "No band: no random arches were asked for.")
    blocks = (Paragraph("For each pulse duration, the smallest amplitude of Oppenheim's pulse "
                        "(first push toward -x) that collapses the arch; collapse is not "
                        "monotonic in the amplitude, so survival windows above it are drawn "
                        "and listed, their edges refined by bisection; "
                        + resolution_line(curve) + ". " + band_txt),
              Figure("curves", "Collapse-acceleration curve.", (curve, band)),
              Table(("t_p [s]", "first collapse |a| [g]", "collapse mode",
                     "survival windows above it [g]"), rows))
    data = {"nominal": curve.to_dict(), "dynamics": choice.to_dict()}
    if band is not None:
        data["band"] = band.to_dict()
    return Section("curves", "Collapse-acceleration curve and its band over irregular arches",
                   blocks, data)


def _windows(windows) -> str:
    """Survival windows as 'lo-hi' [g], to 5 decimals: their edges are bisected to
    min(tol, 1e-4 |a|), and a window can be 0.15% wide (docs/curves.md)."""
    return ", ".join(f"{lo:.5f}-{hi:.5f}" for lo, hi in windows) or "-"


@titled('defects', 'Defect map: which voussoir, if damaged, costs the most capacity')
def section_defects(ctx: Context) -> Section:
    """OPTIONAL: the defect map (archrock.studies.defectmap)."""
    title = "Defect map: which voussoir, if damaged, costs the most capacity"
    try:
        from .defectmap import defect_map
    except ImportError:
        return _optional_missing("defects", title, "studies.defectmap", "The defect map")
    res = defect_map(ctx.arch)  # 30% thickness loss about the centreline, each voussoir
    from .defectmap import worst_summary

    w = worst_summary(res)  # on piers a thinned pier course is a pier defect, said apart
    a, p = w["arch"], w["piers"]
    head = ((w["label"], f"{a['where']}: -{100 * a['relative_loss']:.1f}%"),)
    pier_txt = ""
    if p:
        pier_txt = (f" Each pier course in turn loses 30% of its width the same way: the worst "
                    f"pier defect is {p['where']}: min(k_l, k_r) falls to {p['k']:.4f} g "
                    f"({100 * p['relative_loss']:.1f}%).")
        head += (("worst pier defect", f"{p['where']}: -{100 * p['relative_loss']:.1f}%"),)
    return Section("defects", title, (
        Paragraph(f"Each voussoir in turn loses 30% of its thickness about its centreline "
                  f"(docs/defects.md). The largest loss of capacity comes from {a['where']} "
                  f"(numbered from the arch's left springing): min(k_l, k_r) falls from "
                  f"{res.k0:.4f} to {a['k']:.4f} g ({100 * a['relative_loss']:.1f}%)."
                  f"{pier_txt} `archrock defects` maps the other defects (joint tilt, missing "
                  f"mortar) and, with a pulse, the first-collapse amplitude."),
        Figure("defects", "Capacity lost when each voussoir" + (" or pier course" if p else "")
               + " is the damaged one (red: lost, blue: gained, in % of the undamaged k).",
               res)),
        {"available": True, **res.to_dict()}, head)


@titled('fragility', 'Fragility curves')
def section_fragility(ctx: Context) -> Section:
    cfg = ctx.config
    if not cfg.records:
        why = ("no accelerograms were given: fragility curves are fitted to the collapses of "
               "the arch under recorded ground motions (`archrock assess --records "
               "FILE|DIR|SUITE`, PEER .AT2 or two-column files, or a built-in suite such as "
               "p695-far-field, the default with a site spectrum where the 'records' extra is "
               "installed)")
        return Section("fragility", "Fragility curves", (Paragraph(f"Skipped: {why}."),),
                       {"skipped": True, "reason": why})
    choice = ctx.dynamics
    if choice.engine:
        why = (f"the four-link model is not valid here ({choice.reason}), and the report does "
               f"not run the contact engine over records x scales (minutes per record): no "
               f"fragility is given rather than the four-link model's")
        return Section("fragility", "Fragility curves", (Paragraph(f"Left out: {why}."),),
                       {"skipped": True, "reason": why, "dynamics": choice.to_dict()})
    from .ida import default_stripe_levels, ida, msa, random_models

    records = ctx.records
    models = (random_models(ctx.arch, cfg.samples, cfg.seed, cfg.spreads, cfg.impact)
              if cfg.samples > 0 else [ctx.model])
    res_ida = ida(records, models, np.array(cfg.scales), n_boot=cfg.bootstrap, seed=cfg.seed)
    levels = default_stripe_levels(res_ida, np.array(cfg.scales), records)
    res_msa = msa(records, models, levels, n_boot=cfg.bootstrap, seed=cfg.seed)
    fit = res_msa.fit if res_msa.fit is not None else res_ida.fit
    txt, head = _fragility_words(res_ida, res_msa, fit)
    blocks = (Paragraph(f"{len(records)} record(s) x {len(models)} arch(es): incremental dynamic "
                        f"analysis (first collapse per record and arch) and multiple stripes "
                        f"(binomial likelihood, Baker 2015); IM = PGA of the scaled record. {txt}"),
              Figure("fragility", "Fragility curves.", (fit, res_msa, res_ida)))
    data = {"ida": res_ida.to_dict(), "msa": res_msa.to_dict(),
            "records": [str(r) for r in cfg.records], "dynamics": choice.to_dict()}
    return Section("fragility", "Fragility curves", blocks, data, head)


def _fragility_words(res_ida, res_msa, fit) -> tuple[str, tuple]:
    """The fragility paragraph's result and its headline row, in the words of ``archrock
    fragility`` (archrock.studies.wording): where no record collapses the arch, the bound over
    the range tried and no fit (no median claimed); where the fit levels off, p_max and the
    test's note (theta is then the median of the records that collapse)."""
    from .wording import fit_line, level_off_note, range_tried_line

    rng = res_ida.range_tried()
    said = range_tried_line(res_ida)
    if rng["p_upper_95"] is not None:  # nothing collapsed: the bound is all the data say
        return (f"IDA: {said}; no fragility curve is fitted.",
                (("fragility", f"no collapse up to {rng['max_im']:.3f} g: P(collapse) <= "
                               f"{rng['p_upper_95']:.3f}"),))
    parts = [f"IDA: {said}."] if said else []
    if fit is None:
        why = res_msa.fit_error or res_ida.fit_error
        parts.append(f"No fit could be identified ({why}).")
        return " ".join(parts), ()
    which = "stripes" if fit is res_msa.fit else "IDA"
    parts.append(f"Fit ({which}): {fit_line(fit, res_ida.im)}.")
    note = level_off_note(fit)
    if fit.p_max < 1.0:
        parts.append(f"The curve levels off at P = {fit.p_max:.3f}: "
                     f"{note or 'an upper asymptote below 1 was asked for'}; theta is the "
                     f"median of the records that collapse, and P = 0.5 is "
                     + ("never reached." if fit.p_max <= 0.5 else
                        f"reached at {float(fit.quantile(0.5)):.3f} g."))
        return " ".join(parts), (("fragility theta [g]", f"{fit.theta:.3f}, levelling off at "
                                                          f"P = {fit.p_max:.3f}"),)
    return " ".join(parts), (("fragility median PGA [g]", f"{fit.theta:.3f}"),)


def _contact_rows(eng, lim) -> tuple:
    """The table rows of the contact-engine check, one a direction: the engine's multiplier
    beside the limit analysis's at the same friction, their difference, the refined run's and
    both hinge sets."""
    ref, refined = eng.details["compared_with"], eng.details["refined"]
    rows = []
    for d in ("l", "r"):
        k_eng, k_ref = eng.k(d), ref[d]
        diff = "-" if not k_ref else f"{100 * (k_eng / k_ref - 1):+.1f}%"
        fine = "-" if d not in refined else f"{refined[d]['multiplier']:.4f}"
        rows.append((f"M_{d}", f"{k_eng:.4f}", "-" if k_ref is None else f"{k_ref:.4f}", diff,
                     fine, eng.mechanism(d), " ".join(map(str, lim.mechanism(d).joints)),
                     "holds" if eng.holds[d] else "not converged"))
    return tuple(rows)


@titled('contact', 'Contact-engine check')
def section_contact(ctx: Context) -> Section:
    """OPTIONAL: the contact-engine check (archrock.contact, the 'dem' extra): the governing
    decision's engine ramp at the report's friction, beside the limit analysis at the same
    friction, with the findings where they disagree by more than 2%."""
    from .governing import ENGINE

    title = "Contact-engine check"
    try:
        from ..contact import require_engine

        require_engine()  # archrock's engine: nothing to install
        gov = ctx.governing
    except ImportError:
        return _optional_missing("contact", title, "contact", "The contact-engine (pymunk) check")
    eng = gov.analysis(ENGINE)
    if eng is None:
        why = dict(gov.left_out).get(ENGINE, "not run")
        if "pymunk" in why:
            return _optional_missing("contact", title, "contact",
                                     "The contact-engine (pymunk) check")
        return Section("contact", title, (Paragraph(f"Not run: {why}."),),
                       {"available": False, "why": why})
    det = eng.details
    ref, refined = det["compared_with"], det["refined"]
    rows = _contact_rows(eng, ctx.limit)
    mu = det["settings"]["friction"]
    text = ("The same voussoirs as rigid bodies with contact and non-associative Coulomb "
            f"friction (mu = {mu:g}, the report's friction"
            + (f"; {det['friction_note']}" if det["friction_note"] else "") + ") in the pymunk "
            "engine, under a slowly increasing horizontal ground acceleration in each "
            "direction: the acceleration at which the arch starts to move and the joints that "
            "open, beside the limit analysis at the same friction (docs/verification.md, "
            "Contact engine). Joints are numbered from the left springing (0). Where the two "
            "differ by more than 2%, the ramp is run again refined (fine contact outline, "
            "twice the steps) to tell a disagreement of the models from one of the engine's "
            "discretisation.")
    blocks = [Paragraph(text),
              Table(("direction", "engine multiplier", "limit analysis at the same friction",
                     "difference", "engine refined", "engine hinges", "limit hinges",
                     "engine"), rows)]
    if gov.findings:
        blocks.append(Paragraph("Finding: " + " ".join(gov.findings)))
    data = {"available": True, "k_l": eng.k_l, "k_r": eng.k_r,
            "hinges_l": det["ramp"]["l"]["hinges"], "hinges_r": det["ramp"]["r"]["hinges"],
            "friction": mu, "compared_with": ref, "refined": refined,
            "holds": eng.holds, "why": eng.why, "findings": list(gov.findings),
            "l": det["ramp"]["l"], "r": det["ramp"]["r"], "engine": det["settings"]}
    return Section("contact", title, tuple(blocks), data,
                   (("contact engine k_l / k_r", f"{eng.k_l:.4f} / {eng.k_r:.4f} (mu = {mu:g})"
                     + ("; not converged, see Governing answer"
                        if not all(eng.holds.values()) else "")),))


@titled('codecheck', 'Code check: kinematic analysis (NTC 2018 / Circolare 2019)')
def section_codecheck(ctx: Context) -> Section:
    from .codecheck import code_check
    from ..units import G

    cfg = ctx.config.codecheck
    # once per report: the time-history verification reads the same check's capacity curves
    res = ctx.once("codecheck", lambda: code_check(ctx.arch, ctx.limit, cfg))
    dirs = res.directions
    rows = [("activation multiplier alpha_0", *[f"{c.alpha_0:.6f}" for c in dirs]),
            ("participating mass M* [kg/m]", *[f"{c.m_star:.1f}" for c in dirs]),
            ("mass fraction e*", *[f"{c.e_star:.4f}" for c in dirs]),
            (f"a_0* [g] (FC = {cfg.fc:g})", *[f"{c.a0_star / G:.4f}" for c in dirs]),
            ("d_0* [m]", *[f"{c.d0_star:.4f}" for c in dirs]),
            (f"d_u* = {cfg.ultimate_fraction:g} d_0* [m]", *[f"{c.du_star:.4f}" for c in dirs]),
            ("T_s [s]", *[f"{c.ts:.3f}" for c in dirs])]
    for kind, lab in (("linear", "linear check a_0* / (Se(0)/q)"),
                      ("nonlinear", "nonlinear check d_u* / S_De(T_s)")):
        if all(kind in c.checks for c in dirs):
            rows.append((lab, *[f"{c.checks[kind]['ratio']:.3f} "
                                f"{'pass' if c.checks[kind]['passed'] else 'FAIL'}" for c in dirs]))
    spec = cfg.spectrum
    spec_txt = ("No site spectrum was given (--spectrum FILE, or --ag --f0 --tc-star --soil, "
                "or --ec8-type): the table gives the capacity only, and there is no verdict: "
                "the check compares the capacity with a site's demand." if spec is None
                else f"Site spectrum: {spec.kind}"
                + (f" ({spec.source})" if spec.source else "") + f", Se(0) = {spec.pga:.3f} g.")
    blocks = (Paragraph("The kinematic analysis of local mechanisms of the Italian code (NTC 2018 "
                        "par. 8.7.1, Circolare 2019 C8.7.1.2), applied to the mechanisms that "
                        "limit analysis found, the arch's springings at ground level. The capacity "
                        "curve is the exact equilibrium of the displaced four-link mechanism; the "
                        "code's straight line is drawn beside it. " + spec_txt
                        + " Formulas and clauses: docs/codecheck.md."),
              Table(("quantity", *[f"M_{c.direction}" for c in dirs]), tuple(rows)),
              Figure("codecheck", "Capacity curves a*(d*) of both mechanisms, d_u*, d_s* and the "
                                  "secant period; the demand S_De(T_s) when a spectrum is given.",
                     res))
    head = [("code check a_0* [g]", f"{min(c.a0_star for c in dirs) / G:.4f}")]
    if res.passed is not None:
        head.append(("code check", "pass" if res.passed else "FAIL"))
    return Section("codecheck", "Code check: kinematic analysis (NTC 2018 / Circolare 2019)",
                   blocks, res.to_dict(), tuple(head))


@titled('assumptions', 'Assumptions, conventions and references')
def section_assumptions(ctx: Context) -> Section:
    cfg = ctx.config
    mu = cfg.friction
    fc = getattr(ctx.arch, "fc", None)
    fr_txt = ("sliding excluded by the user (--friction none): Heyman's no-sliding hypothesis, "
              "stated as such" if mu is None else f"Coulomb mu = {mu:g} at every joint, used by "
              "the friction analysis, the governing answer, the routing of the dynamics and the "
              "contact engine alike")
    try:
        choice = ctx.dynamics
        if choice.engine:
            dyn_txt = f"the contact engine, because {choice.reason}."
        else:
            dyn_txt = ("the four-link model (Oppenheim 1992): once activated the arch moves as "
                       "a single-degree-of-freedom mechanism with exact large-rotation "
                       "kinematics, no sliding; at each impact the other mechanism opens with "
                       "the impact law; the arch collapses when the rotation passes the "
                       f"unstable position for the last time. Chosen because {choice.reason}.")
    except ArchrockError as exc:
        dyn_txt = f"no model could be chosen ({' '.join(str(exc).split())})."
    items = [
        "Units: SI; lengths in metres, masses per metre of the arch's depth (a plane problem), "
        "accelerations in g (9.81 m/s^2) unless marked m/s^2. x to the right, y up; joint 0 is "
        "the left springing.",
        "Loads: the weight of each voussoir (with any attached load) and a horizontal force "
        "lambda times it, at its mass centre. M_l: forces toward +x, activated by a ground "
        "acceleration toward -x of k_l g; M_r the mirror case.",
        f"Friction: one coefficient for the whole report, {fr_txt}.",
        ("Limit analysis (no sliding): Heyman's masonry: rigid voussoirs, no tensile strength, "
         "no crushing (unlimited compressive strength), no sliding; hinges form at the ends of "
         "each joint's contact segment." if fc is None else
         f"Limit analysis (no sliding): rigid voussoirs, no tensile strength, compressive "
         f"strength f_c = {fc:g} MPa on a rectangular stress block (1 m deep), no sliding; "
         f"hinges form at the centres of the stress blocks, half a block in from the joints' "
         f"edges; the four-link model rocks about those hinges, frozen at the collapse forces "
         f"(docs/crushing-dynamics.md)."),
        ("Limit analysis with friction: as above, with associative Coulomb friction at "
         f"mu = {mu:g} at every joint instead of no sliding (not a guaranteed lower bound where "
         "the real friction is non-associative: docs/friction.md)." if mu is not None else
         "Limit analysis with friction: left out (sliding excluded by the user)."),
        "Contact engine: rigid blocks with contacts and non-associative Coulomb friction at the "
        "report's friction (pymunk); no crushing; its value depends on its discretisation, "
        "checked by a refined run where it disagrees with the limit analysis by more than 2%.",
        f"Response, curves and fragility: {dyn_txt}",
        f"Impact law: {cfg.impact.model} asked for on the {cfg.impact.on} arch"
        + (f" (c_v {cfg.impact.cv:g})" if cfg.impact.cv else "")
        + " (the law that ran, with any fallback, is in section Impact coefficients).",
        "Irregular arches: spans, thicknesses and radii of the voussoirs drawn uniformly within "
        "the spreads around the nominal arch (docs/method.md, Geometry widths); sample i is the "
        "same arch in every study of a seed.",
        "Code check: the mechanism is at ground level (the springings on the ground); the code's "
        "straight-line capacity curve is replaced by the exact curve of the four-link model "
        "(both reported); FC divides accelerations only; EN 1998-3 has no such procedure, so only "
        "its spectrum (EN 1998-1) can be used with it.",
        "Not modelled in any section: "
        + ("crushing, " if fc is None else "crushing in the contact engine and the friction "
           "analysis, ")
        + "the fill and spandrels (unless given as loads), the deformability of the piers, "
        "vertical ground motion, damping other than impacts.",
    ]
    refs = [f"[{k}] {v}" for k, v in REFERENCES.items()]
    blocks = tuple(Paragraph(t) for t in items) + (Table(("reference",), tuple((r,) for r in refs),
                                                          "References (cited as text)."),)
    return Section("assumptions", "Assumptions, conventions and references", blocks,
                   {"assumptions": items, "references": REFERENCES, "config": cfg.to_dict()})
