"""Measured curves in: a CSV table of an abscissa (time, or an input angle) and a
displacement, for :func:`kinelab.solvers.differentiate`."""
from __future__ import annotations

import numbers
import os
from dataclasses import dataclass

import numpy as np

from kinelab._files import file_path
from kinelab._memory import require
from kinelab.errors import ModelError, describe, quoted, shown
from kinelab.io._csv import TABLE_BYTES, csv_rows, numbers_of
from kinelab.io._csv import header as header_names
from kinelab.io._text import read_text
from kinelab.solvers._differentiate import MAX_SAMPLES, MIN_SAMPLES

__all__ = ["MeasuredCurve", "read_curve"]


def _split(name: str) -> tuple[str, str]:
    """A column's name and unit: "t [s]" is ("t", "s"), "t" is ("t", "")."""
    at = name.find("[")
    if at < 0 or not name.endswith("]"):
        return name, ""
    return name[:at].strip(), name[at + 1:-1].strip()


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
    names = [_split(h)[0] for h in header]
    for k, (full, bare) in enumerate(zip(header, names)):
        if choice in (full, bare):
            return k
    digits = choice if isinstance(choice, int) else choice.strip()
    number = (digits if isinstance(digits, int) else
              int(digits) if digits.isascii() and digits.isdigit() and len(digits) < 10 else 0)
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
    text = read_text(path, max_bytes=TABLE_BYTES, note=f" ({MAX_SAMPLES:,} samples at most)")
    rows = csv_rows(text, source, max_rows=MAX_SAMPLES, what="samples",
                    instead="cut the curve into pieces, or keep every k-th sample")
    first = next(rows, None)
    if first is None:
        raise ModelError("expected a header row and samples, got an empty file", source=source)
    header_line, header = first[0], header_names(first, source)
    if len(header) < 2:
        raise ModelError(f"line {header_line}: expected at least two columns (the abscissa and "
                         f"the curve), got {len(header)}", source=source)
    ix = _column(header, x, 0, "x", source)
    iy = _column(header, y, 1 if ix != 1 else 0, "y", source)
    if ix == iy:
        raise ModelError(f"y: expected a column other than the abscissa's, got "
                         f"{shown(header[iy])} for both", source=source)
    names = [header[ix] or f"column {ix + 1}", header[iy] or f"column {iy + 1}"]
    # the text, already read, and the values (16 bytes a sample) with their lines
    require(8.0 * len(text), "reading it", "cut the file into pieces", source=source)
    lines, data = numbers_of(rows, [ix, iy], names, source)
    if len(lines) < MIN_SAMPLES:
        raise ModelError(f"expected at least {MIN_SAMPLES} samples, got {len(lines)}; a "
                         "derivative of measured data needs several local fits", source=source)
    step = np.diff(data[:, 0])
    bad = np.flatnonzero(step <= 0)
    if bad.size:
        k = int(bad[0]) + 1
        raise ModelError(f"line {lines[k]}, column {shown(names[0])}: expected abscissae "
                         f"that increase, got {data[k, 0]:.10g} after {data[k - 1, 0]:.10g}; sort "
                         "the rows and merge repeated ones", source=source)
    (xn, xu), (yn, yu) = _split(header[ix]), _split(header[iy])
    return MeasuredCurve(data[:, 0].copy(), data[:, 1].copy(), xn, yn, xu, yu, source)
