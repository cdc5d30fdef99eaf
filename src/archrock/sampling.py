"""Irregular arches drawn around a nominal one: the one sampler of every study.

Random arch i of a study is a function of (nominal arch, spreads, seed, i) alone, whichever
command draws it (``ensemble``, ``curves``, ``fragility``), however the work is cut into batches
and however many workers run it.  The draws follow docs/method.md, Geometry (see
:func:`archrock.geometry.perturb_voussoirs`): for each voussoir, independent U on [-1, 1] for the
span, the thickness and the radius.

Streams: samples are grouped in blocks of :data:`BLOCK` (= 500) consecutive indices; block k
draws from numpy's ``SeedSequence(seed, spawn_key=(k,))`` (= ``SeedSequence(seed).spawn(K)[k]``),
the 3 n uniforms of its samples one after the other.  (This is archrock 0.1.0's ensemble stream
with its default batch size, so its published ensembles are unchanged.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import published
from .errors import ArchInputError, InvalidSampleError
from .geometry import Arch, perturb_voussoirs

__all__ = ["Spreads", "ArchSampler", "BLOCK", "DEFAULT_SPREADS"]

#: Samples per random stream.
BLOCK = 500


@dataclass(frozen=True)
class Spreads:
    """Half-widths of the uniform irregularities (dimensionless, 0 <= s < 1): ``span`` s_a and
    ``thickness`` s_t relative to the nominal voussoir's, ``radius`` s_R as a fraction of its
    thickness.  Frozen; ``to_dict``/``from_dict`` use the keys spread_span, spread_thickness,
    spread_radius (the command-line names)."""

    span: float = 0.1
    thickness: float = 0.1
    radius: float = 0.05

    def __post_init__(self):
        for name in ("span", "thickness", "radius"):
            v = getattr(self, name)
            label = f"spread {name}"
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise ArchInputError(f"{label}: {v!r}; allowed a number 0 <= s < 1")
            v = float(v)
            if not (math.isfinite(v) and 0.0 <= v < 1.0):
                raise ArchInputError(f"{label}: {v:g}; allowed 0 <= s < 1")
            object.__setattr__(self, name, v)

    def to_dict(self) -> dict:
        return {"spread_span": self.span, "spread_thickness": self.thickness,
                "spread_radius": self.radius}

    @classmethod
    def from_dict(cls, data) -> "Spreads":
        if data is None:
            return cls()
        if isinstance(data, Spreads):
            return data
        if not isinstance(data, dict):
            raise ArchInputError(f"spreads: {data!r}; allowed an object with spread_span, "
                                 f"spread_thickness, spread_radius")
        keys = {"spread_span": "span", "spread_thickness": "thickness", "spread_radius": "radius"}
        unknown = set(data) - set(keys)
        if unknown:
            raise ArchInputError(f"spreads: unknown key(s) {sorted(unknown)}; allowed "
                                 f"{', '.join(keys)}")
        return cls(**{keys[k]: v for k, v in data.items()})


#: The spreads that give multipliers spread like the paper's RA-1 and RA-2 (docs/method.md, Geometry).
DEFAULT_SPREADS = Spreads.from_dict(published.DEFAULT_SPREADS)


def _seed(seed) -> int:
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ArchInputError(f"seed: {seed!r}; allowed an integer >= 0")
    return int(seed)


@dataclass(frozen=True, eq=False)
class ArchSampler:
    """Random arches around ``nominal`` with ``spreads``, reproducible from ``seed``."""

    nominal: Arch
    spreads: Spreads = DEFAULT_SPREADS
    seed: int = 0

    def __post_init__(self):
        if not isinstance(self.nominal, Arch):
            raise ArchInputError(f"nominal: expected an Arch, got {type(self.nominal).__name__}")
        object.__setattr__(self, "spreads", Spreads.from_dict(self.spreads))
        object.__setattr__(self, "seed", _seed(self.seed))

    def uniforms(self, start: int, count: int) -> np.ndarray:
        """The uniform draws U of samples start .. start + count - 1, shape (count, 3, n)."""
        if isinstance(start, bool) or int(start) != start or start < 0:
            raise ArchInputError(f"start: {start!r}; allowed an integer >= 0")
        if isinstance(count, bool) or int(count) != count or count < 0:
            raise ArchInputError(f"count: {count!r}; allowed an integer >= 0")
        start, count, n = int(start), int(count), self.nominal.n
        out = np.empty((count, 3, n))
        end = start + count
        k = start // BLOCK
        while k * BLOCK < end:
            lo, hi = max(start, k * BLOCK), min(end, (k + 1) * BLOCK)
            rng = np.random.default_rng(np.random.SeedSequence(self.seed, spawn_key=(k,)))
            # a block's stream is read from its start: sample j of the block is its j-th 3n draws
            u = rng.uniform(-1.0, 1.0, size=(hi - k * BLOCK, 3, n))
            out[lo - start:hi - start] = u[lo - k * BLOCK:]
            k += 1
        return out

    def draw(self, start: int, count: int):
        """(spans [rad], thicknesses [m], radii [m]) of samples start .. start + count - 1,
        each of shape (count, n); nothing is validated (see :meth:`arch`)."""
        a = self.nominal
        s = self.spreads
        return perturb_voussoirs(a.spans, a.thicknesses, a.radii, self.uniforms(start, count),
                                 s.span, s.thickness, s.radius)

    def arch(self, index: int) -> Arch:
        """Random arch ``index``; :class:`InvalidSampleError` if the draw is not a valid arch."""
        spans, thick, radii = self.draw(index, 1)
        try:
            return Arch(spans[0], radii[0], thick[0], self.nominal.density,
                        name=f"sample {int(index)}")
        except ArchInputError as exc:
            raise InvalidSampleError(f"not a valid arch: {exc}") from None

    def to_dict(self) -> dict:
        return {"nominal": self.nominal.to_dict(), **self.spreads.to_dict(), "seed": self.seed,
                "block": BLOCK}
