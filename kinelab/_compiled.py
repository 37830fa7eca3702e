"""The compiled kernels, made ready without anyone waiting for them.

numba compiles each entry point of the kernels (``kinematics/_kernel.py``,
``dynamics/_kernel.py``) once per machine, in 15 to 50 seconds each, and keeps the result
in its cache on disk; a later process loads it in a fraction of a second.  Nobody should
wait for that: until an entry point is ready in this process, the work that needs it runs
without it (the kinematics on the kernel's numpy form, ``kinematics/_interpreter.py``, which
gives the same numbers to rounding; forward dynamics on scipy's solve_ivp with a numpy
right-hand side), at once.

The first analysis of a process starts the preparation: a separate Python process brings
numba's cache of every entry point up to date (compiling what is missing, on its own
processor core, so that this process keeps its speed), and as each is done, a thread here
loads it from the cache.  The helper process runs on after this one ends, so that a short
command still leaves the kernel compiled for the next.

The environment variable ``KINELAB_KERNEL`` chooses:

``auto`` (the default)
    as above;
``compiled``
    always the compiled kernel, compiling it in this process when needed (the numbers of
    a run do not depend on how far the preparation has come);
``numpy``
    never compile: the numpy form only.
"""
from __future__ import annotations

import os
import subprocess
import sys
import threading
import warnings

from kinelab.errors import ModelError

__all__ = ["ENTRIES", "mode", "set_mode", "ready", "wait", "wait_for"]

# each entry point, and the module whose warm_up(entry) runs it once with the argument types
# of every call (this module sits below the rooms and names them only here)
ENTRIES = {"closed_form_one_input": "kinelab.kinematics._evaluate",
           "one_sample": "kinelab.kinematics._evaluate",
           "closed_form": "kinelab.kinematics._evaluate",
           "continuation_one_input": "kinelab.kinematics._evaluate",
           "continuation": "kinelab.kinematics._evaluate",
           "dynamics_one_input": "kinelab.dynamics._compiled",
           "dynamics": "kinelab.dynamics._compiled"}
_MODES = ("auto", "compiled", "numpy")

_ready = {name: threading.Event() for name in ENTRIES}
_failed: dict[str, str] = {}
_started = threading.Lock()
_preparing: threading.Thread | None = None
_helper: subprocess.Popen | None = None
_mode = ""


def mode() -> str:
    """How analyses choose between the compiled kernel and its numpy form (see the module)."""
    global _mode
    if not _mode:
        set_mode(os.environ.get("KINELAB_KERNEL", "auto"))
    return _mode


def set_mode(value: str) -> None:
    global _mode
    if value not in _MODES:
        raise ModelError(f"KINELAB_KERNEL: expected one of 'auto', 'compiled', 'numpy', got "
                         f"'{value}'")
    _mode = value


def ready(entry: str) -> bool:
    """Whether to run this entry point compiled now; in "auto" mode, the first call that
    finds it not ready starts the preparation of all of them."""
    if _ready[entry].is_set():
        return True
    chosen = mode()
    if chosen == "compiled":
        return True
    if chosen == "auto" and entry not in _failed:
        _prepare()
    return False


def wait_for(entry: str) -> bool:
    """Wait until this entry point is ready, for work that would take longer without it than
    compiling it takes (in "auto" mode; "compiled" is always ready, "numpy" never); whether
    it is ready."""
    if ready(entry) or mode() != "auto":
        return _ready[entry].is_set() or mode() == "compiled"
    thread = _preparing
    while not _ready[entry].wait(0.2) and entry not in _failed:
        if thread is None or not thread.is_alive():
            break
    return _ready[entry].is_set()


def wait(timeout: float | None = None) -> bool:
    """Wait until every entry point is ready (or failed to compile); whether all are ready."""
    if mode() == "auto":
        _prepare()
    thread = _preparing
    if thread is not None:
        thread.join(timeout)
    return all(e.is_set() for e in _ready.values())


def _prepare() -> None:
    global _preparing
    with _started:
        if _preparing is None:
            _preparing = threading.Thread(target=_prepare_all, name="kinelab-kernel", daemon=True)
            _preparing.start()


def _prepare_all() -> None:
    """Bring numba's cache up to date in a helper process, loading each entry point here as
    it reports it done; then load here whatever it did not report."""
    global _helper
    try:
        env = {**os.environ, "KINELAB_KERNEL": "compiled"}
        command = [sys.executable, "-c", "from kinelab._compiled import _helper_main; _helper_main()"]
        helper = _helper = subprocess.Popen(command, stdin=subprocess.DEVNULL,
                                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                            env=env, text=True, start_new_session=True)
    except OSError:
        helper = None
    if helper is not None:
        for line in helper.stdout:
            if line.strip() in _ready:
                _load(line.strip())
        helper.stdout.close()
        helper.wait()                         # it is ending: reaped here, not left a zombie
    for name in ENTRIES:
        if not _ready[name].is_set():
            _load(name)


def _load(name: str) -> None:
    """Make an entry point ready in this process: from numba's cache, or compiled here."""
    try:
        _warm_up(name)
    except Exception as e:                    # noqa: BLE001 - numba may fail in many ways
        _failed[name] = f"{type(e).__name__}: {e}"
        warnings.warn(f"kinelab: the compiled kernel ({name}) is not available ({_failed[name]}); "
                      "analyses run on its numpy form, which is slower", RuntimeWarning,
                      stacklevel=1)
        return
    _ready[name].set()


def _warm_up(name: str) -> None:
    import importlib
    importlib.import_module(ENTRIES[name]).warm_up(name)


def _helper_main() -> None:
    """The helper process: each entry point made ready (compiled or loaded from the cache),
    reported on its own line, one process at a time per machine."""
    lock = _machine_lock()
    listening = True
    try:
        for name in ENTRIES:
            _warm_up(name)
            if listening:
                try:
                    print(name, flush=True)
                except OSError:             # the process that started this one has ended:
                    listening = False       # compile the rest for the next one
                    sys.stdout = open(os.devnull, "w")
    finally:
        if lock is not None:
            lock.close()


def _machine_lock():
    """An exclusive lock held while compiling, so that processes that start together do
    not all compile: the others wait, then load from the cache.  None where the system has
    no such lock."""
    try:
        import fcntl
        import tempfile
    except ImportError:
        return None
    path = os.path.join(tempfile.gettempdir(), f"kinelab-kernel-{os.getuid()}.lock")
    try:
        f = open(path, "a")
        fcntl.flock(f, fcntl.LOCK_EX)
    except OSError:
        return None
    return f

