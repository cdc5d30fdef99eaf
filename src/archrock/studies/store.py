"""The one store of the studies: a folder of Parquet files written atomically, a manifest, and
resumption.  Two layouts share its writing, provenance and clean-up:

* an ensemble's output folder (:class:`Manifest`, :func:`write_batch`, :func:`read_batch`),
  the format of 0.4.0 and later (tests/data/ensemble-0.4.0 resumes);
* a sweep's kept items (:class:`ResultStore`): IDA, multiple stripes and the curves.

Ensemble layout: ``manifest.json`` (configuration, seeds, versions, runs) next to
``batches/batch-00000.parquet``, each written atomically (``*.tmp-PID``, then rename).  Every
table has its SHA-256 in a sidecar (``batch-00000.parquet.sha256``, written before the table is
renamed into place) and every manifest its own inside (:mod:`archrock.studies.checksums`),
checked before the file is read: a damaged or truncated table is recomputed, never read (a
table without a sidecar, from a folder older than checksums, is read whole, checked by
:func:`_implausible` and its checksum recorded); a damaged manifest is refused.  Each batch
file carries in its Parquet metadata (key ``archrock.ensemble``) the configuration's sha256, its
batch number and the sha256 of the package's sources; a file whose metadata, ``batch`` or
``index`` columns do not match (or that cannot be read) is recomputed, with the reason.  Batches
that differ only by the code that wrote them (an older release) are resumed by verification
(:func:`same_bits`, used by :func:`archrock.studies.ensemble.run.run_ensemble`): one of them is
recomputed, and the others are kept only if it comes out bit for bit the same.  Batch files
without ``manifest.json`` are refused; ``*.tmp-PID`` files of killed writes are removed when a
run starts.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
import os
import platform
import re
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import ArchInputError
from .checksums import (check_seal, check_sidecar, file_sha256, seal, sidecar_path, write_atomic,
                        write_sidecar)

__all__ = ["EnsembleConfigMismatch", "Manifest", "batch_path", "read_batch", "write_batch",
           "written_by", "same_bits", "code_digest", "is_damage", "say_damage", "MANIFEST",
           "FORMAT", "PROVENANCE_KEY", "OTHER_CODE", "ResultStore", "SWEEP_FORMAT"]

#: Why a batch is not loaded as it is: the sources that wrote it differ from these.
OTHER_CODE = "written by other archrock code"
#: how the reasons for a damaged file begin (:func:`is_damage`)
_DAMAGE = ("damaged", "unreadable", "no recorded checksum, and")


def is_damage(why: str | None) -> bool:
    """Whether a reason of :func:`read_batch` (or a chunk's) says the file is damaged: said
    even when progress output is off (a warning), unlike the other reasons to recompute."""
    return bool(why) and why.startswith(_DAMAGE)


def say_damage(line: str, note=None) -> None:
    """A damaged file, in one line: to ``note`` (the progress sink) if there is one, else as a
    warning (the CLI prints ``archrock: warning: ...``), so it is never silent."""
    if note is not None:
        note(line)
    else:
        import warnings

        warnings.warn(line, stacklevel=3)

MANIFEST = "manifest.json"
# 2: spreads and impact as objects; draws by ArchSampler.  3: t_collapse is the last passage of
# the unstable position (no longer the rotation limit), t_limit a new column.  4: early_stopped
FORMAT = "archrock-ensemble/4"
PROVENANCE_KEY = b"archrock.ensemble"


class EnsembleConfigMismatch(ArchInputError):
    """An output folder holds an ensemble with a different configuration."""


def _versions() -> dict:
    from importlib import metadata

    out = {"python": platform.python_version()}
    for pkg in ("archrock", "numpy", "scipy", "numba", "pandas", "pyarrow", "dask", "distributed"):
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            out[pkg] = None
    return out


def _now() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def _write_json_atomic(path: Path, obj) -> None:
    """Write a manifest atomically and durably, sealed with its own checksum."""
    write_atomic(path, json.dumps(seal(obj), indent=2, allow_nan=False).encode("utf-8"))


def _read_manifest(path: Path) -> dict:
    """A manifest's JSON, checked against its own checksum: ArchInputError naming the file
    when it is not readable JSON or is damaged (its configuration cannot then be trusted)."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise ArchInputError(f"out: {str(path)!r} cannot be read ({exc.strerror or exc})") from None
    try:
        data = json.loads(raw.decode("utf-8"))
    except ValueError as exc:  # UnicodeDecodeError too
        why = f"not readable JSON ({exc})"
    else:
        why = check_seal(data)
        if why is None:
            return data
    raise ArchInputError(f"out: {str(path)!r} is damaged ({why}), so what it records cannot be "
                         f"trusted; use another output folder, or delete this one to start "
                         f"again") from None


def batch_path(out: Path, b: int) -> Path:
    """The file of batch ``b`` in the output folder ``out``."""
    return out / "batches" / f"batch-{b:05d}.parquet"


@lru_cache(maxsize=1)
def _code_digest() -> str:
    """sha256 of the package's sources: batches written by other code are recomputed."""
    from .._jit import _package_digest

    return _package_digest()


def _config_hash(config) -> str:
    return config.config_hash()  # from archrock 0.4's form of the configuration


def _provenance(config, b: int) -> dict:
    return {"format": FORMAT, "config_sha256": _config_hash(config), "batch": int(b),
            "code_sha256": _code_digest()}


def write_batch(out: Path, b: int, df, config) -> None:
    """Write batch ``b``'s table atomically, with its provenance in the Parquet metadata."""
    import pyarrow as pa

    table = pa.Table.from_pandas(df, preserve_index=False)
    meta = dict(table.schema.metadata or {})
    meta[PROVENANCE_KEY] = json.dumps(_provenance(config, b), sort_keys=True).encode()
    _write_table(table.replace_schema_metadata(meta), batch_path(out, b))


def _write_table(table, path: Path) -> None:
    """Write a pyarrow ``table`` as ``path`` atomically: a ``*.tmp-PID`` file, its checksum
    recorded (sidecar) first, then the rename, so a table in place always has its checksum
    (module checksums)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    # pyarrow's own SIGINT handling can swallow a Ctrl-C that arrives while it writes (the run
    # then goes on to the end); Python's handler must see it so the study stops and says
    # what it kept
    pa.enable_signal_handlers(False)
    tmp = path.with_name(f"{path.name}.tmp-{os.getpid()}")
    pq.write_table(table, tmp)
    write_sidecar(path, file_sha256(tmp))
    os.replace(tmp, path)


def code_digest() -> str:
    """sha256 of this installation's archrock sources (the ``code_sha256`` of what it writes)."""
    return _code_digest()


def written_by(out: Path, b: int) -> str | None:
    """The ``code_sha256`` recorded in batch ``b``'s file (None: no file or no provenance)."""
    import pyarrow.parquet as pq

    try:
        meta = json.loads((pq.read_schema(batch_path(out, b)).metadata or {})
                          .get(PROVENANCE_KEY, b"null"))
    except Exception:  # no file, or a damaged one: read_batch says why
        return None
    return meta.get("code_sha256") if isinstance(meta, dict) else None


def same_bits(old, new) -> str | None:
    """None when two batch tables are identical bit for bit (floats compared by their bytes, so
    -0.0 != 0.0 and NaN == NaN); else the first column that differs, in words."""
    if list(old.columns) != list(new.columns) or len(old) != len(new):
        return "its columns or number of rows"
    for col in old.columns:
        a, b = old[col].to_numpy(), new[col].to_numpy()
        if a.dtype != b.dtype:
            return f"column {col!r} (type {a.dtype} against {b.dtype})"
        same = (a.tobytes() == b.tobytes() if a.dtype != object
                else all(x == y or (x != x and y != y) for x, y in zip(a, b)))
        if not same:
            return f"column {col!r}"
    return None


def read_batch(out: Path, b: int, config, any_code: bool = False):
    """(DataFrame, None) for a verified batch file; (None, None) when there is none; (None,
    reason) when the file exists but cannot be used (it is then recomputed).  ``any_code``: a
    file written by other archrock sources is returned too (the caller verifies it, see
    :func:`written_by`); otherwise it is (None, :data:`OTHER_CODE`).

    The file's SHA-256 is checked against its sidecar before it is read: a damaged or
    truncated file is never read.  A file without one (written before checksums) is read
    whole and checked (:func:`_implausible`), and its checksum recorded if it passes."""
    path = batch_path(out, b)
    if not path.is_file():
        return None, None
    try:
        damaged, legacy = check_sidecar(path), None
    except FileNotFoundError:
        damaged, legacy = _legacy_sha256(path)  # the bytes that are checked, then recorded
    if damaged is not None:
        return None, damaged
    df, why = _read_checked(path, b, config, any_code)
    if df is not None and legacy is not None:
        why = _implausible(df)
        if why is not None:
            return None, f"no recorded checksum, and {why}"
        write_sidecar(path, legacy)
    return (df, None) if why is None else (None, why)


def _legacy_sha256(path: Path) -> tuple:
    """(None, sha256) of a table without a recorded checksum, or (why, None) if unreadable."""
    try:
        return None, file_sha256(path)
    except OSError as exc:
        return f"unreadable ({exc.strerror or type(exc).__name__})", None


def _read_checked(path: Path, b: int, config, any_code: bool):
    """:func:`read_batch` of a file whose checksum was checked: its provenance and rows."""
    import pyarrow.parquet as pq

    try:
        table = pq.read_table(path)
        meta = json.loads((table.schema.metadata or {}).get(PROVENANCE_KEY, b"null"))
        df = table.to_pandas()
    except Exception as exc:  # a damaged file is recomputed
        return None, f"unreadable ({type(exc).__name__})"
    if not isinstance(meta, dict):
        return None, "no provenance metadata (written by older code)"
    want = _provenance(config, b)
    if meta.get("format") != FORMAT:
        return None, f"format {meta.get('format')!r}, expected {FORMAT!r}"
    if meta.get("config_sha256") != want["config_sha256"]:
        return None, "written for another configuration"
    if meta.get("batch") != b:
        return None, f"holds batch {meta.get('batch')!r}"
    if meta.get("code_sha256") != want["code_sha256"] and not any_code:
        return None, OTHER_CODE
    start, nb = config.batch_range(b)
    if list(df.columns) != COLUMNS or len(df) != nb:
        return None, "unexpected columns or number of rows"
    if not ((df["batch"].to_numpy() == b).all()
            and np.array_equal(df["index"].to_numpy(), np.arange(start, start + nb))):
        return None, f"its batch/index columns are not batch {b}, samples {start}..{start + nb - 1}"
    return df, None


#: Columns of a batch's table (one row per sample).  Times [s]: t_collapse, the last upward
#: passage of the unstable position before the rotation limit (the physical collapse time, which
#: the limit does not move); t_limit, when the limit (a numerical stop) was reached; t_unstable,
#: the first passage of the unstable position (NaN if never).  early_stopped: the arch was no
#: longer followed once it could not collapse (EnsembleConfig.early_stop; status "stopped":
#: peak final, n_impacts / n_activations only those before the stop, no rest).  error: '' for an
#: arch that was analysed, else why it was left out: the text of the
#: :class:`~archrock.leftout.LeftOut` it was refused with (a table and its Parquet file hold
#: text, as every release since 0.4 wrote it), read back by :meth:`~archrock.leftout.LeftOut.read`.
COLUMNS = ["batch", "index", "k_l", "k_r", "mech_l", "mech_r", "c_l_to_r", "c_r_to_l", "collapsed",
           "status", "peak", "t_collapse", "t_limit", "t_unstable", "n_impacts", "n_activations",
           "events_truncated", "early_stopped", "error"]
#: a batch's columns by kind (:data:`COLUMNS`)
_INTS = ("batch", "index", "n_impacts", "n_activations")
_BOOLS = ("collapsed", "events_truncated", "early_stopped")
_FLOATS = ("k_l", "k_r", "c_l_to_r", "c_r_to_l", "peak", "t_collapse", "t_limit", "t_unstable")
_TEXT = ("mech_l", "mech_r", "status", "error")
_SIGNED = ("k_l", "k_r", "c_l_to_r", "c_r_to_l")
#: no stored float is this large: multipliers and restitution coefficients are of order 1,
#: peaks are radians, times seconds of the motion and its free run
_FLOAT_BOUND = 1e3
#: event counts stop at the batch kernel's table (4096), with a wide margin
_COUNT_BOUND = 10**7


def _implausible(df) -> str | None:
    """Why a batch table without a recorded checksum cannot be trusted (None: its types and
    values are those this code writes).  Not a proof: a damaged digit within range passes."""
    from ..dynamics.batch import STATUS_NAMES

    for cols, kinds, what in ((_INTS, "iu", "integers"), (_BOOLS, "b", "booleans"),
                              (_FLOATS, "f", "floats")):
        for c in cols:
            if df[c].dtype.kind not in kinds:
                return f"column {c!r} does not hold {what} ({df[c].dtype})"
    for c in _FLOATS:
        v = df[c].to_numpy()
        v = v[~np.isnan(v)]
        if c in ("k_l", "k_r"):
            v = v[v != np.inf]  # no mechanism: k = +inf
        lo = -_FLOAT_BOUND if c in _SIGNED else 0.0  # peaks and times are not negative
        bad = v[~((v >= lo) & (v <= _FLOAT_BOUND))]
        if bad.size:
            return f"column {c!r} holds {bad[0]:.6g} (allowed NaN or {lo:g}..{_FLOAT_BOUND:g})"
    for c in ("n_impacts", "n_activations"):
        v = df[c].to_numpy()
        if ((v < 0) | (v > _COUNT_BOUND)).any():
            return f"column {c!r} holds {v[(v < 0) | (v > _COUNT_BOUND)][0]} (allowed 0..{_COUNT_BOUND})"
    for c in _TEXT:
        if not all(isinstance(x, str) for x in df[c]):
            return f"column {c!r} does not hold text"
    known = set(STATUS_NAMES.values()) | {"failed", "limit-only"}
    unknown = set(df["status"]) - known
    if unknown:
        return f"column 'status' holds {sorted(unknown)[0]!r} (allowed {sorted(known)})"
    if not np.array_equal(df["collapsed"].to_numpy(), (df["status"] == "collapsed").to_numpy()):
        return "its collapsed and status columns disagree"
    return None


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, ValueError):
        return pid > 0
    return pid > 0


def _remove_stale_tmp(out: Path, sub: str = "batches") -> list[str]:
    """Remove the ``*.tmp-PID`` files of killed writes (not those of a live process)."""
    removed = []
    for folder in (out, out / sub):
        for p in folder.glob("*.tmp-*"):
            m = re.fullmatch(r".*\.tmp-(\d+)", p.name)
            if not m or not p.is_file():
                continue
            pid = int(m.group(1))
            if pid != os.getpid() and _pid_alive(pid):
                continue
            try:
                p.unlink()
                removed.append(p.name)
            except OSError:
                pass
    return removed


class Manifest:
    """``manifest.json`` of an output folder: created, or checked against ``config`` (raises
    :class:`EnsembleConfigMismatch` naming the first differing field); each run is appended."""

    def __init__(self, out: Path, config, impact: dict, nominal: dict):
        self.out = out
        self.path = out / MANIFEST
        try:
            (out / "batches").mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ArchInputError(f"out: cannot create {str(out)!r} ({exc.strerror or exc})") from None
        cfg = config.to_dict()
        if not self.path.is_file() and any((out / "batches").glob("*.parquet")):
            raise ArchInputError(
                f"out: {str(out / 'batches')!r} holds batch files but {str(self.path)!r} is "
                f"missing, so their configuration is unknown; use another output folder or "
                f"delete that folder")
        if self.path.is_file():
            data = _read_manifest(self.path)
            if not (isinstance(data.get("config"), dict) and isinstance(data.get("runs"), list)
                    and isinstance(data.get("batches"), dict)):
                raise ArchInputError(
                    f"out: {str(self.path)!r} is damaged (its config, runs or batches are "
                    f"missing), so what it records cannot be trusted; use another output "
                    f"folder, or delete this one to start again")
            old = type(config).upgrade_dict(data.get("config", {}))  # 0.4-0.6's keys too
            diff = _config_differences(old, cfg)
            if diff:
                a, b = _flatten(old), _flatten(cfg)
                f = diff[0]
                raise EnsembleConfigMismatch(
                    f"out: {str(out)!r} holds an ensemble with a different configuration: field "
                    f"{f!r} is {a.get(f, '<absent>')!r} there and {b.get(f, '<absent>')!r} here"
                    + (f" (and {len(diff) - 1} more)" if len(diff) > 1 else "")
                    + "; use another output folder or the same options")
            self.data = data
        else:
            self.data = {
                "format": FORMAT, "config": cfg, "n_batches": config.n_batches,
                "seeds": {"entropy": config.seed,
                          "streams": "sample i is archrock.geometry.sampling.ArchSampler(nominal, "
                                     "spreads, seed).arch(i): block k = i // 500 reads numpy "
                                     "SeedSequence(entropy, spawn_key=(k,))"},
                "impact": impact, "nominal": nominal, "versions": _versions(),
                "started": _now(), "finished": None, "batches": {}, "runs": []}
        self.data["versions"] = _versions()
        self.run = {"started": _now(), "finished": None, "code_sha256": _code_digest(),
                    "computed": [], "loaded": [], "recomputed": {},
                    "removed_tmp": _remove_stale_tmp(out)}
        self.data["runs"].append(self.run)
        self.save()

    def save(self):
        _write_json_atomic(self.path, self.data)

    def batch_done(self, b: int, nb: int, timings: dict, computed: bool):
        (self.run["computed"] if computed else self.run["loaded"]).append(b)
        if computed or str(b) not in self.data["batches"]:
            self.data["batches"][str(b)] = {
                "file": str(batch_path(self.out, b).relative_to(self.out)), "samples": nb,
                "spawn_key": [b], "run": len(self.data["runs"]) - 1,
                **{k: v for k, v in timings.items() if k != "pid"}}

    def finish(self, complete: bool):
        self.run["finished"] = _now()
        self.run["computed"].sort()
        self.run["loaded"].sort()
        if complete:
            self.data["finished"] = _now()
        self.save()



def _flatten(d, prefix=""):
    out = {}
    if isinstance(d, dict):
        for k, v in d.items():
            out.update(_flatten(v, f"{prefix}.{k}" if prefix else str(k)))
    elif isinstance(d, list):
        out[prefix + ".length"] = len(d)
        for i, v in enumerate(d):
            out.update(_flatten(v, f"{prefix}[{i}]"))
    else:
        out[prefix] = d
    return out


def _config_differences(old: dict, new: dict) -> list[str]:
    a, b = _flatten(old), _flatten(new)
    return [k for k in sorted(set(a) | set(b)) if a.get(k, "<absent>") != b.get(k, "<absent>")]


# ---------------------------------------------------------------------------- a sweep's items
#: columns of a stored chunk of items (:class:`ResultStore`)
_STORED = ("status", "peak", "t_collapse", "t_unstable", "t_limit", "n_events")
SWEEP_FORMAT = STORE_FORMAT = "archrock-sweep/1"


def _digest(arches, motions, extra: dict) -> str:
    """sha256 of everything an item's result depends on: the packed arches and motions (their
    bytes; :class:`~archrock.dynamics.sweep.SweepArches`, ``SweepMotions``), the run settings
    and the package's sources."""
    h = hashlib.sha256()
    for name, arr in sorted(arches.arrays().items()) + [
            (k, v) for k, v in sorted(motions.arrays().items()) if k != "names"]:
        a = np.ascontiguousarray(arr)
        h.update(f"{name}\0{a.dtype.str}\0{a.shape}\0".encode())
        h.update(a.tobytes())
    h.update(json.dumps(extra, sort_keys=True).encode())
    h.update(_code_digest().encode())
    return h.hexdigest()


class ResultStore:
    """Finished items of a study's sweeps kept in a folder (``--out DIR``), so that a killed
    study started again recomputes nothing it had finished: ``manifest.json`` (format, the
    digest of the inputs, what the study is) and ``items/chunk-NNNNN.parquet`` (arch, motion,
    scale and the results of each item), each written atomically, with its checksum, as the
    ensemble's batches are.  A folder holding another study's items (another digest) or a
    damaged manifest is refused; a chunk that fails its checksum or cannot be read is removed
    and its items recomputed, with a line naming it to ``note`` (the progress sink; None: a
    warning) (:attr:`damaged`).  Needs pyarrow (the 'ensemble' extra)."""

    def __init__(self, folder, arches, motions, *, about: dict | None = None,
                 settings: dict | None = None, note=None):
        try:
            import pyarrow.parquet as pq  # noqa: F401
        except ImportError:
            raise ImportError("--out needs pyarrow: pip install 'archrock[ensemble]'") from None
        self.folder = Path(folder)
        self.digest = _digest(arches, motions, settings or {})
        man = self.folder / MANIFEST
        if man.exists():
            old = _read_manifest(man)
            if old.get("format") != SWEEP_FORMAT or old.get("digest") != self.digest:
                raise ArchInputError(f"out: {str(self.folder)!r} holds another study (other "
                                     f"arches, records, settings or archrock version); allowed "
                                     f"the folder of this very study, or a new one")
        else:
            try:
                self.folder.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise ArchInputError(f"out: cannot create {str(self.folder)!r} "
                                     f"({exc.strerror or exc})") from None
            _write_json_atomic(man, {"format": SWEEP_FORMAT, "digest": self.digest,
                                     "study": about or {}})
        (self.folder / "items").mkdir(exist_ok=True)
        _remove_stale_tmp(self.folder, "items")
        self.done: dict = {}
        self.damaged: list[str] = []  # chunks removed, their items to be computed again
        self.next = 0  # number of the next chunk file: after every existing one, never reused
        for f in sorted((self.folder / "items").glob("chunk-*.parquet")):
            num = f.stem.split("-")[-1]
            if num.isdigit():
                self.next = max(self.next, int(num) + 1)
            why = self._load(f)
            if why is not None:
                self._discard(f, why, note)
        self.loaded = len(self.done)

    @staticmethod
    def _key(a, m, s):
        return (int(a), int(m), float(s))

    def _load(self, path) -> str | None:
        """Read a chunk's items, its checksum checked first (None), or say why they cannot be
        trusted.  A chunk without a checksum (older code, or put there by hand) is read whole
        and checked (:func:`_chunk_implausible`), and its checksum recorded if it passes."""
        import pyarrow.parquet as pq

        try:
            why, legacy = check_sidecar(path), None
        except FileNotFoundError:
            why, legacy = _legacy_sha256(path)
        if why is not None:
            return why
        try:
            tab = pq.read_table(path).to_pydict()
        except Exception as exc:  # noqa: BLE001 - a damaged chunk is recomputed, not fatal
            return f"unreadable ({type(exc).__name__})"
        if set(tab) != {"arch", "motion", "scale", *_STORED}:
            return "unexpected columns"
        if legacy is not None:
            why = _chunk_implausible(tab)
            if why is not None:
                return f"no recorded checksum, and {why}"
            write_sidecar(path, legacy)
        for i, (a, m, s) in enumerate(zip(tab["arch"], tab["motion"], tab["scale"])):
            self.done[self._key(a, m, s)] = tuple(tab[c][i] for c in _STORED)
        return None

    def _discard(self, path, why: str, note) -> None:
        """Remove a chunk that cannot be trusted (its items are computed again), saying so."""
        name = f"{path.parent.name}/{path.name}"
        self.damaged.append(name)
        say_damage(f"out: recomputing the items of {name} in {str(self.folder)!r}: {why}", note)
        for p in (path, sidecar_path(path)):
            try:
                p.unlink()
            except OSError:
                pass

    def lookup(self, a, m, s):
        """The stored row of each item (None: not stored)."""
        return [self.done.get(self._key(*x)) for x in zip(a, m, s)]

    def write(self, a, m, s, res):
        """Keep the items (a, m, s) and their results ``res`` (columns of :data:`_STORED`)."""
        import pyarrow as pa

        cols = {"arch": np.asarray(a, np.int64), "motion": np.asarray(m, np.int64),
                "scale": np.asarray(s, float), **{c: np.asarray(res[c]) for c in _STORED}}
        _write_table(pa.table(cols), self.folder / "items" / f"chunk-{self.next:05d}.parquet")
        self.next += 1
        for i, key in enumerate(zip(a, m, s)):
            self.done[self._key(*key)] = tuple(cols[c][i].item() for c in _STORED)


def _chunk_implausible(tab: dict) -> str | None:
    """Why a chunk without a recorded checksum cannot be trusted (None: its values are those
    this code writes: statuses -1..3, finite scales, times and peaks NaN or 0..1000, counts
    0..10^7)."""
    for c in ("arch", "motion", "status", "n_events"):
        if not all(isinstance(x, int) and not isinstance(x, bool) for x in tab[c]):
            return f"column {c!r} does not hold integers"
    if any(x < 0 for x in tab["arch"] + tab["motion"]):
        return "a negative arch or motion index"
    if any(not -1 <= x <= 3 for x in tab["status"]):
        return "column 'status' holds a code outside -1..3"
    if any(not 0 <= x <= _COUNT_BOUND for x in tab["n_events"]):
        return f"column 'n_events' holds a count outside 0..{_COUNT_BOUND}"
    if not np.isfinite(np.asarray(tab["scale"], dtype=float)).all():
        return "column 'scale' holds a value that is not finite"
    for c in ("peak", "t_collapse", "t_unstable", "t_limit"):
        v = np.asarray(tab[c], dtype=float)
        bad = v[~np.isnan(v) & ~((v >= 0.0) & (v <= _FLOAT_BOUND))]
        if bad.size:
            return f"column {c!r} holds {bad[0]:.6g} (allowed NaN or 0..{_FLOAT_BOUND:g})"
    return None
