"""Brick arches of several rings (geometry/rings.py): the bricks, their bond, the ring
interfaces' contacts and the arcade document's round trip."""

from __future__ import annotations

import math

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.geometry.arcade import Arcade, Contact
from archrock.geometry.files import read_arcade, write_arcade
from archrock.geometry.rings import (DEFAULT_RING_FRICTION, interface_contacts, ring_of,
                                     ringed_arch)

R, T, BRICK = 2.5, 0.43, 0.5  # 16 bricks a ring: fast
N = round(math.pi * R / BRICK)


def test_counts_staggered_and_aligned():
    a = ringed_arch(R, T, rings=2, brick=BRICK)
    assert N == 16
    assert a.n_blocks == N + (N + 1)  # the second ring: half bricks at both springings
    assert len(interface_contacts(a)) == 2 * N  # each brick meets two of the other ring
    b = ringed_arch(R, T, rings=2, brick=BRICK, stagger=False)
    assert b.n_blocks == 2 * N and len(interface_contacts(b)) == N
    three = ringed_arch(R, T, rings=3, brick=BRICK)
    assert three.n_blocks == N + (N + 1) + N
    assert len(interface_contacts(three)) == 4 * N


def test_mass_equals_the_one_ring_arch():
    mono = nominal_arch(radius=R, embrace_deg=180.0, thickness=T, voussoirs=N).masses.sum()
    for rings, ts in ((1, None), (2, None), (3, (0.1, 0.2, 0.13))):
        a = ringed_arch(R, T, rings=rings, ring_thicknesses=ts, brick=BRICK)
        assert a.masses.sum() == pytest.approx(mono, rel=1e-12)
        # the polygons (chords on the interfaces) hold the same area to the arcs' sampling
        area = sum(abs(_area(b.outline)) for b in a.blocks)
        assert area * a.density == pytest.approx(mono, rel=2e-4)


def _area(p):
    x, y = np.asarray(p, float).T
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def test_no_joint_runs_through_when_bonded():
    a = ringed_arch(R, T, rings=2, brick=BRICK)
    ang = {1: [], 2: []}
    for ct in a.contacts:
        if " joint " in ct.label:
            p = ct.points[0]
            ang[int(ct.label.split()[1])].append(math.atan2(p[1], p[0]))
    gap = min(abs(x - y) for x in ang[1] for y in ang[2])
    assert gap == pytest.approx(0.5 * math.pi / N, rel=1e-9)  # half a brick apart everywhere


def test_labels_kinds_and_one_ring_is_the_voussoir_arch():
    a = ringed_arch(R, T, rings=2, brick=BRICK)
    assert set(a.kinds) == {"voussoir"}
    assert a.blocks[N + 13].label == "ring 2 brick 14" and ring_of("ring 2 brick 14") == 2
    assert a.contacts[0].label == "ring 1 left springing"
    assert a.contacts[-1].label == f"rings 1-2 interface {2 * N}"
    one = ringed_arch(R, T, rings=1, brick=BRICK)
    arch = nominal_arch(radius=R, embrace_deg=180.0, thickness=T, voussoirs=N)
    for i, b in enumerate(one.blocks):
        assert np.allclose(b.outline, arch.outline(i), rtol=0, atol=1e-14)
    assert np.allclose([c.points for c in one.contacts], arch.joint_points, rtol=0, atol=1e-15)
    assert interface_contacts(one) == []


def test_interfaces_carry_their_friction_and_the_file_keeps_it(tmp_path):
    a = ringed_arch(R, T, rings=2, brick=BRICK, friction=0.6, cohesion=2e3)
    faces = interface_contacts(a)
    assert all(a.contacts[c].friction == 0.6 and a.contacts[c].cohesion == 2e3 for c in faces)
    assert all(ct.friction is None for c, ct in enumerate(a.contacts) if c not in faces)
    assert ringed_arch(R, T, brick=BRICK).contacts[faces[0]].friction == DEFAULT_RING_FRICTION
    back = read_arcade(write_arcade(a, tmp_path / "rings.json"))
    assert back.to_dict() == a.to_dict()
    assert back.mirrored().contacts[faces[0]].friction == 0.6
    # a contact without its own friction writes nothing new: old documents stay as they were
    assert set(a.contacts[0].to_dict()) == {"a", "b", "points", "label", "ends"}


@pytest.mark.parametrize("kw, field", [
    ({"rings": 0}, "rings"), ({"rings": 21}, "rings"),
    ({"ring_thicknesses": (0.2, 0.2)}, "ring_thicknesses"),
    ({"ring_thicknesses": (0.43,)}, "ring_thicknesses"),
    ({"brick": 0.0}, "brick"), ({"brick": 1e-4}, "brick"),
    ({"friction": -1.0}, "friction"), ({"cohesion": -5.0}, "cohesion"),
    ({"friction": None, "cohesion": 1e3}, "cohesion"),
])
def test_bad_input_names_the_field(kw, field):
    with pytest.raises(ArchInputError, match=f"^{field}"):
        ringed_arch(R, T, **{"brick": BRICK, **kw})


def test_contact_friction_is_checked():
    a = ringed_arch(R, T, rings=1, brick=BRICK)
    cts = list(a.contacts)
    cts[3] = Contact(cts[3].a, cts[3].b, cts[3].points, cts[3].label, cts[3].ends, 0.0)
    with pytest.raises(ArchInputError, match=r"^contacts\[3\]\.friction"):
        Arcade(a.blocks, tuple(cts))
    cts[3] = Contact(cts[3].a, cts[3].b, cts[3].points, cts[3].label, cts[3].ends, None, 10.0)
    with pytest.raises(ArchInputError, match=r"^contacts\[3\]\.cohesion"):
        Arcade(a.blocks, tuple(cts))


def test_headers_tie_the_rings_symmetrically():
    a = ringed_arch(R, T, rings=2, brick=BRICK, headers=4)
    heads = [i for i, b in enumerate(a.blocks) if b.label.startswith("header")]
    assert len(heads) == 4  # places 3 and 7 from the left, 8 and 12 their mirrors
    # a header takes one brick of each ring (the staggered ring's two halves stay beside it);
    # the two side by side at the crown take the staggered brick between them too
    assert a.n_blocks == ringed_arch(R, T, rings=2, brick=BRICK).n_blocks - 1
    mono = nominal_arch(radius=R, embrace_deg=180.0, thickness=T, voussoirs=N).masses.sum()
    assert a.masses.sum() == pytest.approx(mono, rel=1e-12)
    xs = sorted(round(float(a.centroids[i][0]), 9) for i in heads)
    assert xs == sorted(-x for x in xs)  # mirror-symmetric about the crown
    # no interface inside a header; each header meets each ring's bricks on both sides
    for h in heads:
        touching = [ct for ct in a.contacts if h in (ct.a, ct.b)]
        assert all(not ct.label.startswith("rings ") for ct in touching)
        assert len(touching) >= 2 * 2 - 1  # 2 rings x 2 sides (a side may meet a header)
    with pytest.raises(ArchInputError, match="^headers"):
        ringed_arch(R, T, rings=2, brick=BRICK, headers=1)
