"""``archrock app``'s guards measured on the real command (docs/app.md, "Security and limits").

Starts ``archrock app --no-browser --port 0`` (numba's cache in a new empty folder: the kernels
compile, as on a first launch), then prints one line each:

* refusals: the status codes of a cross-origin POST, a text/plain body, a call without the
  token and a foreign Host;
* cancel: seconds from the cancel request of a 20,000-arch ensemble, started while the kernels
  compile, to the job's "cancelled" and its worker process gone;
* statics: /api/limit latency p50/p95 [s] (``--requests`` calls, ``--concurrent`` at a time)
  with and without an ensemble running;
* upload: the server's peak memory (VmHWM) before and after a ~20 MB two-column record;
* ctrl-c: seconds from SIGINT (a job running) to the server's exit.

Usage: python benchmarks/bench_app.py [--requests 40] [--concurrent 4] [--warm]
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import httpx

ARCH = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
PULSE = {"kind": "oppenheim", "amplitude": -1.0, "duration": 0.2}


def children(pid: int) -> list[int]:
    """Child process ids (Linux /proc)."""
    try:
        return [int(c) for c in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except OSError:
        return []


def alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().split(")")[-1].split()[0]
    except OSError:
        return False
    return state != "Z"


def peak_mb(pid: int) -> float:
    m = re.search(r"VmHWM:\s+(\d+) kB", Path(f"/proc/{pid}/status").read_text())
    return int(m.group(1)) / 1024


def percentiles(xs):
    xs = sorted(xs)
    return statistics.median(xs), xs[min(len(xs) - 1, round(0.95 * (len(xs) - 1)))]


class App:
    """The command in a subprocess, its URL, token and an httpx client sending them."""

    def __init__(self, cache: str | None):
        env = {**os.environ}
        if cache:
            env["NUMBA_CACHE_DIR"] = cache
        self.proc = subprocess.Popen([sys.executable, "-m", "archrock", "app", "--no-browser",
                                      "--port", "0"], env=env, stderr=subprocess.PIPE,
                                     text=True)
        line = self.proc.stderr.readline()
        self.url = re.search(r"(http://127\.0\.0\.1:\d+)/", line).group(1)
        page = httpx.get(self.url + "/", timeout=60).text
        self.token = re.search(r'name="archrock-token" content="([^"]+)"', page).group(1)
        self.client = httpx.Client(base_url=self.url, timeout=600, headers={
            "Origin": self.url, "X-Archrock-Token": self.token})

    def job(self, body) -> str:
        r = self.client.post("/api/ensemble", json=body)
        r.raise_for_status()
        return r.json()["id"]


def refusals(app: App) -> dict:
    body = {"arch": ARCH, "samples": 20000}
    c = httpx.Client(base_url=app.url, timeout=60)
    return {
        "cross-origin": c.post("/api/ensemble", json=body, headers={
            "Origin": "http://evil.example", "X-Archrock-Token": app.token}).status_code,
        "text/plain": app.client.post("/api/ensemble", content=b"{}", headers={
            "Content-Type": "text/plain"}).status_code,
        "no token": c.post("/api/ensemble", json=body,
                           headers={"Origin": app.url}).status_code,
        "foreign host": app.client.get("/api/limits", headers={"Host": "testserver"}).status_code,
    }


def cancel_time(app: App, wait_s: float) -> float:
    """Cancel a 20,000-arch ensemble ``wait_s`` after its start (its kernels compiling): the
    seconds until it reads "cancelled" and its worker process is gone."""
    worker = children(app.proc.pid)
    job = app.job({"arch": ARCH, "samples": 20000})
    time.sleep(wait_s)
    t0 = time.perf_counter()
    app.client.post(f"/api/jobs/{job}/cancel", json={})
    while app.client.get(f"/api/jobs/{job}").json()["state"] == "running" or \
            any(alive(p) for p in worker):
        time.sleep(0.01)
    return time.perf_counter() - t0


def statics(app: App, n: int, concurrent: int) -> tuple[float, float]:
    def one(_):
        t0 = time.perf_counter()
        r = app.client.post("/api/limit", json={"arch": ARCH})
        assert r.status_code == 200, r.text
        return time.perf_counter() - t0

    with ThreadPoolExecutor(concurrent) as ex:
        return percentiles(list(ex.map(one, range(n))))


def wait_worker_ready(app: App, timeout: float = 900.0) -> None:
    """Run a 10-arch ensemble to its end (the worker's kernels compiled)."""
    job = app.job({"arch": ARCH, "samples": 10, "pulse": PULSE})
    end = time.monotonic() + timeout
    while app.client.get(f"/api/jobs/{job}").json()["state"] == "running":
        if time.monotonic() > end:
            raise TimeoutError("the worker did not finish a 10-arch ensemble")
        time.sleep(0.1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--requests", type=int, default=40)
    ap.add_argument("--concurrent", type=int, default=4)
    ap.add_argument("--cancel-after", type=float, default=1.0,
                    help="seconds between the ensemble's start and its cancel")
    ap.add_argument("--warm", action="store_true", help="use numba's own cache (no compile)")
    args = ap.parse_args()

    with tempfile.TemporaryDirectory(prefix="archrock-bench-app-") as tmp:
        app = App(None if args.warm else tmp)
        try:
            print("refusals:", refusals(app), flush=True)
            print(f"cancel: {cancel_time(app, args.cancel_after):.2f} s (20,000-arch ensemble "
                  f"cancelled {args.cancel_after:g} s after its start, "
                  f"{'warm' if args.warm else 'kernels compiling'})", flush=True)
            app.client.post("/api/limit", json={"arch": ARCH})  # the server's statics warm
            wait_worker_ready(app)  # the fresh worker's kernels too: "idle" is idle
            idle = statics(app, args.requests, args.concurrent)
            job = app.job({"arch": ARCH, "samples": 20000, "pulse": PULSE})
            busy = statics(app, args.requests, args.concurrent)
            state = app.client.get(f"/api/jobs/{job}").json()
            print(f"statics: /api/limit p50 {idle[0]:.3f} s, p95 {idle[1]:.3f} s idle; "
                  f"p50 {busy[0]:.3f} s, p95 {busy[1]:.3f} s with an ensemble running "
                  f"({args.requests} requests, {args.concurrent} at a time; job "
                  f"{state['state']}, {state['done']}/{state['total']})", flush=True)
            app.client.post(f"/api/jobs/{job}/cancel", json={})

            rec = Path(tmp) / "big.txt"
            with open(rec, "w") as f:
                i = 0
                while f.tell() < 19_900_000:
                    f.write(f"{i * 0.001:.3f} {0.1 * ((i * 7919) % 1000 - 500) / 500:.6f}\n")
                    i += 1
            before = peak_mb(app.proc.pid)
            with open(rec, "rb") as f:
                r = app.client.post("/api/record?name=big.txt&units=g", content=f, headers={
                    "Content-Type": "application/octet-stream"})
            after = peak_mb(app.proc.pid)
            print(f"upload: {rec.stat().st_size / 1e6:.1f} MB record ({i:,} samples, HTTP "
                  f"{r.status_code}): server peak memory {before:.0f} MB before, {after:.0f} MB "
                  f"after", flush=True)

            job = app.job({"arch": ARCH, "samples": 20000, "pulse": PULSE})
            worker = children(app.proc.pid)
            time.sleep(0.5)
            t0 = time.perf_counter()
            app.proc.send_signal(signal.SIGINT)
            app.proc.wait(60)
            took = time.perf_counter() - t0
            left = [p for p in worker if alive(p)]
            print(f"ctrl-c: server exited in {took:.2f} s (a job running); worker processes "
                  f"left: {len(left)}", flush=True)
        finally:
            if app.proc.poll() is None:
                app.proc.kill()


if __name__ == "__main__":
    main()
