"""A cam's motion program: segments of rise, dwell and return over one turn, their SVAJ
(displacement and its first three derivatives with respect to the cam angle) and the check of
continuity at every joint of the program."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from kinelab.cams._laws import (LAWS, law_pieces, law_values, polynomial_coefficients,
                                polynomial_values)
from kinelab.errors import ModelError, describe, expected_one_of
from kinelab.model._cams import MAX_DEGREE, PIECE_HEAD, PIECE_WIDTH

__all__ = ["Segment", "MotionProgram", "SVAJ", "Discontinuity", "KINDS", "LAW_NAMES", "motion"]

TURN = 2 * math.pi
KINDS = ("rise", "dwell", "return")
LAW_NAMES = (*LAWS, "polynomial")
ANGLE_TOL = 1e-9        # rad: segments meet when their ends are this close
JUMP_TOL = 1e-9         # relative to the program's lift / beta**order: a joint's jump
QUANTITIES = ("S", "V", "A")


@dataclass(frozen=True)
class Segment:
    """One segment of a motion program.

    Parameters
    ----------
    kind : {'rise', 'dwell', 'return'}
    start, end : float
        Cam angles where it begins and ends, rad, ``0 <= start < end <= 2 pi``.
    lift : float
        The follower's travel over a rise or a return, above 0 (length, or rad for an
        oscillating follower); 0 for a dwell.
    law : str
        One of :data:`LAW_NAMES` (a dwell has none: '').  ``'polynomial'`` takes
        ``conditions`` instead of ``lift``.
    conditions : tuple of (float, int, float)
        For ``law='polynomial'``: (cam angle, order, value), order 0, 1, 2, 3 for S, V, A, J
        (per rad), at the segment's ends or inside it; the polynomial's degree is their
        number less one, and S is absolute (not from the previous segment's end).
    """
    kind: str
    start: float
    end: float
    lift: float = 0.0
    law: str = ""
    conditions: tuple = ()

    def problems(self, where: str = "segment") -> list[str]:
        out = []
        if self.kind not in KINDS:
            out.append(f"{where}.kind: {expected_one_of(self.kind, KINDS)}")
        if self.kind != "dwell" and self.law not in LAW_NAMES:
            out.append(f"{where}.law: {expected_one_of(self.law, LAW_NAMES)}")
        for name in ("start", "end", "lift"):
            v = getattr(self, name)
            if not isinstance(v, (int, float)) or not math.isfinite(v):
                out.append(f"{where}.{name}: expected a finite number, got {describe(v)}")
        if out:
            return out
        if not self.end > self.start:
            out.append(f"{where}: expected its end after its start, got from "
                       f"{math.degrees(self.start):.6g} deg to {math.degrees(self.end):.6g} deg")
        if self.kind in ("rise", "return") and self.law != "polynomial" and not self.lift > 0:
            out.append(f"{where}.lift: expected the {self.kind}'s travel, above 0, got "
                       f"{self.lift:.6g}; a segment without travel is a dwell")
        if self.law == "polynomial" and self.kind != "dwell" and not self.conditions:
            out.append(f"{where}: a polynomial law needs boundary conditions (S, V, A at "
                       "its ends)")
        return out

    @property
    def beta(self) -> float:
        return self.end - self.start


@dataclass(frozen=True)
class Discontinuity:
    """A jump of S, V or A where two segments of a program meet.

    ``angle`` is the joint's cam angle (rad), ``before`` and ``after`` the values of the
    quantity at the end of the segment ``left`` and the start of ``right`` (indices of
    :attr:`MotionProgram.segments`); ``error`` is True for a jump of S or V."""
    angle: float
    quantity: str
    before: float
    after: float
    left: int
    right: int

    @property
    def jump(self) -> float:
        return self.after - self.before

    @property
    def error(self) -> bool:
        return self.quantity in ("S", "V")

    def __str__(self) -> str:
        law = " (the fundamental law of cam design: an infinite jerk)" if self.quantity == "A" else ""
        return (f"{self.quantity} jumps by {self.jump:.6g} at {math.degrees(self.angle):.6g} deg, "
                f"between segments {self.left + 1} and {self.right + 1}{law}")


@dataclass(frozen=True)
class SVAJ:
    """Displacement and its first three derivatives with respect to the cam angle.

    Attributes
    ----------
    theta : (N,) cam angle, rad
    S, V, A, J : (N,) arrays
        S in the lift's unit (m, or rad for an oscillating follower), V = dS/dtheta per rad,
        A per rad**2, J per rad**3; also as ``s, v, a, j``.
    program : MotionProgram or None
        The program they are of (what :func:`~kinelab.cams.profile` takes in their place).
    """
    theta: np.ndarray
    S: np.ndarray
    V: np.ndarray
    A: np.ndarray
    J: np.ndarray
    program: MotionProgram | None = field(default=None, repr=False, compare=False)

    s = property(lambda self: self.S, doc="S, the displacement.")
    v = property(lambda self: self.V, doc="V = dS/dtheta.")
    a = property(lambda self: self.A, doc="A = d2S/dtheta2.")
    j = property(lambda self: self.J, doc="J = d3S/dtheta3.")

    def in_time(self, omega: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``s, v, a, j`` per time at the cam speed ``omega`` (rad/s, constant):
        ``S, V omega, A omega**2, J omega**3``."""
        return self.S, self.V * omega, self.A * omega ** 2, self.J * omega ** 3


@dataclass(frozen=True)
class MotionProgram:
    """The segments of one turn of the cam, in order, from 0 to 2 pi without gap or overlap.

    Parameters
    ----------
    segments : sequence of Segment
    start : float, optional
        S at the start of the first segment; by default the lowest level of the rises,
        dwells and returns is S = 0 (with polynomial segments, 0).
    allow_discontinuous : bool
        Accept jumps of S or V at joints (reported in :attr:`discontinuities` all the same);
        by default they are refused.

    Raises
    ------
    ModelError
        Every problem at once: a bad segment, a gap or an overlap between segments, a turn not
        covered, a jump of S or V (unless allowed).

    Examples
    --------
    >>> from kinelab.cams import MotionProgram, Segment
    >>> d = np.radians
    >>> p = MotionProgram([Segment("rise", 0, d(90), 0.025, "cycloidal"),
    ...                    Segment("dwell", d(90), d(180)),
    ...                    Segment("return", d(180), d(270), 0.025, "harmonic"),
    ...                    Segment("dwell", d(270), d(360))])
    >>> for j in p.discontinuities:      # harmonic: A = -h pi**2 / (2 beta**2) at its ends
    ...     print(j.quantity, round(j.jump, 9), round(np.degrees(j.angle)), j.error)
    A -0.05 180 False
    A -0.05 270 False
    >>> p.svaj(d([45, 135])).S
    array([0.0125, 0.025 ])
    """
    segments: tuple
    start: float | None = None
    allow_discontinuous: bool = False
    levels: tuple = field(init=False, repr=False, compare=False)   # S at each segment's start
    coefficients: tuple = field(init=False, repr=False, compare=False)  # polynomial segments' c

    def __post_init__(self):
        segs = tuple(self.segments)
        object.__setattr__(self, "segments", segs)
        problems = []
        if not segs:
            raise ModelError("segments: expected at least one segment covering 0 to 360 deg")
        for i, s in enumerate(segs):
            if not isinstance(s, Segment):
                problems.append(f"segments[{i}]: expected a Segment, got {describe(s)}")
            else:
                problems += s.problems(f"segments[{i}]")
        if problems:
            raise ModelError(problems)
        problems += _coverage(segs)
        if problems:
            raise ModelError(problems)
        coefs = []
        for i, s in enumerate(segs):
            if s.law == "polynomial" and s.kind != "dwell":
                conds = [((t - s.start) / s.beta, o, v) for t, o, v in s.conditions]
                try:
                    coefs.append(polynomial_coefficients(conds, s.beta))
                except ModelError as exc:
                    raise ModelError(f"segments[{i}]: {exc.problems[0]}") from None
            else:
                coefs.append(None)
        object.__setattr__(self, "coefficients", tuple(coefs))
        object.__setattr__(self, "levels", self._levels())
        if not self.allow_discontinuous:
            bad = [str(d) for d in self.discontinuities if d.error]
            if bad:
                raise ModelError([f"segments: {b}; make the segments meet (a rise's lift equal "
                                  "to the return's), or allow_discontinuous" for b in bad])

    def _levels(self) -> tuple:
        level, out = 0.0 if self.start is None else float(self.start), []
        for s, c in zip(self.segments, self.coefficients):
            if c is not None:
                out.append(float(c[0]))
                level = float(np.polynomial.Polynomial(c)(1.0))
                continue
            out.append(level)
            level += {"rise": s.lift, "return": -s.lift, "dwell": 0.0}[s.kind]
        if self.start is None and all(c is None for c in self.coefficients):
            low = min(min(out), level)
            out = [v - low for v in out]
        return tuple(out)

    @property
    def lift(self) -> float:
        """The largest travel of any segment (the program's scale)."""
        ends = [self._segment_values(i, np.array([0.0, 1.0]))[0] for i in range(len(self.segments))]
        values = np.concatenate(ends)
        return float(values.max() - values.min()) or 1.0

    def _segment_values(self, i: int, x: np.ndarray):
        """S, V, A, J of segment ``i`` at its normalised abscissae ``x`` (per rad)."""
        s, c, b = self.segments[i], self.coefficients[i], self.segments[i].beta
        if c is not None:
            f = polynomial_values(c, x)
            return f[0], f[1] / b, f[2] / b ** 2, f[3] / b ** 3
        if s.kind == "dwell":
            z = np.zeros_like(x)
            return z + self.levels[i], z, z, z
        h = s.lift if s.kind == "rise" else -s.lift
        f = law_values(s.law, x)
        return self.levels[i] + h * f[0], h * f[1] / b, h * f[2] / b ** 2, h * f[3] / b ** 3

    @property
    def discontinuities(self) -> tuple[Discontinuity, ...]:
        """Every jump of S, V or A at a joint of the program, 360 deg to 0 included."""
        n = len(self.segments)
        betas = [s.beta for s in self.segments]
        out = []
        for i in range(n):
            j = (i + 1) % n
            left = self._segment_values(i, np.array([1.0]))
            right = self._segment_values(j, np.array([0.0]))
            for k, q in enumerate(QUANTITIES):
                a, b = float(left[k][0]), float(right[k][0])
                tol = JUMP_TOL * self.lift / min(betas[i], betas[j]) ** k
                if abs(b - a) > tol:
                    out.append(Discontinuity(self.segments[i].end % TURN, q, a, b, i, j))
        return tuple(out)

    def scaled(self, factor: float) -> MotionProgram:
        """The program with every displacement (lifts, polynomial conditions, ``start``)
        multiplied by ``factor``: the same motion for a follower drawn ``factor`` times as
        large."""
        segs = [Segment(s.kind, s.start, s.end, s.lift * factor, s.law,
                        tuple((x, o, v * factor) for x, o, v in s.conditions))
                for s in self.segments]
        return MotionProgram(segs, None if self.start is None else self.start * factor,
                             self.allow_discontinuous)

    def to_dict(self) -> dict:
        """Plain data (SI: rad, and m or rad), the inverse of :meth:`from_dict`."""
        segs = []
        for s in self.segments:
            d = {"kind": s.kind, "start": s.start, "end": s.end}
            if s.kind != "dwell":
                d["law"] = s.law
                if s.law == "polynomial":
                    d["conditions"] = [list(c) for c in s.conditions]
                else:
                    d["lift"] = s.lift
            segs.append(d)
        out = {"segments": segs}
        if self.start is not None:
            out["start"] = self.start
        if self.allow_discontinuous:
            out["allow_discontinuous"] = True
        return out

    @classmethod
    def from_dict(cls, data) -> MotionProgram:
        """A program from plain data (the output of :meth:`to_dict`)."""
        try:
            segs = [Segment(d["kind"], d["start"], d["end"], d.get("lift", 0.0), d.get("law", ""),
                            tuple(tuple(c) for c in d.get("conditions", ())))
                    for d in data["segments"]]
        except (KeyError, TypeError, AttributeError) as exc:
            raise ModelError(f"segments: malformed program data: {describe(str(exc))}") from None
        return cls(segs, data.get("start"), bool(data.get("allow_discontinuous", False)))

    def pieces(self) -> np.ndarray:
        """The program as a table of pieces, one row each (``kinelab.model._cams``): where the
        piece starts, its segment's start and width, its ``x0``, the segment's level and
        height, ``B, k, phase`` and the polynomial's coefficients, so that on the piece
        ``S = level + h (sum(c_i (x - x0)**i) + B sin(k x + phase))``, ``x`` the segment's
        normalised angle.  The planar engine's cam joints (``C``) evaluate this table.

        Raises
        ------
        ModelError
            A polynomial segment of degree above 14.
        """
        rows = []
        for i, (s, c) in enumerate(zip(self.segments, self.coefficients)):
            if c is not None:
                if len(c) - 1 > MAX_DEGREE:
                    raise ModelError(f"segments[{i}]: a polynomial of degree {len(c) - 1} is more "
                                     f"than a cam joint takes ({MAX_DEGREE}); give fewer "
                                     "boundary conditions")
                parts, level, h = [(0.0, tuple(c), 0.0, 0.0, 0.0)], 0.0, 1.0
            elif s.kind == "dwell":
                parts, level, h = [(0.0, (0.0,), 0.0, 0.0, 0.0)], self.levels[i], 0.0
            else:
                parts = law_pieces(s.law)
                level, h = self.levels[i], (s.lift if s.kind == "rise" else -s.lift)
            for x0, coef, B, k, phase in parts:
                row = np.zeros(PIECE_WIDTH)
                row[:PIECE_HEAD] = (s.start + x0 * s.beta, s.start, s.beta, x0, level, h, B, k,
                                    phase)
                row[PIECE_HEAD:PIECE_HEAD + len(coef)] = coef
                rows.append(row)
        return np.array(rows)

    def svaj(self, theta=None, *, samples: int = 721) -> SVAJ:
        """S, V, A, J at the cam angles ``theta`` (rad, any shape; taken modulo a turn), by
        default ``samples`` angles from 0 to 2 pi included.  A sample at a joint takes the
        values of the segment that starts there."""
        if theta is None:
            theta = np.linspace(0.0, TURN, samples)
        theta = np.asarray(theta, dtype=float)
        if not np.all(np.isfinite(theta)):
            raise ModelError("theta: expected finite cam angles, got NaN or infinity")
        t = np.mod(theta, TURN)
        starts = np.array([s.start for s in self.segments])
        idx = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(starts) - 1)
        out = [np.zeros_like(t) for _ in range(4)]
        for i, s in enumerate(self.segments):      # over the segments, not the samples
            m = idx == i
            if m.any():
                vals = self._segment_values(i, (t[m] - s.start) / s.beta)
                for o, v in zip(out, vals):
                    o[m] = v
        return SVAJ(theta, *out, program=self)


def _coverage(segs) -> list[str]:
    """Gaps and overlaps: the segments in order from 0 to 2 pi."""
    out = []
    if abs(segs[0].start) > ANGLE_TOL:
        out.append(f"segments[0]: expected to start at 0 deg, got {math.degrees(segs[0].start):.6g} "
                   "deg; the segments cover one turn, 0 to 360 deg, in order")
    for i in range(len(segs) - 1):
        a, b = segs[i].end, segs[i + 1].start
        if b - a > ANGLE_TOL:
            out.append(f"segments[{i + 1}]: a gap from {math.degrees(a):.6g} deg to "
                       f"{math.degrees(b):.6g} deg after segments[{i}]; start it where the last "
                       "ends, or add a dwell")
        elif a - b > ANGLE_TOL:
            out.append(f"segments[{i + 1}]: overlaps segments[{i}] from {math.degrees(b):.6g} deg "
                       f"to {math.degrees(a):.6g} deg; start it where the last ends")
    if abs(segs[-1].end - TURN) > ANGLE_TOL:
        out.append(f"segments[{len(segs) - 1}]: expected to end at 360 deg, got "
                   f"{math.degrees(segs[-1].end):.6g} deg; the segments cover one turn")
    return out


def motion(program, theta=None, *, samples: int = 721) -> SVAJ:
    """The follower's motion over the cam angle: S, V, A, J (also ``s, v, a, j``) of a
    program, with the program itself (``.program``), ready for :func:`~kinelab.cams.profile`.

    Parameters
    ----------
    program : MotionProgram, sequence of Segment, or sequence of tables
        The program, or its segments in order over one turn: :class:`Segment` objects, or
        tables as a cam task's ``[[segments]]`` (kind, law, from, to, lift; start and end for
        a polynomial), in SI units (rad, m; rad for an oscillating follower's lift).
    theta : array_like, optional
        Cam angles, rad; by default ``samples`` angles from 0 to 2 pi included.

    Examples
    --------
    >>> d = np.radians
    >>> m = kl.cams.motion([{"kind": "rise", "law": "cycloidal", "from": 0, "to": d(90), "lift": 0.025},
    ...                     {"kind": "dwell", "from": d(90), "to": d(180)},
    ...                     {"kind": "return", "law": "3-4-5", "from": d(180), "to": d(270), "lift": 0.025},
    ...                     {"kind": "dwell", "from": d(270), "to": d(360)}], d([45, 135]))
    >>> m.s, m.v.round(12)            # half the rise at its middle, at its peak speed 2 h / beta
    (array([0.0125, 0.025 ]), array([0.03183099, 0.        ]))
    """
    if not isinstance(program, MotionProgram):
        if isinstance(program, (str, bytes)) or not hasattr(program, "__iter__"):
            raise ModelError(f"program: expected a MotionProgram or its segments over one turn, "
                             f"got {describe(program)}")
        segments = list(program)
        if segments and all(isinstance(x, dict) for x in segments):
            from kinelab.cams._task import read_segments     # (it reads this module's Segment)
            problems: list[str] = []
            segments = read_segments(segments, 1.0, 1.0, problems, "program")
            if problems:
                raise ModelError(problems)
        elif not segments or not all(isinstance(x, Segment) for x in segments):
            raise ModelError(f"program: expected Segment objects or [[segments]] tables, got "
                             f"{describe(program)}")
        program = MotionProgram(tuple(segments))
    return program.svaj(theta, samples=samples)
