"""archrock arcade: the work estimate and its bound, overlapping blocks in a document, and a
static program with no answer named by block (docs/arcades.md)."""

from __future__ import annotations

import json

import pytest


# the three-span arcade and the runner of the arcade command's own tests
from test_arcade_cli import THREE, run  # noqa: E402


def test_huge_arcade_refused_before_it_starts(capsys):
    """50 spans x 2000 voussoirs on piers of 200 courses: about 110,000 blocks; it printed
    nothing for minutes, now it is refused at once with what to change."""
    code, out, err = run(capsys, "arcade", "--spans", *["10"] * 50, "--voussoirs", "2000",
                         "--pier-courses", "200", "--pier-height", "8", "--pier-width", "2.5")
    assert code == 3 and out == ""
    assert err.startswith("archrock: error: arcade: about 1.1e+05 blocks, estimated ")
    assert "(ARCHROCK_MAX_WORK_S); fewer voussoirs (--voussoirs), courses (--pier-courses) or " \
           "spans" in err
    days = float(err.split("estimated ")[1].split()[0])
    assert 5 < days < 500  # ~ 2 x 1.5e-4 s x 110,200^2


def test_long_arcade_warns_and_shows_progress(capsys, monkeypatch):
    from archrock.studies import work

    monkeypatch.setattr(work, "WARN_WORK_S", 0.0)  # every arcade is "long"
    code, out, err = run(capsys, *THREE)
    assert code == 0, err
    lines = err.splitlines()
    assert lines[0].startswith("archrock: warning: arcade: about 31 blocks, estimated ")
    assert lines[1:] == ["arcade: static program in direction 'l' (31 blocks) ...",
                         "arcade: static program in direction 'r' (31 blocks) ..."]
    assert "k_l = 0.139911" in out


def test_document_refused_before_its_blocks_are_checked(capsys, tmp_path, monkeypatch):
    doc = tmp_path / "three.json"
    assert run(capsys, *THREE, "--write", str(doc))[0] == 0
    monkeypatch.setenv("ARCHROCK_MAX_WORK_S", "0.01")
    code, _, err = run(capsys, "arcade", "--arcade", str(doc))
    assert code == 3
    assert err.startswith("archrock: error: arcade: about 31 blocks, estimated ")


def test_overlapping_document_named(capsys, tmp_path, narrowed_pier):
    doc = tmp_path / "three.json"
    assert run(capsys, *THREE, "--write", str(doc))[0] == 0
    bad = tmp_path / "narrow.json"
    # pier 2: 1.8 m -> 1.2 m under two springing joints of 0.8 m each: 0.4 m overlap
    bad.write_text(json.dumps(narrowed_pier(json.loads(doc.read_text()), 0.6)))
    code, out, err = run(capsys, "arcade", "--arcade", str(bad))
    assert code == 2 and out == ""
    assert err.startswith(f"archrock: error: {bad}: blocks: block 9 (span 1 voussoir 9) and "
                          f"block 11 (span 2 voussoir 1) overlap by ")
    assert ("inner pier 2 is 1.2 m wide, narrower than the two springing joints it carries "
            "(1.6 m)") in err
    assert len(err.strip().splitlines()) == 1


def test_unheld_arcade_names_blocks_not_highs(capsys, tmp_path):
    doc = tmp_path / "three.json"
    assert run(capsys, *THREE, "--write", str(doc))[0] == 0
    d = json.loads(doc.read_text())
    for c in d["contacts"]:
        c["a"] = -1
    bad = tmp_path / "ground.json"
    bad.write_text(json.dumps(d))
    code, _, err = run(capsys, "arcade", "--arcade", str(bad))
    assert code == 3
    assert err.startswith("archrock: outcome: arcade: no set of contact forces holds the blocks "
                          "in direction 'l': every contact is on the ground (a = -1), so no "
                          "block rests on another; block ")
    assert "HiGHS" not in err and "cannot be held by its contacts" in err


def test_engine_part_is_estimated_and_bounded(capsys, monkeypatch):
    """--ramp and a motion add the contact engine's steps to the estimate: refused past the
    bound (here 1 s) after the static program, with what to leave out."""
    pytest.importorskip("pymunk")
    monkeypatch.setenv("ARCHROCK_MAX_WORK_S", "1")
    code, out, err = run(capsys, *THREE, "--pulse", "one-sine", "--amplitude", "0.3",
                         "--pulse-duration", "0.5")
    assert code == 3 and out == ""
    assert err.startswith("archrock: error: arcade engine: about 8.28e+03 engine steps, "
                          "estimated ")
    assert "leave out --ramp / the motion" in err
    code, out, err = run(capsys, *THREE, "--ramp")
    assert code == 3
    assert err.startswith("archrock: error: arcade engine: about ")
