"""Writing files safely: to a temporary file beside the target, then renamed into place,
so that a failure never leaves a half-written output behind; a command's outputs as a set,
written all or nothing into one directory, under names made safe."""
from __future__ import annotations

import contextlib
import errno
import hashlib
import os
import re
import shutil
import stat
import tempfile
import unicodedata
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO

from kinelab.errors import ModelError, describe, shown, shown_path

__all__ = ["file_path", "atomic_path", "atomic_write", "write_csv", "safe_name", "outputs",
           "Outputs", "output", "NAME_BYTES"]


def file_path(path: object, name: str = "path") -> Path:
    """``path`` (text or path-like) as a :class:`~pathlib.Path`, else a :class:`ModelError`
    naming the argument ``name``: a path must be non-empty text that the file system can
    take (no NUL character, no lone surrogate)."""
    text = os.fspath(path) if isinstance(path, os.PathLike) else path
    if not isinstance(text, str) or not text:
        hint = "; decode it first (path.decode())" if isinstance(text, bytes) else ""
        raise ModelError(f"{name}: expected a file's path (text or pathlib.Path), got "
                         f"{describe(path)}{hint}")
    if "\0" in text:
        raise ModelError(f"{name}: expected a file's path, got {shown(text)}, which holds a NUL "
                         "character (\\x00) that no file's name can hold; remove it")
    try:
        os.fsencode(text)
    except UnicodeError:
        raise ModelError(f"{name}: expected a file's path, got {shown(text)}, which holds a "
                         "character the file system cannot take (a lone surrogate); remove "
                         "it") from None
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


class UnwritableOutput(ModelError):
    """An output that cannot be written: the message names the file (``source``)."""


def _cannot_write(path: Path, exc: OSError) -> ModelError:
    return UnwritableOutput(f"cannot write it: {exc.strerror or exc}; choose another file or "
                            "directory", source=str(path))


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, *, suffix: str = "") -> Iterator[Path]:
    """A temporary file's path beside ``path`` (ending in ``suffix``), for a writer that
    needs a name rather than an open file; renamed to ``path`` when the block ends without
    an error, removed when it does not.  A symbolic link at ``path`` is replaced, never
    written through.

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
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=path.parent)
        os.close(fd)
        yield Path(tmp)
        # mkstemp makes it private: give it the mode the file has, or a new file's usual one
        os.chmod(tmp, path.stat().st_mode & 0o7777 if path.exists() else 0o666 & ~_UMASK)
        os.replace(tmp, path)
    except OSError as exc:
        _remove(tmp)
        raise _cannot_write(path, exc) from None
    except BaseException:
        _remove(tmp)
        raise


def atomic_write(path: str | os.PathLike, write: Callable[[IO], None], *, binary: bool = False) -> Path:
    """Call ``write(file)`` on a temporary file and rename it to ``path`` when it succeeds;
    raises as :func:`atomic_path` does."""
    path = file_path(path)
    with atomic_path(path) as tmp:
        with open(tmp, "wb" if binary else "w", **({} if binary else {"newline": ""})) as f:
            write(f)
    return path


def _remove(tmp: str | os.PathLike | None) -> None:
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


# -- names of outputs -----------------------------------------------------------------------
NAME_BYTES = 96     # UTF-8 bytes of a name made safe, at most: two of them and a command's own
                    # words (_acceleration_polygon.png) stay within the 255 a file's name can take
_FORBIDDEN = frozenset('/\\:*?"<>|')      # separators, and what Windows refuses in a name
_CONTROL = frozenset(("Cc", "Cf", "Cs", "Zl", "Zp"))    # controls, format characters (bidi
                                                         # overrides), lone surrogates, breaks
_DOTS = re.compile(r"\.{2,}")
_ENDS = re.compile(r"\A[. ]+|[. ]+\Z")
_MARKS = re.compile(r"/+")
# names Windows keeps for devices, whatever follows a dot ("con.csv" is the console too)
_RESERVED = frozenset(["con", "prn", "aux", "nul", *(f"{d}{k}" for d in ("com", "lpt")
                                                    for k in "0123456789\u00b9\u00b2\u00b3")])


def safe_name(text: str) -> str:
    """``text`` (the name of a model, point, link, joint or task) made safe to be part of
    a file's name: the same on every file system, never a path.

    A name that is safe already is kept as it is.  Otherwise each run of unsafe characters
    becomes ``_`` — separators and the characters Windows refuses (``/ \\ : * ? " < > |``),
    control and format characters, any run of two or more dots, dots and spaces at either
    end — a name Windows keeps for a device (``CON``, ``nul``, ``COM1`` ...) gets a ``_``
    before it, a long name is cut to :data:`NAME_BYTES` bytes of UTF-8, and the name ends
    in ``-`` and 8 hexadecimal digits of the SHA-256 of ``text``: two names that differ only
    in what was replaced still name two files.  Letters of any script are kept.

    Examples
    --------
    >>> safe_name("crank-rocker"), safe_name("slotted link (Erthal)"), safe_name("Ρ")
    ('crank-rocker', 'slotted link (Erthal)', 'Ρ')
    >>> safe_name("../../etc/passwd"), safe_name("a/b"), safe_name("a\\\\b")
    ('_etc_passwd-3754d6cb', 'a_b-c14cddc0', 'a_b-c62016d0')
    >>> safe_name(".."), safe_name("CON"), len(safe_name("x" * 10_000))
    ('_-5ec1f7e7', '_CON-a3dbc4b6', 96)
    """
    if not isinstance(text, str):
        raise ModelError(f"name: expected text, got {describe(text)}")
    marked = "".join("/" if c in _FORBIDDEN or unicodedata.category(c) in _CONTROL else c
                     for c in text)
    marked = _ENDS.sub("/", _DOTS.sub("/", marked))
    name = _MARKS.sub("_", marked)
    if not name or name.split(".", 1)[0].rstrip(" ").casefold() in _RESERVED:
        name = "_" + name
    if name == text and len(text.encode("utf-8")) <= NAME_BYTES:
        return text
    code = hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()[:8]
    head = name.encode("utf-8")[:NAME_BYTES - len(code) - 1].decode("utf-8", "ignore")
    return f"{head}-{code}"


class Outputs:
    """The files of one command, written all or nothing into one directory.

    Each file is written (by :meth:`write`) into a staging directory inside ``directory``
    (``.kinelab-*``); when every file of the set has been written, each is moved into
    place, an existing file of the same name being kept aside until the last move has
    succeeded.  If anything fails, the staging directory is removed, the files already
    moved are taken back and the files they replaced restored, and the directories made
    for the set (``directory`` and its missing parents) are removed: the directory is as
    it was.  Use it through :func:`outputs`.
    """

    def __init__(self, directory: str | os.PathLike):
        self.directory = file_path(directory, "out")
        self._stage: Path | None = None
        self._made: list[Path] = []          # directories made for the set, outermost first
        self._files: list[tuple[Path, Path]] = []          # (staged, final)
        self._taken: set[str] = set()

    def write(self, name: str, write: Callable[[Path], object]) -> Path:
        """Write the file ``name`` of the set: ``write(path)`` writes it at ``path`` (in the
        staging directory); returns where it will be once the set is complete,
        ``directory / name``.

        ``name`` is one file's name, made by :func:`safe_name` from anything a file or a
        caller chose; a name the set holds already (or one that differs from it only in
        case or Unicode normalisation, the same file on some file systems) gets
        ``-`` and 8 hexadecimal digits before its suffix.  Errors of ``write`` that name
        the staged file name ``directory / name`` instead.
        """
        name = self._unique(name)
        final = self.directory / name
        self._check(final)               # said now, before the other files' work
        staged = self._staging(final) / name
        try:
            write(staged)
        except ModelError as exc:
            if exc.source != str(staged):
                raise
            raise UnwritableOutput(exc.problems, source=str(final)) from None
        except OSError as exc:
            raise _cannot_write(final, exc) from None
        if not staged.is_file():
            raise UnwritableOutput("cannot write it: nothing was written; choose another file "
                                   "or directory", source=str(final))
        self._files.append((staged, final))
        return final

    def _unique(self, name: str) -> str:
        if (not isinstance(name, str) or name in ("", ".", "..") or "/" in name or "\0" in name
                or os.sep in name or (os.altsep and os.altsep in name)):
            raise ModelError(f"name: expected one file's name, not a path, got {describe(name)}")
        key = unicodedata.normalize("NFC", name).casefold()
        if key in self._taken:
            stem, dot, suffix = name.rpartition(".")
            stem, suffix = (stem, dot + suffix) if stem else (name, "")
            code = hashlib.sha256(name.encode("utf-8", "surrogatepass")).hexdigest()[:8]
            name = f"{stem}-{code}{suffix}"
            key = unicodedata.normalize("NFC", name).casefold()
            if key in self._taken:
                raise ModelError(f"name: two outputs would both be named {shown(name)}; rename "
                                 "one of the items they are named after")
        self._taken.add(key)
        return name

    def _check(self, final: Path) -> None:
        """Refuse to write over a directory or a symbolic link at ``final``, or anywhere
        but directly in the set's directory (symbolic links resolved)."""
        try:
            self._refuse(final)
        except OSError as exc:      # a name too long for the file system, a parent not a directory
            raise _cannot_write(final, exc) from None

    def _refuse(self, final: Path) -> None:
        if final.is_symlink():
            raise UnwritableOutput("cannot write it: it is a symbolic link, and kinelab writes "
                                   "neither through one nor over it; remove the link or choose "
                                   "another directory", source=str(final))
        if final.is_dir():
            raise UnwritableOutput("cannot write it: it is a directory; choose another file or "
                                   "directory", source=str(final))
        if final.resolve().parent != self.directory.resolve():
            raise UnwritableOutput(f"cannot write it: it is not in {shown_path(self.directory)}; "
                                   "choose another directory", source=str(final))

    def _staging(self, final: Path) -> Path:
        if self._stage is not None:
            return self._stage
        d = self.directory
        try:
            if d.exists() and not d.is_dir():
                raise NotADirectoryError(errno.ENOTDIR, f"{shown_path(d)} is not a directory")
            missing = [d, *(p for p in d.parents if not p.exists())] if not d.exists() else []
            for p in reversed(missing):
                p.mkdir()
                self._made.append(p)
            self._stage = Path(tempfile.mkdtemp(prefix=".kinelab-", dir=d))
        except OSError as exc:
            raise _cannot_write(final, exc) from None
        return self._stage

    def _commit(self) -> None:
        for _, final in self._files:
            self._check(final)
        moved = []      # (staged, final, backup): where the file it replaces was kept, or None
        old = None
        try:
            for staged, final in self._files:
                failing = final
                backup = None
                if os.path.lexists(final):
                    old = old or Path(tempfile.mkdtemp(dir=self._stage))
                    backup = old / staged.name
                    os.chmod(staged, stat.S_IMODE(final.stat().st_mode))   # keep its mode
                    os.replace(final, backup)
                moved.append((staged, final, backup))
                os.replace(staged, final)
        except OSError as exc:
            for staged, final, backup in reversed(moved):
                with contextlib.suppress(OSError):
                    if not staged.exists():          # it was moved in: take it back
                        os.replace(final, staged)
                    if backup is not None:
                        os.replace(backup, final)
            raise _cannot_write(failing, exc) from None

    def _discard(self, made: bool) -> None:
        """Remove the staging directory and, with ``made``, the directories made for the set
        (each only if empty)."""
        if self._stage is not None:
            shutil.rmtree(self._stage, ignore_errors=True)
            self._stage = None
        for d in reversed(self._made if made else []):
            try:
                d.rmdir()
            except OSError:
                break


def output(path: str | os.PathLike, write: Callable[[Path], object]) -> Path:
    """One file written as a set of one (:func:`outputs`): ``write(path)`` writes it in
    the staging directory beside ``path``; returns ``path``."""
    path = file_path(path, "out")
    with outputs(path.parent) as files:
        return files.write(path.name, write)


@contextlib.contextmanager
def outputs(directory: str | os.PathLike) -> Iterator[Outputs]:
    """The files of one command, all or nothing: those written in the block (by
    :meth:`Outputs.write`) are in ``directory`` when it ends without an error; when it
    raises, none is, and the directory is as it was.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "out"
    >>> with outputs(out) as files:
    ...     a = files.write(f"{safe_name('a/b')}.txt", lambda p: p.write_text("1"))
    >>> a.name, a.read_text()
    ('a_b-c14cddc0.txt', '1')
    >>> try:
    ...     with outputs(out) as files:
    ...         _ = files.write("c.txt", lambda p: p.write_text("2"))
    ...         raise RuntimeError("the second file fails")
    ... except RuntimeError:
    ...     pass
    >>> sorted(p.name for p in out.iterdir())
    ['a_b-c14cddc0.txt']
    """
    files = Outputs(directory)
    try:
        yield files
        files._commit()
    except BaseException:
        files._discard(made=True)
        raise
    files._discard(made=False)
