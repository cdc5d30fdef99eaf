"""archrock limit --fill-pressure KAPPA: k with the fill's mobilised passive pressure beside k
without it; --fill-level/--fill-density give a family arch its fill (docs/fill.md)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.geometry import family_arch
from archrock.statics.fill import fill_pressure_analysis

ARCH = ("--shape", "circular", "--span", "10", "--rise", "3", "--thickness", "0.5",
        "--voussoirs", "9")


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_fill_flags_build_the_family_arch_with_its_fill(capsys):
    code, out, err = run(capsys, "limit", *ARCH, "--fill-level", "3.6", "--fill-density", "1700",
                         "--json")
    assert code == 0, err
    got = json.loads(out)["geometry"]
    want = family_arch("circular", 10, 3, 0.5, 9, fill={"level": 3.6, "density": 1700.0},
                       name="circular")
    assert got["family"]["fill"] == {"level": 3.6, "density": 1700.0}
    assert np.allclose([ld["mass"] for ld in got["loads"]], [ld.mass for ld in want.loads],
                       rtol=1e-15, atol=0)
    assert len(want.loads) == 9


def test_fill_pressure_line_and_json(capsys):
    code, out, err = run(capsys, "limit", *ARCH, "--fill-level", "3.6", "--fill-pressure", "0.2",
                         "--fill-friction-angle", "35")
    assert code == 0, err
    arch = family_arch("circular", 10, 3, 0.5, 9, fill={"level": 3.6, "density": 1800.0})
    r = fill_pressure_analysis(arch, 0.2, 35.0)
    assert r.k > r.k0 + 0.05
    line = out.splitlines()[-1]
    assert line == f"  k = {r.k:.4f} with the fill's passive pressure ({r.k0:.4f} without)"
    code, out, err = run(capsys, "limit", *ARCH, "--fill-level", "3.6", "--fill-pressure", "0.2",
                         "--fill-friction-angle", "35", "--json")
    d = json.loads(out)["fill_pressure"]
    assert d["k_l"] == pytest.approx(r.k_l, rel=1e-12)
    assert d["k0_r"] == pytest.approx(r.k0_r, rel=1e-12)
    assert d["work_multiplier_l"] == pytest.approx(d["k_l"], rel=1e-9)


@pytest.mark.parametrize("extra,start", [
    (("--fill-pressure", "0.3"), "archrock: error: --fill-pressure: the arch has no fill; give "
                                 "one with --fill-level Y"),
    (("--fill-level", "3.6", "--fill-pressure", "-1"), "archrock: error: argument --fill-pressure"),
    (("--fill-level", "3.6", "--fill-friction-angle", "30"),
     "archrock: error: --fill-friction-angle: needs --fill-pressure"),
    (("--fill-level", "3.6", "--fill-pressure", "0.3", "--fill-friction-angle", "90"),
     "archrock: error: --fill-friction-angle: 90.0; allowed 0 <= phi <= 89 deg"),
    (("--fill-density", "1800"), "archrock: error: --fill-density: needs --fill-level"),
    (("--fill-level", "3.6", "--fill-pressure", "0.3", "--fc", "5"),
     "archrock: error: --fill-pressure: computed under Heyman's hypotheses"),
    (("--fill-level", "3.6", "--fill-density", "0"), "archrock: error: --fill-density:"),
])
def test_fill_flags_refused_by_name(capsys, extra, start):
    code, out, err = run(capsys, "limit", *ARCH, *extra)
    assert code == 2 and err.startswith(start), err
