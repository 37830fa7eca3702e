"""The first analyses of a process do not wait for the compiler ("auto", the default).

Each check runs in a fresh Python process, as a user's first command does.  Timings are
the benchmark's (benchmarks/cold_start.py); here: which form of the kernel answers, that
a warm cache is loaded in the process itself (unless the work is light), that at most one
helper process compiles for a cache however many processes start together, that a killed
helper blocks nobody, that processes exit cleanly whatever the helper is doing, and that
both forms give the same numbers.  A helper started on a cache of a test's own is stopped by that test.
"""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from kinelab import _compiled

POSIX = pytest.mark.skipif(not sys.platform.startswith("linux"),
                           reason="helpers are counted in /proc; the cache's lock is POSIX")
TIMEOUT = 600              # s for any one process: the suite never hangs on one

# the three plan kinds (one input, several inputs, Newton groups) and forward dynamics
_SCRIPT = textwrap.dedent("""
    import json, sys
    import numpy as np
    import kinelab as kl
    from kinelab import _compiled

    q = np.linspace(0.0, 2.0 * np.pi, 361)
    cases = [
        (kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q, "auto"),
        (kl.mechanisms.fivebar(3.0, 1.0, 2.5, 2.5, 1.0),
         np.column_stack([1.2 + 0.1 * np.sin(q), 1.9 + 0.1 * np.cos(q)]), "auto"),
        (kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q, "newton"),
    ]
    from kinelab.dynamics import Loads, simulate
    from kinelab.model import Input, Joint, Link, Mechanism, Point
    pendulum = Mechanism(
        "pendulum", (Point("O", 0.0, 0.0), Point("G", 1.0, 0.0)),
        (Link("ground", ("O",), ground=True),
         Link("arm", ("O", "G"), mass=1.0, center_of_mass="G", inertia=1e-3)),
        (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
    def run():
        return [kl.analyze(m, qq, qd=np.ones(qq.shape[1:]) if qq.ndim == 2 else 1.0,
                           method=meth) for m, qq, meth in cases]
    def swing():
        return simulate(pendulum, (0.0, 1.0), 0.0, 0.0, loads=Loads(gravity=(0.0, -9.81)),
                        t_eval=np.linspace(0.0, 1.0, 11), rtol=1e-10, atol=1e-12).q
    first = run()
    first_swing = swing()
    out = {"numba_loaded_first": "numba" in sys.modules,
           "helper_started": _compiled._helper is not None}
    if sys.argv[1] == "wait":
        out["all_ready"] = _compiled.wait(timeout=float(sys.argv[2]))
        second = run()
        out["largest_difference"] = max(
            float(np.nanmax(np.abs(a.jets - b.jets)) + np.nanmax(np.abs(a.rates - b.rates)))
            for a, b in zip(first, second))
        out["same_status"] = all(np.array_equal(np.isnan(a.jets), np.isnan(b.jets))
                                 for a, b in zip(first, second))
        out["swing_difference"] = float(np.max(np.abs(swing() - first_swing)))
    elif _compiled._helper is not None:
        _compiled._helper.kill()
    print(json.dumps(out))
""")


def _run(tmp_path, *args, cache=None, timeout=900):
    env = {**os.environ, "KINELAB_KERNEL": "auto"}
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = str(cache)
    script = tmp_path / "first.py"
    script.write_text(_SCRIPT)
    done = subprocess.run([sys.executable, str(script), *args], env=env, capture_output=True,
                          text=True, timeout=timeout)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_an_empty_compile_cache_is_not_waited_for(tmp_path):
    """Nothing compiled on this machine: every plan kind answers at once from the numpy
    form, a simulation by solve_ivp; the compiler runs in the helper process, not in this
    one."""
    out = _run(tmp_path, "stop", cache=tmp_path / "empty-cache")
    assert out == {"numba_loaded_first": False, "helper_started": True}


@pytest.mark.skipif(sys.platform == "win32", reason="the helper's machine lock is POSIX")
def test_the_helper_makes_every_entry_point_ready_with_the_same_numbers(tmp_path):
    """With the suite's compile cache (filled by the other tests, or compiled here once),
    the helper reports every entry point; the compiled kernel then answers, and its numbers
    are the numpy form's to rounding."""
    out = _run(tmp_path, "wait", "800")
    assert out["all_ready"] and out["same_status"]
    assert out["largest_difference"] < 1e-10
    assert out["swing_difference"] < 1e-8       # two integrations to rtol 1e-10


def test_wait_for_follows_the_mode():
    """A large batch waits for the compiled kernel in "auto" mode only: "compiled" has it
    at once, "numpy" never."""
    from kinelab import _compiled

    saved = _compiled.mode()
    try:
        _compiled.set_mode("numpy")
        assert not _compiled.wait_for("dynamics")
        _compiled.set_mode("compiled")
        assert _compiled.wait_for("dynamics")
    finally:
        _compiled.set_mode(saved)


def test_a_large_batch_runs_compiled_in_a_fresh_process(tmp_path):
    """In "auto" mode, a batch of WAIT_FOR_COMPILED_FROM runs waits for the compiled
    dynamics (loaded from the suite's cache, or compiled by the helper) instead of taking
    each run through solve_ivp."""
    script = tmp_path / "batch.py"
    script.write_text(textwrap.dedent("""
        import json
        import numpy as np
        from kinelab import _compiled
        from kinelab.dynamics import Loads, simulate
        from kinelab.dynamics._forward import WAIT_FOR_COMPILED_FROM
        from kinelab.model import Input, Joint, Link, Mechanism, Point
        pendulum = Mechanism(
            "pendulum", (Point("O", 0.0, 0.0), Point("G", 1.0, 0.0)),
            (Link("ground", ("O",), ground=True),
             Link("arm", ("O", "G"), mass=1.0, center_of_mass="G", inertia=1e-3)),
            (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
        q0 = np.linspace(-1.0, 1.0, WAIT_FOR_COMPILED_FROM)[:, None]
        runs = simulate(pendulum, (0.0, 0.5), q0, 0.0, loads=Loads(gravity=(0.0, -9.81)),
                        t_eval=[0.0, 0.5])
        print(json.dumps({"compiled": _compiled._ready["dynamics_one_input"].is_set(),
                          "shape": list(runs.q.shape)}))
    """))
    env = {**os.environ, "KINELAB_KERNEL": "auto"}
    done = subprocess.run([sys.executable, str(script)], env=env, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout.strip().splitlines()[-1])
    from kinelab.dynamics._forward import WAIT_FOR_COMPILED_FROM
    assert out == {"compiled": True, "shape": [WAIT_FOR_COMPILED_FROM, 2, 1]}


# --------------------------------------------------------------------------------------
# one helper per cache, none for a warm one
# --------------------------------------------------------------------------------------
# a short process of each kind: an analysis (closed form), a Tracker (one sample), a
# simulation; it reports which entry points it ran compiled and whether it started a helper
_SHORT = textwrap.dedent("""
    import json, sys, time
    import numpy as np
    import kinelab as kl
    from kinelab import _compiled
    import threading
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    t = time.perf_counter()
    if "thread" in sys.argv[1:]:        # the process ends while a thread may be loading
        threading.Thread(target=kl.analyze, args=(fb, np.linspace(0.0, 1.0, 10)),
                         daemon=True).start()
        time.sleep(0.05)
    elif "light" in sys.argv[1:]:        # a short command's analysis
        with _compiled.light_work():
            kl.analyze(fb, np.linspace(0.0, 2.0 * np.pi, 361))
            kl.kinematics.reachable_ranges(fb)
    else:
        kl.analyze(fb, np.linspace(0.0, 2.0 * np.pi, 361))
    first = time.perf_counter() - t
    if "tracker" in sys.argv[1:]:
        kl.kinematics.Tracker(fb).positions(0.5)
    if "simulate" in sys.argv[1:]:
        from kinelab.dynamics import Loads, simulate
        from kinelab.model import Input, Joint, Link, Mechanism, Point
        pendulum = Mechanism(
            "pendulum", (Point("O", 0.0, 0.0), Point("G", 1.0, 0.0)),
            (Link("ground", ("O",), ground=True),
             Link("arm", ("O", "G"), mass=1.0, center_of_mass="G", inertia=1e-3)),
            (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
        simulate(pendulum, (0.0, 0.2), 0.5, 0.0, loads=Loads(gravity=(0.0, -9.81)))
    helper = _compiled._helper
    print(json.dumps({"compiled": sorted(n for n, e in _compiled._ready.items() if e.is_set()),
                      "helper": None if helper is None else helper.pid, "first": first,
                      "numba": "numba" in sys.modules}))
""")


def _short(*args: str, cache: Path | None = None, start: bool = True):
    """A short process in "auto" mode (on ``cache``, else the suite's compile cache)."""
    env = {**os.environ, "KINELAB_KERNEL": "auto"}
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = str(cache)
    command = [sys.executable, "-c", _SHORT, *args]
    if not start:
        return subprocess.Popen(command, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
    done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=TIMEOUT)
    return done


def _report(done) -> dict:
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""
    return json.loads(done.stdout.strip().splitlines()[-1])


def _together(n: int, *args: str, cache: Path | None = None) -> list[dict]:
    """n short processes started at once, each to its end."""
    procs = [_short(*args, cache=cache, start=False) for _ in range(n)]
    try:
        outs = [p.communicate(timeout=TIMEOUT) for p in procs]
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
    reports = []
    for p, (out, err) in zip(procs, outs):
        assert p.returncode == 0, err
        assert err == ""
        reports.append(json.loads(out.strip().splitlines()[-1]))
    return reports


def _stop_helpers(place: str) -> None:
    for pid in _compiled.helpers_at_work(place):
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    deadline = time.monotonic() + 30
    while _compiled.helpers_at_work(place) and time.monotonic() < deadline:
        time.sleep(0.05)


def _place(cache: Path | None = None) -> str:
    saved = os.environ.get("NUMBA_CACHE_DIR")
    try:
        if cache is not None:
            os.environ["NUMBA_CACHE_DIR"] = str(cache)
        return _compiled.cache_place()[0]
    finally:
        if cache is not None:
            if saved is None:
                del os.environ["NUMBA_CACHE_DIR"]
            else:
                os.environ["NUMBA_CACHE_DIR"] = saved


@pytest.fixture
def warm():
    """The suite's compile cache with the entry points of the short processes in it (loaded
    or compiled here once): the place of that cache."""
    saved = _compiled.mode()
    try:
        _compiled.set_mode("compiled")
        for entry in ("closed_form_one_input", "one_sample", "dynamics_one_input"):
            _compiled.ready(entry)
    finally:
        _compiled.set_mode(saved)
    return _place()


@pytest.fixture
def cold(tmp_path):
    """An empty compile cache; the helpers started on it are stopped at the end."""
    cache = tmp_path / "cache"
    place = _place(cache)
    yield cache, place
    _stop_helpers(place)


@POSIX
def test_a_warm_cache_is_loaded_in_the_process(warm):
    """With every entry point it needs in the cache, a process loads them itself and
    starts no helper, and neither do 8 processes started at once."""
    before = set(_compiled.helpers_at_work(warm))
    one = _report(_short("tracker", "simulate"))
    assert one["helper"] is None
    assert set(one["compiled"]) == {"closed_form_one_input", "one_sample", "dynamics_one_input"}
    reports = _together(8)
    assert [r["helper"] for r in reports] == [None] * 8
    assert all("closed_form_one_input" in r["compiled"] for r in reports)
    assert set(_compiled.helpers_at_work(warm)) <= before


@POSIX
def test_light_work_leaves_a_warm_cache_unloaded(warm):
    """Light work (a short command's few hundred samples of a closed-form plan) runs on the
    numpy form: numba is not even imported, and no helper is started."""
    light = _report(_short("light"))
    assert light["compiled"] == [] and light["helper"] is None and not light["numba"]


@POSIX
def test_light_work_on_a_cold_cache_starts_the_helper(cold):
    """Light work on an empty cache still has the helper compile the kernel for later."""
    cache, place = cold
    light = _report(_short("light", cache=cache))
    assert light["compiled"] == [] and not light["numba"]
    assert light["helper"] is not None and _compiled.helpers_at_work(place) == [light["helper"]]


@POSIX
def test_processes_started_together_on_a_cold_cache_start_one_helper(cold):
    """8 processes at once on an empty cache: they all answer on the numpy form, one of
    them starts the helper and the others find it at work; later processes start none."""
    cache, place = cold
    reports = _together(8, cache=cache)
    assert all(r["compiled"] == [] for r in reports)
    started = [r["helper"] for r in reports if r["helper"] is not None]
    assert len(started) == 1
    assert _compiled.helpers_at_work(place) == started
    again = _report(_short(cache=cache))
    assert again["helper"] is None and _compiled.helpers_at_work(place) == started


@POSIX
def test_commands_in_a_row_leave_one_helper(cold):
    """`kinelab analyze` run again and again on a cold cache: one helper, the first one."""
    cache, place = cold
    model = Path(__file__).parents[1] / "examples" / "crank_rocker.toml"
    env = {**os.environ, "KINELAB_KERNEL": "auto", "NUMBA_CACHE_DIR": str(cache)}
    seen = set()
    for i in range(5):
        done = subprocess.run([sys.executable, "-c", "from kinelab.cli import main; main()",
                               "analyze", str(model), "--out", str(cache.parent / f"out{i}.csv"),
                               "--quiet"], env=env, capture_output=True, text=True, timeout=TIMEOUT)
        assert done.returncode == 0, done.stderr
        helpers = _compiled.helpers_at_work(place)
        assert len(helpers) <= 1
        seen |= set(helpers)
    assert len(seen) == 1


@POSIX
def test_a_killed_helper_blocks_nobody(cold):
    """The lock goes with the helper: killed, the next process starts another."""
    cache, place = cold
    first = _report(_short(cache=cache))["helper"]
    assert first is not None and _compiled.helpers_at_work(place) == [first]
    _stop_helpers(place)
    assert _compiled.helpers_at_work(place) == []
    second = _report(_short(cache=cache))["helper"]
    assert second is not None and second != first


@POSIX
def test_short_processes_exit_cleanly(cold, warm):
    """Processes that end at once, while the helper compiles (cold cache), right after
    loading the kernel (warm cache) or while a thread of theirs loads it, exit with
    status 0 and nothing on stderr: no thread is inside numba when the interpreter ends."""
    cache, place = cold
    for i in range(12):
        args = ("thread",) if i % 4 == 3 else ("tracker", "simulate")[:i % 4]
        _report(_short(*args, cache=cache if i % 2 else None))
    assert len(_compiled.helpers_at_work(place)) <= 1
