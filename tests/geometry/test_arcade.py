"""Arcades (archrock.geometry.arcade): the builder, the block graph's checks, the file document."""

import json

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import family_arch, nominal_arch, with_piers
from archrock.geometry.arcade import GROUND, Arcade, Block, Contact, arcade, arcade_from_chain
from archrock.geometry.files import read_arcade, read_arch, write_arcade


@pytest.fixture(scope="module")
def semicircle():
    return nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9)


def test_one_span_is_the_chain_of_with_piers(semicircle):
    """Block for block and joint for joint, the chain with_piers builds: the same masses,
    centres and inertias to rounding (the arcade builds its piers by its own code), the same
    joints (to 1e-15 m: the springing joint is the
    arch's own face here, the overlap of two faces there)."""
    for arch, kw in ((semicircle, dict(courses=2)),
                     (family_arch("pointed", 10, 7, 0.9, 10), dict(courses=3)),
                     (semicircle, dict(courses=1))):
        chain = with_piers(arch, 4.0, 2.0, **kw)
        arc = arcade([arch], 4.0, 2.0, **kw)
        assert arc.n_blocks == chain.n and len(arc.contacts) == chain.n + 1
        np.testing.assert_allclose(arc.masses, chain.masses, rtol=1e-12)
        np.testing.assert_allclose(arc.centroids, chain.centroids, rtol=0,
                                   atol=1e-12 * chain.size)
        np.testing.assert_allclose(arc.inertias, chain.inertias, rtol=1e-12)
        assert arc.kinds == chain.block_kinds
        jp = np.asarray(chain.joint_points)
        for j, c in enumerate(arc.contacts):
            assert np.abs(c.points - jp[j]).max() < 1e-15 * chain.size
            assert (c.a, c.b) == (GROUND if j == 0 else j - 1, j) or (j == chain.n and
                                                                      (c.a, c.b) == (GROUND, j - 1))


def test_three_spans_share_their_piers(semicircle):
    arc = arcade([semicircle] * 3, [4.0, 5.0, 5.0, 4.0], [2.0, 1.8, 1.8, 2.0],
                 courses=[1, 2, 2, 1])
    assert len(arc.spans) == 3 and len(arc.piers) == 4
    assert [len(p) for p in arc.piers] == [1, 2, 2, 1]
    assert arc.n_blocks == 27 + 6
    # an inner pier's top course touches both springers, the course under it and nothing else
    top = arc.piers[1][0]
    touching = {arc._other(c, top) for c in arc.contacts_of(top)}
    assert touching == {arc.spans[0][-1], arc.spans[1][0], arc.piers[1][1]}
    # the piers' widths: the clear distance between the intrados springings
    jr = arc.contacts[[c for c in arc.contacts_of(top)
                       if arc._other(c, top) == arc.spans[0][-1]][0]].points
    jl = arc.contacts[[c for c in arc.contacts_of(top)
                       if arc._other(c, top) == arc.spans[1][0]][0]].points
    assert jl[0][0] - jr[0][0] == pytest.approx(1.8, abs=1e-12)
    # foundations at the pier heights below the common springing level
    feet = [c for c in arc.contacts if c.a == GROUND]
    assert [c.label for c in feet] == [f"pier {p} foot" for p in (1, 2, 3, 4)]
    assert [c.points[0][1] for c in feet] == pytest.approx([-4.0, -5.0, -5.0, -4.0], abs=1e-12)
    # mass: three arches and four piers (the inner top course keeps its full rectangle)
    pier_area = 4 * 2 * 2 + 2 * 5 * 1.8
    arch_area = 3 * float(np.sum(with_piers(semicircle, 1, 1).areas[1:-1]))
    assert arc.masses.sum() == pytest.approx(arc.density * (pier_area + arch_area), rel=1e-12)
    # normals from a into b: the foundations push up, a right springing pushes down on its pier
    n = arc.contact_normals
    for c, ct in enumerate(arc.contacts):
        if ct.a == GROUND:
            assert n[c] == pytest.approx([0.0, 1.0])
        if "right springing" in ct.label:
            assert n[c] == pytest.approx([0.0, -1.0], abs=1e-12)


def test_labels_name_piers_and_spans(semicircle):
    arc = arcade([semicircle] * 2, 4.0, 2.0, courses=2)
    labels = [c.label for c in arc.contacts]
    assert labels[:3] == ["pier 1 foot", "pier 1 bed joint 1",
                          "span 1 left springing (pier 1 top)"]
    assert "pier 2 bed joint 1" in labels and "span 2 joint 4" in labels
    inner = [c for c in arc.contacts if c.label == "pier 2 foot"][0]
    assert inner.place(1) == "pier 2 foot, right face"
    end = [c for c in arc.contacts if c.label == "pier 3 foot"][0]
    assert end.place(1) == "pier 3 foot, outer face"
    assert [arc.blocks[i].label for i in arc.piers[1]] == ["pier 2 course 2", "pier 2 course 1"]


def test_file_round_trip_to_the_bit(tmp_path, semicircle):
    arc = arcade([semicircle, family_arch("pointed", 10, 7, 0.9, 10)], [4.0, 5.0, 4.5],
                 [2.0, 2.4, 2.0], courses=[1, 3, 2])
    p = write_arcade(arc, tmp_path / "two.json", metadata={"note": "test"})
    back = read_arcade(p)
    assert back.name == "two"
    assert np.array_equal(back.masses, arc.masses)
    assert np.array_equal(back.centroids, arc.centroids)
    assert back.to_dict() == arc.to_dict()
    assert back.spans == arc.spans and back.piers == arc.piers
    # an arcade from a chain keeps a circular arch's exact sectors in the file
    opp = arcade_from_chain(nominal_arch())
    back = read_arcade(write_arcade(opp, tmp_path / "opp.json"))
    assert np.array_equal(back.masses, nominal_arch().masses)
    # read_arch refuses an arcade document by name
    with pytest.raises(ArchInputError, match="an arcade document"):
        read_arch(p)


def _doc(**change):
    sq = [[0, 0], [1, 0], [1, 1], [0, 1]]
    d = {"kind": "arcade", "blocks": [{"kind": "pier", "outline": sq}],
         "contacts": [{"a": -1, "b": 0, "points": [[0, 0], [1, 0]]}]}
    d.update(change)
    return d


@pytest.mark.parametrize("change, match", [
    ({"kind": "arch"}, "kind: 'arch'; allowed 'arcade'"),
    ({"blocks": []}, "blocks: expected a non-empty list"),
    ({"blocks": [{"kind": "wall", "outline": [[0, 0], [1, 0], [1, 1]]}]},
     r"blocks\[0\].kind: 'wall'; allowed voussoir, pier, buttress, beam"),
    ({"blocks": [{"outline": [[0, 0], [1, 1], [1, 0], [0, 1]]}]}, "intersects itself"),
    ({"blocks": [{"outline": [[0, 0], [1, 0]]}]}, "at least 3 points"),
    ({"contacts": [{"a": -2, "b": 0, "points": [[0, 0], [1, 0]]}]},
     r"contacts\[0\].a: -2; allowed a block index -1 to 0"),
    ({"contacts": [{"a": -1, "b": 3, "points": [[0, 0], [1, 0]]}]}, r"contacts\[0\].b: 3"),
    ({"contacts": [{"a": -1, "b": 0, "points": [[0, 0], [0, 0]]}]}, "its two ends coincide"),
    ({"contacts": [{"a": -1, "b": 0, "points": [[0, -0.5], [1, -0.5]]}]},
     r"an end is 0.5 m off block 0's boundary"),
    ({"colour": "red"}, r"unknown fields \['colour'\]"),
])
def test_bad_documents_are_refused_by_field(change, match):
    with pytest.raises(ArchInputError, match=match):
        Arcade.from_dict(_doc(**change))


def test_floating_and_lonely_blocks_are_refused():
    sq = [(0, 0), (1, 0), (1, 1), (0, 1)]
    up = [(0, 2), (1, 2), (1, 3), (0, 3)]
    up2 = [(0, 3), (1, 3), (1, 4), (0, 4)]
    base = Contact(GROUND, 0, [(0, 0), (1, 0)])
    with pytest.raises(ArchInputError, match="block 1 .* touches nothing"):
        Arcade((Block(sq), Block(up)), (base,))
    with pytest.raises(ArchInputError, match="block 1 is not connected to the ground"):
        Arcade((Block(sq), Block(up), Block(up2)),
               (base, Contact(1, 2, [(0, 3), (1, 3)])))


def test_builder_refusals(semicircle):
    with pytest.raises(ArchInputError, match=r"widths\[1\]: pier 2 is 1.2 m wide, narrower"):
        arcade([semicircle] * 2, 4.0, [2.0, 1.2, 2.0])
    with pytest.raises(ArchInputError, match=r"heights: 2 values; allowed one for all, or 4"):
        arcade([semicircle] * 3, [4.0, 4.0], 2.0)
    with pytest.raises(ArchInputError, match=r"heights\[1\]: .*allowed > 0 m"):
        arcade([semicircle] * 2, [4.0, 0.0, 4.0], 2.0)
    with pytest.raises(ArchInputError, match=r"courses\[0\]: 0 is out of range"):
        arcade([semicircle], 4.0, 2.0, courses=0)
    with pytest.raises(ArchInputError, match=r"already on piers"):
        arcade([with_piers(semicircle, 4, 2)], 4.0, 2.0)


def test_mirror_of_a_symmetric_arcade(semicircle):
    arc = arcade([semicircle] * 3, [4.0, 6.0, 6.0, 4.0], [2.0, 1.8, 1.8, 2.0])
    m = arc.mirrored()
    pts = np.vstack([b.outline for b in arc.blocks])
    shift = np.array([pts[:, 0].min() + pts[:, 0].max(), 0.0])  # mirrored about its middle
    mc = m.centroids + shift
    order = np.lexsort((np.round(mc[:, 1], 6), np.round(mc[:, 0], 6)))
    orig = np.lexsort((np.round(arc.centroids[:, 1], 6), np.round(arc.centroids[:, 0], 6)))
    assert np.allclose(m.masses[order], arc.masses[orig], rtol=1e-12)
    assert np.allclose(mc[order], arc.centroids[orig], atol=1e-9)
    assert json.dumps(m.to_dict())  # serialisable


def test_strength_per_kind_and_its_document(semicircle, tmp_path):
    """fc per kind of block: a contact takes its weaker block's (a pier's foot the pier's),
    the document holds it only when set (a Heyman arcade's file is what it was) and reads it
    back; a bad one is one line naming the field."""
    arc = arcade([semicircle], 4.0, 2.0)
    strong = arc.with_fc({"voussoir": 5, "pier": 2, "beam": None})
    assert strong.fc == {"voussoir": 5.0, "pier": 2.0}
    cf = strong.contact_fc
    kinds = strong.kinds
    for c, ct in enumerate(strong.contacts):
        sides = [kinds[i] for i in (ct.a, ct.b) if i != GROUND]
        assert cf[c] == (2.0 if "pier" in sides else 5.0)
    assert json.dumps(arc.to_dict()) == json.dumps(strong.with_fc(None).to_dict())
    assert "fc" not in arc.to_dict()
    back = read_arcade(write_arcade(strong, tmp_path / "a.json"))
    assert back.fc == strong.fc and np.array_equal(back.contact_fc, cf)
    assert strong.mirrored().fc == strong.fc
    assert np.all(np.isinf(arc.contact_fc))
    for bad, msg in (({"pier": 0.01}, "fc.pier: 0.01 is out of range; allowed 0.1 to 1000 MPa"),
                     ({"wall": 3}, "fc: kind 'wall'; allowed voussoir, pier"),
                     ("3", "fc: expected a number (MPa)")):
        with pytest.raises(ArchInputError, match=msg.replace("(", r"\(").replace(")", r"\)")):
            arc.with_fc(bad)
    doc = strong.to_dict()
    doc["fc"] = {"pier": -1}
    with pytest.raises(ArchInputError, match="fc.pier: -1 is out of range"):
        Arcade.from_dict(doc)
