"""Force laws written as text are parsed against a whitelist and never executed."""
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from kinelab.dynamics import Law, parse_expression, parse_table
from kinelab.errors import ModelError

t = np.array([0.0, 0.5, 2.0])
q1 = np.array([[0.1], [1.0], [-2.0]])
qd1 = np.array([[3.0], [0.0], [-1.0]])
q2 = np.array([[0.1, 5.0], [1.0, 6.0], [-2.0, 7.0]])


@pytest.mark.parametrize("text, expected", [
    ("2 * q + 1", 2 * q1[:, 0] + 1),
    ("-qd ** 2 % 4", np.mod(-qd1[:, 0] ** 2, 4)),
    ("sin(q) * exp(-t) + atan2(q, 2)", np.sin(q1[:, 0]) * np.exp(-t) + np.arctan2(q1[:, 0], 2)),
    ("max(q, 0) + min(qd, 1) + abs(q) + sqrt(hypot(3, 4))",
     np.maximum(q1[:, 0], 0) + np.minimum(qd1[:, 0], 1) + np.abs(q1[:, 0]) + np.sqrt(5.0)),
    ("where(t > 1, 10, 0) + (5 if q > 0 else -5)",
     np.where(t > 1, 10, 0) + np.where(q1[:, 0] > 0, 5, -5)),
    ("1 if 0 < q < 0.5 and not qd < 0 else 0", np.array([1.0, 0.0, 0.0])),
    ("clip(qd, -0.5, 0.5) * pi - e", np.clip(qd1[:, 0], -0.5, 0.5) * np.pi - np.e),
    ("4", np.full(3, 4.0)),
])
def test_expressions_evaluate_like_numpy(text, expected):
    out = np.broadcast_to(parse_expression(text)(t, q1, qd1), (3,))
    np.testing.assert_allclose(out, expected, rtol=1e-15, atol=0)


def test_several_inputs_are_indexed():
    f = parse_expression("q[0] + 10 * q[1]")
    np.testing.assert_allclose(f(t, q2, q2), q2[:, 0] + 10 * q2[:, 1], rtol=1e-15)
    with pytest.raises(ModelError, match=r"'q' in 'q \+ 1': the mechanism has 2 inputs; write "
                                         r"q\[0\] \.\.\. q\[1\]"):
        parse_expression("q + 1")(t, q2, q2)
    with pytest.raises(ModelError, match=r"q\[2\] in 'q\[2\]': the mechanism has 2 input\(s\)"):
        parse_expression("q[2]")(t, q2, q2)


@pytest.mark.parametrize("text, what", [
    ("__import__('os').system('true')", "the function \"__import__('os').system\""),
    ("open('x')", "the function 'open'"),
    ("q.__class__", "Attribute"),
    ("[q for q in range(3)]", "ListComp"),
    ("lambda: 1", "Lambda"),
    ("x + 1", "the name 'x'"),
    ("'text'", "the constant 'text'"),
    ("True + 1", "the constant True"),
    ("q[-1]", "an index that is not a whole number >= 0"),
    ("t[0]", "indexing anything but q or qd"),
    ("sin(x=q)", "a keyword argument"),
    ("q @ q", "the operator MatMult"),
    ("q << 2", "the operator LShift"),
    ("q in (1, 2)", "this comparison"),
    ("(yield)", "Yield"),
])
def test_everything_else_is_refused(text, what):
    with pytest.raises(ModelError, match=r"forces\[0\]\.fx: .*is not allowed in the expression") as info:
        parse_expression(text, where="forces[0].fx")
    assert what in str(info.value)
    assert "an expression may use numbers, t, q, qd" in str(info.value)


@pytest.mark.parametrize("text, message", [
    ("2 * (q", r"cannot parse the expression '2 \* \(q'"),
    ("sin(q, t)", r"sin\(\) takes 1 argument\(s\), got 2"),
    ("q" + " + q" * 2700, r"is 10801 characters long; expected at most 10000"),
    (3, r"expected an expression \(text\) or a number"),
])
def test_malformed_expressions(text, message):
    with pytest.raises(ModelError, match=message):
        parse_expression(text)


def test_a_law_that_gives_nan_or_inf_names_the_sample():
    law = Law("1 / q", "torques[0]")
    with pytest.raises(ModelError, match=r"torques\[0\]: the expression '1 / q' gives inf \(an "
                                         r"overflow or a division by zero\) at t = 0 s, q = 0, qd = 0; "
                                         r"expected a finite value; guard it there"):
        law(np.zeros(2), np.zeros((2, 1)), np.zeros((2, 1)))
    callable_law = Law(lambda t, q, qd: 1 / (q - 1), "torques[1]")
    with np.errstate(divide="ignore"), pytest.raises(
            ModelError, match=r"torques\[1\]: the law gives inf .* at t = 2 s, q = 1, qd = 0"):
        callable_law(np.array([0.0, 2.0]), np.array([[0.0], [1.0]]), np.zeros((2, 1)))
    with pytest.raises(ModelError, match=r"law: expected values of shape \(\) or \(2,\), got \(3,\)"):
        Law(lambda t, q, qd: np.zeros(3))(np.zeros(2), np.zeros((2, 1)), np.zeros((2, 1)))


def test_tables_interpolate_and_repeat():
    f = parse_table({"of": "q", "x": [0.0, 1.0, 2.0], "y": [0.0, 10.0, 0.0], "period": 2.0})
    q = np.array([[0.25], [1.5], [2.25], [-0.5]])
    np.testing.assert_allclose(f(np.zeros(4), q, q), [2.5, 5.0, 2.5, 5.0], rtol=1e-15)
    g = parse_table({"of": "t * 2", "x": [0.0, 1.0], "y": [1.0, 3.0]})
    np.testing.assert_allclose(g(np.array([0.25]), q[:1], q[:1]), [2.0], rtol=1e-15)
    with pytest.raises(ModelError, match=r"table: t \* 2 = 4 is outside the table \[0, 1\]; "
                                         "extend the table or give its period"):
        g(np.array([2.0]), q[:1], q[:1])


@pytest.mark.parametrize("spec, message", [
    ({"x": [0, 1], "y": [1]}, r"x and y: expected two lists of the same length"),
    ({"x": [0, 0], "y": [1, 2]}, r"x: expected strictly increasing values, got x\[0\] = 0.0 then x\[1\] = 0.0"),
    ({"x": [0, 1], "y": [1, 2], "period": -1}, r"period: expected a positive number, got -1"),
    ({"x": [0, 1], "y": [1, 2], "kind": "cubic"}, r"unknown key\(s\) 'kind'"),
    ({"x": [0, 1], "y": [1, 2], "of": "exec(q)"}, r"table.of: the function 'exec' is not allowed"),
])
def test_bad_tables(spec, message):
    with pytest.raises(ModelError, match=message):
        parse_table(spec)


@given(st.lists(st.floats(-1e3, 1e3), min_size=1, max_size=6),
       st.lists(st.sampled_from(["+", "-", "*"]), min_size=5, max_size=5))
def test_arithmetic_matches_python(numbers, ops):
    """Random sums and products of constants and q give what Python gives."""
    terms = [f"({v!r})" for v in numbers] + ["q"]
    text = terms[0] + "".join(f" {o} {x}" for o, x in zip(ops, terms[1:]))
    qv = 0.75
    expected = eval(text, {"__builtins__": {}}, {"q": qv})    # the test's own reference
    out = parse_expression(text)(np.zeros(1), np.array([[qv]]), np.zeros((1, 1)))
    np.testing.assert_allclose(np.broadcast_to(out, (1,)), [expected], rtol=1e-12, atol=1e-9)
