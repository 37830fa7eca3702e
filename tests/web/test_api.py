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
    with TestClient(create_app()) as c:
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
    assert answer.json() == {"error": "\n".join(lines)}
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
    assert c["polygons"] is None or set(c["polygons"]) == {"velocity", "acceleration"}


def test_the_polygons_panel_calls_kinematics_polygons_when_they_exist(monkeypatch):
    class Polygon:
        def __init__(self, vertices):
            self.vertices = vertices

    def velocity_polygon(sol, sample=0):
        return Polygon({p: sol.velocity(p).reshape(2) for p in sol.mechanism.point_names})

    def acceleration_polygon(sol, sample=0):
        return Polygon({p: sol.acceleration(p).reshape(2) for p in sol.mechanism.point_names})
    monkeypatch.setattr(kinematics, "velocity_polygon", velocity_polygon, raising=False)
    monkeypatch.setattr(kinematics, "acceleration_polygon", acceleration_polygon, raising=False)
    mf, model = model_of("crank_rocker")
    c = _api.configuration({"model": model, "q": 10})
    sol = kl.analyze(mf.mechanism, math.radians(10), qd=mf.mechanism.inputs[0].speed)
    assert c["polygons"]["velocity"]["P"] == pytest.approx((sol.velocity("P") * 1000).tolist(), rel=1e-12)
    assert c["polygons"]["acceleration"]["B"] == pytest.approx((sol.acceleration("B") * 1000).tolist(), rel=1e-12)


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
    (("get", "/api/nothing", None), 404, r"no such page or API route"),
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
