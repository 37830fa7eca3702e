"""Batched Newton-Raphson with an analytic Jacobian, and its iteration table."""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ConvergenceError, ModelError, SingularityError, check_choice, describe
from kinelab.model import name_problem
from kinelab.solvers._arguments import finite as check_finite, flag, function, reals, tolerance, whole

__all__ = ["NewtonHistory", "NewtonResult", "iteration_table", "newton"]

_ON_FAILURE = ("raise", "mask")
_SHOWN = 10  # failing samples named in a message
MAX_ITER = 10_000     # Newton steps a sample may be allowed: quadratic convergence needs few
# The rounding of Φ: a change of one unit in the last place of each unknown moves row i of Φ
# by about eps Σ_j |J_ij| |x_j|; a residual within a few dozen times that is zero for Φ.
_ROUNDING = 64 * np.finfo(float).eps


@dataclass(frozen=True)
class NewtonHistory:
    """Every iterate of a Newton-Raphson solve: the rows of the notes' iteration table.

    Row ``k`` holds the iterate ``x⁽ᵏ⁾``, its residual ``Φ(x⁽ᵏ⁾)`` and the step
    ``Δx⁽ᵏ⁾`` solved from ``J Δx⁽ᵏ⁾ = -Φ(x⁽ᵏ⁾)``, so ``x⁽ᵏ⁺¹⁾ = x⁽ᵏ⁾ + Δx⁽ᵏ⁾``.  With K rows,
    N samples and n unknowns (the N axis is absent when ``x0`` was 1-D, as in the result):

    Attributes
    ----------
    x, residual, step : ndarray, shape (K, N, n) or (K, n)
        Iterates (units of the unknowns), residuals (units of Φ), steps.  After a sample
        stops (converged or failed) its rows repeat its final x with a zero step.
    active : ndarray of bool, shape (K, N) or (K,)
        The sample was being iterated at row k.
    """

    x: np.ndarray
    residual: np.ndarray
    step: np.ndarray
    active: np.ndarray

    @property
    def batched(self) -> bool:
        return self.active.ndim == 2

    def sample(self, index: int = 0) -> NewtonHistory:
        """The rows of one sample, while it was iterated: arrays of shape (k, n)."""
        if isinstance(index, (bool, np.bool_)) or not isinstance(index, (int, np.integer)):
            raise ModelError(f"sample: expected the index of a sample, got {describe(index)}")
        if not self.batched:
            if index != 0:
                raise ModelError(f"sample: expected 0 for an unbatched solve, got {index}")
            keep = self.active
            return NewtonHistory(self.x[keep], self.residual[keep], self.step[keep], keep[keep])
        count = self.active.shape[1]
        if not -count <= index < count:
            raise ModelError(f"sample: expected an index in [0, {count}), got {index}")
        keep = self.active[:, index]
        return NewtonHistory(self.x[keep, index], self.residual[keep, index],
                             self.step[keep, index], keep[keep])

    def to_dataframe(self, names: Sequence[str] | None = None):
        """The table as a pandas DataFrame, one row per (iteration, sample) iterated.

        Columns: ``k``, ``sample`` (batched solves only), the unknowns' ``names``
        (default ``x1 … xn``), the residuals ``phi1 … phin`` and the steps ``d<name>``.
        Values are in the units of the unknowns and of Φ (rad stays rad).
        """
        import pandas as pd  # lazy: only needed for export

        names = _names(names, self.x.shape[-1])
        x, residual, step, active = (self.x, self.residual, self.step, self.active)
        if not self.batched:
            x, residual, step, active = x[:, None], residual[:, None], step[:, None], \
                active[:, None]
        k, sample = np.nonzero(active)
        columns = {"k": k}
        if self.batched:
            columns["sample"] = sample
        columns.update({name: x[k, sample, i] for i, name in enumerate(names)})
        columns.update({f"phi{i + 1}": residual[k, sample, i] for i in range(len(names))})
        columns.update({f"d{name}": step[k, sample, i] for i, name in enumerate(names)})
        return pd.DataFrame(columns)


@dataclass(frozen=True)
class NewtonResult:
    """The outcome of :func:`newton`.

    With ``x0`` of shape (N, n) the per-sample fields have a leading N axis; with ``x0``
    of shape (n,) they have none.

    Attributes
    ----------
    x : ndarray, shape (N, n) or (n,)
        The last iterate (the solution where ``converged``), units of the unknowns.
    converged : ndarray of bool, shape (N,) or ()
    iterations : ndarray of int, shape (N,) or ()
        Newton steps taken by each sample.
    residual_norm : ndarray, shape (N,) or ()
        ``max |Φ(x)|`` at the returned x, units of Φ.
    singular : ndarray of bool, shape (N,) or ()
        The sample stopped because its Jacobian was singular (see ``rcond``).
    history : NewtonHistory or None
        Every iterate, when asked for with ``history=True``.
    """

    x: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray
    residual_norm: np.ndarray
    singular: np.ndarray
    history: NewtonHistory | None = None

    def __repr__(self) -> str:
        return (f"NewtonResult(x={self.x!r}, converged={self.converged!r}, "
                f"iterations={self.iterations!r}, residual_norm={self.residual_norm!r})")


def newton(fun: Callable[[np.ndarray], ArrayLike], jac: Callable[[np.ndarray], ArrayLike],
           x0: ArrayLike, *, tol: float = 1e-12, max_iter: int = 50, history: bool = False,
           on_failure: Literal["raise", "mask"] = "raise",
           rcond: float = 1e-13) -> NewtonResult:
    """Solve ``Φ(x) = 0`` by Newton-Raphson, for N independent samples at once.

    Each iteration evaluates ``Φ`` and its Jacobian ``J = ∂Φ/∂x`` for the whole batch,
    solves ``J Δx = -Φ`` for every sample with one batched ``numpy.linalg.solve`` and sets
    ``x ← x + Δx``.  A sample has converged when the step of every unknown is small,
    ``|Δx_j| <= tol (1 + |x_j|)`` (the notes' criterion, "increments below a tolerance",
    made relative for large unknowns, each unknown on its own scale), and the residual it
    leaves is small too: ``|Φ_i(x)| <= sqrt(tol) max(1, max |Φ(x0)|)`` or within the
    rounding of Φ, ``|Φ_i(x)| <= 64 eps Σ_j |J_ij| |x_j|``.  From then on it is held fixed.
    The residual check keeps a small step that left a large residual, in unknowns of very
    different sizes, from passing for a root.

    Parameters
    ----------
    fun : callable
        ``fun(x)`` with ``x`` of shape (N, n) returns the residuals ``Φ``, shape (N, n).
        It is always called with the whole batch (converged rows included, unchanged), so
        it may close over per-sample parameters of length N.
    jac : callable
        ``jac(x)`` returns the analytic Jacobian ``∂Φ/∂x``, shape (N, n, n), with
        ``jac(x)[s, i, j] = ∂Φ_i/∂x_j`` at sample s.
    x0 : array_like, shape (n,) or (N, n)
        Starting guess; units of the unknowns (rad, m, ...).  With shape (n,), ``fun`` and
        ``jac`` get N = 1 and the result drops the sample axis.  A complex ``x0`` makes
        the iteration complex (for complex roots of polynomial systems).
    tol : float, default 1e-12
        Step tolerance (above), a positive number below 1.
    max_iter : int, default 50
        Newton steps allowed per sample, from 1 to 10,000.
    history : bool, default False
        Keep every iterate in ``result.history`` (see :func:`iteration_table`).
    on_failure : {'raise', 'mask'}, default 'raise'
        What to do with samples that did not converge: raise (after finishing the others)
        or report them in ``result.converged`` and ``result.singular``.
    rcond : float, default 1e-13
        A Jacobian whose smallest to largest singular value ratio is below this (a number
        from 0 to below 1) is singular: the sample stops there instead of taking a
        meaningless step.

    Returns
    -------
    NewtonResult
        ``x``, ``converged``, ``iterations``, ``residual_norm``, ``singular``, ``history``.

    Raises
    ------
    SingularityError
        (``on_failure='raise'``) A sample met a singular Jacobian; the message names the
        samples, the iteration and the iterate.  ``err.result`` holds the whole result.
    ConvergenceError
        (``on_failure='raise'``) Some samples did not converge in ``max_iter`` steps or
        diverged to non-finite values; the message names them with their last residual.
        ``err.result`` holds the whole result.
    ModelError
        Bad arguments, or ``fun`` / ``jac`` returning anything but numbers in arrays of
        the right shape.

    References
    ----------
    *Mecanismos*, §4.7, eqs. 38-46 and Ex. 4.4.

    Examples
    --------
    *Mecanismos*, Ex. 4.4: slider-crank with L2 = L3 = 1 and θ2 = 45°; unknowns θ3 and the
    slider position l, ``Φ1 = cos θ2 + cos θ3 - l``, ``Φ2 = sin θ2 + sin θ3``:

    >>> th2 = np.radians(45.0)
    >>> def fun(x):
    ...     th3, l = x[:, 0], x[:, 1]
    ...     return np.stack([np.cos(th2) + np.cos(th3) - l, np.sin(th2) + np.sin(th3)], -1)
    >>> def jac(x):
    ...     th3 = x[:, 0]
    ...     return np.stack([np.stack([-np.sin(th3), -np.ones_like(th3)], -1),
    ...                      np.stack([np.cos(th3), np.zeros_like(th3)], -1)], -2)
    >>> sol = kl.solvers.newton(fun, jac, [np.radians(-60.0), 1.0], history=True)
    >>> round(float(np.degrees(sol.x[0])), 10), round(float(sol.x[1]), 8), int(sol.iterations)
    (-45.0, 1.41421356, 5)
    >>> print(kl.solvers.iteration_table(sol.history, names=["theta3", "l"]))
     k     theta3          l       phi1       phi2    dtheta3         dl
     0     -1.047          1     0.2071    -0.1589     0.3178     0.4824
     1    -0.7294      1.482   -0.02965    0.04071   -0.05461   -0.06604
     2     -0.784      1.416  -0.001093   0.001013  -0.001431   -0.002104
     3    -0.7854      1.414 -7.249e-07  7.236e-07 -1.023e-06 -1.448e-06
     4    -0.7854      1.414 -3.704e-13  3.701e-13 -5.235e-13 -7.405e-13

    A batch: 1000 crank angles at once (one solve per iteration for all of them):

    >>> th2 = np.radians(np.linspace(0.0, 80.0, 1000))
    >>> x0 = np.tile([np.radians(-60.0), 1.0], (1000, 1))
    >>> sol = kl.solvers.newton(fun, jac, x0)
    >>> sol.x.shape, bool(sol.converged.all()), bool(np.allclose(sol.x[:, 0], -th2))
    ((1000, 2), True, True)
    """
    function("fun", fun)
    function("jac", jac)
    check_choice("on_failure", on_failure, _ON_FAILURE)
    max_iter = whole("max_iter", max_iter, 1, MAX_ITER)
    tol = tolerance("tol", tol)
    rcond = tolerance("rcond", rcond, zero=True)
    history = flag("history", history)
    x = np.array(reals("x0", x0, complex_ok=True))      # complex x0 stays complex
    batched = x.ndim == 2
    if x.ndim not in (1, 2) or x.shape[-1] == 0:
        raise ModelError(f"x0: expected shape (n,) or (N, n) with n >= 1, got {x.shape}")
    check_finite("x0", x, "give a starting guess")
    x = np.atleast_2d(x)
    N, n = x.shape

    active = np.ones(N, dtype=bool)
    converged = np.zeros(N, dtype=bool)
    singular = np.zeros(N, dtype=bool)
    diverged = np.zeros(N, dtype=bool)
    iterations = np.zeros(N, dtype=int)
    last_step = np.zeros(N)
    stopped_at = {}  # sample -> (iteration, x) where a singular Jacobian stopped it
    rows: list[tuple[np.ndarray, ...]] = []

    phi = _evaluate(fun, x, (N, n), "fun")
    with np.errstate(invalid="ignore"):      # NaN in Φ(x0): that sample diverges below
        phi_scale = np.sqrt(tol) * np.maximum(1.0, np.max(np.abs(phi), axis=1))
    for k in range(max_iter):
        if not active.any():
            break
        J = _evaluate(jac, x, (N, n, n), "jac")
        finite = np.all(np.isfinite(phi), axis=1) & np.all(np.isfinite(J), axis=(1, 2))
        diverged |= active & ~finite
        active &= finite
        J = np.where(finite[:, None, None], J, 0.0)
        sv = np.linalg.svd(J, compute_uv=False)
        bad = active & ~(sv[:, -1] > rcond * sv[:, 0])
        for s in np.flatnonzero(bad):
            stopped_at[int(s)] = (k, x[s].copy(), sv[s, -1] / sv[s, 0] if sv[s, 0] else 0.0)
        singular |= bad
        active &= ~bad

        # Held rows get an identity system with zero right-hand side: a zero step.
        eye = np.broadcast_to(np.eye(n), J.shape)
        A = np.where(active[:, None, None], J, eye)
        b = np.where(active[:, None], -phi, 0.0)
        step = np.linalg.solve(A, b[..., None])[..., 0]
        if history:
            rows.append((x.copy(), phi.copy(), step, active.copy()))
        with np.errstate(over="ignore"):      # a step to beyond floats: diverged below
            x = x + step
        iterations += active
        size = np.max(np.abs(step), axis=1)
        last_step = np.where(active, size, last_step)
        phi = _evaluate(fun, x, (N, n), "fun")
        with np.errstate(over="ignore", invalid="ignore"):
            small_step = np.all(np.abs(step) <= tol * (1.0 + np.abs(x)), axis=1)
            rounding = _ROUNDING * np.einsum("sij,sj->si", np.abs(J), np.abs(x))
            small_residual = np.all(np.abs(phi) <= np.maximum(phi_scale[:, None], rounding),
                                    axis=1)
        done = active & small_step & small_residual
        converged |= done
        active &= ~done

    residual_norm = np.max(np.abs(phi), axis=1)
    diverged |= active & ~np.all(np.isfinite(x), axis=1)
    record = None
    if history:
        stacked = [np.stack(column) for column in zip(*rows)] if rows else \
            [np.zeros((0, N, n))] * 3 + [np.zeros((0, N), dtype=bool)]
        if not batched:
            stacked = [a[:, 0] for a in stacked]
        record = NewtonHistory(*stacked)
    pick = (lambda a: a) if batched else (lambda a: a[0])
    result = NewtonResult(x=pick(x), converged=pick(converged), iterations=pick(iterations),
                          residual_norm=pick(residual_norm), singular=pick(singular),
                          history=record)

    if on_failure == "raise":
        if singular.any():
            raise _attach(_singular_error(singular, stopped_at, batched), result)
        if not converged.all():
            raise _attach(_convergence_error(~converged, diverged, residual_norm, last_step,
                                             max_iter, batched), result)
    return result


def iteration_table(history: NewtonHistory, *, sample: int = 0,
                    names: Sequence[str] | None = None, digits: int = 4) -> str:
    """The notes' iteration table of one sample, as plain text (for the CLI and teaching).

    Columns: ``k``, the unknowns, the residuals ``phi1 … phin`` and the steps ``d<name>``,
    each printed with ``digits`` significant digits, in the units of the solve (rad stays
    rad: convert before solving, or read ``to_dataframe`` and convert, to show degrees).

    Examples
    --------
    See :func:`newton`.
    """
    if not isinstance(history, NewtonHistory):
        raise ModelError(f"history: expected the history of a solve (newton(..., "
                         f"history=True).history), got {describe(history)}")
    digits = whole("digits", digits, 1, 17)
    one = history.sample(sample)
    names = _names(names, one.x.shape[-1])
    header = ["k", *names, *(f"phi{i + 1}" for i in range(len(names))),
              *(f"d{name}" for name in names)]
    body = [[str(k), *(f"{v:.{digits}g}" for v in np.concatenate([xk, rk, dk]))]
            for k, (xk, rk, dk) in enumerate(zip(one.x, one.residual, one.step))]
    width = max(len(cell) for row in [header, *body] for cell in row) + 1
    widths = [max(2, max(len(row[0]) for row in [header, *body]))] + [width] * (len(header) - 1)
    return "\n".join("".join(cell.rjust(w) for cell, w in zip(row, widths))
                     for row in [header, *body])


def _names(names: Sequence[str] | None, n: int) -> list[str]:
    if names is None:
        return [f"x{i + 1}" for i in range(n)]
    if isinstance(names, str) or not isinstance(names, Sequence):
        raise ModelError(f"names: expected a list of {n} names, one per unknown, got "
                         f"{describe(names)}")
    for name in names:
        if (why := name_problem(name)) is not None:
            raise ModelError(f"names: {why}, got {describe(name)}")
    names = list(names)
    if len(names) != n:
        raise ModelError(f"names: expected {n} names, one per unknown, got {len(names)}")
    return names


def _evaluate(f: Callable, x: np.ndarray, shape: tuple[int, ...], what: str) -> np.ndarray:
    """``f(x)`` as an array of ``x``'s dtype and of shape ``shape``, or a ModelError naming
    ``what`` (shared with :func:`continuation`)."""
    try:
        value = np.asarray(f(x.copy()))
    except (ValueError, OverflowError):     # a ragged list, a whole number beyond floats
        value = np.array(None, dtype=object)
    if value.dtype.kind not in "iufc":
        raise ModelError(f"{what}: expected an array of numbers, got "
                         f"{describe(value if value.dtype.kind != 'O' else value.tolist())}; "
                         f"{what} must return numbers vectorised over the N samples")
    if np.iscomplexobj(value) and not np.iscomplexobj(x):
        raise ModelError(f"{what}: expected real values for a real x, got complex ones; pass "
                         f"a complex x0 to iterate in complex arithmetic")
    value = value.astype(x.dtype, copy=False)
    if value.shape != shape:
        expected = "(N, n)" if len(shape) == 2 else "(N, n, n)"
        raise ModelError(f"{what}: expected an array of shape {expected} = {shape} for x of "
                         f"shape {x.shape}, got {value.shape}; {what} must be vectorised "
                         f"over the N samples along axis 0")
    return value


def _attach(error: Exception, result: NewtonResult) -> Exception:
    error.result = result
    return error


def _indices(mask: np.ndarray) -> str:
    where = np.flatnonzero(mask)
    text = ", ".join(str(i) for i in where[:_SHOWN])
    return text + (f", … ({len(where)} in all)" if len(where) > _SHOWN else "")


def _singular_error(singular: np.ndarray, stopped_at: dict, batched: bool) -> SingularityError:
    first = min(stopped_at)
    k, x, ratio = stopped_at[first]
    where = (f"at {int(singular.sum())} of {singular.size} samples ({_indices(singular)}) "
             if batched else "")
    return SingularityError(
        f"Newton-Raphson met a singular Jacobian {where}(first: "
        f"{'sample ' + str(first) + ', ' if batched else ''}iteration {k}, x = {x.tolist()}, "
        f"smallest/largest singular value = {ratio:.3g}); the configuration there is "
        f"singular (a dead centre, toggle or change of branch) or the guess sits on one; "
        f"start from a different guess, or pass on_failure='mask' to keep the other samples")


def _convergence_error(failed, diverged, residual_norm, last_step, max_iter, batched):
    first = int(np.flatnonzero(failed)[0])
    where = f" for {int(failed.sum())} of {failed.size} samples ({_indices(failed)})" \
        if batched else ""
    at = f"at sample {first} " if batched else ""
    how = ("diverged to non-finite values" if diverged[first]
           else f"did not converge in {max_iter} iterations")
    return ConvergenceError(
        f"Newton-Raphson {how}{where}; {at}the last residual max|Φ| = "
        f"{residual_norm[first]:.3g} and step max|Δx| = {last_step[first]:.3g}; try a closer "
        f"starting guess (in a sweep, the neighbouring solution), a larger max_iter, or "
        f"on_failure='mask' to keep the samples that converged")
