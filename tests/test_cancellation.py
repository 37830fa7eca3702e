"""Work stopped when another thread asks (``within(..., cancel=event)``), and the progress
long work reports to whoever watches it (:mod:`kinelab._progress`)."""
import threading
import time

import pytest

from kinelab import _progress as progress
from kinelab._deadline import within
from kinelab.errors import CancellationError, TimeLimitError

MARGIN = 10.0       # s a loaded machine may take to stop and say so


def busy(seconds, started=None):
    """Python work (a C call such as time.sleep stops only when it returns)."""
    if started is not None:
        started.set()
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass
    return "done"


def test_a_cancelled_call_stops_at_once_with_its_message():
    cancel, started, out = threading.Event(), threading.Event(), {}

    def work():
        try:
            within(None, busy, 60, started, cancel=cancel, cancelled="the derivation: cancelled")
        except BaseException as exc:        # noqa: BLE001 -- handed to the test
            out["error"] = exc
        out["ended"] = time.perf_counter()
    worker = threading.Thread(target=work)
    worker.start()
    assert started.wait(60)
    asked = time.perf_counter()
    cancel.set()
    worker.join(60)
    assert not worker.is_alive()
    assert isinstance(out["error"], CancellationError)
    assert str(out["error"]) == "the derivation: cancelled"
    assert out["ended"] - asked < MARGIN


def test_cancelled_before_it_starts_it_never_runs():
    cancel = threading.Event()
    cancel.set()
    ran = []
    with pytest.raises(CancellationError, match="not wanted"):
        within(None, ran.append, 1, cancel=cancel, cancelled="not wanted")
    assert ran == []


def test_a_call_not_cancelled_returns_and_the_deadline_still_holds():
    cancel = threading.Event()
    assert within(None, sum, [1, 2, 3], cancel=cancel) == 6
    start = time.perf_counter()
    with pytest.raises(TimeLimitError, match="too long"):
        within(0.2, busy, 60, cancel=cancel, message="too long")
    assert time.perf_counter() - start < 0.2 + MARGIN
    # the event set after the call has ended changes nothing
    cancel.set()
    time.sleep(0.3)


def test_an_outer_cancellation_goes_through_an_inner_limit():
    cancel, started = threading.Event(), threading.Event()
    threading.Timer(0.0, lambda: started.wait(60) and cancel.set()).start()
    with pytest.raises(CancellationError):
        within(None, within, 30.0, busy, 60, started, cancel=cancel)


def test_progress_goes_to_the_watcher_of_its_own_thread_only():
    seen = []
    progress.report("nobody watches", 0.5)          # nothing happens
    with progress.watching(lambda label, f: seen.append((label, f))):
        with progress.part(0.5, 1.0):
            progress.report("second half begun", 0.0)
            with progress.part(0.0, 0.5):
                progress.report("nested", 1.0)
            progress.report("no fraction")
        t = threading.Thread(target=lambda: progress.report("elsewhere", 0.1))
        t.start()
        t.join()
    progress.report("after", 1.0)
    assert seen == [("second half begun", 0.5), ("nested", 0.75), ("no fraction", None)]


def test_a_derivation_reports_its_steps_in_order():
    import kinelab as kl
    seen = []
    with progress.watching(lambda label, f: seen.append((label, f))):
        kl.derive.derive(kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5))
    labels = [label for label, _ in seen]
    assert labels[0] == "loop equations" and "det J" in labels and "K: entry 1 of 2" in labels
    fractions = [f for _, f in seen if f is not None]
    assert fractions == sorted(fractions) and 0.0 <= fractions[0] and fractions[-1] <= 1.0
