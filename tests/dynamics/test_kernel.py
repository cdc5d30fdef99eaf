"""The compiled RK4 step and its event location (archrock.dynamics.kernel): the spline-table step against
the exact one, its exact fallback outside the tables, and the located events against a dense
independent solve."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from archrock import geometry
from archrock.dynamics import kernel as K
from archrock.dynamics.fourlink import GEO_SIZE, exact_acceleration, table_acceleration
from archrock.dynamics.response import prepare

G = 9.81


@pytest.fixture(scope="module")
def model():
    return prepare(geometry.oppenheim_arch(), "paper")


@pytest.fixture(scope="module")
def irregular():
    from archrock.studies.ida import random_models

    return random_models(geometry.nominal_arch(), 1, 3)[0]


def _table(model, row=0):
    # the kernel builds missing table intervals in place: it takes writable arrays
    return np.array(model.tables[row])


def _motion(a):
    """A constant ground acceleration a [m/s^2] on one long segment."""
    return np.array([0.0, 100.0]), np.array([a, a])


@pytest.mark.parametrize("row", [0, 1])
def test_table_acceleration_matches_exact(model, irregular, row):
    """The splines of M, L/M, F/M, P/M give phi'' to a relative 1e-8 of the loop closure over
    the whole range of motion (it was ~6e-9 for splines of M, L, F, P and a division)."""
    for m in (model, irregular):
        fl = m.chain[0][row]
        tab = _table(m, row)
        lim = m.chain[1][row]
        worst = 0.0
        for phi in np.linspace(0.0, lim, 301):
            for w in (0.0, 0.7, 2.0):
                for a in (-0.4 * G, 0.0, 0.4 * G):
                    ex = exact_acceleration(phi, w, a, G, fl.geo)
                    worst = max(worst, abs(table_acceleration(phi, w, a, G, tab) - ex) / G)
        assert 1e-13 < worst < 1e-8  # a table, not the exact function, and a good one


def test_table_acceleration_is_nan_outside_the_tables(model):
    fl = model.chain[0][0]
    tab = _table(model)
    start = tab[GEO_SIZE]
    top = start + tab[GEO_SIZE + 1] * tab[GEO_SIZE + 2]
    for phi in (start - 1e-6, top + 1e-6, math.nan):
        assert math.isnan(table_acceleration(phi, 0.3, 1.0, G, tab))
    assert math.isnan(table_acceleration(0.01, 0.3, 1.0, G, np.asarray(fl.geo)))
    assert not math.isnan(table_acceleration(start + 1e-9, 0.3, 1.0, G, tab))


def test_rk4_step_from_tables_and_exact(model):
    """Inside the tables the step is the table step, close to the exact one; a geo without
    tables gives the exact step; a step whose stages leave the tables is exact in those
    stages only."""
    fl = model.chain[0][0]
    tab = _table(model)
    geo = np.array(fl.geo)
    times, accel = _motion(-0.3 * G)
    step = (0.0, 2e-3, 0, times, accel)
    inside = K._rk4(0.05, 0.4, *step, tab, G)
    assert inside == K._rk4_table(0.05, 0.4, *step, tab, G)
    exact = K._rk4(0.05, 0.4, *step, geo, G)
    assert exact == K._rk4_fill(0.05, 0.4, *step, geo, G)
    assert math.isnan(K._rk4_table(0.05, 0.4, *step, geo, G)[0])
    assert inside != exact and np.allclose(inside, exact, rtol=0, atol=1e-12)
    # just above the table's start, moving down: the later stages are outside
    start = tab[GEO_SIZE]
    phi0 = start + 1e-7
    below = K._rk4(phi0, -1.0, *step, tab, G)
    assert math.isnan(K._rk4_table(phi0, -1.0, *step, tab, G)[0])
    assert below != K._rk4(phi0, -1.0, *step, geo, G)
    assert np.allclose(below, K._rk4(phi0, -1.0, *step, geo, G), rtol=0, atol=1e-12)


def test_lazy_tables_equal_built_tables(model, irregular):
    """A table built interval by interval as the motion reaches it (what the ensemble kernel
    does) holds the very numbers of the table built whole, whatever the order."""
    from archrock.dynamics.fourlink import build_interval, empty_table, table_range

    for m in (model, irregular):
        for row, (fl, lim) in enumerate(zip(m.chain[0], m.chain[1])):
            whole = _table(m, row)
            start, top = table_range(fl.geo, lim, fl.phi_dead)
            lazy = empty_table(np.asarray(fl.geo), start, top, 600)
            assert lazy.size == whole.size
            order = np.random.default_rng(row).permutation(600)
            for i in order[:300]:
                build_interval(lazy, int(i))
            base = GEO_SIZE + 4
            for i in order[:300]:
                assert np.array_equal(lazy[base + 16 * i:base + 16 * (i + 1)],
                                      whole[base + 16 * i:base + 16 * (i + 1)])
            assert np.isnan(lazy[base + 16 * order[300]])
            # a response on the lazy table is the response on the whole one
            times, accel = _motion(-0.45 * G)
            for phi, w in ((0.0, 0.3), (0.08, -0.5), (lim * 0.9, 0.2)):
                assert K._rk4(phi, w, 0.0, 2e-3, 0, times, accel, lazy, G) == \
                    K._rk4(phi, w, 0.0, 2e-3, 0, times, accel, whole, G)


def test_hermite_root_of_a_known_cubic():
    """The Hermite interpolant of a cubic is the cubic: phi(t) = t - t^3 over a step of 0.8
    (phi 0 -> 0.288, rate 1 -> -0.92) crosses 0.2 where t - t^3 = 0.2."""
    s = K._hermite_root(0.8, 0.0, 1.0, 0.288, -0.92, 0.2)
    t = 0.8 * s
    assert t - t**3 == pytest.approx(0.2, abs=1e-14)
    assert 0.2 < t < 0.21
    # the root at the end of the step, to the rounding of the cubic's evaluation
    assert K._hermite_root(0.8, 0.0, 1.0, 0.288, -0.92, 0.288) == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("target,phi0,w0,a", [
    (0.0, 0.001, -0.9, -0.3 * G),   # an impact: phi returns to 0
    (0.119, 0.118, 0.8, -0.45 * G),  # an upward passage (phi_u or the limit)
    (0.0, 0.0, 0.001, 0.5 * G),      # from phi = 0 itself: a short arc that closes in the step
])
def test_locate_lands_on_the_target(model, target, phi0, w0, a):
    """The located step ends on the target (1e-15 rad or a 1e-13 s bracket), is an RK4 step of
    its length, and its time agrees with a dense independent solve of the exact equation."""
    tab = _table(model)
    fl = model.chain[0][0]
    times, accel = _motion(a)
    h = 2e-3 if phi0 > 0 else 1e-2
    p1, w1 = K._rk4(phi0, w0, 0.0, h, 0, times, accel, tab, G)
    assert (p1 - target) * (phi0 - target) < 0 or (phi0 == target and p1 < target)
    hc, p, q = K._locate(phi0, w0, 0.0, h, 0, times, accel, tab, G, target, phi0 <= target,
                         p1, w1)
    assert 0.0 < hc <= h
    assert (p, q) == K._rk4(phi0, w0, 0.0, hc, 0, times, accel, tab, G)
    assert abs(p - target) < 1e-13

    def rhs(t, y):
        return [y[1], exact_acceleration(y[0], y[1], a, G, fl.geo)]

    def cross(t, y):
        return y[0] - target
    sol = solve_ivp(rhs, (0.0, h), [phi0, w0], method="DOP853", rtol=1e-12, atol=1e-14,
                    events=cross)
    t_cross = sol.t_events[0][sol.t_events[0] > 1e-9]
    assert t_cross.size == 1
    assert hc == pytest.approx(t_cross[0], abs=1e-11)


@pytest.mark.parametrize("n", [3, 0, -1, 2.5, True, "600"])
def test_table_intervals_refused_by_name(model, n):
    """Tables need at least four intervals (five knots for the end slopes): fewer, or a
    non-integer, is refused naming the field, at every entry point."""
    from archrock.dynamics.batch import prepare_batch, simulate_batch
    from archrock.errors import ArchInputError
    from archrock.groundmotion import oppenheim_pulse
    from archrock.dynamics.sweep import SweepArches

    with pytest.raises(ArchInputError, match=r"n_intervals: .*allowed an integer >= 4"):
        model.chain[0][0].tabulated(0.1, n)
    arch = geometry.oppenheim_arch()
    pb = prepare_batch([arch], impact="momentum")
    with pytest.raises(ArchInputError, match=r"table_intervals: .*allowed an integer >= 4"):
        simulate_batch(pb, oppenheim_pulse(-1.0, 0.2), table_intervals=n)
    with pytest.raises(ArchInputError, match=r"table_intervals: .*allowed an integer >= 4"):
        SweepArches.from_batch(pb, table_intervals=n)


def test_table_error_falls_as_the_fourth_power_of_the_interval(model):
    """The table's largest error in phi'' falls as h^4 (cubic Hermite with fourth-order slopes):
    the fitted order from 40 to 320 intervals is 4.2; the least allowed table (4 intervals)
    still gives finite values."""
    fl = model.chain[0][0]
    lim = model.chain[1][0]
    phis = np.linspace(0.0, lim, 401)
    exact = np.array([exact_acceleration(p, 0.3, -2.0, G, fl.geo) for p in phis])
    errs = []
    for n in (4, 40, 320):
        tab = np.array(fl.tabulated(lim, n))
        approx = np.array([table_acceleration(p, 0.3, -2.0, G, tab) for p in phis])
        errs.append(np.max(np.abs(approx - exact)))
    assert np.all(np.isfinite(errs))
    order = math.log(errs[1] / errs[2]) / math.log(8.0)
    assert 3.7 < order < 4.7


def test_event_table_grows_and_counts_past_max_events(model):
    """The paper's case has 98 events, past the table's first EVENT_ROWS: the table grows and
    keeps every one; with a smaller max_events the run is the same, the table keeps the first
    max_events rows and the count goes on."""
    from archrock.groundmotion import oppenheim_pulse
    from archrock.dynamics.response import respond

    m = oppenheim_pulse(-1.0, 0.2)
    args = model._kernel_chain(True) + (model.k_l, model.k_r, model.v_rest, m.times, m.accel,
                                        G, 601, 0.005, 2e-3, 60.0)
    out, ev, n, st, tf, pk, *_ = K.simulate_chain(*args, 100_000)
    assert n > K.EVENT_ROWS and ev.shape[0] >= n
    assert np.count_nonzero(ev[:n, 0] == K.EV_IMPACT) == len(respond(model, m).impacts) == 96
    out2, ev2, n2, st2, tf2, pk2, *_ = K.simulate_chain(*args, 10)
    assert n2 == n and st2 == st and ev2.shape[0] == 10
    np.testing.assert_array_equal(ev2, ev[:10])
    np.testing.assert_array_equal(out2, out)
    assert tf2 == tf and pk2 == pk  # the same code path on the same machine
