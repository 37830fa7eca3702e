"""Long work in processes of its own: a derivation, a synthesis, an animation.

Python runs one thread at a time in a process, so a derivation (seconds of sympy) in one of
the server's threads would slow every other request's work by as much as it takes.  Here it
runs in a worker process instead (at most :data:`kinelab.web._app.LONG_WORKERS` of them,
started when first needed, each ending after :data:`IDLE` seconds without work), and the
server's threads only wait for its answer.  The worker sends what the work reports of
itself (:mod:`kinelab._progress`) as it goes, then the answer, or kinelab's error as it was
raised; a job cancelled (:mod:`kinelab.web._jobs`) ends its worker process at once, wherever
the work is, even inside one long C call, and the next long request starts another.

The server's bounds hold in the worker: the memory budget, the derivation's and the
animation's time limits and the search's effort are sent with each call.
"""
from __future__ import annotations

import logging
import multiprocessing
import os
import threading
import time

from kinelab.errors import CancellationError

__all__ = ["run", "prestart", "Unavailable", "CALLS", "IDLE", "workers"]

IDLE = 300.0
"""Seconds a worker process waits for work before it ends (the next long request starts
another, which takes a second or two)."""

NICENESS = 5
"""How much lower the worker processes' scheduling priority is than the server's (POSIX
``nice``): on a busy processor, the short requests the server answers itself go first."""

CALLS = {"derive": ("kinelab.web._api", "derivation"),
         "synthesize": ("kinelab.web._api", "synthesize"),
         "export": ("kinelab.web._export", "export")}
"""The long work a worker process does, by name: the function of the server it calls."""

# the module attributes a worker takes from the server with each call (tests and users may
# change them in the server)
_SETTINGS = (("kinelab.web._api", "DERIVE_SECONDS"), ("kinelab.web._api", "MAX_SEARCH_EFFORT"),
             ("kinelab.web._export", "ANIMATION_SECONDS"))
_POLL = 0.05        # s between the waiting thread's looks at the job's cancel
_CONTEXT = multiprocessing.get_context("spawn")     # a fork of a threaded server is unsafe
_log = logging.getLogger("kinelab.web")


class Unavailable(Exception):
    """No worker process can start here (a script that starts the app without the
    ``if __name__ == "__main__":`` guard a new process needs, say): the long work runs in
    the server's threads instead."""


class _Worker:
    """A worker process and the server's end of its pipe; ``ready`` once it has said so
    (its imports done)."""

    def __init__(self):
        self.conn, child = _CONTEXT.Pipe()
        self.process = _CONTEXT.Process(target=_serve, args=(child,), daemon=True,
                                        name="kinelab-long-work")
        self.ready = False
        try:
            self.process.start()
        except Exception as exc:        # noqa: BLE001 -- said as why there is no worker
            self.conn.close()
            raise Unavailable(f"a worker process cannot start here ({exc})".replace("\n", " ")
                              ) from None
        finally:
            child.close()

    def alive(self) -> bool:
        return self.process.is_alive()

    def end(self) -> None:
        """Stop the process now (a cancelled job), whatever it is doing."""
        self.process.kill()
        self.process.join(10)
        self.conn.close()


_idle: list[_Worker] = []
_busy: set[_Worker] = set()
_lock = threading.Lock()
_broken: list[str] = []         # why worker processes cannot start here, once found


def workers() -> dict:
    """The worker processes now: ``{"busy": [pid, ...], "idle": [pid, ...]}``."""
    with _lock:
        return {"busy": [w.process.pid for w in _busy],
                "idle": [w.process.pid for w in _idle if w.alive()]}


def prestart() -> None:
    """Start a worker process ahead of the first long request (the server does at its
    start), unless one is there."""
    with _lock:
        if any(w.alive() for w in _idle) or _busy or _broken:
            return
    try:
        worker = _Worker()
    except Unavailable as exc:
        _broke(str(exc))
        return
    with _lock:
        _idle.append(worker)


def _broke(why: str) -> None:
    if not _broken:
        _broken.append(why)
        _log.warning("long work runs in the server's threads: %s", why)


def _take(job) -> _Worker:
    """A worker process ready for a call (an idle one, or one started now), busy."""
    with _lock:
        worker = None
        while _idle and worker is None:
            worker = _idle.pop()
            if not worker.alive():
                worker.conn.close()
                worker = None
        if worker is not None:
            _busy.add(worker)
    if worker is None:
        job.report("starting a worker process", None)
        try:
            worker = _Worker()      # outside the lock: starting a process takes a while
        except Unavailable as exc:
            _broke(str(exc))
            raise
        with _lock:
            _busy.add(worker)
    try:
        while not worker.ready:     # its imports done: it says so
            _check_cancel(job)
            if worker.conn.poll(_POLL):
                kind, _ = _received(worker)
                worker.ready = kind == "ready"
            elif not worker.alive():
                raise Unavailable(f"a worker process ended as it started (exit code "
                                  f"{worker.process.exitcode}); see the server's log")
    except BaseException as exc:
        _give_back(worker, False)
        if isinstance(exc, Unavailable):
            _broke(str(exc))
        raise
    return worker


def _received(worker: _Worker):
    try:
        return worker.conn.recv()
    except (EOFError, OSError):
        raise RuntimeError(f"the worker process ended (exit code "
                           f"{worker.process.exitcode})") from None


def _check_cancel(job) -> None:
    if job.cancel.is_set():
        raise CancellationError(f"{job.what}: cancelled after "
                                f"{time.monotonic() - job.read:.1f} s, as asked")


def _give_back(worker: _Worker, healthy: bool) -> None:
    with _lock:
        _busy.discard(worker)
        if healthy:
            _idle.append(worker)
            return
    worker.end()


def run(name: str, body: dict, job) -> object:
    """``CALLS[name](body)`` in a worker process, for ``job`` (its progress kept, the
    process ended when the job is cancelled): its answer, or the error it raised.  Raises
    :class:`Unavailable` where no worker process can start."""
    if _broken:
        raise Unavailable(_broken[0])
    import importlib
    settings = {f"{module}.{attr}": getattr(importlib.import_module(module), attr)
                for module, attr in _SETTINGS}
    from kinelab import _memory
    settings["memory_budget"] = _memory.memory_budget()
    _check_cancel(job)
    worker = _take(job)
    healthy = False
    try:
        worker.conn.send((name, body, settings))
        while True:
            _check_cancel(job)
            if not worker.conn.poll(_POLL):
                if not worker.alive():
                    raise RuntimeError(f"the worker process of {name} ended with code "
                                       f"{worker.process.exitcode}")
                continue
            kind, value = _received(worker)
            if kind == "progress":
                job.report(*value)
            elif kind == "answer":
                healthy = True
                return _response(value)
            elif kind == "error":
                healthy = True
                raise value
            else:                       # a fault of kinelab's, logged here with its traceback
                healthy = True
                _log.error("%s failed in its worker process:\n%s", name, value)
                raise RuntimeError(f"{name} failed in its worker process")
    finally:
        _give_back(worker, healthy)


def _response(value):
    """The answer as the route gives it: plain data, or a download rebuilt as a Response."""
    if isinstance(value, tuple) and value and value[0] == "response":
        from starlette.responses import Response
        _, content, media_type, headers = value
        return Response(content, media_type=media_type, headers=headers)
    return value


# -- in the worker process ----------------------------------------------------------------
def _orphaned(parent: int) -> None:
    """End this worker as soon as the server has gone, whatever it is doing (a server ended
    by a signal does not end its worker processes itself)."""
    while os.getppid() == parent:
        time.sleep(0.5)
    os._exit(0)


def _serve(conn) -> None:
    """A worker process: calls, one at a time, until the server's end of the pipe closes or
    no call comes for :data:`IDLE` seconds."""
    import signal
    threading.Thread(target=_orphaned, args=(os.getppid(),), name="kinelab-parent",
                     daemon=True).start()
    signal.signal(signal.SIGINT, signal.SIG_IGN)     # Ctrl-C is the server's to take
    if hasattr(os, "nice"):             # the server's own requests come first on a busy processor
        os.nice(NICENESS)
    import importlib
    import traceback

    from kinelab import _memory
    from kinelab import _progress as progress
    from kinelab.errors import KinelabError
    from kinelab.web import _limits
    calls = {name: getattr(importlib.import_module(module), attr)
             for name, (module, attr) in CALLS.items()}
    try:
        conn.send(("ready", None))
    except (EOFError, OSError):
        return
    while True:
        try:
            if not conn.poll(IDLE):
                return
            name, body, settings = conn.recv()
        except (EOFError, OSError):      # the server has gone
            return
        for key, value in settings.items():
            if key == "memory_budget":
                _memory.memory_budget(value)
            else:
                module, _, attr = key.rpartition(".")
                setattr(importlib.import_module(module), attr, value)
        try:
            with _limits.request(), progress.watching(
                    lambda label, fraction: conn.send(("progress", (label, fraction)))):
                answer = calls[name](body)
            if hasattr(answer, "body") and hasattr(answer, "media_type"):    # a download
                answer = ("response", bytes(answer.body), answer.media_type,
                          {k: v for k, v in answer.headers.items()
                           if k.lower() not in ("content-length", "content-type")})
            message = ("answer", answer)
        except KinelabError as exc:
            message = ("error", exc)
        except Exception:               # noqa: BLE001 -- sent to the server's log
            message = ("fault", traceback.format_exc())
        try:
            conn.send(message)
        except (EOFError, OSError):
            return
