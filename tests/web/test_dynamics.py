"""The forces tab's API: the inverse dynamics of the page's model is ``kinelab dynamics`` of
the same model file, number for number and, as a download, byte for byte; a model the
command refuses is refused with its message (400), never a fault."""
import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from starlette.testclient import TestClient

from kinelab.cli import main
from kinelab.io import ModelFile
from kinelab.web import create_app
from tests.web.test_server_bounds import CHAIN

ROOT = Path(__file__).resolve().parents[2]
ADDRESS = "http://127.0.0.1:8000"


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url=ADDRESS) as c:
        yield c


def engine_with_loads() -> dict:
    """The engine example with a gas force (an expression), a torque, a spring, a damper
    and a point mass: every kind of load the model file takes."""
    model = ModelFile.read(ROOT / "examples" / "engine.toml").to_dict()
    model["dynamics"] = {
        "gravity": [0.0, -9.81],
        "point_masses": {"A": 0.2},
        "forces": [{"point": "B", "link": "slider", "fx": "-800 * (sin(q) > 0)", "fy": 0.0}],
        "torques": [{"link": "crank", "torque": "-0.05 * qd", "reacting": "ground"}],
        "springs": [{"points": ["G3", "O2"], "stiffness": 500.0, "free_length": 0.05}],
        "dampers": [{"points": ["B", "O2"], "damping": 2.0}],
    }
    return model


def command_line(model: dict, tmp_path) -> Path:
    """``kinelab dynamics`` of the model saved as a file: its CSV table."""
    path = tmp_path / "model.toml"
    path.write_text(ModelFile.from_dict(model).to_toml())
    r = CliRunner().invoke(main, ["dynamics", str(path), "--out", str(tmp_path / "out"),
                                  "--no-plots"])
    assert r.exit_code == 0, r.output
    return next((tmp_path / "out").glob("*_dynamics.csv"))


@pytest.mark.parametrize("example", ["engine", "with loads"])
def test_the_forces_are_kinelab_dynamics_of_the_saved_model(client, tmp_path, example):
    model = (ModelFile.read(ROOT / "examples" / "engine.toml").to_dict() if example == "engine"
             else engine_with_loads())
    r = client.post("/api/dynamics", json={"model": model, "source": "engine.toml"})
    assert r.status_code == 200, r.text
    answer = r.json()
    table = np.genfromtxt(command_line(model, tmp_path), delimiter=",", names=True)
    names = list(answer["columns"])
    assert len(names) == len(table.dtype.names)
    for name, column in zip(names, table.dtype.names):
        np.testing.assert_allclose(np.array(answer["columns"][name], float), table[column],
                                   rtol=1e-12, atol=1e-12, err_msg=name)
    assert answer["efforts"] == ["crank_angle.torque[N*m]"]
    assert answer["inputs"] == ["crank_angle.q[deg]"]
    assert [r["joint"] for r in answer["reactions"]] == ["jO2", "jA", "jB", "slide"]
    assert answer["samples"] == 361 and answer["file"] == "engine_dynamics.csv"
    if example == "with loads":
        loads = answer["loads"]
        assert [f["point"] for f in loads["forces"]] == ["B"]
        fx = np.array(loads["forces"][0]["x"])
        q = np.radians(answer["columns"]["crank_angle.q[deg]"])
        np.testing.assert_array_equal(fx, -800.0 * (np.sin(q) > 0))
        assert [s["kind"] for s in loads["springs"]] == ["spring", "damper"]


def test_the_download_is_the_commands_file(client, tmp_path):
    model = engine_with_loads()
    r = client.post("/api/dynamics", json={"model": model, "format": "csv"})
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/csv")
    assert 'filename="engine_dynamics.csv"' in r.headers["content-disposition"]
    assert r.content == command_line(model, tmp_path).read_bytes()


@pytest.mark.parametrize("change, status, match", [
    (lambda m: m["links"][1].pop("mass"), 400, r"link 'crank': mass: missing"),
    (lambda m: m["links"][1].update(mass=-1), 400, r"links\[1\]\.mass"),
    (lambda m: m["links"][1].update(center_of_mass="nowhere"), 400, r"center_of_mass"),
    (lambda m: m.update(dynamics={"forces": [{"point": "B", "fx": "os.system('x')"}]}), 400,
     r"dynamics\.forces\[0\]\.fx: .*not allowed"),
    (lambda m: m.update(dynamics={"forces": [{"point": "B", "fx": "1 / sin(q)"}]}), 400,
     r"gives inf"),
    (lambda m: m.update(dynamics={"springs": [{"points": ["A", "A"], "stiffness": 1}]}), 400,
     r"its two ends are the same point"),
    (lambda m: m.update(dynamics={"gravity": "down"}), 400, r"gravity"),
])
def test_bad_masses_or_loads_are_refused_with_the_commands_message(client, change, status, match):
    import re
    model = ModelFile.read(ROOT / "examples" / "engine.toml").to_dict()
    change(model)
    r = client.post("/api/dynamics", json={"model": model, "source": "engine.toml"})
    assert r.status_code == status, r.text
    assert r.headers["content-type"] == "application/json"
    assert re.search(match, r.json()["error"]), r.json()


@pytest.mark.parametrize("body, match", [
    ({"format": "xlsx"}, r"format: expected one of 'json', 'csv', got 'xlsx'"),
    ({"format": 3}, r"format: expected one of"),
    ({"samples": 1}, r"samples: expected a whole number from 2 to"),
    ({"model": []}, r"model: expected the model file's JSON form"),
])
def test_bad_requests_are_400(client, body, match):
    import re
    model = ModelFile.read(ROOT / "examples" / "engine.toml").to_dict()
    r = client.post("/api/dynamics", json={"model": model, **body})
    assert r.status_code == 400 and re.search(match, r.json()["error"]), r.text


def test_a_system_too_large_is_refused_before_the_work(client):
    chain = json.loads(json.dumps(CHAIN))
    for link in chain["links"][1:]:
        link.update(mass=1.0, center_of_mass=link["points"][0], inertia=0.01)
    r = client.post("/api/dynamics", json={"model": chain, "samples": 2000})
    assert r.status_code == 413
    assert "free-body equations of 2,000 samples of 200 links" in r.json()["error"]


HOSTILE = [
    {}, {"model": None}, {"model": "engine"}, {"model": {}}, {"model": {"schema": 1}},
    {"format": None}, {"format": ["csv"]}, {"samples": "many"}, {"samples": 10 ** 30},
    {"samples": True}, {"samples": 3.5}, {"job": "bad id"}, {"job": ["x"]}, {"job": "x" * 65},
    {"source": 5}, {"source": "../../etc/passwd"},
]


@pytest.mark.parametrize("change", HOSTILE)
@pytest.mark.parametrize("route", ["/api/dynamics", "/api/progress", "/api/cancel"])
def test_hostile_requests_get_json_4xx_never_500(client, route, change):
    body = {"model": ModelFile.read(ROOT / "examples" / "engine.toml").to_dict(), **change}
    if route != "/api/dynamics":
        body = {k: v for k, v in change.items() if k == "job"} or {"job": change.get("model", 7)}
    r = client.post(route, json=body)
    assert r.headers["content-type"].startswith(("application/json", "text/csv")), r.text
    assert r.status_code < 500, r.text
    if r.status_code >= 400:
        assert set(r.json()) <= {"error", "problems"} and r.json()["error"]


def test_a_rocking_cam_follower_gives_its_efforts_and_why_no_reactions(client):
    model = ModelFile.read(ROOT / "examples" / "cam_rocker_slider.toml").to_dict()
    for link, centre, inertia in (("cam", "O", 1e-3), ("rocker", "B", 2e-3),
                                  ("coupler", "C", 1e-3), ("slider", "C", None)):
        entry = next(k for k in model["links"] if k["name"] == link)
        entry.update(mass=0.5, center_of_mass=centre)
        if inertia is not None:
            entry["inertia"] = inertia * 1e6            # kg mm^2: the file's lengths are in mm
    r = client.post("/api/dynamics", json={"model": model, "source": "cam_rocker_slider.toml"})
    assert r.status_code == 200, r.text
    answer = r.json()
    assert answer["reactions"] == [] and answer["shaking"] is None
    assert answer["reactions_refused"].startswith("reactions: cam joint(s) 'contact' drive an "
                                                  "oscillating follower")
    assert all(v is not None for v in answer["columns"]["jO.torque[N*m]"])
