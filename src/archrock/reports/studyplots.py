"""Figures of studies: collapse-acceleration curves (:func:`plot_collapse_curve`),
fragility curves with their stripes and IDA steps (:func:`plot_fragility`), an ensemble's
multiplier histograms (:func:`plot_multiplier_histograms`) and defect maps
(:func:`plot_defect_map`, the arch coloured by the capacity lost).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from ..errors import ArchInputError
from .drawing import (
    STYLE, draw_arch, new_figure, _require_matplotlib, save_figure, voussoir_outline)


# ---------------------------------------------------------------------------- collapse curves, fragility
_MODE_MARKERS = {"before first impact": ("o", "#c0392b"), "after impacts": ("s", "#1f4e9c")}


def _plural(n: int, one: str, many: str | None = None) -> str:
    return f"{n} {one if n == 1 else (many or one + 's')}"


def _n_arches(n: int, n_requested: int, left_out: int) -> str:
    """'n = 20 random arches (3 of 23 left out)' for a legend or title."""
    extra = f" ({left_out} of {n_requested} left out: not counted)" if left_out else ""
    return f"$n$ = {n} random arch{'es' if n != 1 else ''}{extra}"


def plot_collapse_curve(curve, path: str | os.PathLike | None = None, band=None, *, ax=None,
                        title: str | None = None, dpi: int = 120):
    """Collapse-acceleration curve: first collapse amplitude |a| [g] against t_p [s].

    curve: :class:`archrock.studies.curves.CollapseCurve` (the nominal arch when a band is given);
    markers by collapse mode (before the first impact / after impacts), survival windows above
    the first collapse as vertical bars, the static multiplier k as a dotted line.  band: an
    :class:`archrock.studies.curves.EnsembleCurve` (its outer quantiles shaded, its median dashed, over
    its usable arches, n in the legend; a band that cannot be estimated is said so).  Every
    line has a legend entry.  Writes ``path`` when given; returns the figure.
    """
    fig = None
    if ax is None:
        fig, axes = new_figure(1, 1, figsize=(6.4, 4.4))
        ax = axes[0][0]
    d = np.asarray(curve.durations, dtype=float)
    a = np.asarray(curve.amplitudes, dtype=float)
    if band is not None:
        b = np.asarray(band.bands, dtype=float)
        q = band.quantiles
        n_txt = _n_arches(band.n_samples, band.n_requested, len(band.failed))
        if band.band_note:  # nothing to shade: say so rather than draw a zero-width band
            ax.plot([], [], " ", label=f"quantile band n/a ({band.band_note})")
            if len(band.amplitudes) == 1:
                one = np.where(np.isfinite(band.amplitudes[0]), band.amplitudes[0], np.nan)
                ax.plot(band.durations, one, "--", color="#1f4e9c", lw=1.0,
                        label=f"random arch {band.samples[0]}: first collapse $|a|$, {n_txt}")
        else:
            top = np.where(np.isfinite(b[-1]), b[-1], np.nan)  # inf: no collapse up to a_max
            ax.fill_between(band.durations, b[0], top, color="#9bb7d4", alpha=0.45, lw=0,
                            label=f"$q_{{{q[0]:g}}}$ to $q_{{{q[-1]:g}}}$ of random arches, "
                                  f"{n_txt}")
            if len(q) >= 3:
                mid = len(q) // 2
                ax.plot(band.durations, b[mid], "--", color="#1f4e9c", lw=1.0,
                        label=f"$q_{{{q[mid]:g}}}$ of random arches")
    name = "nominal arch" if band is not None else "arch"
    ax.plot(d, a, "-", color="#444444", lw=1.0, zorder=2, label=f"{name}: first collapse $|a|$")
    for key, (marker, color) in _MODE_MARKERS.items():
        sel = np.array([(m == key) if key == "before first impact" else
                        (m is not None and m.startswith("after")) for m in curve.modes])
        if sel.any():
            ax.plot(d[sel], a[sel], marker, color=color, ms=6, zorder=3,
                    label=f"{name}: collapse {key}")
    first = True
    for tp, wins in zip(d, curve.windows):
        for lo, hi in wins:
            ax.plot([tp, tp], [lo, hi], color="#27ae60", lw=3.0, alpha=0.8, zorder=2,
                    label=f"{name}: survival above first collapse" if first else None)
            first = False
    res = [r for r in (getattr(p, "resolution", None) for p in curve.points)
           if r and r.get("step_relative") is not None]  # the engine searches no windows
    if res:  # a list of windows says the step it was searched at (issue 30)
        rel = max(r["step_relative"] for r in res)
        ax.plot([], [], " ", label=f"windows searched at {100 * rel:.2g}% steps of $|a|$: "
                                   f"narrower ones may be missed")
    sign = curve.points[0].sign if curve.points else -1
    k = curve.k_l if sign < 0 else curve.k_r
    if math.isfinite(k):
        ax.axhline(k, color="#777777", ls=":", lw=1.0,
                   label=f"static multiplier $k_{'l' if sign < 0 else 'r'}$ = {k:.3f} g")
    ax.set_xlabel("pulse duration $t_p$ [s]")
    ax.set_ylabel("first collapse amplitude $|a|$ [g]")
    if title:
        ax.set_title(title, fontsize=10)
    ax.set_xlim(0, max(d) * 1.05)
    ax.set_ylim(0, None)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7.5, frameon=False)
    if fig is not None and path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig if fig is not None else ax.figure


def plot_fragility(fit, stripes=None, path: str | os.PathLike | None = None, *, ida=None, ax=None,
                   im_label: str | None = None, dpi: int = 120):
    """Lognormal fragility P(collapse | IM): the fitted curve, its bootstrap band (the
    curves at the ends of the theta and beta intervals, when the fit carries them; an interval
    that cannot be estimated is said so), observed stripe fractions (an
    :class:`archrock.studies.ida.StripeResult`) and IDA first collapses (an
    :class:`archrock.studies.ida.IDAResult`, as an empirical CDF over its curves).  The title states the
    records and arches; im_label defaults to the IM of the results.  Writes ``path``; returns
    the figure."""
    fig = None
    if ax is None:
        fig, axes = new_figure(1, 1, figsize=(6.4, 4.4))
        ax = axes[0][0]
    from ..groundmotion.intensity import im_label as _label, im_units

    im = getattr(stripes, "im", None) or getattr(ida, "im", None) or "pga"
    unit = "" if im == "scale" else im_units(im)
    if im_label is None:
        im_label = _label(im)
    xs = []
    if stripes is not None:
        xs.append(np.asarray(stripes.levels, dtype=float))
    if ida is not None:
        f = ida.first_ims
        xs.append(f[np.isfinite(f)])
        xs.append(np.array([max(c.max_im for c in ida.curves)]))  # the range tried
    if fit is not None:  # a plateau's top quantile is never reached: up to 99% of p_max
        q = np.asarray(fit.quantile(np.array([0.01, 0.99]) * fit.p_max))
        xs.append(q if fit.p_max >= 1.0 else q[:1])
    if not xs:
        raise ArchInputError("fit: nothing to plot (give a fit, stripes or an IDA result)")
    x_hi = max(float(np.max(v)) for v in xs if np.size(v)) * 1.15
    x = np.linspace(0.0, x_hi, 300)
    if fit is not None:
        if fit.theta_ci is not None and fit.beta_ci is not None:
            from scipy.special import ndtr

            with np.errstate(divide="ignore"):
                lnx = np.log(x)
                curves = [fit.p_max * ndtr((lnx - math.log(t)) / b)
                          for t in fit.theta_ci for b in fit.beta_ci]
            ax.fill_between(x, np.min(curves, axis=0), np.max(curves, axis=0), color="#9bb7d4",
                            alpha=0.5, lw=0, label=f"{fit.confidence:.0%} bootstrap band")
        elif fit.ci_note:  # asked for but not estimated: no zero-width band
            import textwrap

            ax.plot([], [], " ", label=textwrap.fill(f"bootstrap band n/a: {fit.ci_note}", 55))
        plateau = (f", plateau $p_{{max}}$ = {fit.p_max:.3f}" if fit.p_max < 1.0 else "")
        ax.plot(x, fit.probability(x), color="#1f4e9c", lw=1.6,
                label=f"{fit.method} fit: $\\theta$ = {fit.theta:.3g} {unit}, "
                      f"$\\beta$ = {fit.beta:.2f}{plateau} ($n$ = "
                      + (_plural(fit.n_records, 'analysis', 'analyses') if fit.method == "mle"
                         else _plural(fit.n_records, 'curve')) + ")")
        if fit.p_max < 1.0:  # the data level off: say where, rather than run to P = 1
            ax.axhline(fit.p_max, color="#1f4e9c", ls=":", lw=1.0,
                       label=f"upper asymptote: P $\\leq$ {fit.p_max:.3f} over the range tried")
    if stripes is not None:
        ax.plot(stripes.levels, stripes.collapses / stripes.trials, "o", color="#c0392b",
                label=f"stripes: collapsed fraction of {_plural(int(stripes.trials[0]), 'analysis', 'analyses')}")
    if ida is not None:
        _ida_steps(ax, ida, unit)
    ax.set_xlabel(im_label)
    ax.set_ylabel("$P(\\mathrm{collapse} \\mid \\mathrm{IM})$")
    ax.set_xlim(0, x_hi)
    ax.set_ylim(-0.02, 1.02)
    ax.grid(True, alpha=0.3)
    nothing = ida is not None and not np.isfinite(ida.first_ims).any()
    ax.legend(fontsize=7.5, frameon=False, loc="upper left" if nothing else "lower right")
    src = stripes if stripes is not None else None
    if src is not None:
        n_rec, n_arch, failed = len(src.records), len(src.arches), len(src.failed)
    elif ida is not None:
        n_rec = len({c.record for c in ida.curves})
        n_arch, failed = len({c.arch for c in ida.curves}), len(ida.failed)
    else:
        n_rec = n_arch = failed = None
    if n_rec is not None:
        ax.set_title(f"{n_rec} record{'s' if n_rec != 1 else ''} $\\times$ {n_arch} "
                     f"arch{'es' if n_arch != 1 else ''}"
                     + (f" ({failed} more arch{'es' if failed != 1 else ''} left out: not counted)"
                        if failed else ""), fontsize=9)
    if fig is not None and path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig if fig is not None else ax.figure


def _ida_steps(ax, ida, unit: str) -> None:
    """The IDA's first collapses as an empirical CDF over all its curves (those that never
    collapse keep it below 1: the plateau), run on to the top of the range tried; where no
    curve collapses, the observations at P = 0 and the sentence that says so."""
    f = np.sort(ida.first_ims)
    n = f.size
    fin = np.isfinite(f)
    top = max(c.max_im for c in ida.curves)
    never = n - int(fin.sum())
    if not fin.any():
        ax.plot([0.0, top], [0.0, 0.0], color="#444444", lw=1.0,
                label=f"IDA: no collapse up to {top:.3g} {unit} "
                      f"({_plural(n, 'curve')}, none collapsed)")
        up = ida.range_tried()["p_upper_95"]
        ax.plot([0.0, top], [up, up], color="#444444", ls="--", lw=1.0,
                label=f"P(collapse) $\\leq$ {up:.3f} up to {top:.3g} {unit} (one-sided 95%)")
        return
    # from P = 0 at the first collapse, so that one curve still draws its jump; on to the top
    xs = np.r_[f[fin][:1], f[fin], max(top, float(f[fin][-1]))]
    ys = np.r_[0.0, (np.arange(n)[fin] + 1) / n]
    ax.step(xs, np.r_[ys, ys[-1]], where="post", color="#444444", lw=1.0,
            label=f"IDA first collapses, empirical ($n$ = {_plural(n, 'curve')}, "
                  f"{never} never up to {top:.3g} {unit})")


# ---------------------------------------------------------------------------- ensembles
def plot_multiplier_histograms(df, path: str | os.PathLike, dpi: int = 150,
                               reference: dict | None = None) -> Path:
    """Histograms of k_l and k_r over the standing arches of an ensemble (a DataFrame with
    columns k_l, k_r and, if present, error, as from :func:`archrock.studies.ensemble.run_ensemble`);
    the samples not shown are counted by reason under the panels.  Optional ``reference``
    {label: (k_l, k_r)} marks e.g. the nominal arch and the paper's RA-1 / RA-2.  Writes
    ``path`` and returns it."""
    from matplotlib.ticker import MaxNLocator

    from ..dynamics.population import LEFT_OUT, left_out_outcome

    try:
        kl_all = np.asarray(df["k_l"], float)
        kr_all = np.asarray(df["k_r"], float)
    except (KeyError, TypeError, ValueError):
        raise ArchInputError("df: expected a table with numeric columns 'k_l' and 'k_r'") from None
    # the summary's rule: k statistics over standing arches (finite k_l, k_r > 0) only
    with np.errstate(invalid="ignore"):
        shown = np.isfinite(kl_all) & np.isfinite(kr_all) & (kl_all > 0) & (kr_all > 0)
    kl, kr = kl_all[shown], kr_all[shown]
    if kl.size == 0:
        raise ArchInputError("df: no standing arch (finite k_l, k_r > 0) to plot")
    errors = np.asarray(df["error"], dtype=object) if "error" in df else np.full(len(kl_all), "")
    hidden = dict.fromkeys(LEFT_OUT, 0)
    for e, ok, kl_i, kr_i in zip(errors, shown, kl_all, kr_all):
        if not ok:  # a k <= 0 without a recorded reason cannot stand all the same
            hidden["cannot_stand" if not e and np.isfinite(kl_i) and np.isfinite(kr_i)
                   else left_out_outcome(str(e))] += 1
    fig, axes = new_figure(1, 2, figsize=(10.0, 4.3), sharey=True)
    lo = float(min(kl.min(), kr.min()))
    hi = float(max(kl.max(), kr.max()))
    if hi - lo < 1e-9:
        lo, hi = lo - 0.01, hi + 0.01
    bins = np.linspace(lo, hi, 41)
    colors = ("#1f4e9c", "#c0392b", "#2e8b57", "#8e44ad")
    for ax, values, name in ((axes[0, 0], kl, "l"), (axes[0, 1], kr, "r")):
        ax.hist(values, bins=bins, color="#9bb7d4", edgecolor="#4a6d94", lw=0.4,
                label=f"standing arches (n = {values.size})")
        ax.set_xlabel(f"$k_{name}$ [g]")
        std = f"{values.std(ddof=1):.4f}" if values.size > 1 else "n/a (one sample)"
        ax.set_title(f"$k_{name}$: mean {values.mean():.4f}, std {std} (n = {values.size})",
                     fontsize=9)
        for (label, ks), c in zip((reference or {}).items(), colors):
            ax.axvline(ks[0] if name == "l" else ks[1], color=c, lw=1.2, ls="--", label=label)
        ax.grid(True, alpha=0.3)
        ax.yaxis.set_major_locator(MaxNLocator(integer=True))  # counts of samples
    axes[0, 0].set_ylabel("samples")
    # one legend for both panels, below them: inside, it overprinted the reference lines
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=min(len(labels), 5),
               fontsize=8, frameon=False)
    n_hidden = int((~shown).sum())
    why = ", ".join(f"{LEFT_OUT[k].split(' (')[0]} {v}" for k, v in hidden.items() if v)
    fig.suptitle(f"{shown.sum()} of {len(kl_all)} samples shown"
                 + (f"; not shown: {n_hidden} ({why})" if n_hidden else ""), fontsize=9)
    return save_figure(fig, path, dpi=dpi)


# ---------------------------------------------------------------------------- defect maps
#: The defect map's colours: a diverging map centred on 0, losses red, gains blue.
DEFECT_CMAP = "RdBu_r"


def defect_norm(values):
    """The colour scale of a defect map: symmetric about 0 (white) over +-max|value|, so that
    a small gain is pale and a large loss dark, whatever their signs (a 0.3% gain once took the
    darkest blue of a scale whose blue half ran only to -0.3%)."""
    from matplotlib.colors import Normalize

    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    top = float(np.abs(v).max()) if v.size else 0.0
    top = top if top > 0 else 1.0  # all unchanged: white over an arbitrary +-1
    return Normalize(vmin=-top, vmax=top)


def _short_place(place: str) -> str:
    """A block's or joint's name for a label on the drawing: "voussoir 3" -> "3", "left pier
    course 2" -> "L pier 2", "arch joint 4" -> "4", "right pier foot" -> "R foot"."""
    for word in ("voussoir ", "arch joint ", "joint "):
        if place.startswith(word):
            return place[len(word):]
    out = place.replace("left ", "L ").replace("right ", "R ").replace(" course ", " ")
    return out.replace("springing (pier top)", "springing").replace("bed joint ", "bed ")


def _defect_panel(ax, dmap, values, label, fmt):
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.patches import Polygon

    arch = dmap.arch
    values = np.asarray(values, float).copy()
    finite = np.isfinite(values)
    if finite.any():  # round-off (an unchanged multiplier recomputed) is no gain nor loss
        values[finite & (np.abs(values) <= 1e-9 * max(np.abs(values[finite]).max(), 1e-300))] = 0.0
    cmap, norm = colormaps[DEFECT_CMAP], defect_norm(values)
    draw_arch(ax, arch, facecolor="#f4f4f4")
    size = arch.size
    for m, i in enumerate(dmap.indices):
        v = values[m]
        colour = cmap(norm(v)) if np.isfinite(v) else "#bbbbbb"
        text = fmt.format(v) if np.isfinite(v) else "n/a"
        name = _short_place(dmap.places[m])
        if dmap.target == "voussoir":
            pier = dmap.groups[m] == "piers"
            ax.add_patch(Polygon(voussoir_outline(arch, int(i)), closed=True, facecolor=colour,
                                 edgecolor=STYLE["voussoir_edge"], linewidth=0.8, zorder=1.5,
                                 hatch="//" if pier else None))
            x, y = arch.area_centroids[int(i)]
            dark = np.isfinite(v) and abs(norm(v) - 0.5) > 0.3
            ax.text(x, y, f"{name}\n{text}", ha="center", va="center", fontsize=7.5, zorder=3,
                    color="white" if dark else "black")
        else:
            (x0, y0), (x1, y1) = arch.joint_points[int(i)]
            ax.plot([x0, x1], [y0, y1], color=colour, lw=6, solid_capstyle="butt", zorder=2)
            u = np.array([x1 - x0, y1 - y0])
            u /= np.hypot(*u)
            at = (x1 + 0.12 * size * u[0], y1 + 0.12 * size * u[1])
            ax.text(*at, f"{name}\n{text}", ha="center", va="center", fontsize=7.5, zorder=3)
            ax.update_datalim([at, (at[0], at[1] + 0.06 * size)])  # room for the label
    sm = ScalarMappable(norm=norm, cmap=cmap)
    bar = ax.figure.colorbar(sm, ax=ax, shrink=0.7)
    bar.set_label(label, fontsize=8)
    ax.set_axis_off()
    ax.autoscale_view()


def _worst_text(dmap, ties) -> str:
    from ..studies.defectmap import names_text

    m = int(np.flatnonzero(dmap.indices == ties[0])[0])
    return (f"{names_text([dmap.place(t) for t in ties])}, -{dmap.loss[m]:.4f} g "
            f"({dmap.relative_loss[m]:.1%})")


def plot_defect_map(dmap, path: str | os.PathLike | None = None, *, dpi: int = 150,
                    relative: bool = True):
    """The arch with each voussoir (or joint) coloured by the drop of min(k_l, k_r) when it
    alone carries the map's defect (as a % of the undamaged k with ``relative``, else in g) on
    a diverging scale centred on 0 (:func:`defect_norm`: losses red, gains blue, symmetric);
    with a pulse, a second panel with the drop of the first collapse amplitude.  Each one is
    labelled with its name (voussoirs by their number from the arch's left springing, pier
    courses hatched and named "L pier 1") and the value; on piers the title gives the worst
    voussoir and the worst pier defect apart.  Writes ``path`` when given; returns the figure."""
    _require_matplotlib()
    panels = [("k", dmap.relative_loss if relative else dmap.loss)]
    amp = dmap.amplitude_loss
    if amp is not None and dmap.amplitude0 and np.isfinite(dmap.amplitude0):
        panels.append(("amp", amp / dmap.amplitude0 if relative else amp))
    fig, axes = new_figure(len(panels), 1, figsize=(6.4, 3.9 * len(panels)))
    for ax, (what, vals) in zip(axes[:, 0], panels):
        vals = np.asarray(vals, float) * (100.0 if relative else 1.0)
        if what == "k":
            lab = "capacity lost"
            head = f"{dmap.arch.name}:\n{dmap.to_dict()['description']}\n"
            base = f"undamaged min($k_l$, $k_r$) = {dmap.k0:.4f} g"
            if dmap.on_piers and dmap.worst_in("arch") and dmap.worst_pier_all:
                kind = "voussoir" if dmap.target == "voussoir" else "arch joint"
                title = (head + f"{base}; worst {kind}: {_worst_text(dmap, dmap.worst_all)}\n"
                         f"worst pier defect: {_worst_text(dmap, dmap.worst_pier_all)}")
            else:
                title = head + f"{base}; worst: {_worst_text(dmap, dmap.worst_all)}"
        else:
            p = dmap.pulse
            lab = "first collapse amplitude lost"
            sgn = "both signs (the smaller)" if p["sign"] == 0 else f"sign {p['sign']:+d}"
            title = (f"{p['kind']} pulse, $t_p$ = {p['duration']:g} s, {sgn}: "
                     f"undamaged first collapse at {dmap.amplitude0:.3f} g")
        if relative:
            lab += " [% of undamaged k]" if what == "k" else " [% of undamaged]"
        else:
            lab += " [g]"
        lab += "\nred: lost, blue: gained"
        _defect_panel(ax, dmap, vals, lab, "{:.1f}%" if relative else "{:.3f}")
        ax.set_title(title, fontsize=8.5)
    if path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig
