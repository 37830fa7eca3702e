"""The compiled kernels, made ready without anyone waiting for them.

numba compiles each entry point of the kernels (``kinematics/_kernel.py``,
``dynamics/_kernel.py``) once, in 15 to 50 seconds each, and keeps the result in its cache
on disk (``__pycache__`` beside the kernels, or under ``NUMBA_CACHE_DIR``); a later process
loads it from there.  Nobody should wait for the compiler, and nobody should wait for
anything when the cache is warm.

**Warm cache.**  Beside numba's cache of the kinematics kernel, a stamp file per entry point
says that it is in the cache for these kernel sources (their contents), this numba and this
Python (``kinelab-<key>-<entry>.ready``; any process that made the entry point ready
writes it).  A process that finds the stamp loads the entry point itself, in the thread
that first needs it, and runs that call compiled: loading takes about half a second, most
of it numba's own start-up, and no other process is involved.

**Light work.**  That half second of loading is far more than work such as ``kinelab
check`` or ``kinelab analyze`` of a few hundred samples of a closed-form plan takes on the
numpy form (milliseconds).  Work run inside :func:`light_work` therefore runs on the numpy
form unless the entry point is loaded in this process already; a cold cache still starts
the helper, so that heavier work later finds the kernel compiled.  The caller says what is
light (the command line: a closed-form plan over a sweep too short for a progress bar).

**Cold cache.**  A call whose entry point has no stamp runs at once on the kernel's numpy
form (``kinematics/_interpreter.py``, the same numbers, statuses and messages; forward
dynamics on scipy's solve_ivp with a numpy right-hand side) and starts the helper process,
which compiles every entry point that has no stamp, one after the other on its own
processor core, writing each stamp as it is done.  At most one helper works on a cache: it
holds the lock ``kinelab-kernel.lock`` beside it for as long as it runs (taken by the
process that starts it, and handed over), so a process that finds the lock held starts
none, and the system lets go of the lock when the helper ends, however it ends (a helper
that is killed leaves no stale lock).  A process that needs an entry point meanwhile
looks for its stamp at most twice a second and loads it as soon as it appears.  The helper
runs on after the process that started it ends, so that a short command still leaves the
kernel compiled for the next; a helper whose entry point fails to compile writes a stamp
saying why, and the processes that need it stay on the numpy form, with a warning.

Nothing of numba runs in a background thread of kinelab's: loading and compiling happen in
the thread that asked, and at exit the interpreter waits for a load under way in any
other thread (and lets none start), so that no thread is inside numba or LLVM while the
interpreter ends.

The environment variable ``KINELAB_KERNEL`` chooses:

``auto`` (the default)
    as above;
``compiled``
    always the compiled kernel, loaded or compiled in this process when first needed (the
    numbers of a run do not depend on the state of the cache);
``numpy``
    never compile: the numpy form only.
"""
from __future__ import annotations

import atexit
import contextlib
import contextvars
import functools
import hashlib
import os
import subprocess
import sys
import tempfile
import threading
import time
import warnings

from kinelab.errors import ModelError

__all__ = ["ENTRIES", "mode", "set_mode", "ready", "wait", "wait_for", "light_work", "cache_place",
           "helpers_at_work"]

# each entry point, and the module whose warm_up(entry) runs it once with the argument types
# of every call (this module sits below the rooms and names them only here)
ENTRIES = {"closed_form_one_input": "kinelab.kinematics._evaluate",
           "one_sample": "kinelab.kinematics._evaluate",
           "closed_form": "kinelab.kinematics._evaluate",
           "continuation_one_input": "kinelab.kinematics._evaluate",
           "continuation": "kinelab.kinematics._evaluate",
           "driven_angles": "kinelab.kinematics._evaluate",
           "dynamics_one_input": "kinelab.dynamics._compiled",
           "dynamics": "kinelab.dynamics._compiled"}
_MODES = ("auto", "compiled", "numpy")
# the files whose contents the compiled entry points are made of (the codes and tolerances
# are read in when compiling): a change to any of them asks for a new compile
_SOURCES = ("kinematics/_kernel.py", "kinematics/_codes.py", "dynamics/_kernel.py",
            "dynamics/_codes.py", "_expressions.py")
# numba keys its cache of a function on the text of the function's own file, yet freezes into
# the compiled code the constants it reads and the functions it calls from other files: each
# kernel file carries the digest of the files it is compiled from besides itself
# (``COMPILED_FROM``, kept true by a test), so that a change to any of them changes its text
_COMPILED_FROM = {"kinematics/_kernel.py": ("kinematics/_codes.py",),
                  "dynamics/_kernel.py": ("kinematics/_kernel.py", "kinematics/_codes.py",
                                          "dynamics/_codes.py", "_expressions.py")}
_LOOK_EVERY = 0.5          # s between two looks for a stamp, while an entry point is not ready
_WAIT_STEP = 0.2           # s between two looks while waiting for one
_LOCK = "kinelab-kernel.lock"
_FENCE = 120.0             # s that exit waits for a load or compile under way in another thread

_ready = {name: threading.Event() for name in ENTRIES}
_failed: dict[str, str] = {}
_next_look = dict.fromkeys(ENTRIES, 0.0)
_loading = threading.RLock()       # one load (or compile) at a time in a process
_in_progress: set[str] = set()     # entry points being made ready (by the thread in _loading)
_starting = threading.Lock()
_helper: subprocess.Popen | None = None
_mode = ""
_light = contextvars.ContextVar("kinelab_light_work", default=False)


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


@contextlib.contextmanager
def light_work(light: bool = True):
    """Inside (when ``light``), in "auto" mode: entry points not loaded in this process run on
    the numpy form rather than being loaded (see the module); a cold cache still starts the
    helper.  "compiled" and "numpy" modes are unchanged."""
    token = _light.set(bool(light) or _light.get())
    try:
        yield
    finally:
        _light.reset(token)


def ready(entry: str) -> bool:
    """Whether to run this entry point compiled now.  In "auto" mode an entry point in the
    cache is loaded here, in this thread (unless the work is light: :func:`light_work`); one
    that is not starts the helper (unless one is at work on the cache) and runs on the numpy
    form meanwhile.  In "compiled" mode it is loaded or compiled here."""
    if _ready[entry].is_set():
        return True
    chosen = mode()
    if entry in _in_progress:           # asked again while this thread makes it ready
        return chosen == "compiled"
    if chosen == "compiled":
        with _loading:
            if not _ready[entry].is_set():
                _warm_up(entry)          # a failure to compile is the caller's error here
        return True
    if chosen == "numpy" or entry in _failed:
        return False
    now = time.monotonic()
    if now < _next_look[entry]:
        return False
    _next_look[entry] = now + _LOOK_EVERY
    return _look(entry, start=True, load=not _light.get())


def wait_for(entry: str) -> bool:
    """Wait until this entry point is ready, for work that would take longer without it than
    compiling it takes (in "auto" mode; "compiled" is always ready, "numpy" never); whether
    it is ready."""
    if mode() != "auto":
        return mode() == "compiled" and ready(entry)
    return _await(entry, None)


def wait(timeout: float | None = None) -> bool:
    """Wait until every entry point is ready here (or failed to compile), loading each in
    this thread; whether all are ready."""
    if mode() == "compiled":
        return all(ready(name) for name in ENTRIES)
    if mode() == "numpy":
        return False
    deadline = None if timeout is None else time.monotonic() + timeout
    for name in ENTRIES:
        _await(name, deadline)
    return all(e.is_set() for e in _ready.values())


def _await(entry: str, deadline: float | None) -> bool:
    """Look for the entry point's stamp until it is there (then load it), it failed, or the
    deadline passes; with no helper at work on the cache, start one; compile here when
    none can run, or when the one this process started ended without it."""
    while not _ready[entry].is_set() and entry not in _failed:
        if _look(entry, start=False):
            break
        place = cache_place()
        helper = _helper
        if place is None or (helper is not None and helper.poll() is not None):
            return _load(entry)
        if helper is None:
            _start_helper(place)              # unless one holds the lock
        if deadline is not None and time.monotonic() >= deadline:
            break
        time.sleep(_WAIT_STEP)
    return _ready[entry].is_set()


def _look(entry: str, start: bool, load: bool = True) -> bool:
    """Load the entry point if its stamp says it is in the cache (and ``load``); note a
    failure to compile it; else (``start``) have the helper compile it.  Whether it is
    ready."""
    place = cache_place()
    if place is None:
        return False
    state = _stamp(place, entry)
    if state == "":
        return load and _load(entry, blocking=False)
    if state is not None:
        _fail(entry, state)
    elif start:
        _start_helper(place)
    return False


def _load(entry: str, blocking: bool = True) -> bool:
    """Make an entry point ready in this thread (from numba's cache, or compiled here);
    whether it is.  Not ``blocking``: False at once while another thread loads one."""
    if not _loading.acquire(blocking=blocking):
        return False
    try:
        if not _ready[entry].is_set():
            _warm_up(entry)
    except Exception as e:                    # noqa: BLE001 - numba may fail in many ways
        _fail(entry, f"{type(e).__name__}: {e}")
    finally:
        _loading.release()
    return _ready[entry].is_set()




def _fail(entry: str, message: str) -> None:
    if entry in _failed:
        return
    _failed[entry] = message
    warnings.warn(f"kinelab: the compiled kernel ({entry}) is not available ({message}); "
                  "analyses run on its numpy form, which is slower", RuntimeWarning,
                  stacklevel=2)


@atexit.register
def _fence() -> None:
    """At exit: let a load or compile under way in another thread end, and start none after
    (a thread inside numba or LLVM while the interpreter ends can abort the process)."""
    _loading.acquire(timeout=_FENCE)


def _warm_up(name: str) -> None:
    """Run the entry point once (loading it from numba's cache, or compiling it), then
    count it ready here and stamp it in the cache."""
    import importlib
    _in_progress.add(name)
    try:
        importlib.import_module(ENTRIES[name]).warm_up(name)
    finally:
        _in_progress.discard(name)
    _ready[name].set()
    place = cache_place()
    if place is not None and _stamp(place, name) is None:
        _write_stamp(place, name, "")


# --------------------------------------------------------------------------------------
# the cache: where numba keeps it, the stamps and the lock beside it
# --------------------------------------------------------------------------------------
def cache_place() -> tuple[str, str] | None:
    """Numba's cache directory of the kinematics kernel and the key of the kernel sources
    (their contents, numba's version, Python's), or None where numba can keep no cache;
    found without importing numba."""
    return _cache_place(os.environ.get("NUMBA_CACHE_DIR", ""))


@functools.cache
def _cache_place(numba_cache_dir: str) -> tuple[str, str] | None:
    package = os.path.dirname(os.path.abspath(__file__))
    kernel = os.path.join(package, "kinematics", "_kernel.py")
    # numba's locators, in numba's order: NUMBA_CACHE_DIR, __pycache__ beside the source
    # where it can be written, the user's cache directory
    here = os.path.dirname(kernel)
    below = f"{os.path.basename(here)}_{hashlib.sha1(here.encode()).hexdigest()}"
    if sys.platform == "darwin":
        user = os.path.expanduser("~/Library/Caches")
    elif sys.platform == "win32":
        user = os.path.join(os.environ.get("LOCALAPPDATA", os.path.expanduser("~")), "numba")
    else:
        user = os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache")
    candidates = ([os.path.join(numba_cache_dir, below)] if numba_cache_dir else []) + [
        os.path.join(here, "__pycache__"),
        os.path.join(user, "numba", below) if sys.platform != "win32"
        else os.path.join(user, "Cache", below)]
    for path in candidates:
        try:
            os.makedirs(path, exist_ok=True)
            tempfile.TemporaryFile(dir=path).close()
        except OSError:
            continue
        return path, _key(package)
    return None


def compiled_from(kernel: str) -> str:
    """The digest of the files a kernel file (``_COMPILED_FROM``'s key) is compiled from
    besides itself: the value of its ``COMPILED_FROM``."""
    package = os.path.dirname(os.path.abspath(__file__))
    digest = hashlib.sha256()
    for name in _COMPILED_FROM[kernel]:
        with open(os.path.join(package, name), "rb") as f:
            digest.update(f.read())
    return digest.hexdigest()[:16]


def _key(package: str) -> str:
    digest = hashlib.sha256()
    for name in _SOURCES:
        with open(os.path.join(package, name), "rb") as f:
            digest.update(f.read())
    try:
        import importlib.util
        numba = os.path.dirname(importlib.util.find_spec("numba").origin)
        with open(os.path.join(numba, "_version.py"), "rb") as f:
            digest.update(f.read())
    except (AttributeError, OSError, TypeError, ValueError, ImportError):
        digest.update(b"numba: unknown")
    digest.update(f"{sys.implementation.cache_tag} {sys.platform}".encode())
    return digest.hexdigest()[:16]


def _stamp_path(place: tuple[str, str], entry: str, suffix: str) -> str:
    path, key = place
    return os.path.join(path, f"kinelab-{key}-{entry}.{suffix}")


def _stamp(place: tuple[str, str], entry: str) -> str | None:
    """"" where the entry point is in the cache, the message of its failure to compile, or
    None where it is not known to be either."""
    if os.path.exists(_stamp_path(place, entry, "ready")):
        return ""
    try:
        with open(_stamp_path(place, entry, "failed"), encoding="utf-8") as f:
            return f.read().strip() or "failed to compile"
    except OSError:
        return None


def _write_stamp(place: tuple[str, str], entry: str, failure: str) -> None:
    path = _stamp_path(place, entry, "failed" if failure else "ready")
    try:
        with tempfile.NamedTemporaryFile("w", dir=place[0], delete=False, encoding="utf-8",
                                         prefix=".kinelab-", suffix=".tmp") as f:
            f.write(failure)
        os.replace(f.name, path)
    except OSError:
        pass


def _clear_old_stamps(place: tuple[str, str]) -> None:
    """Remove the stamps of other kernel sources (an earlier version of kinelab)."""
    path, key = place
    try:
        names = os.listdir(path)
    except OSError:
        return
    for name in names:
        if (name.startswith("kinelab-") and name.endswith((".ready", ".failed"))
                and not name.startswith(f"kinelab-{key}-")):
            try:
                os.unlink(os.path.join(path, name))
            except OSError:
                pass


def _try_lock(place: tuple[str, str]):
    """The cache's lock, taken without waiting: an open file holding it; None while a
    helper holds it; False where the system has no such lock."""
    try:
        import fcntl
    except ImportError:
        return False
    try:
        f = open(os.path.join(place[0], _LOCK), "a")
    except OSError:
        return False
    try:
        fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        f.close()
        return None
    return f


def _start_helper(place: tuple[str, str]) -> bool:
    """Start the helper process with the cache's lock, unless a helper holds it or every
    entry point is already known; whether one was started."""
    global _helper
    with _starting:
        if _helper is not None and _helper.poll() is None:
            return False
        lock = _try_lock(place)
        if lock is None or (lock is False and _helper is not None):
            return False            # one is at work (or, with no lock, this process started one)
        try:
            if all(_stamp(place, name) is not None for name in ENTRIES):
                return False
            fds = () if lock is False else (lock.fileno(),)
            command = [sys.executable, "-c", "from kinelab._compiled import _helper_main; "
                       "_helper_main()", place[0], *map(str, fds)]
            env = {**os.environ, "KINELAB_KERNEL": "compiled"}
            try:
                helper = subprocess.Popen(command, stdin=subprocess.DEVNULL,
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                          env=env, pass_fds=fds, start_new_session=True)
            except OSError:
                return False
            _helper = helper
            # reaped when it ends (a wait for the process in the system: nothing of numba)
            threading.Thread(target=helper.wait, name="kinelab-helper-reaper", daemon=True).start()
            return True
        finally:
            if lock:
                lock.close()        # the helper holds it now


def _helper_main() -> None:
    """The helper process: every entry point without a stamp compiled (or loaded) and
    stamped, while it holds the cache's lock (handed to it as a file descriptor)."""
    place = cache_place()
    if place is None:
        return
    _clear_old_stamps(place)
    for name in ENTRIES:
        if _stamp(place, name) is not None:
            continue
        try:
            _warm_up(name)
        except Exception as e:                # noqa: BLE001 - numba may fail in many ways
            _write_stamp(place, name, f"{type(e).__name__}: {e}")


def helpers_at_work(place: str) -> list[int]:
    """The process ids of the helpers alive on the cache directory ``place`` (Linux: read
    from /proc; elsewhere an empty list), for tests and benchmarks."""
    pids = []
    try:
        entries = os.listdir("/proc")
    except OSError:
        return pids
    for name in entries:
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/cmdline", "rb") as f:
                argv = f.read().split(b"\0")
            with open(f"/proc/{name}/stat", "rb") as f:
                state = f.read().rsplit(b")", 1)[1].split()[0]
        except (OSError, IndexError):
            continue
        if state != b"Z" and place.encode() in argv and any(b"_helper_main" in a for a in argv):
            pids.append(int(name))
    return sorted(pids)
