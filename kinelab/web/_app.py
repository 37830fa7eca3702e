"""The HTTP side: Starlette routes over :mod:`kinelab.web._api`, the page's static files,
request-size caps, and kinelab's errors as JSON with the right status."""
from __future__ import annotations

import json
import logging
from pathlib import Path

from starlette.applications import Starlette
from starlette.exceptions import HTTPException
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from kinelab.errors import KinelabError, ModelError, shown_path
from kinelab.web import _api, _export

__all__ = ["create_app", "MAX_BODY"]

STATIC = Path(__file__).parent / "static"
MAX_BODY = 2 * 1024 * 1024
"""The largest request body, bytes: a model file is a few kilobytes."""

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
    """``{"error": message}``, with ``problems`` one by one when a model has several."""
    return JSONResponse({"error": message, **({"problems": list(problems)} if problems else {})},
                        status_code=status)


def _route(call, *, raw: bool = False):
    """A POST endpoint calling ``call(body)`` in a worker thread; kinelab's errors become
    ``{"error": message}`` (400 for bad input, 422 for an analysis that cannot go on)."""
    from starlette.concurrency import run_in_threadpool

    async def endpoint(request: Request) -> Response:
        try:
            body = await _body(request)
            result = await run_in_threadpool(call, body)
        except _TooLarge:
            return _error(f"body: larger than {MAX_BODY // 1024:,} KiB; a model file is a few "
                          "kilobytes: send less", 413)
        except KinelabError as exc:
            return _error(str(exc), 400 if isinstance(exc, ValueError) or
                          type(exc) is KinelabError else 422,
                          exc.problems if isinstance(exc, ModelError) else ())
        except Exception:            # a fault of kinelab's: logged, never a traceback sent
            _log.exception("request %s failed", request.url.path)
            return _error("internal error: the server could not answer this request; "
                          "the server's log has the details", 500)
        if raw:
            if isinstance(result, Response):
                return result
            return Response(result, media_type="application/json")
        try:        # strict JSON: a number that is not finite is kinelab's fault, said as such
            return Response(json.dumps(result, allow_nan=False), media_type="application/json")
        except ValueError:
            _log.exception("request %s gave a value that is not finite", request.url.path)
            return _error("internal error: the result holds a value that is not a finite "
                          "number; the server's log has the details", 500)
    return endpoint


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


def create_app(start: dict | None = None) -> Starlette:
    """The web app: the page at ``/``, its files under ``/static/``, the API under
    ``/api/``.  ``start``: the model shown first (``{"model": ..., "source": ...}``)."""
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
        Route("/api/derive", _route(_api.derivation), methods=["POST"]),
        Route("/api/synthesize", _route(_api.synthesize), methods=["POST"]),
        Route("/api/export", _route(_export.export, raw=True), methods=["POST"]),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    app = Starlette(routes=routes, exception_handlers={HTTPException: _not_found})
    app.state.start = start
    return app
