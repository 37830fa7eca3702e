"""Erthal, *Mecanismos com 1 GL: análise geral de velocidade e aceleração*: the slotted link
derived by kinelab from the catalogue model, against the notes' results, and the notes'
exercises (the slider-crank and the four-bar) against results derived here by hand.

Checked by hand before use: with A = B (cos A, sin A) on the lever and J the notes' matrix,
J^-1 = [[-sin A / B, cos A / B], [cos A, sin A]]; K = -J^-1 Q gives K_a = R cos(A - q) / B
and K_b = R sin(A - q); differentiating, dK_a/dq = -2 K_a K_b / B + R sin(A - q) / B and
dK_b/dq = B K_a^2 - R cos(A - q), the notes' L_a and L_b (these are right in the notes; what
they print for the inverse and the acceleration right-hand side is right too).
"""
import sympy as sp

import kinelab as kl
from kinelab.derive import derive


def symbols(d):
    by_name = {str(s): s for s in (*d.q, *d.S, *d.parameters)}
    return by_name


def zero(expr) -> bool:
    return sp.simplify(sp.expand_trig(sp.sympify(expr))) == 0


def test_slotted_link_exactly_as_the_notes():
    d = derive(kl.mechanisms.slotted_link(crank=0.1, distance=0.2))
    s = symbols(d)
    A, B, R, C, q = (s[k] for k in "ABRCq")
    assert d.q == (q,) and d.S == (A, B)
    assert d.unknowns == {A: ("angle", "lever"), B: ("slide", "slot")}
    assert d.inputs == {q: "jO2"} and d.parameters == {R: 0.1, C: 0.2}
    # position equations (1) and (2), term by term
    assert d.Phi == sp.Matrix([B * sp.cos(A) - R * sp.cos(q) - C, B * sp.sin(A) - R * sp.sin(q)])
    assert d.J == sp.Matrix([[-B * sp.sin(A), sp.cos(A)], [B * sp.cos(A), sp.sin(A)]])
    assert d.Q == sp.Matrix([R * sp.sin(q), -R * sp.cos(q)])
    assert d.det_J == -B
    Ka, Kb = R * sp.cos(A - q) / B, R * sp.sin(A - q)
    assert d.K == sp.Matrix([Ka, Kb])               # the notes' forms, exactly
    La = -2 * Ka * Kb / B + R / B * sp.sin(A - q)
    Lb = Ka ** 2 * B - R * sp.cos(A - q)
    assert zero(d.L[0] - La) and zero(d.L[1] - Lb)
    # L as the notes write it, with the velocity coefficients as symbols
    KA, KB = d.K_symbols
    assert zero(d.L_in_K[0] - (-2 * KA * KB / B + R / B * sp.sin(A - q)))
    assert zero(d.L_in_K[1] - (KA ** 2 * B - R * sp.cos(A - q)))
    # and L is the total derivative of K (dK/dq + dK/dS K), by a second route
    total = d.K.diff(q) + d.K.jacobian(sp.Matrix(d.S)) * d.K
    assert all(zero(e) for e in d.L - total)
    # a slip would show: the check fails for a wrong sign
    assert not zero(d.L[0] - (2 * Ka * Kb / B + R / B * sp.sin(A - q)))


def test_slotted_link_singular_where_the_slider_reaches_the_pivot():
    d = derive(kl.mechanisms.slotted_link(crank=0.1, distance=0.2))
    (sing,) = d.singularities
    assert sing.kind == "slide" and sing.names == ("slot", "A", "O4") and str(sing.factor) == "B"
    assert ("$B = 0$: the point `A` reaches `O4`, the origin of the slide `slot` (the pivot of "
            "`lever`)") in d.to_markdown()
    assert "o ponto `A` chega a `O4`" in d.to_markdown(lang="pt")


def test_exercise_slider_crank():
    """By hand: L2 (cos q, sin q) + L3 (cos t3, sin t3) - (s, e) = 0, so
    J = [[-L3 sin t3, -1], [L3 cos t3, 0]], det J = L3 cos t3 (singular with the rod
    perpendicular to the slide), K_t3 = -L2 cos q / (L3 cos t3),
    K_s = -L2 sin(q - t3) / cos t3."""
    d = derive(kl.mechanisms.slider_crank(crank=0.05, rod=0.18, offset=0.01))
    s = symbols(d)
    q, t3, sl, L2, L3, e = (s[k] for k in ("q", "theta_3", "s", "L_2", "L_3", "e"))
    assert d.Phi == sp.Matrix([L2 * sp.cos(q) + L3 * sp.cos(t3) - sl,
                               L2 * sp.sin(q) + L3 * sp.sin(t3) - e])
    assert zero(d.det_J - L3 * sp.cos(t3))
    assert zero(d.K[0] + L2 * sp.cos(q) / (L3 * sp.cos(t3)))
    assert zero(d.K[1] + L2 * sp.sin(q - t3) / sp.cos(t3))
    (sing,) = d.singularities
    assert sing.kind == "angle" and sing.names == ("rod",) and sing.values == (-90.0, 90.0)


def test_exercise_fourbar():
    """By hand: L2 e(q) + L3 e(t3) - L4 e(t4) - L1 (1, 0) = 0 (Norton's r2 + r3 - r4 - r1),
    det J = L3 L4 sin(t3 - t4): singular with coupler and rocker in line;
    K_t3 = L2 sin(t4 - q) / (L3 sin(t3 - t4)), K_t4 = L2 sin(t3 - q) / (L4 sin(t3 - t4))."""
    d = derive(kl.mechanisms.fourbar(ground=0.3, crank=0.1, coupler=0.25, rocker=0.2))
    s = symbols(d)
    q, t3, t4, L1, L2, L3, L4 = (s[k] for k in ("q", "theta_3", "theta_4", "L_1", "L_2", "L_3", "L_4"))
    assert d.Phi == sp.Matrix([L2 * sp.cos(q) + L3 * sp.cos(t3) - L4 * sp.cos(t4) - L1,
                               L2 * sp.sin(q) + L3 * sp.sin(t3) - L4 * sp.sin(t4)])
    assert zero(d.det_J - L3 * L4 * sp.sin(t3 - t4))
    assert zero(d.K[0] - L2 * sp.sin(t4 - q) / (L3 * sp.sin(t3 - t4)))
    assert zero(d.K[1] - L2 * sp.sin(t3 - q) / (L4 * sp.sin(t3 - t4)))
    (sing,) = d.singularities
    assert sing.kind == "in_line" and set(sing.names) == {"coupler", "rocker"}
