"""The Sobol indices of docs/ensemble.md: Oppenheim's arch with the paper's spreads, by kind of
irregularity (with the collapse under the paper's pulse) and by voussoir (run from the
repository root: ``python docs/scripts/sensitivity.py``; a few minutes on 2 cores)."""

import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from archrock.geometry import oppenheim_arch  # noqa: E402
from archrock.reports.sensitivity import format_sensitivity  # noqa: E402
from archrock.geometry.sampling import DEFAULT_SPREADS  # noqa: E402
from archrock.studies.sensitivity import sobol_indices  # noqa: E402

arch = oppenheim_arch()
t0 = time.perf_counter()
by_kind = sobol_indices(arch, DEFAULT_SPREADS, 4096, by="kind", seed=0)
print(format_sensitivity(by_kind))
print(f"[{time.perf_counter() - t0:.0f} s]\n")
t0 = time.perf_counter()
by_voussoir = sobol_indices(arch, DEFAULT_SPREADS, 2048, by="voussoir", seed=0)
print(format_sensitivity(by_voussoir))
print(f"[{time.perf_counter() - t0:.0f} s]")

fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), width_ratios=[3, 7])
for ax, res in zip(axes, (by_kind, by_voussoir)):
    outs = list(res.outputs)
    G = len(res.groups)
    w = 0.8 / len(outs)
    for o, out in enumerate(outs):
        x = np.arange(G) + (o - (len(outs) - 1) / 2) * w
        ax.bar(x, res.ST[o], w, color=f"C{o}", alpha=0.35, yerr=res.ST_conf[o], capsize=2,
               error_kw={"lw": 0.7})
        ax.bar(x, res.S1[o], w * 0.5, color=f"C{o}", yerr=res.S1_conf[o], capsize=2,
               error_kw={"lw": 0.7}, label=f"{out}: S1 (dark), ST (light)")
    ax.set_xticks(np.arange(G), [g.replace("voussoir ", "v") for g in res.groups])
    ax.set_ylim(0, 1.05)
    ax.grid(True, axis="y", alpha=0.3)
    ax.set_title(f"by {res.by}: N = {res.samples}, {res.runs} arches, 95% intervals", fontsize=9)
axes[0].set_ylabel("Sobol index")
axes[1].legend(fontsize=7.5, frameon=False, ncol=2)
fig.suptitle("Oppenheim's arch, spreads 0.1 / 0.1 / 0.05, collapse under the paper's pulse",
             fontsize=10)
fig.tight_layout()
fig.savefig("docs/figures/sobol_oppenheim.png", dpi=130)
print("wrote docs/figures/sobol_oppenheim.png")
