"""Inverse dynamics checked against independent methods: the free-body (Newton-Euler)
equations, momentum balance of the whole linkage, energy and finite differences."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.dynamics import (Damper, Loads, MassProperties, PointForce, Spring, Torque,
                              inverse)
from kinelab.model import Input, Joint, Link, Mechanism, Point
from tests.dynamics.models import engine, fourbar, pendulum, pr_robot, prrrr, rp_robot

g = (0.0, -9.81)


def with_masses(m: Mechanism) -> Mechanism:
    """Give every moving link a mass at its first point and an inertia (for catalogue models)."""
    links = tuple(link if link.ground else Link(link.name, link.points, mass=1.0 + 0.1 * i,
                                                center_of_mass=link.points[-1], inertia=0.02 * (i + 1))
                  for i, link in enumerate(m.links))
    return Mechanism(m.name, m.points, links, m.joints, m.inputs)


def loaded(m: Mechanism) -> Loads:
    """Gravity, a state-dependent force, a torque between two links, a spring and a damper."""
    moving = [link for link in m.links if not link.ground]
    last, first = moving[-1], moving[0]
    ground_pt = m.ground.points[0]
    return Loads(gravity=g,
                 forces=[PointForce(last.points[-1], ("3 * cos(t) - 2", lambda t, q, qd: 1.5 + 0 * t))],
                 torques=[Torque(first.name, 0.7, reacting=last.name)],
                 springs=[Spring((ground_pt, last.points[-1]), stiffness=40.0, free_length=0.3)],
                 dampers=[Damper((ground_pt, moving[len(moving) // 2].points[-1]), damping=2.5)])


def motion(m: Mechanism, t=None):
    """A smooth motion of the inputs about the sketch, at times t (default 60 samples over
    2 s), with its exact derivatives: q = q_sketch + amp sin(f t)."""
    t = np.linspace(0.0, 2.0, 60) if t is None else np.asarray(t, float)
    M = len(m.inputs)
    kinds = [("slide" if i.joint and m.joint(i.joint).type == "P" else "angle") for i in m.inputs]
    q0 = kl.kinematics.plan(m).q_sketch
    amp = np.array([0.05 if k == "slide" else 0.4 for k in kinds])
    f = np.random.default_rng(1).uniform(0.8, 1.6, M)
    s, c = np.sin(np.outer(t, f)), np.cos(np.outer(t, f))
    return t, q0 + amp * s, amp * f * c, -amp * f ** 2 * s


def squeeze(a, M):
    return a[:, 0] if M == 1 else a


def catalogue():
    return [fourbar(), engine(), prrrr(), pr_robot(), rp_robot(arm_mass=2.0, gripper_inertia=0.01),
            with_masses(kl.mechanisms.fivebar(ground=1.0, crank1=0.4, coupler1=1.0, coupler2=1.0, crank2=0.4)),
            with_masses(kl.mechanisms.triad6()), with_masses(kl.mechanisms.whitworth(1.0, 0.5, 1.0, 2.0))]


@pytest.fixture(params=catalogue(), ids=lambda m: m.name)
def model(request):
    return request.param


def solve(m, **kw):
    t, q, qd, qdd = motion(m)
    M = len(m.inputs)
    return inverse(m, squeeze(q, M), squeeze(qd, M), squeeze(qdd, M), loads=loaded(m), t=t, **kw)


def test_kane_against_newton_euler(model):
    res = solve(model)
    scale = np.max(np.abs(res.input_forces))
    assert res.reactions_unique and scale > 0.01       # efforts well above the tolerance
    np.testing.assert_allclose(res.newton_euler_efforts, res.input_forces, rtol=0, atol=1e-10 * scale)


def test_shaking_force_and_moment_against_momentum_balance(model):
    """What the links push on the ground = external loads - rate of change of momentum."""
    res = solve(model)
    sol, loads, m = res.kinematics, loaded(model), model
    masses = MassProperties.from_model(m)
    F = np.zeros((res.N, 2))
    Mo = np.zeros(res.N)
    for b in masses.links:
        r, a = sol.position(b.center_of_mass), sol.acceleration(b.center_of_mass)
        f = b.mass * (np.array(g) - a)
        F += f
        Mo += r[:, 0] * f[:, 1] - r[:, 1] * f[:, 0] - b.inertia * sol.alpha(b.link)
    fx = 3 * np.cos(res.t) - 2
    f_ext = np.stack([fx, np.full(res.N, 1.5)], -1)
    r = sol.position(loads.forces[0].point)
    F += f_ext
    Mo += r[:, 0] * f_ext[:, 1] - r[:, 1] * f_ext[:, 0]
    scale = max(np.max(np.abs(F)), 1.0)
    np.testing.assert_allclose(res.shaking_force, F, rtol=0, atol=1e-10 * scale)
    np.testing.assert_allclose(res.shaking_moment, Mo, rtol=0, atol=1e-10 * scale)


def test_power_balance_at_every_sample(model):
    """A consistency check of the bookkeeping (both sides come from the same K, L and
    rates, so they agree by construction); the physics is checked by the finite
    differences of the energy below."""
    res = solve(model)
    lhs = res.actuator_power + res.applied_power
    rhs = res.energy_rate + res.dissipation
    np.testing.assert_allclose(lhs, rhs, rtol=0, atol=1e-10 * np.max(np.abs(lhs)))


def test_power_balance_against_finite_differences(model):
    """d(T + V)/dt by central differences along the motion, against the powers."""
    m, M, h = model, len(model.inputs), 1e-4
    t = np.linspace(0.1, 1.9, 9)
    energy = []
    for tt in (t - h, t + h):
        _, q, qd, qdd = motion(m, tt)
        r = inverse(m, squeeze(q, M), squeeze(qd, M), squeeze(qdd, M), loads=loaded(m), t=tt)
        energy.append(r.kinetic_energy + r.potential_energy)
    _, q, qd, qdd = motion(m, t)
    res = inverse(m, squeeze(q, M), squeeze(qd, M), squeeze(qdd, M), loads=loaded(m), t=t)
    rate = (energy[1] - energy[0]) / (2 * h)
    power = res.actuator_power + res.applied_power - res.dissipation
    # central difference: error ~ h^2 |d3E/dt3| / 6, about 1e-8 of the power's scale
    np.testing.assert_allclose(rate, power, rtol=0, atol=1e-6 * np.max(np.abs(power)))


def test_spinning_pendulum_pivot_force():
    # Newton for the bar: pivot force = m a_G - m g, with a_G = L (-w^2 cos, -w^2 sin) + L a (-sin, cos)
    m, L = 2.0, 0.5
    th, w, a = np.array([0.3, 2.0]), np.array([4.0, -1.0]), np.array([1.0, 5.0])
    res = inverse(pendulum(length=L, mass=m), th, w, a, loads=Loads(gravity=g))
    aG = L * (-w[:, None] ** 2 * np.stack([np.cos(th), np.sin(th)], -1)
              + a[:, None] * np.stack([-np.sin(th), np.cos(th)], -1))
    np.testing.assert_allclose(res.reactions("pivot"), m * aG - m * np.array(g), rtol=1e-13, atol=1e-12)
    # the ground feels the opposite, and the motor's reaction torque
    np.testing.assert_allclose(res.shaking_force, -res.reactions("pivot"), rtol=0, atol=1e-12)
    np.testing.assert_allclose(res.shaking_moment, -res.input_forces[:, 0], rtol=0, atol=1e-12)


def test_redundant_joint_gives_efforts_and_least_squares_reactions():
    """A parallelogram with a third, parallel rocker: the extra hinge is redundant, so the
    reactions are not unique; the efforts still are."""
    pts = dict(O2=(0, 0), O4=(1, 0), O6=(2, 0), A=(0.3, 0.4), B=(1.3, 0.4), C=(2.3, 0.4))
    m = Mechanism(
        "parallel", tuple(Point(n, *xy) for n, xy in pts.items()),
        (Link("ground", ("O2", "O4", "O6"), ground=True),
         Link("crank", ("O2", "A"), mass=1.0, center_of_mass="A", inertia=0.01),
         Link("coupler", ("A", "B", "C"), mass=2.0, center_of_mass="B", inertia=0.2),
         Link("rocker", ("O4", "B"), mass=1.0, center_of_mass="B", inertia=0.01),
         Link("rocker2", ("O6", "C"), mass=1.0, center_of_mass="C", inertia=0.01)),
        tuple(Joint(f"j{p}", "R", ab, point=p) for p, ab in (
            ("O2", ("ground", "crank")), ("A", ("crank", "coupler")), ("B", ("coupler", "rocker")),
            ("O4", ("ground", "rocker")), ("C", ("coupler", "rocker2")), ("O6", ("ground", "rocker2")))),
        (Input(joint="jO2"),))
    q = np.linspace(0.5, 2.5, 9)
    res = inverse(m, q, 2.0, 1.0, loads=Loads(gravity=g))
    # the coupler translates: every link's centre of mass moves on a circle of radius 0.5
    Iz = 3 * 0.01 + (1.0 + 2.0 + 1.0 + 1.0) * 0.25
    weight = (1.0 + 2.0 + 1.0 + 1.0) * 9.81 * 0.5 * np.cos(q)
    np.testing.assert_allclose(res.input_forces[:, 0], Iz * 1.0 + weight, rtol=1e-12)
    assert not res.reactions_unique
    np.testing.assert_allclose(res.newton_euler_efforts, res.input_forces, rtol=1e-10)


def test_shapes_and_single_configuration():
    res = inverse(pr_robot(), [0.1, 0.2], [1.0, 0.0], [0.0, 1.0])
    assert res.input_forces.shape == (1, 2)
    assert res.reactions("wrist").shape == (1, 2) and res.reaction_moment("rail").shape == (1,)
    assert res.shaking_force.shape == (1, 2)
    assert res.input_force("wrist").shape == (1,)
    frame = res.to_dataframe()
    assert "wrist.torque[N*m]" in frame and "rail.force[N]" in frame
    assert "rail.reaction_moment[N*m]" in frame and len(frame) == 1


def test_singular_samples_give_nan_forces_flagged():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=1.0)      # at 90 deg the rod stands upright
    links = tuple(link if link.ground else Link(link.name, link.points, mass=1.0,
                                                center_of_mass=link.points[0], inertia=0.1)
                  for link in sc.links)
    m = Mechanism("sc", sc.points, links, sc.joints, sc.inputs)
    res = inverse(m, [0.5, np.pi / 2], 1.0)
    np.testing.assert_array_equal(res.singular, [False, True])
    assert np.isnan(res.input_forces[1]).all() and np.isfinite(res.input_forces[0]).all()
    assert np.isnan(res.reactions("jA")[1]).all()


def test_reactions_can_be_skipped():
    res = inverse(pendulum(), [0.0, 1.0], reactions=False)
    assert res.shaking_force is None
    with pytest.raises(kl.errors.ModelError, match="reactions=False"):
        res.reactions("pivot")


def test_law_forms_agree():
    """A number, an expression, a table and a callable describing the same force."""
    m = engine()
    q = np.linspace(0.0, 2 * np.pi, 13)
    x = np.linspace(-0.1, 7.0, 400)
    forms = [("200 * sin(q) - 50", 0.0),
             (lambda t, q, qd: 200 * np.sin(q) - 50, 0.0),
             ({"of": "q", "x": x.tolist(), "y": (200 * np.sin(x) - 50).tolist()}, 0.0)]
    out = [inverse(m, q, 10.0, loads=Loads(forces=[PointForce("B", f)])).input_forces for f in forms]
    np.testing.assert_allclose(out[1], out[0], rtol=1e-14, atol=1e-12)
    # linear interpolation of a sine on a 0.018 rad grid: error <= 200 * h^2 / 8 ~ 8e-3 N
    np.testing.assert_allclose(out[2], out[0], rtol=0, atol=0.01 * 0.05)
    vector = inverse(m, q, 10.0, loads=Loads(forces=[PointForce(
        "B", lambda t, q, qd: np.stack([200 * np.sin(q) - 50, 0 * q], -1))])).input_forces
    np.testing.assert_allclose(vector, out[0], rtol=1e-14, atol=1e-12)


def test_time_dependent_load_uses_t():
    m = pendulum()
    loads = Loads(torques=[Torque("arm", "2 * t")])
    res = inverse(m, [0.0, 0.0], t=[1.0, 3.0], loads=loads)
    np.testing.assert_allclose(res.input_forces[:, 0], [-2.0, -6.0], rtol=0, atol=1e-14)
