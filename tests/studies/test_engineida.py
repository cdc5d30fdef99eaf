"""IDA fragility by the contact engine (issue 31, archrock.studies.engineida): the heavy-pier arch
(one degree of freedom cannot follow it) under one-sine pulses, on a coarse engine (100 steps
per T, 10 iterations, 3 T of free motion: fast, not converged) so that the tests take seconds."""

import json
import math

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry.files import read_arch
from archrock.groundmotion import G, GroundMotion
from archrock.studies.engineida import EngineIDAResult, engine_ida
from archrock.studies.enginestudy import EngineRun, choose_dynamics
from archrock.studies.runner import RunSettings

#: the scale grid: 0.05 g is below the arch's activation (k = 0.113 g: nothing moves), 2 g far
#: above the engine's first collapse (about 0.7 g on the heavy piers)
SCALES = (0.05, 0.3, 1.0, 2.0)


def _sine(tp: float) -> GroundMotion:
    """One full sine of period ``tp`` [s] and 1 g amplitude."""
    t = np.linspace(0.0, tp, 201)
    return GroundMotion(t, G * np.sin(2 * np.pi * t / tp), name=f"sine {tp:g} s")


@pytest.fixture(scope="module")
def heavy_arch(heavy_piers_file):
    return read_arch(heavy_piers_file)


@pytest.fixture(scope="module")
def coarse():
    from archrock.contact import EngineSettings

    return EngineRun(EngineSettings(steps_per_T=100, iterations=10), t_free=3.0)


@pytest.fixture(scope="module")
def records():
    return [_sine(1.0), _sine(2.0)]


@pytest.fixture(scope="module")
def result(heavy_arch, records, coarse):
    lines = []
    res = engine_ida(heavy_arch, records, SCALES, run=coarse,
                     settings=RunSettings(progress=lines.append),
                     dynamics=choose_dynamics(heavy_arch))
    return res, lines


def test_far_below_activation_survives_far_above_collapses(result):
    res, lines = result
    assert isinstance(res, EngineIDAResult)
    assert res.collapsed.shape == (2, len(SCALES)) and res.collapsed.dtype == bool
    assert not res.collapsed[:, 0].any()  # 0.05 g cannot open a joint
    assert all(st == "rest" for st in (row[0] for row in res.status))
    assert res.collapsed[:, -1].all()     # 2 g: far above the engine's first collapse
    # each record's capacity is its smallest collapsing grid scale
    for row, first in zip(res.collapsed, res.first_scales):
        assert first == SCALES[int(np.flatnonzero(row)[0])]
    assert len(lines) == 2 and lines[-1].startswith("engine ida: record 2/2")


def test_fit_median_lies_between_the_survival_and_the_collapse(result, records):
    res, _ = result
    assert res.fit is not None and res.fit_error is None
    assert res.fit.method == "moments"  # every record collapsed: no censoring
    lo = min(r.pga_g for r in records) * SCALES[0]
    hi = max(r.pga_g for r in records) * SCALES[-1]
    assert lo < res.fit.theta < hi
    # PGA convention of the IDA: IM = scale x the record's PGA [g]
    np.testing.assert_allclose(res.first_ims, [f * r.pga_g for f, r in
                                               zip(res.first_scales, records)], rtol=1e-12)


def test_result_to_json_and_as_ida(result):
    res, _ = result
    d = json.loads(json.dumps(res.to_dict()))
    assert d["how"] == "contact engine" and d["dynamics"]["used"] == "engine"
    assert d["collapsed"] == res.collapsed.astype(int).tolist()
    assert d["engine"]["settings"]["steps_per_T"] == pytest.approx(100.0)
    ida = res.as_ida()
    assert [c.first_scale for c in ida.curves] == list(res.first_scales)
    assert ida.fit is res.fit
    assert not res.collapsed.flags.writeable


@pytest.mark.slow  # a process pool on a shared 2-core runner: ~30-60 s
def test_two_workers_give_the_same_matrix(heavy_arch, records, coarse, result):
    res1, _ = result
    lines = []
    # two records, one a worker, finishing in any order; the grid's two ends (seconds)
    res2 = engine_ida(heavy_arch, records, SCALES[::3], run=coarse,
                      settings=RunSettings(workers=2, progress=lines.append))
    assert res2.timing["workers"].startswith("process pool")
    np.testing.assert_array_equal(res2.collapsed, res1.collapsed[:, ::3])
    assert res2.status == tuple(row[::3] for row in res1.status)
    assert len(lines) == 2


def test_a_record_that_never_collapses_is_censored(heavy_arch, records, coarse):
    res = engine_ida(heavy_arch, records, (0.02, 0.05), run=coarse)
    assert not res.collapsed.any() and res.n_censored == 2
    assert res.fit is None and res.fit_error  # no collapse at all: nothing to fit
    assert math.isinf(res.first_ims[0])


@pytest.mark.parametrize("kw, field", [
    (dict(scales=(1.0, 0.5)), "scales"),
    (dict(run="fast"), "run"),
    (dict(settings={"workers": 0}), "workers"),
    (dict(n_boot=1), "n_boot"),
    (dict(settings={"progress": 3}), "progress"),
    (dict(settings=RunSettings(out="x")), "out"),
    (dict(im="nope"), "im"),
])
def test_bad_input_names_the_field(heavy_arch, records, kw, field):
    args = dict(scales=SCALES)
    args.update(kw)
    scales = args.pop("scales")
    with pytest.raises(ArchInputError, match=rf"^{field}"):
        engine_ida(heavy_arch, records, scales, **args)


def test_the_0_6_run_keywords_are_gone(heavy_arch, records):
    """0.7: workers, scheduler and progress go in settings= (RunSettings or its dict)."""
    for old in ("workers", "scheduler", "progress"):
        with pytest.raises(TypeError, match=f"unexpected keyword argument '{old}'"):
            engine_ida(heavy_arch, records, SCALES, **{old: None})
