import warnings

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given
from hypothesis import strategies as st

from kinelab.errors import ModelError
from kinelab.solvers import dialytic

x, y, a = sp.symbols("x y a")
small = st.integers(-5, 5)


def circle(cx, cy, r):
    return (x - cx) ** 2 + (y - cy) ** 2 - r**2


@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(0.5, 2), st.floats(-2, 2),
       st.floats(-2, 2), st.floats(0.5, 2))
def test_two_circles_against_the_geometric_construction(x1, y1, r1, x2, y2, r2):
    d = np.hypot(x2 - x1, y2 - y1)
    assume(abs(r1 - r2) + 0.05 < d < r1 + r2 - 0.05 and abs(x2 - x1) > 0.05)
    sol = dialytic(circle(x1, y1, r1), circle(x2, y2, r2))
    # Two circles meet in 2 finite points (the other 2 of Bézout's 4 are at infinity), so
    # the eliminant has degree 2.
    assert sol.eliminant.degree() == 2 and sol.real.all()
    # Construction: foot of the chord at distance h from centre 1 along the centre line.
    h = (d**2 + r1**2 - r2**2) / (2 * d)
    ex = np.array([x2 - x1, y2 - y1]) / d
    foot = np.array([x1, y1]) + h * ex
    half = np.sqrt(r1**2 - h**2)
    points = np.array([foot + half * np.array([-ex[1], ex[0]]),
                       foot - half * np.array([-ex[1], ex[0]])])
    def ordered(a):                  # by x, then y where the x agree to rounding
        return a[np.lexsort((a[:, 1], np.round(a[:, 0], 9)))]
    points, found = ordered(points), ordered(sol.real_solutions)
    # 1e-9: the eliminant's coefficients come from floats through a symbolic determinant.
    np.testing.assert_allclose(found, points, rtol=0, atol=1e-9)


@given(st.lists(small, min_size=12, max_size=12))
def test_generic_quadratics_have_four_checked_solutions(c):
    p = c[0]*x**2 + c[1]*x*y + c[2]*y**2 + c[3]*x + c[4]*y + c[5]
    q = c[6]*x**2 + c[7]*x*y + c[8]*y**2 + c[9]*x + c[10]*y + c[11]
    # Generic: both genuinely quadratic in y and x, no common factor, a square-free
    # eliminant of full degree (Bézout: 2 x 2 = 4 solutions, none at infinity).
    assume(c[2] != 0 and c[8] != 0 and c[0] != 0 and c[6] != 0)
    assume(sp.gcd(p, q) == 1)
    r = sp.Poly(sp.resultant(p, q, y), x)
    assume(r.degree() == 4 and sp.discriminant(r) != 0)
    sol = dialytic(p, q)
    assert sol.x.shape == sol.y.shape == (4,)
    for xi, yi in zip(sol.x, sol.y):
        # Relative residual: |p| over the size of its terms at the solution.  1e-9 allows
        # for the conditioning of the quartic's roots with integer coefficients up to 5.
        for f in (p, q):
            size = sum(abs(float(t)) * abs(xi) ** i * abs(yi) ** j
                       for (i, j), t in sp.Poly(f, x, y).terms())
            assert abs(complex(f.subs({x: xi, y: yi}))) <= 1e-9 * max(size, 1.0)
    # Each x has one y (distinct roots), real when x is (a lone common root of two real
    # polynomials is its own conjugate): so the real solutions are the eliminant's real
    # roots, counted exactly by Sturm sequences.
    assert sol.real.sum() == r.count_roots()


def test_several_solutions_sharing_one_x():
    sol = dialytic(x**2 + y**2 - 1, 2 * x - 1)
    found = sol.real_solutions[np.argsort(sol.real_solutions[:, 1])]
    np.testing.assert_allclose(found, [[0.5, -np.sqrt(0.75)], [0.5, np.sqrt(0.75)]],
                               rtol=0, atol=1e-15)
    assert np.all(sol.residual < 1e-15)


def test_tangent_double_solution_keeps_its_multiplicity():
    sol = dialytic(x**2 + y**2 - 1, x - 1)
    assert sol.real.tolist() == [True, True]
    # 1e-8: a double root is found to about sqrt(eps).
    np.testing.assert_allclose(sol.real_solutions, [[1, 0], [1, 0]], rtol=0, atol=1e-8)


def test_no_real_intersection_is_all_complex():
    sol = dialytic(x**2 + y**2 - 1, x - 2)
    assert not sol.real.any()
    assert sorted(sol.y.imag) == pytest.approx([-np.sqrt(3), np.sqrt(3)], abs=1e-12)
    assert sol.real_solutions.shape == (0, 2)


def test_lines_and_choice_of_the_eliminated_unknown():
    p, q = 2 * x + y - 3, sp.Eq(x - y, 0)
    sol = dialytic(p, q)
    np.testing.assert_allclose(sol.real_solutions, [[1.0, 1.0]], rtol=0, atol=1e-15)
    swapped = dialytic(x**2 + y**2 - 4, x * y - 1, variables=(y, x))
    direct = dialytic(x**2 + y**2 - 4, x * y - 1)
    np.testing.assert_allclose(np.sort(swapped.real_solutions[:, ::-1], axis=0),
                               np.sort(direct.real_solutions, axis=0), rtol=0, atol=1e-12)


def test_dict_input_equals_sympy_input():
    from_dict = dialytic({(1, 1): 1, (0, 0): -1}, {(2, 0): 1, (0, 2): 1, (0, 0): -4})
    from_sympy = dialytic(x * y - 1, x**2 + y**2 - 4)
    assert from_dict.eliminant == from_sympy.eliminant
    assert np.array_equal(from_dict.real_solutions, from_sympy.real_solutions)


def test_matrix_has_the_notes_layout():
    # p = A y² + B y + C, q = D y² + E: rows p, q, y p, y q; columns y³, y², y, 1.
    sol = dialytic(5 * y**2 - 6 * x * y + 5 * x**2 - 8, y**2 + x**2 - 2 * x)
    A, B, C, D, E = 5, -6 * x, 5 * x**2 - 8, 1, x**2 - 2 * x
    assert sol.matrix.equals(sp.Matrix([[0, A, B, C], [0, D, 0, E], [A, B, C, 0],
                                        [D, 0, E, 0]]))
    # Unequal degrees: p of degree 1 in y (multiplied by 1, y), q of degree 2 (by 1).
    sol = dialytic(y - x, y**2 + x - 2)
    assert sol.matrix.shape == (3, 3)
    np.testing.assert_allclose(sol.real_solutions, [[-2, -2], [1, 1]], rtol=0, atol=1e-14)


@pytest.mark.parametrize("p, q, message", [
    (x * (y - 1), x * (y + x), r"share the factor x, so their common solutions form a curve"),
    (sp.sin(x) + y, y - 1, r"p: expected a polynomial in x, y, got y \+ sin\(x\)"),
    (x + y + a, x - y, r"expected the equations to hold two symbols, got 3 \(a, x, y\)"),
    ({(1, -1): 1}, {(0, 1): 1}, r"p: expected keys \(i, j\), the non-negative powers"),
    ({(1, 0): "one"}, {(0, 1): 1}, r"p\[\(1, 0\)\]: expected a number, got 'one'"),
    ({(1, 0): 1}, {(2, 0): 1}, r"expected at least one equation containing y, got neither"),
    (x + y, sp.S.Zero, r"q: expected a non-zero polynomial, got 0"),
])
def test_bad_input_is_explained(p, q, message):
    with pytest.raises(ModelError, match=message):
        dialytic(p, q)


def test_parameters_must_be_substituted():
    with pytest.raises(ModelError, match=r"p: expected numeric coefficients, got .*; "
                                         r"substitute numbers for a first"):
        dialytic(x + a * y, x - y, variables=(x, y))


@pytest.mark.parametrize("p, q, message", [
    ({(10**6, 0): 1.0, (0, 0): -1}, {(0, 1): 1.0, (0, 0): -1},
     r"^p: expected powers of at most 64, got \(1000000, 0\); solve a smaller system$"),
    ({(0, 300): 1.0, (1, 0): 1.0, (0, 0): -1}, {(0, 1): 1.0, (1, 0): -1.0},
     r"^p: expected powers of at most 64, got \(0, 300\)"),
    (x**40 + y, y**2 - x**30, r"^p, q: expected an eliminant of degree at most 64, got degrees "
                              r"1 and 2 in y and 40 and 30 in x, an eliminant of degree up to 110"),
    ({(1, 0): np.nan}, {(0, 1): 1.0},
     r"^p\[\(1, 0\)\]: expected a finite number at most 1e\+100 in size, got nan$"),
    ({(1, 0): np.inf, (0, 0): 1}, {(0, 1): 1.0}, r"^p\[\(1, 0\)\]: expected a finite number"),
    ({(1, 0): 10**400}, {(0, 1): 1.0},
     r"^p\[\(1, 0\)\]: expected a finite number .*got a whole number of 401 digits$"),
    ({(1, 0): True}, {(0, 1): 1.0}, r"^p\[\(1, 0\)\]: expected a number, got true$"),
    (sp.nan * x + y, x - y, r"^p: expected finite coefficients at most 1e\+100 in size, got nan$"),
    (x + y, sp.oo * x + y, r"^q: expected finite coefficients at most 1e\+100 in size, got oo$"),
    (None, {(0, 1): 1.0}, r"^p: expected a sympy expression or equation, or a dict \{\(i, j\): c\} "
                          r"of coefficients, got None$"),
    ({(0, 1): 1.0}, "x + y", r"^q: expected a sympy expression .*got 'x \+ y'$"),
])
def test_bad_polynomials_are_named(p, q, message):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ModelError, match=message):
            dialytic(p, q)


def test_complex_coefficients_are_solved_exactly():
    # (1 + 2i) x + 1 = 0 and y + x = 0: x = -(1 - 2i)/5
    sol = dialytic({(1, 0): 1 + 2j, (0, 0): 1}, {(0, 1): 1.0, (1, 0): 1})
    assert sol.x == pytest.approx([-0.2 + 0.4j], abs=1e-15)
    assert sol.y == pytest.approx([0.2 - 0.4j], abs=1e-15)


def test_bad_imag_tol_is_named():
    with pytest.raises(ModelError, match=r"^imag_tol: expected a number from 0 to below 1, got -1$"):
        dialytic(x + y, x - y, imag_tol=-1)
