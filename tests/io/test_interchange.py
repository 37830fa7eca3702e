"""Pyslvs expressions and linkage2d files in; Pyslvs expressions, SVG and DXF out."""
import math
import re

import ezdxf
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.errors import ModelError
from tests.io.test_modelfile import CATALOGUE

# A crank-rocker written by hand in Pyslvs' form (mm): crank 10, coupler 30, rocker 25, ground 30,
# coupler point P3 15 along and 10 to the left of AB; B from the two circles, open branch.
CRANK_ROCKER = """
# a comment, as Pyslvs allows
M[
  J[R, color[Green], P[0.0, 0.0], L[ground, crank]],
  J[R, color[Green], P[0.0, 10.0], L[crank, coupler, ]],
  J[R, color[(10, 20, 30)], P[26.1506227, 24.7018682], L[coupler, rocker]],
  J[R, P[8.1746886, 26.0678084], L[coupler]],
  J[R, color[Blue], P[30, 0], L[ground, rocker]],
]
"""
SLIDER_CRANK_RP = "M[J[R, P[0, 0], L[ground, crank]], J[R, P[0, 5], L[crank, rod]], " \
                  "J[RP, A[0], P[19.7737199, 2], L[ground, rod]]]"
SLIDER_CRANK_P = "M[J[R, P[0, 0], L[ground, crank]], J[R, P[0, 5], L[crank, rod]], " \
                 "J[P, A[0], P[19.7737199, 2], L[ground, slider, rod]]]"


def test_pyslvs_crank_rocker_matches_the_catalogue():
    m = kl.io.from_pyslvs(CRANK_ROCKER)
    assert m.point_names == ("P0", "P1", "P2", "P3", "P4")
    assert m.link("coupler").points == ("P1", "P2", "P3")
    assert m.link("rocker").points == ("P4", "P2")          # from its ground pivot
    assert m.inputs[0].joint == "jP0" and m.point("P4").xy == (0.03, 0.0)
    fb = kl.mechanisms.fourbar(0.03, 0.01, 0.03, 0.025, coupler_point=(0.015, 0.01))
    q = np.radians(np.arange(0.0, 360.0, 10.0))
    a, b = kl.analyze(m, q), kl.analyze(fb, q)
    np.testing.assert_allclose(a.angle("rocker"), b.angle("rocker"), rtol=0, atol=1e-8)
    np.testing.assert_allclose(a.position("P3"), b.position("P"), rtol=0, atol=1e-10)


@pytest.mark.parametrize("expr, slide", [(SLIDER_CRANK_RP, "sP2"), (SLIDER_CRANK_P, "sP2")])
def test_pyslvs_sliders_match_the_catalogue(expr, slide):
    m = kl.io.from_pyslvs(expr)
    sc = kl.mechanisms.slider_crank(0.005, 0.02, offset=0.002)
    q = np.radians(np.arange(0.0, 360.0, 15.0))
    a, b = kl.analyze(m, q), kl.analyze(sc, q)
    np.testing.assert_allclose(a.position("P2"), b.position("B"), rtol=0, atol=1e-10)
    np.testing.assert_allclose(a.slide(slide), b.slide("slide"), rtol=0, atol=1e-10)


def test_pyslvs_input_pairs():
    m = kl.io.from_pyslvs(CRANK_ROCKER, inputs=[(4, 2)])       # drive the rocker instead
    assert m.inputs[0].joint == "jP4"
    m = kl.io.from_pyslvs(SLIDER_CRANK_RP, inputs=[(2, 2)])     # drive the slide
    assert m.joint(m.inputs[0].joint).type == "P"


@pytest.mark.parametrize("name", CATALOGUE)
def test_pyslvs_round_trip_of_every_catalogue_mechanism(name):
    m = CATALOGUE[name]()
    expr = kl.io.to_pyslvs(m)
    back = kl.io.from_pyslvs(expr)
    assert kl.io.to_pyslvs(back).splitlines()[1:] == expr.splitlines()[1:]
    q = float(kl.kinematics.plan(m).q_sketch[0]) + np.radians(np.linspace(-15, 15, 7)) \
        if len(m.inputs) == 1 else kl.kinematics.plan(m).q_sketch + np.radians(np.linspace(-9, 9, 7))[:, None]
    a, b = kl.analyze(m, q), kl.analyze(back, q)
    for i, p in enumerate(m.point_names):        # point i is Pyslvs joint i
        np.testing.assert_allclose(b.position(f"P{i}"), a.position(p), rtol=0, atol=1e-9)


@pytest.mark.parametrize("expr, message", [
    ("", "expression: the end: expected 'M[' (the mechanism), got 'the end'"),
    ("M[J[Q, P[0, 0], L[a]]]", "expression: joint 0: type: expected one of 'R', 'P', 'RP', got 'Q'"),
    ("M[J[R, P[0, 0] L[a]]]", "expression: character 16: expected ',', got 'L['"),
    ("M[J[P, P[0, 0], L[ground, a]]]", "expression: joint 0: a P joint needs its slot angle, A[degrees]"),
    ("M[J[P, A[1e300], P[0, 0], L[ground, a]]]", "expression: joint 0: the slot angle: expected "
     "angles within 1000 turns of 0 either way, got 1e+300 deg"),
    ("M[J[R, P[0, x], L[a]]]", "expression: character 13: expected a number (y), got 'x'"),
    ("M[J[R, P[0, 0], L[]]]", "expression: joint 0: it joins no link; attach it or delete it"),
    ("M[J[R, P[0, 0], L[a, b]]]", "expression: no joint is on the ground link; name the fixed link 'ground'"),
    ("M[] x", "expression: character 5: unexpected 'x' after the mechanism"),
    ("M[J[R, P[0, 0], L[a]]] @", "expression: character 24: unexpected '@'; expected the Pyslvs form "
     "M[J[R, P[x, y], L[a, b]], ...]"),
])
def test_bad_pyslvs_expressions(expr, message):
    with pytest.raises(ModelError) as info:
        kl.io.from_pyslvs(expr)
    assert str(info.value) == message


def test_pyslvs_inputs_must_be_joint_pairs():
    with pytest.raises(ModelError, match=r"inputs\[0\]: expected a pair of joint numbers from 0 to 4, got \(0, 9\)"):
        kl.io.from_pyslvs(CRANK_ROCKER, inputs=[(0, 9)])
    with pytest.raises(ModelError, match="no link carries both joint 0 and joint 2"):
        kl.io.from_pyslvs(CRANK_ROCKER, inputs=[(0, 2)])


@given(st.text(alphabet="MJRPAL[](),.0123456789- abground#\n", max_size=80))
def test_random_pyslvs_text_raises_only_model_error(text):
    try:
        kl.io.from_pyslvs(text)
    except ModelError:
        pass


def test_to_pyslvs_refuses_names_pyslvs_cannot_hold():
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    import dataclasses
    links = tuple(dataclasses.replace(k, name="coupler link") if k.name == "coupler" else k
                  for k in fb.links)
    joints = tuple(dataclasses.replace(j, links=tuple("coupler link" if n == "coupler" else n
                                                      for n in j.links)) for j in fb.joints)
    bad = kl.Mechanism(fb.name, fb.points, links, joints, fb.inputs)
    with pytest.raises(ModelError, match="link 'coupler link': Pyslvs names links with letters"):
        kl.io.to_pyslvs(bad)


# -- linkage2d --------------------------------------------------------------------------
def _link(lid, name, pose, points, grounded=False, directions=(), lines=()):
    return {"id": lid, "name": name, "isGrounded": grounded,
            "pose": {"position": list(pose[:2]), "angle": pose[2]},
            "points": [{"id": k, "name": k, "position": list(v)} for k, v in points.items()],
            "directions": [{"id": k, "name": k, "angle": a} for k, a in directions],
            "lines": [{"id": k, "name": k, "point_ids": list(v)} for k, v in lines],
            "circles": [], "arcs": []}


def _doc(links, joints, unit="mm"):
    return {"version": "1.0", "id": "t", "name": "t", "type": "planar_mechanism",
            "unit_length": unit, "unit_angle": "deg", "convention": {}, "links": links,
            "joints": joints}


def _rev(jid, parent, p, child, c):
    return {"id": jid, "name": jid, "type": "revolute", "parent": parent, "point_id_parent": p,
            "child": child, "point_id_child": c}


# slider-crank: crank 50, rod 200, offset 20 (mm); links drawn in arbitrary poses
SLIDER = _doc(
    [_link("L1", "ground", (0, 0, 0), {"O": (0, 0), "G": (0, 20)}, True, [("x", 0)]),
     _link("L2", "crank", (10, 10, 70), {"O2": (0, 0), "A": (50, 0)}),
     _link("L3", "rod", (30, 60, -20), {"A3": (0, 0), "B": (200, 0)}),
     _link("L4", "slider", (150, 30, 5), {"B4": (0, 0)}, directions=[("x4", 0)])],
    [_rev("R1", "L1", "O", "L2", "O2"), _rev("R2", "L2", "A", "L3", "A3"),
     _rev("R3", "L3", "B", "L4", "B4"),
     {"id": "P1", "name": "slide", "type": "prismatic", "parent": "L1",
      "axis_parent": {"point_id": "G", "direction_id": "x"}, "child": "L4",
      "axis_child": {"point_id": "B4", "direction_id": "x4"}}])


def test_linkage2d_slider_crank_is_assembled_and_matches_the_catalogue():
    m = kl.io.from_linkage2d_json(SLIDER)
    assert m.joint("slide").type == "P" and m.joint("slide").links == ("ground", "slider")
    sc = kl.mechanisms.slider_crank(0.05, 0.2, offset=0.02)
    q = np.radians(np.arange(0.0, 360.0, 20.0))
    a, b = kl.analyze(m, q), kl.analyze(sc, q)
    # the drawing's poses were nearest the right-hand assembly
    np.testing.assert_allclose(a.position("B"), b.position("B"), rtol=0, atol=1e-9)


def test_linkage2d_pin_in_slot_and_weld():
    # Erthal's slotted link (R = 100, C = 200 mm); the lever is two welded parts
    data = _doc(
        [_link("G", "ground", (0, 0, 0), {"O4": (0, 0), "O2": (200, 0)}, True),
         _link("K", "crank", (200, 0, 90), {"O2k": (0, 0), "A": (100, 0)}),
         _link("V", "lever", (0, 0, 20), {"O4v": (0, 0), "E": (150, 0)}, lines=[("slot", ("O4v", "E"))]),
         _link("V2", "lever tip", (0, 0, 0), {"T": (300, 0)})],
        [_rev("R1", "G", "O2", "K", "O2k"), _rev("R2", "G", "O4", "V", "O4v"),
         {"id": "S", "name": "slot", "type": "pin-in-slot", "parent": "V", "line_id_parent": "slot",
          "child": "K", "point_id_child": "A"},
         {"id": "W", "name": "weld", "type": "weld", "parent": "V", "child": "V2",
          "relative_pos": [0, 0], "relative_angle": 0}])
    m = kl.io.from_linkage2d_json(data, input="R1")
    assert "lever tip" not in m.link_names and "T" in m.link("lever").points
    assert m.link("slot_block").points == ("A",)
    ref = kl.mechanisms.slotted_link(0.1, 0.2)
    q = np.radians(np.arange(5.0, 360.0, 20.0))
    a, b = kl.analyze(m, q), kl.analyze(ref, q)
    np.testing.assert_allclose(a.angle("lever"), b.angle("lever"), rtol=0, atol=1e-9)
    np.testing.assert_allclose(np.hypot(*a.position("T").T), 0.3, rtol=0, atol=1e-12)


@pytest.mark.parametrize("change, message", [
    (lambda d: d.update(unit_length="px"), "t.json: unit_length: expected one of 'mm', 'cm', 'm', "
     "'in', got 'px'"),
    (lambda d: d["joints"].append({"id": "g", "type": "gear", "parent": "L1", "child": "L2",
                                   "ratio": 2, "phase_offset": 0}),
     "t.json: joints[4]: gear joints are not supported yet; remove the gear or replace it"),
    (lambda d: d["joints"][0].update(point_id_child="Q"),
     "t.json: joints[0].point_id_child: expected a declared point, got 'Q'; declared points are 'O2', 'A'"),
    (lambda d: d["links"][0]["points"][1].update(position=[0, 500]),   # slide out of reach
     "t.json: joints: the links cannot be assembled"),
    # beyond the model's limits, one problem each (the link stays known to its joints)
    (lambda d: d["links"][2]["pose"].update(position=[1e300, 0]),
     "t.json: links[2].pose.position: expected at most 1e+09 m in size, got [1e+300, 0]"),
    (lambda d: d["links"][2]["points"][1].update(position=[0, 2e12]),    # mm
     "t.json: links[2].points[1].position: expected at most 1e+09 m in size, got [0, 2000000000000.0]"),
    (lambda d: d["links"][1]["pose"].update(angle=1e300),
     "t.json: links[1].pose.angle: expected angles within 1000 turns of 0 either way, got 1e+300"),
    (lambda d: d["links"][3]["directions"][0].update(angle=-4e5),
     "t.json: links[3].directions[0].angle: expected angles within 1000 turns of 0 either way"),
])
def test_bad_linkage2d_files(change, message, tmp_path):
    import copy
    import json
    data = copy.deepcopy(SLIDER)
    change(data)
    (tmp_path / "t.json").write_text(json.dumps(data))
    with pytest.raises(ModelError) as info:
        kl.io.from_linkage2d_json(tmp_path / "t.json")
    assert str(info.value).startswith(message)
    assert len(info.value.problems) == 1


# -- outlines ----------------------------------------------------------------------------
def _svg_arc_centres(d: str):
    """Centres of the arcs of an SVG path (endpoint parametrisation, SVG spec F.6.5)."""
    tokens = re.findall(r"[MLAZ]|-?[\d.]+(?:e-?\d+)?", d)
    centres, i, cur = [], 0, None
    while i < len(tokens):
        t = tokens[i]
        if t in "ML":
            cur = np.array([float(tokens[i + 1]), float(tokens[i + 2])])
            i += 3
        elif t == "A":
            r = float(tokens[i + 1])
            large, sweep = int(tokens[i + 4]), int(tokens[i + 5])
            end = np.array([float(tokens[i + 6]), float(tokens[i + 7])])
            mid, half = (cur + end) / 2, (end - cur) / 2
            h = math.sqrt(max(r * r - half @ half, 0.0))
            n = np.array([-half[1], half[0]]) / np.linalg.norm(half)
            sign = 1 if large != sweep else -1
            centres.append(mid + sign * h * n)
            cur = end
            i += 8
        else:
            i += 1
    return centres


def test_svg_outlines_round_every_hole_and_draw_each_link(tmp_path):
    fb = kl.mechanisms.fourbar(0.3, 0.1, 0.3, 0.25, coupler_point=(0.15, 0.1))
    text = kl.io.to_svg(fb, tmp_path / "fb.svg", layout="assembly", width=0.02, hole=0.008).read_text()
    assert [g for g in re.findall(r'<g id="([^"]+)"', text)] == ["crank", "coupler", "rocker"]
    holes = [np.array([float(x), float(y)]) for x, y in re.findall(r'cx="([-\d.]+)" cy="([-\d.]+)"', text)]
    assert len(holes) == 7 and 'r="4.000000"' in text            # mm, 8 mm holes
    for d in re.findall(r'class="outline" d="([^"]+)"', text):
        for c in _svg_arc_centres(d):       # every rounded corner turns about a hole
            # (to 0.01 mm: a half circle's centre is ill-conditioned in the 6-decimal text)
            assert min(np.linalg.norm(c - h) for h in holes) < 1e-2
    assert 'width="' in text and 'mm"' in text


def test_dxf_outlines_with_slot_spanning_the_travel(tmp_path):
    mf = kl.io.ModelFile.read("examples/slotted_link.toml")
    sol = kl.analyze(mf.mechanism, *mf.sample_inputs(73))
    path = kl.io.to_dxf(mf.mechanism, tmp_path / "sl.dxf", layout="assembly", sol=sol)
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    assert doc.units == ezdxf.units.MM
    slots = [e for e in msp if e.dxf.layer == "SLOTS"]
    assert len(slots) == 1 and slots[0].closed
    xy = np.array([(p[0], p[1]) for p in slots[0].get_points("xy")])
    along = xy @ np.array([2, 1]) / math.sqrt(5)       # the slot's axis
    # the slot spans the block's travel along the lever: C - R = 100 mm to C + R = 300 mm
    assert along.min() == pytest.approx(100.0, abs=1e-6) and along.max() == pytest.approx(300.0, abs=1e-6)
    assert sum(e.dxftype() == "CIRCLE" for e in msp) == 5       # crank 2, block 1, lever 2
    assert all(e.closed for e in msp if e.dxftype() == "LWPOLYLINE")


def test_outline_options_are_checked():
    fb = kl.mechanisms.fourbar(0.3, 0.1, 0.3, 0.25)
    with pytest.raises(ModelError, match=r"width, hole: expected 0 < hole < width"):
        kl.io.outlines(fb, width=0.01, hole=0.02)
    with pytest.raises(ModelError, match="unit: expected one of"):
        kl.io.to_svg(fb, "x.svg", unit="ft")


def test_export_and_import_commands(tmp_path):
    from click.testing import CliRunner
    from kinelab.cli import main

    def run(*args):
        return CliRunner().invoke(main, [str(a) for a in args])
    for target in ("svg", "dxf", "pyslvs", "json"):
        r = run("export", "examples/whitworth.toml", "--to", target, "--out", tmp_path)
        assert r.exit_code == 0, r.output
        assert (tmp_path / f"whitworth.{target}").stat().st_size > 100
    r = run("import", tmp_path / "whitworth.pyslvs", "--out", tmp_path / "w.toml")
    assert r.exit_code == 0, r.output
    assert "inputs jP1" in r.stdout
    r = run("analyze", tmp_path / "w.toml", "--out", tmp_path, "--samples", "37")
    assert r.exit_code == 0 and "time ratio of sP4: 2 " in r.stdout, r.output
    assert kl.load(tmp_path / "whitworth.json") == kl.load("examples/whitworth.toml")
    bad = tmp_path / "bad.pyslvs"
    bad.write_text("M[J[R, P[0, 0], L[ground]]")
    r = run("import", bad, "--out", tmp_path / "b.toml")
    assert r.exit_code == 2
    assert r.stderr == "kinelab: error: bad.pyslvs: expression: the end: expected ']' (the end " \
                       "of the mechanism), got 'the end'\n"
    assert not (tmp_path / "b.toml").exists()


_l2d_values = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(-5, 5), st.floats(-1e3, 1e3), st.floats(),
              st.sampled_from(["L1", "L2", "L3", "L4", "O", "A", "B", "G", "x", "revolute",
                               "prismatic", "pin-in-slot", "weld", "gear", "mm"])),
    lambda inner: st.one_of(st.lists(inner, max_size=3), st.dictionaries(st.sampled_from(
        ["id", "name", "type", "parent", "child", "point_id_parent", "point_id_child", "points",
         "position", "pose", "angle", "axis_parent", "axis_child", "point_id", "direction_id",
         "directions", "lines", "point_ids", "line_id_parent", "relative_pos", "relative_angle",
         "isGrounded"]), inner, max_size=4)), max_leaves=10)


@given(st.sampled_from(["links", "joints"]), st.integers(0, 3),
       st.sampled_from(["id", "type", "parent", "child", "point_id_parent", "point_id_child",
                        "points", "pose", "axis_parent", "axis_child", "directions", "isGrounded"]),
       _l2d_values)
def test_corrupted_linkage2d_data_raises_only_model_error(section, index, key, value):
    import copy
    data = copy.deepcopy(SLIDER)
    data[section][index][key] = value
    try:
        kl.io.from_linkage2d_json(data)
    except ModelError:
        pass


def test_pyslvs_inputs_get_the_import_speeds():
    """100 rpm for a crank, 0.1 m/s for a slide: Pyslvs gives none, and zero would leave
    every velocity and acceleration of the imported model at zero."""
    crank = kl.io.from_pyslvs(CRANK_ROCKER)
    assert crank.inputs[0].speed == kl.io.IMPORT_SPEEDS["angle"] == pytest.approx(10 * math.pi / 3)
    slide = kl.io.from_pyslvs(SLIDER_CRANK_RP, inputs=[(2, 2)])
    assert slide.inputs[0].speed == kl.io.IMPORT_SPEEDS["slide"] == 0.1
    both = kl.io.from_pyslvs(CRANK_ROCKER, inputs=[(4, 2)])
    assert both.inputs[0].speed == kl.io.IMPORT_SPEEDS["angle"]


@pytest.mark.parametrize("options, message", [
    ({"width": 1j}, r"^width, hole: expected 0 < hole < width, got width 1j m and hole "),
    ({"width": "5"}, r"^width, hole: expected 0 < hole < width, got width '5' m"),
    ({"unit": ["mm"]}, r"^unit: expected one of 'm', 'cm', 'mm', 'in', got \['mm'\]$"),
    ({"layout": {}}, r"^layout: expected one of 'parts', 'assembly', got a table$"),
    ({"width": 1e305}, r"^width: expected a length from 1e-09 m to 1e\+09 m, got 1e\+305 m$"),
    ({"width": 1e-303}, r"^width: expected a length from 1e-09 m to 1e\+09 m, got 1e-303 m$"),
    ({"width": 0.02, "hole": 1e-300}, r"^hole: expected a length from 1e-09 m"),
])
def test_outline_options_of_the_wrong_kind_are_refused(options, message, tmp_path):
    fb = kl.mechanisms.fourbar(ground=0.3, crank=0.1, coupler=0.3, rocker=0.25)
    with pytest.raises(ModelError, match=message):
        kl.io.to_svg(fb, tmp_path / "fb.svg", **options)
    assert not (tmp_path / "fb.svg").exists()
