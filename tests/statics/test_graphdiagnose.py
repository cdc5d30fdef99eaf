"""An arcade whose static program has no answer: the message names the block or contact
(archrock.statics.graphdiagnose through graph_limit)."""

from __future__ import annotations

import copy

import pytest

from archrock.errors import ArchInputError, CannotStandError
from archrock.geometry import nominal_arch
from archrock.geometry.arcade import Arcade, Block, arcade
from archrock.statics.graph import graph_limit


@pytest.fixture(scope="module")
def two_spans():
    a = nominal_arch(radius=2, embrace_deg=180, thickness=0.4, voussoirs=5)
    return arcade([a, a], [3], [1])


def test_sound_arcade_still_answers(two_spans):
    g = graph_limit(two_spans, "l")
    assert abs(g.k - 0.163638) < 1e-6


def test_load_far_from_its_block(two_spans):
    d = copy.deepcopy(two_spans.to_dict())
    d["blocks"][3].pop("mass_properties", None)
    d["blocks"][3]["loads"] = [{"mass": 5000, "at": [100, 0]}]
    arc = Arcade.from_dict(d)
    with pytest.raises(ArchInputError) as err:
        graph_limit(arc, "l")
    assert str(err.value).startswith("blocks[3].loads[0]: 5000 kg/m at (100, 0) m, 99.33 m "
                                     "outside block 3 (span 1 voussoir 3)")


def test_duplicated_block_built_in_python(two_spans):
    """A block given twice (the document reader refuses it; a Python-built arcade reaches the
    program): the failure names the two blocks."""
    blocks = list(two_spans.blocks) + [two_spans.blocks[3]]
    extra = copy.copy(two_spans.contacts[3])
    object.__setattr__(extra, "b", len(blocks) - 1)
    arc = Arcade(tuple(blocks), tuple(two_spans.contacts) + (extra,), spans=two_spans.spans,
                 piers=two_spans.piers)
    try:
        graph_limit(arc, "l")
    except ArchInputError as exc:
        assert str(exc).startswith("blocks: block 13 (span 1 voussoir 3) duplicates block 3")
    else:  # the program may hold the doubled block: then nothing is wrong with it
        pytest.fail("a duplicated block was analysed without a word")


def test_every_contact_on_the_ground(two_spans):
    d = copy.deepcopy(two_spans.to_dict())
    for c in d["contacts"]:
        c["a"] = -1
    with pytest.raises(CannotStandError) as err:
        graph_limit(Arcade.from_dict(d), "l")
    msg = str(err.value)
    assert "every contact is on the ground (a = -1), so no block rests on another" in msg
    assert "block 4 (span 1 voussoir 4) cannot be held by its contacts (span 1 joint 3)" in msg
    assert "HiGHS" not in msg


def test_unheld_block_named_without_ground_contacts(two_spans):
    """A joint left out of a sound arcade: each voussoir beside it hangs on its other joint,
    and the two need horizontal loads of opposite sign."""
    d = copy.deepcopy(two_spans.to_dict())
    del d["contacts"][4]  # span 1 joint 3: voussoir 4 keeps joint 4 only
    with pytest.raises(CannotStandError) as err:
        graph_limit(Arcade.from_dict(d), "r")
    msg = str(err.value)
    assert ("block 3 (span 1 voussoir 3), on span 1 joint 2, is held only under a horizontal "
            "load of at least") in msg
    assert "block 4 (span 1 voussoir 4), on span 1 joint 4, only under at most" in msg
    assert "every contact is on the ground" not in msg and "HiGHS" not in msg
