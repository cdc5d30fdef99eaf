"""The result of an ensemble and its summary statistics.

Definitions used by :meth:`EnsembleResult.summary`:

* outcomes: every sample has exactly one, counted and shared over ALL samples: "invalid_draw",
  "cannot_stand", "no_mechanism", "four_link_not_applicable", "impact_not_applicable", "other"
  (the reasons of :data:`archrock.leftout.REASONS`, read from the ``error`` column by
  :meth:`archrock.leftout.LeftOut.read`), then "integrated" (status rest,
  collapsed or moving) or, without a ground motion, "limit_only".
* k statistics and the "as far as RA-x" shares over the samples whose limit analysis found a
  standing arch (finite k_l, k_r > 0): samples that failed there (invalid geometry, no
  mechanism, "cannot stand") are left out; samples that failed later (four-link model, impact
  law) keep their valid k.  std is the sample standard deviation (ddof = 1); with one sample
  std, q05 and q95 are None (not estimated, ``note`` says so).
* response statistics over the samples whose response was integrated; ``peak_rad`` only over
  those that did not collapse (a collapsed sample's ``peak`` column is its rotation limit).
  Early-stopped samples (status "stopped", column ``early_stopped``) count as integrated, not
  collapsed, with their final peak; ``n_impacts`` (and any statistic of the motion after the
  stop, such as a time to rest) leaves them out: ``response.early_stopped`` says how many.
* p_collapse, conditional: collapses / integrated samples, with the Wilson score interval
  (:func:`archrock.studies.fragility.collapse_probability`); p, low, high None (``note`` says why) when
  no sample was integrated; p_collapse and p_failure are None without a ground motion.
* p_failure, cannot stand counted as failed: (cannot stand + collapsed) / (cannot stand +
  integrated), Wilson interval.  An arch that cannot stand under its own weight has failed; the
  samples whose outcome under the motion is unknown (invalid draw, no mechanism, a model not
  applicable) are in neither count.
* "as far from nominal as RA-x" (RA-1: k_l = 0.4111, k_r = 0.3104; RA-2: k_l = 0.3946,
  k_r = 0.3501, the paper's random arches): with k0_l, k0_r the nominal arch's multipliers,
  ``k_l``: |k_l - k0_l| >= |k_l(RA) - k0_l|; ``k_r``: the same for k_r; ``either`` / ``both``:
  one of / both conditions; ``asymmetry``: |k_l - k_r| >= |k_l(RA) - k_r(RA)|.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ... import published
from ...leftout import REASONS, LeftOut
from .config import EnsembleConfig

__all__ = ["EnsembleResult", "PAPER_RANDOM_ARCHES", "P_COLLAPSE_RULE", "P_FAILURE_RULE"]

#: How the two probabilities of the summary are counted (also in its JSON, ``rule``).
P_COLLAPSE_RULE = ("conditional: collapsed / integrated samples; samples without a response "
                   "(cannot stand, invalid draw, no mechanism, model not applicable) left out")
P_FAILURE_RULE = ("cannot stand counted as failed: (cannot stand + collapsed) / (cannot stand + "
                  "integrated); samples whose outcome is unknown (invalid draw, no mechanism, "
                  "model not applicable) left out")
#: statuses of an integrated sample ("stopped": early stop, EnsembleConfig.early_stop)
INTEGRATED = ("rest", "collapsed", "moving", "stopped")

#: The paper's random arches (plausibility figures, docs/verification.md).
PAPER_RANDOM_ARCHES = published.RANDOM_ARCHES


def _stats(x: np.ndarray) -> dict:
    x = np.asarray(x, float)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return {"mean": None, "std": None, "min": None, "q05": None, "median": None, "q95": None,
                "max": None, "count": 0, "note": "no sample"}
    q = np.quantile(x, [0.05, 0.5, 0.95])
    one = x.size == 1  # a spread of one sample is not estimated (it would read as zero)
    return {"mean": float(x.mean()), "std": None if one else float(x.std(ddof=1)),
            "min": float(x.min()), "q05": None if one else float(q[0]), "median": float(q[1]),
            "q95": None if one else float(q[2]), "max": float(x.max()), "count": int(x.size),
            "note": "one sample: std and 5-95% range not estimated" if one else None}


def _wilson(k: int, trials: int, confidence: float, rule: str, **counts) -> dict:
    """A probability with its Wilson interval; p, low, high None (and a note) with no trials."""
    from ..fragility import collapse_probability

    out = {"p": None, "low": None, "high": None, "confidence": confidence, "method": "wilson",
           **counts, "trials": trials, "rule": rule, "note": None}
    if trials:
        out["p"], out["low"], out["high"] = collapse_probability(k, trials, confidence,
                                                                 "wilson")
    else:
        out["note"] = "no trials: the probability cannot be estimated"
    return out


def _outcomes(df, motion: bool) -> dict:
    """Counts and shares of each sample's one outcome over all samples."""
    n = int(len(df))
    counts = dict.fromkeys(REASONS, 0)
    status = df["status"].to_numpy()
    for e in df.loc[df["error"] != "", "error"]:
        counts[LeftOut.read(e).reason] += 1
    # no error but not integrated either (not expected): counted, not lost
    counts["other"] += int(((df["error"] == "") & ~df["status"].isin(
        INTEGRATED if motion else ("limit-only",))).sum())
    done = "integrated" if motion else "limit_only"
    counts[done] = int(np.isin(status, INTEGRATED if motion else ("limit-only",)).sum())
    out = {"samples": n,
           "rule": "each sample has exactly one outcome; shares over all samples",
           "counts": counts,
           "shares": {k: (v / n if n else None) for k, v in counts.items()}}
    if motion:
        # "stopped" (early stop) only when there is one: other ensembles' summaries unchanged
        out["integrated"] = {k: int((status == k).sum()) for k in INTEGRATED
                             if k != "stopped" or (status == k).any()}
    return out


@dataclass(frozen=True)
class EnsembleResult:
    """Result of :func:`~archrock.studies.ensemble.run.run_ensemble`: the per-sample table and how it was obtained.

    frame: one row per sample (columns :data:`~archrock.studies.ensemble.compute.COLUMNS`), sorted by index; nominal: k_l, k_r and
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
        """JSON-ready summary (definitions in the module docstring); from the stored batches
        (:func:`archrock.studies.ensemble.streaming.summarize_store`) when no frame is kept."""
        if self.frame is None:
            from .streaming import summarize_store

            return summarize_store(self.out_dir, self.config, self.nominal, self.impact,
                                   self.timing, confidence)
        df = self.frame
        kl_all, kr_all = df["k_l"].to_numpy(), df["k_r"].to_numpy()
        # a standing arch by limit analysis (k <= 0: "cannot stand", a failed sample)
        with np.errstate(invalid="ignore"):
            k_ok = np.isfinite(kl_all) & np.isfinite(kr_all) & (kl_all > 0) & (kr_all > 0)
        kl, kr = df["k_l"].to_numpy()[k_ok], df["k_r"].to_numpy()[k_ok]
        failed = df[df["error"] != ""]
        reasons: dict[str, int] = {}
        for e in failed["error"]:
            group = LeftOut.read(e).group
            reasons[group] = reasons.get(group, 0) + 1
        hinges = {}
        for col, name in (("mech_l", "M_l"), ("mech_r", "M_r")):
            vc = df.loc[df[col] != "", col].value_counts()
            hinges[name] = {str(k): int(v) for k, v in vc.items()}
        out = summary_dict(self.config, self.nominal, self.impact, self.timing, int(len(df)),
                           {"k_l": _stats(kl), "k_r": _stats(kr),
                            "k_min": _stats(np.minimum(kl, kr))},
                           hinges, _far(kl, kr, self.nominal),
                           {"count": int(len(failed)), "reasons": reasons},
                           _outcomes(df, self.config.motion is not None))
        if self.config.motion is not None:
            ran = df[df["status"].isin(INTEGRATED)]
            n, k = int(len(ran)), int(ran["collapsed"].sum())
            out.update(probabilities(k, n, out["outcomes"]["counts"]["cannot_stand"],
                                     confidence))
            out["response"] = _response(ran)
        return out


def summary_dict(config: EnsembleConfig, nominal: dict, impact: dict, timing: dict,
                 samples: int, k_stats: dict, hinges: dict, far: dict, failed: dict,
                 outcomes: dict) -> dict:
    """The summary's keys, in order, from its parts (p_collapse, p_failure and response None:
    the ensemble's motion fills them in)."""
    sp = config.spreads
    return {
        "samples": samples, "seed": config.seed,
        "spreads": {"span": sp.span, "thickness": sp.thickness, "radius": sp.radius,
                    "tilt_deg": sp.tilt},
        "nominal": nominal, **k_stats,
        "hinge_patterns": hinges,
        "as_far_as": far,
        "failed": failed,
        "outcomes": outcomes, "impact": impact,
        "motion": None if config.motion is None else config.motion.to_dict(),
        "p_collapse": None, "p_failure": None, "response": None,
        "timing": timing,
    }


def probabilities(collapses: int, integrated: int, cannot_stand: int,
                  confidence: float) -> dict:
    """p_collapse and p_failure of the summary (module docstring), with Wilson intervals."""
    k, n, cs = collapses, integrated, cannot_stand
    return {"p_collapse": _wilson(k, n, confidence, P_COLLAPSE_RULE, collapses=k),
            "p_failure": _wilson(cs + k, cs + n, confidence, P_FAILURE_RULE,
                                 failures=cs + k, cannot_stand=cs, collapses=k)}


def _far(kl, kr, nominal: dict) -> dict:
    """The "as far from nominal as RA-x" shares (module docstring) of the standing arches."""
    k0l, k0r = nominal["k_l"], nominal["k_r"]
    far = {}
    for name, (ral, rar) in PAPER_RANDOM_ARCHES.items():
        dl = np.abs(kl - k0l) >= abs(ral - k0l)
        dr = np.abs(kr - k0r) >= abs(rar - k0r)
        asym = np.abs(kl - kr) >= abs(ral - rar)
        share = (lambda m: float(m.mean()) if m.size else None)
        far[name] = {"k_l_ref": ral, "k_r_ref": rar, "k_l": share(dl), "k_r": share(dr),
                     "either": share(dl | dr), "both": share(dl & dr), "asymmetry": share(asym)}
    return far


def _response(ran) -> dict:
    """The response statistics of the integrated samples ``ran`` (rows of the frame)."""
    n = int(len(ran))
    col = ran[ran["collapsed"]]
    stopped = (ran["early_stopped"].to_numpy() if "early_stopped" in ran
               else np.zeros(len(ran), dtype=bool))
    return {
        "status": {str(k_): int(v) for k_, v in ran["status"].value_counts().items()},
        "activated": float((ran["n_activations"] > 0).mean()) if n else None,
        "peak_rad": _stats(ran.loc[~ran["collapsed"], "peak"].to_numpy()),
        # impacts after an early stop are not counted: those arches are left out
        "n_impacts": _stats(ran.loc[~stopped, "n_impacts"].to_numpy()),
        "early_stopped": int(stopped.sum()),
        "events_truncated": int(ran["events_truncated"].sum()),
        # the last passage of the unstable position; t_limit: the numerical stop
        "t_collapse_s": _stats(col["t_collapse"].to_numpy()),
        "t_limit_s": _stats(col["t_limit"].to_numpy()),
        "t_unstable_s": _stats(ran["t_unstable"].to_numpy()),
        "unstable_but_survived": int((np.isfinite(ran["t_unstable"].to_numpy())
                                      & ~ran["collapsed"].to_numpy()).sum()),
    }
