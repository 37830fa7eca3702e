"""CSV tables in: a header row naming the columns, then rows of numbers, read strictly.

Every CSV file kinelab reads (a measured curve for ``differentiate``, a path for ``atlas
find``, a table of designs for ``sweep`` and ``atlas build``) comes through :func:`csv_rows`,
so that they all take and refuse the same things:

- lines end in LF, CR LF or CR alone (old spreadsheets on the Mac write CR alone): each ends
  a line, and each line is at most one row;
- blank lines (spaces, tabs and commas only) and lines whose first character that is not a
  space or a tab is ``#`` are skipped;
- a field may be quoted whole (``"t [s]"``, ``"1.5"``); a quote that does not close on its
  line (a stray quote, or a line break inside quotes) or one inside an unquoted field is
  refused with its line;
- a column's name is printable, holds no quote, is at most ``MAX_NAME`` characters long and
  is not given twice;
- a number is written as :data:`kinelab.io._text.NUMBER` says;
- the file is at most ``TABLE_BYTES``, a line at most ``MAX_LINE`` characters, and rows are
  counted as they are parsed, so a file of more than ``MAX_ROWS`` rows is refused on its row
  ``MAX_ROWS + 1``.
"""
from __future__ import annotations

import csv
import os
import re
from array import array
from collections.abc import Iterator

import numpy as np

from kinelab._files import file_path
from kinelab._memory import require
from kinelab.errors import PROBLEMS_SHOWN, ModelError, describe, shown
from kinelab.io._text import PLAIN_NUMBER, number, read_text
from kinelab.model import MAX_NAME   # a column is named as a point or link is

__all__ = ["TABLE_BYTES", "MAX_ROWS", "csv_rows", "header", "numbers_of", "read_table"]

TABLE_BYTES = 64 << 20   # a CSV file's size: a million rows of a few numbers each
MAX_ROWS = 1_000_000     # rows of a CSV file (besides its header): a curve's samples, a
                         # path's points, designs (more designs: a Parquet table)
MAX_LINE = 1 << 20       # characters of a line: a row of a few thousand numbers

_LINE_ENDS = re.compile(r"\r\n?")
# a line to parse: not blank (spaces, tabs, commas), not a comment (# first)
_ROW = re.compile(r"^(?![ \t]*#)(?=[^\n]*[^ \t,\n])[^\n]*", re.M)


def csv_rows(text: str, source: str, *, max_rows: int = MAX_ROWS, what: str = "rows",
             instead: str = "cut the file into pieces") -> Iterator[tuple[int, list[str]]]:
    """``(line number, cells)`` of each row of CSV ``text``, the header first (see the
    module); every refusal a :class:`ModelError` naming ``source`` and the line.  More than
    ``max_rows`` rows after the header are refused, naming them ``what`` and saying what to
    do ``instead``."""
    if "\r" in text:
        text = _LINE_ENDS.sub("\n", text)
    line, at, rows = 1, 0, -1
    for match in _ROW.finditer(text):
        line += text.count("\n", at, match.start())
        at = match.start()
        rows += 1
        if match.end() - match.start() > MAX_LINE:
            raise ModelError(f"line {line}: expected at most {MAX_LINE:,} characters on a line, "
                             "got more; is it a CSV table?", source=source)
        if rows > max_rows:
            raise ModelError(f"line {line}: expected at most {max_rows:,} {what}, got more; "
                             f"{instead}", source=source)
        cells = _cells(match.group(), line, source)
        if any(c.strip(" \t") for c in cells):        # else a row of empty fields: skipped
            yield line, cells


def _cells(text: str, line: int, source: str) -> list[str]:
    if '"' not in text:            # no quoting: the fields between the commas
        return text.split(",")
    try:
        cells = next(csv.reader((text,), strict=True))
    except csv.Error as exc:
        why = ("a quoted field that does not end on its line (a stray quote, or a line break "
               "inside quotes)" if "end of data" in str(exc) else
               "a quoted field with more after its closing quote" if "expected after" in str(exc)
               else str(exc))
        raise ModelError(f"line {line}: {why}; quote a whole field on one line (\"t [s]\") or "
                         "remove the quote", source=source) from None
    return cells


def header(row: tuple[int, list[str]], source: str) -> list[str]:
    """A header row's names, stripped of spaces: refused when it holds numbers only (no
    header), or a name is unprintable, holds a quote or is given twice (a column may have
    no name: it is then known by its number alone)."""
    line, cells = row
    names = [c.strip(" \t") for c in cells]
    if all(number(c) is not None for c in names):
        raise ModelError(f"line {line}: expected a header row naming the columns (such as "
                         "'t [s], x [mm]'), got numbers; add one", source=source)
    seen: dict[str, int] = {}
    for k, name in enumerate(names):
        bad = next((c for c in name if not c.isprintable()), None)
        if bad is not None:
            raise ModelError(f"header: column {shown(name)}: expected printable characters in a "
                             f"column's name and unit, got {shown(bad)}; remove it",
                             source=source)
        if len(name) > MAX_NAME:
            raise ModelError(f"header: column {shown(name)}: expected a name and unit of at most "
                             f"{MAX_NAME} characters, got {len(name):,}; shorten it", source=source)
        if '"' in name:
            raise ModelError(f"header: column {shown(name)}: a stray quote; quote a whole field "
                             "(\"t [s]\") or remove the quote", source=source)
        if name and name in seen:
            raise ModelError(f"header: column {k + 1}: the name {shown(name)} is already column "
                             f"{seen[name] + 1}'s; name each column once", source=source)
        seen[name] = k
    return names


def _cell_problem(cell: str, line: int, name: str) -> str:
    got = describe(cell) if cell else "nothing"
    if '"' in cell:
        got += " (a stray quote: CSV quotes a whole field)"
    return (f"line {line}, column {shown(name)}: expected a finite number, got {got}; write "
            f"it in {PLAIN_NUMBER}, or remove the row")


def numbers_of(rows: Iterator[tuple[int, list[str]]], picked: list[int], names: list[str],
               source: str, *, whole: bool = False,
               missing: float | None = None) -> tuple[array, np.ndarray]:
    """The line numbers of the rows after the header, and the numbers in their columns
    ``picked`` (named ``names`` in messages), shape (rows, len(picked)).

    Every cell that is not a finite number is a problem naming its line and column (the
    first ones are written out, the rest counted), but an empty one when ``missing`` is
    given (it is then that value); ``whole``: a row has no non-empty cell beyond the
    header's columns either.
    """
    lines, values = array("q"), array("d")
    problems: list[str] = []
    more = 0
    for line, cells in rows:
        if whole and any(c.strip(" \t") for c in cells[len(names):]):
            raise ModelError(f"line {line}: expected {len(names)} cells (one per column of the "
                             f"header), got {len(cells)}; remove the extra ones", source=source)
        for k, name in zip(picked, names):
            cell = cells[k].strip(" \t") if k < len(cells) else ""
            v = number(cell) if cell or missing is None else missing
            if v is None or not (np.isfinite(v) or not cell):
                v = 0.0
                if len(problems) < PROBLEMS_SHOWN - 1:
                    problems.append(_cell_problem(cell, line, name))
                else:
                    more += 1
            values.append(v)
        lines.append(line)
    if problems:
        if more:
            problems.append(f"and {more:,} more cells that are not finite numbers")
        raise ModelError(problems, source=source)
    return lines, np.frombuffer(values, dtype=float).reshape(-1, len(picked)).copy()


def read_table(path: str | os.PathLike, *, what: str = "rows",
               missing: float | None = None) -> tuple[list[str], np.ndarray]:
    """A CSV table of numbers: its column names and its values, shape (rows, columns).

    Every column is named, and every cell is a finite number, or empty when ``missing`` is
    given (the value it then stands for, such as NaN); see the module for the rest.
    """
    path = file_path(path)
    source = str(path)
    text = read_text(path, max_bytes=TABLE_BYTES, note=f" ({MAX_ROWS:,} {what} at most)")
    rows = csv_rows(text, source, max_rows=MAX_ROWS, what=what)
    first = next(rows, None)
    if first is None:
        raise ModelError(f"expected a header row naming the columns and {what}, got an empty "
                         "file", source=source)
    names = header(first, source)
    if "" in names:
        raise ModelError(f"line {first[0]}, column {names.index('') + 1}: expected a column's "
                         "name, got nothing; name every column", source=source)
    # the text, already read, and the values (8 bytes each)
    require(16.0 * len(text), "reading it", "cut the file into pieces", source=source)
    return names, numbers_of(rows, list(range(len(names))), names, source, whole=True,
                             missing=missing)[1]
