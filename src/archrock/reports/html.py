"""One self-contained HTML report of an :class:`~archrock.studies.assessment.Assessment`, its JSON, and a
printable PDF through headless Chromium when it is installed.

Self-contained: the style sheet is inline and every figure is a PNG embedded as a ``data:`` URI,
so the file opens without a network; references are text, never links.  Every string from the
sections is escaped (:func:`html.escape`).  Figures: ``FIGURES[kind](payload) -> matplotlib
Figure``; a section's :class:`~archrock.studies.assessment.Figure` block names its kind.
"""

from __future__ import annotations

import base64
import html
import io
import json
import math
import shutil
import subprocess
import tempfile
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from ..studies.assessment import Figure, Paragraph, Table
from ..errors import ArchInputError, ArchrockError

__all__ = ["render_html", "write_report", "write_pdf", "find_chromium", "FIGURES",
           "CHROMIUM_FLAGS"]

#: Flags for a headless Chromium that reaches nothing outside the machine.
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync")


# ---------------------------------------------------------------------------- figures
def _fig_arch(arch):
    from .plots import draw_arch, new_figure

    fig, axes = new_figure(1, 1, figsize=(6.4, 3.4))
    ax = axes[0][0]
    draw_arch(ax, arch, label_joints=True)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, lw=0.3, alpha=0.4)
    return fig


def _fig_limit(lim):
    from .plots import new_figure, plot_limit

    fig, axes = new_figure(1, 2, figsize=(12.6, 4.6))
    for ax, d in zip(axes[0], ("l", "r")):
        plot_limit(lim, d, ax=ax)
    return fig


def _fig_response(res):
    from .plots import new_figure, plot_ground_motion, plot_response

    fig, axes = new_figure(2, 1, figsize=(7.0, 5.2), sharex=True,
                           gridspec_kw={"height_ratios": [1, 2]})
    t_end = float(res.time[-1])
    plot_ground_motion(res.motion, axes[0][0], t_end=t_end)
    plot_response(res, axes[1][0])
    axes[1][0].legend(fontsize=7, frameon=False, loc="best")
    return fig


def _fig_curves(payload):
    from .plots import plot_collapse_curve

    curve, band = payload
    return plot_collapse_curve(curve, None, band=band)


def _fig_fragility(payload):
    from .plots import plot_fragility

    fit, stripes, ida = payload
    return plot_fragility(fit, stripes, None, ida=ida)


def _same_curves(a, b, rtol: float = 1e-6) -> bool:
    """Whether two directions of a code check draw the same lines (a symmetric arch)."""
    try:
        if not (np.allclose(a.curve_d_star, b.curve_d_star, rtol=rtol, atol=0)
                and np.allclose(a.curve_a_star, b.curve_a_star, rtol=rtol, atol=0)):
            return False
    except ValueError:  # curves of different lengths
        return False
    keys = ("d0_star", "a0_star", "ds_star", "as_star", "du_star", "ts")
    if not all(math.isclose(getattr(a, k), getattr(b, k), rel_tol=rtol) for k in keys):
        return False
    da = a.checks.get("nonlinear", {}).get("demand_m")
    db = b.checks.get("nonlinear", {}).get("demand_m")
    return (da is None) == (db is None) and (da is None or math.isclose(da, db, rel_tol=rtol))


def _fig_codecheck(res):
    """Capacity curves a*(d*) [m/s^2 vs m], the code's straight lines, d_u*, d_s* with the
    secant line, and the demand S_De(T_s) when a spectrum is given.  Where both mechanisms
    draw the same lines (a symmetric arch) they are drawn and listed once, as "M_l = M_r":
    drawn twice, the second hid the first and the legend listed curves that cannot be seen."""
    from .plots import new_figure

    fig, axes = new_figure(1, 1, figsize=(6.6, 4.2))
    ax = axes[0][0]
    colors = {"l": "#1f4e9c", "r": "#c0392b"}
    dirs = list(res.directions)
    names = {c.direction: f"$M_{c.direction}$" for c in dirs}
    if len(dirs) == 2 and _same_curves(dirs[0], dirs[1]):
        names = {dirs[0].direction: "$M_l$ = $M_r$"}
        dirs = dirs[:1]
        colors = {dirs[0].direction: "#1f4e9c"}
    for c in dirs:
        col, name = colors[c.direction], names[c.direction]
        ax.plot(c.curve_d_star, c.curve_a_star, "-", color=col, lw=1.6,
                label=f"{name}: exact four-link curve")
        ax.plot([0, c.d0_star], [c.a0_star, 0], ":", color=col, lw=1.0,
                label=f"{name}: code's straight line")
        ax.plot([0, c.ds_star], [0, c.as_star], "--", color=col, lw=0.9, alpha=0.8,
                label=f"{name}: secant, $T_s$ = {c.ts:.2f} s")
        ax.axvline(c.du_star, color=col, lw=0.8, alpha=0.6,
                   label=f"{name}: $d_u^*$ = {c.du_star:.3f} m")
        if "nonlinear" in c.checks:
            dem = c.checks["nonlinear"]["demand_m"]
            ax.plot([dem], [0], "v", color=col, ms=9, clip_on=False,
                    label=f"{name}: demand $S_{{De}}(T_s)$ = {dem:.3f} m")
    ax.set_xlabel("spectral displacement $d^*$ [m]")
    ax.set_ylabel("spectral acceleration $a^*$ [m/s$^2$]")
    ax.set_xlim(0, None)
    ax.set_ylim(0, None)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, frameon=False)
    return fig


def _fig_defects(res):
    """The defect map, drawn by archrock.reports.plots when it has a function for it."""
    from . import plots

    draw = getattr(plots, "plot_defect_map", None)
    if draw is None:
        return None
    return draw(res)


def _fig_selection(payload):
    """The records chosen for the site spectrum (reports.selection's figure): payload
    (selection, the motions it was made from, the target spectrum)."""
    from .selection import selection_figure

    selection, motions, spectrum = payload
    return selection_figure(selection, motions=motions, spectrum=spectrum)


FIGURES = {"arch": _fig_arch, "limit": _fig_limit, "response": _fig_response,
           "curves": _fig_curves, "fragility": _fig_fragility, "codecheck": _fig_codecheck,
           "defects": _fig_defects, "selection": _fig_selection}


def _png_data_uri(fig, dpi: int = 110) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


# ---------------------------------------------------------------------------- HTML
_CSS = """
body{font-family:-apple-system,"Segoe UI",Helvetica,Arial,sans-serif;max-width:60rem;margin:2rem auto;
padding:0 1rem;color:#222;line-height:1.45}
h1{font-size:1.6rem;margin-bottom:.2rem} h2{font-size:1.25rem;border-bottom:1px solid #ccc;
padding-bottom:.2rem;margin-top:2.2rem} .meta{color:#666;font-size:.9rem}
table{border-collapse:collapse;margin:.8rem 0;font-size:.88rem} th,td{border:1px solid #ccc;
padding:.25rem .5rem;text-align:left;vertical-align:top} th{background:#f2f4f7}
figure{margin:1rem 0;text-align:center} figure img{max-width:100%;height:auto}
figcaption{font-size:.85rem;color:#555} .note{color:#8a5a00} nav ol{columns:2;font-size:.9rem}
caption{caption-side:bottom;font-size:.8rem;color:#666;text-align:left}
.verdict{border-left:4px solid #888;padding:.4rem .8rem;background:#f6f6f6}
.verdict.pass{border-color:#2e7d32} .verdict.fail{border-color:#c62828}
h1,h2,h3{break-after:avoid;page-break-after:avoid} p,figcaption{orphans:3;widows:3}
@page{size:A4;margin:18mm 15mm 20mm 15mm;
@bottom-center{content:"page " counter(page) " of " counter(pages);font-size:9pt;color:#555}}
@media print{body{margin:0;max-width:none;font-size:10pt} h2{page-break-before:auto}
figure,table,.verdict,.keep{break-inside:avoid;page-break-inside:avoid}
h2+p,h2+table,h2+figure{break-before:avoid;page-break-before:avoid}
nav{display:none}}
"""


def _cell(v) -> str:
    if isinstance(v, float):
        v = f"{v:.6g}" if math.isfinite(v) else "-"
    return html.escape(str(v))


def _figure_html(block, figures: dict, key: str, progress=None, not_drawn=None) -> str:
    """A Figure block as an embedded PNG; a drawing that raises is replaced by the line 'figure
    not drawn: <reason>' (a warning in ``progress``, the pair appended to ``not_drawn``): a
    figure is an illustration of numbers already in the text and the JSON, so it never ends
    the report."""
    draw = figures.get(block.kind)
    try:
        fig = None if draw is None else draw(block.payload)
        uri = None if fig is None else _png_data_uri(fig)
    except Exception as exc:  # noqa: BLE001 -- any failure of a drawing is reported, by design
        why = f"{type(exc).__name__}: {' '.join(str(exc).split()) or 'no message'}"
        if progress:
            progress(f"  warning: figure {key}/{block.kind} not drawn ({why})")
        if not_drawn is not None:
            not_drawn.append({"section": key, "figure": block.kind, "reason": why})
        return f'<p class="note">figure not drawn: {html.escape(why)}</p>'
    if uri is None:
        return (f'<p class="note">Figure "{html.escape(block.kind)}": no drawing function in '
                f'this installation.</p>')
    alt = html.escape(block.caption, quote=True)
    return (f'<figure id="fig-{html.escape(key)}-{html.escape(block.kind)}"><img alt="{alt}" '
            f'src="{uri}"><figcaption>{html.escape(block.caption)}</figcaption></figure>')


def _block_html(block, figures: dict, key: str, progress=None, not_drawn=None) -> str:
    if isinstance(block, Paragraph):
        return f"<p>{html.escape(block.text)}</p>"
    if isinstance(block, Table):
        head = "".join(f"<th>{_cell(h)}</th>" for h in block.header)
        rows = "".join("<tr>" + "".join(f"<td>{_cell(c)}</td>" for c in r) + "</tr>"
                       for r in block.rows)
        cap = f"<caption>{html.escape(block.caption)}</caption>" if block.caption else ""
        return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>"
    if isinstance(block, Figure):
        return _figure_html(block, figures, key, progress, not_drawn)
    raise ArchInputError(f"report block: {type(block).__name__}; allowed Paragraph, Table, Figure")


def render_html(assessment, figures: dict | None = None, progress=None,
                not_drawn: list | None = None) -> str:
    """The report as one HTML document (str); the figures that could not be drawn are said in
    their place and appended to ``not_drawn`` (section, figure, reason)."""
    figs = FIGURES if figures is None else figures
    arch = assessment.arch
    when = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    parts = [
        "<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
        f"<title>archrock assessment: {html.escape(arch.name)}</title>",
        f"<style>{_CSS}</style></head><body>",
        f"<h1>Seismic assessment of the masonry arch “{html.escape(arch.name)}”</h1>",
        f'<p class="meta">archrock {html.escape(assessment.version)}; written {when}; computed '
        f"in {assessment.seconds:.1f} s. The numbers behind every section are in the JSON "
        f"file written beside this report.</p>",
    ]
    head = assessment.headline
    verdict = assessment.verdict
    parts.append(f'<h2 id="summary">Summary</h2><p class="verdict {verdict["status"]}"><strong>'
                 f'Verdict:</strong> {html.escape(verdict["text"])}</p>')
    if head:
        parts.append("<table><tbody>" + "".join(
            f"<tr><th>{_cell(k)}</th><td>{_cell(v)}</td></tr>" for k, v in head) + "</tbody></table>")
    parts.append("<nav><ol>" + "".join(
        f'<li><a href="#{html.escape(s.key)}">{html.escape(s.title)}</a></li>'
        for s in assessment.sections) + "</ol></nav>")
    for s in assessment.sections:
        if progress:
            progress(f"  drawing {s.key}")
        blocks = [_block_html(b, figs, s.key, progress, not_drawn) for b in s.blocks]
        # the heading and the section's first block in one unbreakable box: Chromium's printing
        # does not honour break-after: avoid on its own, and left headings alone at page bottoms
        head = (f'<div class="keep"><h2>{html.escape(s.title)}</h2>'
                f'{blocks[0] if blocks else ""}</div>')
        parts.append(f'<section id="{html.escape(s.key)}">{head}{"".join(blocks[1:])}</section>')
    parts.append("</body></html>")
    return "\n".join(parts)


def _json_safe(obj):
    if isinstance(obj, dict):
        return {str(k): _json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_json_safe(v) for v in obj]
    if isinstance(obj, np.ndarray) or isinstance(obj, np.generic):
        return _json_safe(obj.tolist())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def write_report(assessment, html_path, json_path=None, progress=None) -> tuple[Path, Path]:
    """Write the HTML report and its JSON (default: the HTML's name with .json); returns both
    paths."""
    hp = Path(html_path)
    if hp.suffix.lower() not in (".html", ".htm"):
        raise ArchInputError(f"report: {str(html_path)!r}; allowed a file name ending in .html")
    jp = hp.with_suffix(".json") if json_path is None else Path(json_path)
    not_drawn: list = []
    text = render_html(assessment, progress=progress, not_drawn=not_drawn)
    data = _json_safe(assessment.to_dict())
    if not_drawn:  # the JSON says which figures the HTML lacks, and why
        data["figures_not_drawn"] = not_drawn
    try:
        hp.parent.mkdir(parents=True, exist_ok=True)
        hp.write_text(text, encoding="utf-8")
        jp.write_text(json.dumps(data, indent=1, allow_nan=False) + "\n", encoding="utf-8")
    except OSError as exc:
        raise ArchInputError(f"report: cannot write {hp} ({exc.strerror or exc})") from None
    return hp, jp


def find_chromium() -> str | None:
    """The path of a Chromium/Chrome executable on PATH, or None."""
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        p = shutil.which(name)
        if p:
            return p
    return None


def write_pdf(html_path, pdf_path, timeout: float = 120.0) -> Path:
    """Print the HTML report to PDF with headless Chromium (``--print-to-pdf``): A4 pages with
    "page i of n" at the bottom (the style sheet's ``@page`` rule and its ``@bottom-center``
    margin box; Chromium's own header and footer, with the file's path and the date, are
    switched off), headings kept with what follows them (``break-after: avoid``). Raises
    :class:`ArchrockError` with what to install when no Chromium is on PATH."""
    exe = find_chromium()
    if exe is None:
        raise ArchrockError("--pdf: needs Chromium on PATH (Debian/Ubuntu: apt-get install "
                            "chromium); the HTML report was written and prints to PDF from any "
                            "browser")
    src = Path(html_path).resolve()
    out = Path(pdf_path).resolve()
    with tempfile.TemporaryDirectory() as profile:
        cmd = [exe, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "--no-pdf-header-footer",
               f"--print-to-pdf={out}", src.as_uri()]
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            raise ArchrockError(f"--pdf: Chromium did not finish within {timeout:g} s") from None
    if proc.returncode != 0 or not out.exists() or out.stat().st_size == 0:
        raise ArchrockError(f"--pdf: Chromium failed (exit {proc.returncode}): "
                            f"{(proc.stderr or '').strip()[-300:]}")
    return out


def environment_note() -> str:
    """One line on what the PDF step will use (for progress output)."""
    exe = find_chromium()
    return f"Chromium: {exe}" if exe else "Chromium: not found"

