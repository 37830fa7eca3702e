"""What acts on a mechanism: gravity, forces and torques, springs, dampers, actuator laws.

The mechanism model stays plain geometry and mass data; loads are a separate, frozen
description passed to :func:`~kinelab.dynamics.inverse` and
:func:`~kinelab.dynamics.simulate`.  Every value may be constant, a Python callable
``f(t, q, qd)``, an arithmetic expression of ``t, q, qd`` (text, parsed safely) or a table
to interpolate; all four become a :class:`Law`.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from kinelab._expressions import OP_CONST, not_finite, parse_expression, parse_table, to_program
from kinelab.dynamics._masses import items_of
from kinelab.errors import ModelError, describe, one_line, shown, shown_key
from kinelab.model import MAX_LENGTH, MAX_RATE, Mechanism, is_real

__all__ = ["Law", "PointForce", "Torque", "Spring", "Damper", "Friction", "TorsionalSpring",
           "TorsionalDamper", "Loads", "STANDARD_GRAVITY"]

STANDARD_GRAVITY = 9.80665   # m/s^2
MAX_COEFFICIENT = 1e30       # a spring's stiffness (N/m) or a damper's damping (N s/m), as the
                             # largest mass (kinelab.model.MAX_MASS): no machine goes beyond, and
                             # its forces stay far from overflow


def _number(v) -> bool:
    return isinstance(v, (int, float, np.floating, np.integer)) and not isinstance(v, bool)


@dataclass(frozen=True, eq=False)
class Law:
    """A scalar quantity as a function of time and state: a force component, a torque,
    an actuator effort.

    Parameters
    ----------
    source : float, str, mapping or callable
        A number (constant); an expression of ``t, q, qd`` (see
        :func:`kinelab.dynamics.parse_expression`); a table ``{"of": "q", "x": [...],
        "y": [...], "period": ...}``; or a Python callable ``f(t, q, qd)`` called once
        with every sample: ``t`` of shape (N,), ``q`` and ``qd`` of shape (N,) for a
        mechanism with one input and (N, M) with more.  It returns shape () or (N,).
    where : str
        Where it comes from, for messages.

    Examples
    --------
    >>> Law("-2 * qd")(np.zeros(2), np.zeros((2, 1)), np.array([[1.0], [3.0]]))
    array([-2., -6.])
    >>> Law(5.0)(np.zeros(3), np.zeros((3, 1)), np.zeros((3, 1)))
    array([5., 5., 5.])
    """

    source: Any
    where: str = "law"

    def __post_init__(self):
        s = self.source
        if isinstance(s, Law):          # keep where it was first read from
            object.__setattr__(self, "source", s.source)
            object.__setattr__(self, "where", s.where)
            s = s.source
        if _number(s):
            if not is_real(s):          # inf, nan, or an integer too large for a float
                raise ModelError(f"{self.where}: expected a finite number, got {describe(s)}")
            fn = None
        elif isinstance(s, str):
            fn = parse_expression(s, where=self.where)
        elif isinstance(s, Mapping):
            fn = parse_table(s, where=self.where)
        elif callable(s):
            fn = None
        else:
            got = describe(s) if s is None or isinstance(s, (Iterable, bool)) else f"a {type(s).__name__}"
            raise ModelError(f"{self.where}: expected a number, an expression (text), a table "
                             f"or a callable f(t, q, qd), got {got}")
        object.__setattr__(self, "_fn", fn)

    @property
    def constant(self) -> bool:
        return _number(self.source)

    def __call__(self, t: np.ndarray, q: np.ndarray, qd: np.ndarray,
                 width: int | None = None) -> np.ndarray:
        """Values at N samples: ``t`` (N,), ``q`` and ``qd`` (N, M); returns (N,), or
        (N, width) for a law giving a vector."""
        n = t.shape[0]
        shape = (n,) if width is None else (n, width)
        if self.constant:
            return np.full(shape, float(self.source))
        if self._fn is not None:
            with np.errstate(all="ignore"):
                out = self._fn(t, q, qd)
        else:
            qa, qda = (q[:, 0], qd[:, 0]) if q.shape[1] == 1 else (q, qd)
            try:
                out = self.source(t, qa, qda)
            except Exception as exc:    # the caller's code: say which law, keep its traceback
                at = f" at t = {float(t[0]):.6g} s" if n else ""
                raise ModelError(f"{self.where}: the callable raised {type(exc).__name__}: "
                                 f"{one_line(exc, 300)}{at}; fix the function or guard its "
                                 "domain") from exc
        return _finite(self.where, out, shape, t, q, qd)

    def program(self, M: int):
        """The law as a program for the compiled dynamics (see
        :func:`kinelab._expressions.to_program`), for a mechanism of M inputs; None for a
        table or a Python callable, which run in Python."""
        if self.constant:
            return np.array([[OP_CONST, 0]], np.int64), np.array([float(self.source)])
        if isinstance(self.source, str):
            return to_program(self.source, M, where=self.where)
        return None

    def to_data(self):
        """The number, text or table this law was given as (for model files)."""
        if callable(self.source) and not isinstance(self.source, (str, Mapping)):
            raise ModelError(f"{self.where}: a Python callable cannot be written to a model "
                             "file; give the law as a number, an expression or a table")
        return dict(self.source) if isinstance(self.source, Mapping) else self.source


def _finite(where: str, out, shape: tuple[int, ...], t, q, qd) -> np.ndarray:
    try:
        a = np.broadcast_to(np.asarray(out, dtype=float), shape)
    except (TypeError, ValueError):
        got = np.shape(out) if not isinstance(out, (str, type(None))) else repr(out)
        raise ModelError(f"{where}: expected values of shape () or {shape}, got {got}") from None
    if not np.all(np.isfinite(a)):
        raise not_finite(where, "the law", a, t=t, q=q, qd=qd)
    return np.array(a)


def _laws(value, where: str, width: int) -> tuple[Law, ...] | Law:
    """A vector quantity: a sequence of ``width`` scalar laws, or one callable giving all."""
    if callable(value) and not isinstance(value, (str, Mapping, Law)):
        return Law(value, where)
    if isinstance(value, (str, Mapping)) or _number(value) or not isinstance(value, Iterable):
        raise ModelError(f"{where}: expected {width} components (fx, fy) or a callable "
                         f"f(t, q, qd) returning shape (2,) or (N, 2), got {describe(value)}")
    parts = tuple(value)
    if len(parts) != width:
        raise ModelError(f"{where}: expected {width} components (fx, fy), got {len(parts)}")
    return tuple(Law(p, f"{where}[{i}]") for i, p in enumerate(parts))


@dataclass(frozen=True, eq=False)
class PointForce:
    """A force applied at a named point, components in the ground frame (N).

    Parameters
    ----------
    point : str
        Where it acts.
    force : (fx, fy) or callable
        Each component a number, an expression, a table or a callable (see :class:`Law`);
        or one callable ``f(t, q, qd)`` returning shape (2,) or (N, 2).
    link : str, optional
        The link it acts on, when the point is carried by several (a joint's point); it
        only matters for the joint reactions.  Default: the first moving link, in model
        order, that carries the point.
    name : str, optional
        A label for results and messages.

    Examples
    --------
    >>> PointForce("B", ("-1000 * (q > 0)", 0.0), link="slider").point
    'B'
    """

    point: str
    force: Any
    link: str | None = None
    name: str | None = None

    def __post_init__(self):
        object.__setattr__(self, "_law", _laws(self.force, f"force at {shown(self.point)}", 2))

    def value(self, t, q, qd) -> np.ndarray:
        """The force at N samples, shape (N, 2)."""
        law = self._law
        if isinstance(law, Law):
            return law(t, q, qd, width=2)
        return np.stack([c(t, q, qd) for c in law], axis=-1)


@dataclass(frozen=True, eq=False)
class Torque:
    """A pure torque on a link (N m, CCW positive).

    Parameters
    ----------
    link : str
        The link it turns.
    torque : number, str, mapping or callable
        See :class:`Law`.
    reacting : str, optional
        A link that takes the opposite torque (a motor between two links, the stator on
        ``reacting``).  Default: none (the torque comes from outside the mechanism).
    name : str, optional
    """

    link: str
    torque: Any
    reacting: str | None = None
    name: str | None = None

    def __post_init__(self):
        object.__setattr__(self, "_law", Law(self.torque, f"torque on {shown(self.link)}"))

    def value(self, t, q, qd) -> np.ndarray:
        return self._law(t, q, qd)


@dataclass(frozen=True)
class Spring:
    """A linear spring between two points: tension ``stiffness * (length - free_length)``.

    Parameters
    ----------
    points : (str, str)
        Its two ends (any points, on the ground or on moving links).
    stiffness : float
        N/m, >= 0.
    free_length : float
        m, >= 0.
    links : (str, str), optional
        The links its ends act on, when a point is carried by several (reactions only).
    name : str, optional
    """

    points: tuple[str, str]
    stiffness: float
    free_length: float = 0.0
    links: tuple[str | None, str | None] = (None, None)
    name: str | None = None

    def __post_init__(self):
        _check_pair(self, "spring")
        for label, unit, most in (("stiffness", "N/m", MAX_COEFFICIENT),
                                  ("free_length", "m", MAX_LENGTH)):
            v = getattr(self, label)
            if not (is_real(v) and 0 <= v <= most):
                raise ModelError(f"{_label(self, 'spring')}: {label}: expected a number >= 0 "
                                 f"({unit}) up to {most:g}, got {describe(v)}")


@dataclass(frozen=True)
class Damper:
    """A linear viscous damper between two points: tension ``damping * d(length)/dt``.

    Parameters
    ----------
    points : (str, str)
    damping : float
        N s/m, >= 0.
    links : (str, str), optional
        As for :class:`Spring`.
    name : str, optional
    """

    points: tuple[str, str]
    damping: float
    links: tuple[str | None, str | None] = (None, None)
    name: str | None = None

    def __post_init__(self):
        _check_pair(self, "damper")
        v = self.damping
        if not (is_real(v) and 0 <= v <= MAX_COEFFICIENT):
            raise ModelError(f"{_label(self, 'damper')}: damping: expected a number >= 0 (N s/m) "
                             f"up to {MAX_COEFFICIENT:g}, got {describe(v)}")


@dataclass(frozen=True)
class Friction:
    """Coulomb friction in a revolute or prismatic joint: a torque (R, N m) or a force along
    the slide (P, N) of constant size opposing the joint's relative motion.

    The sign of the relative rate w (the second link's angular velocity relative to the
    first, or the slide's rate) is regularised near zero: the friction on the second link
    is ``-magnitude * tanh(w / smoothing)``, within 0.01 % of the full magnitude beyond
    five times ``smoothing``, smooth (so the equations of motion stay integrable) and zero
    at rest, where true Coulomb friction would stick.  Its power ``magnitude * w *
    tanh(w / smoothing)`` is never negative: it is counted in ``dissipation``.

    Parameters
    ----------
    joint : str
        A revolute (R) or prismatic (P) joint of the model.
    magnitude : float
        N m for a revolute joint, N for a prismatic one, >= 0.
    smoothing : float
        The speed (rad/s or m/s) below which the sign is regularised, > 0 (default 1e-3).
    name : str, optional

    Examples
    --------
    >>> Friction("jO2", 0.5).smoothing
    0.001
    """

    joint: str
    magnitude: float
    smoothing: float = 1e-3
    name: str | None = None

    def __post_init__(self):
        where = f"friction {shown(self.name or self.joint)}"
        if not isinstance(self.joint, str):
            raise ModelError(f"friction: joint: expected a joint name, got {describe(self.joint)}")
        if not (is_real(self.magnitude) and 0 <= self.magnitude <= MAX_COEFFICIENT):
            raise ModelError(f"{where}: magnitude: expected a number >= 0 (N m for an R joint, N "
                             f"for a P joint) up to {MAX_COEFFICIENT:g}, got {describe(self.magnitude)}")
        if not (is_real(self.smoothing) and 0 < self.smoothing <= MAX_RATE):
            raise ModelError(f"{where}: smoothing: expected a speed > 0 (rad/s or m/s) up to "
                             f"{MAX_RATE:g}, got {describe(self.smoothing)}")


def _check_links(item, kind: str) -> str:
    links = item.links
    if isinstance(links, list):
        links = tuple(links)
        object.__setattr__(item, "links", links)
    where = f"{kind} {shown(item.name)}" if item.name else kind
    if not (isinstance(links, tuple) and len(links) == 2 and all(isinstance(n, str) for n in links)):
        raise ModelError(f"{where}: links: expected two link names, got {describe(links)}")
    if links[0] == links[1]:
        raise ModelError(f"{where}: links: its two ends are the same link {shown(links[0])}; a "
                         f"{kind} joins two different links")
    return f"{kind} {shown(item.name)}" if item.name else f"{kind} {'-'.join(map(shown_key, links))}"


@dataclass(frozen=True)
class TorsionalSpring:
    """A torsional spring between two links: the torque on the second link is
    ``-(stiffness * (phi - free_angle) + preload)``, the first taking the opposite, with
    ``phi = theta_b - theta_a`` the second link's angle relative to the first.

    ``phi - free_angle`` is taken within half a turn (a spring that winds less than half a
    turn either way of its free angle).  Its potential energy is
    ``stiffness * (phi - free_angle)**2 / 2 + preload * (phi - free_angle)``.

    Parameters
    ----------
    links : (str, str)
        The two links (either may be the ground).
    stiffness : float
        N m/rad, >= 0.
    free_angle : float
        rad: the relative angle at which the spring gives only its preload (default 0).
    preload : float
        N m, the torque it pushes the second link back with at its free angle (default 0).
    name : str, optional
    """

    links: tuple[str, str]
    stiffness: float
    free_angle: float = 0.0
    preload: float = 0.0
    name: str | None = None

    def __post_init__(self):
        where = _check_links(self, "torsional spring")
        for label, unit, low in (("stiffness", "N m/rad", 0.0), ("free_angle", "rad", None),
                                 ("preload", "N m", None)):
            v = getattr(self, label)
            if not (is_real(v) and abs(float(v)) <= MAX_COEFFICIENT and (low is None or v >= low)):
                raise ModelError(f"{where}: {label}: expected a number{' >= 0' if low is not None else ''} "
                                 f"({unit}) up to {MAX_COEFFICIENT:g} in size, got {describe(v)}")


@dataclass(frozen=True)
class TorsionalDamper:
    """A torsional viscous damper between two links: the torque on the second link is
    ``-damping * phi'``, ``phi'`` its angular velocity relative to the first (which takes
    the opposite torque).

    Parameters
    ----------
    links : (str, str)
    damping : float
        N m s/rad, >= 0.
    name : str, optional
    """

    links: tuple[str, str]
    damping: float
    name: str | None = None

    def __post_init__(self):
        where = _check_links(self, "torsional damper")
        v = self.damping
        if not (is_real(v) and 0 <= v <= MAX_COEFFICIENT):
            raise ModelError(f"{where}: damping: expected a number >= 0 (N m s/rad) up to "
                             f"{MAX_COEFFICIENT:g}, got {describe(v)}")


def _label(item, kind: str) -> str:
    return f"{kind} {shown(item.name)}" if item.name else f"{kind} {'-'.join(map(shown_key, item.points))}"


def _check_pair(item, kind: str) -> None:
    pts = tuple(item.points) if isinstance(item.points, (list, tuple)) else item.points
    object.__setattr__(item, "points", pts)
    object.__setattr__(item, "links", tuple(item.links))
    if not (isinstance(pts, tuple) and len(pts) == 2 and all(isinstance(p, str) for p in pts)):
        raise ModelError(f"{kind}: points: expected two point names, got {describe(pts)}")
    if pts[0] == pts[1]:
        raise ModelError(f"{_label(item, kind)}: points: its two ends are the same point "
                         f"{shown(pts[0])}; a {kind} joins two different points")
    if len(item.links) != 2:
        raise ModelError(f"{_label(item, kind)}: links: expected two entries (or None), got "
                         f"{describe(item.links)}")


@dataclass(frozen=True, eq=False)
class Loads:
    """Everything applied to a mechanism besides its actuators' efforts.

    Parameters
    ----------
    gravity : (float, float)
        Acceleration of gravity in the ground frame, m/s^2; default none.  Use
        ``(0.0, -kinelab.dynamics.STANDARD_GRAVITY)`` for +y up.
    forces : sequence of PointForce
    torques : sequence of Torque
    springs : sequence of Spring
    dampers : sequence of Damper
    friction : sequence of Friction
        Coulomb friction in revolute and prismatic joints.
    torsional_springs : sequence of TorsionalSpring
    torsional_dampers : sequence of TorsionalDamper

    Examples
    --------
    >>> from kinelab.dynamics import Loads, PointForce, Spring
    >>> loads = Loads(gravity=(0.0, -9.81), forces=[PointForce("B", (-100.0, 0.0))],
    ...               springs=[Spring(("O2", "A"), stiffness=50.0, free_length=0.5)])
    >>> len(loads.forces), loads.gravity
    (1, (0.0, -9.81))
    """

    gravity: tuple[float, float] = (0.0, 0.0)
    forces: tuple[PointForce, ...] = ()
    torques: tuple[Torque, ...] = ()
    springs: tuple[Spring, ...] = ()
    dampers: tuple[Damper, ...] = ()
    friction: tuple[Friction, ...] = ()
    torsional_springs: tuple[TorsionalSpring, ...] = ()
    torsional_dampers: tuple[TorsionalDamper, ...] = ()

    def __post_init__(self):
        g = self.gravity
        if (isinstance(g, (str, bytes)) or not isinstance(g, Iterable) or len(tuple(g)) != 2
                or not all(is_real(c) for c in g)):
            raise ModelError(f"gravity: expected two finite numbers (gx, gy) in m/s^2, got {describe(g)}")
        if max(abs(float(c)) for c in g) > MAX_RATE:
            raise ModelError(f"gravity: expected components at most {MAX_RATE:g} m/s^2 in size "
                             f"(forces take it times the masses), got {describe(tuple(g))}")
        object.__setattr__(self, "gravity", tuple(float(c) for c in g))
        for attr, kind in (("forces", PointForce), ("torques", Torque), ("springs", Spring),
                           ("dampers", Damper), ("friction", Friction),
                           ("torsional_springs", TorsionalSpring),
                           ("torsional_dampers", TorsionalDamper)):
            object.__setattr__(self, attr, items_of(getattr(self, attr), attr, kind))

    @property
    def pair_loads(self) -> bool:
        """True when there is friction or a torsional spring or damper (loads the compiled
        kernel does not take)."""
        return bool(self.friction or self.torsional_springs or self.torsional_dampers)

    def problems(self, model: Mechanism) -> list[str]:
        """Every reference to a point or link that the model does not have."""
        out: list[str] = []
        points, links = set(model.point_names), set(model.link_names)

        def point(p, where):
            if p not in points:
                out.append(f"{where}: point: expected a point of '{model.name}', got {shown(p)}; "
                           f"its points are {', '.join(map(repr, model.point_names))}")
                return False
            return True

        def link(n, where, carrying=None):
            if n is None:
                return
            if n not in links:
                out.append(f"{where}: link: expected a link of '{model.name}', got {shown(n)}; "
                           f"its links are {', '.join(map(repr, model.link_names))}")
            elif carrying is not None and carrying not in model.link(n).points:
                out.append(f"{where}: link {shown(n)} does not carry point {shown(carrying)}; name a link "
                           f"that does ({', '.join(map(repr, model.links_carrying(carrying)))})")
        for i, f in enumerate(self.forces):
            where = f"forces[{i}]" + (f" {shown(f.name)}" if f.name else "")
            if point(f.point, where):
                link(f.link, where, f.point)
        for i, tq in enumerate(self.torques):
            where = f"torques[{i}]" + (f" {shown(tq.name)}" if tq.name else "")
            link(tq.link, where)
            link(tq.reacting, where + ".reacting")
        for kind, items in (("springs", self.springs), ("dampers", self.dampers)):
            for i, s in enumerate(items):
                where = f"{kind}[{i}]" + (f" {shown(s.name)}" if s.name else "")
                for p, n in zip(s.points, s.links):
                    if point(p, where):
                        link(n, where, p)
        for i, f in enumerate(self.friction):
            where = f"friction[{i}]" + (f" {shown(f.name)}" if f.name else "")
            if f.joint not in model.joint_names:
                out.append(f"{where}: joint: expected a joint of '{model.name}', got {shown(f.joint)}; "
                           f"its joints are {', '.join(map(repr, model.joint_names))}")
            elif model.joint(f.joint).type not in ("R", "P"):
                out.append(f"{where}: joint {shown(f.joint)} is a {model.joint(f.joint).type} joint; "
                           "friction acts in a revolute (R) or prismatic (P) joint")
        for kind, items in (("torsional_springs", self.torsional_springs),
                            ("torsional_dampers", self.torsional_dampers)):
            for i, s in enumerate(items):
                where = f"{kind}[{i}]" + (f" {shown(s.name)}" if s.name else "")
                for n in s.links:
                    link(n, where)
        return out

    # -- plain data (the [dynamics] section of a model file) ------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Plain data: numbers, expressions and tables (a Python callable cannot be written)."""
        out: dict[str, Any] = {}
        if any(self.gravity):
            out["gravity"] = list(self.gravity)
        if self.forces:
            out["forces"] = [_clean({"name": f.name, "point": f.point, "link": f.link,
                                     "fx": _data(f, 0), "fy": _data(f, 1)}) for f in self.forces]
        if self.torques:
            out["torques"] = [_clean({"name": t.name, "link": t.link, "reacting": t.reacting,
                                      "torque": t._law.to_data()}) for t in self.torques]
        if self.springs:
            out["springs"] = [_clean({"name": s.name, "points": list(s.points),
                                      "stiffness": s.stiffness, "free_length": s.free_length,
                                      "links": _links(s)}) for s in self.springs]
        if self.dampers:
            out["dampers"] = [_clean({"name": d.name, "points": list(d.points),
                                      "damping": d.damping, "links": _links(d)}) for d in self.dampers]
        if self.friction:
            out["friction"] = [_clean({"name": f.name, "joint": f.joint, "magnitude": f.magnitude,
                                       "smoothing": f.smoothing}) for f in self.friction]
        if self.torsional_springs:
            out["torsional_springs"] = [_clean({"name": s.name, "links": list(s.links),
                                                "stiffness": s.stiffness, "free_angle": s.free_angle,
                                                "preload": s.preload}) for s in self.torsional_springs]
        if self.torsional_dampers:
            out["torsional_dampers"] = [_clean({"name": d.name, "links": list(d.links),
                                                "damping": d.damping}) for d in self.torsional_dampers]
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], *, where: str = "dynamics") -> Loads:
        """Loads from plain data (see ``docs/dynamics.md``); every problem is reported at once."""
        problems: list[str] = []
        known = {"gravity", "forces", "torques", "springs", "dampers", "friction",
                 "torsional_springs", "torsional_dampers"}

        def each(key, build, allowed):
            items = []
            raw = data.get(key, [])
            if not isinstance(raw, (list, tuple)):
                problems.append(f"{where}.{key}: expected a list of tables, got {describe(raw)}")
                return ()
            for i, d in enumerate(raw):
                w = f"{where}.{key}[{i}]"
                if not isinstance(d, Mapping):
                    problems.append(f"{w}: expected a table, got {describe(d)}")
                    continue
                extra = set(d) - allowed
                if extra:
                    problems.append(f"{w}: unknown key(s) {', '.join(sorted(map(repr, extra)))}; "
                                    f"expected some of {', '.join(sorted(map(repr, allowed)))}")
                    continue
                try:
                    items.append(build(d, w))
                except ModelError as exc:
                    problems.extend(exc.problems)
                except (KeyError, TypeError) as exc:
                    problems.append(f"{w}: missing or malformed {exc}")
            return tuple(items)

        def force(d, w):
            return PointForce(d["point"], (_rename(d.get("fx", 0.0), f"{w}.fx"),
                                           _rename(d.get("fy", 0.0), f"{w}.fy")),
                              link=d.get("link"), name=d.get("name"))

        def torque(d, w):
            return Torque(d["link"], _rename(d["torque"], f"{w}.torque"),
                          reacting=d.get("reacting"), name=d.get("name"))

        def spring(d, w):
            return Spring(tuple(d["points"]), d["stiffness"], d.get("free_length", 0.0),
                          links=tuple(d.get("links", (None, None))), name=d.get("name"))

        def damper(d, w):
            return Damper(tuple(d["points"]), d["damping"],
                          links=tuple(d.get("links", (None, None))), name=d.get("name"))

        def friction(d, w):
            return Friction(d["joint"], d["magnitude"], d.get("smoothing", 1e-3), name=d.get("name"))

        def torsional_spring(d, w):
            return TorsionalSpring(tuple(d["links"]), d["stiffness"], d.get("free_angle", 0.0),
                                   d.get("preload", 0.0), name=d.get("name"))

        def torsional_damper(d, w):
            return TorsionalDamper(tuple(d["links"]), d["damping"], name=d.get("name"))

        unknown = set(data) - known
        if unknown:
            problems.append(f"{where}: unknown key(s) {', '.join(sorted(map(repr, unknown)))}")
        forces = each("forces", force, {"name", "point", "link", "fx", "fy"})
        torques = each("torques", torque, {"name", "link", "reacting", "torque"})
        springs = each("springs", spring, {"name", "points", "stiffness", "free_length", "links"})
        dampers = each("dampers", damper, {"name", "points", "damping", "links"})
        frictions = each("friction", friction, {"name", "joint", "magnitude", "smoothing"})
        tsprings = each("torsional_springs", torsional_spring,
                        {"name", "links", "stiffness", "free_angle", "preload"})
        tdampers = each("torsional_dampers", torsional_damper, {"name", "links", "damping"})
        try:
            loads = cls(gravity=data.get("gravity", (0.0, 0.0)), forces=forces, torques=torques,
                        springs=springs, dampers=dampers, friction=frictions,
                        torsional_springs=tsprings, torsional_dampers=tdampers)
        except ModelError as exc:
            problems.extend(f"{where}.{p}" for p in exc.problems)
            loads = None
        if problems:
            raise ModelError(problems)
        return loads

    def __repr__(self) -> str:
        parts = [f"gravity={self.gravity}"] + [f"{len(getattr(self, a))} {a}" for a in
                                               ("forces", "torques", "springs", "dampers",
                                                "friction", "torsional_springs",
                                                "torsional_dampers")
                                               if getattr(self, a)]
        return f"Loads({', '.join(parts)})"


def _rename(source, where):
    return Law(source, where)


def _data(f: PointForce, i: int):
    if isinstance(f._law, Law):
        raise ModelError(f"{f._law.where}: a Python callable cannot be written to a model file")
    return f._law[i].to_data()


def _links(item) -> list | None:
    return None if item.links == (None, None) else list(item.links)


def _clean(d: dict) -> dict:
    return {k: v for k, v in d.items() if v is not None}


def default_carrier(model: Mechanism, point: str, link: str | None = None) -> str:
    """The link a load at ``point`` acts on: ``link`` if given, else the first moving link
    carrying the point (the ground when no moving link carries it)."""
    if link is not None:
        return link
    carriers = model.links_carrying(point)
    ground = model.ground.name
    moving = [n for n in carriers if n != ground]
    return moving[0] if moving else ground

