"""Support movements on the command line: --spread / --settlement / --support-side on any
arch, limit --capacity and --supports-plot (docs/supports.md)."""

import json

import pytest

from archrock.cli import main
from archrock.geometry import nominal_arch
from archrock.geometry.displaced import SupportMovement
from archrock.statics.limit import limit_analysis
from archrock.statics.supports import displace, displacement_capacity


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_limit_on_a_displaced_arch(capsys):
    code, out, err = run(capsys, "limit", "--spread", "0.05", "--json")
    assert code == 0, err
    data = json.loads(out)
    from archrock.statics.supports import reclosed

    # one answer: the collapse multipliers of the re-closed displaced arch; the point
    # contacts' lower multipliers only as the bounded gap-closing motion
    moved = displace(nominal_arch(), SupportMovement(0.05)).arch
    lib, pc = limit_analysis(reclosed(moved)), limit_analysis(moved)
    assert data["k_l"] == pytest.approx(lib.k_l, rel=1e-12)
    assert data["k_r"] == pytest.approx(lib.k_r, rel=1e-12)
    sm = data["support_movement"]
    assert sm["reclosed"] is True
    assert sm["gap_closing"]["k_l"] == pytest.approx(pc.k_l, rel=1e-12)
    assert sm["gap_closing"]["k_l"] < 0.02 < 0.3 < data["k_l"]
    assert 4 in sm["gap_closing"]["closing_l"]
    assert sm["movement"] == {"spread": 0.05, "settlement": 0.0, "side": "right"}
    assert [(h["joint"], h["edge"]) for h in sm["hinges"]] == [
        (1, "intrados"), (4, "extrados"), (6, "intrados")]
    code, out, err = run(capsys, "limit", "--settlement", "0.1", "--support-side", "left")
    assert code == 0, err
    assert "displaced arch: settlement +0.1 m (left support); open hinges 0e, 3e, 6i" in out


def test_zero_movement_is_the_arch(capsys):
    _, a, _ = run(capsys, "limit", "--json")
    _, b, _ = run(capsys, "limit", "--json", "--spread", "0")
    assert json.loads(a)["k_l"] == json.loads(b)["k_l"]


def test_capacity(capsys):
    code, out, err = run(capsys, "limit", "--capacity", "spread", "--json")
    assert code == 0, err
    cap = json.loads(out)["capacity"]
    lib = displacement_capacity(nominal_arch(), "spread")
    assert cap["capacity"] == pytest.approx(lib.capacity, rel=1e-12)
    assert cap["reason"] == "fourth hinge" and len(cap["mechanism"]) == 4


@pytest.mark.slow
def test_supports_figure(capsys, tmp_path):
    fig = tmp_path / "cap.png"
    code, out, err = run(capsys, "limit", "--capacity", "settlement", "--supports-plot",
                         str(fig))
    assert code == 0, err and "settlement capacity of the right support" in out
    assert fig.stat().st_size > 1000
    fig2 = tmp_path / "disp.png"
    code, out, err = run(capsys, "limit", "--spread", "0.2", "--supports-plot", str(fig2))
    assert code == 0, err
    assert fig2.stat().st_size > 1000


def test_bad_flags(capsys):
    code, out, err = run(capsys, "limit", "--support-side", "top", "--spread", "0.1")
    assert code != 0 and "invalid choice" in err
    code, out, err = run(capsys, "limit", "--support-side", "left")
    assert code != 0 and "--support-side" in err
    code, out, err = run(capsys, "limit", "--spread", "nan")
    assert code != 0
    code, out, err = run(capsys, "limit", "--spread", "0.1", "--capacity", "spread")
    assert code != 0 and "--capacity" in err
    code, out, err = run(capsys, "limit", "--spread", "5")
    assert code != 0 and "collapses" in err
