"""Irregular arches drawn around a nominal one: the one sampler of every study.

Random arch i of a study is a function of (nominal arch, spreads, seed, i) alone, whichever
command draws it (``ensemble``, ``curves``, ``fragility``), however the work is cut into batches
and however many workers run it.  The draws follow docs/method.md, Geometry (see
:func:`archrock.geometry.perturb_voussoirs`): for each voussoir, independent U on [-1, 1] for the
span, the thickness and the radius.

Streams: samples are grouped in blocks of :data:`BLOCK` (= 500) consecutive indices; block k
draws from numpy's ``SeedSequence(seed, spawn_key=(k,))`` (= ``SeedSequence(seed).spawn(K)[k]``),
the 3 n uniforms of its samples one after the other.  (This is archrock 0.1.0's ensemble stream
with its default batch size, so its published ensembles are unchanged.)  Each sample's draws,
shape (rows, n): row 0 the span (length along the centreline), row 1 the thickness, row 2 the
radius (normal offset of the centreline); with a joint tilt (``Spreads.tilt`` > 0) a fourth
row, whose entries 0 .. n-2 tilt the interior joints 1 .. n-1 (entry n-1 is drawn and unused),
so such a sample reads 4 n uniforms.  Without tilt every family reads 3 n, and a circular arch's
draws and arches are 0.1.0's.

Nominal arches: a circular :class:`~archrock.geometry.Arch` (voussoirs perturbed as annular
sectors, :func:`~archrock.geometry.perturb_voussoirs`) or a family arch
(:class:`~archrock.geometry.FamilyArch`, perturbed through its recipe,
:func:`~archrock.geometry.irregular.perturb_family`; with numba, for a family arch without loads
or fill, its arithmetic compiled in :mod:`archrock.geometry.batchdraw`: the same polylines).  A
polygon arch without a recipe (a surveyed arch, e.g. from a DXF drawing) keeps its joints and
varies each voussoir's thickness and centreline offset (:mod:`archrock.geometry.survey`; span
and tilt spreads must be 0).  An arch on piers is drawn so, pier courses included; with pier
spreads (``Spreads.pier_*``) each pier is first drawn on its own (lean, width, height, bed
joints; :func:`archrock.geometry.piers.reshape_piers`) from its own child stream
``SeedSequence(seed, spawn_key=(k, 2, 0))`` (left) or ``(k, 2, 1)`` (right;
:meth:`ArchSampler.pier_uniforms`), and the blocks' draws are applied to that arch: the voussoirs' uniforms are unchanged, and with the pier
spreads 0 the samples are those drawn before, to the bit (docs/piers.md, Irregular piers).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import published
from ..errors import ArchInputError, InvalidSampleError
from .base import VoussoirArch
from .circular import Arch, perturb_voussoirs
from .families import FamilyArch
from .irregular import perturb_family
from .polygon import PolygonArch

__all__ = ["Spreads", "ArchSampler", "BLOCK", "DEFAULT_SPREADS", "LEGACY_KEYS", "PIER_SPREADS"]

#: Samples per random stream.
BLOCK = 500
#: The pier spreads: (field, upper bound, bound included, what it is).
PIER_SPREADS = (("pier_lean", 15.0, True, "degrees out of plumb, U x s, outward positive"),
                ("pier_width", 1.0, False, "the pier's width times 1 + U s"),
                ("pier_height", 1.0, False, "the pier's height times 1 + U s"),
                ("pier_course", 0.5, False, "bed joints moved by U s course heights"))


@dataclass(frozen=True)
class Spreads:
    """Half-widths of the uniform irregularities (dimensionless, 0 <= s < 1): ``span`` s_a and
    ``thickness`` s_t relative to the nominal voussoir's, ``radius`` s_R as a fraction of its
    thickness (for a family arch: the voussoir's length along the centreline, its thickness,
    the normal offset of its centreline); ``tilt`` [deg], 0 <= tilt < 45: each interior joint
    of a family arch rotated about its centreline point by U x tilt (0: joints as the family's).
    Frozen; ``to_dict`` writes the field names (span, thickness, radius, tilt, and the pier
    spreads when not 0) and ``from_dict`` reads them or archrock <= 0.6's keys
    (:data:`LEGACY_KEYS`: spread_span, spread_thickness, spread_radius, spread_tilt_deg, the
    command-line names); :meth:`legacy_dict` writes those old keys, for the ensemble
    configuration's hash, which keeps its 0.4 form.

    Piers (an arch on piers only; docs/piers.md, Irregular piers), each pier drawn on its own:
    ``pier_lean`` [deg], 0 <= s <= 15: the pier out of plumb by U x s (outward positive);
    ``pier_width`` and ``pier_height``, 0 <= s < 1: its width and height times (1 + U s);
    ``pier_course``, 0 <= s < 0.5: each interior bed joint moved up or down by U s x the
    pier's mean course height.  Written (keys: the field names) only when not 0, so that the
    hash of a configuration without them is unchanged.

    Strength (an arch of finite compressive strength only, ``nominal.fc`` set; docs/crushing-
    dynamics.md): ``fc``, 0 <= s < 1: each arch's f_c is the nominal's times (1 + U s), one U per
    arch from its own child stream ``SeedSequence(seed, spawn_key=(k, 3))``
    (:meth:`ArchSampler.strength_uniforms`), so the blocks' draws do not change.  Written only
    when not 0."""

    span: float = 0.1
    thickness: float = 0.1
    radius: float = 0.05
    tilt: float = 0.0
    pier_lean: float = 0.0
    pier_width: float = 0.0
    pier_height: float = 0.0
    pier_course: float = 0.0
    fc: float = 0.0

    def __post_init__(self):
        for name, hi, closed, what in PIER_SPREADS:
            v = getattr(self, name)
            ok = not isinstance(v, bool) and isinstance(v, (int, float, np.integer, np.floating)) \
                and math.isfinite(float(v)) and 0.0 <= float(v) and \
                (float(v) <= hi if closed else float(v) < hi)
            if not ok:
                raise ArchInputError(f"{name}: {v!r}; allowed 0 <= {name} "
                                     f"{'<=' if closed else '<'} {hi:g} ({what})")
            object.__setattr__(self, name, float(v))
        v = self.tilt
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or \
                not (math.isfinite(float(v)) and 0.0 <= float(v) < 45.0):
            raise ArchInputError(f"spread tilt: {v!r}; allowed 0 <= tilt < 45 degrees")
        object.__setattr__(self, "tilt", float(v))
        for name in ("span", "thickness", "radius", "fc"):
            v = getattr(self, name)
            label = f"spread {name}"
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise ArchInputError(f"{label}: {v!r}; allowed a number 0 <= s < 1")
            v = float(v)
            if not (math.isfinite(v) and 0.0 <= v < 1.0):
                raise ArchInputError(f"{label}: {v:g}; allowed 0 <= s < 1")
            object.__setattr__(self, name, v)

    def to_dict(self) -> dict:
        """The fields by name: ``{"span", "thickness", "radius", "tilt"}``, and the pier spreads
        that are not 0."""
        d = {"span": self.span, "thickness": self.thickness, "radius": self.radius,
             "tilt": self.tilt}
        for name in _OPTIONAL:
            if getattr(self, name):
                d[name] = getattr(self, name)
        return d

    def legacy_dict(self) -> dict:
        """archrock 0.1-0.6's dict (:data:`LEGACY_KEYS`; spread_tilt_deg only when the tilt is
        not 0): the form hashed into an ensemble's configuration, so that folders written by
        0.4-0.6 resume (:meth:`archrock.studies.ensemble.EnsembleConfig.legacy_dict`)."""
        d = {"spread_span": self.span, "spread_thickness": self.thickness,
             "spread_radius": self.radius}
        if self.tilt:
            d["spread_tilt_deg"] = self.tilt
        for name in _OPTIONAL:
            if getattr(self, name):
                d[name] = getattr(self, name)
        return d

    @property
    def piers(self) -> bool:
        """Whether any pier spread is not 0."""
        return any(getattr(self, name) for name, *_ in PIER_SPREADS)

    @classmethod
    def from_dict(cls, data) -> "Spreads":
        """A Spreads of its dict: the field names, or the old keys of :data:`LEGACY_KEYS` (one
        spelling per field); None gives the defaults."""
        if data is None:
            return cls()
        if isinstance(data, Spreads):
            return data
        if not isinstance(data, dict):
            raise ArchInputError(f"spreads: {data!r}; allowed an object with span, thickness, "
                                 f"radius, tilt")
        fields = ("span", "thickness", "radius", "tilt") + _OPTIONAL
        unknown = set(data) - set(fields) - set(LEGACY_KEYS)
        if unknown:
            raise ArchInputError(f"spreads: unknown key(s) {sorted(unknown)}; allowed "
                                 f"{', '.join(fields)} (or archrock 0.6's "
                                 f"{', '.join(LEGACY_KEYS)})")
        kw = {}
        for k, v in data.items():
            name = LEGACY_KEYS.get(k, k)
            if name in kw:
                old = next(o for o, n in LEGACY_KEYS.items() if n == name)
                raise ArchInputError(f"spreads: {name} given twice (as {name} and as {old}); "
                                     f"give one")
            kw[name] = v
        return cls(**kw)


#: The spreads written only when not 0 (the hash of a configuration without them is unchanged).
_OPTIONAL = tuple(n for n, *_ in PIER_SPREADS) + ("fc",)

#: archrock 0.1-0.6's keys of a Spreads dict -> the field they name (read as aliases).
LEGACY_KEYS = {"spread_span": "span", "spread_thickness": "thickness", "spread_radius": "radius",
               "spread_tilt_deg": "tilt"}


#: The spreads that give multipliers spread like the paper's RA-1 and RA-2 (docs/method.md, Geometry).
DEFAULT_SPREADS = Spreads.from_dict(published.DEFAULT_SPREADS)


def _seed(seed) -> int:
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ArchInputError(f"seed: {seed!r}; allowed an integer >= 0")
    return int(seed)


def fixed_joints(nominal) -> str | None:
    """Why the joints of ``nominal`` stay where they are drawn when it is sampled (no span or
    tilt spread: an arch on piers, a polygon arch without a family), or None where they move."""
    if not isinstance(nominal, PolygonArch) or getattr(nominal, "recipe", None) is not None:
        return None
    return ("an arch on piers, whose blocks (piers included) are perturbed as a surveyed arch's"
            if getattr(nominal, "pier_blocks", ()) else
            "a polygon arch without a family (e.g. surveyed)")


@dataclass(frozen=True, eq=False)
class ArchSampler:
    """Random arches around ``nominal`` (a circular Arch or a family arch) with ``spreads``,
    reproducible from ``seed`` (module docstring)."""

    nominal: VoussoirArch
    spreads: Spreads = DEFAULT_SPREADS
    seed: int = 0

    def __post_init__(self):
        object.__setattr__(self, "spreads", Spreads.from_dict(self.spreads))
        object.__setattr__(self, "seed", _seed(self.seed))
        a = self.nominal
        if isinstance(a, Arch):
            if self.spreads.tilt:
                raise ArchInputError(
                    "spread tilt: the circular Arch has radial joints only; for tilted joints give "
                    "the nominal as family_arch('circular', span, rise, t, n, exact=False) "
                    "(--shape circular with --joints or --thickness-crown on the command line)")
        elif fixed_joints(a) is not None:
            # a surveyed arch: thickness and offset vary, its joints stay (geometry.survey)
            if self.spreads.span or self.spreads.tilt:
                what = fixed_joints(a)
                raise ArchInputError(
                    f"spread span and tilt: {self.spreads.span:g} and {self.spreads.tilt:g}; "
                    f"allowed 0 and 0 for {a.name!r}, {what}, whose joints stay where they were "
                    f"measured (--spread-span 0; the thickness and radius spreads apply)")
        elif not isinstance(a, FamilyArch):
            from .displaced import refuse_moved_supports

            refuse_moved_supports(a)
            raise ArchInputError(f"nominal: expected an Arch or a FamilyArch, got "
                                 f"{type(a).__name__}")

        if self.spreads.piers and not getattr(a, "pier_blocks", ()):
            raise ArchInputError(self._no_piers())
        if self.spreads.fc and getattr(a, "fc", None) is None:
            raise ArchInputError(f"spread fc: {self.spreads.fc:g} for {a.name!r}, whose "
                                 f"compressive strength is infinite; allowed 0 (a strength "
                                 f"spread needs a nominal f_c: --fc MPA)")

    @property
    def finite(self) -> bool:
        """Whether the arches have a finite compressive strength (the nominal's ``fc`` set):
        they are then drawn as objects, never as the circular arrays of :meth:`draw`."""
        return getattr(self.nominal, "fc", None) is not None

    def strength_uniforms(self, start: int, count: int) -> np.ndarray:
        """U on [-1, 1] of samples start .. start + count - 1, shape (count,): each arch's
        strength draw (``Spreads.fc``), block k from the child ``SeedSequence(seed,
        spawn_key=(k, 3))``: the blocks' and the piers' draws do not change."""
        return self._stream(start, count, (), -1.0, (3,))

    def _with_strength(self, arch, start: int, count: int = 1, u=None):
        """``arch`` with sample ``start``'s strength: the nominal's f_c times (1 + U s_fc)
        (module docstring); the arch itself where the strength is infinite."""
        if not self.finite or isinstance(arch, Exception):
            return arch
        fc = float(self.nominal.fc)
        if self.spreads.fc:
            u = self.strength_uniforms(start, count)[0] if u is None else u
            fc *= 1.0 + self.spreads.fc * float(u)
        try:
            return arch.with_fc(fc)
        except ArchInputError as exc:  # a draw below the strengths allowed
            return InvalidSampleError(f"not a valid arch: {exc}")

    def _no_piers(self) -> str:
        given = ", ".join(f"{n} {getattr(self.spreads, n):g}" for n, *_ in PIER_SPREADS
                          if getattr(self.spreads, n))
        return (f"pier spreads: {given} for {self.nominal.name!r}, which stands on no piers; "
                f"allowed 0 (pier spreads need an arch on piers: --pier-height/--pier-width)")

    @property
    def circular(self) -> bool:
        """Whether the nominal is a circular Arch (draws as arrays, :meth:`draw`)."""
        return isinstance(self.nominal, Arch)

    @property
    def rows(self) -> int:
        """Rows of uniforms per sample: 3, or 4 with a joint tilt."""
        return 4 if self.spreads.tilt else 3

    def uniforms(self, start: int, count: int) -> np.ndarray:
        """The uniform draws U of samples start .. start + count - 1, shape (count, rows, n)."""
        return self._stream(start, count, (self.rows, self.nominal.n), -1.0, ())

    def _stream(self, start, count, shape: tuple, low: float, child: tuple) -> np.ndarray:
        """Draws uniform on [low, 1) of shape ``shape`` per sample, samples start .. start +
        count - 1: block k reads ``SeedSequence(seed, spawn_key=(k, *child))`` from its start
        (module docstring)."""
        if isinstance(start, bool) or int(start) != start or start < 0:
            raise ArchInputError(f"start: {start!r}; allowed an integer >= 0")
        if isinstance(count, bool) or int(count) != count or count < 0:
            raise ArchInputError(f"count: {count!r}; allowed an integer >= 0")
        start, count = int(start), int(count)
        out = np.empty((count, *shape))
        end = start + count
        k = start // BLOCK
        while k * BLOCK < end:
            lo, hi = max(start, k * BLOCK), min(end, (k + 1) * BLOCK)
            rng = np.random.default_rng(np.random.SeedSequence(self.seed,
                                                               spawn_key=(k, *child)))
            # a block's stream is read from its start: sample j of the block is its j-th draws
            u = rng.uniform(low, 1.0, size=(hi - k * BLOCK, *shape))
            out[lo - start:hi - start] = u[lo - k * BLOCK:]
            k += 1
        return out

    def movement_fractions(self, start: int, count: int) -> np.ndarray:
        """U on [0, 1] of samples start .. start + count - 1, shape (count,): the fraction of a
        study's support movement that each arch takes when the movement is drawn per arch
        (EnsembleConfig(support_draw='uniform')).  Block k's stream is the child
        ``SeedSequence(seed, spawn_key=(k, 1))`` of the arches' stream: the arches' draws do
        not change, and sample i's fraction depends on (seed, i) alone."""
        return self._stream(start, count, (), 0.0, (1,))

    def pier_uniforms(self, start: int, count: int, side: str) -> np.ndarray:
        """U on [-1, 1] of samples start .. start + count - 1 for their ``side`` ('left' or
        'right') pier, shape (count, 2 + c): its lean, width, height and its c - 1 interior bed
        joints' draws (c its courses).  Each pier has its own stream: block k reads the child
        ``SeedSequence(seed, spawn_key=(k, 2, 0))`` (left) or ``(k, 2, 1)`` (right), so the
        voussoirs' draws do not change, nor one pier's with the other's courses."""
        if side not in ("left", "right"):
            raise ArchInputError(f"side: {side!r}; allowed left, right")
        run = self.nominal.piers[0 if side == "left" else 1]
        return self._stream(start, count, (2 + len(run),), -1.0,
                            (2, 0 if side == "left" else 1))

    def _pier_changes(self, index: int) -> dict:
        """The changes of :func:`archrock.geometry.piers.reshape_piers` of sample ``index``'s
        piers (:meth:`pier_uniforms`)."""
        s = self.spreads
        left, right = self.nominal.piers
        out = {}
        for side, run in (("left", left), ("right", right)):
            if not run:
                continue
            u = self.pier_uniforms(index, 1, side)[0]
            jp = self.nominal.joint_points
            if side == "left":
                top, foot = jp[len(run)], jp[0]
            else:
                top, foot = jp[self.nominal.n - len(run)], jp[self.nominal.n]
            course = (float(min(top[:, 1])) - float(max(foot[:, 1]))) / len(run)
            out[side] = {"lean": s.pier_lean * u[0], "width": 1.0 + s.pier_width * u[1],
                         "height": 1.0 + s.pier_height * u[2],
                         "shifts": s.pier_course * course * u[3:]
                         if s.pier_course and len(run) > 1 else None}
        return out

    def _pier_nominal(self, index: int):
        """The nominal arch on sample ``index``'s irregular piers (pier spreads not 0; the
        voussoir draws are then applied to it), else the nominal itself."""
        if not self.spreads.piers:
            return self.nominal
        from .piers import reshape_piers

        ch = self._pier_changes(index)
        try:
            return reshape_piers(self.nominal, self.nominal.block_kinds, ch.get("left"),
                                 ch.get("right"), _trusted=True)
        except ArchInputError as exc:
            raise InvalidSampleError(f"not a valid arch: {exc}") from None

    def draw(self, start: int, count: int):
        """(spans [rad], thicknesses [m], radii [m]) of samples start .. start + count - 1,
        each of shape (count, n), for a circular nominal; nothing is validated (see :meth:`arch`;
        :meth:`arches` for any family)."""
        if not self.circular:
            raise ArchInputError("draw: the arrays of circular arches; a family arch's samples "
                                 "are arches: use ArchSampler.arches(start, count) or arch(i)")
        a = self.nominal
        s = self.spreads
        return perturb_voussoirs(a.spans, a.thicknesses, a.radii, self.uniforms(start, count),
                                 s.span, s.thickness, s.radius)

    def arch(self, index: int) -> VoussoirArch:
        """Random arch ``index`` (an Arch around a circular Arch, a PolygonArch around a family
        arch); :class:`InvalidSampleError` if the draw is not a valid arch."""
        if self.circular:
            spans, thick, radii = self.draw(index, 1)
            try:
                drawn = Arch(spans[0], radii[0], thick[0], self.nominal.density,
                             name=f"sample {int(index)}")
            except ArchInputError as exc:
                raise InvalidSampleError(f"not a valid arch: {exc}") from None
            return _raised(self._with_strength(drawn, int(index)))
        return _raised(self._with_strength(self._family(self.uniforms(index, 1)[0], int(index)),
                                           int(index)))

    def _family(self, u, index: int):
        s = self.spreads
        if getattr(self.nominal, "recipe", None) is None:  # a surveyed arch
            from .survey import perturb_survey

            nominal = self._pier_nominal(index)
            try:
                drawn = perturb_survey(nominal, u, s.thickness, s.radius,
                                       name=f"sample {index}")
            except ArchInputError as exc:
                raise InvalidSampleError(f"not a valid arch: {exc}") from None
            if nominal is self.nominal:
                return drawn
            from .piers import _unchecked  # a checked polygon arch: its kinds put back

            return _unchecked(drawn.intrados, drawn.extrados, drawn.density, drawn.name,
                              drawn.loads, nominal.block_kinds)
        from .batchdraw import compiled_drawing, draw_lines, family_plan

        if compiled_drawing(self):  # the same polylines as perturb_family, compiled
            lines = draw_lines(family_plan(self.nominal), u, s)
            try:
                if isinstance(lines, ArchInputError):
                    raise lines
                return PolygonArch(*lines, self.nominal.recipe["density"], f"sample {index}")
            except ArchInputError as exc:
                raise InvalidSampleError(f"not a valid arch: {exc}") from None
        try:
            return perturb_family(self.nominal, u, s.span, s.thickness, s.radius, s.tilt,
                                  name=f"sample {index}")
        except ArchInputError as exc:
            raise InvalidSampleError(f"not a valid arch: {exc}") from None

    def arches(self, start: int, count: int) -> list:
        """Samples start .. start + count - 1 of any family as a list: each entry the arch, or
        the :class:`InvalidSampleError` saying why its draw is not a valid arch (what
        :func:`archrock.dynamics.batch.prepare_batch` takes)."""
        out = []
        if self.circular:
            spans, thick, radii = self.draw(start, count)
        else:
            u = self.uniforms(start, count)
        for j in range(count):
            try:
                if self.circular:
                    try:
                        out.append(Arch(spans[j], radii[j], thick[j], self.nominal.density,
                                        name=f"sample {start + j}"))
                    except ArchInputError as exc:
                        raise InvalidSampleError(f"not a valid arch: {exc}") from None
                else:
                    out.append(self._family(u[j], start + j))
            except InvalidSampleError as exc:
                out.append(exc)
        if self.finite:
            us = self.strength_uniforms(start, count) if self.spreads.fc else [None] * count
            out = [self._with_strength(a, start + j, u=us[j]) for j, a in enumerate(out)]
        return out

    def to_dict(self) -> dict:
        """What draws its arches, by attribute name (nominal, spreads, seed) and the block size."""
        return {"nominal": self.nominal.to_dict(), "spreads": self.spreads.to_dict(),
                "seed": self.seed, "block": BLOCK}


def _raised(drawn):
    """``drawn`` itself, or raised where it is the reason why the draw is no arch."""
    if isinstance(drawn, Exception):
        raise drawn
    return drawn
