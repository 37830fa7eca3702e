"""The gallery of classic mechanisms: every entry loads, checks, assembles over its input
range with rigid links, and does what its name says (straight lines, Grashof classes, quick
returns, dwells, exact curves); ``kinelab gallery`` lists the entries and writes one's file."""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.errors import ModelError
from kinelab.io import ModelFile

NAMES = kl.gallery.names()
MM = 1e-3


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def sweep(name, samples=None):
    mf = kl.gallery.load(name)
    return mf, mf.analyze(samples)


def line_fit(points):
    """The stroke of ``points`` (N, 2) along their best straight line (principal axis) and
    their largest distance from it."""
    centred = points - points.mean(axis=0)
    _, _, axes = np.linalg.svd(centred, full_matrices=False)
    along, across = centred @ axes[0], centred @ axes[1]
    return np.ptp(along), np.abs(across).max()


def test_the_gallery_has_thirty_entries_with_titles_and_histories():
    assert len(NAMES) >= 30 and len(set(NAMES)) == len(NAMES)
    for e in kl.gallery.entries():
        assert e.title and "\n" not in e.title
        assert 40 < len(e.history) < 600, e.name          # a sentence or two, not a page
        assert e.path.is_file() and e.path.stem == e.name
    # every model file shipped is an entry, and is packaged
    shipped = {p.stem for p in kl.gallery.entry(NAMES[0]).path.parent.glob("*.toml")}
    assert shipped == set(NAMES)
    pyproject = (Path(__file__).resolve().parents[1] / "pyproject.toml").read_text()
    assert '"kinelab.gallery" = ["index.toml", "models/*.toml"]' in pyproject


@pytest.mark.parametrize("name", NAMES)
def test_entry_passes_check(name):
    result = run("check", kl.gallery.entry(name).path)
    assert result.exit_code == 0, result.output
    mf = kl.gallery.load(name)
    assert mf.mechanism.name == name and mf.description == kl.gallery.entry(name).title
    # the sketch shows the assembly mode the file means: nothing switched to the other mode
    assert mf.assembly is None or not mf.assembly.switched
    assert kl.structure.mobility(mf.mechanism).exact == len(mf.mechanism.inputs)


@pytest.mark.parametrize("name", NAMES)
def test_entry_assembles_over_its_inputs_with_rigid_links(name):
    mf, sol = sweep(name)
    assert len(sol.q) >= 200 and not sol.singular.any()
    for link in mf.mechanism.links:
        for i, a in enumerate(link.points):
            for b in link.points[i + 1:]:
                d = np.linalg.norm(sol.position(a) - sol.position(b), axis=1)
                assert np.ptp(d) <= 1e-9 * d.max(), (link.name, a, b)


# name, traced point, crank window (deg, relative to the file's input; None: the whole range),
# largest distance from the best straight line as a fraction of the stroke, shortest stroke
# as a fraction of the input link.
STRAIGHT = [
    ("watt_linkage", "P", None, 0.02, 0.4),                 # arms swinging +-12 deg
    ("beam_engine", "P", None, 0.03, 1.5),                  # Watt's linkage, beam +-16 deg
    ("chebyshev_straight_line", "P", None, 0.003, 0.4),     # rockers +-15 deg
    ("roberts", "P", None, 0.006, 1.0),                     # rockers +-15 deg
    ("hoeken", "P", (90, 270), 0.0015, 3.5),                # half a turn of the crank
    ("chebyshev_lambda", "P", (-90, 90), 0.0015, 3.5),
    ("peaucellier_lipkin", "P", None, 1e-9, 2.5),           # exact
    ("hart_inversor", "Q", None, 1e-9, 2.0),                # exact
]


@pytest.mark.parametrize("name, point, window, tolerance, stroke", STRAIGHT)
def test_straight_line_linkage_is_straight(name, point, window, tolerance, stroke):
    mf, sol = sweep(name, 721)
    q = np.degrees(sol.q[:, 0])
    if window is not None:
        q0, q1 = window
        keep = (q - q0) % 360 <= q1 - q0
        assert keep.sum() > 300
    else:
        keep = np.ones(len(q), bool)
    length, off = line_fit(sol.position(point)[keep])
    driven = mf.mechanism.links[1]
    input_length = np.linalg.norm(sol.position(driven.points[0])[0] - sol.position(driven.points[1])[0])
    assert length > stroke * input_length
    assert off <= tolerance * length


def test_peaucellier_lipkin_inverts_onto_its_line():
    # OD * OP = OB^2 - BD^2 = 250^2 - 100^2, and D on a circle of diameter 200 through O: the
    # line is x = 52500 / 200 = 262.5 mm
    _, sol = sweep("peaucellier_lipkin")
    O, D, P = (sol.position(n) for n in "ODP")
    np.testing.assert_allclose(np.linalg.norm(D - O, axis=1) * np.linalg.norm(P - O, axis=1),
                               (250**2 - 100**2) * MM**2, rtol=1e-10)
    np.testing.assert_allclose(P[:, 0], 262.5 * MM, rtol=1e-10)


def test_hart_inversor_moves_perpendicular_to_its_pivots():
    _, sol = sweep("hart_inversor")
    Q = sol.position("Q")
    pivots = sol.position("Op")[0] - sol.position("O")[0]
    assert np.abs((Q - Q[0]) @ pivots).max() <= 1e-10 * np.ptp(Q, axis=0).max()


def test_hoeken_and_chebyshev_lambda_are_cognates_tracing_one_curve():
    _, hoeken = sweep("hoeken", 3601)
    _, lam = sweep("chebyshev_lambda", 361)
    curve, points = hoeken.position("P"), lam.position("P")
    gaps = np.min(np.linalg.norm(points[:, None, :] - curve[None, :, :], axis=2), axis=1)
    assert gaps.max() < 1e-3 * np.ptp(curve, axis=0).max()
    # while the lambda's crank turns about another pivot
    assert not np.allclose(lam.position("O2")[0], hoeken.position("O2")[0])


def four_lengths(name):
    """ground, input, coupler, output: the four-bar's distances at its sketch."""
    m = kl.gallery.load(name).mechanism
    at = {p.name: np.array(p.xy) for p in m.points}
    dist = lambda a, b: float(np.linalg.norm(at[a] - at[b]))
    return dist("O2", "O4"), dist("O2", "A"), dist("A", "B"), dist("O4", "B")


@pytest.mark.parametrize("name, kind", [
    ("crank_rocker", "crank-rocker"), ("drag_link", "double-crank"),
    ("double_rocker", "double-rocker"), ("triple_rocker", "triple-rocker"),
    ("hoeken", "crank-rocker"), ("windshield_wiper", "crank-rocker"),
])
def test_grashof_class_is_what_the_name_says(name, kind):
    ground, crank, coupler, rocker = four_lengths(name)
    assert kl.mechanisms.grashof(ground, crank, coupler, rocker).kind == kind
    # and the motion agrees: which ground-pivoted links turn fully, measured on a sweep
    m = kl.gallery.load(name).mechanism
    output = m.links[3].name
    turns = kind in ("crank-rocker", "double-crank")
    if turns:
        sol = kl.analyze(m, q=np.radians(np.arange(0.0, 360.5, 0.5)))
        span = np.ptp(np.unwrap(sol.angle(output)))
        assert (span > 1.99 * np.pi) == (kind == "double-crank")
    else:
        with pytest.raises(kl.errors.AssemblyError):      # the input cannot turn a full circle
            kl.analyze(m, q=np.radians(np.arange(0.0, 360.0, 0.5)))


def time_ratio(q, x):
    """Slow stroke over quick stroke: the crank angles spent going from the least to the
    greatest x, and back, on one turn sampled evenly (q in degrees)."""
    lo, hi = q[np.argmin(x)], q[np.argmax(x)]
    forward = (hi - lo) % 360
    return max(forward, 360 - forward) / min(forward, 360 - forward)


@pytest.mark.parametrize("name, output", [
    ("slotted_link", "lever"), ("crank_shaper", "stroke"), ("whitworth", "ram_slide")])
def test_quick_returns_have_time_ratio_two(name, output):
    # each is built with sin(half the lever's swing) = crank / pivot distance = 1/2: a swing of
    # 60 deg, and (180 + 60) / (180 - 60) = 2
    _, sol = sweep(name, 3601)
    q = np.degrees(sol.q[:, 0])
    x = sol.slide(output) if output in ("stroke", "ram_slide") else np.unwrap(sol.angle(output))
    assert time_ratio(q[:-1], x[:-1]) == pytest.approx(2.0, abs=0.01)


def test_dwell_six_bar_pauses_while_the_coupler_point_is_on_its_arc():
    _, sol = sweep("dwell_six_bar", 721)
    q = np.degrees(sol.q[:, 0])
    angle = np.unwrap(sol.angle("output"))
    on_arc = (q >= 114) & (q <= 184)
    assert np.ptp(angle) > np.radians(30)
    assert np.ptp(angle[on_arc]) < 0.01 * np.ptp(angle)


def test_scotch_yoke_is_simple_harmonic():
    _, sol = sweep("scotch_yoke")
    x = sol.slide("guides")
    np.testing.assert_allclose(x - x[0], 100 * MM * (np.cos(sol.q[:, 0]) - 1), atol=1e-12)


def test_elliptic_trammel_draws_its_ellipse():
    _, sol = sweep("elliptic_trammel")
    x, y = sol.position("P").T
    np.testing.assert_allclose((x / (100 * MM))**2 + (y / (400 * MM))**2, 1.0, rtol=1e-10)


def test_pantograph_draws_at_twice_the_scale():
    _, sol = sweep("pantograph")
    np.testing.assert_allclose(sol.position("P"), 2 * sol.position("T"), atol=1e-12)
    assert np.ptp(sol.position("T"), axis=0).min() > 10 * MM       # both inputs move it


def test_toggle_press_ram_stops_at_the_bottom_of_its_stroke():
    _, sol = sweep("toggle_press", 3601)
    y, v = sol.slide("stroke"), sol.slide_velocity("stroke")
    bottom = np.argmin(y)
    assert abs(v[bottom]) < 1e-3 * np.abs(v).max()


def test_jansen_uses_the_holy_numbers():
    m = kl.gallery.load("jansen").mechanism
    at = {p.name: np.array(p.xy) / 0.01 for p in m.points}       # cm
    dist = lambda a, b: np.linalg.norm(at[a] - at[b])
    assert at["O"] - at["B"] == pytest.approx([38, 7.8])          # a, l
    holy = {("O", "A"): 15, ("B", "C"): 41.5, ("B", "D"): 39.3, ("B", "E"): 40.1,
            ("C", "E"): 55.8, ("E", "F"): 39.4, ("D", "F"): 36.7, ("F", "G"): 65.7,
            ("D", "G"): 49, ("A", "C"): 50, ("A", "D"): 61.9}    # m, b, c, d, e, f, g, h, i, j, k
    for (a, b), length in holy.items():
        assert dist(a, b) == pytest.approx(length, abs=1e-9), (a, b)


def test_klann_foot_strides_flat_and_returns_raised():
    # the stance: about half a turn of the crank (20 to 200 deg) with the foot within 4 % of
    # its stride of a straight line, the stride over 4 cranks; the return lifts the foot
    # more than half a stride off that line, on the body's side of it
    mf, sol = sweep("klann", 721)
    q, F = np.degrees(sol.q[:, 0]), sol.position("F")
    stance = (q >= 20) & (q <= 200)
    stride, off = line_fit(F[stance])
    crank = np.linalg.norm(sol.position("A")[0] - sol.position("O")[0])
    assert stride > 4 * crank and off <= 0.04 * stride
    centre = F[stance].mean(axis=0)
    normal = np.linalg.svd(F[stance] - centre)[2][1]
    normal *= np.sign(normal @ (sol.position("O")[0] - centre))        # towards the body
    assert ((F - centre) @ normal).max() > 0.5 * stride
    assert ((F[~stance] - centre) @ normal).min() > -off - 1e-12


def test_load_reads_what_the_model_file_reads():
    e = kl.gallery.entry("watt_linkage")
    assert kl.gallery.load("watt_linkage") == ModelFile.read(e.path)


def test_unknown_entry_is_refused_with_a_suggestion():
    with pytest.raises(ModelError, match=r"gallery: no entry 'wat_linkage' \(did you mean "
                                         r"'watt_linkage'\?\); kinelab.gallery.names\(\)"):
        kl.gallery.entry("wat_linkage")


def test_listing_the_gallery_reads_no_model_file():
    code = ("import sys, kinelab as kl; kl.gallery.names(); kl.gallery.entry('hoeken');"
            "print(sorted(m for m in sys.modules if m.startswith(('kinelab.io', 'numpy'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_cli_lists_every_entry_on_one_line():
    result = run("gallery")
    assert result.exit_code == 0
    lines = result.output.splitlines()
    assert len(lines) == len(NAMES)
    for line, e in zip(lines, kl.gallery.entries()):
        assert line.split()[0] == e.name and line.endswith(e.title)


def test_cli_writes_the_model_file_into_out(tmp_path):
    out = tmp_path / "new" / "dir"
    result = run("gallery", "peaucellier_lipkin", "--out", out)
    assert result.exit_code == 0, result.output
    written = out / "peaucellier_lipkin.toml"
    assert [p.name for p in out.iterdir()] == [written.name]
    assert written.read_bytes() == kl.gallery.entry("peaucellier_lipkin").path.read_bytes()
    assert "Peaucellier" in result.output and "1864" in result.output
    assert ModelFile.read(written).mechanism == kl.gallery.load("peaucellier_lipkin").mechanism
    # the copy is a model file to work on with the other commands
    assert run("check", written).exit_code == 0


def test_cli_writes_into_the_current_directory_by_default(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert run("gallery", "jansen").exit_code == 0
    assert [p.name for p in tmp_path.iterdir()] == ["jansen.toml"]


@pytest.mark.parametrize("name", ["hokeen", "../hoeken", "/etc/passwd", ""])
def test_cli_refuses_an_unknown_name_in_one_line(name, tmp_path):
    result = run("gallery", name, "--out", tmp_path / "out")
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinelab: error: NAME: no entry ")
    assert "'kinelab gallery' lists the" in lines[0]
    assert not (tmp_path / "out").exists() and not (tmp_path / "hoeken.toml").exists()


def test_cli_suggests_a_close_name():
    result = run("gallery", "hokeen")
    assert "no entry 'hokeen' (did you mean 'hoeken'?)" in result.output


def test_cli_out_without_name_is_refused(tmp_path):
    result = run("gallery", "--out", tmp_path / "x")
    assert result.exit_code == 2 and len(result.output.strip().splitlines()) == 1
    assert not (tmp_path / "x").exists()


def test_ackermann_steering_turns_the_inner_wheel_more():
    _, sol = sweep("ackermann_steering")
    middle = len(sol.q) // 2                     # the input range is centred on straight ahead
    left = sol.q[:, 0] - sol.q[middle, 0]
    right = np.unwrap(sol.angle("right_arm")) - np.unwrap(sol.angle("right_arm"))[middle]
    assert np.sign(left[0]) == np.sign(right[0]) and np.sign(left[-1]) == np.sign(right[-1])
    turning_left, turning_right = left > 0, left < 0
    assert np.all(np.abs(left[turning_left]) > np.abs(right[turning_left]))
    assert np.all(np.abs(right[turning_right]) > np.abs(left[turning_right]))
