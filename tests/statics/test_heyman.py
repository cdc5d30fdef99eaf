"""The Heyman optimum on every arch: the static LP's multiplier, the mechanism that attains it
(four-hinge or with lift-off), three independent values that agree (four-hinge enumeration
where it governs, the LP, the kinematic enumeration of every mechanism with lift-off), and the
four-link model only where four-hinge mechanisms govern."""

import sys
import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from archrock.statics import kinematic, limit
from archrock.dynamics.batch import prepare_batch
from archrock.errors import CannotStandError, GeometryOutcome, NotFourHingeError
from archrock.geometry import Arch, Load, family_arch, nominal_arch, oppenheim_arch
from archrock.dynamics.population import left_out_outcome
from archrock.dynamics.response import prepare

# the random family arches of the property test are the sweep benchmark's, drawn by hypothesis
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from sweep_limit import RISE, SHAPES, build  # noqa: E402


def _readme_arch():
    """The README's geometry-file example: three voussoirs of 22.5 deg, R = 10 m, t = 1.5 m."""
    return Arch(np.radians([22.5] * 3), np.full(3, 10.0), np.full(3, 1.5))


def _agree(a, b, tol=1e-9):
    return abs(a - b) <= tol * max(1.0, abs(b))


def test_readme_example_is_governed_by_lift_off():
    res = limit.limit_analysis(_readme_arch())
    # the unsafe four-hinge value 24.035 of 0.4.0 is gone: a springing lifts off at 10.383
    for d in "lr":
        m = res.mechanism(d)
        assert m.kind == "lift-off"
        assert res.k_l == pytest.approx(10.383417117133, rel=1e-9)
        four = res.four_hinge_l if d == "l" else res.four_hinge_r
        assert four.multiplier == pytest.approx(24.0351027973599, rel=1e-9)
    assert res.mechanism_l.label == "0s-1i-3e"
    # mirror symmetry: M_r is M_l's mirror image
    assert res.mechanism_r.label == res.mechanism_l.mirrored(3).label == "0e-2i-3s"
    assert res.discrepancy < 1e-9
    assert not res.four_hinge


def test_flat_bridge_arch_reports_the_static_optimum():
    arch = family_arch("circular", 10.0, 1.0, 0.6, 12)
    res = limit.limit_analysis(arch)
    assert res.k == pytest.approx(res.static_k_l, rel=1e-9)
    assert res.k == pytest.approx(6.3186, abs=5e-5)
    assert res.four_hinge_l.multiplier == pytest.approx(6.3504, abs=5e-5)
    assert res.mechanism_l.lift_off == (0,) and res.mechanism_r.lift_off == (12,)
    # the mechanism's own virtual work gives the multiplier (a third computation)
    assert limit.mechanism_multiplier(arch, res.mechanism_l) == pytest.approx(res.k_l, rel=1e-12)


def test_oppenheim_unchanged_and_four_hinge():
    res = limit.limit_analysis(oppenheim_arch())
    assert res.k == pytest.approx(0.370010, abs=5e-7)
    assert res.four_hinge and res.mechanism_l.label == "0i-3e-5i-7e"
    assert res.discrepancy < 1e-12
    assert res.four_hinge_l is res.mechanism_l
    assert limit.mechanism_multiplier(oppenheim_arch(), res.mechanism_l) == pytest.approx(
        res.k_l, rel=1e-12)


@pytest.mark.parametrize("embrace", [40.0, 80.0, 120.0, 157.5, 180.0])
@pytest.mark.parametrize("thickness", [0.6, 1.5, 3.0])
def test_general_enumeration_equals_static_lp(embrace, thickness):
    """LP duality as a test: the smallest multiplier over every mechanism of at most four
    joint ends, computed kinematically, is the static LP's optimum."""
    arch = nominal_arch(10.0, embrace, thickness, 7)
    try:
        res = limit.limit_analysis(arch)
    except CannotStandError:
        # too thin: some mechanism opens under its own weight (a multiplier <= 0)
        assert min(limit.general_mechanisms(arch, d).multiplier for d in "lr") <= 0
        return
    except GeometryOutcome as exc:
        # too flat and thick to open at all: no mechanism loads that direction, the LP is unbounded
        assert "no mechanism" in str(exc)
        with pytest.raises(GeometryOutcome, match="no mechanism"):
            for d in "lr":
                limit.general_mechanisms(arch, d)
        return
    for d in "lr":
        gen = limit.general_mechanisms(arch, d)
        static = res.static_k_l if d == "l" else res.static_k_r
        assert _agree(gen.multiplier, static, 1e-8)
        assert _agree(res.mechanism(d).multiplier, gen.multiplier, 1e-8)


def test_shallow_arches_lift_off_and_deep_ones_hinge():
    """Where each kind governs on a 7-voussoir arch of t/R = 0.15: the springing lifts off on
    segmental arches from 65 to 80 deg of embrace, four hinges form from 85 deg; below 65 deg
    nothing opens at all (the LP is unbounded: only sliding or crushing could fail it)."""
    kinds = {e: limit.limit_analysis(nominal_arch(10.0, e, 1.5, 7)).mechanism_l.kind
             for e in (65.0, 80.0, 85.0, 157.5)}
    assert kinds == {65.0: "lift-off", 80.0: "lift-off", 85.0: "four-hinge",
                     157.5: "four-hinge"}
    with pytest.raises(GeometryOutcome, match="no mechanism"):
        limit.limit_analysis(nominal_arch(10.0, 60.0, 1.5, 7))


def test_respond_refuses_an_arch_whose_mechanism_lifts_off():
    arch = family_arch("circular", 10.0, 1.0, 0.6, 12)
    with pytest.raises(NotFourHingeError, match=r"lift-off at joint 0 .*archrock dem"):
        prepare(arch, "momentum")
    # an outcome, counted by the studies under its own key
    assert issubclass(NotFourHingeError, GeometryOutcome)
    assert left_out_outcome(str(NotFourHingeError("arch: M_l is governed by a mechanism with "
                                                  "lift-off at joint 0"))) == "lift_off"


def test_batch_leaves_out_lift_off_arches_with_their_heyman_multiplier():
    arches = [nominal_arch(10.0, e, 1.5, 7) for e in (80.0, 157.5)]
    pb = prepare_batch(arches, impact="momentum")
    assert left_out_outcome(pb.error[0]) == "lift_off" and pb.error[1] == ""
    assert pb.k_l[0] == pytest.approx(3.9020130665024, rel=1e-9)  # the LP's, not 4.1423
    assert pb.k_l[1] == pytest.approx(0.370010, abs=5e-7)
    spans = np.stack([a.spans for a in arches])
    pb2 = prepare_batch(spans, np.full((2, 7), 10.0), np.full((2, 7), 1.5), impact="momentum")
    assert list(pb2.error) == list(pb.error)
    np.testing.assert_allclose(pb2.k_l, pb.k_l, rtol=1e-12)


def test_certification_matches_the_lp_on_random_arches():
    """The batch decides 'four-hinge governs' from the line of thrust alone; the single-arch
    path from the same test; both agree with the LP on which kind governs."""
    rng = np.random.default_rng(7)
    kinds = []
    for _ in range(40):
        n = int(rng.integers(3, 11))
        emb = rng.uniform(30, 200)
        t = rng.uniform(0.05, 0.4) * 10
        spans = np.radians(emb) / n * (1 + 0.2 * rng.uniform(-1, 1, n))
        spans *= np.radians(emb) / spans.sum()
        arch = Arch(spans, np.full(n, 10.0), np.full(n, t))
        try:
            res = limit.limit_analysis(arch)
        except GeometryOutcome:
            continue
        pb = prepare_batch([arch], impact="momentum")
        assert (left_out_outcome(pb.error[0]) == "lift_off") == (not res.four_hinge)
        np.testing.assert_allclose([pb.k_l[0], pb.k_r[0]], [res.k_l, res.k_r], rtol=1e-7)
        kinds.append(res.four_hinge)
        for d in "lr":
            m = res.mechanism(d)
            static = res.static_k_l if d == "l" else res.static_k_r
            assert _agree(m.multiplier, static, 1e-7)
            if m.lift_off and res.four_hinge_l is not None:
                four = res.four_hinge_l if d == "l" else res.four_hinge_r
                # a lift-off mechanism governs only below every four-hinge one
                assert four is None or four.multiplier > m.multiplier
    assert 5 <= sum(kinds) < len(kinds)  # both kinds were met


def test_loaded_arch_lp_dual_and_enumeration_agree():
    arch = family_arch("circular", 10.0, 2.5, 0.8, 8,
                       loads=[Load(2, 6000.0, (-2.0, 3.0))])
    res = limit.limit_analysis(arch)
    for d in "lr":
        gen = limit.general_mechanisms(arch, d)
        assert _agree(res.mechanism(d).multiplier, gen.multiplier, 1e-8)


# ------------------------------------------------------------------------ property sweep


@st.composite
def _family(draw, max_n):
    shape = draw(st.sampled_from(SHAPES))
    lo, hi = RISE.get(shape, (0.05, 1.0))
    rise = 10.0 * draw(st.floats(lo, hi))
    thick = 10.0 * draw(st.floats(0.02, 0.3))
    n = draw(st.integers(3, max_n))
    joints = draw(st.sampled_from(["normal", "vertical"]))
    loaded = draw(st.booleans())
    return shape, rise, thick, n, joints, loaded


def _sweep_case(case, seconds):
    n = case[3]
    try:
        arch = build(*case)
    except GeometryOutcome:
        return "no arch"
    except ValueError:  # ArchInputError: the family refuses these proportions by name
        return "refused"
    t0 = time.perf_counter()
    try:
        res = limit.limit_analysis(arch)
    except CannotStandError:
        outcome = "cannot stand"
    except GeometryOutcome:
        outcome = "no mechanism"
    else:
        outcome = "four-hinge" if res.four_hinge else "lift-off"
        assert res.discrepancy <= 1e-7 * max(1.0, res.k)
        if n <= 10:
            for d in "lr":
                gen = limit.general_mechanisms(arch, d)
                assert _agree(res.mechanism(d).multiplier, gen.multiplier, 1e-7)
    assert time.perf_counter() - t0 < seconds
    return outcome


@settings(max_examples=12, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(_family(max_n=24))
def test_property_sweep_sample(case):
    """Every family, rise/span 0.05-1, t/span 0.02-0.3, both joint kinds, with and without a
    load: limit analysis ends in seconds with kinematic = static (or an outcome)."""
    _sweep_case(case, seconds=20.0)


@pytest.mark.slow
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(_family(max_n=200))
def test_property_sweep(case):
    _sweep_case(case, seconds=60.0)


def test_minimum_thickness_search_is_bounded():
    """The worst case: the tightest tolerance allowed ends in fewer than 100 LPs, and a
    tolerance that could never be met is refused by name."""
    from archrock.errors import ArchInputError

    calls = []

    def stands(a):
        calls.append(1)
        return limit._stands(a)

    mt = limit.thickness_bisection(nominal_arch(10.0, 180.0, 1.5, 8), stands, tol=1e-15)
    assert len(calls) < 100 and mt.iterations < 70
    # a semicircle of 8 voussoirs stands down to t/R = 0.10086 (docs/verification.md)
    assert mt.ratio == pytest.approx(0.10086, abs=1e-5)
    for bad in (0.0, 1e-300, 0.5, float("nan")):
        with pytest.raises(ArchInputError, match="tol"):
            limit.minimum_thickness(oppenheim_arch(), tol=bad)


def test_batch_of_many_voussoirs_leaves_lift_off_out_without_a_full_enumeration(monkeypatch):
    """Above 40 voussoirs the batch's guided search gives inf where no four-hinge mechanism is
    confirmed (a full enumeration of 145 voussoirs would take about a minute) and the row is
    left out as lift_off with the LP's multiplier: the arch the sweep found, a loaded
    three-centred arch turning about one springing while the other lifts off."""
    base = family_arch("three-centred", 10.0, 2.9380585324394937, 2.9986037863196753, 145,
                       joints="vertical")
    c = np.asarray(base.centroids)[48]
    arch = family_arch("three-centred", 10.0, 2.9380585324394937, 2.9986037863196753, 145,
                       joints="vertical",
                       loads=[Load(48, 0.5 * float(np.sum(base.masses)),
                                   (float(c[0]), float(c[1]) + 2.9986037863196753))])
    res = limit.limit_analysis(arch)
    assert res.mechanism_l.label == "0s-145e" and res.mechanism_r.is_four_hinge

    def refuse(*args, **kwargs):
        raise AssertionError("the batch ran a full enumeration")

    monkeypatch.setattr(kinematic, "_full_enumeration", refuse)
    pb = prepare_batch([arch], impact="momentum")
    assert left_out_outcome(pb.error[0]) == "lift_off"
    np.testing.assert_allclose([pb.k_l[0], pb.k_r[0]], [res.k_l, res.k_r], rtol=1e-7)


def test_ensemble_around_a_nominal_arch_that_lifts_off(capsys):
    """A segmental nominal arch (80 deg) lifts off: the ensemble still runs, its nominal k is
    Heyman's (3.9020, not the four-hinge 4.1423), the default c_v is that of the nominal arch's
    best four-hinge mechanisms (the note says why), and the samples that lift off are counted
    as such while the others are integrated."""
    import json

    from archrock.cli import main
    from archrock.dynamics.impact import PAPER_PRACTICE

    nominal = nominal_arch(10.0, 80.0, 1.5, 7)
    spec = PAPER_PRACTICE.resolved(nominal)
    assert spec.model == "fixed" and "lift-off at joint 0" in spec.note
    assert "best four-hinge mechanisms" in spec.note
    # Heyman's no-sliding hypothesis stated (--friction none): at the default mu = 0.8 the
    # springing that lifts off needs more friction than any finite coefficient, and the routing
    # (issue 30) sends the ensemble to the contact engine
    from archrock.studies.enginestudy import choose_dynamics

    assert choose_dynamics(nominal).engine and "no finite friction" in choose_dynamics(nominal).reason
    argv = ["ensemble", "--embrace", "80", "--samples", "60", "--pulse", "oppenheim",
            "--amplitude", "-5", "--pulse-duration", "0.2", "--friction", "none",
            "--no-progress", "--json"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["nominal"]["k_l"] == pytest.approx(3.9020130665024, rel=1e-9)
    counts = d["outcomes"]["counts"]
    assert counts["lift_off"] > 0 and counts["integrated"] > 0
    assert counts["lift_off"] + counts["integrated"] + counts["cannot_stand"] == 60
