"""The fill's passive pressure on the extrados of a bridge arch, in limit analysis.

A family arch's fill (:func:`~archrock.geometry.family_arch`, ``fill={"level", "density"}``)
is, by default, dead weight only: the soil above each voussoir rides on it as a load, so it adds
weight and horizontal inertia and nothing else.  Where the arch sways into the soil, the soil
resists: this module adds, as an option, the horizontal pressure

    p(z) = kappa K_p gamma z,   K_p = (1 + sin phi) / (1 - sin phi)   (Rankine's passive
    coefficient),

z [m] the depth below the fill's surface, gamma = rho g its unit weight, phi its friction angle
and kappa the stated fraction of the full passive pressure that the small movements of a
collapsing arch mobilise (RING's "mobilised passive pressure": Gilbert, RING theory manual;
Gilbert 2007, "Limit analysis applied to masonry arch bridges: state-of-the-art and recent
developments", ARCH'07).  The pressure is a resistance, not a load: it does not grow with the
horizontal multiplier, and it acts only on the faces that the mechanism pushes into the soil.

The model.  Each voussoir's extrados is cut into its faces: the runs that rise to the right
(the soil on their left pushes them toward +x) and those that fall (pushed toward -x).  Face p
carries at most its full mobilised resultant R_p (per unit total weight), at the height of the
pressure's centroid; the static program of :mod:`archrock.statics.lp` ("joint-line" form) gains
one unknown per face, the fraction f_p in [0, 1] of R_p that the soil exerts, entering the
prefix sums of forces and moments like the weights do.  The largest multiplier over both the
redundants and the f_p is the lower bound with the soil free to push anywhere between nothing
(an arch moving away from it) and its mobilised limit.  By duality f_p = 1 on every face the
mechanism drives into the soil and f_p = 0 on every face that leaves it: the fixed point of
"load the side that moves into the fill, re-solve, repeat", found in one program rather than by
iteration (so it always settles).  The mechanism is read from the program's dual, and its own
virtual work, the pressure's (negative) work included, gives the same multiplier
(:attr:`FillDirection.work_multiplier`).

Hypotheses: horizontal pressure only (no wall friction on the extrados), the soil's pressure on a
face mobilised as a whole (one fraction per face), out-of-plane depth 1 m, Heyman's hypotheses
for the masonry (no sliding, no crushing).  At kappa = 0 the answer is
:func:`~archrock.statics.limit.limit_analysis`'s, bit for bit (the same call).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog

from ..errors import ArchInputError, CannotStandError, NoMechanismError
from ..geometry import VoussoirArch
from .hinges import DIRECTIONS, Mechanism
from .liftoff import _DUAL_TOL, _kinematic_frame, _mechanism_of_rows, _row_terms
from .lp import ThrustLine, _JointLineStatics, _thrust_from_x
from .sums import _origin

__all__ = ["FillPressure", "FillDirection", "FillResult", "fill_pressure_analysis",
           "passive_coefficient", "DEFAULT_FILL_FRICTION_DEG"]

#: Default friction angle of the fill [deg]: a loose granular fill (Rankine's K_p = 3).
DEFAULT_FILL_FRICTION_DEG = 30.0
_G = 9.80665  # m/s^2; cancels in the multipliers (forces per unit weight), kept for kN/m


def passive_coefficient(phi_deg: float) -> float:
    """Rankine's passive earth-pressure coefficient K_p = (1 + sin phi) / (1 - sin phi)."""
    s = math.sin(math.radians(phi_deg))
    return (1.0 + s) / (1.0 - s)


@dataclass(frozen=True)
class FillPressure:
    """The fill's mobilised passive pressure: surface at y = ``level`` [m] (the arch's frame),
    ``density`` [kg/m^3], friction angle ``phi_deg`` [deg], mobilisation ``kappa`` (the
    fraction of the full passive pressure, >= 0)."""

    level: float
    density: float
    kappa: float
    phi_deg: float = DEFAULT_FILL_FRICTION_DEG

    def __post_init__(self):
        for name, v, lo, hi, allowed in (
                ("fill level", self.level, -math.inf, math.inf, "a finite y [m]"),
                ("fill density", self.density, 0.0, 1e5, "0 < rho <= 1e5 kg/m^3"),
                ("kappa", self.kappa, 0.0, 1e3, "0 <= kappa <= 1000 (a fraction of the full "
                                                "passive pressure)"),
                ("phi", self.phi_deg, 0.0, 89.0, "0 <= phi <= 89 deg")):
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) \
                    or not math.isfinite(v) or not lo <= v <= hi or (name == "fill density"
                                                                     and v <= 0):
                raise ArchInputError(f"{name}: {v!r}; allowed {allowed}")

    @property
    def K_p(self) -> float:
        return passive_coefficient(self.phi_deg)

    @classmethod
    def of(cls, arch: VoussoirArch, kappa: float,
           phi_deg: float = DEFAULT_FILL_FRICTION_DEG) -> "FillPressure":
        """The pressure of ``arch``'s own fill (a family arch's recipe); ArchInputError where it
        has none."""
        recipe = getattr(arch, "recipe", None) or {}
        fill = recipe.get("fill")
        if not fill:
            raise ArchInputError("fill: the arch has no fill (a family arch with "
                                 "fill={'level': y, 'density': rho}, or --fill-level with "
                                 "--shape/--span/--rise); the passive pressure needs one")
        return cls(float(fill["level"]), float(fill["density"]), kappa, phi_deg)


def _faces(arch: VoussoirArch, fp: FillPressure):
    """(voussoir (P,), sign (P,), resultant [N per m of depth] (P,), height y [m] (P,)) of each
    face of the extrados below the fill's surface: a run of segments whose y rises (sign +1,
    pushed toward +x) or falls (sign -1).  On a segment from y0 to y1 the horizontal pressure
    kappa K_p gamma (level - y) integrates over |dy|; its centroid's height follows."""
    extr = getattr(arch, "extrados", None)
    if extr is None:
        raise ArchInputError(f"arch: a {type(arch).__name__} has no extrados polylines; the "
                             f"fill's pressure needs a polygon or family arch")
    c = fp.kappa * fp.K_p * fp.density * _G
    out = []
    for i, e in enumerate(extr):
        e = np.asarray(e, float)
        y0 = np.minimum(e[:-1, 1], fp.level)
        y1 = np.minimum(e[1:, 1], fp.level)
        dy = y1 - y0
        z0, z1 = fp.level - y0, fp.level - y1
        # int (level - y) dy and int (level - y) y dy over each segment (signed by dy)
        f = (z0 * z0 - z1 * z1) / 2.0
        m = fp.level * (y1 ** 2 - y0 ** 2) / 2.0 - (y1 ** 3 - y0 ** 3) / 3.0
        for sign in (1.0, -1.0):
            on = sign * dy > 0.0
            force = sign * float(np.sum(f[on]))
            if force > 0.0:
                out.append((i, sign, c * force, float(np.sum(m[on]) / np.sum(f[on]))))
    if not out:
        return np.zeros(0, int), np.zeros(0), np.zeros(0), np.zeros(0)
    i, s, r, y = (np.array(v) for v in zip(*out))
    return i.astype(int), s, r, y


class _Pressed(_JointLineStatics):
    """The joint-line statics with the fill's forces of fixed size folded into the constant
    terms (for the line of thrust): ``fx`` (n+1,) the horizontal force the faces left of each
    joint add, dN and dm their share of N and m."""

    def __init__(self, arch, direction, fx, dN, dm):
        super().__init__(arch, direction)
        self.fx = fx
        self.b_N = self.b_N + dN
        self.b_m = self.b_m + dm
        self.b_ub = _rhs(self)


def _rhs(st) -> np.ndarray:
    """The right-hand sides of the joint-line rows (:class:`_JointLineStatics`'s order) from
    ``st``'s constant terms b_N and b_m."""
    b = np.concatenate([st.b_m, st.L * st.b_N - st.b_m])
    if st.point.any():
        b = np.concatenate([b, st.b_N[st.point]])
    return b

    def forces(self, x):
        out = super().forces(x)
        out[:, 0] += self.fx
        return out


@dataclass(frozen=True)
class FillDirection:
    """One direction with the fill's pressure: multiplier ``k`` (the program's optimum),
    ``work_multiplier`` (the mechanism's own virtual work, the pressure's included),
    ``mechanism`` (hinges from the dual), ``thrust`` (its line of thrust, the soil's forces
    included), and per face: ``voussoir``, ``sign`` (+1 pushed toward +x), ``resultant``
    [kN per m of depth, full mobilised], ``height`` [m], ``fraction`` (the optimum's f in
    [0, 1]) and ``work`` (the face's virtual work per unit fraction; < 0: the mechanism pushes
    it into the soil)."""

    direction: str
    k: float
    work_multiplier: float
    mechanism: Mechanism
    thrust: ThrustLine
    voussoir: np.ndarray
    sign: np.ndarray
    resultant: np.ndarray
    height: np.ndarray
    fraction: np.ndarray
    work: np.ndarray

    @property
    def loaded(self) -> tuple[int, ...]:
        """Voussoirs with a face the soil pushes (fraction above one half)."""
        return tuple(sorted({int(v) for v, f in zip(self.voussoir, self.fraction) if f > 0.5}))

    @property
    def consistent(self) -> bool:
        """Whether the loaded faces are exactly those the mechanism drives into the soil (the
        fixed point: full pressure where the work is negative, none where it is positive)."""
        scale = max(1e-300, float(np.max(np.abs(self.work), initial=0.0)))
        tol = 1e-7 * scale
        ok_in = np.all(self.fraction[self.work < -tol] > 1 - 1e-7)
        ok_out = np.all(self.fraction[self.work > tol] < 1e-7)
        return bool(ok_in and ok_out)


@dataclass(frozen=True)
class FillResult:
    """:func:`fill_pressure_analysis`: ``k0_l``, ``k0_r`` without the pressure
    (:func:`~archrock.statics.limit.limit_analysis`'s, bit for bit), ``k_l``, ``k_r`` with it,
    each direction's detail (``left``, ``right``; None at kappa = 0), the pressure."""

    pressure: FillPressure
    k0_l: float
    k0_r: float
    k_l: float
    k_r: float
    left: FillDirection | None
    right: FillDirection | None

    @property
    def k0(self) -> float:
        return min(self.k0_l, self.k0_r)

    @property
    def k(self) -> float:
        return min(self.k_l, self.k_r)

    def to_dict(self) -> dict:
        p = self.pressure
        out = {"kappa": p.kappa, "phi_deg": p.phi_deg, "K_p": p.K_p, "level": p.level,
               "density": p.density, "k0_l": self.k0_l, "k0_r": self.k0_r, "k_l": self.k_l,
               "k_r": self.k_r}
        for name, fd in (("l", self.left), ("r", self.right)):
            if fd is not None:
                out[f"mechanism_{name}"] = fd.mechanism.to_dict()
                out[f"work_multiplier_{name}"] = fd.work_multiplier
                out[f"loaded_{name}"] = list(fd.loaded)
        return out


def _solve(arch: VoussoirArch, direction: str, faces, W: float) -> FillDirection:
    """The static program with one fraction per face (module docstring), its mechanism and
    the mechanism's virtual work."""
    vi, sg, R, yh = faces
    st = _JointLineStatics(arch, direction)
    origin, ref = _origin(arch), arch.reference_length
    r = sg * R / W                       # signed horizontal force per unit weight, f = 1
    y = (yh - origin[1]) / ref
    py = -st.A_m[:, 0]                   # the joints' intrados ends
    nux = st.A_N[:, 0]
    n1 = arch.n + 1
    left = (vi[None, :] < np.arange(n1)[:, None]).astype(float)   # face left of joint j
    C = nux[:, None] * r[None, :] * left                            # its share of N_j
    D = r[None, :] * (y[None, :] - py[:, None]) * left             # of m_j (moment about P_in)
    L = st.L
    A = np.vstack([np.hstack([-st.A_m, -D]),
                   np.hstack([st.A_m - L[:, None] * st.A_N, D - L[:, None] * C])])
    if st.point.any():
        A = np.vstack([A, np.hstack([-st.A_N[st.point], -C[st.point]])])
    P = r.size
    c = np.zeros(4 + P)
    c[3] = -1.0
    res = linprog(c, A_ub=A, b_ub=_rhs(st), bounds=[(None, None)] * 4 + [(0.0, 1.0)] * P,
                  method="highs")
    if res.status == 3:
        raise NoMechanismError(f"arch: no mechanism opens under horizontal forces toward "
                               f"{'+x' if st.d > 0 else '-x'} with the fill's pressure")
    if res.status != 0:
        raise CannotStandError(f"arch: no line of thrust fits inside the arch with the fill's "
                               f"pressure (direction {direction!r}, linear program status "
                               f"{res.status}: {res.message})")
    x, f = res.x[:4], np.clip(res.x[4:], 0.0, 1.0)
    lam = float(x[3])
    fx = left @ (r * f)
    thrust = _thrust_from_x(_Pressed(arch, direction, fx, C @ f, D @ f), x)
    # each joint-end row's dual value is the rate of its relative rotation (liftoff.py)
    mu = -np.asarray(res.ineqlin.marginals, float)[:2 * n1]
    mu = np.where(mu > _DUAL_TOL * max(np.max(mu), 1e-300), mu, 0.0)
    wk, work_face = _virtual_work(arch, st.d, mu, vi, r, y, f)
    mech = _mechanism_of_rows(arch, np.flatnonzero(mu), direction, lam)
    return FillDirection(direction, lam, wk, mech, thrust, vi, sg, R / 1e3, yh, f,
                         work_face * W)


def _virtual_work(arch, d, mu, vi, r, y, f):
    """(multiplier, work of each face per unit fraction) of the mechanism whose rows turn at
    rates ``mu``: every voussoir's twist from the joints left of it, then the work of the
    weights, of the horizontal loads (d = +1 toward +x) and of the soil's forces, per unit
    weight."""
    w, g, Pj = _kinematic_frame(arch)
    T, joint, _, _ = _row_terms(w, g, Pj)
    n1 = arch.n + 1
    # twist of voussoir i about the statics' origin (vx, vy, omega): the rows of joints 0..i
    tw = np.stack([np.cumsum(np.bincount(joint, mu * T[k], minlength=n1))[:-1]
                   for k in range(3)], axis=1)
    vx_g = tw[:, 0] - tw[:, 2] * g[:, 1]
    vy_g = tw[:, 1] + tw[:, 2] * g[:, 0]
    work_face = r * (tw[vi, 0] - tw[vi, 2] * y)
    horizontal = d * float(w @ vx_g)
    # lambda * horizontal - sum w vy (the weights) + sum f work (the soil) = 0
    lam = (float(w @ vy_g) - float(work_face @ f)) / horizontal if horizontal > 0 else math.nan
    return lam, work_face


def fill_pressure_analysis(arch: VoussoirArch, kappa: float,
                           phi_deg: float = DEFAULT_FILL_FRICTION_DEG,
                           pressure: FillPressure | None = None,
                           base=None) -> FillResult:
    """Collapse multipliers of ``arch`` with its fill's mobilised passive pressure (module
    docstring): ``kappa`` the fraction of Rankine's full passive pressure, ``phi_deg`` the
    fill's friction angle [deg]; the fill is the arch's own (a family arch's recipe) unless
    ``pressure`` gives it (a :class:`FillPressure`, whose kappa and phi then win).  ``base``: a
    :class:`~archrock.statics.limit.LimitResult` of the arch already computed (the answer
    without the pressure).  kappa = 0 returns that answer, bit for bit."""
    from .limit import limit_analysis

    if getattr(arch, "fc", None) is not None:
        raise ArchInputError(f"fc: {arch.fc!r} MPa; the fill's passive pressure is computed "
                             f"under Heyman's hypotheses (infinite compressive strength): "
                             f"allowed fc None")
    fp = pressure if pressure is not None else FillPressure.of(arch, kappa, phi_deg)
    base = limit_analysis(arch, verify=True) if base is None else base
    if fp.kappa == 0.0:
        return FillResult(fp, base.k_l, base.k_r, base.k_l, base.k_r, None, None)
    faces = _faces(arch, fp)
    W = float(np.sum(np.asarray(arch.masses, float))) * _G
    out = {d: _solve(arch, d, faces, W) for d in DIRECTIONS}
    return FillResult(fp, base.k_l, base.k_r, out["l"].k, out["r"].k, out["l"], out["r"])
