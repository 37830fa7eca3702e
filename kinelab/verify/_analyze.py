"""``kl.analyze`` with ``verify=``, and :func:`certify` for any result."""
from __future__ import annotations

import dataclasses
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab import kinematics
from kinelab.errors import ModelError, describe
from kinelab.kinematics import KinematicSolution
from kinelab.model import Mechanism
from kinelab.verify._certificate import Certificate
from kinelab.verify._kinematics import certify_kinematics

__all__ = ["analyze", "certify"]


def flag(value, name: str) -> bool:
    """``value`` as a bool, or a ModelError unless it is True or False."""
    if not isinstance(value, (bool, np.bool_)):
        raise ModelError(f"{name}: expected True or False, got {describe(value)}")
    return bool(value)


def analyze(mechanism: Mechanism, q: ArrayLike, qd: ArrayLike = 0.0, qdd: ArrayLike = 0.0, *,
            unreachable: Literal["raise", "mask"] = "raise",
            at_singular: Literal["auto", "raise", "flag"] = "auto",
            method: Literal["auto", "newton"] = "auto",
            start: KinematicSolution | None = None,
            at_change_point: Literal["smooth", "switch"] = "smooth",
            verify: bool = False) -> KinematicSolution:
    verify = flag(verify, "verify")
    sol = kinematics.analyze(mechanism, q, qd, qdd, unreachable=unreachable,
                             at_singular=at_singular, method=method, start=start,
                             at_change_point=at_change_point)
    if not verify:
        return sol
    return dataclasses.replace(sol, certificate=certify_kinematics(sol))


_VERIFY = """    verify : bool
        Also compute every number again by independent routes -- loop closure at every
        sample; the Newton engine (or the closed form, for ``method="newton"``), the
        symbolic derivation and finite differences at every sample up to
        ``kinelab.verify.SAMPLES`` and a fixed subset beyond -- and attach the
        :class:`~kinelab.verify.Certificate` as ``sol.certificate``.  A disagreement beyond
        its bound does not raise: ``sol.certificate.passed`` is False and
        ``sol.certificate.verdict()`` names it.  See docs/verification.md.

"""
_VERIFY_EXAMPLE = """    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> cert = kl.analyze(fb, q=np.radians([0.0, 45.0, 90.0]), qd=10.0, verify=True).certificate
    >>> cert["angle"][0], cert.passed
    (('closed form', 'loop closure', 'Newton engine', 'symbolic derivation'), True)
"""
analyze.__doc__ = (kinematics.analyze.__doc__.replace("\n    Returns\n", "\n" + _VERIFY + "    Returns\n")
                   .rstrip() + "\n" + _VERIFY_EXAMPLE)


def certify(result, *, solution: KinematicSolution | None = None, function=None,
            requested=None, loads=None, masses=None, rtol: float | None = None) -> Certificate:
    """The certificate of a result: each of its quantities computed again by independent
    routes, the largest disagreement of each against its bound.

    Parameters
    ----------
    result
        A :class:`~kinelab.kinematics.KinematicSolution` (see :func:`analyze`); an
        :class:`~kinelab.dynamics.InverseDynamics` (power balance with the kinetic energy's
        rate from the kinematics, Newton-Euler's efforts, the momentum of the whole
        mechanism for the shaking force and moment, each link's balance under the
        reactions); a :class:`~kinelab.dynamics.Simulation` (its motion's inverse dynamics
        give back the applied efforts; power balance); a synthesized linkage of
        :mod:`kinelab.synthesis` (re-analysed at every task point); a
        :class:`~kinelab.kinematics.VelocityPolygon` or
        :class:`~kinelab.kinematics.AccelerationPolygon` (closure, every vector against the
        Newton engine, Coriolis from 2 omega x v_rel).
    solution : KinematicSolution, optional
        The solution a polygon was drawn from (required for polygons).
    function : callable, optional
        The prescribed function ``f(x)`` of a function generator (required for a
        :class:`~kinelab.synthesis.FunctionSolution`).
    requested : mapping, optional
        What a crank-rocker or quick return was designed for (``swing``, rad;
        ``time_ratio``; ``stroke``, m): compared with what the linkage reaches.
    loads, masses : optional
        The loads and masses of dynamics, as given to :func:`kinelab.dynamics.inverse` or
        :func:`~kinelab.dynamics.simulate` (default, as there: the model's ``[dynamics]``
        section and its links' mass data).
    rtol : float, optional
        A simulation's rtol: adds its integrated energy balance, within 100 rtol.

    Returns
    -------
    Certificate

    Raises
    ------
    ModelError
        A result of another kind, or a missing ``solution`` or ``function``.

    Examples
    --------
    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> sol = kl.analyze(sc, q=np.linspace(0.1, 3.0, 30), qd=5.0)
    >>> kl.verify.certify(sol).passed
    True
    >>> kl.verify.certify(sc)
    Traceback (most recent call last):
    ...
    kinelab.errors.ModelError: result: expected a result to certify (a KinematicSolution, InverseDynamics, Simulation, synthesized linkage or polygon), got a Mechanism; analyze it first: kl.analyze(mechanism, q, verify=True)
    """
    if isinstance(result, KinematicSolution):
        return certify_kinematics(result)
    kind = type(result).__name__
    if kind in ("InverseDynamics", "Simulation", "SimulationBatch"):
        from kinelab.verify._dynamics import certify_dynamics
        return certify_dynamics(result, loads=loads, masses=masses, rtol=rtol)
    if kind in ("MotionSolution", "FunctionSolution", "PathSolution", "CrankRocker",
                "QuickReturn"):
        from kinelab.verify._synthesis import certify_synthesis
        return certify_synthesis(result, function=function, requested=requested)
    if kind in ("VelocityPolygon", "AccelerationPolygon"):
        from kinelab.verify._polygons import certify_polygon
        return certify_polygon(result, solution)
    hint = ("; analyze it first: kl.analyze(mechanism, q, verify=True)"
            if isinstance(result, Mechanism) else "")
    got = f"a {kind}" if not isinstance(result, (str, int, float, type(None))) else describe(result)
    raise ModelError("result: expected a result to certify (a KinematicSolution, "
                     "InverseDynamics, Simulation, synthesized linkage or polygon), got "
                     f"{got}{hint}")

