"""Fragility of Oppenheim's arch on moved supports beside fixed supports (docs/supports.md).

Records: eight seeded band-limited (0.3-2 Hz) noise accelerograms, 8 s, smooth envelope, PGA
0.3 g (as the synthetic records of tests/studies/test_ida.py, in a lower band for this 20 m
arch: no record suite ships with archrock); IDA on the scale grid 0.5 .. 15 (PGA 0.15 ..
4.5 g), first collapses bisected to 1e-3; the lognormal fit of the first-collapse PGAs (median theta, dispersion beta); the nominal
arch and 20 random arches (default spreads, seed 0) each on the same moved supports (right
support).  Writes docs/figures/supports_fragility.json.

Usage: PYTHONPATH=src python docs/scripts/supports_fragility.py
"""

from __future__ import annotations

import json
import time

import numpy as np
from _figures import FIGURES

from archrock.dynamics.response import prepare
from archrock.geometry import nominal_arch
from archrock.geometry.displaced import SupportMovement
from archrock.groundmotion import band_limited_noise
from archrock.statics.supports import on_moved_supports
from archrock.studies.ida import ida, random_models

CASES = [("fixed", SupportMovement()), ("spread 0.5 m", SupportMovement(0.5)),
         ("spread 1 m", SupportMovement(1.0)), ("settlement 1 m", SupportMovement(0.0, 1.0)),
         ("rotation 0.05 rad", SupportMovement(rotation=0.05))]


def noise_record(seed, duration=8.0, dt=0.01, pga_g=0.3):
    return band_limited_noise(duration, dt, (0.3, 2.0), seed, pga_g)


def main():
    records = [noise_record(s) for s in range(1, 9)]
    scales = np.geomspace(0.5, 15.0, 24)
    rows = []
    for name, mv in CASES:
        t0 = time.perf_counter()
        arch = on_moved_supports(nominal_arch(), mv)
        out = {"case": name, "movement": mv.to_dict()}
        for label, models in (("nominal", [prepare(arch)]),
                              ("random 20", random_models(arch, 20, seed=0))):
            res = ida(records, models, scales)
            fit = res.fit
            out[label] = {"theta_g": None if fit is None else fit.theta,
                          "beta": None if fit is None else fit.beta,
                          "method": None if fit is None else fit.method,
                          "arches": len(models), "curves": len(res.curves),
                          "censored": res.n_censored,
                          "median_first_pga_g": float(np.median(res.first_ims))}
        out["seconds"] = time.perf_counter() - t0
        rows.append(out)
        print(json.dumps(out), flush=True)
    (FIGURES / "supports_fragility.json").write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
