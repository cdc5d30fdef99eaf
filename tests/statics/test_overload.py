"""A load the arch cannot carry is named as the load, with the largest mass it carries there
(statics.overload), not as the self-weight."""

import dataclasses

import pytest

from archrock.errors import CannotStandError
from archrock.geometry import Load, nominal_arch
from archrock.statics.limit import limit_analysis
from archrock.statics.lp import _stands
from archrock.statics.overload import largest_load_mass


def _loaded(*loads):
    return dataclasses.replace(nominal_arch(), loads=tuple(loads))


def test_a_load_too_heavy_is_named_with_what_carries_it():
    arch = _loaded(Load(3, 1e12, (0.0, 11.0)))
    with pytest.raises(CannotStandError) as exc:
        limit_analysis(arch)
    msg = str(exc.value)
    assert msg.startswith("arch: load 0 (1e+12 kg/m on voussoir 3 at (0, 11) m) is more than it "
                          "can carry (k_l = ")
    assert "it stands without its loads; it carries at most 3.09e+05 kg/m there (load 0 alone): "\
           "reduce load 0's mass or thicken the arch" in msg
    assert "own weight" not in msg and "\n" not in msg


def test_the_largest_mass_stands_and_a_little_more_does_not():
    arch = _loaded(Load(3, 1e12, (0.0, 11.0)))
    m = largest_load_mass(arch, 0)
    assert 3.0e5 < m < 3.2e5
    assert _stands(_loaded(Load(3, m, (0.0, 11.0))))
    assert not _stands(_loaded(Load(3, 1.01 * m, (0.0, 11.0))))


def test_the_heaviest_culprit_of_several_loads_is_named():
    arch = _loaded(Load(3, 8000.0, (0.0, 11.0)), Load(1, 3e5, (-6.0, 8.0)))
    with pytest.raises(CannotStandError, match=r"arch: load 1 \(3e\+05 kg/m on voussoir 1 at "
                                               r"\(-6, 8\) m\) is more than it can carry"):
        limit_analysis(arch)


def test_the_self_weight_keeps_its_message():
    thin = dataclasses.replace(nominal_arch(thickness=0.3), loads=(Load(3, 8000.0, (0.0, 11.0)),))
    with pytest.raises(CannotStandError, match=r"arch: it cannot stand under its own weight "
                                               r"\(k_l = .*\); increase the thickness"):
        limit_analysis(thin)


def test_a_load_the_arch_carries_still_gives_its_multipliers():
    res = limit_analysis(_loaded(Load(3, 8000.0, (0.0, 11.0))))
    assert 0 < res.k < 0.37
