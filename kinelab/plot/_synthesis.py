"""Figures of dimensional synthesis: prescribed positions and their poles, the linkage in
each position, Burmester's centre- and circle-point curves, the structural error of a
function generator, the coupler curve of a path generator.

matplotlib is imported inside each function (``import kinelab`` must not need it).  Each
function draws on ``ax`` (a new figure's axes when omitted) and returns the axes; lengths
are plotted in ``units`` (default SI: metres, as the results hold them).
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from kinelab.kinematics import analyze
from kinelab.model import Units
from kinelab.synthesis import (BurmesterCurves, FunctionSolution, MotionSolution, PathSolution,
                               Positions, poles)

__all__ = ["prescribed_positions", "motion_solution", "burmester_curves", "structural_error",
           "path_solution"]

_POSITION_COLOURS = "tab:blue tab:orange tab:green tab:red tab:purple tab:brown tab:pink " \
                    "tab:olive tab:cyan tab:gray".split()


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt
    _, ax = plt.subplots(figsize=(7, 6))
    return ax


def _finish(ax, title, u: Units):
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    return ax


def _colour(j):
    return _POSITION_COLOURS[j % len(_POSITION_COLOURS)]


def prescribed_positions(points, angles=None, *, ax=None, show_poles: bool = True,
                         degrees: bool = False, units: Units | Mapping[str, str] | None = None):
    """The positions of the moving plane (a point and a direction each) and their poles.

    Parameters
    ----------
    points, angles : see :class:`kinelab.synthesis.Positions`
        The positions, or a ``Positions`` with ``angles`` omitted.
    ax : matplotlib Axes, optional
    show_poles : bool
        Mark the finite poles P_ij.
    degrees : bool
        The given angles are in degrees.
    units : Units or mapping, optional
        ``{"length": "mm"}``: the unit of the axes (default SI).

    Returns
    -------
    matplotlib Axes
    """
    pos = points if isinstance(points, Positions) else Positions(points, angles, degrees=degrees)
    u = Units.resolve(units)
    ax = _axes(ax)
    arrow = 0.15 * u.convert(pos.size, "m")
    for j, (P, a) in enumerate(zip(u.convert(pos.points, "m"), pos.alpha)):
        c = _colour(j)
        ax.plot(*P, "o", color=c)
        ax.annotate("", xy=P + arrow * np.array([np.cos(a), np.sin(a)]), xytext=P,
                    arrowprops=dict(arrowstyle="->", color=c, lw=1.5))
        ax.annotate(f"{j + 1}", P, textcoords="offset points", xytext=(-10, -12), color=c)
    if show_poles:
        _poles(ax, pos, u)
    return _finish(ax, f"{pos.n} prescribed positions" + (" and their poles" if show_poles else ""),
                   u)


def _poles(ax, pos: Positions, u: Units) -> np.ndarray:
    """Mark the finite poles P_ij of ``pos``; their positions, in ``u``."""
    p = poles(pos)
    finite = u.convert(p.P[p.finite], "m")
    for (i, j), X in zip([pair for pair, f in zip(p.pairs, p.finite) if f], finite):
        ax.plot(*X, "kx")
        ax.annotate(f"P{i}{j}", X, textcoords="offset points", xytext=(4, 4), fontsize=8)
    return finite


def _linkage(ax, sol, q, colours, u: Units):
    """Draw the four-bar of a synthesized model at crank angles q (engine positions)."""
    s = analyze(sol.model, q=np.asarray(q, float), unreachable="mask", at_singular="flag")
    O2, O4 = (u.convert(np.array(sol.model.point(n).xy), "m") for n in ("O2", "O4"))
    names = [n for n in ("A", "B", "P") if n in s.point_names]
    xy = {n: u.convert(s.position(n), "m") for n in names}
    for k in range(len(q)):
        if not s.assembled[k]:
            continue
        c = colours[k]
        A, B = xy["A"][k], xy["B"][k]
        lw = 2.2 if k == 0 else 1.2
        ax.plot(*np.array([O2, A]).T, "-", color=c, lw=lw)
        ax.plot(*np.array([O4, B]).T, "-", color=c, lw=lw)
        tri = [A, B] + ([xy["P"][k]] if "P" in xy else []) + [A]
        ax.fill(*np.array(tri).T, color=c, alpha=0.15)
        ax.plot(*np.array(tri).T, "-", color=c, lw=lw)
        ax.plot(*np.array([A, B]).T, "o", color=c, ms=4)
    for X, name in ((O2, "A0"), (O4, "B0")):
        ax.plot(*X, "k^", ms=9)
        ax.annotate(name, X, textcoords="offset points", xytext=(5, -12))
    return s


def _coupler_path(sol, q, u: Units) -> np.ndarray:
    """The coupler point P at crank angles q, in ``u``; NaN where the linkage does not
    assemble or is singular, which breaks the drawn line."""
    s = analyze(sol.model, q=q, unreachable="mask", at_singular="flag")
    ok = s.assembled & ~s.singular
    return u.convert(np.where(ok[:, None], s.position("P"), np.nan), "m")


def _travel_curve(ax, sol, q_from, q_to, direction, u: Units):
    span = np.mod(direction * (q_to - q_from), 2 * np.pi) if direction else 2 * np.pi
    d = direction or 1
    q = q_from + d * np.linspace(0.0, span, 361)
    ax.plot(*_coupler_path(sol, q, u).T, "k--", lw=0.8, label="coupler curve on the way")


def motion_solution(sol: MotionSolution, *, ax=None, units: Units | Mapping[str, str] | None = None):
    """A motion-generation four-bar drawn by the engine in each prescribed position, with
    the prescribed points and the coupler curve between the first and the last, lengths in
    ``units`` (default SI).

    Returns
    -------
    matplotlib Axes
    """
    u = Units.resolve(units)
    ax = _axes(ax)
    n = len(sol.q)
    _linkage(ax, sol, sol.q, [_colour(j) for j in range(n)], u)
    for j, P in enumerate(u.convert(sol.points, "m")):
        ax.plot(*P, "s", mfc="none", color=_colour(j), ms=9)
        ax.annotate(f"P{j + 1}", P, textcoords="offset points", xytext=(6, 4), color=_colour(j))
    _travel_curve(ax, sol, sol.q[0], sol.q[-1], sol.direction, u)
    return _finish(ax, f"four-bar through {n} positions ({sol.grashof.kind}, {sol.state})", u)


def burmester_curves(curves: BurmesterCurves, *, ax=None, positions=None, solutions=(),
                     units: Units | Mapping[str, str] | None = None):
    """Burmester's centre-point curve (fixed pivots) and circle-point curve (moving pivots
    in position 1), with the poles and chosen solutions when given.

    Parameters
    ----------
    curves : BurmesterCurves
    positions : Positions, optional
        The four positions, to mark the poles (they lie on the centre-point curve).
    solutions : sequence of MotionSolution
        Linkages whose pivots are marked (fixed: triangles, moving: circles).
    units : Units or mapping, optional
        ``{"length": "mm"}``: the unit of the axes (default SI).

    Returns
    -------
    matplotlib Axes
    """
    u = Units.resolve(units)
    ax = _axes(ax)
    center, circle = u.convert(curves.center, "m"), u.convert(curves.circle, "m")
    for k in range(2):
        c = np.where(curves.valid[k][:, None], center[k], np.nan)
        m = np.where(curves.valid[k][:, None], circle[k], np.nan)
        ax.plot(*c.T, "-", color="tab:blue", lw=1.2, label="centre points (A0)" if k == 0 else None)
        ax.plot(*m.T, "-", color="tab:red", lw=1.2, label="circle points (A1)" if k == 0 else None)
    # the curves run off to infinity: frame the poles, the points and the pivots shown
    # (or, without them, the middle of the curves)
    keep = [u.convert(np.array([x for s in solutions for x in (s.A0, s.B0, s.A1, s.B1)]), "m")
            .reshape(-1, 2)]
    if positions is not None:
        points = u.convert(positions.points, "m")
        keep += [points, _poles(ax, positions, u)]
        ax.plot(*points.T, "ks", mfc="none", label="prescribed P")
    for s in solutions:
        ax.plot(*u.convert(np.array([s.A0, s.B0]), "m").T, "^", color="tab:blue", ms=8)
        ax.plot(*u.convert(np.array([s.A1, s.B1]), "m").T, "o", color="tab:red", ms=6)
    allp = np.vstack(keep)
    if len(allp) < 2:
        allp = np.percentile(np.vstack([center[curves.valid], circle[curves.valid]]),
                             [10, 90], axis=0)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    pad = 0.25 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.legend(loc="best", fontsize=8)
    return _finish(ax, "centre-point and circle-point curves", u)


def structural_error(sol: FunctionSolution, *, ax=None):
    """The structural error of a function generator over [x0, xf], with its precision points.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    e = np.where(np.isfinite(sol.structural_error), sol.structural_error, np.nan)
    ax.plot(sol.x_samples, e, "-", color="tab:blue")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.plot(sol.x, np.zeros_like(sol.x), "o", color="tab:red", label="precision points")
    ax.set_xlabel("x")
    ax.set_ylabel("generated y - f(x)")
    ax.set_title(f"structural error (max {sol.max_structural_error:.3g})")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return ax


def path_solution(sol: PathSolution, *, ax=None, units: Units | Mapping[str, str] | None = None):
    """A path generator: its coupler curve, the targets, and the linkage at the first one,
    lengths in ``units`` (default SI).

    Returns
    -------
    matplotlib Axes
    """
    u = Units.resolve(units)
    ax = _axes(ax)
    n = len(sol.q)
    _linkage(ax, sol, sol.q[:1], [_colour(0)], u)
    q = sol.q[0] + np.linspace(0.0, 2 * np.pi, 721)
    ax.plot(*_coupler_path(sol, q, u).T, "-", color="tab:gray", lw=1.0,
            label="coupler curve (this branch)")
    _travel_curve(ax, sol, sol.q[0], sol.q[-1], sol.direction, u)
    targets = u.convert(sol.points, "m")
    ax.plot(*targets.T, "s", mfc="none", color="tab:red", ms=8, label="targets")
    for j, T in enumerate(targets):
        ax.annotate(f"{j + 1}", T, textcoords="offset points", xytext=(6, 4), color="tab:red")
    ax.legend(loc="best", fontsize=8)
    return _finish(ax, f"path generator through {n} points (rms error "
                       f"{u.convert(sol.rms_error, 'm'):.3g} {u.length})", u)
