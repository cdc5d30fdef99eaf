"""The studies' store never loads a damaged file as data: an ensemble's batches and manifest,
a sweep's chunks and manifest (archrock.studies.store)."""

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch
from archrock.groundmotion import PulseSpec
from archrock.studies.checksums import check_sidecar, file_sha256, sidecar_path
from archrock.studies.ensemble import EnsembleConfig, run_ensemble
from archrock.studies.runner import RunSettings
from archrock.studies import store

pytest.importorskip("pyarrow")


def config():
    """80 arches in 4 batches under the paper's pulse."""
    return EnsembleConfig.from_arch(oppenheim_arch(), samples=80, batch_size=20, seed=3,
                                    motion=PulseSpec("oppenheim", -1.0, 0.2))


def _summary(res) -> str:
    """The summary without its timing, as text (NaN == NaN, floats to their last digit)."""
    s = dict(res.summary())
    s.pop("timing", None)
    return json.dumps(s, sort_keys=True, default=str)


@pytest.fixture(scope="module")
def pristine(tmp_path_factory):
    out = tmp_path_factory.mktemp("store") / "ens"
    res = run_ensemble(config(), settings=RunSettings(out=out))
    return out, res


@pytest.fixture
def folder(pristine, tmp_path):
    out = tmp_path / "ens"
    shutil.copytree(pristine[0], out)
    return out


def _resume(out):
    lines = []
    res = run_ensemble(config(), settings=RunSettings(out=out, progress=lines.append))
    return res, [x for x in lines if not x.startswith("ensemble: ") or "recomputing" in x]


def _flip(path, n=64, seed=0):
    """Overwrite n bytes in the middle of a file with random ones (the review's damage)."""
    data = bytearray(path.read_bytes())
    mid = len(data) // 2
    data[mid:mid + n] = np.random.default_rng(seed).integers(0, 256, n, dtype=np.uint8).tobytes()
    path.write_bytes(bytes(data))


@pytest.mark.parametrize("damage", ["flip", "truncate"])
def test_a_damaged_batch_is_named_recomputed_and_the_summary_is_unchanged(pristine, folder,
                                                                          damage):
    path = store.batch_path(folder, 2)
    if damage == "flip":
        _flip(path)
    else:
        path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    res, notes = _resume(folder)
    assert res.timing["computed_batches"] == [2]
    assert res.timing["loaded_batches"] == [0, 1, 3]
    assert len(notes) == 1
    assert notes[0].startswith("ensemble: recomputing batch 2: batch-00002.parquet damaged: its "
                               "sha256 (") and "batch-00002.parquet.sha256" in notes[0]
    pd.testing.assert_frame_equal(res.frame, pristine[1].frame, check_exact=True)
    assert _summary(res) == _summary(pristine[1])
    assert check_sidecar(path) is None  # rewritten with its checksum
    manifest = json.loads((folder / "manifest.json").read_text())
    assert "damaged" in manifest["runs"][-1]["recomputed"]["2"]


def test_a_damaged_manifest_is_named_and_refused(folder):
    man = folder / "manifest.json"
    text = man.read_text()
    before = {p.name: p.read_bytes() for p in (folder / "batches").iterdir()}
    # still valid JSON, one value changed: only the checksum tells
    man.write_text(text.replace('"samples": 80', '"samples": 81', 1))
    with pytest.raises(ArchInputError, match=r"^out: '.*manifest\.json' is damaged \(its "
                                             r"contents do not match the sha256 it records\)"):
        run_ensemble(config(), settings=RunSettings(out=folder))
    man.write_text(text[: len(text) // 2])  # truncated
    with pytest.raises(ArchInputError, match=r"manifest\.json' is damaged \(not readable JSON"):
        run_ensemble(config(), settings=RunSettings(out=folder))
    assert {p.name: p.read_bytes() for p in (folder / "batches").iterdir()} == before


def test_a_batch_without_a_checksum_is_checked_whole_then_recorded(folder):
    """An older folder's batch (no sidecar) is kept if its columns, types and values are those
    this code writes, and its checksum recorded; one with an impossible value is recomputed."""
    side = sidecar_path(store.batch_path(folder, 1))
    side.unlink()
    res, notes = _resume(folder)
    assert notes == [] and res.timing["loaded_batches"] == [0, 1, 2, 3]
    assert side.read_text().split() == [file_sha256(store.batch_path(folder, 1)),
                                        "batch-00001.parquet"]
    # a value like the review's (c_r_to_l = 1.16e27), in a file with no checksum
    df = pd.read_parquet(store.batch_path(folder, 3))
    df.loc[4, "c_r_to_l"] = 1.16e27
    store.write_batch(folder, 3, df, config())
    sidecar_path(store.batch_path(folder, 3)).unlink()
    res, notes = _resume(folder)
    assert res.timing["computed_batches"] == [3]
    assert res.timing["recomputed_batches"]["3"] == (
        "no recorded checksum, and column 'c_r_to_l' holds 1.16e+27 (allowed NaN or -1000..1000)")
    assert np.isfinite(res.frame["c_r_to_l"]).all() and res.frame["c_r_to_l"].max() < 2


def test_old_folder_batches_pass_the_checks(tmp_path):
    """tests/data/ensemble-0.4.0 holds no checksums: its tables pass the checks as they are."""
    from pathlib import Path

    src = Path(__file__).resolve().parents[1] / "data" / "ensemble-0.4.0"
    for b in range(3):
        path = store.batch_path(src, b)
        assert not sidecar_path(path).exists()
        assert store._implausible(pd.read_parquet(path)) is None


def test_low_memory_summary_refuses_a_batch_damaged_after_the_run(pristine, folder):
    res = run_ensemble(config(), keep_frame=False, settings=RunSettings(out=folder))
    assert res.timing["loaded_batches"] == [0, 1, 2, 3]
    _flip(store.batch_path(folder, 0), seed=1)
    with pytest.raises(ArchInputError, match=r"batch-00000\.parquet' is damaged: its sha256"):
        res.summary()


def test_cli_names_the_damaged_batch_on_stderr(capsys, folder):
    from archrock.cli import main

    argv = ["ensemble", "--samples", "80", "--batch-size", "20", "--seed", "3", "--pulse",
            "oppenheim", "--amplitude", "-1", "--pulse-duration", "0.2", "--out", str(folder),
            "--json"]
    assert main(argv + ["--no-progress"]) == 0
    clean = json.loads(capsys.readouterr().out)
    _flip(store.batch_path(folder, 1), seed=2)
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert "ensemble: recomputing batch 1: batch-00001.parquet damaged: its sha256" in err
    again = json.loads(out)
    assert again["timing"]["computed_batches"] == [1]
    clean.pop("timing"), again.pop("timing")
    assert again == clean
    # without progress output it is still said, once, as a warning
    _flip(store.batch_path(folder, 2), seed=3)
    assert main(argv + ["--no-progress"]) == 0
    err = capsys.readouterr().err
    assert err.startswith("archrock: warning: ensemble: recomputing batch 2: batch-00002.parquet "
                          "damaged: its sha256") and err.count("\n") == 1
    (folder / "manifest.json").write_text("{}")
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("archrock: error: out: ") and "manifest.json' is damaged" in err
    assert err.count("\n") == 1


# ---------------------------------------------------------------------------- a sweep's store
@pytest.fixture(scope="module")
def sweep_inputs():
    from archrock.dynamics.sweep import SweepArches, SweepMotions
    from archrock.geometry import nominal_arch
    from archrock.groundmotion.pulses import pulse
    from archrock.studies.ida import random_models

    models = random_models(nominal_arch(radius=2.0, thickness=0.3), 2, 0)
    return (SweepArches.from_models(models.models),
            SweepMotions.of([pulse("oppenheim", -0.3, 0.2)]))


def _items(k):
    a, m, s = [0, 1] * k, [0] * (2 * k), [1.0 + i for i in range(2 * k)]
    res = {"status": np.array([0, 1] * k), "peak": np.linspace(0.01, 0.2, 2 * k),
           "t_collapse": np.full(2 * k, np.nan), "t_unstable": np.full(2 * k, np.nan),
           "t_limit": np.full(2 * k, np.nan), "n_events": np.arange(2 * k)}
    return a, m, s, res


def test_a_damaged_chunk_is_named_removed_and_its_items_not_loaded(sweep_inputs, tmp_path):
    arches, motions = sweep_inputs
    out = tmp_path / "sweep"
    first = store.ResultStore(out, arches, motions)
    for k in (1, 2, 3):
        a, m, s, res = _items(k)
        first.write(a, m, s, res)
    chunks = sorted((out / "items").glob("chunk-*.parquet"))
    assert [check_sidecar(c) for c in chunks] == [None] * 3
    _flip(chunks[1], n=32)
    notes = []
    again = store.ResultStore(out, arches, motions, note=notes.append)
    assert again.damaged == ["items/chunk-00001.parquet"]
    assert len(notes) == 1 and notes[0].startswith(
        "out: recomputing the items of items/chunk-00001.parquet in ") and "damaged" in notes[0]
    assert not chunks[1].exists() and not sidecar_path(chunks[1]).exists()
    # chunk 0 (2 items) and chunk 2 (6 items, 2 of them those of chunk 1) are kept
    a, m, s, _ = _items(3)
    assert again.loaded == 6 and again.next == 3
    assert repr(again.lookup(a, m, s)) == repr(first.lookup(a, m, s))  # NaN times
    # a chunk without a checksum with an impossible value is not loaded either
    sidecar_path(chunks[2]).unlink()
    import pyarrow.parquet as pq

    tab = pq.read_table(chunks[2]).to_pydict()
    tab["peak"][0] = -3.1e146
    import pyarrow as pa

    pq.write_table(pa.table(tab), chunks[2])
    notes.clear()
    third = store.ResultStore(out, arches, motions, note=notes.append)
    assert third.loaded == 2 and "column 'peak' holds -3.1e+146" in notes[0]


def test_a_chunk_without_a_checksum_is_kept_and_recorded(sweep_inputs, tmp_path):
    arches, motions = sweep_inputs
    out = tmp_path / "sweep"
    store.ResultStore(out, arches, motions).write(*_items(2))
    chunk = out / "items" / "chunk-00000.parquet"
    sidecar_path(chunk).unlink()
    again = store.ResultStore(out, arches, motions, note=pytest.fail)
    assert again.loaded == 4 and check_sidecar(chunk) is None
    chunk.write_bytes(chunk.read_bytes()[:100])  # truncated; no progress sink: a warning
    with pytest.warns(UserWarning, match=r"^out: recomputing the items of items/chunk-00000"
                                         r"\.parquet in .*: damaged: its sha256"):
        assert store.ResultStore(out, arches, motions).loaded == 0


def test_a_damaged_sweep_manifest_is_refused(sweep_inputs, tmp_path):
    arches, motions = sweep_inputs
    out = tmp_path / "sweep"
    store.ResultStore(out, arches, motions, about={"study": "test"})
    man = out / "manifest.json"
    man.write_text(man.read_text().replace('"test"', '"tesT"'))
    with pytest.raises(ArchInputError, match=r"^out: '.*manifest\.json' is damaged"):
        store.ResultStore(out, arches, motions, about={"study": "test"})
