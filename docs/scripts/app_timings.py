"""Timings of ``archrock app`` measured in the browser (docs/app.md) and its screenshot.

Serves the app on a free loopback port, drives Debian's headless Chromium with Playwright and
reads the page's own ``performance.now()`` measurements (``window.__app.timings``):

* slider: from the thickness slider's 'input' event to the frame after the redrawn thrust line;
* pulse: from the click on "play" to the first animation frame drawn;
* ensemble: from the click on "run" to the histogram drawn (10,000 arches, with and without
  the pulse).

Usage: python docs/scripts/app_timings.py [--shot docs/img/app.png] [--chromium /usr/bin/chromium]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time


def wait(page, expr: str, timeout: float = 600.0):
    """Poll the JS expression ``expr`` every 20 ms until it is truthy; its value (a
    TimeoutError after ``timeout`` s).  Polled with ``page.evaluate``, which the app's Content
    Security Policy (no eval) does not govern, unlike ``wait_for_function``; the browser tests
    (tests/app/test_app_browser.py) poll with it too."""
    end = time.monotonic() + timeout
    while True:
        v = page.evaluate(expr)
        if v:
            return v
        if time.monotonic() > end:
            raise TimeoutError(f"still false after {timeout:g} s: {expr}")
        time.sleep(0.02)


def summary(xs):
    xs = sorted(xs)
    return {"n": len(xs), "median_ms": round(statistics.median(xs), 1),
            "p90_ms": round(xs[int(0.9 * (len(xs) - 1))], 1), "max_ms": round(xs[-1], 1)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shot", default=None, help="PNG screenshot to write")
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--moves", type=int, default=30, help="slider moves measured")
    args = ap.parse_args()

    from playwright.sync_api import sync_playwright

    from archrock.app.server import BackgroundServer

    out = {}
    with BackgroundServer() as url, sync_playwright() as p:
        browser = p.chromium.launch(executable_path=args.chromium, headless=True,
                                    args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 1280, "height": 1000})
        page.goto(url)
        wait(page, "window.__app.redraws >= 1")
        # warm: the kernels compiled (or loaded from numba's cache) before measuring
        page.click("#play")
        wait(page, "window.__app.frames > 0")
        page.fill("#samples", "200")
        page.click("#run-ensemble")
        wait(page, "window.__app.timings.ensemble.length >= 1")

        # slider: one move at a time, each waited for
        page.evaluate("window.__app.timings.slider = []")
        for i in range(args.moves):
            value = 1.2 + 0.6 * (i % 10) / 10 + 0.01 * i
            n = page.evaluate("window.__app.timings.slider.length")
            page.fill("#thickness", f"{value:.4f}")
            wait(page, f"window.__app.timings.slider.length > {n}")
        out["slider_to_thrust_line"] = summary(page.evaluate("window.__app.timings.slider"))
        out["slider_server_part"] = summary(page.evaluate("window.__app.timings.sliderServer"
                                                          ".slice(-%d)" % args.moves))
        page.click("#oppenheim")
        wait(page, "document.getElementById('k').textContent === 'k = 0.370'")

        page.evaluate("window.__app.timings.pulse = []")
        for _ in range(5):
            n = page.evaluate("window.__app.timings.pulse.length")
            page.click("#play")
            wait(page, f"window.__app.timings.pulse.length > {n}")
            time.sleep(0.3)
        out["pulse_to_first_frame"] = summary(page.evaluate("window.__app.timings.pulse"))

        for with_pulse in (False, True):
            page.evaluate("window.__app.timings.ensemble = []")
            page.set_checked("#with-pulse", with_pulse)
            page.fill("#samples", "10000")
            page.click("#run-ensemble")
            e = wait(page, "window.__app.timings.ensemble.length && window.__app.timings.ensemble[0]")
            key = "ensemble_10000_pulse" if with_pulse else "ensemble_10000_limit_only"
            out[key] = {"browser_ms": round(e["ms"], 1), "server_s": round(e["server_s"], 3)}
        out["ensemble_text"] = page.text_content("#ensemble-result")

        if args.shot:
            page.check("#show-range")
            page.fill("#samples", "2000")
            page.click("#run-ensemble")
            wait(page, "window.__app.timings.ensemble.length >= 2")
            page.fill("#curve-samples", "30")
            page.click("#run-curve")
            wait(page, "document.getElementById('curve-svg').getAttribute('data-points')")
            page.select_option("#exaggerate", "5")
            page.evaluate("window.__app.frame = -1")
            page.click("#play")
            wait(page, "window.__app.frame >= 40")
            page.screenshot(path=args.shot, full_page=True)
        browser.close()
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
