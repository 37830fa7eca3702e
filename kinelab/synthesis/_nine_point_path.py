"""Nine path points, pivots free: every four-bar, by monodromy and a parameter homotopy.

The formulation (isotropic coordinates: a point z and its conjugate zb taken as independent
unknowns; Wampler, Morgan and Sommese 1992).  The origin is at the first point P_0, and
``d_j = P_j - P_0`` (j = 1..8).  In the first position let ``x = A - P_0`` and ``y = B - P_0``
be the moving pivots seen from the coupler point, ``u = A - A0`` the crank and ``v = B - B0``
the rocker (so A0 = x - u, B0 = y - v), and ``T_j = theta_j - 1`` with theta_j the coupler's
rotation from position 0 to j.  The crank keeps its length, ``|d_j + T_j x + u|^2 = |u|^2``;
with ``theta_j thetab_j = 1``, i.e. ``T_j Tb_j = -(T_j + Tb_j)``, that is linear in (T_j, Tb_j):

    A1_j T_j + B1_j Tb_j = C1_j,   A1_j = x (db_j + ub - xb),  B1_j = xb (d_j + u - x),
                                   C1_j = -(d_j db_j + d_j ub + db_j u)

and likewise for the rocker (A2, B2, C2 with y, v).  Cramer's rule gives T_j = N1_j / D_j,
Tb_j = N2_j / D_j, and the unit rotation becomes eight equations in eight unknowns
z = (x, xb, u, ub, y, yb, v, vb):

    E_j = N1_j N2_j + D_j (N1_j + N2_j) = 0,   N1 = C1 B2 - B1 C2,  N2 = A1 C2 - C1 A2,
                                                D = A1 B2 - B1 A2        (j = 1..8),

of total degree 7 (7^8 = 5,764,801 paths from a total-degree start; WMS's 2-homogeneous
form of it needed 286,720).  Its generic root count on the solution component is 8652:
1442 Roberts-cognate triples, each counted with both labellings of its dyads.  The other
roots (x = y = 0, xb = yb = 0, ...) are degenerate families where D_j vanishes.

How every root is found.  Not from a start system: a real four-bar of general proportions
and nine points of its coupler curve make a *base task* with a root we know.  Monodromy
finds the others: every known root is carried around six loops (from the base task
through two random complex tasks and back), each root around each loop once, all of them
at once (one homotopy per path), until no loop brings a new root.  Only one root of each
six (three cognates, two labellings) is carried; the other five follow in closed form
(:func:`cognates`).  The roots of the base task are then carried to the given points by a
parameter homotopy through a random complex task (so no path meets a singular task).  Only
roots on the component of real four-bars are ever followed: no path ends at infinity or on
a degenerate family.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab import _memory, _progress
from kinelab.errors import ModelError, check_choice
from kinelab.model import MIN_LENGTH
from kinelab.solvers._arguments import seed as check_seed
from kinelab.solvers._homotopy import follow, refine
from kinelab.synthesis._five_point_path import FivePointLinkage
from kinelab.synthesis._arguments import point_array
from kinelab.synthesis._linkage import (TRANSMISSION_LIMIT, at_inputs, circuits,
                                        finite_or_inf, fourbar_model, model_grashof, planned,
                                        transmission_defects, transmission_limit, travel)
from kinelab.synthesis._positions import fmt
from kinelab.synthesis._results import SolutionList

__all__ = ["NinePointLinkage", "NinePointSolutions", "nine_point_path", "loop_residuals",
           "equations", "fourbar_root", "cognates"]

SOLUTIONS = 4326      # generic count up to the labelling of the dyads (WMS 1992)
CLASSES = 1442        # ... up to Roberts cognates
PATH_BYTES = 40_000   # memory of one path while it is followed (measured: about 30 kB)
_SOLVED = 1e-10       # relative residual of the loop equations a root must reach
_DISTINCT = 1e-7      # relative distance under which two roots (or classes) are one
_REAL = 1e-8          # relative |xb - conj(x)| under which a root is real
_REACHED = 1e-8       # relative distance engine vs prescribed point
_MONODROMY_STEPS = 400  # steps after which a monodromy path is given up
_LOOPS = 6              # monodromy loops
_ORDERS = ("transmission", "size", "grashof")


# ---------------------------------------------------------------------------------------
# the equations

def _eliminated(z: np.ndarray, d: np.ndarray, db: np.ndarray, dd: np.ndarray,
                ddb: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """E (N, 8), dE/dz (N, 8, 8) and dE/dt (N, 8) at z (N, 8), for displacements d, db
    (N, 8) moving at dd, ddb (N, 8) per unit t.  The chain rule by hand, term by term:
    every factor depends on few unknowns, so each partial derivative is a few products of
    (N, 8) arrays."""
    x, xb, u, ub, y, yb, v, vb = (z[:, k, None] for k in range(8))
    dxb, dx = db + ub - xb, d + u - x
    dyb, dy = db + vb - yb, d + v - y
    A1, B1, C1 = x * dxb, xb * dx, -(d * db + d * ub + db * u)
    A2, B2, C2 = y * dyb, yb * dy, -(d * db + d * vb + db * v)
    N1, N2, D = C1 * B2 - B1 * C2, A1 * C2 - C1 * A2, A1 * B2 - B1 * A2
    E = N1 * (N2 + D) + D * N2
    eN1, eN2, eD = N2 + D, N1 + D, N1 + N2
    eA1, eB1, eC1 = eN2 * C2 + eD * B2, -eN1 * C2 - eD * A2, eN1 * B2 - eN2 * A2
    eA2, eB2, eC2 = -eN2 * C1 - eD * B1, eN1 * C1 + eD * A1, -eN1 * B1 + eN2 * A1
    J = np.empty(E.shape + (8,), complex)
    J[..., 0] = eA1 * dxb - eB1 * xb
    J[..., 1] = -eA1 * x + eB1 * dx
    J[..., 2] = eB1 * xb - eC1 * db
    J[..., 3] = eA1 * x - eC1 * d
    J[..., 4] = eA2 * dyb - eB2 * yb
    J[..., 5] = -eA2 * y + eB2 * dy
    J[..., 6] = eB2 * yb - eC2 * db
    J[..., 7] = eA2 * y - eC2 * d
    c_t = dd * db + d * ddb
    Et = ((eA1 * x + eA2 * y) * ddb + (eB1 * xb + eB2 * yb) * dd
          - eC1 * (c_t + dd * ub + ddb * u) - eC2 * (c_t + dd * vb + ddb * v))
    return E, J, Et


def _rotations(z: np.ndarray, d: np.ndarray, db: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """theta_j, thetab_j (N, 8) of roots z (N, 8), by Cramer's rule."""
    x, xb, u, ub, y, yb, v, vb = (z[:, k, None] for k in range(8))
    A1, B1, C1 = x * (db + ub - xb), xb * (d + u - x), -(d * db + d * ub + db * u)
    A2, B2, C2 = y * (db + vb - yb), yb * (d + v - y), -(d * db + d * vb + db * v)
    D = A1 * B2 - B1 * A2
    with np.errstate(all="ignore"):
        return 1.0 + (C1 * B2 - B1 * C2) / D, 1.0 + (A1 * C2 - C1 * A2) / D


def _frame(T: np.ndarray) -> tuple[np.ndarray, float]:
    """The task's frame: origin at the first point, unit size."""
    scale = float(np.linalg.norm(T - T[0], axis=1).max())
    return T[0], scale


def _displacements(T: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """d_j, db_j (8,) of points (9, 2) in their own frame (origin P_0, unit size)."""
    o, s = _frame(T)
    d = ((T[1:] - o) / s) @ np.array([1.0, 1j])
    return d, d.conj()


def equations(points: ArrayLike, roots: ArrayLike) -> np.ndarray:
    """The eight eliminated equations E_j at roots z = (x, xb, u, ub, y, yb, v, vb), each
    relative to the size of its terms: (N, 8) complex in, (N, 8) out.  The roots are in the
    frame of the points as given (m)."""
    T = np.asarray(points, float)
    o, s = _frame(T)
    d, db = _displacements(T)
    z = np.atleast_2d(np.asarray(roots, complex)) / s
    N = len(z)
    E, _, _ = _eliminated(z, np.broadcast_to(d, (N, 8)), np.broadcast_to(db, (N, 8)),
                          np.zeros((N, 8)), np.zeros((N, 8)))
    # the size of E's terms: the same products of absolute values
    a = np.abs(z)
    zd = np.abs(d)
    x, xb, u, ub, y, yb, v, vb = (a[:, k, None] for k in range(8))
    A1, B1, C1 = x * (zd + ub + xb), xb * (zd + u + x), zd * zd + zd * ub + zd * u
    A2, B2, C2 = y * (zd + vb + yb), yb * (zd + v + y), zd * zd + zd * vb + zd * v
    N1, N2, D = C1 * B2 + B1 * C2, A1 * C2 + C1 * A2, A1 * B2 + B1 * A2
    return np.abs(E) / (N1 * N2 + D * (N1 + N2))


def loop_residuals(points: ArrayLike, roots: ArrayLike) -> np.ndarray:
    """Relative residuals of the 24 loop equations at roots z (N, 8) complex, (N, 24) out.

    With the rotations theta_j from Cramer's rule: the crank's and the rocker's squared
    lengths in position j against position 0, ``(P_j + theta_j x - A0)(conj) - (x - A0)
    (conj)`` and the same for B (16), and ``theta_j thetab_j - 1`` (8); each over the sum of
    the sizes of its terms.  ``points`` (9, 2) m; the roots in the frame of the points."""
    T = np.asarray(points, float)
    o, s = _frame(T)
    d, db = _displacements(T)
    z = np.atleast_2d(np.asarray(roots, complex)) / s
    th, thb = _rotations(z, d, db)
    x, xb, u, ub, y, yb, v, vb = (z[:, k, None] for k in range(8))
    out = []
    for m, mb, r, rb in ((x, xb, u, ub), (y, yb, v, vb)):
        p, pb = m - r, mb - rb                       # the fixed pivot (A0 or B0)
        e, eb = d + th * m - p, db + thb * mb - pb
        val = e * eb - r * rb
        size = ((np.abs(d) + np.abs(th * m) + np.abs(p))
                * (np.abs(db) + np.abs(thb * mb) + np.abs(pb)) + np.abs(r * rb))
        out.append(np.abs(val) / size)
    out.append(np.abs(th * thb - 1.0) / (1.0 + np.abs(th * thb)))
    return np.concatenate(out, axis=1)


def fourbar_root(points: ArrayLike, A0: ArrayLike, B0: ArrayLike, A1: ArrayLike,
                 B1: ArrayLike) -> np.ndarray:
    """The root z (8,) of a real four-bar: pivots A0, B0, moving pivots A1, B1 when the
    coupler point is at the first point (all (2,), m)."""
    T = np.asarray(points, float)
    c = np.array([1.0, 1j])
    P0 = T[0] @ c
    a0, b0, a1, b1 = (np.asarray(p, float) @ c for p in (A0, B0, A1, B1))
    x, u, y, v = a1 - P0, a1 - a0, b1 - P0, b1 - b0
    return np.array([x, x.conjugate(), u, u.conjugate(), y, y.conjugate(), v, v.conjugate()])


def relabel(z: np.ndarray) -> np.ndarray:
    """The same linkage with its dyads swapped: (N, 8) -> (N, 8)."""
    return np.asarray(z)[..., [4, 5, 6, 7, 0, 1, 2, 3]]


def _cognate(z: np.ndarray) -> np.ndarray:
    """The Roberts cognate that keeps the first fixed pivot (N, 8) -> (N, 8).

    Its crank is the parallelogram side A0-A2 (A2 = A0 + P - A, turning with the coupler)
    and its coupler is A2-P-C (turning with the crank); C = A2 + lam (P - A2) with
    lam = x / (x - y) is the point whose link to the third pivot keeps its length (it turns
    with the rocker).  An involution: applied twice it gives the linkage back."""
    z = np.asarray(z)
    x, xb, u, ub, y, yb, v, vb = (z[..., k] for k in range(8))
    with np.errstate(all="ignore"):
        lam, lamb = x / (x - y), xb / (xb - yb)
    return np.stack([-u, -ub, -x, -xb, (lam - 1) * u, (lamb - 1) * ub, lam * v, lamb * vb],
                    axis=-1)


def cognates(z: ArrayLike) -> np.ndarray:
    """The three Roberts cognates of each root (N, 8) -> (N, 3, 8): the root itself, the
    cognate keeping its first fixed pivot, the cognate keeping its second (each with the
    kept pivot as its first).  :func:`relabel` gives the other three labellings."""
    z = np.atleast_2d(np.asarray(z, complex))
    return np.stack([z, _cognate(z), _cognate(relabel(z))], axis=1)


def _orbit(z: np.ndarray) -> np.ndarray:
    """All six labelled linkages of each root's cognate triple, (N, 8) -> (N, 6, 8)."""
    c = cognates(z)
    return np.concatenate([c, relabel(c)], axis=1)


def _pivots_key(z: np.ndarray) -> np.ndarray:
    """A key of each root's cognate class (N, 8) -> (N, 6): the elementary symmetric
    functions of its three fixed pivots and of their partners (the same for all six)."""
    c = cognates(z)
    p = c[..., 0] - c[..., 2]                 # first fixed pivots A0, A0, B0 ...
    pb = c[..., 1] - c[..., 3]
    # ... and the third: the cognate's second pivot
    third = c[:, 1, 4] - c[:, 1, 6]
    thirdb = c[:, 1, 5] - c[:, 1, 7]
    a, b, cc = p[:, 0], p[:, 2], third
    ab, bb, cb = pb[:, 0], pb[:, 2], thirdb
    return np.stack([a + b + cc, a * b + b * cc + cc * a, a * b * cc,
                     ab + bb + cb, ab * bb + bb * cb + cb * ab, ab * bb * cb], axis=1)


def _unique(w: np.ndarray, tolerance: float, known: np.ndarray | None = None) -> np.ndarray:
    """Indices of the rows of ``w`` (N, m) that are new: not within ``tolerance`` times
    (1 + |w|) of a row of ``known`` nor of an earlier row of ``w`` (sorted by a random real
    projection, so N of thousands costs N log N, not N^2)."""
    w = np.asarray(w, complex)
    k = np.zeros((0, w.shape[1]), complex) if known is None else np.asarray(known, complex)
    allw = np.concatenate([k, w])
    if len(allw) == 0:
        return np.array([], int)
    scale = 1.0 + np.linalg.norm(allw, axis=1)
    direction = np.random.default_rng(12345).standard_normal((w.shape[1], 2))
    proj = allw.real @ direction[:, 0] + allw.imag @ direction[:, 1]
    reach = np.linalg.norm(direction) * tolerance * scale.max()
    order = np.argsort(proj, kind="stable")
    ps = proj[order]
    taken = np.zeros(len(allw), bool)
    taken[:len(k)] = True           # known rows stand; new rows near them are repeats
    keep = []
    # known rows first, then the new ones in their order
    for i in list(range(len(k))) + list(range(len(k), len(allw))):
        if i >= len(k):
            if taken[i]:
                continue
            keep.append(i - len(k))
        pos = np.searchsorted(ps, proj[i] - reach)
        end = np.searchsorted(ps, proj[i] + reach, side="right")
        cand = order[pos:end]
        near = np.linalg.norm(allw[cand] - allw[i], axis=1) <= tolerance * np.maximum(
            scale[cand], scale[i])
        taken[cand[near]] = True
    return np.array(keep, int)


# ---------------------------------------------------------------------------------------
# parameter homotopies

def _segment(p0: np.ndarray, p1: np.ndarray):
    """The homotopy H(z, t) = E(z; (1 - t) p0 + t p1) for tasks p = (d, db) (16,)."""
    dp = p1 - p0

    def H(z, t):
        p = p0 + t[:, None] * dp
        N = len(z)
        E, Ez, Et = _eliminated(z, p[:, :8], p[:, 8:], np.broadcast_to(dp[:8], (N, 8)),
                                np.broadcast_to(dp[8:], (N, 8)))
        return E, Ez, Et
    return H


def _fixed(p: np.ndarray):
    def F(z):
        N = len(z)
        E, Ez, _ = _eliminated(z, np.broadcast_to(p[:8], (N, 8)), np.broadcast_to(p[8:], (N, 8)),
                               np.zeros((N, 8)), np.zeros((N, 8)))
        return E, Ez
    return F


def _carry(z: np.ndarray, route: list[np.ndarray], chunk: int, label: str,
           done: tuple[float, float] = (0.0, 1.0), max_steps: int = 3000,
           ) -> tuple[np.ndarray, np.ndarray]:
    """Follow roots z (N, 8) of the task route[0] through the tasks of ``route`` to its
    last, in chunks of ``chunk`` paths; returns the ends (N, 8) and which arrived (N,)."""
    z = np.array(z, complex)
    ok = np.ones(len(z), bool)
    for lo in range(0, len(z), chunk):
        _progress.report(label, done[0] + (done[1] - done[0]) * lo / max(len(z), 1))
        part = slice(lo, lo + chunk)
        zz, good = z[part], ok[part]
        for p0, p1 in zip(route[:-1], route[1:]):
            r = follow(_segment(p0, p1), zz[good], max_steps=max_steps)
            idx = np.flatnonzero(good)
            zz[idx] = r.z
            good[idx] = r.converged
        zz[good], _, rc = refine(_fixed(route[-1]), zz[good])
        good[np.flatnonzero(good)] &= np.all(np.isfinite(zz[good]), axis=1) & (rc > 1e-13)
        z[part], ok[part] = zz, good
    return z, ok


def _random_task(rng: np.random.Generator) -> np.ndarray:
    """A random complex task (d, db independent), (16,)."""
    return (rng.standard_normal(16) + 1j * rng.standard_normal(16)) / np.sqrt(2)


# the base task: a real four-bar of general proportions (fixed, so results reproduce)
_BASE = dict(A0=(0.0, 0.0), B0=(1.3, 0.2), A1=(0.35, 0.62), B1=(1.55, 1.1), P=(0.9, 1.6))
_BASE_Q = (0.3, 0.9, 1.6, 2.2, 2.9, 3.5, 4.3, 5.0, 5.7)


def base_task() -> tuple[np.ndarray, np.ndarray]:
    """The base task's nine points (9, 2) and its known root (8,) in their frame."""
    import kinelab as kl
    m = fourbar_model(*(np.array(v) for v in _BASE.values()), name="nine-point base")
    sol = kl.analyze(m, q=np.array(_BASE_Q))
    T = sol.position("P")
    r = fourbar_root(T, _BASE["A0"], _BASE["B0"], sol.position("A")[0], sol.position("B")[0])
    return T, r


def _segments(P0: np.ndarray, P1: np.ndarray):
    """The homotopy of each path from its task P0[i] to its task P1[i] (N, 16), for
    :func:`follow` with ``indexed``."""
    dP = P1 - P0

    def H(z, t, rows):
        p = P0[rows] + t[:, None] * dP[rows]
        return _eliminated(z, p[:, :8], p[:, 8:], dP[rows, :8], dP[rows, 8:])
    return H


@dataclass
class _Monodromy:
    """Roots of the base task (one per cognate class) and the loops they are carried
    around: each loop goes from the base task through two random complex tasks and back."""

    base: np.ndarray             # (16,)
    loops: np.ndarray            # (L, 3, 16): the loops' tasks after the base
    reps: np.ndarray             # (k, 8) roots, one per class
    keys: np.ndarray             # (k, 6) class keys
    sent: np.ndarray             # (L,) roots already carried around each loop
    paths: int = 0
    lost: int = 0


def _monodromy(state: _Monodromy, max_classes: int, chunk: int) -> None:
    """Carry every root not yet carried around every loop, all of them at once (a batch
    of (root, loop) pairs, one homotopy per path), adding the new classes found, until no
    loop brings a new one or there are ``max_classes`` classes."""
    L = len(state.loops)
    while len(state.reps) < max_classes:
        pairs = [(i, l) for l in range(L) for i in range(state.sent[l], len(state.reps))]
        if not pairs:
            return
        pairs = pairs[:chunk]
        for i, l in pairs:
            state.sent[l] = max(state.sent[l], i + 1)
        idx = np.array([i for i, _ in pairs])
        loop = np.array([l for _, l in pairs])
        _progress.report(f"nine-point path: monodromy, {len(state.reps)} of {CLASSES} "
                         "cognate classes", min(len(state.reps) / CLASSES, 1.0))
        tasks = [np.broadcast_to(state.base, (len(pairs), 16))] + \
            [state.loops[loop, k] for k in range(3)] + [np.broadcast_to(state.base,
                                                                        (len(pairs), 16))]
        z = state.reps[idx].copy()
        good = np.ones(len(z), bool)
        for k in range(4):
            # a path lost here is no loss: its root comes again around another loop
            rows = np.flatnonzero(good)
            r = follow(_segments(tasks[k][rows], tasks[k + 1][rows]), z[rows], indexed=True,
                       max_steps=_MONODROMY_STEPS)
            z[rows] = r.z
            good[rows] = r.converged
            state.paths += len(rows)
        z, ok = z[good], np.ones(int(good.sum()), bool)
        if len(z):
            z, _, rc = refine(_fixed(state.base), z)
            ok = np.all(np.isfinite(z), axis=1) & (rc > 1e-13)
        state.lost += len(pairs) - int(ok.sum())
        z = z[ok]
        with np.errstate(all="ignore"):
            w = _pivots_key(z)
        fine = np.all(np.isfinite(w), axis=1)
        z, w = z[fine], w[fine]
        new = _unique(w, _DISTINCT, state.keys)
        if len(new):
            state.reps = np.concatenate([state.reps, z[new]])
            state.keys = np.concatenate([state.keys, w[new]])


# ---------------------------------------------------------------------------------------
# the public entry point

class NinePointLinkage(FivePointLinkage):
    """A real four-bar whose coupler point passes through nine points, with its checks: the
    record of :class:`~kinelab.synthesis.FivePointLinkage` (``points``, ``q``, ``rotations``
    and ``errors`` of nine), its fixed pivots ``A0``, ``B0`` found rather than given."""

    def __repr__(self) -> str:
        f = np.array2string
        return (f"NinePointLinkage(A0={f(self.A0, precision=6)}, B0={f(self.B0, precision=6)}, "
                f"{self.grashof.kind}, min transmission "
                f"{math.degrees(self.min_transmission_angle):.1f} deg, {self.state})")


@dataclass(frozen=True, eq=False)
class NinePointSolutions:
    """The four-bars whose coupler point passes through nine points (pivots free).

    ``len()`` is the number of distinct finite roots found, complex ones included, each
    linkage counted once (the relabelling of its dyads is the same linkage) and each of
    the three Roberts cognates counted apart: 4326 for general data when the set is
    complete (Wampler, Morgan and Sommese 1992).

    Attributes
    ----------
    roots : ndarray, shape (k, 8), complex
        Each root (x, xb, u, ub, y, yb, v, vb): ``x = A1 - P_0``, ``u = A1 - A0``,
        ``y = B1 - P_0``, ``v = B1 - B0`` as complex numbers and their isotropic partners,
        m; three consecutive rows are one cognate triple.
    residuals : ndarray, shape (k,)
        Largest relative residual of the 24 loop equations at each root
        (:func:`loop_residuals`).
    up_to_cognates : int
        Cognate triples found (1442 for general data when complete).
    real : SolutionList of NinePointLinkage
        The real roots as checked four-bars, best first by ``order_by``.
    order_by : str
    complete : bool
        The search ran to its end (no ``max_classes`` limit reached, not interrupted).  Even
        then the count is what was found, not a proof: compare it with 1442.
    interrupted : bool
        A KeyboardInterrupt stopped the search; the roots found until then are kept.
    paths : int
        Path segments followed (monodromy and the final homotopy).
    failed : int
        Roots of the base task whose path to the given points was lost (after retries).
    seconds : float
        Wall time of the whole solve, s.
    """

    roots: np.ndarray
    residuals: np.ndarray
    up_to_cognates: int
    real: SolutionList
    order_by: str
    complete: bool
    interrupted: bool
    paths: int
    failed: int
    seconds: float

    def __len__(self) -> int:
        return len(self.roots)

    def __repr__(self) -> str:
        return (f"NinePointSolutions({len(self)} solutions in {self.up_to_cognates} cognate "
                f"triples, {len(self.real)} real, {'complete' if self.complete else 'partial'}"
                f", {self.paths} paths, {self.failed} failed, {self.seconds:.1f} s)")


def _order_key(order_by: str):
    rank = {"crank-rocker": 0, "double-crank": 1, "rocker-crank": 2, "double-rocker": 3}

    def key(s: NinePointLinkage):
        mu = s.min_transmission_angle
        mu = -mu if np.isfinite(mu) else 0.0
        if order_by == "transmission":
            return (not s.valid, mu)
        if order_by == "size":
            return (not s.valid, s.size)
        return (not s.valid, rank.get(s.grashof.kind, 4) if s.grashof.margin > 0 else 4, mu)
    return key


def _points(points) -> np.ndarray:
    T = point_array("points", points, "(9, 2)")
    if T.shape != (9, 2):
        raise ModelError(f"points: expected nine points (x, y), shape (9, 2), got shape "
                         f"{T.shape}; give exactly nine path points")
    size = float(np.ptp(T, axis=0).max())
    if size < MIN_LENGTH:
        raise ModelError(f"points: the points are at most {size:.3g} m apart, less than the "
                         f"smallest length kinelab computes with ({MIN_LENGTH:g} m); give the "
                         "task in smaller units")
    for i in range(8):
        gaps = np.hypot(*(T[i + 1:] - T[i]).T)
        if gaps.min() <= 1e-9 * size:
            j = i + 1 + int(np.argmin(gaps))
            raise ModelError(f"points: points {i + 1} and {j + 1} coincide at {fmt(T[i])}; "
                             "give nine distinct points")
    s = np.linalg.svd(T - T.mean(axis=0), compute_uv=False)
    if s[1] <= 1e-9 * s[0]:
        raise ModelError("points: the nine points lie on one line, which no four-bar's coupler "
                         "curve passes through in general (the task is degenerate); give points "
                         "off a common line")
    return T


def nine_point_path(points: ArrayLike, *, max_classes: int | None = None,
                    order_by: str = "transmission",
                    min_transmission_angle: float = TRANSMISSION_LIMIT, seed: int = 0,
                    chunk: int = 2000) -> NinePointSolutions:
    """Every four-bar whose coupler point passes through nine points (pivots, link lengths
    and timing all free): the complete solution set, by monodromy and a parameter
    homotopy.

    The loop equations are reduced to eight polynomial equations in the moving pivots, the
    crank and the rocker and their isotropic partners (see
    :mod:`kinelab.synthesis._nine_point_path`).  Their roots are found at a fixed base task
    (nine points of a known four-bar's coupler curve) by monodromy, one root of each
    cognate triple, and carried to the given points by a parameter homotopy through a
    random complex task; the cognates follow in closed form.  Each root is refined by
    Newton's method and must solve the 24 loop equations to 1e-10 relative; the real ones
    are four-bars, built as kinelab models and checked by the kinematics engine (branch,
    order and circuit defects, Grashof class, transmission angle).

    Parameters
    ----------
    points : array_like, shape (9, 2)
        The path points, m, in the order the coupler point is to meet them.
    max_classes : int, optional
        Stop the search when this many cognate triples are known (a subset, for a quick
        look); by default the search runs until no route brings a new root.
    order_by : {"transmission", "size", "grashof"}
        How ``real`` is sorted, linkages free of defects first (as
        :func:`five_point_path`).
    min_transmission_angle : float
        Below this (rad, default 30 deg) between the first point and the last, a linkage
        has a transmission angle defect.
    seed : int
        Seed of the random tasks of the homotopies: the result is reproducible.
    chunk : int
        Paths followed at once (memory grows with it, about 40 kB a path).

    Returns
    -------
    NinePointSolutions

    Raises
    ------
    ModelError
        Not nine finite points; repeated or collinear points; an unknown ``order_by``.
    MemoryBudgetError
        ``chunk`` paths at once would exceed :func:`kinelab.memory_budget`.

    Notes
    -----
    The complete set for general data has 4326 roots in 1442 cognate triples (Wampler,
    Morgan and Sommese 1992).  What we observed (nine random points, a shared 2-core
    machine, one run): monodromy stopped with 1438 triples at the base task (4 short of
    1442), and 1430 triples, 4290 roots, 81 of them real, reached the given points (8
    triples lost to the residual test), after 37,252 path segments in 21 minutes (about 30
    segments a second; part of the time another job shared the cores).  So the count is
    what was found, not a proof of completeness: compare ``up_to_cognates`` with 1442.  In
    that run the cognates computed in closed form had residuals up to 6e-7; they are now
    refined by Newton's method (4e-9 at worst, 5 of 4290 above 1e-10, measured on that
    run's roots).  A KeyboardInterrupt stops the search and keeps the roots found until
    then (``interrupted``).

    References
    ----------
    C. W. Wampler, A. P. Morgan and A. J. Sommese, "Complete solution of the nine-point path
    synthesis problem for four-bar linkages", ASME J. Mech. Des. 114 (1992): 153-159.

    Examples
    --------
    Nine points of the catalogue crank-rocker's coupler curve; the search stopped at two
    cognate triples:

    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
    ...                            coupler_point=(1.5, 1.0))
    >>> pts = kl.analyze(fb, q=np.radians(np.arange(0, 360, 40))).position("P")
    >>> sols = kl.synthesis.nine_point_path(pts, max_classes=2)
    >>> len(sols), sols.up_to_cognates
    (6, 2)
    >>> bool(sols.residuals.max() < 1e-10)
    True
    """
    t0 = time.perf_counter()
    T = _points(points)
    check_choice("order_by", order_by, _ORDERS)
    limit = transmission_limit(min_transmission_angle)
    seed = check_seed(seed)
    if max_classes is not None and (isinstance(max_classes, bool)
                                    or not isinstance(max_classes, (int, np.integer))
                                    or max_classes < 1):
        raise ModelError(f"max_classes: expected a positive whole number or None, got "
                         f"{max_classes!r:.40}; give e.g. max_classes=10, or leave it out for "
                         "the complete search")
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ModelError(f"chunk: expected a positive whole number of paths, got {chunk!r:.40}")
    target = max_classes if max_classes is not None else 10 * CLASSES
    _memory.require(min(chunk, target) * PATH_BYTES + min(target, CLASSES) * 6 * 8 * 16 * 8,
                    f"nine_point_path: {min(chunk, target)} paths at once",
                    "give a smaller chunk= (paths followed at once)")
    rng = np.random.default_rng(seed)
    Tb, rb = base_task()
    ob, sb = _frame(Tb)
    d0, db0 = _displacements(Tb)
    d1, db1 = _displacements(T)
    p0, p1 = np.concatenate([d0, db0]), np.concatenate([d1, db1])
    z0 = rb[None] / sb
    loops = np.stack([[_random_task(rng) for _ in range(3)] for _ in range(_LOOPS)])
    state = _Monodromy(base=p0, loops=loops, reps=z0, keys=_pivots_key(z0),
                       sent=np.zeros(_LOOPS, int))
    interrupted = False
    try:
        with _progress.part(0.0, 0.8):
            _monodromy(state, target, chunk)
    except KeyboardInterrupt:
        interrupted = True
    reps = state.reps[:target]
    complete = not interrupted and (max_classes is None or len(state.reps) < max_classes)
    # the base task's roots, carried to the given points through a random complex task
    paths = state.paths
    ends = np.zeros((0, 8), complex)
    failed = 0
    try:
        with _progress.part(0.8, 1.0):
            todo = reps
            for attempt in range(3):
                if len(todo) == 0:
                    break
                route = [p0, _random_task(rng), p1]
                z, ok = _carry(todo, route, chunk, "nine-point path: to the given points")
                paths += 2 * len(todo)
                ends = np.concatenate([ends, z[ok]])
                todo = todo[~ok]
            failed = len(todo)
    except KeyboardInterrupt:
        interrupted, complete = True, False
    # the given points' roots: solved, distinct classes, then the cognates of each
    _, sT = _frame(T)
    with np.errstate(all="ignore"):
        res = np.max(loop_residuals(T, ends * sT), axis=1) if len(ends) else np.zeros(0)
        good = res <= _SOLVED
        ends = ends[good]
        w = _pivots_key(ends)
    first = _unique(w, _DISTINCT)
    ends = ends[first]
    # the cognate map (lam = x / (x - y)) loses digits where x is near y: one Newton
    # refinement of each cognate on the equations brings it back to rounding
    roots = cognates(ends).reshape(-1, 8)
    if len(roots):
        roots, _, _ = refine(_fixed(p1), roots)
    roots = roots * sT
    residuals = np.max(loop_residuals(T, roots), axis=1) if len(roots) else np.zeros(0)
    roots.setflags(write=False)
    residuals.setflags(write=False)
    scale = 1.0 + np.abs(roots)
    real_rows = np.all(np.abs(roots[:, 1::2] - roots[:, 0::2].conj()) <= _REAL * scale[:, 0::2],
                       axis=1)
    linkages, reasons = [], []
    for i in np.flatnonzero(real_rows):
        try:
            linkages.append(_linkage(T, roots[i], limit))
        except ModelError as exc:
            reasons.append(f"real root {i + 1}: {exc}")
    linkages.sort(key=_order_key(order_by))
    return NinePointSolutions(
        roots=roots, residuals=residuals, up_to_cognates=len(ends),
        real=SolutionList(linkages, reason="; ".join(reasons)), order_by=order_by,
        complete=complete, interrupted=interrupted, paths=paths, failed=failed,
        seconds=time.perf_counter() - t0)


def _linkage(T: np.ndarray, root: np.ndarray, limit: float) -> NinePointLinkage:
    """The four-bar of a real root, built and checked by the engine."""
    c = np.array([1.0, 1j])
    P = T @ c
    x, u, y, v = (complex(root[k]) for k in (0, 2, 4, 6))
    th, _ = _rotations(root[None] / 1.0, P[1:] - P[0], (P[1:] - P[0]).conj())
    Q = np.concatenate([[1.0], th[0] / np.abs(th[0])])
    Aj, Bj = P + Q * x, P + Q * y
    A = np.column_stack([Aj.real, Aj.imag])
    B = np.column_stack([Bj.real, Bj.imag])
    a0, b0 = P[0] + x - u, P[0] + y - v
    A0, B0 = np.array([a0.real, a0.imag]), np.array([b0.real, b0.imag])
    model = fourbar_model(A0, B0, A[0], B[0], T[0], name="nine-point path generator")
    planned(model, "points: at the first point", "take another solution")
    q = np.arctan2(A[:, 1] - A0[1], A[:, 0] - A0[0])
    size = max(float(np.ptp(T, axis=0).max()),
               max(model.parameters[k] for k in ("ground", "crank", "coupler", "rocker")))

    def reached(sol, idx):
        return np.linalg.norm(sol.position("P")[idx] - T, axis=-1) <= _REACHED * size

    t = travel(model, q, reached)
    defects = t.defects
    circuit = circuits(A0, B0, A, B, model_grashof(model))
    if circuit is not None and np.any(circuit != circuit[0]):
        lost = ", ".join(str(j + 1) for j in np.flatnonzero(circuit != circuit[0]))
        defects += (f"circuit defect: point(s) {lost} are met on the other circuit of the "
                    "linkage; it cannot move there from the first point without being taken "
                    "apart",)
    circuit_defect = len(defects) > len(t.defects)
    defects += transmission_defects(t.min_transmission_angle, limit,
                                    "between the first point and the last")
    errors = finite_or_inf(np.linalg.norm(at_inputs(model, q).position("P") - T, axis=-1))
    rot = np.angle(Q)
    for arr in (q, rot, errors, A, B):
        arr.setflags(write=False)
    return NinePointLinkage(
        A0=A0, B0=B0, A1=A[0], B1=B[0], points=T, model=model, q=q, rotations=rot,
        errors=errors, coupler_point=model.parameters["coupler_point"],
        grashof=model_grashof(model), min_transmission_angle=t.min_transmission_angle,
        branch_defect=t.branch_defect, order_defect=t.order_defect,
        circuit_defect=circuit_defect, direction=t.direction, defects=defects,
        transmission_limit=limit)
