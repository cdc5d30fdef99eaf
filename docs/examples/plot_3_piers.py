"""
# An arch on piers

A semicircle (span 10 m on the centreline, t = 0.8 m, 9 voussoirs) on two rectangular piers
4 m high and 2 m wide: the piers take part in the mechanism, the arch's capacity drops and a
hinge opens at a pier's foot. docs/piers.md explains the model.
"""

# %%
import matplotlib.pyplot as plt

from archrock.geometry import nominal_arch, with_piers
from archrock.reports.plots import plot_limit
from archrock.statics.limit import limit_analysis

arch = nominal_arch(radius=5.0, embrace_deg=180.0, thickness=0.8, voussoirs=9)
on_piers = with_piers(arch, height=4.0, width=2.0)
alone, piers = limit_analysis(arch), limit_analysis(on_piers)
print(f"on rigid ground k = {alone.k:.4f}; on piers 4 m x 2 m k = {piers.k:.4f}")

fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
plot_limit(alone, direction="l", ax=axes[0])
plot_limit(piers, direction="l", ax=axes[1])
fig.tight_layout()
plt.show()
