"""Figures of sweep studies: the error band of a tolerance study."""
from __future__ import annotations

import numpy as np

from kinelab import _memory as memory
from kinelab.errors import ModelError, describe
from kinelab.plot._figures import _pyplot, plain
from kinelab.solvers._arguments import flag, whole

__all__ = ["tolerance_band", "error_histogram"]


def _axes(ax):
    return ax if ax is not None else _pyplot().figure().gca()


def _study(study) -> "ToleranceStudy":
    from kinelab.sweep import ToleranceStudy   # a study's room, loaded when a study is drawn

    if not isinstance(study, ToleranceStudy):
        raise ModelError(f"study: expected a ToleranceStudy (from kinelab.sweep.tolerance), got "
                         f"{describe(study)}")
    return study


def _scale(study, degrees: bool) -> tuple[float, str]:
    flag("degrees", degrees)
    if study.unit == "m":
        return 1.0, "m"
    return (180.0 / np.pi, "deg") if degrees else (1.0, "rad")


def tolerance_band(study, *, ax=None, degrees: bool = False):
    """The error of the output over the cycle: the median, the 5-95 % band and the extremes
    of the drawn designs that assemble (:func:`kinelab.sweep.tolerance`).

    Returns
    -------
    matplotlib Axes
    """
    study = _study(study)
    k, unit = _scale(study, degrees)
    ax = _axes(ax)
    x = np.degrees(study.q) if degrees else study.q
    lo, p5, p50, p95, hi = study.percentile([0, 5, 50, 95, 100]) * k
    ax.fill_between(x, lo, hi, color="tab:blue", alpha=0.15, label="all designs")
    ax.fill_between(x, p5, p95, color="tab:blue", alpha=0.35, label="5 to 95 %")
    ax.plot(x, p50, color="tab:blue", lw=1.2, label="median")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel(f"input [{'deg' if degrees else 'rad'}]")
    ax.set_ylabel(plain(f"{study.output} error [{unit}]"))
    ax.set_title(f"tolerance study: {len(study.errors)} designs, "
                 f"{int(study.assembles.sum())} assemble")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return ax


def error_histogram(study, *, ax=None, degrees: bool = False, bins: int = 40):
    """How the largest |error| over the cycle is distributed among the drawn designs.

    Returns
    -------
    matplotlib Axes
    """
    study = _study(study)
    k, unit = _scale(study, degrees)
    bins = whole("bins", bins, 1, 10 ** 9)
    # matplotlib holds a few arrays of the bins, and a bar (an object of about 2 kB) each
    memory.require(2048.0 * bins, f"a histogram of {bins:,} bins", "ask for fewer bins")
    m = study.max_error[study.assembles] * k
    if not m.size:
        raise ModelError("study: no drawn design assembles over the cycle, so there is no error "
                         "to show; narrow the tolerances")
    ax = _axes(ax)
    ax.hist(m, bins=bins, color="tab:blue", alpha=0.7)
    ax.axvline(np.percentile(m, 95), color="tab:red", lw=1.0, label="95th percentile")
    ax.set_xlabel(plain(f"largest |{study.output} error| over the cycle [{unit}]"))
    ax.set_ylabel("designs")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return ax
