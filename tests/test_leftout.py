"""LeftOut: why an arch was left out, one type from where the arch is refused to the summaries.

The reference here is the regular expressions the summaries matched before (archrock 0.6's
``population._PATTERNS`` and ``summary._reason``, copied below): :meth:`LeftOut.read` must give
the same reason and :attr:`LeftOut.group` the same key on every message, so the counts by reason
of every study stay what they were."""

import json
import pickle
import re

import numpy as np
import pytest

from archrock.errors import ArchInputError, CannotStandError
from archrock.geometry import nominal_arch, oppenheim_arch
from archrock.geometry.sampling import ArchSampler, Spreads
from archrock.leftout import REASONS, LeftOut, count_reasons

# ---------------------------------------------------------------------------- 0.6's reference
_PATTERNS_0_6 = (
    ("impact_not_applicable", r"^(least-loss chain:|impact\b)"),
    ("cannot_stand", r"cannot stand on its moved supports"),
    ("invalid_draw", r"^geometry:|not a valid arch"),
    ("cannot_stand", r"cannot stand|does not stand"),
    ("lift_off", r"lift-off|lifts off|is governed by a"),
    ("no_mechanism", r"four-hinge mechanism"),
    ("four_link_not_applicable", r"^four-link model:|^mechanism "),
)


def _reason_0_6(text):
    for key, pattern in _PATTERNS_0_6:
        if re.search(pattern, text):
            return key
    return "other"


def _group_0_6(text):
    return re.sub(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?", "#", text.split(" (")[0])


#: Messages of every form archrock writes when it refuses an arch, and near misses.
MESSAGES = [
    "geometry: a voussoir span is <= 0",
    "geometry: cannot stand on its moved supports (spread +0.2 m (right support)): arch x",
    "not a valid arch: neighbouring voussoirs 2 and 3 do not overlap",
    "limit analysis: no admissible four-hinge mechanism",
    "limit analysis: the arch cannot stand (k_l = -0.1, k_r = 0.2)",
    "arch 'sample 3' does not stand under its own weight",
    "limit analysis: a joint lifts off before any four-hinge mechanism opens",
    "M_l is governed by a mechanism with lift-off at joint 3 at k = 0.2000 (four-hinge 0.21)",
    "four-link model: degenerate four-bar (division by zero)",
    "mechanism M_l 0i-3e-5i-7e: the hinges are aligned (singular four-bar)",
    "mechanism M_r 1e-3i-5e-7i: the hinges do not open under forces of its direction",
    "impact r_to_l: the 'paper' model gives a negative rate ratio -0.1 on this geometry",
    "impact l_to_r: the 'paper' model creates energy on this geometry (kinetic energy ratio "
    "1.0312 > 1, rate ratio 1.0100); use the momentum model",
    "impact: the 'paper' model's momentum equations are singular for this geometry",
    "least-loss chain: impact: singular",
    "least-loss chain: mechanism M_l 0i: the hinges are aligned",
    "impact", "impact-law", "impactful words", "impact_x", "impacts", "something new",
    "the impact model cannot stand", "x four-hinge mechanism and lift-off",
    "cannot stand on its moved supports", "mechanism", "mechanisms aligned",
]


def test_read_gives_0_6s_reason_and_group_on_every_form():
    for text in MESSAGES:
        why = LeftOut.read(text)
        assert why.reason == _reason_0_6(text), text
        assert why.group == _group_0_6(text), text
        assert why == text and why.detail == text and str(why) == text


def test_a_left_out_is_its_message_frozen_and_typed():
    why = LeftOut("cannot_stand", "limit analysis: the arch cannot stand (k_l = -0.1, k_r = 0.2)")
    assert isinstance(why, str) and why.reason == "cannot_stand"
    assert json.dumps([3, why]) == json.dumps([3, why.detail])  # the studies' "failed" lists
    back = pickle.loads(pickle.dumps(why))  # process pools, Dask
    assert type(back) is LeftOut and back.reason == "cannot_stand" and back == why
    assert LeftOut.read(why) is why  # a typed reason is never read again
    with pytest.raises(AttributeError, match="immutable"):
        why.reason = "other"
    with pytest.raises(ArchInputError, match="left-out reason: 'tired'"):
        LeftOut("tired", "x")
    with pytest.raises(ArchInputError, match="left-out detail"):
        LeftOut("other", "")
    assert LeftOut.of(CannotStandError("arch 'a' does not stand")).reason == "cannot_stand"
    assert repr(why).startswith("LeftOut('cannot_stand', ")


def test_the_batch_path_refuses_arches_with_their_reason_and_its_text_reads_back():
    """prepare_batch gives each refused row its LeftOut where it refuses it (geometry, limit
    analysis, impact law); the ensemble's table keeps the text, which reads back to the same
    reason."""
    from archrock.dynamics.batch import prepare_batch

    s = ArchSampler(oppenheim_arch(), Spreads(0.3, 0.6, 0.6), 3)
    spans, thick, radii = s.draw(0, 120)
    pb = prepare_batch(spans, radii, thick, 2000.0, impact="paper", parallel=False)
    refused = [e for e in pb.error if e != ""]
    assert refused and all(type(e) is LeftOut for e in refused)
    assert {"invalid_draw", "cannot_stand", "impact_not_applicable"} <= {e.reason for e in refused}
    assert all(LeftOut.read(str(e)).reason == e.reason == _reason_0_6(e) for e in refused)


def test_count_reasons_in_report_order():
    counts = count_reasons([LeftOut("lift_off", "x"), "geometry: bad", "geometry: worse"])
    assert list(counts) == list(REASONS)
    assert counts["lift_off"] == 1 and counts["invalid_draw"] == 2 and sum(counts.values()) == 3


def test_studies_carry_the_type_from_where_the_arch_is_refused():
    from archrock.dynamics.population import count_left_out, prepare_many

    s = ArchSampler(oppenheim_arch(), Spreads(0.1, 0.99, 0.99), seed=27)
    many = prepare_many(s, 3)
    kinds = [(i, type(why).__name__, why.reason) for i, why in many.failed]
    assert kinds == [(0, "LeftOut", "cannot_stand"), (2, "LeftOut", "invalid_draw")]
    assert count_left_out(many.failed)["cannot_stand"] == 1
    mixed = prepare_many([nominal_arch(), nominal_arch(10.0, 180.0, 0.8, 12)], impact="momentum")
    assert [why.reason for _, why in mixed.failed] == ["cannot_stand"]


def _frame(errors):
    """A batch table of len(errors) arches: those with an error failed, the others at rest."""
    import pandas as pd

    from archrock.studies.ensemble.compute import COLUMNS

    n = len(errors)
    failed = np.array([bool(e) for e in errors])
    cols = {c: np.zeros(n) for c in COLUMNS}
    cols.update({"batch": np.zeros(n, dtype=np.int64), "index": np.arange(n, dtype=np.int64),
                 "k_l": np.where(failed, np.nan, 0.4), "k_r": np.where(failed, np.nan, 0.4),
                 "mech_l": np.array(["" if f else "0i-3e-5i-7e" for f in failed], dtype=object),
                 "mech_r": np.array(["" if f else "0e-3i-5e-7i" for f in failed], dtype=object),
                 "collapsed": np.zeros(n, dtype=bool),
                 "status": np.array(["failed" if f else "rest" for f in failed], dtype=object),
                 "n_impacts": np.zeros(n, dtype=np.int64),
                 "n_activations": np.zeros(n, dtype=np.int64),
                 "events_truncated": np.zeros(n, dtype=bool),
                 "early_stopped": np.zeros(n, dtype=bool),
                 "error": np.array(errors, dtype=object)})
    return pd.DataFrame(cols, columns=COLUMNS)


def test_ensemble_summaries_count_by_reason_as_0_6_did():
    """The ensemble's two summaries (of the frame, and streamed from batches) count every
    message of :data:`MESSAGES` by 0.6's reason and group it by 0.6's key."""
    pytest.importorskip("pandas")
    from archrock.groundmotion import PulseSpec
    from archrock.studies.ensemble import EnsembleConfig
    from archrock.studies.ensemble.streaming import summarize_batches
    from archrock.studies.ensemble.summary import EnsembleResult

    errors = MESSAGES + MESSAGES[:5] + [""] * 7
    cfg = EnsembleConfig.from_arch(oppenheim_arch(), samples=len(errors), batch_size=10,
                                   motion=PulseSpec("oppenheim", -1.0, 0.2), impact=0.8)
    nominal = {"k_l": 0.37, "k_r": 0.37}
    s = EnsembleResult(cfg, _frame(errors), nominal, {}).summary()
    expected, groups = dict.fromkeys(REASONS, 0), {}
    for e in filter(None, errors):
        expected[_reason_0_6(e)] += 1
        groups[_group_0_6(e)] = groups.get(_group_0_6(e), 0) + 1
    assert {k: s["outcomes"]["counts"][k] for k in REASONS} == expected
    assert s["failed"] == {"count": len(errors) - 7, "reasons": groups}
    assert s["outcomes"]["counts"]["integrated"] == 7
    assert sum(1 for v in expected.values() if v) == len(REASONS)  # every reason exercised
    halves = [_frame(errors[:20]), _frame(errors[20:])]
    st = summarize_batches(lambda: halves, cfg, nominal, {})
    assert st["outcomes"]["counts"] == s["outcomes"]["counts"] and st["failed"] == s["failed"]


@pytest.mark.slow
def test_a_real_ensembles_counts_by_reason_are_0_6s():
    """Wide spreads and the 'paper' law on each arch: many arches left out, counted as 0.6's
    regular expressions count the same error column."""
    pytest.importorskip("pandas")
    from archrock.dynamics.impact import ImpactSpec
    from archrock.groundmotion import PulseSpec
    from archrock.studies.ensemble import EnsembleConfig, run_ensemble

    cfg = EnsembleConfig.from_arch(oppenheim_arch(), samples=60, batch_size=30, seed=0,
                                   spreads=Spreads(0.3, 0.3, 0.2),
                                   motion=PulseSpec("oppenheim", -1.0, 0.2),
                                   impact=ImpactSpec("paper"))
    res = run_ensemble(cfg)
    s = res.summary()
    err = [e for e in res.frame["error"] if e]
    assert len(err) >= 5
    expected = dict.fromkeys(REASONS, 0)
    for e in err:
        expected[_reason_0_6(e)] += 1
    assert {k: s["outcomes"]["counts"][k] for k in REASONS} == expected
    assert s["failed"]["count"] == len(err)
