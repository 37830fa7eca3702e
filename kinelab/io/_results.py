"""Results export: one row per sample, as CSV, JSON or Parquet."""
from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Literal

import numpy as np

from kinelab._files import atomic_write, write_csv
from kinelab.errors import ModelError, check_choice, describe, shown
from kinelab._files import file_path
from kinelab.kinematics import KinematicSolution
from kinelab.kinematics._solution import takes_solution
from kinelab.model import Units

__all__ = ["RESULT_FORMATS", "write_results", "result_format", "results_json", "json_ready",
           "MAX_TABLE_VALUES", "table_too_large"]

RESULT_FORMATS = ("csv", "json", "parquet")

MAX_TABLE_VALUES = {"csv": 12_000_000, "json": 10_000_000}
"""The most values (rows x columns) ``kinelab analyze`` (and the browser app) writes as CSV or
JSON.  Each number becomes text by Python's shortest round-trip formatting, about 1 us a
value on a slow, loaded machine (a little more as JSON), so a table this large takes about
20 s with its sweep (``benchmarks/tables.py`` prints the rates); Parquet keeps numbers binary
and is bounded by the memory budget only."""


def table_too_large(fmt: str, rows: int, columns: int) -> str | None:
    """Why a table of ``rows`` x ``columns`` is not written as ``fmt`` (past
    :data:`MAX_TABLE_VALUES`), in words; None when it may be."""
    most = MAX_TABLE_VALUES.get(fmt)
    if most is None or rows * columns <= most:
        return None
    return (f"a {fmt.upper()} table of {rows:,} rows x {columns:,} columns is "
            f"{rows * columns:,} values; kinelab writes at most {most:,} as {fmt.upper()} (about "
            f"30 s): ask for at most {max(most // max(columns, 1), 1):,} rows")


@takes_solution
def write_results(sol: KinematicSolution, path: str | os.PathLike, *,
                  format: Literal["csv", "json", "parquet"] | None = None,
                  degrees: bool = False, units: Units | Mapping[str, str] | None = None) -> Path:
    """Write a sweep with one row per sample, every column of ``sol.columns()``.

    The columns are the inputs; every link's angle, omega, alpha, K and L; every slide with
    its rates, K and L; every point's x, y, vx, vy, ax, ay, K and L; det J and the singular
    flag.  Each column is named ``item.quantity[unit]`` (``rocker.angle[deg]``,
    ``P.vx[mm/s]``), without spaces; see :meth:`KinematicSolution.columns`.

    Parameters
    ----------
    sol : KinematicSolution
    path : str or path-like
        Written to a temporary file beside it, then renamed: no half-written output.
    format : {"csv", "json", "parquet"}, optional
        Default: from the suffix of ``path`` (``.csv``, ``.json``, ``.parquet``), CSV when
        it has none; see :func:`result_format`.  JSON is a list of row objects
        (``null`` where a value is undefined); Parquet needs the optional ``pyarrow``.
    degrees : bool
        Angles (and angular rates, K and L) in degrees: shorthand for
        ``units={"angle": "deg"}``.
    units : Units or mapping, optional
        ``{"length": "mm", "angle": "deg"}``: the units of lengths and angles; default SI.

    Raises
    ------
    ModelError
        An unknown format, a suffix of ``path`` that names another format (or none, without
        ``format``), or an unknown unit or key in ``units`` (nothing is written).

    Examples
    --------
    >>> import tempfile, pathlib, csv
    >>> sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=[0.0, 0.5, 1.0], qd=1.0)
    >>> path = kl.io.write_results(sol, pathlib.Path(tempfile.mkdtemp()) / "sc.csv",
    ...                            units={"length": "mm", "angle": "deg"})
    >>> rows = list(csv.DictReader(path.open()))
    >>> len(rows), rows[1]["jO2.q[deg]"], rows[0]["B.x[mm]"]       # 0.5 rad; 1 + 3 m
    (3, '28.64788975654116', '4000.0')
    """
    path = file_path(path)
    fmt = result_format(path, format)
    columns = sol.columns(degrees=degrees, units=units)
    if fmt == "csv":
        return write_csv(columns, path)
    if fmt == "json":
        return atomic_write(path, lambda f: _write_json(columns, f))
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        raise ModelError("format: Parquet needs the optional dependency pyarrow; install it with "
                         "pip install 'kinelab[parquet]', or choose csv or json") from None
    import pandas
    frame = pandas.DataFrame(columns)
    return atomic_write(path, lambda f: frame.to_parquet(f, index=False), binary=True)


def result_format(path: str | os.PathLike, format: str | None = None) -> str:
    """The format a table is written in: ``format`` when given, else the one ``path``'s
    suffix names (CSV when it has none).  A suffix that names another format, or none of
    them, is refused: a file called ``x.xlsx`` or ``x.json`` must not hold CSV."""
    suffix = Path(path).suffix.lower()
    named = {f".{f}": f for f in RESULT_FORMATS}.get(suffix)
    if format is not None:
        check_choice("format", format, RESULT_FORMATS)
        if named is not None and named != format:
            raise ModelError(f"format: {describe(format)} was asked for, but the file name "
                             f"{shown(Path(path).name)} says {describe(named)}; make them agree")
        return format
    if named is None and suffix:
        raise ModelError(f"path: expected a file name ending in "
                         f"{', '.join('.' + f for f in RESULT_FORMATS)}, got "
                         f"{shown(Path(path).name)}; rename it or give the format")
    return named or "csv"


@takes_solution
def results_json(sol: KinematicSolution, *, degrees: bool = False,
                 units: Units | Mapping[str, str] | None = None) -> str:
    """The JSON text :func:`write_results` writes for ``sol``: a list of row objects, one
    per sample, ``null`` where a value is undefined.

    Examples
    --------
    >>> import json
    >>> sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=[0.0, 0.5], qd=1.0)
    >>> rows = json.loads(kl.io.results_json(sol, units={"length": "mm"}))
    >>> len(rows), rows[0]["B.x[mm]"]
    (2, 4000.0)
    """
    import io

    buffer = io.StringIO()
    _write_json(sol.columns(degrees=degrees, units=units), buffer)
    return buffer.getvalue()


def json_ready(value):
    """``value`` as plain data for strict JSON: a number that is not finite becomes None
    (null, never Infinity or NaN), numpy arrays and numbers become lists and Python numbers,
    and mappings, lists and tuples are walked.

    Examples
    --------
    >>> json_ready({"error": np.float64(np.inf), "q": np.array([0.5, np.nan]), "ok": np.True_})
    {'error': None, 'q': [0.5, None], 'ok': True}
    """
    if isinstance(value, dict):
        return {k: json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_ready(v) for v in value]
    if isinstance(value, np.ndarray):
        if value.dtype == bool:
            return value.tolist()
        a = np.asarray(value, float)
        finite = np.isfinite(a)
        if finite.all():
            return a.tolist()
        out = a.astype(object)
        out[~finite] = None
        return out.tolist()
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (float, np.floating, np.integer)):
        x = float(value) if isinstance(value, (float, np.floating)) else int(value)
        return x if math.isfinite(x) else None
    return value


def _write_json(columns: dict[str, np.ndarray], f) -> None:
    from kinelab._tables import json_blocks
    for block in json_blocks(columns):
        f.write(block)
