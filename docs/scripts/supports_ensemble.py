"""The ensemble on moved supports beside the same arches on fixed supports (docs/supports.md).

Oppenheim's arch, the default spreads, seed 0, the paper's pulse shape (a = -1 g, t_p = 0.2 s);
the right support spread or settled by a fixed movement applied to every sample.  Writes
docs/figures/supports_ensemble.json and docs/figures/supports_ensemble.png.

Usage: PYTHONPATH=src python docs/scripts/supports_ensemble.py [--samples 1000]
"""

from __future__ import annotations

import json
import time

from _figures import FIGURES, new_axes, samples_arg, save_axes
from archrock.geometry import nominal_arch
from archrock.geometry.displaced import SupportMovement
from archrock.groundmotion import PulseSpec
from archrock.studies.ensemble import EnsembleConfig, run_ensemble

CASES = [("spread", 0.0), ("spread", 0.1), ("spread", 0.5), ("spread", 1.0), ("spread", 1.5),
         ("settlement", 1.0), ("settlement", 3.0)]


def main(argv=None):
    samples = samples_arg(__doc__, 1000, argv)
    rows = []
    for kind, d in CASES:
        mv = SupportMovement(d, 0.0) if kind == "spread" else SupportMovement(0.0, d)
        t0 = time.perf_counter()
        cfg = EnsembleConfig.from_arch(nominal_arch(), samples=samples, seed=0,
                                       motion=PulseSpec("oppenheim", -1.0, 0.2), support=mv)
        res = run_ensemble(cfg)
        s, f = res.summary(), res.frame
        pc = s["p_collapse"]
        row = {"kind": kind, "movement_m": d, "nominal_k_l": s["nominal"]["k_l"],
               "nominal_k_r": s["nominal"]["k_r"], "k_l_median": float(f["k_l"].median()),
               "k_r_median": float(f["k_r"].median()), "collapsed": pc["collapses"],
               "integrated": pc["trials"], "p_collapse": pc["p"], "low": pc["low"],
               "high": pc["high"],
               "cannot_stand": int(f["error"].str.contains("cannot stand").sum()),
               "wall_s": time.perf_counter() - t0}
        rows.append(row)
        print(json.dumps(row), flush=True)
    (FIGURES / "supports_ensemble.json").write_text(json.dumps(
        {"samples": samples, "rows": rows}, indent=1))
    fig, ax = new_axes((6.4, 3.6))
    for kind, colour in (("spread", "tab:blue"), ("settlement", "tab:red")):
        rr = [r for r in rows if r["kind"] == kind or r["movement_m"] == 0.0]
        x = [r["movement_m"] for r in rr]
        y = [r["p_collapse"] for r in rr]
        err = [[r["p_collapse"] - r["low"] for r in rr], [r["high"] - r["p_collapse"] for r in rr]]
        ax.errorbar(x, y, yerr=err, marker="o", capsize=3, color=colour,
                    label=f"right support {kind}")
    ax.set_xlabel("imposed movement of the right support [m] (span 19.6 m)")
    ax.set_ylabel("P(collapse), 95% Wilson")
    ax.set_title(f"Oppenheim's arch, {samples} irregular arches, pulse -1 g, t_p 0.2 s",
                 fontsize=9)
    save_axes(fig, ax, "supports_ensemble.png")


if __name__ == "__main__":
    main()
