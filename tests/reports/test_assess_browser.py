"""The report in a real browser (headless Chromium from Debian's packages): the page loads
without script errors, every figure decodes, nothing is fetched from a network.  Skipped where
/usr/bin/chromium is absent (apt-get install chromium)."""

import re
import subprocess
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")
CHROMIUM = Path("/usr/bin/chromium")
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not CHROMIUM.exists(), reason="needs /usr/bin/chromium")]

from archrock.studies.assessment import AssessConfig, assess  # noqa: E402
from archrock.geometry import oppenheim_arch  # noqa: E402
from archrock.reports.html import CHROMIUM_FLAGS, write_pdf, write_report  # noqa: E402

# Run after load: count the images the browser decoded and every error the page raised.
PROBE = """<script>
window.__errors = [];
window.addEventListener('error', e => window.__errors.push(String(e.message || e.type)), true);
window.addEventListener('load', () => {
  const imgs = [...document.images];
  const ok = imgs.filter(i => i.complete && i.naturalWidth > 0).length;
  const res = performance.getEntriesByType('resource').map(r => r.name)
      .filter(n => !n.startsWith('data:'));
  document.body.setAttribute('data-images', ok + '/' + imgs.length);
  document.body.setAttribute('data-errors', String(window.__errors.length));
  document.body.setAttribute('data-fetched', String(res.length));
});
</script>"""


def _chromium(tmp_path, *args, timeout=120):
    cmd = [str(CHROMIUM), *CHROMIUM_FLAGS, f"--user-data-dir={tmp_path / 'profile'}",
           "--host-resolver-rules=MAP * ~NOTFOUND", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("browser")
    cfg = AssessConfig(durations=(0.3, 0.7), n_scan=12, samples=2)
    html_path, _ = write_report(assess(oppenheim_arch(), cfg), out / "report.html")
    return out, html_path


def test_page_loads_with_every_figure(report):
    out, html_path = report
    text = html_path.read_text(encoding="utf-8")
    n_img = text.count("<img")
    probe = out / "probe.html"
    probe.write_text(text.replace("<head>", "<head>" + PROBE, 1), encoding="utf-8")
    proc = _chromium(out, "--dump-dom", probe.as_uri())
    assert proc.returncode == 0, proc.stderr[-500:]
    dom = proc.stdout
    m = re.search(r'<body[^>]*data-images="(\d+)/(\d+)"[^>]*>', dom)
    assert m, dom[:500]
    assert int(m.group(1)) == int(m.group(2)) == n_img == 6  # + defect map
    assert 'data-errors="0"' in dom and 'data-fetched="0"' in dom
    srcs = re.findall(r'<img[^>]*\ssrc="([^"]*)"', dom)
    assert len(srcs) == n_img and all(s.startswith("data:image/png;base64,") for s in srcs)


def test_screenshot_and_pdf(report):
    out, html_path = report
    shot = out / "first_page.png"
    proc = _chromium(out, "--hide-scrollbars", "--window-size=1100,1500",
                     f"--screenshot={shot}", html_path.as_uri())
    assert proc.returncode == 0 and shot.stat().st_size > 20_000
    pdf = write_pdf(html_path, out / "report.pdf")
    head = pdf.read_bytes()[:5]
    assert head == b"%PDF-" and pdf.stat().st_size > 50_000
