"""The first analyses of a process do not wait for the compiler ("auto", the default).

Each check runs in a fresh Python process, as a user's first command does.  Timings are
the benchmark's (benchmarks/cold_start.py); here: which form of the kernel answers, that
the helper process is started and makes every entry point ready, and that both forms give
the same numbers.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import pytest

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
