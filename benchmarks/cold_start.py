"""The first analyses of a fresh process, with an empty and with a warm compile cache.

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

    python benchmarks/cold_start.py [--repeat N]
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
        print(f"    {key:27s} best {best:8.3f} s   median {median:8.3f} s")
    return summary


def main() -> None:
    repeat = int(sys.argv[sys.argv.index("--repeat") + 1]) if "--repeat" in sys.argv else 3
    print(f"first analyses of a fresh process (361 samples each), best and median of {repeat}")
    print(" empty compile cache:")
    auto = measure("kinelab (auto)", KINELAB, "auto", True, repeat)
    ref = measure("kinelab compiling in the process (KINELAB_KERNEL=compiled)", KINELAB,
                  "compiled", True, 1)
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


if __name__ == "__main__":
    main()
