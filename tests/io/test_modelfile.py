"""Model files: examples, units, round trips, and every kind of bad file."""
import dataclasses
import json
import math
import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.io import ModelFile, Units
from tests.io.bad_cases import BASE, CASES, JSON_CASES

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))

CATALOGUE = {
    "fourbar": lambda: kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
    "fourbar_crossed": lambda: kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, branch="crossed"),
    "slider_crank": lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.4, branch="left"),
    "inverted_slider_crank": lambda: kl.mechanisms.inverted_slider_crank(2.0, 1.0, offset=0.2),
    "slotted_link": lambda: kl.mechanisms.slotted_link(1.0, 2.0),
    "whitworth": lambda: kl.mechanisms.whitworth(1.0, 0.5, 1.0, 2.0),
    "fivebar": lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0, branch="down"),
    "watt6": kl.mechanisms.watt6,
    "stephenson6": kl.mechanisms.stephenson6,
    "watt6_lengths": lambda: kl.mechanisms.watt6(
        lengths={"O2-A": 0.8, "A-B": 4.0, "O4-B": 4.2, "C-D": 2.0}, branch=("crossed", "open")),
    "stephenson6_lengths": lambda: kl.mechanisms.stephenson6(
        points={"A": (0.0, 2.0)}, lengths={"B-C": 2.0, "D-O6": 3.5}, branch=("open", "crossed")),
    "triad6": kl.mechanisms.triad6,
}


def _sweep(m):
    if len(m.inputs) == 2:
        t = np.radians(np.arange(0.0, 360.0, 10.0))
        return np.stack([np.pi / 2 + 0.3 * np.sin(t), np.pi / 2 + 0.3 * np.cos(t)], axis=-1)
    return float(kl.kinematics.plan(m).q_sketch[0]) + np.radians(np.linspace(-20.0, 20.0, 9))


# -- the bundled examples ----------------------------------------------------------------
@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_examples_sweep_without_singular_or_unassembled_samples(path):
    mf = ModelFile.read(path)
    q, qd, qdd = mf.sample_inputs()
    sol = kl.analyze(mf.mechanism, q, qd, qdd)
    assert sol.assembled.all() and not sol.singular.any()
    assert mf.units.length in ("mm", "cm")


def test_crank_rocker_is_read_in_si():
    mf = ModelFile.read(ROOT / "examples" / "crank_rocker.toml")
    m = mf.mechanism
    assert mf.units == Units("mm", "deg")
    assert m.point("O4").xy == (0.3, 0.0)          # 300 mm
    # drawn by eye, with exact lengths: assembled to them, near the sketch
    for a, b, length in (("O2", "A", 0.1), ("A", "B", 0.3), ("O4", "B", 0.25)):
        assert math.dist(m.point(a).xy, m.point(b).xy) == pytest.approx(length, rel=1e-12)
    assert math.dist(m.point("A").xy, (0.0, 0.1)) < 1e-3
    # the crank is drawn at its length, straight up: at that input only the dyad moves
    assert set(mf.assembly.moved) == {"B", "P"}
    assert m.point("A").xy == pytest.approx((0.0, 0.1), abs=1e-15)
    inp = m.inputs[0]
    assert inp.range == (0.0, pytest.approx(2 * math.pi, abs=1e-15))
    assert inp.speed == pytest.approx(600 * math.pi / 180, rel=1e-15)      # 600 deg/s
    assert mf.samples == (361,)
    assert mf.outputs.report == ("rocker", "coupler", "P")
    assert mf.outputs.transmission == (("coupler", "rocker"),)
    assert kl.load(ROOT / "examples" / "crank_rocker.toml") == m


def test_examples_match_the_catalogue_geometry():
    # the crank-rocker file is fourbar(0.3, 0.1, 0.3, 0.25, coupler_point=(0.15, 0.1)) with the
    # crank at 90 degrees: the same rocker angle at every crank angle, to the sketch's rounding
    m = kl.load(ROOT / "examples" / "crank_rocker.toml")
    fb = kl.mechanisms.fourbar(0.3, 0.1, 0.3, 0.25, coupler_point=(0.15, 0.1))
    q = np.radians(np.arange(0.0, 360.0, 15.0))
    a, b = kl.analyze(m, q), kl.analyze(fb, q)
    np.testing.assert_allclose(a.angle("rocker"), b.angle("rocker"), rtol=0, atol=1e-8)
    np.testing.assert_allclose(a.position("P"), b.position("P"), rtol=0, atol=1e-9)


# -- round trips ---------------------------------------------------------------------------
@pytest.mark.parametrize("name", CATALOGUE)
@pytest.mark.parametrize("fmt", ["toml", "json"])
def test_catalogue_round_trip_in_si_is_exact(name, fmt, tmp_path):
    m = CATALOGUE[name]()
    path = kl.io.save(m, tmp_path / f"{name}.{fmt}")
    back = kl.load(path)
    assert back == m
    assert back.parameters == m.parameters
    q = _sweep(m)
    a, b = kl.analyze(m, q, 1.0), kl.analyze(back, q, 1.0)
    np.testing.assert_array_equal(a.jets, b.jets)
    np.testing.assert_array_equal(a.rates, b.rates)


@pytest.mark.parametrize("name", CATALOGUE)
def test_catalogue_round_trip_in_mm_and_degrees(name, tmp_path):
    m = CATALOGUE[name]()
    path = kl.io.save(m, tmp_path / f"{name}.toml", units={"length": "mm", "angle": "deg"})
    text = path.read_text()
    assert 'length = "mm"' in text and 'angle = "deg"' in text
    back = kl.load(path)
    assert back.link_names == m.link_names and back.joints == m.joints
    assert back.parameters.keys() == m.parameters.keys()
    # the digits written in mm and degrees read back as the very same floats
    assert back == m and back.parameters == m.parameters
    q = _sweep(m)
    a, b = kl.analyze(m, q, 1.0, 0.5), kl.analyze(back, q, 1.0, 0.5)
    np.testing.assert_array_equal(b.jets, a.jets)
    np.testing.assert_array_equal(b.rates, a.rates)


UNITS = [{"length": length, "angle": angle} for length in ("mm", "cm", "in", "m")
         for angle in ("deg", "rad")]


@pytest.mark.parametrize("units", UNITS, ids=lambda u: f"{u['length']}-{u['angle']}")
def test_round_trips_in_every_unit_are_exact(units):
    models = [kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
              kl.synthesis.fourbar_model((0.1, 0.2), (3.3, -0.7), (1.1, 0.3), (2.9, 1.7))]
    models += [kl.load(p) for p in EXAMPLES]
    for m in models:
        assert kl.io.from_toml(kl.io.to_toml(m, units=units)) == m, m.name
        assert kl.io.from_json(kl.io.to_json(m, units=units)) == m, m.name


@given(st.lists(st.floats(-1e3, 1e3, allow_nan=False).filter(lambda v: abs(v) > 1e-6),
                min_size=4, max_size=4))
def test_any_coordinate_round_trips_exactly_in_mm_and_inches(xy):
    """Of the floats in metres, some are no float in mm times 0.001: the file's digits are
    read as written (one rounding), and written as the shortest that read back exactly."""
    from kinelab.io._text import in_si, written
    for scale in (0.001, 0.01, 0.0254, math.pi / 180):
        for v in xy:
            text = kl.io._toml._value(written(v, scale))
            assert in_si(kl.io._text.Written(text), scale) == v, (v, scale, text)
            assert float(text) == pytest.approx(v / scale, rel=1e-15)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_model_file_round_trip_keeps_units_samples_and_outputs(path, tmp_path):
    mf = ModelFile.read(path)
    again = ModelFile.from_toml(mf.to_toml())
    assert again == mf
    assert ModelFile.from_json(mf.to_json()) == mf
    mf.write(tmp_path / "copy.json")
    assert ModelFile.read(tmp_path / "copy.json") == mf


def test_inputs_round_trip_with_degrees_converted():
    m = kl.mechanisms.slider_crank(0.05, 0.2)
    m = dataclasses.replace(m, inputs=(kl.model.Input(joint="jO2", range=(0.0, math.pi),
                                                      speed=2 * math.pi, acceleration=1.0),))
    text = kl.io.to_toml(m, units={"length": "mm", "angle": "deg"})
    assert "range = [0.0, 180.0]" in text and "speed = 360.0" in text
    back = kl.io.from_toml(text)
    assert back.inputs[0].range == (0.0, pytest.approx(math.pi, rel=1e-15))
    assert back.inputs[0].acceleration == pytest.approx(1.0, rel=1e-12)


def test_catalogue_short_form_builds_the_catalogue_mechanism():
    text = BASE.split("[points]")[0] + (
        '[catalogue]\nkind = "slider_crank"\ncrank = 50\nrod = 200\noffset = 20\n'
        '\n[[inputs]]\njoint = "jO2"\nrange = [0, 180]\nspeed = 360\n')
    m = kl.io.from_toml(text)
    ref = kl.mechanisms.slider_crank(0.05, 0.2, offset=0.02)
    assert m.points == ref.points and m.links == ref.links and m.joints == ref.joints
    assert m.name == "fb" and m.inputs[0].speed == pytest.approx(2 * math.pi, rel=1e-15)
    assert m.parameters == ref.parameters


def test_catalogue_short_form_builds_a_six_bar_from_its_lengths():
    text = ('schema = 1\nname = "w6"\n\n[units]\nlength = "mm"\nangle = "deg"\n\n[catalogue]\n'
            'kind = "watt6"\nlengths = { "O2-A" = 800, "B-A" = 4000, "O4-B" = 4200 }\n'
            'branch = ["crossed", "open"]\n')
    m = kl.io.from_toml(text)
    ref = kl.mechanisms.watt6(lengths={"O2-A": 0.8, "B-A": 4.0, "O4-B": 4.2}, branch=("crossed", "open"))
    assert m.points == ref.points and m.links == ref.links and m.joints == ref.joints
    assert m.parameters == ref.parameters
    assert m.parameters["lengths"]["A-B"] == 4.0 and m.parameters["branch"] == ("crossed", "open")
    # written back: the lengths in mm under their link's spelling, the modes as a list
    text = kl.io.to_toml(m, units={"length": "mm", "angle": "deg"})
    assert 'branch = ["crossed", "open"]' in text and "A-B = 4000.0" in text


def test_a_length_within_the_tolerance_is_accepted():
    m = kl.io.from_toml(BASE.replace("length = 100", "length = 100.00005"))   # 5e-7 relative
    assert m.link("crank").points == ("O2", "A")


def test_joint_named_after_its_point_and_axis_given_as_an_angle():
    m = kl.load(ROOT / "examples" / "offset_slider_crank.toml")
    assert m.joint_names == ("jO2", "jA", "jB", "slide")
    assert m.joint("slide").axis == (1.0, 0.0)


# -- the sweep -----------------------------------------------------------------------------
def test_sweep_without_range_covers_the_reachable_interval():
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)  # non-Grashof
    q, qd, qdd = ModelFile(fb).sample_inputs(11)
    hi = math.acos(-5 / 16)
    assert q[0] == pytest.approx(-hi, abs=1e-8) and q[-1] == pytest.approx(hi, abs=1e-8)
    sol = kl.analyze(fb, q)
    assert sol.assembled.all()
    full = ModelFile(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)).sample_inputs(5)[0]
    np.testing.assert_allclose(full, np.linspace(0, 2 * np.pi, 5), rtol=0, atol=1e-15)


def test_sweep_without_range_covers_an_interval_the_search_window_cuts():
    """Sketched at q = 1.5 rad, the one-turn search window around the sketch ends at
    1.5 - pi, inside the reachable interval |q| <= acos(-5/16): both pieces are swept."""
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    at = kl.analyze(fb, 1.5)
    data = fb.to_dict()
    data["points"] = {name: at.position(name).tolist() for name in data["points"]}
    m = kl.model.Mechanism.from_dict(data)
    hi = math.acos(-5 / 16)
    assert kl.kinematics.reachable_ranges(m) == [pytest.approx((-hi, hi), abs=1e-9)]
    q = ModelFile(m).sample_inputs(11)[0]
    assert q[0] == pytest.approx(-hi, abs=1e-8) and q[-1] == pytest.approx(hi, abs=1e-8)


def test_grid_sweep_takes_every_combination():
    mf = ModelFile.read(ROOT / "examples" / "fivebar.toml")
    q = dataclasses.replace(mf, sweep="grid").sample_inputs(4)[0]
    assert q.shape == (16, 2)
    np.testing.assert_allclose(np.degrees(q[:4]), [[90, 0], [90, 120], [90, 240], [90, 360]],
                               rtol=0, atol=1e-12)
    together = mf.sample_inputs(4)[0]
    np.testing.assert_allclose(np.degrees(together), [[90, 0], [210, 120], [330, 240], [450, 360]],
                               rtol=0, atol=1e-12)


def test_samples_must_agree_when_inputs_move_together():
    text = (ROOT / "examples" / "fivebar.toml").read_text().replace("samples = 361", "samples = 10", 1)
    with pytest.raises(ModelError, match=r"^five.toml: inputs: samples: expected the same number "
                       r"for every input when sweep = 'together', got \[10, 361\]"):
        ModelFile.from_toml(text, source="five.toml")


# -- bad files -----------------------------------------------------------------------------
def test_there_are_at_least_thirty_distinct_bad_files():
    assert len(CASES) >= 30
    assert len({text for _, text, _ in CASES}) == len(CASES)


@pytest.mark.parametrize("name, text, message", [("fb.toml", *c[1:]) for c in CASES]
                         + [("fb.json", *c[1:]) for c in JSON_CASES],
                         ids=[c[0] for c in CASES] + [f"json: {c[0]}" for c in JSON_CASES])
def test_bad_file_gives_one_line_naming_file_and_field(name, text, message, tmp_path):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(ModelError) as info:
        kl.load(path)
    assert str(info.value) == message
    assert "\n" not in str(info.value)


def test_every_problem_is_reported_at_once():
    text = BASE.replace('length = "mm"', 'length = "mmm"').replace("speed = 600", 'speed = "x"')
    with pytest.raises(ModelError) as info:
        ModelFile.from_toml(text, source="fb.toml")
    assert info.value.problems == (
        "units.length: expected one of 'm', 'cm', 'mm', 'in', got 'mmm' (did you mean 'mm'?)",
        "inputs[0].speed: expected a number, got 'x'")


@pytest.mark.parametrize("name, content, message", [
    ("fb.yaml", BASE, "fb.yaml: expected a .toml or .json model file, got '.yaml'; rename it or "
     "convert it (kinelab import reads Pyslvs and linkage2d files)"),
    ("fb.toml", b"schema = 1\nname = \"\xff\"\n", "fb.toml: line 2: not UTF-8 text; save the file as UTF-8"),
    ("fb.json", '{"schema": 1,}', "fb.json: line 1, column 14: JSON syntax error: Expecting property "
     "name enclosed in double quotes; fix the syntax there"),
    ("fb.json", "[1, 2]", "fb.json: expected a table, got [1, 2]"),
])
def test_bad_file_names_and_encodings(name, content, message, tmp_path):
    path = tmp_path / name
    path.write_bytes(content if isinstance(content, bytes) else content.encode())
    with pytest.raises(ModelError) as info:
        kl.load(path)
    assert str(info.value) == message


def test_reading_and_checking_is_linear_in_the_size_of_the_file():
    # 20,000 links carrying 100,000 points, each pinned to the ground, which carries 20,001:
    # a walk through a list of names for each name read is 1e9 steps (minutes, hours on a
    # slow machine); with dictionaries it is seconds.  60 s leaves room for a slow machine.
    # The model is far beyond the size kinelab plans (MAX_LINKS): it is read, then refused.
    points, links, joints = {"g": [-1.0, 0.0]}, [], []
    for k in range(20_000):
        names = [f"p{k}_{i}" for i in range(5)]
        points.update({n: [float(k), float(i)] for i, n in enumerate(names)})
        links.append({"name": f"l{k}", "points": names})
        joints.append({"type": "R", "links": ["ground", f"l{k}"], "point": names[0]})
    links.insert(0, {"name": "ground", "points": ["g"] + [j["point"] for j in joints], "ground": True})
    text = json.dumps({"schema": 1, "units": {"length": "m", "angle": "rad"}, "points": points,
                       "links": links, "joints": joints})
    start = time.perf_counter()
    with pytest.raises(ModelError) as info:
        ModelFile.from_json(text, source="big.json")
    assert time.perf_counter() - start < 60.0
    assert str(info.value).splitlines() == [
        "big.json: links: expected at most 200, got 20,001; a model that large takes minutes to "
        "plan (its constraint Jacobian grows as the cube of the size): model the mechanism in parts",
        "big.json: joints: expected at most 400, got 20,000; a model that large takes minutes to "
        "plan (its constraint Jacobian grows as the cube of the size): model the mechanism in parts",
        "big.json: points: expected at most 2,000, got 100,001; every point is solved at every "
        "sample: keep the joints' points and those you report or draw"]


def test_a_model_at_the_size_limit_is_planned():
    """A crank driving 99 RRR dyads side by side: 200 links, the most a model may have."""
    from kinelab.model import MAX_LINKS
    points, links, joints = {"O": [0.0, 0.0], "A": [0.0, 0.1]}, [], []
    ground = ["O"]
    for i in range((MAX_LINKS - 2) // 2):
        a = 2 * np.pi * i / 99
        points[f"G{i}"] = [np.cos(a), np.sin(a)]
        points[f"C{i}"] = [0.5 * np.cos(a) - 0.3 * np.sin(a), 0.05 + 0.5 * np.sin(a) + 0.3 * np.cos(a)]
        ground.append(f"G{i}")
        links += [{"name": f"a{i}", "points": ["A", f"C{i}"]}, {"name": f"b{i}", "points": [f"C{i}", f"G{i}"]}]
        joints += [{"name": f"jA{i}", "type": "R", "links": ["crank", f"a{i}"], "point": "A"},
                   {"name": f"jC{i}", "type": "R", "links": [f"a{i}", f"b{i}"], "point": f"C{i}"},
                   {"name": f"jG{i}", "type": "R", "links": ["ground", f"b{i}"], "point": f"G{i}"}]
    links = [{"name": "ground", "points": ground, "ground": True},
             {"name": "crank", "points": ["O", "A"]}] + links
    joints.insert(0, {"name": "jO", "type": "R", "links": ["ground", "crank"], "point": "O"})
    text = json.dumps({"schema": 1, "units": {"length": "m", "angle": "rad"}, "points": points,
                       "links": links, "joints": joints, "inputs": [{"joint": "jO"}]})
    m = ModelFile.from_json(text, source="limit.json").mechanism
    assert len(m.links) == MAX_LINKS
    sol = kl.analyze(m, [0.0, 0.1])
    assert sol.assembled.all()


def test_missing_file(tmp_path):
    with pytest.raises(ModelError, match=r"nope\.toml: no such file; check the path$"):
        kl.load(tmp_path / "nope.toml")


def test_json_and_toml_give_the_same_model():
    data = json.dumps(__import__("tomllib").loads(BASE))
    assert kl.io.from_json(data) == kl.io.from_toml(BASE)


# -- fuzzing: nothing but ModelError may escape --------------------------------------------
def _load_text(text: str, suffix: str):
    try:
        (ModelFile.from_toml if suffix == "toml" else ModelFile.from_json)(text, source="f")
    except ModelError:
        pass


@given(st.text(max_size=300))
def test_random_text_raises_only_model_error(text):
    _load_text(text, "toml")
    _load_text(text, "json")


_lines = [line for line in BASE.splitlines(keepends=True)]


@given(st.lists(st.integers(0, len(_lines) - 1), max_size=6), st.text(max_size=12),
       st.sampled_from(["toml", "json"]))
def test_mangled_model_files_raise_only_model_error(drop, noise, suffix):
    lines = [line for i, line in enumerate(_lines) if i not in drop]
    if drop:
        lines.insert(drop[0], noise + "\n")
    text = "".join(lines)
    if suffix == "json":
        try:
            text = json.dumps(__import__("tomllib").loads(text))
        except Exception:
            return
    _load_text(text, suffix)


_scalars = st.one_of(st.none(), st.booleans(), st.integers(-10**20, 10**20),
                     st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=6),
                     st.sampled_from(["O2", "A", "B", "ground", "crank", "R", "P", "jO2", "mm", "deg"]))
_values = st.recursive(_scalars, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.sampled_from(
        ["name", "points", "links", "joints", "type", "point", "axis", "ground", "range", "joint",
         "length", "angle", "kind", "crank", "x", "report"]), inner, max_size=4)), max_leaves=12)


@given(st.fixed_dictionaries({}, optional={
    "schema": st.one_of(st.just(1), _scalars), "units": st.one_of(
        st.just({"length": "mm", "angle": "deg"}), _values),
    "points": st.one_of(st.dictionaries(st.sampled_from(["O2", "A", "B"]),
                                        st.lists(st.floats(-1e3, 1e3), min_size=2, max_size=2)),
                        _values),
    "links": _values, "joints": _values, "inputs": _values, "catalogue": _values,
    "outputs": _values, "name": _scalars, "sweep": _scalars, "space": _scalars}))
def test_random_structured_dicts_raise_only_model_error(data):
    try:
        ModelFile.from_dict(data, source="f")
    except ModelError:
        pass


@given(st.sampled_from(list(CATALOGUE)), st.sampled_from(["links", "joints", "inputs", "points"]),
       st.integers(0, 6), st.sampled_from(["name", "points", "links", "type", "point", "axis",
                                             "joint", "range", "ground", "origin"]), _values)
def test_one_corrupted_field_raises_only_model_error(name, section, index, key, value):
    data = ModelFile(CATALOGUE[name]()).to_dict()
    data.pop("catalogue", None)
    items = data[section]
    if isinstance(items, list) and items:
        entry = items[index % len(items)]
        entry[key] = value
    elif isinstance(items, dict):
        items[list(items)[index % len(items)]] = value
    try:
        ModelFile.from_dict(data, source="f")
    except ModelError:
        pass


def test_a_file_far_larger_than_any_model_is_refused_before_it_is_read(tmp_path):
    from kinelab.io._text import MAX_BYTES
    path = tmp_path / "huge.toml"
    path.write_text("schema = 1\n# " + "x" * MAX_BYTES + "\n")
    with pytest.raises(ModelError, match=r"huge\.toml: the file is 8\.0 MiB; expected at most 8 MiB "
                                         r"\(a model, task or drawing file is a few kilobytes\)$"):
        kl.load(path)


@pytest.mark.parametrize("units", [None, {"length": "mm", "angle": "deg"}])
def test_a_catalogue_table_is_written_only_when_it_reads_back(units):
    flat = kl.synthesis.fourbar_model((0, 0), (3, 0), (1, 0), (2, 0))     # 1 + 1 + 1 = 3
    assert flat.parameters["kind"] == "fourbar"
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    no_lengths = dataclasses.replace(fb, parameters={"kind": "fourbar"})
    for m in (flat, no_lengths):
        text = kl.io.to_toml(m, units=units)
        assert "[catalogue]" not in text
        assert kl.io.from_toml(text) == m
        assert kl.io.from_json(kl.io.to_json(m, units=units)) == m
    text = kl.io.to_toml(fb, units=units)
    assert "[catalogue]" in text and kl.io.from_toml(text).parameters == fb.parameters


@pytest.mark.parametrize("name", ["crank_rocker", "offset_slider_crank", "stephenson6", "whitworth",
                                  "jansen"])
def test_a_model_through_json_numbers_is_the_same_model(name):
    """A float stands for the digits it prints as: the JSON form of a file in mm and degrees,
    sent as plain JSON numbers (as the web page does), reads back as the file itself."""
    mf = ModelFile.read(f"examples/{name}.toml")
    assert ModelFile.from_dict(json.loads(json.dumps(mf.to_dict()))) == mf


@pytest.mark.parametrize("written", ["300." + "0" * 5000 + "1", "3.0e" + "0" * 5000 + "2"])
def test_a_number_of_thousands_of_digits_is_the_float_nearest_it(written):
    """Python turns at most 4300 digits into a whole number: such a number is read as the
    float nearest it, not converted digit by digit."""
    text = Path("examples/crank_rocker.toml").read_text()
    mf = ModelFile.from_toml(text.replace("O4 = [300, 0]", f"O4 = [{written}, 0]"))
    assert mf == ModelFile.read("examples/crank_rocker.toml")
