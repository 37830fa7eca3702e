"""--verify on the command line: the certificate printed last, its verdict's exact form,
written beside the outputs; exit status 1 when it fails, 2 for what it cannot take."""
import dataclasses
import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from kinelab.cli import main
from kinelab.verify import Certificate
from tests.synthesis.test_cli import CRANK_ROCKER

ROOT = Path(__file__).resolve().parents[2]
EX = ROOT / "examples"
VERIFIED = re.compile(r"^verified: \d+ quantities, largest disagreement \d(\.\d)?(e-\d+)?$")


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def last_line(result) -> str:
    return result.stdout.rstrip("\n").splitlines()[-1]


def test_analyze_prints_the_certificate_last_and_writes_it(tmp_path):
    res = run("analyze", EX / "crank_rocker.toml", "--verify", "--out", tmp_path, "--samples", 91)
    assert res.exit_code == 0, res.output
    assert VERIFIED.match(last_line(res)), last_line(res)
    assert "certificate: kinematics of 'crank-rocker', 91 samples" in res.stdout
    path = tmp_path / "crank_rocker_certificate.json"
    assert f"wrote {path}" in res.stdout
    data = json.loads(path.read_text())
    assert data["verified"] is True and data["verdict"] == last_line(res)
    cert = Certificate.from_dict(data)
    assert cert.passed and cert["K"][0][0] == "closed form" and len(cert) == 6
    # the table is as without --verify: --verify adds, it changes nothing
    plain = run("analyze", EX / "crank_rocker.toml", "--out", tmp_path / "plain", "--samples", 91)
    assert (tmp_path / "crank_rocker.csv").read_text() == \
        (tmp_path / "plain" / "crank_rocker.csv").read_text()
    assert res.stdout.startswith(plain.stdout.rsplit("wrote", 1)[0])


def test_the_certificate_goes_beside_a_named_table(tmp_path):
    res = run("analyze", EX / "engine.toml", "--verify", "-q", "--samples", 37,
              "--out", tmp_path / "runs" / "engine.json")
    assert res.exit_code == 0, res.output
    assert json.loads((tmp_path / "runs" / "engine_certificate.json").read_text())["verified"]
    assert isinstance(json.loads((tmp_path / "runs" / "engine.json").read_text()), list)


def test_one_configuration(tmp_path):
    res = run("analyze", EX / "slotted_link.toml", "--at", "30", "--verify")
    assert res.exit_code == 0, res.output
    assert "certificate: kinematics of 'slotted link (Erthal)', 1 sample" in res.stdout
    assert VERIFIED.match(last_line(res))


def test_a_corrupted_analysis_fails_with_status_1(tmp_path, monkeypatch):
    from kinelab.cli import _analyze
    real = _analyze.sweep

    def wrong(*args, **kwargs):
        sol = real(*args, **kwargs)
        jets = sol.stored_jets.copy()
        jets[40, int(sol.plan.item_slot[sol.plan.link_item["rocker"]]), 1] *= 1 + 1e-6
        return dataclasses.replace(sol, stored_jets=jets)
    monkeypatch.setattr(_analyze, "sweep", wrong)
    res = run("analyze", EX / "crank_rocker.toml", "--verify", "--out", tmp_path, "--samples", 91)
    assert res.exit_code == 1
    line = last_line(res)
    assert line.startswith("NOT verified: K by Newton engine (") and "> bound" in line
    assert "K by finite differences" in line and "<- exceeds its bound" in res.stdout
    data = json.loads((tmp_path / "crank_rocker_certificate.json").read_text())
    assert data["verified"] is False and data["quantities"]["K"]["passed"] is False


def test_dynamics(tmp_path):
    res = run("dynamics", EX / "engine.toml", "--verify", "--no-plots", "--out", tmp_path,
              "--samples", 73)
    assert res.exit_code == 0, res.output
    assert VERIFIED.match(last_line(res))
    data = json.loads((tmp_path / "engine_dynamics_certificate.json").read_text())
    assert {"effort", "energy", "reaction", "shaking", "K"} <= set(data["quantities"])


def test_polygons(tmp_path):
    res = run("polygons", EX / "slotted_link.toml", "--at", "60", "--verify", "--out", tmp_path)
    assert res.exit_code == 0, res.output
    assert VERIFIED.match(last_line(res))
    assert "Coriolis part" in res.stdout
    assert (tmp_path / "slotted_link_polygons_certificate.json").exists()


def test_synth(tmp_path):
    task = tmp_path / "task.toml"
    task.write_text(CRANK_ROCKER)
    res = run("synth", task, "--verify", "--no-figures", "--out", tmp_path / "out")
    assert res.exit_code == 0, res.output
    assert VERIFIED.match(last_line(res))
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["certificate"]["verified"] is True
    assert "the task's time ratio" in summary["certificate"]["quantities"]["time ratio"]["routes"]
    assert json.loads((tmp_path / "out" / "certificate.json").read_text()) == summary["certificate"]
    # with --json the certificate is in the JSON printed, and nothing follows it
    res = run("synth", task, "--verify", "--json", "--no-figures", "--out", tmp_path / "json")
    assert res.exit_code == 0 and json.loads(res.stdout)["certificate"]["verdict"].startswith("verified")


@pytest.mark.parametrize("args", [
    ("centres", EX / "crank_rocker.toml", "--at", "30", "--verify"),     # nothing to certify
    ("analyze", EX / "crank_rocker.toml", "--verify=yes"),
    ("sweep", "fourbar", "--verify"),
])
def test_verify_where_it_cannot_certify_is_one_line_and_status_2(args):
    res = run(*args)
    assert res.exit_code == 2
    assert len(res.stderr.strip().splitlines()) == 1 and "--verify" in res.stderr
    assert not res.stdout
