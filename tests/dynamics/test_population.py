"""prepare_many: the arches of a study, with those left out and why."""

import pytest

from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch, oppenheim_arch
from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec, nominal_cv
from archrock.dynamics.population import prepare_many
from archrock.dynamics.response import prepare
from archrock.geometry.sampling import ArchSampler, Spreads


def test_prepare_many_from_a_sampler_equals_prepare_one_by_one():
    s = ArchSampler(oppenheim_arch(), seed=4)
    many = prepare_many(s, 5, PAPER_PRACTICE)
    cv = nominal_cv(oppenheim_arch())
    assert many.indices == (0, 1, 2, 3, 4) and not many.failed and many.requested == 5
    for i, m in zip(many.indices, many):
        one = prepare(s.arch(i), cv)
        assert m.impact == one.impact and m.k_l == one.k_l and m.k_r == one.k_r


def test_prepare_many_leaves_out_outcomes_only():
    s = ArchSampler(oppenheim_arch(), Spreads(0.1, 0.99, 0.99), seed=27)
    many = prepare_many(s, 3)
    assert many.indices == (1,) and [i for i, _ in many.failed] == [0, 2]
    assert "cannot stand" in many.failed[0][1] and "not a valid arch" in many.failed[1][1]
    # per-arch 'paper' law: arches on which it creates energy are left out too, and said so
    mixed = prepare_many([nominal_arch(), nominal_arch(10.0, 180.0, 0.8, 12)], impact="momentum")
    assert mixed.indices == (0,) and "cannot stand" in mixed.failed[0][1]
    with pytest.raises(ArchInputError, match="^arches\\[0\\]"):
        prepare_many(["not an arch"])
    with pytest.raises(ArchInputError, match="^samples: none of the 2 arches"):
        prepare_many([nominal_arch(10.0, 180.0, 0.8, 12)] * 2, impact=ImpactSpec("paper"))


def test_left_out_outcome_reads_the_reasons_of_studies_and_batches():
    from archrock.dynamics.population import LEFT_OUT, count_left_out, left_out_outcome

    s = ArchSampler(oppenheim_arch(), Spreads(0.1, 0.99, 0.99), seed=27)
    many = prepare_many(s, 3)
    # the messages of prepare (through UNUSABLE_ARCH) ...
    assert [left_out_outcome(why) for _, why in many.failed] == ["cannot_stand", "invalid_draw"]
    # ... and of batch.prepare_batch
    cases = {"geometry: a voussoir span is <= 0": "invalid_draw",
             "limit analysis: no admissible four-hinge mechanism": "no_mechanism",
             "limit analysis: the arch cannot stand (k_l = -0.1, k_r = 0.2)": "cannot_stand",
             "four-link model: degenerate four-bar (division by zero)": "four_link_not_applicable",
             "mechanism M_l 0i-3e-5i-7e: the hinges are aligned (singular four-bar)":
                 "four_link_not_applicable",
             "impact r_to_l: the 'paper' model gives a negative rate ratio -0.1 on this geometry":
                 "impact_not_applicable",
             "least-loss chain: impact: singular": "impact_not_applicable",
             "something new": "other"}
    for why, key in cases.items():
        assert left_out_outcome(why) == key, why
    counts = count_left_out(many.failed)
    assert list(counts) == list(LEFT_OUT) and counts["cannot_stand"] == counts["invalid_draw"] == 1
    assert sum(counts.values()) == 2
