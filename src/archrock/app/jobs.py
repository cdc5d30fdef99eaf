"""Background jobs of the app (the ensemble, the curve, the report, the contact engine's
response), each run in a worker
process of its own so that cancelling one takes effect at once (a numba kernel being compiled
cannot be interrupted in a thread; a process can be terminated) and the page's statics are
answered meanwhile by the server's own threads.  Progress is polled; a job's file (the report)
is kept beside its result for one download.

One job runs at a time (a second is refused until the first ends or is cancelled); the last
:data:`KEEP` finished jobs are kept for polling.  Job ids are random (:func:`secrets.token_urlsafe`):
another page cannot guess one.  A worker process is started ahead of the first job (its imports
and, with ``warm_up``, the ensemble's kernels ready) and kept for the next one; a cancelled job's
worker is terminated and a fresh one started.
"""

from __future__ import annotations

import secrets
import threading
import time
from dataclasses import dataclass, field

from ..errors import ArchInputError, ArchrockError

#: Finished jobs kept in memory for polling.
KEEP = 8
#: Seconds a terminated worker is given to exit before it is killed.
TERMINATE_WAIT_S = 0.5


class Busy(ArchInputError):
    """Another job is running."""


@dataclass
class Job:
    """A job's state: ``state`` one of running, done, cancelled, failed; ``done`` / ``total``
    arches; ``result`` (done) or ``error`` (failed: the library's one-line message)."""

    id: str
    total: int
    state: str = "running"
    done: int = 0
    result: dict | None = None
    error: str | None = None
    #: (file name, media type, text) of a job that makes a file: the ``"_download"`` entry of
    #: its work's result, kept out of the polled JSON.
    download: tuple | None = field(default=None, repr=False)
    started: float = field(default_factory=time.perf_counter)
    elapsed_s: float = 0.0

    def to_dict(self) -> dict:
        el = self.elapsed_s if self.state != "running" else time.perf_counter() - self.started
        return {"id": self.id, "state": self.state, "done": self.done, "total": self.total,
                "elapsed_s": el, "result": self.result, "error": self.error}

    def finish(self, state: str, **values) -> None:
        if self.state == "running":  # the first word stands (a cancel beats a late result)
            for k, v in values.items():
                setattr(self, k, v)
            self.state, self.elapsed_s = state, time.perf_counter() - self.started


def _worker_main(conn, warm_up: bool) -> None:
    """The worker process: runs ``(func, req)`` jobs received on ``conn``, one at a time,
    sending ("progress", done, total) and one final ("done", result) or ("failed", message)."""
    import os
    import signal

    # Ctrl-C reaches the whole process group: the server ends this worker itself
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:  # the page's statics (server threads) come first on a busy machine
        os.nice(5)
    except OSError:
        pass
    if warm_up:
        warm_up_jobs()
    while True:
        try:
            msg = conn.recv()
        except (EOFError, OSError):
            return
        if msg is None:
            return
        func, req = msg
        try:
            result = func(req, lambda d, t: conn.send(("progress", int(d), int(t))),
                          lambda: False)
        except ArchrockError as exc:
            conn.send(("failed", " ".join(str(exc).split())))
        except Exception as exc:  # noqa: BLE001 - a bug: said in one line, never a traceback
            import logging

            logging.getLogger("archrock.app").error("job failed", exc_info=exc)
            conn.send(("failed", f"internal error ({type(exc).__name__})"))
        else:
            conn.send(("done", result))


def warm_up_jobs() -> None:
    """Compile (or load from numba's cache) the ensemble's kernels in the worker."""
    from . import api

    try:
        arch = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
        cfg = api.ensemble_config({"arch": arch, "samples": 50,
                                   "pulse": {"kind": "oppenheim", "amplitude": -1.0,
                                             "duration": 0.2}})
        api.run_ensemble_job(cfg, lambda d, t: None, lambda: False)
    except Exception:  # noqa: BLE001 - warming up is an optimisation; a real job will say
        pass


class _Worker:
    """One worker process and the parent's end of its pipe."""

    def __init__(self, warm_up: bool):
        import multiprocessing

        # spawn, not fork: the server has threads (and perhaps numba's), unsafe to fork
        ctx = multiprocessing.get_context("spawn")
        self.conn, child = ctx.Pipe()
        self.process = ctx.Process(target=_worker_main, args=(child, warm_up),
                                   name="archrock-app-worker", daemon=True)
        self.process.start()
        child.close()

    def stop(self) -> None:
        """Terminate the process (SIGTERM, then SIGKILL after :data:`TERMINATE_WAIT_S`)."""
        p = self.process
        if p.is_alive():
            p.terminate()
            p.join(TERMINATE_WAIT_S)
            if p.is_alive():
                p.kill()
                p.join(TERMINATE_WAIT_S)
        self.conn.close()


class Jobs:
    """The app's jobs: :meth:`start` ``func(req, progress, cancelled)`` (a module-level
    function and a picklable request) in the worker process."""

    def __init__(self, warm_up: bool = False):
        self._jobs: dict[str, Job] = {}
        self._lock = threading.Lock()
        self._warm_up = warm_up
        self._worker: _Worker | None = None
        self._closed = False

    def prepare(self) -> None:
        """Start the worker ahead of the first job (its imports take seconds)."""
        with self._lock:
            self._ensure_worker()

    def _ensure_worker(self) -> _Worker:
        if self._closed:
            raise ArchInputError("job: the server is stopping")
        if self._worker is None or not self._worker.process.is_alive():
            if self._worker is not None:
                self._worker.stop()
            self._worker = _Worker(self._warm_up)
        return self._worker

    def start(self, total: int, func, req) -> Job:
        with self._lock:
            if any(j.state == "running" for j in self._jobs.values()):
                raise Busy("job: another ensemble, curve, report or engine response is running; "
                           "cancel it or wait for it")
            worker = self._ensure_worker()
            job = Job(f"job-{secrets.token_urlsafe(16)}", total)
            self._jobs[job.id] = job
            finished = [k for k, j in self._jobs.items() if j.state != "running"]
            for k in finished[:-KEEP]:
                del self._jobs[k]
            worker.conn.send((func, req))
        threading.Thread(target=self._follow, args=(job, worker), name="archrock-job-monitor",
                         daemon=True).start()
        return job

    def _follow(self, job: Job, worker: _Worker) -> None:
        """Read the worker's messages of ``job`` until its end (or the worker's)."""
        while True:
            try:
                msg = worker.conn.recv()
            except (EOFError, OSError):  # terminated (a cancel) or died
                job.finish("failed", error="internal error (the job's worker process ended)")
                return
            if msg[0] == "progress":
                job.done, job.total = msg[1], msg[2]
            elif msg[0] == "failed":
                job.finish("failed", error=msg[1])
                return
            else:
                result = msg[1]
                if result is None:
                    job.finish("cancelled")
                else:
                    job.finish("done", download=result.pop("_download", None), result=result)
                return

    def get(self, job_id: str) -> Job:
        job = self._jobs.get(job_id)
        if job is None:
            raise ArchInputError(f"job: {job_id[:40]!r} not found")
        return job

    def cancel(self, job_id: str) -> Job:
        """Cancel a running job now: its worker is terminated (a fresh one started after)."""
        job = self.get(job_id)
        with self._lock:
            if job.state != "running":
                return job
            job.finish("cancelled")
            worker, self._worker = self._worker, None
        if worker is not None:
            worker.stop()
        if not self._closed:  # the next job's worker, ready before it is asked for
            threading.Thread(target=self._prepare_quietly, daemon=True).start()
        return job

    def _prepare_quietly(self) -> None:
        try:
            self.prepare()
        except ArchInputError:
            pass

    def close(self) -> None:
        """Cancel every job and end the worker (the server is stopping)."""
        with self._lock:
            self._closed = True
            for job in self._jobs.values():
                job.finish("cancelled")
            worker, self._worker = self._worker, None
        if worker is not None:
            worker.stop()
