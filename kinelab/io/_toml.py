"""A small TOML writer for model files.

The standard library reads TOML (``tomllib``) but does not write it.  Model files are
read by people, so this writer keeps short arrays on one line (``A = [0.03, 0.0]``) and
lays tables out in the order they are given; it handles what model files contain:
text, booleans, numbers, arrays of those, tables, tables of tables and arrays of tables.
"""
from __future__ import annotations

import json
import math
import numbers
import re
from collections.abc import Mapping
from typing import Any

__all__ = ["dumps", "Inline"]

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


class Inline(dict):
    """A table written on one line, as a value (``P = {A = 30, B = 40, side = "left"}``),
    rather than under a header of its own."""


def toml_key(k: str) -> str:
    """A key as TOML writes it: bare when it can be, else quoted."""
    k = str(k)
    return k if _BARE_KEY.match(k) else json.dumps(k, ensure_ascii=False)


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        if not math.isfinite(v):
            raise ValueError(f"TOML model files hold finite numbers only, got {v}")
        # a value in the file's unit keeps the digits that read back as its SI value
        return getattr(v, "text", None) or repr(float(v))
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, Mapping):
        return "{" + ", ".join(f"{toml_key(k)} = {_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def _is_table_array(v: Any) -> bool:
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, Mapping) for x in v)


def _body(table: Mapping[str, Any], path: str, out: list[str]) -> None:
    """Key-value lines of ``table``, then its sub-tables and arrays of tables."""
    later = []
    for k, v in table.items():
        if (isinstance(v, Mapping) and not isinstance(v, Inline)) or _is_table_array(v):
            later.append((k, v))
        else:
            out.append(f"{toml_key(k)} = {_value(v)}")
    for k, v in later:
        name = f"{path}.{toml_key(k)}" if path else toml_key(k)
        if isinstance(v, Mapping):
            out.append("")
            out.append(f"[{name}]")
            _body(v, name, out)
        else:
            for item in v:
                out.append("")
                out.append(f"[[{name}]]")
                _body(item, name, out)


def dumps(data: Mapping[str, Any]) -> str:
    """TOML text of ``data``.

    Examples
    --------
    >>> print(dumps({"schema": 1, "points": {"A": [0.0, 1.5]}, "links": [{"name": "arm"}]}))
    schema = 1
    <BLANKLINE>
    [points]
    A = [0.0, 1.5]
    <BLANKLINE>
    [[links]]
    name = "arm"
    <BLANKLINE>
    """
    out: list[str] = []
    _body(data, "", out)
    return "\n".join(out) + "\n"
