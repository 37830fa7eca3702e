"""The `mobility` and `types` commands of the `kinelab` group."""
import json

import pytest
from click.testing import CliRunner

import kinelab.io
from kinelab.cli import main

from .models import sarrus


@pytest.fixture
def model_file(tmp_path, monkeypatch):
    """A model file whose loading returns the (spatial) Sarrus mechanism."""
    path = tmp_path / "sarrus.toml"
    path.write_text("# read by kinelab.io.load\n")
    monkeypatch.setattr(kinelab.io, "load", lambda p: sarrus(), raising=False)
    return str(path)


def test_mobility_command(model_file):
    out = CliRunner().invoke(main, ["mobility", model_file])
    assert out.exit_code == 0, out.output
    assert out.output.splitlines()[0] == "RRRRRR (Sarrus): spatial, 6 links, pairs: 6 of class P1"
    assert "M = 6(6 − 1) − 5·6 = 0" in out.output and "M = 1, not 0 as counted" in out.output


def test_mobility_command_json(model_file):
    out = CliRunner().invoke(main, ["mobility", model_file, "--json"])
    data = json.loads(out.output)
    assert (data["kutzbach_gruebler"], data["exact"], data["pairs"]) == (0, 1, {"P1": 6})


def test_mobility_command_reports_model_errors(tmp_path, monkeypatch):
    from kinelab.errors import ModelError

    def broken(path):
        raise ModelError("links[2].points: expected a declared point, got 'Q'", source=path)
    monkeypatch.setattr(kinelab.io, "load", broken, raising=False)
    path = tmp_path / "m.toml"
    path.write_text("")
    out = CliRunner().invoke(main, ["mobility", str(path)])
    assert out.exit_code == 2
    assert "kinelab: error: " in out.output and "links[2].points: expected a declared point, got 'Q'" in out.output


def test_types_active_chains():
    out = CliRunner().invoke(main, ["types", "--space", "spatial", "--mobility", "6"])
    assert out.exit_code == 0, out.output
    assert "C_T = 36; chain connectivities (6, 6, 6, 6, 6, 6)" in out.output
    assert "  6-UPS\n" in out.output


def test_types_open_chain_table():
    out = CliRunner().invoke(main, ["types", "--space", "spatial", "--mobility", "3", "--method", "open"])
    assert "nP1 = 1: Ne = 7/3" in out.output and "nP1 = 3: Ne = 4  (consistent)" in out.output
    assert "8 architectures:" in out.output


def test_types_alternative_json():
    out = CliRunner().invoke(main, ["types", "--space", "planar", "--method", "alternative",
                                     "--motion", "Tx Ty", "--json"])
    data = json.loads(out.output)
    assert data["total_connectivity"] == 5 and data["architectures"][0]["name"] == "RRR+PP"


def test_types_limit_and_joints():
    out = CliRunner().invoke(main, ["types", "--space", "spatial", "--mobility", "3", "--limit", "2",
                                     "--joints", "RPS"])
    assert out.exit_code == 0, out.output
    lines = out.output.splitlines()
    head = next(k for k, line in enumerate(lines) if "architectures (first 2):" in line)
    assert len(lines) == head + 3 and all("S" in line or "P" in line for line in lines[head + 1:])


def test_types_chains():
    out = CliRunner().invoke(main, ["types", "--space", "planar", "--mobility", "1", "--links", "8"])
    assert out.output.startswith("16 planar chains with 8 links and mobility 1")
    assert "71 inversions" in out.output


@pytest.mark.parametrize("args, message", [
    (["--space", "planar", "--mobility", "7"], "mobility: expected a whole number from 1 to 3, got 7"),
    (["--space", "planar", "--mobility", "1", "--links", "5"], "mobility 1 is impossible with 5 links"),
    (["--space", "spatial", "--links", "6"], "--links lists planar kinematic chains"),
    (["--space", "moon", "--mobility", "1"], "Invalid value for '--space'"),
    (["--space", "planar", "--mobility", "1", "--links", "12"],
     "links: 12 links with mobility 1 (5 independent loops) are beyond what is enumerated: at most "
     "12 links and 4 loops"),
    (["--space", "planar", "--mobility", "1", "--links", "1000000"], "(499999 independent loops)"),
    # counts: negative, zero or huge refused by the option itself, exit status 2
    (["--space", "spatial", "--mobility", "3", "--limit", "-1"],
     "Invalid value for '--limit': -1 is not in the range 1<=x<=1000000"),
    (["--space", "spatial", "--mobility", "3", "--limit", "0"], "Invalid value for '--limit'"),
    (["--space", "spatial", "--mobility", "3", "--max-joints", "0"],
     "Invalid value for '--max-joints'"),
    (["--space", "spatial", "--mobility", "3", "--max-joints", "1" + "0" * 30],
     "Invalid value for '--max-joints'"),
    (["--space", "planar", "--mobility", "-1"], "Invalid value for '--mobility'"),
    (["--space", "planar", "--mobility", "1", "--links", "-4"], "Invalid value for '--links'"),
    (["--space", "planar", "--mobility", "1", "--links", "9" * 20], "Invalid value for '--links'"),
])
def test_types_errors(args, message):
    out = CliRunner().invoke(main, ["types", *args])
    assert out.exit_code == 2 and message in out.output
    assert out.output.count("\n") == 1 and out.output.startswith("kinelab: error: ")
