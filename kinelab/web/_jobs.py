"""The work the server is doing, each request's by the id the page gave it (``"job"`` in its
body): how long it has run, how far it has come, and a way to stop it.

A request's work runs in a worker thread within :func:`kinelab._deadline.within`, watched
by its :class:`Job`: what the work reports (:mod:`kinelab._progress`) is kept for
``/api/progress`` to answer, and :meth:`Jobs.cancel` (``/api/cancel``, or the page closing
the request) sets the job's event, at which the work is stopped where it is
(a :class:`~kinelab.errors.CancellationError`).  A job is listed from the moment its request
is read until its work has ended, so that a job no longer listed is work no longer running.
"""
from __future__ import annotations

import re
import threading
import time
from collections import OrderedDict

from kinelab.errors import ModelError, describe, shown

__all__ = ["Job", "Jobs", "JOB_ID"]

JOB_ID = re.compile(r"[A-Za-z0-9_-]{1,64}")
"""What a job's id may be: letters, digits, ``-`` and ``_``, at most 64 of them (the page
gives each request a random one)."""

_REMEMBERED = 256       # ids cancelled before their request arrived, kept for when it does


def check_id(value) -> str:
    """A job id from a request, or a ModelError (400) saying what one is."""
    if not isinstance(value, str) or not JOB_ID.fullmatch(value):
        raise ModelError(f"job: expected an id of 1 to 64 letters, digits, '-' or '_', got "
                         f"{describe(value)}")
    return value


class Job:
    """One request's work: its route, when it was read, its state and its progress."""

    def __init__(self, job_id: str | None, what: str):
        self.id = job_id
        self.what = what
        self.read = time.monotonic()
        self.started: float | None = None       # when a worker thread took it
        self.cancel = threading.Event()
        self.label = ""
        self.fraction: float | None = None
        self.thread: int | None = None

    def start(self) -> None:
        self.started = time.monotonic()
        self.thread = threading.get_ident()

    def report(self, label: str, fraction: float | None) -> None:
        """What the work says of itself (a :mod:`kinelab._progress` watcher)."""
        self.label = label
        if fraction is not None:
            self.fraction = fraction

    def state(self) -> str:
        if self.cancel.is_set():
            return "stopping"
        return "waiting" if self.started is None else "running"

    def view(self) -> dict:
        """What ``/api/progress`` says of it: its id and route, its state (``waiting`` for a
        worker, ``running``, ``stopping`` once cancelled), the seconds since its request was
        read, and what its work last reported (``label``, ``fraction`` done or None)."""
        return {"job": self.id, "what": self.what, "state": self.state(),
                "seconds": round(time.monotonic() - self.read, 3), "label": self.label,
                "fraction": None if self.fraction is None else round(self.fraction, 4)}


class Jobs:
    """The jobs of the requests being worked on (and waiting for a worker)."""

    def __init__(self):
        self._lock = threading.Lock()
        self._jobs: dict[object, Job] = {}
        self._cancelled: OrderedDict[str, None] = OrderedDict()

    def open(self, job_id, what: str) -> Job:
        """The job of a request just read (``job_id`` None: one with no id, which only the
        request's closing can cancel).  An id in use is refused (400); an id cancelled
        before its request arrived gives a job cancelled from the start."""
        if job_id is not None:
            check_id(job_id)
        job = Job(job_id, what)
        with self._lock:
            if job_id is not None:
                if job_id in self._jobs:
                    raise ModelError(f"job: {shown(job_id)} is already running; give each "
                                     "request an id of its own")
                if job_id in self._cancelled:
                    del self._cancelled[job_id]
                    job.cancel.set()
            self._jobs[job_id if job_id is not None else job] = job
        return job

    def close(self, job: Job) -> None:
        """The job's work has ended (whatever its outcome)."""
        with self._lock:
            key = job.id if job.id is not None else job
            if self._jobs.get(key) is job:
                del self._jobs[key]

    def cancel(self, job_id: str) -> bool:
        """Stop a job's work; whether it was listed (if not, its request may still be on its
        way: a job of that id opened later starts cancelled)."""
        check_id(job_id)
        with self._lock:
            job = self._jobs.get(job_id)
            if job is None:
                self._cancelled[job_id] = None
                while len(self._cancelled) > _REMEMBERED:
                    self._cancelled.popitem(last=False)
                return False
        job.cancel.set()
        return True

    def get(self, job_id: str) -> Job | None:
        check_id(job_id)
        with self._lock:
            return self._jobs.get(job_id)

    def listed(self) -> list[Job]:
        """Every job listed now, oldest first."""
        with self._lock:
            return sorted(self._jobs.values(), key=lambda j: j.read)
