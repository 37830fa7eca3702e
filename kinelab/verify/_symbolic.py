"""The symbolic route: the derivation's loop equations, differentiated by sympy and evaluated.

The loop equations Phi(q, S) = 0 of :func:`kinelab.derive.loop_equations` are written in the
notes' relative coordinates (one angle per link group, one slide per prismatic joint), from
the link graph, with no dyad, plan or kernel of the engine in them.  sympy differentiates
them, and every link angle, point and slide as expressions of q and S, once and twice;
numpy evaluates the derivatives at the engine's S, all samples at once.  Then, as the notes
do, ``J K_S = -Q`` and ``J L_S = -C^T H C`` (C = d(q, S)/dq, H the Hessian of Phi) give the
unknowns' K and L, and the chain rule gives those of every other coordinate.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kinelab.kinematics import Plan
from kinelab.model import Mechanism

__all__ = ["SymbolicRoute", "symbolic_route", "MAX_SECOND_DERIVATIVES"]

MAX_SECOND_DERIVATIVES = 20_000
"""The most second derivatives (equations and coordinates times (M + n)^2) the symbolic route
takes: beyond, sympy's differentiation and lambdify take tens of seconds, more than the
analysis it checks, and the route is skipped (the other routes still run)."""


@dataclass(frozen=True, eq=False)
class SymbolicRoute:
    """The compiled derivatives of one mechanism's loop equations and coordinates."""

    M: int
    unknown_items: np.ndarray     # (n,) item of the engine's jets holding each unknown of S
    n_equations: int
    function: object              # f(*q, *S) -> flat list of the nonzero derivatives
    slots: tuple                  # where each returned value goes: (array name, flat index)
    shapes: dict                  # array name -> shape without the sample axis
    angle_items: np.ndarray       # items that are angles (compared modulo a turn)

    def evaluate(self, q: np.ndarray, S: np.ndarray) -> dict[str, np.ndarray]:
        """The loop residual Phi (N, e) and every item's value, K and L, shapes (N, n_out),
        (N, n_out, M), (N, n_out, M, M), at inputs q (N, M) and the engine's unknowns S
        (N, n)."""
        N, M = q.shape
        out = {name: np.zeros((N,) + shape) for name, shape in self.shapes.items()}
        flat = {name: a.reshape(N, -1) for name, a in out.items()}
        with np.errstate(all="ignore"):
            values = self.function(*q.T, *S.T)
        for (name, k), v in zip(self.slots, values):
            flat[name][:, k] = v                         # a constant broadcasts over samples
        n, e = S.shape[1], self.n_equations
        Phi, G, H = out["Phi"], out["PhiG"], out["PhiH"]
        J, Q = G[:, :, M:], G[:, :, :M]
        C = np.zeros((N, M + n, M))
        C[:, :M] = np.eye(M)
        with np.errstate(all="ignore"):
            C[:, M:] = _solve(J, -Q)                                            # K of S
            rhs = np.einsum("nxa,nexy,nyb->neab", C, H, C).reshape(N, e, M * M)
            L_S = _solve(J, -rhs).reshape(N, n, M, M)
            g, h = out["G"], out["H"]
            K = np.einsum("nix,nxa->nia", g, C)
            L = (np.einsum("nxa,nixy,nyb->niab", C, h, C)
                 + np.einsum("nis,nsab->niab", g[:, :, M:], L_S))
        return {"Phi": Phi, "value": out["value"], "K": K, "L": L}


def _solve(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``A x = b`` per sample; NaN where A is singular (a flagged sample)."""
    out = np.full(b.shape, np.nan)
    ok = np.isfinite(A).all(axis=(1, 2)) & (np.abs(np.linalg.det(A)) > 0)
    if ok.any():
        out[ok] = np.linalg.solve(A[ok], b[ok])
    return out


def symbolic_route(mechanism: Mechanism, p: Plan) -> SymbolicRoute | str:
    """The symbolic route of a mechanism, made once per plan (sympy is imported here), or
    why it is skipped: gear joints, more unknowns than :data:`kinelab.derive.MAX_UNKNOWNS`, or more second
    derivatives than :data:`MAX_SECOND_DERIVATIVES`."""
    key = "verify: symbolic route"
    if any(j.type == "G" for j in mechanism.joints):
        return "the derivation does not take gear joints (G)"
    if any(j.type == "C" for j in mechanism.joints):
        return "the derivation does not take cam joints (C)"
    if key not in p.memo:
        p.memo[key] = _build(mechanism, p)
    return p.memo[key]


def _build(m: Mechanism, p: Plan) -> SymbolicRoute:
    import sympy as sp

    from kinelab.derive import loop_equations
    from kinelab.derive import MAX_UNKNOWNS
    eq = loop_equations(m, points=m.point_names)
    q, S = list(eq.q), list(eq.S)
    M, n = len(q), len(S)
    if n > MAX_UNKNOWNS:
        return (f"{n} unknown coordinates; the derivation is written for at most "
                f"{MAX_UNKNOWNS} (kinelab.derive.MAX_UNKNOWNS)")
    count = (len(eq.independent) + p.n_out) * (M + n) ** 2
    if count > MAX_SECOND_DERIVATIVES:
        return (f"{count:,} second derivatives to take in symbols (at most "
                f"{MAX_SECOND_DERIVATIVES:,}: beyond, sympy takes longer than the analysis)")
    X = q + S
    params = eq.parameters
    rows = [sp.sympify(eq.rows[i]).subs(params) for i in eq.independent]
    exprs: list = [None] * p.n_out
    for link, i in p.link_item.items():
        # the ground's angle is not derived: the engine keeps the sketch's, the derivation 0
        exprs[i] = sp.Float(p.sketch_angles[i]) if link == m.ground.name else eq.angle[link]
    for point, i in p.point_item.items():
        exprs[i], exprs[i + 1] = eq.position[point]
    for joint, i in p.slide_item.items():
        exprs[i] = eq.slide[joint]
    exprs = [sp.sympify(e).subs(params) for e in exprs]
    wanted: list = []
    slots: list = []

    def add(name, k, expr):
        if expr != 0:
            wanted.append(expr)
            slots.append((name, k))
    e = len(rows)

    def with_derivatives(functions, value: str, first: str, second: str) -> None:
        """Each function, its gradient and its Hessian in (q, S), into the named arrays."""
        width = M + n
        for r, f in enumerate(functions):
            add(value, r, f)
            for a, x in enumerate(X):
                d = sp.diff(f, x)
                add(first, r * width + a, d)
                for b, y in enumerate(X):
                    add(second, (r * width + a) * width + b, sp.diff(d, y))
    with_derivatives(rows, "Phi", "PhiG", "PhiH")
    with_derivatives(exprs, "value", "G", "H")
    function = sp.lambdify(X, wanted, modules="numpy", cse=True)
    unknown_items = np.array([p.link_item[name] if kind == "angle" else p.slide_item[name]
                              for kind, name in (eq.unknowns[s] for s in S)], np.int64)
    shapes = {"Phi": (e,), "PhiG": (e, M + n), "PhiH": (e, M + n, M + n),
              "value": (p.n_out,), "G": (p.n_out, M + n), "H": (p.n_out, M + n, M + n)}
    return SymbolicRoute(M=M, unknown_items=unknown_items, n_equations=e, function=function,
                         slots=tuple(slots), shapes=shapes,
                         angle_items=np.array(sorted(p.link_item.values()), np.int64))
