"""Monte Carlo over random arches drawn around one nominal arch.

Each sample is an irregular arch (METHOD section 1: span_i = (alpha/n)(1 + s_a U),
t_i = t (1 + s_t U), R_i = R + s_R t U, spans rescaled to the embrace) whose collapse multipliers
k_l, k_r and mechanisms are found by limit analysis and, under a ground motion, whose response is
integrated to rest or collapse (:mod:`archrock.batch`).

Reproducibility: the samples are cut into batches of ``batch_size``; batch b draws its arches
from its own random stream ``SeedSequence(seed, spawn_key=(b,))`` (= ``SeedSequence(seed)
.spawn(n_batches)[b]``), so every sample depends only on (seed, batch_size, its index), never
on the number of workers or on the order in which batches finish.

Execution: in-process by default (numba ``prange`` over the arches of a batch), ``workers > 1``
for a local process pool over batches, ``scheduler=ADDRESS`` for an existing Dask cluster.
With ``out_dir`` every finished batch is written atomically as ``batches/batch-00000.parquet``
next to ``manifest.json`` (configuration, seeds, versions, runs); running again with the same
``out_dir`` and configuration computes only the missing batches.  Each batch file carries in its
Parquet metadata the configuration's sha256, its batch number and the sha256 of the package's
sources; a file whose metadata, ``batch`` or ``index`` columns do not match (or that cannot be
read) is recomputed and the progress output says why.  Batch files without ``manifest.json``
are refused; ``*.tmp-PID`` files of killed writes are removed at start.

Definitions used by :meth:`EnsembleResult.summary`:

* k statistics and the "as far as RA-x" shares over the samples whose limit analysis found a
  standing arch (finite k_l, k_r > 0): samples that failed there (invalid geometry, no
  mechanism, "cannot stand") are left out; samples that failed later (four-link model, impact
  law) keep their valid k.  std is the sample standard deviation (ddof = 1; None for one sample).
* response statistics over the samples whose response was integrated; ``peak_rad`` only over
  those that did not collapse (a collapsed sample's ``peak`` column is its rotation limit).
* p_collapse over the samples whose response was integrated (status rest, collapsed or moving),
  with the Wilson score interval (:func:`archrock.fragility.collapse_probability`).
* "as far from nominal as RA-x" (RA-1: k_l = 0.4111, k_r = 0.3104; RA-2: k_l = 0.3946,
  k_r = 0.3501, the paper's random arches): with k0_l, k0_r the nominal arch's multipliers,
  ``k_l``: |k_l - k0_l| >= |k_l(RA) - k0_l|; ``k_r``: the same for k_r; ``either`` / ``both``:
  one of / both conditions; ``asymmetry``: |k_l - k_r| >= |k_l(RA) - k_r(RA)|.
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import hashlib
import json
import math
import os
import platform
import re
import sys
import time
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import numpy as np

from . import published
from .batch import MAX_EVENTS, ST_NOT_RUN, STATUS_NAMES, perturb, prepare_batch, simulate_batch
from .errors import ArchInputError
from .geometry import Arch

__all__ = ["EnsembleConfig", "EnsembleResult", "EnsembleConfigMismatch", "run_ensemble", "run_batch",
           "pulse_description", "record_description", "motion_from_description", "resolve_impact",
           "sample_arch", "PAPER_RANDOM_ARCHES", "IMPACT_CHOICES"]

#: The paper's random arches (plausibility figures, METHOD section 2).
PAPER_RANDOM_ARCHES = published.RANDOM_ARCHES
IMPACT_CHOICES = ("nominal-paper", "paper", "momentum", "fixed")
MANIFEST = "manifest.json"
#: seconds to wait for a Dask scheduler given by address before giving up with an ArchInputError.
SCHEDULER_TIMEOUT_S = 10.0
FORMAT = "archrock-ensemble/1"
COLUMNS = ["batch", "index", "k_l", "k_r", "mech_l", "mech_r", "c_l_to_r", "c_r_to_l", "collapsed",
           "status", "peak", "t_collapse", "t_unstable", "n_impacts", "n_activations", "events_truncated",
           "error"]


class EnsembleConfigMismatch(ArchInputError):
    """An output folder holds an ensemble with a different configuration."""


# ---------------------------------------------------------------------------- ground motion
def pulse_description(kind: str, amplitude_g: float, duration: float) -> dict:
    """JSON description of a pulse ground motion (checked by building it once)."""
    from .groundmotion import pulse

    pulse(kind, amplitude_g, duration)
    return {"type": "pulse", "kind": str(kind), "amplitude_g": float(amplitude_g),
            "duration": float(duration)}


def _sha256(path) -> str:
    h = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            for chunk in iter(lambda: fh.read(1 << 20), b""):
                h.update(chunk)
    except OSError as exc:
        raise ArchInputError(f"record: cannot read {str(path)!r} ({exc.strerror or exc})") from None
    return h.hexdigest()


def record_description(path, units: str | None = None, scale: float = 1.0) -> dict:
    """JSON description of a recorded ground motion: absolute path, units, scale factor and the
    file's sha256 (checked whenever the motion is rebuilt)."""
    from .groundmotion import load_record

    load_record(path, units).scaled(scale)
    p = Path(path).resolve()
    return {"type": "record", "path": str(p), "units": units, "scale": float(scale),
            "sha256": _sha256(p)}


@lru_cache(maxsize=8)
def _motion_cached(text: str):
    from .groundmotion import load_record, pulse

    d = json.loads(text)
    if d["type"] == "pulse":
        return pulse(d["kind"], d["amplitude_g"], d["duration"])
    digest = _sha256(d["path"])
    if digest != d["sha256"]:
        raise ArchInputError(f"record {d['path']!r}: its sha256 {digest[:12]}... differs from the "
                             f"configuration's {d['sha256'][:12]}...; the file has changed")
    motion = load_record(d["path"], d.get("units"))
    scale = d.get("scale", 1.0)
    return motion.scaled(scale) if scale != 1.0 else motion


def motion_from_description(desc: dict | None):
    """The GroundMotion of a description (None -> None); a record's sha256 is checked."""
    if desc is None:
        return None
    if not isinstance(desc, dict) or desc.get("type") not in ("pulse", "record"):
        raise ArchInputError(f"motion: {desc!r}; allowed None or a pulse/record description")
    return _motion_cached(json.dumps(desc, sort_keys=True))


# ---------------------------------------------------------------------------- configuration
def _int_field(name, value, lo):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < lo:
        raise ArchInputError(f"{name}: {value!r}; allowed an integer >= {lo}")
    return int(value)


@dataclass(frozen=True)
class EnsembleConfig:
    """Everything that determines an ensemble's results (JSON-serialisable).

    nominal: the nominal geometry as ``Arch.to_dict()``; samples >= 1; seed >= 0;
    spread_span, spread_thickness, spread_radius: the widths s_a, s_t, s_R (0 <= s < 1);
    batch_size >= 1 (samples per batch and random stream); motion: None (limit analysis only) or a
    description from :func:`pulse_description` / :func:`record_description`; impact:
    'nominal-paper' (default, the paper's choice: c_v computed once on the nominal arch with the
    'paper' model, then applied as a fixed c_v to every sample), 'paper' or 'momentum' (per
    geometry), 'fixed' (with ``cv``); dt [s]: RK4 step; t_free [s]: free motion allowed after the
    ground motion; tabulate: the RK4 kernel reads the equation's coefficients from spline
    tables (as ``respond``'s default; ~1e-9 relative, about 3x faster) instead of the exact loop
    closure.
    """

    nominal: dict
    samples: int = 1000
    seed: int = 0
    spread_span: float = 0.1
    spread_thickness: float = 0.1
    spread_radius: float = 0.05
    batch_size: int = 500
    motion: dict | None = None
    impact: str = "nominal-paper"
    cv: float | None = None
    dt: float = 2e-3
    t_free: float = 60.0
    tabulate: bool = True

    def __post_init__(self):
        if isinstance(self.nominal, Arch):
            object.__setattr__(self, "nominal", self.nominal.to_dict())
        Arch.from_dict(self.nominal)  # validates
        object.__setattr__(self, "samples", _int_field("samples", self.samples, 1))
        object.__setattr__(self, "seed", _int_field("seed", self.seed, 0))
        object.__setattr__(self, "batch_size", _int_field("batch size", self.batch_size, 1))
        for name in ("spread_span", "spread_thickness", "spread_radius"):
            v = getattr(self, name)
            try:
                v = float(v)
            except (TypeError, ValueError):
                raise ArchInputError(f"{name.replace('_', ' ')}: {v!r}; allowed 0 <= s < 1") from None
            if not (math.isfinite(v) and 0.0 <= v < 1.0):
                raise ArchInputError(f"{name.replace('_', ' ')}: {v:g}; allowed 0 <= s < 1")
            object.__setattr__(self, name, v)
        if self.impact not in IMPACT_CHOICES:
            raise ArchInputError(f"impact: {self.impact!r}; allowed {', '.join(IMPACT_CHOICES)}")
        if self.impact == "fixed":
            cv = self.cv
            if isinstance(cv, bool) or not isinstance(cv, (int, float)) or not (
                    math.isfinite(cv) and 0.0 < cv <= 1.0):
                raise ArchInputError(f"cv: {cv!r}; allowed 0 < cv <= 1")
            object.__setattr__(self, "cv", float(cv))
        elif self.cv is not None:
            raise ArchInputError(f"cv: {self.cv!r}; only with impact 'fixed'")
        for name in ("dt", "t_free"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
                raise ArchInputError(f"{name}: {v!r}; allowed a finite number > 0 s")
            object.__setattr__(self, name, float(v))
        if not isinstance(self.tabulate, bool):
            raise ArchInputError(f"tabulate: {self.tabulate!r}; allowed true or false")
        if self.motion is not None:
            motion_from_description(self.motion)

    @classmethod
    def from_arch(cls, nominal: Arch, **kwargs) -> "EnsembleConfig":
        return cls(nominal.to_dict(), **kwargs)

    @property
    def n_batches(self) -> int:
        return -(-self.samples // self.batch_size)

    def batch_range(self, b: int) -> tuple[int, int]:
        """(first sample index, number of samples) of batch b."""
        start = b * self.batch_size
        return start, min(self.batch_size, self.samples - start)

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), sort_keys=True)

    @classmethod
    def from_dict(cls, data: dict) -> "EnsembleConfig":
        names = {f.name for f in dataclasses.fields(cls)}
        unknown = set(data) - names
        if unknown:
            raise ArchInputError(f"ensemble configuration: unknown field(s) {sorted(unknown)}")
        return cls(**data)


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


# ---------------------------------------------------------------------------- impact
@lru_cache(maxsize=16)
def _nominal_paper_cv(nominal_json: str) -> float:
    import warnings

    from .impact import nominal_cv

    arch = Arch.from_dict(json.loads(nominal_json), name="nominal")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return nominal_cv(arch)  # raises EnergyGainError if it creates energy


def resolve_impact(config: EnsembleConfig) -> dict:
    """{'model': 'fixed' | 'paper' | 'momentum', 'cv': float or None, 'source': ...}."""
    if config.impact == "nominal-paper":
        cv = _nominal_paper_cv(json.dumps(config.nominal, sort_keys=True))
        return {"model": "fixed", "cv": cv,
                "source": "c_v of the nominal arch with the 'paper' model, applied as a fixed c_v "
                          "(kinetic energy after impact = c_v^2 x before)"}
    if config.impact == "fixed":
        return {"model": "fixed", "cv": config.cv, "source": "user-given c_v (energy-consistent)"}
    return {"model": config.impact, "cv": None, "source": "per-geometry impact law"}


# ---------------------------------------------------------------------------- one batch
def _draws(config: EnsembleConfig, b: int, nominal: Arch):
    start, nb = config.batch_range(b)
    rng = np.random.default_rng(np.random.SeedSequence(config.seed, spawn_key=(b,)))
    u = rng.uniform(-1.0, 1.0, size=(nb, 3, nominal.n))
    spans, thick, radii = perturb(nominal.spans, nominal.thicknesses, nominal.radii, u,
                                  config.spread_span, config.spread_thickness, config.spread_radius)
    return start, nb, spans, thick, radii


def sample_arch(config: EnsembleConfig, index: int) -> Arch:
    """The random arch of sample ``index`` (0-based) of the ensemble, rebuilt from the seed."""
    if not 0 <= index < config.samples:
        raise ArchInputError(f"index: {index}; allowed 0..{config.samples - 1}")
    nominal = Arch.from_dict(config.nominal)
    b = index // config.batch_size
    start, _, spans, thick, radii = _draws(config, b, nominal)
    i = index - start
    return Arch(spans[i], radii[i], thick[i], nominal.density, name=f"sample {index}")


def run_batch(config: EnsembleConfig | dict, b: int, parallel: bool = True):
    """Compute batch ``b`` of an ensemble (self-contained: only the config and b are needed).

    Returns (DataFrame with the columns of :data:`COLUMNS`, timings dict).  ``parallel`` uses
    the numba parallel loop; process-pool and Dask workers run it serially.
    """
    import pandas as pd

    t0 = time.perf_counter()
    cfg = config if isinstance(config, EnsembleConfig) else EnsembleConfig.from_dict(config)
    if not 0 <= b < cfg.n_batches:
        raise ArchInputError(f"batch: {b}; allowed 0..{cfg.n_batches - 1}")
    nominal = Arch.from_dict(cfg.nominal)
    start, nb, spans, thick, radii = _draws(cfg, b, nominal)
    imp = resolve_impact(cfg)
    pb = prepare_batch(spans, radii, thick, nominal.density,
                       impact=imp["model"], cv=imp["cv"])
    motion = motion_from_description(cfg.motion)
    error = pb.error.copy()
    if motion is not None:
        res = simulate_batch(pb, motion, dt=cfg.dt, t_free=cfg.t_free, parallel=parallel,
                             tabulate=cfg.tabulate, max_events=MAX_EVENTS)
        st = res["status"]
        status = np.array([STATUS_NAMES.get(int(s), "failed") for s in st], dtype=object)
        status[st == ST_NOT_RUN] = "failed"
        sim_seconds = res["seconds"]
    else:
        res = {"peak": np.full(nb, np.nan), "t_collapse": np.full(nb, np.nan),
               "t_unstable": np.full(nb, np.nan), "n_impacts": np.zeros(nb, dtype=np.int64),
               "n_activations": np.zeros(nb, dtype=np.int64),
               "events_truncated": np.zeros(nb, dtype=bool)}
        status = np.where(error == "", "limit-only", "failed").astype(object)
        sim_seconds = 0.0
    df = pd.DataFrame({
        "batch": np.full(nb, b, dtype=np.int64),
        "index": np.arange(start, start + nb, dtype=np.int64),
        "k_l": pb.k_l, "k_r": pb.k_r,
        "mech_l": pb.mech_l.astype(str), "mech_r": pb.mech_r.astype(str),
        "c_l_to_r": pb.c_l_to_r, "c_r_to_l": pb.c_r_to_l,
        "collapsed": status == "collapsed",
        "status": status.astype(str),
        "peak": res["peak"], "t_collapse": res["t_collapse"], "t_unstable": res["t_unstable"],
        "n_impacts": res["n_impacts"].astype(np.int64),
        "n_activations": res["n_activations"].astype(np.int64),
        "events_truncated": res["events_truncated"].astype(bool),
        "error": error.astype(str),
    }, columns=COLUMNS)
    timings = {"prepare_s": float(sum(pb.seconds.values())), "response_s": float(sim_seconds),
               "total_s": time.perf_counter() - t0, "pid": os.getpid()}
    return df, timings


# ---------------------------------------------------------------------------- output folder
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


def _batch_path(out: Path, b: int) -> Path:
    return out / "batches" / f"batch-{b:05d}.parquet"


PROVENANCE_KEY = b"archrock.ensemble"


@lru_cache(maxsize=1)
def _code_digest() -> str:
    """sha256 of the package's sources: batches written by other code are recomputed."""
    from ._jit import _package_digest

    return _package_digest()


def _config_hash(config: EnsembleConfig) -> str:
    return hashlib.sha256(config.to_json().encode()).hexdigest()


def _provenance(config: EnsembleConfig, b: int) -> dict:
    return {"format": FORMAT, "config_sha256": _config_hash(config), "batch": int(b),
            "code_sha256": _code_digest()}


def _write_batch(out: Path, b: int, df, config: EnsembleConfig) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    path = _batch_path(out, b)
    tmp = path.with_name(f"{path.name}.tmp-{os.getpid()}")
    table = pa.Table.from_pandas(df, preserve_index=False)
    meta = dict(table.schema.metadata or {})
    meta[PROVENANCE_KEY] = json.dumps(_provenance(config, b), sort_keys=True).encode()
    pq.write_table(table.replace_schema_metadata(meta), tmp)
    os.replace(tmp, path)


def _read_batch(out: Path, b: int, config: EnsembleConfig):
    """(DataFrame, None) for a verified batch file; (None, None) when there is none; (None,
    reason) when the file exists but cannot be used (it is then recomputed)."""
    import pyarrow.parquet as pq

    path = _batch_path(out, b)
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
    if meta.get("code_sha256") != want["code_sha256"]:
        return None, "written by other archrock code"
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


def _remove_stale_tmp(out: Path) -> list[str]:
    """Remove the ``*.tmp-PID`` files of killed writes (not those of a live process)."""
    removed = []
    for folder in (out, out / "batches"):
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


class _Manifest:
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
            old = data.get("config", {})
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
                          "streams": "batch b draws from numpy SeedSequence(entropy, spawn_key=(b,)) "
                                     "= SeedSequence(entropy).spawn(n_batches)[b]"},
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
                "file": str(_batch_path(self.out, b).relative_to(self.out)), "samples": nb,
                "spawn_key": [b], "run": len(self.data["runs"]) - 1,
                **{k: v for k, v in timings.items() if k != "pid"}}

    def finish(self, complete: bool):
        self.run["finished"] = _now()
        self.run["computed"].sort()
        self.run["loaded"].sort()
        if complete:
            self.data["finished"] = _now()
        self.save()


# ---------------------------------------------------------------------------- progress
class _Progress:
    def __init__(self, total: int, enabled: bool):
        self.bar = None
        self.enabled = enabled
        self.total = total
        self.done = 0
        self.last = 0.0
        if not enabled:
            return
        try:
            from tqdm import tqdm

            self.bar = tqdm(total=total, unit="arch", desc="ensemble", file=sys.stderr,
                            dynamic_ncols=True)
        except ImportError:
            self.bar = None

    def update(self, n: int):
        self.done += n
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.update(n)
        elif time.monotonic() - self.last > 1.0 or self.done == self.total:
            self.last = time.monotonic()
            print(f"ensemble: {self.done}/{self.total} samples", file=sys.stderr, flush=True)

    def note(self, text: str):
        """A line of progress output (above the bar)."""
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.write(text, file=sys.stderr)
        else:
            print(text, file=sys.stderr, flush=True)

    def close(self):
        if self.bar is not None:
            self.bar.close()


# ---------------------------------------------------------------------------- result
def _stats(x: np.ndarray) -> dict:
    x = np.asarray(x, float)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return {"mean": None, "std": None, "min": None, "q05": None, "median": None, "q95": None,
                "max": None, "count": 0}
    q = np.quantile(x, [0.05, 0.5, 0.95])
    return {"mean": float(x.mean()), "std": float(x.std(ddof=1)) if x.size > 1 else None,
            "min": float(x.min()), "q05": float(q[0]), "median": float(q[1]), "q95": float(q[2]),
            "max": float(x.max()), "count": int(x.size)}


def _reason(text: str) -> str:
    return re.sub(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?", "#", text.split(" (")[0])


@dataclass
class EnsembleResult:
    """Result of :func:`run_ensemble`: the per-sample table and how it was obtained.

    frame: one row per sample (columns :data:`COLUMNS`), sorted by index; nominal: k_l, k_r and
    mechanisms of the nominal arch; impact: the resolved impact law; timing: wall time and
    batches computed / loaded from ``out_dir``.
    """

    config: EnsembleConfig
    frame: object
    nominal: dict
    impact: dict
    timing: dict = field(default_factory=dict)
    out_dir: str | None = None

    def summary(self, confidence: float = 0.95) -> dict:
        """JSON-ready summary (definitions in the module docstring)."""
        from .fragility import collapse_probability

        df = self.frame
        kl_all, kr_all = df["k_l"].to_numpy(), df["k_r"].to_numpy()
        # a standing arch by limit analysis (k <= 0: "cannot stand", a failed sample)
        with np.errstate(invalid="ignore"):
            k_ok = np.isfinite(kl_all) & np.isfinite(kr_all) & (kl_all > 0) & (kr_all > 0)
        kl, kr = df["k_l"].to_numpy()[k_ok], df["k_r"].to_numpy()[k_ok]
        failed = df[df["error"] != ""]
        reasons: dict[str, int] = {}
        for e in failed["error"]:
            reasons[_reason(e)] = reasons.get(_reason(e), 0) + 1
        hinges = {}
        for col, name in (("mech_l", "M_l"), ("mech_r", "M_r")):
            vc = df.loc[df[col] != "", col].value_counts()
            hinges[name] = {str(k): int(v) for k, v in vc.items()}
        k0l, k0r = self.nominal["k_l"], self.nominal["k_r"]
        far = {}
        for name, (ral, rar) in PAPER_RANDOM_ARCHES.items():
            dl = np.abs(kl - k0l) >= abs(ral - k0l)
            dr = np.abs(kr - k0r) >= abs(rar - k0r)
            asym = np.abs(kl - kr) >= abs(ral - rar)
            share = (lambda m: float(m.mean()) if m.size else None)
            far[name] = {"k_l_ref": ral, "k_r_ref": rar, "k_l": share(dl), "k_r": share(dr),
                         "either": share(dl | dr), "both": share(dl & dr), "asymmetry": share(asym)}
        out = {
            "samples": int(len(df)),
            "seed": self.config.seed,
            "spreads": {"span": self.config.spread_span, "thickness": self.config.spread_thickness,
                        "radius": self.config.spread_radius},
            "nominal": self.nominal,
            "k_l": _stats(kl), "k_r": _stats(kr),
            "k_min": _stats(np.minimum(kl, kr)),
            "hinge_patterns": hinges,
            "as_far_as": far,
            "failed": {"count": int(len(failed)), "reasons": reasons},
            "impact": self.impact,
            "motion": self.config.motion,
            "p_collapse": None,
            "response": None,
            "timing": self.timing,
        }
        if self.config.motion is not None:
            ran = df[df["status"].isin(["rest", "collapsed", "moving"])]
            n, k = int(len(ran)), int(ran["collapsed"].sum())
            if n:
                p, lo, hi = collapse_probability(k, n, confidence, "wilson")
                out["p_collapse"] = {"p": p, "low": lo, "high": hi, "confidence": confidence,
                                     "method": "wilson", "collapses": k, "trials": n}
            col = ran[ran["collapsed"]]
            out["response"] = {
                "status": {str(k_): int(v) for k_, v in ran["status"].value_counts().items()},
                "activated": float((ran["n_activations"] > 0).mean()) if n else None,
                "peak_rad": _stats(ran.loc[~ran["collapsed"], "peak"].to_numpy()),
                "n_impacts": _stats(ran["n_impacts"].to_numpy()),
                "events_truncated": int(ran["events_truncated"].sum()),
                "t_collapse_s": _stats(col["t_collapse"].to_numpy()),
                "t_unstable_s": _stats(ran["t_unstable"].to_numpy()),
                "unstable_but_survived": int((np.isfinite(ran["t_unstable"].to_numpy())
                                              & ~ran["collapsed"].to_numpy()).sum()),
            }
        return out


# ---------------------------------------------------------------------------- driver
def _nominal_info(config: EnsembleConfig) -> dict:
    from .batch import mechanism_label
    from .limit import kinematic_multipliers_batch

    arch = Arch.from_dict(config.nominal)
    k_l, k_r, i_l, i_r = kinematic_multipliers_batch(arch.spans[None], arch.radii[None],
                                                     arch.thicknesses[None])
    return {"k_l": float(k_l[0]), "k_r": float(k_r[0]), "mech_l": mechanism_label(arch.n, int(i_l[0])),
            "mech_r": mechanism_label(arch.n, int(i_r[0]))}


def _run_batch_task(config_dict: dict, b: int):
    """Process-pool / Dask entry point (serial numba loop: one worker = one core)."""
    return b, *run_batch(config_dict, b, parallel=False)


def run_ensemble(config: EnsembleConfig, out_dir=None, workers: int = 1, scheduler=None,
                 progress: bool = True) -> EnsembleResult:
    """Run (or resume) an ensemble.

    out_dir: folder for the batches and manifest (None: nothing written); workers: 1 runs
    in-process (numba parallel loop), > 1 a local process pool over batches; scheduler: address
    of a Dask scheduler (or a ``distributed.Client``), which takes precedence over ``workers``;
    progress: a progress bar on stderr.
    """
    import pandas as pd

    if not isinstance(config, EnsembleConfig):
        raise ArchInputError(f"config: expected an EnsembleConfig, got {type(config).__name__}")
    workers = _int_field("workers", workers, 1)
    t_start = time.perf_counter()
    impact = resolve_impact(config)
    nominal = _nominal_info(config)
    out = Path(out_dir) if out_dir is not None else None
    manifest = _Manifest(out, config, impact, nominal) if out is not None else None
    frames: dict[int, object] = {}
    batch_timings: dict[int, dict] = {}
    todo = []
    recomputed: dict[int, str] = {}
    bar = _Progress(config.samples, progress)
    try:
        for b in range(config.n_batches):
            nb = config.batch_range(b)[1]
            df, why = _read_batch(out, b, config) if out is not None else (None, None)
            if df is not None:
                frames[b] = df
                manifest.batch_done(b, nb, {}, computed=False)
                bar.update(nb)
            else:
                todo.append(b)
                if why is not None:
                    recomputed[b] = why
                    manifest.run["recomputed"][str(b)] = why
                    bar.note(f"ensemble: recomputing batch {b}: "
                             f"{_batch_path(out, b).name} {why}")
        if manifest is not None:
            manifest.save()

        def finished(b, df, timings):
            frames[b] = df
            batch_timings[b] = timings
            if out is not None:
                _write_batch(out, b, df, config)
                manifest.batch_done(b, len(df), timings, computed=True)
                manifest.save()
            bar.update(len(df))

        cfg_dict = config.to_dict()
        executor = "in-process"
        if todo and scheduler is not None:
            executor = "dask"
            _run_dask(scheduler, cfg_dict, todo, finished)
        elif todo and workers > 1:
            executor = f"process pool ({workers})"
            import multiprocessing as mp
            from concurrent.futures import ProcessPoolExecutor, as_completed

            with ProcessPoolExecutor(max_workers=workers, mp_context=mp.get_context("spawn")) as pool:
                futs = [pool.submit(_run_batch_task, cfg_dict, b) for b in todo]
                for fut in as_completed(futs):
                    finished(*fut.result())
        else:
            for b in todo:
                df, timings = run_batch(config, b, parallel=True)
                finished(b, df, timings)
    finally:
        bar.close()
        if manifest is not None:
            manifest.finish(complete=len(frames) == config.n_batches)
    frame = pd.concat([frames[b] for b in sorted(frames)], ignore_index=True)
    wall = time.perf_counter() - t_start
    computed = sorted(batch_timings)
    n_computed = int(sum(config.batch_range(b)[1] for b in computed))
    timing = {"wall_s": wall, "executor": executor, "workers": workers,
              "computed_batches": computed, "loaded_batches": sorted(set(frames) - set(computed)),
              "recomputed_batches": {str(b): why for b, why in sorted(recomputed.items())},
              "computed_samples": n_computed,
              "samples_per_s": n_computed / wall if n_computed and wall > 0 else None,
              "prepare_s": float(sum(t["prepare_s"] for t in batch_timings.values())),
              "response_s": float(sum(t["response_s"] for t in batch_timings.values()))}
    return EnsembleResult(config, frame, nominal, impact, timing,
                          str(out) if out is not None else None)


def _run_dask(scheduler, cfg_dict, todo, finished):
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise ImportError("running on a Dask cluster needs the 'dask' extra: "
                          "pip install 'archrock[dask]'") from None
    own = not isinstance(scheduler, Client)
    if own:
        try:
            client = Client(scheduler, timeout=SCHEDULER_TIMEOUT_S)
        except (OSError, ValueError, TypeError) as exc:
            reason = " ".join(str(exc).split()) or type(exc).__name__
            raise ArchInputError(f"scheduler: cannot connect to {scheduler!r} ({reason})") from None
    else:
        client = scheduler
    try:
        futs = [client.submit(_run_batch_task, cfg_dict, b, pure=False) for b in todo]
        for fut in as_completed(futs):
            finished(*fut.result())
    finally:
        if own:
            client.close()
