"""Results as named columns, each in chosen units and named ``item.quantity[unit]``.

The one place that names export columns: :meth:`KinematicSolution.columns` and the
dynamics results build theirs here, so a CSV, a DataFrame, a JSON file and the printed
configuration of ``kinelab analyze --at`` all say the same thing.
"""
from __future__ import annotations

import os
import re
from collections.abc import Mapping

import numpy as np

from kinelab import _memory as memory
from kinelab.errors import ModelError, shown_path
from kinelab.model import Units

__all__ = ["column_name", "Columns", "TableExport", "solution_columns", "table_width",
           "INPUT_SI_UNITS"]

INPUT_SI_UNITS = {"angle": "rad", "slide": "m"}      # by kind of input
_SPACE = re.compile(r"\s")


def column_name(item: str, quantity: str = "", unit: str = "") -> str:
    """``item.quantity[unit]``, whitespace in the names replaced by ``_``.

    >>> column_name("crank angle", "q", "deg"), column_name("det_J")
    ('crank_angle.q[deg]', 'det_J')
    """
    name = _SPACE.sub("_", f"{item}.{quantity}" if quantity else item)
    return f"{name}[{unit}]" if unit else name


class Columns(dict):
    """Named (N,) columns, filled with SI values and converted to ``units`` on the way in.

    A second item whose name gives the same column (``"crank angle"`` and ``"crank_angle"``)
    is refused rather than written over.
    """

    def __init__(self, units: Units):
        super().__init__()
        self.units = units
        self._items: dict[str, str] = {}

    def add(self, item: str, quantity: str, si_unit: str | None, values, *,
            convert: bool = True) -> None:
        """Add the SI ``values`` of ``item.quantity``, converted from ``si_unit`` (a length,
        angle or time unit in SI spelling); ``convert=False`` keeps values and unit as they
        are (N, N*m, J, W), and ``si_unit`` None writes no unit."""
        convert = convert and si_unit is not None
        unit = self.units.unit(si_unit) if convert else (si_unit or "")
        name = column_name(item, quantity, unit)
        if name in self:
            raise ModelError(f"columns: '{self._items[name]}' and '{item}' both give the column "
                             f"'{name}' (whitespace becomes '_' in column names); rename one")
        self._items[name] = item
        self[name] = self.units.convert(values, si_unit) if convert else values

    def add_inputs(self, names, kinds, q, qd, qdd) -> None:
        """Each input's q, qd and qdd ((N, M) arrays), in rad or m by its kind."""
        for k, (name, kind) in enumerate(zip(names, kinds)):
            u = INPUT_SI_UNITS[kind]
            self.add(name, "q", u, q[:, k])
            self.add(name, "qd", f"{u}/s", qd[:, k])
            self.add(name, "qdd", f"{u}/s^2", qdd[:, k])


class TableExport:
    """``to_dataframe`` and ``to_csv`` of a result whose ``columns(degrees=, units=)`` gives
    its named (N,) columns."""

    def columns(self, degrees: bool = False, *,
                units: Units | Mapping[str, str] | None = None) -> dict[str, np.ndarray]:
        raise NotImplementedError    # pragma: no cover

    def to_dataframe(self, degrees: bool = False, *,
                     units: Units | Mapping[str, str] | None = None):
        """A pandas DataFrame with one row per sample and the columns of :meth:`columns`."""
        import pandas as pd
        return pd.DataFrame(self.columns(degrees=degrees, units=units))

    def to_csv(self, path: str | os.PathLike, degrees: bool = False, *,
               units: Units | Mapping[str, str] | None = None) -> None:
        """Write :meth:`columns` as CSV (to a temporary file, then renamed)."""
        from kinelab._files import write_csv
        other = {".parquet": "Parquet", ".json": "JSON", ".xlsx": "Excel", ".toml": "TOML"}
        kind = other.get(os.path.splitext(os.fspath(path))[1].lower()) if isinstance(
            path, (str, os.PathLike)) else None
        if kind:
            raise ModelError(f"path: {shown_path(path)} names a {kind} file, and to_csv writes "
                             "CSV; give a .csv name, or write other formats with "
                             "kinelab.io.write_results")
        write_csv(self.columns(degrees=degrees, units=units), path)


def table_width(p) -> int:
    """The columns of the table of a sweep by plan ``p`` (:func:`solution_columns`), known
    before the sweep: one more ("assembled") when some samples do not close."""
    M = len(p.input_kinds)
    per_item = 3 + M + M * M            # value, rates, K and L
    return 3 * M + (len(p.link_item) + len(p.slide_item) + 2 * len(p.point_item)) * per_item + 3


def solution_columns(sol, units: Units) -> Columns:
    """Every result of a :class:`KinematicSolution` as columns (see its ``columns``)."""
    width = table_width(sol.plan) + 1
    memory.require(8 * width * sol.N, f"a table of {sol.N:,} rows and {width:,} columns",
                   "export fewer samples, or a part of the sweep at a time")
    cols = Columns(units)
    names, M = sol.input_names, sol.M
    in_si = [INPUT_SI_UNITS[k] for k in sol.plan.input_kinds]
    cols.add_inputs(names, sol.plan.input_kinds, sol.q, sol.qd, sol.qdd)

    def jet(item):
        return sol.item_jets([item])[:, 0]

    def rate(item):
        return sol.item_rates([item])[:, 0]

    def coefficients(label, item, si):
        j = jet(item)
        for a, ua in enumerate(in_si):
            tag = f".{names[a]}" if M > 1 else ""
            cols.add(label, f"K{tag}", f"{si}/{ua}", j[:, 1 + a])
            for b, ub in enumerate(in_si):
                tag2 = f".{names[a]}.{names[b]}" if M > 1 else ""
                cols.add(label, f"L{tag2}", f"{si}/({ua}*{ub})", j[:, 1 + M + a * M + b])

    for link, i in sol.link_item.items():
        cols.add(link, "angle", "rad", jet(i)[:, 0])
        cols.add(link, "omega", "rad/s", rate(i)[:, 0])
        cols.add(link, "alpha", "rad/s^2", rate(i)[:, 1])
        coefficients(link, i, "rad")
    for joint, i in sol.slide_item.items():
        cols.add(joint, "slide", "m", jet(i)[:, 0])
        cols.add(joint, "slide_velocity", "m/s", rate(i)[:, 0])
        cols.add(joint, "slide_acceleration", "m/s^2", rate(i)[:, 1])
        coefficients(joint, i, "m")
    for point, i in sol.point_item.items():
        for prefix, si, part in (("", "m", lambda d: jet(i + d)[:, 0]),
                                 ("v", "m/s", lambda d: rate(i + d)[:, 0]),
                                 ("a", "m/s^2", lambda d: rate(i + d)[:, 1])):
            for d, ax in enumerate("xy"):
                cols.add(point, prefix + ax, si, part(d))
        for d, ax in enumerate("xy"):
            coefficients(f"{point}.{ax}", i + d, "m")
    cols.add("det_J", "", None, sol.det_J)
    cols.add("singularity", "", None, sol.singularity)
    cols.add("singular", "", None, sol.singular)
    if not np.all(sol.assembled):
        cols.add("assembled", "", None, sol.assembled)
    return cols
