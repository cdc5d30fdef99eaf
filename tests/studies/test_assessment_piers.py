"""`assess` names the piers (issue 19): the piers section of the report on an arch on piers."""

from __future__ import annotations

import pytest

from archrock.geometry import nominal_arch, with_piers
from archrock.reports.html import render_html
from archrock.statics.buttress import minimum_pier_width
from archrock.studies.assessment import assess, section_piers


def test_assess_names_the_piers():
    """The reference semicircle on piers 4 x 2 m (2 courses): the section gives each pier's
    size, names hinge D of M_l "right pier foot, outer face" (as archrock limit does), the least
    pier width of statics.buttress (1.197882 m, docs/piers.md) and the single-DOF warning; the
    HTML report carries them; an arch on rigid ground has no piers section."""
    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    ap = with_piers(arch, 4.0, 2.0, courses=2)
    a = assess(ap, sections=[section_piers])
    sec = a.section("piers")
    assert sec.data["piers"]["right"]["height"] == pytest.approx(4.0, abs=1e-12)
    assert sec.data["piers"]["left"]["width_top"] == pytest.approx(2.0, abs=1e-12)
    places = {(h["mechanism"], h["hinge"]): h["place"] for h in sec.data["hinges"]}
    assert places[("M_l", "D")] == "right pier foot, outer face"
    assert places[("M_r", "D")] == "left pier foot, outer face"
    mw = sec.data["minimum_pier_width"][0]
    assert mw["height"] == pytest.approx(4.0) and mw["width"] == pytest.approx(1.197882, abs=2e-6)
    assert sec.data["single_dof"]["valid"] is False
    text = " ".join(getattr(b, "text", "") for b in sec.blocks)
    assert "WARNING single degree of freedom not valid" in text
    assert "1.1979 m for piers 4 m high" in text
    html = render_html(a, figures={})
    assert "right pier foot, outer face" in html and "The piers" in html
    assert [s.key for s in assess(arch, sections=[section_piers]).sections] == []


def test_assess_names_the_piers_of_a_file_without_kinds(heavy_piers_file):
    """tests/data/heavy_piers.json names no kinds: the end blocks the single-DOF check takes
    for piers are reported as piers, said to be guessed, with the warning."""
    from archrock.geometry.files import read_arch

    heavy = heavy_piers_file
    sec = assess(read_arch(heavy), sections=[section_piers]).section("piers")
    assert sec.data["piers"]["left"]["width_foot"] == pytest.approx(5.0, abs=1e-9)
    assert sec.data["piers"]["left"]["width_top"] == pytest.approx(5.0, abs=1e-9)
    places = {(h["mechanism"], h["hinge"]): h["place"] for h in sec.data["hinges"]}
    assert places[("M_l", "D")] == "right pier foot, outer face"
    text = " ".join(getattr(b, "text", "") for b in sec.blocks)
    assert "names no block kinds: block(s) 0, 13 are taken for piers" in text
    assert sec.data["single_dof"]["valid"] is False


def test_single_dof_check_counts_buttresses():
    """A stepped or battered buttress is a pier to the single-DOF check (it rocks on its
    foot as a pier does)."""
    from archrock.dynamics.piers import pier_blocks

    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    sb = with_piers(arch, None, None, steps=((2.0, 3.0), (6.0, 2.0)))
    assert pier_blocks(sb) == ((0, 1, 11, 12), "block_kinds")
