"""The follower's dynamics: the contact force against the follower's motion differentiated
numerically in time and against a simulation of the spring-mass follower, the critical speed
and the least preload at their thresholds, the mean shaft torque against the damping's work,
and the arguments refused."""
import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from kinelab.cams import FollowerForces, MotionProgram, Segment, follower_forces
from kinelab.errors import ModelError

d = np.radians
RPM = math.pi / 30


def dwell_program():
    return MotionProgram([Segment("rise", 0, d(90), 0.025, "cycloidal"),
                          Segment("dwell", d(90), d(180)),
                          Segment("return", d(180), d(270), 0.025, "3-4-5"),
                          Segment("dwell", d(270), d(360))])


def rise_return_program():
    return MotionProgram([Segment("rise", 0, d(150), 0.03, "modified-sine"),
                          Segment("return", d(150), d(360), 0.03, "4-5-6-7")])


CASES = {
    "undamped": dict(mass=2.0, stiffness=2000.0, preload=40.0, speed=200 * RPM),
    "damped": dict(mass=1.5, stiffness=3500.0, preload=25.0, speed=260 * RPM, damping=12.0,
                   external=1.5 * 9.81),
    "jumping": dict(mass=2.0, stiffness=2000.0, preload=40.0, speed=400 * RPM, damping=3.0),
}
def swing_program():
    # an oscillating follower's: S in rad; the same equations about the pivot (inertia,
    # torsional spring), so the same checks hold with the numbers read in those units
    return MotionProgram([Segment("rise", 0, d(120), d(20), "modified-trapezoid"),
                          Segment("dwell", d(120), d(160)),
                          Segment("return", d(160), d(360), d(20), "cycloidal")])


PROGRAMS = {"double dwell": dwell_program, "rise-return": rise_return_program,
            "swing": swing_program}


def joints(program):
    """The joints of the program and the eighths of its segments, where the piecewise laws
    change piece (their jerk may jump there)."""
    return np.array([s.start + s.beta * i / 8 for s in program.segments for i in range(8)]
                    + [2 * np.pi])


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("prog", PROGRAMS)
def test_contact_force_against_finite_differences_in_time(prog, case):
    # N = m x'' + c x' + k x + F0 + F_ext along the follower's motion x(t) = S(omega t),
    # differentiated in time by 4th-order central differences of S alone (not the program's
    # V and A); away from the joints and pieces, where J may jump under the stencil.
    p, kw = PROGRAMS[prog](), CASES[case]
    w = kw["speed"]
    theta = np.linspace(0.0, 2 * np.pi, 2000, endpoint=False)
    # s: 1e-3 rad of cam angle, where truncation (h**4) and rounding (1/h**2) balance
    ht = 1e-3 / w
    far = np.abs(theta[:, None] - joints(p)[None, :]).min(axis=1) > 3 * ht * w
    theta = theta[far]
    t = theta / w
    x = [p.svaj((t + k * ht) * w).S for k in (-2, -1, 0, 1, 2)]
    xd = (x[0] - 8 * x[1] + 8 * x[3] - x[4]) / (12 * ht)
    xdd = (-x[0] + 16 * x[1] - 30 * x[2] + 16 * x[3] - x[4]) / (12 * ht ** 2)
    n = (kw["mass"] * xdd + kw.get("damping", 0.0) * xd + kw["stiffness"] * x[2]
         + kw["preload"] + kw.get("external", 0.0))
    ff = follower_forces(p, theta=theta, **kw)
    scale = np.abs(ff.contact_force).max()
    assert np.abs(ff.contact_force - n).max() <= 1e-6 * scale
    # power balance of frictionless contact: T omega = N x'
    assert np.abs(ff.torque * w - ff.contact_force * xd).max() <= 1e-6 * scale * np.abs(xd).max()


@pytest.mark.parametrize("case", ["undamped", "damped"])
def test_the_spring_mass_follower_driven_by_the_contact_force_rides_the_cam(case):
    # Simulate m x'' = -k x - F0 - F_ext - c x' + N(omega t) from the cam's state at 0 with N
    # the computed contact force: the follower must stay on the cam, x(t) = S(omega t).
    p, kw = dwell_program(), CASES[case]
    w, m, k, c = kw["speed"], kw["mass"], kw["stiffness"], kw.get("damping", 0.0)
    f0 = kw["preload"] + kw.get("external", 0.0)

    def rhs(t, y):
        n = follower_forces(p, theta=[w * t], **kw).contact_force[0]
        return [y[1], (n - k * y[0] - f0 - c * y[1]) / m]
    sv = p.svaj([0.0])
    period = 2 * np.pi / w
    sol = solve_ivp(rhs, (0.0, period), [sv.S[0], sv.V[0] * w], method="DOP853", rtol=1e-11,
                    atol=1e-13, dense_output=True)
    t = np.linspace(0.0, period, 1001)
    assert np.abs(sol.sol(t)[0] - p.svaj(w * t).S).max() <= 1e-6 * 0.025


def test_the_follower_leaves_the_cam_where_the_contact_force_falls_to_zero():
    # Above the critical speed: released at the first angle of zero force, the free follower
    # (spring, preload, damping, no contact) flies above the cam's surface.
    p, kw = dwell_program(), CASES["jumping"]
    w, m, k, c = kw["speed"], kw["mass"], kw["stiffness"], kw["damping"]
    ff = follower_forces(p, samples=36001, **kw)
    t0 = ff.jump_angle / w
    sv = p.svaj([ff.jump_angle])
    sol = solve_ivp(lambda t, y: [y[1], (-k * y[0] - kw["preload"] - c * y[1]) / m],
                    (t0, t0 + d(10) / w), [sv.S[0], sv.V[0] * w], rtol=1e-11, atol=1e-14,
                    dense_output=True)
    t = np.linspace(t0, t0 + d(10) / w, 50)[1:]
    assert np.all(sol.sol(t)[0] > p.svaj(w * t).S)
    # and below it, a follower released anywhere would fall back onto the cam: the force
    # needed is positive everywhere
    slow = follower_forces(p, **{**kw, "speed": 0.9 * ff.critical_speed})
    assert not slow.jumps and slow.jump_angle is None and slow.least_force[0] > 0


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("prog", PROGRAMS)
def test_critical_speed_is_where_contact_is_lost(prog, case):
    p, kw = PROGRAMS[prog](), CASES[case]
    wc = follower_forces(p, **kw).critical_speed
    assert 0 < wc < np.inf
    below = follower_forces(p, **{**kw, "speed": wc * (1 - 1e-6)})
    above = follower_forces(p, **{**kw, "speed": wc * (1 + 1e-6)})
    assert below.least_force[0] > 0 and not below.jumps
    assert above.least_force[0] < 0 and above.jumps
    assert below.critical_speed == pytest.approx(wc, rel=1e-12)   # it does not depend on omega


def test_critical_speed_without_damping_in_closed_form():
    # N = m A w**2 + G: where A < 0 it vanishes at w**2 = G / (-m A)
    p, kw = dwell_program(), CASES["undamped"]
    ff = follower_forces(p, **kw)
    g = kw["stiffness"] * ff.S + kw["preload"]
    neg = ff.A < 0
    assert ff.critical_speed == pytest.approx(np.sqrt((g[neg] / (-kw["mass"] * ff.A[neg])).min()),
                                              rel=1e-14)


def test_critical_speed_limits():
    p = dwell_program()
    no_spring = follower_forces(p, mass=1.0, stiffness=0.0, preload=0.0, speed=1.0)
    assert no_spring.critical_speed == 0.0 and no_spring.jumps      # nothing holds it at rest
    lifted = follower_forces(p, mass=1.0, stiffness=100.0, preload=10.0, speed=1.0, external=-20)
    assert lifted.critical_speed == 0.0
    # a parabola over the turn (V jumps back at 360 deg): A > 0 everywhere, never a jump
    rise = MotionProgram([Segment("rise", 0, d(360), 0.01, "polynomial",
                                  conditions=((0.0, 0, 0.0), (0.0, 1, 0.0), (d(360), 0, 0.01)))],
                         allow_discontinuous=True)
    assert follower_forces(rise, mass=1.0, stiffness=1.0, preload=1.0,
                           speed=1.0).critical_speed == np.inf


def test_contact_held_by_inertia_alone_has_no_jump_free_speed():
    # a load away from the cam (-5 N) with no preload: at rest, at S = 0, nothing holds the
    # follower; at 30 rad/s the harmonic law's A > 0 there presses it on the cam
    p = MotionProgram([Segment("rise", 0, d(180), 0.02, "harmonic"),
                       Segment("return", d(180), d(360), 0.02, "harmonic")])
    ff = follower_forces(p, mass=1.0, stiffness=1000.0, preload=0.0, external=-5.0, speed=30.0)
    assert not ff.jumps and ff.critical_speed == 0.0
    # N(0) = m A(0) w**2 + F_ext, A(0) = h pi**2 / (2 beta**2) = 0.01 per rad**2
    assert ff.least_force == pytest.approx((1.0 * 0.01 * 900 - 5.0, 0.0), abs=1e-12)


@pytest.mark.parametrize("margin", [0.0, 5.0])
@pytest.mark.parametrize("case", CASES)
def test_least_preload_keeps_the_margin(case, margin):
    p, kw = dwell_program(), CASES[case]
    # at 1.3 times the critical speed: a preload above the present one is needed
    kw = {**kw, "speed": 1.3 * follower_forces(p, **kw).critical_speed}
    need = follower_forces(p, **kw).least_preload(margin)
    assert need > kw["preload"]
    over = follower_forces(p, **{**kw, "preload": need * (1 + 1e-6)})
    under = follower_forces(p, **{**kw, "preload": need * (1 - 1e-6)})
    assert over.least_force[0] > margin and under.least_force[0] < margin
    if margin == 0.0:
        assert not over.jumps and under.jumps


def shaft_work(p, kw):
    """The integral of the shaft torque over a turn, by adaptive quadrature segment by
    segment (independent of the result's own Gauss-Legendre sum)."""
    def torque(t):
        return float(follower_forces(p, theta=[t], **kw).torque[0])
    return integral(torque, p)


def integral(fun, p):
    """Over each segment, with its eighths as break points (the piecewise laws' pieces)."""
    return sum(quad(fun, s.start, s.end, points=[s.start + s.beta * i / 8 for i in range(1, 8)],
                    epsabs=0, epsrel=1e-13, limit=400)[0] for s in p.segments)


@pytest.mark.parametrize("prog", PROGRAMS)
def test_mean_torque_without_damping_is_zero(prog):
    p, kw = PROGRAMS[prog](), {**CASES["undamped"], "external": 12.0}
    ff = follower_forces(p, **kw)
    peak = abs(ff.peak_torque[0])
    assert abs(ff.mean_torque) <= 1e-9 * peak
    assert abs(shaft_work(p, kw) / (2 * np.pi)) <= 1e-9 * peak


@pytest.mark.parametrize("prog", PROGRAMS)
def test_mean_torque_with_damping_is_the_damping_work_per_turn(prog):
    p, kw = PROGRAMS[prog](), CASES["damped"]
    ff = follower_forces(p, **kw)
    c, w = kw["damping"], kw["speed"]
    v2 = integral(lambda t: float(p.svaj([t]).V[0]) ** 2, p)
    work = c * w * v2                        # J per turn: the damper's force c x' over dx
    assert work > 0
    assert ff.mean_torque == pytest.approx(work / (2 * np.pi), rel=1e-9)
    assert shaft_work(p, kw) == pytest.approx(work, rel=1e-9)


def test_result_shapes_columns_and_repr():
    ff = follower_forces(dwell_program(), samples=361, **CASES["undamped"])
    assert isinstance(ff, FollowerForces)
    for a in (ff.theta, ff.S, ff.V, ff.A, ff.contact_force, ff.torque, ff.contact):
        assert a.shape == (361,)
    cols = ff.to_columns(degrees=True)
    assert list(cols) == ["theta [deg]", "S [m]", "V [m/rad]", "A [m/rad^2]",
                          "contact_force [N]", "shaft_torque [N m]"]
    assert cols["theta [deg]"][-1] == pytest.approx(360.0)
    assert "contact kept" in repr(ff)
    osc = follower_forces(MotionProgram([Segment("rise", 0, d(120), d(20), "cycloidal"),
                                         Segment("return", d(120), d(360), d(20), "3-4-5")]),
                          mass=0.02, stiffness=5.0, preload=1.0, speed=20.0,
                          motion="oscillating")
    assert "contact_moment [N m]" in osc.to_columns() and "S [rad]" in osc.to_columns()


@pytest.mark.parametrize("kw, message", [
    (dict(mass=-1.0), r"mass: expected a number above 0, got -1"),
    (dict(mass=0), r"mass: expected a number above 0, got 0"),
    (dict(stiffness=-5.0), r"stiffness: expected a number at least 0, got -5"),
    (dict(preload="ten"), r"preload: expected a finite number, got 'ten'"),
    (dict(damping=float("nan")), r"damping: expected a finite number, got nan"),
    (dict(speed=0.0), r"speed: expected a number above 0, got 0"),
    (dict(external=True), r"external: expected a finite number, got true"),
    (dict(motion="rolling"), r"motion: expected one of 'translating', 'oscillating', got "
                             r"'rolling'"),
])
def test_bad_arguments_are_refused(kw, message):
    with pytest.raises(ModelError, match=message):
        follower_forces(dwell_program(), **{**CASES["undamped"], **kw})


def test_every_bad_argument_at_once_and_a_bad_margin():
    with pytest.raises(ModelError) as exc:
        follower_forces(dwell_program(), mass=-1, stiffness=-1, preload=1, speed=1)
    assert len(exc.value.problems) == 2
    with pytest.raises(ModelError, match="margin: expected a number at least 0, got -1"):
        follower_forces(dwell_program(), **CASES["undamped"]).least_preload(-1.0)


@pytest.mark.parametrize("case", ["undamped", "jumping"])
def test_forces_figure_draws_the_zero_line_and_shades_the_jump(case):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    import kinelab as kl
    ff = follower_forces(dwell_program(), **CASES[case])
    fig = kl.plot.cam_forces(ff, units={"angle": "deg"})
    try:
        top, bottom = fig.axes
        assert top.get_ylabel() == "contact force [N]"
        assert bottom.get_ylabel() == "cam shaft torque [N m]"
        assert bottom.get_xlabel() == "cam angle [deg]"
        assert any(np.allclose(line.get_ydata(), 0.0) for line in top.get_lines())
        shaded = [c for c in top.collections if isinstance(c, PolyCollection)]
        assert bool(shaded) == ff.jumps
        assert top.get_lines()[0].get_xdata()[-1] == pytest.approx(360.0)
    finally:
        plt.close(fig)
    with pytest.raises(ModelError, match="forces: expected a FollowerForces"):
        kl.plot.cam_forces(dwell_program())


def test_a_task_with_dynamics_solves_at_the_profile_samples():
    from kinelab.cams import read_cam_task, solve_cam_task
    task = read_cam_task({
        "units": {"length": "mm", "angle": "deg"}, "cam": {"speed": 1200, "samples": 361},
        "follower": {"type": "roller", "roller_radius": 10, "base_circle": 40},
        "dynamics": {"mass": 2, "stiffness": 2000, "preload": 40, "damping": 3, "margin": 5},
        "segments": [{"kind": "rise", "law": "cycloidal", "from": 0, "to": 90, "lift": 25},
                     {"kind": "dwell", "from": 90, "to": 180},
                     {"kind": "return", "law": "3-4-5", "from": 180, "to": 270, "lift": 25},
                     {"kind": "dwell", "from": 270, "to": 360}]})
    assert task.dynamics == {"mass": 2.0, "stiffness": 2000.0, "preload": 40.0, "damping": 3.0,
                             "margin": 5.0, "external": 0.0}
    sol = solve_cam_task(task)
    ff = sol.forces
    assert np.array_equal(ff.theta, sol.cam.theta) and ff.speed == pytest.approx(np.radians(1200))
    same = follower_forces(dwell_program(), mass=2, stiffness=2000, preload=40, damping=3,
                           speed=np.radians(1200), samples=361)
    assert ff.contact_force == pytest.approx(same.contact_force, rel=1e-12, abs=1e-9)
    no_dynamics = solve_cam_task(read_cam_task({
        "units": {"length": "mm"}, "cam": {"speed": 1},
        "follower": {"type": "knife-edge", "base_circle": 40},
        "segments": [{"kind": "rise", "law": "cycloidal", "from": 0, "to": 3, "lift": 5},
                     {"kind": "return", "law": "cycloidal", "from": 3, "to": 2 * np.pi,
                      "lift": 5}]}))
    assert no_dynamics.forces is None and no_dynamics.task.dynamics is None
