"""Motion laws of a cam's rise or return, normalised: ``f(x)`` on ``0 <= x <= 1`` going from
0 to 1, with its first three derivatives in closed form.

A segment of rise ``h`` over the cam angle ``beta`` gives ``S = h f(x)``, ``V = h f'(x) / beta``,
``A = h f''(x) / beta**2``, ``J = h f'''(x) / beta**3`` with ``x = (theta - theta0) / beta``
(Norton, *Design of Machinery*, ch. 8).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinelab.errors import ModelError

__all__ = ["LAWS", "law_pieces", "law_values", "polynomial_coefficients", "polynomial_values"]

PI = math.pi


def _harmonic(x):
    s, c = np.sin(PI * x), np.cos(PI * x)
    return (1 - c) / 2, PI / 2 * s, PI ** 2 / 2 * c, -PI ** 3 / 2 * s


def _cycloidal(x):
    s, c = np.sin(2 * PI * x), np.cos(2 * PI * x)
    return x - s / (2 * PI), 1 - c, 2 * PI * s, 4 * PI ** 2 * c


def _poly(coefficients):
    """A law that is the polynomial sum(c_i x**i), with its derivatives."""
    p = np.polynomial.Polynomial(coefficients)
    d = [p, p.deriv(1), p.deriv(2), p.deriv(3)]
    return lambda x: tuple(q(x) for q in d)


@dataclass(frozen=True)
class _Piece:
    """One piece of a law whose acceleration is ``alpha + beta sin(k x + phase)``, integrated
    exactly from ``f(x0) = s0``, ``f'(x0) = v0``."""
    x0: float
    alpha: float
    beta: float
    k: float
    phase: float
    s0: float = 0.0
    v0: float = 0.0

    def values(self, x):
        u = x - self.x0
        c0 = math.cos(self.k * self.x0 + self.phase)
        s0 = math.sin(self.k * self.x0 + self.phase)
        arg = self.k * x + self.phase
        sa, ca = np.sin(arg), np.cos(arg)
        b, k = self.beta, self.k
        f = self.s0 + self.v0 * u + self.alpha * u ** 2 / 2 - b / k ** 2 * (sa - s0) + b / k * c0 * u
        f1 = self.v0 + self.alpha * u - b / k * (ca - c0)
        return f, f1, self.alpha + b * sa, b * k * ca


def _pieces_law(shape):
    """A law whose acceleration is given piece by piece, ``shape`` = [(x0, alpha, beta, k,
    phase), ...] with unit peak; each piece starts where the last ends (S and V continuous),
    and the whole is scaled so that f(1) = 1."""
    pieces, s, v = [], 0.0, 0.0
    for i, (x0, alpha, beta, k, phase) in enumerate(shape):
        p = _Piece(x0, alpha, beta, k, phase, s, v)
        pieces.append(p)
        x1 = shape[i + 1][0] if i + 1 < len(shape) else 1.0
        s, v = (float(t) for t in p.values(np.float64(x1))[:2])
    scale = 1.0 / s
    pieces = [_Piece(p.x0, p.alpha * scale, p.beta * scale, p.k, p.phase, p.s0 * scale,
                     p.v0 * scale) for p in pieces]
    breaks = np.array([p.x0 for p in pieces])

    def values(x):
        x = np.asarray(x, dtype=float)
        idx = np.clip(np.searchsorted(breaks, x, side="right") - 1, 0, len(pieces) - 1)
        out = [np.zeros_like(x) for _ in range(4)]
        for i, p in enumerate(pieces):       # a loop over the pieces, not over the samples
            mask = idx == i
            if mask.any():
                for o, v in zip(out, p.values(x[mask])):
                    o[mask] = v
        return tuple(out)
    values.peak = scale        # the largest |f''|
    values.pieces = tuple(_generic(p) for p in pieces)
    return values


def _generic(p: _Piece) -> tuple:
    """A piece as ``(x0, c, B, k, phase)``: ``f(x) = sum(c_i (x - x0)**i) + B sin(k x + phase)``
    from ``x0`` on (the form the planar engine evaluates, see ``law_pieces``)."""
    a0 = p.k * p.x0 + p.phase
    return (p.x0, (p.s0 + p.beta / p.k ** 2 * math.sin(a0), p.v0 + p.beta / p.k * math.cos(a0),
                   p.alpha / 2), -p.beta / p.k ** 2, p.k, p.phase)


# Modified trapezoid: quarter sines over the first and last eighths and about the middle,
# constant acceleration between (peak 4.8881 h / beta**2).
_modified_trapezoid = _pieces_law([
    (0.0, 0.0, 1.0, 4 * PI, 0.0),
    (1 / 8, 1.0, 0.0, 1.0, 0.0),
    (3 / 8, 0.0, 1.0, 4 * PI, PI / 2 - 4 * PI * 3 / 8),
    (5 / 8, -1.0, 0.0, 1.0, 0.0),
    (7 / 8, 0.0, -1.0, 4 * PI, PI / 2 - 4 * PI * 7 / 8),
])
# Modified sine: a quarter sine of period 1/2 at each end, a sine of period 3/2 between
# (peak 5.5280 h / beta**2).
_modified_sine = _pieces_law([
    (0.0, 0.0, 1.0, 4 * PI, 0.0),
    (1 / 8, 0.0, 1.0, 4 * PI / 3, PI / 2 - 4 * PI / 3 / 8),
    (7 / 8, 0.0, -1.0, 4 * PI, PI / 2 - 4 * PI * 7 / 8),
])

LAWS = {
    "harmonic": _harmonic,
    "cycloidal": _cycloidal,
    "3-4-5": _poly([0, 0, 0, 10, -15, 6]),
    "4-5-6-7": _poly([0, 0, 0, 0, 35, -84, 70, -20]),
    "modified-trapezoid": _modified_trapezoid,
    "modified-sine": _modified_sine,
}
"""The laws by name: each maps x (array) to f, f', f'', f''' (arrays of x's shape)."""


def law_pieces(name: str) -> tuple:
    """The law ``name`` as pieces ``(x0, c, B, k, phase)``, each holding from its ``x0`` to the
    next one's: ``f(x) = sum(c_i (x - x0)**i) + B sin(k x + phase)``, exactly the law of
    :data:`LAWS` (the form the planar engine's cam joints evaluate, compiled or not)."""
    law = LAWS[name]
    if hasattr(law, "pieces"):
        return law.pieces
    return {"harmonic": ((0.0, (0.5,), -0.5, PI, PI / 2),),
            "cycloidal": ((0.0, (0.0, 1.0), -1 / (2 * PI), 2 * PI, 0.0),),
            "3-4-5": ((0.0, (0, 0, 0, 10, -15, 6), 0.0, 0.0, 0.0),),
            "4-5-6-7": ((0.0, (0, 0, 0, 0, 35, -84, 70, -20), 0.0, 0.0, 0.0),)}[name]


def law_values(name: str, x) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``f, f', f'', f'''`` of the law ``name`` at ``x`` (0 to 1)."""
    x = np.asarray(x, dtype=float)
    return tuple(np.broadcast_to(v, x.shape).astype(float) for v in LAWS[name](x))


def polynomial_coefficients(conditions, beta: float) -> np.ndarray:
    """The coefficients ``c`` of ``S(x) = sum(c_i x**i)`` over a segment of ``beta`` rad
    meeting ``conditions``: (x, order, value) with ``order`` 0 to 3 for S, V, A, J (per
    radian: value * beta**order is the derivative with respect to x).  The degree is the
    number of conditions less one."""
    n = len(conditions)
    M = np.zeros((n, n))
    b = np.zeros(n)
    i = np.arange(n)
    for row, (x, order, value) in enumerate(conditions):
        fall = np.ones(n)
        for m in range(order):
            fall = fall * (i - m)
        power = np.clip(i - order, 0, None)
        M[row] = np.where(i >= order, fall * float(x) ** power, 0.0)
        b[row] = value * beta ** order
    if n == 0 or np.linalg.matrix_rank(M) < n:
        raise ModelError("law 'polynomial': its boundary conditions do not fix one polynomial "
                         "(two conditions say the same, or there are none); give each "
                         "derivative at most once at each end")
    return np.linalg.solve(M, b)


def polynomial_values(c: np.ndarray, x):
    """``S, dS/dx, d2S/dx2, d3S/dx3`` of the polynomial with coefficients ``c`` at ``x``."""
    p = np.polynomial.Polynomial(c)
    x = np.asarray(x, dtype=float)
    return tuple(np.broadcast_to(q(x), x.shape).astype(float)
                 for q in (p, p.deriv(1), p.deriv(2), p.deriv(3)))
