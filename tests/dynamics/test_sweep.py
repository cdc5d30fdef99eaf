"""The sweep engine (arches x motions x scales in one parallel loop) against respond, and the
studies on it (IDA, stripes) against their arch-by-arch path: identical, bit for bit."""

import numpy as np
import pytest
from scipy.signal import butter, sosfilt

from archrock.dynamics.batch import prepare_batch, simulate_batch
from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.groundmotion import from_samples
from archrock.studies.ida import ida, msa, random_models
from archrock.studies.runner import RunSettings
from archrock.dynamics.response import respond
from archrock.geometry.sampling import ArchSampler
from archrock.dynamics.sweep import SweepArches, SweepMotions, sweep

STATUS = {"rest": 0, "collapsed": 1, "moving": 2}


def noise_record(seed, duration=5.0, dt=0.01, pga_g=0.3, band=(0.5, 4.0)):
    """Seeded band-limited noise with a sin^2 envelope, PGA = pga_g."""
    rng = np.random.default_rng(seed)
    n = int(duration / dt)
    sos = butter(2, list(band), btype="band", fs=1 / dt, output="sos")
    x = sosfilt(sos, rng.standard_normal(n))
    x *= np.sin(np.pi * np.arange(n) * dt / duration) ** 2
    return from_samples(x * pga_g / np.max(np.abs(x)), dt, name=f"noise {seed}")


@pytest.fixture(scope="module")
def models():
    # small irregular arches (R = 2 m): short responses
    return random_models(nominal_arch(radius=2.0, thickness=0.3), 3, 0)


@pytest.fixture(scope="module")
def records():
    return [noise_record(1), noise_record(2, band=(0.3, 2.0))]


def test_sweep_items_equal_respond_bit_for_bit(models, records):
    A, M = SweepArches.from_models(models.models), SweepMotions.of(records)
    ai, mi, si = (x.ravel() for x in np.meshgrid(np.arange(3), np.arange(2),
                                                  [0.9, 1.4, 2.0, 3.1, 4.5], indexing="ij"))
    res = sweep(A, M, ai, mi, si)
    serial = sweep(A, M, ai, mi, si, parallel=False)
    for key in ("status", "peak", "t_collapse", "t_unstable", "t_limit", "n_events"):
        np.testing.assert_array_equal(res[key], serial[key])
    seen = set()
    for k, (a, m, s) in enumerate(zip(ai, mi, si)):
        r = respond(models[a], records[m].scaled(float(s)), t_end=0.5, dt_out=0.5)
        assert res["status"][k] == STATUS[r.status]
        assert res["peak"][k] == r.peak  # exact: the same numbers in the same order
        for key in ("t_collapse", "t_unstable", "t_limit"):
            v = getattr(r, key)
            assert (np.isnan(res[key][k]) if v is None else res[key][k] == v)
        assert res["n_events"][k] == len(r.events)
        seen.add(r.status)
    assert seen == {"rest", "collapsed"}  # both outcomes are exercised


def test_ida_batch_equals_arch_by_arch(models, records):
    scales = np.linspace(0.8, 6.0, 14)
    new = ida(records, models, scales, tol=2e-3)
    old = ida(records, models, scales, tol=2e-3, engine="respond")
    assert [c.to_dict() for c in new.curves] == [c.to_dict() for c in old.curves]
    assert new.fit == old.fit
    firsts = [c.first_scale for c in new.curves]
    assert sum(f is not None for f in firsts) >= 4
    # lowest grid scale already collapsing: bisected from the no-activation scale, same in both
    high = np.linspace(4.0, 6.0, 3)
    a = ida(records, models, high, tol=2e-3)
    b = ida(records, models, high, tol=2e-3, engine="respond")
    assert [c.to_dict() for c in a.curves] == [c.to_dict() for c in b.curves]
    below = [c for c in a.curves if c.below_grid]
    assert below and all(c.safe_scale is not None and c.bracket[0] == pytest.approx(
        c.bracket[1], rel=3e-3) for c in below)


def test_ida_with_early_stop_keeps_every_first_collapse(models, records):
    """Early stop ends only responses that can no longer collapse (the energy below every
    mechanism's barrier after the record): first-collapse scales, survivals and the fit are
    those of the full responses."""
    from archrock.dynamics.sweep import HAVE_EARLY_STOP

    assert HAVE_EARLY_STOP
    scales = np.linspace(0.8, 6.0, 14)
    full = ida(records, models, scales, tol=2e-3)
    stop = ida(records, models, scales, tol=2e-3, early_stop=True)
    for a, b in zip(full.curves, stop.curves):
        assert a.first_scale == b.first_scale and a.survivals_above == b.survivals_above
        assert a.bracket == b.bracket
        assert np.array_equal(a.collapsed, b.collapsed)
    assert full.fit == stop.fit


def test_stripes_batch_equal_arch_by_arch(models, records):
    levels = [0.3, 0.5, 0.8, 1.2]
    a = msa(records, models, levels)
    b = msa(records, models, levels, engine="respond")
    np.testing.assert_array_equal(a.outcomes, b.outcomes)
    assert a.to_dict() == b.to_dict()
    assert 0 < a.collapses.sum() < a.outcomes.size


@pytest.mark.slow  # compiles the batch preparation and loop (shared with test_batch)
def test_from_batch_agrees_with_simulate_batch(records):
    sampler = ArchSampler(nominal_arch(radius=2.0, thickness=0.3), seed=3)
    pb = prepare_batch(sampler.arches(0, 4), cv=0.8754)
    A = SweepArches.from_batch(pb)
    M = SweepMotions.of([records[1].scaled(3.0)])
    res = sweep(A, M, np.arange(len(A)), np.zeros(len(A)), np.ones(len(A)))
    ref = simulate_batch(pb, records[1].scaled(3.0))
    ok = pb.ok
    np.testing.assert_array_equal(res["status"], ref["status"][ok])
    np.testing.assert_array_equal(res["peak"], ref["peak"][ok])


def test_bad_items_and_engine(models, records):
    A, M = SweepArches.from_models(models.models), SweepMotions.of(records)
    with pytest.raises(ArchInputError, match="lengths"):
        sweep(A, M, [0, 1], [0], [1.0])
    with pytest.raises(ArchInputError, match="arch_index"):
        sweep(A, M, [5], [0], [1.0])
    with pytest.raises(ArchInputError, match="motion_index"):
        sweep(A, M, [0], [2], [1.0])
    with pytest.raises(ArchInputError, match="scales"):
        sweep(A, M, [0], [0], [np.nan])
    with pytest.raises(ArchInputError, match="engine"):
        ida(records, models, [1.0, 2.0], engine="fast")
    with pytest.raises(ArchInputError, match="workers"):
        ida(records, models, [1.0, 2.0], settings={"workers": 0})


def test_sweep_device_auto_is_the_cpu_and_respond_refuses_gpu(models, records, monkeypatch):
    """'auto' on a few items is the CPU's sweep; the arch-by-arch engine has no GPU build and
    says so; without a GPU the batch engine's 'gpu' is refused before any response."""
    from archrock._device import gpu_present

    A, M = SweepArches.from_models(models.models), SweepMotions.of(records)
    cpu = sweep(A, M, [0, 1, 2], [0, 1, 0], [1.4, 2.0, 3.1])
    auto = sweep(A, M, [0, 1, 2], [0, 1, 0], [1.4, 2.0, 3.1], device="auto")
    assert cpu["device"] == auto["device"] == "cpu" and "gpu" not in auto
    for key in ("status", "peak", "n_events"):
        np.testing.assert_array_equal(cpu[key], auto[key])
    with pytest.raises(ArchInputError, match=r"^device: 'gpu'; IDA and multiple stripes by "
                                             r"engine 'respond' runs on the CPU only"):
        ida(records, models, [1.0, 2.0], engine="respond", settings={"device": "gpu"})
    monkeypatch.delenv("NUMBA_ENABLE_CUDASIM", raising=False)
    if not gpu_present():
        with pytest.raises(ArchInputError, match=r"^device: 'gpu' but no CUDA GPU"):
            msa(records, models, [0.3, 0.5], settings={"device": "gpu"})


def test_curves_batch_equal_response_by_response():
    from archrock.studies.curves import collapse_curve, ensemble_curve
    from archrock.dynamics.response import prepare

    nominal = nominal_arch(radius=2.0, thickness=0.3)
    model = prepare(nominal)
    for kind in ("oppenheim", "one-sine"):
        a = collapse_curve(model, [0.15, 0.4], kind=kind, n_scan=25)
        b = collapse_curve(model, [0.15, 0.4], kind=kind, n_scan=25, engine="respond")
        assert a.to_dict(scan=True) == b.to_dict(scan=True)
        assert all(p.amplitude is not None for p in a.points)
    ea = ensemble_curve(nominal, 3, 1, durations=[0.2, 0.5], n_scan=20)
    eb = ensemble_curve(nominal, 3, 1, durations=[0.2, 0.5], n_scan=20, engine="respond")
    assert ea.to_dict() == eb.to_dict()
    with pytest.raises(ArchInputError, match="engine"):
        collapse_curve(model, [0.2], engine="x")


def test_sweep_without_numba_agrees(without_numba):
    """ARCHROCK_NO_NUMBA=1: the Python loop over the items gives the same numbers."""
    import json
    import textwrap

    script = textwrap.dedent("""
        import json
        from archrock.geometry import nominal_arch
        from archrock.groundmotion import pulse
        from archrock.studies.ida import random_models
        from archrock.dynamics.sweep import SweepArches, SweepMotions, sweep
        ms = random_models(nominal_arch(radius=2.0, thickness=0.3), 2, 0)
        A = SweepArches.from_models(ms.models)
        M = SweepMotions.of([pulse("one-sine", 0.3, 0.4), pulse("oppenheim", -0.3, 0.2)])
        r = sweep(A, M, [0, 1, 0, 1], [0, 0, 1, 1], [1.5, 2.5, 1.5, 3.0])
        print(json.dumps({k: r[k].tolist() for k in ("status", "peak")}))
    """)
    pure = json.loads(without_numba("-c", script))
    ms = random_models(nominal_arch(radius=2.0, thickness=0.3), 2, 0)
    from archrock.groundmotion import pulse

    r = sweep(SweepArches.from_models(ms.models),
              SweepMotions.of([pulse("one-sine", 0.3, 0.4), pulse("oppenheim", -0.3, 0.2)]),
              [0, 1, 0, 1], [0, 0, 1, 1], [1.5, 2.5, 1.5, 3.0])
    assert pure["status"] == r["status"].tolist()
    np.testing.assert_allclose(pure["peak"], r["peak"], rtol=1e-12)
    assert set(pure["status"]) >= {1}


def test_out_folder_keeps_responses_and_resumes(models, records, tmp_path, monkeypatch):
    pytest.importorskip("pyarrow")
    import archrock.studies.runner as sr

    scales = np.linspace(0.8, 6.0, 10)
    ref = ida(records, models, scales, tol=5e-3)
    out = tmp_path / "run"
    first = ida(records, models, scales, tol=5e-3, settings=RunSettings(out=out))
    assert [c.to_dict() for c in first.curves] == [c.to_dict() for c in ref.curves]
    chunks = sorted((out / "items").glob("chunk-*.parquet"))
    assert chunks and (out / "manifest.json").exists()
    # lose half the chunks (a killed run): the rerun computes those only, the same curves
    for f in chunks[::2]:
        f.unlink()
    kept = sr.ResultStore(out, SweepArches.from_models(models.models), SweepMotions.of(records),
                          settings={"max_events": 50_000, "early_stop": False}).loaded
    ran = []
    real = sr.sweep
    monkeypatch.setattr(sr, "sweep", lambda *a, **k: ran.append(len(a[2])) or real(*a, **k))
    again = ida(records, models, scales, tol=5e-3, settings=RunSettings(out=out))
    assert [c.to_dict() for c in again.curves] == [c.to_dict() for c in ref.curves]
    total = sum(len(f.read_bytes()) > 0 for f in (out / "items").glob("chunk-*.parquet"))
    assert 0 < sum(ran) and kept > 0 and total > len(chunks) // 2
    # everything kept now: nothing runs
    ran.clear()
    ida(records, models, scales, tol=5e-3, settings=RunSettings(out=out))
    assert sum(ran) == 0
    # another study in the same folder is refused, naming --out
    with pytest.raises(ArchInputError, match="^out:"):
        ida(records[:1], models, scales, tol=5e-3, settings=RunSettings(out=out))


@pytest.mark.slow  # spawns worker processes (each compiles its serial loop) and a Dask cluster
def test_process_pool_and_dask_give_the_same_curves(models, records):
    scales = np.linspace(0.8, 6.0, 8)
    ref = [c.to_dict() for c in ida(records, models, scales).curves]
    assert [c.to_dict() for c in ida(records, models, scales, settings=RunSettings(workers=2)).curves] == ref
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        assert [c.to_dict() for c in ida(records, models, scales,
                                              settings=RunSettings(scheduler=client)).curves] == ref


def test_least_loss_chains_equal_respond(records):
    """Chains longer than M_l, M_r (the least-loss law opens other mechanisms at impacts)."""
    from archrock.dynamics.response import prepare

    sampler = ArchSampler(nominal_arch(radius=2.0, thickness=0.3), seed=0)
    ms = [prepare(sampler.arch(i), "least-loss") for i in (0, 4, 1)]
    assert max(len(m.chain[0]) for m in ms) > 2
    A, M = SweepArches.from_models(ms), SweepMotions.of(records[1:])
    ai = np.repeat(np.arange(3), 3)
    si = np.tile([1.5, 2.5, 3.5], 3)
    res = sweep(A, M, ai, np.zeros(9, int), si)
    for k, (a, s) in enumerate(zip(ai, si)):
        r = respond(ms[a], records[1].scaled(float(s)), t_end=0.5, dt_out=0.5)
        assert res["status"][k] == STATUS[r.status] and res["peak"][k] == r.peak
        assert res["n_events"][k] == len(r.events)
