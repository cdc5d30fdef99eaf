"""Overlapping blocks in an arcade document (archrock.geometry.overlap): refused by name."""

from __future__ import annotations

import copy

import pytest

from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.geometry.arcade import Arcade, arcade
from archrock.geometry.overlap import find_overlap


@pytest.fixture(scope="module")
def two_spans():
    """Two semicircles of span 4 m (t 0.4 m, 5 voussoirs) on piers 3 m high, 1 m wide."""
    a = nominal_arch(radius=2, embrace_deg=180, thickness=0.4, voussoirs=5)
    return arcade([a, a], [3], [1]).to_dict()


def test_document_of_the_builder_has_no_overlap(two_spans):
    arc = Arcade.from_dict(two_spans)
    assert find_overlap([b.outline for b in arc.blocks], 1e-3) is None


def test_inner_pier_narrower_than_its_springings(two_spans, narrowed_pier):
    # pier 2 goes from 1 m to 0.5 m wide: the two 0.4 m springing joints overlap by 0.3 m
    with pytest.raises(ArchInputError) as err:
        Arcade.from_dict(narrowed_pier(two_spans, 0.5))
    msg = str(err.value)
    assert msg.startswith("blocks: block 5 (span 1 voussoir 5) and block 7 (span 2 voussoir 1) "
                          "overlap by ")
    assert ("inner pier 2 is 0.5 m wide, narrower than the two springing joints it carries "
            "(0.8 m)") in msg
    depth = float(msg.split("overlap by ")[1].split()[0])
    assert 0.1 < depth < 0.31


def test_pier_just_wide_enough_is_accepted(two_spans, narrowed_pier):
    # 0.2 m narrower: 0.8 m, exactly the two springing joints; they touch, no overlap
    arc = Arcade.from_dict(narrowed_pier(two_spans, 0.2))
    assert arc.n_blocks == 13


def test_duplicated_block(two_spans):
    d = copy.deepcopy(two_spans)
    d["blocks"].append(copy.deepcopy(d["blocks"][3]))
    d["contacts"].append({**copy.deepcopy(d["contacts"][3]), "b": len(d["blocks"]) - 1})
    with pytest.raises(ArchInputError, match=r"^blocks: block 13 \(span 1 voussoir 3\) "
                                             r"duplicates block 3 \(span 1 voussoir 3\)"):
        Arcade.from_dict(d)
