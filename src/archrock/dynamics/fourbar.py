"""The four-link mechanism's compiled kinematics: exact finite-rotation closure of the loop and the
coefficients of its equation of motion, on a flat geometry vector.

Once activated, the arch moves as a single-degree-of-freedom four-bar linkage: the ground,
link 1 (voussoirs between hinges A and B, pivoting on ground hinge A), link 2 (between B and C)
and link 3 (between C and D, pivoting on ground hinge D).  A is the hinge on the mechanism's
leading side: for M_l the leftmost hinge, for M_r the rightmost one (docs/method.md, Four-link equation).

The Lagrangian coordinate phi is the rotation of link AB, signed so that phi >= 0 while the
mechanism is open.  Lagrange's equation reads

    M(phi) phi'' + L(phi) phi'^2 + F(phi) g = P(phi) xg''

with M = sum m |dG/dphi|^2 + I (dtheta/dphi)^2, L = M'/2, F = sum m dy_G/dphi and
P = -sum m dx_G/dphi, all from exact first and second derivatives of the loop closure.
The same equation holds for both mechanisms (xg'' positive toward +x).

:mod:`archrock.dynamics.fourlink` builds the vector from an arch (``FourLink``, ``four_link``) and
re-exports what is here (``from archrock.dynamics.fourlink import coefficients`` works as ever);
:mod:`archrock.dynamics.tables` tabulates the coefficients for the fast integrator.
"""

from __future__ import annotations

import math


from .._jit import maybe_njit

# Layout of the flat geometry vector used by the scalar kernels (shared with the compiled
# integrator): hinge points A, B, C, D at phi = 0; sign s (theta_1 = s phi); link masses;
# link centroids at phi = 0; link centroidal inertias.
_A, _B, _C, _D = 0, 2, 4, 6
_S = 8
_M = 9       # 9, 10, 11
_GC = 12     # 12..17
_I = 18      # 18, 19, 20
GEO_SIZE = 21


@maybe_njit
def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


@maybe_njit
def configuration(phi, geo):
    """Positions at rotation phi: returns (Bx, By, Cx, Cy, th1, th2, th3, ok).

    ``ok`` is False past the four-bar's dead point (no closure of the loop).
    """
    ax, ay = geo[_A], geo[_A + 1]
    b0x, b0y = geo[_B], geo[_B + 1]
    c0x, c0y = geo[_C], geo[_C + 1]
    dx, dy = geo[_D], geo[_D + 1]
    th1 = geo[_S] * phi
    c1, s1 = math.cos(th1), math.sin(th1)
    rbx, rby = b0x - ax, b0y - ay
    bx = ax + c1 * rbx - s1 * rby
    by = ay + s1 * rbx + c1 * rby
    l2sq = (c0x - b0x) ** 2 + (c0y - b0y) ** 2
    l3sq = (c0x - dx) ** 2 + (c0y - dy) ** 2
    ex, ey = dx - bx, dy - by
    d = math.sqrt(ex * ex + ey * ey)
    a = (l2sq - l3sq + d * d) / (2.0 * d)
    h2 = l2sq - a * a
    ok = h2 >= 0.0
    h = math.sqrt(h2) if ok else 0.0
    ex /= d
    ey /= d
    # keep the branch of the undisplaced configuration (C on the same side of line BD)
    side = _cross(dx - b0x, dy - b0y, c0x - b0x, c0y - b0y)
    sg = 1.0 if side >= 0.0 else -1.0
    cx = bx + a * ex - sg * h * ey
    cy = by + a * ey + sg * h * ex
    u0x, u0y = c0x - b0x, c0y - b0y
    ux, uy = cx - bx, cy - by
    th2 = math.atan2(_cross(u0x, u0y, ux, uy), u0x * ux + u0y * uy)
    w0x, w0y = c0x - dx, c0y - dy
    wx, wy = cx - dx, cy - dy
    th3 = math.atan2(_cross(w0x, w0y, wx, wy), w0x * wx + w0y * wy)
    return bx, by, cx, cy, th1, th2, th3, ok


@maybe_njit
def _rates_at(bx, by, cx, cy, geo):
    """Link-rotation derivatives for given positions of B and C (see :func:`rates`)."""
    ax, ay = geo[_A], geo[_A + 1]
    dx, dy = geo[_D], geo[_D + 1]
    t1 = geo[_S]
    u1x, u1y = bx - ax, by - ay
    u2x, u2y = cx - bx, cy - by
    u3x, u3y = dx - cx, dy - cy
    det = _cross(u2x, u2y, u3x, u3y)
    rx, ry = -t1 * u1x, -t1 * u1y
    t2 = _cross(rx, ry, u3x, u3y) / det
    t3 = _cross(u2x, u2y, rx, ry) / det
    # sum th_k'' u_k = -sum th_k'^2 (k x u_k);  k x u = (-uy, ux)
    qx = -(t1 * t1 * (-u1y) + t2 * t2 * (-u2y) + t3 * t3 * (-u3y))
    qy = -(t1 * t1 * u1x + t2 * t2 * u2x + t3 * t3 * u3x)
    t2d = _cross(qx, qy, u3x, u3y) / det
    t3d = _cross(u2x, u2y, qx, qy) / det
    return t1, t2, t3, t2d, t3d, det


@maybe_njit
def rates(phi, geo):
    """First and second derivatives of the link rotations with respect to phi.

    Returns (th1', th2', th3', th2'', th3'', det) from the loop closure
    th1' u1 + th2' u2 + th3' u3 = 0 (u1 = B-A, u2 = C-B, u3 = D-C) and its derivative;
    ``det`` = u2 x u3 vanishes at the dead point.
    """
    bx, by, cx, cy, _, _, _, _ = configuration(phi, geo)
    return _rates_at(bx, by, cx, cy, geo)


@maybe_njit
def coefficients(phi, geo):
    """(M, L, F, P) of the equation of motion at rotation phi [rad] (per metre of depth).

    M [kg m^2], L [kg m^2], F [kg m], P [kg m].
    """
    bx, by, cx, cy, th1, _, _, _ = configuration(phi, geo)
    t1, t2, t3, t2d, t3d, _ = _rates_at(bx, by, cx, cy, geo)
    ax, ay = geo[_A], geo[_A + 1]
    b0x, b0y = geo[_B], geo[_B + 1]
    c0x, c0y = geo[_C], geo[_C + 1]
    dx, dy = geo[_D], geo[_D + 1]
    m1, m2, m3 = geo[_M], geo[_M + 1], geo[_M + 2]
    i1, i2, i3 = geo[_I], geo[_I + 1], geo[_I + 2]
    # link centroids in the displaced configuration, relative to their reference points;
    # cos/sin of the link rotations come from the link vectors (cheaper than atan2 + cos/sin)
    c1, s1 = math.cos(th1), math.sin(th1)
    px, py = geo[_GC] - ax, geo[_GC + 1] - ay
    r1x, r1y = c1 * px - s1 * py, s1 * px + c1 * py          # G1 - A
    u0x, u0y = c0x - b0x, c0y - b0y
    ux, uy = cx - bx, cy - by
    n2 = u0x * u0x + u0y * u0y
    c2, s2 = (u0x * ux + u0y * uy) / n2, _cross(u0x, u0y, ux, uy) / n2
    px, py = geo[_GC + 2] - b0x, geo[_GC + 3] - b0y
    r2x, r2y = c2 * px - s2 * py, s2 * px + c2 * py          # G2 - B
    w0x, w0y = c0x - dx, c0y - dy
    wx, wy = cx - dx, cy - dy
    n3 = w0x * w0x + w0y * w0y
    c3, s3 = (w0x * wx + w0y * wy) / n3, _cross(w0x, w0y, wx, wy) / n3
    px, py = geo[_GC + 4] - dx, geo[_GC + 5] - dy
    r3x, r3y = c3 * px - s3 * py, s3 * px + c3 * py          # G3 - D
    ubx, uby = bx - ax, by - ay
    # velocities per unit phi-rate: v = th' k x r
    v1x, v1y = -t1 * r1y, t1 * r1x
    vbx, vby = -t1 * uby, t1 * ubx
    v2x, v2y = vbx - t2 * r2y, vby + t2 * r2x
    v3x, v3y = -t3 * r3y, t3 * r3x
    # accelerations at unit rate and zero phi'': a = th'' k x r - th'^2 r
    a1x, a1y = -t1 * t1 * r1x, -t1 * t1 * r1y
    abx, aby = -t1 * t1 * ubx, -t1 * t1 * uby
    a2x = abx - t2d * r2y - t2 * t2 * r2x
    a2y = aby + t2d * r2x - t2 * t2 * r2y
    a3x = -t3d * r3y - t3 * t3 * r3x
    a3y = t3d * r3x - t3 * t3 * r3y
    M = (m1 * (v1x * v1x + v1y * v1y) + m2 * (v2x * v2x + v2y * v2y) + m3 * (v3x * v3x + v3y * v3y)
         + i1 * t1 * t1 + i2 * t2 * t2 + i3 * t3 * t3)
    L = (m1 * (v1x * a1x + v1y * a1y) + m2 * (v2x * a2x + v2y * a2y) + m3 * (v3x * a3x + v3y * a3y)
         + i2 * t2 * t2d + i3 * t3 * t3d)
    F = m1 * v1y + m2 * v2y + m3 * v3y
    P = -(m1 * v1x + m2 * v2x + m3 * v3x)
    return M, L, F, P


@maybe_njit
def potential(phi, geo):
    """Gravity potential per unit g [kg m]: sum m y_G relative to phi = 0 (for energy checks)."""
    bx, by, cx, cy, th1, th2, th3, _ = configuration(phi, geo)
    out = 0.0
    refs = ((geo[_A], geo[_A + 1], geo[_A + 1]), (geo[_B], geo[_B + 1], by),
            (geo[_D], geo[_D + 1], geo[_D + 1]))
    ths = (th1, th2, th3)
    for k in range(3):
        ox, oy, ref_y = refs[k]
        px, py = geo[_GC + 2 * k] - ox, geo[_GC + 2 * k + 1] - oy
        y = ref_y + math.sin(ths[k]) * px + math.cos(ths[k]) * py
        out += geo[_M + k] * (y - geo[_GC + 2 * k + 1])
    return out


# ---------------------------------------------------------------------------- compiled construction
# four_link, FourLink and the batch preparation of archrock.dynamics.batch share these compiled pieces, so
# that one arch prepared alone or in a batch of thousands gets the same model to the last bit.
GEO_OK, GEO_SINGULAR, GEO_NOT_ADMISSIBLE, GEO_WRONG_DIRECTION = 0, 1, 2, 3
GEO_ERRORS = {
    GEO_SINGULAR: "mechanism {m}: the hinges are aligned (singular four-bar)",
    GEO_NOT_ADMISSIBLE: "mechanism {m}: the hinges admit no opening motion",
    GEO_WRONG_DIRECTION: "mechanism {m}: the hinges do not open under forces of its direction",
}


@maybe_njit
def _edge_sign(edge):
    """-1 for a hinge at the intrados (edge 0), +1 at the extrados."""
    return -1.0 if edge == 0 else 1.0


@maybe_njit
def mechanism_geo(px, py, mass, cen, inert, joints, edges, is_r, geo):
    """Fill ``geo`` (GEO_SIZE) for one mechanism of one arch (the compiled core of four_link).

    px, py (n+1, 2): joint points (intrados, extrados); mass, inert (n,), cen (n, 2);
    joints, edges (4,): hinges from the left springing.  Returns an error code (0 = ok).
    """
    # the hinge points by name, not in an array: a GPU thread cannot allocate one
    x0, y0 = px[joints[0], edges[0]], py[joints[0], edges[0]]
    x1, y1 = px[joints[1], edges[1]], py[joints[1], edges[1]]
    x2, y2 = px[joints[2], edges[2]], py[joints[2], edges[2]]
    x3, y3 = px[joints[3], edges[3]], py[joints[3], edges[3]]
    u2x, u2y = x2 - x1, y2 - y1
    u3x, u3y = x3 - x2, y3 - y2
    rx, ry = x0 - x1, y0 - y1
    det = _cross(u2x, u2y, u3x, u3y)
    if abs(det) < 1e-12 * math.hypot(u2x, u2y) * math.hypot(u3x, u3y):
        return GEO_SINGULAR
    w2 = _cross(rx, ry, u3x, u3y) / det
    w3 = _cross(u2x, u2y, rx, ry) / det
    q0 = _edge_sign(edges[0])
    q1 = _edge_sign(edges[1]) * (w2 - 1.0)
    q2 = _edge_sign(edges[2]) * (w3 - w2)
    q3 = _edge_sign(edges[3]) * (-w3)
    tol = 1e-9 * max(max(abs(q0), abs(q1)), max(abs(q2), abs(q3)))
    if q0 > tol and q1 > tol and q2 > tol and q3 > tol:
        sigma = 1.0
    elif q0 < -tol and q1 < -tol and q2 < -tol and q3 < -tol:
        sigma = -1.0
    else:
        return GEO_NOT_ADMISSIBLE
    lead = sigma * w3 if is_r else sigma
    geo[8] = 1.0 if lead > 0 else -1.0
    for k in range(4):
        kk = 3 - k if is_r else k
        geo[2 * k] = px[joints[kk], edges[kk]]
        geo[2 * k + 1] = py[joints[kk], edges[kk]]
    for link in range(3):
        src = 2 - link if is_r else link
        j0, j1 = joints[src], joints[src + 1]
        m = 0.0
        for i in range(j0, j1):
            m += mass[i]
        gx = 0.0
        gy = 0.0
        for i in range(j0, j1):
            gx += mass[i] * cen[i, 0]
            gy += mass[i] * cen[i, 1]
        gx /= m
        gy /= m
        inertia = 0.0
        for i in range(j0, j1):
            inertia += inert[i] + mass[i] * ((cen[i, 0] - gx) ** 2 + (cen[i, 1] - gy) ** 2)
        geo[9 + link] = m
        geo[12 + 2 * link] = gx
        geo[13 + 2 * link] = gy
        geo[18 + link] = inertia
    _, _, F, P = coefficients(0.0, geo)
    k = F / P
    if (not is_r and k >= 0) or (is_r and k <= 0):
        return GEO_WRONG_DIRECTION
    return GEO_OK


@maybe_njit
def _det_signed(phi, geo, det0):
    """det = (C - B) x (D - C) (vanishes at the dead point), times det0; -1 past closure.
    Computed from the positions (rates() would divide by it)."""
    bx, by, cx, cy, _, _, _, ok = configuration(phi, geo)
    if not ok:
        return -1.0
    return _cross(cx - bx, cy - by, geo[6] - cx, geo[7] - cy) * det0


@maybe_njit
def dead_point(geo):
    """First rotation [rad] at which the four-bar locks (dead point), capped at pi/2."""
    det0 = 1.0 if rates(0.0, geo)[5] >= 0 else -1.0
    n = 91
    prev = 0.0
    for k in range(1, n):
        phi = (math.pi / 2) * k / (n - 1)
        if _det_signed(phi, geo, det0) <= 0:
            a, b = prev, phi
            for _ in range(60):
                mid = 0.5 * (a + b)
                if _det_signed(mid, geo, det0) > 0:
                    a = mid
                else:
                    b = mid
            return a
        prev = phi
    return math.pi / 2


@maybe_njit
def unstable_rotation(geo, phi_dead):
    """Rotation [rad] of the unstable static position under gravity alone: the first root of
    F(phi) (bracketed on a 60-point grid, then Illinois), or just below the dead point."""
    top = phi_dead * (1 - 1e-9)
    n = 60
    prev_phi = 0.0
    prev_f = coefficients(0.0, geo)[2]
    for k in range(1, n):
        phi = top * k / (n - 1)
        f = coefficients(phi, geo)[2]
        if prev_f > 0 >= f:
            a, fa, b, fb = prev_phi, prev_f, phi, f
            for _ in range(200):  # bisection safeguarded secant (Illinois)
                c = b - fb * (b - a) / (fb - fa)
                if not (min(a, b) < c < max(a, b)):
                    c = 0.5 * (a + b)
                fc = coefficients(c, geo)[2]
                if fc == 0.0:
                    return c
                if (fc > 0) == (fa > 0):
                    a, fa = c, fc
                    fb *= 0.5
                else:
                    b, fb = c, fc
                    fa *= 0.5
                if abs(b - a) < 1e-14:
                    break
            return 0.5 * (a + b)
        prev_phi, prev_f = phi, f
    return top


@maybe_njit
def rotation_limit(phi_unstable, phi_dead):
    """Default rotation limit [rad] for collapse: well beyond the unstable position, before the
    dead point (halfway to the dead point, at most 2.5 times the unstable rotation)."""
    return min(phi_unstable + 0.5 * (phi_dead - phi_unstable), 2.5 * phi_unstable)


@maybe_njit
def rest_rate(geo, phi_unstable_l, phi_unstable_r, g):
    """Post-impact rate [rad/s] below which the arch is at rest again: 1e-5 of the rate scale
    p * phi_u with p = sqrt(g F(0) / M(0)) (no endless chattering, negligible energy)."""
    M0, _, F0, _ = coefficients(0.0, geo)
    return 1e-5 * math.sqrt(g * F0 / M0) * min(phi_unstable_l, phi_unstable_r)


@maybe_njit
def table_range(geo, phi_limit, phi_dead):
    """(start, top) [rad] of the tables for motions up to ``phi_limit``: past the limit
    by 25% (not past the dead point) and below 0 by 5% of that, halved until the four-bar
    closes on the undisplaced branch from there to 0 (it can lock on the negative side too)."""
    top = min(phi_limit * 1.25, phi_dead * (1 - 1e-6))
    det0 = 1.0 if rates(0.0, geo)[5] >= 0 else -1.0
    start = -0.05 * top
    for _ in range(40):
        ok = True
        for k in range(9):
            p = start * (1.0 - k / 8.0)
            if _det_signed(p, geo, det0) <= 0:
                ok = False
                break
        if ok:
            break
        start *= 0.5
    return start, top
