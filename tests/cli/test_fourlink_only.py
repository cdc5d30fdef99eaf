"""sensitivity and defects run the four-link model only: on an arch whose piers rock with it
(one degree of freedom cannot follow it, docs/piers-dynamics.md) they refuse by --dynamics
instead of printing figures about 4x unconservative, and go on, warned, with --dynamics
fourlink; fragility runs the contact engine's IDA there (issue 31, tests/cli/
test_fragility_engine.py); on rigid ground nothing changes."""


import pytest

from archrock.cli import main


@pytest.mark.parametrize("argv", [
    ["sensitivity", "--samples", "8"],
    ["defects", "--pulse-duration", "0.2"],
])
def test_four_link_only_studies_refuse_an_arch_whose_piers_rock(heavy_piers_file, argv, capsys):
    assert main([argv[0], "--geometry", str(heavy_piers_file), *argv[1:]]) == 2
    err = capsys.readouterr().err
    assert f"--dynamics: {argv[0]} runs the four-link model only" in err
    assert "single degree of freedom not valid" in err and "--dynamics fourlink" in err


def test_dynamics_fourlink_goes_on_with_a_warning(heavy_piers_file, capsys):
    # it gets past the check, warned, to the next refusal (the record file)
    assert main(["fragility", "--geometry", str(heavy_piers_file), "--records", "nowhere.AT2",
                 "--dynamics", "fourlink"]) == 2
    err = capsys.readouterr().err
    assert "WARNING single degree of freedom not valid" in err
    assert "records: 'nowhere.AT2' is neither a file nor a folder" in err


def test_rigid_ground_is_not_checked(capsys):
    # Oppenheim's arch: past the check to the record refusal, no warning
    assert main(["fragility", "--records", "nowhere.AT2"]) == 2
    err = capsys.readouterr().err
    assert "dynamics" not in err and "records: 'nowhere.AT2'" in err
