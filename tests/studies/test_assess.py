"""archrock assess: the report's sections, its JSON, self-containment (no network), embedded
figures, optional sections, the command line."""

import base64
import json
import re
import sys

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from archrock.studies.assessment import (SECTIONS, AssessConfig, Context, Paragraph, Section,
                                         assess, section_geometry)
from archrock.cli import main
from archrock.errors import ArchInputError
from archrock.studies.codecheck import CodeCheckConfig, SiteSpectrum
from archrock.studies.runner import RunSettings
from archrock.geometry import oppenheim_arch
from archrock.dynamics.impact import ImpactSpec
from archrock.reports.html import render_html, write_report

FAST = AssessConfig(durations=(0.3, 0.7), n_scan=12, samples=2, t_end=3.0,
                    codecheck=CodeCheckConfig(spectrum=SiteSpectrum.ntc(0.25, 2.4, 0.3, "B")))
TITLES = ["Geometry", "Governing answer", "Limit analysis (both directions)", "Friction the thrust needs",
          "Impact coefficients by model", "Response to the paper's pulse",
          "Collapse-acceleration curve and its band over irregular arches",
          "Defect map: which voussoir, if damaged, costs the most capacity",
          "Fragility curves", "Contact-engine check", "Code check: kinematic analysis (NTC 2018 / Circolare 2019)",
          "Time-history verification (NTC 2018 par. 7.3.5, EN 1998-1 par. 4.3.3.4.3)",
          "Assumptions, conventions and references"]
KEYS = ["geometry", "governing", "limit", "friction", "impact", "response", "curves", "defects", "fragility",
        "contact", "codecheck", "timehistory", "assumptions"]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    lines = []
    res = assess(oppenheim_arch(), FAST, settings=RunSettings(progress=lines.append))
    out = tmp_path_factory.mktemp("assess")
    html_path, json_path = write_report(res, out / "opp.html")
    return res, html_path.read_text(encoding="utf-8"), json.loads(json_path.read_text()), lines


def test_how_it_runs_is_settings_alone():
    """0.7: the 0.6 progress= keyword is gone; settings= is refused by field where the
    assessment does not use it (it runs in this process and keeps no folder)."""
    with pytest.raises(TypeError, match="unexpected keyword argument 'progress'"):
        assess(oppenheim_arch(), FAST, progress=print)
    with pytest.raises(ArchInputError, match="^workers: 2; assess runs in this process"):
        assess(oppenheim_arch(), FAST, settings={"workers": 2})


def test_sections_titles_and_json(report):
    res, text, data, lines = report
    assert [s.key for s in res.sections] == KEYS  # no records: fragility says it is skipped
    for t in TITLES:
        assert f"<h2>{t.replace(chr(39), '&#x27;')}</h2>" in text, t
    assert list(data["sections"]) == KEYS
    assert set(data) >= {"arch", "config", "headline", "sections", "seconds", "archrock_version"}
    assert AssessConfig.from_dict(data["config"]) == FAST
    # progress: one line as each section starts and ends
    assert sum(line.startswith("[") for line in lines) == len(SECTIONS)


def test_values_are_the_package_s(report):
    """The report carries the package's published values on Oppenheim's arch."""
    _, text, data, _ = report
    s = data["sections"]
    # tolerances: the published values' last digit (half a unit of it)
    assert s["limit"]["data"]["k_l"] == pytest.approx(0.370010, abs=5e-7)
    assert s["limit"]["data"]["k_r"] == pytest.approx(0.370010, abs=5e-7)
    assert s["impact"]["data"]["paper"]["l_to_r"] == pytest.approx(0.87538, abs=5e-6)
    assert s["impact"]["data"]["momentum"]["l_to_r"] == pytest.approx(0.64496, abs=5e-6)
    resp = s["response"]["data"]
    assert resp["impacts"][:3] == pytest.approx([0.6012, 2.2294, 3.3706], abs=5e-5)
    assert resp["peak"] == pytest.approx(0.0372, abs=5e-5) and resp["collapsed"] is False
    cc = s["codecheck"]["data"]
    assert cc["directions"]["l"]["alpha_0"] == pytest.approx(0.370010, abs=5e-7)
    assert cc["passed"] is True
    assert len(s["curves"]["data"]["band"]["samples"]) == 2
    # docs/defects.md: voussoirs 2 and 4 cost most, -29.3%
    assert s["defects"]["data"]["available"] is True
    assert "voussoirs 2 and 4" in text and "-29.3%" in text
    ct = s["contact"]["data"]  # docs/verification.md: the engine's ramp 0.3667, hinges 0 3 5 7
    assert ct["available"] is True and ct["hinges_l"] == [0, 3, 5, 7]
    assert abs(ct["k_l"] / 0.370010 - 1) < 0.05 and abs(ct["k_r"] / 0.370010 - 1) < 0.05
    fr = s["friction"]["data"]  # docs/friction.md: Oppenheim's arch needs 0.4951
    assert fr["available"] is True
    assert fr["friction_needed_l"] == pytest.approx(0.4951, abs=5e-5)
    assert fr["friction_needed_r"] == pytest.approx(0.4951, abs=5e-5)
    assert "0.370010" in text and "0.87538" in text


def test_self_contained(report):
    """No network: every image is an embedded PNG, no src/href points outside, no scripts,
    no stylesheet links; references are text."""
    _, text, _, _ = report
    srcs = re.findall(r'<img[^>]*\ssrc="([^"]*)"', text)
    # arch, Fig. 3, response, curve, defect map, capacity curve
    assert len(srcs) == text.count("<img") == 6
    for s in srcs:
        assert s.startswith("data:image/png;base64,")
        png = base64.b64decode(s.split(",", 1)[1])
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000
    assert not re.search(r'(src|href)\s*=\s*"(?!data:|#)', text)
    assert "http://" not in text and "https://" not in text
    assert "<script" not in text and "<link" not in text
    assert "Heyman" in text and "Circolare" in text


def test_optional_sections_say_when_absent(report, monkeypatch):
    res, text, _, _ = report
    for name in ("statics.friction", "studies.defectmap", "contact"):
        monkeypatch.setitem(sys.modules, f"archrock.{name}", None)
    from archrock.studies.assessment import section_contact, section_defects, section_friction

    ctx_res = assess(oppenheim_arch(), FAST,
                     sections=[section_friction, section_defects, section_contact])
    for s in ctx_res.sections:
        assert s.data["available"] is False
        assert "not available in this installation" in s.blocks[0].text


def test_a_section_is_one_function(tmp_path):
    """The lead adds a section by writing one function: its title, text and data reach the
    HTML and the JSON; None leaves it out; text is escaped."""
    def section_extra(ctx):
        return Section("extra", "Extra <check>", (Paragraph(f"n = {ctx.arch.n} & more"),),
                       {"n": ctx.arch.n}, (("extra n", str(ctx.arch.n)),))

    res = assess(oppenheim_arch(), FAST, sections=[section_geometry, section_extra,
                                                   lambda ctx: None])
    text = render_html(res)
    assert "<h2>Extra &lt;check&gt;</h2>" in text and "n = 7 &amp; more" in text
    assert res.to_dict()["sections"]["extra"]["data"] == {"n": 7}
    assert [s.key for s in res.sections] == ["geometry", "extra"]


@pytest.mark.slow
def test_fragility_section_with_a_record(tmp_path):
    t = np.arange(0, 4, 0.01)
    rec = tmp_path / "rec.txt"
    rec.write_text("\n".join(f"{a:.3f} {0.5 * np.sin(2 * np.pi * 2 * a) * np.exp(-a):.6f}"
                             for a in t))
    cfg = AssessConfig(durations=(0.5,), n_scan=8, samples=0, records=(str(rec),),
                       scales=(0.5, 1, 2, 4, 8))
    res = assess(oppenheim_arch(), cfg)
    assert "fragility" in [s.key for s in res.sections]
    assert res.section("fragility").data["ida"]["n_records"] == 1


def test_cli_assess(tmp_path, capsys, monkeypatch):
    out = tmp_path / "r.html"
    code = main(["assess", "--out", str(out), "--samples", "0", "--durations", "0.5",
                 "--n-scan", "8", "--no-progress"])
    assert code == 0, capsys.readouterr().err
    assert out.exists() and out.with_suffix(".json").exists()
    d = json.loads(out.with_suffix(".json").read_text())
    assert d["config"]["samples"] == 0 and "band" not in d["sections"]["curves"]["data"]
    assert main(["assess", "--out", str(tmp_path / "r.txt")]) == 2
    assert "--out" in capsys.readouterr().err
    assert main(["assess", "--out", str(out), "--records", str(tmp_path / "nope")]) == 2
    import archrock.reports.html as h

    monkeypatch.setattr(h, "find_chromium", lambda: None)
    assert main(["assess", "--out", str(out), "--samples", "0", "--durations", "0.5",
                 "--n-scan", "8", "--no-progress", "--pdf"]) == 3
    assert "apt-get install chromium" in capsys.readouterr().err


def test_an_outcome_is_said_in_its_section_not_fatal():
    """An impact law that cannot apply (the paper's equations create energy on this pointed
    arch) leaves the dynamic sections 'Not computed: ...' and the rest of the report intact; a
    bad input (a missing record) stops before any work."""
    from archrock.studies.assessment import section_limit, section_response
    from archrock.errors import ArchInputError
    from archrock.geometry import family_arch

    arch = family_arch("pointed", 10, 7, 0.8, 12)
    paper = ImpactSpec.parse("paper")  # the paper's law on this arch, no fallback
    res = assess(arch, AssessConfig(impact=paper, durations=(0.5,), samples=0),
                 sections=[section_limit, section_response])
    resp = res.section("response")
    assert resp.title == "Response to the paper's pulse"
    assert resp.data["error_type"] == "EnergyGainError"
    assert resp.blocks[0].text.startswith("Not computed: ") and "momentum" in resp.blocks[0].text
    assert res.section("limit").data["k_l"] == pytest.approx(0.170820, abs=1e-6)
    with pytest.raises(ArchInputError, match="nope"):
        assess(arch, AssessConfig(records=("nope.AT2",)), sections=[section_limit])


def test_geometry_echoes_the_dimensions_and_the_crown_height(report):
    """The height is the extrados crown's (R + t/2 - (R - t/2) sin(11.25 deg) = 8.945 m on
    Oppenheim's arch), not the crown joints' corners (8.739 m); R, t, t/R and the embrace are
    echoed."""
    _, text, data, _ = report
    g = data["sections"]["geometry"]["data"]
    exact = 10.75 - 9.25 * np.sin(np.radians(11.25))
    assert exact == pytest.approx(8.945, abs=5e-4)  # the 8.945 m, to its 3 decimals
    assert g["height"] == pytest.approx(exact, abs=1e-9)
    assert g["dimensions"]["radius"] == pytest.approx(10.0, abs=1e-12)
    assert g["dimensions"]["thickness"] == pytest.approx(1.5, abs=1e-12)
    assert g["dimensions"]["t_over_R"] == pytest.approx(0.15, abs=1e-12)
    assert g["dimensions"]["embrace_deg"] == pytest.approx(157.5, abs=1e-9)
    assert "height 8.945 m" in text and "t/R = 0.1500" in text and "embrace 157.5 deg" in text


def test_family_arch_echoes_span_and_rise():
    from archrock.geometry import family_arch

    arch = family_arch("pointed", 10, 7, 0.8, 12)
    sec = section_geometry(Context(arch, FAST))
    d = sec.data["dimensions"]
    assert d["shape"] == "pointed" and d["rise_over_span"] == pytest.approx(0.7, abs=1e-12)
    assert "F/S = 0.7000" in sec.blocks[0].text
    # the outline's top is the extrados at the pointed crown, above the centreline's rise
    assert sec.data["height"] > 7.0 + 0.3


def test_verdict_and_governing_at_the_default_friction(report):
    """With a spectrum: a verdict that states the governing capacity; at the default friction
    0.8 >= 0.4951 the no-sliding k = 0.370010 governs, first in the summary, with the dynamics
    (the four-link model) and the engine at the same friction beside it."""
    res, text, data, _ = report
    assert data["verdict"]["status"] == "pass"
    assert "Verdict:" in text and "passes the kinematic check" in text
    assert "Governing capacity: k = 0.370010 g (limit analysis (no sliding), both directions)" \
        in data["verdict"]["text"]
    head = res.headline
    assert head[0][0] == "governing capacity [g]"
    assert head[0][1].startswith("0.370010 (limit analysis (no sliding), both directions, ")
    assert "mu = 0.8" in head[0][1]
    assert head[1][0] == "dynamics" and head[1][1].startswith("the four-link model")
    assert dict(head)["k_l [g]"] == "0.370010"  # the friction is enough: no note beside k
    gov = data["governing"]
    assert gov["friction"] == pytest.approx(0.8, abs=1e-15)
    assert gov["governing"]["value"] == pytest.approx(0.370010, abs=5e-7)
    assert gov["dynamics"]["used"] == "fourlink"
    names = [a["name"] for a in gov["analyses"]]
    assert names == ["limit analysis (no sliding)", "limit analysis with friction mu = 0.8",
                     "contact engine ramp at mu = 0.8"]
    assert data["sections"]["contact"]["data"]["friction"] == pytest.approx(0.8, abs=1e-15)
    assert "Not modelled: sliding" not in text
    assert "associative Coulomb friction at mu = 0.8" in text


@pytest.fixture
def no_engine_ramp(monkeypatch):
    """The governing decision without its engine ramp (minutes): the decision logic is
    tests/studies/test_governing.py's; here only what the report makes of it."""
    import archrock.studies.governing as gv

    orig = gv.governing_capacity
    monkeypatch.setattr(gv, "governing_capacity",
                        lambda *a, **kw: orig(*a, **{**kw, "engine": False}))


def test_low_friction_sliding_governs_and_the_engine_runs(no_engine_ramp):
    """--friction 0.4 (EN 1996-1-1's coefficient): k = 0.370 needs 0.4951 > 0.4, so the friction
    analysis's 0.2638 governs; the summary says so beside k; the dynamics go to the engine."""
    from archrock.studies.assessment import section_governing, section_limit

    res = assess(oppenheim_arch(), AssessConfig(samples=0, friction=0.4),
                 sections=[section_limit, section_governing])
    head = dict(res.headline)
    assert res.headline[0][0] == "governing capacity [g]"
    assert head["governing capacity [g]"].startswith("0.263759 (limit analysis with friction "
                                                     "mu = 0.4, both directions")
    assert "needs friction mu >= 0.495" in head["k_l [g]"] and "0.2638" in head["k_l [g]"]
    assert res.governing["dynamics"]["used"] == "engine"
    assert "slide" in res.governing["dynamics"]["reason"]


def test_friction_none_is_stated_and_round_trips(no_engine_ramp):
    from archrock.errors import ArchInputError
    from archrock.studies.assessment import section_friction, section_governing

    cfg = AssessConfig(samples=0, friction=None)
    assert AssessConfig.from_dict(cfg.to_dict()) == cfg
    res = assess(oppenheim_arch(), cfg, sections=[section_friction, section_governing])
    fr = res.section("friction")
    assert "Sliding is excluded by the user (--friction none" in fr.blocks[0].text
    assert res.governing["friction"] is None
    assert any(x["name"] == "limit analysis with friction" for x in res.governing["left_out"])
    for bad in (0.0, -1, float("nan"), True, "a"):
        with pytest.raises(ArchInputError, match="friction"):
            AssessConfig(friction=bad)


def test_no_spectrum_no_verdict_and_why():
    from archrock.studies.assessment import section_codecheck, section_fragility

    res = assess(oppenheim_arch(), AssessConfig(samples=0),
                 sections=[section_codecheck, section_fragility])
    v = res.verdict
    assert v["status"] == "none" and "no site spectrum" in v["text"]
    frag = res.section("fragility")
    assert frag.data["skipped"] is True
    assert frag.blocks[0].text.startswith("Skipped: no accelerograms") and "--records" in \
        frag.blocks[0].text
    assert "Verdict:" in render_html(res)


def test_no_finite_friction_is_said_in_words():
    """friction_needed may answer None for a direction (no finite friction suffices)."""
    from archrock.studies.assessment import friction_note

    fr = {"needed": {"l": None, "r": 0.3}, "mu": 0.4, "with_mu": {"l": 0.21, "r": 0.5},
          "with_mu_error": None, "sliding_governs": {"l": True, "r": False}}
    assert "no finite" not in friction_note(fr, "r") and friction_note(fr, "r") == ""
    note = friction_note(fr, "l")
    assert "no finite friction" in note and "k_l = 0.2100" in note


def test_a_failing_section_never_loses_the_report():
    """Any error in one section (here a plain bug) leaves it 'Not computed' and the rest goes on."""
    def section_broken(ctx):
        raise ZeroDivisionError("boom")

    res = assess(oppenheim_arch(), FAST, sections=[section_broken, section_geometry])
    assert [s.key for s in res.sections] == ["broken", "geometry"]
    assert res.section("broken").data["error_type"] == "ZeroDivisionError"
    assert "boom" in res.section("broken").blocks[0].text


def test_print_css_is_a4_with_page_numbers(report):
    _, text, _, _ = report
    css = text[text.index("<style>"):text.index("</style>")]
    assert "size:A4" in css and "counter(page)" in css and "@bottom-center" in css
    assert re.search(r"h2[^{]*\{break-after:avoid", css.replace("h1,h2,h3", "h2"))
    # every section heading printed together with its first block (no heading alone at a page
    # bottom: Chromium does not honour break-after on its own)
    assert ".keep{" in css.replace("figure,table,.verdict,.keep{", ".keep{")
    assert text.count("<h2>") - text.count('<div class="keep"><h2>') == 0


def test_heavy_piers_summary_gives_the_engine_outcome(heavy_piers_file, no_engine_ramp):
    """The heavy-pier arch at the report's pulse (-1 g, 0.2 s): the four-link model is not
    valid (a pier rocks with the arch), so the summary gives the contact engine's outcome
    (collapse), the impact section says the engine needs no law, and the words of a four-link
    answer ("survives") appear nowhere."""
    pytest.importorskip("pymunk")
    from archrock.geometry.files import read_arch
    from archrock.studies.assessment import (section_governing, section_impact, section_piers,
                                             section_response)

    res = assess(read_arch(heavy_piers_file), AssessConfig(samples=0),
                 sections=[section_governing, section_piers, section_impact, section_response])
    head = dict(res.headline)
    assert res.governing["dynamics"]["used"] == "engine"
    assert head["paper pulse (contact engine)"].startswith("collapse at t = ")
    assert "paper pulse" not in head
    resp = res.section("response").data
    assert resp["how"] == "contact engine" and resp["collapsed"] is True
    assert resp["dynamics"]["used"] == "engine"
    html = render_html(res, figures={})
    assert "survives" not in html
    assert "four-link model on piers" in head  # the warning stays, beside no four-link answer
    assert "contact engine governs the dynamics" in html
