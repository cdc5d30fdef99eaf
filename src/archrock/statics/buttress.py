"""Limit-analysis questions of an arch on piers (docs/piers.md): the collapse multiplier against
the piers' height (:func:`k_against_pier_height`), and, from :mod:`~archrock.statics.pierwidth`
(re-exported here), the least pier width with which the arch stands on its piers under its own
weight.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError
from ..geometry import VoussoirArch, with_piers
from ..geometry.piers import hinge_place
from .limit import limit_analysis
from .pierwidth import (MAX_WIDTH_FACTOR, MinimumPierWidth, _check_arch, minimum_pier_width,
                        piers_cannot_stand)

__all__ = ["MinimumPierWidth", "minimum_pier_width", "PierHeightTable",
           "k_against_pier_height", "MAX_WIDTH_FACTOR", "MAX_HEIGHTS", "piers_cannot_stand"]

#: Most heights in one k-against-height table.
MAX_HEIGHTS = 200


@dataclass(frozen=True)
class PierHeightTable:
    """Collapse multipliers of an arch on two equal piers of width ``width`` [m] against their
    height: ``heights`` [m] (0: the arch on rigid ground), ``k_l``, ``k_r``, the mechanisms'
    hinge labels (joints numbered along each chain) and where hinge D is (``places_l``,
    ``places_r``: "right pier foot, outer face", ...); ``span`` [m]: the clear span between the
    intrados springing points (heights / span is the figure's axis)."""

    heights: np.ndarray
    k_l: np.ndarray
    k_r: np.ndarray
    labels_l: tuple
    labels_r: tuple
    places_l: tuple
    places_r: tuple
    width: float
    courses: int
    batter: float
    span: float
    arch_name: str
    method: str = "limit analysis (kinematic four-hinge search checked by the static LP)"

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def k(self) -> np.ndarray:
        return np.minimum(self.k_l, self.k_r)

    def rows(self) -> list[dict]:
        return [{"height": float(h), "height_over_span": float(h / self.span),
                 "k_l": float(a), "k_r": float(b), "mechanism_l": la, "mechanism_r": lb,
                 "hinge_d_l": pa, "hinge_d_r": pb}
                for h, a, b, la, lb, pa, pb in zip(self.heights, self.k_l, self.k_r,
                                                   self.labels_l, self.labels_r,
                                                   self.places_l, self.places_r)]

    def to_dict(self) -> dict:
        return {"arch": self.arch_name, "width": self.width, "courses": self.courses,
                "batter": self.batter, "span": self.span, "rows": self.rows(),
                "method": self.method, "units": {"height": "m", "width": "m", "span": "m",
                                                 "k": "g (horizontal load / weight)"}}


def k_against_pier_height(arch: VoussoirArch, width: float, heights, *, courses: int = 1,
                          batter: float = 0.0) -> PierHeightTable:
    """k_l and k_r of ``arch`` on two equal piers ``width`` [m] wide for each height in
    ``heights`` [m] (0: the arch on rigid ground; at most :data:`MAX_HEIGHTS` values, each
    >= 0), by :func:`archrock.statics.limit.limit_analysis`."""
    _check_arch(arch)
    try:
        hs = np.asarray(heights, float).ravel()
    except (TypeError, ValueError):
        raise ArchInputError(f"heights: {heights!r}; allowed a list of heights >= 0 m") from None
    if not 1 <= hs.size <= MAX_HEIGHTS or not np.all(np.isfinite(hs)) or np.any(hs < 0):
        raise ArchInputError(f"heights: {hs.size} value(s) {hs[:4].tolist()}...; allowed 1 to "
                             f"{MAX_HEIGHTS} finite heights >= 0 m")
    out = {k: [] for k in ("k_l", "k_r", "ll", "lr", "pl", "pr")}
    for h in hs:
        a = arch if h == 0 else with_piers(arch, float(h), width, courses=courses, batter=batter)
        res = limit_analysis(a)
        out["k_l"].append(res.k_l)
        out["k_r"].append(res.k_r)
        for d in ("l", "r"):
            mech = res.mechanism(d)
            out["l" + d].append(mech.label)
            last = mech.labelled()[-1][1] if mech.hinges else None
            out["p" + d].append("" if last is None else hinge_place(a, last.joint, last.edge))
    jp = np.asarray(arch.joint_points, float)
    span = float(jp[-1, 0, 0] - jp[0, 0, 0])
    return PierHeightTable(hs, np.array(out["k_l"]), np.array(out["k_r"]), tuple(out["ll"]),
                           tuple(out["lr"]), tuple(out["pl"]), tuple(out["pr"]), float(width),
                           int(courses), float(batter), span, arch.name)
