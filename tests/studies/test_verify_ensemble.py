"""Issue 21: the contact engine against the four-link model's mechanisms over an ensemble of
irregular arches (studies.verification.verify_ensemble, `archrock verify --samples N`)."""

import json

import numpy as np
import pytest

pytest.importorskip("pymunk")

from archrock.cli import main  # noqa: E402
from archrock.contact import EngineSettings  # noqa: E402
from archrock.errors import ArchInputError, LimitExceededError  # noqa: E402
from archrock.geometry import family_arch, nominal_arch  # noqa: E402
from archrock.geometry.sampling import ArchSampler, Spreads  # noqa: E402
from archrock.statics.limit import limit_analysis  # noqa: E402
from archrock.studies.verification import verify_ensemble  # noqa: E402
from archrock.studies.runner import RunSettings  # noqa: E402

#: coarse engine and ramp: enough for the hinges and k within a few % on 5 voussoirs
COARSE = EngineSettings(steps_per_T=100, iterations=20)
QUICK = {"tol": 0.05, "rate": 0.2, "hold": 1.5}


def _sampler(seed=2):
    return ArchSampler(nominal_arch(voussoirs=5), Spreads(0.1, 0.1, 0.05), seed=seed)


def test_verify_ensemble_two_arches_matches_limit_analysis():
    s = _sampler()
    res = verify_ensemble(s, 2, settings=COARSE, ramp_options=QUICK, k_tol=0.08)
    assert res.n == 2 and [a.index for a in res.arches] == [0, 1]
    for a in res.arches:
        lim = limit_analysis(s.arch(a.index), verify=False)
        for d in ("l", "r"):
            c = getattr(a, d)
            # the four-link side is the limit analysis, exactly
            assert c.k_four_link == getattr(lim, f"k_{d}")
            assert c.hinges_four_link == tuple(sorted(h.joint for h in lim.mechanism(d).hinges))
            # the engine: rocking in the same mechanism, at k within the quick ramp's bracket
            # (5% wide: its middle is within 2.5% plus the hold's resolution)
            assert c.mode == "rocking" and c.agree and c.differences == ()
            assert c.hinges_engine == c.hinges_four_link
            assert abs(c.k_error) < 0.03
            assert c.k_error == pytest.approx(c.k_engine / c.k_four_link - 1, abs=1e-15)
    assert res.disagreement_rate == 0.0 and res.disagreements == () and res.where == {}
    d = json.loads(json.dumps(res.to_dict()))
    assert d["n"] == 2 and d["sampler"]["seed"] == 2 and len(d["arches"]) == 2


def test_verify_ensemble_bad_input_and_work_bound(monkeypatch):
    s = _sampler()
    with pytest.raises(ArchInputError, match="n: 0; allowed an integer >= 1"):
        verify_ensemble(s, 0)
    with pytest.raises(ArchInputError, match="k_tol"):
        verify_ensemble(s, 1, k_tol=0.0)
    with pytest.raises(ArchInputError, match="workers"):
        verify_ensemble(s, 1, run_settings=RunSettings(workers=0))
    with pytest.raises(ArchInputError, match="ramp_options: unknown"):
        verify_ensemble(s, 1, ramp_options={"lambda_max": 3})
    with pytest.raises(ArchInputError, match="arches"):
        verify_ensemble(42)
    with pytest.raises(ArchInputError, match="n: 5; allowed 1 <= n <= 1"):
        verify_ensemble([nominal_arch(voussoirs=5)], 5)
    # the package's work bound refuses before any engine runs
    monkeypatch.setenv("ARCHROCK_MAX_WORK_S", "10")
    with pytest.raises(LimitExceededError, match="verify over an ensemble.*--samples"):
        verify_ensemble(s, 1000, settings=COARSE)


def test_cli_verify_samples_table_and_flags(capsys):
    args = ["verify", "--voussoirs", "5", "--samples", "1", "--seed", "2", "--steps-per-T",
            "100", "--iterations", "20", "--ramp-tol", "0.05", "--k-tol", "0.08"]
    assert main([*args, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    lim = limit_analysis(_sampler().arch(0), verify=False)
    assert d["arches"][0]["l"]["k_four_link"] == pytest.approx(lim.k_l, rel=1e-12)
    assert d["arches"][0]["l"]["hinges_engine"] == d["arches"][0]["l"]["hinges_four_link"]
    assert d["disagreement_rate"] == 0.0
    assert main(["verify", "--workers", "2"]) == 2
    assert "--workers: applies with --samples" in capsys.readouterr().err
    assert main(["verify", "--samples", "1", "--k-tol", "1.5"]) == 2
    assert "k_tol" in capsys.readouterr().err
    assert main(["verify", "--samples", "1", "--durations", "0.3"]) == 2
    assert "--durations: the pulse grid's; not with --samples" in capsys.readouterr().err


@pytest.mark.slow
def test_verify_ensemble_six_irregular_pointed_arches_in_a_pool():
    """Six irregular pointed arches (tilted joints), on two processes and in this one: the same
    table; every four-link k is the limit analysis's; the disagreements are where the engine's
    hinges differ."""
    s = ArchSampler(family_arch("pointed", 10.0, 7.0, 1.0, 9), Spreads(0.1, 0.1, 0.05, 5.0),
                    seed=1)
    eng = EngineSettings()  # the coarse settings are not converged enough on these arches
    opts = {"tol": 0.02, "rate": 0.1, "hold": 2.0}
    lines = []
    pool = verify_ensemble(s, 6, settings=eng, ramp_options=opts,
                           run_settings=RunSettings(workers=2, progress=lines.append))
    assert len(lines) == 6
    one = verify_ensemble(s, 6, settings=eng, ramp_options=opts,
                          run_settings=RunSettings(workers=1))
    assert [a.to_dict() | {"seconds": 0} for a in pool.arches] == \
        [a.to_dict() | {"seconds": 0} for a in one.arches]
    for a in pool.arches:
        lim = limit_analysis(s.arch(a.index), verify=False)
        assert a.l.k_four_link == lim.k_l and a.r.k_four_link == lim.k_r
        for c in (a.l, a.r):
            assert c.mode == "rocking"
            assert abs(c.k_error) < 0.05
            assert c.agree == (not c.missing and not c.extra and abs(c.k_error) <= 0.05)
    n_bad = sum(not a.agree for a in pool.arches)
    assert pool.disagreement_rate == pytest.approx(n_bad / 6)
    counted = sum(sum(w["missing"].values()) + sum(w["extra"].values())
                  for w in pool.where.values())
    assert counted == sum(len(c.missing) + len(c.extra) for a in pool.arches for c in (a.l, a.r))
    assert np.all(np.isfinite(pool.k_errors("l")))
