"""Nonsmooth contact dynamics of rigid blocks: Moreau-Jean time stepping with each step's
contact problem solved exactly (Moreau 1988, "Unilateral contact and dry friction in finite
freedom dynamics"; Jean 1999, "The non-smooth contact dynamics method", CMAME 177; Acary &
Brogliato 2008, "Numerical Methods for Nonsmooth Dynamical Systems", ch. 10 and 13).

State: for each body (x, y, theta) -- mass centre [m] and rotation from rest [rad,
counter-clockwise] -- and its velocities (vx, vy, omega).  One step of length h:

1. free velocity v_f = v_k + h (-xg''(t), -g) (the ground frame's body force and gravity act at
   the mass centre: no moment in 2-D);
2. at each corner contact (:mod:`.blocksystem`) the gap g, the face's normal n and tangent t from
   the current positions -- exact rotations, no linearisation.  Of the two corner contacts at a
   joint's end (b's corner on a's face, a's corner on b's) the one with the smaller gap bears: the
   same contact where the end is closed, the penetrating one where the faces turn apart.  A
   corner past its face's ends (by ``margin`` of its length), farther than ``reach``, or open and
   not closing within the step is not in the step's problem;
3. the impulses P = (P_n, P_t) and v_{k+1} = v_f + M^-1 H^T P, with u = H v_{k+1} the corners'
   relative velocities, satisfy
   - Signorini-Newton at velocity level: 0 <= P_n  _|_  u_n - b >= 0, with b = -e u_n,k on a
     closed contact (Newton's impact law, restitution e, 0 by default) and b = -g/h on an open
     one that would close within the step (it then closes exactly, its impact at the next step);
   - Coulomb: |P_t| <= mu P_n, u_t = 0 where |P_t| < mu P_n, u_t P_t <= 0 otherwise.
   :func:`_contact_impulses` solves this exactly: the relaxed cone u_n + mu |u_t| >= b + s makes
   the step a strictly convex problem (Anitescu 2006) solved in its dual by a finite active-set
   method (:func:`_bound_qp`), warm-started from the previous step, and De Saxce's shift
   s = mu |u_t| of the previous round turns its fixed point into Coulomb's law.  The solution's
   velocities are unique, so a mirror-symmetric structure stays symmetric whatever the order of
   its contacts.  Converged when the optimality residual and the shifts' change are below
   ``tol`` x g h (a velocity);
4. positions with the new velocities: q_{k+1} = q_k + h v_{k+1} (theta = 1; the rotation exact).

A closed corner with g < 0 (the O(h^2) drift of a rotation integrated along its tangent) is
pushed back by ``b += -beta g / h``.  Everything is a pure function of arrays, compiled when
numba is present (:func:`archrock._jit.maybe_njit`) and the same code in Python otherwise.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import maybe_njit

__all__ = ["advance", "run_response", "end_offsets", "SOLVER_FIELDS"]

#: the per-run counters returned by :func:`advance` (stats[0..3])
SOLVER_FIELDS = ("steps", "qp_iterations", "unconverged_steps", "largest_iterations")


@maybe_njit
def _moved(q, body, x, y, x0):
    """Where the point (x, y) [m] of ``body`` at rest is at positions q (the ground, -1, does
    not move)."""
    if body < 0:
        return x, y
    c, s = math.cos(q[body, 2]), math.sin(q[body, 2])
    rx = x - x0[body, 0]
    ry = y - x0[body, 1]
    return q[body, 0] + c * rx - s * ry, q[body, 1] + s * rx + c * ry


@maybe_njit
def _frame(q, k, owner, face, corner, face_start, tangent, normal, x0):
    """(corner P, face origin F, tangent t, normal n) of corner contact k at positions q."""
    f = face[k]
    px, py = _moved(q, owner[k], corner[k, 0], corner[k, 1], x0)
    fx, fy = _moved(q, f, face_start[k, 0], face_start[k, 1], x0)
    if f >= 0:
        c, s = math.cos(q[f, 2]), math.sin(q[f, 2])
        tx = c * tangent[k, 0] - s * tangent[k, 1]
        ty = s * tangent[k, 0] + c * tangent[k, 1]
        nx = c * normal[k, 0] - s * normal[k, 1]
        ny = s * normal[k, 0] + c * normal[k, 1]
    else:
        tx, ty = tangent[k, 0], tangent[k, 1]
        nx, ny = normal[k, 0], normal[k, 1]
    return px, py, fx, fy, tx, ty, nx, ny


@maybe_njit
def end_offsets(q, owner, corner, joint, end, joints, x0):
    """(joints, 2, 2): the b side's copy minus the a side's copy of each joint's end 0 and
    end 1 [m] at positions q (each joint's rows: b's two corners, then a's two)."""
    out = np.zeros((joints, 2, 2))
    for k in range(owner.size):
        sign = 1.0 if k % 4 < 2 else -1.0
        px, py = _moved(q, owner[k], corner[k, 0], corner[k, 1], x0)
        out[joint[k], end[k], 0] += sign * px
        out[joint[k], end[k], 1] += sign * py
    return out


@maybe_njit
def advance(q, v, impulse, accel, h, g, mu, e, tol, max_rounds, beta, margin, reach,
            masses, inertias, x0, owner, face, corner, face_start, tangent, normal, length,
            stats):
    """Advance ``len(accel)`` steps of length ``h`` [s] in place: q (nb, 3), v (nb, 3) and the
    contacts' ``impulse`` (nc, 2) (the warm start, and on return the last step's impulses
    [N s/m]); ``accel`` [m/s^2] the ground's acceleration during each step; g [m/s^2]; mu, e:
    friction and restitution; tol: the solver's tolerance, as a fraction of g h [m/s];
    max_rounds: the most rounds of De Saxce's shift per step; beta: the fraction of a
    penetration removed per step; margin:
    how far past a face's ends (fraction of its length) a corner still bears on it; reach [m]:
    the largest gap at which a corner contact is kept.  ``stats`` (4,) int64 accumulates
    (steps, QP iterations, steps left unconverged at max_rounds, most QP iterations in a step)."""
    nb = masses.size
    nc = owner.size
    inv_m = 1.0 / masses
    inv_i = 1.0 / inertias
    active = np.zeros(nc, np.bool_)
    jn = np.zeros((nc, 6))  # (n_x, n_y, r_p x n, r_f x n): the owner's and the face's rows
    jt = np.zeros((nc, 6))
    act = np.zeros(nc, np.int64)
    bn = np.zeros(nc)
    gaps = np.zeros(nc)
    frames = np.zeros((nc, 6))  # corner (x, y), tangent, normal at q_k
    along = np.zeros(nc)
    vtol = tol * g * h
    for step in range(accel.size):
        # 1. free velocities
        for i in range(nb):
            v[i, 0] -= h * accel[step]
            v[i, 1] -= h * g
        # 2. contact frames at q_k; of each end's two corner contacts (b's corner on a's face,
        # a's on b's) only the one with the smaller gap bears: where the end is closed they are
        # the same contact, and two copies of it would only slow the solver
        for k in range(nc):
            px, py, fx, fy, tx, ty, nx, ny = _frame(q, k, owner, face, corner, face_start,
                                                    tangent, normal, x0)
            frames[k, 0], frames[k, 1], frames[k, 2], frames[k, 3] = px, py, tx, ty
            frames[k, 4], frames[k, 5] = nx, ny
            gaps[k] = (px - fx) * nx + (py - fy) * ny
            along[k] = (px - fx) * tx + (py - fy) * ty
        for k in range(nc):
            p = owner[k]
            f = face[k]
            px, py, tx, ty = frames[k, 0], frames[k, 1], frames[k, 2], frames[k, 3]
            nx, ny = frames[k, 4], frames[k, 5]
            gap = gaps[k]
            s = along[k]
            lk = length[k]
            other = k + 2 if k % 4 < 2 else k - 2
            beaten = gaps[other] < gap or (gaps[other] == gap and other < k)
            if (beaten or gap > reach or s < -margin * lk - 1e-12
                    or s > (1.0 + margin) * lk + 1e-12):
                if beaten and impulse[other, 0] == 0.0 and impulse[k, 0] != 0.0:
                    impulse[other, 0] = impulse[k, 0]  # the warm start moves to the other
                    impulse[other, 1] = impulse[k, 1]
                active[k] = False
                impulse[k, 0] = 0.0
                impulse[k, 1] = 0.0
                continue
            rpn = rpt = rfn = rft = 0.0
            un = 0.0
            if p >= 0:
                rx, ry = px - q[p, 0], py - q[p, 1]
                rpn = rx * ny - ry * nx
                rpt = rx * ty - ry * tx
                un += v[p, 0] * nx + v[p, 1] * ny + v[p, 2] * rpn
            if f >= 0:
                rx, ry = px - q[f, 0], py - q[f, 1]
                rfn = rx * ny - ry * nx
                rft = rx * ty - ry * tx
                un -= v[f, 0] * nx + v[f, 1] * ny + v[f, 2] * rfn
            # the normal velocity before this step's forces: Newton's law takes u_n,k
            unk = un + (h * accel[step] * nx + h * g * ny) * ((1.0 if p >= 0 else 0.0)
                                                              - (1.0 if f >= 0 else 0.0))
            # an open contact is solved while it could close within the step: its row then
            # only stops it at the face (b = -g/h); 4 (g + |xg''|) h^2 covers what the step's
            # accelerations can close, and a gap of rounding (1e-13 m at rest) stays a contact
            if gap > 0.0 and gap + h * min(un, unk, 0.0) > 4.0 * (g + abs(accel[step])) * h * h:
                active[k] = False  # stays open through the step
                impulse[k, 0] = 0.0
                impulse[k, 1] = 0.0
                continue
            active[k] = True
            jn[k, 0], jn[k, 1], jn[k, 2], jn[k, 3] = nx, ny, rpn, rfn
            jt[k, 0], jt[k, 1], jt[k, 2], jt[k, 3] = tx, ty, rpt, rft
            if gap > 0.0:
                bn[k] = -gap / h
            else:
                bn[k] = -e * min(unk, 0.0) - beta * gap / h
        # 3. the contact problem, solved exactly (:func:`_contact_impulses`)
        na = 0
        for k in range(nc):
            if active[k]:
                act[na] = k
                na += 1
        its, ok = _contact_impulses(v, impulse, act[:na], jn, jt, bn, owner, face, inv_m,
                                    inv_i, mu, vtol, max_rounds)
        stats[0] += 1
        stats[1] += its
        if not ok:
            stats[2] += 1
        if its > stats[3]:
            stats[3] = its
        # 4. positions
        for i in range(nb):
            q[i, 0] += h * v[i, 0]
            q[i, 1] += h * v[i, 1]
            q[i, 2] += h * v[i, 2]


@maybe_njit
def _row_dot(v, k, sign, mu, jn, jt, owner, face):
    """(H_n + sign mu H_t) v at contact k: the relaxed cone's row (sign = +1 or -1)."""
    p = owner[k]
    f = face[k]
    out = 0.0
    if p >= 0:
        out += (v[p, 0] * (jn[k, 0] + sign * mu * jt[k, 0])
                + v[p, 1] * (jn[k, 1] + sign * mu * jt[k, 1])
                + v[p, 2] * (jn[k, 2] + sign * mu * jt[k, 2]))
    if f >= 0:
        out -= (v[f, 0] * (jn[k, 0] + sign * mu * jt[k, 0])
                + v[f, 1] * (jn[k, 1] + sign * mu * jt[k, 1])
                + v[f, 2] * (jn[k, 3] + sign * mu * jt[k, 3]))
    return out


@maybe_njit
def _bound_qp(Q, c, x, tolg, max_iter):
    """min 1/2 x^T Q x - c^T x subject to x >= 0, Q symmetric positive definite: the primal
    active-set method (Nocedal & Wright 2006, sec. 16.5), started from the feasible ``x`` (the
    warm start) and finite because the objective falls at every step.  Stops when the gradient
    Q x - c is >= -tolg on the bound variables (and zero on the free ones, to rounding).
    Returns (iterations, converged); x is the solution, in place."""
    m = c.size
    free = x > 0.0
    z = np.zeros(m)
    it = 0
    while it < max_iter:
        it += 1
        # the unconstrained minimum over the free variables: Q_FF z_F = c_F
        idx = np.flatnonzero(free)
        nf = idx.size
        z[:] = 0.0
        if nf:
            sub = np.empty((nf, nf))
            rhs = np.empty(nf)
            for i in range(nf):
                rhs[i] = c[idx[i]]
                for j in range(nf):
                    sub[i, j] = Q[idx[i], idx[j]]
            sol = _chol_solve(sub, rhs)
            for i in range(nf):
                z[idx[i]] = sol[i]
        blocked = False
        alpha = 1.0
        for i in range(nf):
            zi = z[idx[i]]
            if zi < 0.0:
                xi = x[idx[i]]
                a = xi / (xi - zi) if xi > 0.0 else 0.0
                if a < alpha:
                    alpha = a
                blocked = True
        if blocked:
            for i in range(nf):
                j = idx[i]
                x[j] = x[j] + alpha * (z[j] - x[j])
                if x[j] <= 0.0 or (z[j] < 0.0 and x[j] <= 1e-300):
                    x[j] = 0.0
                    free[j] = False
            continue
        for i in range(m):
            x[i] = z[i]
        # the most negative gradient on a bound variable joins the free set
        worst = -tolg
        add = -1
        for i in range(m):
            if not free[i]:
                gi = -c[i]
                for j in range(nf):
                    gi += Q[i, idx[j]] * x[idx[j]]
                if gi < worst:
                    worst = gi
                    add = i
        if add < 0:
            return it, True
        free[add] = True
    return it, False


@maybe_njit
def _chol_solve(a, b):
    """Solve a x = b for a symmetric positive definite, by Cholesky within a's envelope: row i
    of the factor is zero left of a's first non-zero in row i (fill-in stays inside it), so a
    chain of blocks, whose contacts couple only their neighbours' when listed in order, costs
    O(n w^2) for a band of width w instead of O(n^3)."""
    n = b.size
    first = np.empty(n, np.int64)
    for i in range(n):
        f = i
        for j in range(i):
            if a[i, j] != 0.0:
                f = j
                break
        first[i] = f
    low = np.zeros((n, n))
    for j in range(n):
        d = a[j, j]
        for k in range(first[j], j):
            d -= low[j, k] * low[j, k]
        if d <= 1e-300:
            d = 1e-300
        ljj = math.sqrt(d)
        low[j, j] = ljj
        for i in range(j + 1, n):
            if first[i] > j:
                continue
            s = a[i, j]
            for k in range(max(first[i], first[j]), j):
                s -= low[i, k] * low[j, k]
            low[i, j] = s / ljj
    y = np.empty(n)
    for i in range(n):
        s = b[i]
        for k in range(first[i], i):
            s -= low[i, k] * y[k]
        y[i] = s / low[i, i]
    x = np.empty(n)
    for i in range(n - 1, -1, -1):
        s = y[i]
        for k in range(i + 1, n):
            if first[k] <= i:
                s -= low[k, i] * x[k]
        x[i] = s / low[i, i]
    return x


@maybe_njit
def _contact_impulses(v, impulse, act, jn, jt, bn, owner, face, inv_m, inv_i, mu, vtol,
                      max_rounds):
    """The step's contact impulses, exactly: v (the free velocities) becomes v_{k+1}.

    Each active contact's Coulomb cone is written as the relaxed cone u_n + mu |u_t| >= b + s
    (two linear rows, Anitescu 2006, Math. Program. 105), whose impulses are the friction cone
    itself; the velocities then minimise the kinetic metric's distance to the free velocities
    under those rows, a strictly convex problem solved exactly in its dual (:func:`_bound_qp`).
    De Saxce's shift s = mu |u_t| of the previous round makes the fixed point Coulomb's law
    (u_n >= b where a contact slides, no dilatancy); the rounds stop when no shift moves by
    more than ``vtol`` (a sticking or rocking contact has u_t = 0, s = 0: one round).
    Returns (QP iterations in all, converged)."""
    na = act.size
    m = 2 * na
    if na == 0:
        return 0, True
    eps = 0.0
    # the rows of the relaxed cones, each body's part with its sign: (x, y, r) of the owner,
    # then of the face's body
    rows = np.empty((m, 6))
    for i in range(na):
        k = act[i]
        for si in range(2):
            sg = mu if si == 0 else -mu
            r = 2 * i + si
            rows[r, 0] = jn[k, 0] + sg * jt[k, 0]
            rows[r, 1] = jn[k, 1] + sg * jt[k, 1]
            rows[r, 2] = jn[k, 2] + sg * jt[k, 2]
            rows[r, 3] = -rows[r, 0]
            rows[r, 4] = -rows[r, 1]
            rows[r, 5] = -(jn[k, 3] + sg * jt[k, 3])
    Q = np.zeros((m, m))
    for i in range(na):
        ki = act[i]
        for j in range(i, na):
            kj = act[j]
            for side_i in range(2):
                bi = owner[ki] if side_i == 0 else face[ki]
                if bi < 0:
                    continue
                for side_j in range(2):
                    bj = owner[kj] if side_j == 0 else face[kj]
                    if bj != bi:
                        continue
                    wm = inv_m[bi]
                    wi = inv_i[bi]
                    oi = 3 * side_i
                    oj = 3 * side_j
                    for si in range(2):
                        ri = 2 * i + si
                        for sj in range(2):
                            rj = 2 * j + sj
                            val = (wm * (rows[ri, oi] * rows[rj, oj]
                                         + rows[ri, oi + 1] * rows[rj, oj + 1])
                                   + wi * rows[ri, oi + 2] * rows[rj, oj + 2])
                            Q[ri, rj] += val
                            if j != i:
                                Q[rj, ri] += val
    for i in range(m):
        if Q[i, i] > eps:
            eps = Q[i, i]
    # a compliance of 1e-10 of the largest diagonal: redundant contacts (a statically
    # indeterminate share) get the least-norm share instead of a singular system
    for i in range(m):
        Q[i, i] += 1e-10 * eps
    vf = v.copy()
    af = np.empty(m)
    for i in range(na):
        af[2 * i] = _row_dot(vf, act[i], 1.0, mu, jn, jt, owner, face)
        af[2 * i + 1] = _row_dot(vf, act[i], -1.0, mu, jn, jt, owner, face)
    x = np.empty(m)
    for i in range(na):  # warm start: impulse (P_n, P_t) = (x+ + x-, mu (x+ - x-))
        k = act[i]
        pn, pt = impulse[k, 0], impulse[k, 1]
        tp = pt / mu if mu > 0.0 else 0.0
        x[2 * i] = max(0.0, 0.5 * (pn + tp))
        x[2 * i + 1] = max(0.0, 0.5 * (pn - tp))
    shift = np.zeros(na)
    c = np.empty(m)
    total = 0
    ok = False
    for rnd in range(max_rounds):
        for i in range(na):
            c[2 * i] = bn[act[i]] + shift[i] - af[2 * i]
            c[2 * i + 1] = bn[act[i]] + shift[i] - af[2 * i + 1]
        its, conv = _bound_qp(Q, c, x, vtol, 5 * m + 20)
        total += its
        # velocities and the new shifts
        for i in range(v.shape[0]):
            v[i, 0], v[i, 1], v[i, 2] = vf[i, 0], vf[i, 1], vf[i, 2]
        for i in range(na):
            k = act[i]
            pn = x[2 * i] + x[2 * i + 1]
            pt = mu * (x[2 * i] - x[2 * i + 1])
            if pn != 0.0 or pt != 0.0:
                _apply(v, k, pn, pt, owner, face, jn, jt, inv_m, inv_i)
        moved = 0.0
        for i in range(na):
            k = act[i]
            up = _row_dot(v, k, 1.0, mu, jn, jt, owner, face)
            um = _row_dot(v, k, -1.0, mu, jn, jt, owner, face)
            ut = (up - um) / (2.0 * mu) if mu > 0.0 else 0.0
            s_new = mu * abs(ut)
            # a contact that carries nothing and keeps u_n >= b is inactive with either shift:
            # its change cannot move the next round
            idle = x[2 * i] + x[2 * i + 1] == 0.0 and 0.5 * (up + um) >= bn[k] - vtol
            if not idle and abs(s_new - shift[i]) > moved:
                moved = abs(s_new - shift[i])
            shift[i] = s_new
        if conv and moved <= vtol:
            ok = True
            break
    for i in range(na):
        k = act[i]
        impulse[k, 0] = x[2 * i] + x[2 * i + 1]
        impulse[k, 1] = mu * (x[2 * i] - x[2 * i + 1])
    return total, ok


@maybe_njit
def _apply(v, k, dn, dt, owner, face, jn, jt, inv_m, inv_i):
    """Add the velocity change of impulse (dn, dt) at contact k to its two bodies."""
    p = owner[k]
    f = face[k]
    fx = dn * jn[k, 0] + dt * jt[k, 0]
    fy = dn * jn[k, 1] + dt * jt[k, 1]
    if p >= 0:
        v[p, 0] += inv_m[p] * fx
        v[p, 1] += inv_m[p] * fy
        v[p, 2] += inv_i[p] * (dn * jn[k, 2] + dt * jt[k, 2])
    if f >= 0:
        v[f, 0] -= inv_m[f] * fx
        v[f, 1] -= inv_m[f] * fy
        v[f, 2] -= inv_i[f] * (dn * jn[k, 3] + dt * jt[k, 3])


@maybe_njit
def run_response(q, v, impulse, accel, start, stop, t_motion_end, every, samples, carry,
                 drop_limit, ke_rest, quiet_needed, h, g, mu, e, tol, max_rounds, beta, margin,
                 reach, masses, inertias, x0, owner, face, corner, face_start, tangent, normal,
                 length, stats):
    """A response from step ``start`` to at most ``stop`` in place, with the checks of every
    step: before each step the state is sampled into ``samples`` every ``every`` steps (while
    room is left), a mass centre dropped below its rest height by more than ``drop_limit`` [m]
    is a collapse, and after ``t_motion_end`` [s] a kinetic energy below ``ke_rest`` [J/m] for
    ``quiet_needed`` steps in a row is rest.  ``accel`` [m/s^2] holds every step's ground
    acceleration (the run ends at its length).  ``carry`` (int64: samples taken, quiet steps,
    rest seen) goes on from one call to the next.  Returns (status: 0 going on, 1 at rest,
    2 collapsed, 3 the end of ``accel`` reached; the step reached)."""
    n_out = samples.shape[0]
    nb = masses.size
    s = start
    while s < stop:
        t = s * h
        k = carry[0]
        if k < n_out and s == k * every:
            for i in range(nb):
                samples[k, i, 0] = q[i, 0]
                samples[k, i, 1] = q[i, 1]
                samples[k, i, 2] = q[i, 2]
            carry[0] = k + 1
        for i in range(nb):
            if x0[i, 1] - q[i, 1] > drop_limit:
                return 2, s
        if t > t_motion_end:
            ke = 0.0
            for i in range(nb):
                ke += 0.5 * (masses[i] * (v[i, 0] * v[i, 0] + v[i, 1] * v[i, 1])
                             + inertias[i] * v[i, 2] * v[i, 2])
            carry[1] = carry[1] + 1 if ke < ke_rest else 0
            if carry[1] >= quiet_needed:
                carry[2] = 1
                if carry[0] >= n_out:
                    return 1, s
        if s >= accel.size:
            return 3, s
        advance(q, v, impulse, accel[s:s + 1], h, g, mu, e, tol, max_rounds, beta, margin,
                reach, masses, inertias, x0, owner, face, corner, face_start, tangent, normal,
                length, stats)
        s += 1
    return 0, s
