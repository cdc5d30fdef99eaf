"""Fixtures shared by the test modules."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

import archrock


@pytest.fixture
def without_numba():
    """Run ``python <args>`` with ARCHROCK_NO_NUMBA=1 (the pure-Python kernels) on this checkout;
    returns its stdout, failing the test with its stderr if it exits non-zero."""
    env = {**os.environ, "ARCHROCK_NO_NUMBA": "1",
           "PYTHONPATH": os.pathsep.join([str(Path(archrock.__file__).parents[1]),
                                          os.environ.get("PYTHONPATH", "")])}

    def run(*args: str, timeout: float = 600) -> str:
        proc = subprocess.run([sys.executable, *args], env=env, capture_output=True, text=True,
                              timeout=timeout)
        assert proc.returncode == 0, proc.stderr
        return proc.stdout

    return run
