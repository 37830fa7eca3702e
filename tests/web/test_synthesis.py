"""Synthesis on the server: the same task, read by the same reader, gives the answer
``kinelab synth`` prints and the model files it writes."""
import json
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner
from starlette.testclient import TestClient

import kinelab as kl
from kinelab.cli import main
from kinelab.io import ModelFile
from kinelab.web import create_app
from tests.web.models import assert_same_model
from kinelab.web._api import MAX_SEARCH_EFFORT
from tests.synthesis.test_cli import CRANK_ROCKER, NOTES_6_5, NOTES_6_7

FUNCTION = """
task = "function"
units = { angle = "deg" }
[function]
expression = "sqrt(x)"
x_range = [1, 4]
input_range = [60, 150]
output_range = [10, 100]
points = 4
"""
TASKS = {
    "crank-rocker": CRANK_ROCKER,
    "three positions": NOTES_6_5,
    "four positions": NOTES_6_7,
    "five positions": None,            # five_position_task()
    "function": FUNCTION,
    "function pairs": """
task = "function"
units = { length = "mm", angle = "deg" }
[function]
pairs = [[49, 97], [79, 101], [109, 112]]
O2 = [30, -40]
O4 = [330, 10]
""",
    "path": """
task = "path"
[positions]
points = [[0, 0], [0.25, 0.02], [0.5, 0.03], [0.75, 0.02], [1, 0]]
[search]
runs = 1
maxiter = 20
""",
}


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url="http://127.0.0.1:8000") as c:
        yield c


def synth(tmp_path, text):
    (tmp_path / "task.toml").write_text(text)
    res = CliRunner().invoke(main, ["synth", str(tmp_path / "task.toml"), "--out",
                                    str(tmp_path / "out"), "--json", "--no-figures"])
    return res


def five_position_task():
    """Five poses of a known four-bar's coupler (so the task has real Burmester points)."""
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    s = kl.analyze(fb, q=np.radians([0, 40, 80, 120, 160]))
    return (f'task = "motion"\n[positions]\npoints = {s.position("P").tolist()}\n'
            f'angles = {s.angle("coupler").tolist()}\n')


@pytest.mark.parametrize("kind", list(TASKS))
def test_the_server_answers_what_kinelab_synth_prints_and_writes(client, tmp_path, kind):
    text = five_position_task() if kind == "five positions" else TASKS[kind]
    res = synth(tmp_path, text)
    assert res.exit_code == 0, res.output
    printed = json.loads(res.output)
    answer = client.post("/api/synthesize", json={"task": tomllib.loads(text), "source": "task.toml"})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    models = body.pop("models")
    assert body == printed
    assert len(models) == len(printed["solutions"]) >= 1
    for i, model in enumerate(models, 1):
        written = ModelFile.read(tmp_path / "out" / f"solution_{i}.toml")
        assert_same_model(ModelFile.from_dict(model), written)


def test_the_crank_rocker_opened_swings_its_rocker_by_the_task(client):
    """The design the page opens, analysed as any model: the rocker swings 45 deg and the
    time ratio is 1.25 (from the sweep, not from the synthesis)."""
    task = tomllib.loads(TASKS["crank-rocker"])
    model = client.post("/api/synthesize", json={"task": task}).json()["models"][0]
    m = ModelFile.from_dict(model).mechanism
    q = np.linspace(0.0, 2 * np.pi, 200_001)
    rocker = np.unwrap(kl.analyze(m, q=q).angle("rocker"))
    assert np.degrees(rocker.max() - rocker.min()) == pytest.approx(45.0, abs=1e-6)
    forward = q[np.argmax(rocker)] - q[np.argmin(rocker)]
    forward = forward % (2 * np.pi)
    ratio = max(forward, 2 * np.pi - forward) / min(forward, 2 * np.pi - forward)
    assert ratio == pytest.approx(1.25, abs=1e-3)        # grid step 2 pi / 200000


def test_a_malformed_task_gets_the_command_lines_message(client, tmp_path):
    text = 'task = "crank-rocker"\n[crank_rocker]\nground = 100\nswing = "x"\n'
    res = synth(tmp_path, text)
    assert res.exit_code == 2
    lines = [line.removeprefix("kinelab: error: ") for line in res.output.strip().splitlines()]
    answer = client.post("/api/synthesize", json={"task": tomllib.loads(text),
                                                  "source": str(tmp_path / "task.toml")})
    assert answer.status_code == 400
    assert answer.json()["error"].splitlines() == lines


@pytest.mark.parametrize("task, message", [
    (None, "task: expected a table of the task's sections, got None"),
    ({"task": "motion", "positions": {"points": [[0, 0], [1, 0]], "angles": [0, 1]}},
     "pivots.A1: missing; 2 positions need 'A1', 'B1'"),
    ({"task": "path", "positions": {"points": [[0, 0], [1, 1], [2, 0]]},
      "search": {"runs": 1000, "maxiter": 1000}}, f"the page searches at most {MAX_SEARCH_EFFORT:,}"),
    # 30 points and four times the default search: the points count (it ran for minutes)
    ({"task": "path", "positions": {"points": [[np.cos(a), np.sin(a)] for a in np.linspace(0, 6, 30)]},
      "search": {"runs": 12}}, "search: runs x maxiter x popsize x samples x points is 291,600,000; the page searches at most 97,200,000"),
])
def test_bad_tasks_are_refused_in_one_line(client, task, message):
    answer = client.post("/api/synthesize", json={"task": task})
    assert answer.status_code == 400
    assert message in answer.json()["error"]


def test_a_range_nested_deeper_than_numpy_allows_is_refused_in_one_line(client):
    """A function task whose input range is a list nested 58 deep: a 4xx naming the field,
    not an internal error."""
    deep = 1
    for _ in range(58):
        deep = [deep]
    task = {"task": "function", "units": {"angle": "deg"},
            "function": {"expression": "log10(x)", "x_range": [1, 2], "input_range": deep,
                         "output_range": [0, 90], "points": 3, "ground": 1.0}}
    r = client.post("/api/synthesize", json={"task": task, "source": "task.toml"})
    assert 400 <= r.status_code < 500, r.text
    assert "function.input_range" in r.json()["error"]
