"""`kinelab synth TASK`."""
import json
import re
import warnings

import numpy as np
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main

NOTES_6_7 = """
task = "motion"
name = "Mecanismos, §6.7"
units = { length = "cm", angle = "deg" }

[positions]
points = [[0, 0], [5, 8], [10, 15], [18, 20]]
angles = [10, 20, 30]            # alpha_2..alpha_4, from position 1

[pivots]
a0x = -20.195
b0x = -29.167
"""

NOTES_6_5 = """
task = "motion"
[positions]
points = [[1, 1], [2, 0.5], [3, 1.5]]
angles = [0, 0, 0.7853981633974483]
[pivots]
A0 = [5, 0]
B0 = [0, 0]
"""

LOG10_TASK = """
task = "function"
units = { angle = "deg" }
[function]
expression = "log10(x)"
x_range = [1, 2]
input_range = [90, 150]
output_range = [0, 90]
"""

CRANK_ROCKER = """
task = "crank-rocker"
units = { length = "mm", angle = "deg" }
[crank_rocker]
ground = 100
swing = 45
time_ratio = 1.25
"""


def run(tmp_path, text, *args):
    task = tmp_path / "task.toml"
    task.write_text(text)
    return CliRunner().invoke(main, ["synth", str(task), "--out", str(tmp_path / "out"), *args])


def test_four_positions_from_a_task_file(tmp_path):
    res = run(tmp_path, NOTES_6_7)
    assert res.exit_code == 0, res.output
    assert "Mecanismos, §6.7: motion generation, 9 linkage(s)" in res.output
    # Table 7 of the notes is among them, printed in the file's unit (cm)
    number = r"(-?[\d.]+)"
    pivots = re.findall(rf"A0 \({number}, {number}\) B0 \({number}, {number}\) "
                        rf"A1 \({number}, {number}\)", res.output)
    table_7 = [-20.195, 25.566, -29.167, 42.355, -25.349, 25.379]
    assert len(pivots) == 9
    assert any(np.allclose(np.array(row, float), table_7, atol=2e-3) for row in pivots)
    out = tmp_path / "out"
    names = sorted(p.name for p in out.iterdir())
    assert "curves.png" in names and "positions.png" in names and "summary.json" in names
    assert sum(n.startswith("solution_") and n.endswith(".toml") for n in names) == 9
    summary = json.loads((out / "summary.json").read_text())
    assert summary["units"] == {"length": "cm", "angle": "deg"} and len(summary["solutions"]) == 9


def test_model_file_is_the_linkage(tmp_path):
    res = run(tmp_path, NOTES_6_5, "--no-figures")
    assert res.exit_code == 0, res.output
    m = kl.io.load(tmp_path / "out" / "solution_1.toml")          # SI once read
    np.testing.assert_allclose(m.point("A").xy, [3.547722, -1.654555], atol=1e-6)  # Table 4
    # the engine moves the model file's linkage through the three prescribed points
    P = np.array([[1, 1], [2, 0.5], [3, 1.5]])
    sol = kl.synthesis.three_positions(P, [0, 0, np.pi / 4], (5, 0), (0, 0))
    np.testing.assert_allclose(kl.analyze(m, q=sol.q).position("P"), P, atol=1e-9)
    assert not any(p.suffix == ".png" for p in (tmp_path / "out").iterdir())


def test_function_and_path_tasks(tmp_path):
    res = run(tmp_path, LOG10_TASK)
    assert res.exit_code == 0, res.output
    # the figure the command prints is the library's, for the same task in radians
    printed = float(re.search(r"max structural error ([\d.e-]+)", res.output).group(1))
    same = kl.synthesis.function_generation(np.log10, (1, 2), np.radians([90, 150]),
                                            np.radians([0, 90]))
    assert printed == pytest.approx(same.max_structural_error, rel=2e-3)
    assert printed < 1e-3                     # log10 by three Chebyshev points: well under 0.1 %
    assert (tmp_path / "out" / "solution_1.png").stat().st_size > 5000
    res = run(tmp_path, """
task = "path"
[positions]
points = [[0, 0], [0.25, 0.02], [0.5, 0.03], [0.75, 0.02], [1, 0]]
[search]
runs = 1
maxiter = 20
seed = 0
tolerance = 1e-3
""", "--json")
    assert res.exit_code == 0, res.output
    summary = json.loads(res.output)
    assert summary["task"] == "path" and summary["solutions"][0]["valid"]


def test_every_problem_of_a_task_file_at_once(tmp_path):
    res = run(tmp_path, """
task = "motion"
units = { length = "furlong" }
colour = "red"
[positions]
points = [[0, 0], [1, 1], [2, 0]]
angles = [0, 10, 20]
[pivots]
A0 = [5, 0]
a0x = 3
""")
    assert res.exit_code == 2
    for problem in ["units.length: expected one of 'm', 'cm', 'mm', 'in', got 'furlong'",
                    "colour: unknown key",
                    "pivots.a0x: not used with 3 positions",
                    "pivots: give exactly one of B0 (fixed pivot) and B1"]:
        assert problem in res.output, res.output
    assert "task.toml: " in res.output             # the file is named
    assert not (tmp_path / "out").exists()         # nothing half written


def test_synthesis_failure_is_reported(tmp_path):
    res = run(tmp_path, """
task = "motion"
[positions]
points = [[0, 0], [1, 0], [3, 0]]
angles = [0, 0, 0]
[pivots]
A1 = [0, 1]
B0 = [1, 1]
""")
    assert res.exit_code == 2
    assert "its positions are collinear" in res.output


@pytest.mark.parametrize("expr, message", [
    ("log(y)", "function.expression: the name 'y' (the only variable is 'x') is not allowed in the "
               "expression 'log(y)'; an expression may use numbers, x, pi, e"),
    ("x +* 2", "function.expression: cannot parse the expression 'x +* 2'"),
    ("__import__('os').getcwd()", "is not allowed in the expression"),
    ("9**9**9 * x", "function.expression: the power tower '9**9**9' in the expression '9**9**9 * x' "
                    "is not allowed"),
    ("log10(x - 1)", "function.expression: the expression 'log10(x - 1)' gives -inf (an overflow or "
                     "a division by zero) at x = 1; expected a finite value")])
def test_bad_formula(tmp_path, expr, message):
    res = run(tmp_path, f"""
task = "function"
[function]
expression = "{expr}"
x_range = [1, 2]
input_range = [1, 2]
output_range = [0, 1]
""")
    assert res.exit_code == 2
    assert message in res.output, res.output


def test_a_section_the_task_does_not_read_is_refused(tmp_path):
    res = run(tmp_path, NOTES_6_5 + '\n[output]\nanything = "goes"\n')
    assert res.exit_code != 0 and "output: unknown key" in res.output


def test_answers_in_the_tasks_units_or_si(tmp_path):
    cm = run(tmp_path, NOTES_6_7, "--no-figures", "--json")
    assert cm.exit_code == 0, cm.output
    si = CliRunner().invoke(main, ["synth", str(tmp_path / "task.toml"), "--out",
                                   str(tmp_path / "si"), "--no-figures", "--json", "--si"])
    assert si.exit_code == 0, si.output
    a, b = json.loads(cm.output), json.loads(si.output)
    assert a["units"] == {"length": "cm", "angle": "deg"}
    assert b["units"] == {"length": "m", "angle": "rad"}
    for row_cm, row_m in zip(a["solutions"], b["solutions"]):
        np.testing.assert_allclose(row_cm["A0"], np.array(row_m["A0"]) * 100, rtol=1e-14)
        for k, v in row_m["lengths"].items():
            assert row_cm["lengths"][k] == pytest.approx(v * 100, rel=1e-14)
        if "min_transmission_angle" in row_m:
            assert row_cm["min_transmission_angle"] == pytest.approx(
                np.degrees(row_m["min_transmission_angle"]), rel=1e-14)
    # the model files too: cm, or m with --si; the same linkage once read
    assert 'length = "cm"' in (tmp_path / "out" / "solution_1.toml").read_text()
    assert 'length = "m"' in (tmp_path / "si" / "solution_1.toml").read_text()
    one, two = (kl.load(tmp_path / d / "solution_1.toml") for d in ("out", "si"))
    np.testing.assert_allclose(one.point("A").xy, two.point("A").xy, rtol=1e-11)


@pytest.mark.parametrize("text, problem", [
    ('task = "path"\nname = "a\\u001b[31mb"\n', "name: expected a name of printable characters "
     "(no newline, tab, control character), got 'a\\x1b[31mb'"),
    ('task = "path"\nunits = { length = ["mm"] }\n',
     "units.length: expected one of 'm', 'cm', 'mm', 'in', got ['mm']"),
    ('task = "path"\n[positions]\npoints = [[0, 0], [1, true], [2, "0"]]\n',
     "positions.points: expected finite numbers of shape (n, 2), got [[0, 0], [1, true], [2, '0']]"),
    ('task = "path"\n[positions]\npoints = [[0, 0], [1, 1e300], [2, 0]]\n',
     "positions.points: expected at most 1e+09 m in size, got [[0, 0], [1, 1e+300], [2, 0]]"),
    # bounds that keep a search's time and memory within reason
    ('task = "path"\n[search]\nruns = 1000000000\n',
     "search.runs: expected a whole number from 1 to 1,000, got 1000000000"),
    ('task = "path"\n[search]\nsamples = "x"\nrefine = 1\n',
     "search.samples: expected a whole number from 24 to 10,000, got 'x'"),
    ('task = "path"\n[search]\nrefine = 1\n', "search.refine: expected true or false, got 1"),
    ('task = "path"\n[search]\ntolerance = "1e-3"\n',
     "search.tolerance: expected a positive number, got '1e-3'"),
    ('task = "path"\n[search]\ntolerance = 0\n',
     "search.tolerance: expected a positive number, got 0"),
    ('task = "path"\n[search]\npopsize = 1\n',
     "search.popsize: expected a whole number from 5 to 10,000, got 1"),
    ('task = "function"\n[function]\nexpression = "x"\nx_range = [1, 2]\ninput_range = [1, 2]\n'
     'output_range = [0, 1]\npoints = 1000000000000\n',
     "function.points: expected a whole number from 2 to 100, got 1000000000000"),
    ('task = "path"\n[positions]\npoints = [[0, ' + "9" * 5000 + ']]\n',
     "line 3, column 15: a number of more than 4300 digits; no value needs so many, write it "
     "with an exponent (1.5e3) or fix it"),
    # what a design cannot meet: the field, the feasible range, in the task's units
    (CRANK_ROCKER + "crank = 90\n",
     "crank_rocker.crank: expected a crank between 6.80657 mm and 38.2683 mm (both excluded) "
     "for ground 100 mm, swing 45 deg and time ratio 1.25, got 90 mm; no crank-rocker of this "
     "family has it"),
    (CRANK_ROCKER + "pivot_angle = 10\n",
     "crank_rocker.pivot_angle: expected an angle in (92.5, 160) or (-160, -112.5) deg for swing "
     "45 deg and time ratio 1.25, got 10 deg; elsewhere the two limit positions are on different "
     "assembly branches"),
    (CRANK_ROCKER.replace("swing = 45", "swing = 200"),
     "crank_rocker.swing: expected an angle between 0 and 180 deg (both excluded), got 200 deg; a "
     "rocker that swings half a turn or more has no limit positions"),
    (CRANK_ROCKER.replace("time_ratio = 1.25", "time_ratio = 9"),
     "crank_rocker.time_ratio: expected the slow stroke's time over the fast one's, at least 1 "
     "and less than 4.33333, got 9.0; no crank-rocker with a swing of 45 deg reaches (3 pi + "
     "swing) / (pi - swing): lower the time ratio or widen the swing"),
    (CRANK_ROCKER.replace("ground = 100\n", ""),
     "crank_rocker.ground: missing; a crank-rocker needs 'ground', 'swing', 'time_ratio'"),
    ('task = "quick-return"\n[quick_return]\nmechanism = "shaper"\ntime_ratio = 2\n',
     "quick_return.mechanism: expected one of 'offset slider-crank', 'slotted lever', "
     "'whitworth', got 'shaper'"),
    ('task = "quick-return"\n[quick_return]\nmechanism = "slotted lever"\ntime_ratio = 2\n'
     'distance = 1\nrod = 2\n',
     "quick_return.rod: not used by a slotted lever; it takes 'distance', 'time_ratio'"),
    ('task = "quick-return"\nunits = { length = "mm" }\n[quick_return]\n'
     'mechanism = "offset slider-crank"\nstroke = 100\ntime_ratio = 1.4\nrod = 500\n',
     "quick_return.rod: expected a rod between 50 mm and 186.603 mm (both excluded) for stroke "
     "100 mm and time ratio 1.4, got 500 mm"),
])
def test_bad_values_in_a_task_file_are_refused_in_one_line_each(tmp_path, text, problem):
    res = run(tmp_path, text)
    assert res.exit_code == 2, res.output
    assert f"task.toml: {problem}\n" in res.stderr, res.stderr
    assert "Traceback" not in res.output and not (tmp_path / "out").exists()


def test_a_task_file_that_is_not_utf8(tmp_path):
    task = tmp_path / "task.toml"
    task.write_bytes(b'task = "path"\nname = "\xff"\n')
    res = CliRunner().invoke(main, ["synth", str(task)])
    assert res.exit_code == 2 and res.stderr.endswith("task.toml: line 2: not UTF-8 text; save the "
                                                      "file as UTF-8\n")


# -- swing and time ratio; five and more positions -----------------------------------------
def test_crank_rocker_task_in_the_files_units(tmp_path):
    res = run(tmp_path, CRANK_ROCKER, "--json")
    assert res.exit_code == 0, res.output
    row = json.loads(res.output)["solutions"][0]
    best = kl.synthesis.crank_rocker(0.1, np.radians(45), 1.25)          # SI
    for k, v in best.lengths.items():
        assert row["lengths"][k] == pytest.approx(v * 1000, rel=1e-12)   # mm
    assert row["swing"] == pytest.approx(45, rel=1e-10)                  # deg
    assert row["time_ratio"] == pytest.approx(1.25, rel=1e-10)
    assert row["transmission_min"] == pytest.approx(np.degrees(best.transmission_min), rel=1e-12)
    # the model file, read back in SI, swings 45 deg with time ratio 1.25 by the engine
    m = kl.load(tmp_path / "out" / "solution_1.toml")
    tr = kl.kinematics.time_ratio(m, "rocker")
    th = kl.analyze(m, q=tr.dead_centres).angle("rocker")
    assert abs(np.degrees(abs(th[1] - th[0])) - 45) < 1e-9 and abs(tr.ratio - 1.25) < 1e-9
    assert (tmp_path / "out" / "solution_1.png").stat().st_size > 5000
    # with a crank, the printed line names it in mm
    res = run(tmp_path, CRANK_ROCKER + "crank = 30\n")
    assert res.exit_code == 0, res.output
    assert "crank 30.0000" in res.output and "swing 45 deg, time ratio 1.25" in res.output


@pytest.mark.parametrize("mechanism, values, output, travel", [
    ("offset slider-crank", "stroke = 100\ntime_ratio = 1.4\n", "slide", 100.0),
    ("slotted lever", "distance = 100\ntime_ratio = 2\n", "lever", 60.0),
    ("whitworth", "distance = 50\nstroke = 300\ntime_ratio = 2\n", "ram_slide", 300.0),
])
def test_quick_return_tasks(tmp_path, mechanism, values, output, travel):
    res = run(tmp_path, f'task = "quick-return"\nunits = {{ length = "mm", angle = "deg" }}\n'
                        f'[quick_return]\nmechanism = "{mechanism}"\n{values}', "--json")
    assert res.exit_code == 0, res.output
    row = json.loads(res.output)["solutions"][0]
    assert row["mechanism"] == mechanism
    assert row.get("stroke", row.get("swing")) == pytest.approx(travel, rel=1e-10)
    m = kl.load(tmp_path / "out" / "solution_1.toml")
    assert abs(kl.kinematics.time_ratio(m, output).ratio - row["time_ratio"]) < 1e-9


FIVE = """
task = "motion"
[positions]
points = {points}
angles = {angles}
"""


def test_five_and_more_positions(tmp_path):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    s = kl.analyze(fb, q=np.radians([0, 40, 80, 120, 160, 200, 240]))
    P, th = s.position("P"), s.angle("coupler")
    res = run(tmp_path, FIVE.format(points=P[:5].tolist(), angles=th[:5].tolist()), "--json")
    assert res.exit_code == 0, res.output
    rows = json.loads(res.output)["solutions"]
    assert len(rows) == len(kl.synthesis.five_positions(P[:5], th[:5])) == 6
    assert any(np.allclose(r["A0"] + r["B0"], [0, 0, 3, 0], atol=1e-9) for r in rows)
    assert (tmp_path / "out" / "curves.png").stat().st_size > 5000
    res = run(tmp_path, FIVE.format(points=P.tolist(), angles=th.tolist()) + "[search]\ndyads = 2\n",
              "--json")
    assert res.exit_code == 0, res.output
    best = json.loads(res.output)["solutions"][0]
    assert best["valid"] and np.allclose(best["A0"] + best["B0"], [0, 0, 3, 0], atol=1e-9)
    assert np.abs(best["dyad_residuals"]).max() < 1e-9 and len(best["position_errors"]) == 7
    # pivots are not chosen with five positions or more
    res = run(tmp_path, FIVE.format(points=P[:5].tolist(), angles=th[:5].tolist())
              + "[pivots]\na0x = 1\n")
    assert res.exit_code == 2 and "pivots.a0x: not used with 5 positions" in res.stderr
    res = run(tmp_path, FIVE.format(points=P[:5].tolist(), angles=th[:5].tolist())
              + "[search]\ndyads = 2\n")
    assert res.exit_code == 2 and "search.dyads: not used with 5 positions" in res.stderr


def _strict_json(text):
    """JSON as the standard has it: no Infinity or NaN."""
    def refuse(name):
        raise AssertionError(f"{name} in the JSON output")
    return json.loads(text, parse_constant=refuse)


def _path_task(points):
    return f'task = "path"\n[positions]\npoints = {points}\n[search]\nruns = 1\nmaxiter = 5\n'


def test_a_path_task_takes_at_most_thirty_points(tmp_path):
    """100 points took a minute and 600 ran out of memory; 8 million (a 48 MB file) asked for
    931 TiB: now refused in one line, before any work."""
    t = np.linspace(0, 2 * np.pi, 31, endpoint=False)
    res = run(tmp_path, _path_task(np.column_stack([np.cos(t), np.sin(t)]).tolist()))
    assert res.exit_code == 2
    assert res.stderr == ("kinelab: error: " + str(tmp_path / "task.toml") + ": positions.points: "
                          "expected 3 to 30 points (x, y), got 31; a path is given by 5 to 20 "
                          "points as a rule, so keep the points that matter or space them out\n")
    with pytest.raises(kl.errors.ModelError, match=r"^positions.points: expected 3 to 30 points \(x, y\), "
                                            r"got 8,000,000;"):
        kl.io.read_task({"task": "path", "positions": {"points": [[1, 2]] * 8_000_000}})
    task = kl.io.read_task({"task": "path", "positions": {"points": t[:30, None].repeat(2, 1).tolist()}})
    assert task.targets.shape == (30, 2)
    # coincident points are named by the task's field
    res = run(tmp_path, _path_task([[1, 2]] * 5))
    assert res.exit_code == 2
    assert res.stderr.endswith("task.toml: positions.points: points 1 and 2 coincide; give "
                               "distinct points\n"), res.stderr


FUNCTION = """
task = "function"
units = {{ angle = "deg" }}
[function]
expression = "{expression}"
x_range = [{x_range}]
input_range = [90, 150]
output_range = [{output_range}]
points = 3
ground = 1.0
"""


def test_a_function_with_a_pole_in_x_range_is_refused(tmp_path):
    res = run(tmp_path, FUNCTION.format(expression="1/(x-1.2345678901)", x_range="1, 2",
                                        output_range="0, 90"), "--json")
    assert res.exit_code == 2 and res.stdout == ""
    assert res.stderr.endswith(
        "task.toml: function.expression: expected a function continuous over x_range [1, 2], but "
        "it has a pole (it grows without bound) near x = 1.23456789; a linkage generates only a "
        "continuous function, so choose an x_range that leaves that point out\n"), res.stderr
    assert res.stderr.count("\n") == 1 and not (tmp_path / "out").exists()


def test_an_unbounded_structural_error_is_null_in_the_summary(tmp_path):
    """tan(x) over [0, 1.5] (continuous): the linkage does not close over the whole range, so
    its structural error has no bound; the summary says null, never Infinity."""
    text = FUNCTION.format(expression="tan(x)", x_range="0, 1.5", output_range="0, 90")
    res = run(tmp_path, text, "--json")
    assert res.exit_code == 0, res.output
    row = _strict_json(res.stdout)["solutions"][0]
    assert row["max_structural_error"] is None and not row["valid"]
    same = kl.synthesis.function_generation(np.tan, (0, 1.5), (90, 150), (0, 90), degrees=True)
    assert not np.isfinite(same.max_structural_error)          # the library keeps +inf
    np.testing.assert_allclose(row["precision_errors"], same.precision_errors, rtol=1e-12,
                               atol=1e-15)
    assert _strict_json((tmp_path / "out" / "summary.json").read_text()) == _strict_json(res.stdout)
    res = run(tmp_path, text, "--no-figures")
    assert "max structural error unbounded (the linkage does not close everywhere)" in res.output


def test_a_range_of_two_equal_angles_is_shown_in_the_tasks_units(tmp_path):
    res = run(tmp_path, FUNCTION.format(expression="x", x_range="2, 1", output_range="90, 90"))
    assert res.exit_code == 2
    assert res.stderr.endswith("task.toml: function.output_range: expected two different numbers "
                               "(start, end), got [90, 90] deg\n"), res.stderr
    res = run(tmp_path, FUNCTION.format(expression="x", x_range="2, 2", output_range="0, 90"))
    assert res.stderr.endswith("task.toml: function.x_range: expected two different numbers "
                               "(start, end), got [2, 2]\n"), res.stderr


@pytest.mark.parametrize("n", [3, 4, 5, 6])
def test_positions_that_all_turn_about_one_point_are_refused(tmp_path, n):
    """Six identical points at different angles printed numpy RuntimeWarnings and pivots of
    1e-317 m: every position is a turn about that point, so no four-bar is singled out."""
    pivots = {3: "[pivots]\nA0 = [5, 0]\nB0 = [0, 5]\n", 4: "[pivots]\na0x = 1\nb0x = 2\n"}
    text = (f'task = "motion"\nunits = {{ length = "cm", angle = "deg" }}\n[positions]\n'
            f'points = {[[10, 20]] * n}\nangles = {list(range(0, 10 * n, 10))}\n'
            + pivots.get(n, ""))
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # a library warning would end in a traceback
        res = run(tmp_path, text)
    assert res.exit_code == 2, res.output
    assert res.stderr.endswith(
        "task.toml: positions: every position is a turn of the plane about the same point "
        "(10, 20) cm (all the poles are there), so every crank would be pivoted at that point and "
        "no four-bar is singled out (one link pivoted there gives this motion); give positions "
        "that are not all turns about one point\n"), res.stderr
    assert res.stderr.count("\n") == 1


def test_a_motion_task_takes_at_most_a_thousand_positions():
    """Counted before the positions are read (their coincidence check is by rows)."""
    with pytest.raises(kl.errors.ModelError, match=r"^positions.points: expected at most 1,000 "
                                                   r"positions, got 1,000,000; keep the positions"):
        kl.io.read_task({"task": "motion", "positions": {"points": [[0, 0]] * 1_000_000,
                                                         "angles": [0] * 1_000_000}})
