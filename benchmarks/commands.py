"""Processor time of the short commands of the demo (``make demo``), each a fresh process.

A command imports only what it uses (``kinelab --help`` nothing of kinelab's rooms, ``check``
no scipy, sympy, matplotlib, pandas or numba), and a short command does not load the
compiled kernel (see docs/kinematics.md, "Light work").  Each line is the processor time
(user + system, of the process and its children) of one command, the smallest and the
median of N runs, beside its reference in the same run:

- ``--help``, ``check`` and ``analyze``: a Python that imports numpy and does nothing else,
  the floor of any command that computes;
- ``animate``: the same frames drawn as matplotlib's writers draw them (the whole figure for
  each frame, a palette cut for each frame by Pillow), in the same process set-up.

The compile cache is left as it is (a command that finds the kernel compiled does not load
it for light work).  Whether kinelab's modules are compiled to bytecode is said first:
``make demo`` and ``make test`` compile them; without it (an editable install where
PYTHONDONTWRITEBYTECODE is set), every process compiles the modules it imports, about a
third of ``check``'s time.

    python benchmarks/commands.py [--repeat N]
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEMO = "examples/crank_rocker.toml"

KINELAB = [sys.executable, "-c", "from kinelab.cli import main; main()"]

# animate, its frames drawn whole and written with a palette per frame
WHOLE = textwrap.dedent("""
    import sys
    import numpy as np
    from kinelab.plot import _animate

    def whole(fig, ax, draw, n):
        for k in range(n):
            draw(k)
            fig.canvas.draw()
            yield np.asarray(fig.canvas.buffer_rgba())

    def per_frame_palette(path, frames, fps):
        from PIL import Image
        images = [Image.fromarray(f.copy(), "RGBA").convert("RGB") for f in frames]
        images[0].save(path, format="GIF", save_all=True, append_images=images[1:],
                       duration=int(1000 / fps), loop=0)

    _animate._frames, _animate._write_gif = whole, per_frame_palette
    from kinelab.cli import main
    main()
""")


def _bytecode() -> bool:
    """Whether every module of kinelab has its bytecode, up to date, in __pycache__."""
    import importlib.util
    for source in (ROOT / "kinelab").rglob("*.py"):
        cached = Path(importlib.util.cache_from_source(str(source)))
        if not cached.exists() or cached.stat().st_mtime < source.stat().st_mtime:
            return False
    return True


def cpu(command: list[str]) -> float:
    """Processor time (user + system) of a command and its children, s."""
    proc = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        raise SystemExit(f"failed: {' '.join(command)}")
    return usage.ru_utime + usage.ru_stime


def times(command: list[str], repeat: int) -> str:
    runs = sorted(cpu(command) for _ in range(repeat))
    return f"{runs[0]:.2f} s (median {statistics.median(runs):.2f} s)"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    out = Path(tempfile.mkdtemp(prefix="kinelab-commands-"))
    numpy = [sys.executable, "-c", "import numpy"]
    print(f"processor time, smallest of {args.repeat} runs; kinelab's modules compiled to "
          f"bytecode: {'yes' if _bytecode() else 'no'}")
    print(f"  python -c 'import numpy' (reference): {times(numpy, args.repeat)}")
    for label, extra in [("kinelab --help", ["--help"]),
                         (f"kinelab check {DEMO}", ["check", DEMO]),
                         (f"kinelab analyze {DEMO}", ["analyze", DEMO, "--out", str(out)])]:
        print(f"  {label}: {times(KINELAB + extra, args.repeat)}")
    animate = ["animate", DEMO, "--out", str(out), "--format", "gif"]
    repeat = max(1, args.repeat // 2)
    print(f"  kinelab animate {DEMO} --format gif: {times(KINELAB + animate, repeat)}")
    print(f"    reference, frames drawn whole and a palette per frame: "
          f"{times([sys.executable, '-c', WHOLE] + animate, repeat)}")


if __name__ == "__main__":
    main()
