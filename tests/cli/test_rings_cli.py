"""archrock arcade --rings: a brick arch of several rings from flags, its separation in the
output, the figure and the refusals."""

from __future__ import annotations

import json

import pytest

from archrock.cli import main

TWO = ("arcade", "--spans", "5", "--ring-thickness", "0.215", "0.215", "--brick", "0.5")


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_two_rings_separate(capsys):
    code, out, err = run(capsys, *TWO)
    assert code == 0, err
    assert out.startswith("2-ring brick arch: 1 span, 33 blocks (33 voussoirs), 67 contacts")
    assert "k_l = 0.174130" in out and "k_r = 0.174130" in out
    assert "the rings separate:" in out and "of 32 interface contacts open" in out
    code, out, err = run(capsys, *TWO, "--ring-friction", "0.5", "--json")
    d = json.loads(out)
    assert d["k_l"] == pytest.approx(0.147291, abs=1e-6)
    assert d["l"]["mechanism"]["sliding"]
    rings = d["rings"]["l"]
    assert rings["interfaces"] == 32 and rings["sliding"] and rings["open"]
    assert set(rings["sliding"]) <= set(d["l"]["mechanism"]["sliding"])


def test_one_ring_lists_its_four_hinges(capsys):
    code, out, _ = run(capsys, "arcade", "--spans", "5", "--rings", "1", "--thickness", "0.43",
                       "--brick", "0.5")
    assert code == 0
    assert "k_l = 0.210110" in out
    assert "hinges: ring 1 joint" in out


def test_cohesion_and_file(capsys, tmp_path):
    f = tmp_path / "rings.json"
    code, out, _ = run(capsys, *TWO, "--ring-friction", "0.5", "--ring-cohesion", "5",
                       "--write", str(f))
    assert code == 0
    k = float(out.split("k_l = ")[1].split()[0])
    assert k > 0.147291
    code, out2, _ = run(capsys, "arcade", "--arcade", str(f))
    assert code == 0 and f"k_l = {k:.6f}" in out2


@pytest.mark.parametrize("extra, msg", [
    (("--rings", "0"), "--rings: 0; allowed an integer from 1 to 20"),
    (("--rings", "3"), "--ring-thickness: 2 values for 3 rings"),
    (("--thickness", "0.5"), "--ring-thickness: they add up to 0.43 m"),
    (("--brick", "0"), "--brick: 0 is out of range"),
    (("--ring-cohesion", "-1"), "--ring-cohesion: -1 kPa is out of range"),
    (("--pier-height", "2"), "--rings: cannot be combined with --pier-height"),
    (("--ramp",), "--rings: the contact engine"),
    (("--headers", "1"), "--headers: 1; allowed 0 (none) or a header every 2 to 15 bricks"),
    (("--shape", "pointed", "--rises", "3"), "--shape: 'pointed' with --rings"),
])
def test_bad_flags_one_line(capsys, extra, msg):
    code, out, err = run(capsys, *TWO, *extra)
    assert code == 2
    assert err.startswith("archrock: error: ") and msg in err and "Traceback" not in err


def test_segmental_of_half_span_rise_is_the_semicircle(capsys):
    _, semi, _ = run(capsys, *TWO)
    code, seg, err = run(capsys, *TWO, "--shape", "circular", "--rises", "2.5")
    assert code == 0, err
    k = semi.split("k_l = ")[1].split()[0]
    assert f"k_l = {k}" in seg


def test_a_ringed_file_refuses_the_engine(capsys, tmp_path):
    f = tmp_path / "rings.json"
    assert run(capsys, *TWO, "--write", str(f))[0] == 0
    code, _, err = run(capsys, "arcade", "--arcade", str(f), "--ramp")
    assert code == 2 and "the contact engine does not model" in err


def test_rings_take_the_strength(capsys):
    """--fc reaches a ringed arch (it was silently dropped): weaker masonry carries less, the
    interfaces keep their own friction, and the answer states the static bracket."""
    code, out, err = run(capsys, *TWO, "--fc", "5", "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["arcade"]["fc"] == {"voussoir": 5.0}
    lo, hi = d["l"]["k_bounds"]
    assert hi - lo <= 1e-6 * hi
    assert d["k_l"] < 0.174130 - 1e-3  # the same arch without f_c
    code, out1, _ = run(capsys, *TWO, "--fc", "1", "--json")
    assert json.loads(out1)["k_l"] < d["k_l"]
    code, text, _ = run(capsys, *TWO, "--fc", "5")
    assert "compressive strength f_c: voussoir 5 MPa" in text
