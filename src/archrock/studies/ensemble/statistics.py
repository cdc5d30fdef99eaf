"""The statistics of an ensemble's samples: counts, k statistics, Wilson intervals, the
probabilities and the summary's JSON, shared by the summary of a kept table
(:meth:`~archrock.studies.ensemble.summary.EnsembleResult.summary`) and that of the stored batches
(:mod:`archrock.studies.ensemble.streaming`); definitions in :mod:`.summary`'s docstring."""

from __future__ import annotations

import numpy as np

from ... import published
from ...leftout import REASONS, LeftOut
from .config import EnsembleConfig

__all__ = ["PAPER_RANDOM_ARCHES", "P_COLLAPSE_RULE", "P_FAILURE_RULE", "INTEGRATED",
           "summary_dict", "probabilities"]


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


def summary_dict(config: EnsembleConfig, nominal: dict, impact: dict, timing: dict,
                 samples: int, k_stats: dict, hinges: dict, far: dict, failed: dict,
                 outcomes: dict) -> dict:
    """The summary's keys, in order, from its parts (p_collapse, p_failure and response None:
    the ensemble's motion fills them in)."""
    sp = config.spreads
    return {
        "samples": samples, "seed": config.seed,
        "spreads": {"span": sp.span, "thickness": sp.thickness, "radius": sp.radius,
                    "tilt_deg": sp.tilt, **({"fc": sp.fc} if sp.fc else {})},
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
