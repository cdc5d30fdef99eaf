"""The ASGI application (Starlette): the page, its static files and the JSON API.

Routes (JSON bodies; lengths m, accelerations g, times s):

* ``GET /`` the page; ``/static/...`` its script and style (package data, no CDN);
* ``POST /api/limit`` {arch, friction?, thrust_range?}: :func:`.api.limit`;
* ``POST /api/respond`` {arch, pulse: {kind, amplitude, duration}, t_end?, exaggerate?,
  friction?, dynamics?}: the model of :func:`archrock.studies.enginestudy.choose_dynamics`
  answers: the four-link response at once (:func:`.api.four_link_response`), or the contact
  engine's as a job (``{"job": ..., "dynamics": ...}``, :func:`.engine.run_engine_job`);
* ``POST /api/ensemble`` {arch, samples, seed, spreads, pulse?}: starts a job, returns its id;
  ``GET /api/jobs/{id}`` its progress and result; ``POST /api/jobs/{id}/cancel``;
* ``POST /api/curve`` {arch, samples, seed, spreads, durations, kind}: the collapse-acceleration
  curve and its band, a job as the ensemble;
* ``POST /api/export`` {what, arch, pulse?}: a download (:func:`.api.export`);
* ``POST /api/record?name=&units=&scale=`` the bytes of a record file (PEER .AT2 or two
  columns): read by the library in a temporary folder of the server, kept in memory; its id then
  stands for the pulse in ``/api/respond`` {arch, record: {id}, t_end?} (:func:`.uploads.load_record_upload`);
* ``GET /api/suites``, ``GET /api/suites/{name}``: the built-in FEMA P695 suites and one
  suite's records; ``POST /api/suites/record`` {suite_ref, scale?}: one of them loaded as an
  uploaded record is, its id then played as one (:mod:`.suites`); ``/api/respond`` also takes
  ``record: {suite_ref, scale?}``;
* ``POST /api/dxf?name=&layer=&units=&density=`` the bytes of a DXF survey: its polygon arch's
  geometry file JSON (:func:`.uploads.load_dxf_upload`);
* ``POST /api/report`` {arch, samples, seed, spreads, contact, friction?}: ``archrock assess`` as a job;
  ``GET /api/jobs/{id}/download`` its HTML file.

A bad value answers 400 with ``{"error": message}`` (the CLI's one-line message, naming the
field); a valid arch with no answer of the kind asked (cannot stand, no mechanism) 422; never a
traceback; an upload above uploads.MAX_FILE_BYTES 413.  Only the request bodies are read and only the
downloads written; an uploaded file is streamed into a new temporary folder of the server
(mode 0700), read by the library and deleted with it in the same request.

Who may ask (:class:`_Guard`, docs/app.md): the Host header must be the bound address and port;
a request naming another origin (Origin, or failing that Referer) is refused 403; every API call
must come from the page (its origin) and carry the page's token (``X-Archrock-Token``, made at
launch and written into the served page) or it is refused 403; its body must be
``application/json`` (``application/octet-stream`` on the two upload endpoints) or 415.
"""

from __future__ import annotations

import contextlib
import hashlib
import ipaddress
import json
import secrets
import tempfile
from pathlib import Path

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from ..options import OptionError as CLIError, json_safe
from ..errors import ArchInputError, ArchrockError, GeometryOutcome
from ..statics.friction import DEFAULT_FRICTION
from . import api, engine, suites, uploads
from .jobs import Busy, Jobs

STATIC = Path(__file__).parent / "static"
#: The page may load only its own files (no CDN, no other site).
CSP = ("default-src 'self'; img-src 'self' data: blob:; style-src 'self'; script-src 'self'; "
       "connect-src 'self'; object-src 'none'; base-uri 'none'; frame-ancestors 'none'")
#: The request header carrying the page's token on every API call.
TOKEN_HEADER = "x-archrock-token"
#: Where the served page holds its token (index.html's empty meta element, filled at launch).
TOKEN_META = '<meta name="archrock-token" content="">'
#: The two upload endpoints, which take the file's bytes (application/octet-stream).
UPLOADS = ("/api/record", "/api/dxf")
#: Bound addresses meaning every interface: any IP literal may then name the server (a DNS
#: name could be rebound to it by another site; an address cannot).
WILDCARDS = ("0.0.0.0", "::", "[::]")


def _json(data, status: int = 200) -> JSONResponse:
    return JSONResponse(json_safe(data), status_code=status)


def _error(exc: Exception) -> JSONResponse:
    msg = " ".join(str(exc).split())
    if not isinstance(exc, ArchrockError | CLIError):  # a bug: logged here, not shown
        import logging

        logging.getLogger("archrock.app").error("request failed", exc_info=exc)
    if isinstance(exc, uploads.TooLarge):
        return _json({"error": msg, "kind": "too-large"}, 413)
    if isinstance(exc, Busy):
        return _json({"error": msg, "kind": "busy"}, 409)
    if isinstance(exc, (ArchInputError, CLIError)):
        return _json({"error": msg, "kind": "input"}, 400)
    if isinstance(exc, engine.EngineMissing):
        return _json({"error": msg, "kind": "needs-engine"}, 422)
    if isinstance(exc, GeometryOutcome):
        return _json({"error": msg, "kind": "outcome"}, 422)
    if isinstance(exc, ArchrockError):
        return _json({"error": msg, "kind": "limit"}, 422)
    return _json({"error": f"internal error ({type(exc).__name__}); the server log has more",
                  "kind": "internal"}, 500)


async def _chunks(request: Request, cap: int, too_big):
    """The body's chunks, refused (``too_big(size)`` raised) once past ``cap`` bytes: by its
    declared length before any is read, else as they arrive (never more than ``cap`` held)."""
    size = request.headers.get("content-length")
    if size is not None and size.isdigit() and int(size) > cap:
        raise too_big(int(size))
    n = 0
    async for chunk in request.stream():
        n += len(chunk)
        if n > cap:
            raise too_big(n)
        yield chunk


def _too_long(size: int) -> uploads.TooLarge:
    return uploads.TooLarge(f"request: {size:,} bytes; allowed up to {api.MAX_UPLOAD_CHARS:,} "
                        f"(a JSON body)")


async def _body(request: Request) -> dict:
    raw = b"".join([c async for c in _chunks(request, api.MAX_UPLOAD_CHARS, _too_long)])
    try:
        data = json.loads(raw or b"{}")
    except (ValueError, RecursionError) as exc:
        raise ArchInputError(f"request: not valid JSON ({exc})") from None
    if not isinstance(data, dict):
        raise ArchInputError("request: expected a JSON object")
    return data


async def _upload(request: Request, field: str, folder: str) -> uploads.Upload:
    """The body of a file upload streamed into ``folder`` (hashed on the way), refused (413)
    above uploads.MAX_FILE_BYTES: memory holds one chunk at a time, not the file."""
    path = Path(folder) / "upload.bin"
    sha, n = hashlib.sha256(), 0
    with open(path, "wb") as f:
        async for chunk in _chunks(request, uploads.MAX_FILE_BYTES,
                                   lambda size: uploads.too_large(field, size)):
            f.write(chunk)
            sha.update(chunk)
            n += len(chunk)
    return uploads.Upload(path, n, sha.hexdigest())


def _endpoint(func):
    """A POST endpoint running ``func(body)`` in a worker thread; errors as JSON."""
    async def endpoint(request: Request):
        try:
            body = await _body(request)
            return _json(await run_in_threadpool(func, body))
        except Exception as exc:  # noqa: BLE001 - every error is answered in one line
            return _error(exc)
    return endpoint


def _get(func, *names):
    """A GET endpoint answering ``func(*path parameters names)`` from a worker thread (the
    suites are read from disk once); errors as JSON."""
    async def endpoint(request: Request):
        try:
            args = [request.path_params[n] for n in names]
            return _json(await run_in_threadpool(func, *args))
        except Exception as exc:  # noqa: BLE001 - every error is answered in one line
            return _error(exc)
    return endpoint


def _page(token: str) -> str:
    """index.html with ``token`` in its token element."""
    page = (STATIC / "index.html").read_text(encoding="utf-8")
    if TOKEN_META not in page:
        raise RuntimeError("index.html has lost its token element")
    return page.replace(TOKEN_META, f'<meta name="archrock-token" content="{token}">')


def _index(page: str):
    async def index(request):
        return Response(page, media_type="text/html; charset=utf-8",
                        headers={"Cache-Control": "no-store"})
    return index


async def _favicon(request):
    return Response((STATIC / "favicon.svg").read_bytes(), media_type="image/svg+xml")


async def _limits(request):
    return _json({"max_voussoirs": api.MAX_VOUSSOIRS, "max_samples": api.MAX_SAMPLES,
                  "max_t_end_s": api.MAX_T_END_S, "max_pulse_s": api.MAX_PULSE_S,
                  "max_amplitude_g": api.MAX_AMPLITUDE_G, "shapes": api.SHAPES,
                  "joints": api.JOINTS, "pulses": api.PULSE_KINDS,
                  "max_file_bytes": uploads.MAX_FILE_BYTES,
                  "max_record_t_end_s": uploads.MAX_RECORD_T_END_S,
                  "record_units": uploads.RECORD_UNITS, "dxf_units": uploads.DXF_UNITS,
                  "max_report_samples": api.MAX_REPORT_SAMPLES,
                  "default_friction": DEFAULT_FRICTION, "dynamics": engine.DYNAMICS})


def _job_route(jobs: Jobs, check, total, run, extra=lambda req: {}):
    """A route that checks its request (``check``, in a thread: it may read files or
    estimate work) and starts ``run(req, progress, cancelled)`` as a job of ``total(req)``
    steps in the job worker."""
    async def route(request: Request):
        try:
            req = await run_in_threadpool(check, await _body(request))
            job = await run_in_threadpool(jobs.start, total(req), run, req)
            return _json({**job.to_dict(), **extra(req)})
        except Exception as exc:  # noqa: BLE001
            return _error(exc)
    return route


def _respond(jobs: Jobs, records):
    async def respond(request: Request):
        """The response of the model that holds (the routing of the package): the four-link
        one answered now, the contact engine's started as a job (seconds to minutes)."""
        try:
            req = await run_in_threadpool(api.respond_request, await _body(request), records)
            chosen = req["choice"]
            if not chosen.engine:
                return _json(await run_in_threadpool(api.four_link_response, req))
            job = await run_in_threadpool(jobs.start, 1, engine.run_engine_job, req)
            return _json({"job": job.to_dict(), "model": "engine", "dynamics": chosen.to_dict(),
                          "label": "contact engine (pymunk): " + chosen.reason})
        except Exception as exc:  # noqa: BLE001
            return _error(exc)
    return respond


def _attachment(name: str, media: str, text) -> Response:
    return Response(text, media_type=media,
                    headers={"Content-Disposition": f'attachment; filename="{name}"'})


def _job_endpoints(jobs: Jobs):
    """The routes of one job: (download, status, cancel)."""
    async def job_download(request: Request):
        try:
            job = jobs.get(request.path_params["job"])
            if job.download is None:
                raise ArchInputError(f"job: {job.id} has no file ({job.state})")
        except Exception as exc:  # noqa: BLE001
            return _error(exc)
        return _attachment(*job.download)

    async def job_status(request: Request):
        try:
            return _json(jobs.get(request.path_params["job"]).to_dict())
        except Exception as exc:  # noqa: BLE001
            return _error(exc)

    async def job_cancel(request: Request):
        try:
            return _json((await run_in_threadpool(jobs.cancel,
                                                  request.path_params["job"])).to_dict())
        except Exception as exc:  # noqa: BLE001
            return _error(exc)
    return job_download, job_status, job_cancel


def _uploader(field, func):
    async def endpoint(request: Request):
        try:
            with tempfile.TemporaryDirectory(prefix="archrock-app-") as folder:
                data = await _upload(request, field, folder)
                params = dict(request.query_params)
                return _json(await run_in_threadpool(func, data, params))
        except Exception as exc:  # noqa: BLE001
            return _error(exc)
    return endpoint


def _export(records):
    async def export(request: Request):
        try:
            body = await _body(request)
            name, media, text = await run_in_threadpool(api.export, body, records)
        except Exception as exc:  # noqa: BLE001
            return _error(exc)
        return _attachment(name, media, text)
    return export


def _routes(page: str, jobs: Jobs, records) -> list:
    """The app's routes (module docstring)."""
    ensemble = _job_route(jobs, api.ensemble_request, lambda req: req["config"].samples,
                          api.run_ensemble_request)
    curve = _job_route(jobs, api.curve_request,
                       lambda req: req["samples"] * len(req["durations"]), api.run_curve_job)
    report = _job_route(jobs, api.report_request, lambda req: 1, api.run_report_job,
                        lambda req: {"estimate_s": req["estimate_s"]})
    job_download, job_status, job_cancel = _job_endpoints(jobs)
    return [
        Route("/", _index(page)),
        Route("/favicon.ico", _favicon),
        Route("/api/limits", _limits),
        Route("/api/limit", _endpoint(api.limit), methods=["POST"]),
        Route("/api/respond", _respond(jobs, records), methods=["POST"]),
        Route("/api/record", _uploader("record", lambda data, params: uploads.load_record_upload(
            data, params, records)), methods=["POST"]),
        Route("/api/dxf", _uploader("dxf", uploads.load_dxf_upload), methods=["POST"]),
        Route("/api/suites", _get(suites.suites_index)),
        Route("/api/suites/record", _endpoint(lambda body: suites.load_suite_record(
            body, records)), methods=["POST"]),
        Route("/api/suites/{name}", _get(suites.suite_table, "name")),
        Route("/api/report", report, methods=["POST"]),
        Route("/api/jobs/{job}/download", job_download),
        Route("/api/ensemble", ensemble, methods=["POST"]),
        Route("/api/curve", curve, methods=["POST"]),
        Route("/api/jobs/{job}", job_status),
        Route("/api/jobs/{job}/cancel", job_cancel, methods=["POST"]),
        Route("/api/export", _export(records), methods=["POST"]),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]


def _lifespan(jobs: Jobs, warm_up: bool):
    @contextlib.asynccontextmanager
    async def lifespan(app):
        if warm_up:
            import threading

            threading.Thread(target=_warm_up, name="archrock-warm-up", daemon=True).start()
        await run_in_threadpool(jobs.prepare)  # the worker's imports start now, not at the job
        yield
        await run_in_threadpool(jobs.close)
    return lifespan


def create_app(host: str = "127.0.0.1", port: int = 8765, *, hosts: list[str] | None = None,
               token: str | None = None, warm_up: bool = False) -> Starlette:
    """The app served at ``host``:``port`` (the bound address: the only Host header accepted,
    with the ``host:port`` names of ``hosts``); ``token``: the page's token (default a new
    random one, ``app.state.token``); ``warm_up``: compile the numba kernels in the
    background at start (the statics here, the ensemble's in the job worker)."""
    token = token or secrets.token_urlsafe(32)
    jobs = Jobs(warm_up=warm_up)
    records = uploads.RecordStore()
    page = _page(token)
    app = Starlette(routes=_routes(page, jobs, records), lifespan=_lifespan(jobs, warm_up))
    # outermost first: every answer (a refusal too) carries the security headers
    app.add_middleware(_Guard, names=_host_names(host, port, hosts), port=port, token=token,
                       any_ip=host.strip() in WILDCARDS)
    app.add_middleware(_SecurityHeaders)
    app.state.jobs, app.state.token = jobs, token
    return app


def _host_names(host: str, port: int, hosts) -> set[str]:
    """The Host header values naming the server bound at ``host``:``port``, with ``hosts``."""
    h = host.strip()
    if ":" in h and not h.startswith("["):
        h = f"[{h}]"
    names = {f"{h}:{port}", *(hosts or ())}
    if h in ("127.0.0.1", "[::1]", "localhost", *WILDCARDS):
        names.add(f"localhost:{port}")  # the loopback's own name: not rebindable by a site
    return {n.lower() for n in names}


class _Guard:
    """ASGI middleware: refuses (403) a Host other than the server's, a request from another
    origin, an API call without the page's origin and token; (415) an API body of another
    media type. The security model in docs/app.md."""

    def __init__(self, app, names: set[str], port: int, token: str, any_ip: bool):
        self.app, self.names, self.port, self.any_ip = app, names, port, any_ip
        self.token = token.encode()

    def _host_ok(self, host: str) -> bool:
        if host in self.names:
            return True
        if not self.any_ip:
            return False
        name, _, port = host.rpartition(":")
        try:
            ipaddress.ip_address(name.strip("[]"))
        except ValueError:
            return False
        return port == str(self.port)

    def refusal(self, scope) -> tuple[int, str] | None:
        """(status, message) of a request refused, None for one let through."""
        headers = {k.decode("latin-1").lower(): v.decode("latin-1")
                   for k, v in scope["headers"]}
        host = headers.get("host", "").lower()
        if not self._host_ok(host):
            return 403, (f"host: {host[:60]!r}; allowed {', '.join(sorted(self.names))} "
                         f"(the address the app listens on)")
        path = scope["path"]
        if not path.startswith("/api/"):  # the page and its files: anyone may load them
            return None
        own = f"http://{host}"
        origin, referer = headers.get("origin"), headers.get("referer")
        if origin is not None:
            if origin.lower() != own:
                return 403, f"origin: {origin[:60]!r}; allowed only the app's own page ({own})"
        elif referer is not None:
            if not (referer.lower() == own or referer.lower().startswith(own + "/")):
                return 403, f"referer: another site; allowed only the app's own page ({own})"
        if origin is None and referer is None:
            return 403, f"origin: missing; the API answers only the app's own page ({own})"
        given = headers.get(TOKEN_HEADER, "").encode("latin-1")
        if not secrets.compare_digest(given, self.token):
            return 403, (f"{TOKEN_HEADER}: {'missing' if not given else 'wrong'}; the API "
                         f"answers only the page the app served (reload it)")
        if scope["method"] not in ("GET", "HEAD"):
            media = headers.get("content-type", "").split(";")[0].strip().lower()
            allowed = "application/octet-stream" if path in UPLOADS else "application/json"
            if media != allowed:
                return 415, f"content-type: {media or 'missing'!r}; allowed {allowed}"
        return None

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        refused = self.refusal(scope)
        if refused is None:
            return await self.app(scope, receive, send)
        status, msg = refused
        kind = "media-type" if status == 415 else "forbidden"
        return await _json({"error": msg, "kind": kind}, status)(scope, receive, send)


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
    """Compile (or load from numba's cache) the kernels of the page's first statics and
    response here (the ensemble's are warmed in the job worker)."""
    try:
        arch = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
        api.limit({"arch": arch})
        api.respond({"arch": arch, "pulse": {"kind": "oppenheim", "amplitude": -1.0,
                                             "duration": 0.2}, "t_end": 1.0})
    except Exception:  # noqa: BLE001 - warming up is an optimisation; a real request will say
        pass


#: Seconds uvicorn waits for open requests when asked to stop (Ctrl-C) before closing them.
GRACEFUL_S = 1.0


def server_config(app, **kwargs):
    """uvicorn's Config of the app: quiet, and stopping within about :data:`GRACEFUL_S`."""
    import uvicorn

    return uvicorn.Config(app, log_level="warning", timeout_graceful_shutdown=GRACEFUL_S,
                          **kwargs)


class BackgroundServer:
    """The app served by uvicorn in a daemon thread on a free loopback port (tests, scripts):
    ``with BackgroundServer() as url: ...``; ``url`` is ``http://127.0.0.1:PORT/``, ``token``
    the page's token (``headers``: what an API call of the page sends)."""

    def __init__(self, warm_up: bool = True, timeout_s: float = 30.0):
        self.warm_up, self.timeout_s = warm_up, timeout_s
        self.server = self.thread = self.token = self.url = None

    @property
    def headers(self) -> dict:
        return {"Origin": self.url.rstrip("/"), "X-Archrock-Token": self.token}

    def __enter__(self) -> str:
        import socket
        import threading
        import time

        import uvicorn

        sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
        app = create_app("127.0.0.1", port, warm_up=self.warm_up)
        self.token, self.url = app.state.token, f"http://127.0.0.1:{port}/"
        self.server = uvicorn.Server(server_config(app))
        self.thread = threading.Thread(target=self.server.run, kwargs={"sockets": [sock]},
                                       name="archrock-app-server", daemon=True)
        self.thread.start()
        end = time.monotonic() + self.timeout_s
        while not self.server.started:
            if time.monotonic() > end or not self.thread.is_alive():
                raise RuntimeError("the app's server did not start")
            time.sleep(0.02)
        return self.url

    def __exit__(self, *exc):
        self.server.should_exit = True
        self.thread.join(10)
        return False
