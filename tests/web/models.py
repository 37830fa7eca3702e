"""Comparing the models the web app sends with the files kinelab writes; a real server."""
import contextlib
import math
import re
import subprocess
import sys
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


@contextlib.contextmanager
def serving():
    """``kinelab serve --port 0`` on loopback, ended on leaving: (its port, the lines of its
    log, standard error, as they come)."""
    command = [sys.executable, "-c", "from kinelab.cli import main; main()", "serve", "--port", "0"]
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=ROOT)
    log = []
    try:
        line = proc.stdout.readline()
        match = re.search(r"serving at http://127\.0\.0\.1:(\d+)/", line)
        assert match, line
        threading.Thread(target=lambda: log.extend(proc.stderr), daemon=True).start()
        yield int(match.group(1)), log
    finally:
        proc.terminate()
        proc.wait(timeout=20)


def assert_same_model(a, b) -> None:
    """Two model files equal but for the numbers that a JSON float carries to within one
    unit in the last place (docs/model-format.md: the digits a float prints as)."""
    def same(x, y, where):
        if isinstance(x, float) and isinstance(y, float):
            assert math.isclose(x, y, rel_tol=3e-16, abs_tol=1e-300), (where, x, y)
        elif isinstance(x, dict) and isinstance(y, dict):
            assert x.keys() == y.keys(), where
            for k in x:
                same(x[k], y[k], f"{where}.{k}")
        elif isinstance(x, (list, tuple)) and isinstance(y, (list, tuple)):
            assert len(x) == len(y), where
            for k, (u, v) in enumerate(zip(x, y)):
                same(u, v, f"{where}[{k}]")
        else:
            assert x == y, (where, x, y)
    same(a.to_dict(), b.to_dict(), "model")
