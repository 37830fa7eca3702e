"""The HTTP side: Starlette routes over :mod:`kinelab.web._api`, the page's static files,
request-size caps, and kinelab's errors as JSON with the right status.

The app answers its own page only: a request whose ``Host`` is not the address served
(DNS rebinding) or whose ``Origin`` is another site is refused (403), and so is a POST whose
body is not declared JSON (415: a form or ``text/plain``, which other sites may send without
asking).  The work of a request runs in worker threads, off the event loop; long work (a
derivation, a path-generation search, an animation) in worker processes of its own
(:mod:`kinelab.web._apart`), waited for by threads of their own, so that it neither keeps
the others waiting for a worker nor slows their work; what it may cost is estimated before
it starts (:mod:`kinelab.web._limits`).  Each request's work is a job (:mod:`kinelab.web._jobs`): how
far it has come is asked at ``/api/progress``, and it is stopped by ``/api/cancel`` or when
its request is closed.  Every error is ``{"error": message}``.
"""
from __future__ import annotations

import asyncio
import json
import logging
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from urllib.parse import urlsplit

from starlette.applications import Starlette
from starlette.exceptions import HTTPException
from starlette.middleware import Middleware
from starlette.requests import ClientDisconnect, Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from kinelab import _progress as progress
from kinelab._deadline import within
from kinelab.errors import (CancellationError, KinelabError, MemoryBudgetError, ModelError,
                            TimeLimitError, shown, shown_path)
from kinelab.web import _apart, _api, _dynamics, _export, _jobs, _limits

__all__ = ["create_app", "MAX_BODY", "WORKERS", "LONG_WORKERS", "LOOPBACK_NAMES"]

STATIC = Path(__file__).parent / "static"
MAX_BODY = 2 * 1024 * 1024
"""The largest request body, bytes: a model file is a few kilobytes."""

WORKERS = 4
"""Requests worked on at once (the others wait their turn); their memory is shared as
:mod:`kinelab.web._limits` says."""

LONG_WORKERS = 2
"""Long requests (derivations, path-generation searches, animations) worked on at once,
each in a worker process (:mod:`kinelab.web._apart`) waited for by a thread of its own
beside the :data:`WORKERS`: however many come, the others never wait for them."""

LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")
"""The names the page may be reached by when served on loopback (``Host`` without its port)."""

_log = logging.getLogger("kinelab.web")


class _TooLarge(Exception):
    pass


async def _body(request: Request) -> dict:
    """The request's JSON object, refused past MAX_BODY bytes or when it is not one."""
    declared = request.headers.get("content-length")
    if declared is not None and declared.isdigit() and int(declared) > MAX_BODY:
        raise _TooLarge()
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > MAX_BODY:
            raise _TooLarge()
        chunks.append(chunk)
    try:
        data = json.loads(b"".join(chunks) or b"{}")
    except (ValueError, RecursionError) as exc:
        if "digits" in str(exc):        # Python's limit on the digits of an integer
            raise KinelabError("body: a whole number of more than 4,300 digits; send numbers "
                               "a float can hold") from None
        raise KinelabError("body: expected a JSON object; send the request as JSON") from None
    if not isinstance(data, dict):
        raise KinelabError("body: expected a JSON object; send the request as JSON")
    return data


def _error(message: str, status: int, problems: tuple[str, ...] = ()) -> JSONResponse:
    """``{"error": message}``, with ``problems`` one by one when a model has several (one
    for each line of the message)."""
    return JSONResponse({"error": message, **({"problems": list(problems)} if problems else {})},
                        status_code=status)


def _status(exc: KinelabError) -> int:
    """413 for a request larger than the server takes, 503 while others hold the memory it
    needs, 422 for work that cannot go on (or not within its time, or cancelled), 400 for
    bad input."""
    if isinstance(exc, (MemoryBudgetError, _limits.TooLarge)):
        return 413
    if isinstance(exc, _limits.Busy):
        return 503
    if isinstance(exc, (TimeLimitError, CancellationError)):
        return 422
    return 400 if isinstance(exc, ValueError) or type(exc) is KinelabError else 422


def _is_json(request: Request) -> bool:
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    return media == "application/json"


def _answer(call, body: dict, raw: bool, path: str, job: _jobs.Job, jobs: _jobs.Jobs,
            apart: str | None = None) -> Response:
    """``call(body)`` and its answer's bytes, in a worker thread (or, with ``apart``, the
    call of that name in a worker process, :func:`kinelab.web._apart.run`), as ``job``: its
    progress kept, stopped when it is cancelled; what the request reserves is given back
    once the bytes are made, and the job is closed once its work has ended."""
    def work(apart: str | None) -> Response:
        result = _apart.run(apart, body, job) if apart else call(body)
        if isinstance(result, Response):
            return result
        if raw:
            return Response(result.encode(), media_type="application/json")
        try:        # strict JSON: a number that is not finite is kinelab's fault, said as such
            text = json.dumps(result, allow_nan=False)
        except ValueError:
            _log.exception("request %s gave a value that is not finite", path)
            return _error("internal error: the result holds a value that is not a finite "
                          "number; the server's log has the details", 500)
        return Response(text.encode(), media_type="application/json")
    try:
        job.start()
        with _limits.request(), progress.watching(job.report):
            if apart:                   # its process is ended when the job is cancelled
                try:
                    return work(apart)
                except _apart.Unavailable:
                    pass                # no worker process here: in this thread, then
            return within(None, work, None, cancel=job.cancel,
                          cancelled=f"{shown_path(path)}: cancelled after "
                                    f"{time.monotonic() - job.read:.1f} s, as asked")
    finally:
        jobs.close(job)


async def _closed(request: Request) -> None:
    """Returns when the client closes the request's connection (its body already read)."""
    while (await request.receive())["type"] != "http.disconnect":
        pass


def _retrieved(future) -> None:
    """The outcome of work no one waits for any more, taken so that asyncio does not call
    it lost (a fault of kinelab's logged all the same)."""
    if future.cancelled():
        return
    exc = future.exception()
    if exc is not None and not isinstance(exc, KinelabError):
        _log.error("a request whose client had gone failed", exc_info=exc)


def _route(call, *, raw: bool = False, apart=None):
    """A POST endpoint calling ``call(body)`` in one of the app's worker threads, as a job
    whose id is the body's ``"job"`` (taken out of it); kinelab's errors become ``{"error":
    message}`` with their status (see :func:`_status`).  The client closing the request
    cancels it.  ``apart`` (a name of :data:`kinelab.web._apart.CALLS`, or a function of
    the body giving one or None) sends long work to a worker process instead, waited for by
    one of the long workers' threads."""
    async def endpoint(request: Request) -> Response:
        if not _is_json(request):
            return _error(f"{shown_path(request.url.path)}: expected a JSON body (Content-Type: "
                          "application/json), got "
                          f"{request.headers.get('content-type') or 'none'}", 415)
        try:
            body = await _body(request)
            jobs = request.app.state.jobs
            job = jobs.open(body.pop("job", None), request.url.path)
            state = request.app.state
            name = apart(body) if callable(apart) else apart
            pool = state.long_workers if name else state.workers
            loop = asyncio.get_running_loop()
            work = loop.run_in_executor(pool, _answer, call, body, raw, request.url.path, job,
                                        jobs, name)
            closed = asyncio.ensure_future(_closed(request))
            try:
                await asyncio.wait({work, closed}, return_when=asyncio.FIRST_COMPLETED)
            finally:
                closed.cancel()
            if not work.done():     # no one to answer: stop the work, and wait no more
                job.cancel.set()
                work.add_done_callback(_retrieved)
                _log.info("%s: the client closed the connection; its work is stopped",
                          shown_path(request.url.path))
                return _error("the client closed the connection", 400)
            return work.result()
        except _TooLarge:
            return _error(f"body: larger than {MAX_BODY // 1024:,} KiB; a model file is a few "
                          "kilobytes: send less", 413)
        except ClientDisconnect:     # the client went away: nothing to answer, nothing wrong
            _log.info("%s: the client closed the connection before its request was read",
                      shown_path(request.url.path))
            return _error("the client closed the connection", 400)
        except KinelabError as exc:
            return _error(str(exc), _status(exc),
                          exc.shown_problems() if isinstance(exc, ModelError) else ())
        except Exception:            # a fault of kinelab's: logged, never a traceback sent
            _log.exception("request %s failed", request.url.path)
            return _error("internal error: the server could not answer this request; "
                          "the server's log has the details", 500)
    return endpoint


async def _progress(request: Request) -> Response:
    """``/api/progress``: what job ``{"job": id}`` is doing (``"state": "not running"`` when
    it is not listed: not arrived yet, or ended), or with no id every job listed
    (``"jobs"``).  Answered on the event loop, never behind the work it reports."""
    def answer(jobs: _jobs.Jobs, body: dict) -> dict:
        if body.get("job") is None:
            return {"jobs": [j.view() for j in jobs.listed()]}
        job = jobs.get(body["job"])
        return job.view() if job is not None else {"job": body["job"], "state": "not running"}
    return await _on_loop(request, answer)


async def _cancel(request: Request) -> Response:
    """``/api/cancel``: stop the work of job ``{"job": id}``; ``cancelled`` says whether it
    was running (if its request has not arrived yet, it will be stopped when it does)."""
    return await _on_loop(request, lambda jobs, body: {
        "job": body.get("job"), "cancelled": jobs.cancel(body.get("job"))})


async def _on_loop(request: Request, answer) -> Response:
    """A small POST answered on the event loop: ``answer(jobs, body)``, JSON out."""
    if not _is_json(request):
        return _error(f"{shown_path(request.url.path)}: expected a JSON body (Content-Type: "
                      f"application/json), got {request.headers.get('content-type') or 'none'}",
                      415)
    try:
        return JSONResponse(answer(request.app.state.jobs, await _body(request)))
    except _TooLarge:
        return _error(f"body: larger than {MAX_BODY // 1024:,} KiB", 413)
    except ClientDisconnect:
        return _error("the client closed the connection", 400)
    except KinelabError as exc:
        return _error(str(exc), _status(exc))


def _get(call):
    async def endpoint(request: Request) -> Response:
        try:
            return JSONResponse(call(**request.path_params))
        except KinelabError as exc:
            return _error(str(exc), 404)
    return endpoint


async def _index(request: Request) -> Response:
    return FileResponse(STATIC / "index.html")


async def _start(request: Request) -> Response:
    """The model the server was started with (``kinelab serve MODEL``), if any."""
    return JSONResponse(request.app.state.start or {})


async def _not_found(request: Request, exc: HTTPException) -> Response:
    path = shown_path(request.url.path)
    if exc.status_code == 404:
        return _error(f"{path}: no such page or API route; the API is under /api/ "
                      "(see docs/web.md)", 404)
    if exc.status_code == 405:
        return _error(f"{path}: method {request.method} not allowed here", 405)
    return _error(exc.detail, exc.status_code)


async def _fault(request: Request, exc: Exception) -> Response:
    """A fault that escaped a route (logged by the server): JSON like every other error."""
    return _error("internal error: the server could not answer this request; the server's "
                  "log has the details", 500)


class Served:
    """Where the app is served: the names a request's ``Host`` may give (None: any) and the
    port (None: any, until the server has bound one)."""

    def __init__(self, host: str = "127.0.0.1", port: int | None = None):
        self.names = served_names(host)
        self.port = port


def _split_host(host: str) -> tuple[str, str]:
    """``("name", "port")`` of a Host header (the port "" when it gives none)."""
    if host.startswith("["):
        end = host.find("]") + 1
        name, rest = host[:end], host[end:]
        return name.lower(), rest[1:] if rest.startswith(":") else ""
    name, _, port = host.partition(":")
    return name.lower(), port


class _SameSite:
    """Refuse (403) a request whose ``Host`` is not the address the app is served at, or
    whose ``Origin`` is not the page's own (``http://`` and that address)."""

    def __init__(self, app, served: Served):
        self.app = app
        self.served = served

    async def __call__(self, scope, receive, send):
        if scope["type"] == "http":
            headers = {k.decode("latin-1").lower(): v.decode("latin-1")
                       for k, v in scope["headers"]}
            problem = self.problem(headers.get("host", ""), headers.get("origin"))
            if problem:
                await _error(problem, 403)(scope, receive, send)
                return
        await self.app(scope, receive, send)

    def problem(self, host: str, origin: str | None) -> str | None:
        name, port = _split_host(host)
        names, served = self.served.names, self.served.port
        if (names is not None and name not in names) or (
                served is not None and (port or "80") != str(served)):
            return (f"Host: expected the address this server is at, got {shown(host)}; open "
                    "the address kinelab serve printed")
        if origin is not None:
            parts = urlsplit(origin)
            if parts.scheme != "http" or parts.netloc.lower() != host.lower():
                return (f"Origin: {shown(origin)} is another site; the app answers its own "
                        "page only")
        return None


def create_app(start: dict | None = None, *, host: str = "127.0.0.1",
               port: int | None = None) -> Starlette:
    """The web app: the page at ``/``, its files under ``/static/``, the API under
    ``/api/``.  ``start``: the model shown first (``{"model": ..., "source": ...}``).

    Requests must name the app by the address it is served at, ``host`` (on loopback, any of
    ``127.0.0.1``, ``localhost``, ``[::1]``; on a wildcard address such as ``0.0.0.0``, any
    name) and ``port`` (None: any port)."""
    routes = [
        Route("/", _index),
        Route("/api/start", _start),
        Route("/api/catalogue", _get(_api.catalogue)),
        Route("/api/examples/{name}", _get(_api.example)),
        Route("/api/load", _route(_api.load), methods=["POST"]),
        Route("/api/save", _route(_api.save), methods=["POST"]),
        Route("/api/analyze", _route(_api.analyze, raw=True), methods=["POST"]),
        Route("/api/study", _route(_api.study), methods=["POST"]),
        Route("/api/configuration", _route(_api.configuration), methods=["POST"]),
        Route("/api/drag", _route(_api.drag), methods=["POST"]),
        Route("/api/flip", _route(_api.flip), methods=["POST"]),
        Route("/api/derive", _route(_api.derivation, apart="derive"), methods=["POST"]),
        Route("/api/synthesize", _route(_api.synthesize, apart=lambda body: "synthesize"
                                        if _api.is_search(body) else None), methods=["POST"]),
        Route("/api/export", _route(_export.export, raw=True, apart=lambda body: "export"
                                    if _export.is_long(body) else None), methods=["POST"]),
        Route("/api/dynamics", _route(_dynamics.dynamics, raw=True), methods=["POST"]),
        Route("/api/progress", _progress, methods=["POST"]),
        Route("/api/cancel", _cancel, methods=["POST"]),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    served = Served(host, port)
    app = Starlette(routes=routes, middleware=[Middleware(_SameSite, served=served)],
                    exception_handlers={HTTPException: _not_found, Exception: _fault})
    app.state.start = start
    app.state.served = served
    app.state.workers = ThreadPoolExecutor(WORKERS, thread_name_prefix="kinelab-web")
    app.state.long_workers = ThreadPoolExecutor(LONG_WORKERS, thread_name_prefix="kinelab-long")
    app.state.jobs = _jobs.Jobs()
    return app


def served_names(host: str) -> frozenset[str] | None:
    """The names a request's ``Host`` may give for an app served at ``host``: loopback's
    for loopback, ``host`` itself otherwise, None (any) for a wildcard address."""
    if host in ("0.0.0.0", "::", ""):
        return None
    shown = f"[{host}]" if ":" in host and not host.startswith("[") else host
    if shown.lower() in LOOPBACK_NAMES:
        return frozenset(LOOPBACK_NAMES)
    return frozenset({shown.lower()})
