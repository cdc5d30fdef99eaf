"""The ASGI application (Starlette): the page, its static files and the JSON API.

Routes (JSON bodies; lengths m, accelerations g, times s):

* ``GET /`` the page; ``/static/...`` its script and style (package data, no CDN);
* ``POST /api/limit`` {arch, friction?, thrust_range?}: :func:`.api.limit`;
* ``POST /api/respond`` {arch, pulse: {kind, amplitude, duration}, t_end?}: :func:`.api.respond`;
* ``POST /api/ensemble`` {arch, samples, seed, spreads, pulse?}: starts a job, returns its id;
  ``GET /api/jobs/{id}`` its progress and result; ``POST /api/jobs/{id}/cancel``;
* ``POST /api/curve`` {arch, samples, seed, spreads, durations, kind}: the collapse-acceleration
  curve and its band, a job as the ensemble;
* ``POST /api/export`` {what, arch, pulse?}: a download (:func:`.api.export`);
* ``POST /api/record?name=&units=&scale=`` the bytes of a record file (PEER .AT2 or two
  columns): read by the library in a temporary folder of the server, kept in memory; its id then
  stands for the pulse in ``/api/respond`` {arch, record: {id}, t_end?} (:func:`.api.load_record_upload`);
* ``POST /api/dxf?name=&layer=&units=&density=`` the bytes of a DXF survey: its polygon arch's
  geometry file JSON (:func:`.api.load_dxf_upload`);
* ``POST /api/report`` {arch, samples, seed, spreads, contact}: ``archrock assess`` as a job;
  ``GET /api/jobs/{id}/download`` its HTML file.

A bad value answers 400 with ``{"error": message}`` (the CLI's one-line message, naming the
field); a valid arch with no answer of the kind asked (cannot stand, no mechanism) 422; never a
traceback; an upload above api.MAX_FILE_BYTES 413.  Only the request bodies are read and only the
downloads written; an uploaded file is written only into a new temporary folder of the server
(mode 0700), read by the library and deleted with it in the same request.
"""

from __future__ import annotations

import contextlib
import json
from pathlib import Path

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.middleware import Middleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from ..options import OptionError as CLIError, json_safe
from ..errors import ArchInputError, ArchrockError, GeometryOutcome
from . import api
from .jobs import Busy, Jobs

STATIC = Path(__file__).parent / "static"
#: The page may load only its own files (no CDN, no other site).
CSP = ("default-src 'self'; img-src 'self' data: blob:; style-src 'self'; script-src 'self'; "
       "connect-src 'self'; object-src 'none'; base-uri 'none'; frame-ancestors 'none'")
LOOPBACK_NAMES = ["127.0.0.1", "localhost", "[::1]", "testserver"]


def _json(data, status: int = 200) -> JSONResponse:
    return JSONResponse(json_safe(data), status_code=status)


def _error(exc: Exception) -> JSONResponse:
    msg = " ".join(str(exc).split())
    if not isinstance(exc, ArchrockError | CLIError):  # a bug: logged here, not shown
        import logging

        logging.getLogger("archrock.app").error("request failed", exc_info=exc)
    if isinstance(exc, api.TooLarge):
        return _json({"error": msg, "kind": "too-large"}, 413)
    if isinstance(exc, Busy):
        return _json({"error": msg, "kind": "busy"}, 409)
    if isinstance(exc, (ArchInputError, CLIError)):
        return _json({"error": msg, "kind": "input"}, 400)
    if isinstance(exc, GeometryOutcome):
        return _json({"error": msg, "kind": "outcome"}, 422)
    if isinstance(exc, ArchrockError):
        return _json({"error": msg, "kind": "limit"}, 422)
    return _json({"error": f"internal error ({type(exc).__name__}); the server log has more",
                  "kind": "internal"}, 500)


async def _body(request: Request) -> dict:
    size = request.headers.get("content-length")
    if size is not None and size.isdigit() and int(size) > api.MAX_UPLOAD_CHARS:
        raise ArchInputError(f"request: {int(size)} bytes; allowed up to {api.MAX_UPLOAD_CHARS}")
    raw = await request.body()
    if len(raw) > api.MAX_UPLOAD_CHARS:
        raise ArchInputError(f"request: {len(raw)} bytes; allowed up to {api.MAX_UPLOAD_CHARS}")
    try:
        data = json.loads(raw or b"{}")
    except (ValueError, RecursionError) as exc:
        raise ArchInputError(f"request: not valid JSON ({exc})") from None
    if not isinstance(data, dict):
        raise ArchInputError("request: expected a JSON object")
    return data


async def _upload(request: Request, field: str) -> bytes:
    """The raw body of a file upload, refused (413) above api.MAX_FILE_BYTES before or while
    it is read."""
    size = request.headers.get("content-length")
    if size is not None and size.isdigit() and int(size) > api.MAX_FILE_BYTES:
        raise api.too_large(field, int(size))
    chunks, n = [], 0
    async for chunk in request.stream():
        n += len(chunk)
        if n > api.MAX_FILE_BYTES:
            raise api.too_large(field, n)
        chunks.append(chunk)
    return b"".join(chunks)


def _endpoint(func):
    """A POST endpoint running ``func(body)`` in a worker thread; errors as JSON."""
    async def endpoint(request: Request):
        try:
            body = await _body(request)
            return _json(await run_in_threadpool(func, body))
        except Exception as exc:  # noqa: BLE001 - every error is answered in one line
            return _error(exc)
    return endpoint


def create_app(hosts: list[str] | None = None, warm_up: bool = False) -> Starlette:
    """The app. ``hosts``: Host header names accepted besides the loopback ones (a guard
    against DNS rebinding); ``warm_up``: compile the numba kernels in a background thread at
    start (the first answer then does not wait for them)."""
    jobs = Jobs()
    records = api.RecordStore()

    async def index(request):
        return FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-store"})

    async def favicon(request):
        return FileResponse(STATIC / "favicon.svg", media_type="image/svg+xml")

    def job_route(check, total, run, extra=lambda req: {}):
        """A route that checks its request (``check``, in a thread: it may read files or
        estimate work) and starts ``run(req, progress, cancelled)`` as a job of ``total(req)``
        steps."""
        async def route(request: Request):
            try:
                req = await run_in_threadpool(check, await _body(request))
                job = jobs.start(total(req), lambda progress, cancelled: run(req, progress,
                                                                             cancelled))
                return _json({**job.to_dict(), **extra(req)})
            except Exception as exc:  # noqa: BLE001
                return _error(exc)
        return route

    ensemble = job_route(api.ensemble_config, lambda cfg: cfg.samples, api.run_ensemble_job)
    curve = job_route(api.curve_request, lambda req: req["samples"] * len(req["durations"]),
                      api.run_curve_job)
    report = job_route(api.report_request, lambda req: 1, api.run_report_job,
                       lambda req: {"estimate_s": req["estimate_s"]})

    async def job_download(request: Request):
        try:
            job = jobs.get(request.path_params["job"])
            if job.download is None:
                raise ArchInputError(f"job: {job.id} has no file ({job.state})")
        except Exception as exc:  # noqa: BLE001
            return _error(exc)
        name, media, text = job.download
        return Response(text, media_type=media,
                        headers={"Content-Disposition": f'attachment; filename="{name}"'})

    def _uploader(field, func):
        async def endpoint(request: Request):
            try:
                data = await _upload(request, field)
                params = dict(request.query_params)
                return _json(await run_in_threadpool(func, data, params))
            except Exception as exc:  # noqa: BLE001
                return _error(exc)
        return endpoint

    async def job_status(request: Request):
        try:
            return _json(jobs.get(request.path_params["job"]).to_dict())
        except Exception as exc:  # noqa: BLE001
            return _error(exc)

    async def job_cancel(request: Request):
        try:
            return _json(jobs.cancel(request.path_params["job"]).to_dict())
        except Exception as exc:  # noqa: BLE001
            return _error(exc)

    async def export(request: Request):
        try:
            body = await _body(request)
            name, media, text = await run_in_threadpool(api.export, body, records)
        except Exception as exc:  # noqa: BLE001
            return _error(exc)
        return Response(text, media_type=media,
                        headers={"Content-Disposition": f'attachment; filename="{name}"'})

    async def limits(request):
        return _json({"max_voussoirs": api.MAX_VOUSSOIRS, "max_samples": api.MAX_SAMPLES,
                      "max_t_end_s": api.MAX_T_END_S, "max_pulse_s": api.MAX_PULSE_S,
                      "max_amplitude_g": api.MAX_AMPLITUDE_G, "shapes": api.SHAPES,
                      "joints": api.JOINTS, "pulses": api.PULSE_KINDS,
                      "max_file_bytes": api.MAX_FILE_BYTES,
                      "max_record_t_end_s": api.MAX_RECORD_T_END_S,
                      "record_units": api.RECORD_UNITS, "dxf_units": api.DXF_UNITS,
                      "max_report_samples": api.MAX_REPORT_SAMPLES})

    routes = [
        Route("/", index),
        Route("/favicon.ico", favicon),
        Route("/api/limits", limits),
        Route("/api/limit", _endpoint(api.limit), methods=["POST"]),
        Route("/api/respond", _endpoint(lambda body: api.respond(body, records)),
              methods=["POST"]),
        Route("/api/record", _uploader("record", lambda data, params: api.load_record_upload(
            data, params, records)), methods=["POST"]),
        Route("/api/dxf", _uploader("dxf", api.load_dxf_upload), methods=["POST"]),
        Route("/api/report", report, methods=["POST"]),
        Route("/api/jobs/{job}/download", job_download),
        Route("/api/ensemble", ensemble, methods=["POST"]),
        Route("/api/curve", curve, methods=["POST"]),
        Route("/api/jobs/{job}", job_status),
        Route("/api/jobs/{job}/cancel", job_cancel, methods=["POST"]),
        Route("/api/export", export, methods=["POST"]),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]

    @contextlib.asynccontextmanager
    async def lifespan(app):
        if warm_up:
            import threading

            threading.Thread(target=_warm_up, name="archrock-warm-up", daemon=True).start()
        yield
        jobs.cancel_all()

    app = Starlette(routes=routes,
                    middleware=[Middleware(TrustedHostMiddleware,
                                           allowed_hosts=LOOPBACK_NAMES + list(hosts or ())),
                                Middleware(_SecurityHeaders)],
                    lifespan=lifespan)
    app.state.jobs = jobs
    return app


class _SecurityHeaders:
    """ASGI middleware: every response carries :data:`CSP` and ``nosniff``."""

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)

        async def send_with_headers(message):
            if message["type"] == "http.response.start":
                extra = [(b"content-security-policy", CSP.encode()),
                         (b"x-content-type-options", b"nosniff")]
                message = {**message, "headers": [*message.get("headers", []), *extra]}
            await send(message)

        return await self.app(scope, receive, send_with_headers)


def _warm_up() -> None:
    """Compile (or load from numba's cache) the kernels of the page's first answers."""
    try:
        arch = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
        api.limit({"arch": arch})
        api.respond({"arch": arch, "pulse": {"kind": "oppenheim", "amplitude": -1.0,
                                             "duration": 0.2}, "t_end": 1.0})
        cfg = api.ensemble_config({"arch": arch, "samples": 50,
                                   "pulse": {"kind": "oppenheim", "amplitude": -1.0,
                                             "duration": 0.2}})
        api.run_ensemble_job(cfg, lambda d, t: None, lambda: False)
    except Exception:  # noqa: BLE001 - warming up is an optimisation; a real request will say
        pass


class BackgroundServer:
    """The app served by uvicorn in a daemon thread on a free loopback port (tests, scripts):
    ``with BackgroundServer() as url: ...``; ``url`` is ``http://127.0.0.1:PORT/``."""

    def __init__(self, warm_up: bool = True, timeout_s: float = 30.0):
        self.warm_up, self.timeout_s = warm_up, timeout_s
        self.server = self.thread = None

    def __enter__(self) -> str:
        import socket
        import threading
        import time

        import uvicorn

        sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        sock.bind(("127.0.0.1", 0))
        self.server = uvicorn.Server(uvicorn.Config(create_app(warm_up=self.warm_up),
                                                    log_level="warning"))
        self.thread = threading.Thread(target=self.server.run, kwargs={"sockets": [sock]},
                                       name="archrock-app-server", daemon=True)
        self.thread.start()
        end = time.monotonic() + self.timeout_s
        while not self.server.started:
            if time.monotonic() > end or not self.thread.is_alive():
                raise RuntimeError("the app's server did not start")
            time.sleep(0.02)
        return f"http://127.0.0.1:{sock.getsockname()[1]}/"

    def __exit__(self, *exc):
        self.server.should_exit = True
        self.thread.join(10)
        return False
