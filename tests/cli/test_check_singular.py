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
