"""The profile of a disk cam for a follower: pitch curve, profile, pressure angle, radius of
curvature, undercutting, the smallest base circle (Norton, *Design of Machinery*, ch. 8).

Conventions (derived in docs/cams.md):

- the cam turns counterclockwise; ``theta`` is its angle; the profile is given in the cam's own
  frame, which coincides with the fixed frame at ``theta = 0``;
- a translating follower moves along +y on the line ``x = offset``: its trace point (the
  roller's centre, the knife's edge) is at ``(e, d + S)`` with ``d = sqrt(Rp**2 - e**2)``,
  ``Rp`` the prime circle's radius (base circle + roller);
- an oscillating follower turns about the pivot ``(pivot_distance, 0)``; its arm makes the
  angle ``gamma = gamma0 + S`` with the line from the pivot to the cam's centre, the trace point
  at ``(C - L cos gamma, L sin gamma)``: S > 0 turns the arm away from the cam (clockwise);
- the pressure angle is the signed angle from the direction in which the follower's point of
  contact (the roller's centre) moves as S grows to the common normal at the contact,
  counterclockwise positive.  For a translating roller follower it is
  ``phi = atan((V - e) / (S + d))``: positive on a rise with e = 0, and an offset e > 0 lowers it
  on the rise;
- curvature is positive where the curve is convex (a circle of radius R has radius +R).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinelab.cams._program import TURN, MotionProgram, SVAJ
from kinelab.errors import ModelError, describe, expected_one_of

__all__ = ["Follower", "CamProfile", "profile", "smallest_base_circle", "FOLLOWER_TYPES",
           "FOLLOWER_MOTIONS"]

FOLLOWER_TYPES = ("knife-edge", "roller", "flat-faced")
FOLLOWER_MOTIONS = ("translating", "oscillating")


def _rot(theta, xy):
    """Rotate the points ``xy`` (N, 2) by ``theta`` (N,) counterclockwise."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1]], axis=-1)


def _J(xy):
    """Rotate by +90 deg."""
    return np.stack([-xy[:, 1], xy[:, 0]], axis=-1)


def _cross(a, b):
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


@dataclass(frozen=True)
class Follower:
    """A cam's follower.

    Parameters
    ----------
    type : {'knife-edge', 'roller', 'flat-faced'}
    motion : {'translating', 'oscillating'}
    offset : float
        Translating: the offset e of its line of motion from the cam's centre, m (along +x).
        Oscillating flat-faced: the distance of the face from the pivot, towards the cam, m.
    roller_radius : float
        The roller's radius Rf, m (roller followers only).
    pivot_distance, arm_length : float
        Oscillating: the distance C from the cam's centre to the pivot and the arm's length L
        (pivot to roller centre), m.  The lift of an oscillating follower is an angle (rad).
    """
    type: str
    motion: str = "translating"
    offset: float = 0.0
    roller_radius: float = 0.0
    pivot_distance: float = 0.0
    arm_length: float = 0.0

    def __post_init__(self):
        problems = []
        if self.type not in FOLLOWER_TYPES:
            problems.append(f"follower.type: {expected_one_of(self.type, FOLLOWER_TYPES)}")
        if self.motion not in FOLLOWER_MOTIONS:
            problems.append(f"follower.motion: {expected_one_of(self.motion, FOLLOWER_MOTIONS)}")
        for name in ("offset", "roller_radius", "pivot_distance", "arm_length"):
            v = getattr(self, name)
            if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
                problems.append(f"follower.{name}: expected a finite number, got {describe(v)}")
        if problems:
            raise ModelError(problems)
        if self.type == "roller" and not self.roller_radius > 0:
            problems.append(f"follower.roller_radius: expected a roller's radius above 0, got "
                            f"{self.roller_radius:.6g}")
        if self.type != "roller" and self.roller_radius != 0:
            problems.append(f"follower.roller_radius: a {self.type} follower has no roller; "
                            "leave it out or make the follower a roller")
        if self.motion == "oscillating":
            for name in ("pivot_distance",) if self.flat else ("pivot_distance", "arm_length"):
                if not getattr(self, name) > 0:
                    problems.append(f"follower.{name}: expected an oscillating follower's "
                                    f"{name.replace('_', ' ')} above 0, got "
                                    f"{getattr(self, name):.6g}")
        if problems:
            raise ModelError(problems)

    @property
    def flat(self) -> bool:
        return self.type == "flat-faced"


@dataclass(frozen=True)
class CamProfile:
    """A disk cam's profile for one follower over one turn.

    Attributes
    ----------
    follower : Follower
    base_radius, prime_radius : float
        The base circle's radius Rb and the prime circle's Rp = Rb + Rf, m.
    svaj : SVAJ
        The motion program at the samples; ``svaj.theta`` is (N,), rad.
    pitch : (N, 2) array
        The pitch curve (the trace point's path) in the cam's frame, m; for a flat-faced
        follower, the profile itself.
    profile : (N, 2) array
        The cam's profile in its frame, m.
    contact : (N, 2) array
        The point of contact in the fixed frame, m.
    pressure_angle : (N,) array
        rad, as the module's conventions say (0 for a translating flat-faced follower).
    pitch_curvature : (N,) array
        1/m, convex positive.
    profile_radius : (N,) array
        The profile's radius of curvature, m, convex positive (infinite where it is straight).
    undercut : (N,) bool array
        Where the profile cannot be cut for this follower: a roller whose radius is at least
        the pitch curve's convex radius of curvature (the profile loops), a flat face where
        Rb + S + S'' <= 0 (a cusp).
    face : (float, float)
        A flat-faced follower's extent of contact along its face from its axis (translating:
        min and max of V = S'; oscillating: distance from the pivot), m; (0, 0) otherwise.
    """
    follower: Follower
    base_radius: float
    prime_radius: float
    svaj: SVAJ
    pitch: np.ndarray
    profile: np.ndarray
    contact: np.ndarray
    pressure_angle: np.ndarray
    pitch_curvature: np.ndarray
    profile_radius: np.ndarray
    undercut: np.ndarray
    face: tuple

    @property
    def theta(self) -> np.ndarray:
        return self.svaj.theta

    @property
    def pitch_radius(self) -> np.ndarray:
        """The pitch curve's radius of curvature, m, convex positive (inf where straight)."""
        with np.errstate(divide="ignore"):
            return 1.0 / self.pitch_curvature

    @property
    def face_width(self) -> float:
        """The width of face a flat-faced follower needs, m: the extent of contact (add a
        clearance at each side)."""
        return float(self.face[1] - self.face[0])

    @property
    def largest_pressure_angle(self) -> tuple[float, float]:
        """The largest |pressure angle| (rad, with its sign) and the cam angle where it is."""
        k = int(np.argmax(np.abs(self.pressure_angle)))
        return float(self.pressure_angle[k]), float(self.theta[k])

    @property
    def smallest_radius(self) -> tuple[float, float]:
        """The profile's smallest convex radius of curvature (m) and the cam angle where it
        is; for a profile convex nowhere (inf, nan is never given), (inf, 0)."""
        r = np.where(self.profile_radius > 0, self.profile_radius, np.inf)
        k = int(np.argmin(r))
        return float(r[k]), float(self.theta[k])

    def to_svg(self, unit: str = "mm") -> str:
        """The profile as an SVG document (a closed path), in ``unit`` (see
        :func:`kinelab.cams.profile_svg`)."""
        from kinelab.cams._export import profile_svg
        return profile_svg(self, unit)

    def to_dxf(self, path, unit: str = "mm"):
        """Write the profile as a DXF drawing at ``path`` (a closed LWPOLYLINE), in ``unit``."""
        from kinelab.cams._export import write_dxf
        return write_dxf(self, path, unit)


def _trace(program_svaj: SVAJ, f: Follower, rp: float):
    """The trace point P, dP/dtheta, d2P/dtheta2 (fixed frame) and its direction of motion."""
    S, V, A = program_svaj.S, program_svaj.V, program_svaj.A
    n = S.shape[0]
    if f.motion == "translating":
        e = f.offset
        if not rp > abs(e):
            raise ModelError(f"base circle: too small for the offset: the prime circle's radius "
                             f"{rp:.6g} m must exceed the offset's {abs(e):.6g} m; make the base "
                             "circle larger")
        d = math.sqrt(rp * rp - e * e)
        if not np.all(S + d > 0):
            raise ModelError("base circle: too small: the follower would pass the cam's centre "
                             f"(S + d <= 0 at {math.degrees(program_svaj.theta[np.argmin(S + d)]):.6g}"
                             " deg); make the base circle larger")
        P = np.stack([np.full(n, e), d + S], axis=-1)
        P1 = np.stack([np.zeros(n), V], axis=-1)
        P2 = np.stack([np.zeros(n), A], axis=-1)
        m = np.tile([0.0, 1.0], (n, 1))
        return P, P1, P2, m
    C, L = f.pivot_distance, f.arm_length
    if not abs(C - L) < rp < C + L:
        raise ModelError(f"base circle: the arm cannot reach the prime circle: its radius "
                         f"{rp:.6g} m must lie between |C - L| = {abs(C - L):.6g} m and C + L = "
                         f"{C + L:.6g} m; change the base circle, the pivot distance or the arm")
    g0 = math.acos((C * C + L * L - rp * rp) / (2 * C * L))
    g = g0 + S
    if not np.all((g > 0) & (g < math.pi)):
        raise ModelError("follower: the arm would swing past the line from its pivot to the "
                         "cam's centre; lower the lift or change the geometry")
    sg, cg = np.sin(g), np.cos(g)
    P = np.stack([C - L * cg, L * sg], axis=-1)
    dP = np.stack([L * sg, L * cg], axis=-1)           # dP/dgamma
    d2P = np.stack([L * cg, -L * sg], axis=-1)
    P1 = dP * V[:, None]
    P2 = dP * A[:, None] + d2P * (V * V)[:, None]
    return P, P1, P2, dP / L


def profile(program: MotionProgram | SVAJ, follower: Follower, base_radius: float, *,
            samples: int = 721, theta=None) -> CamProfile:
    """The profile of the disk cam that drives ``follower`` through ``program``.

    Parameters
    ----------
    program : MotionProgram, or the SVAJ of :func:`~kinelab.cams.motion`
        Lifts in m (rad for an oscillating follower).
    follower : Follower
    base_radius : float
        The base circle's radius Rb, m, above 0.
    samples : int
        Cam angles from 0 to 360 deg included, when ``theta`` is not given.
    theta : array_like, shape (N,), optional
        The cam angles, rad.

    Returns
    -------
    CamProfile

    Raises
    ------
    ModelError
        A base circle the follower cannot work with (smaller than the offset, an arm that
        cannot reach it, a flat face whose contact runs away: 1 + V <= 0).

    Examples
    --------
    >>> from kinelab.cams import MotionProgram, Segment, Follower, profile
    >>> d = np.radians
    >>> p = MotionProgram([Segment("rise", 0, d(180), 0.02, "cycloidal"),
    ...                    Segment("return", d(180), d(360), 0.02, "cycloidal")])
    >>> cam = profile(p, Follower("roller", roller_radius=0.01), 0.04, samples=5)
    >>> cam.pitch.round(4) + 0.0    # (0, Rp + S) turned back by theta
    array([[ 0.  ,  0.05],
           [ 0.06,  0.  ],
           [ 0.  , -0.07],
           [-0.06,  0.  ],
           [ 0.  ,  0.05]])
    """
    if isinstance(program, SVAJ):          # kl.cams.motion(program): the program it is of
        program = program.program
    if not isinstance(program, MotionProgram):
        raise ModelError(f"program: expected a MotionProgram or kl.cams.motion(program), got "
                         f"{describe(program)}")
    if not isinstance(base_radius, (int, float)) or not math.isfinite(base_radius) \
            or not base_radius > 0:
        raise ModelError(f"base circle: expected a radius above 0, got {describe(base_radius)}")
    sv = program.svaj(theta, samples=samples)
    th = np.asarray(sv.theta, dtype=float).reshape(-1)
    sv = SVAJ(th, sv.S.reshape(-1), sv.V.reshape(-1), sv.A.reshape(-1), sv.J.reshape(-1))
    rf = follower.roller_radius
    if follower.flat:
        return _flat(sv, follower, base_radius)
    rp = base_radius + rf
    P, P1, P2, m = _trace(sv, follower, rp)
    u = P1 - _J(P)                       # tangent of the pitch curve, turned into the fixed frame
    w = P2 - 2 * _J(P1) - P
    speed = np.hypot(u[:, 0], u[:, 1])
    if not np.all(speed > 1e-12 * rp):
        raise ModelError("follower: the pitch curve stops (its tangent vanishes); change the "
                         "geometry")
    kappa = -_cross(u, w) / speed ** 3    # the pitch curve runs clockwise: convex is negative
    n = _J(u) / speed[:, None]            # outward normal, towards the follower
    contact = P - rf * n
    phi = np.arctan2(_cross(m, n), np.einsum("ij,ij->i", m, n))
    with np.errstate(divide="ignore"):
        radius = 1.0 / kappa - rf
    undercut = kappa * rf >= 1.0 if rf > 0 else np.zeros(th.shape, bool)
    return CamProfile(follower, float(base_radius), float(rp), sv, _rot(-th, P),
                      _rot(-th, contact), contact, phi, kappa, radius, undercut, (0.0, 0.0))


def _flat(sv: SVAJ, f: Follower, rb: float) -> CamProfile:
    """A flat-faced follower: the profile is the envelope of the face's positions in the
    cam's frame, lines N . q = h with N at the angle alpha; q = h N + dh/dalpha T, radius of
    curvature h + d2h/dalpha2."""
    S, V, A = sv.S, sv.V, sv.A
    th = sv.theta
    if f.motion == "translating":
        h, h1, h2 = rb + S, V, A
        a1, a2 = np.ones_like(S), np.zeros_like(S)
        alpha = th
        pivot = None
    else:
        C, off = f.pivot_distance, f.offset
        if not 0 < (rb + off) / C < 1:
            raise ModelError(f"base circle: the face cannot touch it: (Rb + offset) / C = "
                             f"{(rb + off) / C:.6g} must lie between 0 and 1; change the base "
                             "circle, the offset or the pivot distance")
        g = math.asin((rb + off) / C) + S
        if not np.all((g > 0) & (g < math.pi / 2)):
            raise ModelError("follower: the face would swing past the pivot's line to the cam's "
                             "centre or beyond a right angle; lower the lift")
        h = C * np.sin(g) - off
        h1 = C * np.cos(g) * V
        h2 = C * (np.cos(g) * A - np.sin(g) * V * V)
        a1, a2 = 1.0 + V, A
        alpha = th + g
        pivot = np.array([C, 0.0])
    if not np.all(a1 > 0):
        raise ModelError("follower: the face turns back faster than the cam (1 + V <= 0); "
                         "lower the lift or lengthen its segment")
    N = np.stack([np.sin(alpha), np.cos(alpha)], axis=-1)
    T = np.stack([np.cos(alpha), -np.sin(alpha)], axis=-1)
    dh = h1 / a1                                   # dh/dalpha
    q = h[:, None] * N + dh[:, None] * T
    radius = h + (h2 * a1 - h1 * a2) / a1 ** 3
    contact = _rot(th, q)
    if pivot is None:
        phi = np.zeros_like(S)
        face = (float(V.min()), float(V.max()))
    else:
        g = alpha - th
        nf = np.stack([np.sin(g), np.cos(g)], axis=-1)
        m = -_J(contact - pivot)                  # the face's point at the contact, as S grows
        m /= np.hypot(m[:, 0], m[:, 1])[:, None]
        phi = np.arctan2(_cross(m, nf), np.einsum("ij,ij->i", m, nf))
        along = np.einsum("ij,ij->i", contact - pivot, np.stack([-np.cos(g), np.sin(g)], -1))
        face = (float(along.min()), float(along.max()))
    with np.errstate(divide="ignore"):
        kappa = 1.0 / radius
    return CamProfile(f, float(rb), float(rb), sv, q, q, contact, phi, kappa, radius,
                      radius <= 0, face)


def smallest_base_circle(program: MotionProgram, follower: Follower,
                         pressure_angle: float | None = None, *, min_radius: float = 0.0,
                         samples: int = 3601) -> float:
    """The smallest base circle's radius (m) for ``follower`` and ``program``.

    For a knife-edge or roller follower, the smallest whose largest |pressure angle| is
    ``pressure_angle`` (rad): translating, in closed form,
    ``d = max(|V - e| / tan(phi_max) - S)``, ``Rp = sqrt(d**2 + e**2)``, ``Rb = Rp - Rf``,
    its maximum refined between samples; oscillating, by bisection on Rp.
    For a flat-faced follower, the smallest without cusps whose profile's radius of
    curvature is everywhere at least ``min_radius``: translating,
    ``Rb = min_radius - min(S + S'')``.

    Raises
    ------
    ModelError
        No pressure angle for a roller, or one outside (0, 90) deg; a limit that every base
        circle meets (then any base circle will do: give one).
    """
    from scipy.optimize import brentq, minimize_scalar

    theta = np.linspace(0.0, TURN, samples)
    sv = program.svaj(theta)
    if follower.flat:
        if not (isinstance(min_radius, (int, float)) and math.isfinite(min_radius)
                and min_radius >= 0):
            raise ModelError(f"min_radius: expected a radius of at least 0, got {describe(min_radius)}")
        if follower.motion == "translating":
            g = sv.S + sv.A
            k = int(np.argmin(g))
            low = _refine(lambda t: float(np.sum(program.svaj(np.array([t])).S
                                                 + program.svaj(np.array([t])).A)),
                          theta, k, minimize_scalar, lowest=True)
            rb = min_radius - min(float(g[k]), low)
            if not rb > 0:
                raise ModelError("base circle: any base circle gives this profile no cusp; "
                                 "give one")
            return rb
        def margin(rb):
            return float(profile(program, follower, rb, theta=theta).profile_radius.min()) - min_radius
        return _scan(margin, 1e-6 * program.lift, follower.pivot_distance - follower.offset,
                     brentq, "no base circle gives this flat face a profile without cusps")
    if pressure_angle is None or not (0 < pressure_angle < math.pi / 2):
        raise ModelError(f"pressure_angle: expected the largest pressure angle, between 0 and 90 "
                         f"deg, got {describe(pressure_angle)}")
    tan = math.tan(pressure_angle)
    rf = follower.roller_radius
    if follower.motion == "translating":
        e = follower.offset

        def need(t):
            s = program.svaj(np.array([t]))
            return float(np.abs(s.V - e)[0] / tan - s.S[0])
        g = np.abs(sv.V - e) / tan - sv.S
        k = int(np.argmax(g))
        d = max(float(g[k]), _refine(need, theta, k, minimize_scalar))
        rb = math.sqrt(d * d + e * e) - rf
        if not (d > 0 and rb > 0):
            raise ModelError("pressure_angle: every base circle keeps the pressure angle within "
                             "the limit; give the base circle instead")
        return rb

    def margin(rb):
        phi = profile(program, follower, rb, theta=theta).pressure_angle
        return pressure_angle - float(np.abs(phi).max())
    C, L = follower.pivot_distance, follower.arm_length
    return _scan(margin, abs(C - L) - rf, C + L - rf, brentq,
                 "no base circle the arm reaches keeps the pressure angle within the limit")


def _refine(fun, theta, k, minimize_scalar, lowest=False) -> float:
    """The extreme of ``fun`` near the sample ``k`` (largest, or ``lowest``)."""
    a, b = theta[max(k - 1, 0)], theta[min(k + 1, len(theta) - 1)]
    sign = 1.0 if lowest else -1.0
    r = minimize_scalar(lambda t: sign * fun(t), bounds=(a, b), method="bounded",
                        options={"xatol": 1e-13})
    return float(sign * r.fun)


def _scan(margin, lo, hi, brentq, failure) -> float:
    """The smallest radius in (lo, hi) where ``margin`` turns >= 0, by a scan then brentq."""
    grid = np.linspace(lo, hi, 402)[1:-1]
    prev = None
    for rb in grid:            # a scan over candidate circles, each a vectorised profile
        if rb <= 0:
            continue
        try:
            ok = margin(rb)
        except ModelError:
            prev = None
            continue
        if ok >= 0:
            if prev is None:
                return float(rb)
            return float(brentq(margin, prev, rb, xtol=1e-14 * hi))
        prev = rb
    raise ModelError(f"base circle: {failure}; change the follower's geometry or the limit")
