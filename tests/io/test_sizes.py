"""Files whose size is in their counts: a model of many points, a drawing of many points, a
Pyslvs expression of many joints or a long comment, refused (or read) in a few seconds, and
a linkage2d drawing that joins the same links twice refused."""
import copy
import json

import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.errors import ModelError
from kinelab.model import MAX_POINTS
from tests.io.test_interchange import SLIDER

EXAMPLE = open("examples/crank_rocker.toml").read()
TOO_MANY = rf"points: expected at most {MAX_POINTS:,}, got 100,00\d; every point is solved at every sample"


def test_points_no_link_carries_are_counted_before_they_are_read(tmp_path):
    extra = "".join(f"X{i} = [{i}, 1]\n" for i in range(100_000))
    path = tmp_path / "orphans.toml"
    path.write_text(EXAMPLE.replace("P = [82, 261]\n", "P = [82, 261]\n" + extra))
    with pytest.raises(ModelError, match=rf"^orphans\.toml: {TOO_MANY}"):
        kl.load(path)


def test_a_coupler_of_many_points_is_refused_by_the_count(tmp_path):
    n = 100_000
    points = "".join(f"C{i} = [{i % 300}, {i // 300 + 300}]\n" for i in range(n))
    names = ", ".join(f'"C{i}"' for i in range(n))
    path = tmp_path / "coupler.toml"
    path.write_text(EXAMPLE.replace("P = [82, 261]\n", "P = [82, 261]\n" + points)
                    .replace('points = ["A", "B", "P"]', f'points = ["A", "B", "P", {names}]'))
    r = CliRunner().invoke(main, ["check", str(path)])
    assert r.exit_code == 2 and r.stderr.count("\n") == 1
    assert "coupler.toml: points: expected at most 2,000, got 100,005" in r.stderr


def test_a_model_at_the_points_limit_is_taken(tmp_path):
    points = "".join(f"C{i} = [{i % 40}, {i // 40 + 300}]\n" for i in range(MAX_POINTS - 5))
    path = tmp_path / "many.toml"
    path.write_text(EXAMPLE.replace("P = [82, 261]\n", "P = [82, 261]\n" + points))
    assert len(kl.load(path).points) == MAX_POINTS


def test_a_model_of_many_points_is_refused_in_python_too():
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    extra = tuple(kl.model.Point(f"X{i}", 0.0, float(i)) for i in range(MAX_POINTS))
    with pytest.raises(ModelError, match=r"points: expected at most 2,000, got 2,004"):
        kl.model.Mechanism(fb.name, fb.points + extra, fb.links, fb.joints, fb.inputs)


def test_long_names_cost_no_more_than_their_reading(tmp_path):
    """2 MB of names: a model's, a point's, a link's: refused by their length, quoted cut
    in the messages."""
    big = "n" * 1_000_000
    text = (EXAMPLE.replace('name = "crank-rocker"', f'name = "{big}"')
            .replace("P = [82, 261]", f'"{big}P" = [82, 261]')
            .replace('points = ["A", "B", "P"]', f'points = ["A", "B", "{big}P"]')
            .replace("local = { P = [150, 100] }", f'local = {{ "{big}P" = [150, 100] }}')
            .replace('"P"]', f'"{big}Q"]'))
    path = tmp_path / "names.toml"
    path.write_text(text)
    with pytest.raises(ModelError) as info:
        kl.load(path)
    assert len(str(info.value)) < 1000
    assert "name: expected a non-empty text of at most 200 characters, got 1,000,000" in str(info.value)


def _linkage2d(tmp_path, change) -> str:
    data = copy.deepcopy(SLIDER)
    change(data)
    path = tmp_path / "d.json"
    path.write_text(json.dumps(data))
    return str(path)


def test_a_drawing_of_many_points_is_refused_before_it_is_solved(tmp_path):
    path = _linkage2d(tmp_path, lambda d: d["links"][2]["points"].extend(
        {"id": f"X{i}", "name": f"X{i}", "position": [i % 100, i // 100]} for i in range(100_000)))
    with pytest.raises(ModelError, match=rf"^d\.json: {TOO_MANY}"):
        kl.io.from_linkage2d_json(path)


@pytest.mark.parametrize("change, message", [
    (lambda d: d["joints"].append(copy.deepcopy(d["joints"][0])),
     "d.json: joints[4].id: 'R1' is already the id of joints[0]; give each joint its own id"),
    (lambda d: d["joints"].append({**copy.deepcopy(d["joints"][0]), "id": "R9", "name": "R9"}),
     "d.json: joints[4]: joins the same links at the same places as joints[0]; remove one"),
    # the same joint seen from its other link
    (lambda d: d["joints"].append({"id": "R9", "name": "R9", "type": "revolute", "parent": "L2",
                                   "point_id_parent": "O2", "child": "L1", "point_id_child": "O"}),
     "d.json: joints[4]: joins the same links at the same places as joints[0]; remove one"),
])
def test_a_drawing_that_joins_the_same_links_twice_is_refused(tmp_path, change, message):
    with pytest.raises(ModelError) as info:
        kl.io.from_linkage2d_json(_linkage2d(tmp_path, change))
    assert str(info.value) == message
    r = CliRunner().invoke(main, ["import", str(tmp_path / "d.json"), "-o", str(tmp_path / "m.toml")])
    assert r.exit_code == 2 and r.stderr == f"kinelab: error: {message}\n"
    assert not (tmp_path / "m.toml").exists()


def test_two_joints_of_one_pair_at_different_places_are_not_a_repeat(tmp_path):
    """Two pins between the same links at different points weld them: the model says so,
    not the import."""
    def change(d):
        d["links"][1]["points"].append({"id": "C", "name": "C", "position": [25, 0]})
        d["links"][0]["points"].append({"id": "C0", "name": "C0", "position": [0, 0]})
        d["joints"].append({"id": "R9", "name": "R9", "type": "revolute", "parent": "L1",
                            "point_id_parent": "C0", "child": "L2", "point_id_child": "C"})
    with pytest.raises(ModelError) as info:
        kl.io.from_linkage2d_json(_linkage2d(tmp_path, change))
    assert "the same links at the same places" not in str(info.value)


FOURBAR = "M[J[R, P[0, 0], L[ground, a]], J[R, P[0, 10], L[a, b]], J[R, P[26, 25], L[b, c]], " \
          "J[R, P[30, 0], L[ground, c]]]"


@pytest.mark.parametrize("comment", ["#[\n" * 100_000, "#[ open\n" + "x\n" * 100_000,
                                     "#" * 2_000_000 + "\n", "#[ a #] b\n" * 50_000])
def test_pyslvs_comments_are_skipped_once(comment):
    """An unclosed '#[' was looked for to the end once per line: minutes for 10^5 lines.
    Unclosed, it is a line comment as Pyslvs reads it."""
    if comment.startswith("#[ open"):
        with pytest.raises(ModelError, match=r"expression: character 9: expected 'M\['"):
            kl.io.from_pyslvs(comment + FOURBAR)
    else:
        assert len(kl.io.from_pyslvs(comment + FOURBAR).joints) == 4


def test_a_closed_pyslvs_comment_spans_lines():
    m = kl.io.from_pyslvs("#[ a\nb\nc #] rest of the line\n" + FOURBAR)
    assert len(m.joints) == 4


def test_a_pyslvs_expression_of_many_joints_is_refused_as_it_is_read():
    text = "M[" + "J[R, P[0, 0], L[ground, a]], " * (MAX_POINTS + 10) + "]"
    with pytest.raises(ModelError, match=r"expression: expected at most 2,000 joints, got more"):
        kl.io.from_pyslvs(text)


def test_the_inputs_comment_is_found_among_many_hashes():
    text = "#" * 100_000 + " m: inputs (pivot joint, driven joint) = [(3, 2)]\n" + FOURBAR
    assert kl.io.from_pyslvs(text).inputs[0].joint == "jP3"
