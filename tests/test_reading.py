"""Every read is bounded (kinelab._files.read_file): regular files only, refused by their
type before they are opened, and never more than the limit and one byte read.

What could hang (a FIFO with no writer) or eat memory (/dev/zero, /dev/urandom) if the code
regressed runs in a child process with a timeout and a bounded address space, so that a
regression fails the test instead of stalling or starving the suite."""
import json
import os
import socket
import stat
import subprocess
import sys
from pathlib import Path

import pytest

import kinelab as kl
from kinelab._files import read_file
from kinelab.errors import ModelError

ROOT = Path(__file__).resolve().parents[1]
MODEL = (ROOT / "examples" / "crank_rocker.toml").read_text()
TIMEOUT = 120          # s for a child that does a few reads (its start takes about 2 s)

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo") or not Path("/dev/zero").exists(),
                                reason="FIFOs and /dev/zero are POSIX's")

# A child process: runs each command line (or Python call) in-process and prints
# [exit status, stderr, escaped exception] for each, within 2 GiB of address space.
_CHILD = """
import json, resource, sys
resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
from click.testing import CliRunner
from kinelab.cli import main
out = []
for args in json.loads(sys.argv[1]):
    if isinstance(args, str):                # a Python call
        import kinelab as kl
        try:
            eval(args)
            out.append([0, "", None])
        except kl.errors.ModelError as exc:
            out.append([2, str(exc), None])
        except BaseException as exc:
            out.append([1, "", repr(exc)[:300]])
        continue
    r = CliRunner().invoke(main, args)
    escaped = r.exception is not None and not isinstance(r.exception, SystemExit)
    out.append([r.exit_code, r.stderr, repr(r.exception)[:300] if escaped else None])
print(json.dumps(out))
"""


def in_child(cases: list, cwd: Path) -> list:
    """Run ``cases`` in a child process; its timeout kills it (a FIFO read that blocks)."""
    done = subprocess.run([sys.executable, "-c", _CHILD, json.dumps(cases)], cwd=cwd,
                          capture_output=True, text=True, timeout=TIMEOUT,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout.splitlines()[-1])


@pytest.fixture
def hostile(tmp_path):
    """Files that are not regular ones, by kind: a FIFO (no writer), a link to it, links to
    /dev/zero and /dev/urandom, and a socket; each under every suffix kinelab reads."""
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    made = {}
    for suffix in (".toml", ".json", ".csv", ".parquet", ".pyslvs"):
        fifo = tmp_path / f"pipe{suffix}"
        os.mkfifo(fifo)
        made[fifo.name] = "a named pipe (FIFO)"
        for name, target, kind in (("pipelink", fifo, "a named pipe (FIFO)"),
                                   ("zero", "/dev/zero", "a character device"),
                                   ("random", "/dev/urandom", "a character device")):
            (tmp_path / f"{name}{suffix}").symlink_to(target)
            made[f"{name}{suffix}"] = kind
    sock.bind(str(tmp_path / "socket.toml"))
    made["socket.toml"] = "a socket"
    yield tmp_path, made
    sock.close()


def _refused(result, name: str, kind: str) -> None:
    status, stderr, escaped = result
    assert escaped is None, escaped
    assert status == 2, (name, stderr)
    lines = stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinelab: error: "), stderr
    assert name in lines[0] and f"{kind}, not a regular file" in lines[0], lines[0]


# every command that reads a file, on every kind of file that is not a regular one
COMMANDS = [
    ("check", "{}.toml"), ("analyze", "{}.toml"), ("derive", "{}.toml"), ("mobility", "{}.toml"),
    ("dynamics", "{}.toml", "--no-plots"), ("synth", "{}.toml", "--no-figures"),
    ("import", "{}.pyslvs", "-o", "out.toml"), ("import", "{}.json", "-o", "out.toml"),
    ("differentiate", "{}.csv"), ("sweep", "fourbar", "{}.csv", "-o", "s.csv"),
    ("sweep", "fourbar", "{}.parquet", "-o", "s.csv"), ("atlas", "build", "{}.csv"),
    ("atlas", "find", "{}.parquet", "path.csv"),
]


def test_no_command_reads_a_fifo_a_device_or_a_socket(hostile):
    tmp, made = hostile
    cases, expected = [], []
    for command in COMMANDS:
        for stem in ("pipe", "pipelink", "zero", "random"):
            args = [a.format(stem) for a in command]
            name = next(a for a in args if a.startswith(stem))
            cases.append(args)
            expected.append((name, made[name]))
    cases.append(["check", "socket.toml"])
    expected.append(("socket.toml", "a socket"))
    for result, (name, kind) in zip(in_child(cases, tmp), expected):
        _refused(result, name, kind)


def test_the_python_readers_refuse_them_too(hostile):
    tmp, made = hostile
    calls = ["kl.load('pipe.toml')", "kl.io.load_task('zero.toml')",
             "kl.io.read_curve('random.csv')", "kl.io.from_linkage2d_json('pipelink.json')",
             "kl.sweep.Atlas.from_parquet('zero.parquet')", "kl.sweep.read_parquet('pipe.parquet')",
             "kl.io.ModelFile.read('socket.toml')"]
    for call, (status, message, escaped) in zip(calls, in_child(calls, tmp)):
        assert escaped is None and status == 2, (call, escaped)
        assert "not a regular file" in message and message.count("\n") == 0, message


def test_a_regular_file_is_read_whole_up_to_its_limit(tmp_path):
    f = tmp_path / "m.toml"
    f.write_bytes(b"x" * 100)
    assert read_file(f, 100) == b"x" * 100
    with pytest.raises(ModelError, match=r"m\.toml: the file is 100 bytes; expected at most 99 "
                                         r"bytes \(a note\)$"):
        read_file(f, 99, note=" (a note)")


def test_a_file_larger_than_it_says_is_cut_at_the_limit_plus_one():
    """/proc's files are regular but say they hold 0 bytes: read_file reads limit + 1."""
    path = Path("/proc/self/status")
    if not path.exists() or path.stat().st_size != 0:
        pytest.skip("no /proc file that says it is empty")
    with pytest.raises(ModelError, match=r"status: the file holds more than 10 bytes; expected at "
                                         r"most 10 bytes$"):
        read_file(path, 10)


@pytest.mark.parametrize("make, message", [
    (lambda p: None, "no such file; check the path"),
    (lambda p: p.mkdir(), "a directory, not a file; name a file"),
    (lambda p: p.parent.joinpath("file").write_text("") or p.parent.joinpath("file"),
     "no such file; check the path"),
])
def test_what_is_no_file_is_named(tmp_path, make, message):
    path = tmp_path / "x.toml"
    made = make(path)
    if isinstance(made, Path):           # a path through a file: file/x.toml
        path = made / "x.toml"
    with pytest.raises(ModelError, match=f"x.toml: {message}$"):
        read_file(path, 10)


def test_a_file_that_cannot_be_read_is_named(tmp_path):
    if os.geteuid() == 0:
        pytest.skip("root reads every file")
    path = tmp_path / "locked.toml"
    path.write_text(MODEL)
    path.chmod(0)
    with pytest.raises(ModelError, match=r"locked\.toml: cannot read it: Permission denied$"):
        read_file(path, 1 << 20)


@pytest.mark.parametrize("suffix, read, limit", [
    (".toml", lambda p: kl.load(p), "8 MiB"),
    (".csv", lambda p: kl.io.read_curve(p), "64 MiB"),
    (".parquet", lambda p: kl.sweep.Atlas.from_parquet(p), "1 GiB"),
])
def test_a_file_beyond_its_limit_is_refused_before_it_is_read(tmp_path, suffix, read, limit):
    """Sparse files: their size is known without a byte written."""
    from kinelab.io._csv import TABLE_BYTES
    from kinelab.io._text import MAX_BYTES
    from kinelab.sweep._run import PARQUET_BYTES
    size = {".toml": MAX_BYTES, ".csv": TABLE_BYTES, ".parquet": PARQUET_BYTES}[suffix] + 1
    path = tmp_path / f"big{suffix}"
    with path.open("wb") as f:
        f.truncate(size)
    assert stat.S_ISREG(path.stat().st_mode)
    with pytest.raises(ModelError, match=rf"big\{suffix}: .*the file is [\d.]+ [MG]iB; expected "
                                         rf"at most {limit}"):
        read(path)
