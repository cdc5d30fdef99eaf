"""Support movements (archrock.statics.supports): the hinges they open, the exact displaced
three-hinge arch, its thrust against an independent equilibrium, the displacement capacity."""

import math

import numpy as np
import pytest

from archrock.errors import ArchInputError, CannotStandError
from archrock.geometry import family_arch, nominal_arch, random_arch, with_piers
from archrock.geometry.displaced import SupportMovement
from archrock.statics.hinges import Hinge
from archrock.statics.limit import limit_analysis
from archrock.statics.supports import (MAX_MOVEMENT, displace, displacement_capacity,
                                       onset_hinges)
from archrock.statics.thrust import thrust_range
from archrock.units import G


def test_zero_movement_is_the_undisplaced_arch_bit_for_bit():
    arch = nominal_arch()
    st = displace(arch, SupportMovement())
    assert st.arch is arch and st.hinges == ()
    r0, r1 = limit_analysis(arch), limit_analysis(st.arch)
    assert r1.k_l == r0.k_l and r1.k_r == r0.k_r
    assert abs(r1.k_l - 0.3700097) < 5e-7


def test_first_step_is_the_thrust_range():
    arch = nominal_arch()
    tr = thrust_range(arch)
    spread = displacement_capacity(arch, "spread")
    closure = displacement_capacity(arch, "closure")
    assert abs(spread.curve[0, 1] - tr.thrust_min) <= 1e-12 * tr.thrust_min
    assert abs(closure.curve[0, 1] - tr.thrust_max) <= 1e-12 * tr.thrust_max
    # Oppenheim's keystone: the least-thrust line touches both its joints; the hinge set is
    # the one nearer the moving (right) support, the other one for the left support
    assert set(spread.hinges) < set(tr.hinges_min)
    assert spread.hinges == (Hinge(1, "intrados"), Hinge(4, "extrados"), Hinge(6, "intrados"))
    assert onset_hinges(arch, SupportMovement(0.01, 0, "left")) == (
        Hinge(1, "intrados"), Hinge(3, "extrados"), Hinge(6, "intrados"))
    assert set(closure.hinges) < set(tr.hinges_max)
    # a crown joint (even number of voussoirs): exactly the thrust range's three hinges
    semi = nominal_arch(radius=1.0, embrace_deg=180, thickness=0.15, voussoirs=36)
    assert onset_hinges(semi, SupportMovement(0.01)) == thrust_range(semi).hinges_min
    # small steps: the thrust moves continuously away from the range's bound
    H = displace(arch, SupportMovement(1e-4)).thrust
    assert 0 < H - tr.thrust_min < 1e-3 * tr.thrust_min


def _hand_three_hinge(d):
    """H and V across the first hinge from the moments of the two middle bodies about the
    hinges (a plain equilibrium, not archrock's static program)."""
    (j1, *q1), (j2, *q2), (j3, *q3) = d.point_joints
    q1, q2, q3 = (np.array(q) for q in (q1, q2, q3))
    w = np.asarray(d.masses, float) * G
    c = np.asarray(d.centroids, float)
    b1, b2 = slice(j1, j2), slice(j2, j3)
    W1 = w[b1].sum()
    # body 1: force F = (H, V) at q1 from the left, weights; moments about q2
    #   (q1 - q2) x F - sum w (c_x - q2_x) = 0
    # body 2: force F + (0, -W1) at q2; moments about q3
    r1, r2 = q1 - q2, q2 - q3
    A = np.array([[-r1[1], r1[0]], [-r2[1], r2[0]]])
    b = np.array([np.sum(w[b1] * (c[b1, 0] - q2[0])),
                  np.sum(w[b2] * (c[b2, 0] - q3[0])) + r2[0] * W1])
    return np.linalg.solve(A, b)


@pytest.mark.parametrize("arch, mv", [
    (nominal_arch(), SupportMovement(0.5)),
    (nominal_arch(), SupportMovement(-0.3)),
    (nominal_arch(), SupportMovement(0.0, 0.8)),
    (random_arch(seed=7), SupportMovement(0.2, 0.3, "left")),
    (nominal_arch(radius=1.0, embrace_deg=180, thickness=0.2, voussoirs=36),
     SupportMovement(0.1, 0.0, "both")),
    (with_piers(nominal_arch(), 4.0, 2.0, courses=3), SupportMovement(0.1)),
    (family_arch("pointed", span=10, rise=7, thickness=1, voussoirs=12),
     SupportMovement(0.05, 0.1, "left")),
])
def test_thrust_matches_a_hand_written_three_hinge_statics(arch, mv):
    st = displace(arch, mv)
    H, V1 = _hand_three_hinge(st.arch)
    assert abs(st.thrust - H) <= 1e-9 * abs(H)
    # the line of thrust passes through the three point hinges
    jp = st.arch.joint_points
    for j in st.arch.open_joints:
        assert np.allclose(st.line.points[j], jp[j, 0], rtol=0, atol=1e-9 * arch.size)
    # global equilibrium: the vertical reactions carry the weight
    W = G * float(np.sum(arch.masses))
    assert abs(st.v_left + st.v_right - W) <= 1e-12 * W
    assert st.margin > 0


def test_mirror_symmetry():
    arch = random_arch(seed=11)
    mv = SupportMovement(0.3, 0.2, "left")
    a = displace(arch, mv)
    b = displace(arch.mirrored(), mv.mirrored())
    n = arch.n
    assert a.hinges == tuple(Hinge(n - h.joint, h.edge) for h in b.hinges[::-1])
    assert abs(a.thrust - b.thrust) <= 1e-10 * a.thrust
    assert abs(a.v_left - b.v_right) <= 1e-10 * a.v_left
    assert abs(a.crown_drop - b.crown_drop) <= 1e-10 * arch.size


def test_displaced_arch_limit_analysis():
    arch = nominal_arch()
    st = displace(arch, SupportMovement(0.05))
    r = limit_analysis(st.arch)
    # the kinematic four-hinge mechanism and the static LP (point contacts: the line through
    # the point hinges, in compression) agree
    assert r.discrepancy < 1e-9
    assert 0 < min(r.k_l, r.k_r) < limit_analysis(arch).k_l
    # the mirrored case swaps the multipliers
    r2 = limit_analysis(displace(arch, SupportMovement(0.05, 0, "left")).arch)
    assert abs(r2.k_l - r.k_r) <= 1e-9 and abs(r2.k_r - r.k_l) <= 1e-9


def test_capacity_bounded_reproducible_and_collapse_beyond_it():
    arch = nominal_arch()
    c1 = displacement_capacity(arch, "spread")
    c2 = displacement_capacity(arch, "spread")
    assert c1.capacity == c2.capacity and np.array_equal(c1.curve, c2.curve)
    assert 0 < c1.capacity < MAX_MOVEMENT * arch.size and c1.reason == "fourth hinge"
    assert len(c1.mechanism) == 4
    assert abs(c1.fraction * 2 * 10 * math.sin(math.radians(157.5 / 2)) - c1.capacity) < 1e-9
    # the curve: the thrust grows and the crown drops as the span opens
    assert np.all(np.diff(c1.curve[:, 0]) > 0) and np.all(np.diff(c1.curve[:, 4]) > 0)
    displace(arch, SupportMovement(0.999 * c1.capacity))
    with pytest.raises(CannotStandError, match="collapses"):
        displace(arch, SupportMovement(1.01 * c1.capacity))


@pytest.mark.slow
def test_semicircle_spreading_capacity_falls_with_thickness():
    caps = [displacement_capacity(nominal_arch(radius=1.0, embrace_deg=180, thickness=t,
                                               voussoirs=36), "spread").capacity
            for t in (0.12, 0.15, 0.2, 0.3)]
    assert all(a < b for a, b in zip(caps, caps[1:]))


def test_semicircle_spreading_capacity_falls_with_thickness_fast():
    caps = [displacement_capacity(nominal_arch(radius=1.0, embrace_deg=180, thickness=t,
                                               voussoirs=18), "spread").capacity
            for t in (0.13, 0.2)]
    assert 0 < caps[0] < caps[1]


def test_bad_input():
    arch = nominal_arch()
    with pytest.raises(ArchInputError, match="kind"):
        displacement_capacity(arch, "twist")
    with pytest.raises(ArchInputError, match="side"):
        displacement_capacity(arch, "spread", "top")
    with pytest.raises(ArchInputError, match="rigid translation"):
        displacement_capacity(arch, "settlement", "both")
    with pytest.raises(ArchInputError, match="already displaced"):
        displace(displace(arch, SupportMovement(0.1)).arch, SupportMovement(0.1))
    # both supports settling alike: a rigid translation, no hinge
    st = displace(arch, SupportMovement(0.0, 0.1, "both"))
    assert st.hinges == () and abs(st.crown_drop - 0.05) < 1e-15


def test_reclosed_geometry_and_closing_hinges():
    from archrock.statics.supports import closing_hinges, reclosed

    arch = nominal_arch()
    k0 = limit_analysis(arch).k_l
    st = displace(arch, SupportMovement(1e-6))
    r = limit_analysis(st.arch)
    # the point contacts: a mechanism that turns the keystone's open joint back governs M_l
    assert 4 in closing_hinges(st.arch, r.mechanism_l)
    # re-closed, the geometry has hardly changed: k is continuous at zero movement
    rc = limit_analysis(reclosed(st.arch))
    assert abs(rc.k_l - k0) < 1e-4 and abs(rc.k_r - k0) < 1e-4
    assert reclosed(st.arch).open_joints == ()


def test_symmetric_spread_moves_the_crown_hinge_as_the_closed_form():
    """Both supports of a semicircle with a crown joint spread by s/2 each: by symmetry the
    crown hinge stays on the axis, at the height where each half-link (from the haunch hinge
    moved by s/2 to the crown) keeps its length."""
    R, t, s = 1.0, 0.2, 0.15
    arch = nominal_arch(radius=R, embrace_deg=180, thickness=t, voussoirs=36)
    st = displace(arch, SupportMovement(s, 0.0, "both"))
    assert [h.joint for h in st.hinges] == [6, 18, 30]
    h1 = arch.joint_point(6, "intrados")
    crown = arch.joint_point(18, "extrados")
    link = math.hypot(*(crown - h1))
    x1 = h1[0] - s / 2
    y = h1[1] + math.sqrt(link ** 2 - x1 ** 2)
    assert abs(st.points[1][0]) <= 1e-12 and abs(st.points[1][1] - y) <= 1e-12
    assert np.allclose(st.points[0], h1 + [-s / 2, 0.0], rtol=0, atol=1e-15)
