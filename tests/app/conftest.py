"""Fixtures of the app's tests: one TestClient per module and the wait for a job."""

import time

import pytest


@pytest.fixture(scope="module")
def client():
    """Starlette's TestClient on a fresh app (its jobs and uploads die with it)."""
    pytest.importorskip("starlette")
    pytest.importorskip("httpx")
    import warnings

    with warnings.catch_warnings():  # newer Starlette prefers httpx2; httpx still works
        warnings.simplefilter("ignore")
        from starlette.testclient import TestClient

    from archrock.app import create_app

    with TestClient(create_app()) as c:
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
