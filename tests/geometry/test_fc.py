"""The arch's compressive strength ``fc`` [MPa]: checked, kept by every transformation, written
to geometry files only when set, and set by --fc (the common arch option) and the app's field."""

import argparse
import json

import pytest

from archrock.errors import ArchInputError
from archrock.geometry import (apply_defect, arch_from_dict, family_arch, oppenheim_arch,
                               with_piers)
from archrock.geometry.files import read_arch, write_arch
from archrock.options import arch_from_args


def _arches():
    """One arch of each kind in the chain, all with f_c = 5 MPa."""
    circ = oppenheim_arch().with_fc(5.0)
    fam = family_arch("circular", 10.0, 1.5, 0.5, 15, exact=False, fc=5.0)
    piers = with_piers(circ, 3.0, 1.5)
    return {"Arch": circ, "FamilyArch": fam, "ArchOnPiers": piers}


def test_default_is_infinite_and_with_fc_sets_it():
    a = oppenheim_arch()
    assert a.fc is None
    b = a.with_fc(2.5)
    assert b.fc == pytest.approx(2.5, rel=0, abs=0)
    assert b.with_fc(None).fc is None
    assert a.with_fc(None) is a
    # the geometry is the same arch
    assert (b.joint_points == a.joint_points).all() and (b.masses == a.masses).all()


@pytest.mark.parametrize("bad", [0.05, 2000.0, float("nan"), True, "x"])
def test_fc_out_of_range_names_field_and_range(bad):
    with pytest.raises(ArchInputError, match=r"^fc: .*(0\.1 to 1000 MPa|number)"):
        oppenheim_arch().with_fc(bad)


@pytest.mark.parametrize("kind", ["Arch", "FamilyArch", "ArchOnPiers"])
def test_transformations_keep_fc(kind):
    arch = _arches()[kind]
    assert type(arch).__name__ == kind
    assert arch.fc == 5.0
    assert arch.mirrored().fc == 5.0
    assert arch.scaled(2.0).fc == 5.0
    voussoir = arch.n // 2
    assert apply_defect(arch, f"{voussoir}:thickness=0.8").fc == 5.0
    assert apply_defect(arch, f"{voussoir}:tilt=3").fc == 5.0
    assert apply_defect(arch, f"{voussoir}:mortar=0.2").fc == 5.0
    if kind != "ArchOnPiers":
        assert with_piers(arch, 2.0, 1.5).fc == 5.0
    if hasattr(arch, "with_thickness_factor"):
        assert arch.with_thickness_factor(1.1).fc == 5.0


@pytest.mark.parametrize("kind", ["Arch", "FamilyArch", "ArchOnPiers"])
def test_files_round_trip_fc(kind, tmp_path):
    arch = _arches()[kind]
    d = arch.to_dict()
    assert d["fc"] == 5.0
    assert arch_from_dict(d).fc == 5.0
    back = read_arch(write_arch(arch, tmp_path / "a.json"))
    assert back.fc == 5.0 and type(back) is type(arch)


@pytest.mark.parametrize("kind", ["Arch", "FamilyArch", "ArchOnPiers"])
def test_to_dict_without_fc_is_unchanged(kind):
    arch = _arches()[kind].with_fc(None)
    d = arch.to_dict()
    assert "fc" not in d
    with_fc = arch.with_fc(5.0).to_dict()
    with_fc.pop("fc")
    assert json.dumps(with_fc) == json.dumps(d)


def test_file_fc_checked():
    d = oppenheim_arch().to_dict()
    d["fc"] = "strong"
    with pytest.raises(ArchInputError, match=r"^fc: expected a number"):
        arch_from_dict(d)
    d["fc"] = 0.0
    with pytest.raises(ArchInputError, match=r"^fc: 0 is out of range; allowed 0.1 to 1000"):
        arch_from_dict(d)


def test_option_fc_applies_last():
    ns = argparse.Namespace(fc=3.0, defect=["2:thickness=0.8"], pier_height=3.0,
                            pier_width=1.5)
    arch = arch_from_args(ns)
    assert type(arch).__name__ == "ArchOnPiers" and arch.fc == 3.0
    assert arch_from_args(argparse.Namespace()).fc is None


def test_cli_fc_out_of_range(capsys):
    from archrock.cli import main

    assert main(["limit", "--fc", "0.01"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == ("archrock: error: --fc: 0.01 is out of range; allowed 0.1 to 1000 MPa (or "
                   "none: infinite strength)")


def test_displaced_arch_carries_base_fc():
    from archrock.geometry.displaced import SupportMovement
    from archrock.statics.supports import on_moved_supports

    arch = oppenheim_arch().with_fc(4.0)
    moved = on_moved_supports(arch, SupportMovement(0.05, 0.0, "right"))
    assert moved.fc == 4.0
    assert moved.with_fc(8.0).fc == 8.0


def test_app_arch_field_fc():
    from archrock.app.api import arch_from_params

    arch = arch_from_params({"shape": "circular", "span": 10, "rise": 1.5, "thickness": 0.5,
                             "voussoirs": 15, "fc": 2})
    assert arch.fc == 2.0
    uploaded = arch_from_params({"geometry": oppenheim_arch().to_dict(), "fc": 7})
    assert uploaded.fc == 7.0
    with pytest.raises(ArchInputError, match=r"^fc: 5000 is out of range"):
        arch_from_params({"fc": 5000})
