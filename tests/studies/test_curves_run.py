"""The curves' batch engine on the executors and the resumable output of the studies
(archrock.studies.runner): a process pool and a kept folder give the very curves of the in-process run."""

import json

import pytest

from archrock.cli import main
from archrock.studies.curves import collapse_curve, ensemble_curve
from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.studies.runner import RunSettings

NOMINAL = dict(radius=2.0, thickness=0.3)  # small arch: short responses
KW = dict(durations=[0.2, 0.5], n_scan=12)


@pytest.fixture(scope="module")
def ref():
    return ensemble_curve(nominal_arch(**NOMINAL), 2, 1, **KW)


def test_out_folder_keeps_responses_and_resumes(ref, tmp_path, monkeypatch):
    pytest.importorskip("pyarrow")
    import archrock.studies.runner as sr

    nom = nominal_arch(**NOMINAL)
    out = tmp_path / "run"
    first = ensemble_curve(nom, 2, 1, **KW, settings=RunSettings(out=out))
    assert first.to_dict() == ref.to_dict()
    # the same curves as response after response (0.1.0's path)
    assert ref.to_dict() == ensemble_curve(nom, 2, 1, engine="respond", **KW).to_dict()
    chunks = sorted((out / "items").glob("chunk-*.parquet"))
    assert len(chunks) > 2 and (out / "manifest.json").exists()
    # lose half the chunks (a killed run): the rerun computes those items only, the same curves
    import pyarrow.parquet as pq

    lost = sum(pq.read_metadata(f).num_rows for f in chunks[::2])
    for f in chunks[::2]:
        f.unlink()
    ran = []
    real = sr.sweep
    monkeypatch.setattr(sr, "sweep", lambda *a, **k: ran.append(len(a[2])) or real(*a, **k))
    again = ensemble_curve(nom, 2, 1, **KW, settings=RunSettings(out=out))
    assert again.to_dict() == ref.to_dict()
    assert sum(ran) == lost > 0
    # everything kept now: nothing runs, the same curves
    ran.clear()
    assert ensemble_curve(nom, 2, 1, **KW, settings=RunSettings(out=out)).to_dict() == ref.to_dict()
    assert sum(ran) == 0
    # a single curve of the nominal arch is another study (other arches): refused
    with pytest.raises(ArchInputError, match="^out:"):
        collapse_curve(nom, KW["durations"], n_scan=12, settings=RunSettings(out=out))
    # other durations, another pulse kind or sign: refused, naming --out
    for other in (dict(durations=[0.2, 0.6]), dict(kind="one-sine"), dict(sign=1)):
        with pytest.raises(ArchInputError, match="^out:"):
            ensemble_curve(nom, 2, 1, **{**KW, **other}, settings=RunSettings(out=out))


def test_kept_single_curve_is_read_back(tmp_path, monkeypatch):
    pytest.importorskip("pyarrow")
    import archrock.studies.runner as sr

    nom = nominal_arch(**NOMINAL)
    kept = RunSettings(out=tmp_path / "c")
    a = collapse_curve(nom, [0.3], kind="one-sine", n_scan=10, settings=kept)
    ran = []
    real = sr.sweep
    monkeypatch.setattr(sr, "sweep", lambda *x, **k: ran.append(1) or real(*x, **k))
    b = collapse_curve(nom, [0.3], kind="one-sine", n_scan=10, settings=kept)
    assert a.to_dict(scan=True) == b.to_dict(scan=True) and not ran
    assert a.to_dict(scan=True) == collapse_curve(nom, [0.3], kind="one-sine", n_scan=10,
                                                  engine="respond").to_dict(scan=True)
    # items are keyed by their amplitude: another tolerance is the same study, its shared grid
    # read back, its answer that of a run without the folder
    monkeypatch.setattr(sr, "sweep", lambda *x, **k: ran.append(len(x[2])) or real(*x, **k))
    ran.clear()
    c = collapse_curve(nom, [0.3], kind="one-sine", n_scan=10, tol=2e-4, settings=kept)
    n = c.points[0].n_responses
    assert sum(ran) == n - a.points[0].n_responses > 0  # only the new bisection steps ran
    assert c.to_dict(scan=True) == collapse_curve(nom, [0.3], kind="one-sine", n_scan=10,
                                                  tol=2e-4).to_dict(scan=True)


@pytest.mark.slow  # spawns worker processes (each compiles its serial loop) and a Dask cluster
def test_process_pool_and_dask_give_the_same_curves(ref):
    nom = nominal_arch(**NOMINAL)
    pool = RunSettings(workers=2)
    assert ensemble_curve(nom, 2, 1, **KW, settings=pool).to_dict() == ref.to_dict()
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        dask = RunSettings(scheduler=client)
        assert ensemble_curve(nom, 2, 1, **KW, settings=dask).to_dict() == ref.to_dict()


def test_library_refuses_runs_of_the_other_engine(tmp_path):
    nom = nominal_arch(**NOMINAL)
    with pytest.raises(ArchInputError, match="^out: run by the batch engine"):
        collapse_curve(nom, [0.2], engine="respond", settings=RunSettings(out=tmp_path))
    with pytest.raises(ArchInputError, match="^scheduler: run by the batch engine"):
        ensemble_curve(nom, 2, engine="respond",
                       settings=RunSettings(scheduler="tcp://127.0.0.1:1"))
    with pytest.raises(ArchInputError, match="^workers"):
        collapse_curve(nom, [0.2], settings=RunSettings(workers=0))


CLI = ["curves", "--radius", "2", "--thickness", "0.3", "--durations", "0.2,0.5",
       "--n-scan", "12", "--no-progress"]


@pytest.mark.parametrize("extra, message", [
    (["--engine", "respond", "--out", "x"], "out: kept by the batch engine"),
    (["--engine", "respond", "--scheduler", "tcp://127.0.0.1:1"],
     "scheduler: run by the batch engine"),
    (["--workers", "0"], "workers: 0"),
    (["--out", " "], "--out"),
])
def test_cli_run_options_are_checked(capsys, extra, message):
    assert main([*CLI, *extra]) == 2
    assert message in capsys.readouterr().err


def test_cli_out_resumes_and_interrupt_says_what_was_kept(capsys, tmp_path, monkeypatch):
    pytest.importorskip("pyarrow")
    out = tmp_path / "run"
    assert main([*CLI, "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    for _ in range(2):  # computed, then read back: the same JSON
        assert main([*CLI, "--json", "--out", str(out)]) == 0
        assert json.loads(capsys.readouterr().out) == plain
    import archrock.studies.curves as cv

    def interrupted(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(cv, "collapse_curve", interrupted)
    code = main([*CLI, "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 130 and f"the finished responses are kept in {out}" in err
    code = main(CLI)
    assert "nothing was kept (give --out DIR" in capsys.readouterr().err
