"""Parallel batch preparation (limit enumeration, four-link loop, compiled impact laws) against the
serial loop, the one-arch functions and the pure-Python path; early stop against the full run."""

import json
import math
import textwrap
import warnings

import numpy as np
import pytest

from archrock.dynamics import kernel as K
from archrock.dynamics.batch import prepare_batch, simulate_batch
from archrock.studies.ensemble import EnsembleConfig, run_ensemble
from archrock.geometry import family_arch, oppenheim_arch
from archrock.groundmotion import PulseSpec
from archrock.dynamics.impact import ImpactSpec, impact_law
from archrock.dynamics.impact.compiled import np_sum
from archrock.statics.limit import kinematic_mechanisms, kinematic_multipliers_batch
from archrock.dynamics.fourlink import four_link
from archrock.geometry.sampling import ArchSampler, Spreads

FIELDS = ("k_l", "k_r", "mech_l", "mech_r", "geo_l", "geo_r", "phi_unstable_l", "phi_unstable_r",
          "phi_limit_l", "phi_limit_r", "c_l_to_r", "c_r_to_l", "v_rest", "error", "chain_geo",
          "chain_limit", "chain_unstable", "chain_table", "n_mechanisms")
PULSE = PulseSpec("oppenheim", -1.0, 0.2)


def _same(a, b):
    for f in FIELDS:
        x, y = np.asarray(getattr(a, f)), np.asarray(getattr(b, f))
        if x.dtype == object:
            assert x.tolist() == y.tolist(), f
        else:
            np.testing.assert_array_equal(x, y, err_msg=f)


@pytest.fixture(scope="module")
def circular():
    """Irregular Oppenheim arches, and wild ones (many invalid, cannot stand, energy gains)."""
    s = ArchSampler(oppenheim_arch(), seed=5)
    w = ArchSampler(oppenheim_arch(), Spreads(0.3, 0.5, 0.5), seed=3)
    return s.draw(0, 60), w.draw(0, 60)


@pytest.fixture(scope="module")
def families():
    """Irregular pointed arches with tilted joints and irregular elliptical arches."""
    pointed = family_arch("pointed", 10.0, 7.0, 1.0, 12, exact=False)
    ellip = family_arch("elliptical", 10.0, 4.0, 0.8, 9, exact=False)
    return (ArchSampler(pointed, Spreads(0.1, 0.1, 0.05, 5.0), seed=2).arches(0, 12),
            ArchSampler(ellip, Spreads(0.1, 0.1, 0.05), seed=4).arches(0, 12))


@pytest.mark.parametrize("impact", ["paper", "momentum", 0.8754])
def test_parallel_equals_serial_circular(circular, impact):
    for spans, thick, radii in circular:
        par = prepare_batch(spans, radii, thick, 2000.0, impact=impact)
        ser = prepare_batch(spans, radii, thick, 2000.0, impact=impact, parallel=False)
        _same(par, ser)
    assert not par.ok.all() and par.ok.any()  # the wild batch has both kinds of row


@pytest.mark.parametrize("impact", ["paper", "momentum"])
def test_parallel_equals_serial_families(families, impact):
    for arches in families:
        _same(prepare_batch(arches, impact=impact),
              prepare_batch(arches, impact=impact, parallel=False))


def test_parallel_limit_enumeration_is_the_serial_one(circular):
    spans, thick, radii = circular[0]
    par = kinematic_multipliers_batch(spans, radii, thick, parallel=True)
    ser = kinematic_multipliers_batch(spans, radii, thick)
    for a, b in zip(par, ser):
        np.testing.assert_array_equal(a, b)


def _one_arch_law(arch, model):
    """impact_law on the arch's own FourLink objects (one-arch limit analysis)."""
    m_l, m_r = kinematic_mechanisms(arch)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return impact_law(four_link(arch, m_l), four_link(arch, m_r), model)


@pytest.mark.parametrize("model", ["paper", "momentum"])
def test_compiled_impact_laws_are_the_one_arch_laws(circular, families, model):
    """The batch's rate ratios are impact_law's on the arch's FourLink objects, to rounding;
    the arches the 'paper' model refuses carry impact_law's own message."""
    spans, thick, radii = circular[0]
    sampler = ArchSampler(oppenheim_arch(), seed=5)
    checked = refused = 0
    for arches, pb in (([sampler.arch(i) for i in range(12)],
                        prepare_batch(spans[:12], radii[:12], thick[:12], 2000.0, impact=model)),
                       (families[0], prepare_batch(families[0], impact=model)),
                       (families[1], prepare_batch(families[1], impact=model))):
        for b, arch in enumerate(arches):
            if not pb.mech_l[b]:
                continue
            try:
                law = _one_arch_law(arch, model)
            except Exception as exc:  # noqa: BLE001 - the same refusal, same words
                assert pb.error[b] == " ".join(str(exc).split())
                refused += 1
                continue
            assert pb.error[b] == ""
            # rel=1e-12: the compiled batch law and the one-arch Python law are two paths
            assert pb.c_l_to_r[b] == pytest.approx(law.l_to_r, rel=1e-12)
            assert pb.c_r_to_l[b] == pytest.approx(law.r_to_l, rel=1e-12)
            checked += 1
    assert checked >= (12 if model == "paper" else 30)
    if model == "paper":
        assert refused > 0  # the elliptical arches: the paper model creates energy there


def test_np_sum_is_numpy_sum():
    rng = np.random.default_rng(0)
    for n in list(range(0, 140)) + [255, 256, 257, 1000, 3001]:
        a = rng.standard_normal(n) * 10.0 ** rng.uniform(-4, 4, n)
        # the replica of numpy's pairwise sum is a second path: numpy's own loop is SIMD of a
        # width that differs by CPU, so the two agree to the sum's rounding bound, not the bit
        bound = 4 * np.finfo(float).eps * math.log2(n + 2) * float(np.sum(np.abs(a)))
        assert abs(np_sum(a) - np.sum(a)) <= bound, n


def test_no_numba_preparation_is_the_compiled_one(circular, families, without_numba):
    """ARCHROCK_NO_NUMBA=1 (pure Python kernels) prepares the same batch, circular and family."""
    script = textwrap.dedent("""
        import json
        import numpy as np
        from archrock.dynamics.batch import prepare_batch
        from archrock.geometry import family_arch, oppenheim_arch
        from archrock.geometry.sampling import ArchSampler, Spreads
        s, t, r = ArchSampler(oppenheim_arch(), Spreads(0.3, 0.5, 0.5), seed=3).draw(0, 16)
        nom = family_arch("pointed", 10.0, 7.0, 1.0, 12, exact=False)
        fam = ArchSampler(nom, Spreads(0.1, 0.1, 0.05, 5.0), seed=2).arches(0, 4)
        out = {}
        for imp in ("paper", "momentum"):
            for name, pb in (("c", prepare_batch(s, r, t, 2000.0, impact=imp)),
                             ("f", prepare_batch(fam, impact=imp))):
                out[name + imp] = {f: np.asarray(getattr(pb, f)).tolist() for f in
                                   ("k_l", "geo_l", "phi_limit_r", "c_l_to_r", "c_r_to_l",
                                    "v_rest", "error", "mech_r")}
        print(json.dumps(out))
    """)
    got = json.loads(without_numba("-c", script).strip().splitlines()[-1])
    spans, thick, radii = (a[:16] for a in circular[1])
    for imp in ("paper", "momentum"):
        for name, pb in (("c", prepare_batch(spans, radii, thick, 2000.0, impact=imp)),
                         ("f", prepare_batch(families[0][:4], impact=imp))):
            ref = got[name + imp]
            assert ref["error"] == pb.error.tolist() and ref["mech_r"] == pb.mech_r.tolist()
            for f in ("k_l", "geo_l", "phi_limit_r", "c_l_to_r", "c_r_to_l", "v_rest"):
                np.testing.assert_allclose(np.array(ref[f], float), getattr(pb, f), rtol=1e-12,
                                           atol=1e-12, err_msg=f)


# ---------------------------------------------------------------------------- early stop
@pytest.mark.parametrize("impact", [ImpactSpec.fixed(0.8754), "paper", "momentum"])
def test_early_stop_keeps_outcome_and_peak(impact):
    """Collapse, peak and first passage of phi_u as in the full run, on 300 random arches."""
    spans, thick, radii = ArchSampler(oppenheim_arch(), seed=9).draw(0, 300)
    pb = prepare_batch(spans, radii, thick, 2000.0, impact=impact)
    motion = PULSE.build()
    full = simulate_batch(pb, motion)
    fast = simulate_batch(pb, motion, early_stop=True)
    stopped = fast["early_stopped"]
    assert stopped.sum() > 50 and not full["early_stopped"].any()
    np.testing.assert_array_equal(full["status"] == K.ST_COLLAPSED, fast["status"] == K.ST_COLLAPSED)
    np.testing.assert_array_equal(full["peak"], fast["peak"])
    np.testing.assert_array_equal(full["t_unstable"], fast["t_unstable"])
    np.testing.assert_array_equal(full["t_collapse"], fast["t_collapse"])
    # a stopped arch is one the full run follows to rest (or to t_free): never a collapse
    assert set(full["status"][stopped].tolist()) <= {K.ST_REST, K.ST_MOVING}
    assert (fast["status"][stopped] == K.ST_STOPPED).all()
    assert (fast["n_impacts"][stopped] <= full["n_impacts"][stopped]).all()
    np.testing.assert_array_equal(fast["status"][~stopped], full["status"][~stopped])


def test_early_stop_never_under_a_law_that_adds_energy():
    """A literal c_v of 1 on both rates gains energy in one direction on an asymmetric arch:
    no stop is allowed (kernel.cannot_collapse checks every reachable impact)."""
    spans, thick, radii = ArchSampler(oppenheim_arch(), seed=9).draw(0, 40)
    pb = prepare_batch(spans, radii, thick, 2000.0, impact=ImpactSpec.fixed(1.0, literal=True))
    gains = (pb.c_l_to_r**2 * np.array([K.fast_coefficients(0.0, g)[0] for g in pb.geo_r])
             > np.array([K.fast_coefficients(0.0, g)[0] for g in pb.geo_l]))
    assert gains.any() and not gains.all()
    res = simulate_batch(pb, PULSE.build(), early_stop=True, t_free=5.0)
    assert not res["early_stopped"].any()


def test_cannot_collapse_energy_test():
    """Below the barrier of both mechanisms: True; above the smaller one: False."""
    arch = oppenheim_arch()
    pb = prepare_batch(arch.spans[None], arch.radii[None], arch.thicknesses[None], impact=0.8)
    geos = np.ascontiguousarray(pb.chain_geo[0])
    phus = pb.chain_unstable[0].copy()
    nexts = pb.chain_next[0] + 1
    ratios = pb.chain_ratio[0].copy()
    g = 9.81
    barrier = min(g * K.potential(phus[j], geos[j]) for j in range(2))
    m0 = K.fast_coefficients(0.0, geos[0])[0]
    w_at = (lambda e: np.sqrt(2 * e / m0))
    assert K.cannot_collapse(0, w_at(0.5 * barrier), 10.0, geos, phus, nexts, ratios, g)
    assert not K.cannot_collapse(0, w_at(1.01 * barrier), 10.0, geos, phus, nexts, ratios, g)
    # a small peak so far: the energy must also stay below the potential at that peak
    assert not K.cannot_collapse(0, w_at(0.5 * barrier), 1e-3, geos, phus, nexts, ratios, g)


def test_ensemble_early_stop_column_and_summary():
    kw = dict(samples=60, batch_size=30, seed=3, motion=PULSE, impact=ImpactSpec.fixed(0.8754))
    full = run_ensemble(EnsembleConfig.from_arch(oppenheim_arch(), **kw))
    cfg = EnsembleConfig.from_arch(oppenheim_arch(), early_stop=True, **kw)
    fast = run_ensemble(cfg)
    a, b = full.frame, fast.frame
    assert not a["early_stopped"].any() and b["early_stopped"].any()
    assert (b.loc[b["early_stopped"], "status"] == "stopped").all()
    assert a["collapsed"].equals(b["collapsed"]) and a["peak"].equals(b["peak"])
    sa, sb = full.summary(), fast.summary()
    assert sa["p_collapse"] == sb["p_collapse"]
    assert sa["response"]["peak_rad"] == sb["response"]["peak_rad"]
    assert sb["response"]["early_stopped"] == int(b["early_stopped"].sum())
    # impacts after the stop are unknown: the statistic leaves the stopped arches out
    assert sb["response"]["n_impacts"]["count"] == int((~b["early_stopped"]).sum())
    assert sb["outcomes"]["counts"]["integrated"] == sa["outcomes"]["counts"]["integrated"]
    # the flag is in the configuration only when set: other hashes are unchanged
    assert "early_stop" not in full.config.legacy_dict() and cfg.to_dict()["early_stop"] is True
    assert EnsembleConfig.from_dict(cfg.to_dict()) == cfg


@pytest.mark.slow
def test_no_numba_early_stop_is_the_compiled_one(without_numba):
    """The pure-Python kernel stops the same arches with the same outcome and peak."""
    script = textwrap.dedent("""
        import json
        from archrock.dynamics.batch import prepare_batch, simulate_batch
        from archrock.geometry import oppenheim_arch
        from archrock.groundmotion import PulseSpec
        from archrock.geometry.sampling import ArchSampler
        s, t, r = ArchSampler(oppenheim_arch(), seed=9).draw(0, 6)
        res = simulate_batch(prepare_batch(s, r, t, 2000.0, impact=0.8754),
                             PulseSpec("oppenheim", -1.0, 0.2).build(), early_stop=True)
        print(json.dumps({k: res[k].tolist() for k in ("status", "peak", "n_impacts")}))
    """)
    got = json.loads(without_numba("-c", script).strip().splitlines()[-1])
    s, t, r = ArchSampler(oppenheim_arch(), seed=9).draw(0, 6)
    res = simulate_batch(prepare_batch(s, r, t, 2000.0, impact=0.8754), PULSE.build(),
                         early_stop=True)
    assert got["status"] == res["status"].tolist() and K.ST_STOPPED in got["status"]
    assert got["n_impacts"] == res["n_impacts"].tolist()
    np.testing.assert_allclose(got["peak"], res["peak"], rtol=1e-12)


def test_degenerate_four_bar_is_reported_by_the_parallel_loop_too():
    """A division by zero inside prange (massless voussoirs) surfaces as the serial path's
    per-arch error, not as a SystemError or NaN models."""
    s, t, r = ArchSampler(oppenheim_arch(), seed=1).draw(0, 4)
    for parallel in (True, False):
        pb = prepare_batch(s, r, t, 0.0, impact=0.8, parallel=parallel)
        assert pb.error.tolist() == ["four-link model: degenerate four-bar (division by zero)"] * 4
