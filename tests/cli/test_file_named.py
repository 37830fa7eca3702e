"""Every command line error about a file names the file, whichever command finds it and
however late: while the file is read, while its model is planned for a sweep or a value
typed with --at, or while a study or an atlas works on its rows."""
import json
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner

from kinelab.cli import main

ROOT = Path(__file__).resolve().parents[2]


def _model(tmp_path, name, change) -> Path:
    data = tomllib.loads((ROOT / "examples" / name).read_text())
    change(data)
    path = tmp_path / "model.json"
    path.write_text(json.dumps(data))
    return path


def _drop_an_input(data):
    data["inputs"] = data["inputs"][:1]          # a five-bar driven at one input


def _move_a_pivot(data):
    data["points"]["O2"] = [-1, 0]               # the ground's pivots 301 mm apart, length 300


COMMANDS = [["check"], ["analyze", "--out", "{out}"], ["analyze", "--at", "10"],
            ["plot", "--out", "{out}", "--format", "png"], ["derive", "--at", "10", "--out", "{out}"],
            ["polygons", "--at", "10", "--out", "{out}"], ["centres", "--at", "10", "--out", "{out}"],
            ["export", "--to", "svg", "--out", "{out}"], ["dynamics", "--out", "{out}"]]


@pytest.mark.parametrize("example, change, message", [
    ("fivebar.toml", _drop_an_input, "inputs: the linkage has 2 degree(s) of freedom"),
    ("crank_rocker.toml", _move_a_pivot, "links[0].length: the ground's points are the frame"),
])
@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: " ".join(c[:2]))
def test_a_models_problem_names_its_file_in_every_command(tmp_path, example, change, message,
                                                          command):
    path = _model(tmp_path, example, change)
    args = [command[0], str(path), *(a.format(out=tmp_path / "out") for a in command[1:])]
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 2, r.output
    lines = r.stderr.splitlines()
    assert lines and all(line.startswith("kinelab: error: model.json: ") for line in lines), lines
    # dynamics says first what its own section lacks (the examples' masses)
    assert message in r.stderr or command[0] == "dynamics", r.stderr
    assert not (tmp_path / "out").exists()
