"""The code check of an arch on piers (issue 19, part 4): where the mechanism's masses are (the
moving mass, M*, the height Z of their centroid above the foundation) and the checks of a
mechanism above ground (Se(T_1) psi(Z) gamma / q), against hand calculations on the rocking
frame; an arch on the ground keeps its record as before."""

from __future__ import annotations

import math

import pytest

from archrock.errors import ArchInputError
from archrock.geometry import arch_from_dict, nominal_arch, with_piers
from archrock.reports.codecheck import format_codecheck
from archrock.studies.codecheck import AboveGround, CodeCheckConfig, SiteSpectrum, code_check
from archrock.units import G

SPEC = SiteSpectrum.ntc(0.25, 2.4, 0.3, "B")


def _frame(rocking_frame, b=0.3, h=1.2, d=0.3):
    data = rocking_frame(b, h, d).to_dict()
    for v, k in zip(data["voussoirs"], ("pier", "voussoir", "pier")):
        v["kind"] = k
    return arch_from_dict(data)


def test_rocking_frame_mass_and_height_by_hand(rocking_frame):
    """The frame's columns (2b x 2h, mass m_c) rock about their feet and the beam (m_b, depth d)
    translates: every block moves; Z = (2 m_c h + m_b (2h + d/2)) / (2 m_c + m_b); per unit
    rotation the columns' centres move h and the beam 2h, so M* = (sum m dx)^2 / sum m dx^2 =
    2 (m_c + m_b)^2 / (m_c + 2 m_b)."""
    b, h, d = 0.3, 1.2, 0.3
    frame = _frame(rocking_frame, b, h, d)
    mc, mb = frame.masses[0], frame.masses[1]
    r = code_check(frame, config=CodeCheckConfig(spectrum=SPEC))
    for c in r.directions:
        hz = r.heights[c.direction]
        assert hz["moving_blocks"] == [0, 1, 2]
        assert hz["moving_mass"] == pytest.approx(2 * mc + mb, rel=1e-12)
        assert hz["z"] == pytest.approx((2 * mc * h + mb * (2 * h + d / 2)) / (2 * mc + mb),
                                        rel=1e-9)
        assert c.m_star == pytest.approx(2 * (mc + mb) ** 2 / (mc + 2 * mb), rel=1e-9)
        assert c.alpha_0 == pytest.approx(b / h, rel=1e-9)


@pytest.mark.parametrize("storeys,period", [(1, None), (2, 0.4), (3, 1.0)])
def test_checks_above_ground_by_hand(rocking_frame, storeys, period):
    frame = _frame(rocking_frame)
    H = 10.0
    ag = AboveGround(H, storeys, period)
    cfg = CodeCheckConfig(spectrum=SPEC)
    r = code_check(frame, config=cfg, above_ground=ag)
    t1 = period if period is not None else 0.05 * H ** 0.75
    gamma = 3 * storeys / (2 * storeys + 1)
    assert ag.t1 == pytest.approx(t1, rel=1e-15) and ag.gamma == pytest.approx(gamma, rel=1e-15)
    for c in r.directions:
        z = r.heights[c.direction]["z"]
        lin = c.checks["linear_above_ground"]
        demand = float(SPEC.se(t1)) * (z / H) * gamma / 2.0
        assert lin["demand_g"] == pytest.approx(demand, rel=1e-12)
        assert lin["passed"] == (c.a0_star_g >= demand)
        non = c.checks["nonlinear_above_ground"]
        ratio = c.ts / t1
        if ratio < 1.5:
            sde1 = float(SPEC.se(t1)) * G * (t1 / (2 * math.pi)) ** 2
            want = sde1 * (z / H) * gamma * ratio ** 2 / math.sqrt((1 - ratio) ** 2 + 0.02 * ratio)
        else:
            want = c.checks["nonlinear"]["demand_m"]      # S_De(T_s), as at ground level
        assert non["demand_m"] == pytest.approx(want, rel=1e-12)
        # the ground-level checks are those without the structure, unchanged
        assert c.checks["linear"] == code_check(frame, config=cfg).direction(
            c.direction).checks["linear"]
    assert r.passed == all(v["passed"] for c in r.directions for v in c.checks.values())
    assert r.to_dict()["above_ground"]["gamma"] == pytest.approx(gamma)
    text = format_codecheck(r)
    assert "linear, above ground" in text and "Z = " in text


def test_arch_on_piers_reports_where_the_mechanism_is():
    """The reference semicircle on piers 4 x 2 m: M_l moves the arch past hinge A and the far
    pier; Z of their centroid above the pier feet."""
    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    ap = with_piers(arch, 4.0, 2.0)
    r = code_check(ap)
    hz = r.heights["l"]
    assert hz["moving_blocks"] == list(range(2, 11))
    m = ap.masses[2:]
    z = float((m * ap.centroids[2:, 1]).sum() / m.sum()) + 4.0
    assert hz["z"] == pytest.approx(z, rel=1e-12) and hz["z"] == pytest.approx(5.1933, abs=1e-4)
    assert r.to_dict()["mechanism_heights"]["r"]["z"] == pytest.approx(hz["z"], rel=1e-9)
    assert r.direction("l").alpha_0 == pytest.approx(0.168899, abs=1e-6)


def test_arch_on_the_ground_unchanged():
    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    r = code_check(arch, config=CodeCheckConfig(spectrum=SPEC))
    assert r.heights is None and r.above_ground is None
    d = r.to_dict()
    assert "mechanism_heights" not in d and "above_ground" not in d
    assert set(r.direction("l").checks) == {"linear", "nonlinear"}
    assert "above the foundation" not in format_codecheck(r)


def test_bad_structures_by_name(rocking_frame):
    for kw, start in (({"height": 0.0}, "height:"), ({"height": 10.0, "storeys": 0}, "storeys:"),
                      ({"height": 10.0, "storeys": 1.5}, "storeys:"),
                      ({"height": 10.0, "period": 0.0}, "period:"),
                      ({"height": 10.0, "c1": 0.0}, "c1:")):
        with pytest.raises(ArchInputError, match="^" + start):
            AboveGround(**kw)
    frame = _frame(rocking_frame)
    with pytest.raises(ArchInputError, match="^height: 1 m is below the mechanism's centroid"):
        code_check(frame, config=CodeCheckConfig(spectrum=SPEC), above_ground=AboveGround(1.0))
    with pytest.raises(ArchInputError, match="^height: 1 m is below"):
        code_check(frame, above_ground=AboveGround(1.0))
    with pytest.raises(ArchInputError, match="^above_ground:"):
        code_check(frame, above_ground=10.0)


def test_cli_structure_flags(capsys):
    from archrock.cli import main

    base = ("codecheck", "--radius", "5", "--embrace", "180", "--thickness", "0.8", "--voussoirs",
            "9", "--pier-height", "4", "--pier-width", "2", "--ag", "0.25", "--f0", "2.4",
            "--tc-star", "0.3", "--soil", "B")
    code = main([*base, "--structure-height", "12", "--json"])
    d = __import__("json").loads(capsys.readouterr().out)
    assert code == 0 and d["above_ground"]["t1"] == pytest.approx(0.05 * 12 ** 0.75)
    lin = d["directions"]["l"]["checks"]["linear_above_ground"]
    assert lin["demand_g"] == pytest.approx(0.1506, abs=1e-4)
    assert d["mechanism_heights"]["l"]["z"] == pytest.approx(5.1933, abs=1e-4)
    for extra, start in ((("--storeys", "2"), "archrock: error: --structure-height: needed"),
                         (("--structure-height", "1"), "archrock: error: --structure-height: 1 m "
                                                       "is below the mechanism's centroid"),
                         (("--structure-height", "12", "--storeys", "0"),
                          "archrock: error: --storeys:"),
                         (("--structure-height", "12", "--structure-period", "-1"),
                          "archrock: error: --structure-period:")):
        code = main([*base, *extra])
        err = capsys.readouterr().err
        assert code == 2 and err.startswith(start), err
