"""The paper's study, end to end (``archrock paper --out DIR``).

Currently: the limit analysis of Oppenheim's arch (paper section 3, Fig. 3). Each step writes
its files into ``out_dir`` and adds an entry to the summary; ``summary.json`` is written last.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path
from typing import Callable

from .errors import ArchInputError

__all__ = ["run_paper_study", "PAPER_K_OPPENHEIM", "FIG3_NAME"]

#: Oppenheim's arch collapse multiplier published in the paper (4 decimals).
PAPER_K_OPPENHEIM = 0.3700
FIG3_NAME = "fig3_oppenheim_limit.png"


def _limit_step(out: Path, progress: Callable[[str], None]) -> dict:
    """Fig. 3: Oppenheim's arch, collapse hinges and line of thrust."""
    from .geometry import oppenheim_arch
    from .limit import limit_analysis
    from .plots import hinge_labels, save_limit_figure

    result = limit_analysis(oppenheim_arch(), verify=True)
    progress(f"Oppenheim's arch: k_l = {result.k_l:.4f}, k_r = {result.k_r:.4f} "
             f"(paper: k = {PAPER_K_OPPENHEIM:.4f}); kinematic vs static LP differ by "
             f"{result.discrepancy:.1e}")
    fig = save_limit_figure(result, out / FIG3_NAME, directions=("l", "r"))
    progress(f"wrote {fig}")
    return {
        "arch": result.arch.name,
        "geometry": result.arch.to_dict(),
        "k_l": result.k_l,
        "k_r": result.k_r,
        "k": result.k,
        "paper_k": PAPER_K_OPPENHEIM,
        "matches_paper_4_decimals": round(result.k, 4) == PAPER_K_OPPENHEIM,
        "static_k_l": result.static_k_l,
        "static_k_r": result.static_k_r,
        "discrepancy": result.discrepancy,
        "hinges": {d: [{"label": lab, **h.to_dict()} for lab, h in hinge_labels(result.mechanism(d))]
                   for d in ("l", "r")},
        "figure": FIG3_NAME,
    }


def run_paper_study(out_dir: str | os.PathLike, progress: Callable[[str], None] = print) -> dict:
    """Run the paper's study into ``out_dir`` (created if needed); returns the summary dict,
    also written to ``out_dir/summary.json``. ``progress`` receives one-line messages."""
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ArchInputError(f"--out: cannot create the folder {str(out)!r} ({exc.strerror or exc})") from None
    t0 = time.perf_counter()
    summary: dict = {"paper": "Effect of geometric irregularities on the dynamic response of "
                              "masonry arches (EURODYN 2017)",
                     "files": []}
    limit = _limit_step(out, progress)
    summary["limit_oppenheim"] = limit
    summary["files"].append(limit["figure"])
    summary["elapsed_s"] = round(time.perf_counter() - t0, 3)
    summary["files"].append("summary.json")
    path = out / "summary.json"
    # strict JSON: a NaN here would be a bug, not a value to write
    path.write_text(json.dumps(summary, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    progress(f"wrote {path}")
    return summary
