"""The spherical four-bar in the catalogue: a constructor of kinelab.spatial.SphericalFourBar.

The linkage and its analysis live in :mod:`kinelab.spatial` (3-D kinematics); the catalogue
gives it the constructor every standard mechanism has.  That is the one place the catalogue
uses a room above it, and only when called (a lazy import: ``import kinelab.mechanisms``
does not load :mod:`kinelab.spatial`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Literal

from kinelab.errors import ModelError, check_choice
from kinelab.solvers._arguments import flag

if TYPE_CHECKING:
    from kinelab.spatial import SphericalFourBar

__all__ = ["spherical_fourbar"]


def spherical_fourbar(alpha1: float, alpha2: float, alpha3: float, alpha4: float,
                      branch: Literal["open", "crossed"] = "open", *,
                      degrees: bool = False) -> SphericalFourBar:
    """Spherical four-bar (four revolute joints whose axes meet at one point O).

    The same linkage as :class:`kinelab.spatial.SphericalFourBar` (equal to it), built the
    catalogue's way: each link is an arc of great circle on the unit sphere about O, the
    angle between the two joint axes it carries.  Links and axes are named as the planar
    four-bar's (:func:`fourbar`): ``ground`` (alpha1, from axis O2 to axis O4), ``crank``
    (alpha2, O2 to A), ``coupler`` (alpha3, A to B), ``rocker`` (alpha4, B to O4); the
    input is the crank angle theta2 about O2, and ``analyze(theta2)`` gives theta3,
    theta4, their rates and the unit axes ``u_O2, u_A, u_B, u_O4``.  The frame: ``u_O2 =
    z``, the ground arc from O2 towards +x (see :class:`kinelab.spatial.SphericalFourBar`).

    Parameters
    ----------
    alpha1, alpha2, alpha3, alpha4 : float
        Arcs of the ground, crank, coupler and rocker, each in (0, π) rad, or (0, 180)
        with ``degrees=True``.
    branch : {"open", "crossed"}
        The assembly followed unless told otherwise: "open" puts B to the left of the
        great circle from A to O4, seen from outside the sphere, "crossed" to its right.
    degrees : bool
        Arcs in degrees (kept in radians on the linkage).

    Returns
    -------
    SphericalFourBar

    Raises
    ------
    ModelError
        An arc that is not a number in (0, π) (a line for each such arc), or an unknown
        branch.

    Examples
    --------
    A Hooke (Cardan) joint: crank, coupler and rocker are quarter circles, the ground the
    angle between the shafts (30 deg).  The output turns as fast as the input on average,
    but not at every instant:

    >>> hooke = kl.mechanisms.spherical_fourbar(30, 90, 90, 90, degrees=True)
    >>> hooke == kl.spatial.SphericalFourBar(alpha1=np.radians(30), alpha2=np.pi / 2,
    ...                                      alpha3=np.pi / 2, alpha4=np.pi / 2)
    True
    >>> hooke.grashof().kind
    'double-crank'
    >>> sol = hooke.analyze(np.radians([0.0, 90.0]), 1.0)
    >>> sol.omega4.round(6)             # 1 / cos 30 deg and cos 30 deg
    array([1.154701, 0.866025])
    """
    from kinelab.spatial._spherical import SphericalFourBar, _arc   # the lazy import (see above)

    degrees = flag("degrees", degrees)
    arcs, problems = {}, []
    for name, value in (("alpha1", alpha1), ("alpha2", alpha2), ("alpha3", alpha3),
                        ("alpha4", alpha4)):
        arcs[name], problem = _arc(name, value, degrees)
        if problem:
            problems.append(problem)
    if problems:
        raise ModelError(problems)
    check_choice("branch", branch, ("open", "crossed"))
    return SphericalFourBar(**arcs, branch=branch)
