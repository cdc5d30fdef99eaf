"""The built-in FEMA P695 suites in the page's record menu (extra ``records``).

``GET /api/suites``: the suites and whether the extra is installed (if not, how to get it);
``GET /api/suites/{name}``: one suite's records with the set's metadata;
``POST /api/suites/record`` {suite_ref, scale?}: one record loaded as an uploaded file is
(:class:`~archrock.app.uploads.RecordStore`, the same answer as ``/api/record``), so the page
plays it by its id; ``/api/respond`` also takes ``record: {suite_ref, scale?}`` directly.
The record is read by the library's :class:`~archrock.groundmotion.RecordSpec`, as
``--record SUITE/ID`` is: the same samples, checksum and scale checks.
"""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError
from .fields import number, only
from .uploads import RecordStore, trace
from .uploads import record_motion as loaded_record_motion

#: The fields of a suite record in a request.
SUITE_RECORD_FIELDS = ("suite_ref", "scale")
#: A record's metadata the menu shows (names of :class:`~archrock.groundmotion.p695.SuiteRecord`).
MENU_FIELDS = ("ref", "record", "component", "event", "year", "magnitude", "station",
               "distance_km", "site_class", "pga_g", "pgv_max_cm_s", "dt", "duration")


def suites_index() -> dict:
    """The built-in suites (name, what it is), ``installed`` and, without the extra,
    ``install``: the one line saying how to get it."""
    from ..groundmotion.p695 import EXTRA_HINT, NORMALIZED, SUITES, extra_available

    have = extra_available()
    return {"suites": [{"name": k, "description": v[1]} for k, v in SUITES.items()],
            "normalized_suffix": NORMALIZED, "installed": have,
            "install": None if have else f"the FEMA P695 record sets: {EXTRA_HINT}"}


def suite_table(name) -> dict:
    """Every record of suite ``name`` (a built-in suite, ``-normalized`` too) with its
    metadata: ArchInputError naming the field for an unknown name or without the extra."""
    from ..groundmotion.p695 import is_suite, suite_names, suite_records

    if not is_suite(name):
        raise ArchInputError(f"suite: {str(name)[:40]!r}; allowed "
                             f"{', '.join(suite_names())}")
    rows = [{k: getattr(r, k) for k in MENU_FIELDS} for r in suite_records(name)]
    return {"name": name, "count": len(rows), "records": rows}


def suite_record_motion(params) -> tuple:
    """(GroundMotion, info) of the record ``{suite_ref, scale?}``, read by the library: its
    id and what the page shows (name, samples, time step, duration, PGA [g], sha256)."""
    import warnings

    from ..groundmotion import RecordSpec
    from ..groundmotion.p695 import is_suite_ref
    from ..units import G

    if not isinstance(params, dict):
        raise ArchInputError("record: expected an object {suite_ref, scale} of a built-in "
                             "suite's record")
    only(params, SUITE_RECORD_FIELDS, "record")
    ref = params.get("suite_ref")
    if not is_suite_ref(ref):
        raise ArchInputError(f"suite_ref: {str(ref)[:40]!r}; allowed SUITE/ID of a built-in "
                             f"suite, such as p695-far-field/1a (GET /api/suites lists them)")
    scale = number(params, "scale", 1.0)
    if scale == 0:
        raise ArchInputError("scale: 0; allowed a finite nonzero factor on the record")
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        spec = RecordSpec.from_file(ref.strip(), None, scale)
        motion = spec.build()
    t = np.asarray(motion.times, float)
    dt = np.diff(t)
    info = {"id": f"{spec.path}-{scale!r}", "name": spec.path, "suite_ref": spec.path,
            "units": "g", "scale": scale, "sha256": spec.sha256, "samples": int(len(t)),
            "dt_s": float(np.median(dt)) if len(dt) else None, "duration_s": float(t[-1]),
            "pga_g": float(motion.pga / G),
            "title": str(motion.source).removeprefix(f"FEMA P695 {spec.path}: ")[:120],
            "warnings": [" ".join(str(w.message).split()) for w in said]}
    return motion, info


def load_suite_record(params, store: RecordStore) -> dict:
    """The record ``{suite_ref, scale?}`` kept in ``store`` like an uploaded one (the answer
    of ``/api/record``: its id, what the page shows and a small trace)."""
    from ..units import G

    motion, info = suite_record_motion(params)
    store.put(info["id"], motion, info)
    return {**info, "trace": trace(motion.times, np.asarray(motion.accel, float) / G)}


def record_motion(params, store: RecordStore | None) -> tuple:
    """(GroundMotion, info) of a response's ``record``: a built-in suite's record
    ``{suite_ref, scale?}``, or one loaded in ``store`` ``{id}``."""
    if isinstance(params, dict) and "suite_ref" in params:
        return suite_record_motion(params)
    return loaded_record_motion(params, store)
