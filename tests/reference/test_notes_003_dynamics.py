"""*Mecanismos*, §5 (Gibbs-Appell / Kane): the notes' examples, derived by kinelab from the model.

Each printed formula was re-derived by hand before use (see the comments); kinelab never
sees the formulas: it builds the equations from the mechanism, its masses and its loads.
"""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import kinelab as kl
from kinelab.dynamics import Loads, MassProperties, PointForce, inverse, simulate
from tests.dynamics.models import ENGINE, PRRRR, circle_point, engine, pendulum, pr_robot, prrrr, rp_robot

g = 9.81
rng = np.random.default_rng(3)


def test_pendulum_holding_torque_is_m_g_L_cos_theta():
    """§5.3: e = dvG/du . (-m g j) + dw/du . (tau k) = 0 gives tau = m g L cos(theta)."""
    m, L = 2.0, 0.5
    theta = np.linspace(-np.pi, np.pi, 73)
    res = inverse(pendulum(length=L, mass=m), theta, loads=Loads(gravity=(0.0, -g)))
    np.testing.assert_allclose(res.input_forces[:, 0], m * g * L * np.cos(theta), rtol=0, atol=1e-12)


def test_pendulum_swinging_adds_the_inertia_about_the_pivot():
    # beyond the notes' static case: tau = (I + m L^2) theta'' + m g L cos(theta)
    m, L, I = 2.0, 0.5, 0.01
    theta, w, a = rng.uniform(-3, 3, 50), rng.uniform(-5, 5, 50), rng.uniform(-20, 20, 50)
    res = inverse(pendulum(length=L, mass=m, inertia=I), theta, w, a, loads=Loads(gravity=(0.0, -g)))
    expected = (I + m * L ** 2) * a + m * g * L * np.cos(theta)
    np.testing.assert_allclose(res.input_forces[:, 0], expected, rtol=1e-12, atol=1e-12)


# -- §5.5, RP robot ----------------------------------------------------------------------
# The notes' model: only the gripper's mass m2, as a point at G2 (f has zeros for body 1 and
# for the gripper's moment).  Re-derived: a_G2 = (u2' - q2 u1^2) i1 + (2 u1 u2 + q2 u1') j1,
# gravity -g j0 = -g (sin q1 i1 + cos q1 j1), so
#   tau1 = q2 m2 (g cos q1 + 2 u1 u2 + q2 u1'),   tau2 = m2 (g sin q1 + u2' - q2 u1^2)   (as printed).
# Slip in the printed D: the entry [0 q2] is labelled d vG2/d u2; it is d vG2/d u1.
M2 = 2.0


def rp_masses(m):
    return MassProperties.from_model(m, massless=("arm", "gripper"), point_masses={"G2": M2})


def rp_inverse_notes(q1, q2, u1, u2, du1, du2):
    return np.stack([q2 * M2 * (g * np.cos(q1) + 2 * u1 * u2 + q2 * du1),
                     M2 * (g * np.sin(q1) + du2 - q2 * u1 ** 2)], axis=-1)


def random_states(n, lo=(-3.0, 0.2), hi=(3.0, 1.5)):
    q = rng.uniform(lo, hi, (n, 2))
    return q, rng.uniform(-4, 4, (n, 2)), rng.uniform(-10, 10, (n, 2))


def test_rp_robot_inverse_dynamics_notes_5_5():
    m = rp_robot()
    q, qd, qdd = random_states(200)
    res = inverse(m, q, qd, qdd, loads=Loads(gravity=(0.0, -g)), masses=rp_masses(m))
    expected = rp_inverse_notes(*q.T, *qd.T, *qdd.T)
    np.testing.assert_allclose(res.input_forces, expected, rtol=1e-12, atol=1e-11)


def test_rp_robot_direct_dynamics_notes_5_5():
    """The notes' direct dynamics, integrated on their own, against kinelab's simulation."""
    m = rp_robot()
    # a PD law holds the reach near 0.6 m and lifts the arm towards 0.5 rad
    tau1 = "2 * 0.6 * 9.81 * cos(q[0]) + 4 * (0.5 - q[0]) - 1.5 * qd[0]"
    tau2 = "2 * 9.81 * sin(q[0]) + 30 * (0.6 - q[1]) - 4 * qd[1]"
    t_eval = np.linspace(0.0, 2.0, 41)
    sim = simulate(m, (0.0, 2.0), q0=[0.1, 0.8], qd0=[0.5, -0.2], inputs={"shoulder": tau1, "reach": tau2},
                   loads=Loads(gravity=(0.0, -g)), masses=rp_masses(m), t_eval=t_eval, rtol=1e-12, atol=1e-12)

    def notes(t, y):                     # *Mecanismos*, §5.5, "Dinâmica Direta"
        q1, q2, u1, u2 = y
        t1 = 2 * 0.6 * 9.81 * np.cos(q1) + 4 * (0.5 - q1) - 1.5 * u1
        t2 = 2 * 9.81 * np.sin(q1) + 30 * (0.6 - q2) - 4 * u2
        return [u1, u2, (t1 / (q2 * M2) - g * np.cos(q1) - 2 * u1 * u2) / q2,
                t2 / M2 - g * np.sin(q1) + q2 * u1 ** 2]
    ref = solve_ivp(notes, (0.0, 2.0), [0.1, 0.8, 0.5, -0.2], method="DOP853", t_eval=t_eval,
                    rtol=1e-12, atol=1e-12)
    # both integrations at rtol 1e-12: they agree to well under 1e-8
    np.testing.assert_allclose(sim.q, ref.y[:2].T, rtol=0, atol=1e-8)
    np.testing.assert_allclose(sim.qd, ref.y[2:].T, rtol=0, atol=1e-8)


def test_rp_robot_with_arm_mass_and_gripper_inertia():
    # beyond the notes: arm mass m1 at l1 = 0.4 with inertia I1, gripper inertia I2 about G2:
    # tau1 gains (I1 + m1 l1^2 + I2) u1' + m1 g l1 cos q1; tau2 is unchanged
    m = rp_robot(arm_mass=3.0, gripper_inertia=0.02)
    masses = MassProperties.from_model(m)          # gripper: 1 kg at G2 (see the model)
    q, qd, qdd = random_states(50)
    res = inverse(m, q, qd, qdd, loads=Loads(gravity=(0.0, -g)), masses=masses)
    m2 = 1.0
    tau1 = (q[:, 1] * m2 * (g * np.cos(q[:, 0]) + 2 * qd[:, 0] * qd[:, 1] + q[:, 1] * qdd[:, 0])
            + (0.05 + 3.0 * 0.4 ** 2 + 0.02) * qdd[:, 0] + 3.0 * g * 0.4 * np.cos(q[:, 0]))
    tau2 = m2 * (g * np.sin(q[:, 0]) + qdd[:, 1] - q[:, 1] * qd[:, 0] ** 2)
    np.testing.assert_allclose(res.input_forces, np.stack([tau1, tau2], -1), rtol=1e-12, atol=1e-11)


def test_rp_robot_gripper_reaction_is_normal_to_the_arm():
    # Newton for the gripper alone: the slide pushes it across the arm with
    # m2 (a_G2 . j1) + m2 g cos q1 (j1 = (-sin q1, cos q1)); along the arm acts tau2 only
    m = rp_robot()
    q, qd, qdd = random_states(30)
    res = inverse(m, q, qd, qdd, loads=Loads(gravity=(0.0, -g)), masses=rp_masses(m))
    j1 = np.stack([-np.sin(q[:, 0]), np.cos(q[:, 0])], -1)
    normal = M2 * (2 * qd[:, 0] * qd[:, 1] + q[:, 1] * qdd[:, 0]) + M2 * g * np.cos(q[:, 0])
    np.testing.assert_allclose(res.reactions("reach"), normal[:, None] * j1, rtol=1e-12, atol=1e-10)


# -- §5.6, PR robot ----------------------------------------------------------------------
# Re-derived: x_G2 = q1 + L cos q2, so tau1 = (m1 + m2) u1' - m2 L (cos q2 u2^2 + sin q2 u2');
# the moment about S gives tau2 = -m2 L sin q2 u1' + (m2 L^2 + I2) u2' (both as printed; the
# notes leave gravity out here, and so does this test).
PR = dict(m1=3.0, m2=2.0, length=0.6, inertia=0.08)


def pr_inverse_notes(q1, q2, u1, u2, du1, du2, m1=3.0, m2=2.0, L=0.6, I2=0.08):
    return np.stack([(m1 + m2) * du1 + m2 * L * (-np.cos(q2) * u2 ** 2 - np.sin(q2) * du2),
                     m2 * L * (-du1 * np.sin(q2)) + (m2 * L ** 2 + I2) * du2], axis=-1)


def test_pr_robot_inverse_dynamics_notes_5_6():
    q, qd, qdd = random_states(200, lo=(-1.0, -3.0), hi=(1.0, 3.0))
    res = inverse(pr_robot(**PR), q, qd, qdd)
    np.testing.assert_allclose(res.input_forces, pr_inverse_notes(*q.T, *qd.T, *qdd.T),
                               rtol=1e-12, atol=1e-11)


def test_pr_robot_direct_dynamics_notes_5_6():
    """Direct dynamics from the notes' inverse equations (a 2x2 solve), against simulate."""
    tau = {"rail": "-4 * q[0] - 0.5 * qd[0]", "wrist": "0.3 * sin(2 * t)"}
    t_eval = np.linspace(0.0, 3.0, 31)
    sim = simulate(pr_robot(**PR), (0.0, 3.0), q0=[0.2, 0.4], qd0=[0.0, 1.0], inputs=tau,
                   t_eval=t_eval, rtol=1e-12, atol=1e-12)

    def notes(t, y):
        q1, q2, u1, u2 = y
        Mm = np.array([[5.0, -2.0 * 0.6 * np.sin(q2)], [-2.0 * 0.6 * np.sin(q2), 2.0 * 0.36 + 0.08]])
        rhs = np.array([-4 * q1 - 0.5 * u1 + 2.0 * 0.6 * np.cos(q2) * u2 ** 2, 0.3 * np.sin(2 * t)])
        return [u1, u2, *np.linalg.solve(Mm, rhs)]
    ref = solve_ivp(notes, (0.0, 3.0), [0.2, 0.4, 0.0, 1.0], method="DOP853", t_eval=t_eval,
                    rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(sim.q, ref.y[:2].T, rtol=0, atol=1e-8)
    np.testing.assert_allclose(sim.qd, ref.y[2:].T, rtol=0, atol=1e-8)


# -- §5.7, PRRRR with lumped masses ---------------------------------------------------------
# Re-derived from the notes' C^T D f = 0 with J = J_D^-1 R (rows q5, q6 = P; columns q1, q2):
#   tau1 = m1~ (g + u1') - J11 (Fx - m5~ u5') - J21 (Fy - m5~ g - m5~ u6')
#   tau2 = I2~ u2' + m2~ l2~ (g c2 + l2~ u2') - J12 (Fx - m5~ u5') - J22 (Fy - m5~ g - m5~ u6')
# with m1~ = m1 + m3/2, m2~ = m2 + m4/2, m5~ = (m3 + m4)/2, l2~ = (m2 l2 + (m4/2) L2)/m2~.
# Slips found: Phi2 is printed once with "L6" for L0; the first row of D carries a stray 1 under
# d vG2/d u1 (vG2 does not depend on u1); a_G1 is printed as q1' j0 (it is q1'' j0); in f the
# term -m2~(g s2 + l2~ u2^2) should read -m2~(g s2 - l2~ u2^2) (harmless: D multiplies it by 0).
# The notes' I2 must be the *lumped* body's own centroidal inertia
# I2~ = I2 + m2 (l2 - l2~)^2 + (m4/2)(L2 - l2~)^2; read as link 2's I2 the torque would miss
# m2 l2^2 + (m4/2) L2^2 - m2~ l2~^2 times u2'.
F = (30.0, -12.0)


def prrrr_notes(q, qd, qdd):
    p = PRRRR
    q1, q2 = q.T
    u1, u2 = qd.T
    du1, du2 = qdd.T
    c2, s2 = np.cos(q2), np.sin(q2)
    A = np.stack([p["L0"] + p["L2"] * c2, p["L2"] * s2], -1)
    G1 = np.stack([0 * q1, q1], -1)
    q5, q6 = circle_point(G1, A, p["L3"], p["L4"], +1.0).T
    JD = np.stack([np.stack([q5, q6 - q1], -1),
                   np.stack([q5 - p["L2"] * c2 - p["L0"], q6 - p["L2"] * s2], -1)], -2)
    R = np.zeros_like(JD)
    R[:, 0, 0] = q6 - q1
    R[:, 1, 1] = -(q5 - p["L2"] * c2 - p["L0"]) * p["L2"] * s2 + (q6 - p["L2"] * s2) * p["L2"] * c2
    J = np.linalg.solve(JD, R)
    u5, u6 = np.einsum("nij,nj->ni", J, qd).T
    # P's acceleration from the second derivatives of the two constraints
    dxA, dyA = -p["L2"] * s2 * u2, p["L2"] * c2 * u2
    ddxA = -p["L2"] * c2 * u2 ** 2 - p["L2"] * s2 * du2
    ddyA = -p["L2"] * s2 * u2 ** 2 + p["L2"] * c2 * du2
    rhs = np.stack([(q6 - q1) * du1 - u5 ** 2 - (u6 - u1) ** 2,
                    (q5 - A[:, 0]) * ddxA + (q6 - A[:, 1]) * ddyA - (u5 - dxA) ** 2 - (u6 - dyA) ** 2], -1)
    du5, du6 = np.linalg.solve(JD, rhs[..., None])[..., 0].T
    m1t, m2t, m5t = p["m1"] + p["m3"] / 2, p["m2"] + p["m4"] / 2, (p["m3"] + p["m4"]) / 2
    l2t = (p["m2"] * p["l2"] + p["m4"] / 2 * p["L2"]) / m2t
    I2t = p["I2"] + p["m2"] * (p["l2"] - l2t) ** 2 + p["m4"] / 2 * (p["L2"] - l2t) ** 2
    fx, fy = F[0] - m5t * du5, F[1] - m5t * g - m5t * du6
    tau1 = m1t * g + m1t * du1 - J[:, 0, 0] * fx - J[:, 1, 0] * fy
    tau2 = I2t * du2 + m2t * l2t * (g * c2 + du2 * l2t) - J[:, 0, 1] * fx - J[:, 1, 1] * fy
    naive = p["m2"] * p["l2"] ** 2 + p["m4"] / 2 * p["L2"] ** 2 - m2t * l2t ** 2
    return np.stack([tau1, tau2], -1), naive


def prrrr_motion(n=80):
    t = np.linspace(0.0, 4.0, n)
    q = np.stack([0.2 + 0.1 * np.sin(t), 1.2 + 0.3 * np.sin(1.3 * t)], -1)
    qd = np.stack([0.1 * np.cos(t), 0.39 * np.cos(1.3 * t)], -1)
    qdd = np.stack([-0.1 * np.sin(t), -0.507 * np.sin(1.3 * t)], -1)
    return q, qd, qdd


def test_prrrr_lumped_masses_notes_5_7():
    m = prrrr()
    lumped = MassProperties.from_model(m).lumped(m, ["bar3", "bar4"])
    loads = Loads(gravity=(0.0, -g), forces=[PointForce("P", F)])
    q, qd, qdd = prrrr_motion()
    res = inverse(m, q, qd, qdd, loads=loads, masses=lumped)
    expected, naive = prrrr_notes(q, qd, qdd)
    np.testing.assert_allclose(res.input_forces, expected, rtol=1e-11, atol=1e-10)
    assert naive > 1e-3          # reading I2 as link 2's own inertia would be visibly wrong


def test_prrrr_lumping_is_statically_exact():
    """Two-point lumping keeps each bar's mass and centre of mass: at rest, under gravity
    and F, the lumped and the distributed models need the same efforts."""
    m = prrrr()
    loads = Loads(gravity=(0.0, -g), forces=[PointForce("P", F)])
    q, _, _ = prrrr_motion(20)
    whole = inverse(m, q, loads=loads)
    lumped = inverse(m, q, loads=loads, masses=MassProperties.from_model(m).lumped(m, ["bar3", "bar4"]))
    np.testing.assert_allclose(lumped.input_forces, whole.input_forces, rtol=1e-12, atol=1e-11)


# -- a slider-crank engine: distributed masses and a gas force ----------------------------------
def engine_lagrange():
    """tau(theta, w, a, F) of the engine by Lagrange's equations, derived here with sympy from
    explicit closed-form kinematics: nothing of kinelab's engine or of Kane's method."""
    import sympy as sp
    p = ENGINE
    t = sp.Symbol("t")
    th = sp.Function("theta")(t)
    r, l, e = p["crank"], p["rod"], p["offset"]
    A = sp.Matrix([r * sp.cos(th), r * sp.sin(th)])
    xB = r * sp.cos(th) + sp.sqrt(l ** 2 - (e - r * sp.sin(th)) ** 2)
    B = sp.Matrix([xB, e])
    phi = sp.atan2(e - r * sp.sin(th), xB - r * sp.cos(th))
    G2 = A * p["crank_cg"] / r
    G3 = A + (B - A) * p["rod_cg"] / l
    T = (p["crank_mass"] * G2.diff(t).dot(G2.diff(t)) + p["crank_inertia"] * th.diff(t) ** 2
         + p["rod_mass"] * G3.diff(t).dot(G3.diff(t)) + p["rod_inertia"] * phi.diff(t) ** 2
         + p["piston_mass"] * xB.diff(t) ** 2) / 2
    V = g * (p["crank_mass"] * G2[1] + p["rod_mass"] * G3[1] + p["piston_mass"] * e)
    Fx = sp.Symbol("Fx")
    w, a = sp.symbols("w a")
    lag = (T.diff(th.diff(t)).diff(t) - T.diff(th) + V.diff(th) - Fx * xB.diff(th))
    lag = lag.subs(th.diff(t, 2), a).subs(th.diff(t), w).subs(th, sp.Symbol("q"))
    return sp.lambdify((sp.Symbol("q"), w, a, Fx), lag, "numpy")


def gas_table():
    """Cylinder pressure over a four-stroke cycle (0..4 pi of crank angle), Pa: a smooth peak
    after top dead centre on the power stroke.  Top dead centre is at q = 0 (B farthest out)."""
    x = np.linspace(0.0, 4 * np.pi, 181)
    p = 1e5 + 4e6 * np.exp(-((x - 2 * np.pi - 0.25) / 0.45) ** 2)
    return {"of": "q", "x": x.tolist(), "y": p.tolist(), "period": 4 * np.pi}


def test_engine_with_gas_force_against_lagrange():
    m = engine()
    area = np.pi * ENGINE["bore"] ** 2 / 4
    table = gas_table()
    # the gas pushes the piston towards the crank (-x): F = -p A, a table over the cycle,
    # given as a model file's [dynamics] section would give it
    force = {**table, "y": [-area * v for v in table["y"]]}
    loads = Loads.from_dict({"gravity": [0.0, -g],
                             "forces": [{"point": "B", "link": "slider", "fx": force, "fy": 0.0}]})
    theta = np.linspace(0.0, 4 * np.pi, 721)
    w, a = 300.0, 50.0
    res = inverse(m, theta, w, a, loads=loads)
    Fx = -area * np.interp(theta, table["x"], table["y"], period=4 * np.pi)
    expected = engine_lagrange()(theta, w, a, Fx)
    scale = np.max(np.abs(expected))
    np.testing.assert_allclose(res.input_forces[:, 0], expected, rtol=0, atol=1e-11 * scale)
    # the same through Kane's generalized forces and the free-body equations of every link
    np.testing.assert_allclose(res.newton_euler_efforts, res.input_forces, rtol=0, atol=1e-11 * scale)
