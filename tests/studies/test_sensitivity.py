"""Global sensitivity (archrock.studies.sensitivity): the map from draws to arches and Sobol indices."""

import json

import numpy as np
import pytest

pytest.importorskip("SALib")

from archrock.cli import main  # noqa: E402
from archrock.geometry import family_arch, oppenheim_arch  # noqa: E402
from archrock.geometry.sampling import ArchSampler, Spreads  # noqa: E402
from archrock.studies.sensitivity import arches_from_inputs, input_layout, sobol_indices  # noqa: E402
from archrock.studies.runner import RunSettings  # noqa: E402


def _inputs_of(sampler, count):
    """The sampler's own uniforms written as input rows in input_layout's order."""
    layout = input_layout(sampler.nominal, sampler.spreads)
    u = sampler.uniforms(0, count)
    return np.array([[u[b, r, c] for _, _, _, r, c in layout] for b in range(count)])


def test_the_map_is_the_samplers_circular():
    nominal = oppenheim_arch()
    sampler = ArchSampler(nominal, Spreads(0.1, 0.1, 0.05), seed=3)
    spans, thick, radii = arches_from_inputs(nominal, sampler.spreads, _inputs_of(sampler, 6))
    s2, t2, r2 = sampler.draw(0, 6)
    assert np.array_equal(spans, s2) and np.array_equal(thick, t2) and np.array_equal(radii, r2)


def test_the_map_is_the_samplers_family_with_tilt():
    nominal = family_arch("pointed", 10.0, 7.0, 0.9, 8)
    sampler = ArchSampler(nominal, Spreads(0.1, 0.1, 0.05, tilt=4.0), seed=1)
    layout = input_layout(nominal, sampler.spreads)
    assert [name for name, *_ in layout][-7:] == [f"tilt_{j}" for j in range(1, 8)]
    mine = arches_from_inputs(nominal, sampler.spreads, _inputs_of(sampler, 3))
    for a, b in zip(mine, sampler.arches(0, 3)):
        assert np.array_equal(a.joint_points, b.joint_points)
        assert np.array_equal(a.masses, b.masses)


def test_thickness_alone_explains_everything_when_it_alone_varies():
    res = sobol_indices(oppenheim_arch(), Spreads(0.0, 0.1, 0.0), 256, motion=None, seed=1)
    for out in ("k_l", "k_r", "k"):
        assert res.index(out, "thickness") == pytest.approx(1.0, abs=0.1)
        assert res.index(out, "thickness", "ST") == pytest.approx(1.0, abs=0.1)
        for g in ("span", "radius"):  # inputs with no effect: exactly zero
            assert res.index(out, g) == 0.0 and res.index(out, g, "ST") == 0.0
    assert res.runs == 256 * 5 and res.unusable == 0


def test_indices_by_voussoir_are_reproducible_and_sum_sanely():
    args = (oppenheim_arch(), Spreads(0.1, 0.1, 0.05), 128)
    a = sobol_indices(*args, by="voussoir", motion=None, seed=4)
    b = sobol_indices(*args, by="voussoir", motion=None, seed=4)
    c = sobol_indices(*args, by="voussoir", motion=None, seed=5)
    assert a.groups == tuple(f"voussoir {i}" for i in range(7))
    assert np.array_equal(a.S1, b.S1) and np.array_equal(a.ST_conf, b.ST_conf)
    assert not np.array_equal(a.S1, c.S1)
    k_l = a.outputs.index("k_l")
    # first-order effects add up to at most the whole variance (within sampling error), the
    # total ones to at least it; a linear model cannot explain more than the additive part
    assert 0.6 < a.sum_S1[k_l] < 1.15 and a.sum_ST[k_l] > 0.9
    assert a.r2_linear[k_l] < a.sum_S1[k_l] + 0.15
    # as the defect map says (tests/test_defects.py: a loss on voussoirs 4-6 lowers k_l, on
    # 0-2 k_r), the right half drives k_l and the left half k_r, mirror images of each other
    st = {o: [a.index(o, f"voussoir {i}", "ST") for i in range(7)] for o in ("k_l", "k_r")}
    assert sum(st["k_l"][4:]) > 0.8 and sum(st["k_l"][:4]) < 0.2
    assert sum(st["k_r"][:3]) > 0.8 and sum(st["k_r"][3:]) < 0.2


def test_seed_zero_gives_the_same_bootstrap_intervals_twice():
    """SALib's analyze skips its seeding for seed=0 (``if seed:``): archrock passes it a seeded
    Generator, so the default seed's intervals repeat like any other seed's."""
    args = (oppenheim_arch(), Spreads(0.1, 0.1, 0.05), 64)
    a = sobol_indices(*args, motion=None, seed=0, num_resamples=50)
    b = sobol_indices(*args, motion=None, seed=0, num_resamples=50)
    assert np.array_equal(a.S1_conf, b.S1_conf) and np.array_equal(a.ST_conf, b.ST_conf)
    assert np.all(np.isfinite(a.ST_conf[~np.isnan(a.ST_conf)]))


def test_cli_sensitivity(capsys):
    assert main(["sensitivity", "--samples", "32", "--limit-only", "--json", "--no-progress"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert set(d["outputs"]) == {"k_l", "k_r", "k"} and d["runs"] == 160
    assert set(d["outputs"]["k_l"]["groups"]) == {"span", "thickness", "radius"}
    assert main(["sensitivity", "--samples", "100"]) == 2
    assert "power of two" in capsys.readouterr().err
    assert main(["sensitivity", "--spread-tilt", "3", "--samples", "16"]) == 2


# ---- issue 17: zero spreads, constant outputs and the work estimate ---------------------------
def test_zero_spreads_are_refused_with_the_fields(capsys):
    """All spreads 0 gave nan indices and R^2 = -3.47 (rounding noise decomposed)."""
    code = main(["sensitivity", "--spread-span", "0", "--spread-thickness", "0",
                 "--spread-radius", "0", "--samples", "16", "--limit-only", "--no-progress"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert err.startswith("archrock: error: spreads: all 0 (span, thickness, radius, tilt); "
                          "allowed at least one spread > 0 (--spread-span, --spread-thickness, "
                          "--spread-radius or --spread-tilt)")
    from archrock.errors import ArchInputError

    with pytest.raises(ArchInputError, match="spreads: all 0"):
        sobol_indices(oppenheim_arch(), Spreads(0.0, 0.0, 0.0), 16, motion=None)


def test_an_output_constant_up_to_rounding_has_zero_variance_and_no_indices():
    from archrock.groundmotion import PulseSpec
    from archrock.studies.sensitivity import _constant, _r2

    y = np.full(64, 0.37) + np.random.default_rng(0).normal(0, 1e-17, 64)  # noise of 1 ulp
    assert _constant(y) and np.isnan(_r2(np.zeros((64, 3)), y))
    assert not _constant(y + np.linspace(0, 1e-6, 64))
    # a weak pulse collapses no arch: the collapse has variance 0 and undefined indices
    res = sobol_indices(oppenheim_arch(), Spreads(0.05, 0.05, 0.0), 16,
                        motion=PulseSpec("oppenheim", -0.2, 0.2), seed=2)
    o = res.outputs.index("collapse")
    assert res.mean[o] == pytest.approx(0.0, abs=0) and res.variance[o] == pytest.approx(0.0, abs=0)
    assert np.all(np.isnan(res.S1[o])) and np.isnan(res.r2_linear[o])
    k = res.outputs.index("k_l")
    assert res.variance[k] > 1e-6 and np.all(np.isfinite(res.S1[k]))
    from archrock.reports.sensitivity import format_sensitivity

    text = format_sensitivity(res)
    assert "collapse: mean 0.0000, std 0 (the same on every arch): no indices" in text
    assert "nan" not in text.split("collapse: mean")[1].split("\n\n")[0]


def test_sensitivity_estimates_its_work_first(capsys, monkeypatch):
    """--samples 1048576 ran with no estimate: the bootstrap alone would hold ~10 GB."""
    code = main(["sensitivity", "--samples", "1048576", "--no-progress"])
    err = capsys.readouterr().err
    assert code == 2 and err == ("archrock: error: samples: 1048576; allowed a power of two from "
                                 "16 to 131072 (the bootstrap of 200 resamples would hold about "
                                 "10.1 GB)\n")
    from archrock.studies.sensitivity import check_sensitivity_work

    # 65536 x 5 arches with the pulse: minutes, warned; beyond the bound: refused (exit 3)
    with pytest.warns(UserWarning, match=r"sensitivity: about 3\.28e\+05 arches, estimated"):
        est = check_sensitivity_work(oppenheim_arch(), 65536, 3, sensitivity_pulse())
    assert 60.0 < est < 3600.0
    monkeypatch.setenv("ARCHROCK_MAX_WORK_S", "30")
    code = main(["sensitivity", "--samples", "65536", "--no-progress"])
    err = capsys.readouterr().err
    assert code == 3 and err.count("\n") == 1
    assert err.startswith("archrock: error: sensitivity: about 3.28e+05 arches, estimated ")
    assert "allowed up to 30 s (ARCHROCK_MAX_WORK_S); reduce --samples" in err
    # a family arch costs more per arch (pure Python perturbation)
    fam = family_arch("pointed", 10.0, 7.0, 1.0, 7)
    monkeypatch.setenv("ARCHROCK_MAX_WORK_S", "1e9")
    with pytest.warns(UserWarning):
        assert check_sensitivity_work(fam, 4096, 3, None) > 50 * \
            check_sensitivity_work(oppenheim_arch(), 4096, 3, None)


def sensitivity_pulse():
    from archrock.studies.sensitivity import PAPER_PULSE

    return PAPER_PULSE


def test_progress_lines_go_to_the_callback_and_the_cli_prints_them(capsys):
    """The library prints nothing: its progress lines go to the callback; the CLI prints them
    on stderr (and not with --no-progress)."""
    from archrock.errors import ArchInputError

    lines = []
    sobol_indices(oppenheim_arch(), Spreads(0.05, 0.05, 0.0), 16, motion=None,
                  settings=RunSettings(progress=lines.append))
    assert capsys.readouterr() == ("", "")
    assert lines[0] == "sensitivity: 80 arches (16 x (3 groups + 2))"
    assert lines[-1].startswith("sensitivity: 80/80 arches [")
    sobol_indices(oppenheim_arch(), Spreads(0.05, 0.05, 0.0), 16, motion=None)
    assert capsys.readouterr() == ("", "")
    # the one protocol (archrock._progress): anything but None, True or a callable is refused
    with pytest.raises(ArchInputError, match=r"^progress: 'yes'; allowed None, True"):
        sobol_indices(oppenheim_arch(), Spreads(0.05, 0.05, 0.0), 16, motion=None, settings={"progress": "yes"})
    assert main(["sensitivity", "--samples", "16", "--limit-only", "--json"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0] == lines[0] and err[-1].startswith("sensitivity: 80/80 arches [")
    assert main(["sensitivity", "--samples", "16", "--limit-only", "--json", "--no-progress"]) == 0
    assert capsys.readouterr().err == ""
