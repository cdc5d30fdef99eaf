"""Ensembles on moved supports (EnsembleConfig.support, docs/supports.md): each sample analysed
re-closed on its moved supports, fixed-support configurations unchanged."""

import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.errors import ArchInputError, CannotStandError
from archrock.geometry import nominal_arch
from archrock.geometry.displaced import SupportMovement
from archrock.statics.limit import limit_analysis
from archrock.statics.supports import displace, reclosed
from archrock.studies.ensemble import EnsembleConfig, run_ensemble
from archrock.studies.ensemble.compute import sample_arch


def test_zero_or_no_movement_keeps_the_configuration_and_its_hash():
    a = EnsembleConfig.from_arch(nominal_arch(), samples=10)
    b = EnsembleConfig.from_arch(nominal_arch(), samples=10, support=SupportMovement(0.0))
    assert a.to_json() == b.to_json() and a.config_hash() == b.config_hash()
    assert a.to_dict()["support"] is None and "support" not in a.legacy_dict()
    c = EnsembleConfig.from_arch(nominal_arch(), samples=10, support={"spread": 0.2})
    assert c.to_dict()["support"] == {"spread": 0.2, "settlement": 0.0, "side": "right"}
    assert EnsembleConfig.from_dict(json.loads(c.to_json())) == c
    with pytest.raises(ArchInputError, match="support"):
        EnsembleConfig.from_arch(nominal_arch(), samples=10, support="far")


def test_each_row_is_its_arch_on_moved_supports():
    mv = SupportMovement(0.5, 0.2, "left")
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=6, seed=3, batch_size=3, support=mv)
    res = run_ensemble(cfg)
    nom = reclosed(displace(nominal_arch(), mv).arch)
    assert res.nominal["k_l"] == pytest.approx(limit_analysis(nom).k_l, rel=1e-12)
    fixed = run_ensemble(EnsembleConfig.from_arch(nominal_arch(), samples=6, seed=3)).frame
    for row, k_fixed in zip(res.frame.itertuples(), fixed["k_l"]):
        arch = sample_arch(cfg, row.index)
        assert arch.movement == mv and not arch.point_joints  # re-closed
        r = limit_analysis(arch)
        assert row.k_l == pytest.approx(r.k_l, rel=1e-12)
        assert row.k_r == pytest.approx(r.k_r, rel=1e-12)
        assert abs(row.k_l - k_fixed) > 1e-4  # the movement changed the arch


def test_an_arch_that_cannot_stand_on_its_moved_supports_is_counted_so():
    """2 m of spread: Oppenheim's arch stands (capacity 2.268 m), four of these eight samples
    collapse on the way (at 1.87-1.90 m) and count as "cannot stand", not as invalid draws."""
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=8, seed=0,
                                   support=SupportMovement(2.0))
    res = run_ensemble(cfg)
    bad = [e for e in res.frame["error"] if e]
    assert len(bad) == 4 and all("cannot stand on its moved supports" in e for e in bad)
    assert res.summary()["outcomes"]["counts"]["cannot_stand"] == 4
    with pytest.raises(CannotStandError, match="cannot stand"):  # the nominal itself
        run_ensemble(EnsembleConfig.from_arch(nominal_arch(), samples=2,
                                              support=SupportMovement(3.0)))


def test_cli_ensemble_moves_supports_and_other_studies_refuse(capsys):
    code = main(["ensemble", "--samples", "4", "--spread", "0.5", "--json", "--no-progress"])
    out, err = capsys.readouterr()
    assert code == 0, err
    nom = reclosed(displace(nominal_arch(), SupportMovement(0.5)).arch)
    assert json.loads(out)["nominal"]["k_l"] == pytest.approx(limit_analysis(nom).k_l, rel=1e-12)
    code = main(["random-arch", "--spread", "0.5"])
    _, err = capsys.readouterr()
    assert code != 0 and "moved supports" in err


def test_a_movement_drawn_per_arch():
    """support_draw='uniform': sample i takes U_i x the movement, U_i on [0, 1] from its own
    stream (the arches' draws unchanged, independent of the batch size); each row is its arch
    on its own moved supports."""
    from archrock.geometry.sampling import ArchSampler

    mv = SupportMovement(0.0, 0.8)
    s = ArchSampler(nominal_arch(), seed=5)
    u = s.movement_fractions(0, 1200)
    assert 0.0 <= u.min() and u.max() < 1.0 and abs(u.mean() - 0.5) < 0.03
    np.testing.assert_array_equal(s.movement_fractions(498, 5), u[498:503])  # across blocks
    np.testing.assert_array_equal(s.uniforms(0, 3), ArchSampler(nominal_arch(), seed=5)
                                  .uniforms(0, 3))
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=5, seed=5, batch_size=2, support=mv,
                                   support_draw="uniform")
    assert cfg.to_dict()["support_draw"] == "uniform"
    assert EnsembleConfig.from_dict(json.loads(cfg.to_json())) == cfg
    res = run_ensemble(cfg)
    for row in res.frame.itertuples():
        arch = sample_arch(cfg, row.index)
        assert arch.movement == mv.scaled(float(u[row.index]))
        assert row.k_l == pytest.approx(limit_analysis(arch).k_l, rel=1e-12)
    with pytest.raises(ArchInputError, match="support_draw"):
        EnsembleConfig.from_arch(nominal_arch(), samples=5, support_draw="uniform")
    with pytest.raises(ArchInputError, match="support_draw"):
        EnsembleConfig.from_arch(nominal_arch(), samples=5, support=mv, support_draw="normal")
