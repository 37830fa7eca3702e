"""Synthesis task files: a task's data (the TOML of ``kinelab synth``, see
``docs/synthesis.md``, or the same content as plain data) read and checked, converted to SI
once; the task solved by :mod:`kinelab.synthesis`; its linkages summarised as plain data in the
task's units.  The command line and the browser app both read, solve and summarise tasks
here, so a task gives the same answer, and a malformed one the same message, in either.
"""
from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from kinelab import synthesis
from kinelab.errors import ModelError, describe, expected_one_of, quoted, shown_key
from kinelab.io._results import json_ready
from kinelab._files import file_path
from kinelab.io._text import loads, read_text
from kinelab.model import (ANGLE_UNITS, LENGTH_UNITS, Units, is_real, length_problem, name_problem,
                           real_array)
from kinelab.solvers._arguments import MAX_SEED
from kinelab.synthesis._arguments import MAX_POSITIONS
from kinelab.synthesis._function import _function_generation, _function_pairs
from kinelab.synthesis._path import (MAX_PATH_POINTS, MAX_PATH_SAMPLES, MAX_POPSIZE, MAX_ROUNDS,
                                     MAX_RUNS)
from kinelab.synthesis._positions import check_not_one_turn

__all__ = ["Task", "TASK_KINDS", "load_task", "read_task", "solve_task", "task_summary"]

TASK_KINDS = ("motion", "function", "path", "crank-rocker", "quick-return")
MECHANISMS = ("offset slider-crank", "slotted lever", "whitworth")
# Bounds on a task's whole numbers, so that a typo cannot ask for days of search or more
# memory than a machine has; each is far above what a synthesis needs.
MAX_SAMPLES = 1_000_000
MAX_PRECISION_POINTS = 100
# (a path task's targets are at most MAX_PATH_POINTS, checked before anything is computed)
_SEARCH_BOUNDS = {"runs": (1, MAX_RUNS), "maxiter": (1, MAX_ROUNDS), "popsize": (5, MAX_POPSIZE),
                  "samples": (24, MAX_PATH_SAMPLES), "seed": (0, MAX_SEED)}
_SECTIONS = {"task", "name", "units", "positions", "pivots", "function", "search", "crank_rocker",
             "quick_return"}
# the keys of a design task's section: whether each is a length, an angle or a number
_DESIGN_KEYS = {
    "crank_rocker": {"ground": "length", "swing": "angle", "time_ratio": "number",
                     "crank": "length", "pivot_angle": "angle"},
    "quick_return": {"mechanism": "choice", "time_ratio": "number", "stroke": "length",
                     "rod": "length", "distance": "length"},
}
_REQUIRED = {"crank-rocker": ("ground", "swing", "time_ratio"),
             "offset slider-crank": ("stroke", "time_ratio"),
             "slotted lever": ("time_ratio", "distance"),
             "whitworth": ("time_ratio", "distance", "stroke")}


@dataclass
class Task:
    """A synthesis task read from a file, in SI units."""

    kind: str
    name: str
    length_unit: str
    angle_unit: str
    positions: synthesis.Positions | None = None
    pivots: dict[str, Any] = field(default_factory=dict)
    targets: np.ndarray | None = None
    function: dict[str, Any] = field(default_factory=dict)
    search: dict[str, Any] = field(default_factory=dict)
    design: dict[str, Any] = field(default_factory=dict)
    source: str = ""

    @property
    def units(self) -> Units:
        """The units the task file is written in."""
        return Units(self.length_unit, self.angle_unit)


class _Reader:
    """Collects every problem of a task file, each naming its field."""

    def __init__(self, data: dict):
        self.data = data
        self.problems: list[str] = []

    def get(self, section: str, key: str, default=None):
        sec = self.data.get(section, {})
        return sec.get(key, default) if isinstance(sec, dict) else default

    def array(self, where: str, value, shape: tuple, scale: float = 1.0):
        """Real numbers of ``shape`` (None: any length) times ``scale``; with a length
        ``scale`` (the default is not), coordinates of at most MAX_LENGTH m."""
        a = real_array(value)
        ok = a is not None and a.ndim == len(shape) and all(
            s is None or s == n for s, n in zip(shape, a.shape))
        if not ok or not np.all(np.isfinite(a)):
            want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ")"
            self.problems.append(f"{where}: expected finite numbers of shape {want}, got "
                                 f"{describe(value)}")
            return None
        return a * scale

    def lengths(self, where: str, value, shape: tuple, scale: float):
        """Coordinates (file units to m), each at most MAX_LENGTH m in size."""
        a = self.array(where, value, shape, scale)
        if a is not None and a.size and (why := length_problem(float(np.abs(a).max()),
                                                               positive=False)):
            self.problems.append(f"{where}: {why}, got {describe(value)}")
            return None
        return a

    def number(self, where: str, value, scale: float = 1.0, positive: bool = False):
        if not is_real(value) or (positive and value <= 0):
            kind = "a positive number" if positive else "a finite number"
            self.problems.append(f"{where}: expected {kind}, got {describe(value)}")
            return None
        return float(value) * scale

    def integer(self, where: str, value, low: int, high: int):
        """A whole number from ``low`` to ``high``: bounds that keep a search's time and
        memory within reason."""
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral) \
                or not low <= value <= high:
            self.problems.append(f"{where}: expected a whole number from {low:,} to {high:,}, "
                                 f"got {describe(value)}")
            return None
        return int(value)

    def unknown(self, section: str, allowed: set[str]):
        sec = self.data.get(section, {})
        if not isinstance(sec, dict):
            self.problems.append(f"[{section}]: expected a table")
            return
        for key in sec:
            if key not in allowed:
                self.problems.append(f"{section}.{shown_key(key)}: unknown key; expected one of "
                                     f"{quoted(sorted(allowed))}")


def load_task(path: str | Path) -> Task:
    """Read a task file (TOML) and convert it to SI units.

    Raises
    ------
    ModelError
        Every problem of the file at once, each naming its field.
    """
    path = file_path(path)
    data = loads(read_text(path), "TOML", source=str(path))
    return read_task(data, source=str(path), name=path.stem)


def read_task(data: Any, *, source: str | None = None, name: str = "task") -> Task:
    """A task given as plain data (what a task file's TOML reads as), converted to SI units.

    Parameters
    ----------
    data : dict
        The task: ``task``, ``units``, and the sections of its kind (``docs/synthesis.md``).
    source : str, optional
        The file it comes from, named in messages.
    name : str
        The task's name when ``data`` gives none.

    Raises
    ------
    ModelError
        Every problem of the task at once, each naming its field.

    Examples
    --------
    >>> task = kl.io.read_task({"task": "crank-rocker", "units": {"angle": "deg"},
    ...                         "crank_rocker": {"ground": 1.0, "swing": 45, "time_ratio": 1.25}})
    >>> task.kind, round(task.design["swing"], 12) == round(np.pi / 4, 12)
    ('crank-rocker', True)
    """
    if not isinstance(data, dict):
        raise ModelError(f"task: expected a table of the task's sections, got {describe(data)}",
                         source=source)
    r = _Reader(data)
    for key in data:
        if key not in _SECTIONS:
            r.problems.append(f"{shown_key(key)}: unknown key; expected one of "
                              f"{quoted(sorted(_SECTIONS))}")
    kind = data.get("task")
    if kind not in TASK_KINDS:
        r.problems.append(f"task: {expected_one_of(kind, TASK_KINDS)}")
    not_tables = [f"{key}: expected a table, got {describe(data[key])}"
                  for key in sorted(_SECTIONS - {"task", "name"})
                  if key in data and not isinstance(data[key], dict)]
    if not_tables:
        # what those sections hold cannot be read: the problems that follow would be echoes
        raise ModelError(r.problems + not_tables, source=source)
    units = data.get("units", {})
    lu = units.get("length", "m") if isinstance(units, dict) else "m"
    au = units.get("angle", "rad") if isinstance(units, dict) else "rad"
    if not isinstance(lu, str) or lu not in LENGTH_UNITS:
        r.problems.append(f"units.length: {expected_one_of(lu, LENGTH_UNITS)}")
        lu = "m"
    if not isinstance(au, str) or au not in ANGLE_UNITS:
        r.problems.append(f"units.angle: {expected_one_of(au, ANGLE_UNITS)}")
        au = "rad"
    r.unknown("units", {"length", "angle"})
    name = data.get("name", name)
    if (why := name_problem(name)) is not None:
        r.problems.append(f"name: {why}, got {describe(name)}")
    L, A = LENGTH_UNITS[lu], ANGLE_UNITS[au]
    task = Task(kind=str(kind), name=str(name), length_unit=lu, angle_unit=au, source=source or "")
    if kind == "motion":
        _motion_task(r, task, L, A)
    elif kind == "function":
        _function_task(r, task, L, A)
    elif kind == "path":
        _path_task(r, task, L, A)
    elif kind in ("crank-rocker", "quick-return"):
        _design_task(r, task, L, A)
    if r.problems:
        raise ModelError(r.problems, source=source)
    return task


def _motion_task(r: _Reader, task: Task, L: float, A: float) -> None:
    r.unknown("positions", {"points", "angles", "second_points"})
    r.unknown("pivots", {"A0", "B0", "A1", "B1", "a0x", "b0x", "s", "t"})
    pts = r.get("positions", "points")
    if isinstance(pts, list) and len(pts) > MAX_POSITIONS:
        # counted before any work: checks and fits grow with the number of positions
        r.problems.append(f"positions.points: expected at most {MAX_POSITIONS:,} positions, got "
                          f"{len(pts):,}; keep the positions that matter or space them out")
        return
    pts = r.lengths("positions.points", pts, (None, 2), L)
    angles, second = r.get("positions", "angles"), r.get("positions", "second_points")
    if (angles is None) == (second is None):
        r.problems.append("positions: give either angles (orientations, or rotations from "
                          "position 1) or second_points (a second point of the coupler in "
                          "each position)")
        return
    if pts is None:
        return
    try:
        if angles is not None:
            ang = r.array("positions.angles", angles, (None,), A)
            if ang is None:
                return
            task.positions = synthesis.Positions(pts, ang)
        else:
            sec = r.lengths("positions.second_points", second, (None, 2), L)
            if sec is None:
                return
            task.positions = synthesis.Positions.from_two_points(pts, sec)
    except ModelError as exc:
        r.problems.extend(f"positions.{p}" for p in exc.problems)
        return
    n = task.positions.n
    if n >= 3:
        try:
            check_not_one_turn(task.positions, unit=task.length_unit, scale=L)
        except ModelError as exc:
            r.problems.extend(exc.problems)
            return
    piv = {k: r.get("pivots", k) for k in ("A0", "B0", "A1", "B1", "a0x", "b0x", "s", "t")}
    given = {k for k, v in piv.items() if v is not None}
    allowed = {2: {"A1", "B1", "s", "t"}, 3: {"A0", "B0", "A1", "B1"}, 4: {"a0x", "b0x"}}
    s = r.data.get("search", {}) if isinstance(r.data.get("search"), dict) else {}
    if "dyads" in s and n <= 5:
        r.problems.append(f"search.dyads: not used with {n} positions (only with more than five)")
    r.unknown("search", {"dyads", "min_transmission_angle"})
    if "dyads" in s and n > 5:
        task.search["dyads"] = r.integer("search.dyads", s["dyads"], 2, 100)
    _transmission_limit(r, task, s, A)
    if n >= 5:
        # five: Burmester's points; more: least squares; no pivot is chosen
        for k in sorted(given):
            r.problems.append(f"pivots.{k}: not used with {n} positions; with five or more the "
                              "pivots follow from the positions alone")
        return
    for k in sorted(given - allowed[n]):
        r.problems.append(f"pivots.{k}: not used with {n} positions; with {n} give "
                          f"{quoted(sorted(allowed[n]))}")
    for k in given & allowed[n]:
        if k in ("A0", "B0", "A1", "B1"):
            task.pivots[k] = r.lengths(f"pivots.{k}", piv[k], (2,), L)
        else:
            task.pivots[k] = r.number(f"pivots.{k}", piv[k], L)
    need = {2: ("A1", "B1"), 4: ("a0x", "b0x")}.get(n, ())
    for k in need:
        if k not in given:
            r.problems.append(f"pivots.{k}: missing; {n} positions need "
                              f"{quoted(need)}")
    if n == 3:
        for side in "AB":
            if (f"{side}0" in given) == (f"{side}1" in given):
                r.problems.append(f"pivots: give exactly one of {side}0 (fixed pivot) and "
                                  f"{side}1 (moving pivot in position 1)")


def _transmission_limit(r: _Reader, task: Task, search: dict, A: float) -> None:
    """``search.min_transmission_angle`` of a motion, function or path task, if given: an
    angle from 0 up to (not including) a right angle, checked in the file's unit and kept in
    rad among the arguments of the task's synthesis."""
    if "min_transmission_angle" not in search:
        return
    where = "search.min_transmission_angle"
    value = r.number(where, search["min_transmission_angle"], A)
    if value is not None and not 0.0 <= value < math.pi / 2:
        r.problems.append(f"{where}: expected an angle from 0 to {math.pi / 2 / A:g} "
                          f"{task.angle_unit} (not included), got "
                          f"{describe(search['min_transmission_angle'])} {task.angle_unit}")
        value = None
    args = task.function if task.kind == "function" else task.search
    args["min_transmission_angle"] = value


def _function_task(r: _Reader, task: Task, L: float, A: float) -> None:
    keys = {"expression", "x_range", "input_range", "output_range", "points", "ground",
            "samples", "pairs", "O2", "O4"}
    r.unknown("function", keys)
    r.unknown("search", {"min_transmission_angle"})
    if isinstance(r.data.get("search"), dict):
        _transmission_limit(r, task, r.data["search"], A)
    f = dict(r.data.get("function", {})) if isinstance(r.data.get("function"), dict) else {}
    if "samples" in f:
        task.function["samples"] = r.integer("function.samples", f["samples"], 2, MAX_SAMPLES)
    if "pairs" in f:
        _pairs_task(r, task, f, L, A)
        return
    for key in ("O2", "O4"):
        if key in f:
            r.problems.append(f"function.{key}: used only with pairs (a function given by its "
                              "formula has O2 at the origin and O4 at (ground, 0))")
    expr = f.get("expression")
    if not isinstance(expr, str):
        r.problems.append(f"function.expression: expected a formula in x such as 'log10(x)', "
                          f"got {describe(expr)}")
    else:
        try:
            task.function["f"] = _formula(expr)
        except ModelError as exc:
            r.problems.extend(exc.problems)
    for key, scale, unit in (("x_range", 1.0, ""), ("input_range", A, task.angle_unit),
                             ("output_range", A, task.angle_unit)):
        value = r.array(f"function.{key}", f.get(key), (2,), scale)
        if value is not None and value[0] == value[1]:
            # in the file's units: the SI values would show radians where degrees were written
            r.problems.append(f"function.{key}: expected two different numbers (start, end), "
                              f"got {describe(f[key])}{' ' + unit if unit else ''}")
            value = None
        task.function[key] = value
    if "points" in f:
        p = f["points"]
        task.function["points"] = (r.integer("function.points", p, 2, MAX_PRECISION_POINTS)
                                   if isinstance(p, int) else r.array("function.points", p, (None,)))
    if "ground" in f:
        # the ground length is in the file's length unit
        ground = r.number("function.ground", f["ground"], L, positive=True)
        if ground is not None and (why := length_problem(ground)):
            r.problems.append(f"function.ground: {why}, got {describe(f['ground'])}")
        task.function["ground"] = ground


def _pairs_task(r: _Reader, task: Task, f: dict, L: float, A: float) -> None:
    """A function task given by its precision points as (input, output) angle pairs, with
    the fixed pivots O2 and O4 (default (0, 0) and (ground, 0))."""
    for key in ("expression", "x_range", "input_range", "output_range", "points"):
        if key in f:
            r.problems.append(f"function.{key}: not used with pairs (the pairs are the precision "
                              "points); give either pairs or a formula with its ranges")
    pairs = f["pairs"]
    if isinstance(pairs, list) and not 3 <= len(pairs) <= MAX_PRECISION_POINTS:
        r.problems.append(f"function.pairs: expected 3 to {MAX_PRECISION_POINTS} pairs (input "
                          f"angle, output angle), got {len(pairs):,}")
        return
    value = r.array("function.pairs", pairs, (None, 2), A)
    if value is not None:
        task.function["input_angles"], task.function["output_angles"] = value[:, 0], value[:, 1]
    ground = 1.0
    if "ground" in f:
        if "O2" in f or "O4" in f:
            r.problems.append("function.ground: not used with O2 and O4 (their distance is the "
                              "ground); give either ground or the pivots")
        else:
            ground = r.number("function.ground", f["ground"], L, positive=True)
            if ground is not None and (why := length_problem(ground)):
                r.problems.append(f"function.ground: {why}, got {describe(f['ground'])}")
    for key, default in (("O2", (0.0, 0.0)), ("O4", (ground or 1.0, 0.0))):
        task.function[key] = (r.lengths(f"function.{key}", f[key], (2,), L) if key in f
                              else np.array(default))


def _pairs_function(task: Task):
    """The function a pairs task prescribes between its pairs: the straight line joining
    neighbouring pairs (input angle to output angle, rad)."""
    t_in, t_out = task.function["input_angles"], task.function["output_angles"]
    order = np.argsort(t_in)
    return lambda x: np.interp(x, t_in[order], t_out[order])


def _formula(expr: str):
    """A vectorised function of x from a formula, parsed with the whitelist of model-file
    expressions: a task file never executes code."""
    from kinelab._expressions import parse_function
    return parse_function(expr, "x", where="function.expression")


def _path_task(r: _Reader, task: Task, L: float, A: float) -> None:
    r.unknown("positions", {"points"})
    r.unknown("search", {"runs", "maxiter", "popsize", "samples", "seed",
                         "min_transmission_angle", "refine", "tolerance"})
    pts = r.get("positions", "points")
    if isinstance(pts, list) and not 3 <= len(pts) <= MAX_PATH_POINTS:
        # counted before any work: the search's time and memory grow with the number of points
        r.problems.append(f"positions.points: expected 3 to {MAX_PATH_POINTS} points (x, y), got "
                          f"{len(pts):,}; a path is given by 5 to 20 points as a rule, so "
                          "keep the points that matter or space them out")
    else:
        task.targets = r.lengths("positions.points", pts, (None, 2), L)
    s = dict(r.data.get("search", {})) if isinstance(r.data.get("search"), dict) else {}
    s.pop("min_transmission_angle", None)
    task.search = s
    _transmission_limit(r, task, r.data.get("search", {}) if isinstance(r.data.get("search"),
                                                                          dict) else {}, A)
    for key, (low, high) in _SEARCH_BOUNDS.items():
        if key in s:
            s[key] = r.integer(f"search.{key}", s[key], low, high)
    if "tolerance" in s:
        s["tolerance"] = r.number("search.tolerance", s["tolerance"], positive=True)
    if "refine" in s and not isinstance(s["refine"], bool):
        r.problems.append(f"search.refine: expected true or false, got {describe(s['refine'])}")


def _design_task(r: _Reader, task: Task, L: float, A: float) -> None:
    """A crank-rocker or quick-return task: its section's values in SI."""
    section = task.kind.replace("-", "_")
    keys = _DESIGN_KEYS[section]
    r.unknown(section, set(keys))
    sec = r.data.get(section)
    if not isinstance(sec, dict):
        r.problems.append(f"{section}: missing; a {task.kind} task gives its values in a "
                          f"[{section}] table")
        return
    mechanism = "crank-rocker"
    if section == "quick_return":
        mechanism = sec.get("mechanism")
        if mechanism not in MECHANISMS:
            r.problems.append(f"quick_return.mechanism: {expected_one_of(mechanism, MECHANISMS)}")
            return
    task.design["mechanism"] = mechanism
    need = _REQUIRED[mechanism]
    usable = set(need) | ({"crank", "pivot_angle"} if mechanism == "crank-rocker" else set()) \
        | ({"rod"} if mechanism in ("offset slider-crank", "whitworth") else set())
    for key, kind in keys.items():
        if key == "mechanism":
            continue
        where = f"{section}.{key}"
        if key not in sec:
            if key in need:
                r.problems.append(f"{where}: missing; a {mechanism} needs {quoted(need)}")
            continue
        if key not in usable:
            r.problems.append(f"{where}: not used by a {mechanism}; it takes "
                              f"{quoted(sorted(usable))}")
            continue
        scale = {"length": L, "angle": A}.get(kind, 1.0)
        value = r.number(where, sec[key], scale)
        if value is not None and kind == "length" and (why := length_problem(value)):
            r.problems.append(f"{where}: {why}, got {describe(sec[key])}")
            continue
        task.design[key] = value


def _design(task: Task) -> list:
    """Run a crank-rocker or quick-return task (SI in, SI out); a problem the synthesis finds
    names the task's field and is worded in the task's units."""
    from kinelab.synthesis import _quick_return as qr

    d = dict(task.design)
    u = task.units
    mechanism = d.pop("mechanism")
    section = task.kind.replace("-", "_")
    try:
        if mechanism == "crank-rocker":
            return [qr._crank_rocker(d["ground"], d["swing"], d["time_ratio"], d.get("crank"),
                                     d.get("pivot_angle"), False, u)]
        if mechanism == "offset slider-crank":
            return [qr._offset_slider_crank(d["stroke"], d["time_ratio"], d.get("rod"), False, u)]
        if mechanism == "whitworth":
            return [qr._whitworth(d["time_ratio"], d["distance"], d["stroke"], d.get("rod"),
                                  False, u)]
        return [synthesis.slotted_lever(d["time_ratio"], d["distance"])]
    except ModelError as exc:
        raise ModelError([f"{section}.{p}" for p in exc.problems], source=task.source or None) from None


# the task file's field of each argument named in the messages of function and path generation
_FUNCTION_FIELDS = {"f": "function.expression", "theta2, theta4": "function.points",
                    "input_range, output_range": "function.input_range, function.output_range",
                    "min_transmission_angle": "search.min_transmission_angle",
                    **{k: f"function.{k}" for k in ("x_range", "input_range", "output_range",
                                                    "points", "ground", "samples")}}
_PAIRS_FIELDS = {"input_angles, output_angles": "function.pairs", "input_angles": "function.pairs",
                 "output_angles": "function.pairs", "theta2, theta4": "function.pairs",
                 "O2": "function.O2", "O4": "function.O4", "samples": "function.samples",
                 "min_transmission_angle": "search.min_transmission_angle"}
_MOTION_FIELDS = {"points": "positions.points", "dyads": "search.dyads",
                  "min_transmission_angle": "search.min_transmission_angle",
                  **{k: f"pivots.{k}" for k in ("A0", "B0", "A1", "B1", "a0x", "b0x", "s", "t")}}
_PATH_FIELDS = {"points": "positions.points",
                **{k: f"search.{k}" for k in ("runs", "maxiter", "popsize", "samples", "seed",
                                              "min_transmission_angle", "refine", "tolerance")}}


def _fields_named(task: Task, exc: ModelError, fields: dict[str, str]) -> ModelError:
    """A synthesis function's ModelError with each problem naming the task file's field."""
    section = task.kind
    problems = []
    for p in exc.problems:
        key, sep, rest = p.partition(": ")
        if sep and key in fields:
            problems.append(f"{fields[key]}: {rest}")
        elif p.startswith(tuple(f"{v.split('.')[0]}." for v in fields.values())):
            problems.append(p)                  # already named so
        else:
            problems.append(f"{section}: {p}")
    return ModelError(problems, source=task.source or None)


_SOLUTIONS = (synthesis.MotionSolution, synthesis.FunctionSolution, synthesis.PathSolution,
              synthesis.CrankRocker, synthesis.QuickReturn)


def _check_task(task: object) -> None:
    if not isinstance(task, Task):
        raise ModelError(f"task: expected a Task (from load_task or read_task), got "
                         f"{describe(task)}")


def solve_task(task: Task, *, verify: bool = False) -> tuple[list, dict[str, Any]]:
    """Run a task: its solutions, and the extra results worth drawing.

    With ``verify``, ``extra["certificate"]`` is the :class:`kinelab.verify.Certificate` of
    every linkage found: each analysed again at every task point and compared with the task
    and with what the synthesis reported (see :func:`kinelab.verify.certify`).
    """
    _check_task(task)
    if not isinstance(verify, bool):
        raise ModelError(f"verify: expected True or False, got {describe(verify)}")
    sols, extra = _solve(task)
    if verify:
        from kinelab.verify import certify_solutions
        extra = {**extra, "certificate": certify_solutions(
            sols, f"{len(sols)} linkage(s) of the {task.kind} task '{task.name}'",
            function=(_pairs_function(task) if "input_angles" in task.function
                      else task.function.get("f")), requested=task.design)}
    return sols, extra


def _solve(task: Task) -> tuple[list, dict[str, Any]]:
    if task.kind == "function" and "input_angles" in task.function:
        try:
            return [_function_pairs(**task.function, shown=task.angle_unit)], {}
        except ModelError as exc:
            raise _fields_named(task, exc, _PAIRS_FIELDS) from exc
    if task.kind == "function":
        try:
            return [_function_generation(**task.function, shown=task.angle_unit)], {}
        except ModelError as exc:
            raise _fields_named(task, exc, _FUNCTION_FIELDS) from exc
    if task.kind == "path":
        try:
            sols = synthesis.path_generation(task.targets, **task.search)
        except ModelError as exc:
            raise _fields_named(task, exc, _PATH_FIELDS) from exc
        return list(sols), {"reason": sols.reason}
    if task.kind in ("crank-rocker", "quick-return"):
        return _design(task), {}
    try:
        return _motion(task)
    except ModelError as exc:
        raise _fields_named(task, exc, _MOTION_FIELDS) from exc


def _motion(task: Task) -> tuple[list, dict[str, Any]]:
    """Run a motion task (2 to n positions)."""
    pos, piv = task.positions, task.pivots
    limit = {k: v for k, v in task.search.items() if k == "min_transmission_angle"}
    if pos.n == 5:
        sols = synthesis.five_positions(pos, **limit)
        return list(sols), {"five": True, "reason": sols.reason}
    if pos.n > 5:
        sols = synthesis.approximate_positions(pos, **task.search)
        return list(sols), {"reason": sols.reason}
    if pos.n == 2:
        fam = synthesis.two_positions(pos, A1=piv["A1"], B1=piv["B1"])
        return [fam.solution(piv.get("s", 0.0), piv.get("t", 0.0), **limit)], {}
    if pos.n == 3:
        return [synthesis.three_positions(pos, A0=piv.get("A0"), B0=piv.get("B0"),
                                          A1=piv.get("A1"), B1=piv.get("B1"), **limit)], {}
    sols = synthesis.four_positions(pos, a0x=piv["a0x"], b0x=piv["b0x"], **limit)
    curves = synthesis.burmester_curves(pos)
    return list(sols), {"curves": curves, "reason": sols.reason}


def _design_row(i: int, s, u: Units) -> dict[str, Any]:
    """A crank-rocker or quick return as plain data, lengths and angles in ``u``."""
    row: dict[str, Any] = {"solution": i, "mechanism": getattr(s, "kind", "crank-rocker"),
                           "lengths": {k: u.convert(v, "m") for k, v in s.lengths.items()},
                           "time_ratio": s.time_ratio,
                           "dead_centres": u.convert(np.asarray(s.dead_centres), "rad").tolist()}
    for key in ("swing", "transmission_min", "pivot_angle"):
        v = getattr(s, key, None)
        if v is not None and not math.isnan(v):
            row[key] = u.convert(v, "rad")
    if getattr(s, "stroke", None) is not None:
        row["stroke"] = u.convert(s.stroke, "m")
    if hasattr(s, "grashof"):
        row["grashof"] = s.grashof.kind
    return row


def _rows(sols: list, u: Units) -> list[dict[str, Any]]:
    """Each solution as plain data, lengths and angles in ``u``."""
    rows = []
    for i, s in enumerate(sols, 1):
        if isinstance(s, (synthesis.CrankRocker, synthesis.QuickReturn)):
            rows.append(_design_row(i, s, u))
            continue
        row: dict[str, Any] = {"solution": i, "valid": s.valid, "defects": list(s.defects),
                               "grashof": s.grashof.kind,
                               "lengths": {k: u.convert(v, "m") for k, v in s.lengths.items()}}
        if hasattr(s, "A0"):
            row.update({k: u.convert(getattr(s, k), "m").tolist() for k in ("A0", "B0", "A1", "B1")})
        if not math.isnan(s.min_transmission_angle):
            row["min_transmission_angle"] = u.convert(s.min_transmission_angle, "rad")
        row["transmission_limit"] = u.convert(s.transmission_limit, "rad")
        row["meets_transmission_limit"] = s.meets_transmission_limit
        if hasattr(s, "rms_error"):
            row["rms_error"] = u.convert(s.rms_error, "m")
        if hasattr(s, "max_structural_error"):
            row["max_structural_error"] = s.max_structural_error
            row["precision_errors"] = s.precision_errors.tolist()
        if hasattr(s, "dyad_residuals") and s.points.shape[0] > 5:
            # least squares: what each position misses by
            row["dyad_residuals"] = u.convert(s.dyad_residuals, "m").tolist()
            row["position_errors"] = u.convert(s.position_errors, "m").tolist()
            row["angle_errors"] = u.convert(s.angle_errors, "rad").tolist()
        rows.append(row)
    return rows


def task_summary(task: Task, solutions: list, extra: dict[str, Any],
                 units: Units | None = None) -> dict[str, Any]:
    """What ``summary.json`` of ``kinelab synth`` holds: the task, its units and each linkage
    found as plain data (pivots, lengths, angles, defects, Grashof class), in ``units``
    (default the task's own).

    ``solutions, extra`` are what :func:`solve_task` returns.
    """
    _check_task(task)
    if isinstance(solutions, (str, bytes)) or not isinstance(solutions, (list, tuple)):
        raise ModelError(f"solutions: expected the list of solutions solve_task returns, got "
                         f"{describe(solutions)}")
    for i, s in enumerate(solutions):
        if not isinstance(s, _SOLUTIONS):
            raise ModelError(f"solutions[{i}]: expected a linkage found by solve_task, got "
                             f"{describe(s)}")
    if not isinstance(extra, Mapping):
        raise ModelError(f"extra: expected the table of extra results solve_task returns, got "
                         f"{describe(extra)}")
    u = task.units if units is None else Units.resolve(units)
    return {"task": task.kind, "name": task.name,
            "units": {"length": u.length, "angle": u.angle},
            "reason": extra.get("reason", ""), "solutions": json_ready(_rows(solutions, u))}

