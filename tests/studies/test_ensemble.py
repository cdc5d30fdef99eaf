"""Monte Carlo ensembles: nominal limit, reproducibility across executors, resume, summary."""

import hashlib
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from archrock.studies.ensemble import (COLUMNS, EnsembleConfig, EnsembleConfigMismatch, run_batch,
                                       run_ensemble, sample_arch)
from archrock.errors import ArchInputError
from archrock.studies.fragility import collapse_probability
from archrock.studies.runner import RunSettings
from archrock.geometry import oppenheim_arch
from archrock.groundmotion import PulseSpec
from archrock.dynamics.impact import ImpactSpec
from archrock.geometry.sampling import DEFAULT_SPREADS, ArchSampler, Spreads
from archrock.statics.limit import limit_analysis

DATA = Path(__file__).resolve().parents[1] / "data"

PULSE = PulseSpec("oppenheim", -1.0, 0.2)


def config(**kw):
    """An ensemble configuration; spread_* and impact/cv keywords become Spreads / ImpactSpec."""
    spreads = {k: kw.pop(k) for k in list(kw) if k.startswith("spread_")}
    impact = ImpactSpec.parse(kw.pop("impact", "fixed"), cv=kw.pop("cv", 0.8754))
    base = dict(samples=40, batch_size=10, seed=11, motion=PULSE, impact=impact,
                spreads=Spreads.from_dict({**DEFAULT_SPREADS.legacy_dict(), **spreads}))
    base.update(kw)
    return EnsembleConfig.from_arch(oppenheim_arch(), **base)


@pytest.fixture(scope="module")
def base():
    return run_ensemble(config())


def test_zero_spreads_every_sample_is_the_nominal_arch():
    cfg = config(samples=15, batch_size=4, spread_span=0.0, spread_thickness=0.0, spread_radius=0.0)
    res = run_ensemble(cfg)
    df = res.frame
    assert len(df) == 15
    np.testing.assert_allclose(df["k_l"], 0.3700, atol=5e-5)
    np.testing.assert_allclose(df["k_r"], 0.3700, atol=5e-5)
    assert set(df["mech_l"]) == {"0i-3e-5i-7e"} and set(df["mech_r"]) == {"0e-2i-4e-7i"}
    assert not df["collapsed"].any()
    assert set(df["status"]) == {"rest"}
    # identical arches, identical responses: the nominal arch rocks and recovers
    assert df["peak"].nunique() == 1 and df["peak"].iloc[0] > 0.02
    assert (df["n_impacts"] > 10).all()
    s = res.summary()
    assert s["p_collapse"]["p"] == 0.0 and s["p_collapse"]["high"] < 0.25
    assert s["k_l"]["std"] == pytest.approx(0.0, abs=1e-12)


def test_frame_columns_and_values(base):
    df = base.frame
    assert list(df.columns) == COLUMNS
    assert df["index"].tolist() == list(range(40))
    assert df["batch"].tolist() == [i // 10 for i in range(40)]
    assert (df["error"] == "").all()
    assert df["k_l"].between(0.2, 0.5).all() and df["k_r"].between(0.2, 0.5).all()
    assert df["k_l"].std() > 0.005  # the spreads do perturb the multipliers
    # a sample's row is the limit analysis of the arch rebuilt from the seed
    for i in (0, 13, 39):
        lim = limit_analysis(sample_arch(base.config, i), verify=False)
        assert df["k_l"][i] == pytest.approx(lim.k_l, abs=1e-12)
        assert df["k_r"][i] == pytest.approx(lim.k_r, abs=1e-12)
    assert df["collapsed"].tolist() == (df["status"] == "collapsed").tolist()
    col = df[df["collapsed"]]
    assert (col["t_collapse"] >= col["t_unstable"]).all()
    # the collapse (last passage of phi_u) comes before the numerical stop at the limit
    assert (col["t_limit"] > col["t_collapse"]).all()
    assert df.loc[~df["collapsed"], "t_collapse"].isna().all()
    assert df.loc[~df["collapsed"], "t_limit"].isna().all()


def test_summary_numbers(base):
    df, s = base.frame, base.summary()
    assert s["samples"] == 40
    assert s["k_l"]["mean"] == pytest.approx(np.mean(df["k_l"].to_numpy()), rel=1e-12)
    assert s["k_l"]["std"] == pytest.approx(np.std(df["k_l"].to_numpy(), ddof=1), rel=1e-12)
    assert s["k_r"]["mean"] == pytest.approx(np.mean(df["k_r"].to_numpy()), rel=1e-12)
    n_col = int(df["collapsed"].sum())
    assert 0 < n_col < 40
    p, lo, hi = collapse_probability(n_col, 40)
    assert s["p_collapse"]["p"] == pytest.approx(n_col / 40)
    assert (s["p_collapse"]["low"], s["p_collapse"]["high"]) == pytest.approx((lo, hi))
    assert sum(s["hinge_patterns"]["M_l"].values()) == 40
    assert s["hinge_patterns"]["M_l"]["0i-3e-5i-7e"] == int((df["mech_l"] == "0i-3e-5i-7e").sum())
    k0 = s["nominal"]["k_l"]
    share = np.mean(np.abs(df["k_l"] - k0) >= abs(0.4111 - k0))
    assert s["as_far_as"]["RA-1"]["k_l"] == pytest.approx(share)
    asym = np.mean(np.abs(df["k_l"] - df["k_r"]) >= abs(0.3946 - 0.3501))
    assert s["as_far_as"]["RA-2"]["asymmetry"] == pytest.approx(asym)
    json.dumps(s, allow_nan=False)


@pytest.mark.slow  # a process pool on a shared 2-core runner: ~30-60 s
def test_same_seed_same_results_with_two_workers(base):
    res2 = run_ensemble(config(), settings=RunSettings(workers=2))
    pd.testing.assert_frame_equal(base.frame, res2.frame)
    other = run_ensemble(config(seed=12, samples=10))
    assert not np.allclose(other.frame["k_l"], base.frame["k_l"][:10])


def test_batches_are_self_contained(base):
    df, _ = run_batch(config(), 2)
    pd.testing.assert_frame_equal(df.reset_index(drop=True),
                                  base.frame.iloc[20:30].reset_index(drop=True))


@pytest.mark.parametrize("early_stop", [False, True])
def test_batches_computed_together_give_each_batchs_rows(early_stop):
    """In-process, consecutive batches are computed in one call (run_batches); every arch is
    computed on its own, so each batch's table is the one it gets alone, also for a last,
    shorter batch, and timings are shared out by size."""
    from archrock.studies.ensemble.compute import run_batches

    cfg = config(samples=45, early_stop=early_stop)
    together = run_batches(cfg, [1, 2, 3, 4])
    assert [b for b, _, _ in together] == [1, 2, 3, 4]
    for b, df, timings in together:
        alone = run_batches(cfg, [b])[0][1]
        pd.testing.assert_frame_equal(df, alone)
        assert list(df["batch"]) == [b] * len(df) and len(df) == cfg.batch_range(b)[1]
        assert timings["response_s"] > 0
    assert len(together[-1][1]) == 5
    with pytest.raises(ArchInputError, match="batches: .*consecutive"):
        run_batches(cfg, [1, 3])


def test_in_process_groups_runs_of_consecutive_batches(monkeypatch):
    from archrock.studies.ensemble import executors

    monkeypatch.setattr(executors, "GROUP_ARCHES", 25)
    cfg = config(samples=95)  # batches of 10, the last of 5
    assert executors._groups(cfg, [0, 1, 2, 3, 5, 6, 9]) == [[0, 1], [2, 3], [5, 6], [9]]
    assert executors._groups(cfg, [7, 8, 9]) == [[7, 8, 9]]  # 10 + 10 + 5 arches
    monkeypatch.setattr(executors, "GROUP_ARCHES", 1)
    assert executors._groups(cfg, [0, 1]) == [[0], [1]]
    # a resumed run computes only the missing batches, grouped, with the same rows
    full = run_ensemble(config(samples=95)).frame
    monkeypatch.setattr(executors, "GROUP_ARCHES", 4000)
    pd.testing.assert_frame_equal(run_ensemble(config(samples=95)).frame, full)


def test_resume_recomputes_only_the_missing_batch(base, tmp_path):
    out = tmp_path / "ens"
    first = run_ensemble(config(), settings=RunSettings(out=out))
    pd.testing.assert_frame_equal(first.frame, base.frame)
    files = sorted(p.name for p in (out / "batches").iterdir())
    assert files == [f"batch-{b:05d}.parquet{x}" for b in range(4) for x in ("", ".sha256")]
    (out / "batches" / "batch-00002.parquet").unlink()
    # a half-written file of a killed run (its process is gone) is removed
    stale = out / "batches" / "batch-00003.parquet.tmp-99999999"
    stale.write_bytes(b"partial")
    again = run_ensemble(config(), settings=RunSettings(out=out))
    pd.testing.assert_frame_equal(again.frame, base.frame)
    assert again.timing["computed_batches"] == [2]
    assert again.timing["loaded_batches"] == [0, 1, 3]
    assert again.timing["recomputed_batches"] == {}  # a missing file is simply computed
    assert not stale.exists()
    manifest = json.loads((out / "manifest.json").read_text())
    assert [r["computed"] for r in manifest["runs"]] == [[0, 1, 2, 3], [2]]
    assert manifest["config"] == config().to_dict()
    assert manifest["seeds"]["entropy"] == 11
    assert manifest["versions"]["numpy"] == np.__version__
    assert manifest["finished"] is not None
    assert manifest["batches"]["2"]["run"] == 1 and manifest["batches"]["0"]["run"] == 0


def test_progress_callable_receives_the_resume_notes(base, tmp_path, capsys):
    out = tmp_path / "ens"
    run_ensemble(config(), settings=RunSettings(out=out))
    (out / "batches" / "batch-00001.parquet").write_bytes(b"damaged")
    lines = []
    again = run_ensemble(config(), settings=RunSettings(out=out, progress=lines.append))
    pd.testing.assert_frame_equal(again.frame, base.frame)
    assert capsys.readouterr().err == ""
    assert any("recomputing batch 1: batch-00001.parquet damaged: its sha256" in x for x in lines)
    assert lines[-1].startswith("ensemble: ") and lines[-1].endswith("(100%)")


def test_the_0_6_keywords_are_gone(tmp_path):
    """0.7 removed out=, out_dir=, workers=, scheduler=, progress= (and ``out`` positional):
    Python's own TypeError names the keyword, and nothing is written."""
    for kw in ({"out": tmp_path / "a"}, {"out_dir": tmp_path / "a"}, {"workers": 2},
               {"scheduler": "tcp://127.0.0.1:1"}, {"progress": None}):
        with pytest.raises(TypeError, match=f"unexpected keyword argument '{next(iter(kw))}'"):
            run_ensemble(config(samples=2), **kw)
    with pytest.raises(TypeError, match="positional argument"):
        run_ensemble(config(samples=2), tmp_path / "a")
    assert not (tmp_path / "a").exists()


def test_resume_refuses_another_configuration(tmp_path):
    out = tmp_path / "ens"
    run_ensemble(config(samples=10), settings=RunSettings(out=out))
    with pytest.raises(EnsembleConfigMismatch, match="'seed' is 11 there and 12 here"):
        run_ensemble(config(samples=10, seed=12), settings=RunSettings(out=out))


def test_dask_local_cluster(base):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1,
                                  dashboard_address=None) as cluster:
        res = run_ensemble(config(), settings=RunSettings(scheduler=cluster.scheduler_address))
    assert res.timing["executor"] == "dask"
    pd.testing.assert_frame_equal(res.frame, base.frame)


def test_limit_only_without_motion():
    res = run_ensemble(config(samples=12, motion=None))
    s = res.summary()
    assert s["p_collapse"] is None and s["response"] is None
    assert set(res.frame["status"]) == {"limit-only"}
    assert res.frame["peak"].isna().all()


def test_paper_impact_failures_are_counted():
    # wide spreads: the per-geometry 'paper' impact model creates energy on many arches
    res = run_ensemble(config(samples=100, batch_size=50, impact="paper", cv=None, seed=0,
                              spread_span=0.3, spread_thickness=0.3, spread_radius=0.2))
    s = res.summary()
    failed = res.frame[res.frame["error"] != ""]
    assert len(failed) >= 10 and (failed["status"] == "failed").all()
    assert failed["peak"].isna().all() and not failed["collapsed"].any()
    assert s["failed"]["count"] == len(failed)
    assert sum(s["failed"]["reasons"].values()) == len(failed)
    assert any("creates energy" in r for r in s["failed"]["reasons"])
    assert s["p_collapse"]["trials"] == 100 - len(failed)
    used = res.frame[res.frame["error"] == ""]
    # the laws that were used never create energy: c_lr * c_rl <= 1 (energy ratios multiply to it)
    assert (used["c_l_to_r"] * used["c_r_to_l"] <= 1 + 1e-9).all()
    # their k is still known: the k statistics use every sample with finite k
    assert s["k_l"]["count"] == int(np.isfinite(res.frame["k_l"]).sum()) >= 99


def test_nominal_paper_impact_is_the_papers_cv():
    res = run_ensemble(config(samples=3, impact="nominal-paper", cv=None))
    assert res.impact["applied"]["cv"] == pytest.approx(0.8754, abs=5e-5)
    assert res.impact["model"] == "paper" and res.impact["on"] == "nominal"
    assert res.frame["c_l_to_r"].tolist() != [] and np.isfinite(res.frame["c_l_to_r"]).all()


@pytest.mark.parametrize("kw, field", [
    ({"samples": 0}, "samples"), ({"spread_span": -0.1}, "spread span"),
    ({"spread_radius": 1.0}, "spread radius"), ({"batch_size": 0}, "batch size"),
    ({"impact": "fixed", "cv": -0.1}, "cv"), ({"impact": "elastic"}, "impact model"),
    ({"motion": "oppenheim"}, "motion: 'oppenheim'; allowed None, a PulseSpec or RecordSpec"),
    ({"motion": {"type": "pulse", "kind": "oppenheim", "amplitude_g": -1.0, "duration": -0.2}},
     "pulse duration"),
])
def test_bad_configuration(kw, field):
    with pytest.raises(ArchInputError, match=field):
        config(**kw)


def test_motion_specification_serialises_as_the_manifests_dict():
    c = config()
    d = c.to_dict()
    assert d["motion"] == {"type": "pulse", "kind": "oppenheim", "amplitude_g": -1.0, "duration": 0.2}
    # a dict (as read from a manifest) becomes the specification; the round trip is exact
    assert config(motion=d["motion"]).motion == PULSE
    assert EnsembleConfig.from_dict(json.loads(c.to_json())) == c
    # the configuration's hash (batch provenance) is pinned: a change of a field's serialised
    # form invalidates every stored batch, so it must be deliberate (and bump store.FORMAT)
    # (computed from archrock 0.4's form of the configuration, EnsembleConfig.legacy_dict)
    legacy = json.dumps(c.legacy_dict(), sort_keys=True)
    assert c.config_hash() == hashlib.sha256(legacy.encode()).hexdigest() == (
        "752ea31c1cdc51dfcc1b68757ec11ab5ea014a3de3a820561b0f11c71fe48ed8")


def test_bad_workers():
    with pytest.raises(ArchInputError, match="workers"):
        run_ensemble(config(samples=2), settings=RunSettings(workers=0))


# ---------------------------------------------------------------------------- command line
def cli(capsys, *argv):
    from archrock.cli import main

    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_json_summary(capsys):
    code, out, err = cli(capsys, "ensemble", "--samples", "20", "--json", "--no-progress")
    assert code == 0, err
    s = json.loads(out)
    assert s["samples"] == 20
    assert set(s["k_l"]) >= {"mean", "std"} and set(s["k_r"]) >= {"mean", "std"}
    assert 0.3 < s["k_l"]["mean"] < 0.4 and s["k_l"]["std"] > 0.005
    assert s["p_collapse"] is None
    # the same ensemble through the library
    lib = run_ensemble(EnsembleConfig.from_arch(oppenheim_arch(), samples=20))
    assert s["k_l"]["mean"] == pytest.approx(lib.summary()["k_l"]["mean"], rel=1e-12)


def test_cli_pulse_out_resume_and_plot(capsys, tmp_path):
    args = ["ensemble", "--samples", "12", "--batch-size", "5", "--seed", "3", "--pulse", "oppenheim",
            "--amplitude", "-1", "--pulse-duration", "0.2", "--cv", "0.8754", "--out",
            str(tmp_path / "e"), "--json", "--no-progress"]
    code, out, err = cli(capsys, *args, "--plot", str(tmp_path / "k.png"))
    assert code == 0, err
    s = json.loads(out)
    assert s["p_collapse"]["trials"] == 12 and 0 <= s["p_collapse"]["p"] <= 1
    assert s["impact"]["model"] == "fixed" and s["impact"]["cv"] == 0.8754
    assert s["impact"]["applied"] == s["impact"]["applied"] | {"model": "fixed", "cv": 0.8754}
    assert (tmp_path / "k.png").stat().st_size > 5000
    code, out2, err = cli(capsys, *args)
    s2 = json.loads(out2)
    assert s2["timing"]["loaded_batches"] == [0, 1, 2] and s2["timing"]["computed_batches"] == []
    assert s2["p_collapse"] == s["p_collapse"] and s2["k_r"] == s["k_r"]
    code, _, err = cli(capsys, *args[:-4], "--seed", "4", "--out", str(tmp_path / "e"))
    assert code == 2 and "'seed' is 3 there and 4 here" in err


@pytest.mark.parametrize("argv, field", [
    (["--samples", "0"], "samples"), (["--spread-thickness", "-0.1"], "spread thickness"),
    (["--workers", "0"], "workers"), (["--batch-size", "0"], "batch size"),
    (["--cv", "0.8", "--impact", "paper"], "--cv"),
])
def test_cli_bad_input(capsys, argv, field):
    code, out, err = cli(capsys, "ensemble", "--samples", "3", *argv)
    assert code == 2
    assert err.startswith("archrock: error: ") and field in err and err.count("\n") == 1


def test_cli_text_output_without_a_finite_k(capsys):
    # the only sample's geometry is invalid: no k, so no k statistics nor shares ('-')
    code, out, err = cli(capsys, "ensemble", "--samples", "1", "--seed", "1", "--spread-radius",
                         "0.99", "--spread-thickness", "0.99", "--no-progress")
    assert code == 0, err
    assert "as far from nominal as RA-1: k_l -, k_r -, either -, asymmetry |k_l-k_r| -" in out
    assert "failed samples: 1" in out


def _unused_port():
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_unreachable_scheduler_is_a_one_line_error(capsys, monkeypatch):
    pytest.importorskip("distributed")
    import time

    from archrock.studies import executors  # the one executor family

    monkeypatch.setattr(executors, "SCHEDULER_TIMEOUT_S", 1.0)
    address = f"127.0.0.1:{_unused_port()}"
    t0 = time.perf_counter()
    with pytest.raises(ArchInputError, match=f"scheduler: cannot connect to '{address}'"):
        run_ensemble(config(samples=2), settings=RunSettings(scheduler=address))
    code, out, err = cli(capsys, "ensemble", "--samples", "2", "--scheduler", address,
                         "--no-progress")
    assert code == 2 and err.startswith("archrock: error: scheduler: cannot connect to ")
    assert err.count("\n") == 1 and "Traceback" not in err
    assert time.perf_counter() - t0 < 10


def test_event_table_overflow_is_flagged_not_failed(base, monkeypatch):
    from archrock.studies.ensemble import compute

    monkeypatch.setattr(compute, "MAX_EVENTS", 8)
    res = run_ensemble(config())
    df, ref = res.frame, base.frame
    over = df["events_truncated"].to_numpy()
    assert over.any() and not ref["events_truncated"].any()
    assert (df["error"] == "").all()
    # the counts too: impacts and activations are counted as they happen, past the table
    for col in ("status", "collapsed", "peak", "t_collapse", "t_unstable", "n_impacts",
                "n_activations"):
        pd.testing.assert_series_equal(df[col], ref[col])
    s = res.summary()
    assert s["failed"]["count"] == 0 and s["p_collapse"] == base.summary()["p_collapse"]
    assert s["response"]["events_truncated"] == int(over.sum())


def test_summary_leaves_out_arches_that_cannot_stand_and_collapsed_peaks(base):
    from archrock.studies.ensemble import EnsembleResult

    df = base.frame.copy()
    df.loc[0, ["k_l", "k_r"]] = [-0.05, 0.2]
    df.loc[0, "error"] = "limit analysis: the arch cannot stand (k_l = -0.05, k_r = 0.2)"
    df.loc[0, ["mech_l", "mech_r", "status"]] = ["", "", "failed"]
    df.loc[0, "collapsed"] = False
    s = EnsembleResult(base.config, df, base.nominal, base.impact).summary()
    rest = base.frame.iloc[1:]
    assert s["failed"]["count"] == 1
    assert s["k_l"]["count"] == s["k_r"]["count"] == 39
    assert s["k_l"]["mean"] == pytest.approx(rest["k_l"].mean(), rel=1e-12)
    assert s["k_min"]["min"] == pytest.approx(np.minimum(rest["k_l"], rest["k_r"]).min())
    k0 = s["nominal"]["k_l"]
    assert s["as_far_as"]["RA-1"]["k_l"] == pytest.approx(
        np.mean(np.abs(rest["k_l"] - k0) >= abs(0.4111 - k0)))
    assert s["p_collapse"]["trials"] == 39
    # collapsed samples' peak is their rotation limit: peak statistics cover the survivors only
    survived = df[(df["status"] != "failed") & ~df["collapsed"]]
    assert s["response"]["peak_rad"]["count"] == len(survived)
    assert s["response"]["peak_rad"]["max"] == pytest.approx(survived["peak"].max())


def test_one_sample_has_no_std():
    s = run_ensemble(config(samples=1, motion=None)).summary()
    assert s["k_l"]["count"] == 1 and s["k_l"]["std"] is None and s["k_l"]["mean"] is not None
    # nor a 5-95% range: one value would print as a zero-width one
    assert s["k_l"]["q05"] is None and s["k_l"]["q95"] is None and "one sample" in s["k_l"]["note"]
    assert s["k_l"]["median"] == s["k_l"]["mean"] == s["k_l"]["min"]
    from archrock.reports import format_ensemble

    out = format_ensemble(s, "Oppenheim")
    assert "std n/a (one sample), 5-95% n/a (one sample)" in out
    assert s["outcomes"]["counts"]["limit_only"] == 1 and s["p_failure"] is None


def _with_outcomes(base):
    """The base frame with sample 0 unable to stand, 1 an invalid draw, 2 no mechanism and 3 an
    impact law that creates energy (the messages of batch.prepare_batch)."""
    from archrock.studies.ensemble import EnsembleResult

    df = base.frame.copy()
    errors = ["limit analysis: the arch cannot stand (k_l = -0.05, k_r = 0.2)",
              "geometry: two neighbouring voussoirs do not overlap radially",
              "limit analysis: no admissible four-hinge mechanism",
              "impact l_to_r: the 'paper' model creates energy on this geometry (kinetic energy "
              "ratio 1.2, rate ratio 0.9); use the momentum law (ImpactSpec model "
              "'momentum'; --impact momentum) or a fixed c_v (ImpactSpec cv; --cv)"]
    for i, e in enumerate(errors):
        df.loc[i, ["error", "status", "mech_l", "mech_r"]] = [e, "failed", "", ""]
        df.loc[i, "collapsed"] = False
    df.loc[0, ["k_l", "k_r"]] = [-0.05, 0.2]
    df.loc[[1, 2], ["k_l", "k_r"]] = np.nan
    return df, EnsembleResult(base.config, df, base.nominal, base.impact, base.timing).summary()


def test_summary_counts_every_outcome_over_all_samples(base):
    df, s = _with_outcomes(base)
    oc = s["outcomes"]
    assert oc["samples"] == 40
    assert oc["counts"] == {"invalid_draw": 1, "cannot_stand": 1, "no_mechanism": 1,
                            "lift_off": 0,
                            "four_link_not_applicable": 0, "impact_not_applicable": 1,
                            "other": 0, "integrated": 36}
    assert sum(oc["counts"].values()) == 40
    assert oc["shares"]["cannot_stand"] == 1 / 40 and oc["shares"]["integrated"] == 36 / 40
    ran = df.iloc[4:]
    assert oc["integrated"] == {k: int((ran["status"] == k).sum())
                                for k in ("rest", "collapsed", "moving")}
    assert sum(oc["integrated"].values()) == 36


def test_p_collapse_is_conditional_and_p_failure_counts_cannot_stand(base):
    df, s = _with_outcomes(base)
    k = int(df.iloc[4:]["collapsed"].sum())
    pc, pf = s["p_collapse"], s["p_failure"]
    # conditional, as before: over the 36 integrated samples only
    assert (pc["collapses"], pc["trials"]) == (k, 36) and pc["p"] == pytest.approx(k / 36)
    assert "conditional" in pc["rule"]
    # cannot stand = failed: (1 + k) / (1 + 36); invalid draw, no mechanism, impact left out
    assert (pf["failures"], pf["cannot_stand"], pf["collapses"], pf["trials"]) == (k + 1, 1, k, 37)
    p, lo, hi = collapse_probability(k + 1, 37, 0.95, "wilson")
    assert (pf["p"], pf["low"], pf["high"]) == pytest.approx((p, lo, hi), rel=1e-12)
    assert "cannot stand counted as failed" in pf["rule"]
    from archrock.reports import format_ensemble

    out = format_ensemble(s, "Oppenheim")
    assert f"P(collapse | integrated) = {k / 36:.4f}" in out and f"({k} collapsed of 36," in out
    assert (f"P(failure), cannot stand counted as failed = {(k + 1) / 37:.4f}" in out
            and f"(1 cannot stand + {k} collapsed of 37," in out)
    for line in ("invalid draw: 1 (2.5%)", "cannot stand: 1 (2.5%)", "no mechanism: 1 (2.5%)",
                 "impact model not applicable: 1 (2.5%)", "integrated: 36 (90.0%)"):
        assert f"  {line}" in out


def test_no_integrated_sample_gives_no_probability_and_says_why(base):
    from archrock.studies.ensemble import EnsembleResult

    df = base.frame.copy()
    df["error"] = "geometry: two neighbouring voussoirs do not overlap radially"
    df["status"], df["collapsed"] = "failed", False
    df[["k_l", "k_r"]] = np.nan
    s = EnsembleResult(base.config, df, base.nominal, base.impact, base.timing).summary()
    for key in ("p_collapse", "p_failure"):
        assert s[key]["p"] is None and s[key]["low"] is None and s[key]["trials"] == 0
        assert "cannot be estimated" in s[key]["note"]
    assert s["k_l"]["count"] == 0 and s["k_l"]["note"] == "no sample"
    from archrock.reports import format_ensemble

    assert "P(collapse | integrated) = n/a (no trials" in format_ensemble(s, "Oppenheim")


def test_histograms_say_how_many_samples_are_not_shown(base, tmp_path, monkeypatch):
    from archrock.reports import studyplots

    df, _ = _with_outcomes(base)
    figs = []
    real = studyplots.save_figure
    monkeypatch.setattr(studyplots, "save_figure", lambda fig, path, dpi: figs.append(fig) or
                        real(fig, path, dpi))
    studyplots.plot_multiplier_histograms(df, tmp_path / "k.png")
    title = figs[0]._suptitle.get_text()
    # the impact failure keeps its k and is shown; the other three are not
    assert title.startswith("37 of 40 samples shown; not shown: 3 (")
    assert "invalid draw 1" in title and "cannot stand under its own weight 1" in title
    assert "no four-hinge mechanism 1" in title
    ax = figs[0].axes[0]
    assert sum(p.get_height() for p in ax.patches) == 37


# ---------------------------------------------------------------------------- provenance of batches
@pytest.fixture
def written(base, tmp_path):
    out = tmp_path / "ens"
    run_ensemble(config(), settings=RunSettings(out=out))
    return out


def _resume(out, capsys):
    from archrock.studies.runner import RunSettings

    lines = []  # the progress lines (the library prints nothing)
    res = run_ensemble(config(), settings=RunSettings(out=out, progress=lines.append))
    return res, "\n".join(lines)


def test_resume_without_manifest_is_refused(written):
    (written / "manifest.json").unlink()
    with pytest.raises(ArchInputError, match=r"batches'? holds batch files but .*manifest.json"):
        run_ensemble(config(seed=12), settings=RunSettings(out=written))
    assert len(list((written / "batches").iterdir())) == 8  # nothing touched (4 + checksums)


def test_resume_recomputes_a_copied_batch(base, written, capsys):
    import shutil

    from archrock.studies.checksums import file_sha256, write_sidecar

    copy = written / "batches" / "batch-00001.parquet"
    shutil.copy(written / "batches" / "batch-00000.parquet", copy)
    write_sidecar(copy, file_sha256(copy))  # its checksum right: the provenance catches it
    res, err = _resume(written, capsys)
    pd.testing.assert_frame_equal(res.frame, base.frame)
    assert res.frame["index"].is_unique
    assert res.timing["computed_batches"] == [1] and res.timing["loaded_batches"] == [0, 2, 3]
    assert res.timing["recomputed_batches"] == {"1": "holds batch 0"}
    assert "recomputing batch 1: batch-00001.parquet holds batch 0" in err
    manifest = json.loads((written / "manifest.json").read_text())
    assert manifest["runs"][-1]["recomputed"] == {"1": "holds batch 0"}


def test_resume_checks_config_index_and_code(base, written, capsys, monkeypatch):
    from archrock.studies.ensemble import store

    other = written.parent / "other"
    run_ensemble(config(seed=12), settings=RunSettings(out=other))
    batches = written / "batches"
    for name in ("batch-00002.parquet", "batch-00002.parquet.sha256"):  # with its checksum
        (other / "batches" / name).replace(batches / name)
    # right metadata, wrong index column
    df = pd.read_parquet(batches / "batch-00003.parquet")
    df["index"] = df["index"] + 1
    store.write_batch(written, 3, df, config())
    # no metadata at all: written by older code (no checksum either)
    pd.read_parquet(batches / "batch-00000.parquet").to_parquet(batches / "batch-00000.parquet",
                                                                index=False)
    (batches / "batch-00000.parquet.sha256").unlink()
    res, err = _resume(written, capsys)
    pd.testing.assert_frame_equal(res.frame, base.frame)
    why = res.timing["recomputed_batches"]
    assert sorted(why) == ["0", "2", "3"] and res.timing["loaded_batches"] == [1]
    assert "older code" in why["0"] and "another configuration" in why["2"]
    assert "index" in why["3"]
    assert err.count("recomputing batch") == 3
    # the package's sources changed: batch 0 is recomputed and, the same bit for bit, vouches
    # for the others, which are kept and stamped with this code's digest
    monkeypatch.setattr(store, "_code_digest", lambda: "0" * 64)
    res, err = _resume(written, capsys)
    assert res.timing["computed_batches"] == [0]
    assert res.timing["loaded_batches"] == [1, 2, 3]
    assert "recomputed to verify" in res.timing["recomputed_batches"]["0"]
    assert "recomputed bit for bit the same: its 3 other batch(es) kept" in err
    pd.testing.assert_frame_equal(res.frame, base.frame)
    assert {store.written_by(written, b) for b in range(4)} == {"0" * 64}
    res, _ = _resume(written, capsys)
    assert res.timing["loaded_batches"] == [0, 1, 2, 3]
    # sources whose batch 0 this code computes differently: none of their batches is kept
    df = pd.read_parquet(batches / "batch-00000.parquet")
    df.loc[5, "peak"] = np.nextafter(df.loc[5, "peak"], np.inf)  # one float, one ulp
    store.write_batch(written, 0, df, config())
    monkeypatch.setattr(store, "_code_digest", lambda: "1" * 64)
    res, err = _resume(written, capsys)
    assert res.timing["computed_batches"] == [0, 1, 2, 3]
    why = res.timing["recomputed_batches"]
    assert all("recomputes differently (column 'peak')" in why[str(b)] for b in (1, 2, 3))
    pd.testing.assert_frame_equal(res.frame, base.frame)


def test_a_folder_written_by_0_4_0_resumes_by_verification(tmp_path, capsys):
    """tests/data/ensemble-0.4.0: `archrock ensemble --samples 48 --batch-size 16 --seed 7
    --pulse oppenheim --amplitude -1 --pulse-duration 0.2 --out DIR`, run by archrock 0.4.0
    (commit 86d55b4).  Its configuration hash is this release's; its code digest is not, so one
    batch is recomputed and, being the same bit for bit, the other two are kept."""
    import shutil

    from archrock.studies.ensemble import store

    out = tmp_path / "ens"
    shutil.copytree(DATA / "ensemble-0.4.0", out)
    assert sorted(p.name for p in (out / "batches").iterdir()) == [
        f"batch-{b:05d}.parquet" for b in range(3)]
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["versions"]["archrock"] == "0.4.0"
    from archrock.studies.runner import RunSettings

    lines = []
    res = run_ensemble(EnsembleConfig.from_dict(manifest["config"]),
                       settings=RunSettings(out=out, progress=lines.append))
    err = "\n".join(lines)
    if res.timing["loaded_batches"] == [1, 2]:  # the numbers of this installation's numpy/numba
        assert res.timing["computed_batches"] == [0]
        assert "its 2 other batch(es) kept" in err
    else:  # newer releases moved a last digit: then nothing of 0.4.0's is kept, and it says why
        assert res.timing["computed_batches"] == [0, 1, 2]
        assert all("recomputes differently (column" in res.timing["recomputed_batches"][str(b)]
                   for b in (1, 2))
    assert res.summary()["p_collapse"]["collapses"] == 14  # as 0.4.0 reported
    assert {store.written_by(out, b) for b in range(3)} == {store.code_digest()}
    # checksums recorded for all three (none in 0.4.0's folder), and the manifest sealed
    from archrock.studies.checksums import check_seal, check_sidecar

    assert [check_sidecar(store.batch_path(out, b)) for b in range(3)] == [None] * 3
    sealed = json.loads((out / "manifest.json").read_text())
    assert "checksum" in sealed and check_seal(sealed) is None


def test_tmp_files_of_live_processes_are_kept(written):
    import os

    mine = written / "batches" / f"batch-00000.parquet.tmp-{os.getppid()}"
    dead = written / "manifest.json.tmp-99999999"
    mine.write_bytes(b"x")
    dead.write_bytes(b"x")
    run_ensemble(config(), settings=RunSettings(out=written))
    assert mine.exists() and not dead.exists()
    manifest = json.loads((written / "manifest.json").read_text())
    assert manifest["runs"][-1]["removed_tmp"] == ["manifest.json.tmp-99999999"]


def test_sample_i_is_the_same_arch_in_ensemble_curves_and_fragility(base):
    """One sampler: the same seed and index give the same arch in every study, whatever the
    batch size (0.1.0 drew three different arches for i > 0)."""
    from archrock.studies.curves import collapse_amplitude, ensemble_curve
    from archrock.studies.ida import random_models

    cfg = base.config
    other = config(batch_size=7)
    models = random_models(oppenheim_arch(), 6, seed=cfg.seed, spreads=cfg.spreads)
    for i in (0, 3, 5):
        arch = sample_arch(cfg, i)
        assert np.array_equal(arch.spans, sample_arch(other, i).spans)
        assert np.array_equal(arch.spans, models[i].arch.spans)
        assert np.array_equal(arch.thicknesses, models[i].arch.thicknesses)
        assert np.array_equal(arch.spans, ArchSampler(oppenheim_arch(), cfg.spreads, cfg.seed).arch(i).spans)
        row = base.frame.iloc[i]
        assert row["k_l"] == models[i].k_l and row["k_r"] == models[i].k_r
    band = ensemble_curve(oppenheim_arch(), 2, cfg.seed, cfg.spreads, durations=[0.5], n_scan=10,
                          a_max=2.0)
    for i in (0, 1):
        direct = collapse_amplitude(models[i], 0.5, n_scan=10, a_max=2.0).amplitude
        assert band.amplitudes[i, 0] == (np.inf if direct is None else direct)
    assert base.frame["k_l"].tolist() == run_ensemble(other).frame["k_l"].tolist()


def test_least_loss_ensemble_runs_the_chain_and_agrees_with_respond():
    """ensemble --impact least-loss: the batch kernel follows each arch's own chain of
    mechanisms, and its collapse decisions equal single-arch respond."""
    from archrock.dynamics.response import prepare, respond

    motion = PulseSpec("oppenheim", -1.0, 0.4)
    cfg = config(samples=6, batch_size=3, impact="least-loss", cv=None, motion=motion)
    res = run_ensemble(cfg)
    df = res.frame
    assert (df["error"] == "").all()
    for i in range(6):
        one = respond(prepare(sample_arch(cfg, i), "least-loss"), motion.build())
        assert bool(df["collapsed"].iloc[i]) == one.collapsed
        assert df["peak"].iloc[i] == pytest.approx(one.peak, abs=1e-9)
        assert df["n_impacts"].iloc[i] == len(one.impacts)
    assert df["collapsed"].any() and not df["collapsed"].all()
    # the least-loss chain differs from the paper's alternation on these arches
    paper = run_ensemble(config(samples=6, batch_size=3, motion=cfg.motion)).frame
    assert not np.array_equal(paper["peak"].to_numpy(), df["peak"].to_numpy())


def test_ensemble_text_names_the_impact_law_and_its_fallback(capsys):
    """Under a ground motion the text report says which impact law the arches got, and why it
    is the momentum law's where the paper's equations create energy on the nominal arch (a
    17-voussoir semicircle: kinetic energy ratio 1.3035)."""
    from archrock.cli import main

    argv = ["ensemble", "--shape", "circular", "--span", "10", "--rise", "5", "--thickness", "0.9",
            "--voussoirs", "17", "--samples", "8", "--pulse", "oppenheim", "--amplitude", "-0.5",
            "--pulse-duration", "0.2", "--no-progress"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "impact: paper model evaluated on the nominal arch" in out
    assert "impact law fallback: on the nominal arch" in out and "1.3035" in out
