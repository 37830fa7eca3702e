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

Numbers are float64 and every operation is numpy's (``1/0`` is inf, never Python's
ZeroDivisionError; ``10**400`` overflows to inf rather than building a big integer);
comparisons, ``and``, ``or`` and ``not`` give 1.0 or 0.0.  The bounds, the same for every
user of expressions (force laws, tables' ``of``, synthesis targets, :func:`to_sympy`):

- at most :data:`MAX_LENGTH` characters and :data:`MAX_PARTS` numbers, names and
  operators (a law is a formula, not a program: a long law belongs in a table);
- at most :data:`MAX_DEPTH` levels of nesting (brackets, function calls, powers, signs; a
  long sum or product is one level);
- a constant exponent of at most :data:`MAX_EXPONENT` in size, and no power towers
  (``a ** b ** c``);
- a part without variables is evaluated when the text is parsed and must be finite (and
  a constant divisor non-zero);
- where the expression is evaluated, a value that is inf or NaN raises a ModelError
  naming the expression and the sample (t, q, qd) where it happened.
"""
from __future__ import annotations

import ast
import functools
import io
import math
import tokenize
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from kinelab.errors import ModelError, describe, one_line, quoted

__all__ = ["parse_expression", "parse_function", "parse_table", "to_sympy", "to_program", "FUNCTIONS",
           "MAX_LENGTH", "MAX_PARTS", "MAX_DEPTH", "MAX_EXPONENT"]

MAX_LENGTH = 10_000   # characters
MAX_PARTS = 1_000     # numbers, names and operators (brackets and commas not counted)
MAX_DEPTH = 100       # levels of brackets, calls, powers and signs
MAX_EXPONENT = 1_000  # size of a constant exponent: 10.0 ** 309 is already inf
_EXACT_BITS = 4096    # to_sympy: a power with a larger exact coefficient uses a float

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
_CONSTANTS = {"pi": np.float64(math.pi), "e": np.float64(math.e)}
_BINARY = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply,
           ast.Div: np.divide, ast.Pow: np.power, ast.Mod: np.mod}
_UNARY = {ast.USub: np.negative, ast.UAdd: np.positive, ast.Not: np.logical_not}
_COMPARE = {ast.Lt: np.less, ast.LtE: np.less_equal, ast.Gt: np.greater,
            ast.GtE: np.greater_equal, ast.Eq: np.equal, ast.NotEq: np.not_equal}
_BOOL = {ast.And: np.logical_and, ast.Or: np.logical_or}
# Left-associative runs of one precedence (a + b - c, a * b / c % d) are one level of
# nesting, read and evaluated in a loop: a long sum is long, not deep.
_CHAIN = {ast.Add: "sum", ast.Sub: "sum", ast.Mult: "product", ast.Div: "product",
          ast.Mod: "product"}
_NOT_COUNTED = {"(", ")", "[", "]", ","}

_OPERATIONS = ("pi, e, + - * / ** %, comparisons, and/or/not, 'a if c else b' and the "
               "functions " + ", ".join(FUNCTIONS))
ALLOWED = "numbers, t, q, qd (q[i], qd[i] with several inputs), " + _OPERATIONS


class _Env:
    """The state an expression is evaluated at: t (N,), q and qd (N, M)."""

    __slots__ = ("t", "q", "qd")

    def __init__(self, t, q, qd):
        self.t, self.q, self.qd = t, q, qd


class _Const:
    """A part without variables, evaluated (in float64) once, when the text is parsed."""

    __slots__ = ("value",)

    def __init__(self, value):
        self.value = value

    def __call__(self, env):
        return self.value


def _float(value):
    """numpy's float64 of a result: booleans become 1.0 and 0.0."""
    return np.asarray(value, dtype=np.float64)[()]


def _place(where: Any) -> str:
    """Where a text comes from, as a message shows it: one line, of bounded length."""
    return one_line(where, 200)


def _states(where: str, t, q, qd) -> _Env:
    """The state a law is evaluated at, checked: t of shape () or (N,), q and qd of shape
    (N, M), real numbers."""
    arrays = [a if a is None else _real(a) for a in (t, q, qd)]
    ok = (all(a is not None for a in arrays) and arrays[0].ndim <= 1
          and arrays[1].ndim == 2 and arrays[1].shape == arrays[2].shape
          and (arrays[0].ndim == 0 or arrays[0].shape[0] == arrays[1].shape[0]))
    if not ok:
        got = ", ".join(f"{n} = {describe(v)}" if a is None else f"{n} of shape {a.shape}"
                        for n, v, a in zip(("t", "q", "qd"), (t, q, qd), arrays))
        raise ModelError(f"{where}: expected real numbers, t of shape () or (N,), q and qd of "
                         f"shape (N, M) (N samples, M inputs), got {got}")
    return _Env(*arrays)


def _real(value) -> np.ndarray | None:
    """``value`` as a float64 array when it holds real numbers only, else None (as
    :func:`kinelab.model.real_array`, which this module sits below)."""
    try:
        a = np.asarray(value)
    except (TypeError, ValueError, OverflowError):
        return None
    return a.astype(np.float64) if a.dtype.kind in "iuf" else None


def _shown(text: str) -> str:
    """The text in a message, shortened so that the message stays one readable line."""
    text = text.strip()
    return repr(text if len(text) <= 80 else text[:72] + " ...")


def _describe(value: float) -> str:
    if math.isnan(value):
        return "nan (an undefined result such as 0/0, sqrt(-1) or log(-1))"
    return f"{value} (an overflow or a division by zero)"


def not_finite(where: str, what: str, values, **state) -> ModelError:
    """The error for ``values`` of shape (), (N,) or (N, k) that are not all finite: the
    first sample that is not, with the state there (``t=``, ``q=``, ``qd=`` or the
    formula's variable)."""
    values = np.asarray(values, dtype=float)
    bad = ~np.isfinite(values)
    k = int(np.argmax(bad.reshape(len(bad), -1).any(axis=1))) if values.ndim else None
    value = float(values[bad][0])

    def shown(name, a):
        a = np.asarray(a, dtype=float)
        row = np.ravel(a if a.ndim == 0 or k is None else a[min(k, len(a) - 1)])
        text = (f"{row[0]:.6g}" if row.size == 1
                else "[" + ", ".join(f"{v:.6g}" for v in row) + "]")
        return f"{name} = {text}" + (" s" if name == "t" else "")
    at = ", ".join(shown(n, a) for n, a in state.items() if a is not None)
    return ModelError(f"{where}: {what} gives {_describe(value)} at {at}; expected a finite "
                      "value; guard it there, for example with where(...) or clip(...)")


def _refuse(where: str, text: str, what: str, variable: str | None = None) -> ModelError:
    allowed = ALLOWED if variable is None else f"numbers, {variable}, {_OPERATIONS}"
    return ModelError(f"{where}: {what} is not allowed in the expression {_shown(text)}; "
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
        returning float64 values of shape (N,) (or () for a constant).  It raises a
        ModelError naming the sample where a value is inf or NaN.

    Raises
    ------
    ModelError
        The text does not parse, uses anything outside the whitelist, goes beyond the
        bounds (:data:`MAX_LENGTH`, :data:`MAX_PARTS`, :data:`MAX_DEPTH`,
        :data:`MAX_EXPONENT`, power towers), or has a part without variables that is
        not finite.

    Examples
    --------
    >>> f = parse_expression("3 * q + where(t > 1, 2, 0)")
    >>> f(np.array([0.0, 2.0]), np.array([[1.0], [1.0]]), np.zeros((2, 1)))
    array([3., 5.])
    >>> parse_expression("__import__('os')")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    kinelab.errors.ModelError: expression: the function '__import__' is not allowed ...
    >>> parse_expression("1 / q")(np.zeros(1), np.zeros((1, 1)), np.zeros((1, 1)))
    Traceback (most recent call last):
    ...
    kinelab.errors.ModelError: expression: the expression '1 / q' gives inf (an overflow or a division by zero) at t = 0 s, q = 0, qd = 0; expected a finite value; guard it there, for example with where(...) or clip(...)
    """
    where = _place(where)
    _, node = _checked(text, where)
    what = f"the expression {_shown(text)}"

    def law(t, q, qd):
        env = _states(where, t, q, qd)
        with np.errstate(all="ignore"):
            out = _float(node(env))
        if not np.all(np.isfinite(out)):
            raise not_finite(where, what, out, t=env.t, q=env.q, qd=env.qd)
        return out
    law.text = text
    return law


def parse_function(text: str, variable: str = "x", *, where: str = "expression"
                   ) -> Callable[[Any], np.ndarray]:
    """Turn a formula of one variable into a vectorised function, without executing it.

    Same whitelist and bounds as :func:`parse_expression`, with ``variable`` the only
    name; a value that is inf or NaN raises a ModelError naming the variable's value.

    Examples
    --------
    >>> f = parse_function("log10(x) + x**2")
    >>> f(np.array([1.0, 10.0]))
    array([  1., 101.])
    """
    where = _place(where)
    _, node = _checked(text, where, variable)
    what = f"the expression {_shown(text)}"

    def function(x):
        a = _real(x)
        if a is None:
            raise ModelError(f"{where}: expected real numbers for {variable}, got {describe(x)}")
        x = a
        with np.errstate(all="ignore"):
            out = np.broadcast_to(_float(node(_Env(x, None, None))), x.shape)
        if not np.all(np.isfinite(out)):
            raise not_finite(where, what, out, **{variable: x})
        return out
    function.text = text
    return function


def _checked(text: str, where: str, variable: str | None = None):
    """The parsed tree of ``text`` and its closure, once every bound and the whitelist
    are checked: what :func:`parse_expression`, :func:`parse_function` and
    :func:`to_sympy` all refuse."""
    if not isinstance(text, str):
        raise ModelError(f"{where}: expected an expression (text) or a number, got {describe(text)}")
    if len(text) > MAX_LENGTH:
        raise ModelError(f"{where}: the expression is {len(text)} characters long; expected at "
                         f"most {MAX_LENGTH}; use a table for a long law")
    source = text.strip()
    parts = _parts(source)
    if parts > MAX_PARTS:
        raise ModelError(f"{where}: the expression {_shown(text)} has {parts} numbers, names and "
                         f"operators; expected at most {MAX_PARTS}; use a table for a long law")
    try:
        tree = ast.parse(source, mode="eval")
    except SyntaxError as exc:
        raise ModelError(f"{where}: cannot parse the expression {_shown(text)}: {exc.msg} "
                         f"(column {exc.offset}); check the brackets and operators") from None
    except (RecursionError, MemoryError):
        tree = None
    depth = MAX_DEPTH + 1 if tree is None else _depth(tree.body)
    if depth > MAX_DEPTH:
        deep = "too deeply" if tree is None else f"{depth} levels deep"
        raise ModelError(f"{where}: the expression {_shown(text)} is nested {deep} (brackets, "
                         f"function calls, powers, signs); expected at most {MAX_DEPTH} levels; "
                         "write it with fewer brackets or as several laws")
    return tree, _Compiler(where, text, source, variable).compile(tree.body)


def _parts(source: str) -> int:
    """How many numbers, names and operators ``source`` has, counted before it is parsed
    (Python's parser recurses once per term of a long sum)."""
    n = 0
    try:
        for tok in tokenize.generate_tokens(io.StringIO(source).readline):
            if tok.type in (tokenize.NAME, tokenize.NUMBER, tokenize.STRING) or (
                    tok.type == tokenize.OP and tok.string not in _NOT_COUNTED):
                n += 1
    except (tokenize.TokenError, SyntaxError):    # unbalanced brackets: ast.parse says so
        pass
    return n


def _depth(root: ast.expr) -> int:
    """Levels of nesting, without recursion; a run of one precedence is one level."""
    deepest, stack = 0, [(root, 1)]
    while stack:
        node, d = stack.pop()
        deepest = max(deepest, d)
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.expr):
                same = (isinstance(node, ast.BinOp) and child is node.left
                        and isinstance(child, ast.BinOp) and _CHAIN.get(type(child.op)) is not None
                        and _CHAIN.get(type(child.op)) == _CHAIN.get(type(node.op)))
                stack.append((child, d if same else d + 1))
    return deepest


def _chain(node: ast.BinOp) -> tuple[ast.expr, list[ast.BinOp]]:
    """The first operand of the run of one precedence ending at ``node`` and the BinOps
    applying the others, innermost first: ``a - b + c`` is ``a``, [``a - b``, ``... + c``]."""
    kind, links = _CHAIN[type(node.op)], []
    while isinstance(node, ast.BinOp) and _CHAIN.get(type(node.op)) == kind:
        links.append(node)
        node = node.left
    return node, links[::-1]


def _exponent(node: ast.BinOp) -> ast.expr:
    """The exponent of a power, under its signs."""
    e = node.right
    while isinstance(e, ast.UnaryOp) and isinstance(e.op, (ast.USub, ast.UAdd)):
        e = e.operand
    return e


def _boolean(node: ast.expr) -> bool:
    return isinstance(node, (ast.Compare, ast.BoolOp)) or (
        isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not))


class _Compiler:
    """Turns a checked tree into closures; refuses every node type outside the whitelist
    and evaluates the parts without variables once, in float64.

    With ``variable`` the formula is of that one name (held in ``env.t``) and t, q, qd are
    not allowed.
    """

    def __init__(self, where: str, text: str, source: str, variable: str | None):
        self.where, self.text, self.source, self.variable = where, text, source, variable

    def refuse(self, what: str) -> ModelError:
        return _refuse(self.where, self.text, what, self.variable)

    def part(self, node: ast.AST, noun: str = "the part") -> str:
        """How a message names a part of the expression: ``the part '1/0' in the
        expression 'q + 1/0'``, or ``the expression '1/0'`` when it is the whole."""
        segment = ast.get_source_segment(self.source, node) or ""
        if segment == self.source:
            return f"{'the expression' if noun == 'the part' else noun} {_shown(self.text)}"
        return f"{noun} {_shown(segment)} in the expression {_shown(self.text)}"

    def fold(self, node: ast.AST, fn: Callable, *values) -> _Const:
        """``fn(*values)`` now, as a constant; refused unless finite."""
        with np.errstate(all="ignore"):
            value = _float(fn(*values))
        if not np.isfinite(value):
            raise ModelError(f"{self.where}: {self.part(node)} has no variables and evaluates "
                             f"to {_describe(float(value))} in float64; expected a finite "
                             "number (float64 reaches 1.8e308); correct the numbers")
        return _Const(value)

    def apply(self, node: ast.AST, fn: Callable, args: list) -> Callable[[_Env], Any]:
        """``fn`` of the closures ``args``: folded when none has variables."""
        if all(isinstance(a, _Const) for a in args):
            return self.fold(node, fn, *(a.value for a in args))
        if len(args) == 1:
            a, = args
            return lambda env: fn(a(env))
        if len(args) == 2:
            a, b = args
            return lambda env: fn(a(env), b(env))
        return lambda env: fn(*[a(env) for a in args])

    def compile(self, node: ast.AST) -> Callable[[_Env], Any]:
        c, variable = self.compile, self.variable
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise self.refuse(f"the constant {node.value!r}")
            try:
                value = np.float64(node.value)
            except OverflowError:
                value = np.float64(np.inf)
            if not np.isfinite(value):
                raise ModelError(f"{self.where}: {self.part(node, 'the number')} is beyond float64; "
                                 "expected a size of at most 1.8e308; correct the number")
            return _Const(value)
        if isinstance(node, ast.Name):
            if node.id in _CONSTANTS:
                return _Const(_CONSTANTS[node.id])
            if variable is not None:
                if node.id == variable:
                    return lambda env: env.t
                raise self.refuse(f"the name {node.id!r} (the only variable is {variable!r})")
            if node.id == "t":
                return lambda env: env.t
            if node.id in ("q", "qd"):
                return self.state(node.id, None)
            raise self.refuse(f"the name {node.id!r}")
        if isinstance(node, ast.Subscript):
            if variable is not None or not (isinstance(node.value, ast.Name)
                                            and node.value.id in ("q", "qd")):
                raise self.refuse("indexing anything but q or qd")
            index = node.slice
            if not (isinstance(index, ast.Constant) and isinstance(index.value, int)
                    and not isinstance(index.value, bool) and index.value >= 0):
                raise self.refuse("an index that is not a whole number >= 0")
            return self.state(node.value.id, index.value)
        if isinstance(node, ast.BinOp):
            if type(node.op) not in _BINARY:
                raise self.refuse(f"the operator {type(node.op).__name__}")
            if isinstance(node.op, ast.Pow):
                return self.power(node)
            first, links = _chain(node)
            value = c(first)
            rest = []
            for link in links:
                op, right = _BINARY[type(link.op)], c(link.right)
                if (isinstance(link.op, (ast.Div, ast.Mod)) and isinstance(right, _Const)
                        and right.value == 0):
                    raise ModelError(f"{self.where}: division by zero in {self.part(link)}: the "
                                     "divisor is a constant 0; expected a non-zero divisor")
                if not rest and isinstance(value, _Const) and isinstance(right, _Const):
                    value = self.fold(link, op, value.value, right.value)
                else:
                    rest.append((op, right))
            if not rest:
                return value
            if len(rest) == 1:
                (op, right), = rest
                return lambda env: op(value(env), right(env))

            def run(env):
                out = value(env)
                for op, right in rest:
                    out = op(out, right(env))
                return out
            return run
        if isinstance(node, ast.UnaryOp):
            op = _UNARY.get(type(node.op))
            if op is None:
                raise self.refuse(f"the operator {type(node.op).__name__}")
            if isinstance(node.op, ast.Not):
                return self.apply(node, lambda a: _float(np.logical_not(a)), [c(node.operand)])
            return self.apply(node, op, [c(node.operand)])
        if isinstance(node, ast.Compare):
            ops = [_COMPARE.get(type(o)) for o in node.ops]
            if None in ops:
                raise self.refuse("this comparison")

            def compare(*values):
                out = ops[0](values[0], values[1])
                for op, a, b in zip(ops[1:], values[1:], values[2:]):
                    out = np.logical_and(out, op(a, b))
                return _float(out)
            return self.apply(node, compare, [c(node.left)] + [c(n) for n in node.comparators])
        if isinstance(node, ast.BoolOp):
            op = _BOOL[type(node.op)]

            def boolean(*values):
                out = values[0]
                for v in values[1:]:
                    out = op(out, v)
                return _float(out)
            return self.apply(node, boolean, [c(n) for n in node.values])
        if isinstance(node, ast.IfExp):
            return self.apply(node, np.where, [c(node.test), c(node.body), c(node.orelse)])
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
                name = (node.func.id if isinstance(node.func, ast.Name)
                        else ast.get_source_segment(self.source, node.func))
                raise self.refuse(f"the function {name!r}")
            if node.keywords:
                raise self.refuse("a keyword argument")
            fn, nargs = FUNCTIONS[node.func.id]
            if len(node.args) != nargs:
                raise ModelError(f"{self.where}: {node.func.id}() takes {nargs} argument(s), got "
                                 f"{len(node.args)} in {_shown(self.text)}")
            return self.apply(node, fn, [c(a) for a in node.args])
        segment = ast.get_source_segment(self.source, node) or ""
        raise self.refuse(f"{type(node).__name__} ({segment[:60]!r})")

    def power(self, node: ast.BinOp) -> Callable[[_Env], Any]:
        if isinstance(_exponent(node), ast.BinOp) and isinstance(_exponent(node).op, ast.Pow):
            raise ModelError(f"{self.where}: {self.part(node, 'the power tower')} is not "
                             "allowed (a ** b ** c, also with the exponent bracketed); expected "
                             "a number, a name or a bracketed term with no power in it as the "
                             "exponent; write the exponent b ** c out as a number, bracket the "
                             "base if (a ** b) ** c was meant, or write exp(log(a) * b ** c)")
        base, exponent = self.compile(node.left), self.compile(node.right)
        if isinstance(exponent, _Const) and not abs(exponent.value) <= MAX_EXPONENT:
            raise ModelError(f"{self.where}: the exponent {exponent.value:g} of "
                             f"{self.part(node, 'the power')} is too large; expected a constant "
                             f"exponent of at most {MAX_EXPONENT} in size; rescale the quantity "
                             "raised to it")
        return self.apply(node, np.power, [base, exponent])

    def state(self, name: str, k: int | None) -> Callable[[_Env], Any]:
        """``q`` or ``qd`` of a one-input mechanism (``k`` None), or column ``k``."""
        where, text = self.where, _shown(self.text)

        def column(env):
            a = getattr(env, name)
            if k is None:
                if a.shape[1] != 1:
                    raise ModelError(f"{where}: '{name}' in {text}: the mechanism has "
                                     f"{a.shape[1]} inputs; write {name}[0] ... {name}[{a.shape[1] - 1}]")
                return a[:, 0]
            if k >= a.shape[1]:
                raise ModelError(f"{where}: {name}[{k}] in {text}: the mechanism has "
                                 f"{a.shape[1]} input(s), numbered from 0")
            return a[:, k]
        return column


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
    where = _place(where)
    if not isinstance(spec, Mapping):
        raise ModelError(f"{where}: expected a table {{of, x, y, period}}, got {describe(spec)}")
    unknown = set(spec) - {"of", "x", "y", "period"}
    if unknown:
        raise ModelError(f"{where}: unknown key(s) {quoted(sorted(unknown, key=str))}; a table "
                         "has 'of', 'x', 'y' and optionally 'period'")
    problems = []
    x, y = _real(spec.get("x")), _real(spec.get("y"))
    if x is None or y is None:
        raise ModelError(f"{where}: x and y: expected lists of real numbers, got "
                         f"{describe(spec.get('x'))} and {describe(spec.get('y'))}")
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
    p = None if isinstance(period, bool) else _real(period)
    if period is not None and not (p is not None and p.ndim == 0 and math.isfinite(p) and p > 0):
        problems.append(f"{where}: period: expected a positive number, got {describe(period)}")
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



# The instructions of a program (see to_program): the stack machine that runs them is
# kinelab.dynamics._kernel.run_law.  Each is a row (code, argument).
OP_CONST, OP_T, OP_Q, OP_QD = 0, 1, 2, 3          # push constants[arg], t, q[arg], qd[arg]
OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_POW, OP_MOD = 4, 5, 6, 7, 8, 9
OP_NEG, OP_NOT, OP_AND, OP_OR = 10, 11, 12, 13
OP_LT, OP_LE, OP_GT, OP_GE, OP_EQ, OP_NE = 14, 15, 16, 17, 18, 19
OP_WHERE = 20                                    # c, a, b -> a if c != 0 else b
OP_FUNCTION = 21                                 # arg: the index in PROGRAM_FUNCTIONS
PROGRAM_FUNCTIONS = tuple(FUNCTIONS)
_PROGRAM_BINARY = {ast.Add: OP_ADD, ast.Sub: OP_SUB, ast.Mult: OP_MUL, ast.Div: OP_DIV,
                   ast.Pow: OP_POW, ast.Mod: OP_MOD}
_PROGRAM_COMPARE = {ast.Lt: OP_LT, ast.LtE: OP_LE, ast.Gt: OP_GT, ast.GtE: OP_GE,
                    ast.Eq: OP_EQ, ast.NotEq: OP_NE}


@functools.lru_cache(maxsize=256)   # a batch with a model per run asks for each law once a run
def to_program(text: str, M: int, *, where: str = "expression"
               ) -> tuple[np.ndarray, np.ndarray] | None:
    """The expression as a program for a stack machine: a compiled kernel evaluates it
    without Python (forward dynamics calls a law at every step).

    The text is checked as :func:`parse_expression` checks it, and its parts without
    variables are folded by the same numpy arithmetic; the rest is postfix code over
    float64 with the same meaning (numpy's ``mod``, comparisons and ``and``/``or`` giving
    1.0 or 0.0, ``where`` evaluating both branches).

    Returns
    -------
    (code, constants) : ndarray (n, 2) of int64, ndarray of float64
        Rows ``(op, argument)`` (the ``OP_*`` codes of this module) and the constants
        they push (read-only: the result is kept for the next call); None when the text
        names ``q`` or ``qd`` in a way that does not fit ``M`` inputs (a bare ``q`` with
        several inputs, an index past the last), which :func:`parse_expression` reports
        when evaluated.

    Examples
    --------
    >>> code, constants = to_program("2 * q + 1", 1)
    >>> code.tolist(), constants.tolist()
    ([[0, 0], [2, 0], [6, 0], [0, 1], [4, 0]], [2.0, 1.0])
    """
    where = _place(where)
    tree, _ = _checked(text, where)
    compiler = _Compiler(where, text, text.strip(), None)
    code: list[tuple[int, int]] = []
    constants: list[float] = []

    def const(value):
        code.append((OP_CONST, len(constants)))
        constants.append(float(value))

    def emit(node):
        if not isinstance(node, (ast.Constant, ast.Name, ast.Subscript)):
            folded = compiler.compile(node)
            if isinstance(folded, _Const):
                return const(folded.value)
        if isinstance(node, ast.Constant):
            return const(compiler.compile(node).value)
        if isinstance(node, ast.Name):
            if node.id in _CONSTANTS:
                return const(_CONSTANTS[node.id])
            if node.id == "t":
                return code.append((OP_T, 0))
            if M != 1:
                raise _DoesNotFit
            return code.append((OP_Q if node.id == "q" else OP_QD, 0))
        if isinstance(node, ast.Subscript):
            if node.slice.value >= M:
                raise _DoesNotFit
            return code.append((OP_Q if node.value.id == "q" else OP_QD, node.slice.value))
        if isinstance(node, ast.BinOp):
            if isinstance(node.op, ast.Pow):
                emit(node.left)
                emit(node.right)
                return code.append((OP_POW, 0))
            first, links = _chain(node)
            emit(first)
            for link in links:
                emit(link.right)
                code.append((_PROGRAM_BINARY[type(link.op)], 0))
            return None
        if isinstance(node, ast.UnaryOp):
            emit(node.operand)
            if isinstance(node.op, ast.USub):
                code.append((OP_NEG, 0))
            elif isinstance(node.op, ast.Not):
                code.append((OP_NOT, 0))
            return None
        if isinstance(node, ast.Compare):
            terms = [node.left] + list(node.comparators)
            for i, (op, a, b) in enumerate(zip(node.ops, terms, terms[1:])):
                emit(a)
                emit(b)
                code.append((_PROGRAM_COMPARE[type(op)], 0))
                if i:
                    code.append((OP_AND, 0))
            return None
        if isinstance(node, ast.BoolOp):
            emit(node.values[0])
            for v in node.values[1:]:
                emit(v)
                code.append((OP_AND if isinstance(node.op, ast.And) else OP_OR, 0))
            return None
        if isinstance(node, ast.IfExp):
            for part in (node.test, node.body, node.orelse):
                emit(part)
            return code.append((OP_WHERE, 0))
        for a in node.args:                          # ast.Call, checked by _checked
            emit(a)
        if node.func.id == "where":
            return code.append((OP_WHERE, 0))
        return code.append((OP_FUNCTION, PROGRAM_FUNCTIONS.index(node.func.id)))

    try:
        emit(tree.body)
    except _DoesNotFit:
        return None
    program = np.array(code, np.int64).reshape(-1, 2), np.array(constants, np.float64)
    for a in program:
        a.flags.writeable = False
    return program


class _DoesNotFit(Exception):
    """A name of the state that the number of inputs does not have."""


def to_sympy(text: str, t, q, qd, *, where: str = "expression"):
    """The sympy form of an expression, for symbolic equations of motion.

    ``t`` is a sympy symbol, ``q`` and ``qd`` sequences of symbols (one per input).  The
    text is checked as :func:`parse_expression` checks it (same whitelist, same bounds,
    same messages), so only bounded, whitelisted constructs reach this walk.  Integers
    stay exact unless a power of them would exceed a few thousand bits; comparisons used
    as numbers are 1 or 0, as in :func:`parse_expression`.

    Examples
    --------
    >>> import sympy as sp
    >>> t, q1, u1 = sp.symbols("t q1 u1")
    >>> to_sympy("2 * sin(q) - 0.5 * qd", t, [q1], [u1])
    -0.5*u1 + 2*sin(q1)
    >>> to_sympy("-500 * (q > 0)", t, [q1], [u1])
    -500*Piecewise((1, q1 > 0), (0, True))
    """
    import sympy as sp
    where = _place(where)

    tree, _ = _checked(text, where)
    shown = _shown(text)

    def power(base, exponent):
        # Exact integers stay small: a large coefficient is raised as a float.
        coeff, rest = base.as_coeff_Mul()
        if exponent.is_Number and coeff.is_Rational and abs(exponent) * max(
                abs(coeff.p).bit_length(), coeff.q.bit_length()) > _EXACT_BITS:
            base = sp.Float(coeff) * rest
        return base ** exponent
    fn = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "asin": sp.asin, "acos": sp.acos,
          "atan": sp.atan, "atan2": sp.atan2, "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh,
          "exp": sp.exp, "log": sp.log, "log10": lambda x: sp.log(x, 10), "sqrt": sp.sqrt,
          "abs": sp.Abs, "sign": sp.sign, "floor": sp.floor, "ceil": sp.ceiling, "min": sp.Min,
          "max": sp.Max, "hypot": lambda a, b: sp.sqrt(power(a, sp.Integer(2)) + power(b, sp.Integer(2))),
          "clip": lambda x, lo, hi: sp.Min(sp.Max(x, lo), hi),
          "where": lambda c, a, b: sp.Piecewise((a, c), (b, True))}
    binary = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b,
              ast.Mult: lambda a, b: a * b, ast.Div: lambda a, b: a / b, ast.Pow: power,
              ast.Mod: sp.Mod}
    compare = {ast.Lt: sp.Lt, ast.LtE: sp.Le, ast.Gt: sp.Gt, ast.GtE: sp.Ge, ast.Eq: sp.Eq,
               ast.NotEq: sp.Ne}
    names = {"t": t, "pi": sp.pi, "e": sp.E}
    if len(q) == 1:
        names.update(q=q[0], qd=qd[0])

    def number(node):             # a condition used as a number is 1 or 0
        v = walk(node)
        return sp.Piecewise((1, v), (0, True)) if _boolean(node) else v

    def truth(node):              # a number used as a condition is true when non-zero
        v = walk(node)
        return v if _boolean(node) else sp.Ne(v, 0)

    def walk(node):
        if isinstance(node, ast.Constant):
            return sp.Integer(node.value) if isinstance(node.value, int) else sp.Float(node.value)
        if isinstance(node, ast.Name):
            if node.id not in names:
                raise ModelError(f"{where}: '{node.id}' in {shown}: the mechanism has {len(q)} inputs; "
                                 f"write {node.id}[0] ... {node.id}[{len(q) - 1}]")
            return names[node.id]
        if isinstance(node, ast.Subscript):
            seq = q if node.value.id == "q" else qd
            if node.slice.value >= len(seq):
                raise ModelError(f"{where}: {node.value.id}[{node.slice.value}] in {shown}: the "
                                 f"mechanism has {len(seq)} input(s), numbered from 0")
            return seq[node.slice.value]
        if isinstance(node, ast.BinOp):
            if isinstance(node.op, ast.Pow):
                return power(number(node.left), number(node.right))
            first, links = _chain(node)
            out = number(first)
            for link in links:
                out = binary[type(link.op)](out, number(link.right))
            return out
        if isinstance(node, ast.UnaryOp):
            if isinstance(node.op, ast.Not):
                return sp.Not(truth(node.operand))
            v = number(node.operand)
            return -v if isinstance(node.op, ast.USub) else v
        if isinstance(node, ast.Compare):
            terms = [number(node.left)] + [number(n) for n in node.comparators]
            return sp.And(*(compare[type(o)](a, b) for o, a, b in zip(node.ops, terms, terms[1:])))
        if isinstance(node, ast.BoolOp):
            return (sp.And if isinstance(node.op, ast.And) else sp.Or)(*(truth(n) for n in node.values))
        if isinstance(node, ast.IfExp):
            return sp.Piecewise((number(node.body), truth(node.test)), (number(node.orelse), True))
        args = [truth(a) if node.func.id == "where" and i == 0 else number(a)   # ast.Call
                for i, a in enumerate(node.args)]
        return fn[node.func.id](*args)
    try:
        return number(tree.body)
    except ZeroDivisionError:     # sympy found a divisor that is 0 whatever the state
        raise ModelError(f"{where}: the expression {shown} divides by a term that is always 0; "
                         "expected a non-zero divisor") from None
