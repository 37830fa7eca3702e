"""Polynomial homotopy continuation: every isolated root of a square polynomial system.

A start system ``G`` whose roots are known is deformed into the target ``F`` along

    H(z, t) = (1 - t) gamma G(z) + t F(z),      t from 0 to 1,

with a random complex ``gamma`` (the "gamma trick": for all but finitely many gamma, no path
meets a singular point for t < 1, so paths neither cross nor turn back; Morgan, *Solving
polynomial systems using continuation for engineering and scientific problems*, 1987).
Every path is followed by a predictor (classical Runge-Kutta on the Davidenko equation
``H_z dz/dt = -H_t``) and a Newton corrector, with a step of its own that doubles after
three accepted steps and halves after a rejected one.  All paths move at once: each step
is a batch of small linear solves over every path still running (numpy), and only the
steps are a Python loop.

Systems are given as vectorised callables ``f(z) -> (values, jacobian)`` with ``z`` of
shape (N, n) complex, values (N, n) and jacobian (N, n, n).  Paths to infinity are best
handled by homogeneous coordinates on a random affine patch (see
:func:`multihomogeneous_start`): every path then stays bounded, and a root at infinity
ends with its homogenising coordinate at zero.
"""
from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

__all__ = ["HomotopyResult", "track", "follow", "refine", "multihomogeneous_start", "with_rows",
           "distinct"]

System = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]

# path status codes
CONVERGED, STALLED, DIVERGED = 0, 1, 2
STATUS = {CONVERGED: "converged", STALLED: "stalled", DIVERGED: "diverged"}


@dataclass(frozen=True, eq=False)
class HomotopyResult:
    """Where the paths of a homotopy end.

    Attributes
    ----------
    z : ndarray, shape (N, n), complex
        Each path's last point (at t = 1 when it got there).
    t : ndarray, shape (N,)
        How far each path got.
    status : ndarray of int, shape (N,)
        0 reached t = 1, 1 stalled (its step fell below ``min_step`` or it ran out of steps:
        a singular end, or a near-crossing), 2 left every bound (non-finite).
    steps : ndarray of int, shape (N,)
        Accepted steps of each path.
    rejected : ndarray of int, shape (N,)
        Rejected (halved) steps of each path.
    gamma : complex
    """

    z: np.ndarray
    t: np.ndarray
    status: np.ndarray
    steps: np.ndarray
    rejected: np.ndarray
    gamma: complex

    @property
    def converged(self) -> np.ndarray:
        """(N,) bool: the path reached t = 1."""
        return self.status == CONVERGED


def _solve(J: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Batched ``J x = b`` (J (N, n, n), b (N, n)); rows with a singular J give NaN and
    False in the second output."""
    ok = np.ones(len(b), bool)
    try:
        x = np.linalg.solve(J, b[..., None])[..., 0]
    except np.linalg.LinAlgError:
        x = np.empty_like(b)
        for i in range(len(b)):          # rare: only when some J is exactly singular
            try:
                x[i] = np.linalg.solve(J[i], b[i])
            except np.linalg.LinAlgError:
                x[i] = np.nan
                ok[i] = False
    ok &= np.all(np.isfinite(x), axis=1)
    return x, ok


def track(target: System, start: System, starts: np.ndarray, *, gamma: complex,
          first_step: float = 0.02, max_step: float = 0.1, min_step: float = 1e-13,
          max_steps: int = 3000, tolerance: float = 1e-9, max_correction: float = 0.02,
          ) -> HomotopyResult:
    """Follow the roots ``starts`` of ``start`` to roots of ``target``.

    Parameters
    ----------
    target, start : callable
        ``f(z) -> (values (N, n), jacobian (N, n, n))`` for z (N, n) complex.
    starts : ndarray, shape (N, n)
        Roots of ``start`` (one path each).
    gamma : complex
        The gamma of the homotopy (random, on the unit circle).
    first_step, max_step, min_step : float
        Steps in t.
    max_steps : int
        Steps (accepted or not) after which a path still running stalls.
    tolerance : float
        A corrected point is accepted when three Newton steps bring the last correction
        below ``tolerance`` times (1 + |z|).
    max_correction : float
        ... and the first correction is at most this times (1 + |z|): a larger one means
        the predictor left the path's neighbourhood, where it could jump to another path.

    Returns
    -------
    HomotopyResult
    """
    def H(zz, tt):
        f, Jf = target(zz)
        g, Jg = start(zz)
        s = ((1.0 - tt) * gamma)[:, None]
        tt1 = tt[:, None]
        return s * g + tt1 * f, s[..., None] * Jg + tt1[..., None] * Jf, f - gamma * g

    return follow(H, starts, gamma=gamma, first_step=first_step, max_step=max_step,
                  min_step=min_step, max_steps=max_steps, tolerance=tolerance,
                  max_correction=max_correction)


def follow(H: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]],
           starts: np.ndarray, *, gamma: complex = 1.0, first_step: float = 0.02,
           max_step: float = 0.1, min_step: float = 1e-13, max_steps: int = 3000,
           tolerance: float = 1e-9, max_correction: float = 0.02,
           indexed: bool = False) -> HomotopyResult:
    """Follow the roots ``starts`` of ``H(z, 0)`` to roots of ``H(z, 1)``, for any homotopy
    given as ``H(z (N, n), t (N,)) -> (values (N, n), H_z (N, n, n), H_t (N, n))``: the
    predictor-corrector of :func:`track` (which calls it with the gamma homotopy), also for
    parameter homotopies.  Same keywords as :func:`track`; ``gamma`` is only recorded.
    With ``indexed``, H is called as ``H(z, t, rows)``, ``rows`` the indices into
    ``starts`` of the paths given: each path may have a homotopy of its own (its own
    parameters), and still all move at once."""
    z = np.array(starts, complex)
    N = len(z)
    t = np.zeros(N)
    h = np.full(N, float(first_step))
    status = np.full(N, -1)
    steps = np.zeros(N, int)
    rejected = np.zeros(N, int)
    good = np.zeros(N, int)          # accepted steps in a row

    def velocity(zz, tt, rows):
        _, Hz, Ht = Hr(zz, tt, rows)
        v, ok = _solve(Hz, -Ht)
        return v, ok

    Hr = H if indexed else (lambda zz, tt, rows: H(zz, tt))
    with np.errstate(all="ignore"):
        for _ in range(max_steps):
            run = np.flatnonzero(status < 0)
            if run.size == 0:
                break
            zr, tr = z[run], t[run]
            hr = np.minimum(h[run], 1.0 - tr)
            hh = hr[:, None]
            k1, ok1 = velocity(zr, tr, run)
            k2, ok2 = velocity(zr + 0.5 * hh * k1, tr + 0.5 * hr, run)
            k3, ok3 = velocity(zr + 0.5 * hh * k2, tr + 0.5 * hr, run)
            k4, ok4 = velocity(zr + hh * k3, tr + hr, run)
            zp = zr + hh / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
            t1 = tr + hr
            size = 1.0 + np.linalg.norm(zr, axis=1)
            ok = ok1 & ok2 & ok3 & ok4
            first = None
            for it in range(3):
                Hv, Hz, _ = Hr(zp, t1, run)
                dz, oks = _solve(Hz, -Hv)
                ok &= oks
                zp = zp + np.where(ok[:, None], dz, 0.0)
                norm = np.linalg.norm(np.where(ok[:, None], dz, 0.0), axis=1)
                if it == 0:
                    first = norm
            accept = ok & (first <= max_correction * size) & (norm <= tolerance * size) \
                & np.all(np.isfinite(zp), axis=1)
            # accepted: move on, and lengthen the step after three in a row
            a = run[accept]
            z[a], t[a] = zp[accept], t1[accept]
            t[a[t[a] >= 1.0]] = 1.0
            steps[a] += 1
            good[a] += 1
            grow = a[good[a] >= 3]
            h[grow] = np.minimum(2.0 * h[grow], max_step)
            good[grow] = 0
            status[a[t[a] >= 1.0]] = CONVERGED
            # rejected: halve the step
            r = run[~accept]
            rejected[r] += 1
            good[r] = 0
            h[r] *= 0.5
            status[r[h[r] < min_step]] = STALLED
            bad = ~np.all(np.isfinite(z), axis=1)
            status[bad] = DIVERGED
    status[status < 0] = STALLED
    return HomotopyResult(z=z, t=t, status=status, steps=steps, rejected=rejected,
                          gamma=complex(gamma))


def refine(system: System, z: np.ndarray, *, iterations: int = 8,
           tolerance: float = 1e-14) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Newton's method on ``system`` from each row of ``z`` (N, n), all at once.

    Returns the refined points (N, n), the last correction's size relative to (1 + |z|)
    (N,), and the reciprocal condition number of the Jacobian there (N,) (0 where it is
    singular or not finite)."""
    z = np.array(z, complex)
    last = np.full(len(z), np.inf)
    with np.errstate(all="ignore"):
        live = np.all(np.isfinite(z), axis=1)
        for _ in range(iterations):
            if not live.any():
                break
            f, J = system(z[live])
            dz, ok = _solve(J, -f)
            idx = np.flatnonzero(live)
            step = np.where(ok[:, None], dz, 0.0)
            z[idx] = z[idx] + step
            last[idx] = np.where(ok, np.linalg.norm(step, axis=1)
                                 / (1.0 + np.linalg.norm(z[idx], axis=1)), np.inf)
            live[idx] = ok & (last[idx] > tolerance)
        rcond = np.zeros(len(z))
        fine = np.all(np.isfinite(z), axis=1)
        if fine.any():
            _, J = system(z[fine])
            fine_J = np.all(np.isfinite(J), axis=(1, 2))
            s = np.linalg.svd(np.where(fine_J[:, None, None], J, 0.0), compute_uv=False)
            rc = np.where(fine_J & (s[:, 0] > 0), s[:, -1] / np.where(s[:, 0] > 0, s[:, 0], 1.0),
                          0.0)
            rcond[fine] = rc
    return z, last, rcond


def with_rows(system: System, rows: System) -> System:
    """``system`` with the equations of ``rows`` appended (e.g. the affine patches)."""
    def both(z):
        f, J = system(z)
        g, K = rows(z)
        return np.concatenate([f, g], axis=1), np.concatenate([J, K], axis=1)
    return both


def multihomogeneous_start(groups: Sequence[Sequence[int]], degrees: np.ndarray,
                           rng: np.random.Generator) -> tuple[System, System, np.ndarray]:
    """A random linear-product start system of given multidegrees, and all its roots.

    The unknowns ``z`` (n of them) are split into groups of homogeneous coordinates: group
    k holds ``len(groups[k])`` coordinates (its affine unknowns and one homogenising
    coordinate), and lies on a random affine patch ``c_k . z_k = 1``.  Equation i has
    degree ``degrees[i, k]`` in group k; its start equation is a product of that many random
    linear forms in each group.  Its roots: assign each equation to a group, each group k
    getting ``len(groups[k]) - 1`` equations with a factor in it, pick one factor of each,
    and solve each group's linear system with its patch.  Their number is the
    multihomogeneous Bezout number.

    Parameters
    ----------
    groups : sequence of sequences of int
        The indices into z of each group's coordinates; together they cover z once.
    degrees : ndarray of int, shape (m, len(groups))
        m = n - len(groups) equations (the patches make the rest).
    rng : numpy Generator

    Returns
    -------
    start : callable
        The start system, its m product equations followed by the patches (n rows).
    patches : callable
        The patch equations alone (len(groups) rows), to append to the target
        (:func:`with_rows`).
    roots : ndarray, shape (B, n), complex
    """
    degrees = np.asarray(degrees, int)
    n = sum(len(g) for g in groups)
    m = degrees.shape[0]
    G = len(groups)

    def rand(*shape):
        return (rng.standard_normal(shape) + 1j * rng.standard_normal(shape)) / np.sqrt(2)

    # the linear forms: forms[i][k] has shape (degrees[i, k], len(groups[k]))
    forms = [[rand(degrees[i, k], len(groups[k])) for k in range(G)] for i in range(m)]
    patch = [rand(len(g)) for g in groups]
    idx = [np.asarray(g) for g in groups]

    def patches(z):
        vals = np.stack([z[:, idx[k]] @ patch[k] - 1.0 for k in range(G)], axis=1)
        J = np.zeros((len(z), G, n), complex)
        for k in range(G):
            J[:, k, idx[k]] = patch[k]
        return vals, J

    # every equation's factors as rows of one array (m, D, n), padded to the same count D
    # with constant factors 1: the products and their gradients are then one batched
    # computation (no loop over equations on the hot path)
    D = int(degrees.sum(axis=1).max())
    W = np.zeros((m, D, n), complex)
    pad = np.zeros((m, D))
    for i in range(m):
        f = 0
        for k in range(G):
            L = forms[i][k]
            W[i, f:f + len(L)][:, idx[k]] = L
            f += len(L)
        pad[i, f:] = 1.0

    def products(z):
        fac = np.einsum("Nn,mfn->Nmf", z, W) + pad                 # (N, m, D)
        ones = np.ones(fac.shape[:2] + (1,), complex)
        before = np.cumprod(np.concatenate([ones, fac[..., :-1]], axis=2), axis=2)
        after = np.cumprod(np.concatenate([ones, fac[..., :0:-1]], axis=2), axis=2)[..., ::-1]
        others = before * after                                    # product of the other factors
        return before[..., -1] * fac[..., -1], np.einsum("Nmf,mfn->Nmn", others, W)

    start = with_rows(products, patches)
    roots = []
    need = [len(g) - 1 for g in groups]
    for assign in itertools.product(range(G), repeat=m):
        if [assign.count(k) for k in range(G)] != need:
            continue
        if any(degrees[i, assign[i]] == 0 for i in range(m)):
            continue
        for pick in itertools.product(*[range(degrees[i, assign[i]]) for i in range(m)]):
            z = np.zeros(n, complex)
            for k in range(G):
                eqs = [i for i in range(m) if assign[i] == k]
                A = np.vstack([forms[i][k][pick[i]] for i in eqs] + [patch[k]])
                b = np.zeros(len(groups[k]), complex)
                b[-1] = 1.0
                z[idx[k]] = np.linalg.solve(A, b)
            roots.append(z)
    return start, patches, np.array(roots).reshape(-1, n)


def distinct(z: np.ndarray, tolerance: float) -> np.ndarray:
    """Indices of the rows of ``z`` (N, n) kept when rows within ``tolerance`` times
    (1 + |z|) of an earlier kept row are dropped as repeats (sorted: first of each)."""
    keep: list[int] = []
    if len(z) == 0:
        return np.array([], int)
    scale = 1.0 + np.linalg.norm(z, axis=1)
    d = np.linalg.norm(z[:, None, :] - z[None, :, :], axis=2)    # (N, N): N is a few hundred
    taken = np.zeros(len(z), bool)
    for i in range(len(z)):
        if taken[i]:
            continue
        keep.append(i)
        taken |= d[i] <= tolerance * np.maximum(scale, scale[i])
    return np.array(keep, int)
