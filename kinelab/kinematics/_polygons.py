"""Acceleration differences, relative accelerations, and the velocity and acceleration
polygons of a configuration, as data.

Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades* (Universidade do
Minho, 2007), §4.6.1-4.6.2 (velocity polygon and velocity image); Badan (IFG), *Análise de
aceleração* (after Norton, ch. 7) (acceleration difference and relative acceleration; normal,
tangential, Coriolis and sliding parts).

Two points of one link differ in velocity by ``omega k x r`` and in acceleration by
``alpha k x r - omega^2 r`` (r from the reference to the point): the *difference*.  A point P
carried by a slider and the coincident point G of its guide differ by the slide's rate,
``v_P - v_G = s' u``, and ``a_P - a_G = 2 omega k x (s' u) + s'' u``: the *relative*
velocity and acceleration (Coriolis, then sliding).  The polygons draw every point's
velocity (acceleration) from one pole and each difference as a side between two vertices.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from kinelab.errors import AssemblyError, ModelError, describe, quoted, shown
from kinelab.kinematics._geometry import k_cross
from kinelab.kinematics._input_errors import SingularInput
from kinelab.kinematics._solution import KinematicSolution, takes_solution

__all__ = ["AccelerationDifference", "RelativeAcceleration", "Side", "LinkImage",
           "VelocityPolygon", "AccelerationPolygon", "acceleration_difference",
           "relative_acceleration", "velocity_polygon", "acceleration_polygon",
           "coincident_name", "sample_index"]


def coincident_name(point: str, guide: str) -> str:
    """The name of the guide's point under a slider's point: ``'A@lever'``."""
    return f"{point}@{guide}"


# -- acceleration difference and relative acceleration -------------------------------------
@dataclass(frozen=True)
class AccelerationDifference:
    """The acceleration of ``point`` minus that of ``reference``, two points of one link,
    split into its normal and tangential parts.

    With r = point - reference and omega, alpha the link's angular velocity and
    acceleration::

        A_PR = a_P - a_R  =  -omega^2 r  +  alpha k x r
                             normal         tangential
                             (|omega^2 r|,  (|alpha r|,
                             towards R)     perpendicular to r)

    Attributes
    ----------
    point, reference : str
    link : str
        The link that carries both.
    normal, tangential : ndarray, shape (2,) or (N, 2)
        m/s^2.
    total : ndarray, shape (2,) or (N, 2)
        m/s^2: the engine's ``a_P - a_R``, which the two parts add up to.
    """

    point: str
    reference: str
    link: str
    normal: np.ndarray
    tangential: np.ndarray
    total: np.ndarray


@dataclass(frozen=True)
class RelativeAcceleration:
    """The acceleration of a slider's point P relative to the coincident point G of its
    guide (a slider on a turning link, a pin in a slot), split into its parts::

        A_PG = a_P - a_G  =  2 omega k x (s' u)  +  s'' u
                             Coriolis             sliding

    with omega the guide's angular velocity, u the slide's direction and s', s'' the
    slide's rates.  The Coriolis part is zero when the guide does not turn.

    Attributes
    ----------
    joint : str
        The prismatic joint.
    point : str
        P, the joint's point (carried by the slider).
    guide : str
        The guide link.
    coincident : str
        The name G goes by in the polygons: ``'P@guide'``.
    coriolis, sliding : ndarray, shape (2,) or (N, 2)
        m/s^2.
    total : ndarray, shape (2,) or (N, 2)
        m/s^2: the engine's ``a_P`` minus G's acceleration as a point of the guide, which
        the two parts add up to.
    """

    joint: str
    point: str
    guide: str
    coincident: str
    coriolis: np.ndarray
    sliding: np.ndarray
    total: np.ndarray


def _sweep(sol: KinematicSolution, a) -> np.ndarray:
    """An accessor's value with the sample axis, whatever the shape rule dropped."""
    a = np.asarray(a, dtype=float)
    return a[None] if sol.single else a


def _common_link(sol: KinematicSolution, point: str, reference: str, link: str | None) -> str:
    """The link that carries both points (the one named by ``link``, when given)."""
    m = sol.mechanism
    for name in (point, reference):
        sol.position(name)           # an unknown point: the solution's own message
    if point == reference:
        raise ModelError(f"reference: expected a point other than {shown(point)}; a point's "
                         "acceleration difference with itself is zero")
    common = [lk.name for lk in m.links if point in lk.points and reference in lk.points]
    if link is not None:
        if link not in common:
            raise ModelError(f"link: expected a link that carries both {shown(point)} and "
                             f"{shown(reference)}, got {describe(link)}; "
                             + (f"they are both on {quoted(common)}" if common else
                                "no link carries both"))
        return link
    if not common:
        on = "; ".join(f"{shown(p)} is on {quoted(m.links_carrying(p))}" for p in (point, reference))
        raise ModelError(f"acceleration_difference: expected two points of one link, got "
                         f"{shown(point)} and {shown(reference)}, which no link carries both "
                         f"({on}); pick a reference on a link of {shown(point)}, or use "
                         "relative_acceleration for a slider's point and its guide")
    if len(common) > 1:
        raise ModelError(f"acceleration_difference: {shown(point)} and {shown(reference)} are "
                         f"both on {quoted(common)}; name the link with link=")
    return common[0]


def _difference_parts(r: np.ndarray, omega: np.ndarray, alpha: np.ndarray):
    """(normal, tangential) parts of the acceleration difference for r (N, 2) on a link
    turning at omega, alpha (N,)."""
    return -(omega[:, None] ** 2) * r, alpha[:, None] * k_cross(r)


@takes_solution
def acceleration_difference(sol: KinematicSolution, point: str, reference: str, *,
                            link: str | None = None) -> AccelerationDifference:
    """The acceleration difference A_PR of two points of one link, with its normal and
    tangential parts, at every sample.

    Parameters
    ----------
    sol : KinematicSolution
    point, reference : str
        Two points carried by one link (P and R).
    link : str, optional
        The link, when both points are on more than one.

    Returns
    -------
    AccelerationDifference
        Arrays of shape (2,) for one configuration, (N, 2) for N samples; NaN where the
        solution is singular (``sol.singular``).

    Raises
    ------
    ModelError
        An unknown point, or two points that no link carries both (the message says which
        links each is on).

    Examples
    --------
    The crank of a slider-crank (O2A = 1 m) at 90 deg, turning at 2 rad/s and speeding up
    at 3 rad/s^2: the normal part is omega^2 |O2A| = 4 m/s^2 towards O2, the tangential
    part alpha |O2A| = 3 m/s^2 perpendicular to O2A:

    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> d = kl.kinematics.acceleration_difference(kl.analyze(sc, q=np.pi / 2, qd=2.0, qdd=3.0), "A", "O2")
    >>> d.link, d.normal.round(12), d.tangential.round(12)
    ('crank', array([-0., -4.]), array([-3.,  0.]))
    """
    link = _common_link(sol, point, reference, link)
    r = _sweep(sol, sol.position(point)) - _sweep(sol, sol.position(reference))
    normal, tangential = _difference_parts(r, _sweep(sol, sol.omega(link)),
                                           _sweep(sol, sol.alpha(link)))
    total = _sweep(sol, sol.acceleration(point)) - _sweep(sol, sol.acceleration(reference))
    out = sol._out
    return AccelerationDifference(point, reference, link, out(normal), out(tangential), out(total))


def _prismatic(sol: KinematicSolution, joint: str):
    """The prismatic joint named ``joint`` (refusing any other name)."""
    sol.slide(joint)                 # an unknown or non-prismatic joint: the solution's message
    return sol.mechanism.joint(joint)


@takes_solution
def relative_acceleration(sol: KinematicSolution, joint: str) -> RelativeAcceleration:
    """The acceleration of a prismatic joint's point relative to the coincident point of
    its guide, with its Coriolis and sliding parts, at every sample.

    Parameters
    ----------
    sol : KinematicSolution
    joint : str
        A prismatic joint.

    Returns
    -------
    RelativeAcceleration
        Arrays of shape (2,) for one configuration, (N, 2) for N samples.

    Examples
    --------
    The slotted link at q = 90 deg, the crank turning at 3 rad/s: the pin slides out along
    the slot (s' > 0) while the lever turns (omega > 0), so the Coriolis part
    2 omega s' is perpendicular to the slot, to its left:

    >>> sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
    >>> sol = kl.analyze(sl, q=np.pi / 2, qd=3.0)
    >>> rel = kl.kinematics.relative_acceleration(sol, "slot")
    >>> rel.coincident, rel.guide
    ('A@lever', 'lever')
    >>> u = sol.slide_axes("slot")
    >>> expected = 2 * sol.omega("lever") * sol.slide_velocity("slot") * np.array([-u[1], u[0]])
    >>> bool(np.allclose(rel.coriolis, expected)), bool(np.allclose(rel.coriolis + rel.sliding, rel.total))
    (True, True)
    """
    j = _prismatic(sol, joint)
    parts = sol.acceleration_components(j.point, joint)
    g = sol.guide_point(joint)
    return RelativeAcceleration(joint, j.point, j.links[0], coincident_name(j.point, j.links[0]),
                                parts.coriolis, parts.sliding, sol.acceleration(j.point) - g.acceleration)


# -- one sample of a solution ------------------------------------------------------------------
def _q_text(sol: KinematicSolution, i: int) -> str:
    """``q = 0.5 rad`` (or the inputs by name) at sample ``i``, for messages."""
    units = {"angle": "rad", "slide": "m"}
    parts = [f"{v:.6g} {units[k]}" for v, k in zip(sol.q[i], sol.plan.input_kinds)]
    return f"q = {parts[0]}" if len(parts) == 1 else f"q = ({', '.join(parts)})"


def sample_index(sol: KinematicSolution, sample: int) -> int:
    """The sample ``sample`` of ``sol`` (negative counts from the end) as an index, after
    checking that its velocities and accelerations are defined.

    Raises
    ------
    ModelError
        ``sample`` is not a whole number or is out of range.
    AssemblyError
        The loops do not close at that sample.
    SingularityError
        The sample is singular (det J = 0).
    """
    n = sol.N
    if isinstance(sample, bool) or not isinstance(sample, (int, np.integer)):
        raise ModelError(f"sample: expected a whole number, the index of a sample, got "
                         f"{describe(sample)}")
    if n == 0:
        raise ModelError("sample: the solution has no samples; analyze at least one input value")
    if not -n <= sample < n:
        span = "0 (one configuration)" if n == 1 else f"0 to {n - 1} (or -{n} to -1 from the end)"
        raise ModelError(f"sample: expected {span}, got {describe(int(sample))}; the solution "
                         f"has {n} sample{'s' if n > 1 else ''}")
    i = int(sample) % n
    if not sol.assembled[i]:
        raise AssemblyError(f"sample {i}: the loops do not close at {_q_text(sol, i)}; choose "
                            "a sample where the mechanism assembles")
    if sol.singular[i]:
        from kinelab.kinematics._analyze import singular_kind
        raise SingularInput(sol.q[i], sol.plan.input_kinds, sample=i if n > 1 else None,
                            advice="choose another sample",
                            **singular_kind(sol.mechanism, sol.q[i],
                                            "newton" if sol.plan.groups is not None else "auto"))
    return i


# -- polygons ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Side:
    """One side of a polygon: the vector from the reference's vertex to the point's.

    Attributes
    ----------
    point, reference : str
        Vertex names: points of the mechanism, or a guide's coincident point
        (``'A@lever'``).
    kind : {"difference", "relative"}
        "difference": two points of one link (perpendicular to the line joining them in
        the velocity polygon); "relative": a slider's point and the coincident point of its
        guide (along the slide in the velocity polygon).
    link : str
        The link both points are on ("difference"), or the prismatic joint ("relative").
    vector : ndarray, shape (2,)
        m/s or m/s^2: the point's vertex minus the reference's.
    parts : mapping of str to ndarray (2,)
        The named parts the vector is the sum of: acceleration sides only ("normal",
        "tangential" for a difference; "coriolis" when the guide turns, and "sliding", for
        a relative acceleration).
    """

    point: str
    reference: str
    kind: Literal["difference", "relative"]
    link: str
    vector: np.ndarray
    parts: Mapping[str, np.ndarray] = field(default_factory=dict)


@dataclass(frozen=True)
class LinkImage:
    """The image of a link in a polygon: its points' vertices, a figure similar to the link.

    The image is the link turned by ``turn`` and scaled by ``scale``: +-90 deg and |omega|
    in the velocity polygon, ``atan2(alpha, -omega^2)`` and ``sqrt(omega^4 + alpha^2)`` in
    the acceleration polygon.

    Attributes
    ----------
    link : str
    points : tuple of str
        The link's points, then the coincident points of the sliders it guides.
    vertices : ndarray, shape (k, 2)
        m/s or m/s^2, in the order of ``points``.
    turn : float
        rad, CCW.
    scale : float
        1/s or 1/s^2.
    """

    link: str
    points: tuple[str, ...]
    vertices: np.ndarray
    turn: float
    scale: float


@dataclass(frozen=True)
class _Polygon:
    sample: int
    q: np.ndarray
    vertices: dict[str, np.ndarray]
    coincident: dict[str, np.ndarray]
    sides: dict[tuple[str, str], Side]
    images: dict[str, LinkImage]
    omega: dict[str, float]

    @property
    def pole(self) -> np.ndarray:
        """The pole O: the origin of every absolute vector (and the ground's image)."""
        return np.zeros(2)

    def vertex(self, name: str) -> np.ndarray:
        """The vertex of a point of the mechanism or of a coincident point."""
        if name in self.vertices:
            return self.vertices[name]
        if name in self.coincident:
            return self.coincident[name]
        raise ModelError(f"vertex: expected a point of the polygon, got {describe(name)}; they are "
                         f"{quoted([*self.vertices, *self.coincident])}")


@dataclass(frozen=True)
class VelocityPolygon(_Polygon):
    """The velocity polygon of one configuration (Flores & Claro, §4.6.1-4.6.2).

    Every vertex is a velocity drawn from the pole O (the origin): the absolute velocity
    V_A of point A goes from O to ``vertices["A"]``; the relative velocity V_BA of two
    points of a link is the side from A's vertex to B's, perpendicular to AB, of length
    |omega| |AB|; a slider's point and the coincident point of its guide are joined by the
    slide's velocity, along the slide.  Each link's image (its points' vertices) is the link
    turned 90 deg in the sense of omega and scaled by |omega|.

    Attributes
    ----------
    sample : int
        The sample of the solution drawn.
    q : ndarray, shape (M,)
        Its inputs, rad or m.
    vertices : dict of str to ndarray (2,)
        Every point of the mechanism: its velocity, m/s.
    coincident : dict of str to ndarray (2,)
        The point of each prismatic joint's guide under its slider's point (``'A@lever'``).
    sides : dict of (str, str) to Side
        (point, reference): V_point - V_reference.  For each moving link, its points
        measured from its first point; then, for each prismatic joint, the slider's point
        from the coincident point of the guide.
    images : dict of str to LinkImage
        Each moving link's image.
    omega : dict of str to float
        Angular velocity of every link, rad/s.
    """


@dataclass(frozen=True)
class AccelerationPolygon(_Polygon):
    """The acceleration polygon of one configuration (Badan (IFG), *Análise de aceleração*).

    As :class:`VelocityPolygon`, with accelerations (m/s^2); each side is split into its
    parts: A^n_BA (normal, omega^2 |AB| from B towards A) and A^t_BA (tangential,
    alpha |AB| perpendicular to AB) for two points of a link; A^c (Coriolis) and the
    sliding part for a slider's point and the coincident point of its guide.  Each link's
    image is the link turned by ``atan2(alpha, -omega^2)`` and scaled by
    ``sqrt(omega^4 + alpha^2)``.

    Attributes
    ----------
    alpha : dict of str to float
        Angular acceleration of every link, rad/s^2.
    parts : dict of (str, str) to dict of str to ndarray (2,)
        The parts of each side, keyed as ``sides``.
    """

    alpha: dict[str, float] = field(default_factory=dict)

    @property
    def parts(self) -> dict[tuple[str, str], dict[str, np.ndarray]]:
        return {key: dict(side.parts) for key, side in self.sides.items()}


@takes_solution
def velocity_polygon(sol: KinematicSolution, sample: int = 0) -> VelocityPolygon:
    """The velocity polygon and the velocity images of the links at one sample.

    Parameters
    ----------
    sol : KinematicSolution
    sample : int
        Which sample of ``sol`` (0 for a single configuration; negative counts from the end).

    Returns
    -------
    VelocityPolygon

    Raises
    ------
    ModelError
        ``sample`` out of range.
    SingularityError
        The sample is singular (det J = 0): velocities are not defined.
    AssemblyError
        The loops do not close at the sample.

    Examples
    --------
    A crank O2A of 1 m at 90 deg turning at 2 rad/s: V_A = omega k x O2A = (-2, 0) m/s;
    the rod's side V_BA is perpendicular to AB, and closes the polygon at the slider's
    velocity, which is along the slide:

    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> vp = kl.kinematics.velocity_polygon(kl.analyze(sc, q=np.pi / 2, qd=2.0))
    >>> vp.vertices["A"].round(12) + 0.0, vp.vertices["B"].round(12) + 0.0
    (array([-2.,  0.]), array([-2.,  0.]))
    >>> list(vp.sides)
    [('A', 'O2'), ('B', 'A'), ('B', 'B@ground')]
    >>> float(vp.images["crank"].scale), round(float(np.degrees(vp.images["crank"].turn)), 9)
    (2.0, 90.0)
    """
    return _polygon(sol, sample_index(sol, sample), acceleration=False)


@takes_solution
def acceleration_polygon(sol: KinematicSolution, sample: int = 0) -> AccelerationPolygon:
    """The acceleration polygon and the acceleration images of the links at one sample,
    each side split into its normal, tangential, Coriolis and sliding parts.

    Parameters, and the errors raised, as :func:`velocity_polygon`; returns an
    :class:`AccelerationPolygon`.

    Examples
    --------
    The crank at 90 deg, 2 rad/s, 3 rad/s^2: A^n_AO2 = omega^2 |O2A| = 4 m/s^2 towards O2,
    A^t_AO2 = alpha |O2A| = 3 m/s^2 perpendicular to it:

    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> ap = kl.kinematics.acceleration_polygon(kl.analyze(sc, q=np.pi / 2, qd=2.0, qdd=3.0))
    >>> {k: v.round(12) for k, v in ap.parts["A", "O2"].items()}
    {'normal': array([-0., -4.]), 'tangential': array([-3.,  0.])}
    >>> list(ap.parts["B", "B@ground"])               # the slide line does not turn
    ['sliding']
    """
    return _polygon(sol, sample_index(sol, sample), acceleration=True)


def _turn_scale(omega: float, alpha: float, acceleration: bool) -> tuple[float, float]:
    """How a link's image is turned and scaled: multiplication by i omega (velocity) or by
    -omega^2 + i alpha (acceleration), as complex numbers."""
    z = complex(-omega ** 2, alpha) if acceleration else complex(0.0, omega)
    if z == 0:
        return (math.pi / 2 if not acceleration else math.pi), 0.0
    return math.atan2(z.imag, z.real), abs(z)


def _polygon(sol: KinematicSolution, i: int, acceleration: bool):
    m = sol.mechanism

    def at(a):
        return _sweep(sol, a)[i]
    take = sol.acceleration if acceleration else sol.velocity
    pos = {p: at(sol.position(p)) for p in sol.point_names}
    vertices = {p: at(take(p)) for p in sol.point_names}
    omega = {lk: float(at(sol.omega(lk))) for lk in sol.link_names}
    alpha = {lk: float(at(sol.alpha(lk))) for lk in sol.link_names}
    # the guide's point under each slider's point: position, velocity and acceleration
    coincident, on_guide = {}, {}
    for j in m.joints:
        if j.type == "P":
            g = sol.guide_point(j.name)
            name = coincident_name(j.point, j.links[0])
            coincident[name] = at(g.acceleration if acceleration else g.velocity)
            pos[name] = at(g.position)
            on_guide.setdefault(j.links[0], []).append(name)
    vertex = {**vertices, **coincident}
    sides: dict[tuple[str, str], Side] = {}
    images: dict[str, LinkImage] = {}
    for link in m.links:
        if link.ground:
            continue
        name = link.name
        points = (*link.points, *on_guide.get(name, ()))
        first = points[0]
        for p in points[1:]:
            parts = {}
            if acceleration:
                r = (pos[p] - pos[first])[None]
                normal, tangential = _difference_parts(r, np.array([omega[name]]),
                                                       np.array([alpha[name]]))
                parts = {"normal": normal[0], "tangential": tangential[0]}
            sides[(p, first)] = Side(p, first, "difference", name, vertex[p] - vertex[first], parts)
        turn, scale = _turn_scale(omega[name], alpha[name], acceleration)
        images[name] = LinkImage(name, points, np.array([vertex[p] for p in points]), turn, scale)
    for j in m.joints:
        if j.type != "P":
            continue
        g = coincident_name(j.point, j.links[0])
        parts = {}
        if acceleration:
            rel = relative_acceleration(sol, j.name)
            turning = not m.link(j.links[0]).ground
            parts = {**({"coriolis": at(rel.coriolis)} if turning else {}),
                     "sliding": at(rel.sliding)}
        sides[(j.point, g)] = Side(j.point, g, "relative", j.name, vertex[j.point] - vertex[g], parts)
    common = dict(sample=i, q=sol.q[i].copy(), vertices=vertices, coincident=coincident,
                  sides=sides, images=images, omega=omega)
    if acceleration:
        return AccelerationPolygon(**common, alpha=alpha)
    return VelocityPolygon(**common)
