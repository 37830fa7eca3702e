"""A grammar-aware generator of hostile input files for kinelab's command line.

Valid files (the bundled examples, catalogue short forms, dynamics sections and synthesis
task files) are mutated field by field: a value replaced by another of the kinds a file can
hold (numbers at the edges of float64, huge integers, wrong types, text with control
characters, surrogates or escapes, very long text, deep nesting, very long lists), a field
removed, an unknown field added, an entry duplicated or a name reused; then written as TOML
or JSON, sometimes with a duplicated key or a few corrupted bytes.  Each case says which
command reads it.

The property the tests and ``benchmarks/fuzz_model_files.py`` check: the command succeeds
or ends with one line on standard error and exit status 2, within a time and memory bound.
"""
from __future__ import annotations

import copy
import io
import json
import logging
import math
import os
import random
import resource
import sys
import threading
import tomllib
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

CATALOGUE = {
    "fourbar": {"ground": 300, "crank": 100, "coupler": 300, "rocker": 250},
    "slider_crank": {"crank": 50, "rod": 180, "offset": 10},
    "fivebar": {"ground": 100, "crank1": 40, "coupler1": 100, "coupler2": 100, "crank2": 40},
    "watt6": {"lengths": {"O2-A": 0.5}, "branch": ["open", "open"]},
    "triad6": {},
    "whitworth": {"crank": 100, "distance": 50, "lever": 100, "rod": 200},
}

TASKS = [
    {"task": "motion", "units": {"length": "cm", "angle": "deg"},
     "positions": {"points": [[0, 0], [5, 8], [10, 15], [18, 20]], "angles": [10, 20, 30]},
     "pivots": {"a0x": -20.195, "b0x": -29.167}},
    {"task": "motion", "positions": {"points": [[1, 1], [2, 0.5], [3, 1.5]],
                                     "angles": [0, 0, 0.7853981633974483]},
     "pivots": {"A0": [5, 0], "B0": [0, 0]}},
]

BIG = "__5000_digits__"      # written as a 5000-digit integer literal (Python itself refuses to
                             # turn such an int into text by default)
EDGE_NUMBERS = [0, -0.0, 1, -1, 0.5, 1e-308, 5e-324, -5e-324, 1e308, -1e308, 1.7976931348623157e308,
                2.2250738585072014e-308, 1e300, 3e300, 1e-300, 1e16, 9007199254740993,
                10 ** 30, -(10 ** 30), 10 ** 400, BIG, 360, 720, 1e6, 1e12]
NON_FINITE = [math.inf, -math.inf, math.nan]
TEXTS = ["", " ", "a\nb", "tab\there", "\x00", "\x1b[31mred\x1b[0m", "é", "名前", "🙂", "\u202e", "'\"",
         "${HOME}", "$(rm -rf /)", "__import__('os').system('true')", "a" * 100_000,
         "../../etc/passwd", "NaN", "inf", "1e999", "true", "O2", "jO2", "ground"]
LAWS = ["1/0", "10**400", "9**9**9", "+".join(["1"] * 900), "t" * 3, "sin(" * 300 + "t" + ")" * 300,
        "__import__('os')", "q[0]**0.5", "log(0)", "exp(1000)", "1e308*10", "(" * 500 + "1" + ")" * 500]


@dataclass(frozen=True)
class Case:
    """A file to run: its text (or bytes), its suffix and the command line reading it."""

    text: str | bytes
    suffix: str
    command: tuple[str, ...]           # e.g. ("check",): the file's path comes after, or
                                       # where "{file}" stands ("{out}": an output directory;
                                       # "{atlas}", "{path}": a valid atlas, a valid path)
    family: str = "model"              # what the file is: model, task, curve, designs, path,
                                       # atlas; web (a request: text is its body, command its
                                       # method, path and media type); names
    stem: str = "case"                 # the file's name, but its suffix

    def args(self, file: str, **places: str) -> list[str]:
        if "{file}" not in self.command:
            return [self.command[0], file, *self.command[1:]]
        return [a.format(file=file, **places) for a in self.command]


def bases() -> list[tuple[dict, tuple[str, ...]]]:
    """Valid inputs, each with the command that reads it."""
    out = []
    for path in sorted((ROOT / "examples").glob("*.toml")):
        data = tomllib.loads(path.read_text())
        out.append((data, ("check",)))
        if "dynamics" in data:
            out.append((data, ("dynamics", "--no-plots", "--samples", "19")))
    for kind, params in CATALOGUE.items():
        data = {"schema": 1, "name": kind, "units": {"length": "mm", "angle": "deg"},
                "catalogue": {"kind": kind, **params},
                "inputs": [{"joint": "jO2", "speed": 60}]}
        if kind == "fivebar":
            data["inputs"] = [{"joint": "jO2", "range": [0, 90], "speed": 1},
                              {"joint": "jO4", "range": [90, 180], "speed": 1}]
        out.append((data, ("check",)))
    for task in TASKS:
        out.append((task, ("synth", "--no-figures")))
    return out


def _paths(data, prefix=()):
    """Every path into nested dicts and lists (a path is a tuple of keys and indices), down
    to 20 levels (a deeply nested value is one thing to replace, not a place to dig)."""
    yield prefix
    if len(prefix) >= 20:
        return
    if isinstance(data, dict):
        for k, v in data.items():
            yield from _paths(v, prefix + (k,))
    elif isinstance(data, list):
        for i, v in enumerate(data):
            yield from _paths(v, prefix + (i,))


def _get(data, path):
    for key in path:
        data = data[key]
    return data


def _nested(depth: int):
    v: object = 1
    for _ in range(depth):
        v = [v]
    return v


def _value(rng: random.Random, old):
    """A value of another kind, or an edge of the same kind, for a field that held ``old``."""
    kinds = ["number", "number", "text", "bool", "list", "table", "nested", "none"]
    if isinstance(old, str):
        kinds += ["text", "text", "law"]
    kind = rng.choice(kinds)
    if kind == "number":
        v = rng.choice(EDGE_NUMBERS + NON_FINITE)
        return -v if rng.random() < 0.2 and isinstance(v, (int, float)) else v   # (BIG stays)
    if kind == "text":
        return rng.choice(TEXTS)
    if kind == "law":
        return rng.choice(LAWS)
    if kind == "bool":
        return rng.choice([True, False])
    if kind == "list":
        n = rng.choice([0, 1, 2, 3, 10_000])
        item = rng.choice([0, 1.5, "A", [0, 0]])
        return [copy.deepcopy(item) for _ in range(n)]
    if kind == "table":
        return {rng.choice(TEXTS[:12]) or "k": rng.choice(EDGE_NUMBERS[:6])}
    if kind == "nested":
        return _nested(rng.choice([3, 50, 400]))
    return None


def mutate(data: dict, rng: random.Random, count: int) -> dict:
    """``count`` field-level mutations of a copy of ``data`` (a deeply nested value, once
    made, is not copied again: it is only ever replaced)."""
    data = copy.deepcopy(data)
    for _ in range(count):
        paths = [p for p in _paths(data) if p]
        if not paths:
            break
        path = rng.choice(paths)
        parent = _get(data, path[:-1])
        key = path[-1]
        op = rng.random()
        if op < 0.55:
            parent[key] = _value(rng, parent[key])
        elif op < 0.65:
            del parent[key]
        elif op < 0.75 and isinstance(parent, dict):
            parent[rng.choice(["extra", "nme", "lenght", "points ", "\u00e9", "a.b"])] = rng.choice(
                EDGE_NUMBERS[:5])
        elif op < 0.85 and isinstance(parent, list):
            parent.append(parent[key])                          # a duplicated entry
        elif op < 0.92 and isinstance(parent[key], dict) and "name" in parent[key]:
            parent[key]["name"] = rng.choice(["ground", "O2", "A", "jO2", "crank", "x" * 300,
                                              "new\nline"])      # a reused or odd name
        else:
            parent[key] = _value(rng, parent[key])
    return data


def _toml_value(v) -> str:
    if v == BIG:
        return "9" * 5000
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(str(k))} = {_toml_value(x)}" for k, x in v.items()
                               if x is not None) + "}"
    return '""'


def to_toml(data: dict) -> str:
    """TOML for the mutated data: top-level scalars, then tables and arrays of tables, with
    inline tables below (None values are left out: TOML has no null)."""
    lines, tables = [], []
    for k, v in data.items():
        if v is None:
            continue
        key = json.dumps(str(k))
        if isinstance(v, dict):
            tables.append(f"[{key}]\n" + "".join(f"{json.dumps(str(a))} = {_toml_value(b)}\n"
                                                 for a, b in v.items() if b is not None))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for x in v:
                tables.append(f"[[{key}]]\n" + "".join(f"{json.dumps(str(a))} = {_toml_value(b)}\n"
                                                       for a, b in x.items() if b is not None))
        else:
            lines.append(f"{key} = {_toml_value(v)}")
    return "\n".join(lines) + "\n\n" + "\n".join(tables)


def _json(data) -> str:
    return json.dumps(data, ensure_ascii=True, allow_nan=True, default=str).replace(
        json.dumps(BIG), "9" * 5000)


def render(data: dict, rng: random.Random) -> tuple[str | bytes, str]:
    """(text, suffix): TOML or JSON, sometimes with a duplicated key, a lone surrogate or
    corrupted bytes."""
    fmt = rng.choice(["toml", "json"])
    try:
        text = to_toml(data) if fmt == "toml" else _json(data)
    except (ValueError, RecursionError):
        fmt, text = "json", _json({"schema": 1})
    r = rng.random()
    if r < 0.05 and fmt == "json":
        text = text.replace('"name": ', '"name": "dup", "name": ', 1)       # a duplicated key
    elif r < 0.08 and fmt == "json":
        text = text.replace('"name": "', '"name": "\\ud800', 1)              # a lone surrogate
    elif r < 0.12:
        raw = bytearray(text.encode("utf-8", "surrogatepass"))
        for _ in range(rng.randint(1, 4)):
            if raw:
                raw[rng.randrange(len(raw))] = rng.randrange(256)
        return bytes(raw), "." + fmt
    elif r < 0.14:
        text = text[:rng.randrange(max(len(text), 1))]                        # truncated
    return text, "." + fmt


def case(rng: random.Random) -> Case:
    """One hostile case."""
    data, command = rng.choice(bases())
    mutated = mutate(data, rng, rng.choice([1, 1, 2, 3, 5]))
    text, suffix = render(mutated, rng)
    return Case(text, suffix, command, "task" if command[0] == "synth" else "model")


# -- tasks of every kind -----------------------------------------------------------------------
# Tasks as the synthesis docs write them, with searches kept short (a search of days is the
# user's to ask for; a hostile file must not make one by accident too often)
MORE_TASKS = [
    *TASKS,
    {"task": "function", "units": {"angle": "deg"},
     "function": {"expression": "log10(x)", "x_range": [1, 2], "input_range": [90, 150],
                  "output_range": [0, 90], "points": 3, "ground": 1.0}},
    {"task": "path", "positions": {"points": [[0, 0], [0.25, 0.02], [0.5, 0.03], [0.75, 0.02],
                                              [1, 0]]},
     "search": {"runs": 1, "maxiter": 3, "popsize": 5, "samples": 24, "seed": 1}},
    {"task": "crank-rocker", "units": {"length": "mm", "angle": "deg"},
     "crank_rocker": {"ground": 100, "swing": 45, "time_ratio": 1.25}},
    {"task": "quick-return", "units": {"length": "mm"},
     "quick_return": {"mechanism": "offset slider-crank", "stroke": 100, "time_ratio": 1.4}},
    {"task": "quick-return", "units": {"length": "mm"},
     "quick_return": {"mechanism": "whitworth", "time_ratio": 1.5, "distance": 50, "stroke": 200}},
    {"task": "motion", "units": {"length": "cm", "angle": "deg"},
     "positions": {"points": [[10.2, 18.0], [12.6, 21.2], [13.3, 23.6], [12.1, 25.2], [9.7, 26.0],
                              [6.5, 25.9]], "angles": [56, 46, 38, 33, 30, 29]},
     "search": {"dyads": 4}},
]
_SYNTH = ("synth", "{file}", "--no-figures", "--out", "{out}/solutions")


def task_case(rng: random.Random) -> Case:
    """A task file of any kind, mutated field by field, as TOML (what synth reads)."""
    task = rng.choice(MORE_TASKS)
    mutated = mutate(task, rng, rng.choice([1, 1, 2, 3]))
    try:
        text: str | bytes = to_toml(mutated)
    except (ValueError, RecursionError):
        text = to_toml(task)
    text = _damaged(text, rng) if rng.random() < 0.1 else text
    return Case(text, ".toml", _SYNTH, "task")


# -- CSV tables: measured curves, designs, paths -------------------------------------------------
# what a cell may hold instead of a number
CELLS = ["1_000", "\uff11\uff12", "\u0661\u0662", "nan", "NaN", "inf", "-inf", "1e999", "1e-400",
         "0x10", "0b1", "", " ", "--1", "1e", ".", '"1.5"', '"1.5', '1"5', "9" * 5000, "-0", "+.5e-3",
         "1,5", "\x00", "1\t", "\u00a01", "\u2028", "1e+308", "-1.7976931348623157e308", "5e-324",
         "abc", "true", "'1'", "1.5\r2", "\ufeff1"]
NAMES = ["t", "x [mm]", "", " ", "a\x1bb", "\x00", "a\u2028b", "\u0085", 'a"b', '"a"', "#c",
         "x" * 100_000, "名前 [秒]", "t [s] [m]", "[", "]", "x,y", "1", "1e3", "\ufeffx"]


def _curve_text(rng: random.Random) -> str:
    n = rng.choice([15, 20, 40, 60])
    fmt = rng.choice(["{:.6g}", "{!r}", "{:.3e}"])
    header = rng.choice(["t [s],x [mm]", "t,x", "angle [deg],s [mm],extra", '"t [s]","x [mm]"'])
    width = header.count(",") + 1
    rows = []
    for k in range(n):
        t = 0.01 * k
        cells = [fmt.format(t), fmt.format(math.sin(10 * t) + 1e-3 * rng.random())]
        rows.append(",".join(cells + ["0"] * (width - 2)))
    return header + "\n" + "\n".join(rows) + "\n"


def _designs_text(rng: random.Random) -> str:
    header = "ground,crank,coupler,rocker,coupler_point_along,coupler_point_perpendicular"
    rows = [",".join(f"{v:.4g}" for v in (rng.uniform(1, 4), rng.uniform(0.3, 1),
                                         rng.uniform(1, 4), rng.uniform(1, 4),
                                         rng.uniform(-1, 2), rng.uniform(-1, 1)))
            for _ in range(rng.randint(1, 6))]
    return header + "\n" + "\n".join(rows) + "\n"


def _path_text(rng: random.Random) -> str:
    n = rng.choice([20, 40, 80])
    a, b = rng.uniform(0.5, 2), rng.uniform(0.5, 2)
    rows = [f"{a * math.cos(2 * math.pi * k / n):.6g},{b * math.sin(2 * math.pi * k / n):.6g}"
            for k in range(n)]
    return "x,y\n" + "\n".join(rows) + "\n"


def _csv_mutation(text: str, rng: random.Random) -> str:
    lines = text.split("\n")
    op = rng.randrange(14)
    k = rng.randrange(len(lines))
    if op == 0:                                     # a cell replaced
        cells = lines[k].split(",")
        cells[rng.randrange(len(cells))] = rng.choice(CELLS)
        lines[k] = ",".join(cells)
    elif op == 1:                                   # a stray quote
        at = rng.randrange(len(text) + 1)
        return text[:at] + '"' + text[at:]
    elif op == 2:                                   # a line break inside quotes
        lines[k] = '"' + lines[k].replace(",", '\n,', 1) + '"'
    elif op == 3:                                   # other line ends
        end = rng.choice(["\r", "\r\n", "\n\r", "\r\r", "\x85", "\u2028", "\x0b"])
        return text.replace("\n", end) if rng.random() < 0.7 else text.replace("\n", end, 3)
    elif op == 4:                                   # a name replaced
        cells = lines[0].split(",")
        cells[rng.randrange(len(cells))] = rng.choice(NAMES)
        lines[0] = ",".join(cells)
    elif op == 5:                                   # the header twice, or none
        lines = [lines[0]] + lines if rng.random() < 0.5 else lines[1:]
    elif op == 6:                                   # cells added or removed
        lines[k] = lines[k] + rng.choice([",", ",,", ",1", ",1,2,3"]) if rng.random() < 0.5 \
            else lines[k].rsplit(",", 1)[0]
    elif op == 7:                                   # blank, comment and comma lines
        lines.insert(k, rng.choice(["", " ", "# note", ",,", "\t", "  #, 1,2", '""', '"",""']))
    elif op == 8 and len(text) < 1_000_000:         # a very long line
        lines.insert(k, rng.choice(["1", ",", "9,"]) * rng.choice([10_000, 200_000, 2_000_000]))
    elif op == 9 and len(text) < 10_000:            # many rows: beyond MAX_ROWS at times
        body = lines[1:] or ["0,0"]
        lines = lines[:1] + body * (20_000 if rng.random() < 0.1 else rng.choice([10, 1000]))
    elif op == 10:                                  # rows out of order
        body = lines[1:]
        rng.shuffle(body)
        lines = lines[:1] + body
    elif op == 11:                                  # truncated
        return text[:rng.randrange(len(text) + 1)]
    elif op == 12:                                  # a byte-order mark, or text in another order
        return rng.choice(["\ufeff", "\ufeff\ufeff", ""]) + text[::rng.choice([1, -1])]
    else:                                           # a column named twice
        lines[0] = lines[0] + "," + lines[0].split(",")[0]
    return "\n".join(lines)


def _damaged(text: str, rng: random.Random) -> bytes:
    """Bytes that are not UTF-8 text, or not the text at all: corrupted, NUL, cut anywhere."""
    raw = bytearray(text.encode("utf-8", "surrogatepass"))
    for _ in range(rng.randint(1, 4)):
        if raw:
            raw[rng.randrange(len(raw))] = rng.choice([0, 0xff, 0xc3, 0x80, rng.randrange(256)])
    return bytes(raw[:rng.randrange(len(raw) + 1)] if rng.random() < 0.3 else raw)


_CSV_COMMANDS = {
    "curve": [("differentiate", "{file}", "--out", "{out}", "--format", "svg")],
    "designs": [("sweep", "fourbar", "{file}", "--samples", "12", "-o", "{out}/s.csv"),
                ("atlas", "build", "{file}", "--samples", "24", "-o", "{out}/a.parquet")],
    "path": [("atlas", "find", "{atlas}", "{file}", "-k", "2")],
}


def csv_case(rng: random.Random) -> Case:
    """A CSV table (a measured curve, designs or a path) mutated as text."""
    family = rng.choice(["curve", "curve", "designs", "path"])
    text = {"curve": _curve_text, "designs": _designs_text, "path": _path_text}[family](rng)
    for _ in range(rng.choice([1, 1, 2, 3])):
        text = _csv_mutation(text, rng)
    data: str | bytes = _damaged(text, rng) if rng.random() < 0.08 else text
    return Case(data, ".csv", rng.choice(_CSV_COMMANDS[family]), family)


# -- atlases ---------------------------------------------------------------------------------------
_VALUES = [0.0, -0.0, -1.0, 1e-12, 1e300, -1e300, math.inf, -math.inf, math.nan, 5e-324, 1e9,
           2e9, 7, True, "a", None]


def _atlas_frame():
    """A small valid atlas's table (made once per process)."""
    global _ATLAS_FRAME
    if _ATLAS_FRAME is None:
        import kinelab as kl
        designs = kl.sweep.sobol(32, seed=1, ground=(1, 4), crank=(0.3, 1), coupler=(1, 4),
                                 rocker=(1, 4), coupler_point_along=(-1, 2),
                                 coupler_point_perpendicular=(-1, 1))
        a = kl.sweep.atlas(designs)
        _ATLAS_FRAME = a.table.copy()
        _ATLAS_FRAME.attrs = {"harmonics": a.harmonics, "branch": a.branch}
    return _ATLAS_FRAME


_ATLAS_FRAME = None


def atlas_case(rng: random.Random) -> Case:
    """An atlas file: its table and metadata mutated, written as Parquet, sometimes damaged."""
    import io

    import pandas as pd

    df = _atlas_frame().copy()
    attrs = dict(_atlas_frame().attrs)
    for _ in range(rng.choice([1, 1, 2, 3])):
        op = rng.randrange(8)
        column = rng.choice(list(df.columns))
        if op == 0:                                             # the metadata
            key = rng.choice(["harmonics", "branch"])
            attrs[key] = rng.choice([0, -1, 1, 2, 7, 9, 1000, 1001, 10 ** 30, 2.0, True, "8",
                                     "open", "crossed", "weird", None, [8], {"a": 1}])
            if attrs[key] is None:
                del attrs[key]
        elif op == 1 and len(df):                               # a value
            df[column] = df[column].astype(object)
            df.at[rng.randrange(len(df)), column] = rng.choice(_VALUES)
        elif op == 2:                                           # a column dropped
            df = df.drop(columns=[column])
        elif op == 3:                                           # a column added
            df[rng.choice(["fd+9", "fd-9", "extra", "fd+0", "ground ", "7"])] = 1.0
        elif op == 4:                   # rows: none, or many (at most 32,000: more is gigabytes)
            none = rng.random() < 0.5
            df = df.iloc[:0] if none or len(df) > 32 else pd.concat(
                [df] * rng.choice([10, 1000]), ignore_index=True)
        elif op == 5:                                           # a whole column of a kind
            df[column] = rng.choice([-1.0, 0.0, math.nan, 1e300, "x"])
        elif op == 6:                                           # columns renamed, reordered
            df = df[list(reversed(df.columns))] if rng.random() < 0.5 else df.rename(
                columns={column: rng.choice(["crank", "fd+1", "x"])})
        else:                                                   # another index
            df.index = [f"r{i}" for i in range(len(df))]
    df.attrs = attrs
    buffer = io.BytesIO()
    try:
        df.to_parquet(buffer)
        data = buffer.getvalue()
    except Exception:           # a table pyarrow cannot write: keep the valid one's bytes
        buffer = io.BytesIO()
        _atlas_frame().to_parquet(buffer)
        data = buffer.getvalue()
    r = rng.random()
    if r < 0.1:
        data = _damaged(data.decode("latin-1"), rng)
    elif r < 0.13:
        data = data[:rng.randrange(len(data))]
    elif r < 0.15:
        data = rng.choice([b"", b"PAR1", b"PAR1" + b"\x00" * 64 + b"PAR1", b"not parquet\n"])
    command = ("atlas", "find", "{file}", "{path}", "-k", rng.choice(["1", "3", "100000"]))
    return Case(data, ".parquet", command, "atlas")


# -- requests to the web app ---------------------------------------------------------------------
# The page's requests (as tests/web sends them) mutated as JSON, then sometimes as bytes: cut,
# in another encoding, with a huge number, deep nesting, a duplicated key, a body of another
# media type or no object at all; and the routes asked with other methods or other paths.
_WEB_MODELS: dict | None = None
_DERIVED = ("crank_rocker", "offset_slider_crank", "slotted_link", "engine",
            "inverted_slider_crank")    # derivations of a second or less
_ROUTES = ["analyze", "study", "study", "configuration", "drag", "drag", "flip", "derive",
           "synthesize", "export", "export", "load", "save", "get"]
_GETS = ["/api/catalogue", "/api/start", "/api/examples/crank_rocker", "/api/examples/nothing",
         "/api/examples/catalogue:fourbar", "/api/examples/catalogue:x",
         "/api/examples/..%2fREADME", "/api/examples/%00", "/api/examples/" + "x" * 5000, "/",
         "/static/app.css", "/static/../pyproject.toml", "/static/%2e%2e/_api.py",
         "/api/analyze/", "/api/ANALYZE", "/api", "/api/examples/crank_rocker.toml",
         "/api/examples/%ff%fe", "/api/%1b%5b2J"]
_MEDIA = ["text/plain", "application/x-www-form-urlencoded", "multipart/form-data; boundary=x",
          "", "application/json; charset=utf-16", "Application/JSON ; charset=latin-1",
          "application/jsonx", "application/json, text/plain"]
_BODIES = [b"", b" ", b"[]", b"1", b'"x"', b"null", b"{}", b"\x00", b"NaN", b'{"model": NaN}',
           b'{"model": Infinity, "samples": -Infinity}', b"{" * 3, b"\xef\xbb\xbf{}",
           b"\xff\xfe{\x00}\x00"]


def _web_models() -> dict[str, tuple[dict, list[str], str]]:
    """Each example's JSON form, its dyads' steps and its text (made once per process)."""
    global _WEB_MODELS
    if _WEB_MODELS is None:
        from kinelab.io import ModelFile
        from kinelab.web import _api
        _WEB_MODELS = {}
        for path in sorted((ROOT / "examples").glob("*.toml")):
            mf = ModelFile.read(path)
            _WEB_MODELS[path.stem] = (mf.to_dict(), [b["step"] for b in _api._branches(mf)],
                                      path.read_text())
    return _WEB_MODELS


def _web_request(rng: random.Random) -> tuple[str, str, dict | None]:
    """(method, path, body) of a valid request."""
    route = rng.choice(_ROUTES)
    if route == "get":
        return "GET", rng.choice(_GETS), None
    models = _web_models()
    name = rng.choice(sorted(_DERIVED) if route == "derive" else sorted(models))
    model, steps, text = copy.deepcopy(models[name])
    if route == "analyze":
        body = {"model": model, "samples": rng.choice([5, 7, 37])}
    elif route == "study":
        body = {"model": model, "samples": rng.choice([9, 37, None])}
        if rng.random() < 0.3:
            body["columns"] = [f"{rng.choice([lk['name'] for lk in model['links']])}.omega[deg/s]"]
    elif route == "configuration":
        body = {"model": model, "q": rng.choice([0, 40, 90, 359.5, -30])}
    elif route == "drag":
        point = rng.choice(list(model["points"]))
        xy = model["points"][point]
        body = {"model": model, "point": point, "to": [xy[0] + 10, xy[1] - 5]}
    elif route == "flip":
        body = {"model": model, "step": rng.choice(steps or ["x"])}
    elif route == "derive":
        body = {"model": model, "lang": rng.choice(["en", "pt"])}
    elif route == "synthesize":
        body = {"task": copy.deepcopy(rng.choice(MORE_TASKS)), "source": "task.toml"}
    elif route == "export":
        body = {"model": model, "kind": rng.choice(["csv", "json", "svg", "dxf", "csv", "gif"]),
                "samples": 5, "source": f"{name}.toml"}
    elif route == "load":
        body = {"text": text, "source": f"{name}.toml"} if rng.random() < 0.7 else {
            "text": json.dumps(model), "format": "json"}
    else:
        body = {"model": model, "format": rng.choice(["toml", "json"])}
    if "samples" in body and body["samples"] is None:
        del body["samples"]
    return "POST", "/api/" + route, body


def _web_bytes(text: str, rng: random.Random) -> bytes:
    """A request's JSON text as damaged bytes."""
    op = rng.randrange(9)
    if op == 0:                                                 # cut
        return text.encode()[:rng.randrange(len(text) + 1)]
    if op == 1:                                                 # a key given twice
        return text.replace("{", '{"model": ' + rng.choice(['1', '"x"', "null", "{}"]) + ", ",
                            1).encode() if rng.random() < 0.5 else \
            (text[:-1] + ', "model": null}').encode()
    if op == 2:                                                 # a huge number
        number = rng.choice(["9" * 5000, "1" + "0" * 4300, "1e999", "-1e400", "1e-400",
                             "0." + "0" * 5000 + "1", "123456789" * 400, "-0"])
        digits = [i for i in range(len(text)) if text[i].isdigit() and not text[i - 1].isalnum()
                  and text[i - 1] != "."]
        at = rng.choice(digits) if digits else len(text) - 1
        end = at
        while end < len(text) and (text[end].isdigit() or text[end] in ".eE+-"):
            end += 1
        return (text[:at] + number + text[end:]).encode()
    if op == 3:                                                 # deep nesting
        depth = rng.choice([500, 990, 5000, 100_000])
        nest = rng.choice(["[", '{"a": '])
        close = "]" if nest == "[" else "}"
        value = nest * depth + "1" + close * depth
        if rng.random() < 0.5:
            return ('{"model": ' + value + ', "q": 1}').encode()
        return (text[:-1] + ', "deep": ' + value + "}").encode()
    if op == 4:                                                 # not UTF-8
        return _damaged(text, rng)
    if op == 5:                                                 # another encoding
        how = rng.choice(["utf-16", "utf-16-le", "utf-32", "utf-8-sig", "latin-1"])
        return text.replace('"', '"\u00e9', 1).encode(how, "replace") if how == "latin-1" else \
            text.encode(how, "surrogatepass")
    if op == 6:                                                 # no object at all
        return rng.choice(_BODIES)
    if op == 7:                                                 # a NUL byte, or a control
        at = rng.randrange(len(text) + 1)
        return (text[:at] + rng.choice(["\x00", "\x1b", "\ufeff", "\\u0000"]) + text[at:]).encode()
    return (text + " " * (2 * 1024 * 1024)).encode()            # past the server's cap


def web_case(rng: random.Random) -> Case:
    """A request to the web app (``kinelab serve``): a valid one mutated as JSON, then
    sometimes as bytes, with another media type or another method.  The case's command is
    (method, path, media type); its text, the body's bytes."""
    method, path, body = _web_request(rng)
    if body is not None and rng.random() < 0.8:
        body = mutate(body, rng, rng.choice([1, 1, 2, 3]))
    text = "" if body is None else _json(body)
    data = text.encode("utf-8", "surrogatepass")
    if body is not None and rng.random() < 0.3:
        data = _web_bytes(text, rng)
    media = "application/json" if body is not None else ""
    r = rng.random()
    if r < 0.08:
        media = rng.choice(_MEDIA)
    elif r < 0.14:                                              # another method
        method = rng.choice(["GET", "PUT", "DELETE", "PATCH", "HEAD", "OPTIONS"]) if \
            method == "POST" else rng.choice(["POST", "PUT", "DELETE"])
    return Case(data, "", (method, path, media), "web")


# -- hostile names in what the commands write ----------------------------------------------------
# Model files whose model, points, links, joints and inputs are named with paths, separators,
# device names, controls, very long names, names that differ only in case or normalisation and
# mathtext, run through every command that writes files (a task's name through synth, a
# table's file and column names through differentiate).  ABSOLUTE stands for an absolute path
# inside the case's directory, filled in when the case runs.
ABSOLUTE = "@ABSOLUTE@"
HOSTILE_NAMES = [ABSOLUTE, ABSOLUTE + "/x", "/", "..", ".", "../../escaped", "../x", "a/b", "a\\b",
                 "\\\\server\\share", "C:\\x", "C:x", "x:y", "a\x00b", "\x1b[2J", "a\nb", "\t",
                 "\r", "\u202e", "\ufeff", "CON", "nul", "Nul.txt", "COM1", "com\u00b9", "LPT9 ",
                 "aux.", "x" * 300, "\u00e9" * 200, "x" * 10_000, "$", "a$b", "$x$", "$\\alpha{",
                 "\\frac{", "{", "}", "^", "_", "_x", "%", "#", "~", "*", "?", "<>", "|", '"', "'",
                 " ", " x", "x ", "x.", ".hidden", "-rf", "--out", "\u540d\u524d", "\U0001f642",
                 "\\", "a\\$b$", "$$", r"\$", "${HOME}", "$(true)", "e\u0301", "\u00e9", "Q", "q"]
STEMS = ["case", "a\\b", "m\x1b[2Jx", "..x", "nul", "CON", "COM1.x", "$x$", "a$b", "x" * 200,
         " x", "-x", "\u00e9", "e\u0301", "{x}", "..", "x.", "\\frac{"]
_NAMED = {       # example: commands that write what it is named after
    "crank_rocker": ["plot", "centres", "polygons", "analyze", "animate", "export"],
    "slotted_link": ["plot", "polygons", "analyze", "export"],
    "offset_slider_crank": ["plot", "centres", "polygons", "animate"],
    "stephenson6": ["plot", "centres", "analyze"],
    "engine": ["dynamics", "dynamics", "plot", "polygons"],
}
_WRITERS = {
    "dynamics": lambda rng: ("dynamics", "{file}", "--samples", "7", "--out", "{out}",
                             *rng.choice([(), ("--no-plots",), ("--verify",)])),
    "plot": lambda rng: ("plot", "{file}", "--samples", "7", "--format", rng.choice(["png", "svg"]),
                         "--out", "{out}"),
    "centres": lambda rng: ("centres", "{file}", "--at", "30", "--centrodes", "--samples", "7",
                            "--format", rng.choice(["png", "svg"]), "--out", "{out}"),
    "polygons": lambda rng: ("polygons", "{file}", "--at", "30", "--format",
                             rng.choice(["png", "svg"]), "--out", "{out}",
                             *rng.choice([(), ("--verify",)])),
    "analyze": lambda rng: ("analyze", "{file}", "--samples", "5", "-q", "-o", "{out}",
                            *rng.choice([(), ("--verify",), ("--format", "json")])),
    "animate": lambda rng: ("animate", "{file}", "--samples", "5", "--frames", "2", "--format",
                            "gif", "--out", "{out}", *rng.choice([(), ("--centres",),
                                                                   ("--velocities",)])),
    "export": lambda rng: ("export", "{file}", "--to", rng.choice(["svg", "dxf", "toml"]),
                           "--out", "{out}"),
}
_RESERVED_WORDS = {"R", "P", "C", "G", "m", "mm", "cm", "deg", "rad", "in"}


def _names(data: dict) -> list[str]:
    """The names a model file gives: its points', links', joints' and inputs'."""
    names = list(data.get("points", {}))
    for section in ("links", "joints", "inputs"):
        names += [x["name"] for x in data.get(section, []) if "name" in x]
    return [n for n in names if n not in _RESERVED_WORDS]


def _hostile_name(rng: random.Random, taken: list[str]) -> str:
    """A hostile name; at times one that differs from a name given already only in case or
    in Unicode normalisation."""
    import unicodedata
    if taken and rng.random() < 0.25:
        other = rng.choice(taken)
        variant = rng.choice([other.swapcase(), unicodedata.normalize("NFD", other),
                              unicodedata.normalize("NFC", other), other + " "])
        if variant != other:
            return variant
    return rng.choice(HOSTILE_NAMES)


def _renamed(data, names: dict, keyed: bool = False):
    """``data`` with every name in ``names`` replaced where it is a value, and where it is a
    key of a table keyed by names (``keyed``: points, a link's local places and sides)."""
    if isinstance(data, dict):
        return {(names.get(k, k) if keyed else k): _renamed(
            v, names, k in ("points", "local", "sides") and isinstance(v, dict))
            for k, v in data.items()}
    if isinstance(data, list):
        return [_renamed(v, names) for v in data]
    return names.get(data, data) if isinstance(data, str) else data


def _render_names(data: dict, rng: random.Random) -> tuple[str, str]:
    if rng.random() < 0.5:
        return to_toml(data), ".toml"
    return json.dumps(data, ensure_ascii=rng.random() < 0.5), ".json"


def names_case(rng: random.Random) -> Case:
    """A model file (a task file for synth, a table for differentiate) whose names are
    hostile, and a command that writes files named after them."""
    stem = rng.choice(STEMS) if rng.random() < 0.3 else "case"
    r = rng.random()
    if r < 0.1:                                         # a task's name, through synth
        task = copy.deepcopy(rng.choice([t for t in MORE_TASKS if t["task"] in (
            "motion", "crank-rocker", "quick-return") and "search" not in t]))
        task["name"] = _hostile_name(rng, [])
        text, suffix = to_toml(task), ".toml"
        command = ("synth", "{file}", "--out", "{out}", *rng.choice([(), ("--no-figures",),
                                                                     ("--verify",)]))
        return Case(text, suffix, command, "names", stem)
    if r < 0.2:                                         # a table's names, through differentiate
        header = [_hostile_name(rng, []) + rng.choice(["", " [s]", " [mm]"]) for _ in range(2)]
        text = _curve_text(rng).split("\n", 1)[1]
        text = ",".join(json.dumps(h) if ("," in h or '"' in h or "\n" in h) else h
                        for h in header) + "\n" + text
        command = ("differentiate", "{file}", "--out", "{out}", "--format",
                   rng.choice(["png", "svg"]))
        return Case(text.replace("\x00", ""), ".csv", command, "names", stem)
    example = rng.choice(sorted(_NAMED))
    original = tomllib.loads((ROOT / "examples" / f"{example}.toml").read_text())
    for joint in original["joints"]:        # the name a joint is given by default, written
        joint.setdefault("name", f"j{joint['point']}")      # (its point's may change)
    chosen: dict[str, str] = {}
    for old in rng.sample(_names(original), rng.choice([1, 1, 2, 3, 5])):
        chosen[old] = _hostile_name(rng, list(chosen.values()))
    data = _renamed(original, chosen)
    if rng.random() < 0.6:
        data["name"] = _hostile_name(rng, list(chosen.values()))
    if "outputs" in data and rng.random() < 0.5:        # every renamed point reported, traced
        points = [new for old, new in chosen.items() if old in original["points"]]
        data["outputs"]["report"] = list(dict.fromkeys([*data["outputs"].get("report", []),
                                                        *points]))
    text, suffix = _render_names(data, rng)
    command = _WRITERS[rng.choice(_NAMED[example])](rng)
    return Case(text, suffix, command, "names", stem)


FAMILIES = {"model": case, "task": task_case, "csv": csv_case, "atlas": atlas_case,
            "web": web_case, "names": names_case}


def any_case(rng: random.Random, families=("task", "csv", "atlas")) -> Case:
    """A case of one of ``families`` (the readers of tasks, CSV tables and atlases by
    default; "model" adds model files, "web" requests to the web app, "names" hostile names
    through the commands that write files)."""
    return FAMILIES[rng.choice(families)](rng)


# -- running a case ---------------------------------------------------------------------------
MAX_MESSAGE = 2000        # characters of one line of an error
MAX_LINES = 100           # lines of one error (one per problem of a file)


def run(c: Case, directory: Path) -> tuple[str, str]:
    """(outcome, detail) of running a case's command in-process.

    Outcomes: "success" (exit 0), "error" (exit 2: on standard error one bounded line per
    problem of the file, each "kinelab: error: FILE: ...", at most MAX_LINES of them);
    anything else is a finding: "traceback" (an exception escaped), "exit 1", "not an error
    line", "long message", "too many lines", "unnamed" (an error that does not name the
    file, about which every error of a case is), "exit N".  A request to the web app
    (family "web") is judged by :func:`run_web`, hostile names by :func:`run_names`.
    """
    if c.family == "web":
        return run_web(c)
    if c.family == "names":
        return run_names(c, directory)
    from click.testing import CliRunner

    from kinelab.cli import main

    path = _written(c, directory)
    if "{file}" in c.command:
        args = c.args(str(path), out=str(directory / "out"), **_valid_files())
    else:
        args = c.args(str(path))
        if c.command[0] in ("check",):
            pass
        elif c.command[0] == "synth":
            args += ["--out", str(directory / "synth")]
        else:
            args += ["--out", str(directory / "out")]
    return _judged(CliRunner().invoke(main, args), path)


def _written(c: Case, directory: Path, text: str | bytes | None = None) -> Path:
    """The case's file, written in ``directory``."""
    path = directory / f"{c.stem}{c.suffix}"
    text = c.text if text is None else text
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text, encoding="utf-8", errors="surrogatepass")
    return path


def _judged(result, path: Path, named: bool = True) -> tuple[str, str]:
    """The outcome of a command's ``result`` (see :func:`run`); ``named``: every error
    line must name the file ``path``."""
    err = result.stderr
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        return "traceback", f"{type(result.exception).__name__}: {str(result.exception)[:300]}"
    if result.exit_code == 0:
        return "success", ""
    if result.exit_code == 2:
        lines = err.splitlines()
        if not lines or not err.endswith("\n") or not all(
                line.startswith("kinelab: error: ") for line in lines):
            return "not an error line", err[:300]
        if len(lines) > MAX_LINES:
            return "too many lines", f"{len(lines)} lines: {err[:200]}"
        if max(len(line) for line in lines) > MAX_MESSAGE:
            return "long message", f"{max(len(line) for line in lines)} characters: {err[:200]}"
        if named and not all(line.startswith(f"kinelab: error: {path}: ") or
                             line.startswith(f"kinelab: error: {path.name}: ") for line in lines):
            return "unnamed", lines[0][:300]       # every error here is about the file
        return "error", lines[0][:200]
    if result.exit_code == 1:
        return "exit 1", err[:300]
    return f"exit {result.exit_code}", err[:300]


FINE = ("success", "error")


def _valid_files() -> dict[str, str]:
    """A valid atlas and a valid path CSV, for the commands that read one beside the case
    (written once per process)."""
    global _VALID
    if _VALID is None:
        import tempfile

        import kinelab as kl
        place = Path(tempfile.mkdtemp(prefix="kinelab-fuzz-valid-"))
        atlas = kl.sweep.Atlas(_atlas_frame().copy(), _atlas_frame().attrs["harmonics"],
                               _atlas_frame().attrs["branch"])
        atlas.to_parquet(place / "atlas.parquet")
        (place / "path.csv").write_text(_path_text(random.Random(0)))
        _VALID = {"atlas": str(place / "atlas.parquet"), "path": str(place / "path.csv")}
    return _VALID


_VALID = None


# -- running a request to the web app -------------------------------------------------------------
WEB_SECONDS = 90.0          # an answer within: longer than the server's own longest limit on
                            # its work (an animation's 60 s), so a request past it hangs
WEB_MEMORY = 3 * 2**30      # resident bytes of the process a request may take it to


class _Records(logging.Handler):
    """The records logged while a request is answered."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.records: list[logging.LogRecord] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append(record)


def _web_client():
    """The web app, and a client of it (made once per process, as a server runs once)."""
    global _CLIENT
    if _CLIENT is None:
        import warnings

        from kinelab.web import create_app
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")         # starlette's note on httpx
            from starlette.testclient import TestClient
            _CLIENT = TestClient(create_app(), base_url="http://127.0.0.1:8000")
    return _CLIENT


_CLIENT = None


def _peak() -> int:
    """The most resident memory this process has held, bytes."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def _strict(text: bytes):
    """JSON as a browser reads it: no NaN or Infinity."""
    def refuse(constant):
        raise ValueError(f"{constant} is not JSON")
    return json.loads(text, parse_constant=refuse)


def run_web(c: Case, seconds: float = WEB_SECONDS) -> tuple[str, str]:
    """(outcome, detail) of a request to the web app, answered within ``seconds``.

    Outcomes: "success" (2xx; strict JSON when it says it is JSON), "error" (4xx, and
    ``{"error": message}``, one bounded line per problem: one line, or one per entry of
    ``problems``); anything else is a finding: "status N" (5xx, or another status),
    "traceback" (an exception escaped the app), "logged" (an error in the server's log),
    "not json", "not an error", "long message", "too many lines", "timeout", "memory";
    "logged" also for a traceback printed on standard error.
    """
    method, path, media = c.command
    headers = {"content-type": media} if media else {}
    box: dict = {}

    def call():
        try:
            box["answer"] = _web_client().request(method, path, content=c.text or None,
                                                  headers=headers)
        except BaseException as exc:        # noqa: BLE001 -- what escaped is the finding
            box["exception"] = exc
    records = _Records()
    logging.getLogger().addHandler(records)
    peak = _peak()
    thread = threading.Thread(target=call, daemon=True)
    stderr, sys.stderr = sys.stderr, io.StringIO()      # where Python reports what it
    try:                                                # cannot raise (a thread's, a
        thread.start()                                  # finalizer's exception)
        thread.join(seconds)
    finally:
        logging.getLogger().removeHandler(records)
        printed, sys.stderr = sys.stderr.getvalue(), stderr
    where = f"{method} {path}"
    if thread.is_alive():
        return "timeout", f"{where}: no answer in {seconds:g} s"
    if "exception" in box:
        exc = box["exception"]
        return "traceback", f"{where}: {type(exc).__name__}: {str(exc)[:300]}"
    if "Traceback" in printed or "Exception ignored" in printed:
        return "logged", f"{where}: {printed[-300:]!r}"
    if peak < WEB_MEMORY <= _peak():
        return "memory", f"{where}: {_peak():,} bytes resident"
    logged = [r for r in records.records if r.levelno >= logging.ERROR or r.exc_info]
    if logged:
        r = logged[0]
        kind = f"{r.exc_info[0].__name__}: " if r.exc_info and r.exc_info[0] else ""
        return "logged", f"{where}: {kind}{r.getMessage()[:300]}"
    answer = box["answer"]
    status = answer.status_code
    media = answer.headers.get("content-type", "").split(";")[0].strip()
    if 200 <= status < 300:
        if media == "application/json" and method != "HEAD":
            try:
                _strict(answer.content)
            except ValueError as exc:
                return "not json", f"{where}: {status}: {exc}"
        return "success", ""
    if not 400 <= status < 500:
        return f"status {status}", f"{where}: {answer.text[:300]}"
    if method == "HEAD":                    # no body
        return "error", f"{status}"
    if media != "application/json":
        return "not json", f"{where}: {status} {media}: {answer.text[:300]}"
    try:
        data = _strict(answer.content)
    except ValueError as exc:
        return "not json", f"{where}: {status}: {exc}: {answer.text[:300]}"
    message = data.get("error") if isinstance(data, dict) else None
    if not isinstance(message, str) or not message.strip():
        return "not an error", f"{where}: {status}: {answer.text[:300]}"
    lines = message.splitlines()
    problems = data.get("problems")
    if len(lines) > 1 and not (isinstance(problems, list) and len(problems) == len(lines)):
        return "not one line", f"{where}: {status}: {message[:300]!r}"
    if len(lines) > MAX_LINES:
        return "too many lines", f"{where}: {len(lines)} lines: {message[:200]!r}"
    if max(len(line) for line in lines) > MAX_MESSAGE:
        return "long message", f"{where}: {max(len(line) for line in lines)} characters: " \
                               f"{message[:200]!r}"
    return "error", f"{status} {lines[0][:200]}"


# -- running hostile names ------------------------------------------------------------------------
_DEVICES = frozenset(["con", "prn", "aux", "nul", *(f"{d}{k}" for d in ("com", "lpt")
                                                   for k in "0123456789\u00b9\u00b2\u00b3")])


def unsafe_file_name(name: str) -> bool:
    """Whether ``name`` is not one plain file's name on every file system (see "Output
    files" in docs/command-line.md): a separator or a character Windows refuses, a control
    or format character, two dots in a row, a dot or a space at either end, a device's name,
    more than 255 bytes."""
    import unicodedata
    if name in ("", ".", "..") or name.startswith((".", " ")) or name.endswith((".", " ")):
        return True
    if ".." in name or len(name.encode("utf-8", "surrogatepass")) > 255:
        return True
    if any(ch in '/\\:*?"<>|' or unicodedata.category(ch) in ("Cc", "Cf", "Cs", "Zl", "Zp")
           for ch in name):
        return True
    return name.split(".", 1)[0].rstrip(" ").casefold() in _DEVICES


def _tree(root: Path) -> set[Path]:
    """Every file and directory under ``root``."""
    found = set()
    for here, dirs, files in os.walk(root):
        found.update(Path(here) / n for n in dirs + files)
    return found


def run_names(c: Case, directory: Path) -> tuple[str, str]:
    """(outcome, detail) of a command writing files named after hostile names, run from
    ``directory/1/2/3/work`` (so that a path climbing out of it still lands in
    ``directory``), the file in ``work/src``, ``--out`` ``work/out``.

    Outcomes as :func:`run`'s (errors may name an output rather than the file), and the
    findings "written outside --out" (a file or directory that appeared in ``directory``
    but not in ``--out``), "staging left" (a ``.kinelab-*`` directory after the command
    ended), "unsafe name" (see :func:`unsafe_file_name`) and "names meet" (two outputs
    whose names differ only in case or Unicode normalisation).
    """
    import unicodedata

    from click.testing import CliRunner

    from kinelab.cli import main

    directory = directory.resolve()         # the command runs from elsewhere
    work = directory / "1" / "2" / "3" / "work"
    (work / "src").mkdir(parents=True)
    out = work / "out"
    text = c.text.replace(ABSOLUTE, json.dumps(str(directory / "victim"))[1:-1])
    path = _written(c, work / "src", text)
    args = [a.format(file=str(path), out=str(out)) for a in c.command]
    before = _tree(directory)
    here = os.getcwd()
    os.chdir(work)
    try:
        result = CliRunner().invoke(main, args)
    finally:
        os.chdir(here)
    outcome, detail = _judged(result, path, named=False)
    if outcome not in FINE:
        return outcome, detail
    after = _tree(directory)
    new = sorted(after - before)
    outside = [p for p in new if p != out and out not in p.parents]
    if outside:
        return "written outside --out", f"{c.command[0]}: {str(outside[0])!r}"[:300]
    staged = [p for p in after if p.name.startswith(".kinelab-")]
    if staged:
        return "staging left", f"{c.command[0]}: {str(staged[0])!r}"
    seen: dict[str, str] = {}
    for p in new:
        if p == out:
            continue
        if p.parent != out or unsafe_file_name(p.name):
            return "unsafe name", f"{c.command[0]}: {str(p.relative_to(out))!r}"[:300]
        key = unicodedata.normalize("NFC", p.name).casefold()
        if key in seen:
            return "names meet", f"{c.command[0]}: {seen[key]!r} and {p.name!r}"[:300]
        seen[key] = p.name
    return outcome, detail
