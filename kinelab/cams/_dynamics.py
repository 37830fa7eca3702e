"""The follower's dynamics: the contact force between cam and follower over a turn, the jump
check, and the torque on the cam shaft (Norton, *Design of Machinery*, ch. 8, cam dynamics).

The follower train is one rigid mass ``m`` held against the cam by a return spring of
stiffness ``k`` and preload ``F0`` (its force at the follower's lowest position, S = 0), with
viscous damping ``c`` and a constant load ``F_ext`` towards the cam; the cam turns at the
constant speed ``omega``.  The follower's coordinate is x = S(theta), theta = omega t,
positive away from the cam, so that

    x' = V omega,    x'' = A omega**2                 (omega constant)

and Newton's law along x, with the contact force N pushing the follower away from the cam
and every other force pulling it back,

    m x'' = N - (k S + F0) - c x' - F_ext,

gives the contact force the cam must supply:

    N(theta) = m A omega**2 + c V omega + k S + F0 + F_ext.

The cam can only push: where N <= 0 the follower leaves the cam (it *jumps*).  With the
contact frictionless, the power the shaft puts in is the power the cam gives the follower,
T omega = N x' = N V omega, so the torque on the cam shaft is

    T(theta) = N(theta) V(theta).

Without damping N V = d/dtheta (m omega**2 V**2 / 2 + k S**2 / 2 + (F0 + F_ext) S) is an exact
derivative, and the mean torque over a turn is 0; with damping it is the damping's work per
turn over 2 pi, c omega integral(V**2) / (2 pi).

An oscillating follower obeys the same equations about its pivot, with S an angle (rad): its
moment of inertia about the pivot for m (kg m**2), a torsional spring (N m/rad, preload N m),
torsional damping (N m s/rad) and a constant moment (N m); N is then the moment of the
contact force about the pivot (N m) and T the same shaft torque.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinelab.cams._program import TURN, MotionProgram
from kinelab.errors import ModelError, describe, expected_one_of

__all__ = ["FollowerForces", "follower_forces"]

MOTIONS = ("translating", "oscillating")
# The mean torque: Gauss-Legendre over each eighth of each segment, where every law is smooth
# (the piecewise laws, modified trapezoid and modified sine, change piece at eighths).
_GAUSS, _PARTS = 16, 8


def _number(v, name: str, problems: list, *, low=None, strict=False):
    if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) \
            or not math.isfinite(v):
        problems.append(f"{name}: expected a finite number, got {describe(v)}")
        return None
    v = float(v)
    if low is not None and (v <= low if strict else v < low):
        problems.append(f"{name}: expected a number {'above' if strict else 'at least'} "
                        f"{low:g}, got {v:.6g}")
        return None
    return v


@dataclass(frozen=True)
class FollowerForces:
    """The contact force, the jump check and the shaft torque of a cam's follower over a turn.

    Attributes
    ----------
    program : MotionProgram
    motion : {'translating', 'oscillating'}
    mass, stiffness, preload, damping, external, speed : float
        The follower train's mass (kg; kg m**2 oscillating), the return spring's stiffness
        (N/m; N m/rad) and preload at S = 0 (N; N m), the viscous damping (N s/m; N m s/rad),
        the constant load towards the cam (N; N m) and the cam speed (rad/s).
    theta : (N,) array
        Cam angles, rad.
    S, V, A : (N,) arrays
        The program at ``theta`` (per rad).
    contact_force : (N,) array
        N(theta), N (oscillating: its moment about the pivot, N m); contact is kept where it
        is above 0.
    torque : (N,) array
        The torque on the cam shaft, T = N V, N m (frictionless contact).

    Where the contact force is not above 0 the follower has left the cam, and both are the
    force and torque that *would* keep it on its program (what a form-closed cam, a groove or
    a conjugate pair, would have to supply).
    """
    program: MotionProgram
    motion: str
    mass: float
    stiffness: float
    preload: float
    damping: float
    external: float
    speed: float
    theta: np.ndarray
    S: np.ndarray
    V: np.ndarray
    A: np.ndarray
    contact_force: np.ndarray
    torque: np.ndarray

    @property
    def _parameters(self) -> dict:
        return {k: getattr(self, k) for k in ("mass", "stiffness", "preload", "damping",
                                              "external", "speed")}

    @property
    def contact(self) -> np.ndarray:
        """(N,) bool: where the cam holds the follower (contact force above 0)."""
        return self.contact_force > 0

    @property
    def jumps(self) -> bool:
        """True when the follower leaves the cam somewhere over the turn."""
        return not bool(self.contact.all())

    @property
    def jump_angle(self) -> float | None:
        """The first cam angle (rad) where the contact force is at or below 0; None if it is
        above 0 everywhere."""
        bad = np.flatnonzero(~self.contact)
        return float(self.theta[bad[0]]) if bad.size else None

    @property
    def least_force(self) -> tuple[float, float]:
        """The smallest contact force (N; N m oscillating) and the cam angle where it is."""
        k = int(np.argmin(self.contact_force))
        return float(self.contact_force[k]), float(self.theta[k])

    @property
    def peak_torque(self) -> tuple[float, float]:
        """The largest |shaft torque| (N m, with its sign) and the cam angle where it is."""
        k = int(np.argmax(np.abs(self.torque)))
        return float(self.torque[k]), float(self.theta[k])

    @property
    def mean_torque(self) -> float:
        """The shaft torque's mean over one turn, N m: 0 without damping (the spring's and
        the mass's energy come back), the damping's work per turn over 2 pi with it.
        Integrated by Gauss-Legendre quadrature over each eighth of each segment (where the
        laws are smooth), not from the samples."""
        x, w = np.polynomial.legendre.leggauss(_GAUSS)
        starts = np.array([s.start + s.beta * i / _PARTS for s in self.program.segments
                           for i in range(_PARTS)])
        h = np.repeat([0.5 * s.beta / _PARTS for s in self.program.segments], _PARTS)
        t = starts[:, None] + h[:, None] * (x[None, :] + 1.0)
        sv = self.program.svaj(t)
        n = _force(sv.S, sv.V, sv.A, **self._parameters)
        return float(np.sum(h * ((n * sv.V) @ w)) / TURN)

    @property
    def critical_speed(self) -> float:
        """The largest cam speed (rad/s) up to which the contact force stays above 0 at every
        sample: ``inf`` if it never falls to 0, 0 if it is not above 0 even at rest.

        N is ``m A w**2 + c V w + G`` with ``G = k S + F0 + F_ext``.  Without damping it is
        affine in w**2, and where A < 0 it falls to 0 at ``w**2 = G / (-m A)``; with damping
        each sample's first positive root of the quadratic in w is taken.  The least over
        the samples is the answer."""
        g = self.stiffness * self.S + self.preload + self.external
        if np.any(g <= 0):
            return 0.0
        a, b = self.mass * self.A, self.damping * self.V
        root = np.full(g.shape, np.inf)
        with np.errstate(divide="ignore", invalid="ignore"):
            lin = (a == 0) & (b < 0)
            root[lin] = -g[lin] / b[lin]
            quad = a != 0
            disc = b * b - 4 * a * g
            real = quad & (disc >= 0)
            sq = np.sqrt(np.where(real, disc, 0.0))
            q = -0.5 * (b + np.where(b >= 0, sq, -sq))      # the stable pair q / a, g / q
            r1 = np.where(real, q / a, np.inf)
            r2 = np.where(real & (q != 0), g / q, np.inf)
            for r in (r1, r2):
                ok = real & (r > 0)
                root[ok] = np.minimum(root[ok], r[ok])
        return float(root.min())

    def least_preload(self, margin: float = 0.0) -> float:
        """The smallest preload (N; N m oscillating) for which the contact force is at least
        ``margin`` everywhere at this speed: ``margin - min(N - F0)``.  It may be below 0 (no
        spring needed) or below the present preload."""
        m = _number(margin, "margin", problems := [], low=0.0)
        if problems:
            raise ModelError(problems)
        return float(m - (self.contact_force - self.preload).min())

    def to_columns(self, *, degrees: bool = False) -> dict:
        """The table: cam angle, S, V, A, contact force and shaft torque, each column named
        with its unit (angles in degrees when ``degrees``)."""
        a, au = (math.pi / 180, "deg") if degrees else (1.0, "rad")
        osc = self.motion == "oscillating"
        lu = "rad" if osc else "m"
        return {f"theta [{au}]": self.theta / a, f"S [{lu}]": self.S,
                f"V [{lu}/rad]": self.V, f"A [{lu}/rad^2]": self.A,
                ("contact_moment [N m]" if osc else "contact_force [N]"): self.contact_force,
                "shaft_torque [N m]": self.torque}

    def __repr__(self) -> str:
        f, at = self.least_force
        return (f"FollowerForces({self.theta.size} samples at {self.speed:.6g} rad/s, least "
                f"contact {f:.6g} at {math.degrees(at):.6g} deg, "
                f"{'jumps' if self.jumps else 'contact kept'})")


def _force(S, V, A, *, mass, stiffness, preload, damping, external, speed) -> np.ndarray:
    return mass * A * speed ** 2 + damping * V * speed + stiffness * S + preload + external


def follower_forces(program: MotionProgram, *, mass: float, stiffness: float, preload: float,
                    speed: float, damping: float = 0.0, external: float = 0.0,
                    motion: str = "translating", theta=None,
                    samples: int = 721) -> FollowerForces:
    """The contact force between a cam and its spring-loaded follower over a turn, the jump
    check and the torque on the cam shaft.

    With the follower at x = S(theta), theta = omega t, omega constant, Newton's law along x
    (away from the cam), ``m x'' = N - (k S + F0) - c x' - F_ext``, with ``x' = V omega`` and
    ``x'' = A omega**2``, gives the contact force::

        N = m A omega**2 + c V omega + k S + F0 + F_ext

    and the power balance of frictionless contact, ``T omega = N x'``, the shaft torque
    ``T = N V``.  Where N <= 0 the follower leaves the cam.

    Parameters
    ----------
    program : MotionProgram
        S, V, A per rad of cam angle; S = 0 at the follower's lowest position.
    mass : float
        The follower train's effective mass, kg, above 0 (oscillating: its moment of inertia
        about the pivot, kg m**2).
    stiffness : float
        The return spring's stiffness, N/m, at least 0 (oscillating: N m/rad).
    preload : float
        The spring's force at S = 0, N, at least 0 (oscillating: its moment, N m).
    speed : float
        The cam's speed omega, rad/s, above 0 (the cam turns counterclockwise).
    damping : float
        Viscous damping c, N s/m, at least 0 (oscillating: N m s/rad).
    external : float
        A constant load on the follower towards the cam, N (oscillating: N m); e.g. the
        follower's weight when it stands above the cam, ``m g``; negative away from it.
    motion : {'translating', 'oscillating'}
        Which units the numbers are in (the equations are the same).
    theta : array_like, shape (N,), optional
        Cam angles, rad; by default ``samples`` angles from 0 to 2 pi included.

    Returns
    -------
    FollowerForces
        ``contact_force`` and ``torque`` at the samples, ``least_force``, ``jump_angle``,
        ``critical_speed``, ``least_preload(margin)``, ``peak_torque``, ``mean_torque``.

    Raises
    ------
    ModelError
        Every bad argument at once, each named (a mass not above 0, a negative stiffness, a
        number that is not one ...).

    References
    ----------
    R. L. Norton, *Design of Machinery*, ch. 8 (cam dynamics: force-closed followers, jump).

    Examples
    --------
    A double-dwell cam, a 25 mm cycloidal rise and 3-4-5 return over 90 deg each, at 200 rpm,
    with a 2 kg follower on a 2 kN/m spring preloaded to 40 N:

    >>> from kinelab.cams import MotionProgram, Segment, follower_forces
    >>> d = np.radians
    >>> p = MotionProgram([Segment("rise", 0, d(90), 0.025, "cycloidal"),
    ...                    Segment("dwell", d(90), d(180)),
    ...                    Segment("return", d(180), d(270), 0.025, "3-4-5"),
    ...                    Segment("dwell", d(270), d(360))])
    >>> rpm = np.pi / 30                                     # rad/s
    >>> ff = follower_forces(p, mass=2.0, stiffness=2000.0, preload=40.0, speed=200 * rpm)
    >>> ff.contact_force.shape, ff.jumps
    ((721,), False)
    >>> force, at = ff.least_force                           # N, on the rise's deceleration
    >>> round(force, 3), round(float(np.degrees(at)), 1)
    (28.946, 65.0)
    >>> round(ff.critical_speed / rpm, 1)                    # jump-free up to this speed
    246.8
    >>> abs(ff.mean_torque) < 1e-12                          # no damping: no work per turn
    True

    At 400 rpm the follower leaves the cam; a preload of 178.09 N would hold it:

    >>> fast = follower_forces(p, mass=2.0, stiffness=2000.0, preload=40.0, speed=400 * rpm)
    >>> fast.jumps, round(float(np.degrees(fast.jump_angle)), 1), round(fast.least_preload(), 2)
    (True, 50.0, 178.09)
    """
    problems: list[str] = []
    if not isinstance(program, MotionProgram):
        problems.append(f"program: expected a MotionProgram, got {describe(program)}")
    if motion not in MOTIONS:
        problems.append(f"motion: {expected_one_of(motion, MOTIONS)}")
    values = {
        "mass": _number(mass, "mass", problems, low=0.0, strict=True),
        "stiffness": _number(stiffness, "stiffness", problems, low=0.0),
        "preload": _number(preload, "preload", problems, low=0.0),
        "damping": _number(damping, "damping", problems, low=0.0),
        "external": _number(external, "external", problems),
        "speed": _number(speed, "speed", problems, low=0.0, strict=True),
    }
    if problems:
        raise ModelError(problems)
    if theta is None:
        if isinstance(samples, bool) or not isinstance(samples, int) or samples < 2:
            raise ModelError(f"samples: expected a whole number of at least 2, got "
                             f"{describe(samples)}")
        theta = np.linspace(0.0, TURN, samples)
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    if theta.ndim != 1 or theta.size == 0:
        raise ModelError(f"theta: expected cam angles of shape (N,), got shape {theta.shape}")
    sv = program.svaj(theta)
    n = _force(sv.S, sv.V, sv.A, **values)
    return FollowerForces(program, motion, theta=sv.theta, S=sv.S, V=sv.V, A=sv.A,
                          contact_force=n, torque=n * sv.V, **values)
