"""Natural-parameter continuation: predictor-corrector with step halving, for small systems."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ConvergenceError, ModelError, check_choice
from kinelab.solvers._arguments import finite, function, reals, tolerance, whole
from kinelab.solvers._newton import MAX_ITER, _evaluate, newton

__all__ = ["ContinuationResult", "continuation"]

# Halvings of one step: past about 50 the step is below the resolution of p itself.
MAX_HALVINGS = 50
# Parameter values of one path: each is a Python-level step (a few Newton solves), so a path
# of a million values takes minutes; sweep a long range with the planar engine instead.
MAX_PARAMS = 100_000


@dataclass(frozen=True)
class ContinuationResult:
    """Solutions along a parameter path.

    With M parameter values, N paths (absent when ``x0`` was 1-D) and n unknowns:

    Attributes
    ----------
    params : ndarray, shape (M,)
        The parameter values asked for.
    x : ndarray, shape (M, N, n) or (M, n)
        The solution at each value.  Past the first value that could not be reached, the
        last solution reached is repeated (and ``reached`` is False there).
    reached : ndarray of bool, shape (M,)
        The path got to this value, every path converged.
    halvings : ndarray of int, shape (M,)
        How many times the step to this value was halved (0: the full step worked).
    """

    params: np.ndarray
    x: np.ndarray
    reached: np.ndarray
    halvings: np.ndarray


def continuation(fun: Callable, jac: Callable, x0: ArrayLike, params: ArrayLike, *,
                 dfun_dp: Callable | None = None, tol: float = 1e-12, max_iter: int = 8,
                 max_halvings: int = 12,
                 on_failure: Literal["raise", "mask"] = "raise") -> ContinuationResult:
    """Follow the solutions of ``Φ(x, p) = 0`` as the parameter p runs through ``params``.

    From the solution at one value of p, predict the solution at the next and correct it
    with a few Newton steps (:func:`newton`).  The predictor is the tangent
    ``Δx = -J⁻¹ ∂Φ/∂p Δp`` when ``dfun_dp`` is given (the velocity coefficients K of a
    mechanism), otherwise the secant through the last two solutions.  When the corrector
    fails (no convergence in ``max_iter`` steps, a singular Jacobian, or slow contraction
    of its first steps, the sign of a guess sliding toward another branch), the
    parameter step is halved and tried again.  The contraction test catches many, not
    all, branch changes: keep the steps of ``params`` small against the distance between
    assembly modes, and give ``dfun_dp``.  Generic and simple: one small system (or N
    paths advanced together, halving together); the planar engine has its own compiled
    continuation.

    Parameters
    ----------
    fun, jac : callable
        ``fun(x, p)`` with ``x`` of shape (N, n) and p a float returns Φ, shape (N, n);
        ``jac(x, p)`` returns ``∂Φ/∂x``, shape (N, n, n).
    x0 : array_like, shape (n,) or (N, n)
        A (rough) solution at ``params[0]``; it is corrected first.
    params : array_like, shape (M,)
        Parameter values, in order (increasing or decreasing); at most 100,000 of them.
    dfun_dp : callable, optional
        ``dfun_dp(x, p)`` returns ``∂Φ/∂p``, shape (N, n), for the tangent predictor.
    tol, max_iter :
        Passed to :func:`newton` for each correction.
    max_halvings : int, default 12
        Halvings of one step before giving up (the step is then ``Δp / 2**12``), from 0 to
        50.  A step halved below the resolution of p counts as a step that cannot advance.
    on_failure : {'raise', 'mask'}, default 'raise'
        Raise :class:`~kinelab.errors.ConvergenceError` where the path cannot advance, or
        return with ``reached`` False from there on.

    Returns
    -------
    ContinuationResult
        ``params``, ``x``, ``reached``, ``halvings``.

    Raises
    ------
    ConvergenceError
        (``on_failure='raise'``) The path could not advance past some p: usually a limit
        position (the input cannot go further) or a singular configuration.  ``err.result``
        holds what was reached.

    Examples
    --------
    The slider-crank of *Mecanismos*, Ex. 4.4 (L2 = L3 = 1) followed as θ2 turns from 45° to
    80°; the rod angle stays θ3 = -θ2:

    >>> def fun(x, th2):
    ...     th3, l = x[:, 0], x[:, 1]
    ...     return np.stack([np.cos(th2) + np.cos(th3) - l, np.sin(th2) + np.sin(th3)], -1)
    >>> def jac(x, th2):
    ...     th3 = x[:, 0]
    ...     return np.stack([np.stack([-np.sin(th3), -np.ones_like(th3)], -1),
    ...                      np.stack([np.cos(th3), np.zeros_like(th3)], -1)], -2)
    >>> th2 = np.radians(np.linspace(45.0, 80.0, 8))
    >>> path = kl.solvers.continuation(fun, jac, [-0.7, 1.4], th2)
    >>> bool(path.reached.all()), bool(np.allclose(path.x[:, 0], -th2, atol=1e-12))
    (True, True)
    """
    check_choice("on_failure", on_failure, ("raise", "mask"))
    function("fun", fun)
    function("jac", jac)
    if dfun_dp is not None:
        function("dfun_dp", dfun_dp)
    tolerance("tol", tol)
    whole("max_iter", max_iter, 1, MAX_ITER)
    max_halvings = whole("max_halvings", max_halvings, 0, MAX_HALVINGS)
    params = reals("params", params)
    if params.ndim != 1 or params.size == 0:
        raise ModelError(f"params: expected a 1-D array of finite values, got shape "
                         f"{params.shape}")
    if params.size > MAX_PARAMS:
        raise ModelError(f"params: expected at most {MAX_PARAMS:,} values, got "
                         f"{params.size:,}; each is one step of a Python loop: take fewer, "
                         f"or sweep a mechanism with kinelab.analyze")
    finite("params", params)
    steps = np.diff(params)
    if params.size > 1 and not (np.all(steps > 0) or np.all(steps < 0)):
        raise ModelError("params: expected strictly increasing or strictly decreasing "
                         "values; sort them, and drop repeats")
    x = np.array(reals("x0", x0))
    if x.ndim not in (1, 2) or x.shape[-1] == 0:
        raise ModelError(f"x0: expected shape (n,) or (N, n) with n >= 1, got {x.shape}")
    finite("x0", x, "give a starting solution")
    batched = x.ndim == 2
    x = np.atleast_2d(x)

    def correct(guess, p):
        return newton(lambda z: fun(z, p), lambda z: jac(z, p), guess, tol=tol,
                      max_iter=max_iter, on_failure="mask", history=True)

    M = params.size
    xs = np.empty((M,) + x.shape)
    reached = np.zeros(M, dtype=bool)
    halvings = np.zeros(M, dtype=int)
    first = correct(x, params[0])
    failure = None
    if first.converged.all():
        xs[0], reached[0] = first.x, True
    else:
        failure = (params[0], first)
    previous = None                  # (p, x) of the solution before the current one
    for i in range(1, M):
        if failure is not None:
            break
        p_from, x_from = params[i - 1], xs[i - 1]
        p_to = params[i]
        slope = _slope(jac, dfun_dp, x_from, p_from, previous)     # kept while halving
        while True:
            dp = p_to - p_from
            result = correct(x_from + slope * dp, p_to)
            if result.converged.all() and _contracts(result.history):
                previous = (p_from, x_from)
                p_from, x_from = p_to, result.x
                if p_to == params[i]:
                    break
                p_to = params[i]
                slope = _slope(jac, dfun_dp, x_from, p_from, previous)
            elif halvings[i] < max_halvings and p_from + dp / 2 != p_from:
                halvings[i] += 1
                p_to = p_from + dp / 2
            else:
                failure = (p_to, result)
                break
        if failure is not None:
            break
        xs[i], reached[i] = x_from, True

    last = int(np.flatnonzero(reached)[-1]) if reached.any() else -1
    if last < M - 1:
        xs[last + 1:] = xs[last] if last >= 0 else x
    out = ContinuationResult(params=params, x=xs if batched else xs[:, 0],
                             reached=reached, halvings=halvings)
    if failure is not None and on_failure == "raise":
        p_fail, result = failure
        error = ConvergenceError(
            f"continuation could not advance past p = {params[max(last, 0)]:.6g} toward "
            f"p = {p_fail:.6g} (step halved {int(halvings[min(last + 1, M - 1)])} times; last residual max|Φ| = "
            f"{np.max(result.residual_norm):.3g}); a limit position (the input cannot go "
            f"further) or a singular configuration lies there; stop the range before it, "
            f"or pass on_failure='mask' to keep the part reached")
        error.result = out
        raise error
    return out


def _slope(jac, dfun_dp, x, p, previous) -> np.ndarray:
    """dx/dp of the predictor x + slope dp: the tangent -J^-1 ∂Φ/∂p when ∂Φ/∂p is given,
    else the secant through the last two solutions, else zero (the first step without
    ∂Φ/∂p stays at the last solution)."""
    if dfun_dp is not None:
        N, n = x.shape
        J = _evaluate(lambda z: jac(z, p), x, (N, n, n), "jac")
        rhs = -_evaluate(lambda z: dfun_dp(z, p), x, (N, n), "dfun_dp")[..., None]
        try:
            return np.linalg.solve(J, rhs)[..., 0]
        except np.linalg.LinAlgError:     # singular here: fall back to the secant
            pass
    if previous is not None:
        p_prev, x_prev = previous
        return (x - x_prev) / (p - p_prev)
    return np.zeros_like(x)


def _contracts(history) -> bool:
    """The corrector started inside Newton's quadratic basin: its second step is at most
    half its first, on every path (the contraction test of continuation methods).  A
    guess that slid toward another branch (assembly mode) fails it, and the step is
    halved instead of silently changing branch."""
    size = np.max(np.abs(history.step), axis=-1)          # (K, N)
    if size.shape[0] < 2:
        return True
    return bool(np.all((size[1] <= 0.5 * size[0]) | (size[0] == 0)))
