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

from ...leftout import LeftOut
from .config import EnsembleConfig
from .statistics import (INTEGRATED, P_COLLAPSE_RULE, P_FAILURE_RULE,  # noqa: F401
                         PAPER_RANDOM_ARCHES, _far, _outcomes, _response, _stats, probabilities,
                         summary_dict)
from .streaming import summarize_store

__all__ = ["EnsembleResult", "PAPER_RANDOM_ARCHES", "P_COLLAPSE_RULE", "P_FAILURE_RULE"]


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
