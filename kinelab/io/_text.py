"""Untrusted files to plain data: reading the text, parsing TOML or JSON, and refusing what
no model, task or drawing file holds, each as one :class:`ModelError` that names the place.

Every file kinelab reads (model files, synthesis tasks, linkage2d drawings, Pyslvs
expressions) comes through here, so that they all refuse the same things the same way:
text that is not UTF-8, syntax errors (with line and column), whole numbers longer than
Python turns into numbers (``sys.get_int_max_str_digits()``), nesting deeper than
``MAX_DEPTH``, a key given twice in a JSON object, and lone UTF-16 surrogates (a JSON
``"\\ud800"``), which are not text and cannot be written back.
"""
from __future__ import annotations

import json
import math
import os
import re
import sys
import tomllib
from decimal import Decimal, localcontext
from fractions import Fraction
from typing import Any

from kinelab._files import file_path, read_file
from kinelab.errors import ModelError, describe, shown, shown_key

__all__ = ["MAX_DEPTH", "MAX_BYTES", "NUMBER", "number", "read_text", "loads", "Written", "written",
           "in_si"]

DIGITS_READ = 100  # characters of a number converted from its digits; a longer one (a file's
                   # stray thousands of zeros) is read as the float nearest it
MAX_DEPTH = 32     # tables and lists inside each other; a model file needs about 6
MAX_BYTES = 8 << 20  # a file's size: a model, task or drawing is a few kilobytes, and a TOML
                     # parser reads about a megabyte in a few seconds
_MODEL_NOTE = " (a model, task or drawing file is a few kilobytes)"
_SURROGATE = re.compile("[\ud800-\udfff]")

# What a number is, wherever a person writes one (a model or task file, a CSV cell, --at):
# ASCII digits in decimal or scientific notation, with a sign.  Not 1_000, 0x10, inf or nan
# (Python's float() reads them all), nor digits of other scripts ('１２', '١٢').
NUMBER = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
_NUMBER = re.compile(NUMBER)
PLAIN_NUMBER = "decimal or scientific notation in ASCII digits (1000, -0.5, 1.5e3)"


def number(text: str) -> float | None:
    """The number ``text`` writes (spaces and tabs around it allowed) by :data:`NUMBER`, as a
    float (inf beyond the floats); None when it is not one.

    Examples
    --------
    >>> number(" 1.5e3"), number("1_000"), number("\uff11\uff12"), number("nan")
    (1500.0, None, None, None)
    """
    text = text.strip(" \t")
    return float(text) if _NUMBER.fullmatch(text) else None


def read_text(path: str | os.PathLike, *, max_bytes: int = MAX_BYTES,
              note: str = _MODEL_NOTE) -> str:
    """The UTF-8 text of a regular file (a byte-order mark is allowed), refused beyond
    ``max_bytes`` (:func:`kinelab._files.read_file`; ``note`` ends that refusal)."""
    path = file_path(path)
    raw = read_file(path, max_bytes, note=note)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[:exc.start].count(b"\n") + 1
        raise ModelError(f"line {line}: not UTF-8 text; save the file as UTF-8",
                         source=path.name) from None


class Written(float):
    """A number as a file writes it: its float value, and ``text``, the digits themselves.

    A value in a file's unit (mm, in, deg) converts to SI with one rounding, from the
    digits (:func:`in_si`), not from the float nearest them (two roundings); and a value
    written with :func:`written` reads back as exactly the float it was written from.  No
    float in mm times 0.001 can be every float in m: the digits can.
    """

    __slots__ = ("text",)

    def __new__(cls, text: str):
        self = super().__new__(cls, text)
        self.text = text
        return self

    def __reduce__(self):
        return Written, (self.text,)


def in_si(value: int | float, scale: float) -> float:
    """``value`` (a file's number) times ``scale`` (the unit's factor to SI, a float), rounded
    once: the float nearest the product of the digits written and the factor; inf when it is
    beyond the floats."""
    if scale == 1.0 or not math.isfinite(value) or value == 0:
        return float(value) * scale
    # the digits written; a float given as a number stands for the digits it prints as
    text = value.text if isinstance(value, Written) else repr(float(value))
    if len(text) > DIGITS_READ:         # far beyond a float's precision: the float nearest
        text = repr(float(value))       # them (Python turns no more than 4300 into a number)
    exact = Fraction(text) if isinstance(value, float) else Fraction(value)
    try:
        return float(exact * Fraction(scale))
    except OverflowError:
        return math.copysign(math.inf, value)


def written(v: float, scale: float) -> float:
    """``v`` (SI) in a file's unit of ``scale``: the shortest digits that :func:`in_si` reads
    back as ``v`` exactly (a :class:`Written`; ``v`` itself in SI)."""
    if scale == 1.0 or not math.isfinite(v) or v == 0:
        return v / scale if scale != 1.0 else v
    target = Fraction(v) / Fraction(scale)
    factor = Fraction(scale)
    # 17 significant digits always do (an error below half a unit of the float's last place)
    for digits in range(1, 40):
        with localcontext() as ctx:
            ctx.prec = digits
            d = Decimal(target.numerator) / Decimal(target.denominator)
        if float(Fraction(d) * factor) == v:
            break
    shortest = repr(float(d))
    if float(Fraction(shortest) * factor) == v:
        # the digits a float prints as, where they do: a JSON reader, the browser, or a
        # caller's dict gives back those same digits
        return Written(shortest)
    a = abs(d)
    text = format(d, "f") if Decimal("1e-4") <= a < Decimal("1e16") else format(d, "e")
    if "." not in text and "e" not in text:
        text += ".0"
    return Written(text)


class _Twice(dict):
    """A JSON object that had a key more than once (the first such key kept)."""
    twice: str


def _object(pairs: list[tuple[str, Any]]) -> dict:
    out = dict(pairs)
    if len(out) == len(pairs):
        return out
    seen: set[str] = set()
    out = _Twice(pairs)
    out.twice = next(k for k, _ in pairs if k in seen or seen.add(k))
    return out


def loads(text: str, language: str, *, source: str | None = None) -> Any:
    """Plain data from ``text`` in ``language`` ("TOML" or "JSON"); see the module."""
    if not isinstance(text, str):
        hint = "; decode it first (text.decode())" if isinstance(text, (bytes, bytearray)) else ""
        raise ModelError(f"text: expected the {language} text itself (a str), got "
                         f"{describe(text)}{hint}; to read a file, use its path", source=source)
    if not text.strip():
        raise ModelError(f"expected {language} text, got {'an empty text' if not text else 'blank text'}"
                         , source=source)
    try:
        # numbers keep their digits (Written): a unit's conversion reads them exactly
        if language == "TOML":
            data = tomllib.loads(text, parse_float=Written)
        else:
            data = json.loads(text, object_pairs_hook=_object, parse_float=Written)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(_toml_syntax(str(exc), text), source=source) from None
    except json.JSONDecodeError as exc:
        raise ModelError(f"line {exc.lineno}, column {exc.colno}: JSON syntax error: {exc.msg}; "
                         "fix the syntax there", source=source) from None
    except RecursionError:
        raise ModelError(f"nested more than {MAX_DEPTH} deep; no file kinelab reads needs "
                         "that many levels", source=source) from None
    except ValueError:         # a whole number too long for int(): the only other failure
        raise ModelError(_long_number(text), source=source) from None
    if language == "TOML" and (why := _toml_number(text)):
        raise ModelError(why, source=source)
    _check(data, source)
    return data


# TOML's numbers beyond NUMBER, which tomllib reads (JSON's grammar has none of them)
_TOML_OTHER = re.compile(r"[0-9]_|0[xob]")
_TOML_TOKEN = re.compile(r"""
    (?P<string>"{3}(?:[^\\]|\\.)*?"{3,5}|'{3}[\s\S]*?'{3,5}|"(?:[^"\\\n]|\\.)*"|'[^'\n]*')
  | (?P<comment>\#[^\n]*)
  | (?P<bare>[A-Za-z0-9_+.:-]+)
  | (?P<mark>[\[\]{}=,\n])
  | [ \t\r]+
""", re.X)
_DATE_OR_TIME = re.compile(r"[0-9]{4}-[0-9]{2}-[0-9]{2}|.*:")


def _toml_number(text: str) -> str | None:
    """Where valid TOML ``text`` writes a number otherwise than :data:`NUMBER` does
    (``1_000``, ``0x3e8``, ``0o17``, ``0b101``), as a message; None when it does not.

    Keys may hold the same characters (``x_1 = 2``): only values are looked at, told from
    keys by where they stand (after ``=``, in an array)."""
    if not _TOML_OTHER.search(text):
        return None
    stack: list[str] = []        # the arrays ('[') and inline tables ('{') the place is in
    value = False                # a value is next (else a key, or a table's header)
    for m in _TOML_TOKEN.finditer(text):
        kind, token = m.lastgroup, m.group()
        if kind == "mark":
            if token == "=":
                value = True
            elif token == "\n" and not stack:
                value = False
            elif not value:
                continue         # a table's header [a.b], [[a]]
            elif token in "[{":
                stack.append(token)
                value = token == "["
            elif token in "]}" and stack:
                stack.pop()
                value = True
            elif token == ",":
                value = not stack or stack[-1] == "["
        elif kind == "bare" and value and token.lstrip("+-")[:1].isdigit() \
                and not _NUMBER.fullmatch(token) and not _DATE_OR_TIME.match(token):
            line = text.count("\n", 0, m.start()) + 1
            column = m.start() - text.rfind("\n", 0, m.start())
            return (f"line {line}, column {column}: expected a number in {PLAIN_NUMBER}, got "
                    f"{shown(token)}; write it in plain digits")
    return None


def _long_number(text: str) -> str:
    limit = sys.get_int_max_str_digits()
    match = re.search(r"\d[\d_]{%d,}" % limit, text)
    where = ""
    if match:
        line = text.count("\n", 0, match.start()) + 1
        where = f"line {line}, column {match.start() - text.rfind(chr(10), 0, match.start())}: "
    return (f"{where}a number of more than {limit} digits; no value needs so many, "
            "write it with an exponent (1.5e3) or fix it")


def _toml_syntax(message: str, text: str) -> str:
    match = re.match(r"^(.*) \(at (?:line (\d+), column (\d+)|end of document)\)$", message, re.S)
    what = match.group(1) if match else message
    if match and match.group(2):
        where = f"line {match.group(2)}, column {match.group(3)}"
    else:
        where = f"line {text.count(chr(10)) + 1} (end of file)"
    what = what[:1].lower() + what[1:]
    return f"{where}: TOML syntax error: {what}; fix the syntax there"


def _check(data: Any, source: str | None) -> None:
    """Refuse deep nesting, repeated keys and surrogates: one pass, without recursion."""
    todo: list[tuple[Any, str, int]] = [(data, "", 0)]
    while todo:
        value, where, depth = todo.pop()
        if isinstance(value, str):
            if _SURROGATE.search(value):
                raise ModelError(f"{where or 'the file'}: a lone UTF-16 surrogate in "
                                 f"{shown(value)}, which is not text; fix the escape "
                                 "(\\ud800 ... \\udfff) there", source=source)
            continue
        if not isinstance(value, (dict, list)):
            continue
        if depth >= MAX_DEPTH:
            raise ModelError(f"{where or 'the file'}: nested more than {MAX_DEPTH} deep; no "
                             "file kinelab reads needs that many levels", source=source)
        if isinstance(value, _Twice):
            at = f"{where}." if where else ""
            raise ModelError(f"{at}{shown_key(value.twice)}: given twice in the same table; keep "
                             "one", source=source)
        if isinstance(value, dict):
            for k, v in value.items():
                if _SURROGATE.search(k):
                    raise ModelError(f"{where or 'the file'}: a lone UTF-16 surrogate in the "
                                     f"key {shown(k)}, which is not text; fix it", source=source)
                todo.append((v, f"{where}.{shown_key(k)}" if where else shown_key(k), depth + 1))
        else:
            todo.extend((v, f"{where}[{i}]", depth + 1) for i, v in enumerate(value))
