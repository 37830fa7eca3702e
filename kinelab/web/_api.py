"""What the page asks for, as plain data in and out: each function takes the decoded JSON
body of a request and returns what is sent back.  The routes (``_app``) only decode, call
and encode, so these are the server's whole behaviour and are tested without a browser.

Models travel as the model file's JSON form (``ModelFile.to_dict``), in the file's units;
they are read by the same loader as the command line, so a malformed one raises the same
:class:`~kinelab.errors.ModelError`.  Results go out in the model's units, as the command
line writes them.
"""
from __future__ import annotations

import dataclasses
import json
import math
import threading
from pathlib import Path

import numpy as np

from kinelab import _progress as progress
from kinelab import io, kinematics
from kinelab._deadline import within
from kinelab.errors import AssemblyError, KinelabError, ModelError, describe, quoted, shown
from kinelab.io import ModelFile
from kinelab.io._modelfile import errors_from
from kinelab.io._results import json_ready
from kinelab.kinematics import KinematicSolution, Tracker
from kinelab.kinematics._columns import INPUT_SI_UNITS, column_name
from kinelab.model import is_real
from kinelab.web import _limits

__all__ = ["MAX_SAMPLES", "DEFAULT_SAMPLES", "read_model", "with_page_ranges", "analyze", "study",
           "configuration", "drag", "flip", "catalogue", "example", "load", "save", "derivation",
           "synthesize", "is_search", "MAX_SEARCH_EFFORT", "DERIVE_SECONDS"]

MAX_SAMPLES = 20_000
"""The longest sweep the page may ask for: past it a drawing or a plot shows nothing more,
and the answer would take seconds to send."""
DEFAULT_SAMPLES = 361
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
"""The example models beside the package, in a source checkout (none in an installed
wheel: the catalogue is always there)."""


# -- models ---------------------------------------------------------------------------------
def read_model(body: dict) -> ModelFile:
    """The model of a request: ``body["model"]``, the model file's JSON form, read as
    ``kinelab`` reads a file (``body["source"]``, a file name, names it in messages)."""
    model = body.get("model")
    source = body.get("source")
    if source is not None and not isinstance(source, str):
        raise ModelError(f"source: expected a file name, got {describe(source)}")
    if not isinstance(model, dict):
        raise ModelError(f"model: expected the model file's JSON form (an object), got "
                         f"{describe(model)}")
    return ModelFile.from_dict(model, source=source)


def samples_of(body: dict, mf: ModelFile) -> int | None:
    """The samples a request asks for (``body["samples"]``, else the file's), refused past
    :data:`MAX_SAMPLES` in all."""
    samples = body.get("samples")
    if samples is not None and (isinstance(samples, bool) or not isinstance(samples, int)
                                or not 2 <= samples <= MAX_SAMPLES):
        raise ModelError(f"samples: expected a whole number from 2 to {MAX_SAMPLES:,}, got "
                         f"{describe(samples)}; the page sweeps at most {MAX_SAMPLES:,} samples")
    counts = [samples] * len(mf.mechanism.inputs) if samples else list(mf.samples or ())
    total = (math.prod(counts) if mf.sweep == "grid" else max(counts)) if counts else 0
    if total > MAX_SAMPLES:
        raise ModelError(f"{mf.source or 'model'}: inputs: {total:,} samples asked for; the page "
                         f"sweeps at most {MAX_SAMPLES:,}: ask for fewer samples")
    return samples


def load(body: dict) -> dict:
    """A model file's text (``body["text"]``, TOML or JSON as ``body["format"]`` says, or
    the suffix of ``body["source"]``) read and checked, as its JSON form."""
    text = body.get("text")
    if not isinstance(text, str):
        raise ModelError(f"text: expected the model file's text, got {describe(text)}")
    source = body.get("source") if isinstance(body.get("source"), str) else None
    fmt = body.get("format") or (Path(source).suffix.lstrip(".").lower() if source else "toml")
    if fmt not in ("toml", "json"):
        raise ModelError(f"format: expected one of 'toml', 'json', got {describe(fmt)}")
    parse = ModelFile.from_toml if fmt == "toml" else ModelFile.from_json
    mf = parse(text, source=source, _stem=Path(source).stem if source else None)
    return {"model": mf.to_dict(), "source": source}


def save(body: dict) -> dict:
    """The text of the model file (``body["format"]``: "toml" or "json")."""
    mf = read_model(body)
    fmt = body.get("format", "toml")
    if fmt not in ("toml", "json"):
        raise ModelError(f"format: expected one of 'toml', 'json', got {describe(fmt)}")
    return {"text": mf.to_toml() if fmt == "toml" else mf.to_json()}


def catalogue() -> dict:
    """The example models (in a source checkout) and the catalogue's mechanisms, each with
    a name to ask :func:`example` for."""
    examples = sorted(p.stem for p in EXAMPLES.glob("*.toml")) if EXAMPLES.is_dir() else []
    return {"examples": examples, "catalogue": sorted(_CATALOGUE)}


def example(name: str) -> dict:
    """An example model or a catalogue mechanism, as its JSON form."""
    if name.startswith("catalogue:"):
        kind = name.removeprefix("catalogue:")
        if kind not in _CATALOGUE:
            raise ModelError(f"name: expected one of {quoted(sorted(_CATALOGUE))}, got {shown(kind)}")
        mf = ModelFile.from_dict(_CATALOGUE[kind])
        return {"model": mf.to_dict(), "source": f"{kind}.toml"}
    path = EXAMPLES / f"{name}.toml"
    known = sorted(p.stem for p in EXAMPLES.glob("*.toml")) if EXAMPLES.is_dir() else []
    if name not in known:
        raise ModelError(f"name: expected one of {quoted(known)}, got {shown(name)}")
    mf = ModelFile.read(path)
    return {"model": mf.to_dict(), "source": path.name}


# Each catalogue mechanism, as the smallest model file that builds it (SI).
_CATALOGUE = {
    "fourbar": {"catalogue": {"kind": "fourbar", "ground": 3.0, "crank": 1.0, "coupler": 3.0,
                              "rocker": 2.5, "coupler_point": [1.5, 1.0]}},
    "slider_crank": {"catalogue": {"kind": "slider_crank", "crank": 1.0, "rod": 3.0}},
    "inverted_slider_crank": {"catalogue": {"kind": "inverted_slider_crank", "crank": 1.0,
                                            "ground": 2.0}},
    "slotted_link": {"catalogue": {"kind": "slotted_link", "crank": 1.0, "distance": 2.0}},
    "watt6": {"catalogue": {"kind": "watt6"}},
    "stephenson6": {"catalogue": {"kind": "stephenson6"}},
}
for _kind, _data in _CATALOGUE.items():
    _data.update(schema=1, name=_kind.replace("_", "-"), units={"length": "m", "angle": "deg"})


# -- analysis -------------------------------------------------------------------------------
def analyze(body: dict) -> str:
    """The sweep of ``body["model"]`` over ``body["samples"]`` samples (default the
    file's), as the JSON text ``kinelab analyze MODEL --format json`` writes."""
    mf = read_model(body)
    samples = samples_of(body, mf)
    _limits.check_sweep(mf, samples, "rows", "the answer")
    sol = mf.analyze(samples)
    return io.results_json(sol, units=mf.units)


@dataclasses.dataclass
class _Prepared:
    """A model read, swept and ready for one-sample questions."""

    mf: ModelFile
    sol: KinematicSolution
    tracker: Tracker
    lock: threading.Lock


_PREPARED = _limits.Kept(most=16)


def prepare(body: dict, answer: str = "none") -> _Prepared:
    """The model of a request, read, swept and with a :class:`Tracker`; the last few are
    kept (within the server's cache, in bytes), so that the drags that follow a sweep
    answer at once.  ``answer``: what the request makes of the sweep (see
    :func:`kinelab.web._limits.sweep_cost`), refused before the work if too large."""
    # looked up before the model is read: a drag asks again and again of the same model
    key = json.dumps([body.get("model"), body.get("samples"), body.get("source")], sort_keys=True)
    ready = _PREPARED.get(key)
    if ready is not None and answer == "none":
        return ready
    if ready is not None:         # read and checked when it was kept: the same model, samples
        _limits.check_sweep(ready.mf, body.get("samples"), answer, "the answer")
        return ready
    mf = with_page_ranges(read_model(body))
    samples = samples_of(body, mf)
    _limits.check_sweep(mf, samples, answer, "the answer" if answer != "none" else "the sweep")
    sol = _sweep(mf, samples)
    with errors_from(mf):
        tracker = Tracker(mf.mechanism, at_singular="flag")
    ready = _Prepared(mf, sol, tracker, threading.Lock())
    _PREPARED.put(key, ready, _limits.nbytes(sol) + _limits.nbytes(tracker))
    return ready


def with_page_ranges(mf: ModelFile) -> ModelFile:
    """The model with a range for each of its inputs that has none, when it has several
    (a sweep of several inputs needs every range; the page's drawn inputs come without):
    from the sketch's value, a full turn for an angle, half the sketch's size for a slide.
    A model of one input, or whose inputs all have ranges, comes back as it is."""
    m = mf.mechanism
    if len(m.inputs) < 2 or all(i.range is not None for i in m.inputs):
        return mf
    with errors_from(mf, "inputs"):
        p = kinematics.plan(m)
    xy = np.array([pt.xy for pt in m.points], float)
    size = float(np.max(np.ptp(xy, axis=0))) if len(xy) else 0.0
    data = mf.to_dict()
    u = mf.units
    for k, (inp, kind) in enumerate(zip(m.inputs, p.input_kinds)):
        if inp.range is not None:
            continue
        q0 = float(p.q_sketch[k])
        span = 2 * math.pi if kind == "angle" else 0.5 * size or 1.0
        unit = INPUT_SI_UNITS[kind]
        data["inputs"][k]["range"] = [float(f"{u.convert(v, unit):.12g}") for v in (q0, q0 + span)]
    # the sketch's own assembly (what moved) is still the one to report
    return dataclasses.replace(ModelFile.from_dict(data, source=mf.source), assembly=mf.assembly)


def _sweep(mf: ModelFile, samples: int | None) -> KinematicSolution:
    """The page's sweep of the file's inputs: samples where the loops do not close are
    marked (``unassembled``), not refused, so that an edit that leaves part of the input
    range out of reach still shows the linkage where it does close."""
    q, qd, qdd = mf.sample_inputs(samples)
    with errors_from(mf, "inputs"):
        return kinematics.analyze(mf.mechanism, q, qd, qdd, at_singular="flag",
                                  unreachable="mask")


def _finite(values) -> list:
    """Numbers for JSON: ``None`` where a value is not finite."""
    return json_ready(np.asarray(values, float))


def study(body: dict) -> dict:
    """Everything the page draws and plots of a model's sweep, in the model's units.

    ``model`` is the model as assembled (its JSON form; each of several inputs with a range,
    see :func:`with_page_ranges`); ``columns`` every column of
    ``kinelab analyze`` (``body["columns"]``, a list, narrows them; the points' x and y are
    always there, or those of the points ``body["points"]`` lists), and the transmission
    angles; ``singular`` and ``change_points`` the sample indices where they are;
    ``drawing`` the links, joints and points to draw (and each gear pair's pitch circles,
    see :func:`gear_drawing`, each cam's profile, see :func:`cam_drawing`); ``guides`` each prismatic joint's slide direction at every
    sample (see :func:`guides`), ``turns`` each gear's direction (see :func:`turns`).
    """
    ready = prepare(body, "columns")
    mf, sol = ready.mf, ready.sol
    m, u = mf.mechanism, mf.units
    wanted = body.get("columns")
    if wanted is not None and (not isinstance(wanted, list)
                               or not all(isinstance(w, str) for w in wanted)):
        raise ModelError(f"columns: expected a list of column names, got {describe(wanted)}")
    placed = body.get("points", list(m.point_names))
    if not (isinstance(placed, list) and all(isinstance(p, str) and p in m.point_names for p in placed)):
        raise ModelError(f"points: expected a list of some of {quoted(m.point_names)}, got {describe(placed)}")
    from kinelab.io._summary import _default_pairs, _transmission_values
    pairs = list(mf.outputs.transmission) or _default_pairs(m)
    # the inputs and the points, as sol.columns names them, without the other columns
    kinds = kinematics.plan(m).input_kinds
    inputs = [column_name(n, "q", u.unit(INPUT_SI_UNITS[k])) for n, k in zip(m.input_names, kinds)]
    q = np.reshape(sol.q, (sol.N, -1))
    columns = {n: u.convert(q[:, k], INPUT_SI_UNITS[kind])
               for k, (n, kind) in enumerate(zip(inputs, kinds))}
    placed = [p for p in m.point_names if p in placed]
    rows = [sol.point_item[p] for p in placed]
    xy = u.convert(sol.item_jets([i for r in rows for i in (r, r + 1)])[:, :, 0], "m")
    for k, p in enumerate(placed):
        columns[column_name(p, "x", u.length)] = xy[:, 2 * k]
        columns[column_name(p, "y", u.length)] = xy[:, 2 * k + 1]
    made = {f"{a}-{b}.transmission[{u.angle}]" for a, b in pairs}
    if wanted is None or not set(wanted) <= set(columns) | made:
        every = sol.columns(units=u)
        columns = {n: v for n, v in every.items() if n in columns or (
            n in wanted if wanted is not None else not _point_column(n, m, u))}
    out_columns = {n: _finite(v) for n, v in columns.items()
                   if n not in ("singular", "assembled")}
    for a, b in pairs:
        mu = u.convert(_transmission_values(sol, (a, b)), "rad")
        out_columns[f"{a}-{b}.transmission[{u.angle}]"] = _finite(mu)
    qcol = np.reshape(sol.q, (sol.N, -1))[:, 0]
    change = [{"q": u.convert(c.q, INPUT_SI_UNITS[kinematics.plan(m).input_kinds[0]]),
               "index": int(np.argmin(np.abs(qcol - c.q))), "step": c.step}
              for c in sol.change_points]
    return {
        "model": mf.to_dict(),
        "units": {"length": u.length, "angle": u.angle},
        "inputs": inputs,
        "samples": sol.N,
        "columns": out_columns,
        "singular": np.flatnonzero(sol.singular).tolist(),
        "unassembled": np.flatnonzero(~sol.assembled).tolist(),
        "change_points": change,
        "drawing": _drawing(mf),
        "guides": guides(sol),
        "turns": turns(sol),
        "branches": _branches(mf),
        "moved": {} if mf.assembly is None else {
            k: u.convert(v, "m") for k, v in mf.assembly.moved.items()},
        "switched": [] if mf.assembly is None else list(mf.assembly.switched),
    }


def _point_column(name: str, m, u) -> bool:
    """Whether a column is a point's x or y (``P.x[mm]``)."""
    point, _, rest = name.rpartition(".")
    return point in m.point_names and rest in (f"x[{u.length}]", f"y[{u.length}]")


def _drawing(mf: ModelFile) -> dict:
    """What the canvas draws: links (their points), joints, ground points, traced points,
    gear pairs."""
    m = mf.mechanism
    ground = m.ground.name
    traced = [p for p in io.default_outputs(m) if p in m.point_names]
    return {
        "links": [{"name": link.name, "points": list(link.points), "ground": link.ground}
                  for link in m.links],
        "joints": [{"name": j.name, "type": j.type, "point": j.point, "links": list(j.links),
                    "axis": list(j.axis) if j.axis is not None else None} for j in m.joints],
        "ground_points": list(m.link(ground).points),
        "traced": traced,
        "gears": gear_drawing(mf),
        "cams": cam_drawing(mf),
        "inputs": [{"name": n, "joint": i.joint,
                    "kind": k} for n, i, k in zip(m.input_names, m.inputs,
                                                  kinematics.plan(m).input_kinds)],
    }


def gear_drawing(mf: ModelFile) -> list[dict]:
    """Each gear joint's pitch circles, in the model's length unit: ``{"joint", "mesh",
    "carrier", "gears"}``, ``gears`` its two gears in the joint's order, each ``{"link",
    "centre", "radius"}`` (the point where it turns on the carrier, its pitch radius); a
    rack instead ``{"link", "rack": True, "slide", "point", "radius"}`` (its prismatic
    joint, that joint's point on the rack, and the pinion's pitch radius: its pitch line's
    distance from the pinion's centre).  Each gear turns as ``turns`` says (its link's
    angle); a rack's pitch line runs along its slide, to the right of the axis through the
    pinion's centre (:mod:`kinelab.model._gears`)."""
    from kinelab.model._gears import gear_mesh

    m, u = mf.mechanism, mf.units
    out = []
    for j in m.joints:
        if j.type != "G":
            continue
        g = gear_mesh(m, j)
        if g.mesh == "rack":
            slide = m.joint(g.slide)
            gears = [{"link": g.a, "centre": g.centre_a, "radius": u.convert(g.k, "m")},
                     {"link": g.b, "rack": True, "slide": g.slide, "point": slide.point,
                      "radius": u.convert(g.k, "m")}]
        else:
            if j.radii is not None:
                ra, rb = (float(r) for r in j.radii)
            else:
                # Only the ratio rho = r_b / r_a is given (by ratio or teeth): the pitch circles
                # touch, so the distance d between the axes (fixed on the carrier, taken from
                # the sketch) is r_a + r_b for an external pair and |r_b - r_a| for an internal
                # one (the ring the larger): r_a = d / (1 + rho) or d / |rho - 1|, r_b = rho r_a.
                rho = g.ratio
                d = math.dist(m.point(g.centre_a).xy, m.point(g.centre_b).xy)
                ra = d / (1 + rho) if g.mesh == "external" else d / abs(rho - 1)
                rb = rho * ra
            gears = [{"link": g.a, "centre": g.centre_a, "radius": u.convert(ra, "m")},
                     {"link": g.b, "centre": g.centre_b, "radius": u.convert(rb, "m")}]
        out.append({"joint": j.name, "mesh": g.mesh, "carrier": g.carrier, "gears": gears})
    return out


CAM_SAMPLES = 721          # a cam's profile: every half degree of its turn


def cam_drawing(mf: ModelFile, samples: int = CAM_SAMPLES) -> list[dict]:
    """Each cam joint's cam, in the model's length unit, as the page draws it once a model
    (and turns it with the cam's angle, ``turns``):

    ``{"joint", "cam", "follower", "motion", "centre", "contact", "follower_joint", "kind",
    "base_radius", "profile", "theta"}``: ``centre`` the point the cam turns about (its R
    joint on the guide), ``contact`` the follower's point that touches it (a translating
    follower's P joint's point, its knife-edge; an oscillating follower's point nearest the
    cam's centre other than its pivot), ``profile`` the closed curve ``[[x, y], ...]`` in the
    cam's own frame (its origin the centre, its x axis along the cam's angle ``sol.angle``:
    turned by that angle and carried to the centre it is the curve in the plane), at the
    cam angles relative to the guide ``theta`` (rad, ``samples`` of them from 0 to a turn).

    A model says nothing of a follower's shape, so the follower is a knife-edge at its
    contact point and the cam's profile is its pitch curve, with the base circle the sketch
    implies (the contact point's place where the program's S is 0).  A translating follower
    (``kind`` "profile") by :func:`kinelab.cams.profile` with a knife-edge
    :class:`~kinelab.cams.Follower` at the offset of its line of motion: in the cam's frame
    at relative angle theta the edge is at ``(e, d + S(theta))`` turned back by theta, so
    that ``|profile| = sqrt(e**2 + (d + S)**2)``, ``base + S`` for an in-line follower.  An
    oscillating follower (``kind`` "pitch") turns counterclockwise as S grows (the model's
    sense; :func:`kinelab.cams.profile` turns its arm the other way), so its pitch curve is
    the contact point's path turned back by the cam's angle, computed here the same way.
    A cam the sketch cannot give a profile (a translating follower on the far side of its
    cam's centre, a sketch that does not assemble) has ``profile`` None and ``problem``
    saying why.
    """
    from kinelab.cams import Follower, profile
    from kinelab.model._cams import cam_pair

    m, u = mf.mechanism, mf.units
    cams = [j for j in m.joints if j.type == "C" and j.program is not None]
    if not cams:
        return []
    out = []
    try:
        q0 = np.asarray(kinematics.plan(m).q_sketch, float).reshape(-1)
        sketch = kinematics.analyze(m, float(q0[0]) if len(q0) == 1 else q0)
    except KinelabError as exc:
        sketch, why = None, str(exc)
    for j in cams:
        c = cam_pair(m, j)
        fj = m.joint(c.follower_joint)
        centre = m.joint(c.pivot).point
        if c.motion == "translating":
            contact = fj.point
        else:
            others = [p for p in m.link(c.follower).points if p != fj.point]
            o = np.asarray(m.point(centre).xy)
            contact = min(others, key=lambda p: float(np.hypot(*(np.asarray(m.point(p).xy) - o)))) \
                if others else fj.point
        item = {"joint": j.name, "cam": c.cam, "follower": c.follower, "motion": c.motion,
                "centre": centre, "contact": contact, "follower_joint": fj.name,
                "kind": "profile" if c.motion == "translating" else "pitch",
                "base_radius": None, "profile": None, "theta": None}
        out.append(item)
        if sketch is None:
            item["problem"] = f"the sketch does not assemble: {why}"
            continue
        # everything in the guide's frame at the sketch, about the cam's centre
        tg = 0.0 if c.guide == m.ground.name else float(sketch.angle(c.guide))
        ta = float(sketch.angle(c.cam))
        back = _turn(-tg)
        O = np.reshape(sketch.position(centre), 2)
        P0 = back @ (np.reshape(sketch.position(contact), 2) - O)
        # the cam's frame turns by theta = ta - tg from the guide's: at theta = 0 they agree
        S0 = float(j.program.svaj(np.array([ta - tg])).S[0])
        theta = np.linspace(0.0, 2 * math.pi, samples)
        S = np.reshape(j.program.svaj(theta).S, -1)
        try:
            if c.motion == "translating":
                a = back @ np.reshape(sketch.slide_axes(fj.name), 2)
                a = a / math.hypot(*a)
                along, e = float(P0 @ a), float(P0 @ [a[1], -a[0]])
                d = along - S0                # the edge's place along its line where S = 0
                if not d > 0:
                    raise ModelError("the follower's line of motion points towards the cam's "
                                     "centre: a cam pushes its follower away from it")
                rb = math.hypot(d, e)
                cam = profile(j.program, Follower("knife-edge", "translating", offset=e), rb,
                              theta=theta)
                # profile()'s frame has the follower along +y: the guide's turned by phi
                phi = math.atan2(a[1], a[0]) - math.pi / 2
                curve = cam.profile @ _turn(phi).T
            else:
                A = back @ (np.reshape(sketch.position(fj.point), 2) - O)
                arm = P0 - A
                swing = S - S0             # the arm's turn from the sketch, counterclockwise
                c_, s_ = np.cos(swing), np.sin(swing)
                P = A + np.stack([c_ * arm[0] - s_ * arm[1], s_ * arm[0] + c_ * arm[1]], -1)
                ct, st = np.cos(theta), np.sin(theta)     # turned back by the cam's angle
                curve = np.stack([ct * P[:, 0] + st * P[:, 1], -st * P[:, 0] + ct * P[:, 1]], -1)
                base = A + _turn(-S0) @ arm
                rb = float(math.hypot(*base))
        except KinelabError as exc:
            item["problem"] = str(exc)
            continue
        item.update(base_radius=u.convert(rb, "m"), profile=_finite(u.convert(curve, "m")),
                    theta=_finite(theta))
    return out


def _turn(angle: float) -> np.ndarray:
    """The matrix turning a vector counterclockwise by ``angle`` (rad)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def _branches(mf: ModelFile) -> list[dict]:
    """The dyads whose assembly mode the page can switch (RRR groups: the middle joint
    reflected across the line of the outer two)."""
    return [{"step": s.label, "points": list(s.points), "links": list(s.links)}
            for s in kinematics.plan(mf.mechanism).steps if s.kind == "RRR" and len(s.points) == 3]


# -- one configuration ------------------------------------------------------------------
def _input(body: dict, mf: ModelFile, key: str = "q"):
    """The input(s) of a request, in the model's units, to SI (one float, or (M,))."""
    value = body.get(key)
    kinds = kinematics.plan(mf.mechanism).input_kinds
    values = value if isinstance(value, list) else [value]
    if len(values) != len(kinds) or not all(is_real(v) for v in values):
        raise ModelError(f"{key}: expected {len(kinds)} finite number(s), one per input "
                         f"({quoted(mf.mechanism.input_names)}), got {describe(value)}")
    u = mf.units
    si = [float(v) * (u.angle_scale if k == "angle" else u.length_scale)
          for v, k in zip(values, kinds)]
    return si[0] if len(si) == 1 else np.array(si)


_PARTS = ("values", "centres", "guides", "turns", "polygons")


def _parts(body: dict) -> tuple[str, ...]:
    parts = body.get("parts", list(_PARTS))
    if not (isinstance(parts, list) and all(isinstance(p, str) and p in _PARTS for p in parts)):
        raise ModelError(f"parts: expected a list of some of {quoted(_PARTS)}, got {describe(parts)}")
    return tuple(parts)


def configuration(body: dict) -> dict:
    """One configuration (``body["q"]``, in the model's units), solved by the tracker: every
    point's place, every column's value, the instant centres, each prismatic joint's slide
    direction, each gear's direction (``turns``) and, where kinelab draws them, the velocity and acceleration polygons
    (``body["parts"]`` narrows them, as for :func:`drag`)."""
    ready = prepare(body)
    q = _input(body, ready.mf)
    return _configuration(ready, q, _parts(body))


def _configuration(ready: _Prepared, q, parts: tuple[str, ...] = _PARTS) -> dict:
    mf, tracker = ready.mf, ready.tracker
    m, u = mf.mechanism, mf.units
    M = len(m.inputs)
    qd = float(m.inputs[0].speed) if M == 1 else np.array([i.speed for i in m.inputs])
    qdd = float(m.inputs[0].acceleration) if M == 1 else np.array([i.acceleration for i in m.inputs])
    with ready.lock, errors_from(mf, "q"):
        sol = tracker(q, qd, qdd)
    rows = [sol.point_item[p] for p in m.point_names]
    xy = u.convert(sol.item_jets([i for r in rows for i in (r, r + 1)])[0, :, 0], "m")
    out = {
        "q": [u.convert(v, k) for v, k in zip(np.atleast_1d(q).tolist(),
                                              [INPUT_SI_UNITS[k] for k in tracker.plan.input_kinds])],
        "points": dict(zip(m.point_names, _finite(np.reshape(xy, (-1, 2))))),
        "singular": bool(sol.singular[0]),
    }
    if "values" in parts:
        out["values"] = {n: (bool(v[0]) if n in ("singular", "assembled") else
                             (float(v[0]) if math.isfinite(float(v[0])) else None))
                         for n, v in sol.columns(units=u).items()}
    if "centres" in parts:
        out["centres"] = _centres(sol, u)
    if "guides" in parts:
        out["guides"] = {j: a[0] for j, a in guides(sol).items()}
    if "turns" in parts:
        out["turns"] = {g: a[0] for g, a in turns(sol).items()}
    if "polygons" in parts:
        out["polygons"] = polygons(sol, u)
    return out


def guides(sol: KinematicSolution) -> dict[str, list]:
    """Each prismatic joint's slide direction (a unit vector, turning with its guide link)
    at every sample: ``{joint: [[ux, uy], ...]}``, None where the loops do not close."""
    m = sol.mechanism
    return {j.name: _finite(np.reshape(sol.slide_axes(j.name), (-1, 2)))
            for j in m.joints if j.type == "P" and j.name in sol.slide_item}


def turns(sol: KinematicSolution) -> dict[str, list]:
    """Each gear's direction (a unit vector at its link's angle, ``sol.angle``) at every
    sample, for the gears of the model's gear joints (a rack has none: it moves with its
    slide) and the cams of its cam joints (their first link): ``{link: [[cos, sin], ...]}``,
    None where the loops do not close."""
    m = sol.mechanism
    links = dict.fromkeys(link for j in m.joints if j.type == "G"
                          for link in (j.links if (j.mesh or "external") != "rack" else j.links[:1]))
    links.update(dict.fromkeys(j.links[0] for j in m.joints if j.type == "C"))
    out = {}
    for link in links:
        theta = np.reshape(sol.angle(link), -1)
        out[link] = _finite(np.stack([np.cos(theta), np.sin(theta)], axis=-1))
    return out


def _centres(sol: KinematicSolution, u) -> list[dict]:
    if bool(sol.singular[0]):
        return []
    try:
        centres = kinematics.instant_centers(sol)
    except KinelabError:
        return []
    out = []
    for (a, b), c in centres.items():
        at_inf = bool(np.reshape(c.at_infinity, -1)[0])
        out.append({"links": [a, b], "at_infinity": at_inf,
                    "position": None if at_inf else _finite(u.convert(np.reshape(c.position, 2), "m")),
                    "direction": _finite(np.reshape(c.direction, 2)) if at_inf else None})
    return out


def polygons(sol: KinematicSolution, u) -> dict | None:
    """The velocity and acceleration polygons of a one-configuration solution, by
    :func:`kinelab.kinematics.velocity_polygon` and
    :func:`~kinelab.kinematics.acceleration_polygon`, in the model's units (length/s,
    length/s^2); None where they are not defined (a singular configuration).

    Each polygon: ``vertices`` (every point, from the pole o), ``coincident`` (the guide's
    point under each slider's point), ``sides`` (point, reference, kind "difference" or
    "relative", link or joint, the vector and, in the acceleration polygon, its named parts:
    normal and tangential, or Coriolis and sliding) and ``images`` (each moving link's
    points, in the order of its image).
    """
    if bool(sol.singular[0]):
        return None
    try:
        return {"velocity": _polygon_data(kinematics.velocity_polygon(sol), u, "m/s"),
                "acceleration": _polygon_data(kinematics.acceleration_polygon(sol), u, "m/s^2")}
    except KinelabError:
        return None


def _polygon_data(polygon, u, unit: str) -> dict:
    def xy(v) -> list:
        return _finite(u.convert(np.reshape(v, 2), unit))
    return {
        "vertices": {p: xy(v) for p, v in polygon.vertices.items()},
        "coincident": {p: xy(v) for p, v in polygon.coincident.items()},
        "sides": [{"point": side.point, "reference": side.reference, "kind": side.kind,
                   "link": side.link, "vector": xy(side.vector),
                   "parts": {k: xy(v) for k, v in side.parts.items()}}
                  for side in polygon.sides.values()],
        "images": {name: list(image.points) for name, image in polygon.images.items()},
    }


def drag(body: dict) -> dict:
    """The configuration where point ``body["point"]`` comes nearest to ``body["to"]`` (x, y
    in the model's units) on its path: the linkage follows the pointer, lengths kept.

    One input: the nearest sample of the sweep, then the nearest place on the point's path
    between its neighbours, found on the path's second-order expansion about the sample
    (its velocity and acceleration coefficients, K and L, which the sweep holds), and solved
    there by the tracker: one solve a drag.  Several inputs: the nearest sample.

    ``body["parts"]`` (optional) narrows the answer to the points, the input and those
    named of ``"values"``, ``"centres"``, ``"guides"``, ``"turns"`` and ``"polygons"`` (by default
    all): a drag asks for what it redraws."""
    ready = prepare(body)
    mf, sol = ready.mf, ready.sol
    m = mf.mechanism
    point = body.get("point")
    if point not in m.point_names:
        raise ModelError(f"point: expected one of {quoted(m.point_names)}, got {describe(point)}")
    to = body.get("to")
    if not (isinstance(to, list) and len(to) == 2 and all(is_real(v) for v in to)):
        raise ModelError(f"to: expected [x, y], two finite numbers, got {describe(to)}")
    parts = _parts(body)
    target = np.array(to, float) * mf.units.length_scale
    path = sol.position(point)
    gap = np.hypot(*(path - target).T)
    gap[~sol.assembled] = np.inf
    i = int(np.argmin(gap))
    if len(m.inputs) > 1:
        return _configuration(ready, np.asarray(sol.q[i], float), parts)
    q, sample = _nearest_on_path(sol, point, target, i), float(sol.q[i, 0])
    answer = _configuration(ready, q, parts)
    xy = answer["points"][point]
    near = math.dist(xy, to) * mf.units.length_scale if None not in xy else math.inf
    if q != sample and not near <= gap[i] * (1 + 1e-9):
        # the expansion misled (near a cusp or a fold of the path): the sample itself
        answer = _configuration(ready, sample, parts)
    return answer


def _nearest_on_path(sol: KinematicSolution, point: str, target: np.ndarray, i: int) -> float:
    """The input (SI) near sample ``i`` where ``point`` comes nearest to ``target``, on the
    path's expansion P(q_i + h) = P + K h + L h^2 / 2, h between the neighbouring samples
    (those that close): the real roots of d|P(q_i + h) - target|^2 / dh, a cubic in h."""
    q = sol.q[:, 0]
    lo = q[i - 1] - q[i] if i > 0 and sol.assembled[i - 1] else 0.0
    hi = q[i + 1] - q[i] if i + 1 < sol.N and sol.assembled[i + 1] else 0.0
    row = sol.point_item[point]
    jets = sol.item_jets([row, row + 1])[i]          # (2, 3): P, K, L of x and y
    P, K, L = jets[:, 0], jets[:, 1], jets[:, 2]
    if not np.all(np.isfinite(jets)) or lo == hi:
        return float(q[i])                            # singular here: no expansion
    d = P - target
    # d/dh |d + K h + L h^2 / 2|^2 / 2 = (d + K h + L h^2 / 2) . (K + L h)
    cubic = [0.5 * L @ L, 1.5 * K @ L, K @ K + d @ L, d @ K]
    candidates = [lo, hi, 0.0] + [r.real for r in np.roots(cubic)
                                  if abs(r.imag) <= 1e-12 * (1 + abs(r.real))
                                  and min(lo, hi) < r.real < max(lo, hi)]
    h = min(candidates, key=lambda h: float(np.hypot(*(d + K * h + 0.5 * L * h * h))))
    return float(q[i] + h)


# -- editing --------------------------------------------------------------------------------
def flip(body: dict) -> dict:
    """The model with the assembly mode of one RRR dyad switched (``body["step"]``, as
    :func:`study` lists it): its middle joint reflected across the line of its outer two,
    the points of its two links carried along, every length kept."""
    mf = read_model(body)
    m = mf.mechanism
    steps = {b["step"]: b for b in _branches(mf)}
    step = body.get("step")
    if not isinstance(step, (str, int)) or isinstance(step, bool) or step not in steps:
        raise ModelError(f"step: expected one of {quoted(list(steps)) if steps else 'none (no RRR dyad)'}, "
                         f"got {describe(step)}")
    X, Y, Z = steps[step]["points"]
    xy = {p.name: np.array(p.xy) for p in m.points}
    d = (xy[Z] - xy[X]) / np.linalg.norm(xy[Z] - xy[X])
    r = xy[Y] - xy[X]
    mirrored = xy[X] + 2 * np.dot(r, d) * d - r
    moved = {}
    for link in steps[step]["links"]:
        pivot = X if X in m.link(link).points else Z
        turn = _angle(mirrored - xy[pivot]) - _angle(xy[Y] - xy[pivot])
        c, s = math.cos(turn), math.sin(turn)
        for p in m.link(link).points:
            if p not in (X, Z):
                v = xy[p] - xy[pivot]
                moved[p] = xy[pivot] + np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])
    data = _explicit(mf)
    ls = mf.units.length_scale
    for p, v in moved.items():
        data["points"][p] = [float(f"{c / ls:.14g}") for c in v]
    try:
        new = ModelFile.from_dict(data, source=mf.source)
    except AssemblyError as exc:
        raise AssemblyError(f"the other assembly mode of {step} does not close: {exc}") from None
    return {"model": new.to_dict()}


def _angle(v) -> float:
    return math.atan2(v[1], v[0])


def _explicit(mf: ModelFile) -> dict:
    """The model's JSON form with every link's length (its first two points) and the local
    places of its other points written out (but for those given by their sides), and without
    a catalogue section: a form whose points may be moved while every link keeps its shape."""
    data = mf.to_dict()
    data.pop("catalogue", None)
    xy = {p: np.array(v, float) for p, v in data["points"].items()}
    for link in data["links"]:
        pts = link["points"]
        if len(pts) < 2:
            continue
        a, b = xy[pts[0]], xy[pts[1]]
        length = float(np.linalg.norm(b - a))
        link.setdefault("length", float(f"{length:.14g}"))
        if len(pts) > 2 and length > 0:
            e = (b - a) / length
            local = dict(link.get("local", {}))
            for p in (p for p in pts[2:] if p not in link.get("sides", {})):
                v = xy[p] - a
                local.setdefault(p, [float(f"{np.dot(v, e):.14g}"),
                                     float(f"{e[0] * v[1] - e[1] * v[0]:.14g}")])
            if local:
                link["local"] = local
    return data


# -- synthesis ------------------------------------------------------------------------------
MAX_SEARCH_EFFORT = 4 * (3 * 300 * 15 * 180 * 10)
"""The most work a path-generation search may ask of the server (runs x maxiter x popsize x
samples x target points): four times the default search of ten points (a round's work grows
with each); the command line has no such cap."""
_SEARCH_DEFAULTS = {"runs": 3, "maxiter": 300, "popsize": 15, "samples": 180}


def is_search(body: dict) -> bool:
    """Whether a synthesis request is a path-generation search (seconds to minutes of
    work; the other tasks are solved in closed form, at once)."""
    task = body.get("task")
    return isinstance(task, dict) and task.get("task") == "path"


def synthesize(body: dict) -> dict:
    """A synthesis task (``body["task"]``: a task file's content as plain data, as
    ``kinelab synth`` reads it; ``body["source"]``, a file name, names it in messages)
    solved: the summary ``kinelab synth TASK --json`` prints, in the task's units, and
    ``models``, each linkage as the JSON form of the model file ``kinelab synth`` writes
    for it (``solution_<i>.toml``)."""
    source = body.get("source")
    if source is not None and not isinstance(source, str):
        raise ModelError(f"source: expected a file name, got {describe(source)}")
    task = io.read_task(body.get("task"), source=source,
                        name=Path(source).stem if source else "task")
    if task.kind == "path":
        effort = len(task.targets) * math.prod(task.search.get(k, v)
                                               for k, v in _SEARCH_DEFAULTS.items())
        if effort > MAX_SEARCH_EFFORT:
            raise ModelError(f"search: runs x maxiter x popsize x samples x points is {effort:,}; "
                             f"the page searches at most {MAX_SEARCH_EFFORT:,} (four times the "
                             "default search of ten points): ask for less, or run kinelab synth",
                             source=source)
        # each round evaluates 32 designs per unit of popsize at every sample, at once
        designs, samples = 32 * task.search.get("popsize", 15), task.search.get("samples", 180)
        _limits.require(16 * 8 * designs * samples, f"search: the coupler curves of {designs:,} "
                        f"designs at {samples:,} crank angles a round", "ask for a smaller "
                        "popsize or fewer samples")
    solutions, extra = io.solve_task(task)
    summary = io.task_summary(task, solutions, extra)
    summary["models"] = [ModelFile(mechanism=s.model, units=task.units).to_dict()
                         for s in solutions]
    return summary


# -- derivation -----------------------------------------------------------------------------
DERIVE_SECONDS = 30.0
"""The longest the server works on one derivation, its document and its MathML together."""


def derivation(body: dict) -> dict:
    """The derivation of the model in the notes' notation (``body["lang"]``: "en" or
    "pt"): its sections, each a title and equations in presentation MathML, and the whole
    document as Markdown; stopped after :data:`DERIVE_SECONDS` (422)."""
    import sympy.printing.mathml  # noqa: F401 -- imported before the clock starts

    from kinelab.derive import LANGUAGES
    from kinelab.derive._derivation import time_limit_message

    mf = read_model(body)
    lang = body.get("lang", "en")
    if lang not in LANGUAGES:
        raise ModelError(f"lang: expected one of {quoted(LANGUAGES)}, got {describe(lang)}")
    return within(DERIVE_SECONDS, _derivation, mf, lang,
                  message=time_limit_message(mf.mechanism, None, DERIVE_SECONDS, "it"))


def _derivation(mf: ModelFile, lang: str) -> dict:
    import sympy as sp
    from sympy.printing.mathml import mathml

    from kinelab.derive import derive
    from kinelab.derive._words import WORDS

    with errors_from(mf):
        with progress.part(0.0, 0.65):
            d = derive(mf.mechanism, lang, time_limit=None)
        progress.report("the document", 0.65)
        markdown = d.to_markdown(time_limit=None)
    progress.report("MathML", 0.98)
    words = WORDS[lang]

    def math(label: str, expr) -> dict:
        body = mathml(expr, printer="presentation")
        return {"label": label, "mathml": f'<math display="block"><mrow><mi>{label}</mi>'
                                          f'<mo>=</mo>{body}</mrow></math>'}

    def equation(expr) -> dict:
        return {"label": "", "mathml": '<math display="block"><mrow>'
                + mathml(expr, printer="presentation") + "<mo>=</mo><mn>0</mn></mrow></math>"}

    large = {"en": "too large to read here; see the document", "pt":
             "grande demais para ler aqui; veja o documento"}[lang]
    sections = [
        {"title": words["position"], "items": [
            math("q", sp.Matrix(d.q).T), math("S", sp.Matrix(d.S).T), equation(d.Phi)]},
        {"title": words["jacobian"], "items": [
            math("J", d.J), math("Q", d.Q),
            math("det J", d.det_J) if d.readable.get("det_J", True)
            else {"label": "det J", "text": large}]},
        {"title": words["coefficients"], "items": [
            math("K", d.K) if d.readable.get("K", True) else {"label": "K", "text": large},
            math("L", d.L) if d.readable.get("L", True) else {"label": "L", "text": large}]},
    ]
    return {"sections": sections, "markdown": markdown, "lang": lang}
