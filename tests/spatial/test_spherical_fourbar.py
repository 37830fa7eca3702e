"""Spherical four-bar: loop closure of the joint axes, rates against finite differences and
against the planar four-bar (a small linkage on a large sphere) and the Cardan joint,
Grashof's criterion against the exact rotatability of each link, limit positions, masks,
and models."""
import itertools
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
import kinelab.spatial as sp
from kinelab.errors import AssemblyError, ModelError
from kinelab.model import Input, Joint, Link, Mechanism, Point

# (alpha1, alpha2, alpha3, alpha4): a crank-rocker, a double-crank, a rocker-crank with arcs
# beyond π/2 (two reachable intervals), a triple-rocker
GEOMETRIES = [(1.2, 0.4, 1.1, 0.9), (0.3, 0.8, 0.9, 0.7), (2.3, 1.9, 1.3, 0.6),
              (1.0, 0.8, 0.5, 0.6)]
TWO_INTERVALS = (1.0, 0.9, 0.8, 0.3)
BRANCHES = ("open", "crossed")
THETA2 = np.linspace(-np.pi, np.pi, 721)


def fourbar(arcs, **kw):
    return sp.SphericalFourBar(**dict(zip(("alpha1", "alpha2", "alpha3", "alpha4"), arcs)), **kw)


def dots(a, b):
    return np.einsum("...i,...i->...", a, b)


def wrapped(x):
    return np.angle(np.exp(1j * x))


@pytest.mark.parametrize("arcs", GEOMETRIES)
@pytest.mark.parametrize("branch", BRANCHES)
def test_loop_closure(arcs, branch):
    m = fourbar(arcs)
    sol = m.analyze(THETA2, branch=branch, unreachable="mask")
    ok = sol.assembled
    assert ok.sum() > 100
    a1, a2, a3, a4 = arcs
    u_O2, u_A, u_B, u_O4 = sol.u_O2[ok], sol.u_A[ok], sol.u_B[ok], sol.u_O4[ok]
    for u in (u_O2, u_A, u_B, u_O4):
        assert np.abs(np.linalg.norm(u, axis=-1) - 1.0).max() < 1e-15 * 4
    # exact algebra of unit vectors: 1e-12
    assert np.abs(dots(u_A, u_B) - math.cos(a3)).max() < 1e-12
    assert np.abs(dots(u_O2, u_O4) - math.cos(a1)).max() < 1e-15
    assert np.abs(dots(u_O2, u_A) - math.cos(a2)).max() < 1e-15
    assert np.abs(dots(u_B, u_O4) - math.cos(a4)).max() < 1e-15
    # the assembly: B to the left of the great circle A -> O4 on "open"
    side = np.linalg.det(np.stack([u_A, u_O4, u_B], axis=-1))
    assert (np.sign(side) == (1 if branch == "open" else -1)).all()
    # the coupler frame: a rotation, z on u_A, and u_B at α3 along its x-z plane
    R = sol.coupler[ok]
    assert np.abs(np.swapaxes(R, -1, -2) @ R - np.eye(3)).max() < 1e-14
    assert np.abs(np.linalg.det(R) - 1.0).max() < 1e-14
    assert np.abs(R[..., 2] - u_A).max() == 0.0
    local = np.einsum("nji,nj->ni", R, u_B)
    assert np.abs(local - [math.sin(a3), 0.0, math.cos(a3)]).max() < 1e-12
    # θ3 from the frame: Rot(z, θ2) Rot(y, α2) Rot(z, θ3 - θ2)
    t2, t3 = sol.theta2[ok], sol.theta3[ok]
    rot = sp.rotation("z", t2) * sp.rotation("y", a2) * sp.rotation("z", t3 - t2)
    assert np.abs(rot.as_matrix() - R).max() < 1e-12


@pytest.mark.parametrize("arcs", GEOMETRIES)
@pytest.mark.parametrize("branch", BRANCHES)
def test_K_L_against_finite_differences(arcs, branch):
    m = fourbar(arcs)
    t = np.linspace(-3.0, 3.0, 241)
    h = 1e-5
    s0 = m.analyze(t, branch=branch, unreachable="mask")
    sp_, sm = (m.analyze(t + d, branch=branch, unreachable="mask") for d in (h, -h))
    # away from the input's limit positions, where K grows without bound
    ok = s0.assembled & sp_.assembled & sm.assembled & (np.abs(s0.K4) < 20) & (np.abs(s0.K3) < 20)
    assert ok.sum() > 60
    for k, L, angle in (("K4", "L4", "theta4"), ("K3", "L3", "theta3")):
        K0, L0 = getattr(s0, k)[ok], getattr(s0, L)[ok]
        fd_K = wrapped(getattr(sp_, angle) - getattr(sm, angle))[ok] / (2 * h)
        fd_L = (getattr(sp_, k) - getattr(sm, k))[ok] / (2 * h)
        # central differences: error ~ h² |θ'''| ~ 1e-10, relative to max(|K|, 1)
        assert np.abs(fd_K - K0).max() / max(1.0, np.abs(K0).max()) < 1e-7
        assert np.abs(fd_L - L0).max() / max(1.0, np.abs(L0).max()) < 1e-5
    # rates: ω = K θ̇2, α = K θ̈2 + L θ̇2²
    sol = m.analyze(t, 3.0, -2.0, branch=branch, unreachable="mask")
    a = sol.assembled
    assert np.abs(sol.omega4[a] - 3.0 * sol.K4[a]).max() == 0.0
    assert np.allclose(sol.alpha4[a], -2.0 * sol.K4[a] + 9.0 * sol.L4[a], rtol=1e-15, atol=0)


@pytest.mark.parametrize("branch", BRANCHES)
@pytest.mark.parametrize("lengths", [(3.0, 1.0, 3.0, 2.5), (1.0, 2.0, 2.5, 2.2)])
def test_planar_limit(branch, lengths):
    """Arcs ε × lengths: the spherical four-bar tends to the planar one, error O(ε²)."""
    fb = kl.mechanisms.fourbar(ground=lengths[0], crank=lengths[1], coupler=lengths[2],
                               rocker=lengths[3], branch=branch)
    q = np.radians(np.arange(0.0, 360.0, 15.0))
    planar = kl.analyze(fb, q=q, qd=1.0, unreachable="mask", at_singular="flag")
    ok = planar.assembled & ~planar.singular
    errors = []
    for eps in (1e-2, 1e-3):
        s = fourbar(np.array(lengths) * eps).analyze(q, branch=branch, unreachable="mask")
        assert (s.assembled == planar.assembled).all()
        e = max(np.abs(wrapped(s.theta4 - planar.angle("rocker"))[ok]).max(),
                np.abs(wrapped(s.theta3 - planar.angle("coupler"))[ok]).max(),
                np.abs(s.K4 - planar.K("rocker"))[ok].max(),
                np.abs(s.K3 - planar.K("coupler"))[ok].max(),
                np.abs(s.L4 - planar.L("rocker"))[ok].max(),
                np.abs(s.L3 - planar.L("coupler"))[ok].max())
        errors.append(e)
        assert e < 10 * eps**2
    assert errors[1] < errors[0] / 50           # O(ε²): a tenth of ε, a hundredth of the error


@pytest.mark.parametrize("beta", np.radians([5.0, 30.0, 60.0]))
def test_hooke_joint_against_cardan(beta):
    """Ground arc β, the other three π/2: the Cardan joint, with θ2 = φ1 + π/2 (θ2 is measured
    from the plane of the shafts, φ1 from its normal) and on "crossed" θ4 = φ2 + π."""
    hooke = fourbar((beta, np.pi / 2, np.pi / 2, np.pi / 2))
    assert hooke.grashof().kind == "double-crank"
    t = np.linspace(-np.pi, np.pi, 73)
    phi1 = t - np.pi / 2
    ref = sp.cardan_motion(phi1, beta, phi1_dot=1.0)
    for branch, offset in (("crossed", np.pi), ("open", 0.0)):
        sol = hooke.analyze(t, theta2_dot=1.0, branch=branch)
        assert sol.assembled.all() and not sol.singular.any()
        assert np.abs(wrapped(sol.theta4 - ref.phi2 - offset)).max() < 1e-12
        assert np.abs(sol.K4 - sp.cardan_velocity_ratio(phi1, beta)).max() < 1e-12
        assert np.abs(sol.L4 - ref.phi2_ddot).max() < 1e-12
    sol = hooke.analyze(t, branch="crossed")
    inside = np.abs(np.cos(t)) > 1e-3
    assert np.abs(np.tan(sol.theta4 - np.pi / 2) - np.tan(t) / np.cos(beta))[inside].max() < 1e-9


@pytest.mark.parametrize("arcs, kind", [
    ((0.5, 0.2, 0.5, 0.4), "crank-rocker"),
    ((0.2, 0.4, 0.5, 0.5), "double-crank"),
    ((0.5, 0.4, 0.5, 0.2), "rocker-crank"),
    ((0.5, 0.4, 0.2, 0.5), "double-rocker"),
    ((0.5, 0.7, 0.4, 0.5), "triple-rocker"),
    ((0.5, 0.6, 0.4, 0.5), "change-point"),
    ((np.pi / 6, np.pi / 2, np.pi / 2, np.pi / 2), "double-crank"),       # Hooke joint
    # the crank-rocker with the axis O2 reversed (ground and crank supplemented)
    ((np.pi - 0.5, np.pi - 0.2, 0.5, 0.4), "crank-rocker"),
    # ... and with O4 reversed (ground and rocker supplemented)
    ((np.pi - 0.5, 0.2, 0.5, np.pi - 0.4), "crank-rocker"),
])
def test_grashof_known_cases(arcs, kind):
    g = fourbar(arcs).grashof()
    assert g.kind == kind
    assert g.grashof == (kind != "triple-rocker")
    assert all(x <= np.pi / 2 for x in g.reduced)


def test_grashof_reduction_names_reversed_axes():
    g = fourbar((np.pi - 0.5, np.pi - 0.2, 0.5, 0.4)).grashof()
    assert g.reversed_axes == ("O2",)
    assert np.allclose(sorted(g.reduced), sorted((0.5, 0.2, 0.5, 0.4)), rtol=0, atol=1e-15)


arc = st.floats(0.02, np.pi - 0.02)


@given(arc, arc, arc, arc)
def test_grashof_sum_rule_against_sweep(a1, a2, a3, a4):
    """The sum rule on the reduced arcs, the exact condition for each link, and the sweep
    agree: the crank turns fully exactly where every input closes the loop."""
    m = fourbar((a1, a2, a3, a4))
    g = m.grashof(rtol=0.0)
    if abs(g.margin) < 1e-6:
        return                                        # a change point, within rounding
    sweep = m.positions(THETA2).assembled
    assert g.crank_rotates == bool(sweep.all())
    assert g.crank_rotates == (m.reachable_inputs() == [(-np.pi, np.pi)])
    rocker = fourbar((a1, a4, a3, a2))                # the inversion driven by the rocker
    assert g.rocker_rotates == bool(rocker.positions(THETA2).assembled.all())
    # Grashof: some link turns fully relative to a neighbour (an inversion of the chain)
    turns = any(fourbar(c).positions(THETA2).assembled.all()
                for c in ((a1, a2, a3, a4), (a2, a3, a4, a1), (a3, a4, a1, a2),
                          (a4, a1, a2, a3), (a1, a4, a3, a2), (a2, a1, a4, a3),
                          (a3, a2, a1, a4), (a4, a3, a2, a1)))
    assert g.grashof == turns


@pytest.mark.parametrize("arcs", [(0.5, 0.2, 0.5, 0.4), (1.2, 0.4, 1.1, 0.9),
                                  (2.0, 2.5, 1.0, 0.9), (1.0, 0.8, 0.5, 0.6)])
@pytest.mark.parametrize("branch", BRANCHES)
def test_output_limits(arcs, branch):
    m = fourbar(arcs)
    limits = m.output_limits(branch)
    assert len(limits) >= 1
    t2 = np.array([t for t, _ in limits])
    sol = m.analyze(t2, branch=branch)
    assert np.abs(sol.K4).max() < 1e-9                        # the rocker stands still
    assert np.abs(wrapped(sol.theta4 - [t for _, t in limits])).max() < 1e-12
    # O2, A, B on one great circle
    assert np.abs(np.linalg.det(np.stack([sol.u_O2, sol.u_A, sol.u_B], -1))).max() < 1e-12
    # an extreme of θ4: both neighbours on one side
    for t in t2:
        near = m.analyze(t + np.array([-1e-4, 0.0, 1e-4]), branch=branch).theta4
        d = wrapped(near[[0, 2]] - near[1])
        assert d[0] * d[1] > 0


def test_crank_rocker_output_limits_are_the_planar_extremes():
    m = fourbar((0.5, 0.2, 0.5, 0.4))
    t = np.linspace(-np.pi, np.pi, 200001)
    theta4 = m.analyze(t).theta4
    limits = [t4 for _, t4 in m.output_limits()]
    assert min(limits) == pytest.approx(theta4.min(), abs=1e-9)
    assert max(limits) == pytest.approx(theta4.max(), abs=1e-9)


@pytest.mark.parametrize("arcs", [(0.5, 0.7, 0.4, 0.5), (1.0, 0.8, 0.5, 0.6),
                                  (2.3, 1.9, 1.3, 0.6), TWO_INTERVALS])
def test_input_limits_against_bisection(arcs):
    m = fourbar(arcs)
    limits = m.input_limits()
    assert limits
    sol = m.analyze(limits, unreachable="mask")
    assert sol.assembled.all() and sol.singular.all()
    # A, B, O4 on one great circle there
    assert np.abs(np.linalg.det(np.stack([sol.u_A, sol.u_B, sol.u_O4], -1))).max() < 1e-7
    for lim in limits:
        # bisection on the sign of the discriminant A² + B² - C², from a reachable input a
        # little inside to one a little outside
        inside = next(lim + d for d in (-1e-3, 1e-3)
                      if m.positions(lim + d).assembled and not m.positions(lim - d).assembled)

        def closes(t):
            p = m.positions(t)
            return p.A**2 + p.B**2 - p.C**2 >= 0.0
        lo, hi = inside, 2 * lim - inside
        while abs(hi - lo) > 1e-14:
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if closes(mid) else (lo, mid)
        assert abs(lo - lim) < 1e-12
        # K grows without bound towards it
        K = [abs(float(m.analyze(lim + (inside - lim) * f).K4)) for f in (1e-2, 1e-4, 1e-6)]
        assert K[0] < K[1] < K[2]


def test_reachable_inputs_two_intervals():
    m = fourbar(TWO_INTERVALS)
    (a, b), (c, d) = m.reachable_inputs()
    assert a == -d and b == -c and 0 < c < d < np.pi
    pos = m.positions(THETA2)
    expect = ((THETA2 >= c) & (THETA2 <= d)) | ((THETA2 >= a) & (THETA2 <= b))
    assert (pos.assembled == expect).all()


@pytest.mark.parametrize("branch", BRANCHES)
def test_unreachable_masked(branch):
    m = fourbar(TWO_INTERVALS)
    sol = m.analyze(THETA2, 2.0, 1.0, branch=branch, unreachable="mask")
    assert sol.assembled.dtype == bool and sol.singular.dtype == bool
    out = ~sol.assembled
    assert 0 < out.sum() < out.size
    for name in ("theta3", "theta4", "K3", "K4", "L3", "L4", "omega4", "alpha3"):
        x = getattr(sol, name)
        assert np.isnan(x[out]).all() and np.isfinite(x[sol.assembled & ~sol.singular]).all()
    assert np.isnan(sol.u_B[out]).all() and np.isfinite(sol.u_A).all()
    pos = m.positions(THETA2)
    assert (pos.assembled == sol.assembled).all()
    assert np.isnan(pos.theta4[out]).all() and np.isfinite(pos.theta4[~out]).all()


def test_unreachable_raises():
    m = fourbar(TWO_INTERVALS)
    with pytest.raises(AssemblyError, match=r"cannot close at θ2 = 0 rad .*reachable θ2 is "
                                            r"\[-\d\.\d+, -\d\.\d+\] ∪ \[\d\.\d+, \d\.\d+\]") as e:
        m.analyze([0.0, 2.0])
    assert len(e.value.reachable) == 2


def test_shapes():
    m = fourbar((1.2, 0.4, 1.1, 0.9))
    one = m.analyze(0.3)
    assert one.theta4.shape == () and one.u_B.shape == (3,) and one.coupler.shape == (3, 3)
    many = m.analyze(np.zeros(5), theta2_dot=np.arange(5.0))
    assert many.theta4.shape == (5,) and many.u_B.shape == (5, 3)
    assert many.coupler.shape == (5, 3, 3)
    assert m.positions([0.0, 1.0, 2.0]).theta4.shape == (3, 2)


@pytest.mark.parametrize("kw, message", [
    (dict(alpha3=3.5), r"alpha3: expected an arc in \(0, π\) rad .*got 3\.5"),
    (dict(alpha1=0.0), r"alpha1: expected an arc in \(0, π\) rad"),
    (dict(alpha2=-0.1), r"alpha2: expected an arc in \(0, π\) rad"),
    (dict(alpha4=np.pi), r"alpha4: expected an arc in \(0, π\) rad"),
    (dict(alpha2="0.5"), r"alpha2: expected an arc in \(0, π\) rad \(a real number\), got '0.5'"),
    (dict(alpha2=True), r"alpha2: expected an arc .*\(a real number\)"),
    (dict(alpha4=None), r"alpha4: expected an arc .*\(a real number\)"),
    (dict(alpha1=float("nan")), r"alpha1: expected an arc in \(0, π\) rad"),
    (dict(alpha3=float("inf")), r"alpha3: expected an arc in \(0, π\) rad"),
    (dict(alpha2=[0.5]), r"alpha2: expected an arc .*\(a real number\)"),
    (dict(branch="cross"), r"branch: expected one of 'open', 'crossed', got 'cross'"),
])
def test_bad_arguments(kw, message):
    arcs = dict(alpha1=1.0, alpha2=0.5, alpha3=1.0, alpha4=0.8)
    with pytest.raises(ModelError, match=message):
        sp.SphericalFourBar(**{**arcs, **kw})


def test_every_bad_arc_named_at_once():
    with pytest.raises(ModelError) as e:
        sp.SphericalFourBar(alpha1=0.0, alpha2="x", alpha3=1.0, alpha4=4.0)
    text = str(e.value)
    assert "alpha1" in text and "alpha2" in text and "alpha4" in text and "alpha3" not in text


def test_bad_analysis_arguments():
    m = fourbar((1.2, 0.4, 1.1, 0.9))
    with pytest.raises(ModelError, match=r"theta2: expected real numbers"):
        m.analyze("1")
    with pytest.raises(ModelError, match=r"theta2: expected finite numbers"):
        m.analyze([0.0, np.nan])
    with pytest.raises(ModelError, match=r"branch: expected one of 'open', 'crossed', got 1"):
        m.analyze(0.0, branch=1)
    with pytest.raises(ModelError, match=r"unreachable: expected one of 'raise', 'mask'"):
        m.analyze(0.0, unreachable="nan")
    with pytest.raises(ModelError, match=r"rtol: expected a number from 0 to 0.01"):
        m.grashof(rtol=0.5)
    with pytest.raises(ModelError, match=r"theta2, theta2_dot, theta2_ddot: shapes"):
        m.analyze(np.zeros(3), np.zeros(2))


# -- models ----------------------------------------------------------------------------------

def model(arcs, theta2, branch, frame=None, centre=(0.0, 0.0, 0.0), radius=1.0, shift=0.0):
    """A spherical four-bar model with its axes through ``centre``, turned by ``frame``."""
    m = fourbar(arcs)
    theta4 = m.positions(theta2).theta4[0 if branch == "open" else 1]
    axes = m.axes(theta2, theta4)
    R = np.eye(3) if frame is None else frame.as_matrix()
    names = ("O2", "A", "B", "O4")
    pts = [Point(n, *(np.asarray(centre) + radius * R @ u + (shift if n == "B" else 0.0)))
           for n, u in zip(names, axes)]
    links = (Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A")),
             Link("coupler", ("A", "B")), Link("rocker", ("B", "O4")))
    pairs = (("ground", "crank"), ("crank", "coupler"), ("coupler", "rocker"),
             ("rocker", "ground"))
    joints = tuple(Joint(f"j{n}", "R", pair, point=n, axis=tuple(R @ u))
                   for n, pair, u in zip(names, pairs, axes))
    return Mechanism("spherical four-bar", tuple(pts), links, joints,
                     inputs=(Input(joint="jO2"),), space="spherical")


@pytest.mark.parametrize("branch", BRANCHES)
def test_from_mechanism(branch):
    from scipy.spatial.transform import Rotation
    arcs = (1.2, 0.4, 1.1, 0.9)
    frame = Rotation.from_euler("zyx", [0.3, -1.1, 2.0])
    m = sp.SphericalFourBar.from_mechanism(model(arcs, 0.7, branch, frame, (1.0, -2.0, 0.5), 3.0))
    assert np.allclose(m.arcs, arcs, rtol=0, atol=1e-14) and m.branch == branch
    assert kl.structure.mobility(model(arcs, 0.7, branch)).kutzbach_gruebler == 1


@pytest.mark.parametrize("length, scale", [("m", 1.0), ("mm", 1000.0)])
def test_from_model_file(tmp_path, length, scale):
    arcs = (1.2, 0.4, 1.1, 0.9)
    mech = model(arcs, 0.7, "crossed", centre=(0.2, 0.1, -0.3), radius=0.05)
    lines = ["schema = 1", 'name = "spherical four-bar"', 'space = "spherical"', "",
             "[units]", f'length = "{length}"', 'angle = "rad"', "", "[points]"]
    lines += [f"{p.name} = [{p.x * scale!r}, {p.y * scale!r}, {p.z * scale!r}]"
              for p in mech.points]
    for lk in mech.links:
        lines += ["", "[[links]]", f'name = "{lk.name}"',
                  "points = [" + ", ".join(f'"{p}"' for p in lk.points) + "]"]
        lines += ["ground = true"] if lk.ground else []
    for j in mech.joints:
        lines += ["", "[[joints]]", f'name = "{j.name}"', 'type = "R"',
                  f'links = ["{j.links[0]}", "{j.links[1]}"]', f'point = "{j.point}"',
                  "axis = [" + ", ".join(repr(float(c)) for c in j.axis) + "]"]
    lines += ["", "[[inputs]]", 'joint = "jO2"']
    path = tmp_path / "spherical.toml"
    path.write_text("\n".join(lines) + "\n")
    m = sp.SphericalFourBar.from_mechanism(kl.load(path))
    assert np.allclose(m.arcs, arcs, rtol=0, atol=1e-14) and m.branch == "crossed"


def test_from_mechanism_refuses():
    with pytest.raises(ModelError, match=r"joints: the axes of the four R joints must meet in "
                                         r"one point"):
        sp.SphericalFourBar.from_mechanism(model((1.2, 0.4, 1.1, 0.9), 0.7, "open", shift=0.1))
    planar = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    with pytest.raises(ModelError, match=r"space: expected 'spherical'"):
        sp.SphericalFourBar.from_mechanism(planar)
    with pytest.raises(ModelError, match=r"mechanism: expected a kinelab Mechanism"):
        sp.SphericalFourBar.from_mechanism("four-bar.toml")
    import dataclasses
    good = model((1.2, 0.4, 1.1, 0.9), 0.7, "open")
    joints = list(good.joints)
    joints[1] = dataclasses.replace(joints[1], axis=None)
    with pytest.raises(ModelError, match=r"joints\[1\]: a spherical four-bar's R joint needs "
                                         r"its point and its axis"):
        sp.SphericalFourBar.from_mechanism(dataclasses.replace(good, joints=tuple(joints)))
    joints[1] = dataclasses.replace(joints[1], axis=(1.0, 0.0))
    with pytest.raises(ModelError, match=r"joints\[1\].axis: expected three finite numbers"):
        sp.SphericalFourBar.from_mechanism(dataclasses.replace(good, joints=tuple(joints)))


def test_output_limits_all_assemblies_seen():
    """Each output limit of one assembly is the mirror image of one of the other's."""
    m = fourbar((1.2, 0.4, 1.1, 0.9))
    a = m.output_limits("open")
    b = m.output_limits("crossed")
    mirrored = sorted((-t2, -t4) for t2, t4 in b)
    assert np.allclose(a, mirrored, rtol=0, atol=1e-12)


def test_arcs_within_range_all_combinations():
    """Every combination of arcs near the ends of (0, π) builds and analyses without
    warnings."""
    for arcs in itertools.product((1e-6, np.pi / 2, np.pi - 1e-6), repeat=4):
        with np.errstate(all="raise"):
            m = fourbar(arcs)
            m.grashof()
            sol = m.analyze(np.linspace(-3, 3, 7), unreachable="mask")
            assert sol.assembled.dtype == bool


@given(arc, arc, arc, arc, st.floats(-np.pi, np.pi), st.sampled_from(BRANCHES))
def test_loop_closure_random_geometries(a1, a2, a3, a4, theta2, branch):
    m = fourbar((a1, a2, a3, a4))
    sol = m.analyze(theta2, branch=branch, unreachable="mask")
    if not sol.assembled:
        assert np.isnan(sol.theta4) and np.isnan(sol.K4)
        return
    assert abs(sol.u_A @ sol.u_B - math.cos(a3)) < 1e-12
    assert abs(sol.u_B @ sol.u_O4 - math.cos(a4)) < 1e-15
    if not sol.singular:
        # K4 from the triple products (the angular velocities) against -Φ_θ2 / Φ_θ4
        K4 = (np.linalg.det(np.stack([sol.u_O2, sol.u_A, sol.u_B]))
              / np.linalg.det(np.stack([sol.u_O4, sol.u_A, sol.u_B])))
        assert abs(K4 - sol.K4) <= 1e-9 * max(1.0, abs(K4))
