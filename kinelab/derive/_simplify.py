"""Simplification with bounds: the derivation must end, and end soon, whatever the model.

sympy's general simplifiers can take minutes on an expression of a few hundred operations
(a triad's K, a six-bar's L).  Here the simplification is a short, fixed sequence of Fu's
rules (Fu, Zhong and Zeng, *Automated and readable simplification of trigonometric
expressions*, 2006) that does what the notes do by hand: products of sines and cosines of
the unknowns gathered into ``cos(A - q)``, ``sin^2 + cos^2 = 1``, common factors taken out.
Two bounds keep it short: an expression larger than :data:`SIMPLIFY_OPS` operations is left
as derived, and each simplification stops after :data:`SIMPLIFY_SECONDS`, in whichever
thread it runs (:func:`kinelab._deadline.within`); either way the result is flagged.
"""
from __future__ import annotations

from kinelab._deadline import within
from kinelab.errors import TimeLimitError

__all__ = ["SIMPLIFY_OPS", "SIMPLIFY_SECONDS", "READABLE_OPS", "simplified", "size", "factors"]

SIMPLIFY_OPS = 300
"""Operations above which an expression is not simplified."""

SIMPLIFY_SECONDS = 5.0
"""Time after which one simplification gives up and keeps the expression as derived: a
safety net, far above what the operations' bound lets through (the engine's torque's speed
term, 0.6 s on an idle machine), so that a busy machine writes the same document as an idle
one."""

READABLE_OPS = 120
"""Operations above which an expression is too large to read in a document: it is shown in
matrix form with numbers instead."""


def size(expr) -> int:
    """The count of operations of an expression (of a matrix's entries, summed)."""
    import sympy as sp
    if hasattr(expr, "shape"):
        return sum(int(sp.count_ops(e)) for e in expr)
    return int(sp.count_ops(expr))


def _part(x):
    """A polynomial in sines and cosines, made smaller by Fu's rules where they help."""
    import sympy as sp
    from sympy.simplify.fu import TR5, TR6, TR10i
    best = sp.factor_terms(x)
    x = sp.expand(x)
    for rule in (None, TR5, TR6):
        y = x if rule is None else sp.expand(rule(x))
        y = sp.factor_terms(TR10i(y))
        if size(y) < size(best):
            best = y
    return best


def simplified(expr, limit: int = SIMPLIFY_OPS, seconds: float = SIMPLIFY_SECONDS):
    """``(expr simplified, True)``, or ``(expr, False)`` when it is larger than ``limit``
    operations or its simplification takes more than ``seconds``.  The result is never
    larger than the expression it replaces."""
    import sympy as sp
    expr = sp.sympify(expr)
    n = size(expr)
    if n > limit:
        return expr, False
    if not expr.free_symbols:
        return expr, True
    try:
        out = within(seconds, _simplify, expr)
    except TimeLimitError:
        return expr, False
    return (out if size(out) <= n else expr), True


def _simplify(expr):
    import sympy as sp
    num, den = sp.fraction(sp.together(expr))
    num, den = _part(num), _part(den)
    return sp.factor_terms(num / den)


def factors(expr, limit: int = SIMPLIFY_OPS, seconds: float = SIMPLIFY_SECONDS):
    """``(constant, [(factor, power), ...])`` of a product, factorised within the bounds."""
    import sympy as sp
    if size(expr) <= limit:
        try:
            expr = within(seconds, sp.factor, expr)
        except TimeLimitError:
            pass
    const, parts = sp.Integer(1), []
    for f in sp.Mul.make_args(expr):
        base, power = f.as_base_exp()
        if base.free_symbols:
            parts.append((base, power))
        else:
            const *= f
    return const, parts
