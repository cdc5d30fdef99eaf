"""
# A small fragility curve

Incremental dynamic analysis of Oppenheim's arch and four irregular arches around it under
four synthetic accelerograms (seeded band-limited noise: no record suite ships with
archrock), and the lognormal fragility fitted to the first collapses. Kept small so the site
builds quickly; docs/curves.md gives the method and full-size runs.
"""

# %%
import matplotlib.pyplot as plt
import numpy as np
from scipy.signal import butter, sosfilt

from archrock.dynamics.response import prepare
from archrock.geometry import oppenheim_arch
from archrock.groundmotion import from_samples
from archrock.reports.plots import plot_fragility
from archrock.studies.ida import ida, random_models


def noise_record(seed, duration=6.0, dt=0.01, pga_g=0.3):
    """Band-limited (0.3-2 Hz) noise with a smooth envelope, scaled to ``pga_g`` [g]."""
    rng = np.random.default_rng(seed)
    n = int(duration / dt)
    x = sosfilt(butter(2, [0.3, 2.0], btype="band", fs=1 / dt, output="sos"),
                rng.standard_normal(n))
    x *= np.sin(np.pi * np.arange(n) * dt / duration) ** 2
    return from_samples(x * pga_g / np.max(np.abs(x)), dt, name=f"noise {seed}")


records = [noise_record(s) for s in range(1, 5)]
arch = oppenheim_arch()
models = [prepare(arch)] + list(random_models(arch, 4, seed=0))
result = ida(records, models, np.geomspace(0.5, 12.0, 10), tol=1e-2)
fit = result.fit
print(f"{len(result.curves)} IDA curves; median {fit.theta:.2f} g, dispersion {fit.beta:.2f}")

# %%
# The fitted curve with the first collapses as an empirical distribution (drawn on a
# pyplot axis, so that the gallery collects the figure).
fig, ax = plt.subplots(figsize=(6.4, 4.4))
plot_fragility(fit, ida=result, ax=ax)
plt.show()
