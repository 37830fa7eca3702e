"""Tables of designs: one row per design, one column per parameter of a family.

A table is a pandas DataFrame, a mapping of column name to values, or a 2-D array whose
columns are the family's parameters in order; :func:`grid`, :func:`random` and
:func:`sobol` generate one from parameter ranges.
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Mapping

import numpy as np

from kinelab import _memory as memory
from kinelab.errors import MemoryBudgetError, ModelError, describe, expected_one_of, shown
from kinelab.model import MAX_LENGTH, MIN_LENGTH, length_problem, real_array
from kinelab.solvers._arguments import finite, number, reals
from kinelab.solvers._arguments import seed as check_seed

__all__ = ["grid", "random", "sobol", "DesignTable"]


def _ranges(ranges: Mapping[str, object], what: str) -> dict[str, tuple[float, float]]:
    if not ranges:
        raise ModelError(f"{what}: expected parameter ranges, e.g. crank=(0.5, 1.5), got none")
    out = {}
    for name, r in ranges.items():
        if not isinstance(r, (tuple, list, np.ndarray)) or len(r) != 2:
            raise ModelError(f"{name}: expected a range (low, high), got {describe(r)}")
        lo, hi = (number(f"{name}: range", v) for v in r)
        if not lo <= hi:
            raise ModelError(f"{name}: expected a finite range with low <= high, got ({lo:g}, {hi:g})")
        if max(abs(lo), abs(hi)) > MAX_LENGTH:
            # a family's parameters are lengths and coordinates: no design lies beyond
            raise ModelError(f"{name}: expected a range within {MAX_LENGTH:g} m of 0 (a design's "
                             f"lengths and coordinates), got ({lo:g}, {hi:g})")
        out[name] = (lo, hi)
    return out


def seed_of(seed: object) -> int | None:
    """A seed of numpy's generators: None (fresh entropy) or a whole number from 0."""
    return check_seed(seed, none=True)


def real_values(name: str, values: object) -> np.ndarray:
    """``values`` as a float array (whole numbers of any length that floats hold too), else a
    ModelError naming ``name``: never True as 1.0, "3" as 3.0 or a complex number's real part."""
    a = real_array(values)
    if a is None:
        given = values.tolist() if hasattr(values, "tolist") else values
        reals(name, given)      # raises, saying what is wrong
        raise ModelError(f"{name}: expected real numbers, got {describe(given)}")
    return a


def _count(n, what: str) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ModelError(f"{what}: expected a whole number >= 1, got {describe(n)}")
    return int(n)


def _many(n: int) -> str:
    """A count as a message shows it: in full, or to 3 digits past a quadrillion (a grid's
    product of counts may have more digits than a float, or a str, can hold)."""
    if n < 10 ** 15:
        return f"{n:,}"
    e = int(math.log10(n))
    return f"{n // 10 ** (e - 2) / 100:.3g}e+{e}"


def _fits(rows: int, columns: int, what: str) -> None:
    """Refuse a generated table beyond the memory budget (its draws, the scaled table and
    pandas' copy of it)."""
    nbytes, what, instead = (3 * 8 * rows * columns, f"{what} of {_many(rows)} designs",
                             "generate fewer designs, or study them in several tables")
    if nbytes > 10 ** 300:      # more than a float holds: no estimate to show
        raise MemoryBudgetError(f"{what} would take more bytes than a float can count, far beyond "
                                f"the memory budget; {instead}")
    memory.require(nbytes, what, instead)


def grid(**axes) -> "pandas.DataFrame":
    """Every combination of the values of each parameter (the first varies slowest).

    Each axis is a list of values, or ``(low, high, count)`` for evenly spaced ones.  A grid
    whose table (the product of the counts) is beyond :func:`kinelab.memory_budget` is
    refused before any axis is built.

    Examples
    --------
    >>> kl.sweep.grid(crank=[1.0, 2.0], rocker=(2.0, 3.0, 3)).shape
    (6, 2)
    """
    import pandas

    if not axes:
        raise ModelError("grid: expected at least one parameter, e.g. crank=(0.5, 1.5, 11)")
    spaced, values = {}, {}
    for name, axis in axes.items():
        if isinstance(axis, tuple) and len(axis) == 3:
            lo, hi = _ranges({name: axis[:2]}, "grid")[name]
            spaced[name] = (lo, hi, _count(axis[2], f"{name}: count"))
        else:
            if axis is None or isinstance(axis, (str, bytes, Mapping)):
                raise ModelError(f"{name}: expected values or (low, high, count), got "
                                 f"{describe(axis)}")
            v = finite(name, real_values(name, axis)).ravel()
            if v.size and np.abs(v).max() > MAX_LENGTH:
                raise ModelError(f"{name}: expected values within {MAX_LENGTH:g} m of 0 (a "
                                 f"design's lengths and coordinates), got {describe(axis)}")
            if v.size == 0:
                raise ModelError(f"{name}: expected values or (low, high, count), got none")
            values[name] = v
    counts = [spaced[n][2] if n in spaced else len(values[n]) for n in axes]
    _fits(math.prod(counts), len(axes), "a grid")
    values = {n: np.linspace(*spaced[n]) if n in spaced else values[n] for n in axes}
    mesh = np.meshgrid(*values.values(), indexing="ij")
    return pandas.DataFrame({name: m.ravel() for name, m in zip(values, mesh)})


def _scaled(unit: np.ndarray, ranges: dict[str, tuple[float, float]]) -> "pandas.DataFrame":
    import pandas

    lo = np.array([r[0] for r in ranges.values()])
    hi = np.array([r[1] for r in ranges.values()])
    return pandas.DataFrame(lo + unit * (hi - lo), columns=list(ranges))


def random(n: int, *, seed: int | None = 0, **ranges) -> "pandas.DataFrame":
    """``n`` designs drawn uniformly in the given ranges (numpy's default generator).

    Examples
    --------
    >>> t = kl.sweep.random(5, crank=(0.5, 1.0), rocker=(2.0, 3.0))
    >>> t.shape, bool(t["crank"].between(0.5, 1.0).all())
    ((5, 2), True)
    """
    ranges = _ranges(ranges, "random")
    n = _count(n, "n")
    _fits(n, len(ranges), "a random table")
    unit = np.random.default_rng(seed_of(seed)).random((n, len(ranges)))
    return _scaled(unit, ranges)


def sobol(n: int, *, seed: int | None = 0, **ranges) -> "pandas.DataFrame":
    """``n`` designs of a scrambled Sobol sequence in the given ranges (scipy.stats.qmc):
    they fill the ranges more evenly than random ones.  ``n`` a power of 2 keeps the
    sequence's balance; any other ``n`` is the first ``n`` points of the sequence, as
    asked (without scipy's warning that they are not balanced).

    Examples
    --------
    >>> kl.sweep.sobol(8, crank=(0.5, 1.0), rocker=(2.0, 3.0)).shape
    (8, 2)
    """
    from scipy.stats import qmc

    ranges = _ranges(ranges, "sobol")
    n = _count(n, "n")
    _fits(n, len(ranges), "a Sobol table")
    with warnings.catch_warnings():
        # scipy warns that n is not a power of 2: the docstring says what that means
        warnings.filterwarnings("ignore", "The balance properties of Sobol", UserWarning)
        unit = qmc.Sobol(d=len(ranges), scramble=True, seed=seed_of(seed)).random(n)
    return _scaled(unit, ranges)


class DesignTable:
    """A design table checked against a family: its columns (D,) as floats, the row labels,
    and a reason per row that cannot be analysed ('' for the good ones)."""

    def __init__(self, designs, fam):
        import pandas

        if isinstance(designs, pandas.DataFrame):
            index = designs.index
            raw = {str(c): designs[c].to_numpy() for c in designs.columns}
        elif isinstance(designs, Mapping):
            raw = {str(c): np.asarray(v) for c, v in designs.items()}
            index = None
        else:
            a = np.asarray(designs)
            required = sum(p not in fam.defaults for p in fam.parameters)
            if a.ndim != 2 or not required <= a.shape[1] <= len(fam.parameters):
                raise ModelError(f"designs: expected a DataFrame, a mapping of columns or an array "
                                 f"of shape (D, {required}) to (D, {len(fam.parameters)}), its "
                                 f"columns the first of {', '.join(fam.parameters)}, got "
                                 f"{describe(designs)}")
            raw = {p: a[:, i] for i, p in enumerate(fam.parameters[:a.shape[1]])}
            index = None
        for name in raw:
            if name not in fam.parameters:
                raise ModelError(f"designs: column {name!r}: "
                                 f"{expected_one_of(name, fam.parameters)} (parameters of "
                                 f"{fam.name!r}); rename or drop it")
        if not raw:
            raise ModelError("designs: expected a column for each parameter to vary, got none; "
                             + (f"the family {fam.name!r} takes {', '.join(fam.parameters)}"
                                if fam.parameters else
                                f"the family {fam.name!r} has no numeric parameters to vary"))
        missing = [p for p in fam.parameters if p not in raw and p not in fam.defaults]
        if missing:
            raise ModelError(f"designs: missing column(s) {', '.join(map(repr, missing))} of "
                             f"family {fam.name!r}; add them to the table")
        lengths = {len(v) if np.ndim(v) == 1 else -1 for v in raw.values()}
        if len(lengths) != 1 or -1 in lengths:
            raise ModelError("designs: expected columns of one dimension and the same length, got "
                             + ", ".join(f"{k} {np.shape(v)}" for k, v in raw.items()))
        self.size = lengths.pop()
        self.columns: dict[str, np.ndarray] = {}
        problems = [""] * self.size
        for name, v in raw.items():
            f = real_values(f"designs: column {shown(name)}", v)
            self.columns[name] = f
            is_length = name in fam.lengths
            bad = ~((f >= MIN_LENGTH) & (f <= MAX_LENGTH) if is_length else np.abs(f) <= MAX_LENGTH)
            for i in np.flatnonzero(bad):
                if not problems[i]:
                    why = (length_problem(f[i], positive=is_length)
                           or f"expected {'a length' if is_length else 'a finite number'}")
                    problems[i] = f"{name}: {why}, got {f[i]:g}"
        self.problems = np.array(problems, object)    # an array: Dask ships it as one block
        self.index = index if index is not None else pandas.RangeIndex(self.size)

    def chunk(self, lo: int, hi: int) -> dict[str, np.ndarray]:
        return {k: v[lo:hi] for k, v in self.columns.items()}
