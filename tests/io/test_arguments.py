"""Arguments of the io functions: paths, texts, solutions, tasks and options of the wrong
kind are refused with a ModelError that names the argument."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError

FB = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
TASK = kl.io.read_task({"task": "crank-rocker", "units": {"angle": "deg"},
                        "crank_rocker": {"ground": 1.0, "swing": 45, "time_ratio": 1.25}})


@pytest.mark.parametrize("path, message", [
    (None, r"^path: expected a file's path \(text or pathlib.Path\), got None$"),
    (5, r"^path: expected a file's path .*got 5$"),
    (b"x.toml", r"^path: expected a file's path .*got b'x.toml'; decode it first"),
    ("", r"^path: expected a file's path .*got ''$"),
])
@pytest.mark.parametrize("call", [
    lambda p: kl.io.save(FB, p), lambda p: kl.io.load(p), lambda p: kl.io.load_task(p),
    lambda p: kl.io.read_curve(p), lambda p: kl.io.write_results(kl.analyze(FB, 0.0), p),
], ids=["save", "load", "load_task", "read_curve", "write_results"])
def test_a_path_is_text_or_path_like(call, path, message):
    with pytest.raises(ModelError, match=message):
        call(path)


@pytest.mark.parametrize("source", [None, 5, b"l.json"])
def test_a_linkage2d_source_is_a_path_or_its_data(source):
    with pytest.raises(ModelError, match=r"^source: expected a file's path"):
        kl.io.from_linkage2d_json(source)


@pytest.mark.parametrize("data, message", [
    ({"links": []}, r"^linkage2d data: joints: missing; this field is required$"),
    ({"joints": []}, r"^linkage2d data: links: missing; this field is required$"),
    ({}, r"links: missing.*\n.*joints: missing"),
])
def test_linkage2d_data_without_links_or_joints_says_so(data, message, tmp_path):
    with pytest.raises(ModelError, match=message):
        kl.io.from_linkage2d_json(data)
    f = tmp_path / "l.json"
    f.write_text('{"links": []}')
    with pytest.raises(ModelError, match=r"^l.json: joints: missing"):
        kl.io.from_linkage2d_json(f)


@pytest.mark.parametrize("parse", [kl.io.from_toml, kl.io.from_json])
@pytest.mark.parametrize("text, message", [
    (None, r"^text: expected the (TOML|JSON) text itself \(a str\), got None; to read a file, use its path$"),
    (5, r"^text: expected the .* got 5"),
    (b"schema = 1", r"^text: expected the .* got b'schema = 1'; decode it first"),
    ("", r"^expected (TOML|JSON) text, got an empty text$"),
    ("  \n", r"^expected (TOML|JSON) text, got blank text$"),
])
def test_model_text_is_text(parse, text, message):
    with pytest.raises(ModelError, match=message):
        parse(text)


def _curve(tmp_path):
    f = tmp_path / "c.csv"
    f.write_text("t [s],x [mm]\n" + "".join(f"{k},{k * k}\n" for k in range(20)))
    return f


def test_curve_columns_by_number(tmp_path):
    f = _curve(tmp_path)
    by_number = kl.io.read_curve(f, x=2, y=1)
    by_text = kl.io.read_curve(f, x="2", y=np.int64(1))
    assert by_number.x_name == by_text.x_name == "x" and by_number.y[3] == 3.0


@pytest.mark.parametrize("options, message", [
    (dict(x=5), r"c.csv: x: expected a column of the file, by name or number from 1, got 5; the columns are 't', 'x'"),
    (dict(y=2.5), r"^y: expected a column's name or its number from 1, got 2.5$"),
    (dict(x=True), r"^x: expected a column's name or its number from 1, got true$"),
    (dict(x=["t"]), r"^x: expected a column's name or its number from 1, got \['t'\]$"),
])
def test_curve_columns_of_the_wrong_kind(options, message, tmp_path):
    with pytest.raises(ModelError, match=message):
        kl.io.read_curve(_curve(tmp_path), **options)


@pytest.mark.parametrize("sol, message", [
    (FB, r"^sol: expected a KinematicSolution, got a Mechanism; analyze it first"),
    (None, r"^sol: expected a KinematicSolution, got None"),
])
def test_results_need_a_solution(sol, message, tmp_path):
    with pytest.raises(ModelError, match=message):
        kl.io.write_results(sol, tmp_path / "r.csv")
    with pytest.raises(ModelError, match=message):
        kl.io.results_json(sol)
    assert not (tmp_path / "r.csv").exists()


@pytest.mark.parametrize("call, message", [
    (lambda: kl.io.solve_task({}), r"^task: expected a Task \(from load_task or read_task\), got a table$"),
    (lambda: kl.io.task_summary(None, [], {}), r"^task: expected a Task"),
    (lambda: kl.io.task_summary(TASK, [1, 2], {}), r"^solutions\[0\]: expected a linkage found by solve_task, got 1$"),
    (lambda: kl.io.task_summary(TASK, None, {}), r"^solutions: expected the list of solutions solve_task returns, got None$"),
    (lambda: kl.io.task_summary(TASK, [], None), r"^extra: expected the table of extra results solve_task returns, got None$"),
    (lambda: kl.io.task_summary(TASK, [], {}, units=5), r"^units: expected a mapping"),
])
def test_task_functions_check_their_arguments(call, message):
    with pytest.raises(ModelError, match=message):
        call()


def test_a_task_summary_in_other_units():
    sols, extra = kl.io.solve_task(TASK)
    summary = kl.io.task_summary(TASK, sols, extra, units={"length": "mm"})
    assert summary["units"] == {"length": "mm", "angle": "rad"}


@pytest.mark.parametrize("section", ["pivots", "search", "units"])
@pytest.mark.parametrize("value", [None, 5])
def test_a_task_section_that_is_not_a_table_is_one_problem(section, value):
    data = {"task": "motion", "positions": {"points": [[0, 0], [1, 0], [2, 1]], "angles": [0, 0.3, 0.6]},
            section: value}
    with pytest.raises(ModelError, match=fr"^{section}: expected a table, got {value if value else 'None'}$"):
        kl.io.read_task(data)


def test_a_task_takes_numpy_whole_numbers():
    data = {"task": "path", "positions": {"points": [[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.6]]},
            "search": {"runs": np.int64(2), "seed": np.uint32(3)}}
    task = kl.io.read_task(data)
    assert task.search["runs"] == 2 and type(task.search["runs"]) is int


@pytest.mark.parametrize("write", [kl.io.to_svg, kl.io.to_dxf])
def test_drawing_options_are_known_ones(write, tmp_path):
    with pytest.raises(ModelError, match=r"^'bogus': unknown option; the options of a drawing are "
                                         r"unit, layout, 'width', 'hole', 'ground', 'sol'$"):
        write(FB, tmp_path / "x.drw", bogus=1)
    with pytest.raises(ModelError, match=r"^'wdth': unknown option \(did you mean 'width'\?\)"):
        write(FB, tmp_path / "x.drw", wdth=0.1)


@pytest.mark.parametrize("options, message", [
    (dict(sol=5), r"^sol: expected a KinematicSolution of the model .* or None, got 5$"),
    (dict(ground="yes"), r"^ground: expected True or False, got 'yes'$"),
])
def test_outline_options_are_checked(options, message):
    with pytest.raises(ModelError, match=message):
        kl.io.outlines(FB, **options)
