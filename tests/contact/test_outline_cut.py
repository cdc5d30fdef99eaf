"""Issue 21: the contact shapes cut from a simplified outline (within outline_tol x size of the
voussoir's, joints' ends exact), a few convex pieces per voussoir instead of 20 to 60; the
engine's settings made concrete for an arch (engine_scales)."""

import math

import numpy as np
import pytest

pymunk = pytest.importorskip("pymunk")

from archrock.contact import (FINE_CUT, ContactArch, EngineSettings, convex_pieces,  # noqa: E402
                              engine_scales, outline_deviation, ramp, simplify_outline)
from archrock.contact.convex import signed_area, strip_pieces  # noqa: E402
from archrock.errors import ArchInputError  # noqa: E402
from archrock.geometry import family_arch, oppenheim_arch, random_arch  # noqa: E402
from archrock.statics.limit import limit_analysis  # noqa: E402
from archrock.units import G  # noqa: E402

#: the pointed arch of docs/geometry.md (S = 10 m, F = 7 m, t = 1 m, n = 12)
POINTED = dict(shape="pointed", span=10.0, rise=7.0, thickness=1.0, n=12)


def _to_boundary(q, poly):
    """Distance [m] of point q to the boundary of the closed polygon poly."""
    best = np.inf
    for a, b in zip(poly, np.roll(poly, -1, axis=0)):
        d = b - a
        t = np.clip(np.dot(q - a, d) / np.dot(d, d), 0.0, 1.0)
        best = min(best, float(np.hypot(*(q - a - t * d))))
    return best


def _pointed():
    p = POINTED
    return family_arch(p["shape"], p["span"], p["rise"], p["thickness"], p["n"])


@pytest.mark.parametrize("arch", [_pointed(), oppenheim_arch(), random_arch(seed=3),
                                  random_arch(family_arch("pointed", 10.0, 7.0, 1.0, 9), seed=1,
                                              spread_tilt_deg=5.0)])
def test_simplified_outline_within_tolerance_corners_exact(arch):
    tol = EngineSettings().outline_tol * arch.size
    jp = np.asarray(arch.joint_points)
    for i in range(arch.n):
        fine = arch.outline(i)
        corners = jp[[i, i + 1]].reshape(-1, 2)
        simple = simplify_outline(fine, tol, corners)
        # every point of either boundary within tol of the other
        assert outline_deviation(fine, simple) <= tol
        # the joints' contact ends lie on the simplified outline (at a vertex, or on a joint's
        # straight face where the neighbour is thinner), to rounding
        for q in corners:
            assert _to_boundary(q, simple) < 1e-12 * arch.size
        # its convex pieces tile it exactly, far fewer than the fine cut's
        pieces = strip_pieces(simple)
        assert sum(signed_area(p) for p in pieces) == pytest.approx(abs(signed_area(simple)),
                                                                     rel=1e-12)
        for p in pieces:  # every piece convex, counter-clockwise
            d = np.roll(p, -1, axis=0) - p
            assert np.all(d[:, 0] * np.roll(d[:, 1], -1) - d[:, 1] * np.roll(d[:, 0], -1)
                          >= -1e-12 * arch.size ** 2)
        assert len(pieces) <= 4 and 20 <= len(convex_pieces(fine))
        # each joint's contact ends lie in one piece only (no fan of slivers at a hinge)
        for q in corners:
            assert sum(_to_boundary(q, p) < 1e-9 * arch.size for p in pieces) == 1


def test_pieces_per_voussoir_on_the_pointed_arch():
    a = _pointed()
    fine = ContactArch(a, FINE_CUT.replace(steps_per_T=100, iterations=10))
    simple = ContactArch(a, EngineSettings(steps_per_T=100, iterations=10))
    n_fine = [len(p) for p in fine.pieces]
    n_simple = [len(p) for p in simple.pieces]
    assert max(n_fine) == 32 and min(n_fine) == 29
    assert n_simple == [2] * a.n
    # the fine cut keeps every outline vertex; the simplified one only a few
    assert all(len(o) == len(a.outline(i)) for i, o in enumerate(fine.outlines))
    assert all(len(o) == 8 for o in simple.outlines)  # of 66
    # the bodies are the same: the exact mass properties, whatever the cut
    for bf, bs in zip(fine.bodies, simple.bodies):
        assert bf.mass == bs.mass and bf.moment == bs.moment
        assert tuple(bf.position) == tuple(bs.position)


def test_strip_pieces_of_a_mirrored_outline_are_mirrored():
    a = _pointed()
    tol = EngineSettings().outline_tol * a.size
    jp = np.asarray(a.joint_points)
    i, k = 2, a.n - 1 - 2
    left = strip_pieces(simplify_outline(a.outline(i), tol, jp[[i, i + 1]].reshape(-1, 2)))
    right = strip_pieces(simplify_outline(a.outline(k), tol, jp[[k, k + 1]].reshape(-1, 2)))
    key = lambda ps: sorted(round(float(signed_area(p)), 9) for p in ps)  # noqa: E731
    assert key(left) == key(right)
    cx = sorted(round(float(p[:, 0].mean()), 6) for p in left)
    assert cx == sorted(round(-float(p[:, 0].mean()), 6) for p in right)


def test_simplify_outline_bad_input_and_zero_tolerance():
    a = oppenheim_arch()
    o = a.outline(0)
    np.testing.assert_array_equal(simplify_outline(o, 0.0), o)
    with pytest.raises(ArchInputError, match="outline tolerance.*>= 0"):
        simplify_outline(o, -1e-3)
    with pytest.raises(ArchInputError, match="outline tolerance"):
        simplify_outline(o, float("nan"))
    with pytest.raises(ArchInputError, match="voussoir outline"):
        simplify_outline([[0, 0], [1, 1]], 1e-3)
    with pytest.raises(ArchInputError, match=r"outline_tol.*0 <= outline_tol <= 0\.01"):
        EngineSettings(outline_tol=0.02)
    with pytest.raises(ArchInputError, match="outline_tol"):
        EngineSettings(outline_tol=-1e-4)
    assert EngineSettings.from_dict(EngineSettings(outline_tol=0, engine="pymunk").to_dict()) == FINE_CUT


def test_engine_scales_follow_the_size_and_period_of_the_arch():
    """Lengths are fractions of the size, durations of T = sqrt(size/g): an arch 100 times
    larger runs a 10 times longer step, the same steps per T, 100 times larger tolerances."""
    s = EngineSettings()
    a = oppenheim_arch()
    big = a.scaled(100.0)
    sa, sb = engine_scales(a, s), engine_scales(big, s)
    assert sa.time_scale == pytest.approx(math.sqrt(a.size / G), rel=1e-15)
    assert sa.dt == pytest.approx(sa.time_scale / 400.0, rel=1e-15)
    assert sb.dt == pytest.approx(10.0 * sa.dt, rel=1e-12)
    assert sb.time_scale / sb.dt == pytest.approx(sa.time_scale / sa.dt, rel=1e-12)
    for f in ("slop", "rounding", "outline_tol"):
        assert getattr(sb, f) == pytest.approx(100.0 * getattr(sa, f), rel=1e-12)
    assert sa.outline_tol == pytest.approx(2e-3 * 10.0, rel=1e-12)  # 2 cm on the 10 m arch
    ca = ContactArch(a, s.replace(steps_per_T=100))
    assert ca.dt == engine_scales(a, s.replace(steps_per_T=100)).dt
    assert ca.space.collision_slop == pytest.approx(sa.slop, rel=1e-15)


@pytest.mark.slow
def test_ramp_on_the_pointed_arch_simplified_against_the_fine_cut():
    """docs/verification.md, Contact engine: the same hinges and edges with both cuts; the
    simplified cut's activation within 1% of the fine cut's in each direction (measured +0.8%,
    +0.8%: the fine cut, 32 pieces a voussoir, is the more compliant and not even symmetric),
    within 2% of the limit analysis, and at least 3 times faster."""
    import time

    a = _pointed()
    lim = limit_analysis(a)
    t0 = time.perf_counter()
    fine = ramp(a, FINE_CUT, limit=lim)
    t1 = time.perf_counter()
    simple = ramp(a, EngineSettings(engine="pymunk"), limit=lim)
    t2 = time.perf_counter()
    assert simple.l.hinges == fine.l.hinges == (1, 5, 9, 12)
    assert simple.r.hinges == fine.r.hinges == (0, 3, 7, 11)
    assert simple.l.edges == fine.l.edges
    assert simple.r.edges == fine.r.edges
    for d in ("l", "r"):
        assert getattr(simple, f"k_{d}") == pytest.approx(getattr(fine, f"k_{d}"), rel=0.01)
        # within the engine's compliance of the limit analysis (k = 0.24868)
        assert getattr(simple, f"k_{d}") == pytest.approx(getattr(lim, f"k_{d}"), rel=0.02)
    assert (t1 - t0) > 3.0 * (t2 - t1)


def test_engine_friction_has_the_limit_analysis_range():
    """One friction field, one range (finite, > 0) in the limit analysis and the engine."""
    from archrock.contact.settings import EngineSettings
    from archrock.errors import ArchInputError
    from archrock.statics.friction import check_friction

    assert EngineSettings(friction=0.4).friction == check_friction(0.4)
    assert EngineSettings(friction=1e6).friction == pytest.approx(1e6, rel=1e-15)
    for bad in (0, -0.3, float("nan"), float("inf"), True):
        with pytest.raises(ArchInputError, match="friction"):
            EngineSettings(friction=bad)
    with pytest.raises(ArchInputError, match="allowed a finite friction coefficient > 0"):
        EngineSettings(friction=0)
