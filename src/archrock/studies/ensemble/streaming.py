"""An ensemble's summary computed from its stored batches, one batch in memory at a time.

:meth:`EnsembleResult.summary` works on the whole per-sample frame; for 10^7 arches that frame
does not fit.  :func:`summarize_batches` gives the same summary (the same keys, definitions in
:mod:`archrock.studies.ensemble.summary`) from an iterable of batch frames that it reads three times:

1. counts (outcomes, reasons, hinge patterns, "as far as RA-x", P(collapse), statuses) and, per
   statistic, the count, the exact sum (``math.fsum``: the mean is correctly rounded), min, max;
2. the sum of squared deviations from that mean (the sample standard deviation, ddof = 1, as
   numpy's two-pass formula) and a histogram of 4096 equal bins between min and max;
3. the values (with their multiplicities) of the few bins that hold the order statistics the
   5%, 50% and 95% quantiles need, from which the quantiles follow exactly as
   ``numpy.quantile(..., method="linear")`` computes them.

So every figure is exact, not approximate: counts exactly, quantiles exactly, mean and standard
deviation up to the order of summation (relative ~1e-15).  Memory: the counters, 4096 bins per
statistic and the values of at most six bins per statistic (as value -> multiplicity maps, so an
atom such as an integer number of impacts does not grow them).

:func:`summarize_store` reads the batch files of an output folder (pyarrow, only the columns the
summary needs) in batch order.
"""

from __future__ import annotations

import math
from collections import Counter
from pathlib import Path

import numpy as np

from ...leftout import REASONS, LeftOut
from .statistics import INTEGRATED, PAPER_RANDOM_ARCHES, probabilities, summary_dict

__all__ = ["summarize_batches", "summarize_store", "SUMMARY_COLUMNS", "QUANTILE_BINS"]

#: The columns the summary reads.
SUMMARY_COLUMNS = ["k_l", "k_r", "mech_l", "mech_r", "collapsed", "status", "peak", "t_collapse",
                   "t_limit", "t_unstable", "n_impacts", "n_activations", "events_truncated",
                   "early_stopped", "error"]
#: Histogram bins per statistic in the second pass.
QUANTILE_BINS = 4096
_Q = (0.05, 0.5, 0.95)
_SERIES = ("k_l", "k_r", "k_min", "peak", "n_impacts", "t_collapse", "t_limit", "t_unstable")


def _series(df, motion: bool) -> dict:
    """The values of each statistic in one batch (finite values only, as _stats keeps)."""
    kl, kr = df["k_l"].to_numpy(float), df["k_r"].to_numpy(float)
    with np.errstate(invalid="ignore"):
        k_ok = np.isfinite(kl) & np.isfinite(kr) & (kl > 0) & (kr > 0)
    out = {"k_l": kl[k_ok], "k_r": kr[k_ok], "k_min": np.minimum(kl[k_ok], kr[k_ok])}
    if motion:
        ran = np.isin(df["status"].to_numpy(), INTEGRATED)
        col = df["collapsed"].to_numpy(bool)
        stopped = (df["early_stopped"].to_numpy(bool) if "early_stopped" in df
                   else np.zeros(len(df), dtype=bool))
        out["peak"] = df["peak"].to_numpy(float)[ran & ~col]
        out["n_impacts"] = df["n_impacts"].to_numpy(float)[ran & ~stopped]
        out["t_collapse"] = df["t_collapse"].to_numpy(float)[ran & col]
        out["t_limit"] = df["t_limit"].to_numpy(float)[ran & col]
        out["t_unstable"] = df["t_unstable"].to_numpy(float)[ran]
    return {k: v[np.isfinite(v)] for k, v in out.items()}


def _bins(x, lo, hi):
    if hi <= lo:
        return np.zeros(x.size, dtype=np.int64)
    idx = np.floor((x - lo) / (hi - lo) * QUANTILE_BINS).astype(np.int64)
    return np.clip(idx, 0, QUANTILE_BINS - 1)


def _virtual(n: int):
    """numpy.quantile's linear method: (previous index, gamma) of each quantile (numpy's own
    arithmetic, so the interpolation weights are the same numbers)."""
    q = np.asarray(_Q, float)
    virtual = n * q + (1 + q * (1 - 1 - 1)) - 1
    prev = np.floor(virtual)
    gamma = virtual - prev
    prev = prev.astype(np.int64)
    return np.clip(prev, 0, n - 1), np.clip(prev + 1, 0, n - 1), gamma


def _lerp(a, b, t):
    """numpy's _lerp (exact at both ends, symmetric)."""
    diff = b - a
    return b - diff * (1 - t) if t >= 0.5 else a + diff * t


class _Stat:
    def __init__(self):
        self.n = 0
        self.parts = []  # exact partial sums (math.fsum of each batch)
        self.lo = math.inf
        self.hi = -math.inf
        self.m2 = []
        self.hist = np.zeros(QUANTILE_BINS, dtype=np.int64)
        self.want: dict[int, Counter] = {}

    def pass1(self, x):
        if x.size:
            self.n += x.size
            self.parts.append(math.fsum(x.tolist()))
            self.lo = min(self.lo, float(x.min()))
            self.hi = max(self.hi, float(x.max()))

    def start2(self):
        self.mean = math.fsum(self.parts) / self.n if self.n else math.nan

    def pass2(self, x):
        if x.size:
            self.m2.append(float(np.sum((x - self.mean) ** 2)))
            self.hist += np.bincount(_bins(x, self.lo, self.hi), minlength=QUANTILE_BINS)

    def start3(self):
        if self.n < 2:
            return
        cum = np.cumsum(self.hist)
        prev, nxt, _ = _virtual(self.n)
        for r in np.concatenate([prev, nxt]):
            self.want.setdefault(int(np.searchsorted(cum, r, side="right")), Counter())

    def pass3(self, x):
        if self.want and x.size:
            b = _bins(x, self.lo, self.hi)
            for k, cnt in self.want.items():
                vals, mult = np.unique(x[b == k], return_counts=True)
                cnt.update(dict(zip(vals.tolist(), mult.tolist())))

    def _order(self, r: int) -> float:
        """The r-th smallest value (0-based)."""
        cum = np.cumsum(self.hist)
        k = int(np.searchsorted(cum, r, side="right"))
        before = int(cum[k - 1]) if k else 0
        for v in sorted(self.want[k]):
            before += self.want[k][v]
            if before > r:
                return v
        raise AssertionError("order statistic not found")  # pragma: no cover

    def result(self) -> dict:
        if self.n == 0:
            return {"mean": None, "std": None, "min": None, "q05": None, "median": None,
                    "q95": None, "max": None, "count": 0, "note": "no sample"}
        one = self.n == 1
        if one:
            q = [self.lo] * 3
        else:
            prev, nxt, gamma = _virtual(self.n)
            q = [_lerp(self._order(int(p)), self._order(int(m)), float(g))
                 for p, m, g in zip(prev, nxt, gamma)]
        std = None if one else math.sqrt(math.fsum(self.m2) / (self.n - 1))
        return {"mean": self.mean, "std": std, "min": self.lo, "q05": None if one else q[0],
                "median": q[1], "q95": None if one else q[2], "max": self.hi,
                "count": int(self.n),
                "note": "one sample: std and 5-95% range not estimated" if one else None}


def summarize_batches(batches, config, nominal: dict, impact: dict, timing: dict | None = None,
                      confidence: float = 0.95) -> dict:
    """The summary of :meth:`EnsembleResult.summary` from ``batches()``, a callable returning
    a fresh iterable of batch DataFrames (it is called three times; see the module docstring)."""
    motion = config.motion is not None
    tally = _Tally(motion, nominal)
    for df in batches():
        tally.add(df)
    res, passes = _quantile_passes(tally.stats, batches, motion)
    counts, status_counts = tally.counts, tally.status_counts
    n_all = tally.n_all
    done = "integrated" if motion else "limit_only"
    counts[done] = int(sum(status_counts[s] for s in tally.done_status))
    outcomes = {"samples": n_all,
                "rule": "each sample has exactly one outcome; shares over all samples",
                "counts": counts,
                "shares": {k: (v / n_all if n_all else None) for k, v in counts.items()}}
    if motion:
        outcomes["integrated"] = {k: int(status_counts[k]) for k in INTEGRATED
                                  if k != "stopped" or status_counts[k]}
    out = summary_dict(config, nominal, impact, timing or {}, n_all,
                       {k: res[k] for k in ("k_l", "k_r", "k_min")},
                       {name: dict(c.most_common()) for name, c in tally.hinges.items()},
                       tally.far_shares(),
                       {"count": int(sum(tally.reasons.values())),
                        "reasons": dict(tally.reasons)}, outcomes)
    if motion:
        out.update(probabilities(tally.collapses, counts["integrated"],
                                 counts["cannot_stand"], confidence))
        out["response"] = tally.response(res, counts["integrated"])
    out["streamed"] = {"passes": passes,
                       "quantiles": "exact (histogram of %d bins, then the values of the bins "
                                    "holding the order statistics)" % QUANTILE_BINS}
    return out


def _quantile_passes(stats: dict, batches, motion: bool) -> tuple[dict, int]:
    """Passes 2 and 3 (module docstring) of the statistics after the counting pass: (each
    statistic's figures, passes made in all)."""
    for s in stats.values():
        s.start2()
    for df in batches():
        for k, x in _series(df, motion).items():
            stats[k].pass2(x)
    for s in stats.values():
        s.start3()
    third = any(s.want for s in stats.values())
    if third:
        for df in batches():
            for k, x in _series(df, motion).items():
                stats[k].pass3(x)
    return {k: s.result() for k, s in stats.items()}, 3 if third else 2


class _Tally:
    """The counting pass (module docstring, 1.) over the batches, one :meth:`add` each."""

    def __init__(self, motion: bool, nominal: dict):
        self.motion = motion
        self.k0 = (nominal["k_l"], nominal["k_r"])
        self.stats = {k: _Stat() for k in (_SERIES if motion else _SERIES[:3])}
        self.n_all = self.k_ok_n = 0
        self.counts = dict.fromkeys(REASONS, 0)
        self.reasons: Counter = Counter()
        self.hinges = {"M_l": Counter(), "M_r": Counter()}
        self.far = {name: Counter() for name in PAPER_RANDOM_ARCHES}
        self.status_counts: Counter = Counter()
        self.activated = self.truncated = self.unstable_survived = 0
        self.early = self.collapses = 0
        self.done_status = INTEGRATED if motion else ("limit-only",)

    def add(self, df) -> None:
        """Count one batch's outcomes, hinges, "as far as" rows and response flags."""
        self.n_all += len(df)
        err = df["error"].to_numpy()
        status = df["status"].to_numpy()
        failed = err != ""
        for e, c in Counter(err[failed].tolist()).items():
            why = LeftOut.read(e)  # the column holds its text (module docstring of leftout)
            self.counts[why.reason] += c
            self.reasons[why.group] += c
        self.counts["other"] += int((~failed & ~np.isin(status, self.done_status)).sum())
        for col, name in (("mech_l", "M_l"), ("mech_r", "M_r")):
            v = df[col].to_numpy()
            self.hinges[name].update(Counter(v[v != ""].tolist()))
        self._add_far(df["k_l"].to_numpy(float), df["k_r"].to_numpy(float))
        self.status_counts.update(Counter(status.tolist()))
        if self.motion:
            self._add_response(df, np.isin(status, INTEGRATED))
        for k, x in _series(df, self.motion).items():
            self.stats[k].pass1(x)

    def _add_far(self, kl, kr) -> None:
        with np.errstate(invalid="ignore"):
            k_ok = np.isfinite(kl) & np.isfinite(kr) & (kl > 0) & (kr > 0)
        kl, kr = kl[k_ok], kr[k_ok]
        self.k_ok_n += int(k_ok.sum())
        k0l, k0r = self.k0
        for name, (ral, rar) in PAPER_RANDOM_ARCHES.items():
            dl = np.abs(kl - k0l) >= abs(ral - k0l)
            dr = np.abs(kr - k0r) >= abs(rar - k0r)
            asym = np.abs(kl - kr) >= abs(ral - rar)
            self.far[name].update({"k_l": int(dl.sum()), "k_r": int(dr.sum()),
                                   "either": int((dl | dr).sum()), "both": int((dl & dr).sum()),
                                   "asymmetry": int(asym.sum())})

    def _add_response(self, df, ran) -> None:
        col = df["collapsed"].to_numpy(bool)
        self.collapses += int((ran & col).sum())
        self.activated += int((ran & (df["n_activations"].to_numpy() > 0)).sum())
        self.truncated += int((ran & df["events_truncated"].to_numpy(bool)).sum())
        self.unstable_survived += int((ran & np.isfinite(df["t_unstable"].to_numpy(float))
                                       & ~col).sum())
        if "early_stopped" in df:
            self.early += int((ran & df["early_stopped"].to_numpy(bool)).sum())

    def far_shares(self) -> dict:
        """The "as far as RA-x" shares of the standing arches."""
        def share(c):
            return c / self.k_ok_n if self.k_ok_n else None
        return {name: {"k_l_ref": ral, "k_r_ref": rar,
                       **{k: share(self.far[name][k]) for k in
                          ("k_l", "k_r", "either", "both", "asymmetry")}}
                for name, (ral, rar) in PAPER_RANDOM_ARCHES.items()}

    def response(self, res: dict, n: int) -> dict:
        """The summary's response statistics (``res``: the statistics' figures; n: samples
        integrated)."""
        return {
            "status": {k: int(self.status_counts[k]) for k in INTEGRATED
                       if self.status_counts[k]},
            "activated": self.activated / n if n else None,
            "peak_rad": res["peak"], "n_impacts": res["n_impacts"],
            "early_stopped": self.early, "events_truncated": self.truncated,
            "t_collapse_s": res["t_collapse"], "t_limit_s": res["t_limit"],
            "t_unstable_s": res["t_unstable"], "unstable_but_survived": self.unstable_survived,
        }


def summarize_store(out_dir, config, nominal: dict, impact: dict, timing: dict | None = None,
                    confidence: float = 0.95) -> dict:
    """:func:`summarize_batches` over the batch files of an output folder (batch order; only
    :data:`SUMMARY_COLUMNS` are read)."""
    import pyarrow.parquet as pq

    from .store import batch_path

    out = Path(out_dir)
    paths = [batch_path(out, b) for b in range(config.n_batches)]
    missing = [p.name for p in paths if not p.is_file()]
    if missing:
        from ...errors import ArchInputError

        raise ArchInputError(f"out: {str(out)!r} lacks {len(missing)} batch file(s) (first "
                             f"{missing[0]}); run the ensemble to completion first")

    def batches():
        for p in paths:
            _check_batch(p)
            cols = [c for c in SUMMARY_COLUMNS if c in pq.read_schema(p).names]
            yield pq.read_table(p, columns=cols).to_pandas()

    return summarize_batches(batches, config, nominal, impact, timing, confidence)



def _check_batch(path: Path) -> None:
    """Refuse a batch file that no longer matches its recorded checksum (damaged since the run
    that verified or wrote it): its numbers are never summarized."""
    from ..checksums import check_sidecar

    try:
        why = check_sidecar(path)
    except FileNotFoundError:  # a folder older than checksums: its run checked it whole
        return
    if why is not None:
        from ...errors import ArchInputError

        raise ArchInputError(f"out: {str(path)!r} is {why}; run the ensemble again to "
                             f"recompute it")
