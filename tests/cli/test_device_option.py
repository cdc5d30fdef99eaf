"""--device cpu|gpu|auto on ensemble, curves and fragility: bad values and a missing GPU are
one-line errors (exit 2), auto gives the CPU's numbers."""

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


@pytest.mark.parametrize("command, name", [(["curves"], "curves"),
                                           (["fragility", "--records", "r.csv"], "fragility")])
def test_curves_and_fragility_run_on_the_cpu_only(capsys, command, name):
    code, _, err = run(capsys, *command, "--device", "gpu")
    assert code == 2
    assert err.strip() == (f"archrock: error: device: 'gpu'; {name} runs on the CPU only (the "
                           f"GPU builds are the ensemble's batch kernels, docs/gpu.md); allowed "
                           f"'cpu' or 'auto'")


def test_ensemble_auto_gives_the_cpus_numbers(capsys):
    cpu = json.loads(run(capsys, *ENSEMBLE, "--device", "cpu", "--json")[1])
    auto = json.loads(run(capsys, *ENSEMBLE, "--device", "auto", "--json")[1])
    assert cpu["timing"]["device"] == auto["timing"]["device"] == "cpu"
    for d in (cpu, auto):  # timing differs run to run; everything else is the same
        d.pop("timing")
    assert auto == cpu
    assert cpu["outcomes"]["integrated"]["collapsed"] == 2  # 2 of the 6 collapse (the test can fail)
