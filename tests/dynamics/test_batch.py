"""Batch preparation and the parallel response loop against the one-arch path (response.prepare /
response.respond)."""

import json
import textwrap

import numpy as np
import pytest

from archrock.dynamics.batch import (check_geometries, mechanism_label, prepare_batch,
                                     simulate_batch)
from archrock.errors import ArchInputError
from archrock.geometry import (Arch, oppenheim_arch, perturb_voussoirs, random_arch,
                               random_spans_thicknesses_radii)
from archrock.groundmotion import oppenheim_pulse
from archrock.dynamics.response import prepare, respond

CV = 0.8754
STATUS = {0: "rest", 1: "collapsed", 2: "moving"}


@pytest.fixture(scope="module")
def sample():
    nom = oppenheim_arch()
    u = np.random.default_rng(2).uniform(-1, 1, size=(12, 3, nom.n))
    spans, thick, radii = perturb_voussoirs(nom.spans, nom.thicknesses, nom.radii, u, 0.1, 0.1, 0.05)
    return nom, u, spans, thick, radii


def test_perturb_matches_random_spans_thicknesses_radii(sample):
    nom, u, spans, thick, radii = sample
    for b in (0, 5, 11):
        s, t, r = random_spans_thicknesses_radii(nom, u[b], 0.1, 0.1, 0.05)
        # a batch of draws vs one draw: numpy may reduce a 2-d array's rows in another order
        # than a 1-d one (SIMD by CPU), so the rescaled spans to rounding; the rest is exact
        np.testing.assert_allclose(spans[b], s, rtol=1e-14)
        np.testing.assert_array_equal(thick[b], t)
        np.testing.assert_array_equal(radii[b], r)
    np.testing.assert_allclose(spans.sum(axis=1), nom.embrace, rtol=1e-14)


def test_prepare_batch_equals_prepare(sample):
    nom, _, spans, thick, radii = sample
    pb = prepare_batch(spans, radii, thick, nom.density, impact="fixed", cv=CV)
    assert pb.ok.all()
    for b in range(4):
        m = prepare(Arch(spans[b], radii[b], thick[b]), CV)
        assert pb.k_l[b] == pytest.approx(m.k_l, abs=1e-13)
        assert pb.k_r[b] == pytest.approx(m.k_r, abs=1e-13)
        np.testing.assert_allclose(pb.geo_l[b], m.mech_l.geo, rtol=1e-13, atol=1e-12)
        np.testing.assert_allclose(pb.geo_r[b], m.mech_r.geo, rtol=1e-13, atol=1e-12)
        assert pb.phi_unstable_l[b] == pytest.approx(m.phi_unstable_l, abs=1e-12)
        assert pb.phi_unstable_r[b] == pytest.approx(m.phi_unstable_r, abs=1e-12)
        assert pb.phi_limit_l[b] == pytest.approx(m.phi_limit_l, abs=1e-12)
        assert pb.phi_limit_r[b] == pytest.approx(m.phi_limit_r, abs=1e-12)
        assert pb.v_rest[b] == pytest.approx(m.v_rest, rel=1e-10)
        assert pb.c_l_to_r[b] == pytest.approx(m.impact.l_to_r, rel=1e-12)
        assert pb.c_r_to_l[b] == pytest.approx(m.impact.r_to_l, rel=1e-12)
        # energy-consistent fixed c_v: kinetic energy x cv^2 in both directions
        assert m.impact.energy_l_to_r == pytest.approx(CV**2, rel=1e-12)
        assert pb.c_l_to_r[b] * pb.c_r_to_l[b] == pytest.approx(CV**2, rel=1e-12)
        hinges = "-".join(f"{h.joint}{h.edge[0]}" for h in m.limit.mechanism_l.hinges)
        assert pb.mech_l[b] == hinges


def test_nominal_arch_batch():
    nom = oppenheim_arch()
    pb = prepare_batch(nom.spans[None], nom.radii[None], nom.thicknesses[None], impact="paper")
    assert pb.k_l[0] == pytest.approx(0.3700, abs=5e-5)
    assert pb.k_r[0] == pytest.approx(0.3700, abs=5e-5)
    assert pb.c_l_to_r[0] == pytest.approx(0.8754, abs=5e-5)
    assert pb.mech_l[0] == "0i-3e-5i-7e" and pb.mech_r[0] == "0e-2i-4e-7i"
    assert mechanism_label(7, 0) == "0i-1i-2i-3i"


def test_simulate_batch_equals_respond(sample):
    nom, _, spans, thick, radii = sample
    motion = oppenheim_pulse(-1.0, 0.2)
    pb = prepare_batch(spans, radii, thick, impact="fixed", cv=CV)
    res = simulate_batch(pb, motion)
    serial = simulate_batch(pb, motion, parallel=False)
    for key in ("status", "peak", "n_impacts", "n_activations"):
        np.testing.assert_array_equal(res[key], serial[key])
    # exact coefficients instead of the spline tables: same outcomes, peaks to ~1e-9
    exact = simulate_batch(pb, motion, tabulate=False)
    np.testing.assert_array_equal(res["status"], exact["status"])
    np.testing.assert_allclose(res["peak"], exact["peak"], rtol=1e-7)
    assert not np.array_equal(res["peak"], exact["peak"])
    statuses = set()
    for b in range(8):
        r = respond(prepare(Arch(spans[b], radii[b], thick[b]), CV), motion)
        statuses.add(r.status)
        assert {0: "rest", 1: "collapsed", 2: "moving"}[int(res["status"][b])] == r.status
        assert res["peak"][b] == pytest.approx(r.peak, rel=1e-12)
        assert res["n_impacts"][b] == len(r.impacts)
        assert res["n_activations"][b] == sum(e.kind == "activation" for e in r.events)
        if r.collapsed:
            assert res["t_collapse"][b] == pytest.approx(r.t_collapse, rel=1e-9)
        else:
            assert np.isnan(res["t_collapse"][b])
    # the sample covers both outcomes, so the comparison checks both
    assert statuses == {"rest", "collapsed"}


def test_paper_impact_energy_gain_is_recorded_not_used():
    nom = oppenheim_arch()
    u = np.random.default_rng(3).uniform(-1, 1, size=(200, 3, nom.n))
    spans, thick, radii = perturb_voussoirs(nom.spans, nom.thicknesses, nom.radii, u, 0.1, 0.1, 0.05)
    pb = prepare_batch(spans, radii, thick, impact="paper")
    bad = ~pb.ok
    assert bad.sum() >= 1
    assert all("creates energy" in e for e in pb.error[bad])
    assert np.all(np.isnan(pb.c_l_to_r[bad]))
    res = simulate_batch(pb, oppenheim_pulse(-1.0, 0.2))
    assert np.all(res["status"][bad] == -1)
    assert np.all(np.isnan(res["peak"][bad]))
    # the usable ones never gain energy (the energy ratios multiply to (c_lr c_rl)^2) and are
    # the one-arch laws
    assert np.all(pb.c_l_to_r[~bad] * pb.c_r_to_l[~bad] <= 1 + 1e-9)
    for b in np.flatnonzero(~bad)[:3]:
        law = prepare(Arch(spans[b], radii[b], thick[b]), "paper").impact
        assert pb.c_l_to_r[b] == pytest.approx(law.l_to_r, rel=1e-12)
        assert pb.c_r_to_l[b] == pytest.approx(law.r_to_l, rel=1e-12)
        assert max(law.energy_l_to_r, law.energy_r_to_l) <= 1 + 1e-9


def test_invalid_geometry_is_reported():
    nom = oppenheim_arch()
    spans = np.tile(nom.spans, (2, 1))
    radii = np.tile(nom.radii, (2, 1))
    thick = np.tile(nom.thicknesses, (2, 1))
    radii[1, 3] += 3.0  # voussoir 3 no longer overlaps its neighbours
    err = check_geometries(spans, radii, thick)
    assert err[0] == "" and "overlap" in err[1]
    pb = prepare_batch(spans, radii, thick, impact="fixed", cv=CV)
    assert pb.ok.tolist() == [True, False]
    assert np.isnan(pb.k_l[1])


def test_bad_impact_options():
    nom = oppenheim_arch()
    with pytest.raises(ArchInputError, match="cv"):
        prepare_batch(nom.spans[None], nom.radii[None], nom.thicknesses[None], impact="fixed", cv=1.5)
    with pytest.raises(ArchInputError, match="impact"):
        prepare_batch(nom.spans[None], nom.radii[None], nom.thicknesses[None], impact="elastic")


def test_event_table_overflow_keeps_the_outcome(sample):
    # more events than the table holds: status, peak, times and the counts of impacts and
    # activations are still those of the full integration (counted as they happen)
    nom, _, spans, thick, radii = sample
    motion = oppenheim_pulse(-1.0, 0.2)
    pb = prepare_batch(spans, radii, thick, impact="fixed", cv=CV)
    full = simulate_batch(pb, motion)
    assert not full["events_truncated"].any()
    small = simulate_batch(pb, motion, max_events=8)
    over = small["events_truncated"]
    assert over.any() and not over.all()
    for key in ("status", "peak", "t_collapse", "t_unstable"):
        np.testing.assert_array_equal(small[key], full[key])
    assert set(small["status"][over]) <= {0, 1, 2}
    for key in ("n_impacts", "n_activations"):
        np.testing.assert_array_equal(small[key], full[key])
    assert (small["n_impacts"][over] + small["n_activations"][over] > 8).all()
    serial = simulate_batch(pb, motion, max_events=8, parallel=False)
    np.testing.assert_array_equal(serial["events_truncated"], over)


# ------------------------------------------------------------------------- chains of mechanisms
@pytest.fixture(scope="module")
def ten_arches():
    arches = [random_arch(seed=s) for s in range(10)]
    return arches, [np.array([getattr(a, k) for a in arches]) for k in ("spans", "radii", "thicknesses")]


def test_two_row_chain_arrays(sample):
    nom, _, spans, thick, radii = sample
    pb = prepare_batch(spans, radii, thick, impact="fixed", cv=CV)
    assert pb.chain_geo.shape == (len(pb), 2, pb.geo_l.shape[1])
    assert np.all(pb.n_mechanisms == 2)
    np.testing.assert_array_equal(pb.chain_geo[:, 1], pb.geo_r)
    np.testing.assert_array_equal(pb.chain_ratio, np.column_stack([pb.c_l_to_r, pb.c_r_to_l]))
    np.testing.assert_array_equal(pb.chain_next, [[1, 0]] * len(pb))


def test_least_loss_batch_equals_respond(ten_arches):
    """The batch runs each arch's least-loss chain exactly as respond(prepare(arch, 'least-loss'))
    does: same outcomes, peaks, collapse times and impact counts."""
    arches, (spans, radii, thick) = ten_arches
    pb = prepare_batch(spans, radii, thick, arches[0].density, impact="least-loss")
    assert pb.ok.all()
    assert set(pb.n_mechanisms.tolist()) <= {3, 4} and pb.chain_geo.shape[1] == 4
    models = [prepare(arch, "least-loss") for arch in arches]
    for b, model in enumerate(models):
        assert pb.mech_l[b] == model.labels[0] and pb.mech_r[b] == model.labels[1]
        assert pb.n_mechanisms[b] == len(model.chain[0])
    statuses = set()
    # the paper's pulse (all recover) and a longer one (collapses after an impact too)
    for motion in (oppenheim_pulse(-1.0, 0.2), oppenheim_pulse(-1.0, 0.4)):
        res = simulate_batch(pb, motion)
        for b, model in enumerate(models):
            r = respond(model, motion)
            statuses.add((r.status, min(len(r.impacts), 1)))
            assert STATUS[int(res["status"][b])] == r.status
            assert res["peak"][b] == pytest.approx(r.peak, abs=1e-9)
            assert res["n_impacts"][b] == len(r.impacts)
            if r.collapsed:
                assert res["t_collapse"][b] == pytest.approx(r.t_collapse, abs=1e-9)
            else:
                assert np.isnan(res["t_collapse"][b])
    # recoveries, collapses before any impact and collapses in a mechanism opened by an impact
    assert statuses == {("rest", 1), ("collapsed", 0), ("collapsed", 1)}


def test_batch_without_numba_agrees(ten_arches, without_numba):
    """ARCHROCK_NO_NUMBA=1 runs the pure-Python loop over the same chains: the same numbers."""
    script = textwrap.dedent("""
        import json, numpy as np
        from archrock.dynamics.batch import prepare_batch, simulate_batch
        from archrock.geometry import random_arch
        from archrock.groundmotion import oppenheim_pulse
        arches = [random_arch(seed=s) for s in (0, 4, 1)]
        args = [np.array([getattr(a, k) for a in arches]) for k in ("spans", "radii", "thicknesses")]
        out = {}
        for imp in ("least-loss", "fixed"):
            pb = prepare_batch(*args, arches[0].density, impact=imp,
                               cv=0.8754 if imp == "fixed" else None)
            r = simulate_batch(pb, oppenheim_pulse(-1.0, 0.4))
            out[imp] = {k: np.asarray(r[k]).tolist() for k in ("status", "peak", "n_impacts")}
        print(json.dumps(out))
    """)
    pure = json.loads(without_numba("-c", script))
    arches, _ = ten_arches
    sel = [0, 4, 1]
    args = [np.array([getattr(arches[s], k) for s in sel]) for k in ("spans", "radii", "thicknesses")]
    for imp in ("least-loss", "fixed"):
        pb = prepare_batch(*args, arches[0].density, impact=imp,
                           cv=0.8754 if imp == "fixed" else None)
        r = simulate_batch(pb, oppenheim_pulse(-1.0, 0.4))
        assert pure[imp]["status"] == r["status"].tolist()
        assert pure[imp]["n_impacts"] == r["n_impacts"].tolist()
        np.testing.assert_allclose(pure[imp]["peak"], r["peak"], rtol=1e-12)
    assert pure["least-loss"]["status"] == [1, 1, 0]


def test_mechanism_label_is_the_mechanism_label():
    from archrock.statics.limit import _mechanism_from_candidate

    for c in (0, 17, 400, 1000):
        assert mechanism_label(7, c) == _mechanism_from_candidate(7, c, "r", 0.3).label


def test_default_fallback_rows_get_the_momentum_law():
    """A spec with the default's fallback: a row the paper model refuses gets the momentum law
    of that arch (the one-arch path's, note included) and is integrated; the others keep the
    paper law; "paper" by name still records the refusal as the row's error."""
    from archrock.geometry import nominal_arch
    from archrock.dynamics.impact import PAPER_PRACTICE, ImpactSpec

    # a 17-voussoir semicircle that stands; the paper model creates energy on the first
    arches = [nominal_arch(radius=5.0, embrace_deg=180.0, thickness=t, voussoirs=17)
              for t in (0.9, 1.0)]
    pb = prepare_batch(arches, impact=ImpactSpec("paper", fallback="momentum"))
    assert pb.ok.all()
    one = [prepare(a).impact for a in arches]          # the default, arch by arch
    assert one[0].model == "momentum" and one[1].model == "paper"
    assert pb.impact_fallback.tolist() == [one[0].fallback, ""]
    for b, law in enumerate(one):
        # the compiled batch laws agree with impact_law to rounding (test above: 1e-12)
        assert pb.c_l_to_r[b] == pytest.approx(law.l_to_r, rel=1e-12)
        assert pb.c_r_to_l[b] == pytest.approx(law.r_to_l, rel=1e-12)
    res = simulate_batch(pb, oppenheim_pulse(-0.5, 0.2))
    assert np.all(res["status"] >= 0)
    strict = prepare_batch(arches, impact="paper")
    assert strict.ok.tolist() == [False, True] and "creates energy" in strict.error[0]
    assert strict.impact_fallback.tolist() == ["", ""]
    # the default around such a nominal arch: its momentum c_v on every row, each row saying so
    pn = prepare_batch(arches, impact=PAPER_PRACTICE, nominal=arches[0])
    note = PAPER_PRACTICE.resolved(arches[0]).note
    assert note and pn.impact_fallback.tolist() == [note, note]


def test_no_fallback_rows_where_paper_can_be_used(sample):
    nom, u, spans, thick, radii = sample
    from archrock.dynamics.impact import PAPER_PRACTICE

    pb = prepare_batch(spans, radii, thick, impact=PAPER_PRACTICE, nominal=nom)
    assert pb.ok.all() and set(pb.impact_fallback.tolist()) == {""}
    paper = prepare_batch(spans, radii, thick, impact="paper")
    with_fb = prepare_batch(spans, radii, thick, impact=dict(model="paper", fallback="momentum"))
    # the fallback touches no row the paper model can take: the same arrays, bit for bit
    assert np.array_equal(paper.c_l_to_r, with_fb.c_l_to_r)
    assert np.array_equal(paper.c_r_to_l, with_fb.c_r_to_l)
