"""A synthesis that builds a linkage on the user's behalf says what is wrong in the task's
terms: never of a sketch, a model field or a dyad the user never wrote; the engine's own
error is kept as the cause."""
import tomllib

import numpy as np
import pytest

from kinelab.errors import ModelError
from kinelab.io import read_task, solve_task
from kinelab.synthesis import (crank_rocker, function_generation, offset_slider_crank,
                               slotted_lever, two_positions, whitworth)

MODEL_WORDS = ("sketch", "dyad", "'coupler'", "'rocker'", "links[", "points[", "O4")


def assert_task_terms(exc: ModelError):
    message = str(exc)
    assert not any(w in message for w in MODEL_WORDS), message
    assert len(message.splitlines()) == 1
    # the engine's words are kept for whoever debugs, as the cause
    assert isinstance(exc.__cause__, ModelError) and "sketch" in str(exc.__cause__)


def pylinkage_pairs(x):
    """The precision pairs of pylinkage's own tests, (0, 0), (0.5, 0.6), (1.0, 1.1), as a
    function of x (x the input angle, y the output angle)."""
    return np.interp(x, [0.0, 0.5, 1.0], [0.0, 0.6, 1.1])


def test_a_flat_linkage_at_a_precision_point_is_said_in_the_tasks_terms():
    with pytest.raises(ModelError) as info:
        function_generation(pylinkage_pairs, (0, 1), (0, 1), (0, 1.1), points=[0, 0.5, 1.0])
    assert str(info.value) == (
        "input_range, output_range: at the precision point x = 0 (input angle 0 rad, output "
        "angle 0 rad): the linkage is flat: its four pivots lie on one line, the crank, the "
        "coupler and the rocker all along the ground line: a dead centre, where the four-bar's "
        "two assembly modes meet, so it cannot tell which one is meant (and transmits no force "
        "to the rocker there); offset the angle ranges (start the input at, say, 0.2 rad and "
        "the output at 0.4 rad) or choose other precision points")
    assert_task_terms(info.value)
    # in degrees, the angles are shown in degrees
    with pytest.raises(ModelError, match=r"^input_range, output_range: at the precision point "
                                         r"x = 0 \(input angle 0 deg, output angle 0 deg\): the "
                                         r"linkage is flat: .* \(start the input at, say, 10 deg "
                                         r"and the output at 20 deg\)"):
        function_generation(pylinkage_pairs, (0, 1), (0, 57.29577951308232),
                            (0, 63.02535746439057), points=[0, 0.5, 1.0], degrees=True)
    # and the advice works: the same pairs, both angles offset
    sol = function_generation(pylinkage_pairs, (0, 1), (0.2, 1.2), (0.4, 1.5),
                              points=[0, 0.5, 1.0])
    assert np.abs(sol.precision_errors).max() < 1e-9


FLAT_TASK = """
task = "function"
units = {{ angle = "{unit}" }}
[function]
expression = "x + 0.4 * x * (1 - x)"
x_range = [0, 1]
input_range = [0, {end}]
output_range = [0, {end}]
points = [0, 0.5, 1.0]
"""


@pytest.mark.parametrize("unit, end", [("rad", 1), ("deg", 60)])
def test_the_same_in_a_task_file_names_its_fields_and_its_unit(unit, end):
    task = read_task(tomllib.loads(FLAT_TASK.format(unit=unit, end=end)), source="pairs.toml")
    with pytest.raises(ModelError) as info:
        solve_task(task)
    start, other = ("10 deg", "20 deg") if unit == "deg" else ("0.2 rad", "0.4 rad")
    message = str(info.value)
    assert message.startswith(
        "pairs.toml: function.input_range, function.output_range: at the precision point x = 0 "
        f"(input angle 0 {unit}, output angle 0 {unit}): the linkage is flat")
    assert message.endswith(f"(start the input at, say, {start} and the output at {other}) or "
                            "choose other precision points")
    assert not any(w in message for w in MODEL_WORDS)


def test_two_positions_whose_pivots_put_the_linkage_flat():
    fam = two_positions([(0, 0), (1, 0)], [0, 0], A1=(0, 0), B1=(1, 0))
    with pytest.raises(ModelError) as info:
        fam.solution(0.0, 0.0)
    assert str(info.value).startswith("position 1: the linkage is flat: its four pivots lie on "
                                      "one line")
    assert str(info.value).endswith("; choose another t (it moves B0 along its bisector) or B1")
    assert_task_terms(info.value)


def test_two_positions_with_the_coupler_and_rocker_in_line():
    """B0 on the line A1 B1, found by hand: the bisector of B1 B2 meets that line."""
    fam = two_positions([(0, 0), (1, 1)], [0, 90], A1=(0, -1), B1=(1, -1), degrees=True)
    # B0(t) = o + t d; on the line A1 + u (B1 - A1): solve o + t d = A1 + u e
    e = fam.B1 - fam.A1
    t, _ = np.linalg.solve(np.column_stack([fam.B0_direction, -e]), fam.A1 - fam.B0_origin)
    with pytest.raises(ModelError) as info:
        fam.solution(1.0, t)
    B0 = fam.B0(t)
    message = str(info.value)
    assert message.startswith("position 1: the crank pin (0, -1), the rocker pin (1, -1) and the "
                              f"rocker's pivot ({B0[0]:.9g}, {B0[1]:.9g}) are in line, so the "
                              "coupler and the rocker are: a dead centre")
    assert_task_terms(info.value)
    # a little off that line, the same family gives a linkage
    assert fam.solution(1.0, t + 0.1).model is not None


# -- quick returns: the user gave a stroke and a time ratio, not the catalogue's lengths ----

QUICK_RETURN_WORDS = MODEL_WORDS + ("'jO2'", "'slide'", "'lever'", "'ram_slide'", "point '",
                                    "mechanism '", "q = ")


@pytest.mark.parametrize("call, start", [
    # a time ratio near 3: the design's rod all but lines up, a dead centre on the turn
    (lambda: offset_slider_crank(0.1, 2.99), "time_ratio: the offset slider-crank it gives all "
     "but locks at a dead centre on its turn, where the engine finds it singular and cannot "
     "measure its time ratio; lower the time ratio"),
    (lambda: slotted_lever(50, 0.3), "time_ratio: the slotted lever it gives all but locks at a "
     "dead centre on its turn"),
    (lambda: whitworth(1.5, 0.05, 0.3, rod=0.1500001), "time_ratio: the Whitworth quick return "
     "it gives all but locks at a dead centre on its turn, where the engine finds it singular "
     "and cannot measure its time ratio; lengthen the rod or lower the time ratio"),
    # lengths the user never gave, beyond the sizes kinelab computes with
    (lambda: offset_slider_crank(1.5e-9, 1.2), "stroke: the offset slider-crank it gives (crank "
     "7.05711e-10 m, "),
    (lambda: whitworth(1.5, 0.05, 1.5e-9), "stroke: the Whitworth quick return it gives (crank "
     "0.161803 m, distance 0.05 m, lever 7.5e-10 m, rod 1.5e-09 m) lies outside the sizes"),
    (lambda: slotted_lever(1.5, 9.9e8), "distance: the slotted lever it gives (crank "),
    (lambda: crank_rocker(0.1, 1e-7, 1.2, degrees=True), "ground: the crank-rocker it gives "
     "(ground 0.1 m, crank 8.21141e-11 m, "),
])
def test_quick_returns_refuse_in_the_tasks_terms(call, start):
    with pytest.raises(ModelError) as info:
        call()
    message = str(info.value)
    assert message.startswith(start), message
    assert not any(w in message for w in QUICK_RETURN_WORDS), message
    assert isinstance(info.value.__cause__, Exception)      # the engine's or catalogue's words


def test_the_lengths_said_are_the_designs():
    """crank = stroke / 2 / ... : the offset slider-crank's lengths scale with the stroke, so
    the lengths a too-small stroke would give are the 0.1 m design's, scaled."""
    design = offset_slider_crank(0.1, 1.2)
    with pytest.raises(ModelError) as info:
        offset_slider_crank(1.5e-9, 1.2)
    crank = design.lengths["crank"] * 1.5e-9 / 0.1
    assert f"crank {crank:.6g} m" in str(info.value)
