"""Proof of kinelab's numbers by independent routes: the certificate of ``--verify``.

Every number an analysis reports is computed again by routes that share none of its
arithmetic, and the largest disagreement of each, relative to a stated unit, is checked
against a bound with a reason (rounding amplified near singular configurations, truncation
of finite differences, an integration tolerance):

- :func:`analyze` -- :func:`kinelab.kinematics.analyze`, and with ``verify=True`` the
  certificate of its result (``sol.certificate``); it is ``kl.analyze``;
- :func:`certify` -- the certificate of a result already made: a kinematic analysis,
  inverse dynamics, a simulation, a synthesized linkage, a velocity or acceleration polygon;
- :class:`Certificate` -- a mapping from each quantity's name to ``(routes,
  largest_disagreement)``, with the details and the verdict.

This room sits above :mod:`kinelab.derive`, :mod:`kinelab.synthesis` and
:mod:`kinelab.dynamics`, whose results it checks and whose routes it uses, and below
:mod:`kinelab.sweep`, :mod:`kinelab.io` and the command line, which print and store its
certificates.  It imports sympy, the dynamics and the synthesis only when a route needs them.
"""
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy)
__getattr__, __dir__ = exports(__name__, {
    "kinelab.verify._analyze": ("analyze", "certify"),
    "kinelab.verify._certificate": ("Certificate", "Comparison", "Quantity"),
    "kinelab.verify._kinematics": ("CLOSURE_EVERY", "CLOSURE_STRIDE", "EVERY", "NEAR_SAMPLES",
                                   "NEAR_SINGULAR", "NEWTON_EVERY", "NEWTON_STRIDE", "SAMPLES",
                                   "STRIDE", "certify_kinematics", "checked_samples"),
    "kinelab.verify._symbolic": ("MAX_SECOND_DERIVATIVES",),
    "kinelab.verify._synthesis": ("certify_solutions",),
})

__all__ = ["analyze", "certify", "certify_kinematics", "certify_solutions", "checked_samples",
           "Certificate",
           "Comparison", "Quantity", "EVERY", "STRIDE", "NEWTON_EVERY", "NEWTON_STRIDE",
           "CLOSURE_EVERY", "CLOSURE_STRIDE", "SAMPLES", "NEAR_SAMPLES", "NEAR_SINGULAR",
           "MAX_SECOND_DERIVATIVES"]
