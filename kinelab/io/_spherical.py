"""The table of a spherical four-bar's sweep (``kinelab analyze`` of a model with
``space = "spherical"``): named columns in the units asked for."""
from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from kinelab._files import atomic_write, write_csv
from kinelab.errors import ModelError
from kinelab.model import Units

__all__ = ["spherical_columns", "write_spherical_results"]


def spherical_columns(sol, units: Units | None = None) -> dict[str, np.ndarray]:
    """The columns of a :class:`~kinelab.spatial.SphericalFourBarSolution`, each named
    ``item.quantity[unit]`` as the planar table's: the crank's angle and rates (the input),
    the coupler's and rocker's angles, rates, K and L, the unit axes of A and B, and the
    ``assembled`` and ``singular`` flags (1 or 0).

    Examples
    --------
    >>> m = kl.spatial.SphericalFourBar(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9)
    >>> cols = kl.io._spherical.spherical_columns(m.analyze([0.0, 0.5], 1.0),
    ...                                           kl.io.Units("mm", "deg"))
    >>> list(cols)[:4]
    ['crank.angle[deg]', 'crank.omega[deg/s]', 'crank.alpha[deg/s^2]', 'coupler.angle[deg]']
    """
    u = units or Units()
    cols: dict[str, np.ndarray] = {}

    def put(name, values, si_unit):
        cols[f"{name}[{u.unit(si_unit)}]"] = np.asarray(u.convert(np.atleast_1d(values),
                                                                  si_unit), float)
    put("crank.angle", sol.theta2, "rad")
    put("crank.omega", sol.theta2_dot, "rad/s")
    put("crank.alpha", sol.theta2_ddot, "rad/s^2")
    for link, k in (("coupler", "3"), ("rocker", "4")):
        put(f"{link}.angle", getattr(sol, f"theta{k}"), "rad")
        put(f"{link}.omega", getattr(sol, f"omega{k}"), "rad/s")
        put(f"{link}.alpha", getattr(sol, f"alpha{k}"), "rad/s^2")
        put(f"{link}.K", getattr(sol, f"K{k}"), "rad/rad")
        put(f"{link}.L", getattr(sol, f"L{k}"), "rad/rad^2")
    for point in ("A", "B"):
        axis = np.atleast_2d(getattr(sol, f"u_{point}"))
        for i, c in enumerate("xyz"):
            cols[f"{point}.u{c}[-]"] = axis[:, i]
    cols["assembled"] = np.atleast_1d(sol.assembled).astype(float)
    cols["singular"] = np.atleast_1d(sol.singular).astype(float)
    return cols


def write_spherical_results(sol, path: str | os.PathLike, *, format: str = "csv",
                            units: Units | None = None) -> Path:
    """Write the table of :func:`spherical_columns` as CSV or JSON (``{"columns": [...],
    "data": [[...], ...]}``, NaN as null), atomically."""
    cols = spherical_columns(sol, units)
    if format == "csv":
        return write_csv(cols, path)
    if format != "json":
        raise ModelError(f"--format: a spherical four-bar's table is written as 'csv' or "
                         f"'json', got {format!r}")
    names = list(cols)
    rows = np.column_stack([cols[n] for n in names]).tolist()
    data = {"columns": names,
            "data": [[None if v != v else v for v in row] for row in rows]}
    return atomic_write(path, lambda f: f.write(json.dumps(data) + "\n"))
