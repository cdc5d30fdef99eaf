"""The batch on the CPU and on the GPU build under numba's CUDA simulator, for the tests.

``python tests/dynamics/gpu_sim_compare.py N_CIRCULAR N_FAMILY N_SURVEY`` (run with
NUMBA_ENABLE_CUDASIM=1) prepares and integrates three sets of irregular arches both ways and
prints one JSON line per set: the outcomes that differ (counts), and the largest differences
of the multipliers, the four-link vectors and the response's rotations and times, each relative
to max(1, |CPU value|) (rotations in rad and times in s are below 1 to 60, so these are absolute
differences for them; the four-link vectors hold masses in kg).
Circular arches around Oppenheim's under the paper's pulse; pointed arches (a family, tilted
joints) and a surveyed polygon arch under a band-limited noise record.
"""

import json
import sys

import numpy as np


def _largest(a, b) -> float:
    """max |a - b| / max(1, |a|) over the entries finite in both (0 if none)."""
    fin = np.isfinite(a) & np.isfinite(b)
    if not fin.any():
        return 0.0
    return float(np.max(np.abs(a[fin] - b[fin]) / np.maximum(1.0, np.abs(a[fin]))))


def _compare(name, arches_or_arrays, nominal, motion):
    from archrock.dynamics.batch import prepare_batch, simulate_batch

    args, kw = arches_or_arrays
    cpu = prepare_batch(*args, **kw, nominal=nominal)
    gpu = prepare_batch(*args, **kw, nominal=nominal, device="gpu")
    out = {"set": name, "arches": int(cpu.k_l.size), "usable": int(cpu.ok.sum()),
           "errors_differ": int(np.sum(cpu.error != gpu.error)),
           "mechanisms_differ": int(np.sum((cpu.mech_l != gpu.mech_l) | (cpu.mech_r != gpu.mech_r)))}
    for f in ("k_l", "k_r", "geo_l", "geo_r", "phi_unstable_l", "phi_limit_l", "v_rest",
              "c_l_to_r"):
        a, b = getattr(cpu, f), getattr(gpu, f)
        same_nan = np.array_equal(np.isnan(a), np.isnan(b))
        out[f] = _largest(a, b) if same_nan else float("inf")
    rc = simulate_batch(cpu, motion, early_stop=True)
    rg = simulate_batch(cpu, motion, early_stop=True, device="gpu")
    for k in ("status", "n_impacts", "n_activations", "events_truncated", "early_stopped"):
        out[k + "_differ"] = int(np.sum(rc[k] != rg[k]))
    for k in ("peak", "t_collapse", "t_unstable", "t_limit"):
        a, b = rc[k], rg[k]
        out[k] = _largest(a, b) if np.array_equal(np.isnan(a), np.isnan(b)) else float("inf")
    out["collapsed"] = int(np.sum(rc["status"] == 1))
    return out


def main(n_circ: int, n_fam: int, n_sur: int) -> None:
    from archrock.geometry import as_polygon, family_arch, oppenheim_arch
    from archrock.geometry.sampling import ArchSampler, Spreads
    from archrock.groundmotion import band_limited_noise, oppenheim_pulse

    nom = oppenheim_arch()
    pulse = oppenheim_pulse(-1.0, 0.25)
    record = band_limited_noise(6.0, 0.01, (0.5, 5.0), seed=3, pga_g=0.45)
    if n_circ:
        spans, thick, radii = ArchSampler(nom, seed=7).draw(0, n_circ)
        print(json.dumps(_compare("circular", ((spans, radii, thick, nom.density), {}), nom,
                                  pulse)), flush=True)
    if n_fam:
        pointed = family_arch("pointed", 10.0, 7.0, 1.0, 12, exact=False)
        arches = ArchSampler(pointed, Spreads(0.1, 0.1, 0.05, 5.0), seed=2).arches(0, n_fam)
        print(json.dumps(_compare("family", ((arches,), {}), pointed, record)), flush=True)
    if n_sur:
        survey = as_polygon(nom)
        arches = ArchSampler(survey, Spreads(0.0, 0.1, 0.05), seed=4).arches(0, n_sur)
        print(json.dumps(_compare("surveyed", ((arches,), {}), survey, pulse)), flush=True)


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:4]))
