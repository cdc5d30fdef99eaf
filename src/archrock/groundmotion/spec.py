"""Serialisable ground-motion specifications: what to build, rather than the samples themselves.

A specification is frozen, hashable and JSON-ready: ``to_dict()`` / ``from_dict()`` round-trip
exactly, and :meth:`build` returns the :class:`~archrock.groundmotion.GroundMotion` (cached).
The dicts are those of the ensemble manifests written before the specifications existed
({"type": "pulse", ...} and {"type": "record", ...}), so those manifests and their
configuration hashes stay valid.  Each specification is checked by building it once.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from ..errors import ArchInputError
from .motion import UNITS, GroundMotion, _positive, _real, check_pga
from .pulses import pulse, pulse_kind
from .p695 import is_suite_ref
from .records import file_sha256, load_record

__all__ = ["PulseSpec", "RecordSpec", "motion_spec_from_dict"]

_HEX64 = re.compile(r"[0-9a-f]{64}")


def _fields(d, cls_name: str, kind: str, required: tuple, optional: tuple = ()) -> None:
    """Check a specification dict's keys ({"type": kind} plus the fields), naming the field."""
    if not isinstance(d, dict):
        raise ArchInputError(f"motion: {d!r}; allowed a dict with type {kind!r}")
    if d.get("type") != kind:
        raise ArchInputError(f"motion type: {d.get('type')!r}; allowed {kind!r} for a {cls_name}")
    unknown = sorted(set(d) - {"type", *required, *optional})
    if unknown:
        raise ArchInputError(f"motion: unknown field(s) {unknown} in a {kind} specification; "
                             f"allowed {', '.join(('type',) + required + optional)}")
    missing = [k for k in required if k not in d]
    if missing:
        raise ArchInputError(f"motion {missing[0]}: missing from a {kind} specification")


@dataclass(frozen=True)
class PulseSpec:
    """An idealised pulse: ``kind`` one of PULSE_KINDS ('_' and case tolerated; kept as given,
    so the dict is the one written before), ``amplitude_g`` [g] (sign = direction of the main
    lobe, + toward +x; the paper's -1), ``duration`` t_p [s] (for 'ricker' the period)."""

    kind: str
    amplitude_g: float
    duration: float

    def __post_init__(self):
        pulse_kind(self.kind)
        object.__setattr__(self, "amplitude_g", _real("pulse amplitude", self.amplitude_g, "g"))
        object.__setattr__(self, "duration", _positive("pulse duration", self.duration))
        self.build()  # the constructors' own checks (e.g. sampling) run once, here

    def build(self) -> GroundMotion:
        """The pulse as a GroundMotion (cached: equal specifications share one motion)."""
        return _build_pulse(self)

    def describe(self) -> str:
        t = "period" if pulse_kind(self.kind) == "ricker" else "t_p"
        return f"{pulse_kind(self.kind)} pulse: a = {self.amplitude_g:g} g, {t} = {self.duration:g} s"

    def to_dict(self) -> dict:
        return {"type": "pulse", "kind": self.kind, "amplitude_g": self.amplitude_g,
                "duration": self.duration}

    @classmethod
    def from_dict(cls, d: dict) -> PulseSpec:
        _fields(d, cls.__name__, "pulse", ("kind", "amplitude_g", "duration"))
        return cls(d["kind"], d["amplitude_g"], d["duration"])


@dataclass(frozen=True)
class RecordSpec:
    """A recorded ground motion file: ``path`` (a string; :meth:`from_file` makes it absolute),
    ``units`` of a two-column file (None: the reader's default, g; a ``.AT2`` file is in g),
    ``scale``: factor on the acceleration (finite, may be negative), ``sha256``: hex digest of the
    file, checked at every :meth:`build` so that a changed file is never used silently."""

    path: str
    units: str | None
    scale: float
    sha256: str

    def __post_init__(self):
        if not isinstance(self.path, (str, Path)) and not hasattr(self.path, "__fspath__"):
            raise ArchInputError(f"record path: {self.path!r}; allowed a file path")
        object.__setattr__(self, "path", os.fspath(self.path))
        if self.units is not None and (not isinstance(self.units, str) or self.units not in UNITS):
            allowed = ", ".join(repr(k) for k in UNITS)
            raise ArchInputError(f"record units: {self.units!r}; allowed None or one of {allowed}")
        object.__setattr__(self, "scale", _real("record scale", self.scale))
        if not isinstance(self.sha256, str) or not _HEX64.fullmatch(self.sha256):
            raise ArchInputError(f"record sha256: {self.sha256!r}; allowed 64 lowercase hex digits")
        self.build()

    @classmethod
    def from_file(cls, path, units: str | None = None, scale: float = 1.0) -> RecordSpec:
        """The specification of the file at ``path`` as it is now (absolute path, its sha256)."""
        if not isinstance(path, (str, Path)) and not hasattr(path, "__fspath__"):
            raise ArchInputError(f"record path: {path!r}; allowed a file path")
        if is_suite_ref(path):  # a built-in suite's record: its name is its path
            return cls(path.strip(), units, scale, _file_sha256(path.strip()))
        p = Path(path).resolve()
        return cls(str(p), units, scale, _file_sha256(p))

    def build(self) -> GroundMotion:
        """The record as a GroundMotion, after checking the file's sha256 (the parsed record is
        cached per specification; the checksum is computed at every call)."""
        digest = _file_sha256(self.path)
        if digest != self.sha256:
            raise ArchInputError(
                f"record sha256: {self.path!r} now has sha256 {digest[:12]}..., the specification "
                f"says {self.sha256[:12]}...; the file has changed (allowed: the file as "
                f"specified; make a new specification to use the new file)")
        return _build_record(self)

    def describe(self) -> str:
        scale = f", scaled by {self.scale:g}" if self.scale != 1.0 else ""
        return (f"record {_shown(self.path)} (units {self.units or 'g'}{scale}; "
                f"sha256 {self.sha256[:12]}...)")

    def to_dict(self) -> dict:
        return {"type": "record", "path": self.path, "units": self.units, "scale": self.scale,
                "sha256": self.sha256}

    @classmethod
    def from_dict(cls, d: dict) -> RecordSpec:
        # units and scale may be absent (as the ensemble descriptions allowed): None and 1
        _fields(d, cls.__name__, "record", ("path", "sha256"), ("units", "scale"))
        return cls(d["path"], d.get("units"), d.get("scale", 1.0), d["sha256"])


_SPECS = {"pulse": PulseSpec, "record": RecordSpec}


def motion_spec_from_dict(d: dict) -> PulseSpec | RecordSpec:
    """The specification of a dict from ``to_dict()``, by its "type" ('pulse' or 'record')."""
    kind = d.get("type") if isinstance(d, dict) else None
    if kind not in _SPECS:
        raise ArchInputError(f"motion: {d!r}; allowed a dict with type 'pulse' or 'record'")
    return _SPECS[kind].from_dict(d)


@lru_cache(maxsize=8)
def _build_pulse(spec: PulseSpec) -> GroundMotion:
    return pulse(spec.kind, spec.amplitude_g, spec.duration)


@lru_cache(maxsize=8)
def _build_record(spec: RecordSpec) -> GroundMotion:
    motion = load_record(spec.path, spec.units)
    if spec.scale == 1.0:
        return motion
    check_pga(abs(spec.scale) * motion.pga_g, f"record {_shown(spec.path)} scaled by "
              f"{spec.scale:g}", "is the scale factor meant? --scale multiplies the values")
    return motion.scaled(spec.scale)


def _shown(path: str) -> str:
    """A record's name in a message: a suite record's SUITE/ID, a file's name."""
    return path if is_suite_ref(path) else Path(path).name


def _file_sha256(path) -> str:
    if is_suite_ref(path):  # its own line ("records: ... not installed; pip install ...")
        return file_sha256(path)
    try:
        digest = file_sha256(path)
    except ArchInputError as exc:  # missing, unreadable or past the size limit
        raise ArchInputError(f"record path: {exc}") from None
    return digest
