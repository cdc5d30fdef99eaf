"""The command line's arch families: --shape --span --rise and their refusals (the plumbing up
to the arch; limit analysis of polygon arches comes with the limit module)."""

import argparse
import json

import numpy as np
import pytest

from archrock.cli import add_geometry_options, arch_from_args, main
from archrock.cli.options import JOINTS, SHAPES
from archrock.errors import ArchInputError
from archrock.geometry import Arch, FamilyArch, family_arch
from archrock.geometry import JOINTS as GEO_JOINTS
from archrock.geometry import SHAPES as GEO_SHAPES


def _arch(*argv):
    p = argparse.ArgumentParser()
    add_geometry_options(p)
    return arch_from_args(p.parse_args(list(argv)))


def test_cli_names_agree_with_the_library():
    assert SHAPES == GEO_SHAPES and JOINTS == GEO_JOINTS


@pytest.mark.parametrize("shape, rise", [("pointed", 7.0), ("elliptical", 3.0),
                                         ("three-centred", 3.0), ("parabolic", 4.0),
                                         ("catenary", 4.0)])
def test_shape_flags_build_the_family_arch(shape, rise):
    a = _arch("--shape", shape, "--span", "10", "--rise", str(rise), "--thickness", "0.6",
              "--thickness-crown", "0.5", "--voussoirs", "5", "--joints", "vertical",
              "--density", "2400")
    b = family_arch(shape, 10, rise, 0.6, 5, thickness_crown=0.5, joints="vertical", density=2400)
    assert isinstance(a, FamilyArch) and a.name == shape and a.density == 2400
    np.testing.assert_array_equal(a.joint_points, b.joint_points)


def test_circular_span_rise_is_a_segmental_arch():
    a = _arch("--shape", "circular", "--span", "12", "--rise", "3", "--thickness", "0.6")
    assert isinstance(a, Arch) and a.n == 7
    assert a.radii[0] == pytest.approx(7.5)
    # --span/--rise without --shape: circular too
    assert isinstance(_arch("--span", "12", "--rise", "3"), Arch)
    assert isinstance(_arch("--span", "12", "--rise", "3", "--joints", "vertical"), FamilyArch)


@pytest.mark.parametrize("argv, message", [
    (["--shape", "pointed", "--span", "10"], "--rise: needed"),
    (["--shape", "pointed"], "--span and --rise: needed"),
    (["--radius", "5", "--span", "10", "--rise", "3"], "--radius: cannot be combined with --span"),
    (["--embrace", "120", "--shape", "parabolic", "--span", "10", "--rise", "3"],
     "--embrace: cannot be combined with --shape"),
    (["--geometry", "a.json", "--shape", "pointed"], "--geometry: cannot be combined with --shape"),
    (["--thickness-crown", "1"], "--span and --rise: needed"),
])
def test_conflicting_flags_are_refused_in_one_line(capsys, argv, message):
    code = main(["random-arch", *argv])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and message in err, err


def test_out_of_range_rise_names_the_field(capsys):
    code = main(["random-arch", "--shape", "pointed", "--span", "10", "--rise", "4"])
    err = capsys.readouterr().err
    assert code == 2 and "rise: 4 is out of range; allowed F > S/2" in err


def test_random_arch_of_another_family(capsys, tmp_path):
    """random-arch perturbs any family arch, joint tilt included; the same seed, the same arch."""
    from archrock.geometry.files import read_arch
    from archrock.geometry import PolygonArch
    from archrock.statics.limit import limit_analysis

    argv = ["random-arch", "--shape", "parabolic", "--span", "10", "--rise", "4", "--thickness",
            "1", "--voussoirs", "9", "--seed", "5", "--spread-tilt", "3"]
    assert main([*argv, "--out", str(tmp_path / "a.json")]) == 0
    assert main([*argv, "--out", str(tmp_path / "b.json")]) == 0
    capsys.readouterr()
    a, b = read_arch(tmp_path / "a.json"), read_arch(tmp_path / "b.json")
    assert isinstance(a, PolygonArch) and np.array_equal(a.joint_points, b.joint_points)
    assert limit_analysis(a).discrepancy < 1e-9


def test_random_arch_around_a_segmental_arch(capsys):
    code = main(["random-arch", "--span", "12", "--rise", "3", "--thickness", "0.6", "--seed", "1"])
    out = capsys.readouterr().out
    assert code == 0 and len(json.loads(out)["voussoirs"]) == 7


def test_geometry_file_of_a_family(tmp_path):
    from archrock.geometry.files import write_arch

    a = family_arch("catenary", 10, 5, 0.5, 7)
    p = write_arch(a, tmp_path / "cat.json")
    b = _arch("--geometry", str(p))
    np.testing.assert_array_equal(b.joint_points, a.joint_points)
    with pytest.raises(ArchInputError):
        _arch("--shape", "catenary", "--span", "10", "--rise", "5", "--voussoirs", "2")
