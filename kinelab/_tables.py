"""Tables as text, a block of rows at a time: the CSV rows and the JSON row objects that
kinelab writes, column by column rather than value by value.

Every number is written as Python writes it (``repr``: the shortest text that reads back
as the same float), so the files are those ``csv.writer`` and ``json.dumps`` write, made a
third faster (CSV) and nearly twice as fast (JSON): the text of a column is made in one
pass, and each row is put together by one ``join`` or one ``%`` (no dictionary per row).
That text is most of the time left: about a microsecond a number on a slow machine.
"""
from __future__ import annotations

import json
from collections.abc import Iterator, Mapping

import numpy as np

__all__ = ["csv_blocks", "json_blocks", "BLOCK_VALUES"]

BLOCK_VALUES = 1 << 18
"""Values formatted at a time: a block's text, as Python strings of about 80 bytes a value,
is some 20 MB at most."""


def _rows_per_block(width: int) -> int:
    return max(1, BLOCK_VALUES // max(width, 1))


def csv_blocks(data: np.ndarray) -> Iterator[str]:
    """The rows of a 2-D float array as CSV text (``csv.writer``'s: values as ``str`` of a
    float, rows ended by ``\\r\\n``), a block of rows at a time."""
    step = _rows_per_block(data.shape[1] if data.ndim == 2 else 0)
    for start in range(0, len(data), step):
        block = data[start:start + step]
        text = [list(map(float.__repr__, column.tolist())) for column in block.T]
        yield "".join(line + "\r\n" for line in map(",".join, zip(*text)))


def _json_values(column: np.ndarray) -> list[str]:
    """Each value of a column as JSON text: ``null`` where a number is not finite."""
    if column.dtype == bool:
        return ["true" if v else "false" for v in column.tolist()]
    if np.issubdtype(column.dtype, np.integer):
        return list(map(str, column.tolist()))
    column = column.astype(float)
    text = list(map(float.__repr__, column.tolist()))
    for i in np.flatnonzero(~np.isfinite(column)).tolist():
        text[i] = "null"
    return text


def json_blocks(columns: Mapping[str, np.ndarray]) -> Iterator[str]:
    """The JSON text of a list of row objects, one per sample, as ``json.dumps`` writes each
    row (``{"name": value, ...}``), two spaces before each and one row a line, a block of
    rows at a time; ``null`` where a value is not finite."""
    names = list(columns)
    data = [np.asarray(columns[n]) for n in names]
    n = len(data[0]) if data else 0
    row = "  {" + ", ".join(json.dumps(name).replace("%", "%%") + ": %s" for name in names) + "}"
    step = _rows_per_block(len(names))
    yield "[\n"
    for start in range(0, n, step):
        text = [_json_values(column[start:start + step]) for column in data]
        rows = [row % values for values in zip(*text)]
        yield ",\n".join(rows) + (",\n" if start + step < n else "\n")
    yield "]\n"
