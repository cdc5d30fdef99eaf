"""archrock assess: the report's sections, its JSON, self-containment (no network), embedded
figures, optional sections, the command line."""

import base64
import json
import re
import sys

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from archrock.assessment import (SECTIONS, AssessConfig, Paragraph, Section, assess,
                                 section_geometry)
from archrock.cli import main
from archrock.codecheck import CodeCheckConfig, SiteSpectrum
from archrock.geometry import oppenheim_arch
from archrock.reports.html import render_html, write_report

FAST = AssessConfig(durations=(0.3, 0.7), n_scan=12, samples=2, t_end=3.0,
                    codecheck=CodeCheckConfig(spectrum=SiteSpectrum.ntc(0.25, 2.4, 0.3, "B")))
TITLES = ["Geometry", "Limit analysis (both directions)", "Friction the thrust needs",
          "Impact coefficients by model", "Response to the paper's pulse",
          "Collapse-acceleration curve and its band over irregular arches",
          "Defect map: which voussoir, if damaged, costs the most capacity",
          "Contact-engine check", "Code check: kinematic analysis (NTC 2018 / Circolare 2019)",
          "Assumptions, conventions and references"]
KEYS = ["geometry", "limit", "friction", "impact", "response", "curves", "defects", "contact",
        "codecheck", "assumptions"]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    lines = []
    res = assess(oppenheim_arch(), FAST, progress=lines.append)
    out = tmp_path_factory.mktemp("assess")
    html_path, json_path = write_report(res, out / "opp.html")
    return res, html_path.read_text(encoding="utf-8"), json.loads(json_path.read_text()), lines


def test_sections_titles_and_json(report):
    res, text, data, lines = report
    assert [s.key for s in res.sections] == KEYS  # no records: no fragility section
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
    assert round(s["limit"]["data"]["k_l"], 6) == 0.370010
    assert round(s["limit"]["data"]["k_r"], 6) == 0.370010
    assert round(s["impact"]["data"]["paper"]["l_to_r"], 5) == 0.87538
    assert round(s["impact"]["data"]["momentum"]["l_to_r"], 5) == 0.64496
    resp = s["response"]["data"]
    assert [round(t, 4) for t in resp["impacts"][:3]] == [0.6012, 2.2294, 3.3706]
    assert round(resp["peak"], 4) == 0.0372 and resp["collapsed"] is False
    cc = s["codecheck"]["data"]
    assert round(cc["directions"]["l"]["alpha_0"], 6) == 0.370010 and cc["passed"] is True
    assert len(s["curves"]["data"]["band"]["samples"]) == 2
    # docs/defects.md: voussoirs 2 and 4 cost most, -29.3%
    assert s["defects"]["data"]["available"] is True
    assert "voussoirs 2 and 4" in text and "-29.3%" in text
    ct = s["contact"]["data"]  # docs/verification.md: the engine's ramp 0.3667, hinges 0 3 5 7
    assert ct["available"] is True and ct["hinges_l"] == [0, 3, 5, 7]
    assert abs(ct["k_l"] / 0.370010 - 1) < 0.05 and abs(ct["k_r"] / 0.370010 - 1) < 0.05
    fr = s["friction"]["data"]  # docs/friction.md: Oppenheim's arch needs 0.4951
    assert fr["available"] is True
    assert round(fr["friction_needed_l"], 4) == round(fr["friction_needed_r"], 4) == 0.4951
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
    for key in ("friction", "defects", "contact"):
        monkeypatch.setitem(sys.modules, f"archrock.{ {'defects': 'defectmap'}.get(key, key)}", None)
    from archrock.assessment import section_contact, section_defects, section_friction

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
    from archrock.assessment import section_limit, section_response
    from archrock.errors import ArchInputError
    from archrock.geometry import family_arch

    arch = family_arch("pointed", 10, 7, 0.8, 12)
    res = assess(arch, AssessConfig(durations=(0.5,), samples=0),
                 sections=[section_limit, section_response])
    resp = res.section("response")
    assert resp.title == "Response to the paper's pulse"
    assert resp.data["error_type"] == "EnergyGainError"
    assert resp.blocks[0].text.startswith("Not computed: ") and "momentum" in resp.blocks[0].text
    assert res.section("limit").data["k_l"] == pytest.approx(0.170820, abs=1e-6)
    with pytest.raises(ArchInputError, match="nope"):
        assess(arch, AssessConfig(records=("nope.AT2",)), sections=[section_limit])
