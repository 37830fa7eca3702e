"""An imported drawing's problems are said in its own terms: a Pyslvs expression's joint
numbers and the drawing, never kinelab's names for them (P3, jP3) or its sketch; the model's
own error is kept as the cause."""
import json

import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.errors import ModelError

FOURBAR = "M[J[R, P[0, 0], L[ground, crank]], J[R, P[{a}], L[crank, coupler]], " \
          "J[R, P[{b}], L[coupler, rocker]], J[R, P[30, 0], L[ground, rocker]]]"
KINELAB_WORDS = ("sketch", "'P0'", "'P1'", "'P2'", "'P3'", "jP", "points:", "mechanism '")


def refused(text, tmp_path):
    source = tmp_path / "drawing.pyslvs"
    source.write_text(text)
    result = CliRunner().invoke(main, ["import", str(source), "--out", str(tmp_path / "m.toml")])
    assert result.exit_code == 2 and not (tmp_path / "m.toml").exists()
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinelab: error: drawing.pyslvs: ")
    assert not any(w in lines[0] for w in KINELAB_WORDS), lines[0]
    return lines[0][len("kinelab: error: drawing.pyslvs: "):]


def test_two_joints_of_a_link_at_one_place(tmp_path):
    text = FOURBAR.format(a="0, 0", b="20, 10")
    with pytest.raises(ModelError) as info:
        kl.io.from_pyslvs(text)
    assert str(info.value) == ("expression: link 'crank': its first two joints 0 and 1 coincide, "
                               "so the link has no length and no direction; move one of them")
    assert "'P0' and 'P1'" in str(info.value.__cause__)
    assert refused(text, tmp_path) == str(info.value)


def test_a_link_in_one_joint_only(tmp_path):
    text = "M[J[R, P[0, 0], L[ground, crank]], J[R, P[10, 10], L[crank, coupler]], " \
           "J[R, P[20, 10], L[crank, rocker]], J[R, P[30, 0], L[ground, rocker]]]"
    assert refused(text, tmp_path) == (
        "expression: link 'coupler': it is in joint 1 only, and a moving link needs two joints "
        "(one is enough for a link on a slider's slot, whose angle gives its direction); name it "
        "in a second joint's L[...]")


def test_a_dyad_drawn_straight(tmp_path):
    """Joints 1, 2, 3 in line (B halfway between A and O4): the drawing does not tell the
    dyad's assembly mode."""
    assert refused(FOURBAR.format(a="0, 10", b="15, 5"), tmp_path) == (
        "the drawing puts the dyad 'coupler'-'rocker' (joints 1-2-3) in a singular (straight) "
        "position, so its assembly mode is undefined; move a joint of the drawing off that line")


def test_a_linkage_drawn_flat(tmp_path):
    """All four joints on one line: Kutzbach-Gruebler counts one freedom for the one input,
    but the flat drawing allows none; the message says the drawing is at fault, not the inputs."""
    assert refused(FOURBAR.format(a="10, 0", b="20, 0"), tmp_path) == (
        "the linkage is drawn in a singular position: as drawn, its joints allow 0 motion(s) "
        "where its 1 input(s) and Kutzbach-Gruebler's count expect 1 (links drawn in line, say); "
        "draw it in a general position, with no links in line")


def test_a_linkage2d_drawing_is_the_drawing(tmp_path):
    """A linkage2d four-bar whose coupler and rocker are drawn in line (C between B and D):
    its own point names, and the drawing rather than a sketch."""
    def link(i, name, pose, points, grounded=False):
        return {"id": i, "name": name, "isGrounded": grounded,
                "pose": {"position": pose, "angle": 0},
                "points": [{"id": p, "name": p, "position": xy} for p, xy in points]}

    data = {"version": "1.0", "id": "fb", "name": "four-bar", "type": "planar_mechanism",
            "unit_length": "mm", "unit_angle": "deg", "convention": {},
            "links": [link("L1", "ground", [0, 0], [("A", [0, 0]), ("D", [300, 0])], True),
                      link("L2", "crank", [0, 0], [("A2", [0, 0]), ("B", [0, 100])]),
                      link("L3", "coupler", [0, 100], [("B3", [0, 0]), ("C", [150, -50])]),
                      link("L4", "rocker", [300, 0], [("D4", [0, 0]), ("C4", [-150, 50])])],
            "joints": [{"id": j, "name": j, "type": "revolute", "parent": p, "point_id_parent": a,
                        "child": c, "point_id_child": b}
                       for j, p, a, c, b in (("R1", "L1", "A", "L2", "A2"),
                                             ("R2", "L2", "B", "L3", "B3"),
                                             ("R3", "L3", "C", "L4", "C4"),
                                             ("R4", "L1", "D", "L4", "D4"))]}
    source = tmp_path / "fb.json"
    source.write_text(json.dumps(data))
    result = CliRunner().invoke(main, ["import", str(source), "--out", str(tmp_path / "m.toml")])
    assert result.exit_code == 2, result.output
    assert result.stderr == (
        "kinelab: error: fb.json: the drawing puts the dyad 'coupler'-'rocker' (B-C-D) in a "
        "singular (straight) position, so its assembly mode is undefined; move a joint of the "
        "drawing off that line\n")
