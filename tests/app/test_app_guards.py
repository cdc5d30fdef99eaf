"""``archrock app``'s guards: only its own page drives it (Host, Origin/Referer, the launch
token, JSON bodies), jobs are cancelled at once in their worker process, statics are answered
while a job runs, bodies are read under a cap, and the blocks of piers are not called voussoirs.
"""

import contextlib
import re
import time

import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")
pytest.importorskip("pandas")

from archrock.app import api, uploads  # noqa: E402
from archrock.app.jobs import Jobs  # noqa: E402

OPPENHEIM = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
ENSEMBLE = {"arch": OPPENHEIM, "samples": 20000}
EVIL = "http://evil.example"
ORIGIN = "http://127.0.0.1:8765"  # the conftest's client: the app made for that address


def _stuck(req, progress, cancelled):
    """A job that never looks at its cancel flag (as a kernel being compiled): sleeps ``req``
    seconds."""
    progress(1, 2)  # started: past the worker's imports
    time.sleep(req)
    return {"slept": req}


@contextlib.contextmanager
def without(client, *names):
    """The client's requests without its headers ``names`` (the page's Origin, its token)."""
    kept = {n: client.headers.pop(n) for n in names}
    try:
        yield client
    finally:
        client.headers.update(kept)


def _no_job_running(client):
    """A 10-arch ensemble starts (no refused request left a job behind); waits for it."""
    r = client.post("/api/ensemble", json={"arch": OPPENHEIM, "samples": 10})
    assert r.status_code == 200, r.text
    client.post(f"/api/jobs/{r.json()['id']}/cancel", json={})


# ---------------------------------------------------------------------------- refusals
def test_a_cross_origin_post_is_refused(client):
    """The review's request: another site's page posting text/plain (no preflight) without the
    token; and the same with the page's token and JSON: the origin alone refuses it."""
    r = client.post("/api/ensemble", content=b'{"arch": {"radius": 10}, "samples": 20000}',
                    headers={"Origin": EVIL, "Content-Type": "text/plain",
                             "X-Archrock-Token": ""})
    assert r.status_code == 403 and r.json()["error"].startswith("origin: 'http://evil.example'")
    r = client.post("/api/ensemble", json=ENSEMBLE, headers={"Origin": EVIL})
    assert r.status_code == 403 and "allowed only the app's own page" in r.json()["error"]
    # a Referer of another site (no Origin) is refused as well
    with without(client, "Origin"):
        r = client.get("/api/limits", headers={"Referer": EVIL + "/x.html"})
    assert r.status_code == 403 and r.json()["error"].startswith("referer:")
    _no_job_running(client)


def test_a_text_plain_body_is_415(client):
    r = client.post("/api/limit", content=b'{"arch": {"radius": 10}}',
                    headers={"Content-Type": "text/plain"})
    assert r.status_code == 415
    assert r.json()["error"] == "content-type: 'text/plain'; allowed application/json"
    r = client.post("/api/record?name=r.txt", json={"a": 1})  # an upload takes the bytes
    assert r.status_code == 415 and "application/octet-stream" in r.json()["error"]
    r = client.post("/api/ensemble", data={"samples": "20000"})  # an HTML form's body
    assert r.status_code == 415
    _no_job_running(client)


@pytest.mark.parametrize("token", [None, "", "x" * 43], ids=["absent", "empty", "wrong"])
def test_an_api_call_without_the_pages_token_is_403(client, token):
    headers = {"X-Archrock-Token": token} if token is not None else {}
    with without(client, "X-Archrock-Token"):
        for r in (client.get("/api/limits", headers=headers),
                  client.post("/api/limit", json={"arch": OPPENHEIM}, headers=headers)):
            assert r.status_code == 403, r.text
            said = "missing" if not token else "wrong"
            assert r.json()["error"].startswith(f"x-archrock-token: {said}; ")


@pytest.mark.parametrize("host", ["evil.example", "testserver", "127.0.0.1", "127.0.0.1:8766",
                                  "localhost.evil.example:8765"])
def test_a_foreign_host_is_403(client, host):
    """Only the bound address and port name the server (a DNS-rebound name gets nothing, and
    the test client's own 'testserver' is no exception)."""
    for r in (client.get("/", headers={"Host": host}),
              client.get("/api/limits", headers={"Host": host})):
        assert r.status_code == 403 and r.json()["error"].startswith("host: ")


def test_an_api_call_with_neither_origin_nor_referer_is_403(client):
    with without(client, "Origin"):
        r = client.get("/api/limits")
        assert r.status_code == 403 and r.json()["error"].startswith("origin: missing")
        page = client.get("/")  # the page itself (a plain visit) needs neither
        assert page.status_code == 200
        assert client.get("/static/app.js").status_code == 200
        # a same-origin GET of the page's script sends its Referer, not its Origin
        r = client.get("/api/limits", headers={"Referer": ORIGIN + "/"})
        assert r.status_code == 200 and r.json()["max_voussoirs"] == api.MAX_VOUSSOIRS


def test_the_page_carries_its_token_and_its_requests_work(client):
    """What the page's script does: read the token from the page, send it with its origin."""
    with without(client, "Origin", "X-Archrock-Token"):
        page = client.get("/")
    token = re.search(r'<meta name="archrock-token" content="([^"]+)">', page.text).group(1)
    assert token == client.app.state.token and len(token) >= 40
    import httpx

    r = client.post("/api/limit", json={"arch": OPPENHEIM},
                    headers=httpx.Headers({"Origin": ORIGIN, "X-Archrock-Token": token}))
    assert r.status_code == 200 and abs(r.json()["summary"]["k"] - 0.3700097) < 1e-6


def test_job_ids_are_unguessable(client, wait_job):
    ids = []
    for _ in range(2):
        r = client.post("/api/ensemble", json={"arch": OPPENHEIM, "samples": 10})
        ids.append(r.json()["id"])
        assert wait_job(client, ids[-1])["state"] == "done"
    assert all(re.fullmatch(r"job-[A-Za-z0-9_-]{20,}", i) for i in ids) and ids[0] != ids[1]
    assert client.get("/api/jobs/job1").status_code == 400


def test_a_json_body_past_its_cap_is_413_while_it_streams(client):
    """Sent in chunks without a declared length: refused once past the cap, naming it."""
    def chunks():
        for _ in range(api.MAX_UPLOAD_CHARS // 100_000 + 2):
            yield b" " * 100_000

    r = client.post("/api/limit", content=chunks(), headers={"Content-Type": "application/json"})
    assert r.status_code == 413
    assert re.match(r"request: [\d,]+ bytes; allowed up to 2,000,000", r.json()["error"])


def test_an_upload_past_its_cap_is_413_while_it_streams(client):
    def chunks():
        for _ in range(uploads.MAX_FILE_BYTES // 1_000_000 + 1):
            yield b"0" * 1_000_001

    r = client.post("/api/record?name=big.txt", content=chunks(),
                    headers={"Content-Type": "application/octet-stream"})
    assert r.status_code == 413 and "up to 20 MB" in r.json()["error"]


# ---------------------------------------------------------------------------- jobs
def test_a_stuck_job_is_cancelled_within_a_second():
    """A job deaf to its cancel flag (a kernel compiling) ends at the cancel: its worker
    process is terminated, and the next job gets a fresh one."""
    jobs = Jobs()
    try:
        job = jobs.start(1, _stuck, 60.0)
        end = time.monotonic() + 60
        while job.done == 0 and time.monotonic() < end:
            time.sleep(0.02)
        assert job.done == 1 and job.state == "running"
        worker = jobs._worker.process
        t0 = time.perf_counter()
        jobs.cancel(job.id)
        took = time.perf_counter() - t0
        assert job.state == "cancelled" and took < 1.0, took
        assert not worker.is_alive()
        nxt = jobs.start(1, _stuck, 0.0)
        end = time.monotonic() + 120
        while nxt.state == "running" and time.monotonic() < end:
            time.sleep(0.05)
        assert nxt.state == "done" and nxt.result == {"slept": 0.0}
    finally:
        jobs.close()


def test_statics_are_answered_while_a_job_runs(client):
    job = client.post("/api/ensemble", json={"arch": OPPENHEIM, "samples": 4000,
                                             "pulse": {"kind": "oppenheim", "amplitude": -1.0,
                                                       "duration": 0.2}}).json()
    try:
        t0 = time.perf_counter()
        r = client.post("/api/limit", json={"arch": OPPENHEIM})
        took = time.perf_counter() - t0
        assert r.status_code == 200 and abs(r.json()["summary"]["k"] - 0.3700097) < 1e-6
        assert client.get(f"/api/jobs/{job['id']}").json()["state"] == "running"
        assert took < 5.0, took  # generous: a shared test machine (benchmarks/bench_app.py)
    finally:
        c = client.post(f"/api/jobs/{job['id']}/cancel", json={}).json()
    assert c["state"] == "cancelled"


# ---------------------------------------------------------------------------- piers
def test_pier_courses_are_not_called_voussoirs(client):
    arch = {**OPPENHEIM, "pier_height": 4.0, "pier_width": 2.0, "pier_courses": 3}
    d = client.post("/api/limit", json={"arch": arch}).json()["drawing"]
    assert (d["n"], d["voussoirs"], d["pier_courses"]) == (13, 7, 6)
    r = client.post("/api/limit", json={"arch": {**arch, "voussoirs": 120, "pier_courses": 200}})
    assert r.status_code == 400
    assert r.json()["error"] == ("pier_courses: 520 blocks in all (120 voussoirs, 400 pier "
                                 "courses); the app allows up to 120 blocks")


def test_on_every_interface_an_address_names_the_server_and_a_name_does_not():
    """``--host 0.0.0.0``: any IP address with the port (it cannot be rebound), not a name."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        from starlette.testclient import TestClient
    from archrock.app import create_app

    app = create_app("0.0.0.0", 9000)
    c = TestClient(app, base_url="http://192.168.1.5:9000")
    own = {"Origin": "http://192.168.1.5:9000", "X-Archrock-Token": app.state.token}
    assert c.get("/api/limits", headers=own).status_code == 200
    for host in ("evil.example:9000", "192.168.1.5:9001", "[::1]:9000x"):
        r = c.get("/api/limits", headers={**own, "Host": host})
        assert r.status_code == 403 and r.json()["error"].startswith("host: ")
    r = c.get("/api/limits", headers={**own, "Host": "[::1]:9000", "Origin": "http://[::1]:9000"})
    assert r.status_code == 200
