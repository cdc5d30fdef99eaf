"""Fixtures of the app's tests: one TestClient per module (sending what the app's own page
sends: its origin and token) and the wait for a job."""

import time

import pytest


#: The address the tests' app is made for (TestClient connects to no socket; the Host header
#: and the page's origin are this).
HOST, PORT = "127.0.0.1", 8765
ORIGIN = f"http://{HOST}:{PORT}"


@pytest.fixture(scope="module")
def client():
    """Starlette's TestClient on a fresh app (its jobs and uploads die with it), sending the
    page's Origin and token on every request (``client.app.state.token``)."""
    pytest.importorskip("starlette")
    pytest.importorskip("httpx")
    import warnings

    with warnings.catch_warnings():  # newer Starlette prefers httpx2; httpx still works
        warnings.simplefilter("ignore")
        from starlette.testclient import TestClient

    from archrock.app import create_app

    app = create_app(HOST, PORT)
    headers = {"Origin": ORIGIN, "X-Archrock-Token": app.state.token}
    with TestClient(app, base_url=ORIGIN, headers=headers) as c:
        yield c


@pytest.fixture
def wait_job():
    """wait_job(client, job_id, timeout=180 s): the job's final state; fails the test when it
    is still running at the timeout."""
    def wait(client, job_id, timeout=180.0):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            s = client.get(f"/api/jobs/{job_id}").json()
            if s["state"] != "running":
                return s
            time.sleep(0.05)
        raise AssertionError(f"job {job_id} still running after {timeout} s")
    return wait
