"""Synthesis of spherical four-bars, their model files, the CLI and the animation.

Every synthesized linkage is checked by SphericalFourBar's own analysis (an independent
route from the equations the synthesis solved)."""
import csv
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.spatial.transform import Rotation

import kinelab as kl
from kinelab.cli import main
from kinelab.errors import ModelError
from kinelab.solvers import wrap_angle

ROOT = Path(__file__).parents[2]
EXAMPLE = ROOT / "examples" / "spatial" / "spherical_fourbar.toml"
SF = kl.spatial.SphericalFourBar


# -- function generation ---------------------------------------------------------------------

def test_freudenstein_constants_of_a_known_linkage():
    # K1 = sin α1 cot α2, K2 = sin α1 cot α4, K3 = (cos α3 - cos α1 cos α2 cos α4) / (s2 s4)
    a1, a2, a3, a4 = 1.2, 0.4, 1.1, 0.9
    m = SF(alpha1=a1, alpha2=a2, alpha3=a3, alpha4=a4)
    q = np.array([-0.7, 0.1, 0.9])
    K = kl.synthesis.spherical_freudenstein(q, m.analyze(q).theta4, ground=a1)
    want = [math.sin(a1) / math.tan(a2), math.sin(a1) / math.tan(a4),
            (math.cos(a3) - math.cos(a1) * math.cos(a2) * math.cos(a4))
            / (math.sin(a2) * math.sin(a4))]
    assert np.allclose(K, want, rtol=0, atol=1e-12)


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_function_exact_through_three_pairs_recovers_the_linkage(branch):
    m = SF(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9, branch=branch)
    q = np.array([-0.7, 0.1, 0.9])
    s = kl.synthesis.spherical_function(q, m.analyze(q).theta4, ground=1.2)
    assert np.allclose(s.linkage.arcs, m.arcs, rtol=0, atol=1e-11)
    assert s.linkage.branch == branch and s.fit == "exact"
    assert s.max_error < 1e-11


def test_function_exact_through_arbitrary_pairs_checked_by_analysis():
    t2 = np.radians([20.0, 50.0, 80.0])
    t4 = np.radians([100.0, 115.0, 135.0])
    s = kl.synthesis.spherical_function(t2, t4, ground=np.radians(60.0))
    # independent: move the linkage with its analysis and compare the rocker's angle
    got = s.linkage.analyze(t2).theta4
    assert np.abs(wrap_angle(got - t4)).max() < 1e-10
    assert np.allclose(s.structural_error, wrap_angle(got - t4), rtol=0, atol=1e-15)
    # the same in degrees
    d = kl.synthesis.spherical_function([20.0, 50.0, 80.0], [100.0, 115.0, 135.0], ground=60.0,
                                        degrees=True)
    assert np.allclose(d.linkage.arcs, s.linkage.arcs, rtol=0, atol=1e-12)


def test_function_least_squares_against_the_normal_equations():
    a1 = np.radians(50.0)
    t2 = np.radians(np.linspace(10.0, 100.0, 7))
    t4 = np.radians(90.0 + 0.5 * np.linspace(10.0, 100.0, 7) + 0.002 * np.linspace(10, 100, 7) ** 2)
    s = kl.synthesis.spherical_function(t2, t4, ground=a1)
    M = np.column_stack([np.cos(t4), -np.cos(t2), np.ones_like(t2)])
    r = math.cos(a1) * np.cos(t2) * np.cos(t4) + np.sin(t2) * np.sin(t4)
    K = np.linalg.solve(M.T @ M, M.T @ r)
    assert s.fit == "least squares"
    assert np.allclose(s.K, K, rtol=1e-10, atol=1e-12)
    assert np.allclose(M.T @ s.residual, 0.0, atol=1e-12)      # residual ⟂ columns
    # the structural error is the analysis's, not the equation's residual
    got = s.linkage.analyze(t2, unreachable="mask").theta4
    assert np.allclose(s.structural_error, wrap_angle(got - t4), rtol=0, atol=1e-15)
    assert not np.allclose(s.structural_error, s.residual, atol=1e-9)
    assert 0.0 < s.max_error < 0.05


def test_hooke_joint_by_function_generation():
    # the Hooke (Cardan) joint is the spherical four-bar of arcs (β, 90°, 90°, 90°): three
    # pairs of its law give it back, and the linkage then follows the law everywhere
    beta = np.radians(25.0)
    t2 = np.radians([15.0, 45.0, 75.0])
    law = kl.spatial.cardan_output(t2, beta)       # tan φ2 = tan φ1 cos β, φ from the pins
    # SphericalFourBar's θ2 is the Cardan φ1 (pin angle), its θ4 - π/2 the output pin's:
    # tan(θ4 - π/2) = tan θ2 / cos β, the inverse law (the input here drives the other shaft)
    t4 = np.arctan(np.tan(t2) / np.cos(beta)) + np.pi / 2
    s = kl.synthesis.spherical_function(t2, t4, ground=beta)
    assert np.allclose(s.linkage.arcs, [beta, np.pi / 2, np.pi / 2, np.pi / 2], atol=1e-10)
    q = np.radians(np.linspace(-80.0, 80.0, 17))
    sol = s.linkage.analyze(q, 1.0)
    assert np.allclose(np.tan(sol.theta4 - np.pi / 2), np.tan(q) / np.cos(beta), atol=1e-10)
    # its velocity ratio is the Cardan joint's, the input pin a quarter turn on
    assert np.allclose(sol.omega4, kl.spatial.cardan_velocity_ratio(q + np.pi / 2, beta),
                       rtol=0, atol=1e-10)
    assert np.allclose(np.tan(law), np.tan(t2) * np.cos(beta), atol=1e-12)


def test_function_refusals():
    with pytest.raises(ModelError, match=r"input_angles, output_angles: expected two arrays"):
        kl.synthesis.spherical_function([0.1, 0.2], [0.3, 0.4])
    with pytest.raises(ModelError, match=r"ground: expected the ground arc"):
        kl.synthesis.spherical_function([0.1, 0.2, 0.3], [0.3, 0.4, 0.5], ground=4.0)
    with pytest.raises(ModelError, match=r"do not fix the spherical Freudenstein constants"):
        kl.synthesis.spherical_function([0.1, 0.1, 0.1], [0.3, 0.3, 0.3])


# -- motion generation -----------------------------------------------------------------------

def _orientations(m, q):
    """Coupler orientations of a linkage, turned into an arbitrary ground frame."""
    frame = Rotation.from_euler("zyx", [0.4, -0.8, 1.3]).as_matrix()
    sol = m.analyze(q)
    return frame, np.einsum("ij,njk->nik", frame, sol.coupler), sol


def test_three_orientations_recovers_a_known_linkage():
    m = SF(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9, branch="crossed")
    frame, R, sol = _orientations(m, [0.0, 0.5, 1.0])
    s = kl.synthesis.spherical_three_orientations(R, [frame @ sol.u_O2[0], frame @ sol.u_O4[0]])
    assert np.allclose(s.linkage.arcs, m.arcs, atol=1e-12) and s.linkage.branch == "crossed"
    assert s.reached and s.rotation_error.max() <= 1e-9


def test_three_orientations_with_chosen_fixed_axes():
    R = Rotation.from_rotvec([[0.0, 0.0, 0.0], [0.10, 0.25, 0.05], [0.15, 0.5, 0.2]])
    fixed = [[0.0, 0.0, 1.0], [0.8, 0.2, 0.6]]
    s = kl.synthesis.spherical_three_orientations(R, fixed)
    # independent: the moving axes keep their arcs from the fixed ones in every orientation
    M = R.as_matrix()
    for u, b in zip(s.fixed_axes, s.moving_axes):
        arcs = np.einsum("i,nij,j->n", u, M, b)
        assert np.ptp(arcs) < 1e-13
    # and SphericalFourBar's analysis carries the coupler through them
    assert s.reached, s.rotation_error
    assert s.rotation_error.max() <= 1e-9
    # rotating the task and its axes together changes nothing
    turn = Rotation.from_euler("xyz", [0.3, 0.2, -0.5])
    t = kl.synthesis.spherical_three_orientations(turn * R, turn.apply(fixed))
    assert np.allclose(t.linkage.arcs, s.linkage.arcs, atol=1e-12)


def test_three_orientations_refusals():
    R = Rotation.from_rotvec([[0.0, 0.0, 0.0], [0.1, 0.2, 0.0], [0.2, 0.3, 0.1]]).as_matrix()
    with pytest.raises(ModelError, match=r"rotations: expected 3 orientations, got 2"):
        kl.synthesis.spherical_three_orientations(R[:2], [[0, 0, 1], [1, 0, 0]])
    bad = R.copy()
    bad[1] *= 2.0
    with pytest.raises(ModelError, match=r"rotations\[1\]: expected a rotation matrix"):
        kl.synthesis.spherical_three_orientations(bad, [[0, 0, 1], [1, 0, 0]])
    with pytest.raises(ModelError, match=r"fixed_axes: expected two directions"):
        kl.synthesis.spherical_three_orientations(R, [0, 0, 1])
    with pytest.raises(ModelError, match=r"fixed_axes\[1\]: expected a direction"):
        kl.synthesis.spherical_three_orientations(R, [[0, 0, 1], [0, 0, 0]])


def test_four_orientations_centre_axes_and_linkages():
    m = SF(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9)
    frame, R, sol = _orientations(m, [0.0, 0.3, 0.6, 0.9])
    curve = kl.synthesis.spherical_center_axes(R, samples=361)
    D = R[1:] - R[0]
    dets = np.linalg.det(np.einsum("kji,mj->mki", D, curve.center))
    assert np.abs(dets).max() < 1e-12 and curve.residual.max() < 1e-12
    # the known linkage's fixed axes lie on the curve
    for u in (frame @ sol.u_O2[0], frame @ sol.u_O4[0]):
        assert np.abs(np.linalg.det(np.einsum("kji,j->ki", D, u))) < 1e-12
        assert np.abs(curve.center @ u).max() > math.cos(0.02)
    found = kl.synthesis.spherical_four_orientations(R, samples=361)
    assert len(found) >= 3
    for s in found:
        assert s.reached and s.rotation_error.max() <= 1e-9
    # snapped near the known axes: close to the known linkage
    near = kl.synthesis.spherical_four_orientations(
        R, [frame @ sol.u_O2[0], frame @ sol.u_O4[0]], samples=1441)
    assert len(near) == 1 and np.allclose(near[0].linkage.arcs, m.arcs, atol=0.02)


# -- model files and the command line --------------------------------------------------------

def test_example_reads_as_its_arcs():
    m = SF.from_mechanism(kl.load(EXAMPLE))
    assert np.allclose(np.degrees(m.arcs), [70.0, 20.0, 60.0, 45.0], atol=1e-12)
    assert m.branch == "open" and m.grashof().kind == "crank-rocker"


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_model_file_round_trip(tmp_path, branch):
    text = EXAMPLE.read_text().replace('branch = "open"', f'branch = "{branch}"')
    src = tmp_path / "sph.toml"
    src.write_text(text)
    mf = kl.io.ModelFile.read(src)
    again = kl.io.ModelFile.from_toml(mf.to_toml())
    a, b = SF.from_mechanism(mf.mechanism), SF.from_mechanism(again.mechanism)
    assert np.allclose(a.arcs, b.arcs, atol=1e-12) and a.branch == b.branch == branch
    assert again.mechanism.inputs[0].range == pytest.approx((0.0, 2 * math.pi))


BAD = [
    ("coupler = 60", "coupler = 200",
     r"spherical.coupler: expected an arc in \(0, 180\) deg .*got 200"),
    ('branch = "open"', 'branch = "cross"',
     r"spherical.branch: expected one of 'open', 'crossed', got 'cross'"),
    ("coupler = 60\n", "", r"spherical: missing.*coupler|spherical.coupler"),
    ("rocker = 45", "rocker = 45\nlength = 3", r"spherical.length"),
    ('space = "spherical"', 'space = "planar"', r"spherical: a \[spherical\] table needs "
                                                r"space = \"spherical\""),
    ("radius = 50", "radius = -5", r"spherical.radius: expected a positive length"),
    ('joint = "jO2"', 'joint = "jA"', r"inputs: a spherical four-bar has one input"),
]


@pytest.mark.parametrize("old, new, message", BAD)
def test_model_file_bad_fields(tmp_path, old, new, message):
    text = EXAMPLE.read_text()
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(ModelError, match=message) as info:
        kl.load(path)
    assert "bad.toml" in str(info.value)


def test_cli_check_example():
    r = CliRunner().invoke(main, ["check", str(EXAMPLE)])
    assert r.exit_code == 0, r.output
    assert "Grashof on the sphere: crank-rocker" in r.output
    assert "input reaches: [-180, 180] deg" in r.output
    assert "rocker stops (crank and coupler in line): θ2 = -137.468, θ4 = 142.084" in r.output
    assert r.output.rstrip().endswith("ok")


def test_cli_analyze_example(tmp_path):
    r = CliRunner().invoke(main, ["analyze", str(EXAMPLE), "--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    path = tmp_path / "spherical_fourbar.csv"
    rows = list(csv.DictReader(path.open()))
    assert len(rows) == 73
    m = SF.from_mechanism(kl.load(EXAMPLE))
    q = np.radians([float(x["crank.angle[deg]"]) for x in rows])
    sol = m.analyze(q, np.radians(60.0))
    for column, values in (("rocker.angle[deg]", np.degrees(sol.theta4)),
                           ("rocker.K[deg/deg]", sol.K4),
                           ("coupler.K[deg/deg]", sol.K3),
                           ("rocker.omega[deg/s]", np.degrees(sol.omega4))):
        assert np.allclose([float(x[column]) for x in rows], values, rtol=1e-12, atol=1e-12)
    # L in deg/deg²: the SI value (1/rad) times π/180
    assert np.allclose([float(x["rocker.L[deg/deg^2]"]) for x in rows],
                       sol.L4 * np.pi / 180, rtol=1e-12, atol=1e-15)


def test_cli_analyze_refuses_a_range_out_of_reach(tmp_path):
    text = EXAMPLE.read_text().replace("crank = 20", "crank = 40").replace(
        "ground = 70", "ground = 30")
    path = tmp_path / "rocker.toml"
    path.write_text(text)
    r = CliRunner().invoke(main, ["analyze", str(path), "--out", str(tmp_path)])
    assert r.exit_code != 0
    assert "inputs[0].range" in r.output and "narrow the range" in r.output
    assert not list(tmp_path.glob("*.csv"))


# -- animation -------------------------------------------------------------------------------

def test_animation_gif(tmp_path):
    from PIL import Image
    m = kl.mechanisms.spherical_fourbar(70, 20, 60, 45, degrees=True)
    path = kl.plot.animate_spherical_fourbar(m, tmp_path / "s.gif", frames=6, size=2.5)
    with Image.open(path) as im:
        assert im.n_frames == 6
    rocker = SF(alpha1=0.5, alpha2=0.7, alpha3=0.4, alpha4=0.5)    # limits: there and back
    assert kl.plot.animate_spherical_fourbar(rocker, tmp_path / "r.gif", frames=6,
                                             size=2.5).exists()
    with pytest.raises(ModelError, match=r"path: expected a name ending in .gif or .mp4"):
        kl.plot.animate_spherical_fourbar(m, tmp_path / "s.png")
