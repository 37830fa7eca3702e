"""The functions parse_expression and parse_table return check the samples they are given."""
import numpy as np
import pytest

from kinelab._expressions import parse_expression, parse_function, parse_table
from kinelab.errors import ModelError

SHAPES = r"expected real numbers, t of shape \(\) or \(N,\), q and qd of shape \(N, M\)"
TABLE = {"of": "q", "x": [0.0, 1.0], "y": [0.0, 10.0]}


@pytest.mark.parametrize("text", ["sin(q)", "not q", "q<q<q", "where(q>0,1,0)", "qd", "t", "q[5]"])
def test_a_law_refuses_one_dimensional_states(text):
    with pytest.raises(ModelError, match=r"^expression: " + SHAPES + r" .*, got t of shape \(\), "
                       r"q of shape \(1,\), qd of shape \(1,\)$"):
        parse_expression(text)(0.5, np.array([0.3]), np.array([0.1]))


@pytest.mark.parametrize("t, q, qd, got", [
    ("a", "b", "c", "t = 'a', q = 'b', qd = 'c'"),
    (np.zeros(2), np.zeros((3, 1)), np.zeros((3, 1)), r"t of shape \(2,\)"),
    (np.zeros(3), np.zeros((3, 1)), np.zeros((3, 2)), r"qd of shape \(3, 2\)"),
    (np.zeros(1), [[10 ** 400]], np.zeros((1, 1)), "q = "),
    (np.zeros(1), np.zeros((1, 1), complex), np.zeros((1, 1)), "q = "),
])
def test_a_law_refuses_states_that_are_not_real_arrays_of_matching_shapes(t, q, qd, got):
    with pytest.raises(ModelError, match=SHAPES + ".*" + got):
        parse_expression("q + 1")(t, q, qd)


def test_an_index_past_the_inputs_is_named():
    with pytest.raises(ModelError, match=r"q\[5\] in 'q\[5\]': the mechanism has 1 input\(s\)"):
        parse_expression("q[5]")(np.zeros(1), np.zeros((1, 1)), np.zeros((1, 1)))


def test_valid_states_still_give_the_values():
    f = parse_expression("3 * q + where(t > 1, 2, 0)")
    assert f(np.array([0.0, 2.0]), np.ones((2, 1)), np.zeros((2, 1))).tolist() == [3.0, 5.0]
    assert f(0.0, np.ones((2, 1)), np.zeros((2, 1))).tolist() == [3.0, 3.0]


def test_a_table_lookup_checks_the_states_too():
    with pytest.raises(ModelError, match=r"^table\.of: " + SHAPES):
        parse_table(TABLE)(0.5, np.array([0.3]), np.array([0.1]))
    assert parse_table(TABLE)(np.zeros(1), np.array([[0.5]]), np.zeros((1, 1))).tolist() == [5.0]


@pytest.mark.parametrize("spec, message", [
    ({**TABLE, "x": [0, 10 ** 400]}, r"x and y: expected lists of real numbers, got \[0, a whole "
                                     r"number of 401 digits\] and \[0\.0, 10\.0\]"),
    ({**TABLE, "y": ["a", "b"]}, r"x and y: expected lists of real numbers"),
    ({**TABLE, "period": 10 ** 400}, r"period: expected a positive number, got a whole number"),
    ({**TABLE, "period": True}, r"period: expected a positive number, got true"),
    ("q", r"expected a table \{of, x, y, period\}, got 'q'"),
])
def test_table_values(spec, message):
    with pytest.raises(ModelError, match=message):
        parse_table(spec)


@pytest.mark.parametrize("make", [
    lambda: parse_expression("q+", where="x\ny"),
    lambda: parse_table({"x": [0, 1]}, where="x\ny"),
    lambda: parse_function("x+", where="x\ny"),
    lambda: parse_expression("q")(np.zeros(1), np.zeros(1), np.zeros(1)),
])
def test_messages_are_one_line(make):
    with pytest.raises(ModelError) as info:
        make()
    assert "\n" not in str(info.value)


def test_parse_function_refuses_text():
    with pytest.raises(ModelError, match=r"expected real numbers for x, got 'a'"):
        parse_function("x + 1")("a")


def test_lists_nested_deeper_than_numpy_allows_are_not_real_arrays():
    """A list nested 58 deep (a hostile request's range): no array, not a numpy fault."""
    from kinelab.model._values import real_array
    deep = 1
    for _ in range(58):
        deep = [deep]
    assert real_array(deep) is None
    assert real_array([deep, 2]) is None
