"""The static-guided search for many voussoirs: the same mechanisms as the full enumeration,
static = kinematic on hundreds of voussoirs in well under a second, and the full enumeration's
work estimated before it starts (refused beyond a bound, progress on stderr when long)."""

import json
import math
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from archrock.statics import kinematic, limit
from archrock.errors import ArchInputError, CannotStandError, LimitExceededError, NoMechanismError
from archrock.geometry import nominal_arch, oppenheim_arch, random_arch


def _rows(arch):
    return arch.spans[None], arch.radii[None], arch.thicknesses[None]


def _both(arch):
    e = limit.kinematic_multipliers_batch(*_rows(arch), method="enumeration")
    g = limit.kinematic_multipliers_batch(*_rows(arch), method="guided")
    return e, g


def _assert_same_as_enumeration(arch):
    e, g = _both(arch)
    if min(e[0][0], e[1][0]) <= 0:
        # cannot stand: the enumeration's negative multiplier has no static counterpart; the
        # guided search says so with -inf (or finds the same negative one when an LP solves)
        assert min(g[0][0], g[1][0]) <= 0
        return
    # the same candidates (hinges) exactly; the multipliers to rel 1e-12: the guided search
    # and the enumeration evaluate them on two paths, which may round differently by CPU
    for x, y in zip(e, g):
        if np.asarray(x).dtype.kind in "biu":
            np.testing.assert_array_equal(x, y)
        else:
            np.testing.assert_allclose(y, x, rtol=1e-12)


QUICK = [
    oppenheim_arch(),
    nominal_arch(10.0, 157.5, 1.5, 12),
    nominal_arch(10.0, 180.0, 1.3, 20),
    nominal_arch(5.0, 120.0, 0.6, 31),
    nominal_arch(10.0, 157.5, 1.5, 40),
    random_arch(nominal_arch(10.0, 157.5, 1.5, 9), seed=3, spread_span=0.2, spread_thickness=0.2,
                spread_radius=0.1),
    random_arch(nominal_arch(10.0, 140.0, 1.8, 17), seed=4),
    random_arch(nominal_arch(10.0, 200.0, 2.5, 26), seed=5, spread_span=0.15),
    random_arch(nominal_arch(10.0, 157.5, 1.5, 40), seed=6, spread_span=0.2, spread_thickness=0.2,
                spread_radius=0.1),
]


@pytest.mark.parametrize("arch", QUICK, ids=[f"n{a.n}-{a.name}" for a in QUICK])
def test_guided_search_finds_the_enumerated_mechanism(arch):
    _assert_same_as_enumeration(arch)


@pytest.mark.slow
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(7, 40), st.floats(90.0, 210.0), st.floats(0.1, 0.3), st.integers(0, 2**32 - 1),
       st.floats(0.0, 0.2), st.floats(0.0, 0.2), st.floats(0.0, 0.1), st.booleans())
def test_guided_search_finds_the_enumerated_mechanism_many(n, embrace, t_over_r, seed, sa, st_, sr,
                                                           regular):
    nom = nominal_arch(10.0, embrace, 10.0 * t_over_r, n)
    arch = nom if regular else random_arch(nom, seed=seed, spread_span=sa, spread_thickness=st_,
                                           spread_radius=sr)
    _assert_same_as_enumeration(arch)


def test_auto_method_switches_above_the_threshold():
    small = nominal_arch(10.0, 157.5, 1.5, limit.ENUMERATION_MAX_VOUSSOIRS)
    big = nominal_arch(10.0, 157.5, 1.5, limit.ENUMERATION_MAX_VOUSSOIRS + 1)
    assert "enumeration" in limit.limit_analysis(small).method
    assert "static-guided" in limit.limit_analysis(big).method
    for arch in (small, big):
        auto = limit.kinematic_multipliers_batch(*_rows(arch))
        for x, y in zip(auto, _both(arch)[0]):
            np.testing.assert_array_equal(x, y)


@pytest.mark.parametrize("seed", [None, 500])
def test_500_voussoirs_in_well_under_seconds(seed):
    nom = nominal_arch(10.0, 157.5, 1.5, 500)
    arch = nom if seed is None else random_arch(nom, seed=seed, spread_span=0.2,
                                                spread_thickness=0.2, spread_radius=0.1)
    t0 = time.perf_counter()
    res = limit.limit_analysis(arch)
    elapsed = time.perf_counter() - t0
    assert elapsed < 5.0  # measured 0.08 s on one core; the enumeration would take ~6 min
    # the limit theorems: kinematic = static
    assert abs(res.k_l - res.static_k_l) <= 1e-9 * max(1.0, res.k_l)
    assert abs(res.k_r - res.static_k_r) <= 1e-9 * max(1.0, res.k_r)
    for mech in (res.mechanism_l, res.mechanism_r):
        th = limit.thrust_line(arch, mech)
        assert th.multiplier == pytest.approx(mech.multiplier, abs=1e-9)
        assert th.eccentricity_margin(arch) >= -1e-9
    if seed is None:
        # converged towards the continuous arch (0.353747 at n = 56, 0.353407 at 120)
        assert res.k_l == pytest.approx(0.353388, abs=2e-6) and res.k_l == pytest.approx(res.k_r, abs=1e-12)
        assert res.mechanism_r.hinges == res.mechanism_l.mirrored(500).hinges


def test_mirror_swaps_directions_many_voussoirs():
    a = random_arch(nominal_arch(10.0, 157.5, 1.5, 150), seed=8, spread_span=0.2,
                    spread_thickness=0.2, spread_radius=0.1)
    m_l, m_r = limit.kinematic_mechanisms(a)
    mm_l, mm_r = limit.kinematic_mechanisms(a.mirrored())
    assert mm_l.multiplier == pytest.approx(m_r.multiplier, abs=1e-12)
    assert mm_r.multiplier == pytest.approx(m_l.multiplier, abs=1e-12)
    assert mm_l.hinges == m_r.mirrored(a.n).hinges and mm_r.hinges == m_l.mirrored(a.n).hinges


def test_minimum_thickness_many_voussoirs_approaches_milankovitch():
    t = {n: limit.minimum_thickness(nominal_arch(10.0, 180.0, 1.0, n)).ratio for n in (128, 256, 512)}
    assert t[256] == pytest.approx(0.107469, abs=2e-6)
    assert t[512] == pytest.approx(0.107478, abs=2e-6)
    assert t[128] <= t[256] + 1e-9 <= t[512] + 2e-9 <= 0.1075 + 1e-9


def test_candidate_index_inverts_candidate_hinges():
    rng = np.random.default_rng(0)
    for n in (3, 7, 12, 60, 1000):
        total = 16 * math.comb(n + 1, 4)
        idx = np.unique(np.concatenate([[0, total - 1], rng.integers(0, total, 200)]))
        hinges = [limit.candidate_hinges(n, int(i)) for i in idx]
        back = limit._candidate_index(n, [h[0] for h in hinges], [h[1] for h in hinges])
        np.testing.assert_array_equal(back, idx)


def test_search_falls_back_to_the_enumeration(monkeypatch):
    arch = random_arch(nominal_arch(10.0, 157.5, 1.5, 44), seed=2)
    ref = limit.kinematic_multipliers_batch(*_rows(arch), method="enumeration")
    monkeypatch.setattr(kinematic, "_CONFIRM_RTOL", -1.0)  # no mechanism is ever confirmed
    out = limit.kinematic_multipliers_batch(*_rows(arch), method="guided")
    for x, y in zip(ref, out):
        np.testing.assert_array_equal(x, y)
    with pytest.raises(LimitExceededError, match=r"could not confirm.*about .* s.*max_seconds="):
        limit.kinematic_multipliers_batch(*_rows(arch), method="guided", max_seconds=1e-6)


def test_full_enumeration_estimates_its_work(monkeypatch):
    big = nominal_arch(10.0, 157.5, 1.5, 500)
    # numba: ~450 s estimated, beyond the default bound; numpy: the candidates do not fit
    with pytest.raises(LimitExceededError, match=r"3\.63e\+10 candidate.*(max_seconds=\d+|'fast')"):
        limit.limit_analysis(big, method="enumeration")
    est = limit.enumeration_estimate(500)
    assert est["candidates"] == 14 * math.comb(501, 4) and est["seconds"] > 100
    arch = nominal_arch(10.0, 157.5, 1.5, 30)
    with pytest.raises(LimitExceededError, match=r"4\.41e\+05 candidate.* about 0\.0\d+ s.*bound 0\.001 s.*max_seconds=1"):
        limit.kinematic_mechanisms(arch, method="enumeration", max_seconds=1e-3)
    limit.kinematic_mechanisms(arch, method="enumeration", max_seconds=1.0)
    # without numba the candidate list must fit in memory
    monkeypatch.setattr(kinematic, "_NUMBA_ENABLED", False)
    with pytest.raises(LimitExceededError, match=r"memory.*GB.*'fast' extra"):
        limit.kinematic_mechanisms(nominal_arch(10.0, 157.5, 1.5, 60), method="enumeration")


@pytest.mark.parametrize("numba", [True, False])
def test_long_enumeration_reports_progress(monkeypatch, capsys, numba):
    if numba and not kinematic._NUMBA_ENABLED:
        pytest.skip("numba not available")
    monkeypatch.setattr(kinematic, "_NUMBA_ENABLED", numba)
    arch = random_arch(nominal_arch(10.0, 157.5, 1.5, 14), seed=1)
    ref = limit.kinematic_multipliers_batch(*_rows(arch), method="enumeration")
    assert capsys.readouterr().err == ""
    monkeypatch.setattr(kinematic, "_PROGRESS_SECONDS", 0.0)
    monkeypatch.setattr(kinematic, "_BLOCK_ELEMENTS", 512)  # several numpy blocks
    # the library never prints: the lines go to the callable of limit_progress, if any
    limit.kinematic_multipliers_batch(*_rows(arch), method="enumeration", chunk=1)
    assert capsys.readouterr().err == ""
    lines = []
    with limit.limit_progress(lines.append):
        out = limit.kinematic_multipliers_batch(*_rows(arch), method="enumeration", chunk=1)
    err = "\n".join(lines)
    assert "full enumeration of 1.91e+04 candidate mechanisms (1 arch of 14 voussoirs)" in err
    assert "100%" in err and "done in" in err
    for x, y in zip(ref, out):  # split in ranges of first joints: the same result
        np.testing.assert_array_equal(x, y)


def test_bad_method_or_bound_is_an_input_error():
    a = oppenheim_arch()
    with pytest.raises(ArchInputError, match=r"method: 'fast'; allowed 'auto', 'enumeration', 'guided'"):
        limit.limit_analysis(a, method="fast")
    for bad in (0, -1, float("nan"), "x"):
        with pytest.raises(ArchInputError, match="max_seconds"):
            limit.kinematic_multipliers_batch(*_rows(a), max_seconds=bad)


def test_physical_outcomes_many_voussoirs():
    thin = nominal_arch(10.0, 180.0, 0.8, 60)  # t/R = 0.08 < 0.1075: no line of thrust fits
    k_l, k_r, _, _ = limit.kinematic_multipliers_batch(*_rows(thin))
    assert k_l[0] == k_r[0] == -np.inf
    with pytest.raises(CannotStandError, match="arch"):
        limit.limit_analysis(thin)
    flat = nominal_arch(10.0, 40.0, 2.0, 60)  # too flat and thick to hinge
    k_l, k_r, _, _ = limit.kinematic_multipliers_batch(*_rows(flat))
    assert k_l[0] == k_r[0] == np.inf
    with pytest.raises(NoMechanismError):
        limit.limit_analysis(flat)
    # the same outcomes as the enumeration on 12 voussoirs
    assert np.isinf(limit.kinematic_multipliers_batch(*_rows(nominal_arch(10.0, 40.0, 2.0, 12)))[0][0])


_SCRIPT = """
import json
from archrock.statics import limit
from archrock.geometry import nominal_arch, random_arch
out = []
for n, seed in ((60, None), (120, 7), (300, 9)):
    nom = nominal_arch(10.0, 157.5, 1.5, n)
    a = nom if seed is None else random_arch(nom, seed=seed, spread_span=0.2, spread_thickness=0.2,
                                             spread_radius=0.1)
    r = limit.limit_analysis(a)
    out.append([r.k_l, r.k_r, r.mechanism_l.label, r.mechanism_r.label])
print(json.dumps(out))
"""


def test_guided_search_same_without_numba(without_numba):
    ref = json.loads(without_numba("-c", _SCRIPT))
    scope = {}
    exec(compile(_SCRIPT.replace("print(json.dumps(out))", ""), "<script>", "exec"), scope)
    got = scope["out"]
    # the mechanisms exactly; k to rtol=1e-12, not bit for bit: the pure-Python and numba
    # kernels are two paths whose roundings may differ (FMA, SIMD width by CPU)
    assert [r[2:] for r in ref] == [g[2:] for g in got]
    np.testing.assert_allclose([r[:2] for r in ref], [g[:2] for g in got], rtol=1e-12, atol=0)


def test_cli_prints_the_progress_of_a_long_enumeration(monkeypatch, capsys):
    """The CLI hands limit analysis a progress callable that prints on stderr; the library
    itself stays silent (above)."""
    from archrock.cli import main

    monkeypatch.setattr(kinematic, "_PROGRESS_SECONDS", 0.0)
    assert main(["limit", "--voussoirs", "14", "--json"]) == 0
    err = capsys.readouterr().err
    assert "archrock limit analysis: full enumeration of" in err and "done in" in err
