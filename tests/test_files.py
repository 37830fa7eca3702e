"""Atomic writes: the whole file or nothing, with the mode a file would have."""
import os
import stat

import pytest

from kinelab._files import atomic_write


def mode(path):
    return stat.S_IMODE(path.stat().st_mode)


def test_a_new_file_gets_the_usual_mode_and_a_rewrite_keeps_the_files_own(tmp_path):
    path = tmp_path / "out" / "table.csv"
    atomic_write(path, lambda f: f.write("a\n"))
    umask = os.umask(0)
    os.umask(umask)
    assert path.read_text() == "a\n" and mode(path) == 0o666 & ~umask
    path.chmod(0o640)
    atomic_write(path, lambda f: f.write("b\n"))
    assert path.read_text() == "b\n" and mode(path) == 0o640


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    path = tmp_path / "table.csv"
    path.write_text("old\n")

    def fail(f):
        f.write("half")
        raise RuntimeError("disk full")
    with pytest.raises(RuntimeError):
        atomic_write(path, fail)
    assert path.read_text() == "old\n" and [p.name for p in tmp_path.iterdir()] == ["table.csv"]
