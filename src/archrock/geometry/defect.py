"""Local defects of one voussoir or one joint, applied to any :class:`VoussoirArch`.

Four kinds (:class:`Defect`):

* ``thickness``: voussoir i keeps a fraction ``value`` in (0, 1) of its thickness (``0.7``: 30%
  lost).  ``at`` says where the masonry is lost: ``centreline`` (default: both faces move
  toward the centreline by half the loss each), ``intrados`` (the intrados moves outward) or
  ``extrados`` (the extrados moves inward).  Its neighbours' joints keep only the part of their
  contact that the thinner voussoir still covers.
* ``tilt``: joint j's line turns by ``value`` degrees, counter-clockwise positive, about the
  mid-point of its contact segment, in (-45, 45); the two voussoirs it separates (a springing
  joint: its one voussoir and the abutment face) are cut again along the new line.  Masonry
  that a springing joint's new line adds past the springing follows the voussoir's own curve
  continued: the exact circles of a circular :class:`Arch` (the new corners on them), else the
  circle through the polyline's last three vertices (straight on where they are collinear).
* ``mortar``: joint j has no mortar over a depth ``value`` in (0, 1) of its contact length,
  measured from its ``intrados`` (default) or ``extrados`` end: the contact segment is that much
  shorter, the masonry (masses, centroids) unchanged.
* ``pier-tilt``: an arch on piers (:class:`~archrock.geometry.ArchOnPiers`) whose ``left``
  (default) or ``right`` pier stands out of plumb by ``value`` degrees, outward positive
  (|value| <= 15): the pier turned rigidly about its outer foot corner, the voussoirs following
  (:func:`archrock.geometry.piers.lean_pier`; docs/piers.md, Irregular piers).  It has no
  index (0).

A circular :class:`Arch` with a thickness defect stays an exact ``Arch`` (the damaged voussoir
is an annular sector with a new radius and thickness); every other case gives a
:class:`PolygonArch` (a circular arch's arcs as polylines of at most 0.002 rad per segment, so
areas are within ~1e-7 of the sectors').  Loads (a family arch's fill included) stay on their
voussoirs where they were.

String form (:meth:`Defect.parse`, the command line's ``--defect``)::

    3:thickness=0.7[,side=intrados|extrados|centreline]
    4:tilt=5
    2:mortar=0.2[,side=intrados|extrados]
    pier-tilt=2[,side=left|right]

the number before the colon being the voussoir (0..n-1, from the left springing) or the joint
(0..n).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from ..errors import ArchInputError
from .base import VoussoirArch, _check_scalar
from .circular import ARC_STEP, Arch, polygon_form
from .faces import cut_polyline
from .piers import ArchOnPiers, lean_pier
from .polygon import PolygonArch

__all__ = ["Defect", "apply_defect", "apply_defects", "DEFECT_KINDS", "parse_defect",
           "defect_base"]

#: kind -> (what it damages, allowed sides, default side)
DEFECT_KINDS = {
    "thickness": ("voussoir", ("centreline", "intrados", "extrados"), "centreline"),
    "tilt": ("joint", ("",), ""),
    "mortar": ("joint", ("intrados", "extrados"), "intrados"),
    "pier-tilt": ("pier", ("left", "right"), "left"),
}
_SIDE_KEY = {"thickness": "at", "mortar": "from", "pier-tilt": "side"}
#: Smallest fraction a thickness or mortar defect leaves: below it the damaged outline has
#: coinciding points (1e-300 gave "voussoirs[2].intrados: two consecutive points coincide").
MIN_DEFECT_FRACTION = 1e-9
#: largest angle [rad] of one polyline segment when a circular arch is written as a polygon (a
#: module name of its own, so a test may refine it for the defects alone)
_ARC_STEP = ARC_STEP


def _allowed_value(kind: str) -> str:
    return {"thickness": f"a remaining fraction of the thickness, 0 < value < 1 (at least "
                         f"{MIN_DEFECT_FRACTION:g})",
            "tilt": "an angle in degrees, -45 < tilt < 45 (counter-clockwise positive)",
            "mortar": f"a fraction of the joint's contact length, 0 < value < 1 (at least "
                      f"{MIN_DEFECT_FRACTION:g})",
            "pier-tilt": "an angle in degrees, -15 <= tilt <= 15 (outward positive: the pier "
                         "top moves away from the opening)"}[kind]


@dataclass(frozen=True)
class Defect:
    """One local defect (module docstring).

    kind: 'thickness' | 'tilt' | 'mortar'; index: the voussoir (thickness, 0..n-1) or joint
    (tilt, mortar, 0..n) from the left springing; value: the remaining thickness fraction, the
    tilt [deg] or the missing mortar depth fraction; side: for thickness where the masonry is
    lost ('centreline', 'intrados', 'extrados'), for mortar the face the missing depth is
    measured from ('intrados', 'extrados'); '' (the default) means the kind's default.
    """

    kind: str
    index: int
    value: float
    side: str = ""

    def __post_init__(self):
        if self.kind not in DEFECT_KINDS:
            raise ArchInputError(f"defect kind: {self.kind!r}; allowed "
                                 f"{', '.join(DEFECT_KINDS)}")
        what, sides, default = DEFECT_KINDS[self.kind]
        if isinstance(self.index, bool) or not isinstance(self.index, (int, np.integer)) \
                or self.index < 0:
            raise ArchInputError(f"defect {what}: {self.index!r}; allowed an integer index >= 0")
        object.__setattr__(self, "index", int(self.index))
        if self.kind == "pier-tilt":
            if self.index != 0:
                raise ArchInputError(f"defect pier: {self.index}; allowed 0 (a pier tilt names "
                                     f"its pier by side=left|right)")
            v = _check_scalar("defect pier-tilt", self.value, -15.0, 15.0, lo_open=False,
                              hi_open=False, allowed=_allowed_value("pier-tilt"))
        elif self.kind == "tilt":
            v = _check_scalar("defect tilt", self.value, -45.0, 45.0, allowed=_allowed_value("tilt"))
        else:
            v = _check_scalar(f"defect {self.kind}", self.value, 0.0, 1.0,
                              allowed=_allowed_value(self.kind))
            if v < MIN_DEFECT_FRACTION:
                raise ArchInputError(f"defect {self.kind}: {v:g} is out of range; allowed "
                                     f"{_allowed_value(self.kind)}")
        object.__setattr__(self, "value", v)
        side = self.side or default
        if side == "centre":
            side = "centreline"
        if side not in sides:
            raise ArchInputError(f"defect side: {self.side!r}; allowed "
                                 f"{', '.join(s for s in sides if s) or 'none for a tilt'}")
        object.__setattr__(self, "side", side)

    # ------------------------------------------------------------------ constructors
    @classmethod
    def thickness(cls, voussoir: int, remaining: float, at: str = "centreline") -> "Defect":
        """Voussoir ``voussoir`` keeps ``remaining`` (0..1) of its thickness, lost at ``at``."""
        return cls("thickness", voussoir, remaining, at)

    @classmethod
    def tilt(cls, joint: int, degrees: float) -> "Defect":
        """Joint ``joint`` turned by ``degrees`` (counter-clockwise positive)."""
        return cls("tilt", joint, degrees)

    @classmethod
    def mortar(cls, joint: int, depth: float, side: str = "intrados") -> "Defect":
        """Joint ``joint`` without mortar over ``depth`` (0..1) of its contact from ``side``."""
        return cls("mortar", joint, depth, side)

    # ------------------------------------------------------------------ what it damages
    @property
    def target(self) -> str:
        """'voussoir' or 'joint'."""
        return DEFECT_KINDS[self.kind][0]

    def at_index(self, index: int) -> "Defect":
        """The same defect on another voussoir or joint."""
        if self.kind == "pier-tilt":
            raise ArchInputError("defect pier-tilt: has no voussoir or joint index; allowed "
                                 "side=left|right")
        return Defect(self.kind, index, self.value, self.side)

    def check(self, arch: VoussoirArch) -> None:
        """ArchInputError unless the index (a pier tilt: the pier) exists on ``arch``."""
        if self.kind == "pier-tilt":
            run = dict(zip(("left", "right"), getattr(arch, "piers", ((), ()))))
            if not getattr(arch, "pier_blocks", ()) or not run[self.side]:
                raise ArchInputError(f"defect pier-tilt: {arch.name!r} has no {self.side} pier; "
                                     f"allowed on an arch on piers (--pier-height/--pier-width, "
                                     f"or a file with pier blocks)")
            return
        hi = arch.n - 1 if self.target == "voussoir" else arch.n
        if self.index > hi:
            raise ArchInputError(f"defect {self.target}: {self.index}; allowed 0..{hi} (the arch "
                                 f"has {arch.n} voussoirs, joints 0..{arch.n})")

    # ------------------------------------------------------------------ text and dicts
    def spec(self) -> str:
        """The string form (:meth:`parse` reads it back)."""
        s = f"{self.index}:{self.kind}={self.value:g}"
        if self.kind == "pier-tilt":
            s = f"{self.kind}={self.value:g}"
        if self.kind in _SIDE_KEY and self.side != DEFECT_KINDS[self.kind][2]:
            s += f",side={self.side}"
        return s

    def describe(self) -> str:
        """Plain words, e.g. 'voussoir 3 keeps 70% of its thickness (lost about its centreline)'."""
        if self.kind == "thickness":
            where = "about its centreline" if self.side == "centreline" else f"at its {self.side}"
            return (f"voussoir {self.index} keeps {self.value:.0%} of its thickness "
                    f"({1 - self.value:.0%} lost {where})")
        if self.kind == "tilt":
            return f"joint {self.index} tilted by {self.value:g} deg (counter-clockwise positive)"
        if self.kind == "pier-tilt":
            return (f"{self.side} pier out of plumb by {self.value:g} deg ("
                    f"{'outward' if self.value >= 0 else 'inward'}, about its outer foot corner)")
        return (f"joint {self.index} without mortar over {self.value:.0%} of its contact "
                f"from its {self.side}")

    def to_dict(self) -> dict:
        return {"kind": self.kind, "index": self.index, "value": self.value, "side": self.side}

    @classmethod
    def from_dict(cls, data) -> "Defect":
        if not isinstance(data, dict) or not {"kind", "index", "value"} <= set(data) \
                or set(data) - {"kind", "index", "value", "side"}:
            raise ArchInputError(f"defect: {data!r}; allowed an object with kind, index, value "
                                 f"(and side)")
        return cls(data["kind"], data["index"], data["value"], data.get("side") or "")

    @classmethod
    def parse(cls, text: str, n: int | None = None) -> "Defect":
        """Read ``INDEX:KIND=VALUE[,side=SIDE]`` (module docstring; ``at=`` and ``from=``, the 0.5
        spellings, are read too); with ``n`` (the
        arch's voussoirs) the index is checked too."""
        return parse_defect(text, n)


_SPEC = re.compile(r"^\s*(?:([^:]*):)?\s*([a-z-]+)\s*=\s*([^,]*)(.*)$")


def parse_defect(text: str, n: int | None = None) -> Defect:
    """:meth:`Defect.parse`."""
    if not isinstance(text, str):
        raise ArchInputError(f"defect: {text!r}; allowed a string like '3:thickness=0.7'")
    m = _SPEC.match(text)
    forms = ("VOUSSOIR:thickness=F[,side=intrados|extrados|centreline], JOINT:tilt=DEG, "
             "JOINT:mortar=F[,side=intrados|extrados] or pier-tilt=DEG[,side=left|right]")
    if not m:
        raise ArchInputError(f"defect: {text!r}; allowed {forms}")
    idx_text, kind, value_text, rest = m.groups()
    if kind not in DEFECT_KINDS:
        raise ArchInputError(f"defect kind: {kind!r} in {text!r}; allowed {', '.join(DEFECT_KINDS)}")
    what = DEFECT_KINDS[kind][0]
    if (kind == "pier-tilt") != (idx_text is None):
        raise ArchInputError(f"defect: {text!r}; allowed {forms}")
    try:
        index = 0 if idx_text is None else int(idx_text.strip())
    except ValueError:
        raise ArchInputError(f"defect {what}: {idx_text.strip()!r} in {text!r}; allowed an "
                             f"integer index" + (f" 0..{n - 1 if what == 'voussoir' else n}"
                                                 if n else "")) from None
    try:
        value = float(value_text)
    except ValueError:
        raise ArchInputError(f"defect {kind}: {value_text.strip()!r} in {text!r}; allowed "
                             f"{_allowed_value(kind)}") from None
    side = ""
    for part in filter(None, (p.strip() for p in rest.split(","))):
        key, eq, val = part.partition("=")
        old = _SIDE_KEY.get(kind)  # the 0.5 spelling, still read: at= (thickness), from= (mortar)
        if not eq or key.strip() not in ("side", old) or old is None:
            raise ArchInputError(f"defect option: {part!r} in {text!r}; allowed "
                                 + ("side=..." if old else "none for a tilt"))
        side = val.strip()
    d = Defect(kind, index, value, side)
    if n is not None and kind != "pier-tilt":
        hi = n - 1 if what == "voussoir" else n
        if d.index > hi:
            raise ArchInputError(f"defect {what}: {d.index} in {text!r}; allowed 0..{hi}")
    return d


# ---------------------------------------------------------------------------- geometry
def _dedupe(p: np.ndarray, tol: float) -> np.ndarray:
    """Drop points within ``tol`` of the previous kept one (polylines refuse repeated points)."""
    keep = [0]
    for k in range(1, len(p)):
        if np.hypot(*(p[k] - p[keep[-1]])) > tol:
            keep.append(k)
    return p[keep]


def _as_polygon(arch: VoussoirArch) -> PolygonArch:
    return polygon_form(arch, _ARC_STEP)  # read here, so a test may refine the step


def defect_base(arch: VoussoirArch, kind: str) -> VoussoirArch:
    """The undamaged arch in the form a defect of ``kind`` is applied to: ``arch`` itself, or,
    for a tilt or missing mortar on a circular :class:`Arch`, its polygon form (so that a
    comparison with the damaged arch sees the defect, not the polylines' ~1e-7 difference from
    the exact sectors)."""
    if kind not in DEFECT_KINDS:
        raise ArchInputError(f"defect kind: {kind!r}; allowed {', '.join(DEFECT_KINDS)}")
    if kind == "thickness" and isinstance(arch, Arch) or kind == "pier-tilt":
        return arch
    return _as_polygon(arch)


def _arc_param(p: np.ndarray) -> np.ndarray:
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))])
    return s / s[-1]


def _resample(p: np.ndarray, s: np.ndarray) -> np.ndarray:
    u = _arc_param(p)
    return np.column_stack([np.interp(s, u, p[:, 0]), np.interp(s, u, p[:, 1])])


def _thinner(arch: VoussoirArch, d: Defect) -> VoussoirArch:
    f, i = d.value, d.index
    # new intrados at a, new extrados at b, as fractions of the way from intrados to extrados
    a, b = {"centreline": (0.5 * (1 - f), 0.5 * (1 + f)), "intrados": (1 - f, 1.0),
            "extrados": (0.0, f)}[d.side]
    if isinstance(arch, Arch):  # exact: the voussoir stays an annular sector
        t, r = arch.thicknesses.copy(), arch.radii.copy()
        r_in = r[i] - t[i] / 2
        r[i] = r_in + 0.5 * (a + b) * t[i]
        t[i] = (b - a) * t[i]
        return Arch(arch.spans.copy(), r, t, arch.density, arch.name, arch.loads, fc=arch.fc)
    poly = _as_polygon(arch)
    p, q = poly.intrados[i], poly.extrados[i]
    # both lines at the union of their vertices' arc-length fractions: each new point lies on
    # the segment from an intrados point to the extrados point at the same fraction of its line
    s = np.union1d(_arc_param(p), _arc_param(q))
    pp, qq = _resample(p, s), _resample(q, s)
    tol = 1e-12 * poly.size
    intr, extr = list(poly.intrados), list(poly.extrados)
    intr[i] = _dedupe(pp + a * (qq - pp), tol)
    extr[i] = _dedupe(pp + b * (qq - pp), tol)
    return PolygonArch(tuple(intr), tuple(extr), poly.density, poly.name, poly.loads,
                           fc=poly.fc)


def _circle_through(p0, p1, p2):
    """(centre, radius) of the circle through three points, or None when they are collinear
    (to rounding)."""
    ax, ay = p1 - p0
    bx, by = p2 - p0
    det = 2.0 * (ax * by - ay * bx)
    scale = max(ax * ax + ay * ay, bx * bx + by * by)
    if abs(det) <= 1e-12 * scale:
        return None
    a2, b2 = ax * ax + ay * ay, bx * bx + by * by
    c = p0 + np.array([(by * a2 - ay * b2) / det, (ax * b2 - bx * a2) / det])
    return c, float(np.hypot(*(p0 - c)))


def _continued(p: np.ndarray, reach: float, circle=None):
    """(points, circle): points continuing the polyline ``p`` past its first point p[0]
    (farthest first), over an arc length ``reach``: along ``circle`` (centre, radius) when given
    (the exact arc of a circular arch), else along the circle through its first three vertices
    (the curve continued with its end curvature: exact for a sampled circle), else straight on
    (a straight end; circle None)."""
    if circle is None and len(p) >= 3:
        circle = _circle_through(p[0], p[1], p[2])
    if circle is None:
        t = p[0] - p[1]
        return (p[0] + reach * t / np.hypot(*t))[None, :], None
    c, r = np.asarray(circle[0], float), float(circle[1])
    phi0 = math.atan2(p[0][1] - c[1], p[0][0] - c[0])
    phi1 = math.atan2(p[1][1] - c[1], p[1][0] - c[0])
    sign = 1.0 if math.remainder(phi0 - phi1, 2 * math.pi) > 0 else -1.0
    span = min(reach / r, 0.5 * math.pi)  # at most a quarter turn past the springing
    m = max(2, int(math.ceil(span / _ARC_STEP)))
    ang = phi0 + sign * span * np.arange(m, 0, -1) / m
    return np.column_stack([c[0] + r * np.cos(ang), c[1] + r * np.sin(ang)]), (c, r)


def _on_circle(x: np.ndarray, c0: np.ndarray, u: np.ndarray, circle) -> np.ndarray:
    """The point where the line through c0 along u meets ``circle``, nearest ``x`` (a cut found
    on a chord of the continued arc, moved onto the arc itself: its corner is then exact, not a
    sagitta of the sampling step inside)."""
    c, r = np.asarray(circle[0], float), float(circle[1])
    w = c0 - c
    bq, cq = float(w @ u), float(w @ w) - r * r
    disc = bq * bq - cq
    if disc < 0:
        return x
    pts = [c0 + (-bq + sg * math.sqrt(disc)) * u for sg in (-1.0, 1.0)]
    return min(pts, key=lambda q: float(np.hypot(*(q - x))))


def _tilted(arch: VoussoirArch, d: Defect) -> PolygonArch:
    poly = _as_polygon(arch)
    n, j = poly.n, d.index
    jp = np.asarray(poly.joint_points[j], float)
    a, b = jp
    length = float(np.hypot(*(b - a)))
    mid = 0.5 * (a + b)
    th = math.radians(d.value)
    e = (b - a) / length
    u = np.array([math.cos(th) * e[0] - math.sin(th) * e[1], math.sin(th) * e[0] + math.cos(th) * e[1]])
    tol = 1e-9 * poly.size
    intr, extr = list(poly.intrados), list(poly.extrados)
    reach = 4.0 * length  # a springing face's line extended this far past the springing
    for lines, near, side in ((intr, a, -1), (extr, b, 1)):
        if j == 0 or j == n:
            # a springing joint tilted outward adds masonry past the springing: along the
            # voussoir's own curve continued (the exact circle of a circular Arch), not along
            # the straight extension of the polyline's last chord (whose length, the
            # polygon's sampling step, then set k: 2.4e-4 off the true circle)
            v = 0 if j == 0 else n - 1
            p = lines[v]
            circle = None
            if isinstance(arch, Arch):
                circle = ((0.0, 0.0), float(arch.radii[v] + 0.5 * side * arch.thicknesses[v]))
            if j == 0:
                ext, circle = _continued(p, reach, circle)
                line = np.vstack([ext, p])
                beyond = len(ext)  # segments 0..len(ext)-1 lie past the springing
            else:
                ext, circle = _continued(p[::-1], reach, circle)
                line = np.vstack([p, ext[::-1]])
                beyond = -len(p)  # segments len(p)-1.. lie past the springing
        else:
            line = _dedupe(np.vstack([lines[j - 1], lines[j]]), tol)
            circle = None
        hit = cut_polyline(line, mid, u, near)
        if hit is None:
            raise ArchInputError(f"defect tilt: {d.value:g} deg at joint {j}: the tilted joint "
                                 f"misses the voussoirs' faces; allowed a smaller tilt")
        k, x = hit
        # a corner of the tilted springing face on the arc itself, not a sagitta of the sampling
        # step inside it: past the springing (on the continued arc), and anywhere on a circular
        # Arch, whose voussoirs' polyline vertices lie on its exact circles
        if circle is not None and (isinstance(arch, Arch) or (beyond > 0 and k < beyond)
                                   or (beyond < 0 and k >= -beyond - 1)):
            x = _on_circle(x, mid, u, circle)
        left = _dedupe(np.vstack([line[:k + 1], x]), tol)
        right = _dedupe(np.vstack([x, line[k + 1:]]), tol)
        if len(left) < 2 or len(right) < 2:
            raise ArchInputError(f"defect tilt: {d.value:g} deg at joint {j} cuts off a whole "
                                 f"voussoir; allowed a smaller tilt")
        if j == 0:
            lines[0] = right
        elif j == n:
            lines[n - 1] = left
        else:
            lines[j - 1], lines[j] = left, right
    try:
        return PolygonArch(tuple(intr), tuple(extr), poly.density, poly.name, poly.loads,
                           fc=poly.fc)
    except ArchInputError as exc:
        raise ArchInputError(f"defect tilt: {d.value:g} deg at joint {j} does not give a valid "
                             f"arch ({exc}); allowed a smaller tilt") from None


def _unmortared(arch: VoussoirArch, d: Defect) -> PolygonArch:
    poly = _as_polygon(arch)
    n, j = poly.n, d.index
    a, b = np.asarray(poly.joint_points[j], float)
    # the end of the shortened contact segment on the damaged side
    x = a + d.value * (b - a) if d.side == "intrados" else b - d.value * (b - a)
    intr, extr = list(poly.intrados), list(poly.extrados)
    lines = intr if d.side == "intrados" else extr
    # the face that ends at x: voussoir j's left face (j < n) or voussoir n-1's right face; the
    # old face end stays a vertex, so the outline (the masonry) does not change
    if j < n:
        lines[j] = np.vstack([x, lines[j]])
    else:
        lines[n - 1] = np.vstack([lines[n - 1], x])
    return PolygonArch(tuple(intr), tuple(extr), poly.density, poly.name, poly.loads,
                           fc=poly.fc)


def _pier_tilted(arch, d: Defect):
    out = lean_pier(arch, d.side, d.value)
    if out is arch:  # 0 deg: the same arch, under its own name
        out = ArchOnPiers(arch.intrados, arch.extrados, arch.density, arch.name, arch.loads,
                          fc=arch.fc, block_kinds=arch.block_kinds)
    return out


def apply_defect(arch: VoussoirArch, defect: Defect | str) -> VoussoirArch:
    """``arch`` with one defect (a :class:`Defect` or its string form; module docstring): an
    exact :class:`Arch` for a thickness loss on a circular arch, else a :class:`PolygonArch`
    (a family arch loses its recipe: it is no longer a member of its family).  Loads kept."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    d = parse_defect(defect, arch.n) if isinstance(defect, str) else defect
    if not isinstance(d, Defect):
        raise ArchInputError(f"defect: {defect!r}; allowed a Defect or a string like "
                             f"'3:thickness=0.7'")
    d.check(arch)
    out = {"thickness": _thinner, "tilt": _tilted, "mortar": _unmortared,
           "pier-tilt": _pier_tilted}[d.kind](arch, d)
    kinds = getattr(arch, "block_kinds", ())
    if kinds and "voussoir" in kinds and len(set(kinds)) > 1 and not hasattr(out, "block_kinds"):
        # an arch on piers stays one: its piers are still piers, counted and named apart
        out = ArchOnPiers(out.intrados, out.extrados, out.density, out.name, out.loads,
                          fc=out.fc, block_kinds=kinds)
    object.__setattr__(out, "name", f"{arch.name} [{d.spec()}]")
    return out


def apply_defects(arch: VoussoirArch, defects) -> VoussoirArch:
    """Each defect of ``defects`` applied in turn (indices refer to ``arch``'s voussoirs)."""
    for d in defects or ():
        arch = apply_defect(arch, d)
    return arch
