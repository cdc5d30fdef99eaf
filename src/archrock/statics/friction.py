"""Limit analysis with Coulomb friction at the joints: the horizontal-load multiplier when the
joints may slide as well as hinge, the friction the no-sliding (Heyman) collapse needs, and the
friction-limited minimum thickness.

Any :class:`~archrock.geometry.VoussoirArch` (circular, polygon, families, with loads, tilted
joints).  The static problem is :mod:`archrock.statics.lp`'s linear program on the redundants
x = (F0x, F0y, M0, lambda) (forces per total weight W) with two more rows per joint.  Across
joint j the part on its left transmits F_j; with u_j the unit vector along the joint's contact
segment (intrados end -> extrados end) and nu_j = (u_y, -u_x) its compressive normal,

    N_j = F_j . nu_j  (normal force, compression > 0),   T_j = F_j . u_j  (shear along the joint),

and Coulomb's condition |T_j| <= mu N_j is  T_j - mu N_j <= 0  and  -T_j - mu N_j <= 0, linear in
x.  With the no-tension rows (the thrust crosses every contact segment) the largest lambda is the
multiplier with friction.  It is the *associative* answer (a Coulomb cone with normality, i.e.
sliding with dilatancy); with non-associative friction it is not a guaranteed lower bound, see
docs/friction.md.

Public API (for the reports, the assess report and the contact engine):

* :func:`friction_analysis` (arch, mu) -> :class:`FrictionResult`: per direction the multiplier
  with friction, the frictionless one, whether sliding governs, |T|/N at every joint of the
  thrust line found, the joints that need the most friction, the friction needed.
* :func:`friction_needed` (arch) -> {"l": mu_l, "r": mu_r} (a :class:`FrictionNeeded`, a dict
  with ``reasons``): the friction coefficient the frictionless collapse needs.  Definition: the
  smallest mu whose friction multiplier equals the frictionless one, i.e. the minimum, over every
  statically admissible state at the frictionless collapse multiplier, of the largest |T_j|/N_j.
  Where the collapse state is unique (a four-hinge mechanism through which exactly one thrust
  line passes) this is the largest |T|/N along that thrust line; where it is not, the least
  demanding admissible thrust line counts.  Found to a relative tolerance of 1e-10 with at most
  ~55 LPs per direction; None, with a reason, where no mechanism loads the arch or where it
  needs more than MU_CAP = 1000 ("no finite friction": a joint must carry shear with almost no
  normal force, e.g. a springing about to lift off).
* :func:`friction_minimum_thickness` (arch, mu) -> :class:`~archrock.statics.limit.MinimumThickness`:
  the smallest thickness standing under self-weight (lambda = 0) with friction mu;
  CannotStandError when no thickness stands (mu below the friction that sliding alone needs).

Direction 'l': horizontal loads toward +x (M_l); 'r': toward -x (M_r), as in :mod:`archrock.statics.limit`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linprog

from .._records import readonly_arrays
from ..errors import ArchInputError, CannotStandError, LimitExceededError, NoMechanismError
from ..geometry import VoussoirArch
from .hinges import DIRECTIONS
from .lp import ThrustLine, _statics, _Statics, _thrust_from_x
from .thickness import MinimumThickness, thickness_bisection

__all__ = ["DEFAULT_FRICTION", "FrictionDirection", "FrictionResult", "FrictionNeeded", "friction_analysis",
           "friction_needed", "friction_minimum_thickness", "joint_shear_normal", "thrust_friction",
           "check_friction", "MU_CAP", "NO_FINITE_FRICTION", "NO_MECHANISM"]

#: The Coulomb friction coefficient of masonry joints that every archrock analysis uses unless
#: the user states another (``--friction MU``): the limit analysis with friction, the routing of
#: the dynamics (the four-link model assumes no sliding) and the contact engine alike, so that a
#: report states one coefficient.  0.8 is within the range measured on dry and mortared stone
#: joints (about 0.6-0.8) and above what the thrust of the documented arches needs (Oppenheim's
#: arch 0.495); EN 1996-1-1's 0.4 is a design shear coefficient: pass it for a conservative check.
DEFAULT_FRICTION = 0.8

# A joint "needs the most friction" when its |T|/N is within this of the largest (absolute:
# ratios are friction coefficients, O(0.1-1)).
_CRITICAL_TOL = 1e-6
# Relative tolerance on multipliers to call sliding governing (LP optima are good to ~1e-12).
_GOVERNS_TOL = 1e-9
# Margin below which a state is taken as inadmissible in the least-friction bisection
# (nondimensional, per W and per W L): well above HiGHS's rounding, far below any physical margin.
_MARGIN_TOL = 1e-10
# A multiplier whose frictionless margin is below this is beyond the limit (not rounding).
_INADMISSIBLE = 1e-8
# Bisection of the least friction: relative tolerance on mu (an absolute one never ends where
# mu is large: one ulp of 1e7 is 2e-9), with an absolute floor below which a friction
# coefficient is zero for every purpose.
_MU_RTOL = 1e-10
_MU_ATOL = 1e-12
#: The largest friction coefficient reported as a number.  Masonry joints have mu ~ 0.4-0.8
#: (about 1 for rough dry stone); a state needing |T|/N > 1000 has a joint whose normal force is
#: below 1/1000 of its shear, i.e. a thrust within 0.06 deg of the joint's own line (a springing
#: about to lift off, N -> 0 with T != 0).  No material supplies that: "no finite friction".
MU_CAP = 1e3
#: The bisection from MU_CAP to the tolerances takes log2(MU_CAP / _MU_ATOL) ~ 50 LPs; this
#: bound is never reached by the arithmetic, it only turns a solver pathology into an error.
_MAX_BISECTIONS = 100
#: The first words of :attr:`FrictionNeeded.reasons` (and of the JSON's
#: ``friction_needed_reason_l``/``_r``) for the two cases with no number.
NO_FINITE_FRICTION = "no finite friction"
NO_MECHANISM = "no mechanism"
# HiGHS's default feasibility tolerance (1e-7) would accept rows violated by up to 1e-7, i.e.
# a margin of -1e-7 reads as 0 and the least friction comes out ~1e-7 too low: the margin
# programs run at the tightest tolerances HiGHS takes.
_TIGHT = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}


def check_friction(mu, name: str = "friction") -> float:
    """mu as a float, or ArchInputError naming ``name`` and the range (finite, > 0)."""
    try:
        v = float(mu)
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: expected a number, got {mu!r}; allowed a finite "
                             f"friction coefficient > 0") from None
    if not math.isfinite(v) or v <= 0:
        raise ArchInputError(f"{name}: {mu!r} is out of range; allowed a finite friction "
                             f"coefficient > 0")
    return v


def _check_arch(arch) -> None:
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch (Arch, PolygonArch), got "
                             f"{type(arch).__name__}")


def _frames(arch: VoussoirArch):
    """Unit vectors u (along each joint's contact segment, intrados -> extrados) and nu (the
    compressive normal, u turned clockwise), shape (n+1, 2) each."""
    jp = np.asarray(arch.joint_points, float)
    e = jp[:, 1] - jp[:, 0]
    L = np.hypot(e[:, 0], e[:, 1])
    if np.any(L == 0.0):  # point contacts (a displaced arch's open hinges): their direction
        e = np.where((L == 0.0)[:, None], np.asarray(arch.joint_directions, float), e)
        L = np.where(L == 0.0, 1.0, L)
    u = e / L[:, None]
    return u, np.column_stack([u[:, 1], -u[:, 0]])


def _force_rows(st: _Statics):
    """(A_N, b_N, A_T, b_T): N_j = A_N x + b_N and T_j = A_T x + b_T (per W), with
    F_j = (F0x + d lambda cw_j, F0y - cw_j)."""
    u, nu = _frames(st.arch)
    cw, d = st.cw, st.d
    zero = np.zeros(cw.size)

    def rows(v):
        return np.column_stack([v[:, 0], v[:, 1], zero, d * cw * v[:, 0]]), -v[:, 1] * cw

    A_N, b_N = rows(nu)
    A_T, b_T = rows(u)
    return A_N, b_N, A_T, b_T


class _FrictionStatics:
    """The static program of one arch and direction with Coulomb rows at friction mu:
    ``A x <= b`` with the no-tension rows of :func:`archrock.statics.lp._statics` first, then
    T - mu N <= 0 and -T - mu N <= 0 for every joint."""

    def __init__(self, arch: VoussoirArch, direction: str):
        self.st = _statics(arch, direction)
        self.A_N, self.b_N, self.A_T, self.b_T = _force_rows(self.st)

    def rows(self, mu: float | None):
        st = self.st
        if mu is None:
            return st.A_ub, st.b_ub
        A = np.vstack([st.A_ub, self.A_T - mu * self.A_N, -self.A_T - mu * self.A_N])
        b = np.concatenate([st.b_ub, mu * self.b_N - self.b_T, mu * self.b_N + self.b_T])
        return A, b

    def shear_normal(self, x):
        return self.A_T @ x + self.b_T, self.A_N @ x + self.b_N

    def max_lambda(self, mu: float | None):
        """(status, x): the largest lambda with friction mu (None: frictionless)."""
        A, b = self.rows(mu)
        # frictionless: the very program of limit.static_multiplier (same numbers)
        res = linprog(c=[0, 0, 0, -1.0], A_ub=A, b_ub=b, bounds=[(None, None)] * 4,
                      method="highs", options={} if mu is None else _TIGHT)
        return res.status, (res.x if res.status == 0 else None)

    def margin(self, lam: float, mu: float | None):
        """(s, x): the largest common slack s <= 1 of every row at multiplier ``lam``: s >= 0
        where a state admissible with friction mu exists (deciding on the sign of an optimum,
        not on the solver's feasibility verdict, as :func:`archrock.statics.lp._stands`)."""
        A, b = self.rows(mu)
        # unknowns (F0x, F0y, M0, s); lambda fixed
        A_s = np.column_stack([A[:, :3], np.ones(A.shape[0])])
        b_s = b - A[:, 3] * lam
        res = linprog(c=[0, 0, 0, -1.0], A_ub=A_s, b_ub=b_s,
                      bounds=[(None, None)] * 3 + [(None, 1.0)], method="highs",
                      options=_TIGHT)
        if res.status != 0:
            return -math.inf, None
        return float(res.x[3]), np.append(res.x[:3], lam)

    def ratios(self, x):
        T, N = self.shear_normal(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(N > 0, np.abs(T) / np.where(N > 0, N, 1.0),
                         np.where(np.abs(T) > 0, math.inf, 0.0))
        return r

    def least_friction(self, lam: float, x_hint=None, mu_hi: float | None = None):
        """(mu, x): the smallest friction coefficient for which a state admissible at
        multiplier ``lam`` exists (the least, over those states, of max |T|/N), and that state.
        ``x_hint``: an admissible state at ``lam`` (its largest ratio brackets the answer);
        ``mu_hi``: a friction known to be enough.  Bisection on the sign of :meth:`margin`, to
        a relative tolerance of 1e-10 on mu (floor 1e-12), at most ~55 LPs; one or two LPs when
        the state is unique (the hint's ratio is then the answer).

        mu is math.inf (x None) where no state at all is admissible at ``lam``, and None where
        every admissible state needs more than :data:`MU_CAP` (x: the best state known, which
        needs more; "no finite friction")."""
        s0, x0 = self.margin(lam, None)
        if s0 < -_INADMISSIBLE:
            return math.inf, None
        # admissible with friction: the Coulomb rows cost no margin below the frictionless one
        # where that is ~0 (lam at its limit, rounded either way), or keep it >= 0 otherwise
        thr = min(s0, 0.0) - _MARGIN_TOL
        hi, x_hi = math.inf, x0
        for x in (x_hint, x0):
            if x is not None:
                r = float(np.max(self.ratios(x)))
                if r < hi:
                    hi, x_hi = r, x
        if mu_hi is not None and mu_hi < hi:
            s, x = self.margin(lam, mu_hi)
            if s >= thr:
                hi, x_hi = mu_hi, x
        if hi > MU_CAP:
            # one program decides: is any admissible state content with mu = MU_CAP?
            s, x = self.margin(lam, MU_CAP)
            if s < thr:
                return None, x_hi
            hi, x_hi = MU_CAP, x
        if hi <= _MU_ATOL:
            return hi, x_hi
        # the state is usually unique: then nothing below the hint's ratio is admissible
        lo = hi * (1 - 1e-7)
        s, x = self.margin(lam, lo)
        if s < thr:
            return hi, x_hi
        hi, x_hi, lo = lo, x, 0.0
        for _ in range(_MAX_BISECTIONS):
            if hi - lo <= max(_MU_RTOL * hi, _MU_ATOL):
                break
            mid = 0.5 * (lo + hi)
            s, x = self.margin(lam, mid)
            if s >= thr:
                hi, x_hi = mid, x
            else:
                lo = mid
        else:
            raise LimitExceededError(
                f"friction needed: the bisection on mu did not reach its tolerance in "
                f"{_MAX_BISECTIONS} linear programs (bracket [{lo:.17g}, {hi:.17g}]); the "
                f"solver's margins are inconsistent for this arch")
        # report the friction the state found actually needs (<= hi)
        return min(hi, float(np.max(self.ratios(x_hi)))), x_hi


class FrictionNeeded(dict):
    """{"l": mu_l, "r": mu_r} as :func:`friction_needed` returns it (each a float, or None),
    with ``reasons``: {"l": str or None, "r": ...}, why a direction has no number (it begins
    with :data:`NO_FINITE_FRICTION` or :data:`NO_MECHANISM`; None beside a number)."""

    def __init__(self, values: dict, reasons: dict):
        super().__init__(values)
        self.reasons = dict(reasons)


@dataclass(frozen=True)
class FrictionDirection:
    """Friction analysis of one direction.

    mu: the friction coefficient; multiplier: the largest horizontal-load multiplier with
    Coulomb friction mu and no tension (associative, see the module docstring); frictionless:
    the static multiplier without friction (:func:`archrock.statics.limit.static_multiplier`);
    sliding_governs: friction lowers the multiplier (multiplier < frictionless);
    friction_needed: the friction the frictionless collapse needs (:func:`friction_needed`),
    None with ``friction_needed_reason`` where there is no number (no mechanism, or no finite
    friction: more than :data:`MU_CAP`).
    ratios: |T_j|/N_j at every joint 0..n of the least-friction admissible state at
    ``multiplier`` (the one drawn as ``thrust``); shear, normal: T_j, N_j per total weight
    (T along the joint from its intrados end to its extrados end, force of the left part on
    the right one; N > 0 in compression); joints: the joints whose |T|/N is the largest (within
    1e-6), where that thrust needs the most friction (the sliding joints when sliding governs).
    """

    direction: str
    mu: float
    multiplier: float
    frictionless: float
    sliding_governs: bool
    friction_needed: float | None
    joints: tuple[int, ...]
    ratios: np.ndarray
    shear: np.ndarray
    normal: np.ndarray
    thrust: ThrustLine = field(repr=False)
    friction_needed_reason: str | None = None

    def __post_init__(self):
        readonly_arrays(self)

    def to_dict(self) -> dict:
        return {"direction": self.direction, "mu": self.mu, "multiplier": self.multiplier,
                "frictionless": self.frictionless, "sliding_governs": self.sliding_governs,
                "friction_needed": self.friction_needed,
                "friction_needed_reason": self.friction_needed_reason,
                "joints": list(self.joints),
                "ratios": self.ratios.tolist(), "shear": self.shear.tolist(),
                "normal": self.normal.tolist(), "points": self.thrust.points.tolist()}


@dataclass(frozen=True)
class FrictionResult:
    """Result of :func:`friction_analysis`: both directions at friction ``mu``."""

    arch: VoussoirArch = field(repr=False)
    mu: float
    l: FrictionDirection  # noqa: E741 - the package's name for the direction
    r: FrictionDirection
    method: str = ("static LP (HiGHS) with no-tension and Coulomb rows |T| <= mu N at every "
                   "joint (associative friction)")

    def direction(self, d: str) -> FrictionDirection:
        return self.l if d == "l" else self.r

    @property
    def k(self) -> float:
        """The smaller multiplier with friction."""
        return min(self.l.multiplier, self.r.multiplier)

    def to_dict(self) -> dict:
        return {"mu": self.mu, "k": self.k, "l": self.l.to_dict(), "r": self.r.to_dict(),
                "method": self.method}


def _state(fs: _FrictionStatics, direction: str, mu: float, lam: float, lam0: float,
           needed: float | None, reason: str | None, x) -> FrictionDirection:
    """The record of one direction; ``x``: the least-friction admissible state at ``lam``."""
    ratios = fs.ratios(x)
    T, N = fs.shear_normal(x)
    top = float(np.max(ratios))
    joints = tuple(int(j) for j in np.flatnonzero(ratios >= top - _CRITICAL_TOL))
    governs = not math.isfinite(lam0) or lam < lam0 - _GOVERNS_TOL * max(1.0, abs(lam0))
    return FrictionDirection(direction, mu, float(lam), float(lam0), bool(governs), needed, joints,
                             ratios, T, N, _thrust_from_x(fs.st, x), reason)


def _no_finite_reason(fs: _FrictionStatics, lam0: float, x) -> str:
    """Why the collapse at ``lam0`` needs more than MU_CAP: the joint of state ``x`` (the best
    one found) with the largest |T|/N, its N and T."""
    T, N = fs.shear_normal(x)
    j = int(np.argmax(fs.ratios(x)))
    scale = max(1.0, float(np.max(np.abs(T[j]))))
    n_j = 0.0 if abs(N[j]) < 1e-12 * scale else float(N[j])  # rounding noise of a zero
    return (f"{NO_FINITE_FRICTION}: every admissible state at the collapse multiplier "
            f"{lam0:.4f} needs |T|/N > {MU_CAP:g} at some joint; the one found carries "
            f"N = {n_j:.3g} W and T = {T[j]:.3g} W at joint {j} (its thrust runs along the "
            f"joint: about to lift off or slide, whatever the friction)")


def _needed(fs: _FrictionStatics):
    """(friction needed, reason, frictionless multiplier, state x) of one direction; needed is
    None, with a reason, where no mechanism loads the arch (unbounded multiplier) or where no
    finite friction (<= MU_CAP) suffices."""
    d = "l" if fs.st.d > 0 else "r"
    status, x0 = fs.max_lambda(None)
    if status == 3:
        return (None, f"{NO_MECHANISM}: no horizontal load opens a mechanism in direction "
                      f"{d!r} (unbounded multiplier), so no friction is needed", math.inf, None)
    if status != 0:
        raise CannotStandError(f"arch: no line of thrust fits inside the arch for direction "
                               f"{d!r}; the arch cannot stand")
    lam0 = float(x0[3])
    mu, x = fs.least_friction(lam0, x0)
    if mu is None or not math.isfinite(mu):
        return None, _no_finite_reason(fs, lam0, x if x is not None else x0), lam0, x0
    return float(mu), None, lam0, (x if x is not None else x0)


def friction_needed(arch: VoussoirArch) -> FrictionNeeded:
    """{"l": mu_l, "r": mu_r}: the friction coefficient the frictionless (Heyman) collapse
    needs in each direction: the minimum over the statically admissible states at the
    frictionless collapse multiplier of the largest |T_j|/N_j, to a relative tolerance of
    1e-10.  None where no mechanism loads the arch, and None where it needs more than
    :data:`MU_CAP` (no finite friction suffices); ``.reasons`` says which.  Equal to the
    smallest mu at which :func:`friction_analysis` gives the frictionless multiplier."""
    _check_arch(arch)
    out, why = {}, {}
    for d in DIRECTIONS:
        out[d], why[d], _, _ = _needed(_FrictionStatics(arch, d))
    return FrictionNeeded(out, why)


def _self_weight_friction(arch: VoussoirArch) -> float:
    """The least friction with which the arch stands under self-weight (lambda = 0)."""
    fs = _FrictionStatics(arch, "l")
    mu, _ = fs.least_friction(0.0)
    return math.inf if mu is None else mu


def friction_analysis(arch: VoussoirArch, mu: float) -> FrictionResult:
    """Multipliers with Coulomb friction ``mu`` (> 0) at every joint, both directions, beside
    the frictionless ones and the friction those need.  CannotStandError where the arch cannot
    stand under its own weight with this friction (the message gives the friction it needs)."""
    _check_arch(arch)
    mu = check_friction(mu)
    out = {}
    lams = {}
    for d in DIRECTIONS:
        fs = _FrictionStatics(arch, d)
        needed, reason, lam0, _ = _needed(fs)
        # solved even where mu >= needed (then it returns lam0): the two stay independent checks
        status, x = fs.max_lambda(mu)
        if status == 3:  # unbounded even with friction
            raise NoMechanismError(f"arch: no mechanism opens in direction {d!r} even with "
                                   f"friction {mu:g}: the multiplier is unbounded")
        if status != 0:
            lams[d] = -math.inf
            continue
        lam = float(x[3])
        _, xs = fs.least_friction(lam, x, mu)
        out[d] = (fs, lam, lam0, needed, reason, x if xs is None else xs)
        lams[d] = lam
    if min(lams.values()) < 0:
        need = _self_weight_friction(arch)
        needs = (f"at least {need:.4f}" if math.isfinite(need) else
                 f"more than {MU_CAP:g}: no finite friction lets it stand")
        ks = ", ".join(f"k_{d} = {lams[d]:.4g}" if math.isfinite(lams[d]) else
                       f"none in direction {d!r}" for d in DIRECTIONS)
        raise CannotStandError(
            f"arch: with friction {mu:g} it cannot stand under its own weight: its joints slide "
            f"(largest multipliers with friction: {ks}); it needs a friction coefficient of "
            f"{needs}")
    dirs = {d: _state(fs, d, mu, *rest) for d, (fs, *rest) in out.items()}
    return FrictionResult(arch, mu, dirs["l"], dirs["r"])


def _stands_with_friction(mu: float):
    def stands(arch: VoussoirArch) -> bool:
        s, _ = _FrictionStatics(arch, "l").margin(0.0, mu)
        return s >= 0.0
    return stands


def friction_minimum_thickness(arch: VoussoirArch, mu: float,
                               tol: float = 1e-7) -> MinimumThickness:
    """Smallest thickness (common factor on every voussoir, as
    :func:`archrock.statics.limit.minimum_thickness`) at which the arch stands under self-weight with
    Coulomb friction ``mu`` and no tension.  CannotStandError when no thickness the arch allows
    stands with this friction (the joints slide whatever the thickness).  ``tol``: relative
    tolerance on the thickness factor, 0 < tol < 0.5 (the bisection takes ~log2(1e6 / tol)
    steps after at most ~log2 of the largest factor doublings)."""
    _check_arch(arch)
    mu = check_friction(mu)
    # thickness_bisection checks tol (1e-15 <= tol < 0.5) and bounds its steps
    return thickness_bisection(
        arch, _stands_with_friction(mu), tol,
        cannot=f"arch: no thickness stands under its own weight with friction {mu:g}: the joints "
               f"slide at every thickness the arch allows (raise the friction coefficient)")


def joint_shear_normal(arch: VoussoirArch, thrust: ThrustLine) -> tuple[np.ndarray, np.ndarray]:
    """(T, N) at every joint of ``thrust`` (per total weight): T along the joint from its
    intrados end to its extrados end, N normal, compression > 0; |T|/N is the friction the
    thrust line needs there."""
    u, nu = _frames(arch)
    f = np.asarray(thrust.forces, float)
    return np.einsum("ij,ij->i", f, u), np.einsum("ij,ij->i", f, nu)


def thrust_friction(arch: VoussoirArch, thrusts) -> dict:
    """{"l": mu, "r": mu}: the largest |T|/N over the pressed joints of each direction's line
    of thrust (``thrusts``: {"l": ThrustLine, "r": ThrustLine}).  Where the collapse state is
    unique (four hinges: one degree of freedom) this is the friction the collapse needs; the
    finite-strength collapse (statics.crushing) takes it from its own thrust line, which
    Heyman's :func:`friction_needed` (no crushing) does not see."""
    out = {}
    for d in DIRECTIONS:
        T, N = joint_shear_normal(arch, thrusts[d])
        pressed = N > 1e-12 * max(1.0, float(np.abs(N).max()))
        out[d] = float(np.max(np.abs(T[pressed]) / N[pressed]))
    return out

