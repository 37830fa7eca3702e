"""The first analyses of a fresh process, with an empty and with a warm compile cache, and
how many helper processes compile.

Each measurement is a new Python process, as a user's first command is: the import of
kinelab, then the first analysis of each plan kind (a four-bar: one input; a five-bar: two
inputs; the four-bar with ``method="newton"``: Newton groups), 361 samples each, timed
inside the process, in wall time and in the process's CPU time (on a shared machine the
wall time also counts the other processes, the helper compiling among them).  Side by side in the same run:

- kinelab as installed ("auto": the numpy form of the kernel answers while the compiled
  one is prepared in a helper process);
- the reference: the same process with ``KINELAB_KERNEL=compiled`` (compile in the process
  and wait for it, as every analysis did before the numpy form existed);
- pylinkage's first four-bar step and sweep, where it is installed (``pip install -e .[bench]``),
  with its own numba cache emptied the same way.

Then, with the cache warm: how long a fresh process takes to load the kernel itself, and
its first call of a million angles (a four-bar) against the same call once the process is
warm, with its memory for results reused and with fresh memory for each call (the first
call writes its 270 MB of results into memory the operating system has to hand out and
zero first, as every call does with reuse turned off); the numpy form for comparison.  Last,
the helpers: 8 processes started at once, and ``kinelab analyze`` run N times in a row,
each on a warm cache and on an empty one: how many helpers they started and how many were
at work at once.

    python benchmarks/cold_start.py [--repeat N] [--commands N] [--skip-compile]

``--skip-compile`` leaves out the measurements that compile every entry point in one
process (minutes).
"""
from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import textwrap

KINELAB = textwrap.dedent("""
    import json, time
    t0 = time.perf_counter()
    import numpy as np
    import kinelab as kl
    out = {"import": time.perf_counter() - t0}
    q = np.linspace(0.0, 2.0 * np.pi, 361)
    cases = {"one input": (kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q, "auto"),
             "two inputs": (kl.mechanisms.fivebar(3.0, 1.0, 2.5, 2.5, 1.0),
                            np.column_stack([1.2 + 0.1 * np.sin(q), 1.9 + 0.1 * np.cos(q)]), "auto"),
             "Newton groups": (kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q, "newton")}
    for name, (m, qq, method) in cases.items():
        t, c = time.perf_counter(), time.process_time()
        kl.analyze(m, qq, method=method)
        out[name] = time.perf_counter() - t
        out[name + ", CPU"] = time.process_time() - c
    t = time.perf_counter()
    kl.kinematics.Tracker(cases["one input"][0]).positions(0.5)
    out["one sample (Tracker)"] = time.perf_counter() - t
    from kinelab import _compiled
    if _compiled._helper is not None:       # the next measurement starts from the same cache
        _compiled._helper.kill()
    print(json.dumps(out))
""")

PYLINKAGE = textwrap.dedent("""
    import json, sys, time
    t0 = time.perf_counter()
    sys.path.insert(0, sys.argv[1])
    import numpy as np
    import peers
    out = {"import": time.perf_counter() - t0}
    t = time.perf_counter()
    fb = peers.pylinkage_fourbar(3.0, 1.0, 3.0, 2.5, (1.5, 1.0))
    peers.pylinkage_one_step(fb, 0.5)
    out["one sample (step)"] = time.perf_counter() - t
    print(json.dumps(out))
""")


def run(script: str, env: dict, *args: str) -> dict | None:
    done = subprocess.run([sys.executable, "-c", script, *args], env=env, capture_output=True,
                          text=True, timeout=1800)
    if done.returncode:
        print("   failed:", done.stderr.strip().splitlines()[-1] if done.stderr else "")
        return None
    return json.loads(done.stdout.strip().splitlines()[-1])


def measure(label: str, script: str, mode: str | None, cold: bool, repeat: int, *args) -> dict:
    runs = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ)
            if mode is not None:
                env["KINELAB_KERNEL"] = mode
            if cold:
                env["NUMBA_CACHE_DIR"] = cache
            r = run(script, env, *args)
            if r is not None:
                runs.append(r)
    if not runs:
        return {}
    summary = {key: (min(r[key] for r in runs), statistics.median(r[key] for r in runs))
               for key in runs[0]}
    print(f"  {label}")
    for key, (best, median) in summary.items():
        unit = "x" if "/" in key else "s"
        print(f"    {key:27s} best {best:8.3f} {unit}   median {median:8.3f} {unit}")
    return summary


LARGE = textwrap.dedent("""
    import json, sys, time
    import numpy as np
    import kinelab as kl
    from kinelab import _compiled
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    q = np.linspace(0.0, 2.0 * np.pi, 10 ** 6)
    out = {}
    if sys.argv[1] == "load first":
        t, c = time.perf_counter(), time.process_time()
        _compiled.ready("closed_form_one_input")
        out["load"], out["load, CPU"] = time.perf_counter() - t, time.process_time() - c
    times = []
    for _ in range(4):
        t = time.perf_counter()
        kl.analyze(fb, q, qd=1.0)
        times.append(time.perf_counter() - t)
    out["first call"], out["steady call"] = times[0], min(times[1:])
    out["first / steady"] = times[0] / min(times[1:])
    kl.reuse_result_memory(0)             # each call's results in memory never touched before
    fresh = []
    for _ in range(2):
        t = time.perf_counter()
        kl.analyze(fb, q, qd=1.0)
        fresh.append(time.perf_counter() - t)
    out["steady, fresh memory"] = min(fresh)
    out["first / steady, fresh memory"] = times[0] / min(fresh)
    print(json.dumps(out))
""")

SHORT = textwrap.dedent("""
    import json
    import numpy as np
    import kinelab as kl
    from kinelab import _compiled
    kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), np.linspace(0.0, 6.3, 361))
    print(json.dumps({"helper": _compiled._helper.pid if _compiled._helper else None}))
""")


def first_large_call(repeat: int) -> None:
    """A fresh process on a warm cache: loading, then a million angles."""
    print(" a fresh process on a warm cache, a four-bar at 10^6 angles "
          f"(best and median of {repeat}):")
    for label, mode, how in (("load, then the first call", "auto", "load first"),
                             ("the first call loads", "auto", "large first"),
                             ("numpy form (KINELAB_KERNEL=numpy)", "numpy", "large first")):
        measure(label, LARGE, mode, False, repeat, how)


def _cache_place(env: dict) -> str:
    done = subprocess.run([sys.executable, "-c", "from kinelab import _compiled; "
                           "print(_compiled.cache_place()[0])"], env=env, capture_output=True,
                          text=True, timeout=600)
    return done.stdout.strip()


def _stop_helpers(place: str) -> None:
    from kinelab import _compiled
    for pid in _compiled.helpers_at_work(place):
        os.kill(pid, 9)


def helpers(commands: int) -> None:
    """Helpers started by processes started together, and by commands run in a row."""
    from kinelab import _compiled
    model = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples",
                         "crank_rocker.toml")
    print(" helper processes (a warm cache: the default one, filled above; an empty one):")
    for label in ("warm cache", "empty cache"):
        with tempfile.TemporaryDirectory() as tmp:
            env = {**os.environ, "KINELAB_KERNEL": "auto"}
            if label == "empty cache":
                env["NUMBA_CACHE_DIR"] = tmp
            place = _cache_place(env)
            procs = [subprocess.Popen([sys.executable, "-c", SHORT], env=env,
                                      stdout=subprocess.PIPE, text=True) for _ in range(8)]
            started = [json.loads(p.communicate(timeout=1800)[0])["helper"] for p in procs]
            started = [pid for pid in started if pid is not None]
            print(f"  {label}: 8 processes at once started {len(started)} helper(s); "
                  f"{len(_compiled.helpers_at_work(place))} at work after them")
            seen, most = set(), 0
            for i in range(commands):
                subprocess.run([sys.executable, "-c", "from kinelab.cli import main; main()",
                                "analyze", model, "--out", os.path.join(tmp, "out.csv"),
                                "--quiet"], env=env, capture_output=True, timeout=1800)
                at_work = _compiled.helpers_at_work(place)
                seen |= set(at_work)
                most = max(most, len(at_work))
            print(f"  {label}: {commands} `kinelab analyze` in a row: {len(seen)} helper(s) seen, "
                  f"at most {most} at work at once")
            if label == "empty cache":
                _stop_helpers(place)


def main() -> None:
    repeat = int(sys.argv[sys.argv.index("--repeat") + 1]) if "--repeat" in sys.argv else 3
    commands = int(sys.argv[sys.argv.index("--commands") + 1]) if "--commands" in sys.argv else 100
    compile_all = "--skip-compile" not in sys.argv
    print(f"first analyses of a fresh process (361 samples each), best and median of {repeat}")
    print(" empty compile cache:")
    auto = measure("kinelab (auto)", KINELAB, "auto", True, repeat)
    ref = (measure("kinelab compiling in the process (KINELAB_KERNEL=compiled)", KINELAB,
                   "compiled", True, 1) if compile_all else {})
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        import pylinkage  # noqa: F401
        measure("pylinkage", PYLINKAGE, None, True, repeat, here)
    except ImportError:
        print("  pylinkage: not installed (pip install -e .[bench])")
    if auto and ref:
        for key in auto:
            if key != "import":
                print(f"    {key:27s} compiled in the process / auto: "
                      f"{ref[key][0] / auto[key][0]:8.1f} x")
    print(" warm compile cache:")
    run(KINELAB, {**os.environ, "KINELAB_KERNEL": "compiled"})     # fill the default cache
    measure("kinelab (auto)", KINELAB, "auto", False, repeat)
    measure("kinelab (compiled)", KINELAB, "compiled", False, repeat)
    first_large_call(repeat)
    helpers(commands)


if __name__ == "__main__":
    main()
