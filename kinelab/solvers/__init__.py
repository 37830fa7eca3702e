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
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy); dialytic
# elimination needs sympy, which takes a second to import, so it too loads only when used
__getattr__, __dir__ = exports(__name__, {
    "kinelab.solvers._angles": ("turn_intervals", "wrap_angle"),
    "kinelab.solvers._bisect": ("bisect",),
    "kinelab.solvers._continuation": ("ContinuationResult", "continuation"),
    "kinelab.solvers._dialytic": ("DialyticSolution", "dialytic"),
    "kinelab.solvers._differentiate": ("Derivatives", "differentiate"),
    "kinelab.solvers._half_angle": ("HalfAngleSolution", "half_angle"),
    "kinelab.solvers._newton": ("NewtonHistory", "NewtonResult", "iteration_table", "newton"),
})

__all__ = ["bisect", "ContinuationResult", "continuation", "DialyticSolution", "dialytic",
           "Derivatives", "differentiate",
           "HalfAngleSolution", "half_angle",
           "NewtonHistory", "NewtonResult", "iteration_table", "newton", "wrap_angle",
           "turn_intervals"]
