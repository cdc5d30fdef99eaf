"""The figures and numbers of docs/codecheck.md and docs/assess.md (run from the repository root:
``PYTHONPATH=src python docs/scripts/assess_figures.py``; about a minute): the code check of
Oppenheim's arch and its capacity-curve figure, the report of ``archrock assess`` on Oppenheim's
arch with its wall time, and a screenshot of the report's first page (headless Chromium, when
/usr/bin/chromium is installed)."""

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from archrock.studies.codecheck import (CodeCheckConfig, SiteSpectrum, block_kinematics,  # noqa: E402
                                code_check, kinematic_check)
from archrock.geometry import oppenheim_arch  # noqa: E402
from archrock.reports.codecheck import format_codecheck  # noqa: E402
from archrock.reports.html import CHROMIUM_FLAGS, FIGURES  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
FIG = ROOT / "docs" / "figures"
SITE = SiteSpectrum.ntc(0.25, 2.4, 0.3, "B")

res = code_check(oppenheim_arch(), config=CodeCheckConfig(spectrum=SITE))
print(format_codecheck(res))
FIGURES["codecheck"](res).savefig(FIG / "codecheck_oppenheim.png", dpi=120)
blk = kinematic_check(block_kinematics(1.0, 4.0, 1000.0), CodeCheckConfig(fc=1.0))
print(f"block 1 x 4 m, FC 1: alpha_0 {blk.alpha_0:.4f}, M*/m {blk.m_star / 1000:.4f}, "
      f"d_0* {blk.d0_star:.4f} m, a_s* {blk.as_star:.4f} m/s^2 (line {blk.as_star_linear:.4f}), "
      f"T_s {blk.ts:.4f} s")

out = Path(tempfile.mkdtemp())
t0 = time.perf_counter()
subprocess.run([sys.executable, "-m", "archrock", "assess", "--out", str(out / "oppenheim.html"),
                "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3", "--soil", "B"], check=True)
print(f"archrock assess on Oppenheim's arch: {time.perf_counter() - t0:.1f} s wall")
exe = shutil.which("chromium")
if exe:
    subprocess.run([exe, *CHROMIUM_FLAGS, f"--user-data-dir={out / 'profile'}", "--hide-scrollbars",
                    "--window-size=1100,1500",
                    f"--screenshot={FIG / 'assess_report_first_page.png'}",
                    (out / "oppenheim.html").as_uri()], check=True, capture_output=True)
    print("wrote docs/figures/assess_report_first_page.png")
else:
    print("no chromium on PATH: screenshot not taken")
