"""The smallest transmission angle a synthesized linkage may have: 30 deg unless the task says
otherwise, measured by the engine over the travel, and a linkage below it never valid."""
import json
import re
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.errors import ModelError
from kinelab.synthesis import (TRANSMISSION_LIMIT, function_generation, path_generation,
                               three_positions)
from tests.synthesis.test_cli import LOG10_TASK

THIRTY = np.radians(30.0)


def engine_min_transmission(model, q0, q1, samples=20001):
    """The smallest acute transmission angle the engine meets while the crank turns from q0
    to q1 (the sense of q1 - q0), sampled densely: it can only miss the minimum from above."""
    sol = kl.analyze(model, q=np.linspace(q0, q1, samples), unreachable="mask", at_singular="flag")
    assert sol.assembled.all()
    return float(np.min(kl.kinematics.transmission_angle(sol)))


def test_the_default_limit_is_thirty_degrees():
    assert TRANSMISSION_LIMIT == THIRTY
    import inspect
    assert inspect.signature(path_generation).parameters["min_transmission_angle"].default == THIRTY


# A crank-rocker whose transmission angle is smallest with the crank along the ground line
# towards O4 (q = 0): there O2B = ground - crank = 1.6 and, by the law of cosines,
# cos(mu) = (coupler^2 + rocker^2 - 1.6^2) / (2 coupler rocker) = 9.68 / 10.8.
LOW = dict(ground=3.0, crank=1.4, coupler=3.0, rocker=1.8, coupler_point=(1.5, 1.0))
LOW_MU = float(np.arccos(9.68 / 10.8))          # 26.3246 deg


def low_poses():
    fb = kl.mechanisms.fourbar(**LOW)
    s = kl.analyze(fb, q=np.radians([-20.0, 0.0, 35.0]))     # the travel passes q = 0
    return s.position("P"), s.angle("coupler")


def test_three_positions_below_the_limit_is_flagged_with_its_angle():
    P, th = low_poses()
    sol = three_positions(P, th, (0, 0), (3, 0))
    # the task's own linkage comes back, and the engine moves it through the poses ...
    np.testing.assert_allclose(list(sol.lengths.values()), [3.0, 1.4, 3.0, 1.8], atol=1e-9)
    assert sol.position_errors.max() < 1e-9 and not sol.branch_defect and not sol.order_defect
    # ... but its transmission angle falls to 26.3 deg on the way: not valid by default
    assert sol.min_transmission_angle == pytest.approx(LOW_MU, abs=1e-9)
    assert engine_min_transmission(sol.model, sol.q[0], sol.q[-1]) == pytest.approx(LOW_MU, abs=1e-6)
    assert not sol.valid and not sol.meets_transmission_limit
    assert sol.transmission_limit == THIRTY and sol.state == "transmission angle defect"
    assert sol.defects == (f"transmission angle defect: the transmission angle drops to "
                           f"{np.degrees(LOW_MU):.4g} deg between position 1 and position 3, below "
                           "the limit of 30 deg (min_transmission_angle): the coupler pushes the "
                           "rocker too nearly along it; choose another linkage, or lower the limit",)
    # the limit is the task's to choose: in degrees with degrees=True, in rad otherwise
    lower = three_positions(P, np.degrees(th), (0, 0), (3, 0), min_transmission_angle=25,
                            degrees=True)
    assert lower.valid and lower.meets_transmission_limit
    assert lower.transmission_limit == pytest.approx(np.radians(25), abs=1e-15)
    assert three_positions(P, th, (0, 0), (3, 0), min_transmission_angle=0.0).valid
    with pytest.raises(ModelError, match=r"^min_transmission_angle: expected an angle in "
                                         r"\[0, 90\) deg, got 90$"):
        three_positions(P, np.degrees(th), (0, 0), (3, 0), min_transmission_angle=90, degrees=True)


def test_four_and_two_positions_carry_the_limit():
    fb = kl.mechanisms.fourbar(**LOW)
    s = kl.analyze(fb, q=np.radians([-20.0, -5.0, 10.0, 35.0]))
    sols = kl.synthesis.four_positions(s.position("P"), s.angle("coupler"), a0x=0.0, b0x=3.0)
    own = [x for x in sols if np.allclose(np.r_[x.A0, x.B0], [0, 0, 3, 0], atol=1e-9)]
    assert len(own) == 1 and own[0].state == "transmission angle defect"
    assert own[0].min_transmission_angle == pytest.approx(LOW_MU, abs=1e-9)
    fam = kl.synthesis.two_positions([(0, 0), (1, 1)], [0, 90], A1=(0, -1), B1=(1, -1),
                                     degrees=True)
    sol = fam.solution(1.0, 2.0)
    mu = engine_min_transmission(sol.model, sol.q[0], sol.q[0] + sol.direction * np.mod(
        sol.direction * (sol.q[1] - sol.q[0]), 2 * np.pi))
    assert sol.min_transmission_angle == pytest.approx(mu, abs=1e-6)
    assert sol.valid == (mu >= THIRTY)
    tight = fam.solution(1.0, 2.0, min_transmission_angle=mu + 0.01)
    assert not tight.valid and tight.state == "transmission angle defect"


def test_function_generation_against_its_limit():
    f = function_generation(np.log10, (1, 2), (90, 150), (0, 90), degrees=True)
    # the engine over the input range, independently of the solution's own sweep
    mu = engine_min_transmission(f.model, *f.input_range)
    assert f.min_transmission_angle == pytest.approx(mu, abs=1e-6)
    assert mu > THIRTY and f.valid and f.meets_transmission_limit       # 45.4 deg
    strict = function_generation(np.log10, (1, 2), (90, 150), (0, 90), degrees=True,
                                 min_transmission_angle=50)
    assert not strict.valid and not strict.branch_defect
    assert strict.state == "transmission angle defect" and "over the input range" in strict.defects[0]
    assert strict.transmission_limit == pytest.approx(np.radians(50), abs=1e-15)


def test_path_generation_keeps_the_default_limit_and_says_how_low_a_rejected_one_goes():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                               coupler_point=(1.5, 1.0))
    T = kl.analyze(fb, q=np.radians(np.linspace(0, 270, 8))).position("P")
    sols = path_generation(T, runs=1, seed=0)                     # the default limit
    assert len(sols) == 1
    for s in sols:
        assert s.valid and s.transmission_limit == THIRTY and s.meets_transmission_limit
        assert engine_min_transmission(s.model, s.q[0], s.q[-1]) >= THIRTY - 1e-9
    # a limit no linkage near these points keeps: the reason gives the best one's angle
    none = path_generation(T, runs=1, seed=0, maxiter=2, min_transmission_angle=np.radians(85))
    assert len(none) == 0
    assert none.reason.startswith("run 1 (seed 0) found no linkage free of branch and order "
                                  "defects with a transmission angle of at least 85 deg")
    assert none.reason.endswith("; raise maxiter or popsize, or lower min_transmission_angle")


TASK_8 = """
task = "path"
units = {{ length = "mm", angle = "deg" }}
[positions]
points = [[0, 0], [25, 10], [50, 15], [75, 10], [100, 0], [75, -20], [50, -25], [25, -20]]
[search]
runs = 1
{extra}
"""


@pytest.mark.parametrize("extra, limit", [("", 30.0), ("min_transmission_angle = 10", 10.0)])
def test_a_path_task_says_of_each_linkage_whether_it_meets_the_limit(tmp_path, extra, limit):
    """An eight-point path: every linkage printed and summarised meets the task's limit (30 deg
    by default), by the engine's own measure over the travel."""
    (tmp_path / "task.toml").write_text(TASK_8.format(extra=extra))
    res = CliRunner().invoke(main, ["synth", str(tmp_path / "task.toml"), "--no-figures",
                                    "--json", "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    rows = json.loads(res.output)["solutions"]
    assert rows
    task = kl.io.load_task(tmp_path / "task.toml")
    sols, _ = kl.io.solve_task(task)                 # the same search, seeded: the same linkages
    for row, s in zip(rows, sols):
        mu = np.degrees(engine_min_transmission(s.model, s.q[0], s.q[-1]))
        assert row["valid"] and row["meets_transmission_limit"] and mu >= limit - 1e-6
        assert row["transmission_limit"] == pytest.approx(limit, abs=1e-12)
        assert row["min_transmission_angle"] == pytest.approx(mu, abs=1e-4)
    res = CliRunner().invoke(main, ["synth", str(tmp_path / "task.toml"), "--no-figures",
                                    "--out", str(tmp_path / "out")])
    lines = [ln for ln in res.output.splitlines() if ln.startswith("  1: ")]
    assert len(lines) == 1 and f"(meets the {limit:.3g} deg limit)" in lines[0]


MOTION_3 = """
task = "motion"
units = {{ angle = "deg" }}
[positions]
points = {points}
angles = {angles}
[pivots]
A0 = [0, 0]
B0 = [3, 0]
{extra}
"""


def test_a_motion_task_flags_a_linkage_below_the_limit(tmp_path):
    P, th = low_poses()
    text = MOTION_3.format(points=P.tolist(), angles=np.degrees(th).tolist(), extra="")
    (tmp_path / "task.toml").write_text(text)
    res = CliRunner().invoke(main, ["synth", str(tmp_path / "task.toml"), "--no-figures",
                                    "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    line = next(ln for ln in res.output.splitlines() if ln.startswith("  1: "))
    assert f"min transmission {np.degrees(LOW_MU):.3g} deg (below the 30 deg limit)" in line
    assert line.endswith("crank-rocker, transmission angle defect")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())["solutions"][0]
    assert not summary["valid"] and not summary["meets_transmission_limit"]
    # the task's own limit, in its angle unit
    (tmp_path / "task.toml").write_text(text + "[search]\nmin_transmission_angle = 25\n")
    res = CliRunner().invoke(main, ["synth", str(tmp_path / "task.toml"), "--no-figures",
                                    "--out", str(tmp_path / "out")])
    assert res.exit_code == 0 and "(meets the 25 deg limit)" in res.output
    assert res.output.splitlines()[1].endswith("crank-rocker, valid")


@pytest.mark.parametrize("kind, text", [
    ("motion", MOTION_3.format(points=[[1, 1], [2, 0.5], [3, 1.5]], angles=[0, 0, 45], extra="")),
    ("function", LOG10_TASK),
    ("path", TASK_8.format(extra="")),
])
@pytest.mark.parametrize("value, problem", [
    (90, "expected an angle from 0 to 90 deg (not included), got 90 deg"),
    (-1, "expected an angle from 0 to 90 deg (not included), got -1 deg"),
    ("'a'", "expected a finite number, got 'a'"),
])
def test_the_limit_in_a_task_file_is_checked_in_its_units(kind, text, value, problem):
    if "[search]" in text:
        text = text.replace("[search]", f"[search]\nmin_transmission_angle = {value}")
    else:
        text += f"[search]\nmin_transmission_angle = {value}\n"
    with pytest.raises(ModelError, match=rf"^search\.min_transmission_angle: {re.escape(problem)}$"):
        kl.io.read_task(tomllib.loads(text))


def test_a_function_task_takes_the_limit():
    text = LOG10_TASK + "[search]\nmin_transmission_angle = 50\n"
    task = kl.io.read_task(tomllib.loads(text))
    (sol,), _ = kl.io.solve_task(task)
    assert sol.state == "transmission angle defect"
    row = kl.io.task_summary(task, [sol], {})["solutions"][0]
    assert row["transmission_limit"] == pytest.approx(50.0, abs=1e-12)
    assert not row["valid"] and not row["meets_transmission_limit"]
    with pytest.raises(ModelError, match=r"^search\.dyads: unknown key"):
        kl.io.read_task(tomllib.loads(text + "dyads = 3\n"))
