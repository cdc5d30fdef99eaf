"""Support movements of a flat arch wedged between its springings (archrock.statics.supports):
where a straight line of thrust fits inside it, a closure opens no hinge; said as such."""

from __future__ import annotations

import pytest

from archrock.errors import NoMechanismError
from archrock.geometry.circular import nominal_arch
from archrock.statics.supports import displacement_capacity


@pytest.fixture(scope="module")
def flat():
    """R 10 m, embrace 70 deg, t 2 m, 7 voussoirs: the horizontal line y = 9 m touches the
    crown's intrados (9 m) and ends inside both springing joints (7.37 to 9.01 m)."""
    return nominal_arch(10, 70, 2, 7)


def test_closure_of_a_wedged_flat_arch_is_an_outcome(flat):
    with pytest.raises(NoMechanismError) as err:
        displacement_capacity(flat, "closure", "right")
    assert str(err.value).startswith(
        "arch: a closure of the right support cannot bring this arch to a mechanism: a straight "
        "line of thrust fits inside it from one springing to the other")
    assert "gives way only by crushing" in str(err.value)


def test_spread_of_the_same_arch_has_a_capacity(flat):
    cap = displacement_capacity(flat, "spread", "right")
    assert 2.2 < cap.capacity < 2.4  # 2.29463 m, 20% of the span
    assert abs(cap.fraction - 0.2) < 0.01


def test_closure_of_a_thinner_arch_still_answers():
    cap = displacement_capacity(nominal_arch(10, 70, 1, 9), "closure", "right")
    assert 1.7 < cap.capacity < 1.85  # 1.77347 m, 15.46% of the span
