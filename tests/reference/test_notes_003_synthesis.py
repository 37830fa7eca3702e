"""*Mecanismos*, §6: the notes' worked examples of dimensional synthesis, checked.

The notes work in m (§6.5) and cm (§6.7, §6.8); the synthesis is scale-free, so the cm
examples are run in metres (every length times 0.01) and compared in metres.

Every tolerance is derived, not chosen: a printed output is rounded to its last digit
(half a unit of it), and where the notes' *inputs* are rounded too, the output may move by
first-order sensitivity x half a unit of each input (central differences of our own
synthesis, summed in absolute value as a worst case).
"""
import numpy as np
import pytest

from kinelab.synthesis import center_points, four_positions, moving_pivot, three_positions
from tests.synthesis.helpers import engine_pose_errors

CM = 0.01


def rounding_bound(f, x0, half_units, h=1e-7):
    """Worst first-order change of f(x) when each x_i moves by up to half_units[i]."""
    x0 = np.asarray(x0, float)
    J = np.array([(f(x0 + h * e) - f(x0 - h * e)) / (2 * h) for e in np.eye(x0.size)])
    return np.abs(J).T @ np.asarray(half_units, float)


# -- §6.5, Tables 2-4: A0 = (5, 0), B0 = (0, 0) m --------------------------------------------
def test_notes_003_table_4():
    # P and alpha are exact decimals; Table 4 rounds to 1 mm: half a unit = 0.0005 m.
    # Exact: A1 = (3.547722, -1.654555), B1 = (0.994078, 3.238155) (by hand from eq. 68).
    sol = three_positions([(1.0, 1.0), (2.0, 0.5), (3.0, 1.5)], [0.0, 45.0], (5.0, 0.0), (0.0, 0.0),
                          degrees=True)
    np.testing.assert_allclose(sol.A1, [3.548, -1.655], atol=0.0005 + 1e-12)
    np.testing.assert_allclose(sol.B1, [0.994, 3.238], atol=0.0005 + 1e-12)
    assert sol.valid and sol.grashof.kind == "crank-rocker"
    dpos, dang = engine_pose_errors(sol.model, sol.q, sol.points, sol.alpha)
    assert dpos.max() < 1e-9 and dang.max() < 1e-9


# -- §6.7, Tables 5-7: four positions, a0x = -20.195, b0x = -29.167 cm ---------------------------
P7 = np.array([(0.0, 0.0), (5.0, 8.0), (10.0, 15.0), (18.0, 20.0)]) * CM
ALPHA7 = np.radians([10.0, 20.0, 30.0])          # alpha_2..alpha_4 from position 1 (alpha_1 = 0)
TABLE_7 = np.array([-20.195, 25.566, -29.167, 42.355, -25.349, 25.379, -37.086, 36.093]) * CM


def test_notes_003_eq_71_has_three_real_roots_for_each_abscissa():
    # the determinant condition is a cubic in a0y; here all three roots are real
    assert len(center_points(P7, ALPHA7, a0x=-20.195 * CM)) == 3
    assert len(center_points(P7, ALPHA7, a0x=-29.167 * CM)) == 3
    assert len(four_positions(P7, ALPHA7, -20.195 * CM, -29.167 * CM)) == 9


def _table_7_solution(a0x, b0x):
    sols = four_positions(P7, ALPHA7, a0x, b0x)
    return min(sols, key=lambda s: np.linalg.norm(np.r_[s.A0, s.B0] - TABLE_7[:4]))


def test_notes_003_table_7():
    sol = _table_7_solution(-20.195 * CM, -29.167 * CM)
    got = np.concatenate([sol.A0, sol.B0, sol.A1, sol.B1])

    def f(x):          # the same pivots without building and checking all nine linkages
        A0, B0 = (min(center_points(P7, ALPHA7, a0x=v), key=lambda c: abs(c[1] - t))
                  for v, t in zip(x, TABLE_7[[1, 3]]))
        return np.concatenate([A0, B0, moving_pivot(P7, ALPHA7, fixed=A0),
                               moving_pivot(P7, ALPHA7, fixed=B0)])
    np.testing.assert_allclose(f([-20.195 * CM, -29.167 * CM]), got, atol=1e-12)
    # a0x and b0x are printed to 0.001 cm, and so is every output
    tol = rounding_bound(f, [-20.195 * CM, -29.167 * CM], [0.0005 * CM] * 2) + 0.0005 * CM
    assert np.all(np.abs(got - TABLE_7) <= tol + 1e-12)
    # the notes' linkage is usable: no branch or order defect, reached by the engine
    assert sol.valid and sol.grashof.kind == "crank-rocker"
    dpos, dang = engine_pose_errors(sol.model, sol.q, sol.points, sol.alpha)
    assert dpos.max() < 1e-9 and dang.max() < 1e-9


# -- §6.8, Tables 8-10: exercise, A0 = (-16.06, 23.8), B0 = (-9.2, 36.9) cm ------------------------
P8 = np.array([(-19.21, -1.62), (-19.37, 12.18), (-13.33, 54.60)])
ALPHA8 = np.array([-13.86, -179.01])
A0_8, B0_8 = np.array([-16.06, 23.8]), np.array([-9.2, 36.9])
TABLE_10 = np.array([-68.37, 27.52, -54.13, 51.87])
# half a unit of the last printed digit of P (cm), alpha (deg), A0 and B0 (cm)
HALF_8 = np.r_[[0.005] * 6, [0.005] * 2, 0.005, 0.05, 0.05, 0.05]


def _exercise(x):
    """A1 and B1 (cm) of the exercise, by eq. 68, from its inputs (cm and deg)."""
    P, alpha, A0, B0 = x[:6].reshape(3, 2) * CM, np.radians(x[6:8]), x[8:10], x[10:12]
    return np.concatenate([moving_pivot(P, alpha, fixed=A0 * CM),
                           moving_pivot(P, alpha, fixed=B0 * CM)]) / CM


def test_notes_003_table_10_within_what_its_rounded_inputs_allow():
    x0 = np.concatenate([P8.ravel(), ALPHA8, A0_8, B0_8])
    exact = _exercise(x0)
    # Exact answer from the printed inputs: A1 = (-68.649, 27.568), B1 = (-54.124, 51.861) cm.
    # The printed A1 is 0.28 cm off; A1 is very sensitive to the inputs (75 cm per cm of
    # a0x), and the inputs' rounding allows about 2 cm, so the table is consistent with them.
    np.testing.assert_allclose(exact, [-68.6485, 27.5683, -54.1241, 51.8614], atol=5e-4)
    tol = rounding_bound(_exercise, x0, HALF_8) + 0.005
    assert np.all(np.abs(exact - TABLE_10) <= tol)
    assert np.abs(exact - TABLE_10)[0] > 0.25          # the slip the tolerance has to absorb
    sol = three_positions(P8 * CM, ALPHA8, A0_8 * CM, B0_8 * CM, degrees=True)
    np.testing.assert_allclose(np.concatenate([sol.A1, sol.B1]) / CM, exact, atol=1e-12)
    assert sol.valid
    dpos, dang = engine_pose_errors(sol.model, sol.q, sol.points, sol.alpha)
    assert dpos.max() < 1e-9 and dang.max() < 1e-9


@pytest.mark.parametrize("method", ["suh-radcliffe", "poles"])
def test_notes_003_table_4_by_both_methods(method):
    """§6.2 (Burmester's poles) and §6.4 (Suh-Radcliffe) give the same moving pivots; with
    alpha_2 = 0 the pole P12 is at infinity and the construction uses its limit."""
    P, alpha = [(1.0, 1.0), (2.0, 0.5), (3.0, 1.5)], np.radians([0.0, 45.0])
    np.testing.assert_allclose(moving_pivot(P, alpha, fixed=(5.0, 0.0), method=method),
                               [3.5477224, -1.6545552], atol=1e-7)
    np.testing.assert_allclose(moving_pivot(P, alpha, fixed=(0.0, 0.0), method=method),
                               [0.9940777, 3.2381554], atol=1e-7)
