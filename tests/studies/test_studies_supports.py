"""Moved supports in every study (docs/supports.md, "Moved supports in the studies"): curves,
IDA/fragility, Sobol sensitivity and the assessment take a nominal arch on moved supports
(statics.supports.on_moved_supports) and move the supports of every random arch too."""

import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.geometry.displaced import SupportMovement
from archrock.geometry.sampling import ArchSampler
from archrock.statics.limit import limit_analysis
from archrock.statics.supports import (MovedSampler, displace, displacement_capacity,
                                       movement_capacity, moved_parts, on_moved_supports,
                                       study_sampler)
from archrock.studies.ensemble import EnsembleConfig
from archrock.studies.ensemble.compute import sample_arch

SPREAD = SupportMovement(0.05)


def small_arch():
    # a small semicircle: its displacements take few steps (size / 200)
    return nominal_arch(radius=1.0, embrace_deg=160, thickness=0.15, voussoirs=7)


def test_sampler_on_fixed_supports_is_the_old_one_and_on_moved_ones_the_ensembles():
    s = study_sampler(nominal_arch(), None, 3)
    assert type(s) is ArchSampler
    moved = on_moved_supports(nominal_arch(), SPREAD)
    assert moved_parts(moved)[1] == SPREAD and moved_parts(nominal_arch())[1] is None
    for draw in ("fixed", "uniform"):
        ms = study_sampler(moved, None, 3, draw)
        assert isinstance(ms, MovedSampler) and ms.movement == SPREAD
        cfg = EnsembleConfig.from_arch(nominal_arch(), samples=6, seed=3, support=SPREAD,
                                       support_draw=draw)
        listed = ms.arches(0, 6)
        for i in (0, 5):
            a, b = ms.arch(i), sample_arch(cfg, i)
            np.testing.assert_array_equal(a.joint_points, b.joint_points)
            np.testing.assert_array_equal(a.centroids, b.centroids)
            np.testing.assert_array_equal(listed[i].centroids, b.centroids)
            assert a.movement == b.movement
    # zero movement: each random arch is the fixed-support one itself
    zero = MovedSampler(nominal_arch(), seed=3, movement=SupportMovement())
    np.testing.assert_array_equal(zero.arch(2).centroids, s.arch(2).centroids)
    with pytest.raises(ArchInputError, match="point contacts"):
        study_sampler(displace(nominal_arch(), SPREAD).arch)
    with pytest.raises(ArchInputError, match="support_draw"):
        study_sampler(nominal_arch(), support_draw="uniform")


def test_movement_capacity_is_displacement_capacity_along_a_pure_movement():
    a = small_arch()
    mv = SupportMovement(-0.2, side="left")
    c, d = movement_capacity(a, mv), displacement_capacity(a, "closure", "left")
    assert c.kind == "closure" and c.capacity == d.capacity and c.mechanism == d.mechanism
    with pytest.raises(ArchInputError, match="rigid translation"):
        movement_capacity(a, SupportMovement(0.0, 0.1, "both"))


@pytest.mark.slow
def test_movement_capacity_along_a_combined_movement():
    a = nominal_arch()
    for mv, kind in ((SupportMovement(0.05), "spread"), (SupportMovement(0, -0.3), "heave")):
        c, d = movement_capacity(a, mv), displacement_capacity(a, kind, mv.side)
        assert c.kind == kind and c.capacity == d.capacity and c.mechanism == d.mechanism
    c = movement_capacity(a, SupportMovement(0.05, 0.05))
    assert c.kind == "combined" and c.reason == "fourth hinge"
    # just below the capacity along that direction the arch stands; above it, it does not
    u = SupportMovement(1.0, 1.0).scaled(1 / np.sqrt(2))
    displace(a, u.scaled(0.999 * c.capacity))
    from archrock.errors import CannotStandError
    with pytest.raises(CannotStandError):
        displace(a, u.scaled(1.001 * c.capacity))


def test_collapse_curve_on_moved_supports():
    """The paper's point, t_p = 0.2 s (n_scan 20, tol 0.01 g): 5 cm of spread of the right
    support lowers the first collapse amplitude from 1.298 g to 1.264 g (measured), and its
    scan starts at the displaced arch's k_l."""
    from archrock.dynamics.response import prepare
    from archrock.studies.curves import collapse_curve, ensemble_curve

    oppenheim = nominal_arch()
    moved = on_moved_supports(oppenheim, SPREAD)
    kw = dict(n_scan=20, tol=0.01)
    fixed = collapse_curve(prepare(oppenheim), (0.2,), **kw)
    spread = collapse_curve(prepare(moved), (0.2,), **kw)
    assert spread.k_l == pytest.approx(limit_analysis(moved).k_l, rel=1e-12)
    assert fixed.amplitudes[0] == pytest.approx(1.2982, abs=0.011)
    assert spread.amplitudes[0] == pytest.approx(1.2638, abs=0.011)
    # the band: every random arch on the same moved supports; zero movement is fixed supports
    band = ensemble_curve(moved, 3, 0, None, (0.2,), **kw)
    assert band.n_samples == 3 and band.nominal.amplitudes[0] == spread.amplitudes[0]
    zero = ensemble_curve(on_moved_supports(oppenheim, SupportMovement()), 3, 0, None, (0.2,),
                          **kw)
    ref = ensemble_curve(oppenheim, 3, 0, None, (0.2,), **kw)
    np.testing.assert_array_equal(zero.amplitudes, ref.amplitudes)
    assert not np.array_equal(band.amplitudes, ref.amplitudes)


@pytest.mark.slow
def test_random_models_on_moved_supports_leave_out_those_that_cannot_stand():
    """2 m of spread (capacity 2.268 m): four of these eight samples fall on the way, as in the
    ensemble (tests/studies/test_ensemble_supports.py), and are left out as cannot stand."""
    from archrock.dynamics.population import count_left_out
    from archrock.studies.ida import random_models

    moved = on_moved_supports(nominal_arch(), SupportMovement(2.0))
    models = random_models(moved, 8, seed=0)
    assert len(models) == 4 and count_left_out(models.failed)["cannot_stand"] == 4
    # the kept ones are the ensemble's arches on the moved supports, with the moved nominal's c_v
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=8, support=SupportMovement(2.0))
    i = models.indices[0]
    assert models[0].k_l == pytest.approx(limit_analysis(sample_arch(cfg, i)).k_l, rel=1e-12)
    from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec
    cv = ImpactSpec.parse(PAPER_PRACTICE).resolved(moved).cv
    assert models[0].impact.cv == pytest.approx(cv, rel=1e-12)


@pytest.mark.slow
def test_sobol_with_the_support_movement_as_a_factor():
    """Voussoir spreads of 0.1% and a settlement of up to 5% of the radius drawn per arch: the
    settlement explains the variance of k_l (ST near 1, the others near 0)."""
    pytest.importorskip("SALib")
    from archrock.studies.sensitivity import sobol_indices

    arch = small_arch()
    moved = on_moved_supports(arch, SupportMovement(0.0, 0.05))
    r = sobol_indices(moved, {"spread_span": 0.001, "spread_thickness": 0.001,
                              "spread_radius": 0.001}, 16, motion=None, num_resamples=20)
    assert r.groups == ("span", "thickness", "radius", "support")
    assert r.index("k_l", "support", "ST") > 0.9
    assert max(r.index("k_l", g, "ST") for g in ("span", "thickness", "radius")) < 0.05
    assert r.to_dict()["support"] == {"spread": 0.0, "settlement": 0.05, "side": "right"}
    assert "U x (settlement +0.05 m (right support))" in r.method
    # on fixed supports: no support input, as before
    f = sobol_indices(arch, None, 16, motion=None, num_resamples=20)
    assert f.groups == ("span", "thickness", "radius") and "support" not in f.to_dict()


@pytest.mark.slow
def test_assessment_section_on_moved_supports():
    from archrock.studies.assessment import assess, section_limit, section_supports

    oppenheim = nominal_arch()
    moved = on_moved_supports(oppenheim, SPREAD)
    r = assess(moved, sections=[section_limit, section_supports])
    d = r.section("supports").data
    assert d["moved"]["k_l"] == pytest.approx(limit_analysis(moved).k_l, rel=1e-12)
    assert d["fixed"]["k_l"] == pytest.approx(0.370010, abs=5e-7)
    cap = displacement_capacity(oppenheim, "spread").capacity
    assert d["capacity_remaining"] == pytest.approx(cap - 0.05, rel=1e-12)
    assert [(h["joint"], h["edge"][0]) for h in d["hinges"]] == [(1, "i"), (4, "e"), (6, "i")]
    assert d["gap_closing"]["k_l"] < 0.01
    # on fixed supports the section is left out: the report is as before
    r = assess(oppenheim, sections=[section_limit, section_supports])
    assert [s.key for s in r.sections] == ["limit"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 0, err
    return out


def test_cli_curves_on_moved_supports_and_zero_movement(capsys):
    args = ("curves", "--durations", "0.2", "--n-scan", "20", "--tol", "0.01", "--json",
            "--no-progress", "--samples", "2")
    ref = json.loads(run(capsys, *args))
    assert json.loads(run(capsys, *args, "--spread", "0")) == ref
    moved = json.loads(run(capsys, *args, "--spread", "0.05"))
    assert moved["curve"]["amplitudes_g"][0] == pytest.approx(1.2638, abs=0.011)
    assert moved["ensemble"]["n_samples"] == 2 and "support" not in ref["ensemble"]
    assert moved["ensemble"]["support"] == {"spread": 0.05, "settlement": 0.0, "side": "right"}


@pytest.mark.slow
def test_assessment_section_on_a_turned_pier():
    """A pier turned by 0.01 rad: the capacity remaining is in rad, the capacity in rotation
    less the turn so far (0.033263 rad, tests/statics/test_supports_rotation.py)."""
    from archrock.geometry import with_piers
    from archrock.studies.assessment import assess, section_supports

    arch = with_piers(nominal_arch(), 4.0, 2.0)
    r = assess(on_moved_supports(arch, SupportMovement(rotation=0.01)),
               sections=[section_supports])
    d = r.section("supports").data
    cap = displacement_capacity(arch, "rotation").capacity
    assert d["units"]["capacity"] == "rad"
    assert d["capacity_remaining"] == pytest.approx(cap - 0.01, rel=1e-12)


@pytest.mark.slow
def test_cli_fragility_and_sensitivity_on_moved_supports(capsys, tmp_path):
    """fragility and sensitivity take --spread: the random arches of fragility are the
    ensemble's on the moved supports (random_models), and sensitivity adds the input
    'support'."""
    pytest.importorskip("SALib")
    t = np.arange(0.0, 3.0, 0.01)
    rec = tmp_path / "rec.txt"
    np.savetxt(rec, np.column_stack([t, 0.3 * np.sin(2 * np.pi * 2.0 * t) * np.exp(-t)]))
    out = json.loads(run(capsys, "fragility", "--records", str(rec), "--scales", "1:8:4",
                         "--samples", "2", "--bootstrap", "0", "--spread", "0.5", "--json",
                         "--no-progress"))
    assert out["arch"] == "Oppenheim (displaced) (joints re-closed)" and out["n_arches"] == 2
    out = json.loads(run(capsys, "sensitivity", "--spread", "0.2", "--samples", "16", "--json",
                         "--no-progress"))
    assert out["support"]["spread"] == 0.2
    assert "support" in out["outputs"]["k_l"]["groups"]
