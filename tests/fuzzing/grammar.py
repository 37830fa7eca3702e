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
    command: tuple[str, ...]           # e.g. ("check",): the file's path comes after

    def args(self, path: str) -> list[str]:
        return [self.command[0], path, *self.command[1:]]


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
    return Case(text, suffix, command)


# -- running a case ---------------------------------------------------------------------------
MAX_MESSAGE = 2000        # characters of one line of an error
MAX_LINES = 100           # lines of one error (one per problem of a file)


def run(c: Case, directory: Path) -> tuple[str, str]:
    """(outcome, detail) of running a case's command in-process.

    Outcomes: "success" (exit 0), "error" (exit 2: on standard error one bounded line per
    problem of the file, each "kinelab: error: ...", at most MAX_LINES of them); anything else
    is a finding: "traceback" (an exception escaped), "exit 1", "not an error line", "long
    message", "too many lines", "exit N".
    """
    from click.testing import CliRunner

    from kinelab.cli import main

    path = directory / f"case{c.suffix}"
    if isinstance(c.text, bytes):
        path.write_bytes(c.text)
    else:
        path.write_text(c.text, encoding="utf-8", errors="surrogatepass")
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
        return "error", lines[0][:200]
    if result.exit_code == 1:
        return "exit 1", err[:300]
    return f"exit {result.exit_code}", err[:300]


FINE = ("success", "error")
