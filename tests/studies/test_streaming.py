"""The summary computed from the stored batches (three passes, one batch in memory) against the
in-memory summary of the same ensemble."""

import math

import numpy as np
import pytest

from archrock.studies.ensemble import EnsembleConfig, run_ensemble
from archrock.studies.ensemble.streaming import summarize_batches
from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch
from archrock.groundmotion import PulseSpec
from archrock.dynamics.impact import ImpactSpec
from archrock.geometry.sampling import Spreads
from archrock.studies.runner import RunSettings


def _close(a, b, path=""):
    """Equal dicts; floats to 1e-12 relative (the order of summation of mean and std)."""
    if isinstance(a, dict):
        assert set(a) == set(b), (path, set(a) ^ set(b))
        for k in a:
            _close(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, float) and isinstance(b, float) and not (math.isnan(a) and math.isnan(b)):
        assert a == pytest.approx(b, rel=1e-12, abs=1e-15), path
    else:
        assert a == b, path


@pytest.mark.parametrize("early_stop", [False, True])
def test_streamed_summary_equals_in_memory(tmp_path, early_stop):
    # wide spreads: invalid draws, arches that cannot stand, collapses and recoveries
    cfg = EnsembleConfig.from_arch(oppenheim_arch(), samples=300, batch_size=70, seed=4,
                                   spreads=Spreads(0.2, 0.3, 0.3), early_stop=early_stop,
                                   motion=PulseSpec("oppenheim", -1.0, 0.2),
                                   impact=ImpactSpec.fixed(0.8754))
    full = run_ensemble(cfg, settings=RunSettings(out=tmp_path / "a"))
    lean = run_ensemble(cfg, keep_frame=False, settings=RunSettings(out=tmp_path / "a"))
    assert lean.frame is None and lean.timing["loaded_batches"] == list(range(cfg.n_batches))
    ref, got = full.summary(), lean.summary()
    assert got.pop("streamed")["passes"] == 3
    ref.pop("timing"), got.pop("timing")
    c = ref["outcomes"]["counts"]
    assert c["invalid_draw"] + c["cannot_stand"] > 0 and 0 < ref["p_collapse"]["collapses"]
    _close(ref, got)
    # the quantiles are numpy's, exactly (not binned estimates)
    assert got["k_l"]["q05"] == ref["k_l"]["q05"] and got["k_min"]["q95"] == ref["k_min"]["q95"]
    assert got["response"]["n_impacts"]["median"] == ref["response"]["n_impacts"]["median"]


def test_atoms_single_values_and_empty_series():
    """Ties (integers), one value, no value: numpy's quantile / None, without holding the data."""
    import pandas as pd

    from archrock.studies.ensemble.summary import EnsembleResult, _stats

    cfg = EnsembleConfig.from_arch(oppenheim_arch(), samples=4, batch_size=2,
                                   motion=PulseSpec("oppenheim", -1.0, 0.2))
    rng = np.random.default_rng(0)
    n = 5000
    df = pd.DataFrame({"k_l": rng.uniform(0.3, 0.4, n), "k_r": np.full(n, 0.35),
                       "mech_l": "0i-3e-5i-7e", "mech_r": "", "collapsed": False,
                       "status": "rest", "peak": rng.integers(0, 3, n).astype(float),
                       "t_collapse": np.nan, "t_limit": np.nan, "t_unstable": np.nan,
                       "n_impacts": rng.integers(0, 200, n), "n_activations": 1,
                       "events_truncated": False, "early_stopped": False, "error": ""})
    df.loc[0, "t_unstable"] = 1.25
    chunks = [df.iloc[i:i + 700] for i in range(0, n, 700)]
    nominal = {"k_l": 0.37, "k_r": 0.37}
    got = summarize_batches(lambda: iter(chunks), cfg, nominal, {})
    ref = EnsembleResult(cfg, df, nominal, {}).summary()
    for key in ("k_l", "k_r", "k_min"):
        _close(ref[key], got[key], key)
    for key in ("peak_rad", "n_impacts", "t_unstable_s", "t_collapse_s"):
        _close(ref["response"][key], got["response"][key], key)
    assert got["response"]["t_unstable_s"]["count"] == 1 and got["response"]["t_collapse_s"]["count"] == 0
    assert got["k_r"]["std"] == 0.0  # the exact mean of equal values: no rounding residue
    assert _stats(df["k_r"].to_numpy())["std"] == pytest.approx(0.0, abs=1e-15)


def test_keep_frame_false_needs_a_folder():
    cfg = EnsembleConfig.from_arch(oppenheim_arch(), samples=2)
    with pytest.raises(ArchInputError, match="keep_frame"):
        run_ensemble(cfg, keep_frame=False)


def test_cli_low_memory_prints_the_same_summary(tmp_path, capsys):
    import json

    from archrock.cli import main

    args = ["ensemble", "--samples", "40", "--batch-size", "15", "--pulse", "oppenheim",
            "--amplitude", "-1", "--pulse-duration", "0.2", "--cv", "0.8754", "--json",
            "--no-progress", "--out", str(tmp_path / "o")]
    assert main(args) == 0
    ref = json.loads(capsys.readouterr().out)
    assert main(args + ["--low-memory"]) == 0
    got = json.loads(capsys.readouterr().out)
    got.pop("streamed"), ref.pop("timing"), got.pop("timing")
    _close(ref, got)
    assert main(["ensemble", "--samples", "4", "--low-memory", "--no-progress"]) == 2
