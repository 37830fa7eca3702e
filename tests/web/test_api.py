"""The server's API against kinelab's own analysis and the command line's files."""
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from starlette.testclient import TestClient

import kinelab as kl
from kinelab import kinematics
from kinelab.cli import main
from kinelab.io import ModelFile
from kinelab.web import MAX_BODY, MAX_SAMPLES, create_app
from kinelab.web import _api

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url="http://127.0.0.1:8000") as c:
        yield c


def model_of(name):
    mf = ModelFile.read(EXAMPLES / f"{name}.toml")
    return mf, mf.to_dict()


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.mark.parametrize("name", ["crank_rocker", "stephenson6", "offset_slider_crank", "fivebar"])
def test_analyze_answers_what_the_command_line_writes(client, tmp_path, name):
    mf, model = model_of(name)
    model_file = tmp_path / f"{name}.json"
    model_file.write_text(json.dumps(model))        # the same content the page sends
    r = cli("analyze", model_file, "--format", "json", "--samples", 7, "--out", tmp_path / "out.json", "-q")
    assert r.exit_code == 0, r.output
    answer = client.post("/api/analyze", json={"model": model, "samples": 7})
    assert answer.status_code == 200
    assert answer.json() == json.loads((tmp_path / "out.json").read_text())
    assert answer.text == (tmp_path / "out.json").read_text()


def test_a_malformed_model_gets_the_command_lines_message(client, tmp_path):
    _, model = model_of("crank_rocker")
    model["links"][2]["points"] = ["A", "B", "Q"]
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(model))
    r = cli("analyze", bad, "--out", tmp_path)
    assert r.exit_code == 2
    lines = [line.removeprefix("kinelab: error: ") for line in r.output.strip().splitlines()]
    answer = client.post("/api/analyze", json={"model": model, "source": "bad.json"})
    assert answer.status_code == 400
    assert answer.json() == {"error": "\n".join(lines),
                             "problems": [line.removeprefix("bad.json: ") for line in lines]}
    assert "links[2].points" in answer.json()["error"]


def test_study_columns_are_kinelabs_analysis(client):
    mf, model = model_of("crank_rocker")
    s = client.post("/api/study", json={"model": model, "samples": 37}).json()
    q = np.radians(np.linspace(0, 360, 37))
    sol = kl.analyze(mf.mechanism, q, qd=mf.mechanism.inputs[0].speed)
    # mm and deg: converted here by hand, not by the code under test
    assert np.allclose(s["columns"]["P.x[mm]"], sol.position("P")[:, 0] * 1000, rtol=0, atol=1e-9)
    assert np.allclose(s["columns"]["rocker.omega[deg/s]"], np.degrees(sol.omega("rocker")),
                       rtol=1e-12, atol=1e-9)
    assert np.allclose(s["columns"]["coupler.L[deg/deg^2]"], np.degrees(sol.L("coupler")) / np.degrees(1) ** 2,
                       rtol=1e-12, atol=1e-12)
    mu = np.degrees(np.reshape(kinematics.transmission_angle(sol, ("coupler", "rocker")), -1))
    assert np.allclose(s["columns"]["coupler-rocker.transmission[deg]"], mu, rtol=0, atol=1e-9)
    assert s["units"] == {"length": "mm", "angle": "deg"}
    assert s["drawing"]["traced"] == ["P"]


def test_change_points_and_singular_samples_are_marked(client):
    # a parallelogram changes branch at 0 and 180 deg (its change points)
    model = {"schema": 1, "name": "parallelogram", "units": {"length": "m", "angle": "deg"},
             "catalogue": {"kind": "fourbar", "ground": 2.0, "crank": 1.0, "coupler": 2.0,
                           "rocker": 1.0},
             "inputs": [{"joint": "jO2", "range": [0, 360], "speed": 1}]}
    s = client.post("/api/study", json={"model": model, "samples": 73}).json()
    sol = ModelFile.from_dict(model).analyze(73)
    assert [c["q"] for c in s["change_points"]] == pytest.approx(
        [math.degrees(c.q) for c in sol.change_points], abs=1e-9)
    assert s["singular"] == np.flatnonzero(sol.singular).tolist()
    assert s["change_points"] and all(abs(s["columns"]["jO2.q[deg]"][c["index"]] - c["q"]) <= 2.5
                                      for c in s["change_points"])


def test_configuration_is_the_engines_with_its_instant_centres(client):
    mf, model = model_of("crank_rocker")
    c = client.post("/api/configuration", json={"model": model, "q": 40}).json()
    sol = kl.analyze(mf.mechanism, math.radians(40), qd=mf.mechanism.inputs[0].speed)
    assert c["points"]["B"] == pytest.approx((sol.position("B") * 1000).tolist(), abs=1e-9)
    assert c["values"]["rocker.alpha[deg/s^2]"] == pytest.approx(
        math.degrees(float(sol.alpha("rocker"))), rel=1e-12)
    ic = kinematics.instant_centers(sol)
    centres = {tuple(x["links"]): x for x in c["centres"]}
    assert len(centres) == 6
    assert centres["coupler", "rocker"]["position"] == pytest.approx((sol.position("B") * 1000).tolist(), abs=1e-9)
    assert centres["ground", "coupler"]["position"] == pytest.approx(
        (np.reshape(ic["ground", "coupler"].position, 2) * 1000).tolist(), abs=1e-9)
    assert set(c["polygons"]) == {"velocity", "acceleration"}


@pytest.mark.parametrize("name, q", [("crank_rocker", 40), ("slotted_link", 60)])
def test_the_polygons_are_kinematics_polygons_in_the_models_units(client, name, q):
    mf, model = model_of(name)
    c = client.post("/api/configuration", json={"model": model, "q": q}).json()
    m, u = mf.mechanism, mf.units
    sol = kl.analyze(m, math.radians(q), qd=m.inputs[0].speed, qdd=m.inputs[0].acceleration)
    vp, ap = kinematics.velocity_polygon(sol), kinematics.acceleration_polygon(sol)
    scale = 1 / u.length_scale
    for answer, polygon in ((c["polygons"]["velocity"], vp), (c["polygons"]["acceleration"], ap)):
        assert set(answer["vertices"]) == set(m.point_names)
        for p, v in polygon.vertices.items():
            assert answer["vertices"][p] == pytest.approx((v * scale).tolist(), rel=1e-12, abs=1e-12)
        assert [(s["point"], s["reference"]) for s in answer["sides"]] == list(polygon.sides)
        for side in answer["sides"]:
            ref = polygon.sides[side["point"], side["reference"]]
            assert side["vector"] == pytest.approx((ref.vector * scale).tolist(), rel=1e-12, abs=1e-12)
            # each side closes: its vector is its end vertex minus its start vertex, and the
            # sum of its parts (acceleration)
            end, start = (polygon.vertex(side["point"]), polygon.vertex(side["reference"]))
            assert side["vector"] == pytest.approx(((end - start) * scale).tolist(), abs=1e-9)
            if side["parts"]:
                total = np.sum([v for v in side["parts"].values()], axis=0)
                assert total == pytest.approx(side["vector"], abs=1e-9)
    # and the velocities are the engine's point velocities
    assert c["polygons"]["velocity"]["vertices"]["A"] == pytest.approx(
        (sol.velocity("A") * scale).tolist(), rel=1e-12)
    if name == "slotted_link":
        parts = {k for s in c["polygons"]["acceleration"]["sides"] for k in s["parts"]}
        assert {"normal", "tangential", "coriolis", "sliding"} <= parts


def test_a_drag_follows_the_pointer_along_the_path_and_keeps_the_lengths(client):
    mf, model = model_of("crank_rocker")
    target = [40.0, 250.0]
    c = client.post("/api/drag", json={"model": model, "point": "P", "to": target}).json()
    P = np.array(c["points"]["P"])
    # nearest on the whole path: no sample of a fine independent sweep comes nearer
    sol = kl.analyze(mf.mechanism, np.radians(np.linspace(0, 360, 7201)))
    path = sol.position("P") * 1000
    assert np.hypot(*(P - target)) <= np.hypot(*(path - target).T).min() + 1e-9
    pts = {k: np.array(v) for k, v in c["points"].items()}
    for a, b, length in [("O2", "A", 100), ("A", "B", 300), ("O4", "B", 250)]:
        assert np.hypot(*(pts[a] - pts[b])) == pytest.approx(length, rel=1e-12)


@pytest.mark.parametrize("name, point", [("crank_rocker", "P"), ("stephenson6", "C"),
                                         ("stephenson6", "A"), ("whitworth", "D"), ("jansen", "G")])
def test_a_drag_is_one_solve_and_as_near_as_a_search_along_the_path(client, monkeypatch, name, point):
    """The nearest place on the path between the nearest sample's neighbours, found on the
    path's expansion about the sample (K and L of the sweep), then one solve by the tracker:
    as near to the pointer as a golden-section search of the tracker's positions (to 1e-7
    of the path's size), and never farther than the nearest sample."""
    mf, model = model_of(name)
    ready = _api.prepare({"model": model})
    solves = []
    tracker = ready.tracker

    class Counting:
        def __getattr__(self, attr):
            return getattr(tracker, attr)

        def __call__(self, *args, **kwargs):
            solves.append(args)
            return tracker(*args, **kwargs)
    monkeypatch.setattr(ready, "tracker", Counting())
    ls = mf.units.length_scale
    path = ready.sol.position(point) / ls
    size = float(np.max(np.ptp(path[ready.sol.assembled], axis=0)))
    row = tracker.point_names.index(point)
    rng = np.random.default_rng(7)
    for k in range(12):
        j = int(rng.integers(ready.sol.N))
        to = (path[j] + rng.normal(size=2) * 0.03 * size).tolist()
        solves.clear()
        c = client.post("/api/drag", json={"model": model, "point": point, "to": to,
                                           "parts": []}).json()
        assert len(solves) == 1 and set(c) == {"q", "points", "singular"}
        near = math.dist(c["points"][point], to)
        gaps = np.hypot(*(path - to).T)
        i = int(np.nanargmin(gaps))
        assert near <= gaps[i] * (1 + 1e-9)
        # golden section on the tracker's positions between the neighbours, to 1e-13
        a, b = ready.sol.q[max(i - 1, 0), 0], ready.sol.q[min(i + 1, ready.sol.N - 1), 0]
        gap = lambda q: math.dist(tracker.positions(float(q))[row] / ls, to)     # noqa: E731
        g = (math.sqrt(5) - 1) / 2
        while b - a > 1e-13:
            c1, c2 = b - g * (b - a), a + g * (b - a)
            a, b = (a, c2) if gap(c1) < gap(c2) else (c1, b)
        assert near <= gap(a) + 1e-7 * size


def test_a_drag_narrowed_to_parts_answers_them_as_the_configuration_does(client):
    mf, model = model_of("whitworth")
    c = client.post("/api/drag", json={"model": model, "point": "C", "to": [10.0, 95.0],
                                       "parts": ["guides", "centres"]}).json()
    assert set(c) == {"q", "points", "singular", "guides", "centres"}
    full = client.post("/api/configuration", json={"model": model, "q": c["q"][0]}).json()
    assert full["points"] == c["points"] and full["guides"] == c["guides"]
    assert full["centres"] == c["centres"]
    r = client.post("/api/drag", json={"model": model, "point": "C", "to": [10.0, 95.0],
                                       "parts": ["everything"]})
    assert r.status_code == 400 and r.json()["error"].startswith(
        "parts: expected a list of some of 'values', 'centres', 'guides', 'turns', 'polygons', "
        "got")


@pytest.mark.parametrize("name", ["whitworth", "slotted_link"])
def test_the_guides_turn_with_their_links(client, name):
    """Each prismatic joint's slide direction, in the sweep and in one configuration: along
    the guide link as it turns (the slot along the lever O4-C), kinelab's slide_axes."""
    mf, model = model_of(name)
    s = client.post("/api/study", json={"model": model}).json()
    sol = kl.analyze(mf.mechanism, np.radians(s["columns"]["jO2.q[deg]"]))
    for joint in ("slot", "ram_slide") if name == "whitworth" else ("slot",):
        np.testing.assert_allclose(s["guides"][joint], sol.slide_axes(joint), rtol=0, atol=1e-15)
    lever = np.array([s["columns"]["C.x[mm]"], s["columns"]["C.y[mm]"]]).T
    along = lever / np.hypot(*lever.T)[:, None]                 # O4 is at the origin
    np.testing.assert_allclose(np.abs(np.sum(along * np.array(s["guides"]["slot"]), axis=1)), 1.0,
                               rtol=0, atol=1e-12)
    c = client.post("/api/configuration", json={"model": model, "q": 90}).json()
    assert c["guides"]["slot"] == pytest.approx(
        kl.analyze(mf.mechanism, np.pi / 2).slide_axes("slot").tolist(), abs=1e-15)


GEAR_EXAMPLES = ["gear_train", "compound_gear_train", "planetary", "rack_and_pinion",
                 "geared_fivebar"]


@pytest.mark.parametrize("name", GEAR_EXAMPLES)
def test_the_gear_examples_open_sweep_and_answer_every_request(client, tmp_path, name):
    """Each example with gear joints, opened as the page opens it: its sweep is the command
    line's, and a study, a configuration between samples, a drag (one input) and a save
    answer."""
    model = client.get(f"/api/examples/{name}").json()["model"]
    model_file = tmp_path / f"{name}.json"
    model_file.write_text(json.dumps(model))
    r = cli("analyze", model_file, "--format", "json", "--samples", 7, "--out", tmp_path / "out.json", "-q")
    assert r.exit_code == 0, r.output
    answer = client.post("/api/analyze", json={"model": model, "samples": 7})
    assert answer.status_code == 200 and answer.text == (tmp_path / "out.json").read_text()
    s = client.post("/api/study", json={"model": model, "source": f"{name}.toml"}).json()
    assert not s["unassembled"] and s["drawing"]["gears"]
    q = [(s["columns"][n][1] + s["columns"][n][2]) / 2 for n in s["inputs"]]
    c = client.post("/api/configuration", json={"model": model, "q": q[0] if len(q) == 1 else q})
    assert c.status_code == 200 and set(c.json()["turns"]) == set(s["turns"])
    if len(q) == 1:
        first = next(iter(model["points"]))
        d = client.post("/api/drag", json={"model": model, "point": list(model["points"])[1],
                                           "to": model["points"][first], "parts": ["turns"]})
        assert d.status_code == 200 and set(d.json()) == {"q", "points", "singular", "turns"}
    saved = client.post("/api/save", json={"model": model, "format": "toml"}).json()["text"]
    assert ModelFile.from_toml(saved) == ModelFile.read(EXAMPLES / f"{name}.toml")


# The pitch radii, checked by hand from each file's comments: teeth times the module (2 mm)
# over two, or the radii given.
PITCH_RADII = {
    "gear_train": {"mesh12": [20, 30], "mesh23": [30, 40]},
    "compound_gear_train": {"mesh12": [20, 50], "mesh34": [15, 45]},
    "planetary": {"sun_planet": [30, 20], "planet_ring": [20, 70]},
    "rack_and_pinion": {"mesh": [25, 25]},
    "geared_fivebar": {"cranks": [50, 50]},
}


@pytest.mark.parametrize("name", GEAR_EXAMPLES)
def test_the_gears_are_drawn_at_their_pitch_radii_and_their_links_angles(client, name):
    """The drawing's gear pairs: each gear's centre and pitch radius (derived from the
    distance between the axes where only teeth are given), and each gear's direction at
    every sample and in one configuration: its link's angle, kinelab's."""
    mf, model = model_of(name)
    s = client.post("/api/study", json={"model": model}).json()
    gears = {g["joint"]: g for g in s["drawing"]["gears"]}
    assert set(gears) == set(PITCH_RADII[name])
    for joint, radii in PITCH_RADII[name].items():
        assert [g["radius"] for g in gears[joint]["gears"]] == pytest.approx(radii, rel=1e-12)
        j = mf.mechanism.joint(joint)
        assert [g["link"] for g in gears[joint]["gears"]] == list(j.links)
        assert gears[joint]["mesh"] == (j.mesh or "external")
    if name == "rack_and_pinion":
        assert gears["mesh"]["gears"][1] == {"link": "rack", "rack": True, "slide": "guide",
                                             "point": "K", "radius": 25.0}
        assert set(s["turns"]) == {"pinion"}
    if name == "planetary":
        assert [g["centre"] for g in gears["planet_ring"]["gears"]] == ["C", "O"]
        assert gears["planet_ring"]["carrier"] == "arm"
    q = np.column_stack([np.radians(s["columns"][n]) for n in s["inputs"]])
    sol = kl.analyze(mf.mechanism, q if q.shape[1] > 1 else q[:, 0])
    for link, u in s["turns"].items():
        theta = sol.angle(link)
        # to 1e-13: the inputs come back through the file's degrees
        np.testing.assert_allclose(u, np.column_stack([np.cos(theta), np.sin(theta)]),
                                   rtol=0, atol=1e-13)
    qs = [s["columns"][n][3] for n in s["inputs"]]
    c = client.post("/api/configuration", json={"model": model, "q": qs[0] if len(qs) == 1 else qs}).json()
    for link, u in c["turns"].items():
        theta = math.radians(c["values"][f"{link}.angle[deg]"])
        assert u == pytest.approx([math.cos(theta), math.sin(theta)], abs=1e-12)


def test_pitch_radii_from_a_ratio_follow_from_the_distance_between_the_axes(client):
    """A ratio alone: r_a + r_b = d (external), r_b - r_a = d (internal)."""
    _, model = model_of("planetary")
    for j in model["joints"]:
        if j.get("type") == "G":
            j.pop("teeth")
            j["ratio"] = {"sun_planet": 2 / 3, "planet_ring": 3.5}[j["name"]]
    s = client.post("/api/study", json={"model": model}).json()
    radii = {g["joint"]: [x["radius"] for x in g["gears"]] for g in s["drawing"]["gears"]}
    assert radii["sun_planet"] == pytest.approx([30, 20], rel=1e-12)
    assert radii["planet_ring"] == pytest.approx([20, 70], rel=1e-12)


@pytest.mark.parametrize("name", ["crank_rocker", "stephenson6", "whitworth"])
def test_a_narrowed_study_is_the_full_ones_columns_asked_for(client, name):
    """An edit drag asks for the columns it redraws (and the points it traces): the same
    numbers as the full study's, in its order, with everything else of the answer."""
    _, model = model_of(name)
    full = client.post("/api/study", json={"model": model}).json()
    names = list(full["columns"])
    angle = next(n for n in names if ".angle[" in n and not n.startswith("ground"))
    for columns, points in ((full["inputs"], None), ([angle], ["A"]), ([], [])):
        body = {"model": model, "columns": columns, **({"points": points} if points is not None else {})}
        narrow = client.post("/api/study", json=body).json()
        xy = {f"{p}.{c}[{full['units']['length']}]" for p in (points if points is not None else model["points"])
              for c in "xy"}
        assert list(narrow["columns"]) == [n for n in names if n in xy or n in columns or n in full["inputs"]
                                           or ".transmission[" in n]
        assert all(narrow["columns"][n] == full["columns"][n] for n in narrow["columns"])
        assert {k: v for k, v in narrow.items() if k != "columns"} == {k: v for k, v in full.items() if k != "columns"}
    r = client.post("/api/study", json={"model": model, "points": ["nowhere"]})
    assert r.status_code == 400 and r.json()["error"].startswith("points: expected a list of some of")


def test_flipping_a_dyad_gives_the_other_assembly_mode_with_the_same_lengths(client):
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5, coupler_point=(1.5, 1.0))
    model = ModelFile(fb).to_dict()
    s = client.post("/api/study", json={"model": model}).json()
    step = s["branches"][0]["step"]
    flipped = client.post("/api/flip", json={"model": model, "step": step}).json()["model"]
    crossed = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                                    coupler_point=(1.5, 1.0), branch="crossed")
    q = np.radians([10.0, 100.0, 250.0])
    a = kl.analyze(ModelFile.from_dict(flipped).mechanism, q)
    b = kl.analyze(crossed, q)
    for name in ("B", "P"):
        assert np.allclose(a.position(name), b.position(name), rtol=0, atol=1e-12)


def test_flipping_a_dyad_keeps_the_sides_of_a_point_given_by_them(client):
    """Jansen's linkage, its foot G given by its sides on the leg D-F-G: the leg's dyad
    D-F-E flipped, G keeps its sides (and gets no local place beside them)."""
    mf, model = model_of("jansen")
    s = client.post("/api/study", json={"model": model}).json()
    step = next(b["step"] for b in s["branches"] if set(b["points"]) == {"D", "F", "E"})
    flipped = client.post("/api/flip", json={"model": model, "step": step}).json()["model"]
    leg = next(link for link in flipped["links"] if link["name"] == "leg")
    assert leg["sides"] == {"G": {"D": 49.0, "F": 65.7, "side": "left"}} and "local" not in leg
    pts = {p: np.array(v) for p, v in flipped["points"].items()}
    before = {p: np.array(v) for p, v in model["points"].items()}
    assert np.linalg.norm(pts["F"] - before["F"]) > 10          # cm: F is in its other mode
    for a, b, d in [("D", "G", 49.0), ("F", "G", 65.7), ("D", "F", 36.7), ("E", "F", 39.4)]:
        assert np.hypot(*(pts[a] - pts[b])) == pytest.approx(d, rel=1e-12)


def test_load_and_save_are_the_model_files(client):
    text = (EXAMPLES / "crank_rocker.toml").read_text()
    loaded = client.post("/api/load", json={"text": text, "source": "crank_rocker.toml"}).json()
    assert loaded["model"] == ModelFile.read(EXAMPLES / "crank_rocker.toml").to_dict()
    saved = client.post("/api/save", json={"model": loaded["model"], "format": "toml"}).json()["text"]
    assert ModelFile.from_toml(saved) == ModelFile.read(EXAMPLES / "crank_rocker.toml")
    bad = client.post("/api/load", json={"text": "schema = 1\nname = ", "source": "x.toml"})
    assert bad.status_code == 400 and bad.json()["error"].startswith("x.toml: line 2")


def test_catalogue_and_examples_open(client):
    listing = client.get("/api/catalogue").json()
    assert "crank_rocker" in listing["examples"] and "fourbar" in listing["catalogue"]
    for name in listing["catalogue"]:
        model = client.get(f"/api/examples/catalogue:{name}").json()["model"]
        assert client.post("/api/study", json={"model": model, "samples": 9}).status_code == 200
    missing = client.get("/api/examples/nothing")
    assert missing.status_code == 404 and "expected one of" in missing.json()["error"]


def test_the_derivation_comes_as_mathml_in_either_language(client):
    _, model = model_of("offset_slider_crank")
    for lang, word in [("en", "Position equations"), ("pt", "posição")]:
        d = client.post("/api/derive", json={"model": model, "lang": lang}).json()
        assert word.lower() in d["sections"][0]["title"].lower()
        assert all(i["mathml"].startswith("<math") for s in d["sections"] for i in s["items"] if "mathml" in i)
        assert d["markdown"].startswith("#")


def test_the_export_is_the_command_lines_csv(client, tmp_path):
    _, model = model_of("crank_rocker")
    (tmp_path / "m.json").write_text(json.dumps(model))
    assert cli("analyze", tmp_path / "m.json", "--samples", 5, "--out", tmp_path / "m.csv", "-q").exit_code == 0
    r = client.post("/api/export", json={"model": model, "kind": "csv", "samples": 5})
    assert r.status_code == 200 and r.content == (tmp_path / "m.csv").read_bytes()
    assert 'filename="crank-rocker.csv"' in r.headers["content-disposition"]


@pytest.mark.parametrize("request_, status, match", [
    (("post", "/api/analyze", {"model": None}), 400, r"model: expected the model file's JSON form"),
    (("post", "/api/analyze", {"model": "M", "samples": MAX_SAMPLES + 1}), 400, r"samples: expected a whole number from 2 to"),
    (("post", "/api/drag", {"model": "M", "point": "Z", "to": [0, 0]}), 400, r"point: expected one of"),
    (("post", "/api/drag", {"model": "M", "point": "P", "to": [0]}), 400, r"to: expected \[x, y\]"),
    (("post", "/api/configuration", {"model": "M", "q": "40 deg"}), 400, r"q: expected 1 finite number"),
    (("post", "/api/flip", {"model": "M", "step": "x"}), 400, r"step: expected one of"),
    (("post", "/api/derive", {"model": "M", "lang": "fr"}), 400, r"lang: expected one of 'en', 'pt'"),
    (("post", "/api/export", {"model": "M", "kind": "exe"}), 400, r"kind: expected one of"),
    (("post", "/api/export", {"model": "M", "kind": []}), 400, r"kind: expected one of .*, got \[\]"),
    (("post", "/api/flip", {"model": "M", "step": {}}), 400, r"step: expected one of .*, got a table"),
    (("post", "/api/configuration", {"model": "M", "q": 10 ** 400}), 400,
     r"q: expected 1 finite number\(s\), one per input .*, got a whole number of 401 digits"),
    (("post", "/api/drag", {"model": "M", "point": "P", "to": [10 ** 400, 0]}), 400, r"to: expected \[x, y\]"),
    (("get", "/api/nothing", None), 404, r"no such page or API route"),
    (("get", "/api/%1b%5b31mx%07", None), 404, r"^/api/\\x1b\[31mx\\x07: no such page"),
    (("get", "/api/analyze", None), 405, r"method GET not allowed"),
])
def test_bad_requests_get_a_clear_message_and_status(client, request_, status, match):
    method, path, body = request_
    if body is not None and body.get("model") == "M":
        body = {**body, "model": model_of("crank_rocker")[1]}
    r = client.post(path, json=body) if method == "post" else client.get(path)
    assert r.status_code == status
    assert re.search(match, r.json()["error"]), r.json()


def test_oversize_and_malformed_bodies_are_refused(client):
    r = client.post("/api/analyze", content=b" " * (MAX_BODY + 1), headers={"content-type": "application/json"})
    assert r.status_code == 413 and "larger than" in r.json()["error"]
    r = client.post("/api/analyze", content=b"{not json", headers={"content-type": "application/json"})
    assert r.status_code == 400 and r.json()["error"].startswith("body: expected a JSON object")
    r = client.post("/api/analyze", content=b'{"samples": ' + b"9" * 5000 + b"}",
                    headers={"content-type": "application/json"})
    assert r.status_code == 400 and r.json()["error"].startswith("body: a whole number of more "
                                                                 "than 4,300 digits")


def test_a_model_that_cannot_assemble_is_refused_with_the_reason(client):
    _, model = model_of("crank_rocker")
    model["links"][3]["length"] = 10.0       # the rocker cannot reach the coupler
    r = client.post("/api/study", json={"model": model})
    assert r.status_code == 400 and "rocker" in r.json()["error"]


def test_an_unknown_sample_count_past_the_cap_in_the_file_is_refused(client):
    _, model = model_of("crank_rocker")
    model["inputs"][0]["samples"] = MAX_SAMPLES + 1
    r = client.post("/api/analyze", json={"model": model})
    assert r.status_code == 400 and f"at most {MAX_SAMPLES:,}" in r.json()["error"]


def test_web_sits_above_io_and_plot_and_nothing_below_imports_it():
    package = ROOT / "kinelab"
    for path in (package / "web").rglob("*.py"):
        assert "kinelab.cli" not in path.read_text(), path
    for path in package.rglob("*.py"):
        if path.parts[-2] not in ("web", "cli"):
            assert "kinelab.web" not in path.read_text(), path


def test_serving_elsewhere_than_loopback_warns(monkeypatch):
    import uvicorn

    from kinelab.web import serve
    monkeypatch.setattr(uvicorn.Server, "run", lambda self: None)
    with pytest.warns(UserWarning, match="anyone who can reach this address"):
        serve(host="0.0.0.0", port=0)


@pytest.mark.parametrize("source, plain, exact", [
    ("a\nb.toml", "a_b.csv", "a%0Ab.csv"),
    ("\u66f2\u67c4.toml", "__.csv", "%E6%9B%B2%E6%9F%84.csv"),
    ('a".toml', "a_.csv", "a%22.csv"),
    ("a\u0000b.toml", "a_b.csv", "a%00b.csv"),
])
def test_a_download_is_named_after_its_source_whatever_its_characters(client, source, plain, exact):
    """The header carries an ASCII name and the exact one (RFC 6266), never a raw newline,
    quote or non-Latin-1 character (which the server could not send)."""
    _, model = model_of("crank_rocker")
    r = client.post("/api/export", json={"model": model, "kind": "csv", "samples": 5, "source": source})
    assert r.status_code == 200, r.text
    assert r.headers["content-disposition"] == (f'attachment; filename="{plain}"; '
                                                f"filename*=UTF-8''{exact}")


def test_a_flip_without_a_dyad_says_so(client):
    _, model = model_of("engine")
    r = client.post("/api/flip", json={"model": model, "step": "x"})
    assert r.status_code == 400
    assert r.json()["error"] == "step: expected one of none (no RRR dyad), got 'x'"


def test_a_huge_time_ratio_is_answered(client):
    task = {"task": "quick-return", "quick_return": {"mechanism": "whitworth", "time_ratio": 1e308,
                                                     "stroke": 0.1, "distance": 0.04}}
    r = client.post("/api/synthesize", json={"task": task})
    assert r.status_code in (200, 400), r.text
    json.loads(r.text)          # strict JSON either way
