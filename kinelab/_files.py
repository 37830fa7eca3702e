"""Writing files safely: to a temporary file beside the target, then renamed into place,
so that a failure never leaves a half-written output behind."""
from __future__ import annotations

import errno
import os
import stat
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import IO

from kinelab.errors import ModelError, describe


def file_path(path: object, name: str = "path") -> Path:
    """``path`` (text or path-like) as a :class:`~pathlib.Path`, else a :class:`ModelError`
    naming the argument ``name``."""
    text = os.fspath(path) if isinstance(path, os.PathLike) else path
    if not isinstance(text, str) or not text:
        hint = "; decode it first (path.decode())" if isinstance(text, bytes) else ""
        raise ModelError(f"{name}: expected a file's path (text or pathlib.Path), got "
                         f"{describe(path)}{hint}")
    return Path(text)


# -- reading: every file kinelab reads comes through read_file, bounded whatever it is -------
_CHUNK = 1 << 20
_KINDS = ((stat.S_ISFIFO, "a named pipe (FIFO)"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"))
# a pipe or device is opened without waiting for a writer (a FIFO with none would block)
_OPEN_FLAGS = (os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)
               | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0))


def byte_size(n: float, *, exact: bool = False) -> str:
    """A size in bytes as a message says it: ``8 MiB``, ``5.65 GiB`` (a limit, an estimate),
    ``8.0 MiB`` (``exact``: a file's size, which may be just over the limit), ``512 bytes``."""
    for unit, scale in (("TiB", 1 << 40), ("GiB", 1 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)):
        if n >= scale:
            return f"{n / scale:,.1f} {unit}" if exact else f"{n / scale:.3g} {unit}"
    return f"{int(n)} bytes"


def _not_regular(mode: int) -> str | None:
    """What a file that is not a regular one is (a directory, a FIFO, a device ...)."""
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "a directory, not a file; name a file"
    kind = next((name for test, name in _KINDS if test(mode)), "not a regular file")
    return f"{kind}, not a regular file; kinelab reads regular files only: name one"


def read_file(path: str | os.PathLike, limit: int, *, note: str = "") -> bytes:
    """The bytes of the regular file at ``path``, refused beyond ``limit`` bytes whatever the
    file says its size is.

    A FIFO, a device or a socket (or a symbolic link to one) is refused by its type before it
    is opened, and the file is opened without waiting, so that a pipe with no writer cannot
    block; at most ``limit + 1`` bytes are read (``/dev/zero`` and files of ``/proc`` say
    they hold 0).  Every refusal is a :class:`ModelError` naming the file; ``note`` ends the
    refusal of a file too large (what such a file holds, what to do instead).
    """
    path = file_path(path)
    source = str(path)
    try:
        why = _not_regular(os.stat(path).st_mode)
        if why is None:
            fd = os.open(path, _OPEN_FLAGS)
            try:
                info = os.fstat(fd)
                why = _not_regular(info.st_mode)      # the path replaced since os.stat
                if why is None and info.st_size <= limit:
                    data = _read_at_most(fd, limit + 1)
            finally:
                os.close(fd)
    except (FileNotFoundError, NotADirectoryError):
        raise ModelError("no such file; check the path", source=source) from None
    except IsADirectoryError:
        why = _not_regular(stat.S_IFDIR)
    except OSError as exc:
        raise ModelError(f"cannot read it: {exc.strerror or exc}", source=source) from None
    if why is not None:
        raise ModelError(why, source=source)
    if info.st_size > limit or len(data) > limit:
        size = (f"is {byte_size(info.st_size, exact=True)}" if info.st_size > limit else
                f"holds more than {byte_size(limit)}")
        raise ModelError(f"the file {size}; expected at most {byte_size(limit)}{note}",
                         source=source)
    return data


def _read_at_most(fd: int, n: int) -> bytes:
    parts, size = [], 0
    while size < n:
        chunk = os.read(fd, min(_CHUNK, n - size))
        if not chunk:
            break
        parts.append(chunk)
        size += len(chunk)
    return b"".join(parts)


def atomic_write(path: str | os.PathLike, write: Callable[[IO], None], *, binary: bool = False) -> Path:
    """Call ``write(file)`` on a temporary file and rename it to ``path`` when it succeeds.

    Raises
    ------
    ModelError
        When ``path`` cannot be written (a directory, a place that does not exist or is not
        writable, a full disk): the message names ``path``, not the temporary file.
    """
    path = file_path(path)
    tmp = None
    try:
        if path.is_dir():
            raise IsADirectoryError(errno.EISDIR, "it is a directory", str(path))
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
        with os.fdopen(fd, "wb" if binary else "w", **({} if binary else {"newline": ""})) as f:
            write(f)
        # mkstemp makes it private: give it the mode the file has, or a new file's usual one
        os.chmod(tmp, path.stat().st_mode & 0o7777 if path.exists() else 0o666 & ~_UMASK)
        os.replace(tmp, path)
    except OSError as exc:
        _remove(tmp)
        raise ModelError(f"cannot write it: {exc.strerror or exc}; choose another file or "
                         "directory", source=str(path)) from None
    except BaseException:
        _remove(tmp)
        raise
    return path


def _remove(tmp: str | None) -> None:
    if tmp is not None:
        Path(tmp).unlink(missing_ok=True)


def _read_umask() -> int:
    # the umask can only be read by setting it: done once, at import, before any thread of
    # kinelab's creates a file (a change while other threads work would leak to them)
    mask = os.umask(0)
    os.umask(mask)
    return mask


_UMASK = _read_umask()


def write_csv(columns: dict, path: str | os.PathLike) -> Path:
    """Write named (N,) columns as CSV with a header row, atomically."""
    import csv

    import numpy as np

    names = list(columns)
    data = np.column_stack([np.asarray(columns[n], dtype=float) for n in names]) if names else np.zeros((0, 0))

    def write(f):
        w = csv.writer(f)
        w.writerow(names)
        for start in range(0, len(data), 10_000):      # Python floats a block at a time
            w.writerows(data[start:start + 10_000].tolist())
    return atomic_write(path, write)
