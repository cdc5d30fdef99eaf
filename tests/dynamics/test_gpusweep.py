"""The sweep's GPU build (archrock.dynamics.gpusweep) against the CPU's sweep: under numba's CUDA
simulator, in a subprocess (the simulator is chosen when numba is first imported), the same
source run as Python."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from archrock.dynamics.gpusweep import SIMULATOR_CHUNK, chunk_items
from archrock.statics.gpusearch import THREADS_PER_BLOCK

HERE = Path(__file__).parent
pytest.importorskip("numba")

#: the simulator is the CPU's arithmetic but CPython's libm (the exact loop closure outside the
#: tables, the early stop's potential): rotations and times to this, outcomes and event counts
#: exact (measured on these items: every difference 0.0, the CPU's bits)
SIM_TOL = 1e-13


def _simulated(script: str) -> list:
    env = dict(os.environ, NUMBA_ENABLE_CUDASIM="1")
    src = str(Path(__file__).parents[2] / "src")
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    proc = subprocess.run([sys.executable, str(HERE / script)], env=env, capture_output=True,
                          text=True, timeout=900)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]


@pytest.fixture(scope="module")
def compared() -> list:
    """The compare script's lines: two sweeps (early stop off, on), then the stripes."""
    return _simulated("gpu_sweep_compare.py")


@pytest.mark.slow  # numba's simulator in a child process (the default suite's time)
def test_simulated_gpu_sweep_equals_the_cpus(compared):
    rows = compared[:2]
    assert [r["early_stop"] for r in rows] == [False, True]
    for r in rows:
        assert (r["cpu_device"], r["gpu_device"]) == ("cpu", "gpu")
        assert r["items"] == 8 and r["launches"] == -(-8 // SIMULATOR_CHUNK)  # chunked
        assert r["status_differ"] == 0 and r["n_events_differ"] == 0
        for key in ("peak", "t_collapse", "t_unstable", "t_limit"):
            assert r[key] <= SIM_TOL, (r["early_stop"], key, r[key])
    full, stop = (np.array(r["status"]) for r in rows)
    # both outcomes exercised (the paper's pulse at 2.5 x 0.5 g collapses the small arches)
    assert set(full) == {0, 1}
    # early stop ends only items that do not collapse, and does end some
    assert np.array_equal(full == 1, stop == 1) and (stop == 3).sum() >= 1


@pytest.mark.slow  # numba's simulator in a child process (the default suite's time)
def test_stripes_with_device_gpu_run_on_the_gpu_and_equal_the_cpus(compared):
    r = compared[2]
    assert r["cpu_gpu_calls"] == 0 and r["gpu_launches"] >= 1  # the settings' device is used
    assert r["stripes"] == r["stripes_gpu"] == [0, 0, 1, 1] and r["same_dict"]


def test_chunks_fit_the_scratch_budget():
    # 8 bytes x (6000 samples + 7) per item: 1 GiB free, half of it for scratch
    assert chunk_items(10**6, 6000, free_bytes=2**30) == (2**29) // (8 * 6007)
    assert chunk_items(10, 6000, free_bytes=2**30) == THREADS_PER_BLOCK  # at least a block
    assert chunk_items(10**6, 6000, free_bytes=10) == THREADS_PER_BLOCK

