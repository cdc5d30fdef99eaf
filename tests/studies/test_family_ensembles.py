"""Irregular arches of every family: the sampler, the general batch path and ensembles."""

import json

import numpy as np
import pytest

from archrock import groundmotion as gm
from archrock.dynamics.batch import prepare_batch, simulate_batch
from archrock.errors import ArchInputError, InvalidSampleError
from archrock.geometry import (FamilyArch, PolygonArch, arch_from_dict, as_polygon, family_arch,
                               oppenheim_arch)
from archrock.geometry.irregular import perturb_family
from archrock.statics.limit import limit_analysis, static_multiplier
from archrock.dynamics.response import prepare, respond
from archrock.geometry.sampling import ArchSampler, Spreads


@pytest.fixture(scope="module")
def pointed():
    return family_arch("pointed", 10.0, 7.0, 1.0, 12, exact=False)


def test_circular_stream_unchanged_without_tilt():
    s = ArchSampler(oppenheim_arch(), Spreads(), 0)
    assert s.uniforms(3, 4).shape == (4, 3, 7)
    spans, thick, radii = s.draw(3, 4)
    arches = s.arches(3, 4)
    for j, a in enumerate(arches):
        np.testing.assert_array_equal(a.spans, spans[j])
        np.testing.assert_array_equal(a.radii, s.arch(3 + j).radii)
    assert Spreads().to_dict() == {"span": 0.1, "thickness": 0.1, "radius": 0.05, "tilt": 0.0}
    assert Spreads().legacy_dict() == {"spread_span": 0.1, "spread_thickness": 0.1,
                                       "spread_radius": 0.05}


def test_tilt_spread_serialises_and_reads_four_rows(pointed):
    sp = Spreads(0.1, 0.1, 0.05, 2.0)
    assert sp.to_dict()["tilt"] == 2.0 and Spreads.from_dict(sp.to_dict()) == sp
    assert sp.legacy_dict()["spread_tilt_deg"] == 2.0 and Spreads.from_dict(sp.legacy_dict()) == sp
    assert ArchSampler(pointed, sp, 0).uniforms(0, 2).shape == (2, 4, 12)
    with pytest.raises(ArchInputError, match="spread tilt"):
        Spreads(tilt=60)
    with pytest.raises(ArchInputError, match="spread tilt"):
        ArchSampler(oppenheim_arch(), sp, 0)


def test_surveyed_polygon_keeps_its_joints():
    """A polygon arch without a family is perturbed as a survey (geometry.survey): a span or
    tilt spread, which would move a measured joint, is refused by name."""
    with pytest.raises(ArchInputError, match="spread span and tilt: 0.1 and 0; allowed 0 and 0"):
        ArchSampler(as_polygon(oppenheim_arch(), 5), Spreads(), 0)
    sampler = ArchSampler(as_polygon(oppenheim_arch(), 5), Spreads(0.0, 0.1, 0.05), 0)
    assert sampler.arch(0).n == 7


def test_zero_draw_is_the_nominal_family_arch(pointed):
    b = perturb_family(pointed, np.zeros((3, 12)), 0.1, 0.1, 0.05)
    np.testing.assert_allclose(b.joint_points, pointed.joint_points, rtol=0, atol=1e-4)
    np.testing.assert_allclose(b.masses, pointed.masses, rtol=1e-5)


def test_family_dict_rebuilds_the_family_arch(pointed):
    back = arch_from_dict(json.loads(json.dumps(pointed.to_dict())))
    assert isinstance(back, FamilyArch)
    np.testing.assert_array_equal(back.joint_points, pointed.joint_points)


def test_tilt_changes_joints_and_static_equals_kinematic(pointed):
    plain = ArchSampler(pointed, Spreads(0.0, 0.0, 0.0, 0.0), 1).arch(0)
    tilted = ArchSampler(pointed, Spreads(0.0, 0.0, 0.0, 3.0), 1).arch(0)
    assert np.abs(tilted.joint_points - plain.joint_points)[1:-1].max() > 1e-3
    np.testing.assert_allclose(tilted.joint_points[[0, -1]], plain.joint_points[[0, -1]],
                               atol=1e-9)
    res = limit_analysis(tilted)
    for d in ("l", "r"):
        lam = static_multiplier(tilted, d)[0]
        assert lam == pytest.approx(res.mechanism(d).multiplier, rel=1e-8)


@pytest.mark.parametrize("shape,rise", [("pointed", 7.0), ("elliptical", 4.0)])
def test_batch_rows_are_single_arch_limit_analysis(shape, rise):
    nom = family_arch(shape, 10.0, rise, 1.0, 12, exact=False)
    s = ArchSampler(nom, Spreads(0.1, 0.1, 0.05, 1.0), 3)
    arches = s.arches(0, 5)
    pb = prepare_batch(arches, impact=0.8)
    for b, a in enumerate(arches):
        r = limit_analysis(s.arch(b))
        # the compiled batch and the one-arch limit analysis are two paths: k to rounding
        assert pb.k_l[b] == pytest.approx(r.k_l, rel=1e-12)
        assert pb.k_r[b] == pytest.approx(r.k_r, rel=1e-12)
        assert pb.mech_l[b] == r.mechanism("l").label and pb.mech_r[b] == r.mechanism("r").label


def test_batch_responds_as_respond(pointed):
    s = ArchSampler(pointed, Spreads(0.1, 0.1, 0.05), 0)
    arches = s.arches(0, 3)
    pb = prepare_batch(arches, impact=0.8)
    motion = gm.oppenheim_pulse(-0.5, 0.2)
    res = simulate_batch(pb, motion)
    for b, a in enumerate(arches):
        r = respond(prepare(a, 0.8), motion, integrator="fast")
        assert res["status"][b] == {"rest": 0, "collapsed": 1, "moving": 2}[r.status]
        assert res["peak"][b] == pytest.approx(r.peak, rel=1e-9)


def test_batch_rows_of_invalid_draws_and_circular_arches():
    err = InvalidSampleError("not a valid arch: something")
    a = oppenheim_arch()
    pb = prepare_batch([a, err], impact=0.8)
    assert pb.error[0] == "" and pb.error[1].startswith("geometry:")
    ref = prepare_batch(a.spans, a.radii, a.thicknesses, impact=0.8)
    assert pb.k_l[0] == ref.k_l[0] and np.array_equal(pb.geo_l[0], ref.geo_l[0])


def test_ensemble_of_pointed_arches_matches_single_arch_analysis(pointed):
    pytest.importorskip("pandas")
    from archrock.studies.ensemble import EnsembleConfig
    from archrock.studies.ensemble.compute import run_batch

    cfg = EnsembleConfig.from_arch(pointed, samples=6, seed=2, batch_size=3,
                                   spreads=Spreads(0.1, 0.1, 0.05, 2.0), impact=0.8)
    assert EnsembleConfig.from_dict(json.loads(cfg.to_json())).to_json() == cfg.to_json()
    df, _ = run_batch(cfg, 1)
    for row in df.itertuples():
        r = limit_analysis(cfg.sampler.arch(int(row.index)))
        # the ensemble's compiled batch vs one arch: to rounding
        assert row.k_l == pytest.approx(r.k_l, rel=1e-12)
        assert row.k_r == pytest.approx(r.k_r, rel=1e-12)


def test_ensemble_refuses_a_span_spread_on_a_surveyed_polygon():
    from archrock.studies.ensemble import EnsembleConfig

    with pytest.raises(ArchInputError, match="--spread-span 0"):
        EnsembleConfig.from_arch(as_polygon(oppenheim_arch(), 5), samples=2)


def test_cli_ensemble_of_pointed_arches_with_tilt(capsys):
    pytest.importorskip("pandas")
    from archrock.cli import main

    code = main(["ensemble", "--shape", "pointed", "--span", "10", "--rise", "7", "--thickness",
                 "1", "--voussoirs", "12", "--spread-tilt", "2", "--samples", "4", "--cv", "0.8",
                 "--pulse", "oppenheim", "--amplitude", "-1", "--pulse-duration", "0.2",
                 "--no-progress", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["nominal"]["k_l"] > 0
