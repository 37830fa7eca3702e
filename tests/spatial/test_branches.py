"""K and L through a change point, against curves whose branches are known."""
import numpy as np
import pytest

from kinelab.spatial._branches import through_change_point


@pytest.mark.parametrize("f, g", [
    ((1.0, 2.0, 0.5), (-2.0, 1.0, -3.0)),
    ((0.0, -1.5, 2.0), (3.0, 0.25, 0.0)),
    ((-0.3, 0.0, 0.0), (0.7, -4.0, 1.0)),
])
def test_product_of_two_branches(f, g):
    """Φ(q, S) = (S - f(q)) (S - g(q)), f = f1 q + f2 q²/2 + f3 q³/6 (g alike): the branches
    S = f and S = g cross at the origin.  With u = S - f, v = S - g, at the origin (u = v
    = 0): Φ_SS = 2, Φ_qS = -(f1 + g1), Φ_qq = 2 f1 g1, Φ_qqq = 3 (f2 g1 + f1 g2),
    Φ_qqS = -(f2 + g2), Φ_qSS = Φ_SSS = 0; along S = f, Φ_S = u + v = f - g ~ (f1 - g1) q,
    so that branch has the sign of f1 - g1 past the origin."""
    (f1, f2, _), (g1, g2, _) = f, g
    jets = (2 * f1 * g1, -(f1 + g1), 2.0, 3 * (f2 * g1 + f1 * g2), -(f2 + g2), 0.0, 0.0)
    for (k1, k2, _), (o1, _, _) in ((f, g), (g, f)):
        K, L = through_change_point(*jets, np.sign(k1 - o1))
        # 1e-14: a few operations on numbers of order 1
        assert (float(K), float(L)) == pytest.approx((k1, k2), abs=1e-14)


def test_one_branch_and_a_line():
    """Φ = q (S - q²): the line q = 0 (all S) and the branch S = q² (K = 0, L = 2) meet at
    the origin; Φ_SS = 0, so only one root is finite.  Φ_qS = 1, Φ_qq = 0, Φ_qqq = -6,
    Φ_qqS = Φ_qSS = Φ_SSS = 0, and Φ_S = q > 0 past the origin."""
    K, L = through_change_point(0.0, 1.0, 0.0, -6.0, 0.0, 0.0, 0.0, 1)
    assert (float(K), float(L)) == (0.0, 2.0)
