"""`kinelab cam TASK`: the files it writes, its summary, and the tasks it refuses (exit
status 2, one line, nothing written)."""
import csv
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from kinelab.cli import main

CAM_TASK = '''
name = "double-dwell cam"
units = { length = "mm", angle = "deg" }
cam = { speed = 360 }

[follower]
type = "roller"
roller_radius = 10
base_circle = "smallest"
pressure_angle = 30

[[segments]]
kind = "rise"
law = "cycloidal"
from = 0
to = 90
lift = 25

[[segments]]
kind = "dwell"
from = 90
to = 180

[[segments]]
kind = "return"
law = "harmonic"
from = 180
to = 270
lift = 25

[[segments]]
kind = "dwell"
from = 270
to = 360
'''
OUTPUTS = {f"cam_{s}" for s in ("svaj.png", "profile.png", "pressure.png", "curvature.png",
                                 "profile.dxf", "profile.svg", "svaj.csv")}


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_happy_path_writes_every_output_and_a_summary(tmp_path):
    (tmp_path / "cam.toml").write_text(CAM_TASK)
    out = tmp_path / "out"
    result = run("cam", tmp_path / "cam.toml", "--out", out)
    assert result.exit_code == 0, result.output
    assert {p.name for p in out.iterdir()} == OUTPUTS
    lines = result.stdout.splitlines()
    assert lines[0].startswith("double-dwell cam: disk cam, translating roller follower, base "
                               "circle ") and "(the smallest for a pressure angle of 30 deg)" in lines[0]
    assert lines[1].startswith("  largest pressure angle 30 deg at ")
    assert lines[2].startswith("  smallest radius of curvature ")
    assert lines[3] == "  undercut: no"
    # the harmonic return breaks the fundamental law of cam design at both its ends
    assert lines[4].startswith("  continuity: A jumps by ") and "at 180 deg" in lines[4]
    assert "at 270 deg" in lines[5]
    with open(out / "cam_svaj.csv", newline="") as f:
        rows = list(csv.reader(f))
    head = rows[0]
    assert head[:5] == ["theta [deg]", "S [mm]", "V [mm/deg]", "A [mm/deg^2]", "J [mm/deg^3]"]
    table = np.array(rows[1:], dtype=float)
    assert table.shape == (721, len(head)) and np.isfinite(table).all()
    col = {h: table[:, i] for i, h in enumerate(head)}
    assert col["S [mm]"].max() == pytest.approx(25.0)
    # per second at 360 deg/s: v = V [mm/deg] * 360
    assert col["v [mm/s]"] == pytest.approx(col["V [mm/deg]"] * 360, rel=1e-12, abs=1e-12)
    assert np.abs(col["pressure_angle [deg]"]).max() <= 30 + 1e-6


def refused(tmp_path, text, name="bad"):
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    out = tmp_path / "out"
    result = run("cam", path, "--out", out)
    assert result.exit_code == 2, result.output
    assert not out.exists()
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"kinelab: error: {path}: "), result.stderr
    return lines[0]


def test_a_gap_between_segments_is_refused(tmp_path):
    line = refused(tmp_path, CAM_TASK.replace("from = 90\nto = 180", "from = 100\nto = 180"))
    assert "segments[2]: a gap from 90 deg to 100 deg after segments[1]" in line or \
        "segments[1]: a gap from 90 deg to 100 deg after segments[0]" in line


def test_an_overlap_is_refused(tmp_path):
    line = refused(tmp_path, CAM_TASK.replace("from = 270\nto = 360", "from = 260\nto = 360"))
    assert "segments[3]: overlaps segments[2] from 260 deg to 270 deg" in line


def test_a_rise_without_lift_is_refused(tmp_path):
    line = refused(tmp_path, CAM_TASK.replace("lift = 25", "lift = 0", 1))
    assert "segments[0].lift: expected the rise's travel, above 0, got 0" in line


def test_an_unknown_law_is_refused_with_the_nearest_name(tmp_path):
    line = refused(tmp_path, CAM_TASK.replace('"cycloidal"', '"cycloid"'))
    assert line.endswith("segments[0].law: expected one of 'harmonic', 'cycloidal', '3-4-5', "
                         "'4-5-6-7', 'modified-trapezoid', 'modified-sine', 'polynomial', got "
                         "'cycloid' (did you mean 'cycloidal'?)")


def test_a_base_circle_too_small_for_the_pressure_angle_is_refused(tmp_path):
    line = refused(tmp_path, CAM_TASK.replace('base_circle = "smallest"', "base_circle = 20"))
    assert "follower.base_circle: too small: the pressure angle reaches " in line
    assert "the smallest base circle within it is " in line


def test_a_base_circle_smaller_than_the_offset_is_refused(tmp_path):
    line = refused(tmp_path, CAM_TASK.replace('base_circle = "smallest"\npressure_angle = 30',
                                              "base_circle = 20\noffset = 40"))
    assert "must exceed the offset's" in line


def test_a_roller_larger_than_the_curvature_is_refused(tmp_path):
    text = CAM_TASK.replace("roller_radius = 10", "roller_radius = 30").replace(
        'base_circle = "smallest"\npressure_angle = 30', "base_circle = 20").replace(
        "to = 90\nlift = 25", "to = 40\nlift = 25").replace("from = 90\n", "from = 40\n")
    line = refused(tmp_path, text)
    assert "follower.roller_radius: the roller (30 mm) is larger than the pitch curve's radius" in line
    assert "use a smaller roller or a larger base circle" in line


def test_a_flat_face_with_cusps_is_refused_and_the_smallest_is_not(tmp_path):
    text = CAM_TASK.replace('type = "roller"\nroller_radius = 10', 'type = "flat-faced"').replace(
        '"harmonic"', '"cycloidal"')
    line = refused(tmp_path, text.replace('base_circle = "smallest"\npressure_angle = 30',
                                          "base_circle = 5"))
    assert "the profile has a cusp" in line
    (tmp_path / "flat.toml").write_text(text.replace("pressure_angle = 30", "min_radius = 4"))
    result = run("cam", tmp_path / "flat.toml", "--out", tmp_path / "flat")
    assert result.exit_code == 0, result.output
    assert "with a radius of curvature of at least 4 mm" in result.stdout
    assert "smallest radius of curvature 4 mm" in result.stdout and "face width" in result.stdout


def test_an_oscillating_roller_task(tmp_path):
    text = CAM_TASK.replace('roller_radius = 10', 'roller_radius = 10\nmotion = "oscillating"\n'
                            'pivot_distance = 120\narm_length = 100').replace("lift = 25", "lift = 8")
    (tmp_path / "osc.toml").write_text(text)
    result = run("cam", tmp_path / "osc.toml", "--out", tmp_path / "o")
    assert result.exit_code == 0, result.output
    assert "oscillating roller follower" in result.stdout
    with open(tmp_path / "o" / "osc_svaj.csv", newline="") as f:
        assert next(csv.reader(f))[1] == "S [deg]"


def test_several_problems_are_reported_together(tmp_path):
    path = tmp_path / "many.toml"
    path.write_text(CAM_TASK.replace('"cycloidal"', '"cycloid"').replace("speed = 360", "speed = -1"))
    result = run("cam", path)
    assert result.exit_code == 2
    assert "cam.speed: expected a number above 0, got -1" in result.stderr
    assert "(did you mean 'cycloidal'?)" in result.stderr


def test_the_doc_task_is_valid_toml():
    assert tomllib.loads(CAM_TASK)["follower"]["type"] == "roller"
