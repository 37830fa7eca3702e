"""Writing files safely: to a temporary file beside the target, then renamed into place,
so that a failure never leaves a half-written output behind."""
from __future__ import annotations

import errno
import os
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
        from kinelab._tables import csv_blocks
        csv.writer(f).writerow(names)
        for block in csv_blocks(data):
            f.write(block)
    return atomic_write(path, write)
