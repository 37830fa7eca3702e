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
# the entries a model file describes in space (for their mobility): kinelab.spatial analyses
# them, the planar engine the others
SPATIAL = ("sarrus", "bennett", "cardan", "double_cardan", "stewart_platform")
PLANAR = tuple(n for n in NAMES if n not in SPATIAL)
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


def test_spatial_entries_are_the_non_planar_ones():
    assert set(SPATIAL) <= set(NAMES)
    for name in NAMES:
        space = kl.gallery.load(name).mechanism.space
        assert (space != "planar") == (name in SPATIAL), name


@pytest.mark.parametrize("name", PLANAR)
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


@pytest.mark.parametrize("typed, meant", [("hokeen", "hoeken"), ("bennet", "bennett"),
                                          ("sarus", "sarrus"), ("klan", "klann")])
def test_cli_suggests_a_close_name(typed, meant):
    result = run("gallery", typed)
    assert f"no entry '{typed}' (did you mean '{meant}'?)" in result.output


@pytest.mark.parametrize("name", SPATIAL)
def test_cli_writes_a_spatial_entry_that_checks(name, tmp_path):
    result = run("gallery", name, "--out", tmp_path)
    assert result.exit_code == 0, result.output
    assert (tmp_path / f"{name}.toml").read_bytes() == kl.gallery.entry(name).path.read_bytes()
    assert run("check", tmp_path / f"{name}.toml").exit_code == 0


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


# -- the spatial entries: mobility counted and exact, and an analysis by kinelab.spatial,
# each checked by a second route (a closed form, or the closure of the file's own joints)

def spatial_model(name):
    m = kl.gallery.load(name).mechanism
    at = {p.name: np.array([p.x, p.y, p.z]) for p in m.points}
    axis = {j.name: np.array(j.axis) / np.linalg.norm(j.axis) for j in m.joints if j.axis}
    return m, at, axis


def about(axis, angle, point=np.zeros(3)):
    """4x4 transforms of rotations by ``angle`` (N,) about the line through ``point``
    along the unit ``axis`` (Rodrigues), shape (N, 4, 4)."""
    k = np.asarray(axis, float)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    angle = np.atleast_1d(angle)[:, None, None]
    R = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * (K @ K)
    T = np.tile(np.eye(4), (len(R), 1, 1))
    T[:, :3, :3], T[:, :3, 3] = R, point - R @ point
    return T


def angle_between(u, v):
    return float(np.arccos(np.clip(u @ v / np.linalg.norm(u) / np.linalg.norm(v), -1, 1)))


MOBILITY = [
    ("sarrus", "M = 6(6 − 1) − 5·6 = 0.", "M = 1, not 0 as counted: 1 constraint equation"),
    ("bennett", "M = 6(4 − 1) − 5·4 = -2.", "M = 1, not -2 as counted: a negative count"),
    ("cardan", "(spherical, λ = 3): M = 3(4 − 1) − 2·4 = 1.", "M = 1, as counted"),
    ("double_cardan", "M = 6(6 − 1) − 5·6 = 0.", "M = 1, not 0 as counted: 1 constraint"),
    ("stewart_platform", "M = 6(14 − 1) − 5·6 − 3·12 = 12.",
     "M = 6, not 12 as counted: 6 freedoms are passive"),
]
# each spatial entry's analysis by kinelab.spatial, tested below
ANALYSED = {"sarrus": "test_sarrus_plate_rises_straight_by_the_closure_of_both_legs",
            "bennett": "test_bennett_closes_over_a_turn_from_the_file_geometry",
            "cardan": "test_cardan_output_and_speed_ratio_over_a_turn",
            "double_cardan": "test_double_cardan_output_equals_its_input",
            "stewart_platform": "test_stewart_platform_legs_by_inverse_kinematics"}


def test_every_spatial_entry_is_checked_and_analysed():
    assert {name for name, *_ in MOBILITY} == set(ANALYSED) == set(SPATIAL)
    assert all(callable(globals()[test]) for test in ANALYSED.values())


@pytest.mark.parametrize("name, counted, exact", MOBILITY)
def test_spatial_entry_check_counts_and_explains_its_mobility(name, counted, exact):
    result = run("check", kl.gallery.entry(name).path)
    assert result.exit_code == 0, result.output
    assert counted in result.output and exact in result.output
    assert "analyse this" in result.output and result.output.rstrip().endswith("ok")
    mob = kl.structure.mobility(kl.gallery.load(name).mechanism)
    assert mob.exact == len(kl.gallery.load(name).mechanism.inputs)


def test_spatial_check_refuses_inputs_that_miss_the_mobility(tmp_path):
    text = kl.gallery.entry("sarrus").path.read_text()
    path = tmp_path / "sarrus.toml"
    path.write_text(text[:text.index("[[inputs]]")])
    result = run("check", path)
    assert result.exit_code == 2
    assert ("sarrus.toml: inputs: expected 1 input(s), one per degree of freedom (the exact "
            "mobility at the sketch), got 0; add [[inputs]] tables") in result.output


def test_sarrus_plate_rises_straight_by_the_closure_of_both_legs():
    m, at, axis = spatial_model("sarrus")
    l1, l2 = np.linalg.norm(at["A2"] - at["A1"]), np.linalg.norm(at["A3"] - at["A2"])
    m1, m2 = np.linalg.norm(at["B2"] - at["B1"]), np.linalg.norm(at["B3"] - at["B2"])
    lo, hi = m.inputs[0].range
    theta = np.linspace(lo, hi, 361)
    p = kl.spatial.sarrus(theta, (l1, l2), (m1, m2))
    sketch_theta = np.arctan2(*(at["A2"] - at["A1"])[[2, 0]])      # the lower link at 30 deg
    sketch = kl.spatial.sarrus(sketch_theta, (l1, l2), (m1, m2))
    assert float(sketch.height) == pytest.approx(at["A3"][2] - at["A1"][2], rel=1e-12)
    turned = p.angles - sketch.angles                # each hinge turned from the sketch
    size = l1 + l2
    plates = []
    for leg, hinges in enumerate([("hinge_a1", "hinge_a2", "hinge_a3"),
                                  ("hinge_b1", "hinge_b2", "hinge_b3")]):
        T = np.tile(np.eye(4), (len(theta), 1, 1))
        for k, j in enumerate(hinges):
            T = T @ about(axis[j], turned[:, leg, k], at[m.joint(j).point])
        plates.append(T)
    # loop closure: the plate reached through either leg is one pose, to 1e-10
    np.testing.assert_allclose(plates[0], plates[1], rtol=0, atol=1e-10 * size)
    T = plates[0]
    np.testing.assert_allclose(T[:, :3, :3], np.broadcast_to(np.eye(3), T[:, :3, :3].shape),
                               rtol=0, atol=1e-10)
    centre = T[:, :3, :3] @ at["T"] + T[:, :3, 3]
    np.testing.assert_allclose(centre[:, :2] - at["T"][:2], 0.0, rtol=0, atol=1e-10 * size)
    np.testing.assert_allclose(centre[:, 2] - at["T"][2], p.height - sketch.height, rtol=0,
                               atol=1e-10 * size)
    assert np.ptp(centre[:, 2]) > 1.5 * l1            # a stroke, straight up


def test_bennett_closes_over_a_turn_from_the_file_geometry():
    m, at, axis = spatial_model("bennett")
    a, b = np.linalg.norm(at["J2"] - at["J1"]), np.linalg.norm(at["J1"] - at["J4"])
    alpha, beta = angle_between(axis["j1"], axis["j2"]), angle_between(axis["j2"], axis["j3"])
    assert (a / MM, b / MM) == pytest.approx((100, 100 * np.sqrt(3)), rel=1e-12)
    assert np.degrees([alpha, beta]) == pytest.approx([30, 60], rel=1e-12)
    assert a / np.sin(alpha) == pytest.approx(b / np.sin(beta), rel=1e-12)     # Bennett's condition
    # the file's sketch is the closed form's at theta1 = 90 deg
    points, axes = kl.spatial.bennett(np.pi / 2, a, b, alpha, beta).joints()
    for k in range(4):
        np.testing.assert_allclose(points[k], at[f"J{k + 1}"], rtol=0, atol=1e-12 * b)
        np.testing.assert_allclose(axes[k], axis[f"j{k + 1}"], rtol=0, atol=1e-12)
    # over a turn: the product of the four Denavit-Hartenberg transforms is the identity
    p = kl.spatial.bennett(np.linspace(0, 2 * np.pi, 361), a, b, alpha, beta)
    T = p.transforms()
    loop = T[:, 0] @ T[:, 1] @ T[:, 2] @ T[:, 3]
    np.testing.assert_allclose(loop[:, :3, :3], np.broadcast_to(np.eye(3), (361, 3, 3)),
                               rtol=0, atol=1e-10)
    np.testing.assert_allclose(loop[:, :3, 3], 0.0, rtol=0, atol=1e-10 * b)
    assert np.abs(np.diff(p.theta[:, 1])).max() < 0.05      # the output turns smoothly
    # and the links stay rigid: consecutive joints a, b, a, b apart, axes at alpha, beta
    points, axes = p.joints()
    for k, (length, twist) in enumerate(zip((a, b, a, b), (alpha, beta, alpha, beta))):
        nxt = (k + 1) % 4
        np.testing.assert_allclose(np.linalg.norm(points[:, nxt] - points[:, k], axis=1),
                                   length, rtol=1e-12)
        np.testing.assert_allclose(np.einsum("ni,ni->n", axes[:, k], axes[:, nxt]), np.cos(twist),
                                   rtol=0, atol=1e-12)


def test_cardan_output_and_speed_ratio_over_a_turn():
    m, at, axis = spatial_model("cardan")
    shaft_in, shaft_out = axis["input_bearing"], axis["output_bearing"]
    beta = angle_between(shaft_in, shaft_out)
    assert np.degrees(beta) == pytest.approx(30, rel=1e-12)
    phi1 = np.linspace(0, 2 * np.pi, 721)
    motion = kl.spatial.cardan_motion(phi1, beta, phi1_dot=10.0)
    phi2 = motion.phi2
    # the closed form, with both angles measured from the input yoke's pin in the plane of
    # the shafts (a quarter turn from the file's sketch): tan(out) = tan(in) / cos(beta),
    # cross-multiplied so that it holds at the quarter turns too
    psi1, psi2 = phi1 - np.pi / 2, phi2 - np.pi / 2
    assert np.abs(np.sin(psi2) * np.cos(psi1) * np.cos(beta)
                  - np.sin(psi1) * np.cos(psi2)).max() < 1e-12
    # the speed ratio: its closed form, and a central difference of the output angle
    ratio = np.cos(beta) / (1 - np.sin(beta) ** 2 * np.sin(phi1) ** 2)
    np.testing.assert_allclose(motion.ratio, ratio, rtol=1e-12)
    np.testing.assert_allclose(motion.phi2_dot, 10.0 * ratio, rtol=1e-12)
    h = 1e-5
    output = kl.spatial.cardan_output
    fd = (output(phi1 + h, beta) - output(phi1 - h, beta)) / (2 * h)
    np.testing.assert_allclose(fd, ratio, rtol=0, atol=1e-8)
    assert motion.ratio.min() == pytest.approx(np.cos(beta), rel=1e-12)
    assert motion.ratio.max() == pytest.approx(1 / np.cos(beta), rel=1e-9)
    # the file's own joints: the yokes' pins, each turned with its shaft, stay at right
    # angles on the cross (the loop closes)
    pin_in = about(shaft_in, phi1)[:, :3, :3] @ (at["Y1"] - at["O"])
    pin_out = about(shaft_out, phi2)[:, :3, :3] @ (at["Y2"] - at["O"])
    assert np.abs(np.einsum("ni,ni->n", pin_in, pin_out)).max() < 1e-12 * 0.025**2


def test_double_cardan_output_equals_its_input():
    m, at, axis = spatial_model("double_cardan")
    shaft_in, shaft_out = axis["input_bearing"], axis["output_bearing"]
    middle = (at["OB"] - at["OA"]) / np.linalg.norm(at["OB"] - at["OA"])
    beta1, beta2 = angle_between(shaft_in, middle), angle_between(middle, shaft_out)
    phase = angle_between(axis["middle_yoke_a"], axis["middle_yoke_b"])     # yokes in phase
    plane = angle_between(np.cross(shaft_in, middle), np.cross(shaft_out, middle))
    assert np.degrees([beta1, beta2]) == pytest.approx([30, 30], rel=1e-12)
    assert phase == 0.0 and plane == pytest.approx(0.0, abs=1e-12)
    phi1 = np.linspace(0, 2 * np.pi, 721)
    motion = kl.spatial.double_cardan(phi1, beta1, beta2, arrangement="Z", phase=phase,
                                      plane_angle=plane, phi1_dot=10.0)
    np.testing.assert_allclose(motion.output_axis, shaft_out, rtol=0, atol=1e-12)
    assert motion.uniform
    np.testing.assert_allclose(motion.phi3, phi1, rtol=0, atol=1e-12)
    np.testing.assert_allclose(motion.ratio, 1.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(motion.phi3_dot, 10.0, rtol=0, atol=1e-11)
    # while the middle shaft's speed fluctuates (a single Cardan's ratio)
    assert np.ptp(np.gradient(motion.phi2, phi1)) > 0.2
    # the file's own joints: each cross keeps its two pins at right angles
    turn = lambda shaft, angle, pin: about(shaft, angle)[:, :3, :3] @ pin
    pins = [turn(shaft_in, phi1, at["Y1"] - at["OA"]),
            turn(middle, motion.phi2, at["Y2"] - at["OA"]),
            turn(middle, motion.phi2, at["Y3"] - at["OB"]),
            turn(shaft_out, motion.phi3, at["Y4"] - at["OB"])]
    for u, v in (pins[:2], pins[2:]):
        assert np.abs(np.einsum("ni,ni->n", u, v)).max() < 1e-12 * 0.025**2


def test_stewart_platform_legs_by_inverse_kinematics():
    from scipy.spatial.transform import Rotation
    m, at, axis = spatial_model("stewart_platform")
    base = np.array([at[f"B{k}"] for k in range(1, 7)])
    top = np.array([at[f"T{k}"] for k in range(1, 7)])
    centre = top.mean(axis=0)
    platform = top - centre                       # the platform's joints in its own frame
    # at the sketch: the file's legs, and each leg's slide (its input) is its length
    sketch = kl.spatial.stewart_leg_lengths(base, platform, centre, Rotation.identity())
    np.testing.assert_allclose(sketch, np.linalg.norm(top - base, axis=1), rtol=1e-12)
    for k in range(6):
        joint = m.joint(f"leg{k + 1}")
        assert joint.point == f"T{k + 1}" and m.link(joint.links[0]).points[0] == f"B{k + 1}"
        assert axis[f"leg{k + 1}"] @ (top[k] - base[k]) == pytest.approx(sketch[k], rel=1e-12)
    # over a cycle of heave, surge, roll, pitch and yaw
    t = np.linspace(0, 2 * np.pi, 181)
    position = centre + np.c_[0.05 * np.sin(t), np.zeros_like(t), 0.08 * np.sin(2 * t)]
    rotation = Rotation.from_euler("xyz", np.c_[0.1 * np.sin(t), 0.08 * np.cos(t),
                                                0.15 * np.sin(t)])
    lengths = kl.spatial.stewart_leg_lengths(base, platform, position, rotation)
    assert lengths.shape == (181, 6)
    # the legs' geometry, by the homogeneous transforms: |T p - a| with the platform's
    # joints carried from the file's sketch
    moved = np.einsum("nij,kj->nki", rotation.as_matrix(), top - centre) + position[:, None, :]
    np.testing.assert_allclose(lengths, np.linalg.norm(moved - base, axis=2), rtol=1e-12)
    for k, leg in enumerate(m.inputs):                   # within the legs' ranges
        assert leg.range[0] <= lengths[:, k].min() and lengths[:, k].max() <= leg.range[1]
    # and back: forward kinematics from the legs' lengths finds the pose again
    pose = kl.spatial.stewart_forward(base, platform, lengths, centre, Rotation.identity())
    np.testing.assert_allclose(pose.position, position, rtol=0, atol=1e-10)
    np.testing.assert_allclose(pose.rotation.as_matrix(), rotation.as_matrix(), rtol=0, atol=1e-10)
