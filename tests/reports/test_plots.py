"""Figures: the drawn line of thrust stays in the masonry and ends at the springing crossings,
the animation's ground is at the springings, legends do not hide what they label."""

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from archrock.geometry import family_arch, nominal_arch, oppenheim_arch  # noqa: E402
from archrock.statics.limit import limit_analysis  # noqa: E402
from archrock.reports.plots import clip_thrust_polyline, new_figure, plot_limit, springing_level


def _below_springings(arch, poly):
    """How far the polyline goes below the lowest springing corner [m] (0: not at all)."""
    return max(0.0, springing_level(arch) - float(np.min(poly[:, 1])))


@pytest.mark.parametrize("arch", [family_arch("pointed", 10, 7, 1, 12),
                                  nominal_arch(voussoirs=120)])
def test_thrust_line_stops_at_the_springing_crossings(arch):
    """The funicular polygon runs below the springings (into the abutment); the drawn line
    starts and ends at the crossings of joints 0 and n and goes no lower."""
    lim = limit_analysis(arch)
    for t in (lim.thrust_l, lim.thrust_r):
        raw = np.asarray(t.polyline)
        assert _below_springings(arch, raw) > 0.05 * arch.size  # the defect being fixed
        drawn = clip_thrust_polyline(raw, arch, t.points)
        np.testing.assert_allclose(drawn[0], t.points[0], atol=1e-12)
        np.testing.assert_allclose(drawn[-1], t.points[-1], atol=1e-12)
        assert _below_springings(arch, drawn) < 1e-9 * arch.size
        # every crossing is still on the drawn line, in order
        idx = [int(np.argmin(np.hypot(*(drawn - p).T))) for p in t.points]
        assert idx == sorted(idx) and all(np.hypot(*(drawn[i] - p)) < 1e-12
                                          for i, p in zip(idx, t.points))


def test_thrust_line_unchanged_where_it_stays_inside():
    """Oppenheim's arch: no vertex outside its voussoir, the polyline is drawn as it is."""
    a = oppenheim_arch()
    t = limit_analysis(a).thrust_l
    np.testing.assert_array_equal(clip_thrust_polyline(t.polyline, a, t.points), t.polyline)


def test_plot_limit_draws_the_clipped_line():
    a = family_arch("pointed", 10, 7, 1, 12)
    fig, axes = new_figure(1, 1)
    ax = plot_limit(limit_analysis(a), "l", ax=axes[0][0])
    line = [ln for ln in ax.get_lines() if ln.get_label() == "line of thrust at collapse"][0]
    assert min(line.get_ydata()) >= springing_level(a) - 1e-9


def test_springing_level_is_the_lowest_springing_corner():
    a = oppenheim_arch()  # intrados corner at (R - t/2) sin(11.25 deg) = 1.8046 m
    assert springing_level(a) == pytest.approx(9.25 * np.sin(np.radians(11.25)), abs=1e-12)


@pytest.mark.filterwarnings("ignore:Animation was deleted")  # captured, never rendered
def test_animation_ground_at_the_springings_and_axes_in_metres(tmp_path, monkeypatch):
    from archrock.reports import animate
    from archrock.groundmotion import oppenheim_pulse
    from archrock.dynamics.response import prepare, respond

    seen = {}

    def capture(anim, path, fps, dpi, progress=None):
        ax = anim._fig.axes[0]
        seen["xlabel"], seen["ylabel"] = ax.get_xlabel(), ax.get_ylabel()
        seen["ground"] = [ln.get_ydata()[0] for ln in ax.get_lines()
                          if len(set(ln.get_ydata())) == 1 and ln.get_xdata()[0] == 0]
        return path

    monkeypatch.setattr(animate, "save_animation", capture)
    a = oppenheim_arch()
    res = respond(prepare(a), oppenheim_pulse(-1, 0.2), t_end=0.5)
    animate.animate_response(res, tmp_path / "a.gif", max_frames=2)
    assert seen["xlabel"] == "x [m]" and seen["ylabel"] == "y [m]"
    assert seen["ground"] == [pytest.approx(springing_level(a), abs=1e-12)]


def test_codecheck_legend_lists_each_visible_curve_once():
    """A symmetric arch: M_r's lines lie on M_l's; listed once as 'M_l = M_r' (4 without a
    spectrum, not 8); an irregular arch keeps both."""
    from archrock.studies.codecheck import CodeCheckConfig, SiteSpectrum, code_check
    from archrock.geometry import random_arch
    from archrock.reports.html import FIGURES

    def labels(res):
        fig = FIGURES["codecheck"](res)
        return [t.get_text() for t in fig.axes[0].get_legend().get_texts()]

    sym = labels(code_check(oppenheim_arch(), config=CodeCheckConfig()))
    assert len(sym) == 4 and all(lab.startswith("$M_l$ = $M_r$") for lab in sym)
    spec = CodeCheckConfig(spectrum=SiteSpectrum.ntc(0.25, 2.4, 0.3, "B"))
    assert len(labels(code_check(oppenheim_arch(), config=spec))) == 5
    irr = labels(code_check(random_arch(seed=3), config=CodeCheckConfig()))
    assert len(irr) == 8 and len(set(irr)) == 8


def test_ensemble_histogram_legend_below_the_panels(tmp_path, monkeypatch):
    pd = pytest.importorskip("pandas")
    from archrock.reports import studyplots

    figs = []
    real = studyplots.save_figure
    monkeypatch.setattr(studyplots, "save_figure",
                        lambda fig, path, dpi=150: (figs.append(fig), real(fig, path, dpi))[1])
    rng = np.random.default_rng(0)
    k = rng.normal(0.37, 0.02, (200, 2))
    studyplots.plot_multiplier_histograms(pd.DataFrame({"k_l": k[:, 0], "k_r": k[:, 1]}),
                                          tmp_path / "h.png",
                                          reference={"nominal": (0.37, 0.37),
                                                     "RA-1": (0.35, 0.38)})
    fig = figs[0]
    assert all(ax.get_legend() is None for ax in fig.axes)  # nothing inside the panels
    leg = fig.legends[0]
    fig.canvas.draw()
    box = leg.get_window_extent()
    assert all(box.y1 <= ax.get_window_extent().y0 for ax in fig.axes)
    assert [t.get_text() for t in leg.get_texts()][1:] == ["nominal", "RA-1"]


def test_dem_figure_legends_outside_the_axes(tmp_path, monkeypatch):
    pytest.importorskip("pymunk")
    from archrock.reports import contactplots, plots
    from archrock.contact import EngineSettings, engine_respond
    from archrock.groundmotion import oppenheim_pulse

    figs = []
    monkeypatch.setattr(plots, "save_figure", lambda fig, path, dpi=150: figs.append(fig) or path)
    a = oppenheim_arch()
    res = engine_respond(a, oppenheim_pulse(-0.5, 0.2), EngineSettings(steps_per_T=100,
                                                                       iterations=10),
                         t_end=0.3, t_free=0.5)
    contactplots.save_engine_figure(res, None, tmp_path / "d.png")
    fig = figs[0]
    fig.canvas.draw()
    for ax in fig.axes[:2]:
        leg, box = ax.get_legend(), ax.get_window_extent()
        assert leg.get_window_extent().x0 >= box.x1  # right of the plotting area
    assert len(fig.axes[1].get_legend().get_texts()) == a.n


def test_fragility_figure_shows_the_plateau_through_the_stripes(levelling_ida):
    """Stripes that level off at ~0.54 (45% of the records never collapse): the figure's fitted
    curve passes through the top stripes and stops at its asymptote, drawn and labelled, and
    the IDA's empirical curve runs to the top of the range (issue 30)."""
    import matplotlib.pyplot as plt

    from archrock.reports.plots import plot_fragility
    from archrock.studies.fragility import fit_stripes_mle
    from archrock.studies.ida import StripeResult

    x, ida = levelling_ida
    n = x.size
    lv = np.geomspace(0.15, 1.0, 8)
    out = (np.isfinite(x) & (x <= lv[:, None]))[:, None, :]
    z = out.reshape(8, -1).sum(axis=1)
    fit = fit_stripes_mle(lv, np.full(8, n), z, plateau="auto")
    st = StripeResult(lv, np.full(8, n), z, out, "pga", fit, None,
                      tuple(f"r{i}" for i in range(n)), (0,))
    fig = plot_fragility(fit, st, None, ida=ida)
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("upper asymptote" in lab for lab in labels)
    assert any(f"plateau $p_{{max}}$ = {fit.p_max:.3f}" in lab for lab in labels)
    line = next(ln for ln in ax.get_lines() if ln.get_label().startswith("mle fit"))
    xs, ys = line.get_data()
    top = z[-1] / n
    assert ys.max() == pytest.approx(fit.p_max, abs=0.01)
    assert np.interp(lv[-1], xs, ys) == pytest.approx(top, abs=0.02)
    ecdf = next(ln for ln in ax.get_lines() if ln.get_label().startswith("IDA first collapses"))
    assert ecdf.get_data()[0][-1] == pytest.approx(1.0) and ecdf.get_data()[1][-1] == pytest.approx(top)
    plt.close(fig)


def test_plot_limit_draws_the_compressed_zones():
    """With f_c the figure draws a band of the zone's depth N / f_c along each compressed
    joint, centred on the thrust, and the hinges at the stress blocks' centres."""
    arch = oppenheim_arch().with_fc(2.0)
    res = limit_analysis(arch)
    fig, axes = new_figure(1, 1)
    ax = plot_limit(res, "l", ax=axes[0][0])
    bands = [ln for ln in ax.get_lines() if ln.get_label().startswith("compressed zone")]
    assert len(bands) == 1
    lengths = []
    for ln in ax.get_lines():
        if ln.get_color() == "#e07b00":
            xy = np.column_stack(ln.get_data())
            lengths.append(float(np.hypot(*(xy[1] - xy[0]))))
    zones = res.zones_l[res.zones_l > 0]
    np.testing.assert_allclose(sorted(lengths), sorted(zones), rtol=1e-9)
    assert "$f_c$ = 2 MPa" in ax.get_title()
    import matplotlib.pyplot as plt

    plt.close(fig)
