"""An assessment of one arch: every answer of archrock about it, in one ordered report.

The report is an ordered list of *sections* (:data:`SECTIONS`).  A section is a function
``section(context) -> Section | None``: it computes what it needs (the context caches the
limit analysis and the prepared dynamic model, shared by all), and returns a :class:`Section`
with a title, its content as *blocks* (paragraphs, tables, figures) and ``data``, the numbers
behind it, which go to the report's JSON.  ``None`` leaves the section out.  Blocks are plain
data at this layer; :mod:`archrock.reports.html` (layer 7) renders them, and draws each
:class:`Figure` with the figure function its ``kind`` names (``reports.html.FIGURES``).

Adding a section: write one function here and add it to :data:`SECTIONS`; a new kind of figure
also needs one function in ``reports.html.FIGURES``.  Sections that use an optional part of the
package (:func:`section_defects`, :func:`section_friction`, :func:`section_contact`) import it
inside, and say "not available in this installation" when it does not import.

Nothing here draws or writes files: :func:`assess` returns an :class:`Assessment` (sections,
config, timings); ``reports.html`` turns it into one self-contained HTML file and its JSON.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .codecheck import CodeCheckConfig
from .runner import UNSET
from ..errors import ArchInputError, ArchrockError
from ..geometry import Arch, PolygonArch, VoussoirArch
from ..dynamics.impact import PAPER_PRACTICE, ImpactSpec
from ..geometry.sampling import Spreads

__all__ = ["AssessConfig", "Section", "Paragraph", "Table", "Figure", "Context", "Assessment",
           "SECTIONS", "assess", "REFERENCES", "MASONRY_FRICTION", "MASONRY_FRICTION_SOURCE",
           "arch_extent"]

#: The paper and the works the report cites (in the order of first use in docs/method.md).
REFERENCES = {
    "paper": "Effect of geometric irregularities on the dynamic response of masonry arches "
             "(EURODYN 2017): the method this package implements (docs/method.md).",
    "heyman": "J. Heyman, The stone skeleton, Int. J. Solids Struct. 2 (1966) 249-279: "
              "no tensile strength, unlimited compressive strength, no sliding.",
    "oppenheim": "I. J. Oppenheim, The masonry arch as a four-link mechanism under base motion, "
                 "Earthquake Eng. Struct. Dyn. 21 (1992) 1005-1017.",
    "delorenzis": "L. De Lorenzis, M. DeJong, J. Ochsendorf, Failure of masonry arches under "
                  "impulse base motion, Earthquake Eng. Struct. Dyn. 36 (2007) 2119-2136.",
    "bisegna": "P. Bisegna, S. Coccia, M. Como et al. (2023): the post-impact mechanism that "
               "keeps the most energy (least-loss law, docs/method.md).",
    "ntc": "NTC 2018: D.M. 17 gennaio 2018, Norme tecniche per le costruzioni, par. 3.2.3 "
           "(spectra) and 8.7.1 (existing masonry, local mechanisms).",
    "circolare": "Circolare 21 gennaio 2019 n. 7 C.S.LL.PP., C8.7.1.2 (kinematic analysis of "
                 "local mechanisms), C8.5.4 (confidence factors).",
    "ec8": "EN 1998-1:2004 par. 3.2.2.2 (elastic spectrum); EN 1998-3:2005 (assessment of "
           "existing buildings; its Annex C, masonry, gives no kinematic procedure for local "
           "mechanisms: docs/codecheck.md).",
    "baker": "J. W. Baker, Efficient analytical fragility function fitting using dynamic "
             "structural analysis, Earthquake Spectra 31 (2015) 579-599.",
    "ec6": "EN 1996-1-1:2005 (Eurocode 6) par. 3.6.2, eq. (3.5): f_vk = f_vk0 + 0.4 sigma_d, "
           "the characteristic shear strength of masonry, whose coefficient 0.4 on the normal "
           "stress is the code's friction coefficient of masonry joints (used here as mu = 0.4).",
}

#: The friction coefficient the report takes for masonry joints, and where it comes from: where
#: the multiplier k needs more friction than this, the summary says so beside k and gives the
#: multiplier with this friction (archrock.statics.friction.friction_analysis).
MASONRY_FRICTION = 0.4
MASONRY_FRICTION_SOURCE = "EN 1996-1-1 (Eurocode 6) 3.6.2"


# ---------------------------------------------------------------------------- content blocks
@dataclass(frozen=True)
class Paragraph:
    """A paragraph of plain text (escaped when rendered)."""

    text: str


@dataclass(frozen=True)
class Table:
    """A table: header cells and rows of cells (strings or numbers, rendered as given)."""

    header: tuple
    rows: tuple
    caption: str = ""


@dataclass(frozen=True)
class Figure:
    """A figure to draw: ``kind`` names a function of ``reports.html.FIGURES``, which draws
    ``payload`` (the section's own objects, not serialised)."""

    kind: str
    caption: str
    payload: object = field(default=None, repr=False, compare=False)


@dataclass(frozen=True)
class Section:
    """One section of the report: key (an identifier, the JSON key), title, blocks, data (the
    numbers behind it, JSON-ready), headline (label, value text) pairs for the summary table,
    and seconds, the time it took."""

    key: str
    title: str
    blocks: tuple = ()
    data: dict = field(default_factory=dict)
    headline: tuple = ()
    seconds: float = 0.0


# ---------------------------------------------------------------------------- configuration
@dataclass(frozen=True)
class AssessConfig:
    """What the assessment computes, frozen and serialisable.

    impact: the impact law (:class:`ImpactSpec`); pulse_amplitude [g], pulse_duration [s]: the
    paper's Oppenheim pulse (-1 g, 0.2 s); t_end [s]: the response window;
    durations [s]: pulse durations of the collapse-acceleration curve; n_scan: its amplitude grid;
    samples, seed, spreads: the irregular arches of the band (and of the fragility, if records);
    records: accelerogram files (none: no fragility section); record_units; scales: IDA scale
    factors; bootstrap: fragility resamples; codecheck: the code check's configuration.
    """

    impact: ImpactSpec = field(default_factory=lambda: ImpactSpec.parse(PAPER_PRACTICE))
    pulse_amplitude: float = -1.0
    pulse_duration: float = 0.2
    t_end: float = 3.0
    durations: tuple = (0.1, 0.2, 0.3, 0.5, 0.7, 1.0)
    n_scan: int = 60
    samples: int = 12
    seed: int = 0
    spreads: Spreads = field(default_factory=Spreads)
    records: tuple = ()
    record_units: str | None = None
    scales: tuple = tuple(np.round(np.linspace(0.2, 3.0, 15), 6))
    bootstrap: int = 0
    codecheck: CodeCheckConfig = field(default_factory=CodeCheckConfig)

    def __post_init__(self):
        for name in ("pulse_amplitude", "pulse_duration", "t_end"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ArchInputError(f"{name}: {v!r}; allowed a finite number")
        if self.pulse_duration <= 0 or self.t_end <= 0:
            raise ArchInputError("pulse_duration, t_end: allowed > 0 s")
        if self.pulse_amplitude == 0:
            raise ArchInputError("pulse_amplitude: 0; allowed a nonzero amplitude in g")
        d = tuple(float(x) for x in self.durations)
        if not d or any(not (math.isfinite(x) and x > 0) for x in d):
            raise ArchInputError(f"durations: {self.durations!r}; allowed positive periods in s")
        object.__setattr__(self, "durations", d)
        object.__setattr__(self, "scales", tuple(float(x) for x in self.scales))
        object.__setattr__(self, "records", tuple(str(r) for r in self.records))
        for name, lo in (("n_scan", 2), ("samples", 0), ("seed", 0), ("bootstrap", 0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
                raise ArchInputError(f"{name}: {v!r}; allowed an integer >= {lo}")
        if self.bootstrap == 1:
            raise ArchInputError("bootstrap: 1; allowed 0 or an integer >= 2")
        if isinstance(self.spreads, dict):
            object.__setattr__(self, "spreads", Spreads.from_dict(self.spreads))

    def to_dict(self) -> dict:
        return {"impact": self.impact.to_dict(), "pulse_amplitude": self.pulse_amplitude,
                "pulse_duration": self.pulse_duration, "t_end": self.t_end,
                "durations": list(self.durations), "n_scan": self.n_scan, "samples": self.samples,
                "seed": self.seed, "spreads": self.spreads.to_dict(), "records": list(self.records),
                "record_units": self.record_units, "scales": list(self.scales),
                "bootstrap": self.bootstrap, "codecheck": self.codecheck.to_dict()}

    @classmethod
    def from_dict(cls, d: dict) -> "AssessConfig":
        d = dict(d)
        d["impact"] = ImpactSpec.from_dict(d["impact"])
        d["spreads"] = Spreads.from_dict(d["spreads"])
        d["codecheck"] = CodeCheckConfig.from_dict(d["codecheck"])
        for k in ("durations", "records", "scales"):
            d[k] = tuple(d[k])
        return cls(**d)


# ---------------------------------------------------------------------------- context
@dataclass(frozen=True)
class _Failed:
    exc: Exception


@dataclass
class Context:
    """What the sections share: the arch, the configuration, a progress callback and a cache of
    results computed once (the limit analysis, the dynamic model)."""

    arch: VoussoirArch
    config: AssessConfig
    progress: Callable[[str], None] = lambda msg: None
    cache: dict = field(default_factory=dict)

    def once(self, key: str, compute: Callable):
        """compute() the first time; its result, or the error it raised, every time after (a
        failed limit analysis is not run again by each section that needs it)."""
        if key not in self.cache:
            try:
                self.cache[key] = compute()
            except Exception as exc:  # noqa: BLE001 - kept and raised again, not swallowed
                self.cache[key] = _Failed(exc)
        value = self.cache[key]
        if isinstance(value, _Failed):
            raise value.exc
        return value

    @property
    def limit(self):
        from ..statics.limit import limit_analysis

        return self.once("limit", lambda: limit_analysis(self.arch, verify=True))

    @property
    def records(self) -> list:
        """The accelerograms of the configuration, read once."""
        from ..groundmotion import load_record

        return self.once("records", lambda: [load_record(f, units=self.config.record_units)
                                             for f in self.config.records])

    @property
    def model(self):
        from ..dynamics.response import prepare

        return self.once("model", lambda: prepare(self.arch, self.config.impact, limit=self.limit))

    @property
    def friction(self) -> dict | None:
        """What friction does to k, computed once: {"needed": {"l": mu or None, "r": ...} (None:
        no finite friction suffices), "mu": MASONRY_FRICTION, "with_mu": {"l": k, "r": k} or
        None, "with_mu_error": why not, or None}; None when archrock.statics.friction does not import."""
        return self.once("friction", self._friction)

    def _friction(self):
        try:
            from ..statics.friction import friction_analysis, friction_needed
        except ImportError:
            return None
        out = {"needed": friction_needed(self.arch), "mu": MASONRY_FRICTION, "with_mu": None,
               "with_mu_error": None, "sliding_governs": None}
        try:
            fa = friction_analysis(self.arch, MASONRY_FRICTION)
        except ArchrockError as exc:  # e.g. the joints slide under self-weight at this mu
            out["with_mu_error"] = " ".join(str(exc).split())
        else:
            out["with_mu"] = {d: fa.direction(d).multiplier for d in ("l", "r")}
            out["sliding_governs"] = {d: fa.direction(d).sliding_governs for d in ("l", "r")}
        return out


def titled(key: str, title: str):
    """Decorator naming a section function's key and title (used when it cannot be computed)."""
    def mark(func):
        func.key, func.title = key, title
        return func
    return mark


def _f(x, spec=".4f") -> str:
    if x is None:
        return "-"
    if isinstance(x, float) and not math.isfinite(x):
        return "no collapse in the scan"
    return format(x, spec)


# ---------------------------------------------------------------------------- sections
def arch_extent(arch: VoussoirArch) -> tuple[float, float, float, float]:
    """(x_min, x_max, y_min, y_max) of the masonry [m]: of the voussoirs' outlines, so that the
    height is the extrados crown's (the crown is inside a voussoir when n is odd, above the
    corners of the joints).  A circular :class:`Arch`'s arcs are taken exactly (their highest
    point is the extrados radius where an arc crosses the vertical through the centre)."""
    jp = np.asarray(arch.joint_points, float).reshape(-1, 2)
    pts = [jp] + [np.asarray(arch.outline(i), float) for i in range(arch.n)]
    allp = np.vstack(pts)
    x0, x1 = float(allp[:, 0].min()), float(allp[:, 0].max())
    y0, y1 = float(allp[:, 1].min()), float(allp[:, 1].max())
    if isinstance(arch, Arch):
        psi = np.asarray(arch.joint_angles, float)
        ro = np.asarray(arch.extrados_radii, float)
        for i in range(arch.n):  # exact extremes of each extrados arc (centre at the origin)
            a, b = sorted((psi[i], psi[i + 1]))
            for ang, fx, fy in ((0.5 * math.pi, 0, 1), (0.0, 1, 0), (math.pi, -1, 0)):
                if a <= ang <= b:
                    x0, x1 = min(x0, fx * ro[i]), max(x1, fx * ro[i])
                    y1 = max(y1, fy * ro[i])
    return x0, x1, y0, y1


def _shape_lines(arch: VoussoirArch) -> tuple[str, dict]:
    """The arch's defining dimensions as a sentence and a dict: R, t, t/R and the embrace of a
    circular arch; shape, span, rise, rise/span and thickness of a family's."""
    if isinstance(arch, Arch):
        R, t = np.asarray(arch.radii, float), np.asarray(arch.thicknesses, float)
        emb = math.degrees(float(np.sum(arch.spans)))
        d = {"radius": float(R.mean()), "thickness": float(t.mean()),
             "t_over_R": float((t / R).mean()), "embrace_deg": emb}
        if np.ptp(R) <= 1e-12 * R.mean() and np.ptp(t) <= 1e-12 * t.mean():
            txt = (f"mean radius R = {R[0]:g} m, thickness t = {t[0]:g} m, t/R = "
                   f"{t[0] / R[0]:.4f}, embrace {emb:g} deg")
        else:
            d.update(radius_range=[float(R.min()), float(R.max())],
                     thickness_range=[float(t.min()), float(t.max())])
            txt = (f"mean radius R = {R.mean():.4g} m ({R.min():.4g}-{R.max():.4g}), thickness "
                   f"t = {t.mean():.4g} m ({t.min():.4g}-{t.max():.4g}), mean t/R = "
                   f"{d['t_over_R']:.4f}, embrace {emb:.4g} deg")
        return txt, d
    recipe = getattr(arch, "recipe", None)
    if recipe:
        S, F, t = recipe["span"], recipe["rise"], recipe["thickness"]
        tc = recipe.get("thickness_crown")
        d = {"shape": recipe["shape"], "span": S, "rise": F, "rise_over_span": F / S,
             "thickness": t, "thickness_crown": tc, "t_over_span": t / S,
             "joints": recipe.get("joints")}
        txt = (f"{recipe['shape']} family: centreline span S = {S:g} m, rise F = {F:g} m, "
               f"F/S = {F / S:.4f}, thickness t = {t:g} m"
               + (f" (crown {tc:g} m)" if tc is not None else "")
               + f", t/S = {t / S:.4f}, {recipe.get('joints', 'normal')} joints")
        return txt, d
    return "a polygon arch (surveyed or drawn): its dimensions are those measured below", {}


@titled('geometry', 'Geometry')
def section_geometry(ctx: Context) -> Section:
    arch = ctx.arch
    jp = np.asarray(arch.joint_points, float)
    x0, x1, y0, y1 = arch_extent(arch)
    span, rise = x1 - x0, y1 - y0
    shape_txt, shape = _shape_lines(arch)
    masses = np.asarray(arch.masses, float)
    from ..geometry.blocks import arch_phrase, block_counts, block_name, describe_blocks

    counts = block_counts(arch)
    piers = counts["piers"] > 0
    # on piers each block named by kind (voussoirs in the arch's own numbering)
    rows = tuple((f"{i} ({block_name(arch, i)})" if piers else i, f"{m:.1f}", f"{c[0]:.3f}",
                  f"{c[1]:.3f}", f"{math.hypot(*(jp[i, 1] - jp[i, 0])):.3f}")
                 for i, (m, c) in enumerate(zip(masses, arch.centroids)))
    kind = "circular (exact sectors)" if isinstance(arch, Arch) else type(arch).__name__

    # blocks by kind: "an arch of 9 voussoirs on two piers", never "of 11 voussoirs"
    adjective = {"Arch": "circular (exact sectors)", "PolygonArch": "polygon",
                 "FamilyArch": "family"}.get(type(arch).__name__, "")
    blocks = [Paragraph(f"{arch.name}: {arch_phrase(arch, adjective)}; {shape_txt}."),
              Paragraph(f"Measured on the masonry: overall span {span:.3f} m (outside to outside), "
                        f"height {rise:.3f} m (from the lowest point of the springings to the top "
                        f"of the extrados at the crown), mass {masses.sum():.1f} kg per metre of "
                        f"depth" + (f", {len(arch.loads)} attached load(s)" if arch.loads else "")
                        + "."),
              Figure("arch", f"{arch.name}: {'blocks' if piers else 'voussoirs'} and joints "
                             f"(joint 0 at the left {'pier foot' if piers else 'springing'}).",
                     arch),
              Table(("block" if piers else "voussoir", "mass [kg/m]", "x_G [m]", "y_G [m]",
                     "joint i contact length [m]"), rows,
                    ("Each block (piers and voussoirs, in chain order from the left pier's foot)"
                     if piers else "Each voussoir") + " with its loads; joint i is its left face.")]
    data = {"name": arch.name, "kind": kind, "voussoirs": counts["voussoirs"], "blocks": counts,
            "span": span, "height": rise,
            "mass": float(masses.sum()), "dimensions": shape, "geometry": arch.to_dict(),
            "units": {"span": "m", "height": "m", "mass": "kg/m", "radius": "m",
                      "thickness": "m", "embrace_deg": "deg", "rise": "m"}}
    head = [("arch", shape_txt), ("blocks", describe_blocks(arch)),
            ("span x height [m]", f"{span:.3f} x {rise:.3f}"),
            ("mass [kg/m]", f"{masses.sum():.1f}")]
    return Section("geometry", "Geometry", tuple(blocks), data, tuple(head))


@titled('limit', 'Limit analysis (both directions)')
def section_limit(ctx: Context) -> Section:
    lim = ctx.limit
    rows = []
    for d in ("l", "r"):
        m = lim.mechanism(d)
        hinges = ", ".join(f"{lab}: joint {h.joint} {h.edge}" for lab, h in m.labelled())
        st = lim.static_k_l if d == "l" else lim.static_k_r
        rows.append((f"M_{d}", _f(m.multiplier, ".6f"), _f(st, ".6f"), m.label, hinges))
    blocks = (
        Paragraph("Horizontal forces proportional to the weight, toward +x (M_l) or -x (M_r), "
                  "with Heyman's hypotheses; k is the smallest multiplier of the weight that "
                  "opens a four-hinge mechanism (kinematic enumeration), checked by the static "
                  f"theorem (a linear program): they differ by {_f(lim.discrepancy, '.1e')}. "
                  "The arch rocks when the ground acceleration reaches -k_l g (M_l) or +k_r g (M_r)."),
        Table(("mechanism", "k (kinematic)", "k (static LP)", "hinges", "A..D from the leading side"),
              tuple(rows)),
        Figure("limit", "Collapse mechanisms and lines of thrust at the collapse multipliers "
                        "(as the paper's Fig. 3), both directions.", lim),
    )
    data = {"k_l": lim.k_l, "k_r": lim.k_r, "k": lim.k, "static_k_l": lim.static_k_l,
            "static_k_r": lim.static_k_r, "discrepancy": lim.discrepancy, "method": lim.method,
            "mechanism_l": lim.mechanism_l.to_dict(), "mechanism_r": lim.mechanism_r.to_dict(),
            "units": {"k": "g"}}
    try:
        fr = ctx.friction
    except Exception:  # noqa: BLE001 - the friction section says why; k stands without it
        fr = None
    notes = {d: friction_note(fr, d) for d in ("l", "r")}
    if fr is not None:
        data["friction"] = {"mu": fr["mu"], "source": MASONRY_FRICTION_SOURCE,
                            "needed": fr["needed"], "k_with_mu": fr["with_mu"],
                            "with_mu_error": fr["with_mu_error"], "notes": notes,
                            "caveat": friction_caveat(fr)}
        if any(notes.values()):
            blocks = blocks + (Paragraph("Friction: " + " ".join(
                f"M_{d}: {notes[d]}." for d in ("l", "r") if notes[d])),)
    head = tuple((f"k_{d} [g]", f"{getattr(lim, f'k_{d}'):.6f}"
                  + (f" - {notes[d]}" if notes[d] else "")) for d in ("l", "r"))
    return Section("limit", "Limit analysis (both directions)", blocks, data, head)


@titled('supports', 'Supports that have moved')
def section_supports(ctx: Context) -> Section | None:
    """The arch on moved supports (docs/supports.md): the movement, the hinges it opened, the
    multipliers on the displaced arch beside those on fixed supports, and the capacity that
    remains along the movement's direction.  None (left out) on fixed supports."""
    from ..statics.limit import limit_analysis
    from ..statics.supports import (displace, gap_closing, moved_parts, movement_capacity,
                                    movement_size)

    base, mv = moved_parts(ctx.arch)
    if mv is None:
        return None
    lim, fixed = ctx.limit, limit_analysis(base, verify=False)
    st = displace(base, mv)
    labels = ", ".join(f"{h.joint}{h.edge[0]}" for h in st.hinges) or "none (a rigid move)"
    rows = [("k_l [g]", f"{fixed.k_l:.6f}", f"{lim.k_l:.6f}"),
            ("k_r [g]", f"{fixed.k_r:.6f}", f"{lim.k_r:.6f}")]
    data = {"movement": mv.to_dict(), "hinges": [h.to_dict() for h in st.hinges],
            "points": st.points.tolist(), "fixed": {"k_l": fixed.k_l, "k_r": fixed.k_r},
            "moved": {"k_l": lim.k_l, "k_r": lim.k_r}, "units": {"k": "g", "H": "N/m",
                                                                 "movement": "m"}}
    text = (f"The supports have moved: {mv.describe()}. Hinges {labels} opened; the arch is "
            f"analysed on the displaced geometry with those joints bearing on whole faces again "
            f"(re-closed, docs/supports.md), as every other section of this report takes it.")
    if st.hinges:
        rows.append(("thrust H [kN/m]", "-", f"{st.thrust / 1e3:.4g}"))
        rows.append(("crown drop [m]", "0", f"{st.crown_drop:.4g}"))
        data.update(H=st.thrust, crown_drop=st.crown_drop)
    head = [("support movement", mv.describe())]
    blocks = [Paragraph(text)]
    if np.any(mv.relative) or mv.rotation:
        cap = movement_capacity(base, mv)
        mag = movement_size(base, mv)  # in the capacity's units: rad for a turn alone, else m
        unit = "rad" if cap.fraction is None else "m"
        left = cap.capacity - mag
        mech = ", ".join(f"{h.joint}{h.edge[0]}" for h in cap.mechanism)
        span = "" if cap.fraction is None else f"{100 * cap.fraction:.3g}% of the span; "
        blocks.append(Paragraph(
            f"Pushed further the same way, the arch stands up to {cap.capacity:.4g} {unit} of "
            f"this movement ({span}{cap.reason}, hinges {mech}): {left:.4g} {unit} remain, "
            f"{cap.capacity / mag:.3g} times the movement so far"
            + (f" (a turn with a translation is measured as hypot(spread, settlement, rotation x "
               f"{base.size:.4g} m), docs/supports.md)" if mv.rotation and unit == "m" else "")
            + "."))
        data["capacity"] = {k: v for k, v in cap.to_dict().items() if k != "curve"}
        data["capacity_remaining"] = left
        data["units"]["capacity"] = unit
        head.append((f"support capacity remaining [{unit}]",
                     f"{left:.4g} ({cap.capacity / mag:.3g} x the movement)"))
        gc = gap_closing(ctx.arch)
        if gc is not None:
            shut = sorted(set(gc.closing_l) | set(gc.closing_r))
            blocks.append(Paragraph(
                f"Before those multipliers, the open joints' point contacts let the arch rock "
                f"from k_l = {gc.k_l:.4g}, k_r = {gc.k_r:.4g} g, turning joint(s) "
                f"{', '.join(map(str, shut))} back until their gaps close: a bounded motion, "
                f"not a collapse."))
            data["gap_closing"] = gc.to_dict()
    blocks += [Table(("", "fixed supports", "moved supports"), tuple(rows)),
               Figure("arch", f"{ctx.arch.name}: the arch on its moved supports.", ctx.arch)]
    return Section("supports", "Supports that have moved", tuple(blocks), data, tuple(head))
@titled('piers', 'The piers')
def section_piers(ctx: Context) -> Section | None:
    """An arch on piers (docs/piers.md): each pier's size, where the mechanisms' hinges are
    (named as ``archrock limit`` names them), the least width of rectangular piers of that
    height that carry the arch (statics.buttress), and whether the four-link model (one
    degree of freedom) can follow the structure (dynamics.piers).  None (left out) on rigid
    ground."""
    from ..geometry.piers import ArchOnPiers, arch_without_piers, hinge_place, pier_sizes

    arch = ctx.arch
    guessed = ""
    if not isinstance(arch, ArchOnPiers) or not arch.pier_blocks:
        # a geometry file that names no kinds: the end blocks the single-DOF check takes for
        # piers (heavy, rising as columns from level foundations), if any
        from ..dynamics.piers import pier_blocks

        found, how = pier_blocks(arch) if isinstance(arch, PolygonArch) else ((), "none")
        if how != "geometry":
            return None
        kinds = tuple("pier" if i in found else "voussoir" for i in range(arch.n))
        arch = ArchOnPiers(arch.intrados, arch.extrados, arch.density, arch.name, arch.loads,
                           block_kinds=kinds)
        guessed = (f" The geometry names no block kinds: block(s) "
                   f"{', '.join(map(str, found))} are taken for piers (heavy end blocks rising "
                   f"as columns from level foundations; kinds in the file would say so).")
    sizes = pier_sizes(arch)
    rows = tuple((side, sz["kind"], sz["blocks"], f"{sz['height']:.3f}",
                  f"{sz['width_top']:.3f}" if math.isfinite(sz["width_top"]) else "-",
                  f"{sz['width_foot']:.3f}",
                  f"{sz['lean_deg']:.3f}") for side, sz in sizes.items())
    words = "; ".join(f"{side} {sz['kind']} {sz['height']:.3g} m high, "
                      f"{sz['width_top']:.3g} m wide at its top and {sz['width_foot']:.3g} m at "
                      f"its foot, {sz['blocks']} block(s)"
                      + (f", {abs(sz['lean_deg']):.3g} deg out of plumb "
                         f"{'outward' if sz['lean_deg'] > 0 else 'inward'}"
                         if abs(sz["lean_deg"]) > 1e-9 else "") for side, sz in sizes.items())
    blocks = [Paragraph(f"The arch stands on piers ({words}). Blocks are numbered from the "
                        f"left pier's foot; hinges are named where they are on the drawing."
                        + guessed),
              Table(("pier", "kind", "blocks", "height [m]", "width at top [m]",
                     "width at foot [m]", "lean [deg, outward +]"), rows,
                    "Sizes in each pier's own frame (turned back by its lean).")]
    lim = ctx.limit
    hinge_rows, at_piers = [], []
    for d in ("l", "r"):
        for lab, h in lim.mechanism(d).labelled():
            place = hinge_place(arch, h.joint, h.edge)
            hinge_rows.append((f"M_{d}", lab, f"{h.joint}{h.edge[0]}", place))
            if "pier" in place or "buttress" in place:
                at_piers.append(f"M_{d} {lab}: {place}")
    blocks.append(Table(("mechanism", "hinge", "joint", "where"), tuple(hinge_rows),
                        "The hinges of the limit mechanisms, named as archrock limit names "
                        "them."))
    data = {"piers": sizes, "hinges": [dict(zip(("mechanism", "hinge", "joint", "place"), r))
                                       for r in hinge_rows],
            "units": {"height": "m", "width_top": "m", "width_foot": "m", "foot_level": "m",
                      "lean_deg": "deg"}}
    head = [("piers", words)]
    if at_piers:
        blocks.append(Paragraph("Hinges in the piers: " + "; ".join(at_piers) + "."))
    # the buttress question: the least width of rectangular piers of this height
    from ..statics.buttress import minimum_pier_width

    mins = {}
    for h in sorted({round(sz["height"], 9) for sz in sizes.values()}):
        try:
            mw = minimum_pier_width(arch_without_piers(arch), h, tol=1e-6)
            mins[h] = {"width": mw.width, "governed_by": mw.governed_by}
        except ArchrockError as exc:
            mins[h] = {"width": None, "error": " ".join(str(exc).split())}
    data["minimum_pier_width"] = [{"height": h, **v} for h, v in mins.items()]
    txt = []
    for side, sz in sizes.items():
        m = mins[round(sz["height"], 9)]
        if m["width"] is None:
            txt.append(f"{side}: not computed ({m['error']})")
        else:
            ratio = sz["width_top"] / m["width"] if math.isfinite(sz["width_top"]) else math.nan
            txt.append(f"{side}: {m['width']:.4f} m for piers {sz['height']:.3g} m high "
                       f"(this pier {sz['width_top']:.3g} m, {ratio:.2f} x"
                       + (", the springing joint's own width governs" if m["governed_by"] ==
                          "springing" else "") + ")")
    blocks.append(Paragraph("The least width of two rectangular monolithic piers of this height "
                            "with which the arch stands under its own weight (a line of thrust "
                            "inside arch and piers; Heyman 1995, Ochsendorf 2002): "
                            + "; ".join(txt) + "."))
    # one degree of freedom or more (docs/piers-dynamics.md)
    try:
        from ..dynamics.piers import single_dof_check

        chk = single_dof_check(ctx.model)
        data["single_dof"] = chk.to_dict()
        if not chk.valid:
            blocks.append(Paragraph(
                f"WARNING single degree of freedom not valid: {chk.reason}. The response, "
                f"curves and fragility of this report are the four-link model's: on piers they "
                f"can be unconservative (docs/piers-dynamics.md)."))
            head.append(("four-link model on piers", "not valid: a pier rocks with the arch "
                         "(figures can be unconservative)"))
    except ArchrockError as exc:
        data["single_dof"] = {"error": " ".join(str(exc).split())}
    return Section("piers", "The piers", tuple(blocks), data, tuple(head))


def _mu(x) -> str:
    return "no finite friction" if x is None else f"{x:.3f}"


def friction_note(fr: dict | None, d: str) -> str:
    """'' where the masonry's friction (MASONRY_FRICTION) is enough for k in direction ``d``;
    else what k needs and the multiplier with that friction (or why there is none)."""
    if fr is None:
        return ""
    need = fr["needed"][d]
    mu = fr["mu"]
    if need is not None and need <= mu:
        return ""
    what = ("needs more friction than any finite coefficient (no finite friction)"
            if need is None else f"needs friction mu >= {need:.3f}")
    head = f"{what}, more than masonry's mu = {mu:g} ({MASONRY_FRICTION_SOURCE}); "
    if fr["with_mu"] is not None:
        return head + f"with mu = {mu:g} the joints slide first, at k_{d} = {fr['with_mu'][d]:.4f}"
    return head + f"with mu = {mu:g} no multiplier ({fr['with_mu_error']})"


def friction_caveat(fr: dict | None) -> str:
    """One sentence for the verdict where k needs more friction than masonry has ('' where it
    does not): both directions at once when they need the same."""
    if fr is None:
        return ""
    short = [d for d in ("l", "r") if friction_note(fr, d)]
    if not short:
        return ""
    need, wm = fr["needed"], fr["with_mu"]
    same = (len(short) == 2 and (need["l"] is None) == (need["r"] is None)
            and (need["l"] is None or math.isclose(need["l"], need["r"], rel_tol=1e-6))
            and (wm is None or math.isclose(wm["l"], wm["r"], rel_tol=1e-6)))
    if same:
        note = friction_note(fr, "l").replace("k_l =", "k =")
        return f"k (both directions) {note}"
    return "; ".join(f"k_{d} {friction_note(fr, d)}" for d in short)



def _optional_missing(key: str, title: str, module: str, what: str) -> Section:
    return Section(key, title, (Paragraph(
        f"{what}: not available in this installation (the module archrock.{module} does not "
        f"import)."),), {"available": False, "module": f"archrock.{module}"})


@titled('friction', 'Friction the thrust needs')
def section_friction(ctx: Context) -> Section:
    """OPTIONAL: the friction coefficient the thrust needs (archrock.statics.friction)."""
    title = "Friction the thrust needs"
    fr = ctx.friction
    if fr is None:
        return _optional_missing("friction", title, "statics.friction",
                                 "The friction the limit thrust needs at the joints")
    need, mu = fr["needed"], fr["mu"]  # need: {"l": mu or None (no finite friction), "r": ...}
    lim = ctx.limit
    rows = []
    for d in ("l", "r"):
        k_mu = ("-" if fr["with_mu"] is None else f"{fr['with_mu'][d]:.4f}")
        gov = ("-" if fr["sliding_governs"] is None else
               "sliding" if fr["sliding_governs"][d] else "hinges (no sliding)")
        rows.append((f"M_{d}", _mu(need[d]), f"{getattr(lim, f'k_{d}'):.4f}", k_mu, gov))
    notes = [f"M_{d}: {friction_note(fr, d)}." for d in ("l", "r") if friction_note(fr, d)]
    verdict = (" ".join(notes) if notes else
               f"Masonry's friction mu = {mu:g} ({MASONRY_FRICTION_SOURCE}) is enough for the "
               f"multipliers above in both directions.")
    if fr["with_mu_error"] and not notes:
        verdict += f" With mu = {mu:g}: {fr['with_mu_error']}."
    return Section("friction", title, (
        Paragraph("The smallest Coulomb friction coefficient at the joints with which the thrust "
                  "at collapse needs no sliding (Heyman's no-sliding hypothesis made explicit; "
                  "static LP, docs/friction.md), and the multiplier when the joints have the "
                  f"friction of masonry, mu = {mu:g}: the coefficient 0.4 of EN 1996-1-1 "
                  "(Eurocode 6) 3.6.2, f_vk = f_vk0 + 0.4 sigma_d, taken as the friction "
                  "coefficient of the joints. Joints with less friction than needed slide before "
                  "the hinge mechanism forms: `archrock limit --friction MU` gives any other "
                  "coefficient. " + verdict),
        Table(("mechanism", "friction coefficient needed", "k, no sliding [g]",
               f"k with mu = {mu:g} [g]", f"at mu = {mu:g} governs"), tuple(rows))),
        {"available": True, "friction_needed_l": need["l"], "friction_needed_r": need["r"],
         "no_finite_friction": {d: need[d] is None for d in ("l", "r")},
         "mu_masonry": mu, "mu_source": REFERENCES["ec6"],
         "k_with_mu": fr["with_mu"], "sliding_governs": fr["sliding_governs"],
         "with_mu_error": fr["with_mu_error"]})


@titled('impact', 'Impact coefficients by model')
def section_impact(ctx: Context) -> Section:
    from ..dynamics.impact import least_loss_mechanism
    from ..dynamics.response import prepare

    lim = ctx.limit
    rows, data = [], {}
    for model in ("paper", "momentum"):
        try:
            law = prepare(ctx.arch, model, limit=lim).impact
        except ArchrockError as exc:
            rows.append((model, "-", "-", f"not applicable: {exc}"))
            data[model] = {"error": str(exc)}
            continue
        rows.append((model, f"{law.l_to_r:.5f}", f"{law.r_to_l:.5f}", f"{law.equivalent_cv:.5f}"))
        data[model] = law.to_dict()
    try:
        m = ctx.model
        ll = least_loss_mechanism(m.mech_l, m.mech_r)
        data["least_loss_after_M_l"] = ll.to_dict()
        ll_txt = (f"After an impact closing M_l, the post-impact mechanism that keeps the most "
                  f"kinetic energy under the momentum law keeps {ll.energy_ratio:.3f} of it, "
                  f"against {ll.limit_energy_ratio:.3f} for M_r (Bisegna et al. 2023).")
    except ArchrockError as exc:
        ll_txt = f"Least-loss mechanism: not found ({exc})."
    used = ctx.config.impact
    blocks = (Paragraph("At each impact the mechanism closes and the other opens; the rate of "
                        "the new mechanism is c times the old (kinetic energy times c^2 on a "
                        "symmetric arch). 'paper': De Lorenzis et al.'s five equations as the "
                        "paper applies them; 'momentum': the energy-consistent projection of the "
                        "momentum balance on the new motion."),
              Table(("model", "c (M_l -> M_r)", "c (M_r -> M_l)", "equivalent c_v"), tuple(rows)),
              Paragraph(ll_txt),
              Paragraph(f"The response and the curves below use: {used.model}"
                        + (f" (c_v {used.cv:g})" if used.cv else "") + f", evaluated on the "
                        f"{'nominal arch' if used.on == 'nominal' else 'arch'}."))
    data["used"] = used.to_dict()
    head = ()
    if "paper" in data and "l_to_r" in data["paper"]:
        head = (("c_v (paper model)", f"{data['paper']['l_to_r']:.5f}"),)
    return Section("impact", "Impact coefficients by model", blocks, data, head)


@titled('response', "Response to the paper's pulse")
def section_response(ctx: Context) -> Section:
    from ..groundmotion import oppenheim_pulse
    from ..dynamics.response import respond

    cfg = ctx.config
    motion = oppenheim_pulse(cfg.pulse_amplitude, cfg.pulse_duration)
    res = respond(ctx.model, motion, t_end=cfg.t_end)
    impacts = res.impacts
    outcome = (f"collapses (last passage of the unstable position at {res.t_collapse:.3f} s)"
               if res.collapsed else f"does not collapse ({res.status})")
    blocks = (Paragraph(f"Oppenheim's pulse: a = {cfg.pulse_amplitude:g} g for t_p = "
                        f"{cfg.pulse_duration:g} s, then -a/2 for 2 t_p (the paper's forcing). "
                        f"The arch {outcome}; peak rotation {res.peak:.4f} rad; "
                        f"{len(impacts)} impact(s)"
                        + (f", the first at {', '.join(f'{t:.4f}' for t in impacts[:3])} s"
                           if impacts else "") + "."),
              Figure("response", "Ground acceleration and the signed response (+phi in M_l, "
                                 "-phi in M_r).", res))
    data = res.to_dict(samples=False)
    data["pulse"] = {"kind": "oppenheim", "amplitude_g": cfg.pulse_amplitude,
                     "duration_s": cfg.pulse_duration}
    return Section("response", "Response to the paper's pulse", blocks, data,
                   (("paper pulse", "collapse" if res.collapsed else f"survives, peak {res.peak:.4f} rad"),))


@titled('curves', 'Collapse-acceleration curve and its band over irregular arches')
def section_curves(ctx: Context) -> Section:
    from .curves import collapse_curve, ensemble_curve
    from .enginestudy import choose_dynamics, engine_curves_section

    choice = choose_dynamics(ctx.arch)  # issue 19: where one degree of freedom cannot follow
    if choice.engine:
        return engine_curves_section(ctx, choice)
    cfg = ctx.config
    kw = dict(kind="oppenheim", sign=-1, n_scan=cfg.n_scan)
    band = None
    if cfg.samples > 0 and isinstance(ctx.arch, VoussoirArch):
        try:
            band = ensemble_curve(ctx.arch, cfg.samples, cfg.seed, cfg.spreads, cfg.durations,
                                  impact=cfg.impact, **kw)
        except ArchInputError as exc:  # an arch that cannot be perturbed: nominal curve only
            ctx.progress(f"  band over irregular arches left out: {exc}")
    curve = band.nominal if band is not None else collapse_curve(ctx.model, cfg.durations, **kw)
    rows = tuple((f"{d:g}", _f(float(a), ".4f"), m or "-")
                 for d, a, m in zip(curve.durations, curve.amplitudes, curve.modes))
    s = cfg.spreads
    band_txt = (f"The band spans the quantiles of {band.n_samples} irregular arches (seed "
                f"{cfg.seed}; spreads: span {s.span:g}, thickness {s.thickness:g}, radius "
                f"{s.radius:g} t" + (f", joint tilt {s.tilt:g} deg" if s.tilt else "")
                + ")." if band is not None else "No band: no random arches were asked for.")
    blocks = (Paragraph("For each pulse duration, the smallest amplitude of Oppenheim's pulse "
                        "(first push toward -x) that collapses the arch; collapse is not "
                        "monotonic in the amplitude, so survival windows above it are drawn. "
                        + band_txt),
              Figure("curves", "Collapse-acceleration curve.", (curve, band)),
              Table(("t_p [s]", "first collapse |a| [g]", "collapse mode"), rows))
    data = {"nominal": curve.to_dict()}
    if band is not None:
        data["band"] = band.to_dict()
    return Section("curves", "Collapse-acceleration curve and its band over irregular arches",
                   blocks, data)


@titled('defects', 'Defect map: which voussoir, if damaged, costs the most capacity')
def section_defects(ctx: Context) -> Section:
    """OPTIONAL: the defect map (archrock.studies.defectmap)."""
    title = "Defect map: which voussoir, if damaged, costs the most capacity"
    try:
        from .defectmap import defect_map
    except ImportError:
        return _optional_missing("defects", title, "studies.defectmap", "The defect map")
    res = defect_map(ctx.arch)  # 30% thickness loss about the centreline, each voussoir
    from .defectmap import worst_summary

    w = worst_summary(res)  # on piers a thinned pier course is a pier defect, said apart
    a, p = w["arch"], w["piers"]
    head = ((w["label"], f"{a['where']}: -{100 * a['relative_loss']:.1f}%"),)
    pier_txt = ""
    if p:
        pier_txt = (f" Each pier course in turn loses 30% of its width the same way: the worst "
                    f"pier defect is {p['where']}: min(k_l, k_r) falls to {p['k']:.4f} g "
                    f"({100 * p['relative_loss']:.1f}%).")
        head += (("worst pier defect", f"{p['where']}: -{100 * p['relative_loss']:.1f}%"),)
    return Section("defects", title, (
        Paragraph(f"Each voussoir in turn loses 30% of its thickness about its centreline "
                  f"(docs/defects.md). The largest loss of capacity comes from {a['where']} "
                  f"(numbered from the arch's left springing): min(k_l, k_r) falls from "
                  f"{res.k0:.4f} to {a['k']:.4f} g ({100 * a['relative_loss']:.1f}%)."
                  f"{pier_txt} `archrock defects` maps the other defects (joint tilt, missing "
                  f"mortar) and, with a pulse, the first-collapse amplitude."),
        Figure("defects", "Capacity lost when each voussoir" + (" or pier course" if p else "")
               + " is the damaged one (red: lost, blue: gained, in % of the undamaged k).",
               res)),
        {"available": True, **res.to_dict()}, head)


@titled('fragility', 'Fragility curves')
def section_fragility(ctx: Context) -> Section:
    cfg = ctx.config
    if not cfg.records:
        why = ("no accelerograms were given: fragility curves are fitted to the collapses of "
               "the arch under recorded ground motions (`archrock assess --records FILE|DIR`, "
               "PEER .AT2 or two-column files)")
        return Section("fragility", "Fragility curves", (Paragraph(f"Skipped: {why}."),),
                       {"skipped": True, "reason": why})
    from .ida import default_stripe_levels, ida, msa, random_models

    records = ctx.records
    models = (random_models(ctx.arch, cfg.samples, cfg.seed, cfg.spreads, cfg.impact)
              if cfg.samples > 0 else [ctx.model])
    res_ida = ida(records, models, np.array(cfg.scales), n_boot=cfg.bootstrap, seed=cfg.seed)
    levels = default_stripe_levels(res_ida, np.array(cfg.scales), records)
    res_msa = msa(records, models, levels, n_boot=cfg.bootstrap, seed=cfg.seed)
    fit = res_msa.fit if res_msa.fit is not None else res_ida.fit
    txt = (f"median collapse PGA theta = {fit.theta:.3f} g, dispersion beta = {fit.beta:.2f} "
           f"({fit.method})" if fit is not None else "no fit could be identified")
    blocks = (Paragraph(f"{len(records)} record(s) x {len(models)} arch(es): incremental dynamic "
                        f"analysis (first collapse per record and arch) and multiple stripes "
                        f"(binomial likelihood, Baker 2015); IM = PGA of the scaled record. {txt}."),
              Figure("fragility", "Fragility curves.", (fit, res_msa, res_ida)))
    data = {"ida": res_ida.to_dict(), "msa": res_msa.to_dict(),
            "records": [str(r) for r in cfg.records]}
    head = (("fragility median PGA [g]", f"{fit.theta:.3f}"),) if fit is not None else ()
    return Section("fragility", "Fragility curves", blocks, data, head)


@titled('contact', 'Contact-engine check')
def section_contact(ctx: Context) -> Section:
    """OPTIONAL: the contact-engine check (archrock.contact, the 'dem' extra)."""
    title = "Contact-engine check"
    try:
        from ..contact import import_pymunk, ramp
        import_pymunk()  # the package imports without pymunk; the engine needs it
    except ImportError:
        return _optional_missing("contact", title, "contact", "The contact-engine (pymunk) check")
    lim = ctx.limit
    # default EngineSettings: within 1% of k on the documented arches; the ramp's range follows
    # the arch's k (max(2, 1.5 k), archrock.contact.ramp_range); an arch that does not move in
    # it is an outcome said in this section (LimitExceededError), the report goes on
    res = ramp(ctx.arch, limit=lim)
    rows = []
    for d in ("l", "r"):
        eng, mech = res.l if d == "l" else res.r, lim.mechanism(d)
        rows.append((f"M_{d}", f"{eng.multiplier:.4f}", f"{mech.multiplier:.4f}",
                     f"{100 * (eng.multiplier / mech.multiplier - 1):+.1f}%",
                     " ".join(map(str, eng.hinges)) + ("" if eng.mode == "rocking" else
                                                       f" ({eng.mode})"),
                     " ".join(map(str, mech.joints))))
    return Section("contact", title, (
        Paragraph("The same voussoirs as rigid bodies with contact and Coulomb friction "
                  f"(mu = {res.settings.friction:g}) in the pymunk engine, under a slowly "
                  "increasing horizontal ground acceleration in each direction (up to |xg''|/g = "
                  + " / ".join(f"{res.ramp['lambda_max'][d]:.3g}" for d in ("l", "r"))
                  + ", i.e. max(2, 1.5 k)): the acceleration "
                  "at which the arch starts to move and the joints that open, beside the limit "
                  "analysis (docs/verification.md, Contact engine). Joints are numbered from the "
                  "left springing (0)." + _engine_friction_note(ctx, res.settings.friction)),
        Table(("direction", "engine multiplier", "limit analysis k", "difference",
               "engine hinges", "limit hinges"), tuple(rows))),
        {"available": True, **res.to_dict()},
        (("contact engine k_l / k_r", f"{res.k_l:.4f} / {res.k_r:.4f}"),))


def _engine_friction_note(ctx: Context, mu: float) -> str:
    try:
        fr = ctx.friction
    except Exception:  # noqa: BLE001 - said in the friction section
        return ""
    if fr is None:
        return ""
    short = [d for d in ("l", "r") if fr["needed"][d] is None or fr["needed"][d] > mu]
    if not short:
        return ""
    return (" The engine's friction is less than the no-sliding collapse needs in "
            + " and ".join(f"M_{d} ({_mu(fr['needed'][d])})" for d in short)
            + ": there the engine's joints slide first and its multiplier is below k.")


@titled('codecheck', 'Code check: kinematic analysis (NTC 2018 / Circolare 2019)')
def section_codecheck(ctx: Context) -> Section:
    from .codecheck import code_check
    from ..units import G

    cfg = ctx.config.codecheck
    res = code_check(ctx.arch, ctx.limit, cfg)
    dirs = res.directions
    rows = [("activation multiplier alpha_0", *[f"{c.alpha_0:.6f}" for c in dirs]),
            ("participating mass M* [kg/m]", *[f"{c.m_star:.1f}" for c in dirs]),
            ("mass fraction e*", *[f"{c.e_star:.4f}" for c in dirs]),
            (f"a_0* [g] (FC = {cfg.fc:g})", *[f"{c.a0_star / G:.4f}" for c in dirs]),
            ("d_0* [m]", *[f"{c.d0_star:.4f}" for c in dirs]),
            (f"d_u* = {cfg.ultimate_fraction:g} d_0* [m]", *[f"{c.du_star:.4f}" for c in dirs]),
            ("T_s [s]", *[f"{c.ts:.3f}" for c in dirs])]
    for kind, lab in (("linear", "linear check a_0* / (Se(0)/q)"),
                      ("nonlinear", "nonlinear check d_u* / S_De(T_s)")):
        if all(kind in c.checks for c in dirs):
            rows.append((lab, *[f"{c.checks[kind]['ratio']:.3f} "
                                f"{'pass' if c.checks[kind]['passed'] else 'FAIL'}" for c in dirs]))
    spec = cfg.spectrum
    spec_txt = ("No site spectrum was given (--spectrum FILE, or --ag --f0 --tc-star --soil, "
                "or --ec8-type): the table gives the capacity only, and there is no verdict: "
                "the check compares the capacity with a site's demand." if spec is None
                else f"Site spectrum: {spec.kind}"
                + (f" ({spec.source})" if spec.source else "") + f", Se(0) = {spec.pga:.3f} g.")
    blocks = (Paragraph("The kinematic analysis of local mechanisms of the Italian code (NTC 2018 "
                        "par. 8.7.1, Circolare 2019 C8.7.1.2), applied to the mechanisms that "
                        "limit analysis found, the arch's springings at ground level. The capacity "
                        "curve is the exact equilibrium of the displaced four-link mechanism; the "
                        "code's straight line is drawn beside it. " + spec_txt
                        + " Formulas and clauses: docs/codecheck.md."),
              Table(("quantity", *[f"M_{c.direction}" for c in dirs]), tuple(rows)),
              Figure("codecheck", "Capacity curves a*(d*) of both mechanisms, d_u*, d_s* and the "
                                  "secant period; the demand S_De(T_s) when a spectrum is given.",
                     res))
    head = [("code check a_0* [g]", f"{min(c.a0_star for c in dirs) / G:.4f}")]
    if res.passed is not None:
        head.append(("code check", "pass" if res.passed else "FAIL"))
    return Section("codecheck", "Code check: kinematic analysis (NTC 2018 / Circolare 2019)",
                   blocks, res.to_dict(), tuple(head))


@titled('assumptions', 'Assumptions, conventions and references')
def section_assumptions(ctx: Context) -> Section:
    cfg = ctx.config
    items = [
        "Units: SI; lengths in metres, masses per metre of the arch's depth (a plane problem), "
        "accelerations in g (9.81 m/s^2) unless marked m/s^2. x to the right, y up; joint 0 is "
        "the left springing.",
        "Masonry (Heyman): no tensile strength, unlimited compressive strength, no sliding at the "
        "joints; voussoirs are rigid; hinges form at the ends of each joint's contact segment.",
        "Loads: the weight of each voussoir (with any attached load) and a horizontal force "
        "lambda times it, at its mass centre. M_l: forces toward +x, activated by a ground "
        "acceleration toward -x of k_l g; M_r the mirror case.",
        "Dynamics (Oppenheim 1992): once activated the arch moves as a single-degree-of-freedom "
        "four-link mechanism with exact large-rotation kinematics; at each impact the other "
        "mechanism opens with the chosen impact law; the arch collapses when the rotation "
        "passes the unstable position for the last time before the rotation limit.",
        f"Impact law: {cfg.impact.model} on the {cfg.impact.on} arch"
        + (f" (c_v {cfg.impact.cv:g})" if cfg.impact.cv else "") + ".",
        "Irregular arches: spans, thicknesses and radii of the voussoirs drawn uniformly within "
        "the spreads around the nominal arch (docs/method.md, Geometry widths); sample i is the "
        "same arch in every study of a seed.",
        "Code check: the mechanism is at ground level (the springings on the ground); the code's "
        "straight-line capacity curve is replaced by the exact curve of the four-link model "
        "(both reported); FC divides accelerations only; EN 1998-3 has no such procedure, so only "
        "its spectrum (EN 1998-1) can be used with it.",
        "Not modelled: sliding, crushing, the fill and spandrels (unless given as loads), the "
        "deformability of the piers, vertical ground motion, damping other than impacts.",
    ]
    refs = [f"[{k}] {v}" for k, v in REFERENCES.items()]
    blocks = tuple(Paragraph(t) for t in items) + (Table(("reference",), tuple((r,) for r in refs),
                                                          "References (cited as text)."),)
    return Section("assumptions", "Assumptions, conventions and references", blocks,
                   {"assumptions": items, "references": REFERENCES, "config": cfg.to_dict()})


#: The report's sections in order.  Optional ones (friction, defects, contact) say so when their
#: module is absent; fragility appears only with records.
SECTIONS: list[Callable[[Context], Section | None]] = [
    section_geometry, section_limit,
    section_piers,  # left out on rigid ground (docs/piers.md)
    section_supports,  # left out on fixed supports (docs/supports.md)
    section_friction, section_impact, section_response,
    section_curves, section_defects, section_fragility, section_contact, section_codecheck,
    section_assumptions,
]


@dataclass(frozen=True)
class Assessment:
    """The result of :func:`assess`: the arch, the configuration, the sections in order and the
    total time [s]."""

    arch: VoussoirArch = field(repr=False)
    config: AssessConfig
    sections: tuple
    seconds: float
    version: str = ""

    def section(self, key: str) -> Section:
        return {s.key: s for s in self.sections}[key]

    @property
    def headline(self) -> list:
        return [h for s in self.sections for h in s.headline]

    @property
    def verdict(self) -> dict:
        """{"status": "pass" | "fail" | "none", "text": the verdict in words}: the code check
        against the site spectrum (both mechanisms, every check), with the friction caveat where
        k needs more friction than masonry has; "none" with the reason where there is no
        spectrum or no code check."""
        secs = {s.key: s for s in self.sections}
        cc = secs.get("codecheck")
        caveat = ""
        lim = secs.get("limit")
        fr = (lim.data.get("friction") or {}).get("caveat") if lim is not None else None
        if fr:
            caveat = (f" This is on Heyman's no-sliding hypothesis: {fr} (section Friction the "
                      f"thrust needs).")
        if cc is None:
            return {"status": "none", "text": "No verdict: the code check was not part of this "
                                              "report."}
        if "error" in cc.data:
            return {"status": "none", "text": f"No verdict: the code check could not be "
                                              f"computed ({cc.data['error']})."}
        passed = cc.data.get("passed")
        if passed is None:
            return {"status": "none", "text": (
                "No verdict: no site spectrum was given (--spectrum FILE, or --ag --f0 --tc-star "
                "--soil, or --ec8-type), so there is no demand to compare the capacity with; the "
                "report gives the arch's capacity (k, a_0*, d_u*) only." + caveat)}
        word = "passes" if passed else "FAILS"
        return {"status": "pass" if passed else "fail", "text": (
            f"The arch {word} the kinematic check of NTC 2018 / Circolare 2019 (both mechanisms, "
            f"linear and nonlinear checks) for the given site spectrum." + caveat)}

    def to_dict(self) -> dict:
        return {"arch": self.arch.name, "archrock_version": self.version,
                "config": self.config.to_dict(), "seconds": self.seconds,
                "verdict": self.verdict,
                "headline": [list(h) for h in self.headline],
                "sections": {s.key: {"title": s.title, "seconds": s.seconds, "data": s.data}
                             for s in self.sections}}


def _version() -> str:
    try:
        from importlib.metadata import version

        return version("archrock")
    except Exception:
        return "unknown"


def assess(arch: VoussoirArch, config: AssessConfig | None = None, *,
           progress=UNSET, sections=None, settings=None) -> Assessment:
    """Run every section of :data:`SECTIONS` (or ``sections``) on ``arch``; the ``progress``
    of ``settings`` (a :class:`~archrock.studies.runner.RunSettings`; 0.6's ``progress=``
    with a DeprecationWarning) receives one line per section as it starts and ends."""
    from .runner import resolve_settings

    progress = resolve_settings(settings, "assess", progress=progress).only("assess").sink
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    ctx = Context(arch, AssessConfig() if config is None else config,
                  progress or (lambda msg: None))
    ctx.records  # read (and check) the records before any long computation
    out = []
    t_all = time.perf_counter()
    for k, func in enumerate(SECTIONS if sections is None else sections, 1):
        name = func.__name__.removeprefix("section_")
        ctx.progress(f"[{k}/{len(SECTIONS if sections is None else sections)}] {name} ...")
        t0 = time.perf_counter()
        try:
            sec = func(ctx)
        except Exception as exc:  # noqa: BLE001 - one section lost, never the whole report
            # an outcome (an impact law that cannot apply, a ramp whose range the arch does not
            # move in, ...) or anything else: the section says why and the report goes on.  The
            # user's input (arch, configuration, records) is checked before this loop.
            key = getattr(func, "key", name)
            msg = " ".join(str(exc).split()) or type(exc).__name__
            if not isinstance(exc, ArchrockError):
                msg = f"internal error ({type(exc).__name__}): {msg}"
            sec = Section(key, getattr(func, "title", name), (Paragraph(
                f"Not computed: {msg}"),), {"error": msg, "error_type": type(exc).__name__})
            ctx.progress(f"      {name}: not computed ({type(exc).__name__})")
        dt = time.perf_counter() - t0
        if sec is None:
            ctx.progress(f"      {name}: left out")
            continue
        out.append(Section(sec.key, sec.title, sec.blocks, sec.data, sec.headline, round(dt, 3)))
        ctx.progress(f"      {name}: {dt:.1f} s")
    return Assessment(arch, ctx.config, tuple(out), round(time.perf_counter() - t_all, 3),
                      _version())
