"""The contact engine (archrock.contact, pymunk): exact bodies, rest, activation and hinges against
the limit analysis, mirror symmetry, sliding at low friction, the dem/verify command line."""

import json

import numpy as np
import pytest

pymunk = pytest.importorskip("pymunk")

from archrock.cli import main  # noqa: E402
from archrock.contact import (ContactArch, EngineSettings, convex_pieces, engine_respond,  # noqa: E402
                              ramp_direction)
from archrock.contact.convex import signed_area  # noqa: E402
from archrock.errors import ArchInputError  # noqa: E402
from archrock.geometry import (PolygonArch, family_arch, oppenheim_arch,  # noqa: E402
                               polygon_properties, random_arch)
from archrock.groundmotion import oppenheim_pulse  # noqa: E402
from archrock.statics.limit import limit_analysis  # noqa: E402

#: coarse but sufficient engine settings for the default suite (the defaults are finer)
COARSE = EngineSettings(steps_per_T=150, iterations=20)
FAST_RAMP = {"tol": 0.02, "rate": 0.1, "hold": 2.0}


def _notched_arch():
    """Three voussoirs, the middle one with a rectangular notch cut into its extrados (concave)."""
    left = {"intrados": [[-3.0, 0.0], [-2.0, 2.0]], "extrados": [[-4.0, 0.0], [-2.5, 3.0]]}
    mid = {"intrados": [[-2.0, 2.0], [2.0, 2.0]],
           "extrados": [[-2.5, 3.0], [-0.5, 3.0], [-0.5, 2.6], [0.5, 2.6], [0.5, 3.0],
                        [2.5, 3.0]]}
    right = {"intrados": [[2.0, 2.0], [3.0, 0.0]], "extrados": [[2.5, 3.0], [4.0, 0.0]]}
    return PolygonArch.from_dict({"voussoirs": [left, mid, right]})


def test_convex_pieces_tile_a_concave_outline_exactly():
    a = _notched_arch()
    outline = a.outline(1)
    pieces = convex_pieces(outline)
    assert len(pieces) > 1
    area, cen, polar = polygon_properties(outline)
    assert sum(signed_area(p) for p in pieces) == pytest.approx(area, rel=1e-12)
    # first moments add up to the outline's: the pieces cover it without overlap
    cx = sum(signed_area(p) * polygon_properties(p)[1] for p in pieces) / area
    np.testing.assert_allclose(cx, cen, rtol=0, atol=1e-12)
    for p in pieces:  # every piece convex, counter-clockwise
        d = np.roll(p, -1, axis=0) - p
        cross = d[:, 0] * np.roll(d[:, 1], -1) - d[:, 1] * np.roll(d[:, 0], -1)
        assert np.all(cross >= -1e-12)


@pytest.mark.parametrize("arch", [oppenheim_arch(), _notched_arch(), random_arch(seed=4)])
def test_bodies_carry_the_exact_mass_centroid_and_inertia(arch):
    ca = ContactArch(arch, COARSE)
    for i, b in enumerate(ca.bodies):
        assert b.mass == pytest.approx(arch.masses[i], rel=1e-12)
        assert b.moment == pytest.approx(arch.inertias[i], rel=1e-12)
        np.testing.assert_allclose(tuple(b.position), arch.centroids[i], atol=1e-12)
        assert tuple(b.center_of_gravity) == (0.0, 0.0)
        assert all(s.mass == 0 and s.density == 0 for s in b.shapes)
        # every contact combines to exactly MU: sqrt(MU) on each shape
        assert all(s.friction ** 2 == pytest.approx(COARSE.friction) for s in b.shapes)


def test_loads_are_folded_into_the_bodies():
    base = oppenheim_arch()
    d = base.to_dict()
    d["loads"] = [{"voussoir": 3, "mass": 5000.0, "at": [0.5, 11.0]}]
    from archrock.geometry import arch_from_dict

    loaded = arch_from_dict(d)
    ca = ContactArch(loaded, COARSE)
    b = ca.bodies[3]
    m0 = base.masses[3]
    assert b.mass == pytest.approx(m0 + 5000.0)
    g = (m0 * base.centroids[3] + 5000.0 * np.array([0.5, 11.0])) / (m0 + 5000.0)
    np.testing.assert_allclose(tuple(b.position), g, atol=1e-9)
    assert b.moment > base.inertias[3]


def test_arch_at_rest_stays_at_rest():
    a = oppenheim_arch()
    ca = ContactArch(a)  # the default settings: the settled sag is theirs
    ca.settle()
    ca.step(0.0, int(3 * ca.settings.steps_per_T))  # about 3 s
    pos, ang, vel, rate = ca.state()
    assert np.abs(ang - ca.ref_ang).max() < 1e-6  # vs the 1e-3 rad that counts as motion
    assert np.abs(pos - ca.ref_pos).max() < 1e-6 * a.size
    assert ca.kinetic_energy(vel, rate) < 1e-12 * a.masses.sum() * 9.81 * a.size
    # the settled arch is the drawn one to within the joints' rounding
    assert np.abs(ca.drops(pos)).max() < 1e-4 * a.size


def test_ramp_activation_hinges_and_symmetry_of_oppenheims_arch():
    """The limit analysis's k and hinges; a symmetric arch: M_r is M_l mirrored (joints n - j),
    at the same multiplier."""
    a = oppenheim_arch()
    r_l = ramp_direction(a, "l", COARSE, **FAST_RAMP)
    r_r = ramp_direction(a, "r", COARSE, **FAST_RAMP)
    # M_l against the limit analysis (k = 0.370010, hinges 0i-3e-5i-7e)
    assert r_l.mode == "rocking"
    assert r_l.multiplier == pytest.approx(0.370010, rel=0.05)
    assert r_l.hinges == (0, 3, 5, 7)
    assert r_l.edges == ("intrados", "extrados", "intrados", "extrados")
    # the bracket holds: one hold below it rests, one at its top moves
    assert any(not moved and lam == r_l.lower for lam, moved in r_l.holds)
    assert any(moved and lam == r_l.upper for lam, moved in r_l.holds)
    assert r_r.multiplier == pytest.approx(r_l.multiplier, rel=0.02)
    assert tuple(sorted(a.n - j for j in r_r.hinges)) == r_l.hinges


@pytest.mark.slow
def test_ramp_mirror_symmetry_of_an_irregular_arch():
    """k_l of an irregular arch is k_r of its mirror image, hinges at n - j, to the engine's
    accuracy (its Gauss-Seidel contact sweeps are not mirror-symmetric)."""
    a = random_arch(seed=3)
    n = a.n
    r_l = ramp_direction(a, "l")
    m_r = ramp_direction(a.mirrored(), "r")
    assert m_r.multiplier == pytest.approx(r_l.multiplier, rel=0.02)
    assert tuple(sorted(n - j for j in m_r.hinges)) == r_l.hinges
    lim = limit_analysis(a)
    assert r_l.multiplier == pytest.approx(lim.k_l, rel=0.05)


def test_low_friction_slides_where_and_when_the_friction_limit_analysis_says():
    """Two independent methods: the engine's ramp and the static LP with Coulomb rows
    (archrock.statics.friction). Oppenheim's arch needs 0.4951; with mu = 0.3 both slide first, at the
    springing the loads push toward (joint 7 for M_l), at lambda 0.1472 (LP) and 0.1466 (engine,
    default settings)."""
    from archrock.statics.friction import friction_analysis

    a = oppenheim_arch()
    lp = friction_analysis(a, 0.3).l
    assert lp.sliding_governs and lp.joints == (7,)
    r = ramp_direction(a, "l", EngineSettings(friction=0.3), tol=0.01)  # default engine
    assert r.mode == "sliding" and r.hinges == ()
    assert r.sliding_joints == (7,)
    assert r.multiplier == pytest.approx(lp.multiplier, rel=0.03)


def test_engine_settings_round_trip_and_bad_input():
    s = EngineSettings(steps_per_T=300, friction=0.5)
    assert EngineSettings.from_dict(json.loads(json.dumps(s.to_dict()))) == s
    with pytest.raises(ArchInputError, match="friction"):
        EngineSettings(friction=-0.1)
    with pytest.raises(ArchInputError, match="iterations"):
        EngineSettings(iterations=0)
    with pytest.raises(ArchInputError, match="unknown"):
        EngineSettings.from_dict({"step": 1})


def test_engine_response_small_pulse_stays_and_big_one_collapses():
    a = oppenheim_arch()
    small = engine_respond(a, oppenheim_pulse(-0.2, 0.2), COARSE, t_end=0.5, t_free=1.0)
    assert not small.collapsed and small.peak < 1e-4  # below k: no activation
    big = engine_respond(a, oppenheim_pulse(-3.0, 0.5), COARSE, t_end=1.0, collapse_drop=0.05)
    assert big.collapsed and big.t_collapse is not None
    assert big.rotations.shape[1] == a.n and big.max_sliding.shape == (a.n + 1,)


def test_cli_dem_json_keys(capsys):
    coarse = ["--steps-per-T", "150", "--iterations", "20"]
    assert main(["dem", "--pulse", "oppenheim", "--amplitude", "-0.2", "--pulse-duration", "0.2",
                 "--t-end", "0.3", "--json", *coarse]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["collapsed"] is False and "max_sliding" in d and "four_link" in d
    assert main(["dem", "--voussoirs", "5", "--ramp", "--ramp-tol", "0.03", "--json",
                 *coarse]) == 0
    d = json.loads(capsys.readouterr().out)
    for key in ("k_l", "k_r", "hinges_l", "hinges_r"):
        assert key in d
    assert d["k_l"] == pytest.approx(d["limit"]["k_l"], rel=0.05)
    assert d["hinges_l"] == d["limit"]["hinges_l"]


def test_cli_dem_needs_ramp_or_motion(capsys):
    assert main(["dem"]) == 2
    assert "give --ramp" in capsys.readouterr().err
    assert main(["dem", "--ramp", "--friction", "-1"]) == 2


@pytest.mark.slow
@pytest.mark.parametrize("arch", [family_arch("pointed", 10.0, 7.0, 1.0, 9),
                                  random_arch(seed=3),
                                  random_arch(family_arch("pointed", 10.0, 7.0, 1.0, 9), seed=1,
                                              spread_tilt_deg=5.0)])
def test_ramp_agrees_with_limit_analysis_on_other_arches(arch):
    lim = limit_analysis(arch)
    for d in ("l", "r"):
        r = ramp_direction(arch, d)
        assert r.multiplier == pytest.approx(getattr(lim, f"k_{d}"), rel=0.05)
        expected = tuple(h.joint for h in sorted(lim.mechanism(d).hinges, key=lambda h: h.joint))
        assert set(expected) <= set(r.hinges)


def test_cli_verify_agrees_where_the_models_must(capsys):
    """Below activation nothing moves; a 4 g, 0.4 s pulse brings down all three models."""
    assert main(["verify", "--amplitudes=-0.3,-4", "--durations", "0.4", "--steps-per-T", "150",
                 "--iterations", "20", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    for m in ("engine", "paper", "momentum"):
        assert d["collapsed"][m] == [[False, True]]
        assert d["first_collapse"][m] == [4.0]
    assert d["agreement"] == {"paper": 1.0, "momentum": 1.0}
    assert d["cv"]["paper"] == pytest.approx(0.87538, abs=1e-5)
    assert d["cv"]["momentum"] == pytest.approx(0.64496, abs=1e-5)


def test_ramp_range_follows_the_multiplier():
    """lambda_max = max(2, 1.5 k) (at most 100), the ramp starting at 0.5 k where k > 2."""
    from archrock.contact import ramp_range

    assert ramp_range(0.37) == (0.0, pytest.approx(2.0, abs=1e-12))
    start, top = ramp_range(2.375)  # --embrace 90
    assert start == pytest.approx(1.1875, abs=1e-12) and top == pytest.approx(3.5625, abs=1e-12)
    assert ramp_range(float("inf")) == (0.0, pytest.approx(100.0, abs=1e-12))
    assert ramp_range(None)[1] == pytest.approx(100.0, abs=1e-12)
    assert ramp_range(80.0) == (pytest.approx(40.0, abs=1e-12), pytest.approx(100.0, abs=1e-12))


def test_ramp_that_does_not_move_is_an_outcome_not_an_input_error():
    from archrock.errors import ArchInputError, LimitExceededError

    with pytest.raises(LimitExceededError, match="did not move") as info:
        ramp_direction(oppenheim_arch(), "l", COARSE, rate=0.5, lambda_max=0.2)
    assert not isinstance(info.value, ArchInputError)
    with pytest.raises(ArchInputError, match="lambda_start"):
        ramp_direction(oppenheim_arch(), "l", COARSE, lambda_max=0.2, lambda_start=0.3)


@pytest.mark.slow
def test_ramp_past_two_g_on_a_segmental_arch():
    """--embrace 90: k = 2.375 > 2, beyond the old fixed lambda_max = 2; the ramp (default
    engine) finds the activation, below k where the joints slide (friction 0.8 < the 2.14 the
    thrust needs)."""
    from archrock.contact import ramp
    from archrock.geometry import nominal_arch

    a = nominal_arch(embrace_deg=90)
    lim = limit_analysis(a)
    res = ramp(a, limit=lim, tol=0.02)
    assert res.ramp["lambda_max"]["l"] == pytest.approx(1.5 * lim.k_l, rel=1e-12)
    assert 2.0 < res.k_l < lim.k_l and 2.0 < res.k_r < lim.k_r


def test_cli_dem_ignores_impact_options_and_needs_no_law(capsys):
    """The engine uses no impact law: --ramp accepts the impact options and ignores them; a
    pulse on a pointed arch, where the paper's law creates energy, runs (the four-link run
    beside it uses the momentum law and says so)."""
    coarse = ["--steps-per-T", "150", "--iterations", "20"]
    assert main(["dem", "--voussoirs", "5", "--ramp", "--ramp-tol", "0.03", "--impact", "paper",
                 "--impact-on", "nominal", "--json", *coarse]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["k_l"] == pytest.approx(d["limit"]["k_l"], rel=0.05)
    pointed = ["--shape", "pointed", "--span", "10", "--rise", "7", "--thickness", "0.8",
               "--voussoirs", "12"]
    motion = ["--pulse", "oppenheim", "--amplitude", "-0.1", "--pulse-duration", "0.2",
              "--t-end", "0.2"]
    assert main(["dem", *pointed, *motion, "--json", *coarse]) == 0
    d = json.loads(capsys.readouterr().out)
    # the four-link run beside it: the momentum law (said in the note, or by the law itself
    # where the default falls back to it)
    assert d["four_link"]["collapsed"] is False
    assert "momentum" in d.get("four_link_note", "") + json.dumps(d["four_link"])
    assert main(["dem", *pointed, *motion, "--impact", "paper", "--json", *coarse]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["four_link_note"].startswith("four-link model not run") and "four_link" not in d
