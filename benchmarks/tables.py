"""Time to write the largest tables the command line allows, end to end (start-up, sweep,
text, file), and the rates that set those limits.

``kinelab analyze`` writes CSV and JSON up to ``kinelab.io._results.MAX_TABLE_VALUES``
values (rows x columns) and Parquet up to 1,000,000 samples; ``kinelab dynamics`` writes its
table and figures up to ``kinelab.cli._dynamics.MAX_VALUES`` values.  Each case runs the
command at its limit on the example models and prints the seconds it took, which should
stay well under 30 s on a slow machine.

    python benchmarks/tables.py [--quick]
"""
from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

from kinelab import kinematics
from kinelab.cli._dynamics import MAX_VALUES
from kinelab.dynamics._inverse import table_width as dynamics_width
from kinelab.io import ModelFile
from kinelab.io._results import MAX_TABLE_VALUES
from kinelab.kinematics._columns import table_width

ROOT = Path(__file__).resolve().parents[1]
KINELAB = [sys.executable, "-c", "from kinelab.cli import main; main()"]


def timed(*args: str) -> float:
    start = time.perf_counter()
    subprocess.run(KINELAB + list(args), check=True, capture_output=True, cwd=ROOT)
    return time.perf_counter() - start


def main(quick: bool = False) -> None:
    scale = 0.1 if quick else 1.0
    crank_rocker = ROOT / "examples" / "crank_rocker.toml"
    engine = ROOT / "examples" / "engine.toml"
    width = table_width(kinematics.plan(ModelFile.read(crank_rocker).mechanism))
    cases = [(fmt, int(scale * MAX_TABLE_VALUES[fmt] // width)) for fmt in ("csv", "json")]
    cases.append(("parquet", int(scale * 1_000_000)))
    print(f"kinelab analyze {crank_rocker.name} ({width} columns)")
    print(f"{'format':>8} {'rows':>10} {'values':>12} {'seconds':>8} {'values/s':>12}")
    with tempfile.TemporaryDirectory() as folder:
        for fmt, rows in cases:
            try:
                seconds = timed("analyze", str(crank_rocker), "--samples", str(rows), "--format",
                                fmt, "-q", "--out", str(Path(folder) / f"table.{fmt}"))
            except subprocess.CalledProcessError as exc:     # Parquet needs pyarrow
                print(f"{fmt:>8} {rows:>10,} not written: {exc.stderr.decode().strip()}")
                continue
            values = rows * width
            print(f"{fmt:>8} {rows:>10,} {values:>12,} {seconds:>8.1f} {values / seconds:>12,.0f}")
        dyn_width = dynamics_width(ModelFile.read(engine).mechanism)
        rows = int(scale * MAX_VALUES // dyn_width)
        seconds = timed("dynamics", str(engine), "--samples", str(rows), "--out", folder)
        print(f"kinelab dynamics {engine.name} ({dyn_width} columns, with its figures)")
        print(f"{'csv':>8} {rows:>10,} {rows * dyn_width:>12,} {seconds:>8.1f} "
              f"{rows * dyn_width / seconds:>12,.0f}")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv[1:])
