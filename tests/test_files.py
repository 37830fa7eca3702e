"""Atomic writes: the whole file or nothing, with the mode a file would have; a command's
outputs as a set, all or nothing, only in its directory; writers that say which path they
cannot write."""
import errno
import os
import stat
from pathlib import Path

import pytest

from kinelab._files import atomic_write, outputs
from kinelab.errors import ModelError


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


# -- a set of outputs, all or nothing -------------------------------------------------------


def contents(d):
    """The files of ``d`` and their text (a staging directory is not one)."""
    return {p.name: p.read_text() for p in d.iterdir() if p.is_file()}


def test_a_set_is_moved_into_place_only_when_every_file_is_written(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.txt").write_text("old a")
    (out / "a.txt").chmod(0o640)
    with outputs(out) as files:
        a = files.write("a.txt", lambda p: p.write_text("new a"))
        files.write("b.txt", lambda p: p.write_text("new b"))
        assert contents(out) == {"a.txt": "old a"}        # staged, nothing in place yet
    assert a == out / "a.txt" and contents(out) == {"a.txt": "new a", "b.txt": "new b"}
    assert mode(out / "a.txt") == 0o640                    # a rewritten file keeps its mode


def test_a_move_that_fails_takes_back_the_files_moved_and_restores_the_old_ones(tmp_path,
                                                                                monkeypatch):
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.txt").write_text("old a")
    (out / "c.txt").write_text("old c")
    replace = os.replace

    def fails_on_c(src, dst):           # the last move into place
        if Path(dst) == out / "c.txt" and Path(src).parent.name.startswith(".kinelab-"):
            raise OSError(errno.ENOSPC, "No space left on device")
        replace(src, dst)
    monkeypatch.setattr(os, "replace", fails_on_c)
    with pytest.raises(ModelError, match=rf"^{out / 'c.txt'}: cannot write it: No space left"):
        with outputs(out) as files:
            for name in ("a.txt", "b.txt", "c.txt"):
                files.write(name, lambda p, n=name: p.write_text(f"new {n}"))
    assert contents(out) == {"a.txt": "old a", "c.txt": "old c"}
    assert sorted(p.name for p in out.iterdir()) == ["a.txt", "c.txt"]


def test_names_that_meet_on_some_file_system_are_told_apart(tmp_path):
    with outputs(tmp_path) as files:
        names = [files.write(n, lambda p: p.write_text(n)).name
                 for n in ("P.png", "p.png", "\u00e9.csv", "e\u0301.csv", "P.png")]
    assert names[0] == "P.png" and names[2] == "\u00e9.csv"
    assert len({n.casefold() for n in names}) == 5 and names[1].startswith("p-")
    assert names[1].endswith(".png") and names[4].endswith(".png")


@pytest.mark.parametrize("name", ["", ".", "..", "a/b", "../x", "/abs", "a\x00b"])
def test_a_set_takes_file_names_not_paths(name, tmp_path):
    with pytest.raises(ModelError, match="expected one file's name, not a path"):
        with outputs(tmp_path / "out") as files:
            files.write(name, lambda p: p.write_text("x"))
    assert list(tmp_path.iterdir()) == []          # not even the directory


def test_a_symbolic_link_or_a_directory_at_a_name_is_refused(tmp_path):
    outside = tmp_path / "outside"
    outside.write_text("keep")
    out = tmp_path / "out"
    out.mkdir()
    (out / "link.txt").symlink_to(outside)
    (out / "inside.txt").symlink_to(out / "dir")
    (out / "dir").mkdir()
    for name, why in (("link.txt", "symbolic link"), ("inside.txt", "symbolic link"),
                      ("dir", "directory")):
        with pytest.raises(ModelError, match=rf"^{out / name}: cannot write it: it is a {why}"):
            with outputs(out) as files:
                files.write(name, lambda p: p.write_text("x"))
    assert outside.read_text() == "keep" and sorted(p.name for p in out.iterdir()) == [
        "dir", "inside.txt", "link.txt"]


def test_a_directory_that_cannot_be_made_names_the_file(tmp_path):
    (tmp_path / "file").write_text("")
    with pytest.raises(ModelError, match=rf"^{tmp_path / 'file' / 'x.csv'}: cannot write it: "):
        with outputs(tmp_path / "file") as files:
            files.write("x.csv", lambda p: p.write_text("x"))


# -- the Python writers: a path that cannot be written is a ModelError naming it -------------
def writers():
    import numpy as np
    import kinelab as kl
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
                     q=np.linspace(0, 1, 3), qd=1.0)
    mf = kl.io.ModelFile.read("examples/crank_rocker.toml")
    return {
        "write_results": lambda p: kl.io.write_results(sol, p),
        "to_csv": lambda p: sol.to_csv(p),
        "save": lambda p: kl.io.save(mf, p),
        "to_svg": lambda p: kl.io.to_svg(mf.mechanism, p),
        "plot.save": lambda p: _figure_saved(p),
        "animate": lambda p: kl.plot.animate(sol, p, frames=2),
        "certificate": lambda p: kl.verify.certify(sol).to_json(p),
    }


def _figure_saved(path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import kinelab as kl
    fig = plt.figure()
    try:
        return kl.plot.save(fig, path)
    finally:
        plt.close(fig)


SUFFIX = {"save": ".toml", "to_svg": ".svg", "plot.save": ".png", "animate": ".gif",
          "certificate": ".json"}


@pytest.mark.parametrize("writer", ["write_results", "to_csv", "save", "to_svg", "plot.save",
                                    "animate", "certificate"])
def test_a_path_that_cannot_be_written_is_one_line_naming_it(writer, tmp_path):
    write = writers()[writer]
    suffix = SUFFIX.get(writer, ".csv")
    with pytest.raises(ModelError) as nul:
        write(f"x\x00y{suffix}")
    assert "\n" not in str(nul.value) and f"'x\\x00y{suffix}'" in str(nul.value)
    assert "NUL character" in str(nul.value) and "remove it" in str(nul.value)
    (tmp_path / "file").write_text("")
    where = tmp_path / "file" / f"x{suffix}"       # under a file: not a directory
    with pytest.raises(ModelError, match=rf"^{where}: cannot write it: .*; choose another file"):
        write(where)
    assert (tmp_path / "file").read_text() == "" and len(list(tmp_path.iterdir())) == 1
