"""Code check (archrock.studies.codecheck): closed forms of a rigid block, Oppenheim's arch, mirror
symmetry, units, the work balance of the capacity curve, the spectra and bad input."""

import json
import math

import numpy as np
import pytest

from archrock.cli import main
from archrock.studies.codecheck import (CodeCheckConfig, SiteSpectrum, block_kinematics,
                                        code_check, kinematic_check, mechanism_kinematics,
                                        ntc_spectrum_parameters)
from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch, random_arch
from archrock.dynamics.fourlink import four_link, potential
from archrock.units import G

K_OPPENHEIM = 0.370010


@pytest.fixture(scope="module")
def opp(oppenheim):
    return oppenheim.arch, oppenheim.limit


# ---------------------------------------------------------------------------- rigid block
@pytest.mark.parametrize("b,h,fc", [(1.0, 4.0, 1.0), (0.6, 3.0, 1.35), (2.0, 2.5, 1.2)])
def test_block_overturning_closed_forms(b, h, fc):
    """Simple overturning of a monolith b x h about a base corner: alpha_0 = b/h, M* = m
    (one rigid rotation: (m dx)^2 / (m dx^2)), e* = 1, a_0* = g b / (h FC), d_0 = d_0* = b/2 (the
    mass centre over the pivot), and on the exact curve alpha = tan(beta - theta)."""
    m = 1234.0
    c = kinematic_check(block_kinematics(b, h, m, points=2001), CodeCheckConfig(fc=fc))
    assert c.alpha_0 == pytest.approx(b / h, rel=1e-12)
    assert c.m_star == pytest.approx(m, rel=1e-12)
    assert c.e_star == pytest.approx(1.0, rel=1e-12)
    assert c.a0_star == pytest.approx(G * b / (h * fc), rel=1e-12)
    assert c.d0 == pytest.approx(b / 2, rel=1e-12)
    assert c.d0_star == pytest.approx(b / 2, rel=1e-12)
    assert c.du_star == pytest.approx(0.4 * b / 2, rel=1e-12)
    ds = 0.16 * b / 2
    assert c.ds_star == pytest.approx(ds, rel=1e-12)
    # exact: d = R (sin beta - sin(beta - theta)), alpha = tan(beta - theta)
    r = 0.5 * math.hypot(b, h)
    gamma = math.asin((b / 2 - ds) / r)  # beta - theta at d_s*
    a_s = G * math.tan(gamma) / fc
    assert c.as_star == pytest.approx(a_s, rel=1e-5)
    assert c.ts == pytest.approx(2 * math.pi * math.sqrt(ds / a_s), rel=1e-5)
    # the straight line of the code lies above the exact curve (rocking softens faster)
    assert c.as_star_linear == pytest.approx(G * b / (h * fc) * 0.84, rel=1e-12)
    assert c.as_star < c.as_star_linear


# ---------------------------------------------------------------------------- Oppenheim's arch
def test_oppenheim_alpha0_is_k_and_mirror_symmetric(opp):
    arch, lim = opp
    res = code_check(arch, lim)
    l, r = res.direction("l"), res.direction("r")
    # K_OPPENHEIM has 6 decimals: any alpha_0 that rounds to it (an LP/enumeration result)
    assert l.alpha_0 == pytest.approx(K_OPPENHEIM, abs=5e-7)
    assert r.alpha_0 == pytest.approx(K_OPPENHEIM, abs=5e-7)
    assert l.alpha_0 == pytest.approx(lim.k_l, rel=1e-10)
    for name in ("m_star", "e_star", "a0_star", "d0_star", "du_star", "as_star", "ts"):
        assert getattr(l, name) == pytest.approx(getattr(r, name), rel=1e-9), name
    # measured values (docs/codecheck.md): the whole arch is 82,467 kg/m, 78% participates
    assert l.mass == pytest.approx(2000 * 1.5 * 10 * math.radians(157.5), rel=1e-12)
    assert l.e_star == pytest.approx(0.7757, abs=1e-4)
    assert l.a0_star == pytest.approx(K_OPPENHEIM * G / (l.e_star * 1.35), rel=1e-5)
    assert l.d0_star == pytest.approx(0.6474, abs=1e-4)
    assert 0 < l.e_star < 1


def test_mirror_symmetry_of_an_irregular_arch():
    arch = random_arch(oppenheim_arch(), seed=3)
    a, b = code_check(arch), code_check(arch.mirrored())
    for d, e in (("l", "r"), ("r", "l")):
        x, y = a.direction(d), b.direction(e)
        for name in ("alpha_0", "m_star", "a0_star", "d0_star", "ts"):
            assert getattr(x, name) == pytest.approx(getattr(y, name), rel=1e-8), name


def test_capacity_curve_does_the_work_of_gravity(opp):
    """Independent check of the exact curve: the horizontal forces alpha m g do, along the
    mechanism's path, the work that lifts the weights: integral alpha d(sum m x) = sum m dy at
    the unstable rotation (four-link potential)."""
    arch, lim = opp
    for d in ("l", "r"):
        kin = mechanism_kinematics(arch, lim.mechanism(d), points=4001)
        x = kin.shift @ kin.masses
        work = np.trapezoid(kin.alpha, x)
        lift = potential(kin.rotation[-1], four_link(arch, lim.mechanism(d)).geo)
        assert work == pytest.approx(lift, rel=1e-5)
        assert kin.alpha[0] == pytest.approx(lim.k_l, rel=1e-10)
        assert np.all(np.diff(kin.alpha) < 0)  # rocking: capacity falls as it opens


def test_units_scale(opp):
    """An arch twice as large: the same alpha_0 and e*, a_0*; displacements double, masses per
    metre x4, the period x sqrt(2)."""
    arch, _ = opp
    a, b = code_check(arch).direction("l"), code_check(arch.scaled(2.0)).direction("l")
    assert b.alpha_0 == pytest.approx(a.alpha_0, rel=1e-10)
    assert b.e_star == pytest.approx(a.e_star, rel=1e-10)
    assert b.a0_star == pytest.approx(a.a0_star, rel=1e-10)
    assert b.m_star == pytest.approx(4 * a.m_star, rel=1e-10)
    assert b.d0_star == pytest.approx(2 * a.d0_star, rel=1e-9)
    assert b.ts == pytest.approx(math.sqrt(2) * a.ts, rel=1e-6)


def test_control_point_changes_d_star_little(opp):
    """d* = d_k sum P dx^2 / (dx_k sum P dx) is the same for every control point to first order."""
    arch, lim = opp
    c0 = code_check(arch, lim).direction("l")
    c3 = code_check(arch, lim, CodeCheckConfig(control=3)).direction("l")
    assert c3.d0_star == pytest.approx(c0.d0_star, rel=0.1)
    assert c3.a0_star == c0.a0_star
    with pytest.raises(ArchInputError, match="control"):
        code_check(arch, lim, CodeCheckConfig(control=7))  # 7 voussoirs: 0..6


# ---------------------------------------------------------------------------- spectra and checks
def test_ntc_spectrum_shape():
    s = SiteSpectrum.ntc(0.25, 2.4, 0.3, "B", "T2")
    p = ntc_spectrum_parameters(0.25, 2.4, 0.3, "B", "T2")
    ss = min(max(1.40 - 0.40 * 2.4 * 0.25, 1.0), 1.2)
    assert p["S"] == pytest.approx(ss * 1.2)
    assert p["T_C"] == pytest.approx(1.10 * 0.3 ** -0.2 * 0.3)
    assert s.pga == pytest.approx(0.25 * p["S"])
    assert s.se(p["T_C"] * 0.99) == pytest.approx(0.25 * p["S"] * 2.4)
    assert s.se(2 * p["T_C"]) == pytest.approx(0.25 * p["S"] * 2.4 / 2)
    td = p["T_D"]
    assert td == pytest.approx(2.6)
    assert s.se(2 * td) == pytest.approx(0.25 * p["S"] * 2.4 * p["T_C"] * td / (2 * td) ** 2)
    e = SiteSpectrum.ec8(0.3, "C", 1)
    assert e.pga == pytest.approx(0.3 * 1.15) and e.se(0.4) == pytest.approx(0.3 * 1.15 * 2.5)


def test_checks_against_spectrum_and_table(opp, tmp_path):
    arch, lim = opp
    ntc = SiteSpectrum.ntc(0.25, 2.4, 0.3, "B")
    c = code_check(arch, lim, CodeCheckConfig(spectrum=ntc)).direction("l")
    lin, non = c.checks["linear"], c.checks["nonlinear"]
    assert lin["demand_g"] == pytest.approx(ntc.pga / 2.0)
    assert lin["ratio"] == pytest.approx(c.a0_star / G / lin["demand_g"])
    assert non["demand_m"] == pytest.approx(ntc.se(c.ts) * G * (c.ts / (2 * math.pi)) ** 2)
    assert lin["passed"] and non["passed"]
    # the same spectrum as a table file gives the same demands (to its sampling)
    t = np.linspace(0, 4, 4001)
    f = tmp_path / "se.txt"
    f.write_text("# T Se\n" + "\n".join(f"{a:.6f} {ntc.se(a):.9f}" for a in t))
    ct = code_check(arch, lim, CodeCheckConfig(spectrum=SiteSpectrum.from_file(f))).direction("l")
    assert ct.checks["linear"]["demand_g"] == pytest.approx(lin["demand_g"], rel=1e-6)
    assert ct.checks["nonlinear"]["demand_m"] == pytest.approx(non["demand_m"], rel=1e-4)
    # a strong site: a_0* = 0.353 g < ag S / 2 fails
    strong = code_check(arch, lim, CodeCheckConfig(spectrum=SiteSpectrum.ntc(0.8, 2.4, 0.3, "A")))
    assert not strong.direction("l").checks["linear"]["passed"] and strong.passed is False
    d = strong.to_dict()
    assert CodeCheckConfig.from_dict(json.loads(json.dumps(d["config"]))) == strong.config


def test_bad_input():
    with pytest.raises(ArchInputError, match="fc"):
        CodeCheckConfig(fc=0.5)
    with pytest.raises(ArchInputError, match="soil"):
        SiteSpectrum.ntc(0.2, 2.4, 0.3, "F")
    with pytest.raises(ArchInputError, match="start at T = 0"):
        SiteSpectrum("table", periods=(0.1, 1.0), values=(0.5, 0.3))
    with pytest.raises(ArchInputError, match="ag"):
        SiteSpectrum.ntc(-0.1, 2.4, 0.3)


# ---------------------------------------------------------------------------- CLI
def test_cli_codecheck(capsys, tmp_path):
    assert main(["codecheck", "--json", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3",
                 "--soil", "B"]) == 0
    d = json.loads(capsys.readouterr().out)
    # K_OPPENHEIM to its 6 decimals (an LP/enumeration result)
    assert d["directions"]["l"]["alpha_0"] == pytest.approx(K_OPPENHEIM, abs=5e-7)
    assert d["passed"] is True
    assert main(["codecheck", "--ag", "0.25"]) == 2
    assert "--f0" in capsys.readouterr().err
    f = tmp_path / "bad.txt"
    f.write_text("0.1 0.3\n1 0.2\n")
    assert main(["codecheck", "--spectrum", str(f)]) == 2
    assert main(["codecheck", "--confidence-factor", "1.0"]) == 0
    out = capsys.readouterr().out
    assert "0.370010" in out and "no check" in out


def test_fc_is_the_strength_and_says_so(capsys):
    """--fc, the confidence factor until 0.7, is the masonry's strength now: the command says
    so on stderr, and the confidence factor is --confidence-factor."""
    from archrock.cli import main

    assert main(["codecheck", "--fc", "1.35"]) == 0
    err = capsys.readouterr().err
    assert "--fc 1.35 is the masonry's compressive strength [MPa]" in err
    assert "--confidence-factor (now 1.35)" in err
