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


# The follower's dynamics: a [dynamics] table adds the forces figure, two columns and the
# jump verdict.  The critical speed of this train (2 kg, 2 kN/m, 40 N) on this program is
# 246.8 rpm (1481 deg/s): checked against the API, whose numbers tests/cams/test_dynamics.py
# checks against a simulation.
DYNAMICS = "\n[dynamics]\nmass = 2.0\nstiffness = 2000.0\npreload = 40.0\n"
DYNAMIC_TASK = CAM_TASK.replace('"harmonic"', '"3-4-5"').replace(
    "pressure_angle = 30\n", "pressure_angle = 30\n" + DYNAMICS)


def dynamic(tmp_path, text, name="dyn"):
    (tmp_path / f"{name}.toml").write_text(text)
    out = tmp_path / "out"
    result = run("cam", tmp_path / f"{name}.toml", "--out", out)
    assert result.exit_code == 0, result.output
    with open(out / f"{name}_svaj.csv", newline="") as f:
        rows = list(csv.reader(f))
    table = np.array(rows[1:], dtype=float)
    return result, out, {h: table[:, i] for i, h in enumerate(rows[0])}


def test_dynamics_contact_kept_writes_the_figure_the_columns_and_the_verdict(tmp_path):
    from kinelab import cams
    result, out, col = dynamic(tmp_path, DYNAMIC_TASK.replace("speed = 360", "speed = 1200"))
    assert {p.name for p in out.iterdir()} == {n.replace("cam_", "dyn_") for n in OUTPUTS} | {
        "dyn_forces.png"}
    lines = result.stdout.splitlines()
    assert "  dynamics: contact kept: least contact force 28.95 N at 65 deg; jump-free up to " \
           "246.8 rpm (1481 deg/s)" in lines
    assert any(s.startswith("  cam shaft torque: peak 2.539 N m at 35.5 deg, mean 0 N m")
               for s in lines)
    # the columns are the API's, in N and N m whatever the task's length unit
    task = cams.read_cam_task(tomllib.loads(DYNAMIC_TASK.replace("speed = 360", "speed = 1200")))
    ff = cams.follower_forces(task.program, mass=2.0, stiffness=2000.0, preload=40.0,
                              speed=np.radians(1200), theta=np.radians(col["theta [deg]"]))
    assert col["contact_force [N]"] == pytest.approx(ff.contact_force, rel=1e-12, abs=1e-9)
    assert col["shaft_torque [N m]"] == pytest.approx(ff.torque, rel=1e-12, abs=1e-12)
    assert ff.critical_speed * 30 / np.pi == pytest.approx(246.8, abs=0.05)


def test_dynamics_jump_says_where_and_the_preload_needed(tmp_path):
    text = DYNAMIC_TASK.replace("speed = 360", "speed = 2400")
    result, out, col = dynamic(tmp_path, text)
    assert ("  dynamics: jump: contact force below zero from 50 deg at this speed (400 rpm); "
            "preload of at least 178.1 N needed") in result.stdout.splitlines()
    assert (out / "dyn_forces.png").stat().st_size > 0
    assert col["contact_force [N]"].min() < 0
    # with a margin, the preload grows by it
    result, _, _ = dynamic(tmp_path, text.replace("preload = 40.0", "preload = 40.0\nmargin = 20"),
                           "margin")
    assert "preload of at least 198.1 N needed (for a margin of 20 N)" in result.stdout
    # and with that preload, contact is kept at 400 rpm
    result, _, col = dynamic(tmp_path, text.replace("preload = 40.0", "preload = 198.1"), "held")
    assert "dynamics: contact kept: least contact force 20" in result.stdout
    assert col["contact_force [N]"].min() > 19.9


def test_dynamics_of_an_oscillating_follower(tmp_path):
    text = CAM_TASK.replace('roller_radius = 10', 'roller_radius = 10\nmotion = "oscillating"\n'
                            'pivot_distance = 120\narm_length = 100').replace(
        "lift = 25", "lift = 8").replace(
        "pressure_angle = 30\n", "pressure_angle = 30\n\n[dynamics]\ninertia = 0.004\n"
        "stiffness = 20\npreload = 2\ndamping = 0.01\n")
    result, out, col = dynamic(tmp_path, text, "osc")
    assert "  dynamics: contact kept: least contact moment " in result.stdout
    assert " N m at " in result.stdout
    assert "contact_moment [N m]" in col and "shaft_torque [N m]" in col
    assert (out / "osc_forces.png").exists()


@pytest.mark.parametrize("dynamics, message", [
    ("mass = -2.0\nstiffness = 2000.0\npreload = 40.0",
     "dynamics.mass: expected a number above 0, got -2"),
    ("mass = 2.0\nstiffness = -1\npreload = 40.0",
     "dynamics.stiffness: expected at least 0, got -1"),
    ('mass = 2.0\nstiffness = "stiff"\npreload = 40.0',
     "dynamics.stiffness: expected a finite number, got 'stiff'"),
    ("mass = 2.0\nstiffness = 2000.0\npreload = -40.0",
     "dynamics.preload: expected at least 0, got -40"),
    ("mass = 2.0\nstiffness = 2000.0\npreload = 40.0\ndamping = -3",
     "dynamics.damping: expected at least 0, got -3"),
    ("mass = 2.0\nstiffness = 2000.0\npreload = 40.0\nexternal = true",
     "dynamics.external: expected a finite number, got true"),
    ("mass = 2.0\nstiffness = 2000.0\npreload = 40.0\nmargin = -1",
     "dynamics.margin: expected at least 0, got -1"),
    ("mass = 2.0\nstiffness = 2000.0", "dynamics.preload: missing; give the follower train's "
                                       "preload, in N"),
    ("mas = 2.0\nstiffness = 2000.0\npreload = 40.0", "dynamics.mas: unknown key (did you mean "
                                                       "'mass'?)"),
    ("inertia = 2.0\nstiffness = 2000.0\npreload = 40.0", "dynamics.inertia: a translating "
                                                           "follower takes its mass (kg); give "
                                                           "mass instead"),
])
def test_bad_dynamics_fields_are_refused(tmp_path, dynamics, message):
    text = CAM_TASK.replace("pressure_angle = 30\n",
                            "pressure_angle = 30\n\n[dynamics]\n" + dynamics + "\n")
    line = refused(tmp_path, text)
    assert message in line


HELD_TASK = """
units = { length = "mm", angle = "deg" }
cam = { speed = 1718.8733853924696 }       # 30 rad/s
follower = { type = "roller", roller_radius = 10, base_circle = 60 }
dynamics = { mass = 1, stiffness = 1000, preload = 0, external = -5 }

[[segments]]
kind = "rise"
law = "harmonic"
from = 0
to = 180
lift = 20

[[segments]]
kind = "return"
law = "harmonic"
from = 180
to = 360
lift = 20
"""


def test_dynamics_contact_held_by_inertia_only_at_this_speed(tmp_path):
    # the train of tests/cams/test_dynamics.py's test of it: nothing holds the follower at
    # rest, its inertia does at 30 rad/s
    result, _, _ = dynamic(tmp_path, HELD_TASK, "held")
    assert ("  dynamics: contact kept: least contact force 4 N at 0 deg; jump-free at this speed, "
            "but not at every lower one (contact is lost at rest)") in result.stdout.splitlines()


def test_the_summary_and_figures_in_portuguese(tmp_path, monkeypatch):
    """--lang pt: the same numbers, with decimal commas, in the notes' terms; the figures'
    words in Portuguese; the table as in English (decimal points, the same columns)."""
    from kinelab import plot as kplot
    titles = []
    save = kplot.save

    def saving(fig, path):
        titles.extend(t for ax in fig.axes for t in (ax.get_title(), ax.get_xlabel()))
        return save(fig, path)
    monkeypatch.setattr(kplot, "save", saving)
    text = DYNAMIC_TASK.replace("speed = 360", "speed = 1200")
    (tmp_path / "dyn.toml").write_text(text)
    en = run("cam", tmp_path / "dyn.toml", "--out", tmp_path / "en")
    titles.clear()
    pt = run("cam", tmp_path / "dyn.toml", "--out", tmp_path / "pt", "--lang", "pt")
    assert pt.exit_code == 0, pt.output
    lines = pt.stdout.splitlines()
    assert lines[0].startswith("double-dwell cam: came de disco, seguidor de rolete de translação, "
                               "círculo de base ")
    assert lines[1].startswith("  maior ângulo de pressão 30 deg em ")
    assert ("  dinâmica: contato mantido: menor força de contato 28,95 N em 65 deg; sem salto "
            "até 246,8 rpm (1481 deg/s)") in lines
    assert any(s.startswith("  torque no eixo do came: máximo 2,539 N m em 35,5 deg") for s in lines)
    assert len(lines) == len(en.stdout.splitlines())
    assert "diagrama SVAJ" in titles and "ângulo do came [deg]" in titles
    assert any(t.startswith("came de disco, seguidor de rolete de translação") for t in titles)
    assert (tmp_path / "pt" / "dyn_svaj.csv").read_text() == (tmp_path / "en" / "dyn_svaj.csv").read_text()
