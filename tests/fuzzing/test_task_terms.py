"""Degenerate tasks thrown at everything that builds a model on the user's behalf (synthesis,
quick returns, sweep families, importers): each ends in a result or in a kinelab error whose
message speaks of the task, never of a sketch, a model field or a name the user never wrote
(kinelab's P3, jO2, 'slide'), and never in a traceback of another kind."""
import itertools
import re

import numpy as np
import pytest

import kinelab as kl
from kinelab import synthesis as sy
from kinelab.errors import KinelabError

# words of the model that a task's author never wrote
MODEL_WORDS = re.compile(r"sketch|\blinks\[|\bpoints\[\d+\]\.|\bjoints\[|'P\d+'|'jP?\w*'|'sP\d+'|"
                         r"'O[24]'|\(A-B-O4\)|mechanism '|\bq = |^q: ")


def outcome(call):
    """'ok', or the message of the kinelab error the call ends in (anything else fails)."""
    try:
        call()
    except KinelabError as exc:
        return str(exc)
    return "ok"


def assert_in_task_terms(message):
    assert message == "ok" or not MODEL_WORDS.search(message), message


ANGLES = (0, 90, 180, 270)


@pytest.mark.parametrize("a, b", list(itertools.product(ANGLES, ANGLES)))
def test_function_generation_on_the_axes(a, b):
    """Input and output ranges that start (or end) on the ground line, where the linkage
    may lie flat at a precision point."""
    for span, points in ((60, [1.0, 1.5, 2.0]), (-60, 3), (90, [1.0, 1.25, 1.5, 2.0])):
        assert_in_task_terms(outcome(lambda: sy.function_generation(
            np.log10, (1, 2), (a, a + span), (b, b + span), points=points, degrees=True)))


@pytest.mark.parametrize("s, t", list(itertools.product((-1.0, 0.0, 1.0), (-1.0, 0.0, 1.0))))
def test_two_positions_in_line(s, t):
    fam = sy.two_positions([(0, 0), (1, 0)], [0, 0], A1=(0, 0), B1=(1, 0))
    assert_in_task_terms(outcome(lambda: fam.solution(s, t)))


def test_three_and_four_positions_on_a_grid():
    rng = np.random.default_rng(5)
    for _ in range(40):
        P = rng.integers(-3, 4, size=(3, 2)).astype(float)
        angles = rng.choice([0.0, 15.0, 45.0, 90.0, 180.0], size=3)
        a0, b0 = (tuple(rng.integers(-3, 4, size=2).astype(float)) for _ in range(2))
        assert_in_task_terms(outcome(lambda: sy.three_positions(P, angles, a0, b0, degrees=True)))
        a1, b1 = (tuple(rng.integers(-3, 4, size=2).astype(float)) for _ in range(2))
        assert_in_task_terms(outcome(lambda: sy.three_positions(P, angles, A1=a1, B1=b1,
                                                                degrees=True)))
    P4 = np.array([(0, 0), (1, 0), (2, 0), (3, 0)], float)
    for a0x, b0x in itertools.product((-1.0, 0.0, 1.5), (0.0, 3.0)):
        assert_in_task_terms(outcome(lambda: sy.four_positions(P4, [0, 0.1, 0.2, 0.3], a0x, b0x)))


@pytest.mark.parametrize("call", [
    lambda: sy.offset_slider_crank(0.1, 2.999), lambda: sy.offset_slider_crank(1.1e-9, 1.5),
    lambda: sy.slotted_lever(80, 0.3), lambda: sy.slotted_lever(1.5, 9.99e8),
    lambda: sy.whitworth(2000, 0.05, 0.3), lambda: sy.whitworth(1.5, 0.05, 1.1e-9),
    lambda: sy.crank_rocker(1.1e-9, 45, 1.2, degrees=True),
    lambda: sy.crank_rocker(0.1, 1e-8, 1.2, degrees=True),
])
def test_quick_returns_at_their_edges(call):
    assert_in_task_terms(outcome(call))


@pytest.mark.parametrize("family, rows", [
    ("slider_crank", dict(crank=[1, 1, 1, 1], rod=[1, 0.5, 2, 3], offset=[0, 0, 1, 5])),
    ("inverted_slider_crank", dict(ground=[1, 1, 2, 2], crank=[1, 2, 1, 1], offset=[0, 0, 1, 3])),
    ("slotted_link", dict(crank=[1, 2, 1], distance=[1, 1, 1e-12])),
    ("whitworth", dict(crank=[1, 1, 1], distance=[1, 0.5, 0.5], lever=[1, 1, 1], rod=[1, 0.1, 2])),
    ("fivebar", dict(ground=[2.0], crank1=[1.0], coupler1=[1.0], coupler2=[1.0], crank2=[1.0])),
])
def test_sweeps_of_degenerate_designs(family, rows):
    df = None

    def study():
        nonlocal df
        df = kl.sweep.run(family, rows, samples=8)
    assert_in_task_terms(outcome(study))
    for reason in (df.attrs["problems"].values() if df is not None else ()):
        assert_in_task_terms(reason)


@pytest.mark.parametrize("joints", [
    "[0, 0] [10, 0] [20, 0] [30, 0]", "[0, 0] [0, 0] [20, 10] [30, 0]",
    "[0, 0] [0, 10] [15, 5] [30, 0]", "[0, 0] [10, 10] [10, 10] [30, 0]",
    "[0, 0] [30, 0] [20, 10] [30, 0]",
])
def test_pyslvs_drawings_in_line_or_on_one_place(joints, tmp_path):
    from click.testing import CliRunner
    from kinelab.cli import main
    xy = [p.strip("[]") for p in joints.split("] [")]
    links = ("ground, crank", "crank, coupler", "coupler, rocker", "ground, rocker")
    text = "M[" + ", ".join(f"J[R, P[{p}], L[{n}]]" for p, n in zip(xy, links)) + "]"
    assert_in_task_terms(outcome(lambda: kl.io.from_pyslvs(text)))
    (tmp_path / "d.pyslvs").write_text(text)
    result = CliRunner().invoke(main, ["import", str(tmp_path / "d.pyslvs"), "--out",
                                       str(tmp_path / "m.toml")])
    assert result.exit_code in (0, 2), result.output
    if result.exit_code == 2:
        assert len(result.stderr.splitlines()) == 1
        assert_in_task_terms(result.stderr)
