"""Sentences about a study's result that more than one output says: the fragility's range tried
and its fits, the resolution a curve's survival windows were searched at.  They live here, below
the reports, so that ``archrock fragility`` / ``archrock curves`` (archrock.reports) and the
assess report (archrock.studies.assessment_dynamics) word them once."""

from __future__ import annotations

from ..groundmotion.intensity import im_units

__all__ = ["im_suffix", "range_tried_line", "fit_line", "level_off_note", "resolution_line"]


def im_suffix(im: str) -> str:
    """' g', ' m/s', ...: the units after an intensity ('' for the scale factor)."""
    return "" if im == "scale" else " " + im_units(im)


def range_tried_line(ida_result) -> str | None:
    """What the IDA can say where records never collapse the arch: none collapsed -> 'no
    collapse up to X in N curve(s): P(collapse) <= p over the range tried' (one-sided 95%
    Clopper-Pearson bound); some -> how many are censored observations; all collapsed -> None."""
    rng = ida_result.range_tried()
    u = im_suffix(ida_result.im)
    if rng["p_upper_95"] is not None:
        return (f"no collapse up to {rng['max_im']:.4f}{u} in {rng['n_curves']} curve(s): "
                f"P(collapse) <= {rng['p_upper_95']:.3f} over the range tried (one-sided 95%, "
                f"Clopper-Pearson)")
    if rng["n_never"]:
        return (f"{rng['n_never']} of {rng['n_curves']} curves never collapse up to "
                f"{rng['max_im']:.4f}{u} (censored observations in the fit)")
    return None


def fit_line(fit, im: str) -> str:
    """'<method> theta = T, beta = B[, p_max = P] (n = N)': p_max only where the curve levels
    off below P = 1 (theta is then the median of the records that do collapse)."""
    u = im_suffix(im)
    plateau = f", p_max = {fit.p_max:.3f}" if fit.p_max < 1.0 else ""
    return (f"{fit.method} theta = {fit.theta:.4f}{u}, beta = {fit.beta:.3f}{plateau} "
            f"(n = {fit.n_records})")


def level_off_note(fit) -> str | None:
    """The level-off test's sentence where it chose the plateau, else None."""
    lo = fit.level_off
    return lo["note"] if lo is not None and lo.get("levels_off") else None


def resolution_line(curve) -> str:
    """The resolution a curve's survival windows were searched at (the grid's step in g at each
    first collapse: a narrower window can lie between two grid points unseen)."""
    res = [p.resolution for p in curve.points]
    if not res or any(r.get("step_relative") is None for r in res):
        return res[0]["note"] if res else "no survival windows searched"  # the engine's curve
    steps = [r["step_g"] for r in res]
    lo, hi = min(steps), max(steps)
    span = f"{lo:.4f} g" if hi - lo < 5e-5 else f"{lo:.4f}-{hi:.4f} g"
    r = res[0]
    return (f"survival windows searched on a geometric grid of {r['n_scan']} points stepping "
            f"{100 * r['step_relative']:.2g}% of |a|: windows narrower than {span} (the step at "
            f"the first collapse; {max(x['step_g_at_a_max'] for x in res):.3g} g at a_max) may "
            f"be missed; edges of those found bisected to {r['edge_tol_g']} g")
