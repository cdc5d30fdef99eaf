"""The configuration of an ensemble: everything that determines its results, JSON-serialisable.

``to_dict``/``to_json`` write every field under its own name (the manifest's form);
``from_dict`` reads that and archrock 0.4-0.6's form.  The configuration hash in each batch
file's provenance (:meth:`EnsembleConfig.config_hash`) is computed from 0.4-0.6's form
(:meth:`EnsembleConfig.legacy_dict`), written out explicitly here, so that folders written by
those releases resume without recomputing; that form must not change without a format change.
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import json
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ...errors import ArchInputError
from ...geometry import VoussoirArch, arch_from_dict
from ...groundmotion import PulseSpec, RecordSpec, motion_spec_from_dict
from ...dynamics.impact import PAPER_PRACTICE, ImpactSpec
from ...dynamics.response import default_steps
from ...geometry.displaced import SupportMovement, refuse_moved_supports
from ...geometry.sampling import DEFAULT_SPREADS, LEGACY_KEYS, ArchSampler, Spreads

__all__ = ["EnsembleConfig", "SUPPORT_DRAWS"]

#: How a support movement is applied to the samples: the same to every arch, or a fraction U
#: uniform on [0, 1] of it drawn per arch.
SUPPORT_DRAWS = ("fixed", "uniform")


def int_field(name, value, lo):
    """``value`` as an int >= ``lo``, or ArchInputError naming the field ``name``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < lo:
        raise ArchInputError(f"{name}: {value!r}; allowed an integer >= {lo}")
    return int(value)


@dataclass(frozen=True)
class EnsembleConfig:
    """Everything that determines an ensemble's results (JSON-serialisable).

    nominal: the nominal geometry as ``Arch.to_dict()`` or a family arch's ``FamilyArch.to_dict()``
    (with its recipe under "family"; an arch object is turned into its dict); samples >= 1; seed >= 0; spreads: a
    :class:`~archrock.geometry.sampling.Spreads` (or its dict): sample i is arch i of
    ``ArchSampler(nominal, spreads, seed)``, the same arch as in ``curves`` and ``fragility``;
    batch_size >= 1: samples per batch, the unit of work, of parallelism and of resumption (the
    draws do not depend on it); motion: None (limit analysis only), a
    :class:`~archrock.groundmotion.PulseSpec` or :class:`~archrock.groundmotion.RecordSpec`, or
    the dict of one (``to_dict()``, as in a manifest), kept as the specification; impact: an
    :class:`~archrock.dynamics.impact.ImpactSpec` (or what ``ImpactSpec.parse`` reads; default the paper's
    practice, the 'paper' model's c_v of the nominal arch fixed on every sample); dt [s]: RK4
    step; t_free [s]: free motion allowed after the ground motion (both by default from the nominal
    arch's size, :func:`archrock.dynamics.response.default_steps`); tabulate: the RK4 kernel reads
    the equation's coefficients from tables (as ``respond``'s default; ~1e-9 relative,
    about 3x faster) instead of the exact loop closure; early_stop: stop following an arch once,
    after the ground motion, it can no longer collapse (:func:`archrock.dynamics.batch.simulate_batch`:
    outcome and peak exact, impacts and time to rest not followed; written to the JSON only when
    true, so other configurations and their hashes are unchanged); support: a
    :class:`~archrock.geometry.displaced.SupportMovement` (or its dict) applied to every sample
    (:mod:`archrock.statics.supports`, each arch analysed re-closed on its moved supports; an arch
    that cannot stand there is left out as "cannot stand"); None or zero: fixed supports, not
    written to the JSON; support_draw: 'fixed' (every sample takes ``support``) or 'uniform'
    (sample i takes U_i x ``support``, :meth:`movements`; the nominal arch is analysed at the
    whole movement), written only when 'uniform'.
    """

    nominal: dict
    samples: int = 1000
    seed: int = 0
    spreads: Spreads | dict = DEFAULT_SPREADS
    batch_size: int = 500
    motion: PulseSpec | RecordSpec | dict | None = None
    impact: ImpactSpec | dict | str | None = PAPER_PRACTICE
    dt: float | None = None
    t_free: float | None = None
    tabulate: bool = True
    early_stop: bool = False
    support: SupportMovement | dict | None = None
    support_draw: str = "fixed"

    def __post_init__(self):
        refuse_moved_supports(self.nominal)  # before its dict, which cannot be read back
        if isinstance(self.nominal, VoussoirArch):
            object.__setattr__(self, "nominal", self.nominal.to_dict())
        arch = arch_from_dict(self.nominal, name="nominal")  # validates
        object.__setattr__(self, "samples", int_field("samples", self.samples, 1))
        object.__setattr__(self, "seed", int_field("seed", self.seed, 0))
        object.__setattr__(self, "batch_size", int_field("batch size", self.batch_size, 1))
        object.__setattr__(self, "spreads", Spreads.from_dict(self.spreads))
        # the sampler refuses what cannot be sampled (a surveyed polygon, tilt on a circular Arch)
        # and is kept: the cached :attr:`sampler`
        object.__setattr__(self, "sampler", ArchSampler(arch, self.spreads, self.seed))
        object.__setattr__(self, "impact", ImpactSpec.parse(self.impact))
        # default steps follow the nominal arch's size (response.default_steps): 2e-3 s and 60 s
        # for arches of 0.4-14 m, so configurations (and their hashes) of such arches are 0.1.0's
        steps = dict(zip(("dt", "t_free"), default_steps(arch)))
        for name in ("dt", "t_free"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, steps[name])
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
                raise ArchInputError(f"{name}: {v!r}; allowed a finite number > 0 s")
            object.__setattr__(self, name, float(v))
        if not isinstance(self.tabulate, bool):
            raise ArchInputError(f"tabulate: {self.tabulate!r}; allowed true or false")
        if not isinstance(self.early_stop, bool):
            raise ArchInputError(f"early_stop: {self.early_stop!r}; allowed true or false")
        motion = self.motion
        if isinstance(motion, dict):
            motion = motion_spec_from_dict(motion)  # checked as it is built
        elif motion is not None and not isinstance(motion, (PulseSpec, RecordSpec)):
            raise ArchInputError(f"motion: {motion!r}; allowed None, a PulseSpec or RecordSpec, "
                                 "or the dict of one")
        object.__setattr__(self, "motion", motion)
        support = self.support
        if support is not None:
            if not isinstance(support, SupportMovement):
                if not isinstance(support, dict):
                    raise ArchInputError(f"support: {support!r}; allowed None, a SupportMovement "
                                         f"or its dict")
                support = SupportMovement.from_dict(support)
            if support.is_zero:
                support = None  # fixed supports: the configuration (and hash) without movement
        object.__setattr__(self, "support", support)
        if self.support_draw not in SUPPORT_DRAWS:
            raise ArchInputError(f"support_draw: {self.support_draw!r}; allowed "
                                 f"{', '.join(SUPPORT_DRAWS)}")
        if self.support_draw != "fixed" and support is None:
            raise ArchInputError(f"support_draw: {self.support_draw!r} needs a support movement "
                                 f"(support=...; --spread/--settlement)")

    @classmethod
    def from_arch(cls, nominal: VoussoirArch, **kwargs) -> "EnsembleConfig":
        return cls(nominal, **kwargs)  # __post_init__ checks it, then keeps its dict

    @cached_property
    def sampler(self) -> ArchSampler:
        """The sampler of this ensemble's random arches (built and checked at construction)."""
        return ArchSampler(arch_from_dict(self.nominal, name="nominal"), self.spreads, self.seed)

    @cached_property
    def analysed_nominal(self) -> VoussoirArch:
        """The nominal arch as every sample is analysed: on its moved supports (re-closed,
        :func:`archrock.statics.supports.on_moved_supports`) when ``support`` is set."""
        if self.support is None:
            return self.sampler.nominal
        from ...statics.supports import on_moved_supports

        return on_moved_supports(self.sampler.nominal, self.support)

    def movements(self, start: int, count: int) -> list:
        """The support movement of samples start .. start + count - 1 (None: fixed supports):
        ``support`` itself, or with support_draw 'uniform' ``support`` times the sample's
        :meth:`~archrock.geometry.sampling.ArchSampler.movement_fractions`."""
        if self.support is None:
            return [None] * int(count)
        if self.support_draw == "fixed":
            return [self.support] * int(count)
        return [self.support.scaled(float(u))
                for u in self.sampler.movement_fractions(start, count)]

    @property
    def n_batches(self) -> int:
        return -(-self.samples // self.batch_size)

    def batch_range(self, b: int) -> tuple[int, int]:
        """(first sample index, number of samples) of batch b."""
        start = b * self.batch_size
        return start, min(self.batch_size, self.samples - start)

    def to_dict(self) -> dict:
        """JSON-ready dict, every field under its own name; the motion, spreads, impact and
        support as their specifications' dicts (the manifests' format)."""
        d = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        d["nominal"] = copy.deepcopy(self.nominal)
        d["motion"] = None if self.motion is None else self.motion.to_dict()
        d["spreads"] = self.spreads.to_dict()
        d["impact"] = self.impact.to_dict()
        d["support"] = None if self.support is None else self.support.to_dict()
        return d

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), sort_keys=True)

    def legacy_dict(self) -> dict:
        """The dict archrock 0.4-0.6 wrote, which the configuration hash is computed from: the
        spreads under their old keys (``Spreads.legacy_dict``), and early_stop, support and
        support_draw left out at their defaults (false, none, 'fixed'), as they were before
        those fields existed.  Kept as it is so that output folders of those releases resume."""
        d = self.to_dict()
        d["spreads"] = self.spreads.legacy_dict()
        if not self.early_stop:
            del d["early_stop"]
        if self.support is None:
            del d["support"]
        if self.support_draw == "fixed":
            del d["support_draw"]
        return d

    def config_hash(self) -> str:
        """sha256 (hex) of :meth:`legacy_dict` as JSON with sorted keys: the ``config_sha256``
        of every stored batch (archrock 0.4's form, so its folders resume)."""
        text = json.dumps(self.legacy_dict(), sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()

    @staticmethod
    def upgrade_dict(data: dict) -> dict:
        """A stored configuration dict (a manifest's, of any release since 0.4) in
        :meth:`to_dict`'s form, without building anything: the spreads' old keys renamed, the
        fields left out at their defaults filled in.  A dict that is not a configuration's is
        returned as it is (the comparison that follows names what differs)."""
        if not isinstance(data, dict):
            return data
        d = dict(data)
        sp = d.get("spreads")
        if isinstance(sp, dict):
            sp = {LEGACY_KEYS.get(k, k): v for k, v in sp.items()}
            sp.setdefault("tilt", 0.0)
            d["spreads"] = sp
        for name, default in (("early_stop", False), ("support", None), ("support_draw", "fixed")):
            d.setdefault(name, default)
        return d

    @classmethod
    def from_dict(cls, data: dict) -> "EnsembleConfig":
        """The configuration of :meth:`to_dict`'s dict or of archrock 0.4-0.6's (the spreads'
        old keys are read as aliases, :data:`archrock.geometry.sampling.LEGACY_KEYS`)."""
        names = {f.name for f in dataclasses.fields(cls)}
        unknown = set(data) - names
        if unknown:
            raise ArchInputError(f"ensemble configuration: unknown field(s) {sorted(unknown)}")
        return cls(**data)
