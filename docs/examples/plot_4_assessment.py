"""
# The assessment report

`archrock assess` gathers every analysis of one arch in a self-contained HTML report. Here the
same from Python on Oppenheim's arch, kept small for the site's build (six of its sections, no
irregular arches, two pulse durations, a coarse amplitude grid): the report's summary lines and
its collapse-acceleration figure. docs/assess.md lists every section.
"""

# %%
import tempfile
from pathlib import Path

from archrock.geometry import oppenheim_arch
from archrock.reports.html import write_report
from archrock.studies.assessment import (AssessConfig, assess, section_codecheck,
                                         section_curves, section_geometry, section_impact,
                                         section_limit, section_response)

config = AssessConfig(samples=0, durations=(0.2, 0.5), n_scan=12)
sections = [section_geometry, section_limit, section_impact, section_response, section_curves,
            section_codecheck]
report = assess(oppenheim_arch(), config, sections=sections)
for label, value in report.headline:
    print(f"{label}: {value}")

with tempfile.TemporaryDirectory() as tmp:
    html, _ = write_report(report, Path(tmp) / "oppenheim.html")
    print(f"report: {html.stat().st_size / 1e6:.2f} MB of self-contained HTML")

# %%
# The collapse-acceleration curve of the report's section "Collapse-acceleration curve",
# drawn from the objects the section carries.
import matplotlib.pyplot as plt

from archrock.reports.plots import plot_collapse_curve

figure = next(b for b in report.section("curves").blocks if getattr(b, "kind", "") == "curves")
curve, band = figure.payload
fig, ax = plt.subplots(figsize=(7, 4.4))
plot_collapse_curve(curve, None, band=band, ax=ax)
plt.show()
