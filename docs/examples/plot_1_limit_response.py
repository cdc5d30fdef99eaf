"""
# Oppenheim's arch: collapse mechanisms and the response to the paper's pulse

The paper's Fig. 3 and Fig. 4 (a) in one figure: the mechanisms M_l and M_r of Oppenheim's
arch (R = 10 m, embrace 157.5 deg, t = 1.5 m, 7 voussoirs) with their hinges and lines of thrust,
and the arch's rotation under the paper's Oppenheim pulse (a = -1 g, t_p = 0.2 s).
"""

# %%
# Limit analysis: the kinematic enumeration and the static LP must agree.
import matplotlib.pyplot as plt

from archrock.dynamics.response import prepare, respond
from archrock.geometry import oppenheim_arch
from archrock.groundmotion import oppenheim_pulse
from archrock.reports.plots import plot_limit, plot_response
from archrock.statics.limit import limit_analysis

arch = oppenheim_arch()
res = limit_analysis(arch)
print(f"k_l = {res.k_l:.4f}, k_r = {res.k_r:.4f}, |kinematic - static| = {res.discrepancy:.1e}")

# %%
# The four-link model with the paper's impact law, under the paper's pulse.
model = prepare(arch, "paper")
response = respond(model, oppenheim_pulse(-1.0, 0.2), t_end=3.0)
print(f"c_v = {model.impact.l_to_r:.4f}; outcome: {response.status}, "
      f"peak rotation {response.peak:.4f} rad")

fig = plt.figure(figsize=(13, 8.5))
grid = fig.add_gridspec(2, 2, height_ratios=[1.1, 1])
plot_limit(res, direction="l", ax=fig.add_subplot(grid[0, 0]))
plot_limit(res, direction="r", ax=fig.add_subplot(grid[0, 1]))
ax = fig.add_subplot(grid[1, :])
plot_response(response, ax, label="Oppenheim's arch")
ax.legend()
fig.tight_layout()
plt.show()
