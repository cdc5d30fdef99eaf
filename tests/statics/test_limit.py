"""Limit analysis: Oppenheim's arch, static LP == kinematic enumeration, mirror symmetry, thrust
lines, convergence with the number of voussoirs, minimum thickness, infeasible arches, batches."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from archrock.statics import kinematic, limit
from archrock.errors import ArchInputError, CannotStandError, LimitExceededError
from archrock.geometry import Arch, nominal_arch, oppenheim_arch, random_arch
from archrock.statics.limit import Hinge, Mechanism

I, E = "intrados", "extrados"


def _edge_radius(arch, hinge):
    return arch.contact_inner[hinge.joint] if hinge.edge == I else arch.contact_outer[hinge.joint]


def test_oppenheim_multipliers_and_hinges():
    a = oppenheim_arch()
    res = limit.limit_analysis(a)
    # the paper's k to its 4 printed decimals
    assert res.k_l == pytest.approx(0.3700, abs=5e-5) and res.k_r == pytest.approx(0.3700, abs=5e-5)
    assert res.k_l == pytest.approx(0.370010, abs=5e-7)
    assert res.k_l == pytest.approx(res.k_r, abs=1e-12)
    assert res.static_k_l == pytest.approx(res.k_l, abs=1e-9)
    assert res.static_k_r == pytest.approx(res.k_r, abs=1e-9)
    assert res.discrepancy < 1e-9
    assert res.mechanism_l.hinges == (Hinge(0, I), Hinge(3, E), Hinge(5, I), Hinge(7, E))
    assert res.mechanism_r.hinges == (Hinge(0, E), Hinge(2, I), Hinge(4, E), Hinge(7, I))
    assert res.mechanism_r.hinges == res.mechanism_l.mirrored(7).hinges
    assert res.mechanism_l.direction == "l" and res.mechanism_r.direction == "r"


def test_mechanism_mirrored_twice_is_identity():
    m = Mechanism("l", (Hinge(0, I), Hinge(2, E), Hinge(5, I), Hinge(9, E)), 0.3)
    mm = m.mirrored(9)
    assert mm.direction == "r" and mm.joints == (0, 4, 7, 9)
    assert [h.edge for h in mm.hinges] == [E, I, E, I]
    assert mm.mirrored(9) == m


def _random(n, seed, sa, st_, sr):
    return random_arch(nominal_arch(10.0, 157.5, 1.5, n), seed=seed, spread_span=sa,
                       spread_thickness=st_, spread_radius=sr)


def _check_static_equals_kinematic(arch):
    m_l, m_r = limit.kinematic_mechanisms(arch)
    s_l, th_l = limit.static_multiplier(arch, "l")
    s_r, th_r = limit.static_multiplier(arch, "r")
    assert abs(s_l - m_l.multiplier) < 1e-6, (arch, s_l, m_l)
    assert abs(s_r - m_r.multiplier) < 1e-6, (arch, s_r, m_r)
    # the static optimum is a thrust line inside the arch
    assert th_l.eccentricity_margin(arch) > -1e-9
    assert th_r.eccentricity_margin(arch) > -1e-9


arch_params = st.tuples(st.integers(5, 12), st.integers(0, 2**32 - 1), st.floats(0.0, 0.2),
                        st.floats(0.0, 0.2), st.floats(0.0, 0.1))


@settings(max_examples=100, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(arch_params)
def test_static_equals_kinematic_random_arches(params):
    n, seed, sa, st_, sr = params
    _check_static_equals_kinematic(_random(n, seed, sa, st_, sr))


@pytest.mark.slow
@settings(max_examples=600, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(arch_params)
def test_static_equals_kinematic_random_arches_many(params):
    n, seed, sa, st_, sr = params
    _check_static_equals_kinematic(_random(n, seed, sa, st_, sr))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_mirror_swaps_directions(seed):
    a = _random(9, seed, 0.2, 0.2, 0.1)
    m_l, m_r = limit.kinematic_mechanisms(a)
    mm_l, mm_r = limit.kinematic_mechanisms(a.mirrored())
    assert m_l.multiplier != pytest.approx(m_r.multiplier, abs=1e-3)  # really irregular
    assert mm_l.multiplier == pytest.approx(m_r.multiplier, abs=1e-12)
    assert mm_r.multiplier == pytest.approx(m_l.multiplier, abs=1e-12)
    assert mm_l.hinges == m_r.mirrored(a.n).hinges
    assert mm_r.hinges == m_l.mirrored(a.n).hinges
    assert mm_l == Mechanism("l", m_r.mirrored(a.n).hinges, mm_l.multiplier)


@pytest.mark.parametrize("arch", [oppenheim_arch(), _random(7, 4, 0.1, 0.1, 0.05),
                                  _random(11, 5, 0.2, 0.2, 0.1)])
def test_thrust_line_through_the_hinges(arch):
    for mech in limit.kinematic_mechanisms(arch):
        th = limit.thrust_line(arch, mech)
        assert th.direction == mech.direction
        assert th.multiplier == pytest.approx(mech.multiplier, abs=1e-9)
        assert th.eccentricity_margin(arch) >= -1e-9
        for h in mech.hinges:
            assert th.radii[h.joint] == pytest.approx(_edge_radius(arch, h), abs=1e-9)
        np.testing.assert_allclose(np.hypot(*th.points.T), th.radii, rtol=1e-12)
        # compression across every joint: normal force N = F . (sin psi, -cos psi) > 0
        psi = arch.joint_angles
        normal = th.forces[:, 0] * np.sin(psi) - th.forces[:, 1] * np.cos(psi)
        assert np.all(normal > 0)
        # strictly inside away from the hinges (a four-hinge mechanism, not more)
        others = [j for j in range(arch.n + 1) if j not in mech.joints]
        gap = np.minimum(th.radii[others] - arch.contact_inner[others],
                         arch.contact_outer[others] - th.radii[others])
        assert gap.min() > 1e-3


def test_thrust_line_of_static_optimum_oppenheim():
    a = oppenheim_arch()
    lam, th = limit.static_multiplier(a, "l")
    touching = np.isclose(th.radii, a.contact_inner, atol=1e-7) | np.isclose(th.radii, a.contact_outer, atol=1e-7)
    assert list(np.flatnonzero(touching)) == [0, 3, 5, 7]


def _nominal_k(n):
    return limit.kinematic_mechanisms(nominal_arch(10.0, 157.5, 1.5, n))[0].multiplier


def test_multiplier_converges_with_voussoirs():
    k = [_nominal_k(n) for n in (7, 14, 28)]
    assert k[0] == pytest.approx(0.370010, abs=1e-6)
    assert k[1] == pytest.approx(0.358865, abs=1e-6)
    assert k[2] == pytest.approx(0.354686, abs=1e-6)
    # more joints, more places for hinges: the multiplier decreases, by ever smaller steps
    d = np.diff(k)
    assert np.all(d < 0)
    assert abs(d[1]) < 0.5 * abs(d[0])


@pytest.mark.slow
def test_multiplier_converges_with_voussoirs_56():
    k = [_nominal_k(n) for n in (7, 14, 28, 56)]
    d = np.diff(k)
    assert np.all(d < 0) and abs(d[2]) < abs(d[1]) < abs(d[0])
    assert k[3] == pytest.approx(0.353747, abs=1e-6)
    assert abs(d[2]) < 1.5e-3


def _tmin(n):
    return limit.minimum_thickness(nominal_arch(10.0, 180.0, 1.0, n)).ratio


def test_minimum_thickness_semicircle_milankovitch():
    t = {n: _tmin(n) for n in (8, 16, 60)}
    # many voussoirs: Milankovitch's continuous value t/R = 0.1075
    assert t[60] == pytest.approx(0.1075, abs=1e-3)
    assert t[60] == pytest.approx(0.107460, abs=2e-6)
    # hinges only at joints: a discrete arch needs no more than the continuous one, and refining
    # the joints (every joint of n is a joint of 2n) can only raise the minimum thickness
    assert t[8] < t[16] <= t[60] + 1e-9 <= 0.1075 + 1e-4
    assert t[8] == pytest.approx(0.100861, abs=2e-6)
    # at the minimum thickness the arch just stands: the LP multiplier is ~0 in both directions
    a = nominal_arch(10.0, 180.0, 1.0, 16).with_thickness_factor(limit.minimum_thickness(
        nominal_arch(10.0, 180.0, 1.0, 16)).factor)
    m_l, m_r = limit.kinematic_mechanisms(a)
    assert abs(m_l.multiplier) < 1e-5 and abs(m_r.multiplier) < 1e-5


def test_minimum_thickness_refinement_is_monotone():
    t = [_tmin(n) for n in (6, 12, 24, 48)]
    assert np.all(np.diff(t) >= -1e-9)
    assert all(x < 0.1075 + 1e-4 for x in t)


def test_thicker_arch_has_larger_multiplier():
    ks = [limit.kinematic_mechanisms(nominal_arch(10.0, 157.5, t, 7))[0].multiplier
          for t in (1.0, 1.5, 2.0, 3.0)]
    assert np.all(np.diff(ks) > 0)
    a = _random(8, 21, 0.1, 0.1, 0.05)
    base = limit.kinematic_mechanisms(a)
    thick = limit.kinematic_mechanisms(a.with_thickness_factor(1.3))
    assert thick[0].multiplier > base[0].multiplier
    assert thick[1].multiplier > base[1].multiplier


def test_too_thin_arch_is_refused():
    thin = nominal_arch(10.0, 180.0, 0.8, 12)  # t/R = 0.08 < 0.105
    # a physical outcome, not an input error
    with pytest.raises(CannotStandError, match="arch"):
        limit.static_multiplier(thin, "l")
    with pytest.raises(CannotStandError, match="arch"):
        limit.static_multiplier(thin, "r")
    with pytest.raises(CannotStandError, match="arch"):
        limit.limit_analysis(thin)
    with pytest.raises(ArchInputError, match="direction"):
        limit.static_multiplier(oppenheim_arch(), "up")
    with pytest.raises(ArchInputError, match="arch"):
        limit.limit_analysis("not an arch")


def _batch(n, count, seed0):
    arches = [_random(n, seed0 + k, 0.2, 0.2, 0.1) for k in range(count)]
    return arches, (np.array([a.spans for a in arches]), np.array([a.radii for a in arches]),
                    np.array([a.thicknesses for a in arches]))


@pytest.mark.parametrize("n", [5, 7, 10])
def test_batch_equals_per_arch(n):
    arches, (S, R, T) = _batch(n, 40, 100 * n)
    k_l, k_r, i_l, i_r = limit.kinematic_multipliers_batch(S, R, T)
    jq, eq = limit._candidates(n)
    for b, a in enumerate(arches):
        m_l, m_r = limit.kinematic_mechanisms(a)
        # the batch takes its sums from the sector formulas of the whole batch, the arch from its
        # own properties: the same numbers up to the rounding of numpy's reductions (which moved
        # by an ulp with numpy 2.4), so the same candidates and multipliers to 1e-14
        assert k_l[b] == pytest.approx(m_l.multiplier, rel=1e-14, abs=1e-15)
        assert k_r[b] == pytest.approx(m_r.multiplier, rel=1e-14, abs=1e-15)
        assert tuple(jq[i_l[b]]) == m_l.joints and tuple(jq[i_r[b]]) == m_r.joints
        assert tuple(limit.EDGES[e] for e in eq[i_l[b]]) == tuple(h.edge for h in m_l.hinges)
    # block sizes do not change anything
    for chunk in (1, 3, 1000):
        out = limit.kinematic_multipliers_batch(S, R, T, chunk=chunk)
        np.testing.assert_array_equal(out[0], k_l)
        np.testing.assert_array_equal(out[3], i_r)


def test_numpy_and_compiled_paths_agree(monkeypatch):
    """The optional numba kernel and the numpy enumeration give the same mechanisms and
    multipliers to rounding (two paths: numpy's SIMD width and numba's codegen differ by CPU)."""
    arches, (S, R, T) = _batch(7, 60, 7)
    ref = limit.kinematic_multipliers_batch(S, R, T)
    monkeypatch.setattr(kinematic, "_NUMBA_ENABLED", False)
    out = limit.kinematic_multipliers_batch(S, R, T)
    # multipliers to rel 1e-12; candidate indices exactly (random arches: no two candidates
    # within rounding of each other)
    np.testing.assert_allclose(out[0], ref[0], rtol=1e-12)
    np.testing.assert_allclose(out[1], ref[1], rtol=1e-12)
    np.testing.assert_array_equal(out[2], ref[2])
    np.testing.assert_array_equal(out[3], ref[3])
    # and the full per-candidate table agrees with the reduced minimum
    lam_l, lam_r, _, _ = limit._enumerate(S, R, T)
    np.testing.assert_allclose(lam_l.min(axis=1), ref[0], rtol=1e-12)
    np.testing.assert_array_equal(np.argmin(lam_r, axis=1), ref[3])


def test_batch_rejects_bad_input():
    with pytest.raises(ArchInputError, match="shapes"):
        limit.kinematic_multipliers_batch(np.ones((2, 5)), np.ones((2, 4)), np.ones((2, 5)))
    with pytest.raises(ArchInputError, match="voussoirs"):
        limit.kinematic_multipliers_batch(np.ones((2, 2)), np.ones((2, 2)), np.ones((2, 2)))
    with pytest.raises(ArchInputError, match="spans"):
        limit.kinematic_multipliers_batch([[0.3, np.nan, 0.3]], [[10] * 3], [[1] * 3])


def test_result_serialises():
    d = limit.limit_analysis(oppenheim_arch()).to_dict()
    assert d["k_l"] == pytest.approx(0.370010, abs=1e-6)
    assert d["mechanism_l"]["hinges"][1] == {"joint": 3, "edge": E}
    assert Arch.from_dict(d["arch"]).n == 7
    assert math.isclose(d["discrepancy"], 0.0, abs_tol=1e-9)


def test_many_voussoirs_without_building_the_candidate_list():
    """120 voussoirs: the static-guided search (with or without numba) finds the mechanism that
    the full enumeration of 14 C(121, 4) = 124 million candidates finds (numba: loops, no list);
    the result still matches the static LP."""
    from archrock import _jit
    from archrock.geometry import nominal_arch
    from archrock.statics.limit import limit_analysis

    arch = nominal_arch(10.0, 157.5, 1.5, 120)
    res = limit_analysis(arch)
    assert res.discrepancy < 1e-9
    assert res.k_l == pytest.approx(0.353407, abs=2e-6)
    assert res.mechanism_l.joints == (1, 45, 89, 120)
    if _jit.HAVE_NUMBA:
        full = limit_analysis(arch, method="enumeration")
        assert (full.k_l, full.k_r) == (res.k_l, res.k_r)
        assert (full.mechanism_l, full.mechanism_r) == (res.mechanism_l, res.mechanism_r)
    else:
        with pytest.raises(LimitExceededError, match="voussoirs"):
            limit_analysis(arch, method="enumeration")


def test_candidate_hinges_unranks_the_candidate_list():
    from archrock.statics.limit import _candidates, candidate_hinges

    for n in (3, 7, 12):
        jq, eq = _candidates(n)
        for i in range(0, len(jq), 5):
            assert candidate_hinges(n, i) == (tuple(jq[i]), tuple(eq[i]))


def test_one_enumeration_of_four_hinge_sets():
    """four_hinge_sets is the one list of quadruples: C(n+1, 4) rows, each a < b < c < d, in
    lexicographic order, the same order the combinadic unranking (candidate_hinges) computes
    without the list; four_hinge_candidates walks it with the 14 patterns that can open, and a
    pool of joints keeps that order (quadruples)."""
    import math

    from archrock.statics.hinges import (_active_candidates, candidate_hinges,
                                         four_hinge_candidates, four_hinge_sets, quadruples)

    for n in (3, 6, 11):
        q = four_hinge_sets(n)
        assert q.shape == (math.comb(n + 1, 4), 4) and not q.flags.writeable
        assert np.all(np.diff(q, axis=1) > 0) and q.min() == 0 and q.max() == n
        keys = q @ (n + 1) ** np.arange(3, -1, -1)  # lexicographic order = increasing keys
        assert np.all(np.diff(keys) > 0)
        for r in range(0, len(q), 7):
            assert candidate_hinges(n, 16 * r + 5)[0] == tuple(q[r].tolist())
        mechs = list(four_hinge_candidates(n, "r"))
        assert len(mechs) == 14 * len(q) == len(_active_candidates(n)[0])
        idx = _active_candidates(n)[0]
        for i in range(0, len(mechs), 11):
            joints, edges = candidate_hinges(n, int(idx[i]))
            assert mechs[i].joints == joints and mechs[i].direction == "r"
            assert tuple(h.edge for h in mechs[i].hinges) == tuple(
                ("intrados", "extrados")[e] for e in edges)
    pool = [1, 4, 5, 9, 10]
    sub = quadruples(pool)
    full = four_hinge_sets(10)
    assert np.array_equal(sub, full[np.isin(full, pool).all(axis=1)])
    assert quadruples([2, 3, 4]).shape == (0, 4)
