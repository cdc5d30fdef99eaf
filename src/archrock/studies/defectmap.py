"""Defect maps: which voussoir (or joint), if damaged, costs the arch the most capacity.

:func:`defect_map` applies one kind of :class:`~archrock.geometry.Defect` (a thickness loss, a
joint tilt, a missing mortar depth) to each voussoir (or joint) in turn and records, for each
damaged arch, the limit analysis in both directions (k_l, k_r [g] and the hinges of M_l, M_r)
and, with a pulse, the first collapse amplitude at one duration
(:func:`archrock.studies.curves.collapse_amplitude`).  The capacity lost is the drop of
min(k_l, k_r), or of the first collapse amplitude, from the undamaged arch's.

An arch that can no longer stand under its own weight has lost all its capacity: its k_l and
k_r are recorded as NaN (null in JSON), ``stands`` False, and its loss is the whole nominal k.

On an arch on piers the indices are the chain's (block 0 the left pier's foot course), and each
damaged block or joint is named and grouped by kind (:attr:`DefectMap.places`,
:attr:`DefectMap.groups`): the arch's own voussoirs and joints ("voussoir 3", numbered from the
arch's left springing; "arch joint 2") apart from the piers' courses and bed joints ("left pier
course 1", "right pier foot").  A thinned pier course is a pier defect: the worst of each group
is reported apart (:attr:`DefectMap.worst_all`, :attr:`DefectMap.worst_pier_all`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..errors import UNUSABLE_ARCH, ArchInputError, CannotStandError, GeometryOutcome
from ..geometry import Defect, VoussoirArch, apply_defect
from ..geometry.blocks import block_counts, block_name
from ..geometry.defect import defect_base
from ..geometry.piers import _pier_runs, joint_place
from ..statics.kinematic import kinematic_mechanisms
from .runner import RunSettings

__all__ = ["DefectMap", "defect_map", "defect_places", "names_text", "worst_summary"]

#: The groups of a defect map's rows: the arch's own voussoirs and joints, and the piers'
#: courses and bed joints (foundations included).
GROUPS = ("arch", "piers")


def names_text(places, sep: str = ", ", tied: str = " (tied)") -> str:
    """'voussoir 2', 'voussoirs 2, 6 (tied)', 'left pier, right pier (tied)': damaged places
    in words (``sep`` between several names, ``tied`` after them)."""
    places = list(places)
    if len(places) == 1:
        return places[0]
    for word in ("voussoir", "arch joint", "joint"):
        if all(p.startswith(word + " ") for p in places):
            return f"{word}s {sep.join(p[len(word) + 1:] for p in places)}{tied}"
    return sep.join(places) + tied


def worst_summary(dmap, sep: str = " and ", tied: str = "") -> dict:
    """The worst defects of ``dmap`` in words, the arch's and (on piers) the piers' apart:
    {"arch": {"where", "k", "relative_loss"}, "piers": the same or None, "label": "worst
    defect" or "worst voussoir defect"} (the assessment report's summary rows)."""
    def one(ties):
        m = int(np.flatnonzero(dmap.indices == ties[0])[0])
        return {"where": names_text([dmap.place(t) for t in ties], sep, tied),
                "k": float(dmap.k[m]), "relative_loss": float(dmap.relative_loss[m])}
    apart = bool(dmap.worst_in("arch") and dmap.worst_pier_all)
    what = "voussoir" if dmap.target == "voussoir" else "arch joint"
    return {"arch": one(dmap.worst_all), "piers": one(dmap.worst_pier_all) if apart else None,
            "label": f"worst {what} defect" if apart else "worst defect"}


def defect_places(arch, target: str, indices) -> tuple[tuple, tuple]:
    """(places, groups) of the damaged ``indices`` (chain order) of ``arch``: each block's
    :func:`~archrock.geometry.blocks.block_name` or each joint's
    :func:`~archrock.geometry.piers.joint_place`, and "arch" or "piers" for each (a springing
    joint, between a pier top and the arch, is the arch's)."""
    kinds = tuple(getattr(arch, "block_kinds", ()) or ())
    left, right = _pier_runs(kinds) if kinds else ((), ())
    cl, cr, n = len(left), len(right), arch.n
    places, groups = [], []
    for i in (int(i) for i in indices):
        if target == "voussoir":
            places.append(block_name(arch, i))
            groups.append("piers" if kinds and kinds[i] != "voussoir" else "arch")
        else:
            places.append(joint_place(arch, i) if kinds else f"joint {i}")
            groups.append("piers" if i < cl or i > n - cr else "arch")
    return tuple(places), tuple(groups)


@dataclass(frozen=True)
class DefectMap:
    """Result of :func:`defect_map`.

    defect: the defect applied (its ``index`` is the first damaged one; :attr:`defects` lists
    them all); indices: the voussoirs (thickness) or joints (tilt, mortar) damaged in turn;
    k_l0, k_r0 [g] and hinges_l0, hinges_r0 (labels, e.g. '0i-3e-5i-7e') of the undamaged arch;
    k_l, k_r [g] and hinges_l, hinges_r of each damaged arch (NaN / '' where it cannot stand);
    pulse: None, or {kind, duration [s], sign} of the pulse, with amplitude0 [g] (undamaged)
    and amplitudes [g] (each damaged arch; NaN: no collapse up to a_max or cannot stand).
    """

    arch: VoussoirArch = field(repr=False)
    defect: Defect
    indices: np.ndarray
    k_l0: float
    k_r0: float
    hinges_l0: str
    hinges_r0: str
    k_l: np.ndarray
    k_r: np.ndarray
    hinges_l: tuple
    hinges_r: tuple
    notes: tuple
    pulse: dict | None = None
    amplitude0: float | None = None
    amplitudes: np.ndarray | None = None
    method: str = "kinematic enumeration of each damaged arch (archrock.statics.limit)"
    places: tuple = ()
    groups: tuple = ()

    def __post_init__(self):
        if not self.places or not self.groups:
            places, groups = defect_places(self.arch, self.defect.target, self.indices)
            object.__setattr__(self, "places", places)
            object.__setattr__(self, "groups", groups)
        readonly_arrays(self)

    # ------------------------------------------------------------------ derived
    @property
    def target(self) -> str:
        """'voussoir' or 'joint'."""
        return self.defect.target

    @property
    def defects(self) -> tuple:
        return tuple(self.defect.at_index(int(i)) for i in self.indices)

    @property
    def k0(self) -> float:
        """min(k_l, k_r) of the undamaged arch [g]."""
        return min(self.k_l0, self.k_r0)

    @property
    def stands(self) -> np.ndarray:
        return np.isfinite(self.k_l) & np.isfinite(self.k_r)

    @property
    def k(self) -> np.ndarray:
        """min(k_l, k_r) of each damaged arch [g] (0 where it cannot stand)."""
        return np.where(self.stands, np.fmin(self.k_l, self.k_r), 0.0)

    @property
    def loss(self) -> np.ndarray:
        """Capacity lost, k0 - min(k_l, k_r) [g] (negative: the defect raised it; a change
        within 1e-12 k0, round-off of an unchanged multiplier, is 0)."""
        loss = self.k0 - self.k
        return np.where(np.abs(loss) <= 1e-12 * self.k0, 0.0, loss)

    @property
    def relative_loss(self) -> np.ndarray:
        return self.loss / self.k0

    @property
    def amplitude_loss(self) -> np.ndarray | None:
        """Drop of the first collapse amplitude [g] (None without a pulse; NaN where undefined;
        the whole amplitude0 where the damaged arch cannot stand)."""
        if self.amplitudes is None or self.amplitude0 is None:
            return None
        a = np.where(self.stands, self.amplitudes, 0.0)
        return self.amplitude0 - a

    @property
    def on_piers(self) -> bool:
        """Whether some damaged block or joint is a pier's (reported apart)."""
        return "piers" in self.groups

    def worst_in(self, group: str) -> tuple:
        """Every index of ``group`` ("arch" or "piers") whose loss is within 1e-9 k0 of that
        group's largest (mirror images on a symmetric arch tie); () where it has none."""
        if group not in GROUPS:
            raise ArchInputError(f"group: {group!r}; allowed {', '.join(GROUPS)}")
        rows = np.flatnonzero(np.array(self.groups) == group)
        if rows.size == 0:
            return ()
        loss = self.loss[rows]
        top = rows[loss >= loss.max() - 1e-9 * self.k0]
        return tuple(int(self.indices[t]) for t in top)

    @property
    def worst(self) -> int:
        """The voussoir (or joint) whose damage lowers min(k_l, k_r) most (the first of
        :attr:`worst_all`)."""
        return self.worst_all[0]

    @property
    def worst_all(self) -> tuple:
        """Every voussoir (or joint) of the arch itself whose loss is within 1e-9 k0 of the
        largest: mirror images on a symmetric arch tie.  On piers the piers' courses and joints
        are apart (:attr:`worst_pier_all`); where only they were damaged, theirs."""
        return self.worst_in("arch") or self.worst_in("piers")

    @property
    def worst_pier_all(self) -> tuple:
        """The worst pier courses (or pier joints), as :attr:`worst_all`; () without piers."""
        return self.worst_in("piers")

    def place(self, index: int) -> str:
        """The name of damaged index ``index`` ("voussoir 3", "left pier course 1")."""
        return self.places[int(np.flatnonzero(self.indices == int(index))[0])]

    def _worst_dict(self, ties: tuple) -> dict:
        m = int(np.flatnonzero(self.indices == ties[0])[0])
        return {self.target: ties[0], "ties": list(ties), "places": [self.place(t) for t in ties],
                "k": float(self.k[m]), "loss": float(self.loss[m]),
                "relative_loss": float(self.relative_loss[m])}

    @property
    def hinges_changed(self) -> np.ndarray:
        """Whether M_l or M_r of each damaged arch has other hinges than the undamaged arch's."""
        return np.array([(a, b) != (self.hinges_l0, self.hinges_r0)
                         for a, b in zip(self.hinges_l, self.hinges_r)])

    def to_dict(self) -> dict:
        rows = []
        amp_loss = self.amplitude_loss
        for m, i in enumerate(self.indices):
            row = {self.target: int(i), "place": self.places[m], "group": self.groups[m],
                   "k_l": float(self.k_l[m]), "k_r": float(self.k_r[m]),
                   "k": float(self.k[m]), "loss": float(self.loss[m]),
                   "relative_loss": float(self.relative_loss[m]),
                   "hinges_l": self.hinges_l[m], "hinges_r": self.hinges_r[m],
                   "hinges_changed": bool(self.hinges_changed[m]),
                   "stands": bool(self.stands[m])}
            if self.amplitudes is not None:
                row["amplitude_g"] = float(self.amplitudes[m])
                row["amplitude_loss_g"] = float(amp_loss[m])
            if self.notes[m]:
                row["note"] = self.notes[m]
            rows.append(row)
        each = f"each {self.target}" + (" and pier course" if self.target == "voussoir"
                                        and self.on_piers else "")
        return {
            "arch": self.arch.name, "defect": {**self.defect.to_dict(), "index": None,
                                               "spec": self.defect.spec().split(":", 1)[1]},
            "description": self.defect.describe().replace(f"{self.target} {self.defect.index}",
                                                          f"{each} in turn"),
            "target": self.target, "blocks": block_counts(self.arch),
            "numbering": ("indices in chain order (0: the left pier's foot course); 'place' "
                          "names each, voussoirs numbered from the arch's left springing")
            if self.on_piers else "from the left springing",
            "nominal": {"k_l": self.k_l0, "k_r": self.k_r0, "k": self.k0,
                        "hinges_l": self.hinges_l0, "hinges_r": self.hinges_r0,
                        **({"amplitude_g": self.amplitude0} if self.pulse else {})},
            "worst": self._worst_dict(self.worst_all),
            **({"worst_pier": self._worst_dict(self.worst_pier_all)}
               if self.worst_pier_all and self.worst_in("arch") else {}),
            "pulse": self.pulse,
            "rows": rows,
            "method": self.method,
            "units": {"k": "g (horizontal load / weight)", "amplitude": "g", "duration": "s"},
        }


def _labels(arch):
    if getattr(arch, "fc", None) is not None:  # finite strength: the statics that honour it
        from ..statics.limit import limit_analysis

        lim = limit_analysis(arch, verify=False)
        m_l, m_r = lim.mechanism_l, lim.mechanism_r
    else:
        m_l, m_r = kinematic_mechanisms(arch)
    if m_l.multiplier <= 0 or m_r.multiplier <= 0:
        raise CannotStandError("cannot stand under its own weight")
    return m_l.multiplier, m_r.multiplier, m_l.label, m_r.label


def _amplitude(arch, nominal, impact, pulse, a_max, n_scan, tol):
    """First collapse |a| [g] (NaN: none up to a_max); sign 0: the smaller of both signs'."""
    from .curves import collapse_amplitude
    from ..dynamics.response import prepare

    model = prepare(arch, impact, nominal=nominal)
    out = math.inf
    for sign in ((-1, 1) if pulse["sign"] == 0 else (pulse["sign"],)):
        res = collapse_amplitude(model, pulse["duration"], pulse["kind"], sign, a_max=a_max,
                                 n_scan=n_scan, tol=tol)
        if res.amplitude is not None:
            out = min(out, float(res.amplitude))
    return out if math.isfinite(out) else np.nan


def _template(kind, value, side) -> Defect:
    """The defect applied in turn: ``kind`` a Defect (its own value and side) or a kind's name
    with ``value`` (default: the kind's) and ``side``."""
    if isinstance(kind, Defect):
        if value is not None or side:
            raise ArchInputError("value, side: given with a Defect, which holds its own; give "
                                 "one or the other")
        return kind
    default = {"thickness": 0.7, "tilt": 5.0, "mortar": 0.3}
    if kind not in default:
        raise ArchInputError(f"kind: {kind!r}; allowed {', '.join(default)}")
    return Defect(kind, 0, default[kind] if value is None else value, side)


def _indices(arch, template: Defect, indices) -> np.ndarray:
    """The voussoirs (or joints) damaged in turn: ``indices``, checked, or all of them."""
    hi = arch.n - 1 if template.target == "voussoir" else arch.n
    if indices is None:
        return np.arange(hi + 1)
    idx = np.atleast_1d(np.asarray(indices))
    if idx.size == 0 or idx.dtype.kind not in "iu" or np.any(idx < 0) or np.any(idx > hi):
        raise ArchInputError(f"indices: {indices!r}; allowed {template.target} indices "
                             f"0..{hi}")
    return idx


def _pulse(pulse_duration, pulse_kind, sign) -> dict | None:
    """The pulse of the first collapse amplitudes ({"kind", "duration" [s], "sign"}), or None
    without a duration."""
    if pulse_duration is None:
        return None
    from ..groundmotion import pulse_kind as _pk

    if not np.isfinite(pulse_duration) or pulse_duration <= 0:
        raise ArchInputError(f"pulse_duration: {pulse_duration!r}; allowed a number > 0 s")
    if isinstance(sign, bool) or sign not in (-1, 0, 1):
        raise ArchInputError(f"sign: {sign!r}; allowed -1, +1 or 0 (both: the smaller "
                             f"first collapse amplitude)")
    return {"kind": _pk(pulse_kind), "duration": float(pulse_duration), "sign": int(sign)}


def _damaged(arch, base, d: Defect, impact, pulse, scan) -> tuple:
    """(k_l, k_r, hinges of M_l, hinges of M_r, first collapse amplitude or NaN, note) of
    ``arch`` with defect ``d``; NaN multipliers and the reason in the note where the damaged
    arch cannot stand (or has no amplitude)."""
    note, a = "", np.nan
    try:
        damaged = apply_defect(arch, d)
        kl, kr, hl, hr = _labels(damaged)
    except GeometryOutcome as exc:
        kl = kr = np.nan
        hl = hr = ""
        note = "cannot stand under its own weight" if isinstance(exc, CannotStandError) \
            else str(exc)
    if pulse and not note:
        try:
            a = _amplitude(damaged, base, impact, pulse, *scan)
        except UNUSABLE_ARCH as exc:  # e.g. an impact law that creates energy on it
            note = f"no first collapse amplitude: {exc}"
    return kl, kr, hl, hr, a, note


def _method(pulse, a_max, n_scan, tol) -> str:
    how = "kinematic enumeration of each damaged arch (archrock.statics.limit)"
    if pulse:
        how += (f"; first collapse amplitude of a {pulse['kind']} pulse, t_p = "
                f"{pulse['duration']:g} s, scan of {n_scan} amplitudes up to {a_max:g} g "
                f"bisected to {tol:g} g (archrock.studies.curves.collapse_amplitude)")
    return how


def defect_map(arch: VoussoirArch, kind: str | Defect = "thickness", value: float | None = None,
               side: str = "", *, indices=None, pulse_duration: float | None = None,
               pulse_kind: str = "oppenheim", sign: int = -1, impact=None, a_max: float = 10.0,
               n_scan: int = 60, tol: float = 1e-3, settings=None) -> DefectMap:
    """The defect map of ``arch`` (module docstring).

    kind: 'thickness' (value: remaining fraction, default 0.7), 'tilt' (value [deg], default 5)
    or 'mortar' (value: missing depth fraction, default 0.3), or a :class:`Defect` whose kind,
    value and side are used; side: as :class:`Defect`; indices: the voussoirs (or joints)
    damaged in turn (default all); pulse_duration [s]: with it, the first collapse amplitude of
    a ``pulse_kind`` pulse of sign ``sign`` (-1 opens M_l, +1 M_r, 0 both: the smaller
    amplitude of the two) on each arch, with the impact law
    ``impact`` (an ImpactSpec or its name; default the paper's practice, evaluated on the
    undamaged arch), scanning ``n_scan`` amplitudes up to ``a_max`` [g] and bisecting to
    ``tol`` [g]; settings: a :class:`~archrock.studies.runner.RunSettings` (or its dict) whose
    ``progress`` gets one line of text per damaged arch (:mod:`archrock._progress`).
    """
    progress = RunSettings.from_dict(settings).only("defect_map").sink
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    template = _template(kind, value, side)
    idx = _indices(arch, template, indices)
    pulse = _pulse(pulse_duration, pulse_kind, sign)
    t0 = time.monotonic()
    # the undamaged arch in the form the defects are applied to (a circular arch's polygon for a
    # tilt or missing mortar): the losses are then the defects' alone
    base = defect_base(arch, template.kind)
    k_l0, k_r0, h_l0, h_r0 = _labels(base)
    scan = (a_max, n_scan, tol)
    amp0 = _amplitude(base, base, impact, pulse, *scan) if pulse else None
    places, groups = defect_places(arch, template.target, idx)
    rows = []
    for m, i in enumerate(idx):
        rows.append(_damaged(arch, base, template.at_index(int(i)), impact, pulse, scan))
        kl, kr, _, _, a, _ = rows[-1]
        if progress is not None:
            progress(f"  {places[m]} ({m + 1}/{len(idx)}): k_l = {kl:.4f}, "
                     f"k_r = {kr:.4f}" + (f", amplitude {a:.4f} g" if pulse else "")
                     + f"  [{time.monotonic() - t0:.1f} s]")
    k_l, k_r, h_l, h_r, amps, notes = zip(*rows)
    return DefectMap(arch, template.at_index(int(idx[0])), idx.astype(int), float(k_l0),
                     float(k_r0), h_l0, h_r0, np.array(k_l, float), np.array(k_r, float),
                     tuple(h_l), tuple(h_r), tuple(notes), pulse, amp0,
                     np.array(amps, float) if pulse else None,
                     _method(pulse, a_max, n_scan, tol), places, groups)
