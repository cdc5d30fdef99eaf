"""The one table from flags to spec fields (archrock.options.fields) against the specs and the
parser: every spec field is set by a flag or said why not, every flag of the spec groups sets a
field, and a command line's values arrive in the spec's fields."""

import argparse
import dataclasses
import inspect

import pytest

from archrock.cli import build_parser
from archrock.cli.options import (add_geometry_options, add_impact_options, add_motion_options,
                                  add_spread_options)
from archrock.dynamics.impact import ImpactSpec
from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch, with_piers
from archrock.geometry.displaced import SupportMovement
from archrock.geometry.sampling import Spreads
from archrock.groundmotion import PulseSpec, RecordSpec
from archrock.options import arch_from_args, impact_spec_from_args, motion_spec_from_args, spreads
from archrock.options.fields import DERIVED, FLAGS, dest, flag_message

SPECS = {"Spreads": Spreads, "PulseSpec": PulseSpec, "RecordSpec": RecordSpec,
         "ImpactSpec": ImpactSpec, "SupportMovement": SupportMovement}


def _fields(name):
    if name == "with_piers":
        params = inspect.signature(with_piers).parameters
        return {p for p in params if p not in ("arch", "_trusted")}
    return {f.name for f in dataclasses.fields(SPECS[name])}


def _parser():
    p = argparse.ArgumentParser()
    add_geometry_options(p)  # with the piers' and the support movement's flags
    add_spread_options(p, tilt=True, piers=True, strength=True)
    add_motion_options(p)
    add_impact_options(p)
    return p


def test_every_field_of_every_spec_has_its_flag_or_a_reason():
    assert set(FLAGS) == set(SPECS) | {"with_piers"}
    for name, row in FLAGS.items():
        assert set(row) == _fields(name), name
        for field, flag in row.items():
            assert (flag is None) == ((name, field) in DERIVED), (name, field)
    assert set(DERIVED) <= {(n, f) for n, row in FLAGS.items() for f in row}


def test_every_flag_of_the_spec_groups_sets_a_field():
    actions = {a.option_strings[0]: a for a in _parser()._actions if a.option_strings}
    table = {flag: (name, field) for name, row in FLAGS.items() for field, flag in row.items()
             if flag is not None}
    assert len(table) == sum(1 for row in FLAGS.values() for f in row.values() if f)  # one use
    for flag in table:
        assert flag in actions, flag
        assert actions[flag].dest == dest(flag), flag
    groups = {"support movement", "ground motion", "impact"}
    in_groups = {a.option_strings[0] for g in _parser()._action_groups if g.title in groups
                 for a in g._group_actions}
    spread = {f for f in actions if f.startswith(("--spread-", "--pier-", "--right-pier-"))}
    assert in_groups | spread <= set(table), sorted((in_groups | spread) - set(table))
    # the flags exist in the commands themselves, with the same dest
    commands = build_parser()._subparsers._group_actions[0].choices
    for cmd, flags in (("ensemble", ["--spread-span", "--pulse", "--cv", "--spread"]),
                       ("curves", ["--spread-tilt", "--impact-on"]),
                       ("limit", ["--pier-height", "--right-pier-batter", "--support-side"])):
        have = {a.option_strings[0]: a.dest for a in commands[cmd]._actions if a.option_strings}
        assert all(have[f] == dest(f) for f in flags), cmd


def test_a_command_lines_values_arrive_in_the_specs_fields(tmp_path):
    rec = tmp_path / "r.txt"
    rec.write_text("0 0\n0.01 0.1\n0.02 -0.1\n0.03 0\n")
    argv = ["--spread-span", "0.2", "--spread-thickness", "0.15", "--spread-radius", "0.03",
            "--spread-tilt", "2", "--impact", "momentum", "--impact-on", "nominal"]
    args = _parser().parse_args(argv + ["--pulse", "ricker", "--amplitude", "0.4",
                                        "--pulse-duration", "0.5"])
    assert spreads(args) == Spreads(span=0.2, thickness=0.15, radius=0.03, tilt=2.0)
    assert motion_spec_from_args(args) == PulseSpec(kind="ricker", amplitude_g=0.4, duration=0.5)
    assert impact_spec_from_args(args) == ImpactSpec(model="momentum", on="nominal")
    r = motion_spec_from_args(_parser().parse_args(["--record", str(rec), "--units", "m/s2",
                                                   "--scale", "2"]))
    assert (r.path, r.units, r.scale) == (str(rec.resolve()), "m/s2", 2.0)
    # the arch on piers and on moved supports
    a = arch_from_args(_parser().parse_args(["--pier-height", "4", "--pier-width", "2",
                                             "--right-pier-width", "2.5"]))
    assert type(a).__name__ == "ArchOnPiers"
    assert a.to_dict() == with_piers(nominal_arch(), 4.0, 2.0, width_right=2.5).to_dict()


def test_library_messages_are_worded_with_the_flag():
    assert flag_message("height_right: -1; allowed > 0", "with_piers") == \
        "--right-pier-height: -1; allowed > 0"
    assert flag_message("width: 0; allowed > 0", "with_piers") == "--pier-width: 0; allowed > 0"
    assert flag_message("settlement: nan", "SupportMovement") == "--settlement: nan"
    assert flag_message("name: x", "with_piers") is None  # set by no flag
    assert flag_message("spread radius: x", "Spreads") is None  # names no field
    with pytest.raises(ArchInputError, match="^--right-pier-courses: "):
        arch_from_args(_parser().parse_args(["--pier-height", "4", "--pier-width", "2",
                                             "--right-pier-courses", "0"]))
