"""Families of mechanisms: one topology, its dimensions as named parameters.

A family is either a catalogue constructor (``"fourbar"``, ``"slider_crank"`` ...: the
design columns are its numeric arguments) or a model file (its ``[catalogue]`` table when it
has one, else the sketch coordinates of its points, ``"B.x"``, ``"B.y"``, and its links'
masses and moments of inertia, ``"crank.mass"``, ``"crank.inertia"``, as parameters).
"""
from __future__ import annotations

import dataclasses
import inspect
import math
import types
import typing
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from kinelab import mechanisms
from kinelab.errors import KinelabError, ModelError, check_choice, describe, expected_one_of
from kinelab.kinematics import SketchNotAssembled, analyze, analyze_designs, plan
from kinelab.model import MAX_INERTIA, MAX_LENGTH, MAX_MASS, Mechanism, Point
from kinelab.mechanisms._catalogue import NeverAssembles
from kinelab.sweep._batch import Batch, DesignsBatch

__all__ = ["Family", "Designs", "family", "CATALOGUE", "DesignOffModel"]

CATALOGUE = ("fourbar", "slider_crank", "inverted_slider_crank", "slotted_link", "whitworth",
             "fivebar", "watt6", "stephenson6", "triad6")

# What the metrics look at, per catalogue kind: the output whose swing and time ratio are
# measured, the two links whose angle is the transmission angle, the coupler point.
_ROLES = {"fourbar": ("rocker", ("coupler", "rocker"), "P"),
          "slider_crank": ("slide", None, None),
          "inverted_slider_crank": ("rocker", None, None),
          "slotted_link": ("lever", None, None),
          "whitworth": ("ram_slide", None, None)}

_SLIDE_OUTPUTS = ("slide", "ram_slide")

# The four-bar's coupler point is one constructor argument, (along, perpendicular): two columns.
_POINT_COLUMNS = ("coupler_point_along", "coupler_point_perpendicular")
# A model's link with mass data has its mass and moment of inertia as columns, in these units.
_MASS_DATA = {"mass": "kg", "inertia": "kg m^2"}


def _real(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)


@dataclasses.dataclass(frozen=True, eq=False)
class Family:
    """Mechanisms of one topology told apart by named parameters (lengths in m, angles in rad).

    Build one with :func:`family`.

    Attributes
    ----------
    name : str
    parameters : tuple of str
        The design columns it takes.
    defaults : dict
        Parameters a design table may leave out, with the value they take.
    lengths : tuple of str
        Parameters that must be positive lengths.
    output : str or None
        Link or prismatic joint whose swing and time ratio are measured.
    transmission : (str, str) or None
        The links between which the transmission angle is measured.
    point : str or None
        The point whose path the coupler-curve descriptors describe.
    has_masses : bool
        The mechanisms carry mass data (the peak input torque can be computed).
    """

    name: str
    parameters: tuple[str, ...]
    defaults: Mapping[str, float]
    lengths: tuple[str, ...]
    output: str | None
    transmission: tuple[str, str] | None
    point: str | None
    has_masses: bool = False
    make: Callable[..., Mechanism] | None = None
    options: Mapping[str, Any] = dataclasses.field(default_factory=dict)
    base: Mechanism | None = None

    def is_slide(self, name: str | None) -> bool:
        """``name`` is a prismatic joint's slide (m), not a link's angle (rad)."""
        if self.base is not None:
            return any(j.name == name and j.type == "P" for j in self.base.joints)
        return name in _SLIDE_OUTPUTS

    @property
    def output_is_slide(self) -> bool:
        return self.is_slide(self.output)

    def has_point(self, columns) -> bool:
        """Whether designs with these columns have the coupler point (the catalogue four-bar
        has one only when its columns are given)."""
        return self.make is not mechanisms.fourbar or any(c in columns for c in _POINT_COLUMNS)

    @property
    def grashof(self) -> bool:
        return self.make is mechanisms.fourbar

    def build(self, row: Mapping[str, float]) -> Mechanism:
        """The mechanism of one design (a mapping parameter -> value)."""
        values = {**self.defaults, **row}
        if self.make is not None:
            kwargs = dict(self.options)
            if self.make is mechanisms.fourbar:
                along, across = (values.pop(c, math.nan) for c in _POINT_COLUMNS)
                if not (math.isnan(along) and math.isnan(across)):
                    kwargs["coupler_point"] = (along, across)
            kwargs.update(values)
            return self.make(**kwargs)
        points = tuple(Point(p.name, values.get(f"{p.name}.x", p.x), values.get(f"{p.name}.y", p.y),
                             p.z) for p in self.base.points)
        # the points make the lengths: a length the file declares is the sketch's, not the
        # design's; a link's mass and inertia are the design's where its columns give them
        links = tuple(dataclasses.replace(
            link, length=None, **{k: values[f"{link.name}.{k}"] for k in _MASS_DATA
                                  if f"{link.name}.{k}" in values})
            for link in self.base.links)
        return dataclasses.replace(self.base, points=points, links=links)

    def unit(self, parameter: str) -> str:
        """The SI unit of a design column: m, or kg and kg m^2 for a link's mass data."""
        return _MASS_DATA.get(parameter.rpartition(".")[2], "m") if self.base is not None else "m"

    def prepare(self, columns: Mapping[str, np.ndarray], problems: list[str]) -> Designs:
        """D designs ready to evaluate: ``columns`` parameter -> (D,) values, ``problems`` the
        reason per design that cannot be analysed ('' if it can), updated in place with the
        designs that cannot be built."""
        return _SketchedDesigns(self, columns, problems)


class Designs:
    """A chunk of designs of one family, evaluated at any inputs."""

    problems: list[str]

    def batch(self, q: np.ndarray) -> Batch:
        """Their kinematics at inputs ``q`` (D, S)."""
        raise NotImplementedError

    def take(self, rows: np.ndarray) -> Designs:
        """Some of them (``rows`` index the chunk)."""
        new = object.__new__(type(self))
        new.__dict__.update(self.__dict__)
        new.problems = [self.problems[r] for r in rows]
        new._take(rows)
        return new


class DesignOffModel(ModelError):
    """A design of a model's family that moves points off the lengths, places or offsets the
    model declares (a link's ``local`` place or ``sides``, a joint's ``offset``): ``detail``
    says which and by how much, ``design`` the parameters that moved."""

    def __init__(self, detail: str, design: str):
        self.detail, self.design = detail, design
        super().__init__(f"designs: the design {design} moves points off the places the model "
                         f"declares ({detail}); vary only points that no declaration fixes, or "
                         "remove that declaration (a link's local place or sides, a joint's "
                         "offset) from the model")


def _check_design(mech: Mechanism, row: Mapping[str, float], base: Mechanism) -> None:
    """Plan a design's mechanism (the plan is cached on it), saying in the sweep's terms
    when the design breaks what its model declares."""
    try:
        plan(mech)
    except SketchNotAssembled as exc:
        # the engine's advice (assemble the sketch in Python) would move the design itself
        sketch = {f"{p.name}.{c}": getattr(p, c) for p in base.points for c in "xy"}
        moved = {p: v for p, v in row.items() if v != sketch.get(p)}
        design = ", ".join(f"{p} = {v:g} m" for p, v in list(moved.items())[:4]) or "as drawn"
        raise DesignOffModel(exc.miss, f"({design}{', ...' if len(moved) > 4 else ''})") from None


class _SketchedDesigns(Designs):
    """Designs analysed together: their sketches, the places of the family's points, in
    one array, and each chunk's samples in one call of the kernel
    (:func:`kinelab.kinematics.analyze_designs`).

    The sketches are made in array operations for the catalogue's kinds of
    :data:`kinelab.mechanisms.SKETCHED` and for model files' families whose points no
    declaration ties (a link's local place or sides, a joint's offset); otherwise each
    design's mechanism is built (and planned, to check what the file declares) and gives its
    sketch.  A design whose sketch the family's plan cannot take (a dyad drawn straight, two
    points at one place) is analysed on its own, with a plan of its own.
    """

    def __init__(self, fam: Family, columns, problems):
        self.fam, self.problems = fam, problems
        D = len(problems)
        self.nowhere = np.zeros(D, bool)
        self.rows = {p: np.asarray(v, float) for p, v in columns.items()}
        self.template: Mechanism | None = None
        if fam.make is not None and fam.name in mechanisms.SKETCHED:
            xy, axes = self._catalogue(D)
        elif fam.base is not None and not _declares_places(fam.base):
            xy, axes = self._model(D)
        else:
            xy, axes = self._one_by_one(D)
        names = [] if self.template is None else self.template.point_names
        self.points = np.stack([xy[n] for n in names], 1) if names else np.zeros((D, 0, 2))
        self.axes = axes
        if self.template is not None and len(self.template.inputs) != 1:
            # the family's, not the design's: every sample of a sweep is one input's value
            raise ModelError(f"family: the mechanisms of {fam.name!r} have "
                             f"{len(self.template.inputs)} inputs, but a sweep turns one input "
                             "through its samples; sweep a family with one input (a model "
                             "file of it with one input, say)")

    def _row(self, d: int) -> dict[str, float]:
        return {p: float(v[d]) for p, v in self.rows.items()}

    def _build(self, d: int) -> Mechanism | None:
        """Design ``d``'s mechanism, planned; None (and its problem said) when it cannot be
        analysed."""
        row = self._row(d)
        try:
            mech = self.fam.build(row)
            if self.fam.base is not None:
                _check_design(mech, row, self.fam.base)
            else:
                plan(mech)          # cached on the mechanism for the analyses
            return mech
        except DesignOffModel:      # the column, not the row: vary another point
            raise
        except NeverAssembles:      # a design that assembles nowhere: no sample assembles
            self.nowhere[d] = True
            return None
        except KinelabError as exc:     # this design alone cannot be analysed
            self.problems[d] = str(exc).splitlines()[0]
            return None

    def usable(self) -> np.ndarray:
        """The designs to analyse, (D,): neither a problem nor lengths that close nowhere."""
        return np.array([not p for p in self.problems], bool) & ~self.nowhere

    def _catalogue(self, D):
        fam = self.fam
        good = self.usable()
        values = {p: self.rows[p] if p in self.rows else np.full(D, fam.defaults.get(p, math.nan))
                  for p in fam.parameters}
        # a placeholder in the rows already reported: their values may overflow the sketch
        values = {p: np.where(good, v, 1.0) for p, v in values.items()}
        point = fam.make is mechanisms.fourbar and fam.has_point(self.rows)
        if fam.make is mechanisms.fourbar:
            for c in _POINT_COLUMNS:       # no coupler point, or one where a row leaves it out
                values[c] = np.nan_to_num(values[c]) if point else None
            values = {k: a for k, a in values.items() if a is not None}
        xy, axes, ok = mechanisms.sketches(fam.name, values, fam.options)
        ok &= good
        for d in np.flatnonzero(~ok & good):     # the constructor says why
            mech = self._build(d)
            if mech is not None:
                ok[d] = True
                for p in mech.points:
                    xy[p.name][d] = p.xy[:2]
                for j in mech.joints:
                    if j.type == "P":
                        axes[j.name][d] = j.axis[:2]
        first = np.flatnonzero(ok)
        if len(first):
            self.template = self._build(first[0])
        return xy, axes

    def _model(self, D):
        base = self.fam.build({})
        self.template = base
        xy = {p.name: np.stack([self.rows.get(f"{p.name}.{c}", np.full(D, getattr(p, c)))
                                for c in "xy"], -1) for p in base.points}
        drawable = np.all([np.all(np.abs(a) <= MAX_LENGTH, axis=1) for a in xy.values()], axis=0)
        for c, v in self.rows.items():  # masses and inertias the model would refuse
            kind = c.rpartition(".")[2]
            if kind in _MASS_DATA:
                limit = MAX_MASS if kind == "mass" else MAX_INERTIA
                drawable &= (v > 0) & (v <= limit)
        for d in np.flatnonzero(~drawable & self.usable()):
            self._build(d)          # says why
        return xy, {}

    def _one_by_one(self, D):
        built = {d: self._build(d) for d in np.flatnonzero(self.usable())}
        built = {d: m for d, m in built.items() if m is not None}
        self.template = self.fam.base or next(iter(built.values()), None)
        if self.template is None:
            return {}, {}
        xy = {n: np.full((D, 2), np.nan) for n in self.template.point_names}
        axes = {j.name: np.full((D, 2), np.nan) for j in self.template.joints if j.type == "P"}
        for d, mech in built.items():
            for p in mech.points:
                xy[p.name][d] = p.xy[:2]
            for j in mech.joints:
                if j.type == "P":
                    axes[j.name][d] = j.axis[:2]
        return xy, axes

    def _take(self, rows):
        self.rows = {p: v[rows] for p, v in self.rows.items()}
        self.points = self.points[rows]
        self.axes = {n: a[rows] for n, a in self.axes.items()}
        self.nowhere = self.nowhere[rows]

    def batch(self, q):
        return DesignsBatch(self, q)

    def mechanism(self, d: int) -> Mechanism | None:
        """Design ``d``'s own mechanism (None if it cannot be built)."""
        return self._build(d) if self.usable()[d] else None

    def _weights(self, system, rows: np.ndarray, samples: int) -> np.ndarray | None:
        """The masses and moments of inertia of ``system.items`` for designs ``rows`` at
        each of their samples, (len(rows) samples, k), where the designs give them; else
        None (the family's own)."""
        columns = [(c, v) for c, v in self.rows.items() if c.rpartition(".")[2] in _MASS_DATA]
        if not columns:
            return None
        w = np.tile(system.weights, (len(rows), 1))
        links = [b.link for b in system.masses.links]
        turning = [b.link for b in system.masses.links if b.inertia > 0]
        for c, v in columns:
            link, _, kind = c.rpartition(".")
            if kind == "mass":
                i = 2 * links.index(link)
                w[:, i:i + 2] = v[rows, None]
            else:
                w[:, 2 * len(system.t_mass) + turning.index(link)] = v[rows]
        return np.repeat(w, samples, axis=0)

    def peak_torque(self, q: np.ndarray, speed: float) -> np.ndarray:
        """Largest |input torque| over ``q`` (D, S) at constant input ``speed`` (rad/s), (D,);
        NaN where a design does not assemble or is singular somewhere.  Kane's terms of the
        family's masses and loads (its model file's) over every design's analysis at once
        (:func:`kinelab.kinematics.analyze_designs`, the designs' own places of the centres
        of mass), and one :func:`kinelab.dynamics.inverse` for each design whose sketch the
        family's plan cannot take."""
        from kinelab.dynamics import inverse
        from kinelab.dynamics._terms import build_system, evaluate

        out = np.full(len(q), np.nan)
        clean = np.zeros(len(q), bool)      # designs that assemble, never singular
        good = self.usable() & (self.template is not None)
        alone = ()
        if good.any():
            rows = np.flatnonzero(good)
            axes = {n: a[good] for n, a in self.axes.items()}
            sol = analyze_designs(self.template, self.points[good], q[good], qd=speed,
                                  axes=axes or None)
            system = build_system(self.template, None, None)
            with np.errstate(over="ignore", invalid="ignore"):
                terms = evaluate(system, sol, np.zeros(sol.q.shape[0]),
                                 weights=self._weights(system, rows, q.shape[1]))
                tau = sol.by_design(np.abs(terms.inertia - terms.applied)[:, 0])
            ok = sol.by_design(sol.assembled & ~sol.singular).all(axis=1) & sol.valid
            clean[rows[ok]] = True
            out[rows[ok]] = tau[ok].max(axis=1)
            alone = rows[~sol.valid]
        for d in alone:         # a design with a plan of its own
            mech = self.mechanism(d)
            if mech is None:
                continue
            sol = analyze(mech, q[d], unreachable="mask", at_singular="flag")
            if sol.assembled.all() and not sol.singular.any():
                clean[d] = True
                with np.errstate(over="ignore", invalid="ignore"):
                    out[d] = np.abs(inverse(mech, q[d], qd=speed, reactions=False).input_forces).max()
        for d in np.flatnonzero(clean & ~np.isfinite(out)):   # an overflow: said, never a silent NaN
            out[d] = np.nan
            self.problems[d] = self.problems[d] or (
                f"peak_torque: the input torque overflows at {speed:g} rad/s; lower the "
                "speed or the masses")
        return out


def _declares_places(m: Mechanism) -> bool:
    """Whether a model ties some of its points to others (a link's local place or sides, a
    joint's offset): its designs must be built one by one, to check they keep them."""
    return (any(link.local or getattr(link, "sides", None) for link in m.links)
            or any(j.offset is not None for j in m.joints))


def _catalogue_family(kind: str, options: Mapping[str, Any], defaults: Mapping[str, Any]) -> Family:
    make = getattr(mechanisms, kind)
    signature = inspect.signature(make).parameters
    numeric, fixed = [], {}
    for name, p in signature.items():
        if name == "q0":
            continue
        if name == "coupler_point" and make is mechanisms.fourbar:
            numeric += list(_POINT_COLUMNS)
        elif p.default is inspect.Parameter.empty or _real(p.default):
            numeric.append(name)
        else:
            fixed[name] = p.default
    unknown = [k for k in options if k not in fixed]
    if unknown:
        raise ModelError(f"{kind}: option {unknown[0]!r}: "
                         + (expected_one_of(unknown[0], fixed) if fixed else
                            f"'{kind}' takes no options beyond its design columns "
                            f"{', '.join(numeric)}"))
    hints = typing.get_type_hints(make)
    for name, value in options.items():
        _check_option(name, value, hints.get(name))
    given = {k: v for k, v in defaults.items() if k in numeric and v is not None}
    if make is mechanisms.fourbar and defaults.get("coupler_point") is not None:
        given.update(zip(_POINT_COLUMNS, defaults["coupler_point"]))
    base = {name: p.default for name, p in signature.items()
            if name in numeric and _real(p.default)}
    if make is mechanisms.fourbar:
        base.update(dict.fromkeys(_POINT_COLUMNS, math.nan))     # no coupler point
    output, transmission, point = _ROLES.get(kind, (None, None, None))
    lengths = tuple(n for n in ("ground", "crank", "coupler", "rocker", "rod", "lever",
                                "distance", "crank1", "crank2", "coupler1", "coupler2")
                    if n in numeric)
    return Family(kind, tuple(numeric), {**base, **given}, lengths, output, transmission, point,
                  make=make, options={**{k: defaults[k] for k in fixed if k in defaults},
                                      **options})


def _check_option(name: str, value, hint) -> None:
    """Refuse an option outside the choices its constructor's annotation lists, as the
    constructor would (the closed-form four-bar never calls it): ``Literal[...]``, or a
    tuple of them (the six-bars' assembly modes); None where the default is None."""
    if typing.get_origin(hint) in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(hint) if a is not type(None)]
        if value is None and len(args) < len(typing.get_args(hint)):
            return
        hint = args[0] if len(args) == 1 else hint
    if typing.get_origin(hint) is typing.Literal:
        check_choice(name, value, typing.get_args(hint))
    elif typing.get_origin(hint) is tuple and all(typing.get_origin(a) is typing.Literal
                                                  for a in typing.get_args(hint)):
        parts = typing.get_args(hint)
        if not isinstance(value, (tuple, list)) or len(value) != len(parts):
            raise ModelError(f"{name}: expected {len(parts)} values, one of "
                             f"{', '.join(map(repr, typing.get_args(parts[0])))} each, got "
                             f"{describe(value)}")
        for k, (v, part) in enumerate(zip(value, parts)):
            check_choice(f"{name}[{k}]", v, typing.get_args(part))


def family(spec: str | Mechanism | Family, *, output: str | None = None,
           transmission: tuple[str, str] | None = None, point: str | None = None,
           **options) -> Family:
    """A family of mechanisms to sweep.

    Parameters
    ----------
    spec : str, Mechanism or Family
        A catalogue kind (``"fourbar"``, ``"slider_crank"``, ... the constructors of
        :mod:`kinelab.mechanisms`), or a mechanism, usually read from a model file
        (``kl.load(path)``): one built by the catalogue (a file with a ``[catalogue]`` table)
        is that kind with its values as defaults; any other has the sketch coordinates of its
        points as parameters, ``"<point>.x"`` and ``"<point>.y"`` (m), defaulting to the
        sketch's, and for each link with mass data its mass and moment of inertia about its
        centre of mass, ``"<link>.mass"`` (kg) and ``"<link>.inertia"`` (kg m^2), defaulting
        to the model's; it keeps the model's assembly mode.
    output, transmission, point : optional
        What the metrics measure (see :class:`Family`); the catalogue sets them for its
        four-bar (rocker; coupler and rocker; P) and slider-cranks.
    **options
        Fixed, non-numeric arguments of a catalogue constructor, e.g. ``branch="crossed"``.

    Examples
    --------
    >>> fam = kl.sweep.family("fourbar", branch="crossed")
    >>> fam.parameters
    ('ground', 'crank', 'coupler', 'rocker', 'coupler_point_along', 'coupler_point_perpendicular')
    >>> kl.sweep.family("slider_crank").defaults
    {'offset': 0.0}
    """
    if isinstance(spec, Family):
        fam = spec
    elif isinstance(spec, str) and spec in CATALOGUE:
        fam = _catalogue_family(spec, options, {})
    elif isinstance(spec, Mechanism):
        fam = _mechanism_family(spec, options)
    else:
        raise ModelError(f"family: {expected_one_of(spec, CATALOGUE)}, or a mechanism "
                         "(kinelab.load('model.toml'))")
    for name, value in (("output", output), ("point", point)):
        if value is not None and not isinstance(value, str):
            raise ModelError(f"{name}: expected a name, got {describe(value)}")
    changes = {k: v for k, v in (("output", output), ("point", point)) if v is not None}
    if transmission is not None:
        if not (isinstance(transmission, (tuple, list)) and len(transmission) == 2
                and all(isinstance(n, str) for n in transmission)
                and transmission[0] != transmission[1]):
            raise ModelError(f"transmission: expected two different links (a coupler and an "
                             f"output), got {describe(transmission)}")
        changes["transmission"] = tuple(transmission)
    names = _names(fam)
    if names is not None:           # the names are known: refuse a misspelt one now
        links, slides, points = names
        if output is not None:
            check_choice("output", output, [*links, *slides])
        for k, link in enumerate(transmission or ()):
            check_choice(f"transmission[{k}]", link, links)
        if point is not None:
            check_choice("point", point, points)
    return dataclasses.replace(fam, **changes) if changes else fam


def _names(fam: Family) -> tuple[list[str], list[str], list[str]] | None:
    """The links, prismatic joints and points of a family's mechanisms, when known without
    building one: a model's, or the catalogue four-bar's."""
    if fam.base is not None:
        m = fam.base
        return list(m.link_names), [j.name for j in m.joints if j.type == "P"], list(m.point_names)
    if fam.make is mechanisms.fourbar:
        return ["ground", "crank", "coupler", "rocker"], [], ["O2", "A", "B", "O4", "P"]
    return None


def _mechanism_family(mech: Mechanism, options) -> Family:
    kind = mech.parameters.get("kind")
    has_masses = any(link.mass is not None for link in mech.links)
    if kind in CATALOGUE and not has_masses:
        return _catalogue_family(kind, options, mech.parameters)
    if options:
        raise ModelError(f"{mech.name}: options {', '.join(map(repr, options))}: the family of a "
                         "model takes none (its assembly mode is the sketch's)")
    defaults = {f"{p.name}.{c}": getattr(p, c) for p in mech.points for c in "xy"}
    defaults.update({f"{link.name}.{k}": getattr(link, k) for link in mech.links
                     for k in _MASS_DATA if getattr(link, k)})
    names = tuple(defaults)
    output, transmission, point = _ROLES.get(kind, (None, None, None))
    return Family(mech.name, names, defaults, (), output, transmission, point,
                  has_masses=has_masses, base=mech)
