"""Measured curves in: a CSV table of an abscissa (time, or an input angle) and a
displacement, for :func:`kinelab.solvers.differentiate`."""
from __future__ import annotations

import csv
import math
import numbers
import os
import re
from dataclasses import dataclass

import numpy as np

from kinelab._memory import require
from kinelab.errors import ModelError, describe, quoted, shown
from kinelab._files import file_path
from kinelab.io._text import read_text
from kinelab.solvers._differentiate import MIN_SAMPLES

__all__ = ["MeasuredCurve", "read_curve"]

_UNIT = re.compile(r"^\s*(.*?)\s*\[(.*)\]\s*$")      # "t [s]": name t, unit s


@dataclass(frozen=True)
class MeasuredCurve:
    """Two columns of a CSV file: the abscissa and the measured values.

    Attributes
    ----------
    x, y : ndarray, shape (N,)
        As written in the file (no unit conversion).
    x_name, y_name : str
        The columns' names, without their units.
    x_unit, y_unit : str
        The units written in brackets in the header (``t [s]``), else "".
    source : str
        The file.
    """

    x: np.ndarray
    y: np.ndarray
    x_name: str
    y_name: str
    x_unit: str
    y_unit: str
    source: str


def _number(text: str) -> float | None:
    try:
        v = float(text)
    except ValueError:
        return None
    return v


def _choice(value: object, what: str) -> str | int | None:
    """A column as given: None, a name, or a number from 1 (a whole number or its digits)."""
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)):
        return int(value)
    raise ModelError(f"{what}: expected a column's name or its number from 1, got {describe(value)}")


def _column(header: list[str], choice: str | int | None, default: int, what: str, source: str) -> int:
    if choice is None:
        return default
    names = [_UNIT.sub(r"\1", h).strip() for h in header]
    for k, (full, bare) in enumerate(zip(header, names)):
        if choice in (full.strip(), bare):
            return k
    number = choice if isinstance(choice, int) else int(choice) if choice.isdigit() else 0
    if 1 <= number <= len(header):
        return number - 1
    raise ModelError(f"{what}: expected a column of the file, by name or number from 1, got "
                     f"{shown(choice)}; the columns are {quoted(names)}", source=source)


def read_curve(path: str | os.PathLike, *, x: str | None = None, y: str | None = None) -> MeasuredCurve:
    """Read a measured curve from a CSV file.

    The file has a header row naming its columns (a unit may follow a name in brackets,
    ``t [s]``) and one sample a row; blank lines and lines starting with ``#`` are skipped.
    By default the first column is the abscissa and the second the curve.

    Parameters
    ----------
    path : str or path-like
    x, y : str or int, optional
        The columns to use, by name (with or without the unit) or by number from 1 (``2``
        or ``"2"``).

    Returns
    -------
    MeasuredCurve

    Raises
    ------
    ModelError
        The file cannot be read, a column is unknown, a cell of those columns is not a finite
        number (the message names the line and the column), fewer than 15 samples, or
        abscissae that do not increase (naming the line).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "x.csv"
    >>> _ = f.write_text("t [s],x [mm]\\n" + "".join(f"{0.1 * k},{k * k}\\n" for k in range(20)))
    >>> c = kl.io.read_curve(f)
    >>> c.x_name, c.y_unit, c.y[:3]
    ('t', 'mm', array([0., 1., 4.]))
    """
    path = file_path(path)
    x, y = _choice(x, "x"), _choice(y, "y")
    source = str(path)
    try:
        size = path.stat().st_size
    except OSError:
        size = 0
    # text, rows of Python strings and the arrays: about 20 times the file's size
    require(20.0 * size, f"reading {path.name}", "cut the file into pieces")
    text = read_text(path, max_bytes=None)      # bounded by the memory budget above
    rows = [(line_no, row) for line_no, row in enumerate(csv.reader(text.splitlines()), 1)
            if row and any(c.strip() for c in row) and not row[0].lstrip().startswith("#")]
    if not rows:
        raise ModelError("expected a header row and samples, got an empty file", source=source)
    header_line, header = rows[0]
    if all(_number(c) is not None for c in header):
        raise ModelError(f"line {header_line}: expected a header row naming the columns "
                         "(such as 't [s], x [mm]'), got numbers; add one", source=source)
    if len(header) < 2:
        raise ModelError(f"line {header_line}: expected at least two columns (the abscissa and "
                         f"the curve), got {len(header)}", source=source)
    ix = _column(header, x, 0, "x", source)
    iy = _column(header, y, 1 if ix != 1 else 0, "y", source)
    if ix == iy:
        raise ModelError(f"y: expected a column other than the abscissa's, got "
                         f"{shown(header[iy].strip())} for both", source=source)
    names = [header[ix].strip(), header[iy].strip()]
    problems, values = [], []
    for line_no, row in rows[1:]:
        pair = []
        for k, name in zip((ix, iy), names):
            cell = row[k].strip() if k < len(row) else ""
            v = _number(cell)
            if v is None or not math.isfinite(v):
                problems.append(f"line {line_no}, column {shown(name)}: expected a finite number, "
                                f"got {describe(cell) if cell else 'nothing'}; remove or fill in "
                                "that sample")
            pair.append(v)
        values.append(pair)
    if problems:
        raise ModelError(problems, source=source)
    if len(values) < MIN_SAMPLES:
        raise ModelError(f"expected at least {MIN_SAMPLES} samples, got {len(values)}; a "
                         "derivative of measured data needs several local fits", source=source)
    data = np.array(values, dtype=float)
    step = np.diff(data[:, 0])
    bad = np.flatnonzero(step <= 0)
    if bad.size:
        k = int(bad[0]) + 1
        raise ModelError(f"line {rows[k + 1][0]}, column {shown(names[0])}: expected abscissae "
                         f"that increase, got {data[k, 0]:.10g} after {data[k - 1, 0]:.10g}; sort "
                         "the rows and merge repeated ones", source=source)

    def split(name):
        m = _UNIT.match(name)
        return (m.group(1), m.group(2).strip()) if m else (name, "")
    (xn, xu), (yn, yu) = split(names[0]), split(names[1])
    return MeasuredCurve(data[:, 0].copy(), data[:, 1].copy(), xn, yn, xu, yu, source)
