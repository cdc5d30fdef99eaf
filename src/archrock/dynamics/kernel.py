"""Fast integrator of the rocking arch: fixed-step RK4 with event location, compiled by numba.

One function, :func:`simulate`, runs the whole response: rest, activation by the paper's
eq. (1), motion in M_l or M_r, impacts at phi = 0 with a rate ratio per direction, rest again,
collapse.  The collapse time is physical: the last upward passage of the open mechanism's
unstable position phi_u (F = 0) before the rotation limit, after which phi never comes back
below phi_u; the limit (well past phi_u) is only where the integration stops (t_limit).  The ground motion is piecewise linear (steps encoded by
repeated times); steps never straddle a sample time, so the forcing is smooth inside a step.
The state machine mirrors the reference integrator in :mod:`archrock.dynamics.response`, which uses
scipy's adaptive solver instead.
"""

from __future__ import annotations

import math

import numpy as np

from .._device import device_override
from .._jit import maybe_njit
from .fourbar import potential
from .tables import fast_coefficients, filling_acceleration, table_acceleration

# event kinds (column 0 of the event table)
# EV_COLLAPSE: the last upward passage of phi_u before the limit; EV_LIMIT: the limit reached
# (the end of the run); EV_UNSTABLE: the first passage of phi_u
EV_ACTIVATION, EV_IMPACT, EV_REST, EV_COLLAPSE, EV_UNSTABLE, EV_LIMIT = 1, 2, 3, 4, 5, 6
# status codes; ST_STOPPED: early stop (simulate_chain_stop), the arch can no longer collapse
ST_REST, ST_COLLAPSED, ST_MOVING, ST_STOPPED = 0, 1, 2, 3
#: early stop: the energy must be below every barrier by this fraction (integration error of the
#: energy, table coefficients; one impact of the paper's law removes about a quarter)
STOP_MARGIN = 1e-2
#: step multiplier in the free motion after the ground motion
FREE_STEP_FACTOR = 4.0
#: rows of the event table a run starts with (doubled as needed, up to ``max_events``)
EVENT_ROWS = 64


@maybe_njit
def _accel(t, i, times, accel):
    """Ground acceleration at t inside segment i (times[i] <= t <= times[i+1])."""
    if i >= times.size - 1:
        return 0.0
    t0, t1 = times[i], times[i + 1]
    if t1 <= t0:
        return accel[i + 1]
    return accel[i] + (accel[i + 1] - accel[i]) * (t - t0) / (t1 - t0)


def _rk4_with(acceleration):
    """The RK4 step with ``acceleration(phi, rate, a, g, geo)`` as phi''."""
    @maybe_njit
    def step(phi, w, t, h, i, times, accel, geo, g):
        # the step lies inside segment i, where the ground acceleration is linear in t
        if i >= times.size - 1:
            a0 = am = a1 = 0.0
        else:
            t0, t1 = times[i], times[i + 1]
            if t1 <= t0:
                a0 = am = a1 = accel[i + 1]
            else:
                slope = (accel[i + 1] - accel[i]) / (t1 - t0)
                a0 = accel[i] + slope * (t - t0)
                am = accel[i] + slope * (t + 0.5 * h - t0)
                a1 = accel[i] + slope * (t + h - t0)
        k1w = acceleration(phi, w, a0, g, geo)
        k2p = w + 0.5 * h * k1w
        k2w = acceleration(phi + 0.5 * h * w, k2p, am, g, geo)
        k3p = w + 0.5 * h * k2w
        k3w = acceleration(phi + 0.5 * h * k2p, k3p, am, g, geo)
        k4p = w + h * k3w
        k4w = acceleration(phi + h * k3p, k4p, a1, g, geo)
        return (phi + h / 6.0 * (w + 2 * k2p + 2 * k3p + k4p),
                w + h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w))
    return step


_rk4_table = _rk4_with(table_acceleration)
_rk4_fill = _rk4_with(filling_acceleration)


@maybe_njit
def _rk4(phi, w, t, h, i, times, accel, geo, g):
    """One RK4 step of length h from t in segment i: (phi, phi') at t + h, from the tables
    (``FourLink.tabulated``, about 7x cheaper than the loop closure).  A stage outside the built
    intervals gives NaN, which propagates to the result: the step is then redone building the
    intervals it needs (``geo`` is written), exactly where it leaves the tables."""
    p1, w1 = _rk4_table(phi, w, t, h, i, times, accel, geo, g)
    if p1 != p1 or w1 != w1:
        p1, w1 = _rk4_fill(phi, w, t, h, i, times, accel, geo, g)
    return p1, w1


@maybe_njit
def _hermite_root(h, phi0, w0, phi1, w1, target):
    """s in [0, 1] where the cubic Hermite interpolant of a step of length h from (phi0, w0) to
    (phi1, w1) crosses ``target`` (phi0 - target and phi1 - target of opposite signs):
    safeguarded Newton on the cubic, no evaluation of the equation of motion."""
    a = 2.0 * (phi0 - phi1) + h * (w0 + w1)
    b = 3.0 * (phi1 - phi0) - h * (2.0 * w0 + w1)
    c = h * w0
    f0 = phi0 - target
    f1 = phi1 - target
    if f1 == 0.0:
        return 1.0
    lo, hi, f_lo = 0.0, 1.0, f0
    s = f0 / (f0 - f1)
    for _ in range(40):
        v = ((a * s + b) * s + c) * s + f0
        if v == 0.0:
            return s
        if (v > 0.0) == (f_lo > 0.0):
            lo, f_lo = s, v
        else:
            hi = s
        d = (3.0 * a * s + 2.0 * b) * s + c
        sn = s - v / d if d != 0.0 else -1.0
        if not (lo <= sn <= hi):
            sn = 0.5 * (lo + hi)
        if abs(sn - s) < 1e-15:
            return sn
        s = sn
    return s


@maybe_njit
def _locate(phi, w, t, hmax, i, times, accel, geo, g, target, from_zero, p_max, w_max):
    """The RK4 step that ends on phi = target: (h, phi, phi') at the step length h in
    (0, hmax] where it does, from the step (phi, w) -> (p_max, w_max) of length hmax that
    crossed it.

    Newton on h -> RK4(h) (its derivative is the step's end rate to O(h^4)) from the root of
    the step's cubic Hermite interpolant, kept inside a bracket that every evaluation narrows:
    about 3.5 RK4 evaluations per event instead of the 8 of regula falsi.  Stops as that did: |phi - target| < 1e-15 rad or a bracket narrower than 1e-13 s.  With ``from_zero``
    the step starts on the target itself (just after an impact), so the lower end of the
    bracket is first moved off zero by halving.
    """
    lo, hi = 0.0, hmax
    f_lo = phi - target
    f_hi = p_max - target
    if from_zero:
        h = hmax
        found = False
        for _ in range(60):
            h *= 0.5
            fh = _rk4(phi, w, t, h, i, times, accel, geo, g)[0] - target
            if (fh > 0) != (f_hi > 0):
                lo, f_lo = h, fh
                found = True
                break
            hi, f_hi = h, fh
        if not found:
            return 0.0, phi, w
        h = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
    else:
        h = hmax * _hermite_root(hmax, phi, w, p_max, w_max, target)
    p, q = phi, w
    for _ in range(100):
        p, q = _rk4(phi, w, t, h, i, times, accel, geo, g)
        fh = p - target
        if (fh > 0) == (f_hi > 0):
            hi, f_hi = h, fh
        else:
            lo, f_lo = h, fh
        if abs(fh) < 1e-15 or hi - lo < 1e-13:
            break
        hn = h - fh / q if q != 0.0 else -1.0
        if not (lo < hn < hi):
            hn = 0.5 * (lo + hi)
        h = hn
    return h, p, q


@maybe_njit
def _fill(out, dt_out, t0, t1, phi0, w0, phi1, w1, sign, start):
    """Write output samples with t0 <= k dt_out < t1 by cubic Hermite interpolation."""
    k = start
    h = t1 - t0
    while k < out.size and k * dt_out < t1:
        s = (k * dt_out - t0) / h if h > 0 else 0.0
        h00 = 2 * s**3 - 3 * s**2 + 1
        h10 = s**3 - 2 * s**2 + s
        h01 = -2 * s**3 + 3 * s**2
        h11 = s**3 - s**2
        out[k] = sign * (h00 * phi0 + h10 * h * w0 + h01 * phi1 + h11 * h * w1)
        k += 1
    return k


@maybe_njit
def _hermite_max(h, phi0, w0, phi1, w1):
    """Maximum of the cubic Hermite interpolant over a step where the rate turns from + to -."""
    a = 2.0 * (phi0 - phi1) + h * (w0 + w1)
    b = 3.0 * (phi1 - phi0) - h * (2.0 * w0 + w1)
    c = h * w0
    best = max(phi0, phi1)
    # p'(s) = 3 a s^2 + 2 b s + c
    if abs(a) < 1e-300:
        roots = (-c / (2.0 * b) if b != 0.0 else -1.0, -1.0)
    else:
        disc = b * b - 3.0 * a * c
        if disc < 0.0:
            return best
        sq = math.sqrt(disc)
        roots = ((-b + sq) / (3.0 * a), (-b - sq) / (3.0 * a))
    for s in roots:
        if 0.0 < s < 1.0:
            best = max(best, ((a * s + b) * s + c) * s + phi0)
    return best


@maybe_njit
def _fill_value(out, dt_out, t1, value, start):
    k = start
    while k < out.size and k * dt_out < t1:
        out[k] = value
        k += 1
    return k


@maybe_njit
def _add_event(ev, n_ev, max_events, kind, t, mode_before, mode_after, rate_before, rate_after):
    """Write event ``n_ev`` into the table ``ev``, doubled when full up to ``max_events`` rows
    (an event past those is only counted).  Returns (table, count)."""
    if n_ev >= ev.shape[0] and ev.shape[0] < max_events:
        bigger = np.zeros((min(2 * ev.shape[0], max_events), 6))
        bigger[:n_ev] = ev[:n_ev]
        ev = bigger
    _write_event(ev, n_ev, kind, t, mode_before, mode_after, rate_before, rate_after)
    return ev, n_ev + 1


@maybe_njit
def _write_event(ev, n_ev, kind, t, mode_before, mode_after, rate_before, rate_after):
    """Row ``n_ev`` of the event table, where the table has it (an event past it is only
    counted by the caller)."""
    if n_ev < ev.shape[0]:
        ev[n_ev, 0] = kind
        ev[n_ev, 1] = t
        ev[n_ev, 2] = mode_before
        ev[n_ev, 3] = mode_after
        ev[n_ev, 4] = rate_before
        ev[n_ev, 5] = rate_after


@maybe_njit
def simulate(geo_l, geo_r, k_l, k_r, c_lr, c_rl, lim_l, lim_r, phu_l, phu_r, v_rest,
             times, accel, g, n_out, dt_out, dt, t_free, max_events):
    """Run one response with the two limit mechanisms.  Modes: 0 rest, 1 M_l open, 2 M_r open.

    Returns (out, events, n_events, status, t_final, peak, t_collapse, t_unstable):
    out[k] = signed response at k dt_out (+phi in M_l, -phi in M_r, NaN once the rotation limit
    is reached); t_collapse [s]: the last upward passage of phi_u before the limit (-1 if no
    collapse); t_unstable [s]: the first passage of phi_u (-1 if never); after a collapse
    t_final is when the limit was reached;
    events rows (kind, time, mode before, mode after, rate before, rate after);
    status 0 at rest, 1 collapsed, 2 still moving at t_motion_end + t_free.
    """
    size = max(geo_l.size, geo_r.size)
    geos = np.zeros((2, size))
    geos[0, :geo_l.size] = geo_l
    geos[1, :geo_r.size] = geo_r
    return simulate_chain(geos, np.array([lim_l, lim_r]), np.array([phu_l, phu_r]),
                          np.array([1.0, -1.0]), np.array([2, 1]), np.array([c_lr, c_rl]),
                          k_l, k_r, v_rest, times, accel, g, n_out, dt_out, dt, t_free,
                          max_events)


@maybe_njit
def simulate_chain(geos, lims, phus, dirs, nexts, ratios, k_l, k_r, v_rest, times, accel, g,
                   n_out, dt_out, dt, t_free, max_events):
    """Run one response over a chain of mechanisms.  Mode m >= 1 is row m - 1 of ``geos``;
    rows 0 and 1 are the limit mechanisms M_l and M_r that open from rest (paper eq. 1).
    dirs: +1 for a mechanism of direction l, -1 for r (the sign of the response); closing
    mode m opens mode nexts[m - 1] with rate ratio ratios[m - 1].  Returns as :func:`simulate`.
    """
    return simulate_chain_stop(geos, lims, phus, dirs, nexts, ratios, k_l, k_r, v_rest, times,
                               accel, g, n_out, dt_out, dt, t_free, max_events, False)


@maybe_njit
def cannot_collapse(row, w, peak, geos, phus, nexts, ratios, g):
    """Whether an arch just out of an impact into chain row ``row`` at rate ``w`` [rad/s], with
    no ground motion left, can neither collapse nor exceed ``peak`` [rad] any more.

    Free motion conserves E = M phi'^2 / 2 + g V(phi) between impacts, and an impact from row j
    into row k multiplies the kinetic energy at phi = 0 by e_j = c_j^2 M_k(0) / M_j(0).  If
    every impact the arch can meet (rows reachable from ``row`` by ``nexts``) has e_j <= 1, the
    energy never grows; then in every such row j the rotation stays below the phi at which
    g V_j(phi) = E, and V_j increases on [0, phi_u,j] (F > 0 below the unstable position).
    So E < (1 - STOP_MARGIN) g V_j(min(peak, phi_u,j)) for all of them means no passage of
    any phi_u (no collapse) and no new peak.  An impact law that can add energy (e_j > 1, e.g.
    the 'paper' model on some arches, a literal c_v) never allows the stop."""
    R = phus.size
    energy = 0.5 * fast_coefficients(0.0, geos[row])[0] * w * w
    j = row
    for _ in range(R):
        k = nexts[j] - 1
        m_j = fast_coefficients(0.0, geos[j])[0]
        m_k = fast_coefficients(0.0, geos[k])[0]
        if ratios[j] * ratios[j] * m_k > m_j:  # e_j > 1: this impact can add energy
            return False
        top = phus[j] if phus[j] < peak else peak
        if not energy < (1.0 - STOP_MARGIN) * g * potential(top, geos[j]):
            return False
        j = k
    return True


@maybe_njit
def simulate_chain_stop(geos, lims, phus, dirs, nexts, ratios, k_l, k_r, v_rest, times, accel,
                        g, n_out, dt_out, dt, t_free, max_events, early_stop):
    """:func:`simulate_chain`, and with ``early_stop`` the run ends with status
    :data:`ST_STOPPED` at the first impact after the ground motion from which the arch
    :func:`cannot_collapse`: its outcome (no collapse) and peak are final, its impacts and
    time to rest are not followed."""
    out = np.zeros(n_out)
    # a table of max_events rows zeroed up front cost as much as a short response
    ev = np.zeros((min(max_events, EVENT_ROWS), 6))
    ev, n_ev, status, t, peak, t_collapse, t_unstable, _, _ = run_chain(
        out, ev, geos, lims, phus, dirs, nexts, ratios, k_l, k_r, v_rest, times, accel, g,
        dt_out, dt, t_free, max_events, early_stop)
    return out, ev, n_ev, status, t, peak, t_collapse, t_unstable


@device_override(_add_event)
def _add_event_fixed(ev, n_ev, max_events, kind, t, mode_before, mode_after, rate_before,
                     rate_after):
    """:func:`_add_event` into a table that never grows (a GPU thread cannot allocate): rows
    past its size are only counted."""
    _write_event(ev, n_ev, kind, t, mode_before, mode_after, rate_before, rate_after)
    return ev, n_ev + 1


@maybe_njit
def run_chain(out, ev, geos, lims, phus, dirs, nexts, ratios, k_l, k_r, v_rest, times, accel,
              g, dt_out, dt, t_free, max_events, early_stop):
    """The state machine of :func:`simulate_chain_stop` writing into buffers it is given: the
    signed response samples ``out`` (n_out,) and the event table ``ev`` (rows, 6), grown on the
    CPU up to ``max_events`` rows and fixed on a GPU.  No allocation of its own, so that the
    same source runs in a GPU thread (:mod:`archrock._device`).

    Returns (ev, n_events, status, t_final, peak, t_collapse, t_unstable, n_impacts,
    n_activations); the two counts are complete whatever the table's size."""
    n_ev = 0
    n_imp = 0
    n_act = 0
    nseg = times.size - 1
    t_motion = times[-1]
    t_stop = t_motion + t_free
    t = 0.0
    i = 0  # current segment
    mode = 0
    phi = 0.0
    w = 0.0
    k_out = 0
    peak = 0.0
    t_collapse = -1.0
    t_unstable = -1.0
    # last upward passage of the open mechanism's phi_u: every arc starts at phi = 0 < phi_u,
    # so at the limit it is in the arc that reaches it
    t_up = -1.0
    w_up = 0.0
    status = ST_REST
    thr_l = -k_l * g
    thr_r = k_r * g
    t_free_from = t_motion  # not the output window: results must not depend on it
    while True:
        # keep i the segment that contains t (zero-length segments skipped)
        while i < nseg and times[i + 1] <= t:
            i += 1
        if mode == 0:
            # search the first activation instant at or after t
            t_act = -1.0
            new_mode = 0
            j = i
            while j < nseg:
                t0 = max(t, times[j])
                t1 = times[j + 1]
                if t1 > t0:
                    a0 = _accel(t0, j, times, accel)
                    a1 = accel[j + 1]
                    # strictly beyond: at the threshold itself phi = 0 is in equilibrium, and
                    # activating there could stall (no motion, rest, activation again, ...)
                    if a0 < thr_l:
                        t_act, new_mode = t0, 1
                    elif a0 > thr_r:
                        t_act, new_mode = t0, 2
                    elif a1 < thr_l:
                        t_act, new_mode = t0 + (t1 - t0) * (thr_l - a0) / (a1 - a0), 1
                    elif a1 > thr_r:
                        t_act, new_mode = t0 + (t1 - t0) * (thr_r - a0) / (a1 - a0), 2
                    if new_mode != 0:
                        break
                j += 1
            if new_mode == 0:
                k_out = _fill_value(out, dt_out, 1e300, 0.0, k_out)
                status = ST_REST
                t = max(t, t_motion)
                break
            k_out = _fill_value(out, dt_out, t_act, 0.0, k_out)
            t = t_act
            i = j
            mode = new_mode
            phi = 0.0
            w = 0.0
            ev, n_ev = _add_event(ev, n_ev, max_events, EV_ACTIVATION, t, 0, mode, 0.0, 0.0)
            n_act += 1
            continue
        geo = geos[mode - 1]
        lim = lims[mode - 1]
        phu = phus[mode - 1]
        sign = dirs[mode - 1]
        if t >= t_stop:
            status = ST_MOVING
            break
        h = dt
        if t >= t_free_from:
            # free rocking after the ground motion: smooth and autonomous between impacts,
            # which are located exactly anyway
            h = FREE_STEP_FACTOR * dt
        if i < nseg and times[i + 1] - t < h:
            h = times[i + 1] - t
        if h <= 1e-14:
            t = times[i + 1]
            continue
        p1, w1 = _rk4(phi, w, t, h, i, times, accel, geo, g)
        if phi < phu <= p1:
            # an upward passage of phi_u inside this step (also when it reaches the limit too)
            hu, _, w_up = _locate(phi, w, t, h, i, times, accel, geo, g, phu, False, p1, w1)
            t_up = t + hu
            if t_unstable < 0:
                t_unstable = t_up
                ev, n_ev = _add_event(ev, n_ev, max_events, EV_UNSTABLE, t_up, mode, mode,
                                      w_up, w_up)
        if p1 >= lim:
            hc, p1, w1 = _locate(phi, w, t, h, i, times, accel, geo, g, lim, False, p1, w1)
            k_out = _fill(out, dt_out, t, t + hc, phi, w, p1, w1, sign, k_out)
            t = t + hc
            # the collapse became certain at the last upward passage of phi_u; the limit
            # (a numerical stop) only ends the run
            t_collapse = t_up if t_up >= 0 else t
            peak = max(peak, lim)
            ev, n_ev = _add_event(ev, n_ev, max_events, EV_COLLAPSE, t_collapse, mode, mode,
                                  w_up, w_up)
            ev, n_ev = _add_event(ev, n_ev, max_events, EV_LIMIT, t, mode, mode, w1, 0.0)
            k_out = _fill_value(out, dt_out, 1e300, np.nan, k_out)
            status = ST_COLLAPSED
            break
        if p1 < 0.0:
            hc, p1, w1 = _locate(phi, w, t, h, i, times, accel, geo, g, 0.0, phi <= 0.0, p1,
                                 w1)
            k_out = _fill(out, dt_out, t, t + hc, phi, w, 0.0, w1, sign, k_out)
            t = t + hc
            w_minus = w1 if w1 < 0 else 0.0
            w_plus = -ratios[mode - 1] * w_minus
            n_imp += 1
            if w_plus < v_rest:
                ev, n_ev = _add_event(ev, n_ev, max_events, EV_IMPACT, t, mode, 0, w_minus, 0.0)
                ev, n_ev = _add_event(ev, n_ev, max_events, EV_REST, t, mode, 0, 0.0, 0.0)
                mode = 0
                phi = 0.0
                w = 0.0
            else:
                new_mode = nexts[mode - 1]
                ev, n_ev = _add_event(ev, n_ev, max_events, EV_IMPACT, t, mode, new_mode,
                                      w_minus, w_plus)
                mode = new_mode
                phi = 0.0
                w = w_plus
                if early_stop and t >= t_motion and cannot_collapse(
                        mode - 1, w, peak, geos, phus, nexts, ratios, g):
                    k_out = _fill_value(out, dt_out, 1e300, np.nan, k_out)
                    status = ST_STOPPED
                    break
            continue
        k_out = _fill(out, dt_out, t, t + h, phi, w, p1, w1, sign, k_out)
        if w > 0.0 and w1 <= 0.0:
            peak = max(peak, _hermite_max(h, phi, w, p1, w1))
        t = t + h
        phi, w = p1, w1
        if phi > peak:
            peak = phi
    return ev, n_ev, status, t, peak, t_collapse, t_unstable, n_imp, n_act
