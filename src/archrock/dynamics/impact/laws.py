"""Impact of the arch at phi = 0: the old mechanism closes, the opposite one opens.

Every model reduces to a rate ratio per direction, c = phi'+ / |phi'-|, each rate in its own
mechanism's coordinate (docs/method.md, Impact):

* ``"paper"`` (De Lorenzis, DeJong, Ochsendorf 2007, as used by the paper): five momentum
  equations written on the old links, impulses at the closing points A*, B*, C*, D* (the
  opposite edge of each old hinge's joint), post-impact velocities taken from the new mechanism
  voussoir by voussoir.  Refused with :class:`EnergyGainError` when it creates energy (with
  :class:`ImpactModelError` when a rate ratio is negative or the equations are singular), unless
  a ``fallback`` model is named (the default spec's ``"momentum"``): the arch then gets that law,
  and ``ImpactLaw.fallback`` says why.
* ``"momentum"``: impulses only at the hinges of the new mechanism; projecting the momentum
  balance on the new mechanism gives c = -(sum m v'.v + I w' w) / M'(0).  Never creates energy;
  Housner's c = 1 - 1.5 sin^2(alpha) for a single block.
* ``"fixed"``: a user-given c_v, applied so that the kinetic energy after the impact is c_v^2
  times the energy before: c = c_v sqrt(M_old(0) / M_new(0)).  ``literal=True`` applies c_v to
  the rates directly (the paper's reading), with a warning when an impact gains energy.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass

import numpy as np

from ...errors import ArchInputError, EnergyGainError, ImpactModelError
from ...geometry import power_of_two_near
from ..fourlink import FourLink

__all__ = ["ImpactLaw", "impact_law", "paper_rate_ratio", "momentum_rate_ratio",
           "EnergyGainWarning", "projection_ratio", "fallback_note"]

#: The impact models an ImpactSpec can name (the laws below, and the least-loss choice).
IMPACT_MODELS = ("paper", "momentum", "fixed", "least-loss")
#: The models that give a rate ratio per direction (least-loss builds a chain on top of momentum).
_LAW_MODELS = tuple(m for m in IMPACT_MODELS if m != "least-loss")


class EnergyGainWarning(UserWarning):
    """An impact law multiplies the kinetic energy by more than one."""


@dataclass(frozen=True)
class ImpactLaw:
    """Rate ratios applied at impacts, both directions, and how they were obtained.

    l_to_r: c at an impact closing M_l and opening M_r; r_to_l the reverse.
    energy_l_to_r / energy_r_to_l: kinetic energy after / before for each (<= 1 unless literal).
    cv: the user-given coefficient for the "fixed" model (None otherwise).
    fallback: None when this is the law asked for; otherwise why another was used (the paper
    model could not be used on this arch, so ``model`` is the fallback's; or a fixed c_v that is
    the fallback's on the nominal arch).
    """

    model: str
    l_to_r: float
    r_to_l: float
    energy_l_to_r: float
    energy_r_to_l: float
    cv: float | None = None
    literal: bool = False
    fallback: str | None = None

    @property
    def equivalent_cv(self) -> float:
        """One coefficient of restitution for this law: sqrt of the mean kinetic-energy ratio of
        the two directions (the rate ratio itself on a symmetric arch)."""
        return math.sqrt(0.5 * (self.energy_l_to_r + self.energy_r_to_l))

    def to_dict(self) -> dict:
        """JSON-ready dict (``fallback`` only when one was used)."""
        d = {"model": self.model, "l_to_r": self.l_to_r, "r_to_l": self.r_to_l,
             "energy_l_to_r": self.energy_l_to_r, "energy_r_to_l": self.energy_r_to_l,
             "cv": self.cv, "literal": self.literal}
        if self.fallback is not None:
            d["fallback"] = self.fallback
        return d


#: The advice that ends the paper model's refusals, in the vocabulary of the spec first (a
#: Python user sets ImpactSpec's field; the command line's flag is named after it).
USE_MOMENTUM = "use the momentum law (ImpactSpec model 'momentum'; --impact momentum)"
OR_FIXED_CV = " or a fixed c_v (ImpactSpec cv; --cv)"


def fallback_note(refusal: str, fallback: str = "momentum") -> str:
    """The note of a law used instead of the paper model: the paper model's refusal (the message
    of its :class:`ImpactModelError`, without the advice that follows it) and the law used.
    The one-arch and the batch paths word their refusals alike, so their notes are the same."""
    reason = " ".join(str(refusal).split()).split("; " + USE_MOMENTUM)[0]
    return f"{reason}; {fallback} law used"


def _m0(fl: FourLink) -> float:
    return fl.coefficients(0.0)[0]


def projection_ratio(masses, inertias, v_old, w_old, v_new, w_new) -> float:
    """Rate ratio of a perfectly plastic impact with impulses only at the new pivots/hinges.

    Bodies with masses [kg], centroidal inertias [kg m^2], velocity fields per unit rate of the
    old (v_old (n, 2), w_old (n,)) and new (v_new, w_new) motions.  Projecting the momentum
    balance on the new motion gives c = -(sum m v'.v + I w' w) / (sum m |v'|^2 + I w'^2),
    clipped at 0 (no opening).  For one rectangular block rocking from one corner to the other
    it is Housner's 1 - 1.5 sin^2(alpha).
    """
    m = np.asarray(masses, float)
    i = np.asarray(inertias, float)
    v_old, v_new = np.asarray(v_old, float).reshape(-1, 2), np.asarray(v_new, float).reshape(-1, 2)
    w_old, w_new = np.asarray(w_old, float).ravel(), np.asarray(w_new, float).ravel()
    s = float(np.sum(m * np.sum(v_new * v_old, axis=1) + i * w_new * w_old))
    m_new = float(np.sum(m * np.sum(v_new * v_new, axis=1) + i * w_new * w_new))
    return max(0.0, -s / m_new)


def momentum_rate_ratio(old: FourLink, new: FourLink) -> float:
    """c = -(sum m_i v'_i.v_i + I_i w'_i w_i) / M_new(0) over the voussoirs, clipped at 0."""
    v, w = old.voussoir_field()
    vn, wn = new.voussoir_field()
    return projection_ratio(old.arch.masses, old.arch.inertias, v, w, vn, wn)


def _ordered_hinges(fl: FourLink):
    hinges = sorted(fl.mechanism.hinges, key=lambda h: h.joint)
    return hinges[::-1] if fl.direction == "r" else hinges


def paper_rate_ratio(old: FourLink, new: FourLink) -> float:
    """De Lorenzis et al.'s five-equation impact on the old links (see module docstring).

    Unknowns: phi'+ and the internal impulses J_B (on L2 from L1 at B*) and J_C (on L3 from L2
    at C*).  Pre-impact rate phi'- = -1 (closing).
    """
    arch = old.arch
    # nondimensional: masses / total mass, lengths / the arch's reference length (a power of
    # two near its size, exact), so that the five equations (momenta ~ m L, angular momenta ~ m L^2, impulses)
    # have the same numbers, and the same pivots, at any size and density
    ref = arch.reference_length
    mass_ref = power_of_two_near(float(np.sum(arch.masses)))
    v, w = old.voussoir_field()
    vn, wn = new.voussoir_field()
    v, vn = v / ref, vn / ref
    m = arch.masses / mass_ref
    inertia = arch.inertias / (mass_ref * ref * ref)
    g = arch.centroids / ref
    opposite = {"intrados": "extrados", "extrados": "intrados"}
    a_s, b_s, c_s, d_s = (arch.joint_point(h.joint, opposite[h.edge]) / ref
                          for h in _ordered_hinges(old))
    l1, l2, l3 = (np.asarray(ix, dtype=int) for ix in old.link_voussoirs)
    pre = -1.0

    def ang(idx, q, vel, om):
        """Angular momentum about q of voussoirs idx with velocities vel, rates om (per unit)."""
        r = g[idx] - q
        return float(np.sum(inertia[idx] * om[idx] + m[idx] * (r[:, 0] * vel[idx, 1] - r[:, 1] * vel[idx, 0])))

    def cross_row(r):
        # moment about a point of an impulse J = (Jx, Jy) applied at offset r: r x J
        return np.array([-r[1], r[0]])

    # x = [phi+, JBx, JBy, JCx, JCy];  rows: A x = b
    A = np.zeros((5, 5))
    b = np.zeros(5)
    # L1 about A*: dH = (B* - A*) x (-J_B)
    A[0, 0] = ang(l1, a_s, vn, wn)
    A[0, 1:3] = cross_row(b_s - a_s)
    b[0] = pre * ang(l1, a_s, v, w)
    # L3 about D*: dH = (C* - D*) x J_C
    A[1, 0] = ang(l3, d_s, vn, wn)
    A[1, 3:5] = -cross_row(c_s - d_s)
    b[1] = pre * ang(l3, d_s, v, w)
    # L2 linear: dp = J_B - J_C
    p_new = np.sum(m[l2, None] * vn[l2], axis=0)
    p_old = np.sum(m[l2, None] * v[l2], axis=0)
    A[2:4, 0] = p_new
    A[2:4, 1:3] = -np.eye(2)
    A[2:4, 3:5] = np.eye(2)
    b[2:4] = pre * p_old
    # L2 about B*: dH = (C* - B*) x (-J_C)
    A[4, 0] = ang(l2, b_s, vn, wn)
    A[4, 3:5] = cross_row(c_s - b_s)
    b[4] = pre * ang(l2, b_s, v, w)
    try:
        x = np.linalg.solve(A, b)
    except np.linalg.LinAlgError:
        raise ImpactModelError("impact: the 'paper' model's momentum equations are singular for "
                             "this geometry; " + USE_MOMENTUM) from None
    return float(x[0])


def impact_law(mech_l: FourLink, mech_r: FourLink, model: str, cv: float | None = None,
               literal: bool = False, *, fallback: str | None = None,
               note: str | None = None) -> ImpactLaw:
    """Rate ratios of an arch's two mechanisms for the chosen impact model.

    fallback: with ``model="paper"``, the model used where the paper model cannot be used on
    this arch (``"momentum"``: the default spec's; None refuses with ImpactModelError); the law
    returned is then the fallback's, its ``fallback`` the reason (:func:`fallback_note`).
    note: recorded as the law's ``fallback`` (a fixed c_v resolved on a nominal arch that fell
    back).  Where the paper model can be used, the result does not depend on either."""
    if model not in _LAW_MODELS:
        raise ArchInputError(f"impact model: {model!r}; allowed {', '.join(_LAW_MODELS)}")
    if fallback is not None:
        if model != "paper" or fallback not in ("momentum",):
            raise ArchInputError(f"fallback: {fallback!r}; allowed None, or 'momentum' with the "
                                 f"'paper' model (got model {model!r})")
        try:
            return impact_law(mech_l, mech_r, model, cv, literal)
        except ImpactModelError as exc:
            law = impact_law(mech_l, mech_r, fallback)
            return dataclasses.replace(law, fallback=fallback_note(exc, fallback))
    m_l, m_r = _m0(mech_l), _m0(mech_r)
    if model == "fixed":
        if cv is None or not math.isfinite(float(cv)) or not 0.0 <= float(cv) <= 1.0:
            raise ArchInputError(f"cv: {cv!r}; allowed 0 <= cv <= 1 (0: every impact stops the arch)")
        cv = float(cv)
        if literal:
            c_lr = c_rl = cv
        else:
            c_lr, c_rl = cv * math.sqrt(m_l / m_r), cv * math.sqrt(m_r / m_l)
    elif model == "momentum":
        c_lr, c_rl = momentum_rate_ratio(mech_l, mech_r), momentum_rate_ratio(mech_r, mech_l)
    else:
        c_lr, c_rl = paper_rate_ratio(mech_l, mech_r), paper_rate_ratio(mech_r, mech_l)
    e_lr = c_lr**2 * m_r / m_l
    e_rl = c_rl**2 * m_l / m_r
    if model == "paper":
        for name, e, c in (("l_to_r", e_lr, c_lr), ("r_to_l", e_rl, c_rl)):
            if e > 1.0 + 1e-9:
                raise EnergyGainError(
                    f"impact {name}: the 'paper' model creates energy on this geometry (kinetic "
                    f"energy ratio {e:.4f} > 1, rate ratio {c:.4f}); " + USE_MOMENTUM + OR_FIXED_CV)
            if c < 0:
                raise ImpactModelError(f"impact {name}: the 'paper' model gives a negative rate "
                                     f"ratio {c:.4f} on this geometry; " + USE_MOMENTUM)
    if max(e_lr, e_rl) > 1.0 + 1e-9:
        warnings.warn(f"impact law {model!r} gains kinetic energy at impact "
                      f"(ratios l_to_r {e_lr:.4f}, r_to_l {e_rl:.4f})", EnergyGainWarning, stacklevel=2)
    return ImpactLaw(model, float(c_lr), float(c_rl), float(e_lr), float(e_rl),
                     cv if model == "fixed" else None, bool(literal and model == "fixed"), note)
