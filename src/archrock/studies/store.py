"""The one store of the studies: a folder of Parquet files written atomically, a manifest, and
resumption.  Two layouts share its writing, provenance and clean-up:

* an ensemble's output folder (:class:`Manifest`, :func:`write_batch`, :func:`read_batch`),
  the format of 0.4.0 and later (tests/data/ensemble-0.4.0 resumes);
* a sweep's kept items (:class:`ResultStore`): IDA, multiple stripes and the curves.

Ensemble layout: ``manifest.json`` (configuration, seeds, versions, runs) next to
``batches/batch-00000.parquet``, each written atomically (``*.tmp-PID`` then rename).  Each batch
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

from typing import TYPE_CHECKING

from ..errors import ArchInputError

if TYPE_CHECKING:  # imported lazily: the ensemble package imports this module
    from .ensemble.config import EnsembleConfig

__all__ = ["EnsembleConfigMismatch", "Manifest", "batch_path", "read_batch", "write_batch",
           "written_by", "same_bits", "code_digest", "MANIFEST", "FORMAT", "PROVENANCE_KEY",
           "OTHER_CODE", "ResultStore", "SWEEP_FORMAT"]

#: Why a batch is not loaded as it is: the sources that wrote it differ from these.
OTHER_CODE = "written by other archrock code"

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
    tmp = path.with_name(f"{path.name}.tmp-{os.getpid()}")
    tmp.write_text(json.dumps(obj, indent=2, allow_nan=False), encoding="utf-8")
    os.replace(tmp, path)


def batch_path(out: Path, b: int) -> Path:
    """The file of batch ``b`` in the output folder ``out``."""
    return out / "batches" / f"batch-{b:05d}.parquet"


@lru_cache(maxsize=1)
def _code_digest() -> str:
    """sha256 of the package's sources: batches written by other code are recomputed."""
    from .._jit import _package_digest

    return _package_digest()


def _config_hash(config: EnsembleConfig) -> str:
    return config.config_hash()  # from archrock 0.4's form of the configuration


def _provenance(config: EnsembleConfig, b: int) -> dict:
    return {"format": FORMAT, "config_sha256": _config_hash(config), "batch": int(b),
            "code_sha256": _code_digest()}


def write_batch(out: Path, b: int, df, config: EnsembleConfig) -> None:
    """Write batch ``b``'s table atomically, with its provenance in the Parquet metadata."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    # pyarrow's own SIGINT handling can swallow a Ctrl-C that arrives while it writes (the run
    # then goes on to the end); Python's handler must see it so the ensemble stops and says
    # which batches it kept
    pa.enable_signal_handlers(False)
    path = batch_path(out, b)
    tmp = path.with_name(f"{path.name}.tmp-{os.getpid()}")
    table = pa.Table.from_pandas(df, preserve_index=False)
    meta = dict(table.schema.metadata or {})
    meta[PROVENANCE_KEY] = json.dumps(_provenance(config, b), sort_keys=True).encode()
    pq.write_table(table.replace_schema_metadata(meta), tmp)
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


def read_batch(out: Path, b: int, config: EnsembleConfig, any_code: bool = False):
    """(DataFrame, None) for a verified batch file; (None, None) when there is none; (None,
    reason) when the file exists but cannot be used (it is then recomputed).  ``any_code``: a
    file written by other archrock sources is returned too (the caller verifies it, see
    :func:`written_by`); otherwise it is (None, :data:`OTHER_CODE`)."""
    import pyarrow.parquet as pq

    from .ensemble.compute import COLUMNS

    path = batch_path(out, b)
    if not path.is_file():
        return None, None
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

    def __init__(self, out: Path, config: EnsembleConfig, impact: dict, nominal: dict):
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
            try:
                data = json.loads(self.path.read_text(encoding="utf-8"))
            except (OSError, ValueError) as exc:
                raise ArchInputError(f"out: {str(self.path)!r} is not a readable manifest ({exc})") from None
            from .ensemble.config import EnsembleConfig

            old = EnsembleConfig.upgrade_dict(data.get("config", {}))  # 0.4-0.6's keys too
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
    scale and the results of each item), each written atomically as the ensemble's batches
    are.  A folder holding another study's items (another digest) is refused; an unreadable
    chunk is recomputed.  Needs pyarrow (the 'ensemble' extra)."""

    def __init__(self, folder, arches, motions, *, about: dict | None = None,
                 settings: dict | None = None):
        try:
            import pyarrow.parquet as pq  # noqa: F401
        except ImportError:
            raise ImportError("--out needs pyarrow: pip install 'archrock[ensemble]'") from None
        self.folder = Path(folder)
        self.digest = _digest(arches, motions, settings or {})
        man = self.folder / MANIFEST
        if man.exists():
            try:
                old = json.loads(man.read_text(encoding="utf-8"))
            except (OSError, ValueError) as exc:
                raise ArchInputError(f"out: {str(man)!r} cannot be read ({exc}); allowed a "
                                     f"folder written by this study, or a new one") from None
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
        self.next = 0  # number of the next chunk file: after every existing one, never reused
        for f in sorted((self.folder / "items").glob("chunk-*.parquet")):
            try:
                self._load(f)
            except Exception:  # noqa: BLE001 - an unreadable chunk is recomputed, not fatal
                continue
            finally:
                num = f.stem.split("-")[-1]
                if num.isdigit():
                    self.next = max(self.next, int(num) + 1)
        self.loaded = len(self.done)

    @staticmethod
    def _key(a, m, s):
        return (int(a), int(m), float(s))

    def _load(self, path):
        import pyarrow.parquet as pq

        tab = pq.read_table(path).to_pydict()
        for i, (a, m, s) in enumerate(zip(tab["arch"], tab["motion"], tab["scale"])):
            self.done[self._key(a, m, s)] = tuple(tab[c][i] for c in _STORED)

    def lookup(self, a, m, s):
        """The stored row of each item (None: not stored)."""
        return [self.done.get(self._key(*x)) for x in zip(a, m, s)]

    def write(self, a, m, s, res):
        """Keep the items (a, m, s) and their results ``res`` (columns of :data:`_STORED`)."""
        import pyarrow as pa
        import pyarrow.parquet as pq

        pa.enable_signal_handlers(False)  # as write_batch: a Ctrl-C must reach Python
        cols = {"arch": np.asarray(a, np.int64), "motion": np.asarray(m, np.int64),
                "scale": np.asarray(s, float), **{c: np.asarray(res[c]) for c in _STORED}}
        path = self.folder / "items" / f"chunk-{self.next:05d}.parquet"
        tmp = path.with_name(f"{path.name}.tmp-{os.getpid()}")
        pq.write_table(pa.table(cols), tmp)
        os.replace(tmp, path)
        self.next += 1
        for i, key in enumerate(zip(a, m, s)):
            self.done[self._key(*key)] = tuple(cols[c][i].item() for c in _STORED)
