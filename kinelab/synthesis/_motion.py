"""Motion generation with a four-bar: two and three prescribed positions (*Mecanismos*, §6.1-6.5).

Every synthesized linkage comes back as a :class:`MotionSolution`: its pivots, a kinelab
model sketched in position 1, and the checks made with the kinematics engine.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.mechanisms import Grashof
from kinelab.model import MAX_LENGTH, Mechanism, is_real
from kinelab.solvers import wrap_angle
from kinelab.synthesis._linkage import (TRANSMISSION_LIMIT, CheckedLinkage, at_inputs, circuits,
                                        finite_or_inf, fourbar_model, model_grashof,
                                        nearer_branch, planned, transmission_defects,
                                        transmission_limit, travel)
from kinelab.solvers._arguments import flag
from kinelab.synthesis._arguments import angle_array, coordinate
from kinelab.synthesis._pivots import fixed_pivot, moving_pivot, standard_form_dyad
from kinelab.synthesis._positions import (Positions, as_positions, as_xy, check_not_one_turn,
                                          cross, fmt, poles)

__all__ = ["MotionSolution", "TwoPositions", "two_positions", "three_positions", "motion_solution"]

_REACHED = 1e-8   # relative pose error under which the engine reaches a prescribed pose


@dataclass(frozen=True, eq=False)
class MotionSolution(CheckedLinkage):
    """A four-bar that guides its coupler through prescribed positions, with its checks.

    Attributes
    ----------
    A0, B0 : ndarray, shape (2,)
        Fixed pivots of the crank (the input) and of the rocker, m.
    A1, B1 : ndarray, shape (2,)
        Moving pivots in position 1, m.
    points : ndarray, shape (n, 2)
        The prescribed positions of the coupler point P, m.
    alpha : ndarray, shape (n,)
        The prescribed rotations of the coupler from position 1, rad.
    model : Mechanism
        The four-bar (names as :func:`kinelab.mechanisms.fourbar`: links ``ground, crank,
        coupler, rocker``, points ``O2 = A0, A, B, O4 = B0, P``), sketched in position 1.
    q : ndarray, shape (n,)
        The crank angle (the model's input) in each position, rad.
    grashof : Grashof
        Grashof class of the linkage.
    min_transmission_angle : float
        Smallest transmission angle (folded to [0, pi/2]) met while the crank carries the
        coupler from position 1 to position n, rad (the engine's, :func:`kinelab.analyze`).
    branch_defect, order_defect : bool
        See :mod:`kinelab.synthesis` (a branch defect: some position lies on the other
        assembly branch or beyond a limit position; an order defect: turning the crank one
        way does not pass the positions in order).
    circuit_defect : bool
        Some position lies on the other circuit of a Grashof linkage: no motion of the
        assembled linkage reaches it from position 1 (see :func:`circuits`).
    direction : int
        +1 if the crank turns counter-clockwise from position 1 to n, -1 clockwise, 0 if
        no single sense passes the positions in order.
    position_errors : ndarray, shape (n,)
        Distance between the engine's coupler point at ``q[j]`` and the prescribed one, m
        (+inf where the linkage cannot close there on position 1's branch).
    angle_errors : ndarray, shape (n,)
        Error of the engine's coupler rotation at ``q[j]``, rad (+inf likewise).
    dyad_residuals : ndarray, shape (n, 2)
        For each position, how much the crank (column 0) and the rocker (column 1) would
        have to change length to reach it: ``|A_j - A0| - crank``, ``|B_j - B0| - rocker``,
        m.  Zero (to rounding) for exact synthesis; the residuals of the least-squares fit
        for :func:`approximate_positions`.
    defects : tuple of str
        A sentence for each defect found (a transmission angle below ``transmission_limit``
        is one); empty for a usable linkage.
    transmission_limit : float
        The smallest transmission angle the task accepts, rad (30 deg unless it says
        otherwise); ``meets_transmission_limit`` says whether the linkage keeps it.
    """

    A0: np.ndarray
    B0: np.ndarray
    A1: np.ndarray
    B1: np.ndarray
    points: np.ndarray
    alpha: np.ndarray
    model: Mechanism
    q: np.ndarray
    grashof: Grashof
    min_transmission_angle: float
    branch_defect: bool
    order_defect: bool
    circuit_defect: bool
    direction: int
    position_errors: np.ndarray
    angle_errors: np.ndarray
    dyad_residuals: np.ndarray
    defects: tuple[str, ...]
    transmission_limit: float = TRANSMISSION_LIMIT

    def __repr__(self) -> str:
        f = np.array2string
        state = self.state
        return (f"MotionSolution(A0={f(self.A0, precision=6)}, B0={f(self.B0, precision=6)}, "
                f"A1={f(self.A1, precision=6)}, B1={f(self.B1, precision=6)}, "
                f"{self.grashof.kind}, {state})")


def motion_solution(pos: Positions, A0, B0, A1, B1,
                    radii: tuple[float, float] | None = None, *,
                    limit: float = TRANSMISSION_LIMIT,
                    remedy: str = "choose another rocker pivot") -> MotionSolution:
    """Build the model of a synthesized four-bar and check it with the engine.

    ``limit`` is the smallest transmission angle accepted (rad); ``remedy`` what the
    task's author is told to change when position 1 is a dead centre of the linkage.
    With ``radii`` (the crank's and the rocker's lengths fitted by least squares) the
    linkage is approximate: it is sketched with those lengths at the crank angle of
    position 1, and a position counts as reached on the sketch's branch when the engine's
    rocker pin is nearer the prescribed one than its mirror image across the line from the
    crank pin to B0 (the other branch's pin) is.
    """
    A0, B0, A1, B1 = (np.asarray(v, float) for v in (A0, B0, A1, B1))
    Aj, Bj = pos.carry(A1), pos.carry(B1)
    exact = radii is None
    if exact:
        model = fourbar_model(A0, B0, A1, B1, P=pos.points[0], name="synthesized fourbar")
        radii = (float(np.linalg.norm(A1 - A0)), float(np.linalg.norm(B1 - B0)))
    else:
        model = _fitted_model(pos, A0, B0, A1, B1, radii)
    planned(model, "position 1", remedy)
    q = np.arctan2(Aj[:, 1] - A0[1], Aj[:, 0] - A0[0])
    scale = max(pos.size, max(model.parameters[k] for k in ("ground", "crank", "coupler", "rocker")))

    def pose_errors(sol, idx):
        P = sol.position("P")[idx]
        th = sol.angle("coupler")
        dpos = np.linalg.norm(P - pos.points, axis=-1)
        dang = np.abs(wrap_angle(th[idx] - th[0] - pos.alpha))
        return finite_or_inf(dpos), finite_or_inf(dang)

    def reached(sol, idx):
        if not exact:
            return nearer_branch(sol, idx, Bj, B0)
        dpos, dang = pose_errors(sol, idx)
        return (dpos <= _REACHED * scale) & (dang <= _REACHED)

    t = travel(model, q, reached)
    circuit = circuits(A0, B0, Aj, Bj, model_grashof(model))
    defects = t.defects
    if circuit is not None and np.any(circuit != circuit[0]):
        lost = ", ".join(str(j + 1) for j in np.flatnonzero(circuit != circuit[0]))
        defects += (f"circuit defect: position(s) {lost} lie on the other circuit of the "
                    "linkage; it cannot move there from position 1 without being taken apart",)
    circuit_defect = len(defects) > len(t.defects)
    defects += transmission_defects(t.min_transmission_angle, limit,
                                    f"between position 1 and position {pos.n}")
    dpos, dang = pose_errors(at_inputs(model, q), np.arange(pos.n))
    residuals = np.column_stack([np.linalg.norm(Aj - A0, axis=1) - radii[0],
                                 np.linalg.norm(Bj - B0, axis=1) - radii[1]])
    for a in (A0, B0, A1, B1, q, dpos, dang, residuals):
        a.setflags(write=False)
    return MotionSolution(A0=A0, B0=B0, A1=A1, B1=B1, points=pos.points, alpha=pos.alpha,
                          model=model, q=q, grashof=model_grashof(model),
                          min_transmission_angle=t.min_transmission_angle,
                          branch_defect=t.branch_defect, order_defect=t.order_defect,
                          circuit_defect=circuit_defect,
                          direction=t.direction, position_errors=dpos, angle_errors=dang,
                          dyad_residuals=residuals, defects=defects, transmission_limit=limit)


def _fitted_model(pos: Positions, A0, B0, A1, B1, radii) -> Mechanism:
    """The four-bar with crank and rocker of the fitted lengths, the coupler of the moving
    plane, assembled at position 1's crank angle on position 1's branch."""
    ra, rb = radii
    A = A0 + ra * (A1 - A0) / np.linalg.norm(A1 - A0)
    coupler = float(np.linalg.norm(B1 - A1))
    D = B0 - A
    L = float(np.linalg.norm(D))
    if not abs(coupler - rb) < L < coupler + rb:
        raise ModelError("the fitted crank and rocker cannot be assembled at position 1's crank "
                         "angle (the coupler does not reach the rocker's circle)")
    along = (L * L + coupler * coupler - rb * rb) / (2 * L)
    side = np.sign(cross(B0 - A1, B1 - A1)) or 1.0
    perp = side * np.array([-D[1], D[0]]) / L    # towards B1's side of the line A -> B0
    B = A + along * D / L + math.sqrt(max(coupler * coupler - along * along, 0.0)) * perp
    # the coupler point: the same place relative to AB as in the moving plane
    e1 = (B1 - A1) / coupler
    r = pos.points[0] - A1
    u, v = float(r @ e1), float(cross(e1, r))
    e = (B - A) / coupler
    P = A + u * e + v * np.array([-e[1], e[0]])
    return fourbar_model(A0, B0, A, B, P=P, name="synthesized fourbar")
# -- two positions ----------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class TwoPositions:
    """Two positions with the moving pivots chosen: the fixed pivots form a family.

    A fixed pivot A0 keeps |A1 - A0| = |A2 - A0|, so it can be any point of the
    perpendicular bisector of A1A2 (*Mecanismos*, §6.1, fig. 52); likewise B0.  Both
    bisectors pass through the pole P12.

    Attributes
    ----------
    positions : Positions
    A1, B1, A2, B2 : ndarray, shape (2,)
        The moving pivots in positions 1 and 2, m.
    A0_origin, A0_direction : ndarray, shape (2,)
        The bisector of A1A2: its midpoint and unit direction; A0 = origin + s direction.
    B0_origin, B0_direction : ndarray, shape (2,)
        The same for B.
    pole : ndarray, shape (2,), or None
        P12, m; None when the plane only translates (alpha_12 = 0: the pole is at
        infinity and the two bisectors are parallel).
    alpha : float
        alpha_12, rad.
    """

    positions: Positions
    A1: np.ndarray
    B1: np.ndarray
    A2: np.ndarray
    B2: np.ndarray
    A0_origin: np.ndarray
    A0_direction: np.ndarray
    B0_origin: np.ndarray
    B0_direction: np.ndarray
    pole: np.ndarray | None
    alpha: float

    def A0(self, s: ArrayLike) -> np.ndarray:
        """Fixed pivots A0 = A0_origin + s A0_direction, shape s.shape + (2,)."""
        return self.A0_origin + np.multiply.outer(np.asarray(s, float), self.A0_direction)

    def B0(self, t: ArrayLike) -> np.ndarray:
        """Fixed pivots B0 = B0_origin + t B0_direction, shape t.shape + (2,)."""
        return self.B0_origin + np.multiply.outer(np.asarray(t, float), self.B0_direction)

    def solution(self, s: float, t: float, *,
                 min_transmission_angle: float = TRANSMISSION_LIMIT) -> MotionSolution:
        """The four-bar with fixed pivots ``A0(s)`` and ``B0(t)``, checked (``s`` and ``t``
        in m, at most 1e9 in size; below ``min_transmission_angle``, rad, on the way from
        position 1 to 2 it has a transmission angle defect)."""
        s, t = coordinate("s", s), coordinate("t", t)
        limit = transmission_limit(min_transmission_angle)
        A0, B0 = self.A0(s), self.B0(t)
        for name, X in (("s", A0), ("t", B0)):
            if np.abs(X).max() > MAX_LENGTH:
                raise ModelError(f"{name}: puts the fixed pivot at {fmt(X)}, beyond the "
                                 f"coordinates kinelab computes with ({MAX_LENGTH:g} m); choose "
                                 "a smaller value")
        return motion_solution(self.positions, A0, B0, self.A1, self.B1, limit=limit,
                               remedy="choose another t (it moves B0 along its bisector) or B1")


def _bisector(X1, X2, name, size):
    d = X2 - X1
    L = np.linalg.norm(d)
    if L <= 1e-12 * size:
        raise ModelError(f"{name}1: it is the pole P12, the one point of the moving plane that is "
                         "in the same place in both positions, so any fixed pivot would do and "
                         "none is singled out; choose another moving pivot")
    return 0.5 * (X1 + X2), np.array([-d[1], d[0]]) / L


def two_positions(points, angles=None, A1: ArrayLike = None, B1: ArrayLike = None, *,
                  degrees: bool = False) -> TwoPositions:
    """Two positions, moving pivots chosen: the bisector families of fixed pivots.

    Parameters
    ----------
    points, angles : see :class:`Positions`
        Two positions of the moving plane.
    A1, B1 : array_like, shape (2,)
        The moving pivots in position 1, m.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    TwoPositions
        The families; ``.solution(s, t)`` picks one linkage.

    Raises
    ------
    ModelError
        Not two positions, or a moving pivot at the pole (it does not move, so no fixed
        pivot is singled out).

    Examples
    --------
    >>> fam = kl.synthesis.two_positions([(0, 0), (1, 1)], [0, 90], A1=(0, -1), B1=(1, -1),
    ...                                  degrees=True)
    >>> fam.pole.round(12) + 0.0          # P12: a quarter turn about (0, 1) takes P1 to P2
    array([0., 1.])
    >>> sol = fam.solution(s=1.0, t=2.0)
    >>> bool(np.allclose(np.linalg.norm(sol.A0 - fam.A1), np.linalg.norm(sol.A0 - fam.A2)))
    True
    """
    pos = as_positions(points, angles, degrees)
    if pos.n != 2:
        raise ModelError(f"points: expected two positions, got {pos.n}; use three_positions or "
                         "four_positions for more")
    A1, B1 = as_xy("A1", A1), as_xy("B1", B1)
    p = poles(pos)
    (A1_, A2), (B1_, B2) = pos.carry(A1), pos.carry(B1)
    size = max(pos.size, float(np.ptp(np.vstack([A1, B1, pos.points]), axis=0).max()))
    oa, da = _bisector(A1_, A2, "A", size)
    ob, db = _bisector(B1_, B2, "B", size)
    out = dict(A1=A1, B1=B1, A2=A2, B2=B2, A0_origin=oa, A0_direction=da, B0_origin=ob,
               B0_direction=db)
    for a in out.values():
        a.setflags(write=False)
    return TwoPositions(positions=pos, alpha=float(p.alpha[0]),
                        pole=p.P[0] if p.finite[0] else None, **out)


# -- three positions ----------------------------------------------------------------------
def _rotations(beta, degrees: bool) -> tuple[np.ndarray | None, np.ndarray | None]:
    """``beta`` as (the crank's (beta_2, beta_3) or None, the rocker's or None), rad."""
    if beta is None:
        return None, None
    shape = ("expected the crank's rotations (beta_2, beta_3), or one pair for each dyad "
             "((beta_2, beta_3), (gamma_2, gamma_3)) with None for a dyad given by its pivots")
    try:
        items = list(beta)
    except TypeError:
        raise ModelError(f"beta: {shape}, got {describe(beta)}") from None
    if len(items) == 2 and all(is_real(v) or (isinstance(v, np.ndarray) and v.ndim == 0)
                               for v in items):
        items = [beta, None]                  # the crank's pair alone
    elif len(items) != 2 or all(v is None for v in items):
        raise ModelError(f"beta: {shape}, got {describe(beta)}")
    out = []
    for k, row in enumerate(items):
        if row is None:
            out.append(None)
            continue
        a = angle_array(f"beta[{k}]", row, degrees)
        if a.shape != (2,):
            raise ModelError(f"beta[{k}]: expected two rotations (from position 1 to 2 and to 3), "
                             f"got {describe(row)}")
        out.append(a)
    return out[0], out[1]


def three_positions(points, angles=None, A0: ArrayLike | None = None, B0: ArrayLike | None = None,
                    *, A1: ArrayLike | None = None, B1: ArrayLike | None = None,
                    beta: ArrayLike | None = None,
                    method: str = "suh-radcliffe", min_transmission_angle: float | None = None,
                    degrees: bool = False) -> MotionSolution:
    """Three positions: the four-bar through them, from two chosen pivots or rotations.

    For each dyad give either its fixed pivot (``A0``, ``B0``: the moving pivot follows
    from the Suh-Radcliffe linear system, *Mecanismos*, eq. 67-68, or from Burmester's pole
    construction, §6.2), its moving pivot in position 1 (``A1``, ``B1``: the fixed
    pivot is the centre of the circle through its three positions), or the rotations of
    its link from position 1 to 2 and 3 (``beta``).

    **Rotations: Erdman and Sandor's standard form** (Norton, *Design of Machinery*,
    ch. 5).  Let W be the crank, from A0 to A1, and Z the coupler's vector from A1 to
    P1, as complex numbers.  In position j the crank has turned by beta_j and the
    coupler by alpha_j, so P_j = A0 + W e^(i beta_j) + Z e^(i alpha_j), and

        W (e^(i beta_j) - 1) + Z (e^(i alpha_j) - 1) = delta_j = P_j - P_1,   j = 2, 3:

    two complex equations, linear in W and Z once beta_2 and beta_3 are chosen: one
    dyad, A1 = P1 - Z, A0 = A1 - W.  The rocker's dyad (U, S in Norton) is the same
    equation with the rocker's rotations (gamma_2, gamma_3).  Both rotations are CCW
    positive; the crank of the linkage found turns by exactly beta_2, beta_3 (``q[j] -
    q[0]``, to a multiple of a turn).

    Parameters
    ----------
    points : array_like, shape (3, 2), or Positions
        The coupler point P in positions 1, 2, 3, m.
    angles : array_like, shape (3,) or (2,)
        Orientations of the coupler, or rotations alpha_2, alpha_3 from position 1, rad.
    A0, B0 : array_like, shape (2,), optional
        Fixed pivots of the crank and of the rocker, m.
    A1, B1 : array_like, shape (2,), optional, keyword-only
        Moving pivots in position 1, m (instead of A0, B0).
    beta : array_like, shape (2,) or (2, 2), optional, keyword-only
        ``(beta_2, beta_3)``: the crank's rotations from position 1 to 2 and to 3 (rad,
        or degrees with ``degrees=True``), instead of A0 or A1; or one pair for each
        dyad, ``((beta_2, beta_3), (gamma_2, gamma_3))``, the second the rocker's
        rotations instead of B0 or B1, either pair None for a dyad given by its pivots.
    method : {"suh-radcliffe", "poles"}
        How a moving pivot is found from a fixed one (see :func:`moving_pivot`).
    min_transmission_angle : float, optional
        The smallest transmission angle accepted between position 1 and position 3 (rad,
        or degrees with ``degrees=True``); default 30 deg (:data:`TRANSMISSION_LIMIT`).
        Below it the linkage has a transmission angle defect.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    MotionSolution
        With ``A0, B0, A1, B1`` and the ``model`` in position 1, checked by the engine.

    Raises
    ------
    ModelError
        Not three positions, a dyad given by more or fewer than one of its pivots and its
        rotations, a pivot at infinity, coincident pivots, rotations that fix no dyad (or a
        link of zero length), or pivots that put the linkage at a dead centre in position 1
        (the coupler and the rocker in line).

    Examples
    --------
    *Mecanismos*, §6.5: A0 = (5, 0), B0 = (0, 0) m, P = (1, 1), (2, 0.5), (3, 1.5) m,
    alpha_2 = 0, alpha_3 = 45 deg -> Table 4:

    >>> sol = kl.synthesis.three_positions([(1, 1), (2, 0.5), (3, 1.5)], [0, 45], (5, 0), (0, 0),
    ...                                    degrees=True)
    >>> sol.A1.round(3), sol.B1.round(3)
    (array([ 3.548, -1.655]), array([0.994, 3.238]))
    >>> sol.model.parameters["kind"], bool(sol.position_errors.max() < 1e-9)
    ('fourbar', True)

    The same positions with the rotations chosen instead (the standard form): the crank
    turns by -30 and -75 deg, the rocker by 15 and 30 deg:

    >>> sol = kl.synthesis.three_positions([(1, 1), (2, 0.5), (3, 1.5)], [0, 45],
    ...                                    beta=((-30, -75), (15, 30)), degrees=True)
    >>> sol.A0.round(6), sol.B0.round(6)
    (array([-2.296115,  0.461672]), array([1.873598, 5.044869]))
    >>> np.degrees(sol.q - sol.q[0]).round(9) + 0.0       # the crank's turns
    array([  0., -30., -75.])
    >>> sol.valid
    True
    >>> bool(sol.position_errors.max() < 1e-9 and sol.angle_errors.max() < 1e-9)
    True
    """
    pos = as_positions(points, angles, degrees)
    limit = transmission_limit(min_transmission_angle, degrees)
    if pos.n != 3:
        raise ModelError(f"points: expected three positions, got {pos.n}"
                         + ("; use four_positions" if pos.n == 4 else ""))
    check_not_one_turn(pos)
    rotations = _rotations(beta, flag("degrees", degrees))
    pivots = {}
    problems = []
    for k, (side, fixed, moving, turns) in enumerate((("A", A0, A1, rotations[0]),
                                                       ("B", B0, B1, rotations[1]))):
        given = [n for n, v in ((f"{side}0", fixed), (f"{side}1", moving), (f"beta[{k}]", turns))
                 if v is not None]
        if turns is None and len(given) != 1:
            problems.append(f"{side}0, {side}1: give exactly one of the fixed pivot {side}0 and "
                            f"the moving pivot {side}1, got "
                            + ("both" if fixed is not None else "neither"))
            continue
        if len(given) != 1:
            problems.append(f"{side}0, {side}1, beta[{k}]: give exactly one of the fixed pivot "
                            f"{side}0, the moving pivot {side}1 and the rotations beta[{k}], got "
                            + " and ".join(given))
            continue
        if turns is not None:
            link = "crank" if k == 0 else "rocker"
            pivots[side] = standard_form_dyad(pos, turns, f"beta[{k}]", link)
        elif fixed is not None:
            f = as_xy(f"{side}0", fixed)
            pivots[side] = (f, moving_pivot(pos, fixed=f, method=method))
        else:
            m = as_xy(f"{side}1", moving)
            pivots[side] = (fixed_pivot(pos, moving=m), m)
    if problems:
        raise ModelError(problems)
    (A0v, A1v), (B0v, B1v) = pivots["A"], pivots["B"]
    return motion_solution(pos, A0v, B0v, A1v, B1v, limit=limit,
                           remedy="choose another B0 or B1 (or A0, A1)")
