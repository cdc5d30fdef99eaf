"""Blocks by kind (archrock.geometry.blocks): voussoirs, pier courses and buttress blocks
counted and named apart."""

from __future__ import annotations

import pytest

from archrock.geometry import nominal_arch, oppenheim_arch, with_piers
from archrock.geometry.files import read_arch
from archrock.geometry.blocks import (arch_phrase, block_counts, block_name, block_names,
                                      describe_blocks)


@pytest.fixture(scope="module")
def semicircle():
    return nominal_arch(5.0, 180.0, 0.8, 9)


def test_arch_without_piers_has_only_voussoirs():
    a = oppenheim_arch()
    assert describe_blocks(a) == "7 voussoirs"
    assert arch_phrase(a, "circular") == "a circular arch of 7 voussoirs"
    assert block_counts(a) == {"voussoirs": 7, "pier_blocks": 0, "buttress_blocks": 0,
                               "piers": 0, "blocks": 7}
    assert block_name(a, 3) == "voussoir 3"


def test_nine_voussoirs_on_two_piers_are_not_eleven_voussoirs(semicircle):
    a = with_piers(semicircle, 4.0, 2.0)
    assert arch_phrase(a) == "an arch of 9 voussoirs on two piers (1 block each)"
    assert block_counts(a) == {"voussoirs": 9, "pier_blocks": 2, "buttress_blocks": 0,
                               "piers": 2, "blocks": 11}
    assert block_names(a)[0] == "left pier" and block_names(a)[-1] == "right pier"
    assert block_names(a)[1:-1] == tuple(f"voussoir {i}" for i in range(9))


def test_courses_buttresses_and_mixed_piers(semicircle):
    assert describe_blocks(with_piers(semicircle, 4.0, 2.0, courses=3)) == \
        "9 voussoirs on two piers (3 courses each)"
    uneven = with_piers(semicircle, 4.0, 2.0, courses=3, courses_right=2)
    assert describe_blocks(uneven) == "9 voussoirs on two piers (3 and 2 courses)"
    # courses counted from the foot up on both sides (the right run is top-down in the chain)
    assert block_names(uneven)[:3] == ("left pier course 1", "left pier course 2",
                                       "left pier course 3")
    assert block_names(uneven)[-2:] == ("right pier course 2", "right pier course 1")
    assert describe_blocks(with_piers(semicircle, 4.0, 2.0, batter=0.1)) == \
        "9 voussoirs on two buttresses (1 block each)"
    mixed = with_piers(semicircle, 4.0, 2.0, courses=2, batter_right=0.1)
    assert describe_blocks(mixed) == \
        "9 voussoirs on a pier (left, 2 courses) and a buttress (right, 2 courses)"
    assert block_counts(mixed)["buttress_blocks"] == 2 and block_counts(mixed)["pier_blocks"] == 2


def test_counts_survive_the_geometry_file(semicircle, tmp_path):
    from archrock.geometry.files import write_arch

    path = write_arch(with_piers(semicircle, 4.0, 2.0, courses=2), tmp_path / "a.json")
    assert describe_blocks(read_arch(path)) == "9 voussoirs on two piers (2 courses each)"


def test_arcade_counts_piers_not_courses(semicircle):
    from archrock.geometry.arcade import arcade
    from archrock.geometry.blocks import arcade_counts, describe_arcade

    arc = arcade([semicircle, semicircle], [4.0] * 3, [2.0] * 3, courses=2)
    assert describe_arcade(arc) == "18 voussoirs, 3 piers in 6 courses"
    assert arcade_counts(arc) == {"voussoirs": 18, "pier_blocks": 6, "buttress_blocks": 0,
                                  "beams": 0, "piers": 3, "blocks": 24}
