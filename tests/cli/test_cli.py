"""The kinelab command: files written, summary printed, bad input refused with status 2."""
import csv
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.cli._main import analyze_in_chunks
from kinelab.errors import ModelError
from tests.io.bad_cases import BASE, CASES

ROOT = Path(__file__).resolve().parents[2]
EX = ROOT / "examples"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_commands_are_registered():
    assert {"analyze", "check", "plot", "animate", "export", "import", "mobility", "types"} <= set(main.commands)
    result = run("--help")
    assert result.exit_code == 0 and "analyze" in result.output


MM, DEG = 1e-3, math.pi / 180           # SI value of one mm, one degree


def read_csv(path):
    rows = list(csv.DictReader(Path(path).open()))
    return {name: np.array([float(r[name]) if r[name] not in ("True", "False")
                            else r[name] == "True" for r in rows]) for name in rows[0]}


@pytest.fixture(scope="module")
def crank_rocker_si():
    """The example's sweep worked in Python: 361 samples, 0 to 360 deg, 600 deg/s."""
    m = kl.load(EX / "crank_rocker.toml")
    return kl.analyze(m, np.radians(np.linspace(0.0, 360.0, 361)), np.radians(600.0))


def test_analyze_writes_csv_and_prints_summary_in_the_files_units(tmp_path, crank_rocker_si):
    result = run("analyze", EX / "crank_rocker.toml", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert "crank-rocker: 361 samples, crank angle from 0 to 360 deg" in out
    assert "Grashof: crank-rocker (GCRR); s + l <= p + q by 150 mm; lengths ground, crank, " \
           "coupler, rocker = 300, 100, 300, 250 mm" in out
    assert "time ratio of rocker: 1.211" in out          # (180 + 17.15) / (180 - 17.15) deg
    # at q = 0, |A O4| = 200 mm: cos mu = (300^2 + 250^2 - 200^2) / (2 300 250) = 0.75
    assert "transmission angle coupler-rocker: min 41.4096 deg at crank angle = 0 deg" in out \
        or "transmission angle coupler-rocker: min 41.4096 deg at crank angle = 360 deg" in out
    assert f"{math.degrees(math.acos(0.75)):.6g}" == "41.4096"
    assert "limit positions: none; crank angle turns fully" in out
    assert "rocker.angle[deg]" in out and "P.speed[mm/s]" in out and "[m]" not in out
    col = read_csv(tmp_path / "crank_rocker.csv")
    assert len(col["det_J"]) == 361
    for column in ("crank_angle.q[deg]", "rocker.angle[deg]", "rocker.omega[deg/s]",
                   "rocker.alpha[deg/s^2]", "rocker.K[deg/deg]", "rocker.L[deg/deg^2]",
                   "P.x[mm]", "P.vy[mm/s]", "P.ay[mm/s^2]", "P.x.K[mm/deg]", "P.x.L[mm/deg^2]",
                   "det_J", "singular"):
        assert column in col, column
    # mm and deg out, as the file is written; checked against the SI results times the
    # exact factors
    ref = crank_rocker_si
    assert col["O4.x[mm]"][0] == 300.0
    np.testing.assert_allclose(col["crank_angle.q[deg]"], np.linspace(0, 360, 361), rtol=1e-15)
    np.testing.assert_allclose(col["crank_angle.qd[deg/s]"], 600.0, rtol=1e-14)
    np.testing.assert_allclose(col["rocker.omega[deg/s]"], ref.omega("rocker") / DEG,
                               rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(col["P.vy[mm/s]"], ref.velocity("P")[:, 1] / MM, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(col["P.x.L[mm/deg^2]"], ref.L("P")[:, 0] * DEG ** 2 / MM,
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(col["rocker.K[deg/deg]"], ref.K("rocker"), rtol=1e-12, atol=1e-12)


def test_analyze_si_and_degrees_flags(tmp_path, crank_rocker_si):
    ref = crank_rocker_si
    result = run("analyze", EX / "crank_rocker.toml", "--out", tmp_path / "si.csv", "--si")
    assert result.exit_code == 0, result.output
    assert "crank angle from 0 to 6.28319 rad" in result.stdout
    assert "lengths ground, crank, coupler, rocker = 0.3, 0.1, 0.3, 0.25 m" in result.stdout
    col = read_csv(tmp_path / "si.csv")
    assert col["O4.x[m]"][0] == 0.3
    np.testing.assert_allclose(col["crank_angle.q[rad]"], ref.q[:, 0], rtol=1e-15)
    np.testing.assert_allclose(col["P.vy[m/s]"], ref.velocity("P")[:, 1], rtol=1e-12, atol=1e-12)
    result = run("analyze", EX / "crank_rocker.toml", "--out", tmp_path / "r.json", "--si",
                 "--degrees", "--samples", "5", "--quiet")
    assert result.exit_code == 0, result.output
    assert "Grashof" not in result.stdout
    rows = json.loads((tmp_path / "r.json").read_text())
    assert [r["crank_angle.q[deg]"] for r in rows] == pytest.approx([0, 90, 180, 270, 360], abs=1e-12)
    assert rows[0]["crank_angle.qd[deg/s]"] == pytest.approx(600.0, rel=1e-14)
    # metres: the crank's 100 mm along +x at 0 deg, along +y at 90 deg
    assert rows[0]["A.x[m]"] == pytest.approx(0.1, rel=1e-15)
    assert rows[1]["A.x[m]"] == pytest.approx(0.0, abs=1e-16) and rows[1]["A.y[m]"] == pytest.approx(0.1, rel=1e-15)
    m = kl.load(EX / "crank_rocker.toml")
    five = kl.analyze(m, np.radians([0.0, 90, 180, 270, 360]))
    assert [r["rocker.angle[deg]"] for r in rows] == pytest.approx(
        np.degrees(five.angle("rocker")), abs=1e-10)


def test_an_inch_file_answers_in_inches(tmp_path):
    mf = kl.io.ModelFile.read(EX / "crank_rocker.toml")
    path = kl.io.save(mf, tmp_path / "inch.toml", units={"length": "in", "angle": "rad"})
    result = run("analyze", path, "--out", tmp_path, "--samples", "9")
    assert result.exit_code == 0, result.output
    assert "A.x[m]" not in result.stdout and "P.x[in]" in result.stdout
    col = read_csv(tmp_path / "inch.csv")
    assert col["O4.x[in]"][0] == pytest.approx(0.3 / 0.0254, rel=1e-11)   # 12 digits in the file
    np.testing.assert_allclose(col["crank_angle.q[rad]"], np.linspace(0, 2 * np.pi, 9), rtol=1e-11)
    result = run("analyze", path, "--at", "0.5")
    assert "  A.x[in]" in result.stdout and "  crank_angle.q[rad]" in result.stdout


def test_analyze_parquet(tmp_path):
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    result = run("analyze", EX / "offset_slider_crank.toml", "--out", tmp_path, "--format",
                 "parquet", "--samples", "7", "-q")
    assert result.exit_code == 0, result.output
    frame = pd.read_parquet(tmp_path / "offset_slider_crank.parquet")
    assert frame.shape[0] == 7 and "slide.slide[mm]" in frame.columns
    assert not any(" " in name for name in frame.columns)


@pytest.mark.parametrize("path", sorted(EX.glob("*.toml")), ids=lambda p: p.stem)
def test_every_example_checks_and_analyses(path, tmp_path):
    result = run("check", path)
    assert result.exit_code == 0, result.output
    assert result.stdout.rstrip().endswith("ok")
    result = run("analyze", path, "--out", tmp_path, "--samples", "37")
    assert result.exit_code == 0, result.output
    assert (tmp_path / f"{path.stem}.csv").exists()


@pytest.mark.parametrize("where", ["under a file", "a directory", "a directory with a suffix"])
def test_unwritable_output_is_a_one_line_error_naming_the_target(where, tmp_path):
    (tmp_path / "file").write_text("")
    (tmp_path / "dir.csv").mkdir()
    target = {"under a file": tmp_path / "file" / "x.csv", "a directory": tmp_path / "dir.csv",
              "a directory with a suffix": tmp_path / "dir.csv"}[where]
    if where == "a directory with a suffix":     # not taken as a directory to write into
        from kinelab._files import write_csv
        with pytest.raises(ModelError, match=rf"^{re.escape(str(target))}: cannot write it: "):
            write_csv({"a": [1.0]}, target)
        return
    result = run("analyze", EX / "whitworth.toml", "--out", target, "--samples", "3", "-q")
    if where == "a directory":                   # the table goes inside it
        assert result.exit_code == 0 and (target / "whitworth.csv").exists()
        return
    assert result.exit_code == 2
    assert result.stderr.startswith(f"kinelab: error: {target}: cannot write it: ")
    assert result.stderr.count("\n") == 1 and ".x.csv." not in result.stderr
    assert sorted(tmp_path.iterdir()) == [tmp_path / "dir.csv", tmp_path / "file"]   # no leftovers


def test_whitworth_time_ratio_is_two(tmp_path):
    result = run("analyze", EX / "whitworth.toml", "--out", tmp_path)
    assert "time ratio of ram_slide: 2 " in result.stdout, result.output   # (pi + pi/3) / (pi - pi/3)


def test_check_reports_mobility_and_reachable_range():
    result = run("check", EX / "crank_rocker.toml")
    assert "mobility: 1 degree(s) of freedom at the sketch" in result.stdout
    assert "reachable: crank angle turns fully" in result.stdout
    assert "dyad 'coupler'-'rocker' (RRR A-B-O4)" in result.stdout


def at_values(text):
    return dict(re.split(r"\s{2,}", line.strip()) for line in text.splitlines()[1:] if line.strip())


def test_at_prints_one_configuration_in_the_files_units():
    result = run("analyze", EX / "crank_rocker.toml", "--at", "90")      # the file's degrees
    assert result.exit_code == 0, result.output
    again = run("analyze", EX / "crank_rocker.toml", "--at", f"{math.pi / 2}rad")
    assert again.stdout == result.stdout
    values = at_values(result.stdout)
    ref = kl.analyze(kl.load(EX / "crank_rocker.toml"), math.pi / 2, 600 * DEG)
    # printed to 10 significant digits, converted here by hand from the SI results
    assert float(values["crank_angle.q[deg]"]) == 90.0
    assert float(values["rocker.angle[deg]"]) == pytest.approx(float(ref.angle("rocker")) / DEG, rel=1e-9)
    assert float(values["rocker.omega[deg/s]"]) == pytest.approx(float(ref.omega("rocker")) / DEG, rel=1e-9)
    assert float(values["rocker.alpha[deg/s^2]"]) == pytest.approx(float(ref.alpha("rocker")) / DEG,
                                                                   rel=1e-9)
    assert float(values["B.vx[mm/s]"]) == pytest.approx(float(ref.velocity("B")[0]) / MM, rel=1e-9)
    assert float(values["B.y.L[mm/deg^2]"]) == pytest.approx(float(ref.L("B")[1]) * DEG ** 2 / MM,
                                                             rel=1e-9)
    assert float(values["A.y[mm]"]) == pytest.approx(100.0, abs=1e-9)     # the crank straight up
    assert values["singular"] == "false"
    assert "O2.x[mm]" not in values            # the frame's points are not repeated
    si = at_values(run("analyze", EX / "crank_rocker.toml", "--at", "90", "--si").stdout)
    assert float(si["rocker.angle[rad]"]) == pytest.approx(float(ref.angle("rocker")), rel=1e-9)
    assert float(si["A.y[m]"]) == pytest.approx(0.1, abs=1e-12)


A_NUMBER = ("a number in decimal or scientific notation in ASCII digits (1000, -0.5, 1.5e3), "
            "optionally followed by one of rad, deg")


@pytest.mark.parametrize("at, message", [
    ("abc", f"kinelab: error: --at: expected {A_NUMBER}, got 'abc'"),
    ("30mm", f"kinelab: error: --at: expected {A_NUMBER}, got '30mm'"),
    # one rule of numbers, as in files and CSV tables: no underscores, no other scripts' digits
    ("1_000", f"kinelab: error: --at: expected {A_NUMBER}, got '1_000'"),
    ("\uff13\uff10", f"kinelab: error: --at: expected {A_NUMBER}, got '\uff13\uff10'"),
    ("\u0663\u0660deg", f"kinelab: error: --at: expected {A_NUMBER}, got '\u0663\u0660deg'"),
    ("30,40", "kinelab: error: --at: expected 1 value(s) separated by commas (one per input: 'crank "
              "angle'), got '30,40'"),
    # 1e400 is inf; 1e300 deg is finite but no angle a sweep or a sine means anything at
    ("1e400", "kinelab: error: --at: expected a finite number, got '1e400'"),
    ("1e300deg", "kinelab: error: --at: expected angles within 1000 turns of 0 either way, got "
                 "'1e300deg'"),
])
def test_bad_at_value(at, message):
    result = run("analyze", EX / "crank_rocker.toml", "--at", at)
    assert result.exit_code == 2
    assert result.stderr.strip() == message


@pytest.mark.parametrize("name, text, message", CASES[::4], ids=[c[0] for c in CASES[::4]])
def test_bad_file_exit_status_2_one_line_and_no_output(name, text, message, tmp_path):
    model = tmp_path / "fb.toml"
    model.write_text(text)
    out = tmp_path / "out"
    for command in (["analyze", model, "--out", out], ["check", model], ["plot", model, "--out", out]):
        result = run(*command)
        assert result.exit_code == 2, result.output
        assert result.stderr == f"kinelab: error: {message}\n"
        assert "Traceback" not in result.output
    assert not out.exists()


def test_analyze_names_a_parallelogram_and_its_change_point_class(tmp_path):
    model = tmp_path / "parallelogram.toml"
    kl.io.save(kl.mechanisms.fourbar(0.1, 0.06, 0.1, 0.06), model, units={"length": "mm", "angle": "deg"})
    result = run("analyze", model, "--out", tmp_path / "out")
    assert result.exit_code == 0, result.output
    # s + l = 60 + 100 = p + q: a change point, with ground = coupler and crank = rocker
    assert "Grashof: change-point (S2X, parallelogram); s + l <= p + q by 0 mm; lengths ground, " \
           "crank, coupler, rocker = 100, 60, 100, 60 mm" in result.stdout


def test_unreachable_input_range_names_file_and_field(tmp_path):
    model = tmp_path / "nongrashof.toml"
    # non-Grashof: crank 200, coupler 100, rocker 150, ground 100; reaches |q| <= 108.21 deg
    model.write_text(BASE.replace("A = [0, 100]", "A = [200, 0]")
                     .replace("B = [261.506227, 247.018682]", "B = [212.5, -99.215674]")
                     .replace("O4 = [300, 0]", "O4 = [100, 0]").replace("length = 100", "length = 200"))
    result = run("check", model)
    assert result.exit_code == 2
    assert result.stderr.startswith("kinelab: error: nongrashof.toml: inputs[0].range: [0, 360] deg "
                                    "goes where the mechanism does not assemble; it reaches "
                                    "[-108.21, 108.21] deg; narrow the range")
    result = run("analyze", model, "--out", tmp_path / "out")
    assert result.exit_code == 2
    # in the file's units and names, with the file's advice
    assert re.fullmatch(r"kinelab: error: nongrashof\.toml: inputs: dyad 'coupler'-'rocker' \(RRR "
                        r"A-B-O4\) cannot close at 'jO2' = [0-9.]+ deg: it misses by [0-9.]+ "
                        r"mm; 'jO2' reaches \[-108\.21\d*, 108\.21\d*\] deg; narrow the "
                        r"range of the file's inputs\n", result.stderr)
    assert not (tmp_path / "out").exists()


def test_singular_sketch_is_refused(tmp_path):
    model = tmp_path / "straight.toml"
    # B halfway from A to O4: coupler and rocker drawn folded in one line, so the sketch cannot
    # tell the assembly branch
    model.write_text(BASE.replace("B = [261.506227, 247.018682]", "B = [150, 50]"))
    result = run("check", model)
    assert result.exit_code == 2
    assert result.stderr.startswith("kinelab: error: straight.toml: the sketch puts the dyad "
                                    "'coupler'-'rocker'")
    assert result.stderr.count("\n") == 1


def test_chunked_sweep_matches_one_sweep():
    for m, q in ((kl.load(EX / "crank_rocker.toml"), np.linspace(0, 2 * np.pi, 101)),
                 (kl.mechanisms.triad6(), np.linspace(0.0, 2 * np.pi, 101) + np.pi / 2)):
        qd, qdd = np.full_like(q, 2.0), np.full_like(q, 1.0)
        one = kl.analyze(m, q, qd, qdd, at_singular="flag")
        parts = analyze_in_chunks(m, q, qd, qdd, chunks=7)
        np.testing.assert_allclose(parts.jets, one.jets, rtol=0, atol=1e-9)
        np.testing.assert_allclose(parts.rates, one.rates, rtol=0, atol=1e-8)
        np.testing.assert_array_equal(parts.singular, one.singular)


def test_progress_sweep_gives_the_same_results():
    from kinelab.cli._main import sweep
    mf = kl.io.ModelFile.read(EX / "crank_rocker.toml")
    quiet = sweep(mf, 20001, progress=False)
    shown = sweep(mf, 20001, progress=True)          # in pieces, behind a bar on stderr
    np.testing.assert_allclose(shown.jets, quiet.jets, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(shown.q, quiet.q)


def test_speed_sets_the_input_speed_for_the_run(tmp_path):
    """--speed in the file's unit (deg/s here) or with its own; velocities scale with the speed
    and accelerations with its square (qdd = 0): K and L do not change."""
    base = run("analyze", EX / "crank_rocker.toml", "--out", tmp_path / "a.csv", "--samples", "13", "-q")
    fast = run("analyze", EX / "crank_rocker.toml", "--out", tmp_path / "b.csv", "--samples", "13", "-q",
               "--speed", "1800")
    assert base.exit_code == 0 and fast.exit_code == 0, fast.output
    a = list(csv.DictReader((tmp_path / "a.csv").open()))
    b = list(csv.DictReader((tmp_path / "b.csv").open()))
    for ra, rb in zip(a, b):
        assert float(rb["crank_angle.qd[deg/s]"]) == pytest.approx(1800.0, rel=1e-15)
        assert float(rb["rocker.omega[deg/s]"]) == pytest.approx(3 * float(ra["rocker.omega[deg/s]"]),
                                                                rel=1e-12, abs=1e-12)
        assert float(rb["P.ay[mm/s^2]"]) == pytest.approx(9 * float(ra["P.ay[mm/s^2]"]), rel=1e-12,
                                                          abs=1e-12)
        assert rb["rocker.K[deg/deg]"] == ra["rocker.K[deg/deg]"]
    one = run("analyze", EX / "crank_rocker.toml", "--at", "90", "--speed", "2rad", "--si")
    values = dict(re.split(r"\s{2,}", line.strip()) for line in one.stdout.splitlines()[1:]
                  if line.strip())
    assert float(values["crank_angle.qd[rad/s]"]) == 2.0
    ref = kl.analyze(kl.load(EX / "crank_rocker.toml"), math.pi / 2, 2.0)
    assert float(values["rocker.omega[rad/s]"]) == pytest.approx(float(ref.omega("rocker")), rel=1e-9)


def test_speed_of_several_inputs(tmp_path):
    result = run("analyze", EX / "fivebar.toml", "--out", tmp_path / "f.csv", "--samples", "5", "-q",
                 "--speed", "60deg,-1rad")
    assert result.exit_code == 0, result.output
    rows = list(csv.DictReader((tmp_path / "f.csv").open()))
    assert [float(r["jO2.qd[deg/s]"]) for r in rows] == pytest.approx([60.0] * 5, rel=1e-15)
    assert [float(r["jO4.qd[deg/s]"]) for r in rows] == pytest.approx([-math.degrees(1.0)] * 5, rel=1e-15)


@pytest.mark.parametrize("speed, message", [
    ("fast", f"--speed: expected {A_NUMBER}, got 'fast'"),
    ("60mm", f"--speed: expected {A_NUMBER}, got '60mm'"),
    ("inf", f"--speed: expected {A_NUMBER}, got 'inf'"),
    ("6_0", f"--speed: expected {A_NUMBER}, got '6_0'"),
    ("60,30", "--speed: expected 1 value(s) separated by commas (one per input: 'crank angle'), "
              "got '60,30'"),
])
def test_bad_speed_value(speed, message, tmp_path):
    result = run("analyze", EX / "crank_rocker.toml", "--speed", speed, "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert result.stderr == f"kinelab: error: {message}\n"
    assert not (tmp_path / "out").exists()


def test_imported_pyslvs_model_has_a_speed(tmp_path):
    """Pyslvs gives no speeds: the imported file says which it was given, and its velocities
    are not zero (velocities = K times 100 rpm)."""
    source = tmp_path / "sc.pyslvs"
    source.write_text("M[J[R, P[0, 0], L[ground, crank]], J[R, P[0, 5], L[crank, rod]], "
                      "J[RP, A[0], P[19.7737199, 2], L[ground, rod]]]")
    result = run("import", source, "--out", tmp_path / "sc.toml")
    assert result.exit_code == 0, result.output
    text = (tmp_path / "sc.toml").read_text()
    assert "600 deg/s (100 rpm) for an angle, 100 mm/s for a slide" in text
    assert "speed = 600.0" in text
    m = kl.load(tmp_path / "sc.toml")
    assert m.inputs[0].speed == pytest.approx(2 * math.pi * 100 / 60, rel=1e-15)
    result = run("analyze", tmp_path / "sc.toml", "--at", "30", "--si")
    values = dict(re.split(r"\s{2,}", line.strip()) for line in result.stdout.splitlines()[1:]
                  if line.strip())
    K = float(kl.analyze(m, math.radians(30)).K("sP2"))
    assert float(values["sP2.slide_velocity[m/s]"]) == pytest.approx(K * 2 * math.pi * 100 / 60, rel=1e-9)
    assert K != 0.0


def test_summary_of_a_crank_that_cannot_turn(tmp_path):
    """No time ratio, and why; limit positions written near the swept range (the window
    around the catalogue's sketch put them a turn away, at -6.62 rad)."""
    model = tmp_path / "long_crank.toml"
    model.write_text('schema = 1\nname = "long crank"\n[units]\nlength = "m"\nangle = "deg"\n'
                     '[catalogue]\nkind = "slider_crank"\ncrank = 3.0\nrod = 1.0\n'
                     '[[inputs]]\njoint = "jO2"\nrange = [-15, 15]\nspeed = 60\n'
                     '[outputs]\ntime_ratio = "slide"\n')
    result = run("analyze", model, "--out", tmp_path, "--si")
    assert result.exit_code == 0, result.output
    # |sin q| <= 1/3: asin(1/3) = 0.339837 rad
    assert ("limit positions of jO2 (it cannot go past them): -3.48143 rad and -2.80176 rad; "
            "-0.339837 rad and 0.339837 rad") in result.stdout
    assert ("time ratio of slide: none; jO2 cannot turn a full turn (it reaches only "
            "[-3.48143, -2.80176] and [-0.339837, 0.339837] rad)") in result.stdout
    result = run("analyze", model, "--out", tmp_path)            # the file's degrees
    assert "(it reaches only [-199.471, -160.529] and [-19.4712, 19.4712] deg)" in result.stdout


@pytest.mark.parametrize("field, bad, message", [
    ("length", "furlong", "units.length: expected one of 'm', 'cm', 'mm', 'in', got 'furlong'"),
    ("angle", "grad", "units.angle: expected one of 'rad', 'deg', got 'grad' (did you mean 'rad'?)"),
])
def test_a_unit_the_file_cannot_declare_is_one_line_status_2_nothing_written(tmp_path, field, bad,
                                                                            message):
    model = tmp_path / "fb.toml"
    model.write_text(BASE.replace(f'{field} = "{"mm" if field == "length" else "deg"}"',
                                  f'{field} = "{bad}"'))
    out = tmp_path / "out"
    for command in (["analyze", model, "--out", out], ["analyze", model, "--at", "30"],
                    ["analyze", model, "--si", "--out", out], ["check", model],
                    ["plot", model, "--out", out], ["animate", model, "--out", out],
                    ["dynamics", model, "--out", out]):
        result = run(*command)
        assert result.exit_code == 2, (command, result.output)
        assert result.stderr == f"kinelab: error: fb.toml: {message}\n", command
    assert not out.exists()


# -- options and outputs: one line, exit status 2, nothing written -------------------------
@pytest.mark.parametrize("args, message", [
    (["--out", "x.xlsx"], "path: expected a file name ending in .csv, .json, .parquet, got "
                          "'x.xlsx'; rename it or give the format"),
    (["--out", "x.json", "--format", "csv"], "format: 'csv' was asked for, but the file name "
                                             "'x.json' says 'json'; make them agree"),
])
def test_a_table_is_not_written_under_another_formats_name(args, message, tmp_path):
    args = [str(tmp_path / a) if a.startswith("x.") else a for a in args]
    result = run("analyze", EX / "crank_rocker.toml", "--samples", "5", "-q", *args)
    assert result.exit_code == 2 and result.stderr == f"kinelab: error: {message}\n"
    assert list(tmp_path.iterdir()) == []


def test_an_explicit_format_under_another_name_says_so(tmp_path):
    out = tmp_path / "table.txt"
    result = run("analyze", EX / "crank_rocker.toml", "--samples", "5", "-q", "--out", out,
                 "--format", "json")
    assert result.exit_code == 0, result.output
    assert "(JSON as --format says, whatever the name;" in result.stdout
    assert len(json.loads(out.read_text())) == 5


def test_plot_writes_every_figure_in_its_directory(tmp_path):
    out = tmp_path / "figures.png"        # a directory, whatever its name looks like
    result = run("plot", EX / "crank_rocker.toml", "--samples", "9", "--out", out,
                 "--format", "png", "--format", "svg")
    assert result.exit_code == 0, result.output
    written = sorted(p.name for p in out.iterdir())
    assert "crank_rocker_motion.png" in written and "crank_rocker_motion.svg" in written
    assert len(written) == len(set(result.stdout.split())) - 1 == result.stdout.count("wrote ")


@pytest.mark.parametrize("command, option, value, message", [
    ("plot", "--outputs", "rocker,a\x1b[2Jb," + ",".join(f"q{i}" for i in range(100)),
     "--outputs: expected links, slides or points of 'crank-rocker', got 'a\\x1b[2Jb', 'q0', "
     + ", ".join(f"'q{i}'" for i in range(1, 19)) + " and 81 more; they are 'ground', 'crank', "
     "'coupler', 'rocker', 'O2', 'A', 'B', 'O4', 'P'"),
    ("animate", "--trace", "P,\ud800",
     "--trace: expected points of 'crank-rocker', got '\\ud800'; they are 'O2', 'A', 'B', 'O4', 'P'"),
])
def test_names_in_options_are_escaped_and_bounded(command, option, value, message, tmp_path):
    result = run(command, EX / "crank_rocker.toml", option, value, "--out", tmp_path)
    assert result.exit_code == 2
    assert result.stderr == f"kinelab: error: {message}\n"


@pytest.mark.parametrize("name, text, message", [
    ("long.pyslvs", "M[J[R, P[0, " + "9" * 5000 + "], L[ground, a]]]",
     "long.pyslvs: expression: joint 0: expected finite numbers"),
    ("big.pyslvs", "M[J[R, P[0, 0], L[ground, a]], J[R, P[0, 1e300], L[a]]]",
     "big.pyslvs: expression: joint 1: coordinates: expected at most 1e+09 m in size, got "
     "(0, 1e+297, 0) m"),
    ("bad.pyslvs", "M[J[Q" + "x" * 1000 + ", P[0, 0], L[ground, a]]]",
     "bad.pyslvs: expression: joint 0: type: expected one of 'R', 'P', 'RP', got 'Q"
     + "x" * 56 + "\u2026'"),
    ("twice.json", '{"links": [], "joints": [], "links": []}',
     "twice.json: links: given twice in the same table; keep one"),
    ("deep.json", '{"links": ' + "[" * 400 + "]" * 400 + ', "joints": []}',
     "deep.json: links" + "[0]" * 31 + ": nested more than 32 deep; no file kinelab reads needs "
     "that many levels"),
])
def test_imported_files_are_refused_in_one_line(name, text, message, tmp_path):
    source = tmp_path / name
    source.write_text(text)
    result = run("import", source, "--out", tmp_path / "m.toml")
    assert result.exit_code == 2, result.output
    assert result.stderr == f"kinelab: error: {message}\n"
    assert not (tmp_path / "m.toml").exists()


def test_file_paths_are_shown_escaped_on_one_line(tmp_path):
    """A newline or an escape sequence in a file's name cannot split a message or reach the
    terminal: the path is shown as given, with those characters escaped."""
    odd = tmp_path / "a\nb\x1b[31m.toml"
    result = run("check", odd)
    assert result.exit_code == 2
    assert result.stderr == f"kinelab: error: {tmp_path}/a\\nb\\x1b[31m.toml: no such file; check the path\n"
    odd.write_text((EX / "crank_rocker.toml").read_text())
    result = run("check", odd)
    assert result.exit_code == 0, result.output
    assert result.output.startswith(f"{tmp_path}/a\\nb\\x1b[31m.toml: crank-rocker: ")
    result = run("analyze", odd, "--out", tmp_path / "out\nput")
    assert result.exit_code == 0, result.output
    assert f"wrote {tmp_path}/out\\nput/" in result.output and "\x1b" not in result.output


@pytest.mark.parametrize("args, message", [
    (["types", "--space", "planar", "--mobility", "abc"],
     "Invalid value for '--mobility': 'abc' is not a valid integer range. (see 'kinelab types --help')"),
    (["check"], "Missing argument 'MODEL'. (see 'kinelab check --help')"),
    (["nosuch"], "No such command 'nosuch'. (see 'kinelab --help')"),
    (["--memory-budget", "0.0000001", "check", "x.toml"],
     "Invalid value for '--memory-budget': expected a size such as 8G, 512M or a number of bytes "
     "(at least 1), got '0.0000001' (see 'kinelab --help')"),
    (["dynamics", "no\nsuch.toml"],
     "Invalid value for 'MODEL': File 'no\\nsuch.toml' does not exist. (see 'kinelab dynamics --help')"),
])
def test_usage_errors_are_one_line(args, message):
    """What the command line cannot parse is said like every other error: one line, exit
    status 2, pointing to --help."""
    result = run(*args)
    assert result.exit_code == 2
    assert result.stderr == f"kinelab: error: {message}\n"


def test_a_bad_memory_budget_in_the_environment_is_said_before_any_work(monkeypatch):
    from kinelab import _memory
    monkeypatch.setenv("KINELAB_MEMORY_BUDGET", "abc")
    monkeypatch.setattr(_memory, "_budget", None)
    result = run("check", EX / "crank_rocker.toml")
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr == ("kinelab: error: KINELAB_MEMORY_BUDGET: expected a size such as 8G, "
                             "512M or a number of bytes (at least 1), got 'abc' (see 'kinelab --help')\n")


def test_an_import_that_check_would_refuse_writes_nothing(tmp_path):
    """Three inputs on a four-bar: the written file would fail 'kinelab check'; the import
    says why instead, and writes no file."""
    source = tmp_path / "cr.pyslvs"
    assert run("export", EX / "crank_rocker.toml", "--to", "pyslvs", "--out", source).exit_code == 0
    result = run("import", source, "--out", tmp_path / "m.toml", "--inputs", "0,1;1,2;2,3")
    assert result.exit_code == 2
    assert result.stderr == ("kinelab: error: cr.pyslvs: inputs: the linkage has 1 degree(s) of "
                             "freedom as drawn (exact mobility; Kutzbach-Gruebler counts 1) but 3 "
                             "input(s); give it 1 input(s), or fewer joints\n")
    assert not (tmp_path / "m.toml").exists()


@pytest.mark.parametrize("fmt", ["json", "csv"])
def test_a_table_too_large_to_write_as_text_is_refused_before_the_sweep(tmp_path, fmt):
    """The documented maximum of samples holds for Parquet; as text, the bound on values
    (rows x columns) says how many rows fit, before any work."""
    res = run("analyze", EX / "crank_rocker.toml", "--samples", 1_000_000, "-o", tmp_path / f"big.{fmt}")
    assert res.exit_code == 2
    most = kl.io._results.MAX_TABLE_VALUES[fmt]
    assert res.output == (f"kinelab: error: --samples: a {fmt.upper()} table of 1,000,000 rows x 76 "
                          f"columns is 76,000,000 values; kinelab writes at most {most:,} as "
                          f"{fmt.upper()} (about 30 s): ask for at most {most // 76:,} rows; or "
                          "write Parquet (--format parquet)\n")
    assert not list(tmp_path.iterdir())
