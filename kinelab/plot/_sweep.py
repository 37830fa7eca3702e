"""Figures of sweep studies: the error band of a tolerance study."""
from __future__ import annotations

import numpy as np

from kinelab.plot._figures import _pyplot

__all__ = ["tolerance_band", "error_histogram"]


def _axes(ax):
    return ax if ax is not None else _pyplot().figure().gca()


def _scale(study, degrees: bool) -> tuple[float, str]:
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
    ax = _axes(ax)
    k, unit = _scale(study, degrees)
    x = np.degrees(study.q) if degrees else study.q
    lo, p5, p50, p95, hi = study.percentile([0, 5, 50, 95, 100]) * k
    ax.fill_between(x, lo, hi, color="tab:blue", alpha=0.15, label="all designs")
    ax.fill_between(x, p5, p95, color="tab:blue", alpha=0.35, label="5 to 95 %")
    ax.plot(x, p50, color="tab:blue", lw=1.2, label="median")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel(f"input [{'deg' if degrees else 'rad'}]")
    ax.set_ylabel(f"{study.output} error [{unit}]")
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
    ax = _axes(ax)
    k, unit = _scale(study, degrees)
    m = study.max_error[study.assembles] * k
    ax.hist(m, bins=bins, color="tab:blue", alpha=0.7)
    ax.axvline(np.percentile(m, 95), color="tab:red", lw=1.0, label="95th percentile")
    ax.set_xlabel(f"largest |{study.output} error| over the cycle [{unit}]")
    ax.set_ylabel("designs")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return ax
