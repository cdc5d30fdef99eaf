"""The displaced arch (archrock.geometry.displaced): a support movement, rigid moves of the
voussoirs, point contacts at the open hinges."""

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch, polygon_properties, random_arch
from archrock.geometry.displaced import DisplacedArch, SupportMovement
from archrock.statics.supports import displace


def test_movement_validation_and_round_trip():
    mv = SupportMovement(0.02, -0.01, "both")
    assert SupportMovement.from_dict(mv.to_dict()) == mv
    ul, ur = mv.supports
    assert np.allclose(ul, [-0.01, 0.005], rtol=0, atol=1e-15)
    assert np.allclose(ur, [0.01, 0.005], rtol=0, atol=1e-15)
    assert np.allclose(mv.relative, [0.02, 0.0], rtol=0, atol=1e-15)
    assert np.allclose(SupportMovement(0.03, 0.01, "left").relative, [0.03, 0.01], atol=1e-15)
    with pytest.raises(ArchInputError, match="side"):
        SupportMovement(0.01, 0.0, "top")
    with pytest.raises(ArchInputError, match="spread"):
        SupportMovement(float("nan"))
    with pytest.raises(ArchInputError, match="settlement"):
        SupportMovement(0.0, 1e9)
    with pytest.raises(ArchInputError, match="spread"):
        SupportMovement.from_dict({"spread": 0.1, "tilt": 1})


@pytest.mark.parametrize("mv", [SupportMovement(0.3), SupportMovement(-0.2),
                                SupportMovement(0.0, 0.4), SupportMovement(0.2, 0.1, "left"),
                                SupportMovement(0.3, 0.0, "both")])
def test_rigid_moves_keep_blocks_and_hinge_distances(mv):
    arch = nominal_arch()
    st = displace(arch, mv)
    d = st.arch
    assert isinstance(d, DisplacedArch) and len(d.open_joints) == 3
    # areas, polar moments and masses are the base's; each block's moved outline has its area
    assert np.array_equal(d.areas, arch.areas) and np.array_equal(d.masses, arch.masses)
    for i in range(arch.n):
        a0, c0, j0 = polygon_properties(arch.outline(i))
        a1, c1, j1 = polygon_properties(d.outline(i))
        assert abs(a1 - a0) <= 1e-12 * a0 and abs(j1 - j0) <= 1e-12 * j0
    # open joints are points; the hinges' mutual distances are the base's
    jp = d.joint_points
    for j in d.open_joints:
        assert np.array_equal(jp[j, 0], jp[j, 1])
    base_pts = [arch.joint_point(h.joint, h.edge) for h in st.hinges]
    for a, b in ((0, 1), (1, 2)):
        L0 = np.hypot(*(base_pts[b] - base_pts[a]))
        L1 = np.hypot(*(st.points[b] - st.points[a]))
        assert abs(L1 - L0) <= 1e-12 * L0
    # the hinges at the supports' bodies moved exactly with their supports
    ul, ur = mv.supports
    assert np.allclose(st.points[0] - base_pts[0], ul, rtol=0, atol=1e-12 * arch.size)
    assert np.allclose(st.points[2] - base_pts[2], ur, rtol=0, atol=1e-12 * arch.size)
    # closed joints keep their lengths (their blocks move rigidly)
    L0 = np.hypot(*(arch.joint_points[:, 1] - arch.joint_points[:, 0]).T)
    L1 = np.hypot(*(jp[:, 1] - jp[:, 0]).T)
    closed = [j for j in range(arch.n + 1) if j not in d.open_joints]
    assert np.allclose(L1[closed], L0[closed], rtol=1e-12, atol=0)


def test_mirrored_displaced_arch_is_the_mirrored_arch_displaced():
    arch = random_arch(seed=3)
    mv = SupportMovement(0.25, 0.1, "right")
    a = displace(arch, mv).arch.mirrored()
    b = displace(arch.mirrored(), mv.mirrored()).arch
    assert a.open_joints == b.open_joints
    assert np.allclose(a.joint_points, b.joint_points, rtol=0, atol=1e-9 * arch.size)
    assert np.allclose(a.centroids, b.centroids, rtol=0, atol=1e-9 * arch.size)


def test_scaled_and_dict():
    arch = nominal_arch()
    d = displace(arch, SupportMovement(0.2)).arch
    s = d.scaled(2.0)
    assert np.allclose(s.joint_points, 2.0 * d.joint_points, rtol=1e-14, atol=1e-13)
    out = d.to_dict()["displaced"]
    assert out["movement"] == {"spread": 0.2, "settlement": 0.0, "side": "right"}
    assert len(out["point_joints"]) == 3
    with pytest.raises(ArchInputError, match="angles"):
        DisplacedArch(arch, (0.0,), ((0, 0),), ((0, 0),))


def test_contact_engine_takes_a_displaced_arch_with_point_springings():
    """Closing the span opens both springings (0e, 7e): the contact engine builds the supports
    from their own faces, and the displaced arch stands still in it."""
    pytest.importorskip("pymunk")
    from archrock.contact import ContactArch, EngineSettings

    arch = nominal_arch()
    d = displace(arch, SupportMovement(-0.05)).arch
    assert {0, 7} <= set(d.open_joints)
    faces = d.abutment_faces
    assert np.allclose(faces[1] - arch.joint_points[-1], [-0.05, 0.0], rtol=0, atol=1e-15)
    ca = ContactArch(d, EngineSettings(steps_per_T=150, iterations=20))
    assert np.all(np.isfinite(ca.joint_tangents))
    ca.settle()
    ca.step(0.0, int(ca.settings.steps_per_T))
    pos, ang, vel, rate = ca.state()
    assert np.abs(ang - ca.ref_ang).max() < 1e-4
    assert np.abs(pos - ca.ref_pos).max() < 1e-4 * arch.size
