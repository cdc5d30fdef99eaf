"""A support (abutment or pier) that turns about its foot: SupportMovement(rotation=...,
pivot_depth=...), the exact displaced arch, its thrust against a hand-written three-hinge
statics and a virtual-work balance, and the displacement capacity in rotation
(docs/supports.md, "Rotation of a pier or abutment")."""

import math

import numpy as np
import pytest

from archrock.errors import ArchInputError, CannotStandError
from archrock.geometry import nominal_arch, with_piers
from archrock.geometry.displaced import SupportMovement
from archrock.statics.supports import displace, displacement_capacity, movement_capacity
from archrock.units import G

OPP = nominal_arch()
PIERS = with_piers(nominal_arch(), 4.0, 2.0)
SEMI = nominal_arch(radius=10.0, embrace_deg=180, thickness=2.0, voussoirs=16)


def _rot(a):
    return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])


def _hand(d):
    """(H, V) across the first hinge, from the moments of the two middle bodies about the
    other hinges (plain equilibrium), and the crossing fraction s of every closed joint by the
    resultant built from it (s in [0, 1]: inside; tests/statics/test_supports.py's method)."""
    (j1, *q1), (j2, *q2), (j3, *q3) = d.point_joints
    q1, q2, q3 = (np.array(q) for q in (q1, q2, q3))
    w = np.asarray(d.masses, float) * G
    c = np.asarray(d.centroids, float)
    b1, b2 = slice(j1, j2), slice(j2, j3)
    r1, r2 = q1 - q2, q2 - q3
    A = np.array([[-r1[1], r1[0]], [-r2[1], r2[0]]])
    b = np.array([np.sum(w[b1] * (c[b1, 0] - q2[0])),
                  np.sum(w[b2] * (c[b2, 0] - q3[0])) + r2[0] * w[b1].sum()])
    F = np.linalg.solve(A, b)
    jp = np.asarray(d.joint_points, float)
    M1 = q1[0] * F[1] - q1[1] * F[0]  # counter-clockwise moment about the origin
    s = {}
    for j in range(d.n + 1):
        if j >= j1:
            Fj = F - np.array([0.0, w[j1:j].sum()])
            Mj = M1 - np.sum(w[j1:j] * c[j1:j, 0])
        else:
            Fj = F + np.array([0.0, w[j:j1].sum()])
            Mj = M1 + np.sum(w[j:j1] * c[j:j1, 0])
        a, e = jp[j, 0], jp[j, 1] - jp[j, 0]
        if np.hypot(*e) == 0:
            continue
        cross = lambda u, v: u[0] * v[1] - u[1] * v[0]  # noqa: E731
        s[j] = (Mj - cross(a, Fj)) / cross(e, Fj)
    return F, s


def test_movement_fields_validated_and_written_only_when_set():
    mv = SupportMovement(0.1, rotation=0.02, pivot_depth=3.0, side="left")
    assert SupportMovement.from_dict(mv.to_dict()) == mv
    assert SupportMovement(0.1).to_dict() == {"spread": 0.1, "settlement": 0.0, "side": "right"}
    assert mv.scaled(0.5) == SupportMovement(0.05, 0.0, "left", 0.01, 3.0)
    assert mv.mirrored().side == "right" and mv.mirrored().rotation == 0.02
    assert not mv.is_zero and SupportMovement(rotation=0.0).is_zero
    assert "rotation +0.02 rad outward" in mv.describe()
    for kw, field in (({"rotation": 0.6}, "rotation"), ({"rotation": math.nan}, "rotation"),
                      ({"pivot_depth": -1.0}, "pivot_depth"), ({"rotation": "x"}, "rotation")):
        with pytest.raises(ArchInputError, match=f"^{field}"):
            SupportMovement(**kw)
    # an inward turn about the springing's own outer corner moves nothing of the arch
    with pytest.raises(ArchInputError, match="inward"):
        displace(OPP, SupportMovement(rotation=-0.01))


def test_zero_rotation_is_the_translation_bit_for_bit():
    a, b = displace(OPP, SupportMovement(0.05)), displace(OPP, SupportMovement(0.05, rotation=0.0))
    assert a.thrust == b.thrust and np.array_equal(a.arch.centroids, b.arch.centroids)


@pytest.mark.parametrize("arch, mv", [
    (OPP, SupportMovement(rotation=0.01)),
    (OPP, SupportMovement(rotation=-0.01, pivot_depth=3.0)),
    (OPP, SupportMovement(0.05, rotation=0.02, side="left")),
    (PIERS, SupportMovement(rotation=0.01)),
    (PIERS, SupportMovement(rotation=-0.01, pivot_depth=1.0, side="left")),
    (SEMI, SupportMovement(rotation=0.02, side="both")),
])
def test_rigid_support_motion_and_hand_statics(arch, mv):
    st = displace(arch, mv)
    d = st.arch
    (tl, cl, ul), (tr, cr, ur) = mv.rigid_motions(arch.joint_points)
    (j1, *q1), _, (j3, *q3) = d.point_joints
    P = np.asarray(arch.joint_points, float)
    # h1 and h3 ride on their supports' rigid motions, exactly; the bodies between a support
    # and its hinge turn with it (a pier about its outer foot, which stays where it was)
    hinge_pt = {h.joint: P[h.joint, 0 if h.edge == "intrados" else 1] for h in d.hinges}
    np.testing.assert_allclose(q1, _rot(tl) @ (hinge_pt[j1] - cl) + cl + ul, atol=1e-12 * 30)
    np.testing.assert_allclose(q3, _rot(tr) @ (hinge_pt[j3] - cr) + cr + ur, atol=1e-12 * 30)
    for i in range(arch.n):
        if i >= j3:
            assert d.angles[i] == tr
            np.testing.assert_allclose(d.outline(i), (arch.outline(i) - cr) @ _rot(tr).T + cr + ur,
                                       atol=1e-12 * 30)
        if i < j1:
            assert d.angles[i] == tl
    if arch is PIERS and mv.side == "right":
        foot = P[-1][np.argmax(P[-1][:, 0])]
        assert np.any(np.all(np.abs(d.outline(arch.n - 1) - foot) < 1e-12 * 30, axis=1))
    # the thrust through the three point hinges by hand equals the LP's, and its line lies
    # inside every closed joint
    F, s = _hand(d)
    assert abs(st.thrust - F[0]) <= 1e-9 * abs(F[0])
    assert min(s.values()) > -1e-9 and max(s.values()) < 1 + 1e-9


@pytest.mark.parametrize("arch, mv", [(OPP, SupportMovement(rotation=1e-3)),
                                      (OPP, SupportMovement(rotation=1e-3, pivot_depth=3.0)),
                                      (PIERS, SupportMovement(rotation=1e-3)),
                                      (SEMI, SupportMovement(0.01, rotation=2e-3, side="left"))])
def test_virtual_work_of_the_turning_support(arch, mv):
    """Over a small further turn the arch's potential energy falls by the work its forces do on
    the supports (the line of thrust's force at its crossing of the support's joint, moved with
    the support's rigid motion): kinematics and statics checked against each other."""
    st = displace(arch, mv)
    eps = 1e-6
    st2 = displace(arch, mv.scaled(1 + eps))
    V = lambda a: G * float(np.sum(a.masses * a.centroids[:, 1]))  # noqa: E731
    dV = V(st2.arch) - V(st.arch)
    # the increments of the supports' motions (turns about the feet c, now at c + u)
    (tl, cl, ul), (tr, cr, ur) = mv.scaled(eps).rigid_motions(arch.joint_points)
    (_, _, Ul), (_, _, Ur) = mv.rigid_motions(arch.joint_points)
    line = st.line
    W = G * float(np.sum(arch.masses))
    F0, Fn = line.forces[0] * W, line.forces[-1] * W
    p0, pn = line.points[0], line.points[-1]
    perp = lambda r: np.array([-r[1], r[0]])  # noqa: E731
    work = Fn @ (ur + tr * perp(pn - (cr + Ur))) - F0 @ (ul + tl * perp(p0 - (cl + Ul)))
    assert abs(work + dV) <= 2e-4 * abs(dV) + 1e-9 * W * arch.size * eps


@pytest.mark.parametrize("arch, expected, fourth", [
    pytest.param(OPP, 0.22499, "7e", marks=pytest.mark.slow), (PIERS, 0.033263, "9e")])
def test_rotation_capacity_and_its_fourth_hinge_by_hand(arch, expected, fourth):
    cap = displacement_capacity(arch, "rotation")
    assert cap.capacity == pytest.approx(expected, rel=1e-4)
    assert cap.reason == "fourth hinge" and cap.fraction is None
    assert f"{cap.mechanism[-1].joint}{cap.mechanism[-1].edge[0]}" == fourth
    j4 = cap.mechanism[-1].joint
    # the hand statics: just below, the line is inside joint j4; just above, it leaves it
    below = _hand(displace(arch, SupportMovement(rotation=cap.capacity * (1 - 1e-4))).arch)[1]
    assert 0 < min(below[j4], 1 - below[j4]) < 1e-2
    with pytest.raises(CannotStandError):
        displace(arch, SupportMovement(rotation=cap.capacity * (1 + 1e-4)))
    assert movement_capacity(arch, SupportMovement(rotation=0.01)).capacity == cap.capacity


def test_mirror_symmetry_of_a_turning_support():
    from archrock.geometry import random_arch

    arch = random_arch(seed=7)
    a = displace(arch, SupportMovement(0.02, rotation=0.01, side="left", pivot_depth=1.0))
    b = displace(arch.mirrored(), SupportMovement(0.02, rotation=0.01, pivot_depth=1.0))
    n = arch.n
    assert [(n - h.joint, h.edge) for h in a.hinges[::-1]] == [(h.joint, h.edge)
                                                                for h in b.hinges]
    assert abs(a.thrust - b.thrust) <= 1e-10 * a.thrust
    assert abs(a.v_left - b.v_right) <= 1e-10 * a.v_left
