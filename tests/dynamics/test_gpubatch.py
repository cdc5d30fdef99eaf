"""The batch kernels' GPU build (archrock._device, statics.gpusearch, dynamics.gpubatch) against
the CPU's: under numba's CUDA simulator (the same source run as Python, in a subprocess because
the simulator is chosen when numba is first imported), and compiled to PTX for sm_90 where
numba's CUDA target and NVVM are installed (the ``gpu`` extra)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from archrock._device import (AUTO_MIN_ARCHES, DEVICES, check_device, gpu_present,
                              resolve_device)
from archrock.dynamics.batch import prepare_batch, simulate_batch
from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch
from archrock.groundmotion import oppenheim_pulse

HERE = Path(__file__).parent
numba = pytest.importorskip("numba")


def _run(script: str, *args: str, simulator: bool, timeout: float = 1800) -> list:
    env = dict(os.environ)
    env["NUMBA_ENABLE_CUDASIM"] = "1" if simulator else "0"
    src = str(Path(__file__).parents[2] / "src")
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    proc = subprocess.run([sys.executable, str(HERE / script), *args], env=env,
                          capture_output=True, text=True, timeout=timeout)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]


def _agree(rows: list, tol: float) -> None:
    for row in rows:
        for key, value in row.items():
            if key.endswith("_differ"):
                assert value == 0, (row["set"], key, value)
            elif key in ("k_l", "k_r", "geo_l", "geo_r", "phi_unstable_l", "phi_limit_l",
                         "v_rest", "c_l_to_r", "peak", "t_collapse", "t_unstable", "t_limit"):
                assert value <= tol, (row["set"], key, value)
        assert row["usable"] > 0


def test_device_option_is_checked():
    assert DEVICES == ("cpu", "gpu", "auto")
    assert check_device(" GPU ") == "gpu"
    for bad in ("tpu", "", None, 1):
        with pytest.raises(ArchInputError, match="device: .*allowed cpu, gpu, auto"):
            check_device(bad)
    nom = oppenheim_arch()
    with pytest.raises(ArchInputError, match="device"):
        prepare_batch(nom.spans[None], nom.radii[None], nom.thicknesses[None], nominal=nom,
                      device="tpu")


@pytest.mark.skipif(gpu_present(), reason="a GPU is present here")
def test_without_a_gpu_auto_is_the_cpu_and_gpu_says_why():
    assert resolve_device("auto", 10 * AUTO_MIN_ARCHES) == "cpu"
    assert resolve_device("cpu", 10**9) == "cpu"
    nom = oppenheim_arch()
    pb = prepare_batch(nom.spans[None], nom.radii[None], nom.thicknesses[None], nominal=nom,
                       device="auto")
    res = simulate_batch(pb, oppenheim_pulse(-1.0, 0.25), device="auto")
    assert res["status"][0] == 1  # the nominal arch collapses under this pulse (paper, fig. 3)
    if not os.environ.get("NUMBA_ENABLE_CUDASIM"):
        with pytest.raises(ArchInputError, match="device: 'gpu' but no CUDA GPU"):
            simulate_batch(pb, oppenheim_pulse(-1.0, 0.25), device="gpu")


#: the simulator runs the device source as Python: the CPU's arithmetic but CPython's libm and
#: x**2 for LLVM's (measured on 1000 arches: 2.9e-11 kg on four-link masses of 1e4 kg, 3.6e-15 s
#: on times, peaks equal)
SIM_TOL = 1e-13


def test_simulator_equals_cpu_on_three_kinds_of_arches():
    rows = _run("gpu_sim_compare.py", "5", "2", "2", simulator=True)
    assert [r["set"] for r in rows] == ["circular", "family", "surveyed"]
    _agree(rows, SIM_TOL)
    assert sum(r["collapsed"] for r in rows) > 0


@pytest.mark.slow
def test_simulator_equals_cpu_on_eighteen_arches():
    # numba-cuda's simulator takes seconds an arch: 1,000 arches (docs/gpu.md) are a command
    # to run by hand (python tests/dynamics/gpu_sim_compare.py 1000 60 60), not a CI test
    rows = _run("gpu_sim_compare.py", "12", "3", "3", simulator=True)
    _agree(rows, SIM_TOL)
    circ = rows[0]
    assert circ["arches"] == 12 and circ["usable"] > 9 and circ["collapsed"] > 0


@pytest.mark.slow
def test_kernels_compile_for_sm90():
    """The four kernels (the batch's three and the sweep's) through NVVM for an H100/H200 (no
    GPU needed; skipped without the ``gpu`` extra's compiler)."""
    try:
        from numba.cuda.cudadrv import nvvm

        nvvm.NVVM()
    except Exception as exc:  # noqa: BLE001 - no NVVM here: the check cannot run
        pytest.skip(f"numba's CUDA target or NVVM is missing: {str(exc).splitlines()[0][:80]}")
    rows = _run("gpu_compile_check.py", simulator=False, timeout=900)
    assert set(rows[0]) == {"_four_hinge_kernel", "_prepare_kernel", "_simulate_kernel",
                            "_sweep_kernel"}
    assert all(v["ptx_bytes"] > 10_000 for v in rows[0].values())


@pytest.mark.slow
def test_fused_multiply_adds_keep_the_outcomes_within_the_stated_tolerance(tmp_path):
    """The kernels rebuilt for the CPU with FMA contraction (a GPU's rounding) against the plain
    build, through benchmarks/gpu_rounding.py: docs/gpu.md's tolerance (on a CPU without FMA
    both builds are the same bits)."""
    out = tmp_path / "rounding.json"
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).parents[2] / "src"))
    proc = subprocess.run([sys.executable, str(Path(__file__).parents[2] / "benchmarks"
                                               / "gpu_rounding.py"), "--samples", "3000",
                           "--json", str(out)], env=env, capture_output=True, text=True,
                          timeout=1200)
    assert proc.returncode == 0, proc.stderr[-3000:]
    r = json.loads(out.read_text())
    assert r["outcomes_differ"] == 0 and r["impact_counts_differ"] == 0
    assert 0 < r["collapsed"] < r["samples"]
    for k in ("k_l", "k_r", "geo_l", "geo_r"):
        assert r[k] <= 1e-13 and r[k + "_nan_differ"] == 0, k
    assert r["peak"] <= 1e-10
    assert r["t_collapse"] <= 1e-9 and r["t_unstable"] <= 1e-9
