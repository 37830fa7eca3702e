"""A derivation ends within its time limit in whichever thread it runs: the limit is not a
timer signal (which only the main thread receives) but a watchdog that stops the work."""
import threading
import time

import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab._deadline import within
from kinelab.cli import main
from kinelab.errors import ModelError, TimeLimitError
from kinelab.io import ModelFile
from tests.derive.cases import four_slider_dyads

MARGIN = 10.0       # s past the limit a loaded machine may take to stop and say so


def busy(seconds):
    """Python work (a C call such as time.sleep stops only when it returns)."""
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass
    return "done"


def in_a_thread(call):
    """``call()`` in a worker thread: what it returned or raised, and how long it took."""
    out = {}

    def work():
        start = time.perf_counter()
        try:
            out["value"] = call()
        except BaseException as exc:        # noqa: BLE001 -- handed back to the test
            out["error"] = exc
        out["seconds"] = time.perf_counter() - start
    worker = threading.Thread(target=work)
    worker.start()
    worker.join(300)
    assert not worker.is_alive(), "the derivation did not stop"
    return out


def test_a_long_derivation_stops_at_its_limit_off_the_main_thread():
    m = ModelFile.from_dict(four_slider_dyads()).mechanism
    out = in_a_thread(lambda: kl.derive.derive(m, time_limit=2.0))
    assert isinstance(out.get("error"), TimeLimitError), out
    assert out["seconds"] < 2.0 + MARGIN
    assert str(out["error"]).startswith("derivation of 'four sliders': it took more than 2 s, "
                                        "the time limit;")
    assert "--time-limit" in str(out["error"])


def test_the_document_has_a_limit_of_its_own():
    d = kl.derive.derive(kl.mechanisms.slotted_link(crank=0.1, distance=0.2))

    out = in_a_thread(lambda: within(0.5, busy, 30, message="worked too long"))
    assert isinstance(out.get("error"), TimeLimitError) and str(out["error"]) == "worked too long"
    assert out["seconds"] < 0.5 + MARGIN
    with pytest.raises(TimeLimitError, match="its document took more than"):
        d.to_markdown(time_limit=1e-9)


def test_after_the_limit_the_thread_goes_on_untouched():
    """Calls that end just before, at and after their deadlines: whatever the race, nothing
    is raised once ``within`` has returned or raised."""
    outcomes = set()
    for k in range(200):
        try:
            outcomes.add(within(0.002, busy, 0.0015 + 0.00001 * k))
        except TimeLimitError:
            outcomes.add("stopped")
    busy(0.5)           # any shot left over would land here
    assert outcomes <= {"done", "stopped"}


def test_limits_nest():
    def inner():
        try:
            return within(0.2, busy, 30)
        except TimeLimitError:
            return "inner stopped"
    assert within(10.0, inner) == "inner stopped"
    with pytest.raises(TimeLimitError, match="outer"):
        within(0.2, within, 10.0, busy, 30, message="outer")


def test_a_small_derivation_is_the_same_in_a_worker_thread():
    m = kl.mechanisms.slotted_link(crank=0.1, distance=0.2)
    here = kl.derive.derive(m)
    there = in_a_thread(lambda: kl.derive.derive(m))["value"]
    assert (there.K, there.L, there.det_J, there.readable) == (here.K, here.L, here.det_J,
                                                              here.readable)


@pytest.mark.parametrize("value", [0, -1.0, "10", True, float("nan")])
def test_a_time_limit_is_a_positive_number_of_seconds(value):
    with pytest.raises(ModelError, match=r"time_limit: expected a number of seconds > 0"):
        kl.derive.derive(kl.mechanisms.slotted_link(crank=0.1, distance=0.2), time_limit=value)


def test_the_command_stops_at_its_limit_in_one_line(tmp_path):
    path = tmp_path / "sliders.json"
    path.write_text(ModelFile.from_dict(four_slider_dyads()).to_json())
    start = time.perf_counter()
    res = CliRunner().invoke(main, ["derive", str(path), "--time-limit", "1", "--out", str(tmp_path)])
    assert time.perf_counter() - start < 1.0 + MARGIN
    assert res.exit_code == 2
    assert res.output.count("\n") == 1 and res.output.startswith(
        "kinelab: error: sliders.json: derivation of 'four sliders': it took more than 1 s")
    assert not list(tmp_path.glob("*.md"))


def test_a_module_imported_at_the_deadline_is_imported_whole(tmp_path, monkeypatch):
    """The watchdog holds its shot while the thread imports a module (a module stopped
    midway would be left half made), and stops the work once the import is done."""
    (tmp_path / "slow_module_for_deadline.py").write_text(
        "import time\nend = time.perf_counter() + 1.0\nwhile time.perf_counter() < end:\n"
        "    pass\nWHOLE = True\n")
    monkeypatch.syspath_prepend(str(tmp_path))

    def work():
        import slow_module_for_deadline  # noqa: F401
        busy(30)
    start = time.perf_counter()
    with pytest.raises(TimeLimitError):
        within(0.2, work)
    assert time.perf_counter() - start < 1.0 + MARGIN
    import sys
    assert sys.modules["slow_module_for_deadline"].WHOLE


def test_the_deadline_is_known_behind_another_error():
    """Python turns an exception raised in ``__set_name__`` into a RuntimeError, and code
    that catches everything may raise another: still a time-out."""
    def wrapped():
        try:
            busy(30)
        except BaseException as exc:
            raise RuntimeError("something else") from exc
    with pytest.raises(TimeLimitError):
        within(0.2, wrapped)


def test_a_shot_that_lands_in_a_weak_references_callback_prints_nothing():
    """A deadline's shot delivered in a weak reference's callback (or a finalizer) cannot be
    raised there: Python reports it on standard error, a traceback in a server's log.
    kinelab's hook says nothing of it and raises it again in the frame that ran the
    callback, so work that is nearly all callbacks stops too, and the thread's trace
    function is as it was before (none, or one of a debugger's kind).
    A subprocess: pytest puts a hook of its own in place."""
    import subprocess
    import sys
    import textwrap
    script = textwrap.dedent("""
        import weakref
        from kinelab._deadline import within
        from kinelab.errors import TimeLimitError

        class Thing:
            pass

        def callback(ref):
            s = 0
            for i in range(2000):
                s += i

        def work():
            while True:
                t = Thing()
                r = weakref.ref(t, callback)
                del t

        import sys
        tracer = TRACER
        sys.settrace(tracer)
        for _ in range(5):
            try:
                within(0.05, work)
            except TimeLimitError:
                print("stopped")
        print(sys.gettrace() is tracer)
        """)
    for tracer in ("None", "lambda frame, event, arg: None"):
        done = subprocess.run([sys.executable, "-c", script.replace("TRACER", tracer)],
                              capture_output=True, text=True, timeout=120)
        assert (done.stdout, done.stderr) == ("stopped\n" * 5 + "True\n", "")


def test_limits_hold_under_a_debuggers_trace_function():
    """With a trace function set (a debugger, a coverage tool), a call that ends in time and
    one stopped at its limit both leave the thread able to go on: Python 3.11 loops for ever
    at the next call if a shot is withdrawn rather than taken (a subprocess: the trace
    function is the process's)."""
    import subprocess
    import sys
    import textwrap
    script = textwrap.dedent("""
        import sys
        from kinelab._deadline import within
        from kinelab.errors import TimeLimitError

        def spin():
            while True:
                pass

        def double(x):
            return 2 * x

        sys.settrace(lambda frame, event, arg: None)
        print(within(5.0, double, 3), double(4))
        try:
            within(0.05, spin)
        except TimeLimitError:
            print("stopped", double(5))
        """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120)
    assert (done.stdout, done.stderr) == ("6 8\nstopped 10\n", "")
