"""Time limits that hold in any thread: :func:`within` runs a call and stops it at a deadline,
or when another thread asks it to stop (an event set: the web app's *cancel*).

A timer signal (``SIGALRM``) interrupts only the main thread, so a limit built on it does
nothing in a web server's worker threads.  Here a watchdog thread raises an exception in the
working thread when its time is up (``PyThreadState_SetAsyncExc``), which the interpreter
delivers at its next bytecode boundary: pure-Python work such as sympy's stops within
milliseconds, wherever it is.  Work inside one long C call stops when that call returns.

The exception is a :class:`BaseException` of a class made for each call, so neither
sympy's ``except Exception`` nor an inner limit takes it for its own; the watchdog raises
it again every :data:`_AGAIN` seconds until the call has ended, in case a bare ``except:``
swallowed it, and holds its shot while the thread imports a module (which a shot would
leave half made).  A shot that lands in a finalizer or a weak reference's callback cannot
be raised there (Python reports it as unraisable); kinelab's hook says nothing of it and
raises it again at the next line of the frame that ran the callback (a trace function on
that frame alone), so work that spends nearly all its time in callbacks stops as promptly
as any other.  The call's end and the watchdog's shot exclude each other without a lock:
the watchdog tests "ended?" and shoots in one step (no bytecode boundary between the test
and the C call, so no other thread runs in between), and the working thread marks the end
and then replaces a shot not yet delivered by one of its own, which it takes at once; so
nothing is raised after :func:`within` returns.  (Withdrawing the shot instead, by
``PyThreadState_SetAsyncExc`` with no exception, leaves Python 3.11 signalling an
exception that is not there, and a thread with a trace function set, a debugger's or a
coverage tool's, then loops for ever at its next call.)  A call with no deadline that only
a cancel can stop is watched the same way by one thread shared by all such calls, so that
a short call does not pay for a thread of its own.
"""
from __future__ import annotations

import ctypes
import math
import sys
import threading
import time

from kinelab.errors import CancellationError, TimeLimitError

__all__ = ["within"]

_AGAIN = 0.1        # s between shots while the call goes on
_POLL = 0.05        # s between the watchdog's looks at the clock before the deadline

_shoot = ctypes.pythonapi.PyThreadState_SetAsyncExc
_shoot.argtypes = (ctypes.c_ulong, ctypes.py_object)
_shoot.restype = ctypes.c_int


class _Expired(BaseException):
    """Raised in the working thread at its deadline (a class of its own per call)."""


class _Withdrawn(BaseException):
    """Put in place of a shot not yet delivered when the call ends, and taken at once."""


def _checkpoint() -> None:
    """Nothing: Python delivers a pending asynchronous exception as a function starts."""


def _unraisable(previous):
    """A ``sys.unraisablehook`` that passes everything to ``previous`` but a deadline's shot
    delivered where it cannot be raised (a finalizer, a weak reference's callback), which
    would otherwise print a traceback in a server's log: that one is raised again in the
    frame that ran the callback (the hook's caller)."""
    def hook(unraisable):
        if isinstance(unraisable.exc_value, _Expired):
            _raise_at_next_line(type(unraisable.exc_value), sys._getframe(1))
        else:
            previous(unraisable)
    return hook


def _raise_at_next_line(expired: type, frame) -> None:
    """Raise ``expired`` at the next line ``frame`` runs, unless its call has ended by then.

    A trace function set on that frame alone (Python calls a frame's own trace function
    only while one is set for the thread, so the thread gets one that traces nothing, or
    keeps the one it had); :func:`within` puts the thread's trace function back as it
    found it.  Raising from a trace function unsets the thread's, which is why it is put
    back at the end, not at the raise."""
    if expired.ended or frame is None:
        return

    def line(frame, event, arg):
        if not expired.ended:
            raise expired
        return None

    if not expired.tracing:
        expired.tracing.append(sys.gettrace())
    frame.f_trace = line
    if sys.gettrace() is None:
        sys.settrace(_nothing)


def _nothing(frame, event, arg):
    """The thread's trace function while one frame has its own: new frames are not traced."""
    return None


sys.unraisablehook = _unraisable(sys.unraisablehook)


def _importing(thread: int) -> bool:
    """Whether a thread is importing a module: a module stopped midway would be left out
    of ``sys.modules`` (or, for a class being made, turned into another error)."""
    frame = sys._current_frames().get(thread)
    while frame is not None:
        if frame.f_code.co_filename.startswith("<frozen importlib"):
            return True
        frame = frame.f_back
    return False


def _watch(thread: int, expired: type, ended: list, seconds: float, cancel,
           cancelled: list) -> None:
    deadline = time.monotonic() + seconds
    while not ended:
        left = deadline - time.monotonic()
        stop = cancel is not None and cancel.is_set()
        if (left > 0 and not stop) or _importing(thread):
            time.sleep(min(left, _POLL) if left > 0 and not stop else _POLL / 5)
            continue
        if stop and not cancelled:
            cancelled.append(True)      # said before the shot: the call's end reads it
        if not ended:                   # the test and the shot: one step under the GIL
            _shoot(thread, expired)
        time.sleep(_AGAIN)


class _Cancellable:
    """The calls only a cancel can stop (no deadline), watched by one thread for them all:
    a thread of their own each would cost more than a short call (the web app's drags)."""

    def __init__(self):
        self._lock = threading.Lock()
        self._calls: dict = {}
        self._thread: threading.Thread | None = None

    def watch(self, key, thread: int, expired: type, ended: list, cancel, cancelled: list) -> None:
        with self._lock:
            self._calls[key] = (thread, expired, ended, cancel, cancelled, [0.0])
            if self._thread is None or not self._thread.is_alive():
                self._thread = threading.Thread(target=self._run, name="kinelab-cancel",
                                                daemon=True)
                self._thread.start()

    def forget(self, key) -> None:
        with self._lock:
            self._calls.pop(key, None)

    def _run(self) -> None:
        while True:
            time.sleep(_POLL)
            with self._lock:
                calls = list(self._calls.values())
            for thread, expired, ended, cancel, cancelled, shot in calls:
                if ended or not cancel.is_set() or _importing(thread):
                    continue
                now = time.monotonic()
                if now - shot[0] < _AGAIN:
                    continue
                shot[0] = now
                if not cancelled:
                    cancelled.append(True)
                if not ended:           # the test and the shot: one step under the GIL
                    _shoot(thread, expired)


_cancellable = _Cancellable()


def _caused_by(exc: BaseException, expired: type) -> bool:
    """Whether ``exc`` is, or was raised while handling, the deadline's exception (Python
    turns one raised in ``__set_name__`` into a RuntimeError, and so may code that catches
    everything)."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, expired):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False


def within(seconds: float | None, call, *args, message: str | None = None,
           cancel: threading.Event | None = None, cancelled: str | None = None):
    """``call(*args)``, stopped after ``seconds`` with a :class:`TimeLimitError` (whose
    text is ``message``); ``None`` or ``inf`` runs it without a limit.  With ``cancel``,
    it is also stopped as soon as that event is set (by another thread), with a
    :class:`CancellationError` whose text is ``cancelled``; an event set before the call
    stops it before it starts.

    Limits nest: an inner one ends the inner call only; an outer one that expires first
    (or is cancelled) goes through the inner call as it is.

    >>> within(1.0, sum, [1, 2, 3])
    6
    """
    if cancel is not None and cancel.is_set():
        raise CancellationError(cancelled or "cancelled before it started")
    if (seconds is None or math.isinf(seconds)) and cancel is None:
        return call(*args)
    seconds = math.inf if seconds is None else max(seconds, 0.0)
    thread = threading.get_ident()
    ended: list = []
    # the thread's trace function before a shot was raised again by tracing (see _unraisable)
    expired = type("Expired", (_Expired,), {"ended": ended, "tracing": []})
    stopped: list = []          # the watchdog's shot was a cancellation, not the deadline
    shared = math.isinf(seconds)        # a cancel only: the watcher of all such calls
    key = object()
    try:
        try:
            if shared:
                _cancellable.watch(key, thread, expired, ended, cancel, stopped)
            else:
                threading.Thread(target=_watch, args=(thread, expired, ended, seconds, cancel,
                                                      stopped),
                                 name="kinelab-deadline", daemon=True).start()
            return call(*args)
        finally:
            # After the first C call the watchdog shoots no more (a shot delivered right
            # after it is the one the except clause below takes); a shot fired before it
            # and not yet delivered is replaced by one taken here.
            ended.append(True)
            try:
                _shoot(thread, _Withdrawn)
                _checkpoint()
            except _Withdrawn:
                pass
            if expired.tracing:
                sys.settrace(expired.tracing[0])
            if shared:
                _cancellable.forget(key)
    except BaseException as exc:
        if _caused_by(exc, expired):
            if stopped:
                raise CancellationError(cancelled or "cancelled") from None
            raise TimeLimitError(message or f"stopped after {seconds:g} s, its time limit") from None
        raise
