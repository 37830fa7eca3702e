"""`kinelab check`: the lines on toggles (det J = 0) and dead centres (K = 0), against the
closed forms (see tests/kinematics/test_dead_centres.py for their derivation)."""
import math
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from kinelab.cli import main

EX = Path(__file__).resolve().parents[2] / "examples"
HERE = Path(__file__).resolve().parent
DEG_TOL = 1e-6      # nine significant figures of a few hundred degrees


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def line(output: str, start: str) -> str:
    found = [s for s in output.splitlines() if s.startswith(start)]
    assert len(found) == 1, output
    return found[0]


def pairs(text: str) -> list[float]:
    """Input and output value of each 'q deg (name = v unit)' of a dead-centre line, one
    after the other."""
    return [float(v) for a, b in
            re.findall(r"(-?[\d.e+-]+) deg \([^=]+ = (-?[\d.e+-]+) (?:deg|mm|m)\)", text)
            for v in (a, b)]


def test_engine_slider_dead_centres_and_no_toggle():
    """In-line engine, crank 50 mm, rod 180 mm: top dead centre at 0 deg (x = 230 mm), bottom
    at 180 deg (x = 130 mm); det J = 180 cos(theta3) is never zero (50 < 180)."""
    result = run("check", EX / "engine.toml")
    assert result.exit_code == 0, result.output
    out = result.stdout
    # the lines that were there stay as they were, the new ones come after the sweep's
    assert "sweep: 361 samples assemble, none singular\ntoggles (det J = 0" in out
    assert out.rstrip().endswith("\nok")
    assert line(out, "toggles") == ("toggles (det J = 0, dead centres of the chain): not reached "
                                    "for crank angle in [0, 360] deg")
    slide = pairs(line(out, "slide 'slide' dead centres (K = 0"))
    assert slide == pytest.approx([0.0, 230.0, 180.0, 130.0], abs=DEG_TOL)
    rod = pairs(line(out, "link 'rod' dead centres (K = 0"))
    swing = math.degrees(math.asin(50 / 180))        # theta3 = -asin(r sin q / l)
    assert rod == pytest.approx([90.0, -swing, 270.0, swing], abs=DEG_TOL)


def test_crank_rocker_rocker_extremes_against_the_law_of_cosines():
    """Ground 300, crank 100, coupler 300, rocker 250 (mm): the rocker turns back where crank
    and coupler are in line, |O2 B| = 400 (crank along O2 B) or 200 (crank opposite)."""
    result = run("check", EX / "crank_rocker.toml")
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert "not reached for crank angle in [0, 360] deg" in line(out, "toggles (det J = 0")
    got = pairs(line(out, "link 'rocker' dead centres"))
    expected = []
    for reach, turn in ((400.0, 0.0), (200.0, 180.0)):
        phi = math.acos((300 ** 2 + reach ** 2 - 250 ** 2) / (2 * 300 * reach))   # at O2
        bx, by = reach * math.cos(phi), reach * math.sin(phi)                    # open: B above
        expected += [math.degrees(phi) + turn, math.degrees(math.atan2(by, bx - 300))]
    assert got == pytest.approx(expected, abs=DEG_TOL)
    assert "P" not in "".join(s for s in out.splitlines() if "dead centres" in s)  # a point has none


def test_triple_rocker_toggles_reached_at_its_limit_positions():
    result = run("check", HERE / "triple_rocker.toml")
    assert result.exit_code == 0, result.output
    toggles = line(result.stdout, "toggles (det J = 0")
    q = [float(v) for v in re.findall(r"(-?[\d.]+) deg \(limit position: coupler and rocker in "
                                      r"line\)", toggles)]
    limit = math.degrees(math.acos(-0.3125))
    assert q == pytest.approx([-limit, limit], abs=DEG_TOL)
    # the rocker turns back once, with crank and coupler folded: |O2 B| = 2 - 1 = 1
    rocker = pairs(line(result.stdout, "link 'rocker' dead centres"))
    phi = math.degrees(math.acos((1 + 1 - 1.5 ** 2) / 2))
    assert rocker[::2] == pytest.approx([phi], abs=DEG_TOL)


def test_check_in_portuguese_uses_the_notes_terms():
    result = run("check", EX / "engine.toml", "--lang", "pt")
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert "sweep: 361 samples assemble, none singular" in out       # the lines that were there
    assert line(out, "posições de travamento") == (
        "posições de travamento (det J = 0, cadeia alinhada): não atingidas para crank angle "
        "em [0, 360] deg")
    slide = line(out, "pontos mortos do deslizamento 'slide'")
    assert "crank angle = 0 deg (deslocamento = 230 mm), 180 deg (deslocamento = 130 mm)" in slide
    rocker = run("check", HERE / "triple_rocker.toml", "--lang", "pt").stdout
    assert "posição limite: coupler e rocker alinhados" in line(rocker, "posições de travamento")


def test_check_si_gives_the_dead_centres_in_si():
    out = run("check", EX / "engine.toml", "--si").stdout
    assert pairs(line(out, "slide 'slide' dead centres").replace(" rad", " deg")) == \
        pytest.approx([0.0, 0.23, math.pi, 0.13], abs=1e-8)


def test_check_refuses_an_unknown_language():
    result = run("check", EX / "engine.toml", "--lang", "fr")
    assert result.exit_code == 2
    assert "'fr' is not one of 'en', 'pt'" in result.output


def test_slider_crank_that_cannot_turn_reports_its_rod_perpendicular_to_the_slide(tmp_path):
    """Crank 2, rod 1.5, offset 0.25 (m): the rod stands perpendicular to the slide line at
    the limit positions, |r sin q - e| = l: sin q = (e - l) / r and (e + l) / r."""
    import kinelab as kl
    path = tmp_path / "short_rod.toml"
    kl.io.save(kl.mechanisms.slider_crank(crank=2.0, rod=1.5, offset=0.25), path,
               units={"length": "m", "angle": "deg"})
    result = run("check", path)
    assert result.exit_code == 0, result.output
    toggles = line(result.stdout, "toggles (det J = 0")
    q = [float(v) for v in re.findall(r"(-?[\d.]+) deg \(limit position: rod perpendicular to "
                                      r"the slide of slider\)", toggles)]
    assert q == pytest.approx([math.degrees(math.asin((0.25 - 1.5) / 2)),
                               math.degrees(math.asin((0.25 + 1.5) / 2))], abs=DEG_TOL)


def points_of(text: str, unit: str = "deg") -> list[tuple[float, float]]:
    """The '(q1 deg, q2 deg)' pairs of a toggles line of several inputs."""
    return [(float(a), float(b)) for a, b in
            re.findall(rf"\((-?[\d.e+-]+) {unit}, (-?[\d.e+-]+) {unit}\)", text)]


def pin_distance(q1, q2, crank=100.0, ground=100.0):
    """|AB| of a five-bar at crank angles q1, q2 (deg), in closed form."""
    a, b = math.radians(q1), math.radians(q2)
    return math.hypot(ground + crank * math.cos(b) - crank * math.cos(a),
                      crank * math.sin(b) - crank * math.sin(a))


def test_two_inputs_toggles_over_the_box_of_their_ranges():
    """The symmetric five-bar (ground, cranks 100 mm, couplers 120 mm) over the box of its
    ranges: its couplers fall in line on the curve |AB| = 240 mm, where its loops stop
    closing, and fold onto each other where A and B meet (|AB| = 0)."""
    result = run("check", HERE / "fivebar_reach.toml")
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert out.rstrip().endswith("\nok")
    toggles = line(out, "toggles (det J = 0")
    assert toggles.startswith("toggles (det J = 0, dead centres of the chain): reached in "
                              "jO2 in [90, 450] deg x jO4 in [90, 450] deg: ")
    count = re.search(r": (\d+) points found on a 61 x 61 grid, (\d+) limit positions \(the "
                      r"loops stop closing; bisected along the grid lines\): coupler1 and "
                      r"coupler2 in line, 2 isolated points on the grid; e\.g\. \(jO2, jO4\) = ",
                      toggles)
    assert count and int(count[1]) == int(count[2]) + 2 and int(count[2]) > 100
    shown = points_of(toggles)
    assert 2 <= len(shown) <= 4
    # each shown point is on the curve (nine figures of the angles: |AB| to about 1e-5 mm)
    # or where the pins meet
    for q1, q2 in shown:
        d = pin_distance(q1, q2)
        assert d == pytest.approx(240.0, abs=1e-4) or d == pytest.approx(0.0, abs=1e-4)
    assert line(out, "dead centres (K = 0)") == ("dead centres (K = 0): found for mechanisms "
                                                 "of one input; not searched for 2 inputs")


def test_two_inputs_toggles_in_portuguese():
    result = run("check", HERE / "fivebar_reach.toml", "--lang", "pt")
    assert result.exit_code == 0, result.output
    toggles = line(result.stdout, "posições de travamento")
    assert toggles.startswith("posições de travamento (det J = 0, cadeia alinhada): atingidas "
                              "em jO2 em [90, 450] deg x jO4 em [90, 450] deg: ")
    assert "posições limite (as malhas deixam de fechar" in toggles
    assert "coupler1 e coupler2 alinhados" in toggles and "2 pontos isolados na grade" in toggles
    assert all(pin_distance(*q) == pytest.approx(240.0, abs=1e-4)
               or pin_distance(*q) == pytest.approx(0.0, abs=1e-4)
               for q in points_of(toggles))
    assert "pontos mortos (K = 0): procurados em mecanismos de uma entrada" in result.stdout


def test_two_inputs_isolated_toggles_and_si():
    """The example five-bar (couplers 150 mm): det J = 0 only where |AB| = 300 mm at (180, 0)
    and (180, 360) deg, and where A and B meet at (300, 240) and (420, 120) deg, all on the
    grid's 6 deg steps; in SI, in rad."""
    out = run("check", EX / "fivebar.toml").stdout
    toggles = line(out, "toggles (det J = 0")
    assert ": 4 points found on a 61 x 61 grid, 4 isolated points on the grid; " in toggles
    assert points_of(toggles) == [(180.0, 0.0), (180.0, 360.0), (300.0, 240.0), (420.0, 120.0)]
    si = line(run("check", EX / "fivebar.toml", "--si").stdout, "toggles (det J = 0")
    assert "jO2 in [1.57079633, 7.85398163] rad x jO4 in [0, 6.28318531] rad" in si
    assert points_of(si, "rad")[0] == pytest.approx((math.pi, 0.0), abs=1e-8)


def test_two_inputs_not_reached_says_how_close_the_grid_came(tmp_path):
    """Ranges near the sketch, where the couplers never fall in line: not reached, with the
    grid sample closest to it."""
    text = (HERE / "fivebar_reach.toml").read_text()
    near = tmp_path / "near.toml"
    near.write_text(text.replace("range = [90, 450]", "range = [70, 110]"))
    result = run("check", near)
    assert result.exit_code == 0, result.output
    toggles = line(result.stdout, "toggles (det J = 0")
    found = re.fullmatch(r"toggles \(det J = 0, dead centres of the chain\): not reached in "
                         r"jO2 in \[70, 110\] deg x jO4 in \[70, 110\] deg \(a 61 x 61 grid; "
                         r"closest at \(jO2, jO4\) = \((-?[\d.]+) deg, (-?[\d.]+) deg\), where "
                         r"the sine of the transmission angle is ([\d.e-]+)\)", toggles)
    assert found, toggles
    q1, q2, sine = (float(v) for v in found.groups())
    # the couplers' angle there, from |AB| by the law of cosines (isosceles, sides 120)
    d = pin_distance(q1, q2)
    assert sine == pytest.approx(math.sin(2 * math.asin(d / 240.0)), rel=1e-3)
    pt = line(run("check", near, "--lang", "pt").stdout, "posições de travamento")
    assert "não atingidas em jO2 em [70, 110] deg x jO4 em [70, 110] deg" in pt


def test_two_inputs_solved_by_newton_say_toggles_are_not_searched(monkeypatch):
    """A plan with Newton-Raphson groups is continued from sample to sample, so its grid
    samples cannot be solved each on its own: check says so and goes on."""
    from kinelab import kinematics
    planned = kinematics.plan
    monkeypatch.setattr(kinematics, "plan", lambda m, method="auto": planned(m, method="newton"))
    result = run("check", HERE / "fivebar_reach.toml")
    assert result.exit_code == 0, result.output
    assert line(result.stdout, "toggles (det J = 0") == (
        "toggles (det J = 0, dead centres of the chain): not searched: with several inputs "
        "they are searched for mechanisms solved in closed form (dyads), and this one has a "
        "Newton-Raphson group")
    assert result.stdout.rstrip().endswith("\nok")
