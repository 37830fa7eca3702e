"""Tolerance studies by Monte Carlo: dimensions drawn within their tolerances, and the
error of an output over the cycle that they cause."""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from kinelab import _memory as memory
from kinelab.errors import ModelError, check_choice, describe, expected_one_of
from kinelab.model import MAX_LENGTH, is_real
from kinelab.solvers import wrap_angle
from kinelab.solvers._arguments import finite, number, whole
from kinelab.sweep._designs import DesignTable, real_values, seed_of
from kinelab.sweep._family import Family, family as make_family
from kinelab.sweep._run import MAX_SAMPLES, chunk_size_for

__all__ = ["ToleranceStudy", "tolerance"]


@dataclass(frozen=True, eq=False)
class ToleranceStudy:
    """The error of an output over a cycle for dimensions drawn within their tolerances.

    Attributes
    ----------
    q : ndarray, shape (S,)
        The input samples, rad.
    nominal : ndarray, shape (S,)
        The output of the nominal design (rad for an angle, m for a slide).
    errors : ndarray, shape (n, S)
        Output of each drawn design minus the nominal one (angles wrapped to (-pi, pi]); NaN
        where that design does not assemble.
    designs : pandas.DataFrame
        The drawn designs, one row each.
    output : str
    unit : str
        "rad" for a link's angle, "m" for a slide.
    """

    q: np.ndarray
    nominal: np.ndarray
    errors: np.ndarray
    designs: "pandas.DataFrame"
    output: str
    unit: str

    @property
    def assembles(self) -> np.ndarray:
        """(n,) bool: the drawn design assembles at every sample."""
        return np.isfinite(self.errors).all(axis=1)

    @property
    def max_error(self) -> np.ndarray:
        """(n,) largest |error| of each drawn design over the cycle (NaN if it does not assemble)."""
        return np.where(self.assembles, np.max(np.abs(np.nan_to_num(self.errors)), axis=1), np.nan)

    def percentile(self, p: float | np.ndarray) -> np.ndarray:
        """The p-th percentile (0 to 100) of the error at each sample, over the designs that
        assemble: shape (S,), or (len(p), S)."""
        q = finite("p", real_values("p", p))
        if q.size and not (0.0 <= q.min() and q.max() <= 100.0):
            raise ModelError(f"p: expected percentiles from 0 to 100, got {describe(p)}")
        ok = self.errors[self.assembles]
        if len(ok) == 0:
            raise ModelError("tolerance: no drawn design assembles over the cycle; narrow the "
                             "tolerances")
        return np.percentile(ok, q, axis=0)


def tolerance(family: str | Family, nominal: Mapping[str, float],
              tolerances: Mapping[str, float], *, n: int = 1000, output: str | None = None,
              samples: int = 72, distribution: str = "uniform", seed: int | None = 0) -> ToleranceStudy:
    """Monte Carlo of a family's output error under dimensional tolerances.

    Each design draws every toleranced parameter independently around its nominal value:
    uniformly within +-tolerance, or normally with the tolerance as three standard
    deviations (``distribution="normal"``).  All the designs are analysed at once, in
    chunks.

    Parameters
    ----------
    family : str, Mechanism or Family
    nominal : mapping
        The nominal design, parameter -> value (m; the family's defaults fill the rest).
    tolerances : mapping
        Parameter -> tolerance (m), e.g. ``{"crank": 1e-4, "ground": 2e-4}``; pivots of a model
        as ``"O4.x"``.
    n : int
        Designs drawn.
    output : str, optional
        The link or prismatic joint whose error is measured (default: the family's output).
    samples : int
        Samples over a full turn of the input.

    Returns
    -------
    ToleranceStudy

    Examples
    --------
    >>> nominal = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> study = kl.sweep.tolerance("fourbar", nominal, {"crank": 1e-3, "rocker": 1e-3}, n=200)
    >>> study.errors.shape, bool(study.assembles.all())
    ((200, 72), True)
    >>> bool(np.degrees(study.max_error.max()) < 0.2)       # 1 mm on 1 m links: tenths of a degree
    True
    """
    import pandas

    fam = make_family(family)
    check_choice("distribution", distribution, ("uniform", "normal"))
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ModelError(f"n: expected a whole number >= 1, got {describe(n)}")
    samples = whole("samples", samples, 4, MAX_SAMPLES)
    seed = seed_of(seed)
    if not isinstance(nominal, Mapping):
        raise ModelError(f"nominal: expected a mapping of parameter to value (m), e.g. "
                         f"{{'crank': 1.0}}, got {describe(nominal)}")
    if not isinstance(tolerances, Mapping):
        raise ModelError(f"tolerances: expected a mapping of parameter to tolerance (m), e.g. "
                         f"{{'crank': 1e-4}}, got {describe(tolerances)}")
    for name in nominal:
        if name not in fam.parameters:
            raise ModelError(f"nominal: {expected_one_of(name, fam.parameters)}")
    nominal = {name: number(f"nominal: {name}", value) for name, value in nominal.items()}
    output = output if output is not None else fam.output
    if output is None:
        raise ModelError(f"output: family {fam.name!r} has no default output; name a link or a "
                         "prismatic joint, e.g. output='rocker'")
    for name, tol in tolerances.items():
        if name not in fam.parameters:
            raise ModelError(f"tolerances: unknown parameter {name!r} of family {fam.name!r}; "
                             f"its parameters are {', '.join(fam.parameters)}")
        if not (is_real(tol) and 0 <= float(tol) <= MAX_LENGTH):
            raise ModelError(f"tolerances: {name}: expected a tolerance >= 0 and at most {MAX_LENGTH:g} m, "
                             f"got {describe(tol)}")
    memory.require(8 * n * (samples + 3 * len(fam.parameters)),
                   f"a tolerance study of {n:,} designs at {samples:,} samples",
                   "draw fewer designs or take fewer samples")
    rng = np.random.default_rng(seed)  # checked above
    base = {**{k: v for k, v in fam.defaults.items() if not (isinstance(v, float) and math.isnan(v))},
            **nominal}
    drawn = {}
    for name, value in base.items():
        tol = float(tolerances.get(name, 0.0))
        noise = (rng.uniform(-1.0, 1.0, n) if distribution == "uniform"
                 else rng.standard_normal(n) / 3.0)
        drawn[name] = float(value) + tol * noise
    table = pandas.DataFrame(drawn)
    first = DesignTable(pandas.DataFrame({k: [float(v)] for k, v in base.items()}), fam)
    if first.problems[0]:
        raise ModelError(f"nominal: {first.problems[0]}")
    q = np.linspace(0.0, 2 * math.pi, samples, endpoint=False)
    ref_designs = fam.prepare(first.columns, list(first.problems))
    if ref_designs.problems[0]:
        raise ModelError(f"nominal: {ref_designs.problems[0]}")
    ref = ref_designs.batch(q[None, :]).value(output)[0]
    checked = DesignTable(table, fam)
    errors = np.full((n, samples), np.nan)
    size = chunk_size_for(samples)
    angle = not fam.is_slide(output)
    for lo in range(0, n, size):
        hi = min(n, lo + size)
        designs = fam.prepare(checked.chunk(lo, hi), list(checked.problems[lo:hi]))
        value = designs.batch(np.broadcast_to(q, (hi - lo, samples))).value(output)
        errors[lo:hi] = wrap_angle(value - ref) if angle else value - ref
    return ToleranceStudy(q, ref, errors, table, output, "rad" if angle else "m")
