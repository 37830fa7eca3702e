"""The graphical constructions of the velocity notes, step by step, as data: graphical
differentiation by tangents and a polar distance, the velocity image of a link by similar
triangles, and the instant centres by Kennedy's theorem on the circle diagram.

Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades* (Universidade do
Minho, 2007): §4.6.4 (graphical differentiation, Fig. 4.22), §4.6.2 (the velocity image,
Figs. 4.18-4.19) and §4.6.3 (instant centres; the circle diagram and Kennedy's theorem).

Each construction is derived here from its geometry, and its answer is checked in the tests
against an independent computation (the numerical derivative, the engine's velocities, the
centres solved from the velocities); :mod:`kinelab.plot` draws them.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe, quoted, shown, suggest
from kinelab.kinematics._solution import KinematicSolution, takes_solution

__all__ = ["TangentConstruction", "tangent_construction", "VelocityImage", "velocity_image",
           "KennedyLine", "KennedyDrawingStep", "KennedySteps", "kennedy_steps"]

MIN_POINTS = 1          # chosen points of a tangent construction


# -- graphical differentiation (§4.6.4, Fig. 4.22) ---------------------------------------------
@dataclass(frozen=True)
class TangentConstruction:
    """Graphical differentiation of a sampled curve y(x) by the notes' construction.

    At each chosen point A of the curve the tangent is drawn, and the triangle BCD under it
    whose horizontal side BD is the polar distance H (B and C on the tangent, D below C at
    B's height).  On the derivative diagram, which shares the curve's abscissa, the pole P
    lies H to the left of the origin O; the line through P parallel to the tangent meets the
    ordinate axis at the height CD = H * (slope of the tangent): the *intercept*.  Carried
    across to A's abscissa, it is A', a point of the derivative drawn to the scale H (one
    unit of the diagram's ordinate is 1/H units of dy/dx).

    The tangent's slope (``method``):

    - ``"chord"`` (the notes' way): parallel to the chord between the chosen point's
      neighbours on either side, ``every`` samples away; on unevenly spaced samples the two
      half-chords are weighted by each other's width, which is the slope at A of the parabola
      through the three points (on evenly spaced ones, the chord itself).  Its error is
      about f''' w^2 / 6 for neighbours w apart, plus the noise over 2 w.
    - ``"fitted"``: the slope of :func:`kinelab.solvers.differentiate` (local least-squares
      polynomials), a tangent drawn by eye through noisy data.

    Attributes
    ----------
    x, y : ndarray, shape (N,)
        The curve, as given.
    index : ndarray of int, shape (n,)
        The chosen samples.
    points : ndarray, shape (n, 2)
        The chosen points A (x, y).
    neighbours : ndarray, shape (n, 2, 2)
        The two samples each chord is drawn between ("chord"; NaN for "fitted").
    slope : ndarray, shape (n,)
        The tangents' slopes dy/dx.
    tangents : ndarray, shape (n, 2, 2)
        B and C: the ends of each tangent, H apart in x, centred on A.
    triangles : ndarray, shape (n, 3, 2)
        B, C, D of each triangle (D at B's height, below or above C).
    polar_distance : float
        H, in x's unit.
    origin, pole : ndarray, shape (2,)
        O = (x[0], 0) and P = (x[0] - H, 0) on the derivative diagram.
    rays : ndarray, shape (n, 2, 2)
        From P to the intercept on the ordinate axis (x = x[0]), parallel to each tangent.
    intercepts : ndarray, shape (n,)
        The rays' heights on the ordinate axis, CD = H * slope, in y's unit.
    derived : ndarray, shape (n, 2)
        The points A' (x of A, intercept) of the derivative diagram.
    derivative : ndarray, shape (n,)
        intercept / H: dy/dx at each chosen point.
    method : {"chord", "fitted"}
    every : int
        Samples between two chosen points (and from each point to its chord's ends).
    """

    x: np.ndarray
    y: np.ndarray
    index: np.ndarray
    points: np.ndarray
    neighbours: np.ndarray
    slope: np.ndarray
    tangents: np.ndarray
    triangles: np.ndarray
    polar_distance: float
    origin: np.ndarray
    pole: np.ndarray
    rays: np.ndarray
    intercepts: np.ndarray
    derived: np.ndarray
    derivative: np.ndarray
    method: str
    every: int

    def __repr__(self) -> str:
        return (f"TangentConstruction({len(self.index)} points, H = {self.polar_distance:.4g}, "
                f"{self.method})")


def tangent_construction(x: ArrayLike, y: ArrayLike, *, points: int | None = None,
                         polar_distance: float | None = None,
                         method: Literal["chord", "fitted"] = "chord") -> TangentConstruction:
    """Differentiate a sampled curve by the notes' construction (Flores & Claro, §4.6.4,
    Fig. 4.22): tangents at chosen points, a pole at the polar distance H, rays parallel to
    the tangents, their intercepts on the ordinate axis.

    Parameters
    ----------
    x, y : array_like, shape (N,)
        The curve: abscissae (time or an input angle) that increase, and values.
    points : int, optional
        How many points to draw tangents at (at least 1; default 12, or as many as the
        samples allow, N - 2, when fewer): every k-th sample, with
        k = (N - 1) // (points + 1), so that each has a neighbour k samples away on either side.
    polar_distance : float, optional
        H, in x's unit.  Default: the notes' choice, twice the interval between the chosen
        points (the width of the chords, BD), which makes each intercept the rise of its
        chord.
    method : {"chord", "fitted"}
        How the tangent's slope is found; see :class:`TangentConstruction`.

    Returns
    -------
    TangentConstruction

    Raises
    ------
    ModelError
        Samples that are not finite or do not increase, too few samples for the points asked,
        a polar distance that is not a positive number, an unknown method.

    Examples
    --------
    y = x^2 sampled at x = 0, 0.1, ..., 1 and three points: every 2nd sample, H = 0.4; the
    chord's slope of a parabola is exact, 2 x:

    >>> tc = kl.kinematics.tangent_construction(np.linspace(0, 1, 11), np.linspace(0, 1, 11) ** 2, points=3)
    >>> tc.index.tolist(), round(tc.polar_distance, 12)
    ([2, 4, 6], 0.4)
    >>> tc.intercepts.round(12).tolist(), tc.derivative.round(12).tolist()
    ([0.16, 0.32, 0.48], [0.4, 0.8, 1.2])
    >>> tc.pole.round(12).tolist()
    [-0.4, 0.0]
    """
    from kinelab.solvers._differentiate import _samples
    x, y = _samples("x", x), _samples("y", y)
    if len(x) != len(y):
        raise ModelError(f"y: expected as many samples as x ({len(x)}), got {len(y)}")
    step = np.diff(x)
    bad = np.flatnonzero(~(step > 0))
    if bad.size:
        k = int(bad[0]) + 1
        raise ModelError(f"x[{k}]: expected abscissae that increase, got {float(x[k])!r} after "
                         f"x[{k - 1}] = {float(x[k - 1])!r}; sort the samples and merge repeated ones")
    if method not in ("chord", "fitted"):
        raise ModelError(f"method: expected 'chord' or 'fitted', got {describe(method)}"
                         f"{suggest(str(method), ['chord', 'fitted'])}")
    n = len(x)
    if n < 3:
        raise ModelError(f"x: expected at least 3 samples (a point and a neighbour on either "
                         f"side), got {n}")
    if points is None:
        points = min(12, n - 2)
    if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or points < MIN_POINTS:
        raise ModelError(f"points: expected a whole number of points, at least {MIN_POINTS}, "
                         f"got {describe(points)}")
    if n < int(points) + 2:
        raise ModelError(f"points: expected at most {max(n - 2, 0)} points for {n} samples (each "
                         f"needs a sample on either side), got {int(points)}; ask for fewer points")
    k = (n - 1) // (int(points) + 1)
    index = k * np.arange(1, int(points) + 1)
    span = float(x[-1] - x[0])
    if polar_distance is None:
        H = 2.0 * k * span / (n - 1)
    else:
        H = polar_distance
        if isinstance(H, bool) or not isinstance(H, (int, float, np.integer, np.floating)) \
                or not np.isfinite(H) or not H > 0:
            raise ModelError(f"polar_distance: expected a positive number (in x's unit), got "
                             f"{describe(polar_distance)}")
        H = float(H)
    xa, ya = x[index], y[index]
    if method == "chord":
        left, right = index - k, index + k
        h1, h2 = xa - x[left], x[right] - xa
        m1, m2 = (ya - y[left]) / h1, (y[right] - ya) / h2
        # the slope at A of the parabola through the three samples: each half-chord's slope
        # weighted by the other's width (with h1 = h2, the chord from left to right)
        slope = (h2 * m1 + h1 * m2) / (h1 + h2)
        neighbours = np.stack([np.stack([x[left], y[left]], axis=1),
                               np.stack([x[right], y[right]], axis=1)], axis=1)
    else:
        from kinelab.solvers import differentiate
        slope = differentiate(x, y).velocity[index]
        neighbours = np.full((len(index), 2, 2), np.nan)
    A = np.stack([xa, ya], axis=1)
    half = 0.5 * np.stack([np.full_like(slope, H), H * slope], axis=1)
    B, C = A - half, A + half
    D = np.stack([C[:, 0], B[:, 1]], axis=1)
    intercepts = H * slope
    origin = np.array([float(x[0]), 0.0])
    pole = origin - [H, 0.0]
    ends = np.stack([np.full_like(slope, origin[0]), intercepts], axis=1)
    rays = np.stack([np.broadcast_to(pole, ends.shape), ends], axis=1)
    derived = np.stack([xa, intercepts], axis=1)
    return TangentConstruction(x=x.copy(), y=y.copy(), index=index, points=A,
                               neighbours=neighbours, slope=slope,
                               tangents=np.stack([B, C], axis=1),
                               triangles=np.stack([B, C, D], axis=1), polar_distance=H,
                               origin=origin, pole=pole, rays=rays, intercepts=intercepts,
                               derived=derived, derivative=intercepts / H, method=method,
                               every=int(k))


# -- the velocity image by similar triangles (§4.6.2) --------------------------------------------
@dataclass(frozen=True)
class VelocityImage:
    """The velocity image of a link built by similar triangles, step by step.

    Two points A and B of the link have known velocities: from the pole o, oa = V_A
    (step 1) and ob = V_B (step 2); ab = V_B - V_A (step 3) is the image of AB.  Each
    further point C of the link is placed by drawing on ab the triangle abc similar to ABC,
    with the same orientation (step 4): as complex numbers,
    c = a + (b - a) (C - A) / (B - A).  Then oc is the velocity of C (step 5).  Only the
    positions and ab are used, not the link's angular velocity: the similarity's ratio
    (b - a) / (B - A) is i omega, which the tests check, with oc against the engine's V_C.

    Attributes
    ----------
    link : str
    known : (str, str)
        A and B.
    points : tuple of str
        The points C placed by similar triangles.
    positions : dict of str to ndarray (2,)
        m: A, B and each C.
    vertices : dict of str to ndarray (2,)
        m/s: a, b (the known velocities) and each c found.
    ratio : complex
        (b - a) / (B - A), 1/s: the image's turn and scale (i omega for a rigid link).
    velocities : dict of str to ndarray (2,)
        m/s: the engine's velocity of each C, for comparison.
    sample : int
    """

    link: str
    known: tuple[str, str]
    points: tuple[str, ...]
    positions: dict[str, np.ndarray]
    vertices: dict[str, np.ndarray]
    ratio: complex
    velocities: dict[str, np.ndarray]
    sample: int

    @property
    def pole(self) -> np.ndarray:
        return np.zeros(2)


def _at(sol: KinematicSolution, a, i: int) -> np.ndarray:
    a = np.asarray(a, dtype=float)
    return a.copy() if sol.single else a[i].copy()


@takes_solution
def velocity_image(sol: KinematicSolution, link: str, *, known: tuple[str, str] | None = None,
                   sample: int = 0) -> VelocityImage:
    """The velocity image of ``link`` built by similar triangles (Flores & Claro, §4.6.2).

    Parameters
    ----------
    sol : KinematicSolution
    link : str
        A moving link with at least three points.
    known : (str, str), optional
        The two points whose velocities are taken as known (default: the link's first two,
        its joints in a model file).  The link's other points are placed.
    sample : int

    Returns
    -------
    VelocityImage

    Raises
    ------
    ModelError
        An unknown or ground link, a link with fewer than three points, ``known`` not two
        different points of the link, or two known points at one place.
    SingularityError, AssemblyError
        At a singular or unassembled sample.

    Examples
    --------
    The crank-rocker's coupler A, B, P: p found from ab alone is the engine's V_P:

    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> sol = kl.analyze(fb, q=np.radians(60.0), qd=10.0)
    >>> vi = kl.kinematics.velocity_image(sol, "coupler")
    >>> vi.known, vi.points
    (('A', 'B'), ('P',))
    >>> bool(np.allclose(vi.vertices["P"], sol.velocity("P"), rtol=0, atol=1e-12))
    True
    >>> bool(np.isclose(vi.ratio, 1j * sol.omega("coupler")))
    True
    """
    from kinelab.kinematics._polygons import sample_index
    m = sol.mechanism
    names = list(sol.link_names)
    if link not in names:
        raise ModelError(f"link: expected one of {quoted(names)}, got {describe(link)}"
                         f"{suggest(str(link), names)}")
    lk = m.link(link)
    if lk.ground:
        raise ModelError(f"link: expected a moving link, got the ground {shown(link)}, whose "
                         "velocity image is the pole")
    if len(lk.points) < 3:
        raise ModelError(f"link: expected a link with at least three points, got {shown(link)} "
                         f"with {quoted(lk.points)}; a two-point link's image is the side ab")
    if known is None:
        known = tuple(lk.points[:2])
    if (not isinstance(known, (tuple, list)) or len(known) != 2
            or any(p not in lk.points for p in known) or known[0] == known[1]):
        raise ModelError(f"known: expected two different points of {shown(link)} "
                         f"({quoted(lk.points)}), got {describe(known)}")
    i = sample_index(sol, sample)
    a_name, b_name = known
    others = tuple(p for p in lk.points if p not in known)
    pos = {p: _at(sol, sol.position(p), i) for p in (a_name, b_name, *others)}
    vel = {p: _at(sol, sol.velocity(p), i) for p in (a_name, b_name, *others)}

    def z(v):
        return complex(v[0], v[1])
    AB = z(pos[b_name]) - z(pos[a_name])
    size = max(abs(z(v)) for v in pos.values())
    if abs(AB) <= 1e-12 * max(size, 1e-300):
        raise ModelError(f"known: {shown(a_name)} and {shown(b_name)} are at one place; the "
                         "side AB fixes no triangle; name two points apart")
    a, b = z(vel[a_name]), z(vel[b_name])
    ratio = (b - a) / AB
    vertices = {a_name: vel[a_name], b_name: vel[b_name]}
    for c in others:
        w = a + ratio * (z(pos[c]) - z(pos[a_name]))
        vertices[c] = np.array([w.real, w.imag])
    return VelocityImage(link=link, known=(a_name, b_name), points=others, positions=pos,
                         vertices=vertices, ratio=ratio,
                         velocities={c: vel[c] for c in others}, sample=i)


# -- Kennedy's construction, step by step (§4.6.3) ----------------------------------------------
@dataclass(frozen=True)
class KennedyLine:
    """A line of centres: through the centres of ``through`` (two pairs of links).

    Attributes
    ----------
    through : ((str, str), (str, str))
    point : ndarray (2,)
        m: a finite point of the line (the first finite centre of the two).
    direction : ndarray (2,)
        Unit direction of the line; NaN when both centres are at infinity (the line at
        infinity) or coincide.
    """

    through: tuple[tuple[str, str], tuple[str, str]]
    point: np.ndarray
    direction: np.ndarray


@dataclass(frozen=True)
class KennedyDrawingStep:
    """One secondary centre of the construction: the two lines that fix it and where they
    meet.

    Attributes
    ----------
    number : int
        1, 2, ... in the order found.
    pair : (str, str)
    thirds : (str, str)
        The two third links k, l: I_ab is on the line I_ak I_kb and on the line I_al I_lb.
    lines : (KennedyLine, KennedyLine)
    position : ndarray (2,)
        m, where the centre is finite.
    at_infinity : bool
    direction : ndarray (2,)
        Towards a centre at infinity.
    known : tuple of (str, str)
        The pairs whose centres are known once this one is (the circle diagram's sides).
    """

    number: int
    pair: tuple[str, str]
    thirds: tuple[str, str]
    lines: tuple[KennedyLine, KennedyLine]
    position: np.ndarray
    at_infinity: bool
    direction: np.ndarray
    known: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class KennedySteps:
    """Kennedy's construction at one sample, in the order the notes draw it: the primary
    centres (the joints), then each secondary centre as the meeting point of two lines of
    known centres (Kennedy's theorem: the three centres of any three bodies lie on one line).

    Attributes
    ----------
    construction : KennedyConstruction
        The whole construction over the solution's samples.
    sample : int
    numbers : dict of str to int
        Each link's number (the ground 1).
    primary : dict of (str, str) to str
        Pairs whose centre is a joint, and the joint.
    steps : tuple of KennedyDrawingStep
    from_velocities : tuple of (str, str)
        Pairs the construction cannot reach (taken from the velocities).
    """

    construction: object
    sample: int
    numbers: dict[str, int]
    primary: dict[tuple[str, str], str]
    steps: tuple[KennedyDrawingStep, ...]
    from_velocities: tuple[tuple[str, str], ...]

    def label(self, pair) -> str:
        """``'O13'``: the notes' name of a centre."""
        return self.construction.label(pair)

    def center(self, pair):
        """(position, at_infinity, direction) of a centre at the sample."""
        c = self.construction.centers[pair]
        i = self.sample if np.ndim(c.at_infinity) else None

        def at(a):
            return np.asarray(a, float) if i is None else np.asarray(a, float)[i]
        return at(c.position), bool(at(c.at_infinity) if i is None else np.asarray(c.at_infinity)[i]), \
            at(c.direction)


def _line(steps_center, p1, p2) -> KennedyLine:
    (x1, inf1, d1), (x2, inf2, d2) = steps_center(p1), steps_center(p2)
    nan = np.full(2, np.nan)
    if inf1 and inf2:
        return KennedyLine((p1, p2), nan, nan)
    if inf1 or inf2:
        point, d = (x2, d1) if inf1 else (x1, d2)
    else:
        point, d = x1, x2 - x1
    norm = float(np.hypot(*d))
    scale = max(float(np.hypot(*point)), 1.0)
    d = d / norm if norm > 1e-12 * scale else nan
    return KennedyLine((p1, p2), np.asarray(point, float).copy(), d)


@takes_solution
def kennedy_steps(sol: KinematicSolution, sample: int = 0) -> KennedySteps:
    """Kennedy's construction at one sample, each secondary centre with the two lines of
    centres that fix it, in the order found (Flores & Claro, §4.6.3).

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    >>> ks = kl.kinematics.kennedy_steps(kl.analyze(fb, q=np.radians(60.0)))
    >>> [(s.number, ks.label(s.pair)) for s in ks.steps]
    [(1, 'O13'), (2, 'O24')]
    >>> [[ks.label(p) for p in line.through] for line in ks.steps[0].lines]
    [['O12', 'O23'], ['O14', 'O34']]
    """
    from kinelab.kinematics._centrodes import kennedy_construction
    from kinelab.kinematics._instant_centers import _model_order
    from kinelab.kinematics._polygons import sample_index
    i = sample_index(sol, sample)
    kc = kennedy_construction(sol)
    holder = KennedySteps(kc, i, dict(kc.numbers), dict(kc.primary), (), tuple(kc.from_velocities))
    known = list(kc.primary)
    steps = []
    for number, s in enumerate(kc.steps, start=1):
        chosen = int(np.asarray(s.chosen).reshape(-1)[i if np.ndim(s.chosen) else 0])
        a, b = s.pair
        k, l = s.thirds[max(chosen, 0)]
        lines = tuple(_line(holder.center, _model_order(sol, a, t), _model_order(sol, t, b))
                      for t in (k, l))
        position, inf, direction = holder.center(s.pair)
        known.append(s.pair)
        steps.append(KennedyDrawingStep(number, s.pair, (k, l), lines, position, inf, direction,
                                        tuple(known)))
    return KennedySteps(kc, i, dict(kc.numbers), dict(kc.primary), tuple(steps),
                        tuple(kc.from_velocities))
