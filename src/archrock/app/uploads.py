"""Files the page uploads: a recorded ground motion (PEER .AT2 or two columns) and a DXF survey.

The server streams each body to a temporary file under :data:`MAX_FILE_BYTES` (:class:`Upload`);
this module reads it through the library's readers, as ``--record`` and ``import-dxf`` do, and
keeps the last :data:`KEEP_RECORDS` records for ``/api/respond`` (:class:`RecordStore`).
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..errors import ArchInputError
from .fields import COMPUTE_LOCK, MAX_VOUSSOIRS, choice, number, only, xy

#: Largest uploaded file (a record or a DXF drawing) [bytes].
MAX_FILE_BYTES = 20_000_000
#: A recorded ground motion: the response window [s] (the record's own length is free; the
#: response runs to the window's end) and the package's estimate of one response's time [s]
#: (archrock.studies.work.response_cost_s; without numba about 50 times more).
MAX_RECORD_T_END_S = 120.0
MAX_RESPONSE_WORK_S = 2.0
#: Loaded records kept in memory (the oldest is forgotten first).
KEEP_RECORDS = 4
RECORD_UNITS = ("g", "m/s2", "cm/s2")
DXF_UNITS = ("m", "cm", "mm")


class Upload(NamedTuple):
    """An uploaded file as the server streamed it: its ``path`` (in a temporary folder of the
    server, mode 0700, deleted after the request), ``size`` [bytes] and ``sha256``."""

    path: Path
    size: int
    sha256: str

    @classmethod
    def of_bytes(cls, data: bytes, folder) -> Upload:
        """The upload of ``data`` written into ``folder`` (scripts, tests)."""
        import hashlib

        path = Path(folder) / "upload.bin"
        path.write_bytes(data)
        return cls(path, len(data), hashlib.sha256(data).hexdigest())


class TooLarge(ArchInputError):
    """An upload above :data:`MAX_FILE_BYTES` (HTTP 413)."""


def too_large(field: str, size: int) -> TooLarge:
    return TooLarge(f"{field}: {size:,} bytes; the app reads files of up to "
                    f"{MAX_FILE_BYTES // 1_000_000} MB ({MAX_FILE_BYTES:,} bytes)")


def safe_name(name, default: str) -> str:
    """A file name safe to create in the server's own temporary folder: the last path part of
    ``name``, letters, digits and ``._-`` only, at most 80 characters (the suffix kept: the
    readers choose by it), ``default`` when nothing is left."""
    import re

    base = str(name or "").replace("\\", "/").rsplit("/", 1)[-1]
    base = re.sub(r"[^A-Za-z0-9._-]", "_", base).lstrip(".")
    if len(base) > 80:
        stem, dot, suffix = base.rpartition(".")
        base = (stem[:70] + dot + suffix[:9]) if dot else base[:80]
    return base or default


def _parse_in(upload: Upload, name: str, read):
    """``read(path)`` of the uploaded file renamed ``name`` in its own temporary folder (the
    readers choose by the suffix); messages name the file, not the folder."""
    path = upload.path.with_name(name)
    upload.path.replace(path)
    try:
        return read(path)
    except ArchInputError as exc:
        folder = str(path.parent)
        raise type(exc)(str(exc).replace(str(path), name).replace(folder + "/", "")) from None


class RecordStore:
    """The records loaded in this server: id -> (GroundMotion, info), the last
    :data:`KEEP_RECORDS` kept."""

    def __init__(self):
        from collections import OrderedDict

        self._items = OrderedDict()
        self._lock = threading.Lock()

    def put(self, key: str, motion, info: dict) -> None:
        with self._lock:
            self._items[key] = (motion, info)
            self._items.move_to_end(key)
            while len(self._items) > KEEP_RECORDS:
                self._items.popitem(last=False)

    def get(self, key):
        with self._lock:
            item = self._items.get(key) if isinstance(key, str) else None
        if item is None:
            raise ArchInputError(f"record: {str(key)[:20]!r} is not loaded in this server (it "
                                 f"keeps the last {KEEP_RECORDS}); open the record file again")
        return item


def trace(times, accel_g, points: int = 2000) -> dict:
    """A record drawn small: the least and greatest value of each of ``points`` stretches
    (the peaks kept), or every sample of a short one."""
    t, a = np.asarray(times, float), np.asarray(accel_g, float)
    if len(t) <= 2 * points:
        return {"time": xy(t), "accel_g": xy(a)}
    edges = np.linspace(0, len(t), points + 1).astype(int)
    ts, vs = [], []
    for i0, i1 in zip(edges[:-1], edges[1:]):
        seg = a[i0:i1]
        lo, hi = i0 + int(np.argmin(seg)), i0 + int(np.argmax(seg))
        for j in sorted((lo, hi)):
            ts.append(t[j])
            vs.append(a[j])
    return {"time": xy(ts), "accel_g": xy(vs)}


def load_record_upload(data: Upload, params: dict, store: RecordStore) -> dict:
    """Read an uploaded record file (``data``, streamed by the server; its ``name``: ``.AT2`` is a PEER file in g,
    anything else two columns "time accel"), with ``units`` (g, m/s2, cm/s2) and ``scale``, by
    the library's :class:`~archrock.groundmotion.RecordSpec` (``load_record`` and the scale's
    check) in a temporary folder of the server; keep it in ``store``.  Returns its id and
    what the page shows of it: name, samples, time step, duration, PGA [g], sha256 and a small
    trace of it."""
    import warnings

    from ..groundmotion import RecordSpec
    from ..units import G

    only(params, ("name", "units", "scale"), "record")
    if data.size > MAX_FILE_BYTES:
        raise too_large("record", data.size)
    if not data.size:
        raise ArchInputError("record: the file is empty; allowed a PEER .AT2 file or two "
                             "columns 'time accel'")
    name = safe_name(params.get("name"), "record.txt")
    units = choice(params, "units", RECORD_UNITS)
    scale = number(params, "scale", 1.0)
    if scale == 0:
        raise ArchInputError("scale: 0; allowed a finite nonzero factor on the record")
    if name.lower().endswith(".at2") and units not in (None, "g"):
        raise ArchInputError(f"units: {units!r} for {name}; allowed g (PEER .AT2 values are in g)")
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        motion = _parse_in(
            data, name, lambda p: RecordSpec.from_file(p, None if name.lower().endswith(".at2")
                                                       else units, scale).build())
    sha = data.sha256
    key = f"{sha[:16]}-{units or 'g'}-{scale!r}"
    t = np.asarray(motion.times, float)
    dt = np.diff(t)
    info = {"id": key, "name": name, "units": units or "g", "scale": scale, "sha256": sha,
            "samples": int(len(t)), "dt_s": float(np.median(dt)) if len(dt) else None,
            "duration_s": float(t[-1]), "pga_g": float(motion.pga / G),
            "title": str(motion.name)[:120],
            "warnings": [" ".join(str(w.message).split()) for w in said]}
    store.put(key, motion, info)
    return {**info, "trace": trace(t, np.asarray(motion.accel, float) / G)}


def record_motion(params, store: RecordStore | None):
    """The loaded record named by ``{"id": ...}`` and its info."""
    if store is None:
        raise ArchInputError("record: no record can be loaded here")
    if not isinstance(params, dict):
        raise ArchInputError("record: expected an object {id} of a loaded record")
    only(params, ("id",), "record")
    return store.get(params.get("id"))


def load_dxf_upload(data: Upload, params: dict) -> dict:
    """Read an uploaded DXF survey (one closed polyline per voussoir) as ``archrock
    import-dxf`` does (:func:`archrock.geometry.dxf.read_dxf_outlines` then
    :func:`~archrock.geometry.dxf.arch_from_outlines`, the steps of ``read_dxf``, with its
    defaults: every layer, drawing units m, density 2000 kg/m^3), the number of voussoirs
    checked before the chain is built.  Returns the geometry file's JSON (what the page then
    sends as an opened geometry file), the name and the DXF handles from the left springing."""
    from ..options import GEOMETRY_DEFAULTS
    from ..geometry.dxf import arch_from_outlines, read_dxf_outlines

    only(params, ("name", "layer", "units", "density"), "dxf")
    if data.size > MAX_FILE_BYTES:
        raise too_large("dxf", data.size)
    if not data.size:
        raise ArchInputError("dxf: the file is empty; allowed a DXF drawing")
    name = safe_name(params.get("name"), "survey.dxf")
    layer = params.get("layer") or None
    if layer is not None and (not isinstance(layer, str) or len(layer) > 255):
        raise ArchInputError("layer: expected a layer name")
    units = choice(params, "units", DXF_UNITS, "m")
    density = number(params, "density", GEOMETRY_DEFAULTS["density"])
    if not density > 0:
        raise ArchInputError(f"density: {density:g}; allowed > 0 kg/m^3")
    stem = name.rsplit(".", 1)[0] or "survey"

    def read(path):
        found = read_dxf_outlines(path, layer, units)
        if len(found) > MAX_VOUSSOIRS:
            raise ArchInputError(f"{name}: {len(found)} closed polylines; the app allows 3 to "
                                 f"{MAX_VOUSSOIRS} voussoirs")
        handles = [h for h, _ in found]
        try:
            arch, order = arch_from_outlines([p for _, p in found], handles, density=density,
                                             name=stem)
        except ArchInputError as exc:
            raise ArchInputError(f"{name}: {exc}") from None
        return arch, [handles[i] for i in order]

    try:
        with COMPUTE_LOCK:
            arch, handles = _parse_in(data, name, read)
    except ImportError as exc:  # ezdxf missing: the extra to install
        raise ArchInputError(f"dxf: {exc}") from None
    except ArchInputError as exc:
        raise ArchInputError(f"dxf: {exc}") from None
    from ..options import json_safe

    geometry = {**arch.to_dict(), "metadata": {"generator": "archrock app (import-dxf)",
                                               "drawing": name, "layer": layer,
                                               "units": units, "handles": handles}}
    return {"geometry": json_safe(geometry), "name": stem, "n": int(arch.n),
            "handles": handles}


