"""The errata of the lecture notes (docs/errata.md, docs/errata.pt.md), entry by entry.

Each test runs the kinelab lines of its entry and checks that kinelab gives the right form's
value and, where the printed form is a different number, not the printed one.  The right
forms are written here again from the entry, not taken from kinelab.  The last tests keep
the entries of the two pages and of this file the same.
"""
import re
from pathlib import Path

import numpy as np
import pytest
import sympy as sy

import kinelab as kl
from kinelab.model import Input, Joint, Link, Mechanism, Point

sp = kl.spatial
DOCS = Path(__file__).resolve().parents[1] / "docs"
ENTRY = re.compile(r"^### ((?:FC|M)-\d+)\. ", re.M)
TESTED = set()


def entry(name):
    """Mark a test as the check of one entry of the errata."""
    def mark(test):
        TESTED.add(name)
        return test
    return mark


def close(a, b, tol=1e-12):
    return np.allclose(a, b, rtol=tol, atol=tol)


# -- Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades* ------------------
# Slider-crank r2 = 1, r3 = 3, omega2 = 7 rad/s; eqs. 4.63-4.89 measure theta3 clockwise.
R2, R3, W2 = 1.0, 3.0, 7.0
TH2 = np.radians(np.arange(-170.0, 180.0, 20.0))


@pytest.fixture(scope="module")
def slider_crank():
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=R2, rod=R3), q=TH2, qd=W2)
    return sol, -sol.angle("rod"), -sol.omega("rod")


@entry("FC-1")
def test_fc1_velocity_of_a_point_sliding_on_a_turning_link():
    sol = kl.analyze(kl.mechanisms.slotted_link(crank=1.0, distance=2.0), q=TH2, qd=3.0)
    r, rdot = sol.slide("slot"), sol.slide_velocity("slot")
    th, w = sol.angle("lever"), sol.omega("lever")
    r_hat = np.stack([np.cos(th), np.sin(th)], -1)
    t_hat = np.stack([-np.sin(th), np.cos(th)], -1)
    # V = (dr/dt) r_hat + r omega t_hat: the limit of Δr/Δt, not of r/Δt
    assert close(sol.velocity("A"), rdot[:, None] * r_hat + (r * w)[:, None] * t_hat)


@entry("FC-2")
def test_fc2_omega3_from_cramers_rule(slider_crank):
    _, th3, w3 = slider_crank
    right = R2 * W2 * np.cos(TH2) / (R3 * np.cos(th3))
    assert close(w3, right)
    printed = -right
    away = np.abs(np.cos(TH2)) > 0.1                  # at cos(theta2) = 0 both are 0
    assert np.all(np.abs(printed - w3)[away] > 1e-2)


@entry("FC-3")
def test_fc3_theta3_of_eq_4_64(slider_crank):
    sol, th3, _ = slider_crank
    right, printed = np.arcsin(R2 * np.sin(TH2) / R3), np.arcsin(-R2 * np.sin(TH2) / R3)
    assert close(th3, right)
    eq_4_75 = lambda t3: -R2 * W2 * np.sin(TH2 + t3) / np.cos(t3)
    assert close(eq_4_75(right), sol.slide_velocity("slide"))
    away = np.abs(np.cos(TH2)) > 0.1                  # at theta2 = ±90° both give -r2 omega2 sin
    assert np.all(np.abs(eq_4_75(printed) - sol.slide_velocity("slide"))[away] > 1e-2)


@entry("FC-4")
def test_fc4_slider_speed_towards_the_crank(slider_crank):
    sol, th3, _ = slider_crank
    v1 = sol.velocity("B")[:, 0]                      # along +x
    vB = W2 * R2
    eq_4_84 = vB * np.sin(TH2) + vB * np.cos(TH2) / (R3 * np.cos(th3)) * R3 * np.sin(th3)
    eq_4_89 = W2 * R2 * (np.sin(TH2) + np.cos(TH2) * np.tan(th3))
    root = np.sqrt(R3**2 - R2**2 * np.sin(TH2) ** 2)
    right = W2 * R2 * (np.sin(TH2) + R2 * np.sin(TH2) * np.cos(TH2) / root)
    assert close(eq_4_84, right) and close(eq_4_89, right)
    assert close(right, -v1)                          # v_C, towards A, is -v1
    printed = -right                                  # eqs. 4.85 and 4.92
    assert close(printed, v1) and np.all(np.abs(printed - eq_4_84) > 1e-3)


FB = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
TH2_FB = np.radians(np.arange(-175.0, 180.0, 15.0))


@entry("FC-5")
def test_fc5_omega4_sign():
    sol = kl.analyze(kl.mechanisms.fourbar(**FB), q=TH2_FB, qd=W2)
    t3, t4 = sol.angle("coupler"), sol.angle("rocker") + np.pi      # R4 from B to O4
    ratio = FB["crank"] * W2 / FB["rocker"] * np.sin(TH2_FB - t3) / np.sin(t4 - t3)
    assert close(sol.omega("rocker"), -ratio)
    assert close(sol.omega("coupler"),                                # eq. 4.114, right
                 FB["crank"] * W2 / FB["coupler"] * np.sin(TH2_FB - t4) / np.sin(t4 - t3))
    moving = np.abs(sol.omega("rocker")) > 1e-2
    assert np.all(np.abs(ratio - sol.omega("rocker"))[moving] > 1e-2)


def wrap(a):
    return np.angle(np.exp(1j * np.asarray(a)))


@entry("FC-6")
@pytest.mark.parametrize("branch, sign", [("open", -1.0), ("crossed", +1.0)])
def test_fc6_theta_d_is_the_direction_of_A_to_O4(branch, sign):
    r1, r2, r3, r4 = FB["ground"], FB["crank"], FB["coupler"], FB["rocker"]
    th2 = TH2_FB
    sol = kl.analyze(kl.mechanisms.fourbar(**FB, branch=branch), q=th2)
    t3, t4 = sol.angle("coupler"), sol.angle("rocker") + np.pi
    rd = np.sqrt(r1**2 + r2**2 - 2 * r1 * r2 * np.cos(th2))
    g3 = np.arccos((rd**2 + r3**2 - r4**2) / (2 * rd * r3))
    g4 = np.arccos((rd**2 + r4**2 - r3**2) / (2 * rd * r4))
    thd = np.arctan2(-r2 * np.sin(th2), r1 - r2 * np.cos(th2))
    assert close(thd, -np.arcsin(r2 / rd * np.sin(th2)))             # crank shorter than ground
    # upper signs (sign = +1): theta3 = thd - g3, theta4 = thd + g4; lower: the other way
    assert close(wrap(thd - sign * g3 - t3), 0.0, 1e-10)
    assert close(wrap(thd + sign * g4 - t4), 0.0, 1e-10)
    printed = np.arcsin(r2 / rd * np.sin(th2))                       # eq. 4.118 as printed
    off = np.abs(np.sin(th2)) > 0.1
    assert np.all(np.abs(wrap(printed - sign * g3 - t3))[off] > 1e-2)
    # ... with the other signs it gives the mirror image of this assembly: -theta3, -theta4
    assert close(wrap(printed + sign * g3 + t3), 0.0, 1e-10)
    assert close(wrap(printed - sign * g4 + t4), 0.0, 1e-10)


@entry("FC-7")
def test_fc7_offset_slider_crank_velocity():
    e, t = 0.5, np.radians(np.arange(-170.0, 180.0, 20.0))
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=R2, rod=R3, offset=-e), q=t, qd=W2)
    u = R2 * np.sin(t) + e
    root = np.sqrt(R3**2 - u**2)
    right = -W2 * R2 * np.sin(t) - W2 * R2 * np.cos(t) * u / root
    printed = -W2 * R2 * np.sin(t) - W2 * R2**2 * np.cos(t) * np.sin(t) / root
    assert close(sol.velocity("B")[:, 0], right)
    assert close(printed - right, e * W2 * R2 * np.cos(t) / root)
    # and the right form is the derivative of eq. 4.133
    x = R2 * np.cos(t) + np.sqrt(R3**2 - u**2)
    assert close(sol.slide("slide"), x)


@entry("FC-8")
def test_fc8_inverted_slider_crank_theta3():
    r1, r2, r4 = 2.0, 1.0, 0.3
    t = np.radians(np.arange(-175.0, 180.0, 10.0))
    sol = kl.analyze(kl.mechanisms.inverted_slider_crank(ground=r1, crank=r2, offset=-r4), q=t)
    th3, r3 = sol.angle("rocker"), sol.slide("slide")
    a, b = r2 * np.cos(t) - r1, r2 * np.sin(t)                      # theta1 = 0
    assert close(r3, np.sqrt(r1**2 + r2**2 - r4**2 - 2 * r1 * r2 * np.cos(t)))   # eq. 4.136
    u = lambda beta: (r4 + beta * np.sqrt(r4**2 - a**2 + r3**2)) / (a + r3)
    beta = np.sign(b)
    assert close(wrap(2 * np.arctan(u(beta)) - th3), 0.0, 1e-10)
    assert close(wrap(np.arctan2(b, a) + np.arctan2(r4, r3) - th3), 0.0, 1e-10)
    assert np.all(np.abs(wrap(np.arctan(u(beta)) - th3)) > 1e-2)    # as printed: half of it
    other = 2 * np.arctan(u(-beta))                                  # solves x only
    assert close(r3 * np.cos(other) + r4 * np.sin(other), a)
    assert np.all(np.abs(r3 * np.sin(other) - r4 * np.cos(other) - b) > 1e-2)


# -- *Mecanismos* ----------------------------------------------------------------------------

@entry("M-1")
def test_m1_the_planar_transform_is_eq_13():
    t, p = np.radians(30.0), [1.0, 2.0]
    T = sp.planar_transform(t, p)
    assert T.shape == (3, 3)
    assert sp.homogeneous(sp.rotation("z", t), [*p, 0.0]).shape == (4, 4)
    R = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    assert close(sp.transform_points(T, [0.3, -0.4]), p + R @ [0.3, -0.4])        # eq. 17
    rates = sp.transform_rates(T, 2.0, [0.5, 0.0])
    m = sp.point_motion(T, rates.Td, rates.Tdd, [1.0, 0.0], [0.0, 0.0])
    assert close(m.velocity, (rates.Td @ [1.0, 0.0, 1.0])[:2])                    # eq. 47


@entry("M-2")
def test_m2_half_angle_keeps_theta_pi():
    E, F, G = 1.5, -0.5, 1.5
    s = kl.solvers.half_angle(E, F, G)
    assert int(s.count) == 2
    printed = 2 * np.arctan(-(G + E) / (2 * F))
    assert close(np.sort(s.theta), np.sort([printed, np.pi]))
    assert close(E * np.cos(np.pi) + F * np.sin(np.pi) + G, 0.0)


THETA2 = np.radians(45.0)


def phi(x):
    th3, l = x[..., 0], x[..., 1]
    return np.stack([np.cos(THETA2) + np.cos(th3) - l, np.sin(THETA2) + np.sin(th3)], -1)


def jac(x):
    th3, one = x[..., 0], np.ones_like(x[..., 0])
    return np.stack([np.stack([-np.sin(th3), -one], -1), np.stack([np.cos(th3), 0 * one], -1)], -2)


@pytest.fixture(scope="module")
def ex_4_4():
    return kl.solvers.newton(phi, jac, [np.radians(-60.0), 1.0], history=True).history


def test_ex_4_4_start_is_the_mechanism_at_60_degrees():
    # Not a slip: theta2(0) = 60°, theta3(0) = -60°, l(0) = 1 closes the loop at theta2 = 60°
    c = np.radians(60.0)
    assert close([np.cos(c) + np.cos(-c) - 1.0, np.sin(c) + np.sin(-c)], [0.0, 0.0])


@entry("M-3")
def test_m3_newton_step_uses_the_current_iterate(ex_4_4):
    h = ex_4_4
    assert close(h.step[:4, 0], -h.residual[:4, 1] / np.cos(h.x[:4, 0]))
    assert abs(h.step[0, 0] - 0.318) < 5e-4                           # the worked row 0
    with_next = -h.residual[0, 1] / np.cos(h.x[1, 0])                 # eq. 45 as printed
    assert abs(with_next - 0.318) > 0.1


@entry("M-4")
def test_m4_iteration_table(ex_4_4):
    h = ex_4_4
    table = np.column_stack([h.x, h.residual, h.step])
    right = [[-0.7294, 1.4824, -0.02965, 0.04071, -0.05461, -0.06604],
             [-0.78397, 1.41632, -0.001093, 0.001013, -0.001431, -0.002104],
             [-0.785397, 1.414215, -7.249e-7, 7.236e-7, -1.023e-6, -1.448e-6]]
    for k, row in enumerate(right, start=1):
        assert np.allclose(table[k], row, rtol=5e-4, atol=0), k    # to the digits written
    assert abs(table[2, 4] - (-0.0016)) > 1e-4                     # printed Δθ3(2)
    assert abs(table[3, 0] - (-0.7855)) > 5e-5                     # printed θ3(3)
    assert table[3, 3] > 0 and abs(table[3, 3] - (-7.2e-5)) > 7e-5  # printed Φ2(3)
    assert np.all(np.abs(table[3, 4:]) > 1e-7) and np.all(np.abs(table[4, 4:]) < 1e-7)
    assert "-0.001431" in kl.solvers.iteration_table(h, names=["theta3", "l"])


@entry("M-5")
def test_m5_J_D_is_the_jacobian_of_the_dependent_coordinates():
    d = kl.derive.derive(kl.mechanisms.slotted_link(crank=0.1, distance=0.2))
    assert [str(s) for s in d.S] == ["A", "B"] and [str(s) for s in d.q] == ["q"]
    assert d.J == d.Phi.jacobian(d.S) and d.Q == d.Phi.jacobian(d.q)
    assert sy.simplify(d.K + d.J.inv() * d.Q) == sy.zeros(2, 1)


@entry("M-6")
def test_m6_eq_54_multiplies_the_position_of_A():
    L2, t, w = 1.0, np.radians(50.0), 7.0
    Td = sp.transform_rates(sp.planar_transform(t), w, [0.0, 0.0]).Td
    vA = kl.analyze(kl.mechanisms.slider_crank(crank=L2, rod=3.0), q=t, qd=w).velocity("A")
    assert close((Td @ [L2, 0.0, 1.0])[:2], vA)
    assert close((Td @ [0.0, 0.0, 1.0])[:2], [0.0, 0.0]) and np.linalg.norm(vA) > 1.0


@entry("M-7")
def test_m7_slider_rate_and_J_I(slider_crank):
    sol, _, _ = slider_crank
    th3 = sol.angle("rod") + np.pi                   # Ex. 4.6: A = B + L3 (c3, s3)
    s2, c2, s3, c3 = np.sin(TH2), np.cos(TH2), np.sin(th3), np.cos(th3)
    right = R2 * (-s2 + c2 * s3 / c3) * W2
    printed = R2 * (s2 + c2 * s3 / c3) * W2
    assert close(sol.slide_velocity("slide"), right)
    assert close(right, -R2 * np.sin(TH2 - th3) / c3 * W2)
    assert np.all(np.abs(printed - right)[np.abs(s2) > 0.1] > 1e-2)
    # J_I = -L2(-s2 + c2 s3/c3) vanishes at the dead centres (O, A, B in line)
    for q2 in (0.0, np.pi):
        s = kl.analyze(kl.mechanisms.slider_crank(crank=R2, rod=R3), q=q2, qd=1.0)
        t3 = float(s.angle("rod")) + np.pi
        assert abs(-R2 * (-np.sin(q2) + np.cos(q2) * np.tan(t3))) < 1e-12
        assert abs(float(s.slide_velocity("slide"))) < 1e-12


def rp_robot():
    return Mechanism("RP", (Point("O", 0, 0), Point("G1", 0.4, 0), Point("G2", 0.8, 0)),
        (Link("ground", ("O",), ground=True),
         Link("arm", ("O", "G1"), mass=3.0, center_of_mass="G1", inertia=0.05),
         Link("gripper", ("G2",), mass=2.0, center_of_mass="G2", inertia=0.02)),
        (Joint("shoulder", "R", ("ground", "arm"), point="O"),
         Joint("reach", "P", ("arm", "gripper"), point="G2", axis=(1, 0), origin="O")),
        (Input(joint="shoulder"), Input(joint="reach")))


@pytest.fixture(scope="module")
def kane():
    return kl.derive.derive(rp_robot()).dynamics


@entry("M-8")
def test_m8_each_body_with_its_own_inertia(kane):
    assert str(kane.f[2]) == "-I_arm*q_1_ddot"
    assert str(kane.f[5]) == "-I_gripper*q_1_ddot"


@entry("M-9")
def test_m9_partial_velocities_of_the_gripper(kane):
    q1, q2 = sy.symbols("q_1 q_2")
    assert sy.simplify(kane.D[0, 3:5] - sy.Matrix([[-q2 * sy.sin(q1), q2 * sy.cos(q1)]])) == sy.zeros(1, 2)
    assert sy.simplify(kane.D[1, 3:5] - sy.Matrix([[sy.cos(q1), sy.sin(q1)]])) == sy.zeros(1, 2)
    a, r = 0.5, 0.8
    J = sp.rp().jacobian([a, r])
    R01 = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    assert close(R01.T @ J[:, 0], [0.0, r])          # [0 q2] in base 1: d vG2/d u1
    assert close(R01.T @ J[:, 1], [1.0, 0.0])        # [1 0]: d vG2/d u2


L0, L2, L2_TILDE = 1.0, 0.4, 0.25
Q57, U57, DU57 = [0.3, 1.3], [0.7, -1.1], [0.4, 2.0]


def prrrr():
    return Mechanism("PRRRR",
        (Point("O", 0, 0), Point("O2", L0, 0), Point("G1", 0, 0.2), Point("A", L0, L2),
         Point("G2", L0, L2_TILDE), Point("P", 0.6, 1.0)),
        (Link("ground", ("O", "O2"), ground=True), Link("slider", ("G1",)),
         Link("crank", ("O2", "A", "G2")), Link("bar3", ("G1", "P")), Link("bar4", ("A", "P"))),
        (Joint("rail", "P", ("ground", "slider"), point="G1", axis=(0, 1), origin="O"),
         Joint("jO2", "R", ("ground", "crank"), point="O2"),
         Joint("jG1", "R", ("slider", "bar3"), point="G1"),
         Joint("jA", "R", ("crank", "bar4"), point="A"),
         Joint("jP", "R", ("bar3", "bar4"), point="P")),
        (Input(joint="rail"), Input(joint="jO2")))


@pytest.fixture(scope="module")
def s57():
    return kl.analyze(prrrr(), q=Q57, qd=U57, qdd=DU57)


def notes_J(s57):
    """J = -J_D^-1 J_I from the notes' J_D and J_I (with L0, M-10)."""
    (q1, q2), (q5, q6) = Q57, s57.position("P")
    c2, s2 = np.cos(q2), np.sin(q2)
    JD = np.array([[q5, q6 - q1], [q5 - L2 * c2 - L0, q6 - L2 * s2]])
    JI = -np.array([[q6 - q1, 0], [0, -(q5 - L2 * c2 - L0) * L2 * s2 + (q6 - L2 * s2) * L2 * c2]])
    return -np.linalg.solve(JD, JI)


@entry("M-10")
def test_m10_second_constraint_with_L0(s57):
    q2 = Q57[1]
    A, P = s57.position("A"), s57.position("P")
    assert close(A, [L0 + L2 * np.cos(q2), L2 * np.sin(q2)])
    assert close(np.linalg.norm(P - A), np.sqrt(0.52))
    assert close(np.linalg.norm(P - s57.position("G1")), 1.0)
    assert close(notes_J(s57) @ U57, s57.velocity("P"))


@entry("M-11")
def test_m11_G2_does_not_move_with_u1():
    assert close(kl.analyze(prrrr(), q=Q57, qd=[1.0, 0.0]).velocity("G2"), [0.0, 0.0])
    assert np.linalg.norm(kl.analyze(prrrr(), q=Q57, qd=[0.0, 1.0]).velocity("G2")) > 0.1


@entry("M-12")
def test_m12_acceleration_of_G1(s57):
    assert close(s57.acceleration("G1"), [0.0, DU57[0]])
    assert abs(DU57[0] - U57[0]) > 0.1                 # printed q1' would give 0.7


@entry("M-13")
def test_m13_centripetal_term_of_the_crank(s57):
    q2, u2, du2 = Q57[1], U57[1], DU57[1]
    i2, j2 = np.array([np.cos(q2), np.sin(q2)]), np.array([-np.sin(q2), np.cos(q2)])
    a = s57.acceleration("G2")
    assert close([a @ i2, a @ j2], [-L2_TILDE * u2**2, L2_TILDE * du2])   # 2_a_G2 = l2~(-u2², u2')
    m2, g = 1.7, 9.81
    right = -m2 * g * np.sin(q2) - m2 * (a @ i2)                           # gravity minus m a, along i2
    assert close(right, -m2 * (g * np.sin(q2) - L2_TILDE * u2**2))
    assert abs(right - (-m2 * (g * np.sin(q2) + L2_TILDE * u2**2))) > 0.1


@entry("M-14")
def test_m14_C_is_eq_60(s57):
    C = np.vstack([np.eye(2), s57.K("P")])
    assert C.shape == (4, 2) and close(C[2:], notes_J(s57))


@entry("M-15")
def test_m15_rotations_about_fixed_axes():
    al, be, ga = 0.1, 0.2, 0.3
    Rx, Ry, Rz = (sp.rotation(a, v).as_matrix() for a, v in (("x", al), ("y", be), ("z", ga)))
    fixed = sp.euler_rotation("zyx", [ga, be, al], axes="fixed").as_matrix()
    assert close(fixed, Rx @ Ry @ Rz)
    assert np.abs(fixed - Rz @ Ry @ Rx).max() > 1e-2
    assert close(fixed[0, 1], -np.cos(be) * np.sin(ga))


@entry("M-16")
def test_m16_rssr_output_frame():
    rssr = sp.RSSR(H1=1.0, L1=0.2, L0=1.0, L2=1.3, H3=0.8, L3=0.3).positions(0.4)
    Tr = sp.compose(sp.translation([-0.5, 0.0, 0.0]), sp.translation([0.0, 1.0, 0.0]))
    rB3 = [0.5, -0.3, 0.8]
    for t3, B in zip(rssr.theta3, rssr.B):
        Rot = sp.homogeneous(sp.rotation("x", t3), [0.0, 0.0, 0.0])
        assert close(sp.transform_points(sp.compose(Tr, Rot), rB3), B)
        assert np.linalg.norm(sp.transform_points(sp.compose(Rot, Tr), rB3) - B) > 1e-2
        # B as printed: (0, L0 - L3 c3 - H3 s3, -L3 s3 + H3 c3)
        assert close(B, [0.0, 1.0 - 0.3 * np.cos(t3) - 0.8 * np.sin(t3),
                         -0.3 * np.sin(t3) + 0.8 * np.cos(t3)])


@entry("M-17")
def test_m17_rrr_has_four_solutions():
    P = [np.sqrt(2) / 4, np.sqrt(2) / 4, 1 + np.sqrt(3) / 2]
    robot = sp.rrr(1.0, 1.0)
    q = np.degrees(robot.inverse(P))
    assert close(q, [[-45, 90, -30], [-45, 60, 30], [135, 90, 30], [135, 120, -30]], 1e-9)
    for row in np.radians(q):
        assert close(robot.forward(row), P)
    rho = np.cos(np.radians(90)) + np.cos(np.radians(120))               # back solutions: rho < 0
    assert rho < 0 and close(-np.sin(np.radians(135)) * rho, P[0])


@entry("M-18")
def test_m18_leg_lengths_for_item_b():
    r3 = np.sqrt(3)
    base = np.array([[-0.5, 0, 0], [-0.5, 0, 0], [0.5, 0, 0], [0.5, 0, 0], [0, r3 / 2, 0], [0, r3 / 2, 0]])
    top = np.array([[0, 0, 0], [0.2, 0, 0], [0.2, 0, 0], [0.1, 0.1 * r3, 0], [0.1, 0.1 * r3, 0], [0, 0, 0]])
    R = sp.euler_rotation("zx", [15.0, 30.0], axes="moving", degrees=True)
    d = sp.stewart_leg_lengths(base, top, [0.2, 0.0, 0.866], R)
    # item b's pose: Trans(0.866, z0) Trans(0.2, x0), then 15° about z, 30° about the new x
    Rm = sp.rotation("z", np.radians(15.0)).as_matrix() @ sp.rotation("x", np.radians(30.0)).as_matrix()
    by_hand = np.linalg.norm([0.2, 0.0, 0.866] + top @ Rm.T - base, axis=1)
    assert close(d, by_hand)
    assert close(d, [1.113533, 1.245157, 0.874097, 0.997642, 1.207177, 1.24095], 5e-7)


# -- The pages and this file list the same entries --------------------------------------------

def entries(page):
    return ENTRY.findall((DOCS / page).read_text(encoding="utf-8"))


def test_both_pages_list_the_same_entries_in_order():
    en, pt = entries("errata.md"), entries("errata.pt.md")
    assert en == pt
    assert len(en) == len(set(en)) and en[0] == "FC-1"


def test_every_entry_is_tested():
    assert set(entries("errata.md")) == TESTED
