"""Model files: a mechanism described in TOML (or JSON), with its units and its sweep.

The format is documented field by field in ``docs/model-format.md``.  Reading converts
every length and angle to SI once, on entry; writing converts back once, on export.
Every problem of a file is collected and raised together as one
:class:`~kinelab.errors.ModelError` whose lines each name the file and the field.
"""
from __future__ import annotations

import copy
import dataclasses
import inspect
import json
import math
import os
import re
from collections.abc import Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np

from kinelab import mechanisms as catalogue
from kinelab import _memory as memory
from kinelab._files import UnwritableOutput, atomic_write, file_path
from kinelab.errors import AssemblyError, KinelabError, ModelError
from kinelab.io import _toml
from kinelab.io._fields import Reader, describe, quoted, shown, shown_key
from kinelab.io._text import Written, in_si, loads, read_text, written
from kinelab.kinematics import Assembly, assemble
from kinelab.kinematics._assemble import assembly_miss, needs_assembly
from kinelab.model import (GEAR_MESHES, ANGLE_UNITS, JOINT_TYPES, LENGTH_UNITS, SIDE_WORDS, SPACES, Input,
                           Joint, Link, Mechanism, Point, Units, angle_problem,
                           coordinate_problem, length_problem, name_problem, place_problems,
                           range_problem, rate_problem, size_problems)

__all__ = ["SCHEMA", "LENGTH_UNITS", "ANGLE_UNITS", "Units", "Outputs", "ModelFile", "load",
           "save", "from_toml", "to_toml", "from_json", "to_json", "errors_from"]

SCHEMA = 1
"""The newest schema version this kinelab reads and the one it writes."""

DEFAULT_SAMPLES = 361
MAX_SAMPLES = 1_000_000
"""The most samples per input a file or ``--samples`` may ask for: a sweep this long, with
its table, fits the default memory budget (see :func:`kinelab.memory_budget`)."""
LENGTH_RTOL = 1e-6    # a catalogue's lengths agree with the file's sketch to this relative error
_ASSEMBLED = 1e-12    # relative: a sketch that misses its lengths by less is assembled (the
                      # 14 digits a file is written with)
CATALOGUE_KINDS = ("fourbar", "slider_crank", "inverted_slider_crank", "slotted_link",
                   "whitworth", "fivebar", "watt6", "stephenson6", "triad6")

_TOP = ("schema", "name", "description", "space", "units", "points", "links", "joints",
        "inputs", "sweep", "catalogue", "outputs", "dynamics", "notation", "spherical")
_RESERVED = {key: "loads belong in the [dynamics] section (see docs/dynamics.md); move it there"
             for key in ("forces", "gravity", "loads")}
_LINK = ("name", "points", "ground", "length", "local", "sides", "mass", "center_of_mass",
         "inertia")
_JOINT = ("name", "type", "links", "point", "axis", "origin", "offset", "axis2", "pitch",
          "mesh", "ratio", "radii", "teeth", "radius", "carrier", "segments")
_INPUT = ("joint", "links", "name", "range", "speed", "acceleration", "samples")
_OUTPUTS = ("report", "transmission", "time_ratio")
_SWEEPS = ("together", "grid")
_SPHERICAL = ("ground", "crank", "coupler", "rocker", "branch", "radius")
_SIGNED_PARAMETERS = ("offset", "ram_height")   # catalogue lengths that may be zero or negative


@dataclass(frozen=True)
class Outputs:
    """What a person wants reported and plotted (the file's optional ``[outputs]``).

    Attributes
    ----------
    report : tuple of str
        Links, points and prismatic joints (slides) to summarise and plot.
    transmission : tuple of (str, str)
        Pairs of links whose transmission angle is reported (coupler, output).
    time_ratio : str, optional
        The output (a link or a slide) whose quick-return time ratio is reported.
    """

    report: tuple[str, ...] = ()
    transmission: tuple[tuple[str, str], ...] = ()
    time_ratio: str | None = None

    def __bool__(self) -> bool:
        return bool(self.report or self.transmission or self.time_ratio)


@dataclass(frozen=True)
class ModelFile:
    """A mechanism as a model file holds it: the model (SI), the file's units, how many
    samples each input is swept over, and what to report.

    Build one with :meth:`read` (or :meth:`from_toml`, :meth:`from_json`,
    :meth:`from_dict`); ``kinelab.load(path)`` is ``ModelFile.read(path).mechanism``.

    Attributes
    ----------
    mechanism : Mechanism
    units : Units
    samples : tuple of int
        Samples per input (empty: the default, 361).
    sweep : {"together", "grid"}
        With several inputs, "together" moves them all at once from their start to their
        stop (N samples); "grid" takes every combination (N1 x N2 ... samples).
    outputs : Outputs
    description : str
    source : str, optional
        Where the file came from (for messages); not part of equality.
    assembly : Assembly, optional
        When the file gives lengths, places or offsets: how its sketch was moved to the
        assembly at its inputs (which points moved, by how much, which dyads changed
        side); not part of equality.
    """

    mechanism: Mechanism
    units: Units = Units()
    samples: tuple[int, ...] = ()
    sweep: Literal["together", "grid"] = "together"
    outputs: Outputs = Outputs()
    description: str = ""
    source: str | None = field(default=None, compare=False)
    assembly: Assembly | None = field(default=None, compare=False, repr=False)

    # -- reading ---------------------------------------------------------------------------
    @classmethod
    def read(cls, path: str | os.PathLike) -> ModelFile:
        """Read a ``.toml`` or ``.json`` model file.

        Examples
        --------
        >>> mf = kl.io.ModelFile.read("examples/crank_rocker.toml")
        >>> mf.units, mf.mechanism.link_names
        (Units(length='mm', angle='deg'), ('ground', 'crank', 'coupler', 'rocker'))
        """
        path = file_path(path)
        source = path.name
        suffix = path.suffix.lower()
        if suffix not in (".toml", ".json"):
            raise ModelError(f"expected a .toml or .json model file, got {shown(path.suffix or path.name)}; "
                             "rename it or convert it (kinelab import reads Pyslvs and "
                             "linkage2d files)", source=source)
        text = read_text(path)
        parse = cls.from_toml if suffix == ".toml" else cls.from_json
        return parse(text, source=source, _stem=path.stem)

    @classmethod
    def from_toml(cls, text: str, *, source: str | None = None, _stem: str | None = None) -> ModelFile:
        """Parse model-file text in TOML."""
        return cls.from_dict(loads(text, "TOML", source=source), source=source, _stem=_stem)

    @classmethod
    def from_json(cls, text: str, *, source: str | None = None, _stem: str | None = None) -> ModelFile:
        """Parse model-file text in JSON (the same fields as TOML)."""
        return cls.from_dict(loads(text, "JSON", source=source), source=source, _stem=_stem)

    @classmethod
    def from_dict(cls, data: Any, *, source: str | None = None, _stem: str | None = None) -> ModelFile:
        """Build from plain data shaped like the file (in the file's units)."""
        return _Parser(source, _stem).parse(data)

    # -- writing ---------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Plain data shaped like the file, in the file's units (inverse of :meth:`from_dict`)."""
        return _dump(self)

    def to_toml(self) -> str:
        """TOML text of the file."""
        return _toml.dumps(self.to_dict())

    def to_json(self) -> str:
        """JSON text of the file."""
        return _json_text(self.to_dict())

    def write(self, path: str | os.PathLike) -> Path:
        """Write TOML or JSON, by the suffix of ``path`` (to a temporary file, then renamed)."""
        path = file_path(path)
        suffix = path.suffix.lower()
        if suffix not in (".toml", ".json"):
            raise ModelError(f"path: expected a .toml or .json file name, got {shown(path.name)}")
        text = self.to_toml() if suffix == ".toml" else self.to_json()
        return atomic_write(path, lambda f: f.write(text))

    # -- the sweep -------------------------------------------------------------------------
    def analyze(self, samples: int | None = None, *,
              at_change_point: Literal["smooth", "switch"] = "smooth"):
        """The analysis of the file's sweep (:meth:`sample_inputs`), singular samples
        flagged, through change points as ``at_change_point`` says: what ``kinelab
        analyze`` writes.  Errors name the file and its ``inputs``.

        Examples
        --------
        >>> sol = kl.io.ModelFile.read("examples/crank_rocker.toml").analyze(5)
        >>> sol.N, sol.mechanism.name
        (5, 'crank-rocker')
        """
        from kinelab.kinematics import analyze

        q, qd, qdd = self.sample_inputs(samples)
        with errors_from(self, "inputs"):
            return analyze(self.mechanism, q, qd, qdd, at_singular="flag",
                           at_change_point=at_change_point)

    def dynamics_setup(self, gravity: tuple[float, float] | None = None):
        """The loads and the mass properties of the file's ``[dynamics]`` section and its
        links' mass data, gravity replaced by ``gravity`` (m/s^2) if given: ``(loads,
        masses)``, as :func:`kinelab.dynamics.inverse` takes them."""
        from kinelab import dynamics

        setup = dynamics.DynamicsSetup.from_model(self.mechanism)
        loads = setup.loads
        if gravity is not None:
            loads = dynamics.Loads(gravity=gravity, forces=loads.forces, torques=loads.torques,
                                   springs=loads.springs, dampers=loads.dampers)
        return loads, setup.masses(self.mechanism)

    def inverse_dynamics(self, samples: int | None = None, *,
                         gravity: tuple[float, float] | None = None):
        """The inverse dynamics of the file's sweep (:meth:`sample_inputs`) under its
        :meth:`dynamics_setup`, time running along the sweep (:func:`sweep_times`): what
        ``kinelab dynamics`` writes, and the browser app's *forces* tab shows.

        Examples
        --------
        >>> res = kl.io.ModelFile.read("examples/engine.toml").inverse_dynamics(5)
        >>> res.input_forces.shape, round(float(res.input_forces[0, 0]), 4)      # N m
        ((5, 1), 0.6867)
        """
        from kinelab import dynamics

        loads, masses = self.dynamics_setup(gravity)
        q, qd, qdd = self.sample_inputs(samples)
        inp = self.mechanism.inputs[0]
        return dynamics.inverse(self.mechanism, q, qd, qdd, loads=loads, masses=masses,
                                t=sweep_times(q, inp.speed, inp.acceleration))

    def sample_count(self, samples: int | None = None) -> int:
        """The number of samples (rows) of the file's sweep with ``samples`` per input
        (default the file's): their product for a grid of several inputs.

        >>> kl.io.ModelFile.read("examples/fivebar.toml").sample_count(100)
        100
        """
        counts = self._counts(samples)
        return math.prod(counts) if (len(counts) > 1 and self.sweep == "grid") else max(counts)

    def _counts(self, samples: int | None) -> list[int]:
        M = len(self.mechanism.inputs)
        if M == 0:
            raise ModelError("inputs: the mechanism has no input; add one under [[inputs]]",
                             source=self.source)
        if samples is not None and not (isinstance(samples, int) and not isinstance(samples, bool)
                                        and 2 <= samples <= MAX_SAMPLES):
            raise ModelError(f"samples: expected a whole number from 2 to {MAX_SAMPLES:,}, got {describe(samples)}")
        return [samples] * M if samples is not None else (
            list(self.samples) if self.samples else [DEFAULT_SAMPLES] * M)

    def sample_inputs(self, samples: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Input values, rates and accelerations of the file's sweep, SI.

        Each input runs from its ``range`` start to its stop; an input without a range (one
        input only) covers the range where the mechanism assembles on its sketch's branch:
        one full turn from 0 when it turns fully, else from one limit position to the other.

        Parameters
        ----------
        samples : int, optional
            Samples per input, instead of the file's.

        Returns
        -------
        q, qd, qdd : ndarray, shape (N,) for one input, (N, M) for M inputs

        Examples
        --------
        >>> q, qd, qdd = kl.io.ModelFile.read("examples/crank_rocker.toml").sample_inputs(5)
        >>> np.degrees(q).round(9), float(qd[0])            # 600 deg/s
        (array([  0.,  90., 180., 270., 360.]), 10.471975511965978)
        """
        m = self.mechanism
        M = len(m.inputs)
        counts = self._counts(samples)
        total = self.sample_count(samples)
        memory.require(total * M * 8 * 3, f"the inputs of {total:,} samples"
                       + (f" (a grid of {' x '.join(f'{c:,}' for c in counts)})" if M > 1 and
                          self.sweep == "grid" else ""),
                       "ask for fewer samples")
        axes = []
        for k, inp in enumerate(m.inputs):
            if inp.range is not None:
                lo, hi = inp.range
            elif M == 1:
                lo, hi = _reachable_span(m)
            else:
                raise ModelError(f"inputs[{k}].range: missing; with more than one input every "
                                 "input needs a range [start, stop]", source=self.source)
            axes.append(np.linspace(lo, hi, counts[k]))
        if M == 1:
            q = axes[0]
        elif self.sweep == "grid":
            q = np.stack([g.ravel() for g in np.meshgrid(*axes, indexing="ij")], axis=-1)
        else:
            q = np.stack(axes, axis=-1)
        shape = (len(q),) if M == 1 else (len(q), M)
        qd = np.broadcast_to(np.array([i.speed for i in m.inputs]).reshape(shape[1:] or ()), shape)
        qdd = np.broadcast_to(np.array([i.acceleration for i in m.inputs]).reshape(shape[1:] or ()),
                              shape)
        return q, np.array(qd), np.array(qdd)


def sweep_times(q: np.ndarray, speed: float, acceleration: float) -> np.ndarray:
    """Time along a one-input sweep ``q`` (N,) at constant ``speed``, s, from 0 at its first
    sample; zeros for several inputs, a speed of zero or an acceleration.

    >>> sweep_times(np.radians([0.0, 90.0, 180.0]), np.pi, 0.0)
    array([0. , 0.5, 1. ])
    """
    if q.ndim == 1 and speed != 0.0 and acceleration == 0.0:
        return (q - q[0]) / speed
    return np.zeros(q.shape[0])


# what a model file's user is asked for instead of input values that will not do, by the
# field that gave them ({} is the error's ``instead``: a value within reach, off it, ...)
_INSTEAD = {"inputs": "narrow the range of the file's inputs", "--at": "give --at {}",
            "q": "choose {}"}


@contextmanager
def errors_from(mf: ModelFile, field: str = ""):
    """Name the file (and a field) in the errors raised inside: ``crank_rocker.toml:
    inputs: ...`` (``model: ...`` when the file has no name).  Input values that will not
    do are said in the file's units and with its inputs' names.  An error that names a file
    of its own (an output that cannot be written) is left as it is."""
    from kinelab.kinematics import SingularInput, UnreachableInput

    try:
        yield
    except KinelabError as exc:
        prefix = f"{mf.source or 'model'}: {field + ': ' if field else ''}"
        if isinstance(exc, UnwritableOutput):
            raise
        if isinstance(exc, ModelError):
            raise ModelError([prefix + p for p in exc.problems]) from None
        if isinstance(exc, (UnreachableInput, SingularInput)):
            said = copy.copy(exc)          # the same error, with its data, in the file's words
            advice = _INSTEAD.get(field, "choose {}").format(exc.instead)
            said.args = (f"{prefix}{exc.saying(mf.units, mf.mechanism.input_names)}; {advice}",)
            raise said from None
        raise type(exc)("\n".join(prefix + line for line in str(exc).splitlines())) from None


def _reachable_span(m: Mechanism) -> tuple[float, float]:
    from kinelab.kinematics import plan, reachable_ranges, turns_fully
    q0 = float(plan(m).q_sketch[0])
    ranges = reachable_ranges(m)
    if not ranges:
        raise ModelError("inputs[0].range: the mechanism does not assemble near its sketch; "
                         "check the sketch")
    if turns_fully(m, ranges):
        return 0.0, 2 * math.pi
    lo, hi = next(((a, b) for a, b in ranges if a <= q0 <= b), ranges[0])
    shrink = 1e-9 * (hi - lo)     # stop just short of the limit positions, which are singular
    return lo + shrink, hi - shrink


# ------------------------------------------------------------------------------------------
# reading
# ------------------------------------------------------------------------------------------
class _Parser:
    def __init__(self, source: str | None, stem: str | None):
        self.source = source
        self.stem = stem
        self.r = Reader()
        self.where: dict[tuple[str, str], str] = {}   # (kind, name) -> "links[2]"
        self.assembly: Assembly | None = None

    def fail(self, problems=None):
        raise ModelError(problems or self.r.problems, source=self.source)

    def parse(self, data: Any) -> ModelFile:
        r = self.r
        top = r.table(data, "", _TOP, reserved=_RESERVED)
        if top is None:
            self.fail()
        if "schema" not in top:
            r.fail("schema", f"missing; add schema = {SCHEMA} at the top of the file")
        if "units" not in top:
            r.fail("units", "missing; say which units the file is written in, e.g. [units] "
                   "length = \"mm\", angle = \"deg\"")
        if "schema" in top:
            schema = top["schema"]
            if isinstance(schema, int) and not isinstance(schema, bool) and schema > SCHEMA:
                self.fail([f"schema: this file is written for schema {describe(schema)}, but this kinelab "
                           f"reads schema {SCHEMA} and older; upgrade kinelab"])
            r.integer(schema, "schema", low=1, high=SCHEMA)
        name = r.string(top.get("name", self.stem or "mechanism"), "name")
        description = top.get("description", "")
        if not isinstance(description, str):
            r.fail("description", f"expected a text, got {describe(description)}")
            description = ""
        space = r.string(top.get("space", "planar"), "space", choices=SPACES) or "planar"
        units = self.units(top.get("units"))
        sweep = r.string(top.get("sweep", "together"), "sweep", choices=_SWEEPS) or "together"
        explicit = [k for k in ("points", "links", "joints") if k in top]
        if "spherical" in top:
            mech, samples = self.from_spherical(top, units, name, space, explicit)
        elif "catalogue" in top and not explicit:
            mech, samples = self.from_catalogue(top, units, name)
        else:
            for k in ("points", "links", "joints"):
                if k not in top:
                    r.fail(k, f"missing; a model needs [points], [[links]] and [[joints]] (or a "
                           "[catalogue] table instead of all three)")
            mech, samples = self.explicit(top, units, name, space)
        if r.problems:
            self.fail()
        if "dynamics" in top:
            mech = self.dynamics(top["dynamics"], mech)
        if "notation" in top:
            mech = self.notation(top["notation"], mech)
        outputs = self.outputs(top.get("outputs"), mech) if "outputs" in top else Outputs()
        if samples and sweep == "together" and len(set(samples)) > 1:
            r.fail("inputs", f"samples: expected the same number for every input when sweep = "
                   f"'together', got {list(samples)}; make them equal or set sweep = 'grid'")
        if r.problems:
            self.fail()
        return ModelFile(mechanism=mech, units=units, samples=samples, sweep=sweep,
                         outputs=outputs, description=description, source=self.source,
                         assembly=self.assembly)

    # -- sections ----------------------------------------------------------------------------
    def dynamics(self, value, mech: Mechanism) -> Mechanism:
        """The [dynamics] section (SI units), checked against the model and kept, as plain
        data, in ``mechanism.parameters["dynamics"]`` for kinelab.dynamics."""
        from kinelab.dynamics import DynamicsSetup

        try:
            setup = DynamicsSetup.from_dict(value, where="dynamics")
            setup.check(mech)
        except ModelError as exc:
            for problem in exc.problems:
                field, _, what = problem.partition(": ")
                self.r.fail(field, what)
            return mech
        return dataclasses.replace(mech, parameters={**mech.parameters, "dynamics": setup.to_dict()})

    def notation(self, value, mech: Mechanism) -> Mechanism:
        """The [notation] table: for ``kinelab derive``, the symbol to write instead of each
        one named (``theta_lever = "A"``), kept in ``mechanism.parameters["notation"]``;
        whether each names a symbol of the model's equations is checked by the derivation."""
        if not isinstance(value, Mapping):
            self.r.fail("notation", f"expected a table of symbol = \"symbol to write\", such as "
                        f"theta_lever = \"A\", got {describe(value)}")
            return mech
        table = {}
        for key, symbol in value.items():
            problem = name_problem(symbol)
            if problem:
                self.r.fail(f"notation.{key}", f"{problem} for the symbol, got {describe(symbol)}")
            else:
                table[str(key)] = symbol
        if not table:
            return mech
        return dataclasses.replace(mech, parameters={**mech.parameters, "notation": table})

    def units(self, value) -> Units:
        if value is None:
            return Units()
        t = self.r.table(value, "units", ("length", "angle"), required=("length", "angle"))
        if t is None:
            return Units()
        length = self.r.string(t.get("length", "m"), "units.length", choices=LENGTH_UNITS)
        angle = self.r.string(t.get("angle", "rad"), "units.angle", choices=ANGLE_UNITS)
        return Units(length or "m", angle or "rad")

    def explicit(self, top, units: Units, name, space):
        r = self.r
        ls, dim = units.length_scale, (2 if space == "planar" else 3)
        points: dict[str, tuple[float, ...]] = {}
        raw_points = top.get("points", {})
        point_names = None        # unknown: references to points are not checked
        if not isinstance(raw_points, Mapping):
            r.fail("points", f"expected a table of name = [x, y], got {describe(raw_points)}")
            raw_points = {}
        elif "points" in top:
            point_names = dict.fromkeys(raw_points)
        counts = {k: len(v) if isinstance(v, (list, Mapping)) else 0 for k, v in
                  (("points", raw_points), *((k, top.get(k)) for k in ("links", "joints")))}
        if too_large := size_problems(**counts):      # before any of them is read
            self.fail(too_large)
        for pname, xy in raw_points.items():
            v = r.numbers(xy, f"points.{shown_key(pname)}", dim, scale=ls, what="coordinates",
                          unit=units.length, check=coordinate_problem)
            if v is not None:
                points[pname] = v
        raw_links = list(self.items(top.get("links", []), "links", _LINK, ("name", "points")))
        raw_joints = list(self.items(top.get("joints", []), "joints", _JOINT, ("type", "links")))
        # names first, so that one bad field does not make every reference to it fail too
        taken = {p: f"points.{shown_key(p)}" for p in point_names or ()}
        link_names = self.declare(raw_links, "links", taken, lambda t: t.get("name"))
        joint_names = self.declare(raw_joints, "joints", taken, _joint_name)
        joint_types: dict[str, Any] = {}
        for t in raw_joints:
            if t is not None and isinstance(_joint_name(t), str) and _joint_name(t) in joint_names:
                joint_types.setdefault(_joint_name(t), t.get("type"))
        links = []
        for i, t in enumerate(raw_links):
            where = f"links[{i}]"
            if t is None:
                continue
            lname = r.name(t["name"], f"{where}.name") if "name" in t else None
            pts = r.names(t["points"], f"{where}.points", point_names, "point") if "points" in t else None
            ground = r.boolean(t.get("ground", False), f"{where}.ground")
            mass = self.optional_number(t, "mass", where, positive=True)
            inertia = self.optional_number(t, "inertia", where, scale=ls * ls, positive=True)
            com = t.get("center_of_mass")
            if com is not None:
                com = r.name(com, f"{where}.center_of_mass", pts or (), "point",
                             "the link's points")
            length = self.optional_number(t, "length", where, scale=ls, positive=True,
                                          unit=units.length, check=length_problem)
            local = self.local(t["local"], f"{where}.local", pts or (), ls) if "local" in t else None
            sides = self.sides(t["sides"], f"{where}.sides", units) if "sides" in t else None
            if None in (lname, pts, ground) or any(k in t and v is None for k, v in
                                                   (("local", local), ("sides", sides))):
                continue
            if length is not None and len(pts) < 2:
                r.fail(f"{where}.length", "a link with one point has no length; remove it")
                continue
            link = Link(lname, pts, ground=ground, mass=mass, center_of_mass=com,
                        inertia=inertia, length=length, local=local, sides=sides)
            for why in place_problems(link, points, units):     # lengths in the file's unit
                r.fail("", f"{where}.{why}")
            links.append(link)
        joints = []
        self.raw_joints = raw_joints
        for i, t in enumerate(raw_joints):
            if t is not None:
                j = self.joint(t, f"joints[{i}]", point_names, link_names, units, dim)
                if j is not None:
                    joints.append(j)
        inputs, samples = self.inputs(top.get("inputs", []), joint_types, link_names, units)
        if r.problems:
            self.fail()
        mech = self.build(lambda: Mechanism(
            name=name, points=tuple(Point(n, *xy) for n, xy in points.items()), links=tuple(links),
            joints=tuple(joints), inputs=tuple(inputs), space=space))
        if needs_assembly(mech):
            mech = self.assemble(mech, units)
        if "catalogue" in top and not self.r.problems:
            built = self.catalogue(top["catalogue"], units)
            if built is not None:
                self.check_catalogue(mech, built, units)
                mech = dataclasses.replace(mech, parameters=built.parameters)
        return mech, samples

    def items(self, value, section: str, allowed, required):
        rows = self.r.array(value, section, "tables")
        for i, t in enumerate(rows or []):
            yield self.r.table(t, f"{section}[{i}]", allowed, required=required)

    def declare(self, tables, section: str, taken: dict[str, str], name_of) -> dict[str, None]:
        """The names of a section's entries (a dict, for its fast ``in``), each checked to
        be unique across the file."""
        names: dict[str, None] = {}
        for i, t in enumerate(tables):
            n = name_of(t) if t is not None else None
            if name_problem(n) is not None:       # refused where the name is read
                continue
            if n in taken:
                self.r.fail(f"{section}[{i}].name", f"{shown(n)} is already the name of {taken[n]}; "
                            "names must be unique across points, links and joints")
            else:
                taken[n] = f"{section}[{i}]"
            if n in names:
                continue
            self.where[(section[:-1], n)] = f"{section}[{i}]"
            names[n] = None
        return names

    def optional_number(self, t, key, where, *, scale=1.0, positive=False, unit="", check=None):
        if t.get(key) is None:
            return None
        return self.r.number(t[key], f"{where}.{key}", scale=scale, positive=positive, unit=unit,
                             check=check)

    def joint(self, t, where, point_names, link_names, units: Units, dim: int) -> Joint | None:
        r = self.r
        jtype = r.string(t["type"], f"{where}.type", choices=JOINT_TYPES) if "type" in t else None
        jlinks = (r.names(t["links"], f"{where}.links", link_names, "link", count=2)
                  if "links" in t else None)
        point = t.get("point")
        if point is not None:
            point = r.name(point, f"{where}.point", point_names, "point")
        jname = _joint_name(t)
        if jname is None:
            if (jtype is not None and JOINT_TYPES[jtype].needs_point
                    and not (jtype == "C" and dim == 2)):      # a planar C: a cam, no point
                r.fail(f"{where}.point", f"missing; a joint of type '{jtype}' needs the point where it acts")
            else:
                r.fail(f"{where}.name", "missing; a joint without a point needs a name")
        else:
            jname = r.name(jname, f"{where}.name")
        origin = t.get("origin")
        if origin is not None:
            origin = r.name(origin, f"{where}.origin", point_names, "point")
        axis = self.axis(t.get("axis"), f"{where}.axis", units, dim) if "axis" in t else None
        axis2 = self.axis(t.get("axis2"), f"{where}.axis2", units, dim) if "axis2" in t else None
        pitch = self.optional_number(t, "pitch", where, scale=units.length_scale / units.angle_scale)
        offset = self.optional_number(t, "offset", where, scale=units.length_scale, unit=units.length)
        gear = self.gear_fields(t, where, link_names, units)
        if "segments" in t and gear is not None:
            gear["program"] = self.cam_program(t, where, jlinks, units)
        if None in (jtype, jlinks, jname, gear) or gear.get("program", 0) is None or (
                "point" in t and point is None) or (
                "origin" in t and origin is None) or ("axis" in t and axis is None):
            return None
        return Joint(jname, jtype, jlinks, point=point, axis=axis, origin=origin, axis2=axis2,
                     pitch=pitch, offset=offset, **gear)

    def gear_fields(self, t, where, link_names, units: Units) -> dict[str, Any] | None:
        """A gear joint's fields (``mesh``, ``ratio``, ``radii``, ``teeth``, ``radius``,
        ``carrier``), lengths in SI; None when one is malformed (its problem recorded).  What
        they must be together is the model's check (:mod:`kinelab.model._gears`)."""
        r, ls, out = self.r, units.length_scale, {}
        if "mesh" in t:
            out["mesh"] = r.string(t["mesh"], f"{where}.mesh", choices=GEAR_MESHES)
        if "ratio" in t:
            out["ratio"] = r.number(t["ratio"], f"{where}.ratio", positive=True)
        if "radii" in t:
            out["radii"] = r.numbers(t["radii"], f"{where}.radii", 2, scale=ls,
                                     what="two pitch radii [r_a, r_b]", unit=units.length,
                                     check=length_problem)
        if "teeth" in t:
            v = t["teeth"]
            out["teeth"] = tuple(v) if isinstance(v, list) else v   # checked by the model
        if "radius" in t:
            out["radius"] = r.number(t["radius"], f"{where}.radius", scale=ls, positive=True,
                                     unit=units.length, check=length_problem)
        if "carrier" in t:
            out["carrier"] = r.name(t["carrier"], f"{where}.carrier", link_names, "link")
        return None if any(v is None for v in out.values()) else out

    def cam_program(self, t, where, jlinks, units: Units):
        """A cam joint's ``[[joints.segments]]``, as a cam task's ``[[segments]]``: angles in
        the file's angle unit, lifts in its length unit (a translating follower) or its angle
        unit (an oscillating one: no P joint of the follower on the guide); None when one is
        malformed (its problems recorded)."""
        from kinelab.cams import MotionProgram, read_segments
        follower = jlinks[1] if jlinks else None
        guide = t.get("carrier")
        slides = any(isinstance(u, Mapping) and u.get("type") == "P"
                     and isinstance(u.get("links"), list) and len(u["links"]) == 2
                     and u["links"][1] == follower and guide in (None, u["links"][0])
                     for u in getattr(self, "raw_joints", ()) or ())
        lift_scale = units.length_scale if slides else units.angle_scale
        problems: list[str] = []
        segments = read_segments(t["segments"], units.angle_scale, lift_scale, problems,
                                 f"{where}.segments")
        if not problems:
            try:
                return MotionProgram(segments)
            except ModelError as exc:
                problems = [f"{where}.{p}" for p in exc.problems]
        self.r.problems.extend(problems)
        return None

    def axis(self, value, where, units: Units, dim: int):
        if isinstance(value, (int, float)) and not isinstance(value, bool) and dim == 2:
            a = self.r.number(value, where, scale=units.angle_scale, check=angle_problem)
            return None if a is None else (math.cos(a), math.sin(a))
        v = self.r.numbers(value, where, dim)
        if v is not None and math.hypot(*v) == 0.0:
            self.r.fail(where, "expected a direction, got the zero vector")
            return None
        if v is None and dim == 2:
            self.r.problems[-1] = (f"{where}: expected an angle ({units.angle}) or a direction "
                                   f"[x, y], got {describe(value)}")
        return v

    def inputs(self, value, joint_types: Mapping[str, Any], link_names, units: Units):
        r = self.r
        inputs, samples = [], []
        for i, t in enumerate(self.items(value, "inputs", _INPUT, ())):
            if t is None:
                continue
            where = f"inputs[{i}]"
            if ("joint" in t) == ("links" in t):
                r.fail(where, "expected either joint = \"name\" or links = [\"a\", \"b\"]")
                continue
            joint = links = None
            if "joint" in t:
                joint = r.name(t["joint"], f"{where}.joint", joint_types, "joint")
            else:
                links = r.names(t["links"], f"{where}.links", link_names, "link", count=2)
            slide = joint is not None and joint_types[joint] == "P"
            scale = units.length_scale if slide else units.angle_scale
            unit = units.length if slide else units.angle
            rng = None
            if "range" in t:
                rng = r.numbers(t["range"], f"{where}.range", 2, scale=scale)
                if rng is not None and rng[0] == rng[1]:
                    r.fail(f"{where}.range", f"start and stop are equal ({describe(t['range'][0])} "
                           f"{unit}); give an interval")
                elif rng is not None and (why := range_problem(*rng, angle=not slide)):
                    r.fail(f"{where}.range", f"{why}, got {describe(t['range'])} {unit}")
                    rng = None
            si = "m" if slide else "rad"
            speed = self.optional_number(t, "speed", where, scale=scale, unit=f"{unit}/s",
                                         check=lambda v: rate_problem(v, f"{si}/s"))
            accel = self.optional_number(t, "acceleration", where, scale=scale, unit=f"{unit}/s^2",
                                         check=lambda v: rate_problem(v, f"{si}/s^2"))
            name = t.get("name")
            if name is not None:
                name = r.name(name, f"{where}.name")
            if "samples" in t:
                n = r.integer(t["samples"], f"{where}.samples", low=2, high=MAX_SAMPLES)
                samples.append(n or DEFAULT_SAMPLES)
            else:
                samples.append(DEFAULT_SAMPLES)
            if (joint is None and links is None) or ("range" in t and rng is None):
                continue
            inputs.append(Input(joint=joint, links=links, range=rng, speed=speed or 0.0,
                                acceleration=accel or 0.0, name=name))
        stated = isinstance(value, (list, tuple)) and any(
            isinstance(t, Mapping) and "samples" in t for t in value)
        return inputs, tuple(samples) if stated else ()

    def outputs(self, value, m: Mechanism) -> Outputs:
        r = self.r
        t = r.table(value, "outputs", _OUTPUTS)
        if t is None:
            return Outputs()
        slides = [j.name for j in m.joints if j.type == "P"]
        reportable = dict.fromkeys([*m.link_names, *m.point_names, *slides])
        report = ()
        if "report" in t:
            report = r.names(t["report"], "outputs.report", reportable, "link, point or slide",
                             plural="its links, points and slides") or ()
        pairs = ()
        if "transmission" in t:
            v = t["transmission"]
            if isinstance(v, (list, tuple)) and v and all(isinstance(x, str) for x in v):
                v = [v]
            rows = r.array(v, "outputs.transmission", "pairs of links") or []
            links = dict.fromkeys(m.link_names)
            pairs = tuple(p for k, x in enumerate(rows)
                          if (p := self.pair(x, f"outputs.transmission[{k}]", links)) is not None)
        ratio = None
        if "time_ratio" in t:
            ratio = r.name(t["time_ratio"], "outputs.time_ratio", dict.fromkeys([*m.link_names, *slides]),
                           "link or slide", "its links and slides")
        return Outputs(tuple(report), pairs, ratio)

    def pair(self, value, where: str, links) -> tuple[str, str] | None:
        """Two different links: a transmission angle is between a coupler and an output."""
        pair = self.r.names(value, where, links, "link", count=2)
        if pair is not None and pair[0] == pair[1]:
            self.r.fail(where, f"expected two different links (a coupler and an output), got "
                        f"{shown(pair[0])} twice")
            return None
        return pair

    # -- catalogue ---------------------------------------------------------------------------
    def catalogue(self, value, units: Units):
        """The mechanism the catalogue constructor builds, or None (the problems are recorded)."""
        r = self.r
        if not isinstance(value, Mapping):
            r.fail("catalogue", f"expected a table with kind = \"...\" and parameters, got "
                   f"{describe(value)}")
            return None
        kind = r.string(value.get("kind"), "catalogue.kind", choices=CATALOGUE_KINDS)
        if kind is None:
            return None
        make = getattr(catalogue, kind)
        params = [p for p in inspect.signature(make).parameters if p != "q0"]
        t = r.table(value, "catalogue", ["kind"] + params)
        before = len(r.problems)
        kwargs = {}
        for key, v in (t or {}).items():
            if key == "kind":
                continue
            where = f"catalogue.{key}"
            if key == "branch" and isinstance(v, list):      # one mode per dyad (six-bars)
                kwargs[key] = [r.string(b, f"{where}[{i}]") for i, b in enumerate(v)]
            elif key == "branch":
                kwargs[key] = r.string(v, where)
            elif key == "coupler_point":
                kwargs[key] = r.numbers(v, where, 2, scale=units.length_scale)
            elif key == "points":
                if not isinstance(v, Mapping):
                    r.fail(where, f"expected a table of name = [x, y], got {describe(v)}")
                    continue
                kwargs[key] = {n: r.numbers(xy, f"{where}.{shown_key(n)}", 2,
                                            scale=units.length_scale, what="coordinates")
                               for n, xy in v.items()}
            elif key == "lengths":
                if not isinstance(v, Mapping):
                    r.fail(where, f"expected a table of \"X-Y\" = length, got {describe(v)}")
                    continue
                kwargs[key] = {n: r.number(x, f"{where}.{_toml.toml_key(n)}", positive=True,
                                           scale=units.length_scale, unit=units.length)
                               for n, x in v.items()}
            else:
                kwargs[key] = r.number(v, where, scale=units.length_scale, unit=units.length,
                                       positive=key not in _SIGNED_PARAMETERS)
        for p, sig in inspect.signature(make).parameters.items():
            if sig.default is inspect.Parameter.empty and p not in kwargs:
                r.fail(f"catalogue.{p}", f"missing; a {kind} needs it")
        if len(r.problems) > before or t is None:
            return None
        try:
            return make(**kwargs)
        except ModelError as exc:
            for p in exc.problems:
                p = _file_lengths(p, units)
                base = re.sub(r"[\[._:].*$", "", p)
                if base in params:
                    r.fail("", f"catalogue.{p}")
                else:
                    r.fail("catalogue", p if p.startswith(kind) else f"{kind}: {p}")
        return None

    def from_catalogue(self, top, units: Units, name):
        built = self.catalogue(top["catalogue"], units)
        if built is None:
            self.fail()
        joint_types = {j.name: j.type for j in built.joints}
        inputs, samples = (self.inputs(top["inputs"], joint_types, built.link_names, units)
                           if "inputs" in top else (list(built.inputs), ()))
        if self.r.problems:
            self.fail()
        mech = self.build(lambda: dataclasses.replace(built, name=name, inputs=tuple(inputs)))
        return mech, samples

    def from_spherical(self, top, units: Units, name, space, explicit):
        """A spherical four-bar given by its arcs: the ``[spherical]`` table (arcs ground,
        crank, coupler, rocker in the file's angle unit, ``branch``, optional ``radius``
        of the sketch's sphere), built as a model by SphericalFourBar.to_mechanism."""
        from kinelab.spatial import SphericalFourBar

        r = self.r
        if space != "spherical":
            r.fail("spherical", f"a [spherical] table needs space = \"spherical\", got "
                   f"space = {shown(space)}")
        for k in explicit + (["catalogue"] if "catalogue" in top else []):
            r.fail(k, "a spherical four-bar given by its arcs ([spherical]) has no "
                   f"[{k}]; give the arcs or the joints' axes, not both")
        t = r.table(top["spherical"], "spherical", _SPHERICAL,
                    required=("ground", "crank", "coupler", "rocker"))
        if t is None:
            self.fail()
        arcs, top_deg = {}, 180.0 if units.angle == "deg" else math.pi
        for key, arc in zip(("ground", "crank", "coupler", "rocker"),
                            ("alpha1", "alpha2", "alpha3", "alpha4")):
            if key not in t:
                continue
            v = r.number(t[key], f"spherical.{key}", scale=units.angle_scale)
            if v is not None and not 0.0 < v < math.pi:
                r.fail(f"spherical.{key}", f"expected an arc in (0, {top_deg:g}) "
                       f"{units.angle} (the angle between two joint axes), got "
                       f"{describe(t[key])}")
            elif v is not None:
                arcs[arc] = v
        branch = r.string(t.get("branch", "open"), "spherical.branch",
                          choices=("open", "crossed"))
        radius = 1.0
        if "radius" in t:
            radius = r.number(t["radius"], "spherical.radius", scale=units.length_scale,
                              positive=True, unit=units.length, check=length_problem)
        joint_types = {f"j{n}": "R" for n in ("O2", "A", "B", "O4")}
        inputs, samples = (self.inputs(top["inputs"], joint_types,
                                       ("ground", "crank", "coupler", "rocker"), units)
                           if "inputs" in top else ([], ()))
        if len(inputs) > 1 or any(i.joint != "jO2" for i in inputs):
            r.fail("inputs", "a spherical four-bar has one input, on joint \"jO2\" (the "
                   "crank's joint with the ground)")
        if r.problems:
            self.fail()
        linkage = SphericalFourBar(**arcs, branch=branch)
        inp = inputs[0] if inputs else None
        theta2 = None
        if inp is not None and inp.range is not None:
            start = float(inp.range[0])
            if bool(linkage.positions(start).assembled):
                theta2 = start
        try:
            mech = linkage.to_mechanism(
                theta2, radius=radius, name=name,
                input_range=None if inp is None else inp.range,
                speed=0.0 if inp is None else inp.speed,
                acceleration=0.0 if inp is None else inp.acceleration)
        except KinelabError as exc:
            self.fail([f"spherical: {exc}"])
        return mech, samples

    def check_catalogue(self, m: Mechanism, built: Mechanism, units: Units) -> None:
        kind = built.parameters.get("kind")
        for attr in ("point_names", "link_names", "joint_names"):
            mine, theirs = getattr(m, attr), getattr(built, attr)
            if set(mine) != set(theirs):
                extra = sorted(set(mine) - set(theirs))
                gone = sorted(set(theirs) - set(mine))
                self.r.fail("catalogue", f"the model's {attr.split('_')[0]}s differ from {kind}'s"
                            + (f": {quoted(extra)} not in it" if extra else "")
                            + (f"; {quoted(gone)} missing" if gone else "")
                            + "; fix the names or delete [catalogue]")
                return
        scale = max(1e-300, max(math.dist(a.xy, b.xy) for a in built.points for b in built.points))
        ls = units.length_scale
        for link in m.links:
            pts = link.points
            for a, b in zip(pts, pts[1:] + pts[:1]):
                mine = math.dist(m.point(a).xy, m.point(b).xy)
                theirs = math.dist(built.point(a).xy, built.point(b).xy)
                if abs(mine - theirs) > LENGTH_RTOL * scale:
                    self.r.fail("catalogue", f"the sketch does not match {kind}: link '{link.name}' "
                                f"has {a}-{b} = {mine / ls:.6g} {units.length} in the sketch but "
                                f"{theirs / ls:.6g} {units.length} from the parameters; fix the points "
                                "or the parameters, or delete [catalogue]")
                    return

    # -- whole-model checks --------------------------------------------------------------------
    def build(self, make) -> Mechanism:
        try:
            return make()
        except ModelError as exc:
            self.fail([_locate(p, self.where) for p in exc.problems])

    def assemble(self, m: Mechanism, units: Units) -> Mechanism:
        """The model moved from its sketch to its assembly with its links' lengths
        and places and its slides' offsets; what moved is kept in ``self.assembly``.

        The assembled coordinates are kept to the digits a model file is written with
        (:func:`_rounded`); a sketch already assembled to those digits is taken as it is."""
        try:
            if assembly_miss(m) <= _ASSEMBLED:
                return m
            self.assembly = assemble(m, units=units)
        except AssemblyError as exc:
            self.fail([f"{self.field_of(exc)}: {exc}"])
        except ModelError as exc:
            self.fail([_locate(p, self.where) for p in exc.problems])
        ls = units.length_scale
        done = self.assembly.mechanism
        return dataclasses.replace(done, points=tuple(
            dataclasses.replace(p, x=_rounded(p.x, ls) if ls != 1.0 else p.x,
                                y=_rounded(p.y, ls) if ls != 1.0 else p.y) for p in done.points))

    def field_of(self, exc: AssemblyError) -> str:
        """The field of the file whose dimension a refused assembly names (the one changed
        the most from the sketch): ``links[2].length``, ``links[2].local.P``,
        ``joints[4].offset``; else ``points``."""
        dimension = getattr(exc, "dimension", None) or (("length", exc.link) if exc.link else ())
        kind, name = (dimension[0], dimension[1]) if dimension else ("", "")
        if kind in ("length", "local") and ("link", name) in self.where:
            where = self.where[("link", name)]
            return f"{where}.local.{shown_key(dimension[2])}" if kind == "local" else f"{where}.length"
        if kind == "offset" and ("joint", name) in self.where:
            return f"{self.where[('joint', name)]}.offset"
        if kind == "pivot":
            return f"points.{shown_key(name)}"
        return "points"

    def local(self, value, where: str, pts, scale: float):
        """A link's ``local`` table: point = [along, left], in the file's length unit."""
        if not isinstance(value, Mapping):
            self.r.fail(where, f"expected a table of point = [along, left], got {describe(value)}")
            return None
        out, rest = {}, set(pts[2:])
        for name, v in value.items():
            if name not in rest:
                self.r.fail(f"{where}.{shown_key(name)}", f"expected one of the link's points "
                            f"after its first two ({quoted(pts[2:])}), got {shown(name)}")
                continue
            xy = self.r.numbers(v, f"{where}.{shown_key(name)}", 2, scale=scale,
                                what="a place [along, left]", check=coordinate_problem)
            if xy is not None:
                out[name] = xy
        return out if len(out) == len(value) else None


    def sides(self, value, where: str, units: Units):
        """A link's ``sides`` table: point = {A = distance, B = distance, side = "left"},
        the distances in the file's length unit.  Which points they are, and whether they
        make a triangle, is checked with the link (:func:`kinelab.model.place_problems`)."""
        shape = 'A = distance, B = distance, side = "left" or "right"'
        if not isinstance(value, Mapping):
            self.r.fail(where, f"expected a table of point = {{{shape}}}, got {describe(value)}")
            return None
        out = {}
        for name, spec in value.items():
            field = f"{where}.{shown_key(name)}"
            if not isinstance(spec, Mapping):
                self.r.fail(field, f"expected a table {{{shape}}} of its distances from two "
                            f"points of the link placed before it, got {describe(spec)}")
                continue
            before = len(self.r.problems)
            read = {k: self.r.string(v, f"{field}.side", choices=SIDE_WORDS) if k == "side"
                    else self.r.number(v, f"{field}.{shown_key(k)}", scale=units.length_scale,
                                       positive=True, unit=units.length, check=length_problem)
                    for k, v in spec.items()}
            if len(self.r.problems) == before:
                out[name] = read
        return out if len(out) == len(value) else None


def _file_lengths(problem: str, units: Units) -> str:
    """A catalogue constructor's message (lengths in m) with its lengths in the file's unit."""
    if units.length == "m":
        return problem
    return re.sub(r"(?<![\w.])(-?\d+(?:\.\d*)?(?:e[-+]?\d+)?) m\b",
                  lambda g: f"{float(g.group(1)) / units.length_scale:.6g} {units.length}", problem)


def _joint_name(t: Mapping[str, Any]) -> Any:
    """A joint's name: its ``name``, else ``j`` + its point."""
    if "name" in t:
        return t["name"]
    return f"j{t['point']}" if isinstance(t.get("point"), str) else None


def _locate(problem: str, where: Mapping[tuple[str, str], str]) -> str:
    """Turn the model's "link 'coupler': points: ..." into the file's "links[2].points: ..."."""
    m = re.match(r"^(link|joint|point) '([^']*)': (?:(\w+): )?(.*)$", problem, re.S)
    if not m:
        return problem
    kind, name, fld, rest = m.groups()
    place = (f"points.{shown_key(name)}" if kind == "point"
             else where.get((kind, name), f"{kind}s['{name}']"))
    return f"{place}{'.' + fld if fld else ''}: {rest}"


# ------------------------------------------------------------------------------------------
# writing
# ------------------------------------------------------------------------------------------
def _out(v: float, scale: float) -> float:
    """A value in file units: the shortest digits that read back as exactly ``v`` (SI), so
    that a file written from a model in any unit reads back as the same model."""
    return written(v, scale)


def _rounded(v: float, scale: float) -> float:
    """``v`` (SI) as it reads back from 14 significant digits in file units: an assembled
    sketch keeps the digits a person would write, so that a change-point geometry (a
    parallelogram) stays one."""
    return in_si(Written(f"{v / scale:.14g}"), scale)


def _json_text(data: Any) -> str:
    """JSON text of ``data``, numbers in file units with the digits that read back exactly
    (json writes a float's own repr, so they go through as marked text and are unmarked)."""
    mark = "\ue000kinelab-number\ue000"
    if mark in json.dumps(data, ensure_ascii=False):    # never from a model; but be sure
        return json.dumps(data, indent=2, ensure_ascii=False) + "\n"

    def marked(v):
        if isinstance(v, Written):
            return mark + v.text + mark
        if isinstance(v, Mapping):
            return {k: marked(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return [marked(x) for x in v]
        return v
    text = json.dumps(marked(data), indent=2, ensure_ascii=False)
    return re.sub(f'"{mark}([^"]*){mark}"', r"\1", text) + "\n"


def _catalogue_reads_back(cat: Mapping[str, Any], m: Mechanism, units: Units) -> bool:
    """Whether a ``[catalogue]`` table, read with the model's points, builds the model."""
    parser = _Parser(None, None)
    try:
        built = parser.catalogue(cat, units)
        if built is not None:
            parser.check_catalogue(m, built, units)
    except KinelabError:
        return False
    return built is not None and not parser.r.problems


def _dump(mf: ModelFile) -> dict[str, Any]:
    m, u = mf.mechanism, mf.units
    ls, a_s = u.length_scale, u.angle_scale
    out: dict[str, Any] = {"schema": SCHEMA, "name": m.name}
    if mf.description:
        out["description"] = mf.description
    if m.space != "planar":
        out["space"] = m.space
    if mf.sweep != "together":
        out["sweep"] = mf.sweep
    out["units"] = {"length": u.length, "angle": u.angle}
    out["points"] = {p.name: [_out(c, ls) for c in (p.xy if m.space == "planar" else (p.x, p.y, p.z))]
                     for p in m.points}
    # the model's own plain data (SI), with the fields that carry units scaled to the file's
    data = m.to_dict()
    for d in data["links"]:
        if "inertia" in d:
            d["inertia"] = _out(d["inertia"], ls * ls)
        if "length" in d:
            d["length"] = _out(d["length"], ls)
        if "local" in d:
            d["local"] = {k: [_out(c, ls) for c in v] for k, v in d["local"].items()}
        if "sides" in d:
            d["sides"] = {k: _toml.Inline((r, v if r == "side" else _out(v, ls))
                                          for r, v in spec.items())
                          for k, spec in d["sides"].items()}
    for d in data["joints"]:
        for key in ("axis", "axis2"):
            if key in d:
                d[key] = [float(c) for c in d[key]]
        if "pitch" in d:
            d["pitch"] = _out(d["pitch"], ls / a_s)
        if "offset" in d:
            d["offset"] = _out(d["offset"], ls)
        if "radius" in d:
            d["radius"] = _out(d["radius"], ls)
        if "radii" in d:
            d["radii"] = [_out(v, ls) for v in d["radii"]]
        if "teeth" in d:
            d["teeth"] = list(d["teeth"])
        if "program" in d:
            from kinelab.cams import segments_data
            j = m.joint(d["name"])
            slides = any(x.type == "P" and x.links[1] == j.links[1] for x in m.joints)
            d["segments"] = segments_data(j.program, a_s, ls if slides else a_s)
            del d["program"]
    out["links"], out["joints"] = data["links"], data["joints"]
    for k, (inp, d) in enumerate(zip(m.inputs, data["inputs"])):
        slide = inp.joint is not None and m.joint(inp.joint).type == "P"
        s = ls if slide else a_s
        for key in ("range", "speed", "acceleration"):
            if key in d:
                d[key] = [_out(v, s) for v in d[key]] if key == "range" else _out(d[key], s)
        if mf.samples:
            d["samples"] = mf.samples[k]
    if data["inputs"]:
        out["inputs"] = data["inputs"]
    params = dict(m.parameters)
    dynamics = params.pop("dynamics", None)
    notation = params.pop("notation", None)
    if params.get("kind") in CATALOGUE_KINDS:
        def file_value(v):
            """A catalogue parameter in the file's units: lengths scaled, names kept."""
            if isinstance(v, str):
                return v
            if isinstance(v, Mapping):
                return {n: file_value(x) for n, x in v.items()}
            if isinstance(v, (list, tuple)):
                return [file_value(x) for x in v]
            return _out(float(v), ls)
        cat: dict[str, Any] = {"kind": params.pop("kind")}
        cat.update((key, file_value(v)) for key, v in params.items() if v is not None)
        if _catalogue_reads_back(cat, m, u):
            out["catalogue"] = cat
        # else the points, links and joints alone: a file is written only as it reads back
        # (parameters the catalogue would refuse, a sketch it would not build)
    if mf.outputs:
        o: dict[str, Any] = {}
        if mf.outputs.report:
            o["report"] = list(mf.outputs.report)
        if mf.outputs.transmission:
            o["transmission"] = [list(p) for p in mf.outputs.transmission]
        if mf.outputs.time_ratio:
            o["time_ratio"] = mf.outputs.time_ratio
        out["outputs"] = o
    if dynamics:
        out["dynamics"] = dynamics
    if notation:
        out["notation"] = dict(notation)
    return out


# ------------------------------------------------------------------------------------------
# the short public names
# ------------------------------------------------------------------------------------------
def load(path: str | os.PathLike) -> Mechanism:
    """Read a model file (TOML or JSON) and return its mechanism, in SI units.

    Parameters
    ----------
    path : str or path-like
        A ``.toml`` or ``.json`` file in the format of ``docs/model-format.md``.

    Returns
    -------
    Mechanism

    Raises
    ------
    ModelError
        Every problem of the file at once, one line each, naming the file and the field.

    Examples
    --------
    >>> m = kl.load("examples/crank_rocker.toml")        # written in mm and degrees
    >>> m.point("O4").xy                                  # metres
    (0.3, 0.0)
    """
    return ModelFile.read(path).mechanism


def save(model: Mechanism | ModelFile, path: str | os.PathLike, *,
         units: Units | Mapping[str, str] | None = None) -> Path:
    """Write a mechanism to a model file, TOML or JSON by the suffix of ``path``.

    The sketch (every point's position) is written, so reading the file back gives the
    same mechanism on the same assembly branch; a catalogue mechanism also records its
    kind and parameters under ``[catalogue]``, when they build that mechanism again (a
    flat four-bar the catalogue refuses, parameters without their lengths: the points,
    links and joints alone).  Other entries of ``parameters`` than the catalogue's (and
    the dynamics) have no place in a model file and are not written.

    Parameters
    ----------
    model : Mechanism or ModelFile
    path : str or path-like
        Ends in ``.toml`` or ``.json``; written to a temporary file, then renamed.
    units : Units or mapping, optional
        ``{"length": "mm", "angle": "deg"}``; default: the model file's units, else SI.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> fb = kl.mechanisms.fourbar(ground=0.3, crank=0.1, coupler=0.3, rocker=0.25)
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "fourbar.toml"
    >>> _ = kl.io.save(fb, path, units={"length": "mm", "angle": "deg"})
    >>> kl.load(path).point("O4").xy
    (0.3, 0.0)
    """
    mf = model if isinstance(model, ModelFile) else ModelFile(mechanism=_as_mechanism(model))
    if units is not None:
        mf = dataclasses.replace(mf, units=Units.resolve(units))
    return mf.write(path)


def _as_mechanism(model: Any) -> Mechanism:
    if not isinstance(model, Mechanism):
        raise ModelError(f"model: expected a kinelab Mechanism or ModelFile, got "
                         f"{type(model).__name__}")
    return model


def from_toml(text: str) -> Mechanism:
    """The mechanism of model-file text in TOML (see :func:`load`)."""
    return ModelFile.from_toml(text).mechanism


def to_toml(model: Mechanism, *, units: Units | Mapping[str, str] | None = None) -> str:
    """Model-file text in TOML (see :func:`save`).

    Examples
    --------
    >>> sc = kl.mechanisms.slider_crank(crank=0.05, rod=0.2)
    >>> kl.io.from_toml(kl.io.to_toml(sc)) == sc
    True
    """
    return ModelFile(mechanism=_as_mechanism(model), units=Units.resolve(units)).to_toml()


def from_json(text: str) -> Mechanism:
    """The mechanism of model-file text in JSON."""
    return ModelFile.from_json(text).mechanism


def to_json(model: Mechanism, *, units: Units | Mapping[str, str] | None = None) -> str:
    """Model-file text in JSON."""
    return ModelFile(mechanism=_as_mechanism(model), units=Units.resolve(units)).to_json()
