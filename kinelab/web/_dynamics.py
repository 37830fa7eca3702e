"""The page's *forces* tab: the inverse dynamics of the model's sweep, computed as
``kinelab dynamics`` computes it (:meth:`kinelab.io.ModelFile.inverse_dynamics`, with the
model's mass data and its ``[dynamics]`` section), its table's columns as that command
writes them, and what the drawing needs to show the forces as arrows.
"""
from __future__ import annotations

import json
import tempfile
from pathlib import Path

import numpy as np
from starlette.responses import Response

from kinelab._files import safe_name
from kinelab.errors import ModelError, describe, quoted
from kinelab.io._modelfile import errors_from
from kinelab.io._results import json_ready
from kinelab.kinematics._columns import column_name
from kinelab.web import _api, _limits

__all__ = ["dynamics", "MAX_VALUES", "MAX_WORK"]

MAX_VALUES = 5_000_000
"""The most values (samples x columns) of the table, as ``kinelab dynamics`` writes at most."""

MAX_WORK = 3e10
"""The most arithmetic the free-body equations of a sweep may ask of the server (samples x
unknowns^3 / 3, about ten seconds): a linkage of 200 links has some 600 unknowns per sample,
so at most about 250 samples."""

FORMATS = ("json", "csv")


def dynamics(body: dict):
    """The inverse dynamics of ``body["model"]`` over its sweep (``body["samples"]``, default
    the file's): ``body["format"]`` "json" (default) gives the columns and what to draw as
    JSON text; "csv" the table ``kinelab dynamics`` writes, as a download."""
    fmt = body.get("format", "json")
    if not isinstance(fmt, str) or fmt not in FORMATS:
        raise ModelError(f"format: expected one of {quoted(FORMATS)}, got {describe(fmt)}")
    mf = _api.read_model(body)
    samples = _api.samples_of(body, mf)
    _check(mf, samples)
    with errors_from(mf):
        res = mf.inverse_dynamics(samples)
    units = mf.units
    if fmt == "csv":
        name = f"{safe_name(mf.mechanism.name)}_dynamics.csv"
        with tempfile.TemporaryDirectory(prefix="kinelab-web-") as folder:
            path = Path(folder) / "dynamics.csv"
            res.to_csv(path, units=units)
            content = path.read_bytes()
        from kinelab.web._export import attachment
        return Response(content, media_type="text/csv",
                        headers={"Content-Disposition": attachment(name)})
    columns = res.columns(units=units)
    m = mf.mechanism
    kinds = list(zip(res.input_names, res.input_kinds))
    reactions = [{"joint": j.name, "type": j.type, "point": j.point, "links": list(j.links),
                  "x": column_name(j.name, "reaction.x", "N"),
                  "y": column_name(j.name, "reaction.y", "N"),
                  "moment": column_name(j.name, "reaction_moment", "N*m") if j.type == "P"
                  else None} for j in m.joints] if not res.reactions_refused else []
    answer = {
        "units": {"length": units.length, "angle": units.angle},
        "samples": res.N,
        "columns": {n: json_ready(np.asarray(v, float)) for n, v in columns.items()},
        "inputs": [column_name(n, "q", units.angle if k == "angle" else units.length)
                   for n, k in kinds],
        "efforts": [column_name(n, *(("torque", "N*m") if k == "angle" else ("force", "N")))
                    for n, k in kinds],
        "input_joints": [{"name": n, "kind": k, "joint": i.joint,
                          "links": list(m.joint(i.joint).links if i.joint else i.links)}
                         for (n, k), i in zip(kinds, m.inputs)],
        "reactions": reactions,
        "reactions_unique": bool(res.reactions_unique),
        "reactions_refused": res.reactions_refused,     # why there are none (a rocking cam follower)
        "shaking": None if res.reactions_refused else {
            "x": "shaking_force.x[N]", "y": "shaking_force.y[N]",
            "moment": "shaking_moment[N*m]", "at": m.ground.points[0] if m.ground.points else None},
        "singular": np.flatnonzero(res.singular).tolist(),
        "loads": _loads(mf, res),
        "file": f"{safe_name(m.name)}_dynamics.csv",
    }
    return json.dumps(answer, allow_nan=False)


def _check(mf, samples: int | None) -> None:
    """Refuse, before the work, a table or a free-body system larger than the server makes,
    and reserve the memory of the rest."""
    from kinelab.dynamics._inverse import table_width
    m = mf.mechanism
    rows, width = mf.sample_count(samples), table_width(m)
    if rows * width > MAX_VALUES:
        raise _limits.TooLarge(f"samples: a table of {rows:,} samples x {width} columns is "
                               f"{rows * width:,} values; the page computes at most "
                               f"{MAX_VALUES:,}: ask for at most {MAX_VALUES // width:,} samples")
    equations = 3 * (len(m.links) - 1)
    unknowns = 2 * len(m.joints) + len(m.inputs)
    work = rows * equations * equations * unknowns / 3
    if work > MAX_WORK:
        most = max(int(MAX_WORK // (equations * equations * unknowns / 3)), 1)
        raise _limits.TooLarge(f"samples: the free-body equations of {rows:,} samples of "
                               f"{len(m.links)} links ({equations} equations in {unknowns} "
                               f"unknowns each) are more than the page solves; ask for at most "
                               f"{most:,} samples, or run kinelab dynamics")
    engine = _limits.sweep_cost(mf, samples, "none")[0]
    system = 4 * 8 * rows * equations * unknowns        # the matrices, a copy, the solver's
    table = rows * width * (2 * 8 + 3 * 25 + 32)        # columns, their lists, their text
    _limits.require(engine + system + table, f"the forces ({rows:,} samples x {width} "
                    "columns)", "ask for fewer samples")


def _loads(mf, res) -> dict:
    """The loads at every sample, to draw: gravity (m/s^2), each point force (N, in the
    ground frame), each torque (N m), each spring's and damper's tension (N, positive
    pulling its ends together)."""
    from kinelab.dynamics._terms import build_system, evaluate
    m = mf.mechanism
    loads, masses = mf.dynamics_setup()
    with errors_from(mf), np.errstate(over="ignore", invalid="ignore"):
        terms = evaluate(build_system(m, loads, masses), res.kinematics, res.t)
    pairs = list(loads.springs) + list(loads.dampers)
    return {
        "gravity": list(loads.gravity),
        "forces": [{"point": f.point, "link": f.link, "x": json_ready(terms.forces[:, i, 0]),
                    "y": json_ready(terms.forces[:, i, 1])}
                   for i, f in enumerate(loads.forces)],
        "torques": [{"link": t.link, "reacting": t.reacting,
                     "values": json_ready(terms.torques[:, i])}
                    for i, t in enumerate(loads.torques)],
        "springs": [{"points": list(s.points), "kind": "spring" if k < len(loads.springs)
                     else "damper", "tension": json_ready(terms.tensions[:, k])}
                    for k, s in enumerate(pairs)],
    }
