"""The device of an ensemble's run (cpu, gpu, auto): a run setting, never part of the
configuration; the GPU build (under numba's CUDA simulator) gives the CPU's table."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import archrock
from archrock.dynamics.impact import ImpactSpec
from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch
from archrock.geometry.sampling import Spreads
from archrock.groundmotion import PulseSpec
from archrock.studies.ensemble import EnsembleConfig, run_ensemble
from archrock.studies.ensemble.compute import run_batches
from archrock.studies.ensemble.executors import GPU_GROUP_ARCHES, _groups
from archrock.studies.runner import RunSettings
from archrock.studies.store import read_batch

#: the paper's pulse (Oppenheim's, -1 g, 0.2 s) on 6 arches: the simulator runs ~0.7 s an arch
SIX = dict(samples=6, batch_size=6, seed=11, motion=PulseSpec("oppenheim", -1.0, 0.2),
           impact=ImpactSpec.parse("fixed", cv=0.8754), early_stop=True)

#: run in a fresh interpreter with NUMBA_ENABLE_CUDASIM=1 (numba reads it when numba.cuda is
#: first imported, so never in this process): the ensemble kept in argv[2] on device 'gpu'
_ON_SIMULATED_GPU = """
import json, sys
from archrock.studies.ensemble import EnsembleConfig, run_ensemble
from archrock.studies.runner import RunSettings
cfg = EnsembleConfig.from_dict(json.loads(sys.argv[1]))
res = run_ensemble(cfg, settings=RunSettings(out=sys.argv[2], device="gpu"))
from archrock._device import _BUILT
# the GPU kernels this run launched: the four-hinge search, the four-link loop, the response
built = sorted(k[1].__name__ for k in _BUILT if isinstance(k, tuple) and k[0] == "kernel")
print(json.dumps({**res.timing, "kernels": built}))
"""


def six(**kw) -> EnsembleConfig:
    return EnsembleConfig.from_arch(oppenheim_arch(), **{**SIX, **kw})


@pytest.fixture(scope="module")
def simulated_gpu_store(tmp_path_factory):
    """(config, folder, timing): :data:`SIX` run on device 'gpu' under numba's CUDA simulator
    in a child process, its batch kept in the folder."""
    pytest.importorskip("numba")
    cfg = six()
    out = tmp_path_factory.mktemp("gpu") / "store"
    env = {**os.environ, "NUMBA_ENABLE_CUDASIM": "1",
           "PYTHONPATH": os.pathsep.join([str(Path(archrock.__file__).parents[1]),
                                          os.environ.get("PYTHONPATH", "")])}
    env.pop("ARCHROCK_NO_NUMBA", None)
    proc = subprocess.run([sys.executable, "-c", _ON_SIMULATED_GPU, cfg.to_json(), str(out)],
                          env=env, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return cfg, out, json.loads(proc.stdout.strip().splitlines()[-1])


@pytest.mark.slow  # numba's simulator in a child process (the default suite's time)
def test_the_simulated_gpu_gives_the_cpus_table(simulated_gpu_store):
    cfg, out, timing = simulated_gpu_store
    assert timing["device"] == "gpu" and timing["executor"] == "in-process"
    assert timing["computed_batches"] == [0]
    assert timing["kernels"] == ["_four_hinge_kernel", "_prepare_kernel", "_simulate_kernel"]
    gpu, why = read_batch(out, 0, cfg)
    assert why is None
    (_, cpu, t_cpu), = run_batches(cfg, [0], device="cpu")
    assert t_cpu["device"] == "cpu"
    assert len(gpu) == len(cpu) == 6
    # the same outcomes, and not all alike (the comparison can fail): both collapse and
    # early-stopped survivals
    for col in ("index", "status", "collapsed", "mech_l", "mech_r", "n_impacts",
                "n_activations", "early_stopped", "events_truncated", "error"):
        assert list(gpu[col]) == list(cpu[col]), col
    assert set(cpu["status"]) == {"collapsed", "stopped"}
    for col in ("k_l", "k_r", "c_l_to_r", "c_r_to_l", "peak", "t_collapse", "t_limit",
                "t_unstable"):
        np.testing.assert_allclose(gpu[col].to_numpy(float), cpu[col].to_numpy(float),
                                   rtol=1e-12, atol=0, equal_nan=True, err_msg=col)
    assert np.all(cpu["peak"] > 0)


@pytest.mark.slow  # numba's simulator in a child process (the default suite's time)
def test_a_store_made_on_the_gpu_resumes_on_the_cpu(simulated_gpu_store):
    cfg, out, _ = simulated_gpu_store
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["runs"][0]["device"] == "gpu" and manifest["batches"]["0"]["device"] == "gpu"
    assert manifest["runs"][0]["gpu"].startswith("numba CUDA simulator")
    assert "device" not in json.dumps(manifest["config"])  # a run setting, not the study's
    res = run_ensemble(cfg, settings=RunSettings(out=out, device="cpu"))
    assert res.timing["computed_batches"] == [] and res.timing["loaded_batches"] == [0]
    assert res.timing["device"] == "cpu"
    assert json.loads((out / "manifest.json").read_text())["runs"][1]["device"] == "cpu"


def test_device_is_a_run_setting_checked_by_name():
    with pytest.raises(ArchInputError, match=r"^device: 'tpu'; allowed cpu, gpu, auto$"):
        RunSettings(device="tpu")
    with pytest.raises(ArchInputError, match=r"^device: 'gpu' runs in this process .*process "
                                             r"pool's workers\); allowed device 'gpu' with "
                                             r"workers 1 and no scheduler"):
        RunSettings(workers=2, device="gpu")
    with pytest.raises(ArchInputError, match=r"^device: 'gpu' runs in this process .*dask"):
        RunSettings(scheduler="tcp://127.0.0.1:8786", device="gpu")
    assert RunSettings(workers=2, device="auto").run_device == "cpu"
    assert RunSettings(device="auto").run_device == "auto"
    s = RunSettings(device="GPU")
    assert s.device == "gpu" and RunSettings.from_dict(json.loads(json.dumps(s.to_dict()))) == s
    assert RunSettings().device == "cpu"


def test_studies_without_a_gpu_build_refuse_gpu_and_take_auto_on_the_cpu():
    from archrock.studies.sensitivity import sobol_indices

    with pytest.raises(ArchInputError, match=r"^device: 'gpu'; defect maps runs on the CPU "):
        RunSettings(device="gpu").on_cpu("defect maps")
    assert RunSettings(device="auto").on_cpu("defect maps").device == "auto"
    with pytest.raises(ArchInputError, match=r"^device: 'gpu'; sobol_indices runs on the CPU"):
        sobol_indices(oppenheim_arch(), Spreads(0.05, 0.05, 0.0), 16, motion=None,
                      settings=RunSettings(device="gpu"))


def test_gpu_without_a_gpu_is_refused_before_any_work(monkeypatch):
    from archrock._device import gpu_present

    monkeypatch.delenv("NUMBA_ENABLE_CUDASIM", raising=False)
    if gpu_present():
        pytest.skip("a CUDA GPU is present here")
    with pytest.raises(ArchInputError, match=r"^device: 'gpu'"):
        run_ensemble(six(), settings=RunSettings(device="gpu"))


def test_auto_on_a_small_ensemble_is_the_cpus_table():
    cfg = six(samples=4, batch_size=2, early_stop=False)
    cpu = run_ensemble(cfg, settings=RunSettings())
    auto = run_ensemble(cfg, settings=RunSettings(device="auto"))
    # 4 arches: far below the GPU's break-even, so the CPU, bit for bit
    assert auto.timing["device"] == cpu.timing["device"] == "cpu"
    pd.testing.assert_frame_equal(auto.frame, cpu.frame)


def test_gpu_groups_are_larger_than_the_cpus():
    cfg = six(samples=250_000, batch_size=50_000, motion=None, early_stop=False)
    assert _groups(cfg, [0, 1, 2, 3, 4]) == [[0], [1], [2], [3], [4]]
    assert _groups(cfg, [0, 1, 2, 3, 4], GPU_GROUP_ARCHES) == [[0, 1], [2, 3], [4]]
