"""The static linear program on a graph of rigid blocks (an :class:`~archrock.geometry.arcade.
Arcade`), and its mechanism read from the dual (docs/arcades.md).

Heyman's hypotheses (no tension, no crushing, no sliding unless Coulomb rows are asked for) on
any set of blocks and contacts.  Unknowns, nondimensional (forces per total weight W, lengths
per the arcade's extent L): at each contact c the normal force at each of its two ends, N0 and
N1 >= 0 (compression; their resultant is the thrust, inside the joint, crossing it at
t = N1 / (N0 + N1) of the way from end 0), the shear V along the joint (free, or with friction
|V| <= mu (N0 + N1)), and the horizontal load factor k.  Block b carries its weight w_b at its
mass centre and d k w_b horizontally there (d = +1 for direction 'l', loads toward +x; -1 for
'r'); the contact forces act on block b along the normal n from a into b and on block a
opposite.  Three equilibrium rows per block (forces, and moments about its own mass centre).
Maximise k (scipy.optimize.linprog, HiGHS).

The dual: one (u_x, u_y, omega) per block, the multipliers of its three rows; up to sign they
are a virtual velocity of the block (its mass centre's velocity and its angular velocity), and
dual feasibility says that no contact end closes (relative normal velocity >= 0), that no joint
slides without friction (relative tangential velocity 0), and with friction that the sliding is
the associated (dilatant) flow.  Where the dual opens a contact at one end only, the contact is
a hinge about the other end.  The mechanism is then rebuilt from those hinges alone (the
velocities that keep every hinge point, closed contact and sliding condition: a null space) and
its multiplier recomputed by its own virtual work, k = sum w_b v_y,b / sum d w_b v_x,b (the
weights rise while the horizontal loads work; no energy is dissipated in rocking or in the
associated sliding), which must equal the LP's optimum.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linprog

from .._records import readonly_arrays
from ..errors import ArchInputError, CannotStandError, NoMechanismError
from ..units import G
from ..geometry.arcade import GROUND, Arcade
from .friction import check_friction
from .hinges import DIRECTIONS

__all__ = ["GraphHinge", "GraphMechanism", "GraphLimit", "graph_multiplier", "graph_limit",
           "graph_limit_cost_s", "mechanism_velocities", "generalized_mass", "generalized_loads"]

#: A relative velocity smaller than this fraction of the largest block velocity counts as zero.
VELOCITY_TOL = 1e-6
#: Seconds of :func:`graph_limit` in one direction per block squared (the dense program's
#: arrays and HiGHS): two semicircles on 10-course piers, 230 to 830 blocks, took 11 to 116 s
#: on the 2-core development machine, shared (t ~ nb^2).
GRAPH_LIMIT_S_PER_BLOCK2 = 1.5e-4
#: Seconds to build or read and check one block of an arcade (830 blocks: 1.4 s).
GRAPH_BUILD_S = 2e-3


def graph_limit_cost_s(n_blocks: int, directions: int = 2) -> float:
    """Rough seconds [s] to build an arcade of ``n_blocks`` blocks and solve its static program
    in ``directions`` directions (within a factor of a few)."""
    n = float(n_blocks)
    return n * GRAPH_BUILD_S + directions * GRAPH_LIMIT_S_PER_BLOCK2 * n * n


@dataclass(frozen=True)
class GraphHinge:
    """A hinge: contact ``contact`` rotates about its end ``end`` (0 or 1); ``place`` in words
    ("pier 2 foot, outer face"); ``point`` (x, y) [m] where it is off that end (under finite
    strength: the stress block's centre, nearer end ``end``), else None."""

    contact: int
    end: int
    place: str
    point: tuple | None = None

    def to_dict(self) -> dict:
        d = {"contact": self.contact, "end": self.end, "place": self.place}
        if self.point is not None:
            d["point"] = list(self.point)
        return d


@dataclass(frozen=True, eq=False)
class GraphMechanism:
    """The mechanism of one direction: ``hinges`` (:class:`GraphHinge`), ``lift_off`` (contacts
    that open at both ends), ``sliding`` (contacts that slide), ``moving`` (blocks that move);
    ``velocities`` (n_blocks, 3): each block's (v_x, v_y) of its mass centre [m/s per unit
    rate] and omega [rad/s], scaled so that the horizontal loads' work is sum d m_b v_x,b / M =
    1 m/s; ``dof`` the dimension of the null space of the hinge conditions (1: one degree of
    freedom); ``multiplier`` its virtual-work k."""

    direction: str
    hinges: tuple
    lift_off: tuple
    sliding: tuple
    moving: tuple
    velocities: np.ndarray = field(repr=False)
    dof: int
    multiplier: float

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def label(self) -> str:
        return "-".join(f"{h.contact}{'ab'[h.end]}" for h in self.hinges)

    def to_dict(self) -> dict:
        return {"direction": self.direction, "hinges": [h.to_dict() for h in self.hinges],
                "lift_off": list(self.lift_off), "sliding": list(self.sliding),
                "moving": list(self.moving), "velocities": self.velocities.tolist(),
                "dof": self.dof, "multiplier": self.multiplier}


@dataclass(frozen=True, eq=False)
class GraphLimit:
    """The limit analysis of an arcade in one direction: ``k`` the LP's optimum (the horizontal
    load, per unit weight, that the structure carries at most; the collapse multiplier under
    Heyman's hypotheses; the signed horizontal loads the blocks carry form [-k_r, k_l], so a
    negative k says the arcade cannot stand under its own weight), ``k_virtual_work`` the mechanism's own multiplier (equal to ``k`` to
    about 1e-9 when the dual was read right), ``mechanism``, ``forces`` (m, 3): N0, N1, V at each
    contact [N/m] at the optimum, ``friction`` (None: no sliding), ``method``."""

    direction: str
    k: float
    k_virtual_work: float
    mechanism: GraphMechanism
    forces: np.ndarray = field(repr=False)
    friction: float | None
    method: str
    #: finite compressive strength (statics.graphcrush): (k_lower, k_upper) of the static
    #: optimum's bracket (k is k_lower), and each contact's stress block depth N / f_c [m]
    k_bounds: tuple | None = None
    zones: np.ndarray | None = field(default=None, repr=False)

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def hinges(self) -> tuple:
        return self.mechanism.hinges

    def to_dict(self) -> dict:
        d = {"direction": self.direction, "k": self.k,
             "k_virtual_work": self.k_virtual_work,
             "mechanism": self.mechanism.to_dict(), "forces": self.forces.tolist(),
             "friction": self.friction, "method": self.method,
             "units": {"k": "g", "forces": "N per m of depth",
                       "velocities": "m/s and rad/s per unit work of the horizontal loads"}}
        if self.k_bounds is not None:  # only under finite strength: Heyman's output unchanged
            d["k_bounds"] = list(self.k_bounds)
            d["zones"] = self.zones.tolist()
            d["units"]["zones"] = "m (depth of the stress block at each contact)"
        return d


class _Program:
    """The arrays of the LP: x = [N0_0, N1_0, V_0, N0_1, ..., k]."""

    def __init__(self, arc: Arcade, direction: str, friction: float | None):
        if not isinstance(arc, Arcade):
            raise ArchInputError(f"arcade: expected an Arcade, got {type(arc).__name__}")
        if direction not in DIRECTIONS:
            raise ArchInputError(f"direction: {direction!r}; allowed 'l' or 'r'")
        self.arc = arc
        self.d = 1.0 if direction == "l" else -1.0
        self.L = arc.extent
        m = np.asarray(arc.masses, float)
        self.w = m / m.sum()
        self.G = np.asarray(arc.centroids, float)
        nb, nc = arc.n_blocks, len(arc.contacts)
        self.nb, self.nc = nb, nc
        nv = 3 * nc + 1
        A = np.zeros((3 * nb, nv))
        self.normals = np.asarray(arc.contact_normals, float)
        self.tangents = np.column_stack([self.normals[:, 1], -self.normals[:, 0]])
        for c, ct in enumerate(arc.contacts):
            n, t = self.normals[c], self.tangents[c]
            for blk, sgn in ((ct.b, 1.0), (ct.a, -1.0)):
                if blk == GROUND:
                    continue
                r = 3 * blk
                g = self.G[blk]
                for e in (0, 1):  # normal force at end e
                    arm = (ct.points[e] - g) / self.L
                    A[r, 3 * c + e] += sgn * n[0]
                    A[r + 1, 3 * c + e] += sgn * n[1]
                    A[r + 2, 3 * c + e] += sgn * (arm[0] * n[1] - arm[1] * n[0])
                arm = (ct.points[0] - g) / self.L  # the shear's line of action is the joint
                A[r, 3 * c + 2] += sgn * t[0]
                A[r + 1, 3 * c + 2] += sgn * t[1]
                A[r + 2, 3 * c + 2] += sgn * (arm[0] * t[1] - arm[1] * t[0])
        # horizontal loads d k w_b; weights -w_b moved to the right-hand side
        A[0::3, -1] = self.d * self.w
        b = np.zeros(3 * nb)
        b[1::3] = self.w
        self.A_eq, self.b_eq = A, b
        bounds = []
        for _ in range(nc):
            bounds += [(0, None), (0, None), (None, None)]
        bounds.append((None, None))
        self.bounds = bounds
        self.friction = friction
        self.mu, self.coh = _contact_strengths(arc, friction)
        rows, rhs = [], []
        for c in np.flatnonzero(np.isfinite(self.mu)):
            for s in (1.0, -1.0):  # s V - mu (N0 + N1) <= c L (per W)
                row = np.zeros(nv)
                row[3 * c + 2] = s
                row[3 * c] = row[3 * c + 1] = -self.mu[c]
                rows.append(row)
                rhs.append(self.coh[c])
        if rows:
            self.A_ub, self.b_ub = np.array(rows), np.array(rhs)
        else:
            self.A_ub = self.b_ub = None
        self.c = np.zeros(nv)
        self.c[-1] = -1.0

    def point_velocity(self, v: np.ndarray, blk: int, p: np.ndarray) -> np.ndarray:
        """Velocity of point p [m] of block blk (ground: 0) for block velocities v (nb, 3) with
        omega per L (the dual's units)."""
        if blk == GROUND:
            return np.zeros(2)
        r = (p - self.G[blk]) / self.L
        return np.array([v[blk, 0] - v[blk, 2] * r[1], v[blk, 1] + v[blk, 2] * r[0]])

    def relative(self, v: np.ndarray, c: int):
        """(normal (2,), tangential (2,)) relative velocity of block b to block a at the two
        ends of contact c."""
        ct = self.arc.contacts[c]
        dn, dt = np.empty(2), np.empty(2)
        for e in (0, 1):
            p = ct.points[e]
            dv = self.point_velocity(v, ct.b, p) - self.point_velocity(v, ct.a, p)
            dn[e] = dv @ self.normals[c]
            dt[e] = dv @ self.tangents[c]
        return dn, dt

    def compat_rows(self, c: int, what: str, end: int = 0, slip_sign: float = 0.0,
                    point=None):
        """Rows R (k, 3 nb) with R v = 0 for contact c: 'closed' (no relative motion at both
        ends), 'hinge' (none at end ``end``, or at ``point`` [m] where given), 'slide' (no
        relative normal velocity at both ends, or the associated dilatancy dn = mu |dt| with
        friction)."""
        ct = self.arc.contacts[c]
        n, t = self.normals[c], self.tangents[c]
        rows = []

        def vel_row(p, direction):
            row = np.zeros(3 * self.nb)
            for blk, sgn in ((ct.b, 1.0), (ct.a, -1.0)):
                if blk == GROUND:
                    continue
                r = (p - self.G[blk]) / self.L
                row[3 * blk] += sgn * direction[0]
                row[3 * blk + 1] += sgn * direction[1]
                row[3 * blk + 2] += sgn * (-r[1] * direction[0] + r[0] * direction[1])
            return row
        if what == "closed":
            for e in (0, 1):
                rows += [vel_row(ct.points[e], n), vel_row(ct.points[e], t)]
        elif what == "hinge":
            p = ct.points[end] if point is None else np.asarray(point, float)
            rows += [vel_row(p, n), vel_row(p, t)]
        elif what == "slide":
            mu = float(self.mu[c]) if np.isfinite(self.mu[c]) else 0.0
            for e in (0, 1):
                rows.append(vel_row(ct.points[e], n) - mu * slip_sign * vel_row(ct.points[e], t))
        return rows


def _contact_strengths(arc: Arcade, friction: float | None):
    """(mu, c) per contact: its own Coulomb coefficient, else ``friction`` (nan: no sliding),
    and its cohesion times its length per total weight (the Coulomb row's right-hand side)."""
    W = float(np.sum(arc.masses)) * G
    mu = np.full(len(arc.contacts), np.nan if friction is None else float(friction))
    coh = np.zeros(len(arc.contacts))
    for c, ct in enumerate(arc.contacts):
        if ct.friction is not None:
            mu[c] = ct.friction
            coh[c] = ct.cohesion * float(np.hypot(*(ct.points[1] - ct.points[0]))) / W
    return mu, coh


def _friction_words(arc: Arcade, mu: float | None) -> str:
    """The method's words on friction: the analysis's, and the contacts' own."""
    own = [c for c, ct in enumerate(arc.contacts) if ct.friction is not None]
    out = ""
    if mu is not None:
        out += (f"; Coulomb friction mu = {mu:g} at every contact"
                + (" without its own" if own else "") + " (associated flow)")
    if own:
        mus = sorted({arc.contacts[c].friction for c in own})
        cmax = max(arc.contacts[c].cohesion for c in own)
        out += (f"; {len(own)} contacts with their own friction (mu {mus[0]:g}"
                + (f" to {mus[-1]:g}" if len(mus) > 1 else "")
                + (f", cohesion up to {cmax / 1e3:g} kPa" if cmax > 0 else "")
                + ", associated flow)")
    return out


def _solve(prog: _Program):
    res = linprog(prog.c, A_ub=prog.A_ub, b_ub=prog.b_ub, A_eq=prog.A_eq, b_eq=prog.b_eq,
                  bounds=prog.bounds, method="highs")
    return res


def graph_multiplier(arc: Arcade, direction: str, friction: float | None = None) -> float:
    """The LP's optimum k alone (module docstring); under finite strength the lower bound of
    its bracket (:mod:`archrock.statics.graphcrush`)."""
    prog = _Program(arc, direction, None if friction is None else check_friction(friction))
    if arc.finite_strength:
        from .graphcrush import crushing_bracket

        return crushing_bracket(prog, direction, _check_status)[1][0]
    res = _solve(prog)
    _check_status(res, direction, prog)
    return float(res.x[-1])


def _check_status(res, direction, prog: _Program):
    """Raise where the program has no optimum, naming the block or contact that explains it
    where one does (:mod:`archrock.statics.graphdiagnose`)."""
    if res.status not in (2, 3):
        if res.status != 0:
            raise CannotStandError(f"arcade: no set of contact forces holds the blocks in "
                                   f"direction {direction!r} (linear program status "
                                   f"{res.status}: {res.message}); it cannot stand")
        return
    from .graphdiagnose import diagnose, input_mistake

    mistake = input_mistake(prog.arc)  # the arcade itself is wrong: say what to change
    if mistake is not None:
        raise ArchInputError(mistake)
    why = diagnose(prog, res.status)
    if res.status == 3:
        raise NoMechanismError(f"arcade: no mechanism opens under horizontal loads in direction "
                               f"{direction!r} (the static program is unbounded"
                               + (f": {why})" if why else ")"))
    raise CannotStandError(f"arcade: no set of contact forces holds the blocks in direction "
                           f"{direction!r}: " + (why or "the linear program is infeasible, "
                                                 "though every block alone can be held")
                           + "; it cannot stand")


def _classify(prog: _Program, v: np.ndarray, tol: float):
    """Hinges, lift-off, sliding and closed contacts of block velocities v."""
    hinges, lift, slide, closed, slip_sign = [], [], [], [], {}
    for c in range(prog.nc):
        dn, dt = prog.relative(v, c)
        opened = dn > tol
        slid = np.abs(dt) > tol
        mu = float(prog.mu[c]) if np.isfinite(prog.mu[c]) else None
        # sliding: with friction the associated flow (dn = mu |dt| at both ends), without it
        # a tangential motion of a closed joint (which the dual excludes: kept for safety)
        if slid.any() and ((mu is not None and np.all(np.abs(dn - mu * np.abs(dt)) <= tol))
                           or (mu is None and not opened.any())):
            slide.append(c)
            slip_sign[c] = float(np.sign(dt[np.argmax(np.abs(dt))]))
            continue
        if opened.all():
            lift.append(c)
        elif opened.any():
            hinges.append((c, int(np.flatnonzero(~opened)[0])))
        else:
            closed.append(c)
    return hinges, lift, slide, closed, slip_sign


def graph_limit(arc: Arcade, direction: str, friction: float | None = None) -> GraphLimit:
    """k, the mechanism and its virtual-work check for one direction (module docstring).
    ``friction``: Coulomb coefficient mu of every contact (None: no sliding)."""
    mu = None if friction is None else check_friction(friction)
    prog = _Program(arc, direction, mu)
    if arc.finite_strength:
        return _graph_limit_crushing(prog, direction, mu)
    res = _solve(prog)
    _check_status(res, direction, prog)
    k = float(res.x[-1])
    y = np.asarray(res.eqlin.marginals, float).reshape(prog.nb, 3)
    # the dual's sign: the velocities under which no contact end closes
    cands = []
    for v in (-y, y):
        worst = min(float(np.min(prog.relative(v, c)[0])) for c in range(prog.nc))
        cands.append((worst, v))
    v = max(cands, key=lambda t: t[0])[1]
    scale = _velocity_scale(prog, v)
    if scale == 0.0:
        raise NoMechanismError(f"arcade: the static program's dual gives no motion in direction "
                               f"{direction!r}")
    tol = VELOCITY_TOL * scale
    hinges, lift, slide, closed, slip_sign = _classify(prog, v, tol)
    mech = _rebuild(prog, direction, v, hinges, lift, slide, closed, slip_sign)
    k_vw = mech.multiplier
    W = float(np.sum(arc.masses)) * G
    forces = res.x[:-1].reshape(prog.nc, 3) * W
    how = ("static LP on the graph of blocks (scipy HiGHS); mechanism from its dual (hinges "
           "where a contact opens at one end), rebuilt from its hinges and confirmed by its "
           f"virtual work (|k_vw - k| = {abs(k_vw - k):.1e})")
    how += _friction_words(prog.arc, mu)
    return GraphLimit(direction, k, k_vw, mech, forces, mu, how)


def _graph_limit_crushing(prog: _Program, direction: str, mu) -> GraphLimit:
    """:func:`graph_limit` under finite compressive strength: the bracket of
    :mod:`archrock.statics.graphcrush`, the mechanism from its lower bound's dual with each
    hinge at the thrust's crossing (the stress block's centre where f_c is finite, the edge
    itself where it is not), so that the contact forces do no work on it."""
    from .graphcrush import classify, crushing_bracket

    res, bounds, rounds, rows = crushing_bracket(prog, direction, _check_status)
    x = res.x
    k = float(x[-1])
    v = -np.asarray(res.eqlin.marginals, float).reshape(prog.nb, 3)
    if np.sum(prog.d * prog.w * v[:, 0]) < 0:  # the sign under which the loads do work
        v = -v
    scale = _velocity_scale(prog, v)
    if scale == 0.0:
        raise NoMechanismError(f"arcade: the static program's dual gives no motion in direction "
                               f"{direction!r}")
    hinges, lift, slide, closed, slip_sign = classify(prog, v, VELOCITY_TOL * scale)
    points, ends = {}, []
    for c, e in hinges:
        n0, n1 = float(x[3 * c]), float(x[3 * c + 1])
        if np.isfinite(prog.arc.contact_fc[c]) and n0 + n1 > 0:
            p0, p1 = prog.arc.contacts[c].points
            t = n1 / (n0 + n1)
            points[c] = p0 + t * (p1 - p0)
            e = 0 if t < 0.5 else 1
        ends.append((c, e))
    mech = _rebuild(prog, direction, v, ends, lift, slide, closed, slip_sign, points)
    k_vw = mech.multiplier
    forces = x[:-1].reshape(prog.nc, 3) * rows.W
    how = (f"static LP on the graph of blocks with the stress block at every contact of finite "
           f"f_c (a bracket of linear programs, scipy HiGHS: tangent planes above, chords below, "
           f"{rounds} round{'s' if rounds != 1 else ''}, k in [{bounds[0]:.9g}, "
           f"{bounds[1]:.9g}]); mechanism from the lower bound's dual, its hinges at the stress "
           f"blocks' centres, confirmed by its virtual work (|k_vw - k| = {abs(k_vw - k):.1e})")
    how += _friction_words(prog.arc, mu)
    return GraphLimit(direction, k, k_vw, mech, forces, mu, how, bounds, rows.zones(x))


def _rebuild(prog: _Program, direction: str, v: np.ndarray, hinges, lift, slide, closed,
             slip_sign, points=None) -> GraphMechanism:
    """The mechanism from its hinges alone (the null space of the compatibility conditions),
    nearest the dual's velocities ``v``, scaled to unit horizontal work; its virtual-work k.
    ``points``: {contact: (x, y) [m]} hinge points off the contact's ends (a stress block's
    centre under finite strength)."""
    points = points or {}
    # the mechanism from its hinges alone: the null space of the compatibility conditions
    rows = []
    for c in closed:
        rows += prog.compat_rows(c, "closed")
    for c, e in hinges:
        rows += prog.compat_rows(c, "hinge", e, point=points.get(c))
    for c in slide:
        rows += prog.compat_rows(c, "slide", slip_sign=slip_sign[c])
    nv = 3 * prog.nb
    C = np.array(rows) if rows else np.zeros((0, nv))
    if C.shape[0] < nv:  # square it with zero rows: the thin SVD then gives every direction
        C = np.vstack([C, np.zeros((nv - C.shape[0], nv))])
    _, s, vt = np.linalg.svd(C, full_matrices=False)
    rank = int(np.sum(s > 1e-9 * (s[0] if s.size else 1.0)))
    null = vt[rank:]
    dof = null.shape[0]
    vflat = v.reshape(-1)
    if dof == 0:
        raise NoMechanismError(f"arcade: the hinges read from the dual in direction "
                               f"{direction!r} leave no motion")
    # the mechanism in the null space nearest to the dual's velocities
    coef, *_ = np.linalg.lstsq(null.T, vflat, rcond=None)
    vm = (null.T @ coef).reshape(prog.nb, 3)
    work_h = float(np.sum(prog.d * prog.w * vm[:, 0]))
    if abs(work_h) <= 1e-12 * max(1.0, float(np.abs(vm).max())):
        raise NoMechanismError(f"arcade: the mechanism in direction {direction!r} does no work "
                               f"against the horizontal loads")
    vm = vm / work_h
    # the weights' rise, plus what cohesion dissipates wherever a contact slips, open or
    # closed (c L |slip|: the tangential relative velocity is the same all along a joint)
    k_vw = float(np.sum(prog.w * vm[:, 1])) + sum(
        prog.coh[c] * float(np.abs(prog.relative(vm, c)[1][0]))
        for c in np.flatnonzero(prog.coh > 0))
    # the velocities in SI: v of the mass centres [m/s], omega [rad/s] (per unit work rate)
    vel = np.column_stack([vm[:, 0], vm[:, 1], vm[:, 2] / prog.L])
    moving = tuple(int(i) for i in np.flatnonzero(
        np.abs(vm).max(axis=1) > VELOCITY_TOL * float(np.abs(vm).max())))
    contacts = prog.arc.contacts
    gh = tuple(GraphHinge(c, e, contacts[c].place(e),
                          None if c not in points else tuple(float(p) for p in points[c]))
               for c, e in hinges)
    return GraphMechanism(direction, gh, tuple(lift), tuple(slide), moving, vel, dof, k_vw)


def _velocity_scale(prog: _Program, v: np.ndarray) -> float:
    """The largest velocity of any block's vertex (dual units)."""
    best = 0.0
    for i, b in enumerate(prog.arc.blocks):
        r = (np.asarray(b.outline, float) - prog.G[i]) / prog.L
        vx = v[i, 0] - v[i, 2] * r[:, 1]
        vy = v[i, 1] + v[i, 2] * r[:, 0]
        best = max(best, float(np.max(np.hypot(vx, vy))))
    return best


def mechanism_velocities(arc: Arcade, hinges, lift_off=()) -> np.ndarray:
    """The motions of ``arc`` (in its present configuration) in which every contact is closed
    except the ``hinges`` ((contact, end), ...: no relative motion at that end only) and the
    ``lift_off`` contacts (free): a basis of that null space, (dof, n_blocks, 3), each row the
    blocks' (v_x, v_y) of their mass centres [m/s] and omega [rad/s], scaled to a largest
    |omega| of 1 rad/s (or |v| of 1 m/s where nothing turns).  dof = 1 for the mechanism of a
    four-link-like model; more where the hinges leave the blocks several independent motions.

    This is the kinematics a one-degree-of-freedom model of an arcade needs at each step (the
    hinges' points move with the blocks: rebuild the arcade in the displaced configuration and
    call it again), and the candidate set a multi-span impact law would choose from
    (docs/arcades.md)."""
    prog = _Program(arc, "l", None)
    hinge_set = {(int(c), int(e)) for c, e in hinges}
    free = {int(c) for c in lift_off} | {c for c, _ in hinge_set}
    for c, e in hinge_set:
        if not 0 <= c < prog.nc or e not in (0, 1):
            raise ArchInputError(f"hinges: ({c}, {e}); allowed (contact 0 to {prog.nc - 1}, "
                                 f"end 0 or 1)")
    rows = []
    for c in range(prog.nc):
        if c not in free:
            rows += prog.compat_rows(c, "closed")
    for c, e in sorted(hinge_set):
        rows += prog.compat_rows(c, "hinge", e)
    nv = 3 * prog.nb
    C = np.array(rows) if rows else np.zeros((0, nv))
    if C.shape[0] < nv:
        C = np.vstack([C, np.zeros((nv - C.shape[0], nv))])
    _, sv, vt = np.linalg.svd(C, full_matrices=False)
    rank = int(np.sum(sv > 1e-9 * (sv[0] if sv.size and sv[0] > 0 else 1.0)))
    out = []
    for row in vt[rank:]:
        v = row.reshape(prog.nb, 3).copy()
        v[:, 2] /= prog.L  # omega in rad/s
        big = np.abs(v[:, 2]).max()
        v /= big if big > 1e-12 * np.abs(v[:, :2]).max() else np.abs(v[:, :2]).max()
        out.append(v)
    return np.array(out).reshape(len(out), prog.nb, 3)


def generalized_mass(arc: Arcade, velocities: np.ndarray) -> float:
    """sum_b m_b |v_b|^2 + I_b omega_b^2 [kg m^2 per m of depth, for velocities per unit rate]:
    the M(phi) of a one-degree-of-freedom equation of motion (twice the kinetic energy per unit
    rate squared), as the four-link model's M for its three links."""
    v = np.asarray(velocities, float).reshape(arc.n_blocks, 3)
    return float(np.sum(arc.masses * (v[:, 0] ** 2 + v[:, 1] ** 2))
                 + np.sum(arc.inertias * v[:, 2] ** 2))


def generalized_loads(arc: Arcade, velocities: np.ndarray) -> tuple[float, float]:
    """(Q, H) [N m per m of depth, for velocities per unit rate]: Q = g sum_b m_b v_y,b, the
    rate at which the mechanism lifts the weights, and H = g sum_b m_b v_x,b, the rate at which
    a horizontal ground acceleration of 1 g (toward -x: the loads toward +x) works on it.  The
    mechanism's one-degree-of-freedom equation at this configuration is M theta'' = lambda H - Q
    for a load factor lambda (:func:`generalized_mass` gives M), so it starts at lambda = Q / H,
    the virtual-work k."""
    v = np.asarray(velocities, float).reshape(arc.n_blocks, 3)
    m = np.asarray(arc.masses, float)
    return float(G * np.sum(m * v[:, 1])), float(G * np.sum(m * v[:, 0]))
