"""Formulas written as text in files: arithmetic expressions of t, q, q' (force laws) or of
one variable (a function to generate), and tables to interpolate.

A model file never executes code.  An expression is parsed with :mod:`ast` and checked
against a small whitelist (numbers, the names ``t``, ``q``, ``qd``, ``pi``, ``e``, the
operators ``+ - * / ** %``, comparisons, ``a if c else b`` and a fixed set of numpy
functions); the checked tree is turned into nested Python closures over numpy, never
handed to ``eval`` or ``compile``.  Anything else is refused with a message naming the
construct and the place it was found.

Variables, vectorised over N samples:

- ``t`` -- time, s, shape (N,);
- ``q``, ``qd`` -- the input coordinate and its rate when the mechanism has one input
  (rad or m, rad/s or m/s); with several inputs write ``q[0]``, ``qd[1]`` ... (0-based,
  in the order of the model's inputs).
"""
from __future__ import annotations

import ast
import math
import operator
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from kinelab.errors import ModelError

__all__ = ["parse_expression", "parse_function", "parse_table", "to_sympy", "FUNCTIONS"]

MAX_LENGTH = 2000   # characters: a force law is a formula, not a program

FUNCTIONS: dict[str, tuple[Callable, int]] = {
    # name: (numpy function, number of arguments)
    "sin": (np.sin, 1), "cos": (np.cos, 1), "tan": (np.tan, 1),
    "asin": (np.arcsin, 1), "acos": (np.arccos, 1), "atan": (np.arctan, 1),
    "atan2": (np.arctan2, 2), "sinh": (np.sinh, 1), "cosh": (np.cosh, 1),
    "tanh": (np.tanh, 1), "exp": (np.exp, 1), "log": (np.log, 1), "log10": (np.log10, 1),
    "sqrt": (np.sqrt, 1), "abs": (np.abs, 1), "sign": (np.sign, 1), "floor": (np.floor, 1),
    "ceil": (np.ceil, 1), "min": (np.minimum, 2), "max": (np.maximum, 2),
    "hypot": (np.hypot, 2), "clip": (np.clip, 3), "where": (np.where, 3),
}
_CONSTANTS = {"pi": math.pi, "e": math.e}
_BINARY = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
           ast.Div: operator.truediv, ast.Pow: operator.pow, ast.Mod: np.mod}
_UNARY = {ast.USub: operator.neg, ast.UAdd: operator.pos, ast.Not: np.logical_not}
_COMPARE = {ast.Lt: np.less, ast.LtE: np.less_equal, ast.Gt: np.greater,
            ast.GtE: np.greater_equal, ast.Eq: np.equal, ast.NotEq: np.not_equal}
_BOOL = {ast.And: np.logical_and, ast.Or: np.logical_or}
_STATE = ("t", "q", "qd")

_OPERATIONS = ("pi, e, + - * / ** %, comparisons, and/or/not, 'a if c else b' and the "
               "functions " + ", ".join(FUNCTIONS))
ALLOWED = "numbers, t, q, qd (q[i], qd[i] with several inputs), " + _OPERATIONS


class _Env:
    """The state an expression is evaluated at: t (N,), q and qd (N, M)."""

    __slots__ = ("t", "q", "qd")

    def __init__(self, t, q, qd):
        self.t, self.q, self.qd = t, q, qd


def _refuse(where: str, text: str, what: str, variable: str | None = None) -> ModelError:
    allowed = ALLOWED if variable is None else f"numbers, {variable}, {_OPERATIONS}"
    return ModelError(f"{where}: {what} is not allowed in the expression {text!r}; "
                      f"an expression may use {allowed}")


def parse_expression(text: str, *, where: str = "expression") -> Callable[[Any, Any, Any], np.ndarray]:
    """Turn the text of a force law into a function ``f(t, q, qd)`` without executing it.

    Parameters
    ----------
    text : str
        The expression, e.g. ``"-2000 * sin(q)"`` or ``"10 - 0.5 * qd[0]"``.
    where : str
        Where the text comes from (``"dynamics.forces[0].fx"``), for messages.

    Returns
    -------
    callable
        ``f(t, q, qd)`` with ``t`` of shape (N,) and ``q``, ``qd`` of shape (N, M),
        returning an array of shape (N,).

    Raises
    ------
    ModelError
        The text does not parse, or uses anything outside the whitelist.

    Examples
    --------
    >>> f = parse_expression("3 * q + where(t > 1, 2, 0)")
    >>> f(np.array([0.0, 2.0]), np.array([[1.0], [1.0]]), np.zeros((2, 1)))
    array([3., 5.])
    >>> parse_expression("__import__('os')")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    kinelab.errors.ModelError: expression: the function '__import__' is not allowed ...
    """
    tree = _parse(text, where)
    node = _compile(tree.body, where, text)

    def law(t, q, qd):
        return node(_Env(t, q, qd))
    law.text = text
    return law


def parse_function(text: str, variable: str = "x", *, where: str = "expression"
                   ) -> Callable[[Any], np.ndarray]:
    """Turn a formula of one variable into a vectorised function, without executing it.

    Same whitelist as :func:`parse_expression`, with ``variable`` the only name.

    Examples
    --------
    >>> f = parse_function("log10(x) + x**2")
    >>> f(np.array([1.0, 10.0]))
    array([  1., 101.])
    """
    tree = _parse(text, where)
    node = _compile(tree.body, where, text, variable)

    def function(x):
        x = np.asarray(x, float)
        return np.broadcast_to(np.asarray(node(_Env(x, None, None)), float), x.shape)
    function.text = text
    return function


def _parse(text: str, where: str) -> ast.Expression:
    if not isinstance(text, str):
        raise ModelError(f"{where}: expected an expression (text) or a number, got {text!r}")
    if len(text) > MAX_LENGTH:
        raise ModelError(f"{where}: the expression is {len(text)} characters long; a formula "
                         f"is limited to {MAX_LENGTH}; use a table for long laws")
    try:
        return ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ModelError(f"{where}: cannot parse the expression {text!r}: {exc.msg} "
                         f"(column {exc.offset}); check the brackets and operators") from None
    except (RecursionError, MemoryError):
        raise ModelError(f"{where}: the expression {text!r} is nested too deeply") from None


def _compile(node: ast.AST, where: str, text: str, variable: str | None = None
             ) -> Callable[[_Env], Any]:
    """A closure computing ``node``; refuses every node type outside the whitelist.

    With ``variable`` the formula is of that one name (held in ``env.t``) and t, q, qd are
    not allowed.
    """
    c = lambda n: _compile(n, where, text, variable)   # noqa: E731 - local shorthand

    def _refuse_here(what):
        return _refuse(where, text, what, variable)
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            raise _refuse_here(f"the constant {node.value!r}")
        value = float(node.value)
        return lambda env: value
    if isinstance(node, ast.Name):
        if node.id in _CONSTANTS:
            value = _CONSTANTS[node.id]
            return lambda env: value
        if variable is not None:
            if node.id == variable:
                return lambda env: env.t
            raise _refuse_here(f"the name {node.id!r} (the only variable is {variable!r})")
        if node.id == "t":
            return lambda env: env.t
        if node.id in ("q", "qd"):
            name = node.id

            def whole(env):
                a = getattr(env, name)
                if a.shape[1] != 1:
                    raise ModelError(f"{where}: '{name}' in {text!r}: the mechanism has "
                                     f"{a.shape[1]} inputs; write {name}[0] ... {name}[{a.shape[1] - 1}]")
                return a[:, 0]
            return whole
        raise _refuse_here(f"the name {node.id!r}")
    if isinstance(node, ast.Subscript):
        if variable is not None or not (isinstance(node.value, ast.Name)
                                        and node.value.id in ("q", "qd")):
            raise _refuse_here("indexing anything but q or qd")
        index = node.slice
        if not (isinstance(index, ast.Constant) and isinstance(index.value, int)
                and not isinstance(index.value, bool) and index.value >= 0):
            raise _refuse_here("an index that is not a whole number >= 0")
        name, k = node.value.id, index.value

        def column(env):
            a = getattr(env, name)
            if k >= a.shape[1]:
                raise ModelError(f"{where}: {name}[{k}] in {text!r}: the mechanism has "
                                 f"{a.shape[1]} input(s), numbered from 0")
            return a[:, k]
        return column
    if isinstance(node, ast.BinOp):
        op = _BINARY.get(type(node.op))
        if op is None:
            raise _refuse_here(f"the operator {type(node.op).__name__}")
        left, right = c(node.left), c(node.right)
        return lambda env: op(left(env), right(env))
    if isinstance(node, ast.UnaryOp):
        op = _UNARY.get(type(node.op))
        if op is None:
            raise _refuse_here(f"the operator {type(node.op).__name__}")
        operand = c(node.operand)
        return lambda env: op(operand(env))
    if isinstance(node, ast.Compare):
        ops = [_COMPARE.get(type(o)) for o in node.ops]
        if None in ops:
            raise _refuse_here("this comparison")
        terms = [c(node.left)] + [c(n) for n in node.comparators]

        def compare(env):
            values = [f(env) for f in terms]
            out = ops[0](values[0], values[1])
            for op, a, b in zip(ops[1:], values[1:], values[2:]):
                out = np.logical_and(out, op(a, b))
            return out
        return compare
    if isinstance(node, ast.BoolOp):
        op = _BOOL[type(node.op)]
        terms = [c(n) for n in node.values]

        def boolean(env):
            out = terms[0](env)
            for f in terms[1:]:
                out = op(out, f(env))
            return out
        return boolean
    if isinstance(node, ast.IfExp):
        test, body, orelse = c(node.test), c(node.body), c(node.orelse)
        return lambda env: np.where(test(env), body(env), orelse(env))
    if isinstance(node, ast.Call):
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            name = node.func.id if isinstance(node.func, ast.Name) else ast.unparse(node.func)
            raise _refuse_here(f"the function {name!r}")
        if node.keywords:
            raise _refuse_here("a keyword argument")
        fn, nargs = FUNCTIONS[node.func.id]
        if len(node.args) != nargs:
            raise ModelError(f"{where}: {node.func.id}() takes {nargs} argument(s), got "
                             f"{len(node.args)} in {text!r}")
        args = [c(a) for a in node.args]
        return lambda env: fn(*(a(env) for a in args))
    raise _refuse_here(f"{type(node).__name__} ({ast.unparse(node)!r})")


def parse_table(spec: Mapping[str, Any], *, where: str = "table") -> Callable[[Any, Any, Any], np.ndarray]:
    """A force law given as a table, linearly interpolated.

    Parameters
    ----------
    spec : mapping
        ``x`` and ``y`` (equal-length lists of numbers, ``x`` strictly increasing, at least
        two), ``of`` (the expression the table is read at, default ``"q"``) and optionally
        ``period`` (the table repeats with this period in ``of``).  Without a period, a
        value outside ``[x[0], x[-1]]`` is an error rather than a silent extrapolation.
    where : str
        Where the table comes from, for messages.

    Examples
    --------
    >>> f = parse_table({"of": "q", "x": [0.0, 1.0, 2.0], "y": [0.0, 10.0, 0.0]})
    >>> f(np.zeros(2), np.array([[0.5], [1.5]]), np.zeros((2, 1)))
    array([5., 5.])
    """
    if not isinstance(spec, Mapping):
        raise ModelError(f"{where}: expected a table {{of, x, y, period}}, got {spec!r}")
    unknown = set(spec) - {"of", "x", "y", "period"}
    if unknown:
        raise ModelError(f"{where}: unknown key(s) {', '.join(sorted(map(repr, unknown)))}; a table "
                         "has 'of', 'x', 'y' and optionally 'period'")
    problems = []
    try:
        x = np.asarray(spec.get("x"), dtype=float)
        y = np.asarray(spec.get("y"), dtype=float)
    except (TypeError, ValueError):
        raise ModelError(f"{where}: x and y: expected lists of numbers") from None
    if x.ndim != 1 or y.ndim != 1 or x.size != y.size or x.size < 2:
        problems.append(f"{where}: x and y: expected two lists of the same length (at least 2), "
                        f"got {x.size if x.ndim == 1 else x.shape} and {y.size if y.ndim == 1 else y.shape}")
    elif not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        problems.append(f"{where}: x and y: expected finite numbers")
    elif np.any(np.diff(x) <= 0):
        i = int(np.flatnonzero(np.diff(x) <= 0)[0])
        problems.append(f"{where}: x: expected strictly increasing values, got x[{i}] = {x[i]} "
                        f"then x[{i + 1}] = {x[i + 1]}")
    period = spec.get("period")
    if period is not None and not (isinstance(period, (int, float)) and not isinstance(period, bool)
                                   and math.isfinite(period) and period > 0):
        problems.append(f"{where}: period: expected a positive number, got {period!r}")
    if problems:
        raise ModelError(problems)
    of_text = spec.get("of", "q")
    of = parse_expression(of_text, where=f"{where}.of")
    lo, hi = float(x[0]), float(x[-1])

    def table(t, q, qd):
        s = np.asarray(of(t, q, qd), dtype=float)
        if period is not None:
            return np.interp(s, x, y, period=period)
        bad = (s < lo) | (s > hi)
        if np.any(bad):
            v = float(np.asarray(s)[bad][0]) if np.ndim(s) else float(s)
            raise ModelError(f"{where}: {of_text} = {v:.6g} is outside the table [{lo:.6g}, "
                             f"{hi:.6g}]; extend the table or give its period")
        return np.interp(s, x, y)
    return table


def to_sympy(text: str, t, q, qd, *, where: str = "expression"):
    """The sympy form of an expression, for symbolic equations of motion.

    ``t`` is a sympy symbol, ``q`` and ``qd`` sequences of symbols (one per input).  The
    text is checked by :func:`parse_expression` first, so only whitelisted constructs
    reach this walk.

    Examples
    --------
    >>> import sympy as sp
    >>> t, q1, u1 = sp.symbols("t q1 u1")
    >>> to_sympy("2 * sin(q) - 0.5 * qd", t, [q1], [u1])
    -0.5*u1 + 2*sin(q1)
    """
    import sympy as sp

    parse_expression(text, where=where)          # the whitelist
    fn = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "asin": sp.asin, "acos": sp.acos,
          "atan": sp.atan, "atan2": sp.atan2, "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh,
          "exp": sp.exp, "log": sp.log, "log10": lambda x: sp.log(x, 10), "sqrt": sp.sqrt,
          "abs": sp.Abs, "sign": sp.sign, "floor": sp.floor, "ceil": sp.ceiling, "min": sp.Min,
          "max": sp.Max, "hypot": lambda a, b: sp.sqrt(a ** 2 + b ** 2),
          "clip": lambda x, lo, hi: sp.Min(sp.Max(x, lo), hi),
          "where": lambda c, a, b: sp.Piecewise((a, c), (b, True))}
    binary = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
              ast.Div: operator.truediv, ast.Pow: operator.pow, ast.Mod: sp.Mod}
    compare = {ast.Lt: sp.Lt, ast.LtE: sp.Le, ast.Gt: sp.Gt, ast.GtE: sp.Ge, ast.Eq: sp.Eq,
               ast.NotEq: sp.Ne}
    names = {"t": t, "pi": sp.pi, "e": sp.E}
    if len(q) == 1:
        names.update(q=q[0], qd=qd[0])

    def walk(node):
        if isinstance(node, ast.Constant):
            return sp.nsimplify(node.value) if isinstance(node.value, int) else sp.Float(node.value)
        if isinstance(node, ast.Name):
            if node.id not in names:
                raise ModelError(f"{where}: '{node.id}' in {text!r}: the mechanism has {len(q)} inputs; "
                                 f"write {node.id}[0] ... {node.id}[{len(q) - 1}]")
            return names[node.id]
        if isinstance(node, ast.Subscript):
            seq = q if node.value.id == "q" else qd
            if node.slice.value >= len(seq):
                raise ModelError(f"{where}: {node.value.id}[{node.slice.value}] in {text!r}: the "
                                 f"mechanism has {len(seq)} input(s), numbered from 0")
            return seq[node.slice.value]
        if isinstance(node, ast.BinOp):
            return binary[type(node.op)](walk(node.left), walk(node.right))
        if isinstance(node, ast.UnaryOp):
            v = walk(node.operand)
            return {ast.USub: lambda: -v, ast.UAdd: lambda: v, ast.Not: lambda: sp.Not(v)}[type(node.op)]()
        if isinstance(node, ast.Compare):
            terms = [walk(node.left)] + [walk(n) for n in node.comparators]
            return sp.And(*(compare[type(o)](a, b) for o, a, b in zip(node.ops, terms, terms[1:])))
        if isinstance(node, ast.BoolOp):
            return (sp.And if isinstance(node.op, ast.And) else sp.Or)(*(walk(n) for n in node.values))
        if isinstance(node, ast.IfExp):
            return sp.Piecewise((walk(node.body), walk(node.test)), (walk(node.orelse), True))
        return fn[node.func.id](*(walk(a) for a in node.args))      # ast.Call, checked above
    return walk(ast.parse(text.strip(), mode="eval").body)
