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
import json
import math
import random
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
    family: str = "model"              # what the file is: model, task, curve, designs, path, atlas

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
        elif op == 4:                                           # rows: none, or many
            df = df.iloc[:0] if rng.random() < 0.5 else pd.concat([df] * rng.choice([10, 1000]),
                                                                    ignore_index=True)
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


FAMILIES = {"model": case, "task": task_case, "csv": csv_case, "atlas": atlas_case}


def any_case(rng: random.Random, families=("task", "csv", "atlas")) -> Case:
    """A case of one of ``families`` (the readers of tasks, CSV tables and atlases by
    default; "model" adds model files)."""
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
    file, about which every error of a case is), "exit N".
    """
    from click.testing import CliRunner

    from kinelab.cli import main

    path = directory / f"case{c.suffix}"
    if isinstance(c.text, bytes):
        path.write_bytes(c.text)
    else:
        path.write_text(c.text, encoding="utf-8", errors="surrogatepass")
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
    result = CliRunner().invoke(main, args)
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
        if not all(line.startswith(f"kinelab: error: {path}: ") or
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
