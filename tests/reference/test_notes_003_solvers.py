"""Worked examples of *Mecanismos*, §4.5-4.7: the solvers.

Every printed number was recomputed before being used here; where the notes slip, the test
holds the verified value and says what the notes print.
"""
from decimal import Decimal

import numpy as np
import pytest
import sympy as sp

from kinelab.solvers import dialytic, half_angle, newton

# --- §4.5, Ex. 4.2: four-bar L1 = 2, L2 = L3 = L4 = 1, θ2 = 0 -------------------------------


def fourbar_EFG(L1, L2, L3, L4, th2):
    """Eq. 26, derived again: isolate L3 cos θ3, L3 sin θ3 in eqs. 25, square, add, ÷ L4²."""
    E = 2 * L1 / L4 - 2 * L2 / L4 * np.cos(th2)
    F = -2 * L2 / L4 * np.sin(th2)
    G = (L1**2 + L2**2 + L4**2 - L3**2 - 2 * L1 * L2 * np.cos(th2)) / L4**2
    return E, F, G


def test_ex_4_2_fourbar_by_half_angle():
    L1, L2, L3, L4 = 2.0, 1.0, 1.0, 1.0
    E, F, G = fourbar_EFG(L1, L2, L3, L4, 0.0)
    assert (E, F, G) == (2.0, 0.0, 1.0)               # as printed: E = 2, F = 0, G = 1
    sol = half_angle(E, F, G)
    # Printed: u = ±√3, θ4 = ±120°.  "+" branch first: θ4 = -120°.
    assert sol.count == 2
    assert np.degrees(sol.theta) == pytest.approx([-120.0, 120.0], abs=1e-12)
    assert np.tan(sol.theta / 2) == pytest.approx([-np.sqrt(3), np.sqrt(3)], rel=1e-14)
    # θ3 from eqs. 25 (printed: θ3 = ±60°, with the sign of θ4), then the loop closes.
    th4 = sol.theta
    th3 = np.arctan2(L4 * np.sin(th4) - L2 * 0.0, L1 + L4 * np.cos(th4) - L2 * 1.0)
    assert np.degrees(th3) == pytest.approx([-60.0, 60.0], abs=1e-12)
    closure = (L2 + L3 * np.exp(1j * th3)) - (L1 + L4 * np.exp(1j * th4))
    assert np.all(np.abs(closure) < 1e-15)


def test_ex_4_2_coefficients_hold_over_a_cycle():
    # Independent check of eq. 26: at every crank angle both roots close the loop.
    L1, L2, L3, L4 = 3.0, 1.0, 3.0, 2.5
    th2 = np.linspace(-np.pi, np.pi, 73)
    sol = half_angle(*fourbar_EFG(L1, L2, L3, L4, th2))
    assert np.all(sol.count == 2)
    B = L1 + L4 * np.exp(1j * sol.theta)                  # (73, 2) rocker tip
    A = (L2 * np.exp(1j * th2))[:, None]
    assert np.max(np.abs(np.abs(B - A) - L3)) < 1e-13      # coupler length kept


def test_case_G_equal_E_loses_theta_pi():
    # §4.5 case 1 (G = E) gives one root, u = -(G + E)/(2F); θ = π also solves eq. 23 then
    # (E cos π + G = 0), which the substitution u = tan(θ/2) cannot reach.  half_angle
    # returns both.
    E, F, G = 1.5, -0.5, 1.5
    sol = half_angle(E, F, G)
    assert sol.count == 2
    u_notes = -(G + E) / (2 * F)
    assert np.sort(sol.theta) == pytest.approx(np.sort([2 * np.arctan(u_notes), np.pi]),
                                               abs=1e-15)


# --- §4.6, Ex. 4.3: dialytic elimination ---------------------------------------------------
# Checked: eq. 36 (det M in terms of A … E) expands to the determinant of eq. 35's M; eq. 37
# is det M for eqs. 27-28, sign included; its roots and y = (10x - 8)/(6x) (eq. 27 minus
# 5 x eq. 28) are right to the digits printed.  No slip found.

x, y = sp.symbols("x y")
ELLIPSE = 5 * x**2 + 5 * y**2 - 6 * x * y - 8       # eq. 27
CIRCLE = x**2 + y**2 - 2 * x                        # eq. 28


@pytest.fixture(scope="module")
def ex_4_3():
    return dialytic(ELLIPSE, CIRCLE)


def test_ex_4_3_matrix_and_eliminant(ex_4_3):
    A, B, C, D, E = 5, -6 * x, 5 * x**2 - 8, 1, x**2 - 2 * x       # eqs. 31-32
    M = sp.Matrix([[0, A, B, C], [0, D, 0, E], [A, B, C, 0], [D, 0, E, 0]])   # eq. 35
    assert ex_4_3.matrix.equals(M)
    eq_36 = -(A * E) ** 2 + A * C * D * E - B**2 * D * E + D * C * (A * E - C * D)
    assert sp.expand(eq_36 - ex_4_3.eliminant.as_expr()) == 0
    # Eq. 37, exactly as printed (sign and all): -36x⁴ + 72x³ - 100x² + 160x - 64.
    assert ex_4_3.eliminant.all_coeffs() == [-36, 72, -100, 160, -64]
    # Against sympy's resultant (subresultants, another method): equal up to sign.
    assert sp.expand(sp.resultant(ELLIPSE, CIRCLE, y) + ex_4_3.eliminant.as_expr()) == 0


def test_ex_4_3_all_four_solutions(ex_4_3):
    # Printed: x = (0.5237, 1.5734, -0.0486 + 1.468j, -0.0486 - 1.468j), to the digits shown.
    assert ex_4_3.real.tolist() == [True, True, False, False]
    assert ex_4_3.x.real[:2] == pytest.approx([0.5237, 1.5734], abs=5e-5)
    assert ex_4_3.x[2:] == pytest.approx([-0.0486 - 1.468j, -0.0486 + 1.468j], abs=5e-4)
    # y from the notes' back-substitution, y = (10x - 8)/(6x), for all four.
    assert ex_4_3.y == pytest.approx((10 * ex_4_3.x - 8) / (6 * ex_4_3.x), rel=1e-13)
    # Checked by substitution: 1e-13, the rounding of quartic roots of size ~1.
    assert np.all(ex_4_3.residual < 1e-13)
    for xi, yi in zip(ex_4_3.x, ex_4_3.y):
        assert abs(complex(ELLIPSE.subs({x: xi, y: yi}))) < 1e-13
        assert abs(complex(CIRCLE.subs({x: xi, y: yi}))) < 1e-13


def test_ex_4_3_real_points_are_where_the_ellipse_meets_the_circle(ex_4_3):
    # The circle is (x - 1)² + y² = 1: parametrise it and find the ellipse's sign changes.
    t = np.linspace(-np.pi, np.pi, 200001)
    cx, cy = 1 + np.cos(t), np.sin(t)
    g = 5 * cx**2 + 5 * cy**2 - 6 * cx * cy - 8
    crossings = np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))
    points = np.column_stack([cx[crossings], cy[crossings]])
    points = points[np.argsort(points[:, 0])]
    # 1e-4: the grid spacing on the unit circle is 3e-5.
    np.testing.assert_allclose(ex_4_3.real_solutions, points, rtol=0, atol=1e-4)


# --- §4.7, Ex. 4.4: Newton-Raphson on the slider-crank ------------------------------------
# Eqs. 38-41 with L2 = L3 = 1 and θ2 = 45°, unknowns x = (θ3, l), start (-60°, 1).  The
# Jacobian below (eq. 44) is right.  The start "θ2⁽⁰⁾ = 60°, θ3⁽⁰⁾ = -60°, l⁽⁰⁾ = 1" is the
# known configuration of the mechanism at θ2 = 60° (it closes the loop), the guess for
# θ2 = 45°: not a slip.  Slip in the notes' text (docs/errata.md, M-3): eq. 45 divides by
# cos θ3⁽ᵏ⁺¹⁾; Newton's step uses the current iterate, cos θ3⁽ᵏ⁾ (and the worked row 0 does
# divide by cos(-60°) = 0.5).

TH2 = np.radians(45.0)


def fun(x):
    th3, l = x[:, 0], x[:, 1]
    return np.stack([np.cos(TH2) + np.cos(th3) - l, np.sin(TH2) + np.sin(th3)], axis=-1)


def jac(x):
    th3 = x[:, 0]
    return np.stack([np.stack([-np.sin(th3), -np.ones_like(th3)], -1),
                     np.stack([np.cos(th3), np.zeros_like(th3)], -1)], -2)


def notes_iteration(th3, l, steps):
    """Eqs. 45-46 (with cos θ3⁽ᵏ⁾), scalar, as a student would compute them."""
    rows = []
    for _ in range(steps):
        phi1 = np.cos(TH2) + np.cos(th3) - l
        phi2 = np.sin(TH2) + np.sin(th3)
        d_th3 = -phi2 / np.cos(th3)
        d_l = -np.sin(th3) * d_th3 + phi1
        rows.append((th3, l, phi1, phi2, d_th3, d_l))
        th3, l = th3 + d_th3, l + d_l
    return np.array(rows)


# Columns: θ3 (rad), l, Φ1, Φ2, Δθ3 (rad), Δl.  Verified in double precision (and by the
# scalar eqs. 45-46 in test_ex_4_4_matches_the_notes_update_formulas).
VERIFIED = np.array([
    [-1.04719755, 1.00000000, 2.07106781e-01, -1.58918623e-01, 3.17837245e-01, 4.82361910e-01],
    [-0.729360306, 1.48236191, -2.96542863e-02, 4.07139662e-02, -5.46055797e-02, -6.60430522e-02],
    [-0.783965886, 1.41631886, -1.09324756e-03, 1.01349824e-03, -1.43125448e-03, -2.10384673e-03],
    [-0.785397140, 1.41421501, -7.24941791e-07, 7.23558194e-07, -1.02326476e-06, -1.44849850e-06],
])

# The printed table, as printed (strings keep the printed precision).
PRINTED = [
    ("-1.05", "1", "0.207", "-0.159", "0.318", "0.4824"),
    ("-0.729", "1.482", "-0.0292", "0.0408", "-0.0547", "-0.0656"),
    ("-0.7839", "1.4164", "-0.0011", "0.0011", "-0.0016", "-0.0022"),
    ("-0.7855", "1.4142", "-5.8e-5", "-7.2e-5", "1e-4", "1.4e-5"),
]
PRINTED_DEGREES = [-60.0, -41.8, -44.9, -45.0]   # θ3 in degrees, beside the radians
# Entries that differ from the verified iteration by more than half a unit of their last
# printed digit.  The table was computed by hand with rounded intermediate values:
#   - rows 1-2: last-digit slips (Φ1⁽¹⁾ -0.0292 for -0.02965, Δl⁽¹⁾ -0.0656 for -0.06604,
#     Δθ3⁽²⁾ -0.0016 for -0.00143, θ3⁽²⁾ -0.7839 for -0.78397, l⁽²⁾ 1.4164 for 1.41632, ...);
#   - row 3: θ3⁽³⁾ = -0.7855 for -0.785397 (-π/4 = -0.7854), and its Φ and Δ are those of
#     the rounded point (-0.7855, 1.4142), not of the iterate (test below), e.g. Φ2⁽³⁾ is
#     printed -7.2e-5 for +7.2e-7.
SLIPS = {(1, 2), (1, 3), (1, 4), (1, 5),
         (2, 0), (2, 1), (2, 3), (2, 4), (2, 5),
         (3, 0), (3, 2), (3, 3), (3, 4), (3, 5)}


def half_unit(text: str) -> float:
    """Half a unit in the last printed digit: the precision the notes claim."""
    return 0.5 * 10.0 ** Decimal(text).as_tuple().exponent


@pytest.fixture(scope="module")
def ex_4_4():
    return newton(fun, jac, [np.radians(-60.0), 1.0], history=True)


def test_ex_4_4_solution(ex_4_4):
    # Printed: θ3 = -45°, l = 1.4142.  Exactly -π/4 and √2 (the crank and rod, both of
    # length 1, make an isosceles right triangle); 1e-12: converged Newton.
    assert ex_4_4.converged
    assert ex_4_4.x == pytest.approx([-np.pi / 4, np.sqrt(2)], abs=1e-12)


def test_ex_4_4_iterates_against_verified_table(ex_4_4):
    h = ex_4_4.history
    table = np.column_stack([h.x, h.residual, h.step])[:4]
    # rel 1e-8: VERIFIED is written to 9 significant digits.
    assert table == pytest.approx(VERIFIED, rel=1e-8, abs=1e-15)


def test_ex_4_4_matches_the_notes_update_formulas(ex_4_4):
    h = ex_4_4.history
    rows = notes_iteration(np.radians(-60.0), 1.0, steps=4)
    # 1e-14: the same arithmetic up to the order of operations in a 2x2 solve.
    assert np.column_stack([h.x, h.residual, h.step])[:4] == pytest.approx(rows, abs=1e-14)


def test_ex_4_4_printed_table_to_its_printed_precision(ex_4_4):
    h = ex_4_4.history
    table = np.column_stack([h.x, h.residual, h.step])
    for k, row in enumerate(PRINTED):
        for column, text in enumerate(row):
            off = abs(float(text) - table[k, column])
            if (k, column) in SLIPS:
                assert off > half_unit(text), f"row {k} column {column} is not a slip"
            else:
                assert off <= half_unit(text), f"row {k} column {column}: {table[k, column]}"
    assert np.degrees(h.x[:4, 0]) == pytest.approx(PRINTED_DEGREES, abs=0.05)
    # Every printed iterate is within 1e-4 of the verified one, once rounding of the
    # printed digits is allowed for, except row 3's θ3 (-0.7855 for -0.785397).
    assert np.abs(h.x[1:3, 1] - [1.482, 1.4164]) == pytest.approx(0, abs=1e-4 + 5e-4)


def test_ex_4_4_last_row_is_the_rounded_point():
    # Row 3's printed Φ and Δ are reproduced from the rounded iterate (-0.7855, 1.4142).
    x = np.array([[-0.7855, 1.4142]])
    phi = fun(x)[0]
    step = np.linalg.solve(jac(x)[0], -phi)
    for value, text in zip([*phi, *step], PRINTED[3][2:]):
        assert abs(value - float(text)) <= half_unit(text)
