"""The assess report's dynamic sections say what the studies know: the fragility's bound where no
record collapses the arch and its plateau where the fit levels off, the curve's survival windows
with their refined edges and the resolution they were searched at; a figure that fails to draw
never ends the report."""

import dataclasses
import json

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from archrock.geometry import oppenheim_arch
from archrock.reports import html as report_html
from archrock.reports.html import render_html, write_report
from archrock.studies import ida as ida_module
from archrock.studies.assessment import AssessConfig, assess, section_geometry
from archrock.studies.assessment_dynamics import section_curves, section_fragility
from archrock.studies.fragility import FragilityFit


def _record(path, amplitude_g: float):
    """A decaying 2 Hz sine, 4 s, two columns 'time accel [g]'."""
    t = np.arange(0, 4, 0.01)
    path.write_text("\n".join(f"{a:.3f} {amplitude_g * np.sin(4 * np.pi * a) * np.exp(-a):.6f}"
                              for a in t))
    return str(path)


def _fragility(tmp_path, amplitude_g: float):
    cfg = AssessConfig(durations=(0.5,), n_scan=8, samples=0, bootstrap=0,
                       records=(_record(tmp_path / "rec.txt", amplitude_g),),
                       scales=(0.5, 1, 2, 4, 8))
    return assess(oppenheim_arch(), cfg, sections=[section_fragility])


def test_fragility_with_no_collapse_gives_the_bound_and_no_median(tmp_path):
    """A record too weak to collapse Oppenheim's arch at 8 times its scale (PGA 0.14 g < k =
    0.370): the section states the range tried and the one-sided 95% bound (1 curve: 0.95), fits
    nothing, and its headline claims no median; the figure is still drawn."""
    res = _fragility(tmp_path, 0.02)
    s = res.section("fragility")
    text = s.blocks[0].text
    rng = s.data["ida"]["range_tried"]
    assert rng["n_never"] == 1 and rng["p_upper_95"] == pytest.approx(0.95, abs=1e-9)
    assert f"no collapse up to {rng['max_im']:.4f} g in 1 curve(s)" in text
    assert "P(collapse) <= 0.950" in text and "no fragility curve is fitted" in text
    assert "median" not in text and "theta" not in text
    (label, value), = s.headline
    assert "median" not in label and value.startswith("no collapse up to 0.142 g")
    html = render_html(res)
    assert "figure not drawn" not in html and "data:image/png;base64," in html


def test_fragility_that_levels_off_states_p_max_and_the_note(tmp_path, monkeypatch):
    """Where the stripes' fit levels off (here put in place of the fit of one collapsing
    record), the paragraph gives p_max and the level-off test's note, the P = 0.5 intensity of
    the plateau curve, and the headline says 'levelling off' rather than 'median'."""
    note = "the data level off below P = 1: fitted with an upper asymptote p_max = 0.600 (test)"
    plateau = FragilityFit(theta=0.4, beta=0.3, method="mle", n_records=40, p_max=0.6,
                           level_off={"levels_off": True, "p_max": 0.6, "note": note})
    real = ida_module.msa
    monkeypatch.setattr(ida_module, "msa",
                        lambda *a, **k: dataclasses.replace(real(*a, **k), fit=plateau))
    s = _fragility(tmp_path, 0.5).section("fragility")
    text = s.blocks[0].text
    assert "Fit (stripes): mle theta = 0.4000 g, beta = 0.300, p_max = 0.600 (n = 40)" in text
    assert f"levels off at P = 0.600: {note}" in text
    # theta exp(beta Phi^-1(0.5 / 0.6)) = 0.4 exp(0.3 x 0.96742) = 0.5348 g
    assert "P = 0.5 is reached at 0.535 g" in text
    assert s.headline == (("fragility theta [g]", "0.400, levelling off at P = 0.600"),)


def test_curves_list_windows_with_refined_edges_and_the_resolution():
    """Oppenheim's arch at t_p = 1 s on a 30-point grid: the survival window above the first
    collapse (0.46440-0.46510 g, bisected), listed in the table, and the grid's resolution quoted
    once in the paragraph, as `archrock curves` words it."""
    from archrock.studies.wording import resolution_line

    cfg = AssessConfig(durations=(1.0,), n_scan=30, samples=0)
    s = assess(oppenheim_arch(), cfg, sections=[section_curves]).section("curves")
    text = s.blocks[0].text
    (lo, hi), = s.data["nominal"]["survival_windows_g"][0]
    assert lo == pytest.approx(0.46439, abs=2e-5) and hi == pytest.approx(0.46508, abs=2e-5)
    table = s.blocks[2]
    assert table.header[-1] == "survival windows above it [g]"
    assert table.rows[0][-1] == f"{lo:.5f}-{hi:.5f}"
    # (10 / 0.3700)^(1/29) - 1 = 12%: 0.0445 g at the first collapse, 0.3825 g
    assert text.count("windows narrower than") == 1 and "stepping 12% of |a|" in text
    assert "windows narrower than 0.0445 g" in text
    assert resolution_line(s.blocks[1].payload[0]) in text  # the words of `archrock curves`


def test_a_figure_that_fails_is_a_line_not_the_end_of_the_report(tmp_path, monkeypatch):
    """A drawing function that raises: the HTML says 'figure not drawn: <reason>' in its place,
    progress warns, the JSON lists it, and the other sections and figures are intact."""
    def broken(arch):
        raise RuntimeError("no\nfont")

    monkeypatch.setitem(report_html.FIGURES, "arch", broken)
    res = assess(oppenheim_arch(), AssessConfig(samples=0), sections=[section_geometry])
    said = []
    hp, jp = write_report(res, tmp_path / "r.html", progress=said.append)
    html = hp.read_text(encoding="utf-8")
    assert '<p class="note">figure not drawn: RuntimeError: no font</p>' in html
    assert "Geometry" in html and "</html>" in html
    assert any("warning: figure geometry/arch not drawn (RuntimeError: no font)" in m
               for m in said)
    data = json.loads(jp.read_text())
    assert data["figures_not_drawn"] == [{"section": "geometry", "figure": "arch",
                                          "reason": "RuntimeError: no font"}]
    assert "geometry" in data["sections"]
