"""A cam task: what a task file for ``kinelab cam`` says (its format is in docs/cams.md), as
data in SI, and its solution."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinelab.cams._dynamics import FollowerForces, follower_forces
from kinelab.cams._profile import (FOLLOWER_MOTIONS, FOLLOWER_TYPES, CamProfile, Follower,
                                   profile, smallest_base_circle)
from kinelab.cams._program import KINDS, LAW_NAMES, MotionProgram, Segment
from kinelab.errors import ModelError, describe, expected_one_of, quoted, suggest
from kinelab.model import ANGLE_UNITS, LENGTH_UNITS, Units

__all__ = ["CamTask", "CamSolution", "read_cam_task", "solve_cam_task", "read_segments",
           "segments_data"]

_TOP = ("name", "units", "cam", "follower", "segments", "dynamics")
_CAM = ("speed", "samples", "allow_discontinuous")
_FOLLOWER = ("type", "motion", "offset", "roller_radius", "pivot_distance", "arm_length",
             "base_circle", "pressure_angle", "min_radius")
_SEGMENT = ("kind", "law", "from", "to", "lift", "start", "end")
_DYNAMICS = ("mass", "inertia", "stiffness", "preload", "damping", "external", "margin")
# the follower's train in SI: translating (N, m) or oscillating (N m, rad)
_DYNAMICS_UNITS = {
    "translating": {"mass": "kg", "stiffness": "N/m", "preload": "N", "damping": "N s/m",
                    "external": "N", "margin": "N"},
    "oscillating": {"inertia": "kg m^2", "stiffness": "N m/rad", "preload": "N m",
                    "damping": "N m s/rad", "external": "N m", "margin": "N m"},
}
_ORDERS = {"S": 0, "V": 1, "A": 2, "J": 3}
MAX_SAMPLES = 100_000


@dataclass(frozen=True)
class CamTask:
    """A cam task in SI: its motion program, follower, base circle (a radius, or None for the
    smallest meeting ``pressure_angle``, or for a flat face ``min_radius``), the cam's speed
    (rad/s) and the samples over a turn; ``dynamics``, when the task has a ``[dynamics]``
    table, holds the follower train's ``mass``, ``stiffness``, ``preload``, ``damping``,
    ``external`` and ``margin`` in SI (the keywords of :func:`follower_forces`, ``margin``
    apart)."""
    name: str
    units: Units
    program: MotionProgram
    follower: Follower
    base_circle: float | None
    pressure_angle: float | None
    min_radius: float
    speed: float
    samples: int
    dynamics: dict | None = None


@dataclass(frozen=True)
class CamSolution:
    """A solved cam task: the profile and whether its base circle is the smallest; with a
    ``[dynamics]`` table, the follower's contact force, jump check and shaft torque at the
    profile's samples."""
    task: CamTask
    cam: CamProfile
    smallest: bool
    forces: FollowerForces | None = None


def _unknown(table: dict, known: tuple, where: str) -> list[str]:
    return [f"{where}{k}: unknown key{suggest(k, known)}; the keys are {quoted(known)}"
            for k in table if k not in known]


def _number(table, key, where, problems, *, default=None, positive=False, at_least=None):
    v = table.get(key, default)
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        problems.append(f"{where}{key}: expected a finite number, got {describe(v)}")
        return None
    if positive and not v > 0:
        problems.append(f"{where}{key}: expected a number above 0, got {v:.6g}")
        return None
    if at_least is not None and v < at_least:
        problems.append(f"{where}{key}: expected at least {at_least:g}, got {v:.6g}")
        return None
    return float(v)


def read_cam_task(data, *, source: str | None = None, name: str = "cam") -> CamTask:
    """A cam task given as plain data (what its TOML file reads as), in SI.

    Raises
    ------
    ModelError
        Every problem of the task at once, each naming its field, with ``source`` (the
        file) before them.

    Examples
    --------
    >>> task = kl.cams.read_cam_task({
    ...     "units": {"length": "mm", "angle": "deg"}, "cam": {"speed": 360},
    ...     "follower": {"type": "roller", "roller_radius": 10, "base_circle": 40},
    ...     "segments": [{"kind": "rise", "law": "cycloidal", "from": 0, "to": 180, "lift": 20},
    ...                  {"kind": "return", "law": "cycloidal", "from": 180, "to": 360,
    ...                   "lift": 20}]})
    >>> task.base_circle, round(task.speed, 6), task.program.segments[0].lift
    (0.04, 6.283185, 0.02)
    """
    problems: list[str] = []

    def fail():
        raise ModelError(problems, source=source)
    if not isinstance(data, dict):
        problems.append(f"task: expected a table of the task's sections, got {describe(data)}")
        fail()
    problems += _unknown(data, _TOP, "")
    units_table = data.get("units", {})
    if not isinstance(units_table, dict):
        problems.append(f"units: expected a table, got {describe(units_table)}")
        units_table = {}
    problems += _unknown(units_table, ("length", "angle"), "units.")
    try:
        units = Units(units_table.get("length", "m"), units_table.get("angle", "rad"))
    except ModelError as exc:
        problems += list(exc.problems)
        units = Units()
    ls, ang = LENGTH_UNITS[units.length], ANGLE_UNITS[units.angle]
    task_name = data.get("name", name)
    if not isinstance(task_name, str):
        problems.append(f"name: expected text, got {describe(task_name)}")
        task_name = name

    cam = data.get("cam", {})
    if not isinstance(cam, dict):
        problems.append(f"cam: expected a table, got {describe(cam)}")
        cam = {}
    problems += _unknown(cam, _CAM, "cam.")
    speed = _number(cam, "speed", "cam.", problems, positive=True)
    if "speed" not in cam:
        problems.append("cam.speed: missing; give the cam's speed, in the task's angle unit per "
                        "second")
    samples = cam.get("samples", 721)
    if isinstance(samples, bool) or not isinstance(samples, int) or not 9 <= samples <= MAX_SAMPLES:
        problems.append(f"cam.samples: expected a whole number from 9 to {MAX_SAMPLES:,}, got "
                        f"{describe(samples)}")
        samples = 721
    allow = cam.get("allow_discontinuous", False)
    if not isinstance(allow, bool):
        problems.append(f"cam.allow_discontinuous: expected true or false, got {describe(allow)}")
        allow = False

    fol = data.get("follower")
    if not isinstance(fol, dict):
        problems.append(f"follower: expected a table (type, base_circle, ...), got {describe(fol)}")
        fol = {}
    problems += _unknown(fol, _FOLLOWER, "follower.")
    ftype = fol.get("type", "")
    if ftype not in FOLLOWER_TYPES:
        problems.append(f"follower.type: {expected_one_of(ftype, FOLLOWER_TYPES)}")
    motion = fol.get("motion", "translating")
    if motion not in FOLLOWER_MOTIONS:
        problems.append(f"follower.motion: {expected_one_of(motion, FOLLOWER_MOTIONS)}")
    lengths = {k: _number(fol, k, "follower.", problems, default=0.0)
               for k in ("offset", "roller_radius", "pivot_distance", "arm_length")}
    lengths = {k: (v or 0.0) * ls for k, v in lengths.items()}
    base = fol.get("base_circle")
    smallest = base == "smallest"
    if base is None:
        problems.append('follower.base_circle: missing; give its radius, or "smallest"')
    elif not smallest:
        base = _number(fol, "base_circle", "follower.", problems, positive=True)
        if base is None and isinstance(fol.get("base_circle"), str):
            problems[-1] = (f'follower.base_circle: expected a radius or "smallest", got '
                            f'{describe(fol["base_circle"])}')
        base = None if base is None else base * ls
    phi = _number(fol, "pressure_angle", "follower.", problems, positive=True)
    phi = None if phi is None else phi * ang
    if phi is not None and not phi < math.pi / 2:
        problems.append(f"follower.pressure_angle: expected less than 90 deg, got "
                        f"{math.degrees(phi):.6g} deg")
    if smallest and ftype != "flat-faced" and phi is None and "pressure_angle" not in fol:
        problems.append('follower.pressure_angle: missing; a "smallest" base circle for a '
                        f"{ftype or 'roller'} follower is the smallest meeting the largest "
                        "pressure angle: give it")
    min_radius = _number(fol, "min_radius", "follower.", problems, at_least=0.0)
    follower = None
    if ftype in FOLLOWER_TYPES and motion in FOLLOWER_MOTIONS:
        try:
            follower = Follower(ftype, motion, **lengths)
        except ModelError as exc:
            problems += list(exc.problems)

    lift_scale = ang if motion == "oscillating" else ls
    segments = read_segments(data.get("segments"), ang, lift_scale, problems)
    dynamics = _dynamics(data, motion, problems)
    program = None
    if segments and not problems:
        try:
            program = MotionProgram(segments, allow_discontinuous=allow)
        except ModelError as exc:
            problems += list(exc.problems)
    if problems:
        fail()
    return CamTask(task_name, units, program, follower, None if smallest else base, phi,
                   (min_radius * ls) if min_radius is not None else 0.05 * program.lift
                   * (1.0 if motion == "translating" else follower.pivot_distance),
                   speed * ang, samples, dynamics)


def read_segments(raw, ang: float, lift_scale: float, problems: list, where: str = "segments"
                  ) -> list[Segment]:
    """The ``[[segments]]`` tables of a cam task or of a model file's cam joint (kind, law,
    from, to, lift; start and end for a polynomial law), in SI: angles times ``ang``, lifts
    times ``lift_scale`` (a length's or, for an oscillating follower, an angle's).  Each
    problem is appended to ``problems``, naming its field under ``where``."""
    segments = []
    if not isinstance(raw, list) or not raw:
        problems.append(f"{where}: expected [[segments]] tables (kind, law, from, to, lift) "
                        f"covering one turn, got {describe(raw)}")
        raw = []
    for i, seg in enumerate(raw):
        at = f"{where}[{i}]."
        if not isinstance(seg, dict):
            problems.append(f"{where}[{i}]: expected a table, got {describe(seg)}")
            continue
        problems += _unknown(seg, _SEGMENT, at)
        kind = seg.get("kind", "")
        if kind not in KINDS:
            problems.append(f"{at}kind: {expected_one_of(kind, KINDS)}")
            continue
        law = seg.get("law", "")
        if kind != "dwell" and law not in LAW_NAMES:
            problems.append(f"{at}law: {expected_one_of(law, LAW_NAMES)}")
            continue
        a = _number(seg, "from", at, problems)
        b = _number(seg, "to", at, problems)
        for k in ("from", "to"):
            if k not in seg:
                problems.append(f"{at}{k}: missing; give the cam angle where it "
                                f"{'begins' if k == 'from' else 'ends'}")
        lift = _number(seg, "lift", at, problems, default=0.0)
        if kind != "dwell" and law != "polynomial" and "lift" not in seg:
            problems.append(f"{at}lift: missing; give the {kind}'s travel")
        if a is None or b is None or lift is None:
            continue
        conds = []
        if law == "polynomial" and kind != "dwell":
            for end_key, x in (("start", a), ("end", b)):
                table = seg.get(end_key, {})
                if not isinstance(table, dict):
                    problems.append(f"{at}{end_key}: expected a table such as "
                                    f"{{S = 0, V = 0, A = 0}}, got {describe(table)}")
                    continue
                problems += _unknown(table, tuple(_ORDERS), f"{at}{end_key}.")
                for q, order in _ORDERS.items():
                    v = _number(table, q, f"{at}{end_key}.", problems)
                    if v is not None:
                        conds.append((x * ang, order, v * lift_scale / ang ** order))
        elif "start" in seg or "end" in seg:
            problems.append(f"{at}: start and end (boundary conditions) belong to a "
                            "polynomial law; leave them out or make the law 'polynomial'")
        segments.append(Segment(kind, a * ang, b * ang, lift * lift_scale,
                                law if kind != "dwell" else "", tuple(conds)))
    return segments


def segments_data(program: MotionProgram, ang: float, lift_scale: float) -> list[dict]:
    """The ``[[segments]]`` tables of a program in a file's units (the inverse of
    :func:`read_segments`)."""
    out = []
    for s in program.segments:
        d = {"kind": s.kind, "from": s.start / ang, "to": s.end / ang}
        if s.kind != "dwell":
            d["law"] = s.law
            if s.law != "polynomial":
                d["lift"] = s.lift / lift_scale
            for end_key, x in (("start", s.start), ("end", s.end)):
                ends = {q: v * ang ** o / lift_scale for x0, o, v in s.conditions
                        for q, oq in _ORDERS.items() if oq == o and abs(x0 - x) <= 1e-12}
                if ends:
                    d[end_key] = ends
        out.append(d)
    return out


def _dynamics(data: dict, motion: str, problems: list) -> dict | None:
    """The ``[dynamics]`` table in SI (its numbers already are), or None without one."""
    if "dynamics" not in data:
        return None
    table = data["dynamics"]
    if not isinstance(table, dict):
        problems.append(f"dynamics: expected a table (mass, stiffness, preload, ...), got "
                        f"{describe(table)}")
        return None
    problems += _unknown(table, _DYNAMICS, "dynamics.")
    units = _DYNAMICS_UNITS.get(motion, _DYNAMICS_UNITS["translating"])
    inertial = "inertia" if motion == "oscillating" else "mass"
    other = "mass" if inertial == "inertia" else "inertia"
    if other in table:
        problems.append(f"dynamics.{other}: a {motion} follower takes its {inertial} ("
                        f"{units[inertial]}{', about its pivot' if inertial == 'inertia' else ''})"
                        f"; give {inertial} instead")
    out = {}
    # a key misspelt, or mass for inertia, is said once: not again as the key missing
    meant = {other: inertial} if other in table else {}
    meant.update({k: k2 for k in table if k not in _DYNAMICS for k2 in _DYNAMICS
                  if f"'{k2}'" in suggest(k, _DYNAMICS)})
    for key in (inertial, "stiffness", "preload"):
        if key not in table and key not in meant.values():
            problems.append(f"dynamics.{key}: missing; give the follower train's {key}, in "
                            f"{units[key]}")
    n = len(problems)
    out["mass"] = _number(table, inertial, "dynamics.", problems, positive=True)
    for key in ("stiffness", "preload", "damping", "margin"):
        out[key] = _number(table, key, "dynamics.", problems, at_least=0.0,
                           default=None if key in ("stiffness", "preload") else 0.0)
    out["external"] = _number(table, "external", "dynamics.", problems, default=0.0)
    return out if len(problems) == n and None not in out.values() else None


def solve_cam_task(task: CamTask, *, source: str | None = None) -> CamSolution:
    """The profile of a cam task, with its base circle (the smallest when asked).

    Raises
    ------
    ModelError
        A base circle too small (a pressure angle over the limit, cusps of a flat face, a
        follower that cannot reach it), or a roller larger than the pitch curve's convex
        radius of curvature (undercutting): each says what to change.
    """
    f = task.follower
    try:
        rb = task.base_circle
        if rb is None:
            rb = smallest_base_circle(task.program, f, task.pressure_angle,
                                      min_radius=task.min_radius)
        cam = profile(task.program, f, rb, samples=task.samples)
        _check(task, cam)
        forces = None
        if task.dynamics is not None:
            kw = {k: v for k, v in task.dynamics.items() if k != "margin"}
            forces = follower_forces(task.program, speed=task.speed, motion=f.motion,
                                     theta=cam.theta, **kw)
    except ModelError as exc:
        raise ModelError(exc.problems, source=source) from None
    return CamSolution(task, cam, task.base_circle is None, forces)


def _check(task: CamTask, cam: CamProfile) -> None:
    u = task.units
    ls = LENGTH_UNITS[u.length]
    deg = math.degrees
    if task.pressure_angle is not None and not task.follower.flat:
        phi, at = cam.largest_pressure_angle
        if abs(phi) > task.pressure_angle * (1 + 1e-6):
            best = smallest_base_circle(task.program, task.follower, task.pressure_angle)
            raise ModelError(
                f"follower.base_circle: too small: the pressure angle reaches {deg(abs(phi)):.4g} deg "
                f"at {deg(at):.4g} deg, over the limit of {deg(task.pressure_angle):.4g} deg; the "
                f"smallest base circle within it is {best / ls:.6g} {u.length} (or \"smallest\")")
    if cam.undercut.any():
        k = int(np.argmax(cam.undercut))
        at = deg(cam.theta[k])
        if task.follower.flat:
            raise ModelError(
                f"follower.base_circle: too small: the profile has a cusp (Rb + S + S'' = "
                f"{cam.profile_radius.min() / ls:.4g} {u.length} <= 0) near {at:.4g} deg; make "
                f"the base circle larger than {(cam.base_radius - cam.profile_radius.min()) / ls:.6g}"
                f" {u.length}")
        rho = float(cam.pitch_radius[cam.undercut].min())
        raise ModelError(
            f"follower.roller_radius: the roller ({task.follower.roller_radius / ls:.6g} "
            f"{u.length}) is larger than the pitch curve's radius of curvature ({rho / ls:.4g} "
            f"{u.length} near {at:.4g} deg): the profile would be undercut; use a smaller "
            "roller or a larger base circle")
