"""Background jobs of the app (the ensemble, the curve, the report): one thread each, progress
polled, cancellable; a job's file (the report) is kept beside its result for one download.

One job runs at a time (a second is refused until the first ends or is cancelled); the last
:data:`KEEP` finished jobs are kept for polling.
"""

from __future__ import annotations

import itertools
import threading
import time
from dataclasses import dataclass, field

from ..errors import ArchInputError, ArchrockError

#: Finished jobs kept in memory for polling.
KEEP = 8


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
    cancel: threading.Event = field(default_factory=threading.Event, repr=False)
    thread: threading.Thread | None = field(default=None, repr=False)

    def to_dict(self) -> dict:
        el = self.elapsed_s if self.state != "running" else time.perf_counter() - self.started
        return {"id": self.id, "state": self.state, "done": self.done, "total": self.total,
                "elapsed_s": el, "result": self.result, "error": self.error}


class Jobs:
    """The app's jobs: :meth:`start` a callable ``work(progress, cancelled)`` in a thread."""

    def __init__(self):
        self._jobs: dict[str, Job] = {}
        self._lock = threading.Lock()
        self._ids = itertools.count(1)

    def start(self, total: int, work) -> Job:
        with self._lock:
            if any(j.state == "running" for j in self._jobs.values()):
                raise Busy("job: another ensemble, curve or report is running; cancel it or wait "
                           "for it")
            job = Job(f"job{next(self._ids)}", total)
            self._jobs[job.id] = job
            finished = [k for k, j in self._jobs.items() if j.state != "running"]
            for k in finished[:-KEEP]:
                del self._jobs[k]

        def progress(done, total_):
            job.done, job.total = int(done), int(total_)

        def run():
            try:
                result = work(progress, job.cancel.is_set)
            except ArchrockError as exc:
                job.error, job.state = " ".join(str(exc).split()), "failed"
            except Exception as exc:  # noqa: BLE001 - a bug: said in one line, never a traceback
                import logging

                logging.getLogger("archrock.app").error("job %s failed", job.id, exc_info=exc)
                job.error, job.state = f"internal error ({type(exc).__name__})", "failed"
            else:
                if result is None:
                    job.state = "cancelled"
                else:
                    job.download = result.pop("_download", None)
                    job.result, job.state = result, "done"
            job.elapsed_s = time.perf_counter() - job.started

        job.thread = threading.Thread(target=run, name=f"archrock-{job.id}", daemon=True)
        job.thread.start()
        return job

    def get(self, job_id: str) -> Job:
        job = self._jobs.get(job_id)
        if job is None:
            raise ArchInputError(f"job: {job_id!r} not found")
        return job

    def cancel(self, job_id: str) -> Job:
        job = self.get(job_id)
        job.cancel.set()
        return job

    def cancel_all(self) -> None:
        for job in list(self._jobs.values()):
            job.cancel.set()
