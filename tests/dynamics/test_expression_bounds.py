"""Expressions are evaluated with bounded numbers, depth and exponent, in numpy's float64;
every problem is a ModelError naming the field, never Python's arithmetic errors."""
import functools
import re
import subprocess
import sys
import textwrap
import time
from typing import Callable, NamedTuple

import numpy as np
import pytest
import sympy as sp
from hypothesis import event, given
from hypothesis import strategies as st

from kinelab._expressions import (MAX_DEPTH, MAX_EXPONENT, MAX_LENGTH, MAX_PARTS, parse_expression,
                                  parse_function, to_sympy)
from kinelab.errors import ModelError

WHERE = "dynamics.torques[0].torque"
W = re.escape(WHERE)      # in patterns
T = np.array([0.0, 0.5, 1.0, 2.0])
Q = np.array([[0.0], [1.0], [-2.0], [0.3]])
QD = np.array([[1.0], [0.0], [3.0], [-0.7]])
SYMBOLS = sp.symbols("t q1 u1")


def evaluate(text):
    return parse_expression(text, where=WHERE)(T, Q, QD)


def sympy_form(text):
    t, q1, u1 = SYMBOLS
    return to_sympy(text, t, [q1], [u1], where=WHERE)


# -- the bounds -----------------------------------------------------------------------------

def test_a_long_sum_is_refused_with_a_model_error():
    text = "+".join(["1"] * 900)            # 1799 numbers and operators, within the length
    assert len(text) <= MAX_LENGTH
    with pytest.raises(ModelError, match=rf"^{W}: the expression '1\+1\+1.* \.\.\.' has 1799 numbers, "
                                         rf"names and operators; expected at most {MAX_PARTS}; use a "
                                         "table for a long law$"):
        parse_expression(text, where=WHERE)


def test_a_long_sum_within_the_bounds_is_one_level_deep():
    terms = 500                              # 999 names and operators, 500 levels of ast
    expected = Q[:, 0]
    for _ in range(terms - 1):
        expected = expected + Q[:, 0]
    np.testing.assert_array_equal(evaluate(" + ".join(["q"] * terms)), expected)
    alternating = "q" + "".join(f" {'-' if k % 2 else '+'} {k} * t" for k in range(1, 250))
    expected = Q[:, 0].copy()
    for k in range(1, 250):                  # left to right, as written
        expected = expected - k * T if k % 2 else expected + k * T
    np.testing.assert_array_equal(evaluate(alternating), expected)
    assert sp.expand(sympy_form(alternating) - (SYMBOLS[1] - 125 * SYMBOLS[0])) == 0


def test_nesting_is_bounded():
    def nested(levels):                      # levels - 1 calls around q
        return "sin(" * (levels - 1) + "q" + ")" * (levels - 1)
    expected = Q[:, 0]
    for _ in range(MAX_DEPTH - 1):
        expected = np.sin(expected)
    np.testing.assert_array_equal(evaluate(nested(MAX_DEPTH)), expected)
    for text, levels in ((nested(MAX_DEPTH + 1), MAX_DEPTH + 1), ("-" * 150 + "q", 151)):
        with pytest.raises(ModelError, match=rf"^{W}: the expression '.*' is nested {levels} "
                                             r"levels deep \(brackets, function calls, powers, signs\); "
                                             rf"expected at most {MAX_DEPTH} levels"):
            parse_expression(text, where=WHERE)


@pytest.mark.parametrize("text, message", [
    ("1/0", r"division by zero in the expression '1/0': the divisor is a constant 0; expected a "
            r"non-zero divisor"),
    ("q % (2 - 2)", r"division by zero in the expression 'q % \(2 - 2\)'"),
    ("q + 3 / 0.0", r"division by zero in the part '3 / 0.0' in the expression 'q \+ 3 / 0.0'"),
    ("10**400", r"the expression '10\*\*400' has no variables and evaluates to inf \(an overflow "
                r"or a division by zero\) in float64; expected a finite number"),
    ("q * exp(1000)", r"the part 'exp\(1000\)' in the expression 'q \* exp\(1000\)' has no variables "
                      r"and evaluates to inf"),
    ("sqrt(-1) + t", r"the part 'sqrt\(-1\)' .* evaluates to nan \(an undefined result"),
    ("1e400 * q", r"the number '1e400' in the expression '1e400 \* q' is beyond float64"),
    ("1" + "0" * 400, r"the number '10000.* is beyond float64"),
    ("9**9**9", r"the power tower '9\*\*9\*\*9' is not allowed \(a \*\* b \*\* c, also with the "
                r"exponent bracketed\); expected a number, a name or a bracketed term with no power "
                r"in it as the exponent"),
    ("(qd**2)**(qd**2)", r"the power tower '\(qd\*\*2\)\*\*\(qd\*\*2\)' is not allowed .* or write "
                         r"exp\(log\(a\) \* b \*\* c\)$"),
    ("2 ** -(q ** 2)", r"the power tower '2 \*\* -\(q \*\* 2\)' is not allowed"),
    ("q ** 1000.5", rf"the exponent 1000.5 of the power 'q \*\* 1000.5' is too large; expected a "
                    rf"constant exponent of at most {MAX_EXPONENT} in size"),
    ("t + q ** -(600 * 2)", r"the exponent -1200 of the power 'q \*\* -\(600 \* 2\)' in the expression"),
])
def test_constant_parts_are_float64_and_checked_when_parsed(text, message):
    with pytest.raises(ModelError, match=rf"^{W}: {message}"):
        parse_expression(text, where=WHERE)


def test_limits_themselves_are_allowed():
    np.testing.assert_array_equal(evaluate(f"q ** {MAX_EXPONENT} + 1e308 + 5e-324"),
                                  Q[:, 0] ** 1000 + 1e308 + 5e-324)
    assert evaluate("2 ** 1000 / 2 ** 999") == 2.0
    assert evaluate("1.7976931348623157e308") == np.finfo(float).max
    assert evaluate("(2 ** 3) ** 2") == 64.0    # a bracketed base is no tower


@pytest.mark.parametrize("text, at", [
    ("1 / (q - 1)", r"gives inf \(an overflow or a division by zero\) at t = 0.5 s, q = 1, qd = 0"),
    ("exp(1000 * qd)", r"gives inf .* at t = 0 s, q = 0, qd = 1"),
    ("log(q + 1)", r"gives nan \(an undefined result .*\) at t = 1 s, q = -2, qd = 3"),
    ("q * 1e308 * 10", r"gives inf .* at t = 0.5 s, q = 1, qd = 0"),
])
def test_values_that_are_not_finite_name_the_sample(text, at):
    f = parse_expression(text, where=WHERE)
    with pytest.raises(ModelError, match=rf"^{W}: the expression {re.escape(repr(text))} {at}; expected a finite "
                                         r"value; guard it there, for example with where\(\.\.\.\)"):
        f(T, Q, QD)


def test_a_formula_of_x_names_x():
    f = parse_function("log10(x - 1)", "x", where="function.expression")
    with pytest.raises(ModelError, match=r"^function.expression: the expression 'log10\(x - 1\)' "
                                         r"gives -inf .* at x = 1; expected a finite value"):
        f(np.array([2.0, 1.0]))
    with pytest.raises(ModelError, match=r"^function.expression: the power tower '9\*\*9\*\*x'"):
        parse_function("9**9**x", "x", where="function.expression")


def test_comparisons_are_numbers():
    np.testing.assert_array_equal(evaluate("-(q > 0) + (qd < 0) - (not q)"),
                                  -1.0 * (Q[:, 0] > 0) + (QD[:, 0] < 0) - (Q[:, 0] == 0))
    assert evaluate("q > 0").dtype == np.float64


# -- to_sympy: the same bounds and messages ---------------------------------------------------

@pytest.mark.parametrize("text", [
    "+".join(["1"] * 900), "-" * 150 + "q", "1/0", "10**400", "q ** 2000", "1e400", "sqrt(-1)",
    "q % 0", "x + 1", "q" + " + q" * 2700])
def test_to_sympy_refuses_what_parse_expression_refuses(text):
    with pytest.raises(ModelError) as parsed:
        parse_expression(text, where=WHERE)
    with pytest.raises(ModelError) as symbolic:
        sympy_form(text)
    assert str(symbolic.value) == str(parsed.value)


def test_to_sympy_of_comparisons_used_as_numbers():
    t, q1, u1 = SYMBOLS
    assert sp.piecewise_fold(sympy_form("-500 * (sin(q) > 0)")) == sp.Piecewise((-500, sp.sin(q1) > 0),
                                                                                   (0, True))
    f = sp.lambdify(SYMBOLS, sympy_form("-(q > 0) + (qd < 0) - (not q)"), "numpy")
    np.testing.assert_array_equal(f(T, Q[:, 0], QD[:, 0]), evaluate("-(q > 0) + (qd < 0) - (not q)"))


def test_to_sympy_of_a_power_tower_stays_fast():
    """In a child process, so that an exact power tower (hours of big-integer arithmetic)
    fails this test by its time-out instead of hanging the suite."""
    script = textwrap.dedent("""
        import sympy as sp
        from kinelab._expressions import to_sympy
        from kinelab.errors import ModelError
        t, q, u = sp.symbols("t q u")
        for text in ("9**9**9", "2**3**q"):
            try:
                to_sympy(text, t, [q], [u])
                print("accepted", text)
            except ModelError as exc:
                print(exc)
        # no tower, but sympy would raise 10**300 to the millionth power exactly
        form = to_sympy("((q * 10**300) ** 1000) ** 1000", t, [q], [u])
        print(max(len(str(n)) for n in form.atoms(sp.Integer)), form.has(sp.Float))
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].startswith("expression: the power tower '9**9**9' is not allowed")
    assert lines[1].startswith("expression: the power tower '2**3**q' is not allowed")
    assert lines[2] == "7 True"        # q**1000000, and the coefficient a float


# -- properties ---------------------------------------------------------------------------------

class Expr(NamedTuple):
    """A random expression: its text and, built alongside, numpy's value of the same
    formula, applied operation by operation in float64."""
    text: str
    ref: Callable            # (t, q, qd) -> value
    const: bool              # no variables
    bad: bool                # refused when parsed: a constant part not finite, a constant
    #                          divisor 0, a constant exponent too large, a power tower
    simple: bool = False     # a name or a number: what discontinuous functions take below
    power: bool = False      # a power, under its signs
    parts: tuple = ()

    def largest(self, t, q, qd):
        """The largest magnitude this formula and its parts reach, sample by sample."""
        own = np.abs(np.nan_to_num(self.ref(t, q, qd), nan=0.0, posinf=1e308, neginf=1e308))
        return functools.reduce(np.maximum, [p.largest(t, q, qd) for p in self.parts], own)


def f64(x):
    return np.asarray(x, dtype=np.float64)[()]


def value_of(e: Expr):
    with np.errstate(all="ignore"):
        return e.ref(T, Q[:, 0], QD[:, 0])


def made(text, ref, parts, *, power=False):
    const = all(p.const for p in parts)
    e = Expr(text, ref, const, any(p.bad for p in parts), power=power, parts=tuple(parts))
    if const and not e.bad and not np.all(np.isfinite(value_of(e))):
        e = e._replace(bad=True)
    return e


OPS = {"+": np.add, "-": np.subtract, "*": np.multiply, "/": np.divide, "%": np.mod}
COMPARE = {"<": np.less, "<=": np.less_equal, ">": np.greater, ">=": np.greater_equal,
           "==": np.equal, "!=": np.not_equal}
SMOOTH = {"sin": np.sin, "cos": np.cos, "tan": np.tan, "asin": np.arcsin, "acos": np.arccos,
          "atan": np.arctan, "sinh": np.sinh, "cosh": np.cosh, "tanh": np.tanh, "exp": np.exp,
          "log": np.log, "log10": np.log10, "sqrt": np.sqrt, "abs": np.abs}
STEPS = {"sign": np.sign, "floor": np.floor, "ceil": np.ceil}
TWO = {"atan2": np.arctan2, "min": np.minimum, "max": np.maximum, "hypot": np.hypot}
EDGES = [0.0, 1.0, 0.5, 2.0, 1e308, 1.7976931348623157e308, 5e-324, 2.2250738585072014e-308,
         1e-300, 1e300, 709.0, 710.0, 1000.0, 1001.0]


def number(v):
    text = repr(v) if isinstance(v, float) else str(v)
    return Expr(f"({text})" if text.startswith("-") else text, lambda t, q, qd: f64(v), True,
                False, simple=True)


def leaves(numbers):
    names = st.sampled_from([
        Expr("t", lambda t, q, qd: t, False, False, simple=True),
        Expr("q", lambda t, q, qd: q, False, False, simple=True),
        Expr("qd", lambda t, q, qd: qd, False, False, simple=True),
        Expr("pi", lambda t, q, qd: f64(np.pi), True, False, simple=True),
        Expr("e", lambda t, q, qd: f64(np.e), True, False, simple=True)])
    return st.one_of(names, numbers.map(number))


def binary(op, a, b):
    e = made(f"({a.text}) {op} ({b.text})", lambda t, q, qd: OPS[op](a.ref(t, q, qd), b.ref(t, q, qd)), (a, b))
    if op in "/%" and b.const and not b.bad and value_of(b) == 0:
        e = e._replace(bad=True)
    return e


def power(a, b):
    e = made(f"({a.text}) ** ({b.text})", lambda t, q, qd: np.power(a.ref(t, q, qd), b.ref(t, q, qd)),
             (a, b), power=True)
    if b.power or (b.const and not b.bad and abs(value_of(b)) > MAX_EXPONENT):
        e = e._replace(bad=True)
    return e


def signed(op, a):
    fn = np.negative if op == "-" else np.positive
    return made(f"{op}({a.text})", lambda t, q, qd: fn(a.ref(t, q, qd)), (a,))._replace(power=a.power)


def call(name, fn, *xs):
    return made(f"{name}({', '.join(x.text for x in xs)})",
                lambda t, q, qd: fn(*(x.ref(t, q, qd) for x in xs)), xs)


def compare(ops, xs):
    def ref(t, q, qd):
        v = [x.ref(t, q, qd) for x in xs]
        out = COMPARE[ops[0]](v[0], v[1])
        for o, a, b in zip(ops[1:], v[1:], v[2:]):
            out = np.logical_and(out, COMPARE[o](a, b))
        return f64(out)
    text = f"({xs[0].text})" + "".join(f" {o} ({x.text})" for o, x in zip(ops, xs[1:]))
    return made(f"({text})", ref, xs)


def boolean(op, xs):
    fn = np.logical_and if op == "and" else np.logical_or

    def ref(t, q, qd):
        out = xs[0].ref(t, q, qd)
        for x in xs[1:]:
            out = fn(out, x.ref(t, q, qd))
        return f64(out)
    return made(f"({f' {op} '.join(f'({x.text})' for x in xs)})", ref, xs)


def negation(c):
    return made(f"not ({c.text})", lambda t, q, qd: f64(np.logical_not(c.ref(t, q, qd))), (c,))


def choice(c, a, b):
    return made(f"(({a.text}) if ({c.text}) else ({b.text}))",
                lambda t, q, qd: np.where(c.ref(t, q, qd), a.ref(t, q, qd), b.ref(t, q, qd)), (c, a, b))


KINDS = ["arithmetic", "mod", "power", "sign", "smooth", "step", "two", "clip", "compare",
         "boolean", "not", "if", "where"]


@st.composite
def expressions(draw, numbers, depth=3, steps_on_anything=True):
    """A random expression of the grammar, up to ``depth`` operations deep; discontinuous
    operations (%, sign, floor, ceil, comparisons) take only names and numbers unless
    ``steps_on_anything``: there a rounding difference could flip their result."""
    if depth == 0 or draw(st.integers(0, 3)) == 0:
        return draw(leaves(numbers))

    def sub():
        return draw(expressions(numbers, depth - 1, steps_on_anything))

    def step():
        return sub() if steps_on_anything else draw(leaves(numbers))

    def condition():
        ops = draw(st.lists(st.sampled_from(sorted(COMPARE)), min_size=1, max_size=2))
        return compare(ops, [step() for _ in range(len(ops) + 1)])
    kind = draw(st.sampled_from(KINDS))
    if kind == "arithmetic":
        return binary(draw(st.sampled_from("+-*/")), sub(), sub())
    if kind == "mod":
        return binary("%", step(), step())
    if kind == "power":
        return power(sub(), sub())
    if kind == "sign":
        return signed(draw(st.sampled_from("-+")), sub())
    if kind == "smooth":
        name = draw(st.sampled_from(sorted(SMOOTH)))
        return call(name, SMOOTH[name], sub())
    if kind == "step":
        name = draw(st.sampled_from(sorted(STEPS)))
        return call(name, STEPS[name], step())
    if kind == "two":
        name = draw(st.sampled_from(sorted(TWO)))
        return call(name, TWO[name], sub(), sub())
    if kind == "clip":
        return call("clip", np.clip, sub(), sub(), sub())
    if kind == "compare":
        return condition()
    if kind == "boolean":
        return boolean(draw(st.sampled_from(["and", "or"])), [condition() for _ in range(draw(st.integers(2, 3)))])
    if kind == "not":
        return negation(condition())
    if kind == "if":
        return choice(condition(), sub(), sub())
    return call("where", np.where, condition(), sub(), sub())


EDGE_NUMBERS = st.one_of(st.sampled_from(EDGES), st.floats(allow_nan=False, allow_infinity=False),
                         st.integers(0, 10 ** 20))


@st.composite
def stressing(draw):
    """Expressions at and beyond the bounds: deep, long, towers, big numbers."""
    kind = draw(st.sampled_from(["plain", "deep", "long", "tower", "digits"]))
    e = draw(expressions(EDGE_NUMBERS, depth=4 if kind in ("plain", "digits") else 1))
    if kind == "deep":
        wrap = draw(st.sampled_from(["sin(", "-(", "exp(", "abs(", "max(1, ", "(q) ** ("]))
        k = draw(st.integers(MAX_DEPTH - 10, MAX_DEPTH + 10))
        return wrap * k + e.text + ")" * k
    if kind == "long":
        n = draw(st.integers(300, 700))         # about 2n + 1 parts
        ops = draw(st.lists(st.sampled_from(["+", "-", "*", "/", "%"]), min_size=n, max_size=n))
        return e.text + "".join(f" {o} ({e.text})" for o in ops)
    if kind == "tower":
        a, b, c = (draw(expressions(EDGE_NUMBERS, depth=1)) for _ in range(3))
        return f"({a.text}) ** ({b.text}) ** ({c.text})"
    if kind == "digits":
        return f"{draw(st.integers(0, 10 ** 400))} * ({e.text}) ** {draw(st.integers(-2000, 2000))}"
    return e.text


KINDS_OF_ERROR = ("numbers, names and operators", "characters long", "levels deep", "cannot parse",
                  "power tower", "exponent", "has no variables", "division by zero",
                  "beyond float64", "expected a finite value")


@given(stressing())
def test_any_expression_gives_a_model_error_or_finite_float64_quickly(text):
    start = time.perf_counter()
    try:
        out = evaluate(text)
    except ModelError as exc:
        parse_error = exc
        assert str(exc).startswith(f"{WHERE}: ") and "\n" not in str(exc)
        event(next((k for k in KINDS_OF_ERROR if k in str(exc)), "other"))
    else:
        parse_error = None
        event("finite")
        assert out.dtype == np.float64 and np.all(np.isfinite(out))
    try:
        sympy_form(text)
    except ModelError as exc:
        # refused when parsed: the same message; else a divisor sympy finds to be always 0
        # (numpy gives nan or inf there, refused where evaluated)
        assert (str(exc) == str(parse_error) if parse_error is not None
                else "divides by a term that is always 0" in str(exc)), (text, str(exc))
    assert time.perf_counter() - start < 10.0        # milliseconds, not the hours of 9**9**9


@given(expressions(st.one_of(st.sampled_from(EDGES), st.floats(-1e6, 1e6)), depth=4))
def test_values_are_numpys_float64_values_of_the_same_formula(e):
    try:
        f = parse_expression(e.text, where=WHERE)
    except ModelError:
        assert e.bad, e.text
        event("refused when parsed")
        return
    assert not e.bad, e.text
    expected = np.broadcast_to(value_of(e), T.shape)
    try:
        out = f(T, Q, QD)
    except ModelError:
        assert not np.all(np.isfinite(expected)), e.text
        event("not finite where evaluated")
        return
    assert np.all(np.isfinite(expected)), e.text
    event("compared")
    np.testing.assert_array_equal(np.broadcast_to(out, T.shape), expected)


SMALL = st.sampled_from([0.5, 1.0, 1.5, 2.0, 3.0, 0.25, 10.0, 7])


@given(expressions(SMALL, depth=3, steps_on_anything=False),
       st.lists(st.floats(-3, 3), min_size=3, max_size=3))
def test_to_sympy_agrees_with_parse_expression(e, state):
    try:
        f = parse_expression(e.text, where=WHERE)
    except ModelError:
        return
    t, q, qd = (np.array([v, v / 3 + 0.1]) for v in state)
    try:
        out = np.broadcast_to(f(t, q[:, None], qd[:, None]), t.shape)
    except ModelError:
        event("not finite where evaluated")
        return
    event("compared")
    # a branch dividing by 0 is zoo in sympy, which numpy's printer lacks: nan, as in numpy
    g = sp.lambdify(SYMBOLS, sympy_form(e.text).xreplace({sp.zoo: sp.nan}), "numpy")
    with np.errstate(all="ignore"):
        symbolic = np.broadcast_to(np.asarray(g(t, q, qd), dtype=complex), t.shape)
    # sympy reorders sums and products: allow rounding of the largest value on the way
    with np.errstate(all="ignore"):
        tolerance = 1e-12 * (1.0 + e.largest(t, q, qd))
    assert np.all(np.abs(symbolic - out) <= tolerance), (e.text, symbolic, out)
