"""The least width of two equal piers under an arch (docs/piers.md), and why an arch on piers
cannot stand.

The minimum width is the classic buttress question: the arch's thrust leans on the pier, and
the pier stands while a line of thrust fits inside it down to its foundation (Heyman, *The
Stone Skeleton*, 1995, ch. 4 and 5; Ochsendorf, *Collapse of masonry structures*, PhD thesis,
Cambridge 2002, ch. 3, arches on buttresses).  It is found by a bounded bisection on the width
of both piers (equal), each step the static program's feasibility under self-weight (lambda = 0,
:func:`archrock.statics.lp._stands`, the test the minimum thickness uses), so it is a lower-bound
(safe) answer under Heyman's hypotheses: no tension, no crushing, no sliding.  At the minimum
the admissible thrust passes through the pier's outer foot corner: for a monolithic
rectangular pier of height h and weight w = rho g h W, under the arch's thrust H and vertical
reaction V crossing the pier top at s outward of its inner face, the moment about that corner
gives  w W / 2 + V (W - s) = H h,  i.e.  W = (-V + sqrt(V^2 + 2 rho g h (H h + V s))) / (rho g h).

No limit analysis here: :mod:`~archrock.statics.overload` (below the limit analysis) asks
:func:`piers_cannot_stand` why an arch falls.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linprog

from .._records import readonly_arrays
from ..errors import ArchInputError, CannotStandError
from ..geometry import ArchOnPiers, VoussoirArch, with_piers
from ..geometry.circular import polygon_form
from ..geometry.piers import arch_without_piers, pier_sizes
from ..units import G
from .lp import ThrustLine, _stands, _statics, _thrust_from_x
from .search import check_tol, least_standing

__all__ = ["MinimumPierWidth", "minimum_pier_width", "MAX_WIDTH_FACTOR", "piers_cannot_stand"]

#: Default bound of the width search, in units of the arch's extent (its span): a pier wider
#: than 20 spans is no pier.  The caller may raise it to 100 spans (with_piers' own bound).
MAX_WIDTH_FACTOR = 20.0
_MAX_STEPS = 200


def _extent(poly) -> float:
    """The extent [m] of a polygon arch, as :func:`~archrock.geometry.with_piers` measures it
    (the larger side of the box around its voussoirs)."""
    pts = np.vstack(list(poly.intrados) + list(poly.extrados))
    return float(np.max(np.ptp(pts, axis=0)))


def _reach(arch: VoussoirArch) -> float:
    """The narrowest pier allowed: the wider horizontal reach of the two springing joints [m]."""
    jp = np.asarray(arch.joint_points, float)
    return float(max(jp[0, 0, 0] - jp[0, 1, 0], jp[-1, 1, 0] - jp[-1, 0, 0]))


def _margin_state(arch: VoussoirArch):
    """(margin, thrust line) of the self-weight state with the largest smallest margin (as
    :func:`archrock.statics.lp._stands`, whose verdict is margin >= 0)."""
    st = _statics(arch, "l")
    A_ub = np.column_stack([st.A_ub[:, :3], np.ones(st.A_ub.shape[0])])
    res = linprog(c=[0, 0, 0, -1.0], A_ub=A_ub, b_ub=st.b_ub,
                  bounds=[(None, None)] * 3 + [(None, 1.0)], method="highs")
    if res.status != 0:
        return -math.inf, None
    x = np.array([res.x[0], res.x[1], res.x[2], 0.0])
    return float(res.x[3]), _thrust_from_x(st, x)


@dataclass(frozen=True)
class MinimumPierWidth:
    """The least width [m] of two equal piers ``height`` [m] high with which the arch stands
    under self-weight (:func:`minimum_pier_width`).

    governed_by: "pier" (the thrust at that width passes through a pier's outer foot corner) or
    "springing" (the narrowest pier the springing joint allows, ``reach``, already stands: the
    width is not what limits the arch); bracket: the last (lo, hi) of the bisection, width = hi
    (stands); thrust: the self-weight line of thrust at ``width`` (the state of largest margin,
    forces per unit total weight of arch and piers); structure: the arch on those piers.
    springing_force: (H, V) [N/m] the arch transmits to the left pier's top (H > 0 outward) and
    springing_point [m] where its line crosses the springing joint.
    """

    width: float
    height: float
    courses: int
    batter: float
    governed_by: str
    reach: float
    max_width: float
    bracket: tuple
    tol: float
    iterations: int
    springing_force: tuple
    springing_point: np.ndarray
    thrust: ThrustLine = field(repr=False)
    structure: ArchOnPiers = field(repr=False)
    method: str = ("bisection on the width of both piers; each step the static program's "
                   "feasibility under self-weight (no tension, lambda = 0)")

    def __post_init__(self):
        readonly_arrays(self)

    def to_dict(self) -> dict:
        return {"width": self.width, "height": self.height, "courses": self.courses,
                "batter": self.batter, "governed_by": self.governed_by, "reach": self.reach,
                "max_width": self.max_width, "bracket": list(self.bracket), "tol": self.tol,
                "iterations": self.iterations,
                "springing_force": {"H": self.springing_force[0], "V": self.springing_force[1]},
                "springing_point": self.springing_point.tolist(),
                "foot_point": self.thrust.points[0].tolist(), "method": self.method,
                "units": {"width": "m", "height": "m", "H": "N/m", "V": "N/m"}}


def _check_arch(arch) -> None:
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected an archrock arch (Arch or PolygonArch), got "
                             f"{type(arch).__name__}")
    if isinstance(arch, ArchOnPiers) and arch.pier_blocks:
        raise ArchInputError("arch: already on piers; allowed the arch without its piers (the "
                             "width is what is sought)")


def minimum_pier_width(arch: VoussoirArch, height: float, *, courses: int = 1,
                       batter: float = 0.0, max_width: float | None = None,
                       tol: float = 1e-7) -> MinimumPierWidth:
    """The least width W [m] (at the pier top) of two equal piers ``height`` [m] high under
    ``arch`` (:func:`archrock.geometry.with_piers`, ``courses`` and ``batter`` as there) with
    which the arch stands under its own weight (module docstring).

    Starts at the narrowest pier allowed (the springing joint's reach: if that stands, it is
    the answer, ``governed_by="springing"``), doubles the width up to ``max_width`` (default
    :data:`MAX_WIDTH_FACTOR` x the arch's extent, at most 100 x), then bisects to a relative
    width ``tol`` (1e-15 <= tol < 0.5).  CannotStandError when the arch does not stand on rigid
    ground (no pier helps) or when no width up to ``max_width`` suffices."""
    _check_arch(arch)
    tol = check_tol(tol, "width")
    poly = polygon_form(arch)  # checked once; the search rebuilds only the piers under it
    extent = _extent(poly)
    if max_width is None:
        max_width = MAX_WIDTH_FACTOR * extent
    if isinstance(max_width, (bool, str)):
        raise ArchInputError(f"max_width: expected a number in metres, got {max_width!r}")
    max_width = float(max_width)
    reach = _reach(arch)
    if not (math.isfinite(max_width) and reach <= max_width <= 100.0 * extent):
        raise ArchInputError(f"max_width: {max_width!r} m; allowed from the springing joint's "
                             f"reach ({reach:.4g} m) to 100 x the arch's extent "
                             f"({100 * extent:.4g} m)")
    # checks height, courses, batter by name (with_piers' messages)
    with_piers(poly, height, reach, courses=courses, batter=batter, _trusted=True)
    if not _stands(arch):
        raise CannotStandError("arch: it does not stand under its own weight even on rigid "
                               "supports; no pier carries it")

    def build(w, trusted=False):
        return with_piers(poly, height, w, courses=courses, batter=batter, name=arch.name + \
                          " on piers", _trusted=trusted)

    def stands(w):
        return _stands(build(w, trusted=True))

    it = 0
    if stands(reach):
        lo = hi = reach
        governed = "springing"
    else:
        lo, hi = reach, min(2.0 * reach, max_width)
        while not stands(hi):
            it += 1
            if hi >= max_width:
                raise CannotStandError(
                    f"minimum pier width: no width up to max_width = {max_width:.6g} m carries "
                    f"the arch on piers {height:g} m high (raise max_width, at most "
                    f"{100 * extent:.6g} m, or lower the piers)")
            lo, hi = hi, min(2.0 * hi, max_width)
        # 1e-15 from a doubling bracket takes ~ 50 halvings of the _MAX_STEPS
        hi, it = least_standing(stands, lo, hi, tol, _MAX_STEPS, "minimum pier width", it)
        governed = "pier"
    structure = build(hi)
    _, thrust = _margin_state(structure)
    c = len(structure.piers[0])
    weight = float(np.sum(structure.masses)) * G
    f = thrust.forces[c] * weight
    return MinimumPierWidth(float(hi), float(height), int(courses), float(batter), governed,
                            reach, max_width, (float(lo), float(hi)), tol, it,
                            (float(f[0]), float(f[1])), np.array(thrust.points[c], float),
                            thrust, structure)


# ---------------------------------------------------------------------------- piers that cannot stand
#: Relative tolerance of the least pier width a "cannot stand on its piers" message gives (the
#: width is rounded up to the millimetre there; 1e-5 takes ~18 linear programs).
MESSAGE_TOL = 1e-5
#: Largest structure (blocks) whose message searches the least pier width (each step one LP).
MESSAGE_MAX_BLOCKS = 400


def _equal_piers(arch, sizes) -> dict | None:
    """{height, width, courses, batter} of the two equal plumb piers of ``arch`` as
    :func:`~archrock.geometry.with_piers` builds them (rebuilt and compared joint for joint),
    or None (unequal, stepped, leaning or reshaped piers: no one width to give)."""
    left, right = sizes.get("left"), sizes.get("right")
    if not left or not right or left["kind"] != right["kind"] or \
            left["blocks"] != right["blocks"] or left["lean_deg"] or right["lean_deg"]:
        return None
    h, w, foot = left["height"], left["width_top"], left["width_foot"]
    if not all(map(math.isfinite, (h, w, foot))) or h <= 0:
        return None
    batter = max(foot - w, 0.0) / h
    try:
        rebuilt = with_piers(arch_without_piers(arch), h, w, courses=left["blocks"],
                             batter=batter)
    except Exception:  # noqa: BLE001 - piers with_piers cannot build: no width to give
        return None
    if rebuilt.n != arch.n or not np.allclose(rebuilt.joint_points, arch.joint_points,
                                              rtol=0, atol=1e-7 * arch.size):
        return None
    return {"height": h, "width": w, "courses": left["blocks"], "batter": batter,
            "kind": left["kind"]}


def piers_cannot_stand(arch, detail: str = "") -> str | None:
    """The one-line reason an arch on piers cannot stand under its own weight where its
    voussoirs alone stand on rigid supports: the piers are to blame, and (two equal piers built
    as :func:`~archrock.geometry.with_piers` builds them) the least width that carries it,
    :func:`minimum_pier_width` to :data:`MESSAGE_TOL`.  None where it does not apply (no piers,
    the voussoirs fall on rigid supports too, more than :data:`MESSAGE_MAX_BLOCKS` blocks).
    ``detail``: e.g. the multipliers, "(k_l = -0.02593, k_r = -0.02593)"."""
    if not isinstance(arch, ArchOnPiers) or not arch.pier_blocks or \
            arch.n > MESSAGE_MAX_BLOCKS:
        return None
    bare = arch_without_piers(arch)
    if not _stands(bare):
        return None  # it falls on rigid supports too: not the piers' fault
    sizes = pier_sizes(arch)
    eq = _equal_piers(arch, sizes)
    kind = (eq or next(iter(sizes.values()), {"kind": "pier"}))["kind"]
    kinds = "buttresses" if kind == "buttress" else "piers"
    detail = f" {detail}" if detail else ""
    if eq is None:
        desc = "; ".join(f"{side}: {s['width_top']:.4g} m wide, {s['height']:.4g} m high"
                         for side, s in sizes.items())
        return (f"arch: it cannot stand on its {kinds} ({desc}) under its own weight{detail}; "
                f"on rigid supports it stands: its {kinds} cannot carry its thrust (archrock "
                f"limit --min-pier-width H gives the least width of two equal piers H m high; "
                f"docs/piers.md)")
    h, w = eq["height"], eq["width"]
    each = f"of {eq['courses']} courses, " if eq["courses"] > 1 else ""
    batter = f", batter {eq['batter']:.4g}" if eq["batter"] > 0 else ""
    head = (f"arch: it cannot stand on its {kinds} (two {kinds} {each}{w:.4g} m wide, "
            f"{h:.4g} m high{batter}) under its own weight{detail}; on rigid supports it stands")
    try:
        mpw = minimum_pier_width(bare, h, courses=eq["courses"], batter=eq["batter"],
                                 tol=MESSAGE_TOL)
    except CannotStandError:
        return (f"{head}, and no {kind} {h:.4g} m high up to "
                f"{MAX_WIDTH_FACTOR:g} times its span wide carries it: lower the {kinds} "
                f"(docs/piers.md)")
    need = math.ceil(mpw.width * 1000) / 1000  # a width one can type that stands
    return (f"{head}, and {kinds} {h:.4g} m high carry it from {mpw.width:.4f} m wide: give the "
            f"{kinds} a width of {need:g} m or more (the least pier width, "
            f"archrock.statics.buttress.minimum_pier_width; docs/piers.md)")
