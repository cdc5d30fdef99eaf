"""--device cpu|gpu|auto on ensemble, curves and fragility: bad values and a missing GPU are
one-line errors (exit 2), auto gives the CPU's numbers, and the curves on numba's simulated GPU
give the CPU's JSON."""

import json

import pytest

from archrock.cli import main

#: six arches of the paper's pulse, early stop: a second or so once compiled
ENSEMBLE = ["ensemble", "--samples", "6", "--batch-size", "3", "--seed", "11", "--pulse",
            "oppenheim", "--pulse-duration", "0.2", "--amplitude", "-1", "--early-stop",
            "--no-progress"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("command", [ENSEMBLE, ["curves"], ["fragility", "--records", "r.csv"]])
def test_a_bad_device_is_argparses_one_line_error(capsys, command):
    code, out, err = run(capsys, *command, "--device", "bogus")
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert "argument --device: invalid choice: 'bogus' (choose from 'cpu', 'gpu', 'auto')" in err


def test_ensemble_on_gpu_without_one_is_refused(capsys, monkeypatch):
    from archrock._device import gpu_present

    monkeypatch.delenv("NUMBA_ENABLE_CUDASIM", raising=False)
    if gpu_present():
        pytest.skip("a CUDA GPU is present here")
    code, out, err = run(capsys, *ENSEMBLE, "--device", "gpu")
    assert code == 2 and out == ""
    assert err.startswith("archrock: error: device: 'gpu'") and "Traceback" not in err
    assert "allowed 'cpu' or 'auto'" in err and len(err.strip().splitlines()) == 1


def test_ensemble_on_gpu_with_a_pool_is_refused(capsys):
    code, _, err = run(capsys, *ENSEMBLE, "--device", "gpu", "--workers", "2")
    assert code == 2
    assert err.startswith("archrock: error: device: 'gpu' runs in this process")


@pytest.mark.parametrize("command", [["curves"], ["fragility", "--records", "r.csv"]])
def test_curves_and_fragility_on_gpu_without_one_are_refused(capsys, monkeypatch, command):
    from archrock._device import gpu_present

    monkeypatch.delenv("NUMBA_ENABLE_CUDASIM", raising=False)
    if gpu_present():
        pytest.skip("a CUDA GPU is present here")
    code, out, err = run(capsys, *command, "--device", "gpu")  # before any work (no r.csv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert err.startswith("archrock: error: device: 'gpu' but no CUDA GPU is usable here")


@pytest.mark.parametrize("command, study", [
    (["curves", "--durations", "0.5", "--friction", "0.4"], "curves by the contact engine"),
    (["curves", "--durations", "0.5", "--engine", "respond"], "curves by engine 'respond'"),
])
def test_what_has_no_gpu_build_refuses_gpu_by_name(capsys, monkeypatch, command, study):
    # the simulator passes the check for a GPU; the study itself then refuses by name
    monkeypatch.setenv("NUMBA_ENABLE_CUDASIM", "1")
    code, _, err = run(capsys, *command, "--device", "gpu", "--no-progress")
    assert code == 2
    assert err.strip() == (f"archrock: error: device: 'gpu'; {study} runs on the CPU only (the "
                           f"GPU builds are the batch kernels and the sweep, docs/gpu.md); "
                           f"allowed 'cpu' or 'auto'")


#: a small arch, one duration, 6 responses (the simulator: ~0.5 s each)
TINY_CURVE = ["curves", "--radius", "2", "--thickness", "0.3", "--durations", "0.3",
              "--n-scan", "3", "--a-max", "3", "--tol", "0.1", "--json", "--no-progress"]


def _close(a, b, path="") -> None:
    """The same JSON, floats to 1e-9 relative (the GPU may fuse a multiply and an add)."""
    assert type(a) is type(b), path
    if isinstance(a, dict):
        assert a.keys() == b.keys(), path
        for k in a:
            _close(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            _close(x, y, f"{path}[{i}]")
    elif isinstance(a, float):
        assert a == pytest.approx(b, rel=1e-9, abs=1e-12), path
    else:
        assert a == b, path


@pytest.mark.slow  # numba's simulator in a child process (the default suite's time)
def test_curves_on_the_simulated_gpu_give_the_cpus_json(capsys):
    import os
    import subprocess
    import sys
    from pathlib import Path

    pytest.importorskip("numba")
    code, out, _ = run(capsys, *TINY_CURVE)
    assert code == 0
    cpu = json.loads(out)
    env = dict(os.environ, NUMBA_ENABLE_CUDASIM="1")
    src = str(Path(__file__).parents[2] / "src")
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    proc = subprocess.run([sys.executable, "-m", "archrock", *TINY_CURVE, "--device", "gpu"],
                          env=env, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    gpu = json.loads(proc.stdout)
    _close(cpu, gpu)
    point = cpu["curve"]["points"][0]
    assert point["n_responses"] == 6 and point["mode"] == "after 1 impact"
    assert point["amplitude_g"] == pytest.approx(0.455, abs=1e-3)  # inside the 0.1 g bracket


def test_ensemble_auto_gives_the_cpus_numbers(capsys):
    cpu = json.loads(run(capsys, *ENSEMBLE, "--device", "cpu", "--json")[1])
    auto = json.loads(run(capsys, *ENSEMBLE, "--device", "auto", "--json")[1])
    assert cpu["timing"]["device"] == auto["timing"]["device"] == "cpu"
    for d in (cpu, auto):  # timing differs run to run; everything else is the same
        d.pop("timing")
    assert auto == cpu
    assert cpu["outcomes"]["integrated"]["collapsed"] == 2  # 2 of the 6 collapse (the test can fail)
