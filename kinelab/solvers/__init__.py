"""Solvers: the generic numerical kernels of the course.

- :func:`half_angle` — ``E cos θ + F sin θ + G = 0`` by the half-angle substitution;
- :func:`dialytic` — two polynomial equations in two unknowns by dialytic elimination;
- :func:`newton` — batched Newton-Raphson with an analytic Jacobian and its iteration table;
- :func:`continuation` — predictor-corrector along a parameter, with step halving;
- :func:`bisect` — vectorised bisection on a boolean predicate;
- :func:`differentiate` — first and second derivatives of sampled, noisy data, with error
  estimates (local least-squares polynomials, the window chosen by cross-validation);
- :func:`wrap_angle` — angles into (-π, π]; :func:`turn_intervals` — angle intervals
  shifted by whole turns near a given angle.
"""
from kinelab.solvers._angles import turn_intervals, wrap_angle
from kinelab.solvers._bisect import bisect
from kinelab.solvers._continuation import ContinuationResult, continuation
from kinelab.solvers._differentiate import Derivatives, differentiate
from kinelab.solvers._half_angle import HalfAngleSolution, half_angle
from kinelab.solvers._newton import NewtonHistory, NewtonResult, iteration_table, newton

__all__ = ["bisect", "ContinuationResult", "continuation", "DialyticSolution", "dialytic",
           "Derivatives", "differentiate",
           "HalfAngleSolution", "half_angle",
           "NewtonHistory", "NewtonResult", "iteration_table", "newton", "wrap_angle",
           "turn_intervals"]


def __getattr__(name: str):
    # dialytic elimination needs sympy, which takes a second to import: only when it is used
    if name in ("dialytic", "DialyticSolution"):
        from kinelab.solvers import _dialytic
        return getattr(_dialytic, name)
    raise AttributeError(f"module 'kinelab.solvers' has no attribute {name!r}")
