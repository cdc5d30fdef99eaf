"""Code check of an arch's collapse mechanism: the kinematic analysis of local mechanisms of the
Italian code (NTC 2018 par. 8.7.1; Circolare 21 January 2019 n. 7, C8.7.1.2), linear and
nonlinear, against an elastic site spectrum.  Formulas and clauses: docs/codecheck.md.

The mechanism is the one limit analysis finds (:func:`archrock.statics.limit.limit_analysis`), in each
direction; the four-link model (:class:`archrock.dynamics.fourlink.FourLink`) gives its virtual
displacements at rest and its exact large-displacement kinematics, so the capacity curve
alpha(d) is the exact equilibrium multiplier of the displaced mechanism (virtual work at every
configuration), not the code's straight-line approximation (reported beside it).

Quantities (P_i = m_i g the weight of voussoir i with its loads, dx_i, dy_i the horizontal
displacement of its mass centre in the direction of the loads and its upward displacement, per
unit rotation of the mechanism at rest):

* alpha_0 = sum P_i dy_i / sum P_i dx_i (= k of limit analysis);
* M* = (sum P_i dx_i)^2 / (g sum P_i dx_i^2) [kg per metre of depth], e* = g M* / sum P_i;
* a_0* = alpha_0 sum P_i / (M* FC) = alpha_0 g / (e* FC) [m/s^2];
* capacity curve: d* = d_k sum P_i dx_i^2 / (dx_k sum P_i dx_i), a* = alpha(d_k) g / (e* FC);
  d_0* where alpha = 0; d_u* = 0.4 d_0*; d_s* = 0.4 d_u*; a_s* = a*(d_s*);
  T_s = 2 pi sqrt(d_s* / a_s*);
* checks of a mechanism at ground level: linear a_0* >= a_g S / q (q = 2.0), i.e. Se(0)/q;
  nonlinear d_u* >= S_De(T_s) = Se(T_s) (T_s / 2 pi)^2.

Lengths in metres, accelerations reported in m/s^2 and in g, masses per metre of depth.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError
from ..units import G

__all__ = ["SiteSpectrum", "CodeCheckConfig", "Kinematics", "DirectionCheck", "CodeCheckResult",
           "code_check", "mechanism_kinematics", "block_kinematics", "kinematic_check",
           "ntc_spectrum_parameters", "ec8_spectrum_parameters", "SOILS", "TOPOGRAPHY",
           "AboveGround", "mechanism_height", "above_ground_checks"]

SOILS = ("A", "B", "C", "D", "E")
#: NTC 2018 Tab. 3.2.V: topographic amplification S_T (the value at the top of the relief).
TOPOGRAPHY = {"T1": 1.0, "T2": 1.2, "T3": 1.2, "T4": 1.4}
# NTC 2018 Tab. 3.2.IV: S_S = clip(a - b F0 ag/g, lo, hi); C_C = c (Tc*)^e
_NTC_SS = {"A": (1.0, 0.0, 1.0, 1.0), "B": (1.40, 0.40, 1.00, 1.20), "C": (1.70, 0.60, 1.00, 1.50),
           "D": (2.40, 1.50, 0.90, 1.80), "E": (2.00, 1.10, 1.00, 1.60)}
_NTC_CC = {"A": (1.0, 0.0), "B": (1.10, -0.20), "C": (1.05, -0.33), "D": (1.25, -0.50),
           "E": (1.15, -0.40)}
# EN 1998-1:2004 Tables 3.2 (Type 1) and 3.3 (Type 2): S, T_B, T_C, T_D
_EC8 = {1: {"A": (1.0, 0.15, 0.4, 2.0), "B": (1.2, 0.15, 0.5, 2.0), "C": (1.15, 0.20, 0.6, 2.0),
            "D": (1.35, 0.20, 0.8, 2.0), "E": (1.4, 0.15, 0.5, 2.0)},
        2: {"A": (1.0, 0.05, 0.25, 1.2), "B": (1.35, 0.05, 0.25, 1.2), "C": (1.5, 0.10, 0.25, 1.2),
            "D": (1.8, 0.10, 0.30, 1.2), "E": (1.6, 0.05, 0.25, 1.2)}}
SPECTRUM_KINDS = ("ntc", "ec8", "table")


def _real(name, value, lo=None, hi=None, lo_open=False, allowed=""):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: {value!r}; allowed a number {allowed}".rstrip()) from None
    bad = not math.isfinite(v) or (lo is not None and (v <= lo if lo_open else v < lo)) \
        or (hi is not None and v > hi)
    if bad:
        raise ArchInputError(f"{name}: {value!r}; allowed {allowed}")
    return v


# ---------------------------------------------------------------------------- spectrum
#: Largest spectral acceleration accepted from a spectrum file [g]: elastic design spectra peak
#: at 2.5 a_g S, a few g at the most; tens or hundreds of g is a file in m/s^2 or cm/s^2.
MAX_SPECTRUM_G = 20.0
#: Above this peak [g] a warning: beyond any code's elastic spectrum (2.5 a_g S, at most about
#: 3 g), so probably a file in m/s^2.
WARN_SPECTRUM_G = 5.0


def _check_spectrum_units(where: str, se) -> None:
    """Refuse a spectrum file whose Se (read in g) cannot be meant, with the units that would
    make it plausible (peak 0.005-5 g)."""
    finite = np.asarray(se, float)[np.isfinite(se)]
    peak = float(np.max(finite)) if finite.size else 0.0
    if peak <= WARN_SPECTRUM_G:
        return
    if peak <= MAX_SPECTRUM_G:
        import warnings
        warnings.warn(f"spectrum file {where!r}: Se up to {peak:.4g} g is above any code "
                      f"spectrum (about 3 g); units? if Se is in m/s^2, divide the column by "
                      f"{G:g} (peak {peak / G:.3g} g)", stacklevel=3)
        return
    fits = [(u, f) for u, f in (("m/s^2", G), ("cm/s^2", 100.0 * G)) if 0.005 <= peak / f <= 5.0]
    hint = ("units? Se is read in g; " + " or ".join(
        f"if it is in {u}, divide the column by {f:g} (peak {peak / f:.3g} g)" for u, f in fits)
        if fits else "units? Se is read in g")
    raise ArchInputError(f"spectrum file {where!r}: Se up to {peak:.4g} g; allowed at most "
                         f"{MAX_SPECTRUM_G:g} g ({hint})")


def ntc_spectrum_parameters(ag: float, f0: float, tc_star: float, soil: str = "A",
                            topography="T1") -> dict:
    """S = S_S S_T, T_B, T_C, T_D [s] of the NTC 2018 elastic horizontal spectrum (par. 3.2.3.2.1,
    Tab. 3.2.IV-VI); ag in g."""
    s_a, s_b, lo, hi = _NTC_SS[soil]
    ss = min(max(s_a - s_b * f0 * ag, lo), hi)
    c, e = _NTC_CC[soil]
    cc = c * tc_star ** e
    st = TOPOGRAPHY[topography] if isinstance(topography, str) else float(topography)
    tc = cc * tc_star
    return {"S_S": ss, "S_T": st, "S": ss * st, "C_C": cc, "T_B": tc / 3.0, "T_C": tc,
            "T_D": 4.0 * ag + 1.6}


def ec8_spectrum_parameters(spectrum_type: int, soil: str) -> dict:
    """S, T_B, T_C, T_D [s] of the EN 1998-1 elastic spectrum (Tables 3.2 / 3.3)."""
    s, tb, tc, td = _EC8[int(spectrum_type)][soil]
    return {"S": s, "T_B": tb, "T_C": tc, "T_D": td}


@dataclass(frozen=True)
class SiteSpectrum:
    """An elastic acceleration spectrum at 5% damping, Se(T) in g.

    kind 'ntc': NTC 2018 par. 3.2.3.2.1 from ag [g] (on rock, at the limit state checked), F0,
    tc_star [s], soil (A-E) and topography (T1-T4 or a number S_T >= 1);
    kind 'ec8': EN 1998-1 par. 3.2.2.2 from ag [g] (design ground acceleration on rock, gamma_I
    included), spectrum_type (1 or 2) and soil (A-E);
    kind 'table': periods [s] (starting at 0, increasing) and values Se [g].
    """

    kind: str = "ntc"
    ag: float | None = None
    f0: float | None = None
    tc_star: float | None = None
    soil: str = "A"
    topography: object = "T1"
    spectrum_type: int = 1
    periods: tuple = ()
    values: tuple = ()
    source: str = ""

    def __post_init__(self):
        if self.kind not in SPECTRUM_KINDS:
            raise ArchInputError(f"spectrum.kind: {self.kind!r}; allowed {', '.join(SPECTRUM_KINDS)}")
        if self.kind in ("ntc", "ec8"):
            _real("spectrum.ag", self.ag, 0.0, 3.0, True, "a number of g, 0 < ag <= 3")
            if self.soil not in SOILS:
                raise ArchInputError(f"spectrum.soil: {self.soil!r}; allowed {', '.join(SOILS)}")
        if self.kind == "ntc":
            _real("spectrum.f0", self.f0, 1.0, 5.0, False, "a number 1 <= F0 <= 5 (NTC: about 2.2-2.8)")
            _real("spectrum.tc_star", self.tc_star, 0.0, 2.0, True, "a period 0 < Tc* <= 2 s")
            if isinstance(self.topography, str):
                if self.topography not in TOPOGRAPHY:
                    raise ArchInputError(f"spectrum.topography: {self.topography!r}; allowed "
                                         f"{', '.join(TOPOGRAPHY)} or a number 1 <= S_T <= 1.4")
            else:
                _real("spectrum.topography", self.topography, 1.0, 1.4, False,
                      "T1-T4 or a number 1 <= S_T <= 1.4")
        if self.kind == "ec8" and self.spectrum_type not in (1, 2):
            raise ArchInputError(f"spectrum.spectrum_type: {self.spectrum_type!r}; allowed 1 or 2")
        if self.kind == "table":
            t = np.asarray(self.periods, float)
            v = np.asarray(self.values, float)
            if t.ndim != 1 or t.size < 2 or t.shape != v.shape:
                raise ArchInputError("spectrum table: need two columns T [s], Se [g] with at "
                                     "least 2 rows")
            if not (np.all(np.isfinite(t)) and np.all(np.isfinite(v))):
                raise ArchInputError("spectrum table: values must be finite numbers")
            if t[0] != 0.0 or np.any(np.diff(t) <= 0):
                raise ArchInputError(f"spectrum table: periods must start at T = 0 (the peak "
                                     f"ground acceleration Se(0)) and increase; got T from {t[0]:g}")
            if np.any(v < 0):
                raise ArchInputError("spectrum table: Se must be >= 0 g")
            object.__setattr__(self, "periods", tuple(map(float, t)))
            object.__setattr__(self, "values", tuple(map(float, v)))

    @classmethod
    def ntc(cls, ag, f0, tc_star, soil="A", topography="T1") -> "SiteSpectrum":
        return cls("ntc", ag=float(ag), f0=float(f0), tc_star=float(tc_star), soil=soil,
                   topography=topography)

    @classmethod
    def ec8(cls, ag, soil="A", spectrum_type=1) -> "SiteSpectrum":
        return cls("ec8", ag=float(ag), soil=soil, spectrum_type=int(spectrum_type))

    @classmethod
    def from_file(cls, path) -> "SiteSpectrum":
        """A two-column text file: T [s], Se [g] ('#' comments, commas or blanks)."""
        from ..geometry.inputfile import read_input

        try:
            # bounded by size; its errors name the file, the kind and the limit
            text = read_input(path, "spectrum").decode("utf-8")
        except UnicodeDecodeError as exc:
            raise ArchInputError(f"spectrum file {str(path)!r}: not a text file (UTF-8 decoding "
                                 f"failed at byte {exc.start})") from None
        rows = []
        for k, line in enumerate(text.splitlines(), 1):
            line = line.split("#")[0].replace(",", " ").strip()
            if not line:
                continue
            try:
                vals = [float(x) for x in line.split()]
            except ValueError:
                raise ArchInputError(f"spectrum file {str(path)!r}, line {k}: expected two "
                                     f"numbers T [s] and Se [g]") from None
            if len(vals) != 2:
                raise ArchInputError(f"spectrum file {str(path)!r}, line {k}: expected two "
                                     f"columns T [s] and Se [g], got {len(vals)}")
            rows.append(vals)
        if not rows:
            raise ArchInputError(f"spectrum file {str(path)!r}: no data rows")
        a = np.array(rows)
        _check_spectrum_units(str(path), a[:, 1])
        import os
        return cls("table", periods=tuple(a[:, 0]), values=tuple(a[:, 1]),
                   source=os.path.basename(str(path)))

    @property
    def parameters(self) -> dict:
        if self.kind == "ntc":
            return ntc_spectrum_parameters(self.ag, self.f0, self.tc_star, self.soil, self.topography)
        if self.kind == "ec8":
            return ec8_spectrum_parameters(self.spectrum_type, self.soil)
        return {}

    @property
    def t_max(self) -> float:
        return self.periods[-1] if self.kind == "table" else 4.0 if self.kind == "ec8" else 10.0

    def se(self, period) -> np.ndarray | float:
        """Elastic spectral acceleration Se(T) [g] at period(s) T [s] (5% damping, eta = 1)."""
        t = np.asarray(period, float)
        if np.any(t < 0) or np.any(t > self.t_max * (1 + 1e-12)):
            raise ArchInputError(f"spectrum: period {float(np.max(t)):.4g} s outside its range "
                                 f"0 to {self.t_max:g} s")
        if self.kind == "table":
            out = np.interp(t, self.periods, self.values)
        else:
            p = self.parameters
            tb, tc, td = p["T_B"], p["T_C"], p["T_D"]
            ags = self.ag * p["S"]
            amp = self.f0 if self.kind == "ntc" else 2.5
            tt = t
            if self.kind == "ntc":  # NTC (3.2.2): Se = ag S eta F0 [T/T_B + (1 - T/T_B)/(eta F0)]
                rise = ags * amp * (t / tb + (1.0 - t / tb) / amp)
            else:  # EN 1998-1 (3.2): Se = ag S [1 + T/T_B (2.5 eta - 1)]
                rise = ags * (1.0 + t / tb * (amp - 1.0))
            with np.errstate(divide="ignore", invalid="ignore"):
                out = np.where(t < tb, rise, np.where(t < tc, ags * amp, np.where(
                    t < td, ags * amp * tc / tt, ags * amp * tc * td / tt ** 2)))
        return float(out) if np.ndim(out) == 0 else out

    def sde(self, period) -> float:
        """Elastic spectral displacement S_De(T) = Se(T) g (T / 2 pi)^2 [m]."""
        return float(self.se(period)) * G * (float(period) / (2 * math.pi)) ** 2

    @property
    def pga(self) -> float:
        """Se(0) [g]: a_g S for the code spectra."""
        return float(self.se(0.0))

    def to_dict(self) -> dict:
        d = asdict(self)
        d["periods"], d["values"] = list(self.periods), list(self.values)
        d["parameters"] = self.parameters
        d["pga_g"] = self.pga
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "SiteSpectrum":
        d = {k: v for k, v in d.items() if k not in ("parameters", "pga_g")}
        d["periods"], d["values"] = tuple(d.get("periods", ())), tuple(d.get("values", ()))
        return cls(**d)


# ---------------------------------------------------------------------------- configuration
@dataclass(frozen=True)
class CodeCheckConfig:
    """What the check assumes.

    fc: confidence factor FC (NTC 2018 C8.5.4: 1.35 / 1.20 / 1.00 for knowledge levels LC1-3);
    q: behaviour factor of the linear check (Circolare 2019: 2.0);
    ultimate_fraction: d_u* / d_0* (0.4); secant_fraction: d_s* / d_u* (0.4);
    control: 'centre' (the mass centre of the voussoirs that move) or a voussoir index;
    points: rotations sampled on the capacity curve, 0 to the unstable rotation;
    spectrum: a :class:`SiteSpectrum` or None (quantities only, no check).
    """

    fc: float = 1.35
    q: float = 2.0
    ultimate_fraction: float = 0.4
    secant_fraction: float = 0.4
    control: object = "centre"
    points: int = 201
    spectrum: SiteSpectrum | None = None

    def __post_init__(self):
        _real("fc", self.fc, 1.0, 3.0, False, "a confidence factor 1 <= FC <= 3 (NTC: 1, 1.2, 1.35)")
        _real("q", self.q, 1.0, 10.0, False, "a behaviour factor 1 <= q <= 10 (Circolare 2019: 2)")
        for name in ("ultimate_fraction", "secant_fraction"):
            _real(name, getattr(self, name), 0.0, 1.0, True, "a fraction 0 < f <= 1 (code: 0.4)")
        if not (self.control == "centre" or (isinstance(self.control, (int, np.integer))
                                             and not isinstance(self.control, bool)
                                             and self.control >= 0)):
            raise ArchInputError(f"control: {self.control!r}; allowed 'centre' or a voussoir "
                                 f"index >= 0")
        if not isinstance(self.points, (int, np.integer)) or self.points < 11:
            raise ArchInputError(f"points: {self.points!r}; allowed an integer >= 11")
        if self.spectrum is not None and not isinstance(self.spectrum, SiteSpectrum):
            raise ArchInputError("spectrum: expected a SiteSpectrum or None")

    def to_dict(self) -> dict:
        d = {k: getattr(self, k) for k in ("fc", "q", "ultimate_fraction", "secant_fraction",
                                           "control", "points")}
        d["control"] = self.control if self.control == "centre" else int(self.control)
        d["spectrum"] = None if self.spectrum is None else self.spectrum.to_dict()
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "CodeCheckConfig":
        d = dict(d)
        if d.get("spectrum") is not None:
            d["spectrum"] = SiteSpectrum.from_dict(d["spectrum"])
        return cls(**d)


@dataclass(frozen=True)
class AboveGround:
    """The structure a mechanism above ground sits in (an arch on piers in a church, a portal in
    a building), for the code's checks of a mechanism above ground level (docs/codecheck.md,
    Mechanisms above ground):

    height: H [m], the structure's height above its foundation (the mechanism's centroid must
    lie within it); storeys: N, the number of storeys (gamma = 3N / (2N + 1), the first mode's
    participation factor, 1 for a one-storey hall or a free-standing arch on piers); period:
    T_1 [s], the structure's first period, or None for the estimate T_1 = C_1 H^(3/4) with
    C_1 = ``c1`` (0.05 for masonry)."""

    height: float
    storeys: int = 1
    period: float | None = None
    c1: float = 0.05

    def __post_init__(self):
        _real("height", self.height, 0.0, 1e4, True, "a structure height 0 < H <= 10000 m")
        if isinstance(self.storeys, bool) or not isinstance(self.storeys, (int, np.integer)) \
                or not 1 <= self.storeys <= 100:
            raise ArchInputError(f"storeys: {self.storeys!r}; allowed an integer 1 to 100")
        if self.period is not None:
            _real("period", self.period, 0.0, 10.0, True, "a first period 0 < T_1 <= 10 s")
        _real("c1", self.c1, 0.0, 1.0, True, "0 < C_1 <= 1 (masonry 0.05)")

    @property
    def gamma(self) -> float:
        """The first mode's participation factor 3N / (2N + 1)."""
        return 3.0 * self.storeys / (2.0 * self.storeys + 1.0)

    @property
    def t1(self) -> float:
        """T_1 [s]: the given period or C_1 H^(3/4)."""
        return float(self.period) if self.period is not None else self.c1 * self.height ** 0.75

    def to_dict(self) -> dict:
        return {"height": self.height, "storeys": int(self.storeys), "period": self.period,
                "c1": self.c1, "gamma": self.gamma, "t1": self.t1,
                "t1_from": "given" if self.period is not None else "C_1 H^(3/4)"}


def mechanism_height(arch, kin: "Kinematics") -> dict:
    """Where the mechanism's masses are: the masses that move (dx != 0, with their loads)
    [kg/m], and Z [m], the height above the foundation (the lowest point of the two end joints:
    a pier's foot, or the springing of an arch on the ground) of their centroid, the code's Z
    (the centroid of the weights whose masses load the mechanism)."""
    m = np.asarray(kin.masses, float)
    moving = np.asarray(kin.dx, float) != 0
    jp = np.asarray(arch.joint_points, float)
    base = float(min(jp[0, :, 1].min(), jp[-1, :, 1].min()))
    w = m * moving
    yc = float(np.sum(w * np.asarray(arch.centroids, float)[:, 1]) / w.sum())
    return {"moving_mass": float(w.sum()), "z": yc - base, "foundation_y": base,
            "moving_blocks": [int(i) for i in np.flatnonzero(moving)]}


def above_ground_checks(check: "DirectionCheck", z: float, structure: AboveGround,
                        spectrum: "SiteSpectrum") -> dict:
    """The checks of a mechanism whose centroid is z [m] above the foundation of ``structure``
    (Circolare 2019 C8.7.1.2 ff., as in the 2009 Circolare's C8A.4; docs/codecheck.md):
    linear a_0* >= Se(T_1) psi(Z) gamma / q, psi(Z) = Z / H; nonlinear d_u* >= S_De(T_1) psi(Z)
    gamma (T_s/T_1)^2 / sqrt((1 - T_s/T_1)^2 + 0.02 T_s/T_1) where T_s < 1.5 T_1, else
    d_u* >= S_De(T_s).  Both beside the ground-level checks (the code asks for both)."""
    H = structure.height
    if not 0 <= z <= H:
        raise ArchInputError(f"height: {H:g} m is below the mechanism's centroid (Z = {z:.4g} "
                             f"m above the foundation); allowed a structure height >= Z")
    psi = z / H
    t1, gamma = structure.t1, structure.gamma
    if t1 > spectrum.t_max:
        raise ArchInputError(f"spectrum: the structure's period T_1 = {t1:.3g} s lies beyond "
                             f"the spectrum's last period {spectrum.t_max:g} s; extend the table")
    se1 = float(spectrum.se(t1))
    q = check.checks["linear"]["q"]
    demand = se1 * psi * gamma / q
    cap = check.a0_star / G
    lin = {"clause": "Circolare 2019 C8.7.1.2 ff. (linear, mechanism above ground): a_0* >= "
                     "Se(T_1) psi(Z) gamma / q, psi(Z) = Z / H",
           "capacity_g": cap, "demand_g": demand, "Se_T1_g": se1, "psi": psi, "gamma": gamma,
           "z": z, "H": H, "t1": t1, "q": q,
           "ratio": cap / demand if demand > 0 else math.inf, "passed": bool(cap >= demand)}
    ts = check.ts
    r = ts / t1
    if r < 1.5:
        d_dem = spectrum.sde(t1) * psi * gamma * r * r / math.sqrt((1 - r) ** 2 + 0.02 * r)
        how = "S_De(T_1) psi(Z) gamma (T_s/T_1)^2 / sqrt((1 - T_s/T_1)^2 + 0.02 T_s/T_1)"
    else:
        d_dem = spectrum.sde(ts)
        how = "S_De(T_s) (T_s >= 1.5 T_1)"
    non = {"clause": "Circolare 2019 C8.7.1.2 ff. (nonlinear, mechanism above ground): d_u* >= "
                     + how,
           "capacity_m": check.du_star, "demand_m": float(d_dem), "ts": ts, "t1": t1,
           "psi": psi, "gamma": gamma,
           "ratio": check.du_star / d_dem if d_dem > 0 else math.inf,
           "passed": bool(check.du_star >= d_dem)}
    return {"linear_above_ground": lin, "nonlinear_above_ground": non}


# ---------------------------------------------------------------------------- kinematics
@dataclass(frozen=True)
class Kinematics:
    """A one-degree-of-freedom rigid mechanism sampled from rest to its unstable position.

    masses (n,) [kg/m]; dx, dy (n,): horizontal displacement of each mass centre in the
    direction of the loads and upward displacement, per unit rotation at rest [m/rad];
    rotation (k,) [rad] from 0 to the rotation where alpha = 0; alpha (k,): the horizontal
    multiplier in equilibrium there; shift (k, n): horizontal displacement of each mass centre
    in the direction of the loads [m]."""

    masses: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    rotation: np.ndarray
    alpha: np.ndarray
    shift: np.ndarray
    label: str = ""

    def __post_init__(self):
        readonly_arrays(self)


def block_kinematics(width: float, height: float, mass: float = 1.0, points: int = 201) -> Kinematics:
    """A rigid rectangular block overturning about a base corner (the code's simple overturning):
    alpha(theta) = tan(beta - theta), beta = atan(b/h); its centre moves R [sin beta -
    sin(beta - theta)] horizontally, R the half-diagonal."""
    b = _real("width", width, 0.0, None, True, "a width > 0 m")
    h = _real("height", height, 0.0, None, True, "a height > 0 m")
    beta = math.atan2(b, h)
    r = 0.5 * math.hypot(b, h)
    th = np.linspace(0.0, beta, points)
    return Kinematics(np.array([float(mass)]), np.array([h / 2]), np.array([b / 2]), th,
                      np.tan(beta - th), (r * (math.sin(beta) - np.sin(beta - th)))[:, None],
                      "rigid block")


def mechanism_kinematics(arch, mechanism, points: int = 201, zones=None) -> Kinematics:
    """The mechanism's four-link kinematics on ``arch``: virtual displacements of the voussoirs'
    mass centres at rest and, on rotations from 0 to the unstable one (F = 0), the exact
    multiplier alpha = -s F / P and the voussoirs' horizontal displacements (s = +1 for M_l,
    -1 for M_r: displacements in the loads' direction); zones: with f_c, the compressed zones
    [m] at collapse (hinges half a zone in from the edges)."""
    from ..dynamics.fourlink import configuration, four_link

    fl = four_link(arch, mechanism, zones)
    s = 1.0 if mechanism.direction == "l" else -1.0
    v, _ = fl.voussoir_field()
    phi_u = fl.phi_unstable
    rot = np.linspace(0.0, phi_u, points)
    alpha = np.empty(points)
    shift = np.zeros((points, arch.n))
    x0 = np.asarray(arch.centroids, float)
    (ax0, ay0), (b0x, b0y), _, (dx0, dy0) = fl.points
    for k, phi in enumerate(rot):
        _, _, F, P = fl.coefficients(phi)
        alpha[k] = -s * F / P
        if phi == 0:
            continue
        bx, by, cx, cy, th1, th2, th3, _ = configuration(phi, fl.geo)
        refs = (((ax0, ay0), (ax0, ay0), th1), ((b0x, b0y), (bx, by), th2),
                ((dx0, dy0), (dx0, dy0), th3))
        for idx, (p0, p1, th) in zip(fl.link_voussoirs, refs):
            idx = np.asarray(idx, dtype=int)
            r = x0[idx] - np.array(p0)
            xn = p1[0] + math.cos(th) * r[:, 0] - math.sin(th) * r[:, 1]
            shift[k, idx] = s * (xn - x0[idx, 0])
    alpha[-1] = 0.0  # F(phi_u) = 0 to the root finder's tolerance
    return Kinematics(np.asarray(arch.masses, float), s * v[:, 0], v[:, 1], rot, alpha, shift,
                      f"M_{mechanism.direction} {mechanism.label}")


# ---------------------------------------------------------------------------- results
@dataclass(frozen=True)
class DirectionCheck:
    """The kinematic analysis of one mechanism (one direction of the loads).

    alpha_0: activation multiplier; mass [kg/m]: sum m_i; m_star [kg/m]; e_star; a0_star
    [m/s^2]; d0, d0_star, du_star, ds_star [m]; as_star [m/s^2]; ts [s] the secant period;
    curve_d_star [m] and curve_a_star [m/s^2]: the capacity curve; curve_rotation [rad];
    checks: a dict of the linear and nonlinear checks (empty without a spectrum)."""

    direction: str
    label: str
    alpha_0: float
    mass: float
    m_star: float
    e_star: float
    a0_star: float
    control: str
    dx_control: float
    d0: float
    d0_star: float
    du_star: float
    ds_star: float
    as_star: float
    as_star_linear: float
    ts: float
    curve_rotation: np.ndarray = field(repr=False)
    curve_d_star: np.ndarray = field(repr=False)
    curve_a_star: np.ndarray = field(repr=False)
    checks: dict = field(default_factory=dict)

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def a0_star_g(self) -> float:
        return self.a0_star / G

    def to_dict(self) -> dict:
        d = {k: getattr(self, k) for k in (
            "direction", "label", "alpha_0", "mass", "m_star", "e_star", "a0_star", "control",
            "dx_control", "d0", "d0_star", "du_star", "ds_star", "as_star", "as_star_linear", "ts")}
        d = {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in d.items()}
        d["a0_star_g"] = self.a0_star_g
        d["capacity_curve"] = {"rotation": self.curve_rotation.tolist(),
                               "d_star": self.curve_d_star.tolist(),
                               "a_star": self.curve_a_star.tolist()}
        d["checks"] = self.checks
        return d


@dataclass(frozen=True)
class CodeCheckResult:
    """Both directions' kinematic analyses and checks; ``governing`` is the direction with the
    smaller safety ratio (capacity / demand) of the checks, or the smaller a_0* without a
    spectrum."""

    config: CodeCheckConfig
    directions: tuple
    arch_name: str = ""
    method: str = ("kinematic analysis of local mechanisms, NTC 2018 par. 8.7.1 and Circolare "
                   "2019 C8.7.1.2; mechanisms from limit analysis, exact four-link kinematics")
    #: per direction, where the mechanism's masses are (:func:`mechanism_height`), for an arch
    #: on piers or a check above ground; None otherwise (the record as before)
    heights: dict | None = None
    above_ground: AboveGround | None = None

    def direction(self, d: str) -> DirectionCheck:
        return {c.direction: c for c in self.directions}[d]

    @property
    def governing(self) -> DirectionCheck:
        def key(c):
            ratios = [v["ratio"] for v in c.checks.values() if isinstance(v, dict) and "ratio" in v]
            return min(ratios) if ratios else c.a0_star
        # rounded: on a symmetric arch the two directions tie and M_l is named
        return min(self.directions, key=lambda c: round(key(c), 9))

    @property
    def passed(self) -> bool | None:
        if self.config.spectrum is None:
            return None
        return all(v["passed"] for c in self.directions for v in c.checks.values())

    def to_dict(self) -> dict:
        out = {"arch": self.arch_name, "method": self.method, "config": self.config.to_dict(),
               "directions": {c.direction: c.to_dict() for c in self.directions},
               "governing": self.governing.direction, "passed": self.passed,
               "units": {"mass": "kg/m", "m_star": "kg/m", "a0_star": "m/s^2",
                         "as_star": "m/s^2", "d0": "m", "d0_star": "m", "du_star": "m",
                         "ds_star": "m", "ts": "s", "a0_star_g": "g", "Se": "g"}}
        if self.heights is not None:
            out["mechanism_heights"] = self.heights
            out["units"].update({"z": "m (above the foundation)", "moving_mass": "kg/m"})
        if self.above_ground is not None:
            out["above_ground"] = self.above_ground.to_dict()
        return out


def _control_point(kin: Kinematics, control):
    """(displacements d_k [m] of the control point along the mechanism, its virtual dx_k, its
    name): the mass centre of the moving voussoirs ("centre") or of voussoir ``control``."""
    m, dx = kin.masses, kin.dx
    if control == "centre":
        w = m * (dx != 0)
        return (kin.shift @ w / w.sum(), float(np.sum(w * dx) / w.sum()),
                "mass centre of the moving voussoirs")
    i = int(control)
    if i >= m.size:
        raise ArchInputError(f"control: {i}; allowed 'centre' or a voussoir index 0..{m.size - 1}")
    if not dx[i] > 0:
        raise ArchInputError(f"control: voussoir {i} does not move horizontally in this "
                             f"mechanism; choose one that does, or 'centre'")
    return kin.shift[:, i], float(dx[i]), f"mass centre of voussoir {i}"


def _spectrum_checks(cfg: CodeCheckConfig, a0_star: float, du: float, ts: float) -> dict:
    """The linear (a_0* [m/s^2] against Se(0) / q) and nonlinear (d_u* [m] against
    S_De(T_s)) checks of Circolare 2019 C8.7.1.2.1 against the configuration's spectrum."""
    spec = cfg.spectrum
    if ts > spec.t_max:
        raise ArchInputError(f"spectrum: the secant period T_s = {ts:.3g} s lies beyond the "
                             f"spectrum's last period {spec.t_max:g} s; extend the table")
    demand, sde = spec.pga / cfg.q, spec.sde(ts)
    return {"linear": {
        "clause": "Circolare 2019 C8.7.1.2.1 (linear kinematic analysis, mechanism at ground "
                  "level): a_0* >= a_g S / q = Se(0) / q",
        "capacity_g": a0_star / G, "demand_g": demand, "q": cfg.q,
        "ratio": (a0_star / G) / demand if demand > 0 else math.inf,
        "passed": bool(a0_star / G >= demand)}, "nonlinear": {
        "clause": "Circolare 2019 C8.7.1.2.1 (nonlinear kinematic analysis, mechanism at "
                  "ground level): d_u* >= S_De(T_s)",
        "capacity_m": du, "demand_m": sde, "Se_Ts_g": float(spec.se(ts)), "ts": ts,
        "ratio": du / sde if sde > 0 else math.inf, "passed": bool(du >= sde)}}


def kinematic_check(kin: Kinematics, config: CodeCheckConfig | None = None,
                    direction: str = "l") -> DirectionCheck:
    """The code's linear and nonlinear kinematic analysis of one mechanism (module docstring)."""
    cfg = CodeCheckConfig() if config is None else config
    m, dx, dy = kin.masses, kin.dx, kin.dy
    sx = float(np.sum(m * dx))
    sxx = float(np.sum(m * dx * dx))
    if not sx > 0:
        raise ArchInputError("mechanism: its masses do not move in the direction of the loads")
    alpha_0 = float(np.sum(m * dy)) / sx
    mass = float(np.sum(m))
    m_star = sx * sx / sxx               # (sum P dx)^2 / (g sum P dx^2), P = m g
    e_star = m_star / mass               # g M* / sum P
    a0_star = alpha_0 * G / (e_star * cfg.fc)
    d_k, dx_k, control = _control_point(kin, cfg.control)
    factor = sxx / (dx_k * sx)           # d* = d_k sum P dx^2 / (dx_k sum P dx)
    d_star = np.asarray(d_k) * factor
    a_star = np.asarray(kin.alpha) * G / (e_star * cfg.fc)
    d0 = float(d_k[-1])
    d0_star = float(d_star[-1])
    du = cfg.ultimate_fraction * d0_star
    ds = cfg.secant_fraction * du
    as_star = float(np.interp(ds, d_star, a_star))
    as_lin = a0_star * (1.0 - ds / d0_star)
    ts = 2.0 * math.pi * math.sqrt(ds / as_star)
    checks = {} if cfg.spectrum is None else _spectrum_checks(cfg, a0_star, du, ts)
    return DirectionCheck(direction, kin.label, alpha_0, mass, m_star, e_star, a0_star, control,
                          dx_k, d0, d0_star, du, ds, as_star, as_lin, ts,
                          np.asarray(kin.rotation, float).copy(), d_star, a_star, checks)


def code_check(arch, limit=None, config: CodeCheckConfig | None = None,
               above_ground: AboveGround | None = None) -> CodeCheckResult:
    """The code check of ``arch`` in both directions, from the mechanisms of ``limit`` (a
    LimitResult; computed when None; with f_c on its inset hinges).  On piers: where each
    mechanism's masses are (:func:`mechanism_height`); with ``above_ground`` and a spectrum,
    the checks above ground (:func:`above_ground_checks`) join the ground-level ones."""
    from ..dynamics.finite import collapse_zones
    from ..statics.limit import limit_analysis

    if above_ground is not None and not isinstance(above_ground, AboveGround):
        raise ArchInputError("above_ground: expected an AboveGround or None")
    cfg = CodeCheckConfig() if config is None else config
    lim = limit_analysis(arch, verify=True) if limit is None else limit
    kins = {d: mechanism_kinematics(arch, lim.mechanism(d), cfg.points, collapse_zones(lim, d))
            for d in ("l", "r")}
    out = tuple(kinematic_check(kins[d], cfg, d) for d in ("l", "r"))
    if not (getattr(arch, "pier_blocks", ()) or above_ground is not None):
        return CodeCheckResult(cfg, out, getattr(arch, "name", ""))
    heights = {d: mechanism_height(arch, kins[d]) for d in ("l", "r")}
    if above_ground is not None and cfg.spectrum is not None:
        out = tuple(DirectionCheck(**{**{f: getattr(c, f) for f in c.__dataclass_fields__},
                                      "checks": {**c.checks, **above_ground_checks(
                                          c, heights[c.direction]["z"], above_ground,
                                          cfg.spectrum)}})
                    for c in out)
    elif above_ground is not None:
        for d in ("l", "r"):
            z = heights[d]["z"]
            if not 0 <= z <= above_ground.height:
                raise ArchInputError(f"height: {above_ground.height:g} m is below the "
                                     f"mechanism's centroid (Z = {z:.4g} m above the "
                                     f"foundation); allowed a structure height >= Z")
    return CodeCheckResult(cfg, out, getattr(arch, "name", ""), heights=heights,
                           above_ground=above_ground)
