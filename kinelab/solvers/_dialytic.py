"""Two polynomial equations in two unknowns, by dialytic elimination."""
from __future__ import annotations

import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Union

import numpy as np
import sympy as sp
from sympy.polys.matrices import DomainMatrix
from sympy.polys.polyerrors import CoercionFailed

from kinelab.errors import ModelError, describe, one_line
from kinelab.model import MAX_RATE
from kinelab.solvers._arguments import tolerance
from kinelab.solvers._newton import newton

__all__ = ["DialyticSolution", "dialytic"]

Polynomial = Union[sp.Expr, sp.Eq, Mapping[tuple[int, int], complex]]

# Two roots of the eliminant closer than this (relative) are one x of several solutions:
# a double root comes out of the companion matrix split by ~sqrt(eps) ≈ 1.5e-8.
_SAME_X = 1e-6
# The largest eliminant: its degree is at most m deg_x(q) + n deg_x(p) (m, n the degrees in
# y), and both the exact determinant and the roots grow fast with it (degree 64 takes about a
# second, 300 minutes).  Mechanism problems stay far below: the four-bar's is 4, the
# Stewart platform's forward kinematics 40.
MAX_DEGREE = 64
# Coefficients at most this size: the eliminant multiplies up to 2 MAX_DEGREE of them, and
# its coefficients, roots and residuals must stay floats.
MAX_COEFFICIENT = MAX_RATE


@dataclass(frozen=True)
class DialyticSolution:
    """Every solution (x, y), real and complex, of two polynomial equations.

    With k solutions (k = degree of the eliminant):

    Attributes
    ----------
    x, y : ndarray of complex, shape (k,)
        The solutions: the real ones first, by increasing x, then the complex ones, by
        real part and then imaginary part.
    real : ndarray of bool, shape (k,)
        Both x and y are real to ``imag_tol`` (their ``.real`` parts are then the values).
    residual : ndarray, shape (k, 2)
        ``|p(x, y)|`` and ``|q(x, y)|`` at each solution: the check by substitution.  A
        large residual marks a root of the eliminant with no finite y (both leading
        coefficients in y vanish there: a solution at infinity).
    matrix : sympy.Matrix, shape (m + n, m + n)
        The dialytic matrix ``M`` (*Mecanismos*, eq. 35): the rows are p, q, y·p, y·q, …
        (p times y⁰ … yⁿ⁻¹ and q times y⁰ … yᵐ⁻¹, m and n their degrees in y), the columns
        the powers ``y^(m+n-1) … y, 1``, so that ``M v = 0`` with ``v = (y^(m+n-1), …, y, 1)``.
    eliminant : sympy.Poly
        ``det M``, a polynomial in x alone (the resultant of p and q with respect to y, up
        to sign), whose roots are the x of the solutions.
    variables : tuple of two sympy.Symbol
        (x, y): x is kept, y eliminated.
    """

    x: np.ndarray
    y: np.ndarray
    real: np.ndarray
    residual: np.ndarray
    matrix: sp.Matrix
    eliminant: sp.Poly
    variables: tuple[sp.Symbol, sp.Symbol]

    @property
    def coefficients(self) -> np.ndarray:
        """The eliminant's coefficients, highest power first (``numpy.roots`` order)."""
        return _numeric(self.eliminant.all_coeffs())

    @property
    def real_solutions(self) -> np.ndarray:
        """Shape (r, 2): the real solutions (x, y), by increasing x."""
        return np.column_stack([self.x[self.real].real, self.y[self.real].real])

    def __repr__(self) -> str:
        return (f"DialyticSolution(eliminant={self.eliminant.as_expr()}, x={self.x!r}, "
                f"y={self.y!r}, real={self.real!r})")


def dialytic(p: Polynomial, q: Polynomial, variables: tuple | None = None, *,
             imag_tol: float = 1e-8) -> DialyticSolution:
    """Solve ``p(x, y) = 0``, ``q(x, y) = 0`` by dialytic elimination of y.

    The method of *Mecanismos*, §4.6:

    1. write p and q as polynomials in y whose coefficients depend on x,
       ``p = Σ a_j(x) yʲ`` (degree m) and ``q = Σ b_j(x) yʲ`` (degree n);
    2. multiply p by ``1, y, …, yⁿ⁻¹`` and q by ``1, y, …, yᵐ⁻¹``: m + n equations, linear
       in the m + n "unknowns" ``v = (y^(m+n-1), …, y, 1)``, ``M(x) v = 0``;
    3. since ``v`` ends in 1 it is not zero, so ``det M(x) = 0``: the eliminant, a
       polynomial in x alone (symbolic, with sympy);
    4. its roots (numerically, by the eigenvalues of the companion matrix) are the x of the
       solutions; for each, y is the common root of ``p(x, ·)`` and ``q(x, ·)``.

    Parameters
    ----------
    p, q : sympy expression or equation, or dict
        The two polynomials.  A sympy expression means ``expr = 0`` (an ``Eq`` means
        ``lhs - rhs = 0``); a dict ``{(i, j): c}`` means ``Σ c xⁱ yʲ = 0``.  Coefficients
        must be numbers (substitute any parameters first).
    variables : (x, y), optional
        The two sympy symbols, y being the one eliminated.  Needed when the expressions
        hold other than two symbols; by default, their two symbols in alphabetical order.
        With dicts, the symbols to show the eliminant in (default ``x, y``).
    imag_tol : float, default 1e-8
        A number from 0 to below 1: a solution is real when ``|Im x| <= imag_tol max(1, |x|)`` and the same for y.
        (Repeated roots of an exact eliminant are separated out before the numerical
        root finding, which would split a double root by ~1e-8.)

    Returns
    -------
    DialyticSolution
        ``x``, ``y`` (k,) complex, ``real`` (k,), ``residual`` (k, 2), ``matrix``,
        ``eliminant``, ``variables``.

    Raises
    ------
    ModelError
        If p or q is not a polynomial with finite numeric coefficients (at most 1e100 in
        size), neither contains y, the two share a factor (their solutions then form a
        curve, not isolated points), or the eliminant's degree could exceed 64.

    References
    ----------
    *Mecanismos*, §4.6, eqs. 27-37 and Ex. 4.3.

    Examples
    --------
    *Mecanismos*, Ex. 4.3: where the ellipse ``5x² + 5y² - 6xy - 8 = 0`` meets the circle
    ``x² + y² - 2x = 0``.

    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> sol = kl.solvers.dialytic(5*x**2 + 5*y**2 - 6*x*y - 8, x**2 + y**2 - 2*x)
    >>> sol.eliminant.as_expr()
    -36*x**4 + 72*x**3 - 100*x**2 + 160*x - 64
    >>> sol.real_solutions
    array([[ 0.52370692, -0.87928659],
           [ 1.57342472,  0.81925826]])
    >>> sol.x[~sol.real]
    array([-0.04856582-1.4680271j, -0.04856582+1.4680271j])
    >>> bool(sol.residual.max() < 1e-12)
    True

    The same system as coefficient dicts ``{(i, j): c}`` for ``c xⁱ yʲ``:

    >>> p = {(2, 0): 5, (0, 2): 5, (1, 1): -6, (0, 0): -8}
    >>> q = {(2, 0): 1, (0, 2): 1, (1, 0): -2}
    >>> kl.solvers.dialytic(p, q).coefficients
    array([ -36.,   72., -100.,  160.,  -64.])
    """
    for name, f in (("p", p), ("q", q)):
        if not isinstance(f, (Mapping, sp.Basic, numbers.Number)) or isinstance(f, bool):
            raise ModelError(f"{name}: expected a sympy expression or equation, or a dict "
                             f"{{(i, j): c}} of coefficients, got {describe(f)}")
    imag_tol = tolerance("imag_tol", imag_tol, zero=True)
    x, y = _variables(p, q, variables)
    P, inexact_p = _poly(p, "p", x, y)
    Q, inexact_q = _poly(q, "q", x, y)
    inexact = inexact_p or inexact_q
    m, n = P.degree(y), Q.degree(y)
    if m <= 0 and n <= 0:
        raise ModelError(f"p, q: expected at least one equation containing {y}, got neither; "
                         f"pass variables=(x, y) with y the unknown to eliminate")
    degree = max(m, 0) * max(Q.degree(x), 0) + max(n, 0) * max(P.degree(x), 0)
    if max(m, n, degree) > MAX_DEGREE:
        raise ModelError(f"p, q: expected an eliminant of degree at most {MAX_DEGREE}, got "
                         f"degrees {max(m, 0)} and {max(n, 0)} in {y} and {P.degree(x)} and "
                         f"{Q.degree(x)} in {x}, an eliminant of degree up to "
                         f"{max(degree, m + n)}; solve a smaller system, or use newton from "
                         f"starting guesses")

    common = sp.gcd(P, Q)
    if common.total_degree() > 0:
        raise ModelError(f"p, q: the equations share the factor {common.as_expr()}, so their "
                         f"common solutions form a curve, not isolated points; divide it "
                         f"out of both and solve again")
    # Exact arithmetic (floats enter as the rationals they are), so that terms which cancel
    # in the determinant cancel exactly instead of leaving a 1e-16 x⁴ with roots at 1e16.
    M = _dialytic_matrix(P, Q, y)
    rational = all(f.domain in (sp.ZZ, sp.QQ) for f in (P, Q))
    try:                                      # det over Q[x]: exact and fast
        if not rational:
            raise CoercionFailed("irrational or complex coefficients")
        det = DomainMatrix.from_Matrix(M).convert_to(sp.QQ[x]).det()
        eliminant = sp.Poly(sp.QQ[x].to_sympy(det), x)
    except CoercionFailed:                    # irrational or complex coefficients
        eliminant = sp.Poly(M.det(method="berkowitz"), x)
    try:
        _numeric(eliminant.all_coeffs())
    except (OverflowError, ValueError):
        raise ModelError("p, q: the eliminant's coefficients exceed the range of floats; "
                         "scale the equations (divide each by its largest coefficient)") \
            from None
    xs = _roots(eliminant)
    if inexact:                               # show floats as floats
        M = M.evalf()
        eliminant = sp.Poly(eliminant.as_expr().evalf(), x)

    pn, qn = _Bivariate(P), _Bivariate(Q)
    ys = _back_substitute(xs, pn, qn)
    xs, ys = _polish(xs, ys, pn, qn)

    residual = np.abs(np.column_stack([pn(xs, ys), qn(xs, ys)]))
    real = (np.abs(xs.imag) <= imag_tol * np.maximum(1.0, np.abs(xs))) \
        & (np.abs(ys.imag) <= imag_tol * np.maximum(1.0, np.abs(ys)))
    order = np.lexsort((xs.imag, xs.real, ~real))
    return DialyticSolution(x=xs[order], y=ys[order], real=real[order],
                            residual=residual[order], matrix=M, eliminant=eliminant,
                            variables=(x, y))


def _variables(p, q, variables) -> tuple[sp.Symbol, sp.Symbol]:
    if variables is not None:
        if len(variables) != 2 or not all(isinstance(v, sp.Symbol) for v in variables):
            raise ModelError(f"variables: expected two sympy symbols (x, y), got {describe(variables)}")
        return tuple(variables)
    if isinstance(p, Mapping) and isinstance(q, Mapping):
        return sp.symbols("x y")
    free = set()
    for f in (p, q):
        if not isinstance(f, Mapping):
            free |= sp.sympify(f).free_symbols
    if len(free) != 2:
        names = ", ".join(sorted(str(s) for s in free)) or "none"
        raise ModelError(f"variables: expected the equations to hold two symbols, got "
                         f"{len(free)} ({names}); pass variables=(x, y), y the one to "
                         f"eliminate, and substitute numbers for the others")
    return tuple(sorted(free, key=str))


def _poly(f, name: str, x: sp.Symbol, y: sp.Symbol) -> tuple[sp.Poly, bool]:
    """The polynomial, with exact coefficients, and whether any was a float."""
    if isinstance(f, Mapping):
        terms = []
        for key, c in f.items():
            if not (isinstance(key, tuple) and len(key) == 2
                    and all(isinstance(e, numbers.Integral) and e >= 0 for e in key)):
                raise ModelError(f"{name}: expected keys (i, j), the non-negative powers of "
                                 f"x and y, got {describe(key)}")
            if key[0] > MAX_DEGREE or key[1] > MAX_DEGREE:
                raise ModelError(f"{name}: expected powers of at most {MAX_DEGREE}, got "
                                 f"{describe(key)}; solve a smaller system")
            if not isinstance(c, numbers.Number) or isinstance(c, bool):
                raise ModelError(f"{name}[{key}]: expected a number, got {describe(c)}")
            if _size(c) is None:
                raise ModelError(f"{name}[{key}]: expected a finite number at most "
                                 f"{MAX_COEFFICIENT:g} in size, got {describe(c)}")
            terms.append(sp.sympify(c) * x**key[0] * y**key[1])
        f = sp.Add(*terms)
    f = sp.sympify(f)
    if isinstance(f, sp.Equality):
        f = f.lhs - f.rhs
    try:
        P = sp.Poly(f, x, y)
    except sp.PolynomialError:
        raise ModelError(f"{name}: expected a polynomial in {x}, {y}, got {f}") from None
    if P.is_zero:
        raise ModelError(f"{name}: expected a non-zero polynomial, got 0")
    if not all(c.is_number for c in P.coeffs()):
        raise ModelError(f"{name}: expected numeric coefficients, got {f}; substitute "
                         f"numbers for {', '.join(sorted(map(str, P.free_symbols - {x, y})))}"
                         f" first (expr.subs)")
    for c in P.coeffs():
        if _size(c) is None:
            raise ModelError(f"{name}: expected finite coefficients at most "
                             f"{MAX_COEFFICIENT:g} in size, got {one_line(c, 60)}")
    floats = P.as_expr().atoms(sp.Float)
    if floats:
        P = sp.Poly(P.as_expr().xreplace({v: sp.Rational(v) for v in floats}), x, y)
    return P, bool(floats)


def _size(c) -> float | None:
    """``|c|`` when ``c`` is a finite number at most ``MAX_COEFFICIENT`` in size, else None."""
    try:
        size = abs(complex(c))
    except (OverflowError, TypeError, ValueError):
        return None
    return size if size <= MAX_COEFFICIENT else None     # NaN compares False


def _dialytic_matrix(P: sp.Poly, Q: sp.Poly, y: sp.Symbol) -> sp.Matrix:
    """Rows p, q, y p, y q, …; columns y^(m+n-1) … y⁰ (the notes' ordering, eq. 35)."""
    m, n = max(P.degree(y), 0), max(Q.degree(y), 0)
    size = m + n
    a = _coefficients_in(P, y, m)
    b = _coefficients_in(Q, y, n)
    rows = []
    for k in range(max(m, n)):
        for coeffs, shifts in ((a, n), (b, m)):
            if k < shifts:
                row = [sp.S.Zero] * size
                for j, c in enumerate(coeffs):          # c multiplies y^(j + k)
                    row[size - 1 - (j + k)] = c
                rows.append(row)
    return sp.Matrix(rows)


def _coefficients_in(P: sp.Poly, y: sp.Symbol, degree: int) -> list[sp.Expr]:
    """[a_0(x), …, a_degree(x)]: P = Σ a_j(x) yʲ."""
    a = [sp.S.Zero] * (degree + 1)
    for (i, j), c in P.terms():
        a[j] += c * P.gens[0] ** i
    return a


def _numeric(coeffs) -> np.ndarray:
    values = np.array([complex(c) for c in coeffs])
    if not np.isfinite(values).all():
        raise OverflowError("a coefficient beyond the range of floats")
    return values.real if np.all(values.imag == 0) else values


def _roots(eliminant: sp.Poly) -> np.ndarray:
    """All roots, with multiplicity, by the companion matrix of each square-free factor.

    A double root given to the companion matrix as such comes back split by ~sqrt(eps),
    possibly into a complex pair; factoring the exact eliminant first keeps it exact.
    """
    if eliminant.domain.is_Exact and eliminant.degree() > 0:
        factors = eliminant.sqf_list()[1]
    else:
        factors = [(eliminant, 1)]
    roots = [np.repeat(np.roots(_numeric(f.all_coeffs())), k) for f, k in factors]
    return np.concatenate([np.zeros(0), *roots]).astype(complex)


class _Bivariate:
    """A polynomial Σ c xⁱ yʲ evaluated with numpy, in complex arithmetic."""

    def __init__(self, P: sp.Poly):
        terms = P.terms()
        self.i = np.array([e[0] for e, _ in terms])
        self.j = np.array([e[1] for e, _ in terms])
        self.c = np.array([complex(c) for _, c in terms])

    def __call__(self, x, y, di: int = 0, dj: int = 0) -> np.ndarray:
        """The value, or with di / dj = 1 the partial derivative in x / y."""
        x = np.asarray(x, dtype=complex)[..., None]
        y = np.asarray(y, dtype=complex)[..., None]
        c = self.c * (self.i if di else 1) * (self.j if dj else 1)
        terms = c * x ** np.maximum(self.i - di, 0) * y ** np.maximum(self.j - dj, 0)
        return terms.sum(axis=-1)

    def size(self, x, y) -> np.ndarray:
        """The size of its terms at (x, y), powers of max(1, |x|), max(1, |y|): near the
        origin, where all terms but the constant vanish, it falls back on the
        coefficients."""
        X = np.maximum(1.0, np.abs(np.asarray(x)))[..., None]
        Y = np.maximum(1.0, np.abs(np.asarray(y)))[..., None]
        return (np.abs(self.c) * X**self.i * Y**self.j).sum(axis=-1)

    def roots_in_y(self, x) -> np.ndarray | None:
        """Roots in y at this x; None when there are none to offer (identically zero, or
        a non-zero constant, in y)."""
        a = np.zeros(self.j.max() + 1, dtype=complex)
        np.add.at(a, self.j, self.c * complex(x) ** self.i)
        scale = np.max(np.abs(a))
        if scale == 0.0:
            return None
        a = np.where(np.abs(a) <= 1e-13 * scale, 0.0, a)
        roots = np.roots(a[::-1]).astype(complex)
        return roots if roots.size else None


def _back_substitute(xs: np.ndarray, p: _Bivariate, q: _Bivariate) -> np.ndarray:
    """y at each root x: the common root of p(x, ·) and q(x, ·).

    Every common root is a root of each polynomial: the candidates are the roots in y of
    the one of lower degree in y at that x (fewer to reject; one source, so a root shared
    by two solutions appears once per multiplicity, not once per polynomial), and those
    that best satisfy both equations win.  Roots of the eliminant that coincide (several
    solutions sharing one x, or a double root) take distinct candidates, best first.
    """
    ys = np.zeros_like(xs)
    taken = np.zeros(xs.size, dtype=bool)
    for i in range(xs.size):                 # over the roots (a handful), not over samples
        if taken[i]:
            continue
        group = np.flatnonzero(~taken & (np.abs(xs - xs[i])
                                         <= _SAME_X * max(1.0, abs(xs[i]))))
        xc = xs[group].mean()
        sources = [r for r in (p.roots_in_y(xc), q.roots_in_y(xc)) if r is not None]
        candidates = min(sources, key=len) if sources else np.zeros(1, dtype=complex)
        score = sum(np.abs(f(xc, candidates)) / f.size(xc, candidates) for f in (p, q))
        best = candidates[np.argsort(score, kind="stable")]
        ys[group] = best[np.arange(group.size) % best.size]
        taken[group] = True
    return ys


def _polish(xs, ys, p: _Bivariate, q: _Bivariate) -> tuple[np.ndarray, np.ndarray]:
    """A few Newton steps on p = q = 0 itself, from each (x, y) found.

    Two solutions with (nearly) the same x make a (nearly) double root of the eliminant,
    which the companion matrix resolves only to ~1e-8, even when each solution is a simple,
    well-conditioned root of the system; Newton on the system restores full accuracy.
    Solutions whose Jacobian is singular (a genuine double solution) keep their values.
    """
    if xs.size == 0:
        return xs, ys

    def fun(X):
        return np.stack([f(X[:, 0], X[:, 1]) for f in (p, q)], axis=-1)

    def jac(X):
        return np.stack([np.stack([f(X[:, 0], X[:, 1], 1, 0), f(X[:, 0], X[:, 1], 0, 1)], -1)
                         for f in (p, q)], -2)

    start = np.column_stack([xs, ys])
    polished = newton(fun, jac, start, max_iter=8, on_failure="mask")
    before = np.max(np.abs(fun(start)), axis=1)
    keep = polished.converged & (polished.residual_norm <= before)
    best = np.where(keep[:, None], polished.x, start)
    return best[:, 0], best[:, 1]
