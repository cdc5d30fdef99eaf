"""Collapse-acceleration curves on moved supports beside fixed supports (docs/supports.md).

Oppenheim's arch (the paper's), Oppenheim's pulse with its main lobe toward -x (sign -1), the
study's defaults (150 amplitudes from k to 10 g, bisected to 1e-3 g); the right support spread
or settled.  The nominal arch's curve at every duration, and the 5/50/95% band of the first
collapse amplitude over random arches (default spreads, seed 0) at the paper's t_p = 0.2 s,
each arch on the same moved supports.  Writes docs/figures/supports_curves.json and .png.

Usage: PYTHONPATH=src python docs/scripts/supports_curves.py [--samples 100]
"""

from __future__ import annotations

import json
import time

from _figures import FIGURES, new_axes, samples_arg, save_axes
from archrock.dynamics.response import prepare
from archrock.geometry import nominal_arch
from archrock.geometry.displaced import SupportMovement
from archrock.statics.supports import on_moved_supports
from archrock.studies.curves import collapse_curve, ensemble_curve

CASES = [("fixed", 0.0), ("spread", 0.05), ("spread", 0.5), ("spread", 1.0),
         ("settlement", 0.5), ("settlement", 1.0)]
DURATIONS = (0.1, 0.2, 0.3, 0.5, 0.7, 1.0)


def main(argv=None):
    samples = samples_arg(__doc__, 100, argv)
    rows = []
    for kind, d in CASES:
        mv = SupportMovement(d if kind == "spread" else 0.0, d if kind == "settlement" else 0.0)
        arch = on_moved_supports(nominal_arch(), mv)
        t0 = time.perf_counter()
        curve = collapse_curve(prepare(arch), DURATIONS)
        band = ensemble_curve(arch, samples, 0, None, (0.2,))
        rows.append({"kind": kind, "movement_m": d, "k_l": curve.k_l, "k_r": curve.k_r,
                     "durations": list(DURATIONS),
                     "amplitudes_g": [float(a) for a in curve.amplitudes],
                     "band_0.2s_g": [float(b) for b in band.bands[:, 0]],
                     "usable": band.n_samples, "requested": band.n_requested,
                     "seconds": time.perf_counter() - t0})
        print(json.dumps(rows[-1]))
    (FIGURES / "supports_curves.json").write_text(json.dumps(rows, indent=1))
    fig, ax = new_axes((6.4, 4.0))
    for r in rows:
        lab = "fixed supports" if r["kind"] == "fixed" else f"{r['kind']} {r['movement_m']:g} m"
        ax.plot(r["durations"], r["amplitudes_g"], "o-" if r["kind"] != "settlement" else "s--",
                ms=3, lw=1, label=lab)
    ax.set_xlabel("pulse duration t_p [s]")
    ax.set_ylabel("first collapse amplitude |a| [g]")
    ax.set_title("Oppenheim's arch, right support moved (Oppenheim pulse, sign -1)")
    print("wrote", save_axes(fig, ax, "supports_curves.png", lw=0.3, alpha=0.5))


if __name__ == "__main__":
    main()
