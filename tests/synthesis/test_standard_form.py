"""Three positions in Erdman and Sandor's standard form: the crank's and the rocker's
rotations given, W (e^{i beta_j} - 1) + Z (e^{i alpha_j} - 1) = delta_j solved for each dyad."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import three_positions

from .helpers import engine_pose_errors, wrap

FOURBARS = [
    dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5, coupler_point=(1.5, 1.0)),
    dict(ground=2.0, crank=0.7, coupler=2.2, rocker=1.6, coupler_point=(0.4, -0.8)),
    dict(ground=4.0, crank=1.5, coupler=3.5, rocker=3.0, coupler_point=(2.0, 1.5)),
]


@pytest.mark.parametrize("dims", FOURBARS)
@pytest.mark.parametrize("q_deg", [(0.0, 30.0, 60.0), (200.0, 150.0, 110.0), (10.0, 95.0, 170.0)])
@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_rotations_of_a_catalogue_linkage_give_it_back(dims, q_deg, branch):
    fb = kl.mechanisms.fourbar(branch=branch, **dims)
    q = np.radians(q_deg)
    s = kl.analyze(fb, q=q)
    th4 = s.angle("rocker")
    beta = (q[1:] - q[0], th4[1:] - th4[0])
    sol = three_positions(s.position("P"), s.angle("coupler"), beta=beta)
    # the pivots are the catalogue's (closed form against the engine's positions)
    np.testing.assert_allclose(sol.A0, s.position("O2")[0], atol=1e-9)
    np.testing.assert_allclose(sol.B0, s.position("O4")[0], atol=1e-9)
    np.testing.assert_allclose(sol.A1, s.position("A")[0], atol=1e-9)
    np.testing.assert_allclose(sol.B1, s.position("B")[0], atol=1e-9)
    # moved by the engine, the synthesized linkage carries the coupler through the poses ...
    dpos, dang = engine_pose_errors(sol.model, sol.q, s.position("P"), s.angle("coupler"))
    assert dpos.max() < 1e-9 * 4.0 and dang.max() < 1e-9
    # ... while its crank turns by beta_2, beta_3 and its rocker by gamma_2, gamma_3
    e = kl.analyze(sol.model, q=sol.q)
    np.testing.assert_allclose(wrap(e.angle("crank")[1:] - e.angle("crank")[0] - beta[0]), 0.0,
                               atol=1e-9)
    np.testing.assert_allclose(wrap(e.angle("rocker")[1:] - e.angle("rocker")[0] - beta[1]),
                               0.0, atol=1e-9)


def test_worked_by_hand():
    # crank A0 = (0, 0) -> A1 = (1, 0) (W = 1), coupler vector Z = i to P1 = (1, 1).  Turning
    # the crank by 90 and 180 deg and the coupler by 0 and 90 deg:
    #   P2 = A0 + W i + Z = (0, 2),   P3 = A0 - W + Z i = (-2, 0)
    sol = three_positions([(1, 1), (0, 2), (-2, 0)], [0, 90], B0=(3, 0),
                          beta=((90, 180), None), degrees=True)
    np.testing.assert_allclose(sol.A0, [0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(sol.A1, [1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(np.degrees(wrap(sol.q - sol.q[0])), [0.0, 90.0, 180.0], atol=1e-12)
    # the rocker dyad, from B0 by Suh and Radcliffe, keeps its length in the three positions
    Bj = kl.synthesis.Positions([(1, 1), (0, 2), (-2, 0)], [0, 90], degrees=True).carry(sol.B1)
    r = np.linalg.norm(Bj - sol.B0, axis=1)
    np.testing.assert_allclose(r, r[0], rtol=1e-12)


def test_both_dyads_by_rotations_the_hand_check_of_the_docs():
    # Mecanismos §6.5's positions; crank -30, -75 deg, rocker 15, 30 deg
    P, alpha = [(1, 1), (2, 0.5), (3, 1.5)], [0, 45]
    sol = three_positions(P, alpha, beta=((-30, -75), (15, 30)), degrees=True)
    assert sol.valid
    # the standard form itself, with the pivots found: P_j = A0 + W e^{i beta_j} + Z e^{i alpha_j}
    z = lambda v: complex(*v)                                     # noqa: E731
    for X0, X1, turns in ((sol.A0, sol.A1, (-30, -75)), (sol.B0, sol.B1, (15, 30))):
        W, Z = z(X1) - z(X0), z(P[0]) - z(X1)
        for Pj, b, a in zip(P[1:], np.radians(turns), np.radians(alpha)):
            assert abs(z(X0) + W * np.exp(1j * b) + Z * np.exp(1j * a) - z(Pj)) < 1e-12
    dpos, dang = engine_pose_errors(sol.model, sol.q, np.array(P, float), np.radians([0, 0, 45]))
    assert dpos.max() < 1e-9 and dang.max() < 1e-9


def test_degrees_and_radians_and_pivot_forms_agree():
    P, alpha = [(1, 1), (2, 0.5), (3, 1.5)], [0, 45]
    a = three_positions(P, alpha, beta=((-30, -75), (15, 30)), degrees=True)
    b = three_positions(P, np.radians(alpha), beta=np.radians([[-30, -75], [15, 30]]))
    np.testing.assert_allclose(b.A0, a.A0, atol=1e-12)
    np.testing.assert_allclose(b.B1, a.B1, atol=1e-12)
    # the crank's pair alone, the rocker by its fixed pivot: the same linkage
    c = three_positions(P, alpha, B0=a.B0, beta=(-30, -75), degrees=True)
    np.testing.assert_allclose(c.A1, a.A1, atol=1e-12)
    np.testing.assert_allclose(c.B1, a.B1, atol=1e-9)
    # and by its fixed pivot A0 (Suh-Radcliffe) the crank's moving pivot is the same
    d = three_positions(P, alpha, A0=a.A0, beta=(None, (15, 30)), degrees=True)
    np.testing.assert_allclose(d.A1, a.A1, atol=1e-9)


@pytest.mark.parametrize("kwargs, message", [
    (dict(beta=(10, 20, 30)), r"^beta: expected the crank's rotations \(beta_2, beta_3\), or one "
     r"pair for each dyad"),
    (dict(beta=(None, None)), r"^beta: expected the crank's rotations"),
    (dict(beta=((10, 20, 30), None), B0=(0, 0)), r"^beta\[0\]: expected two rotations"),
    (dict(beta=((10, "x"), None), B0=(0, 0)), r"^beta\[0\]: expected real numbers"),
    (dict(beta=((10, np.inf), None), B0=(0, 0)), r"^beta\[0\]\[1\]: expected finite angles"),
    (dict(beta=(10, 20), A0=(5, 0), B0=(0, 0)),
     r"^A0, A1, beta\[0\]: give exactly one of the fixed pivot A0, the moving pivot A1 and the "
     r"rotations beta\[0\], got A0 and beta\[0\]$"),
    (dict(beta=((0, 0), None), B0=(0, 0)), r"^beta\[0\]: these rotations of the crank and the "
     r"coupler's rotations alpha_2, alpha_3 do not fix the dyad"),
    (dict(beta=(None, (0, 45)), A0=(5, 0)), r"^beta\[1\]: these rotations of the rocker"),
    (dict(beta=(10, 20), B0=(0, 0), degrees="yes"), r"^degrees: "),
])
def test_bad_rotations_one_line_naming_the_field(kwargs, message):
    with pytest.raises(ModelError, match=message) as info:
        three_positions([(1, 1), (2, 0.5), (3, 1.5)], [0, 45], **{"degrees": True, **kwargs})
    assert "\n" not in str(info.value)


def test_against_the_real_four_by_four_system_of_the_textbooks():
    # Norton's form of the task (Design of Machinery, ch. 5; numbers of our own): P1 at the
    # origin, P21 = p21 at angle d2, P31 = p31 at angle d3, coupler rotations a2, a3, crank
    # rotations b2, b3.  Written in real components (W = (W1x, W1y), Z = (Z1x, Z1y)), the two
    # complex equations are four real ones, solved here with numpy alone.
    p21, d2, p31, d3 = 2.1, np.radians(-25.0), 3.4, np.radians(15.0)
    a2, a3, b2, b3 = np.radians([20.0, 55.0, 40.0, 95.0])
    rows, rhs = [], []
    for a, b, p, d in ((a2, b2, p21, d2), (a3, b3, p31, d3)):
        rows += [[np.cos(b) - 1, -np.sin(b), np.cos(a) - 1, -np.sin(a)],
                 [np.sin(b), np.cos(b) - 1, np.sin(a), np.cos(a) - 1]]
        rhs += [p * np.cos(d), p * np.sin(d)]
    Wx, Wy, Zx, Zy = np.linalg.solve(np.array(rows), np.array(rhs))
    P = [(0.0, 0.0), (p21 * np.cos(d2), p21 * np.sin(d2)), (p31 * np.cos(d3), p31 * np.sin(d3))]
    sol = three_positions(P, [a2, a3], beta=((b2, b3), (-0.3, -0.5)))
    np.testing.assert_allclose(sol.A1, [-Zx, -Zy], atol=1e-12)
    np.testing.assert_allclose(sol.A0, [-Zx - Wx, -Zy - Wy], atol=1e-12)
    np.testing.assert_allclose(wrap(sol.q[1:] - sol.q[0]), [b2, b3], atol=1e-12)
    # a crank-rocker that reaches the poses on one branch (its transmission angle is poor)
    assert not (sol.branch_defect or sol.order_defect or sol.circuit_defect)
    dpos, dang = engine_pose_errors(sol.model, sol.q, np.array(P), np.array([0.0, a2, a3]))
    assert dpos.max() < 1e-9 and dang.max() < 1e-9
