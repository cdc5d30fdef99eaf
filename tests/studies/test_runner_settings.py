"""One study runner: RunSettings taken by every study, one executor family, one store, one
progress protocol that the CLI renders (issue 18)."""

import argparse
import ast
import json
import logging
import os
from pathlib import Path

import pandas as pd
import pytest

from archrock._progress import Progress
from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch
from archrock.geometry.sampling import Spreads
from archrock.groundmotion import PulseSpec
from archrock.dynamics.impact import ImpactSpec
from archrock.studies.ensemble import EnsembleConfig, run_ensemble
from archrock.studies.executors import Executor
from archrock.studies.runner import RunSettings

SRC = Path(__file__).resolve().parents[2] / "src" / "archrock"


def small_config(samples=24, batch_size=8):
    return EnsembleConfig.from_arch(oppenheim_arch(), samples=samples, batch_size=batch_size,
                                    seed=3, motion=PulseSpec("oppenheim", -1.0, 0.2),
                                    impact=ImpactSpec.parse("fixed", cv=0.8754))


# ---------------------------------------------------------------------------- the settings
@pytest.mark.parametrize("field, value", [
    ("workers", 0), ("workers", True), ("workers", 1.5), ("workers", "2"),
    ("scheduler", 8786), ("scheduler", "  "), ("out", 3), ("out", ""),
    ("progress", "yes"), ("progress", 1)])
def test_each_field_is_checked_by_name(field, value):
    with pytest.raises(ArchInputError, match=f"^{field}: "):
        RunSettings(**{field: value})


def test_settings_are_frozen_and_read_back_from_json(tmp_path):
    s = RunSettings(workers=3, scheduler="tcp://127.0.0.1:8786", out=str(tmp_path / "o"),
                    progress=True)
    assert s.out == tmp_path / "o" and isinstance(s.out, Path)
    assert s.executor == "dask" and RunSettings(workers=2).executor == "process pool"
    assert RunSettings(workers=1).executor == "in-process" == RunSettings().executor
    with pytest.raises(AttributeError):
        s.workers = 1
    d = json.loads(json.dumps(s.to_dict()))
    assert RunSettings.from_dict(d) == s
    assert RunSettings.from_dict(None) == RunSettings() and RunSettings(progress=False) == RunSettings()
    with pytest.raises(ArchInputError, match="^settings: unknown field 'n_jobs'"):
        RunSettings.from_dict({"n_jobs": 2})
    with pytest.raises(ArchInputError, match="^progress: a callable cannot be written"):
        RunSettings(progress=print).to_dict()


def test_a_study_refuses_the_fields_it_does_not_use():
    from archrock.studies.defectmap import defect_map
    from archrock.studies.sensitivity import sobol_indices

    with pytest.raises(ArchInputError, match="^workers: 2; sobol_indices runs in this process"):
        sobol_indices(oppenheim_arch(), Spreads(0.05, 0.05, 0.0), 16, motion=None,
                      settings=RunSettings(workers=2))
    with pytest.raises(ArchInputError, match="^out: .*defect_map runs in this process"):
        defect_map(oppenheim_arch(), settings=RunSettings(out="x"))


def test_ensemble_with_settings_in_process_kept_and_resumed(tmp_path):
    cfg = small_config()
    new = run_ensemble(cfg, settings=RunSettings())
    one = run_ensemble(cfg, settings=RunSettings(workers=1))  # 1 worker: in-process too
    pd.testing.assert_frame_equal(new.frame, one.frame)
    assert new.timing["executor"] == "in-process" and new.timing["workers"] == 1
    # kept in a folder, then resumed: nothing computed, the same table
    lines = []
    kept = run_ensemble(cfg, settings=RunSettings(out=tmp_path / "e", progress=lines.append))
    again = run_ensemble(cfg, settings=RunSettings(out=tmp_path / "e"))
    pd.testing.assert_frame_equal(kept.frame, new.frame)
    pd.testing.assert_frame_equal(again.frame, new.frame)
    assert again.timing["computed_batches"] == [] and again.timing["loaded_batches"] == [0, 1, 2]
    assert lines[-1] == "ensemble: 24/24 samples (100%)"


@pytest.mark.slow
def test_ensemble_pool_and_dask_through_settings_are_the_in_process_table():
    cfg = small_config()
    ref = run_ensemble(cfg, settings=RunSettings())
    pool = run_ensemble(cfg, settings=RunSettings(workers=2))
    pd.testing.assert_frame_equal(pool.frame, ref.frame)
    assert pool.timing["executor"] == f"process pool ({min(2, os.cpu_count() or 1)})"
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        dask = run_ensemble(cfg, settings=RunSettings(scheduler=client))
    pd.testing.assert_frame_equal(dask.frame, ref.frame)
    assert dask.timing["executor"] == "dask"


# ---------------------------------------------------------------------------- one executor family
def test_one_executor_family_runs_the_ensemble_and_the_sweeps():
    import archrock.studies.ensemble.executors as ens
    import archrock.studies.runner as runner

    assert ens.Executor is Executor and runner.Executor is Executor
    with Executor(RunSettings(), shared=3) as ex:
        assert ex.in_process and ex.name == "in-process" and ex.parts == 1
        # tasks get the shared state first, results come with their task number
        assert list(ex.map_unordered(max, [(1,), (5,), (2,)])) == [(0, 3), (1, 5), (2, 3)]
    with Executor(RunSettings(), shared=3, local=10) as ex:
        assert list(ex.map_unordered(max, [(1,)])) == [(0, 10)]


@pytest.mark.slow
def test_the_pool_and_dask_executors_give_what_in_process_gives():
    want = {0: 3, 1: 5, 2: 3}
    with Executor(RunSettings(workers=2), shared=3) as ex:
        assert not ex.in_process and ex.name.startswith("process pool (")
        assert dict(ex.map_unordered(max, [(1,), (5,), (2,)])) == want
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        with Executor(RunSettings(scheduler=client), shared=3) as ex:
            assert ex.name == "dask"
            assert dict(ex.map_unordered(max, [(1,), (5,), (2,)])) == want


# ---------------------------------------------------------------------------- one store
def test_one_store_module_for_ensembles_and_sweeps(tmp_path):
    import archrock.studies.ensemble.store as old_path
    import archrock.studies.runner as runner
    import archrock.studies.store as store

    assert old_path is store and runner.ResultStore is store.ResultStore
    # the sweeps' items clean up killed writes the ensemble's way: a dead writer's temporary
    # file goes, a live one's stays
    from archrock.dynamics.response import prepare
    from archrock.dynamics.sweep import SweepArches, SweepMotions

    arches = SweepArches.from_models([prepare(oppenheim_arch(), ImpactSpec("paper"))])
    motions = SweepMotions.of([PulseSpec("oppenheim", -1.0, 0.2).build()])
    (tmp_path / "items").mkdir()
    dead = tmp_path / "items" / "chunk-00000.parquet.tmp-999999999"
    live = tmp_path / "items" / f"chunk-00001.parquet.tmp-{os.getppid()}"
    dead.write_text("x")
    live.write_text("x")
    kept = store.ResultStore(tmp_path, arches, motions, settings={"k": 1})
    assert not dead.exists() and live.exists() and kept.loaded == 0
    manifest = json.loads((tmp_path / "manifest.json").read_text())
    assert manifest["format"] == store.SWEEP_FORMAT and manifest["digest"] == kept.digest
    with pytest.raises(ArchInputError, match="^out: .* holds another study"):
        store.ResultStore(tmp_path, arches, motions, settings={"k": 2})


# ---------------------------------------------------------------------------- one progress protocol
class _Renderer:
    """A renderer as the CLI's: lines, or a bar that gets every count."""

    def __init__(self):
        self.lines, self.counts = [], []

    def __call__(self, line):
        self.lines.append(line)

    def bar(self, total, desc, unit):
        outer = self

        class Bar:
            def update(self, n):
                outer.counts.append(n)

            def write(self, text):
                outer.lines.append(text)

            def close(self):
                outer.lines.append(f"closed {desc} {total} {unit}")
        return Bar()


def test_progress_goes_to_a_renderers_bar_or_to_the_logger(caplog, capsys):
    r = _Renderer()
    bar = Progress(5, r, desc="curves", unit="response")
    bar.note("curves: starting")
    for _ in range(5):
        bar.update(1)
    bar.close()
    assert r.counts == [1] * 5 and r.lines == ["curves: starting", "closed curves 5 response"]
    with caplog.at_level(logging.INFO, logger="archrock.progress"):
        run_ensemble(small_config(8, 8), settings=RunSettings(progress=True))
    assert [x.getMessage() for x in caplog.records] == ["ensemble: 8/8 samples (100%)"]
    assert capsys.readouterr() == ("", "")


def test_the_cli_builds_its_settings_from_its_flags(tmp_path):
    from archrock.cli.runsettings import STDERR_PROGRESS, run_settings

    ns = argparse.Namespace(workers=1, scheduler=None, no_progress=True)
    assert run_settings(ns) == RunSettings()
    ns = argparse.Namespace(workers=3, scheduler="tcp://h:1", no_progress=False)
    assert run_settings(ns, out=tmp_path) == RunSettings(3, "tcp://h:1", tmp_path,
                                                         STDERR_PROGRESS)
    assert run_settings(ns, workers=False, scheduler=False, progress=False) == RunSettings()
    with pytest.raises(ArchInputError, match="^workers: 0; allowed an integer >= 1"):
        run_settings(argparse.Namespace(workers=0))


def test_the_library_never_prints():
    """No print() and no write to sys.stdout/sys.stderr below the CLI, the app and the reports:
    progress goes through archrock._progress, which the CLI renders."""
    found = []
    for path in SRC.rglob("*.py"):
        rel = path.relative_to(SRC).parts
        if rel[0] in ("cli", "app", "reports"):
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call):
                f = node.func
                if isinstance(f, ast.Name) and f.id == "print":
                    found.append(f"{'/'.join(rel)}:{node.lineno} print")
                if (isinstance(f, ast.Attribute) and f.attr == "write"
                        and isinstance(f.value, ast.Attribute)
                        and f.value.attr in ("stdout", "stderr")):
                    found.append(f"{'/'.join(rel)}:{node.lineno} sys.{f.value.attr}.write")
    assert found == []


# ---------------------------------------------------------------------------- 0.7: settings only
@pytest.mark.parametrize("keyword", ["workers", "scheduler", "out", "out_dir", "progress"])
def test_the_0_6_keywords_are_python_type_errors(keyword, tmp_path):
    """0.7 removed the 0.6 run keywords: each study of this list names the one given in
    Python's own TypeError, before any work (nothing is written)."""
    from archrock.studies.curves import collapse_curve, ensemble_curve
    from archrock.studies.paper import run_paper_study
    from archrock.studies.sensitivity import sobol_indices
    from archrock.studies.verification import verify, verify_ensemble

    arch = oppenheim_arch()
    calls = [lambda **k: run_ensemble(small_config(), **k),
             lambda **k: collapse_curve(arch, [0.2], **k),
             lambda **k: ensemble_curve(arch, 2, **k),
             lambda **k: sobol_indices(arch, Spreads(0.05, 0.05, 0.0), 16, **k),
             lambda **k: verify(arch, [-1.0], [0.2], **k),
             lambda **k: verify_ensemble([arch], **k),
             lambda **k: run_paper_study(**k)]
    for call in calls:
        with pytest.raises(TypeError, match=f"unexpected keyword argument '{keyword}'"):
            call(**{keyword: tmp_path / "x" if keyword.startswith("out") else None})
    assert not (tmp_path / "x").exists()


#: the studies reshaped in 0.7 as configure -> decide the dynamics -> prepare the nominal ->
#: batches, every function short enough to read at once
SHAPED = ["runner.py", "curves.py", "amplitude.py", "sensitivity.py", "verification.py",
          "paper.py", *(f"ensemble/{p.name}" for p in (SRC / "studies" / "ensemble").glob("*.py"))]


def test_no_function_of_the_reshaped_studies_is_over_60_lines():
    long = []
    for name in SHAPED:
        tree = ast.parse((SRC / "studies" / name).read_text(encoding="utf-8"))
        long += [f"{name}:{n.lineno} {n.name} {n.end_lineno - n.lineno + 1} lines"
                 for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))
                 and n.end_lineno - n.lineno + 1 > 60]
    assert long == []
    assert len((SRC / "studies" / "curves.py").read_text(encoding="utf-8").splitlines()) < 700
