"""Response of an arch to a ground motion: activation, rocking, impacts, rest or collapse.

Data flow: geometry -> limit analysis (k_l, k_r, M_l, M_r) -> four-link equations -> impact law
-> :func:`respond`.  :func:`prepare` does everything that depends on the arch alone (reuse it for
many ground motions); :func:`respond` integrates one ground motion with either

* ``integrator="fast"``: fixed-step RK4 with event location (:mod:`archrock.dynamics.kernel`, compiled
  by numba when installed), or
* ``integrator="reference"``: scipy's adaptive DOP853 with event location at tight tolerances.

Both follow the same rules (docs/method.md, Response and Impact): the arch starts from rest when
xg''/g <= -k_l (M_l) or xg''/g >= k_r (M_r); when phi returns to 0 the joints close (an impact)
and the opposite mechanism opens with the rate given by the impact law; a post-impact rate below
``v_rest`` means the arch is at rest again (no endless chattering).  The collapse time is the
last upward passage of the open mechanism's unstable position phi_u (F = 0) before phi reaches
the rotation limit: from then on the arch never comes back below phi_u.  The limit itself, well
past phi_u, is only where the integration stops (``t_limit``), so ``limit_factor`` moves
``t_limit`` but not ``t_collapse``.  Integration continues after the ground motion until rest or
the limit.
The signed response is +phi while M_l is open, -phi while M_r is open and 0 at rest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple
from functools import cached_property

import numpy as np
from scipy.integrate import solve_ivp

from . import kernel as K
from .._jit import HAVE_NUMBA
from .._records import readonly_arrays
from ..errors import ArchInputError, LimitExceededError
from ..geometry import VoussoirArch
from ..groundmotion import G, GroundMotion
from .impact import ImpactLaw, ImpactSpec, impact_law
from ..statics.limit import LimitResult, limit_analysis, require_four_hinge
from .finite import collapse_zones
from .chain import least_loss_chain, pack_chains, rotation_limit
from .fourlink import FourLink, exact_acceleration, four_link, rest_rate
from .piers import SingleDofCheck, single_dof_check

__all__ = ["DynamicModel", "Event", "Response", "prepare", "respond", "default_steps",
           "time_scale"]

_MODE_NAME = {0: "rest", 1: "l", 2: "r"}
MAX_SAMPLES = 10_000_000  # output samples of one response (80 MB)
_KIND_NAME = {K.EV_ACTIVATION: "activation", K.EV_IMPACT: "impact", K.EV_REST: "rest",
              K.EV_COLLAPSE: "collapse", K.EV_UNSTABLE: "unstable", K.EV_LIMIT: "limit"}


@dataclass(frozen=True, eq=False)
class DynamicModel:
    """Everything about an arch's dynamics that does not depend on the ground motion.

    phi_limit_* [rad]: rotation limits, where the integration of a collapse stops (past them the
    collapse is certain; its time is the last passage of phi_unstable); phi_unstable_* [rad]:
    unstable positions (F = 0); v_rest [rad/s]: post-impact rates below it end the motion.
    """

    arch: VoussoirArch
    limit: LimitResult
    mech_l: FourLink
    mech_r: FourLink
    impact: ImpactLaw
    phi_limit_l: float
    phi_limit_r: float
    v_rest: float
    #: extra mechanisms opened after impacts, as (FourLink, rotation limit) (least-loss law)
    extra: tuple = ()
    #: per mechanism of the chain (M_l, M_r, extra...): (row opened at its closing, rate ratio);
    #: empty means the paper's alternation M_l <-> M_r with the impact law's ratios
    transitions: tuple = ()

    @property
    def chain(self) -> tuple[list, list, list]:
        """(mechanisms, rotation limits, [(next row, rate ratio)]): rows 0 and 1 are M_l, M_r."""
        mechs = [self.mech_l, self.mech_r] + [fl for fl, _ in self.extra]
        lims = [self.phi_limit_l, self.phi_limit_r] + [lim for _, lim in self.extra]
        trans = list(self.transitions) or [(1, self.impact.l_to_r), (0, self.impact.r_to_l)]
        return mechs, lims, trans

    @property
    def k_l(self) -> float:
        return self.limit.k_l

    @property
    def k_r(self) -> float:
        return self.limit.k_r

    @property
    def phi_unstable_l(self) -> float:
        return self.mech_l.phi_unstable

    @property
    def phi_unstable_r(self) -> float:
        return self.mech_r.phi_unstable

    def mechanism(self, mode: str | int) -> FourLink:
        """The mechanism of chain row ``mode`` (an int; rows 0 and 1 are M_l and M_r), or of
        direction 'l' / 'r' (the limit mechanisms M_l / M_r)."""
        if isinstance(mode, (int, np.integer)) and not isinstance(mode, bool):
            mechs = self.chain[0]
            if not 0 <= mode < len(mechs):
                raise ArchInputError(f"mechanism row: {mode!r}; allowed 0..{len(mechs) - 1}")
            return mechs[int(mode)]
        if mode not in ("l", "r"):
            raise ArchInputError(f"mechanism: {mode!r}; allowed 'l', 'r' or a chain row "
                                 f"0..{len(self.chain[0]) - 1}")
        return self.mech_l if mode == "l" else self.mech_r

    @property
    def labels(self) -> list[str]:
        """Compact hinge label of every row of the chain ('0i-3e-5i-7e', ...)."""
        return [_label(fl) for fl in self.chain[0]]

    def chain_dicts(self) -> list[dict]:
        """The chain as plain data: per row its direction, hinges, label, rotation limit and
        unstable rotation [rad], the row it opens at its closing and the rate ratio."""
        mechs, lims, trans = self.chain
        return [{"row": j, "direction": fl.direction,
                 "hinges": [h.to_dict() for h in fl.mechanism.hinges] if fl.mechanism else [],
                 "label": _label(fl), "phi_limit": float(lim), "phi_unstable": fl.phi_unstable,
                 "opens": int(n), "rate_ratio": float(c)}
                for j, (fl, lim, (n, c)) in enumerate(zip(mechs, lims, trans))]

    @cached_property
    def single_dof(self) -> SingleDofCheck:
        """Whether one degree of freedom can follow this arch (:func:`~archrock.dynamics.piers.
        single_dof_check`): not where a limit mechanism moves a pier (issue 19; the numbers are
        computed as ever, this only says whether to trust them)."""
        return single_dof_check(self)

    @cached_property
    def tables(self) -> tuple[np.ndarray, ...]:
        """Geometry vectors with tables of M, L/M, F/M, P/M (fast integrator), one per mechanism
        of the chain (M_l, M_r, extra...)."""
        mechs, lims, _ = self.chain
        return tuple(fl.tabulated(lim) for fl, lim in zip(mechs, lims))

    @cached_property
    def steps(self) -> tuple[float, float]:
        """:func:`default_steps` of the arch: (dt, t_free) [s]."""
        return default_steps(self.arch)

    def _kernel_chain(self, tabulate: bool) -> tuple[np.ndarray, ...]:
        """The chain as the arrays :func:`kernel.simulate_chain` reads (rows, limits, unstable
        rotations, directions, next modes, rate ratios), packed once per model and form so that
        each :func:`respond` only passes them on.  Private: the kernel never writes into them
        (the tables are complete, no interval is left to build), but numba wants them
        writable."""
        packed = self._packed
        if tabulate not in packed:
            c = pack_chains([self.chain], rows=[self.tables] if tabulate else None)
            packed[tabulate] = (c["rows"][0], c["limit"][0], c["unstable"][0],
                                c["direction"][0], c["next"][0] + 1, c["ratio"][0])
        return packed[tabulate]

    @cached_property
    def _packed(self) -> dict:
        return {}

    @cached_property
    def _event_codes(self) -> dict:
        """(kind, mode before, mode after) of a kernel event -> the fields of its :class:`Event`
        that do not change from run to run; filled as codes come (:func:`_events`)."""
        return {}


def _event_code(model: DynamicModel, k: int, b: int, a: int) -> tuple:
    """(kind, before, after, energy ratio, row before, row after, label before, label after) of
    a kernel event of kind ``k`` from mode ``b`` to mode ``a`` (modes are chain rows + 1, 0 at
    rest)."""
    mechs, _, trans = model.chain
    name = ["rest"] + [fl.direction for fl in mechs]
    label = [None] + model.labels
    gain = None
    if k == K.EV_IMPACT:
        n, c = trans[b - 1]
        gain = 0.0
        if a == n + 1:  # kinetic energy after / before the impact (0: the arch came to rest)
            m0 = [fl.coefficients(0.0)[0] for fl in mechs]
            gain = c * c * m0[n] / m0[b - 1]
    return _KIND_NAME[k], name[b], name[a], gain, b - 1, a - 1, label[b], label[a]


def _events(model: DynamicModel, table: np.ndarray) -> tuple:
    """The :class:`Event` records of the kernel's event table (rows kind, time, mode before,
    mode after, rate before, rate after)."""
    codes = model._event_codes
    new = tuple.__new__
    events = []
    for k, t, b, a, rb, ra in table.tolist():
        c = codes.get((k, b, a))
        if c is None:
            c = codes[(k, b, a)] = _event_code(model, int(k), int(b), int(a))
        events.append(new(Event, (c[0], t, c[1], c[2], rb, ra, c[3], c[4], c[5], c[6], c[7])))
    return tuple(events)


def _label(fl: FourLink) -> str:
    return fl.mechanism.label if fl.mechanism is not None else f"M_{fl.direction}"


def prepare(arch: VoussoirArch, impact=None, *, cv: float | None = None,
            literal_cv: bool = False, limit_factor: float | None = None,
            limit: LimitResult | None = None, nominal: VoussoirArch | None = None) -> DynamicModel:
    """Limit analysis, four-link models and impact law of ``arch`` (any :class:`VoussoirArch`).

    impact: an :class:`~archrock.dynamics.impact.ImpactSpec`, or what :meth:`ImpactSpec.parse` reads: a
    model name ("paper", "momentum", "fixed" with ``cv``, "least-loss": the momentum law, each
    impact opening the admissible mechanism that keeps the most kinetic energy, Bisegna et al.
    2023), a number (a fixed c_v), or None: the paper's model (on ``nominal`` when given, else on
    ``arch``), the momentum law where the paper model cannot be used on that arch (it would
    create energy; ``model.impact.fallback`` then says so), whereas "paper" given by name
    refuses such an arch.  An :class:`ImpactLaw` is used as it is.  ``literal_cv`` applies a fixed c_v to the
    rates.  nominal: the study's nominal arch, on which a spec with ``on='nominal'`` is evaluated.
    limit_factor: rotation limit as a multiple of the unstable rotation (default: halfway to
    the four-bar's dead point, at most 2.5 times the unstable rotation); must be > 1.
    limit: the limit analysis of this very arch (skips computing it again).
    """
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch (Arch, PolygonArch), got "
                             f"{type(arch).__name__}")
    if limit is not None and not _same_arch(limit.arch, arch):
        raise ArchInputError("limit: it is the limit analysis of another arch; give the one of "
                             "this arch (or none: prepare computes it)")
    if isinstance(impact, ImpactLaw):
        spec = None
    else:
        spec = ImpactSpec.parse(impact, cv=cv, literal=literal_cv)
        if spec.on == "nominal" and spec.literal and nominal is None:
            nominal = arch  # a c_v to apply literally: the arch alone is its own nominal arch
        spec = spec.resolved(nominal)
    lim = limit_analysis(arch, verify=False) if limit is None else limit
    require_four_hinge(lim)
    # finite strength: the hinges at the centres of the stress blocks at collapse (None: edges)
    m_l = four_link(arch, lim.mechanism_l, collapse_zones(lim, "l"))
    m_r = four_link(arch, lim.mechanism_r, collapse_zones(lim, "r"))
    if spec is not None and spec.model == "least-loss":
        return _prepare_least_loss(arch, lim, m_l, m_r, limit_factor)
    # the default spec falls back to the momentum law where the paper model cannot be used
    # (spec.fallback); a fixed c_v resolved on such a nominal arch carries the reason (spec.note)
    law = impact if spec is None else impact_law(m_l, m_r, spec.model, cv=spec.cv,
                                                 literal=spec.literal, fallback=spec.fallback,
                                                 note=spec.note)
    pl_l, pl_r = rotation_limit(m_l, limit_factor), rotation_limit(m_r, limit_factor)
    v_rest = float(rest_rate(m_l.geo, m_l.phi_unstable, m_r.phi_unstable, G))
    return DynamicModel(arch, lim, m_l, m_r, law, pl_l, pl_r, v_rest)


def _same_arch(a, b) -> bool:
    """Whether two arches have the same contact segments and mass properties."""
    if a is b:
        return True
    return (type(a) is type(b) and a.n == b.n
            and all(np.array_equal(getattr(a, k), getattr(b, k))
                    for k in ("joint_points", "masses", "centroids", "inertias")))


def _prepare_least_loss(arch, lim, m_l, m_r, limit_factor) -> DynamicModel:
    """The model of the least-loss law over its chain (:func:`~archrock.dynamics.chain.
    least_loss_chain`): its impact law holds the first impacts out of M_l and M_r."""
    mechs, lims, trans = least_loss_chain(arch, m_l, m_r, limit_factor)
    m0 = [fl.coefficients(0.0)[0] for fl in mechs]
    (n_l, c_l), (n_r, c_r) = trans[0], trans[1]
    law = ImpactLaw("least-loss", c_l, c_r, c_l**2 * m0[n_l] / m0[0], c_r**2 * m0[n_r] / m0[1])
    v_rest = float(rest_rate(m_l.geo, m_l.phi_unstable, m_r.phi_unstable, G))
    return DynamicModel(arch, lim, m_l, m_r, law, lims[0], lims[1], v_rest,
                        tuple(zip(mechs[2:], lims[2:])), tuple(trans))


class Event(NamedTuple):
    """A discrete event: kind in {activation, impact, rest, unstable, collapse, limit}; time [s]
    (unstable: first upward passage of phi_u; collapse: the last one, after which phi never
    returns below phi_u; limit: the rotation limit reached, the end of the run);
    directions before/after ('l', 'r' or 'rest'); rates [rad/s] before/after, each in its own
    mechanism's coordinate (an impact's rate before is negative: the joints are closing);
    energy_ratio: for an impact, kinetic energy after / before (0 when the arch comes to rest);
    row_before/row_after: the open mechanism's row of :attr:`DynamicModel.chain` (-1 at rest);
    mechanism_before/mechanism_after: its hinge label ('0e-2i-5e-7i'; None at rest)."""

    kind: str
    time: float
    before: str
    after: str
    rate_before: float
    rate_after: float
    energy_ratio: float | None = None
    row_before: int = -1
    row_after: int = -1
    mechanism_before: str | None = None
    mechanism_after: str | None = None

    def to_dict(self) -> dict:
        return {"kind": self.kind, "time": self.time, "before": self.before, "after": self.after,
                "rate_before": self.rate_before, "rate_after": self.rate_after,
                "energy_ratio": self.energy_ratio, "row_before": self.row_before,
                "row_after": self.row_after, "mechanism_before": self.mechanism_before,
                "mechanism_after": self.mechanism_after}


@dataclass(frozen=True, eq=False)
class Response:
    """Result of :func:`respond`: what happened and how it was computed.

    time, response: the signed response (+phi in M_l, -phi in M_r, 0 at rest, NaN from the
    rotation limit) [rad] sampled every ``dt_out`` up to ``t_end``; peak: max phi over the whole
    run [rad]; t_collapse [s]: the last upward passage of the unstable position phi_u before the
    rotation limit (None without collapse), which the limit does not move; t_unstable [s]: the
    first passage of phi_u (None if never; the arch may come back); t_final [s]: when the run
    ended (at rest, or :attr:`t_limit` after a collapse); status: 'rest', 'collapsed' or
    'moving' (still rocking when the free-motion cap ran out).
    event_table: the integrator's events as rows (kind code, time [s], mode before, mode after,
    rate before, rate after [rad/s]); :attr:`events` reads them as :class:`Event` records.
    """

    model: DynamicModel = field(repr=False)
    motion: GroundMotion = field(repr=False)
    time: np.ndarray = field(repr=False)
    response: np.ndarray = field(repr=False)
    event_table: np.ndarray = field(repr=False)
    status: str
    peak: float
    t_collapse: float | None
    t_unstable: float | None
    t_final: float
    integrator: str
    settings: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def collapsed(self) -> bool:
        return self.status == "collapsed"

    @cached_property
    def events(self) -> tuple[Event, ...]:
        """The events of the run, in time order.  Decoded at the first use: a study that reads
        only the outcome should not pay for records it never reads (the paper's case has about a
        hundred events; making them took a quarter of the kernel's time)."""
        return _events(self.model, self.event_table)

    @property
    def t_limit(self) -> float | None:
        """When phi reached the rotation limit [s] (None without collapse): a numerical stop
        after :attr:`t_collapse`, which moves with ``prepare(..., limit_factor=...)``."""
        return self.t_final if self.collapsed else None

    @property
    def impacts(self) -> list[float]:
        return [e.time for e in self.events if e.kind == "impact"]

    @property
    def activated(self) -> bool:
        return any(e.kind == "activation" for e in self.events)

    @property
    def single_dof(self) -> SingleDofCheck:
        """Whether the four-link model can follow this arch (:attr:`DynamicModel.single_dof`)."""
        return self.model.single_dof

    @property
    def single_dof_valid(self) -> bool:
        """False where the piers rock with the arch: one degree of freedom cannot follow the
        contact engine there (``single_dof.reason`` says why; docs/piers-dynamics.md)."""
        return self.model.single_dof.valid

    def impacts_before_collapse(self) -> int:
        return len(self.impacts) if self.collapsed else 0

    def rows_at(self, t) -> np.ndarray:
        """Row of :attr:`DynamicModel.chain` open at time(s) ``t`` [s]: the row after the last
        event at or before t; -1 at rest and from the rotation limit on, where the response is
        NaN (int array shaped like t)."""
        t = np.asarray(t, dtype=float)
        ev_t = np.array([e.time for e in self.events], dtype=float)
        ev_row = np.array([-1 if e.kind == "limit" else e.row_after for e in self.events]
                          + [-1], dtype=np.int64)
        # index -1 (before the first event) picks the trailing -1: at rest
        return ev_row[np.searchsorted(ev_t, t, side="right") - 1]

    @cached_property
    def rows(self) -> np.ndarray:
        """Row of the chain open at each output sample (:meth:`rows_at` of ``time``)."""
        rows = self.rows_at(self.time)
        rows.setflags(write=False)
        return rows

    def mechanisms_opened(self) -> list[tuple[float, int, str]]:
        """(time [s], row, label) of every mechanism opened (activations and impacts)."""
        return [(e.time, e.row_after, e.mechanism_after) for e in self.events
                if e.kind in ("activation", "impact") and e.row_after >= 0]

    def to_dict(self, samples: bool = True) -> dict:
        d = {
            "collapsed": self.collapsed,
            "status": self.status,
            "t_collapse": self.t_collapse,
            "t_limit": self.t_limit,
            "t_unstable": self.t_unstable,
            "t_final": self.t_final,
            "peak": self.peak,
            "impacts": self.impacts,
            "k_l": self.model.k_l,
            "k_r": self.model.k_r,
            "restitution": {"model": self.model.impact.model, "l_to_r": self.model.impact.l_to_r,
                            "r_to_l": self.model.impact.r_to_l,
                            "energy_l_to_r": self.model.impact.energy_l_to_r,
                            "energy_r_to_l": self.model.impact.energy_r_to_l,
                            # None, or why the law is not the one asked for (the default's
                            # paper model cannot be used on this arch: momentum law used)
                            "fallback": self.model.impact.fallback},
            "phi_limit": {"l": self.model.phi_limit_l, "r": self.model.phi_limit_r},
            "phi_unstable": {"l": self.model.phi_unstable_l, "r": self.model.phi_unstable_r},
            "chain": self.model.chain_dicts(),
            # False, with the reason, where a limit mechanism moves a pier (issue 19)
            "single_dof_valid": self.single_dof_valid,
            "single_dof": self.single_dof.to_dict(),
            "events": [e.to_dict() for e in self.events],
            "integrator": self.integrator,
            "settings": self.settings,
        }
        if samples:
            d["time"] = self.time.tolist()
            d["response"] = [None if not math.isfinite(v) else float(v) for v in self.response]
        return d


#: RK4 step [s] and free-motion cap [s] of 0.1.0, kept for arches of a metre and more.
DEFAULT_DT, DEFAULT_T_FREE = 2e-3, 60.0


def time_scale(arch: VoussoirArch) -> float:
    """sqrt(R/g) [s] for R the arch's size (``arch.size``: the mean radius of a circular arch):
    times of similar arches scale with it."""
    return math.sqrt(float(arch.size) / G)


def default_steps(arch: VoussoirArch) -> tuple[float, float]:
    """(dt, t_free) [s] for ``arch``: 2e-3 s and 60 s, but dt at most T/100 and t_free at least
    50 T with T = :func:`time_scale` (a step of 2e-3 s is a whole rocking arc of a 1 mm arch,
    and 60 s is a few free arcs of a 1 km one); unchanged for 0.4 m <= R <= 14 m."""
    T = time_scale(arch)
    return min(DEFAULT_DT, T / 100.0), max(DEFAULT_T_FREE, 50.0 * T)


def _check_times(t_end, dt_out, dt, t_free):
    for name, v in (("t_end", t_end), ("dt_out", dt_out), ("dt", dt), ("t_free", t_free)):
        if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v) or v <= 0:
            raise ArchInputError(f"{name}: {v!r}; allowed a finite number > 0 s")
    if dt_out > t_end:
        raise ArchInputError(f"dt_out: {dt_out} s; allowed <= t_end = {t_end} s")
    if t_end / dt_out > MAX_SAMPLES:
        raise ArchInputError(f"t_end: {t_end:g} s at dt_out = {dt_out:g} s is {t_end / dt_out:.3g} "
                             f"output samples; allowed at most {MAX_SAMPLES:,} (raise dt_out)")


def respond(arch_or_model: VoussoirArch | DynamicModel, motion: GroundMotion, *, impact=None,
            cv: float | None = None, t_end: float = 3.0, dt_out: float = 0.005,
            integrator: str = "fast", dt: float | None = None, t_free: float | None = None,
            rtol: float = 1e-10, atol: float = 1e-12, max_events: int = 100_000,
            tabulate: bool = True) -> Response:
    """Response of an arch (or a prepared :class:`DynamicModel`) to ``motion``.

    t_end [s]: end of the sampled output (the outcome covers the whole ground motion and the free
    motion after it, at most ``t_free`` seconds); dt_out [s]: output sampling; dt [s]: RK4 step
    of the fast integrator.  Default dt and t_free (None) follow the arch's size (see
    :func:`default_steps`): 2e-3 s and 60 s for arches of metres and more, as in 0.1.0, a step
    at most T/100 and a free motion at least 50 T for T = sqrt(R/g).
    rtol/atol: tolerances of the reference integrator; tabulate: the fast
    integrator reads phi'' from tables (relative error ~2e-9) instead of the exact
    loop closure (the reference always uses the exact one).
    """
    model = arch_or_model if isinstance(arch_or_model, DynamicModel) else prepare(arch_or_model, impact, cv=cv)
    if not isinstance(motion, GroundMotion):
        raise ArchInputError(f"motion: expected a GroundMotion, got {type(motion).__name__}")
    dt0, t_free0 = model.steps
    dt = dt0 if dt is None else dt
    t_free = t_free0 if t_free is None else t_free
    _check_times(t_end, dt_out, dt, t_free)
    n_out = int(math.floor(t_end / dt_out + 1e-9)) + 1
    times = np.ascontiguousarray(motion.times, dtype=float)
    accel = np.ascontiguousarray(motion.accel, dtype=float)
    settings = {"t_end": t_end, "dt_out": dt_out, "t_free": t_free}
    if integrator == "fast":
        res = K.simulate_chain(*model._kernel_chain(bool(tabulate)), model.k_l, model.k_r,
                               model.v_rest, times, accel, G, n_out, dt_out, dt, t_free,
                               max_events)
        settings.update(dt=dt, tabulated=tabulate, method="RK4 fixed step with event location"
                        + (" (numba)" if HAVE_NUMBA else " (pure Python)"))
    elif integrator == "reference":
        res = _reference(model, times, accel, n_out, dt_out, t_free, rtol, atol, max_events)
        settings.update(rtol=rtol, atol=atol, method="scipy solve_ivp DOP853 with events")
    else:
        raise ArchInputError(f"integrator: {integrator!r}; allowed 'fast' or 'reference'")
    out, ev, n_ev, status, t_final, peak, t_col, t_uns = res
    if n_ev > max_events:
        raise LimitExceededError(f"max_events: more than {max_events} events; raise max_events")
    return Response(model, motion, np.arange(n_out) * dt_out, out, ev[:n_ev],
                    {K.ST_REST: "rest", K.ST_COLLAPSED: "collapsed", K.ST_MOVING: "moving"}[int(status)],
                    float(peak), None if t_col < 0 else float(t_col), None if t_uns < 0 else float(t_uns),
                    float(t_final), integrator, settings)


# ---------------------------------------------------------------------------- reference
class _Reference:
    """Adaptive reference integrator (scipy DOP853), same rules as :func:`kernel.simulate_chain`:
    the record's state (sampled output, events, peak, times of instability and collapse)."""

    def __init__(self, model: DynamicModel, times, accel, n_out, dt_out, t_free, rtol, atol):
        self.model, self.times, self.accel, self.rtol, self.atol = model, times, accel, rtol, atol
        self.mechs, self.lims, self.trans = model.chain
        self.out = np.zeros(n_out)
        self.ev = []
        self.t_motion = times[-1]
        self.t_stop = self.t_motion + t_free
        self.grid = np.arange(n_out) * dt_out
        self.thr_l, self.thr_r = -model.k_l * G, model.k_r * G
        # segments with positive length, plus the free motion after the record
        self.seg_j = [j for j in range(times.size - 1) if times[j + 1] > times[j]]
        self.peak, self.t_col, self.t_uns = 0.0, -1.0, -1.0
        # last upward passage of the open mechanism's phi_u (each arc starts at phi = 0 < phi_u)
        self.t_up, self.w_up = -1.0, 0.0

    def a_of(self, t, j):
        if j < 0:
            return 0.0
        return K._accel(t, j, self.times, self.accel)

    def segments_from(self, t):
        """(j, t_start, t_end) pieces from t on; j = -1 is the free motion after the record."""
        for j in self.seg_j:
            if self.times[j + 1] > t:
                yield j, max(t, self.times[j]), self.times[j + 1]
        yield -1, max(t, self.t_motion), self.t_stop

    def first_activation(self, t):
        """(time [s], segment, mode) of the first activation from rest at t, None if none."""
        thr_l, thr_r = self.thr_l, self.thr_r
        for j, t0, t1 in self.segments_from(t):
            if j < 0:
                return None
            a0, a1 = self.a_of(t0, j), self.accel[j + 1]
            if a0 < thr_l:  # strictly: at the threshold phi = 0 is in equilibrium
                return t0, j, 1
            if a0 > thr_r:
                return t0, j, 2
            if a1 < thr_l:
                return t0 + (t1 - t0) * (thr_l - a0) / (a1 - a0), j, 1
            if a1 > thr_r:
                return t0 + (t1 - t0) * (thr_r - a0) / (a1 - a0), j, 2
        return None

    def fill(self, t0, t1, sol_fun, sign, value=None):
        """The output samples in [t0, t1): ``value``, or sign x phi from ``sol_fun``."""
        mask = (self.grid >= t0) & (self.grid < t1)
        if value is not None:
            self.out[mask] = value
        elif np.any(mask):
            self.out[mask] = sign * sol_fun(self.grid[mask])[0]

    def solve(self, j, t0, t1, phi, w, geo, lim, phu):
        """One piece of an arc: solve_ivp from (phi, w) at t0 to t1 or a terminal event."""
        def rhs(tt, y):
            return [y[1], exact_acceleration(y[0], y[1], self.a_of(tt, j), G, geo)]

        def close(tt, y):
            # phi = 0 exactly at the start of an arc is not a closure: only a return to 0
            return y[0] if tt > t0 else 1.0
        close.terminal, close.direction = True, -1

        def turning(tt, y):
            return y[1]
        turning.terminal, turning.direction = False, -1

        def limit_ev(tt, y):
            return y[0] - lim
        limit_ev.terminal, limit_ev.direction = True, 1

        def unstable_ev(tt, y):
            return y[0] - phu
        unstable_ev.terminal, unstable_ev.direction = False, 1

        return solve_ivp(rhs, (t0, t1), [phi, w], method="DOP853", rtol=self.rtol, atol=self.atol,
                         events=(close, limit_ev, unstable_ev, turning), dense_output=True,
                         first_step=min(1e-4, (t1 - t0) / 2))

    def note(self, sol, mode):
        """The instability's passages and the peak met by one solved piece of an arc."""
        if sol.t_events[2].size:
            if self.t_uns < 0:
                self.t_uns = float(sol.t_events[2][0])
                self.ev.append((K.EV_UNSTABLE, self.t_uns, mode, mode,
                                float(sol.y_events[2][0][1]), float(sol.y_events[2][0][1])))
            # the last upward passage so far (events past a terminal one are not listed)
            self.t_up, self.w_up = float(sol.t_events[2][-1]), float(sol.y_events[2][-1][1])
        # the true maximum is at a turning point (phi' = 0), not at a solver node
        self.peak = max(self.peak, float(np.max(sol.y[0])),
                        max((float(y[0]) for y in sol.y_events[3]), default=0.0))

    def arc(self, mode, t, phi, w):
        """Follow mechanism ``mode`` from t: (how it ended: 'collapse', 'impact' or None, t, w)."""
        fl, lim = self.mechs[mode - 1], self.lims[mode - 1]
        sign = 1.0 if fl.direction == "l" else -1.0
        for j, t0, t1 in self.segments_from(t):
            if t0 >= self.t_stop:
                break
            sol = self.solve(j, t0, t1, phi, w, fl.geo, lim, fl.phi_unstable)
            self.note(sol, mode)
            self.fill(t0, sol.t[-1], sol.sol, sign)
            if sol.status == 1 and sol.t_events[1].size:
                return "collapse", float(sol.t_events[1][0]), float(sol.y_events[1][0][1])
            if sol.status == 1 and sol.t_events[0].size:
                return "impact", float(sol.t_events[0][0]), float(sol.y_events[0][0][1])
            if sol.status != 0:
                raise RuntimeError(f"reference integrator failed: {sol.message}")
            t, phi, w = t1, float(sol.y[0, -1]), float(sol.y[1, -1])
        return None, t, w

    def collapse(self, mode, t, w):
        """Record the collapse of ``mode``, whose limit rotation is reached at t with rate w."""
        # certain since the last upward passage of phi_u; the limit only ends the run
        self.t_col = self.t_up if self.t_up >= 0 else t
        if self.t_uns < 0:
            self.t_uns = self.t_col
        self.peak = max(self.peak, self.lims[mode - 1])
        self.ev.append((K.EV_COLLAPSE, self.t_col, mode, mode, self.w_up, self.w_up))
        self.ev.append((K.EV_LIMIT, t, mode, mode, w, 0.0))
        self.fill(t, np.inf, None, 1.0, np.nan)

    def impact(self, mode, t, w):
        """The impact closing ``mode`` at t with rate w: the next (mode, phi, w), 0 at rest."""
        w_minus = min(w, 0.0)
        nxt, ratio = self.trans[mode - 1]
        w_plus = -ratio * w_minus
        if w_plus < self.model.v_rest:
            self.ev.append((K.EV_IMPACT, t, mode, 0, w_minus, 0.0))
            self.ev.append((K.EV_REST, t, mode, 0, 0.0, 0.0))
            return 0, 0.0, 0.0
        new = nxt + 1
        self.ev.append((K.EV_IMPACT, t, mode, new, w_minus, w_plus))
        return new, 0.0, w_plus

    def run(self, max_events):
        """Integrate the record: (out, event table, events, status, t_final, peak, t_col, t_uns)."""
        t, mode, phi, w = 0.0, 0, 0.0, 0.0
        while True:
            if mode == 0:
                act = self.first_activation(t)
                if act is None:
                    self.fill(t, np.inf, None, 1.0, 0.0)
                    t, status = max(t, self.t_motion), K.ST_REST
                    break
                t_act, _, mode = act
                self.fill(t, t_act, None, 1.0, 0.0)
                t, phi, w = t_act, 0.0, 0.0
                self.ev.append((K.EV_ACTIVATION, t, 0, mode, 0.0, 0.0))
                continue
            ended, t, w = self.arc(mode, t, phi, w)
            if ended is None:
                status = K.ST_MOVING
                break
            if ended == "collapse":
                self.collapse(mode, t, w)
                status = K.ST_COLLAPSED
                break
            mode, phi, w = self.impact(mode, t, w)
            if len(self.ev) > max_events:
                status = K.ST_REST
                break
        table = np.array(self.ev, dtype=float).reshape(-1, 6)
        return (self.out, table, len(self.ev), status, t, self.peak, self.t_col, self.t_uns)


def _reference(model: DynamicModel, times, accel, n_out, dt_out, t_free, rtol, atol, max_events):
    """Adaptive reference integrator (scipy DOP853), same rules as :func:`kernel.simulate_chain`."""
    ref = _Reference(model, times, accel, n_out, dt_out, t_free, rtol, atol)
    return ref.run(max_events)
