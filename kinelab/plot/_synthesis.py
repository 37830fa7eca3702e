"""Figures of dimensional synthesis: prescribed positions and their poles, the linkage in
each position, Burmester's centre- and circle-point curves (of four positions, and the two
whose crossings are the Burmester points of five), the structural error of a function
generator, the coupler curve of a path generator, a quick return at its limit positions.

matplotlib is imported inside each function (``import kinelab`` must not need it).  Each
function draws on ``ax`` (a new figure's axes when omitted) and returns the axes; lengths
are plotted in ``units`` (default SI: metres, as the results hold them).
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from kinelab import _memory as memory
from kinelab.errors import ModelError, describe
from kinelab.kinematics import analyze
from kinelab.solvers._arguments import whole
from kinelab.model import Units
from kinelab.plot._words import decimal_commas, kind_words, number, words
from kinelab.synthesis import (BurmesterCurves, CrankRocker, FunctionSolution, MotionSolution,
                               PathSolution, Positions, QuickReturn, SolutionList, poles)
from kinelab.synthesis import burmester_curves as synthesis_curves

__all__ = ["prescribed_positions", "motion_solution", "burmester_curves", "structural_error",
           "path_solution", "limit_positions", "five_positions"]

_POSITION_COLOURS = "tab:blue tab:orange tab:green tab:red tab:purple tab:brown tab:pink " \
                    "tab:olive tab:cyan tab:gray".split()


_POLES_NAMED = 45       # poles named on a figure, at most (those of ten positions)


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt
    _, ax = plt.subplots(figsize=(7, 6), layout="constrained")
    return ax


def _finish(ax, title, u: Units, lang: str = "en"):
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    decimal_commas(ax.figure, lang)
    return ax


def _given(name: str, value, kinds: type | tuple[type, ...], what: str):
    """``value`` when it is one of ``kinds``, else a ModelError naming ``name``."""
    if not isinstance(value, kinds):
        raise ModelError(f"{name}: expected {what}, got {describe(value)}")
    return value


def _solutions(solutions) -> list:
    """Linkages whose pivots are marked: MotionSolutions."""
    if isinstance(solutions, (str, bytes)) or not isinstance(solutions, (list, tuple, SolutionList)):
        raise ModelError(f"solutions: expected a list of MotionSolution, got {describe(solutions)}")
    for k, s in enumerate(solutions):
        _given(f"solutions[{k}]", s, MotionSolution, "a MotionSolution (from kinelab.synthesis)")
    return list(solutions)


def _colour(j):
    return _POSITION_COLOURS[j % len(_POSITION_COLOURS)]


def prescribed_positions(points, angles=None, *, ax=None, show_poles: bool = True,
                         degrees: bool = False, units: Units | Mapping[str, str] | None = None,
                         lang: str = "en"):
    """The positions of the moving plane (a point and a direction each) and their poles.

    Parameters
    ----------
    points, angles : see :class:`kinelab.synthesis.Positions`
        The positions, or a ``Positions`` with ``angles`` omitted.
    ax : matplotlib Axes, optional
    show_poles : bool
        Mark the finite poles P_ij (named P12, P13 ... when there are at most 45 of them:
        ten positions).
    degrees : bool
        The given angles are in degrees.
    units : Units or mapping, optional
        ``{"length": "mm"}``: the unit of the axes (default SI).
    lang : str
        Language of the title and legends, ``"en"`` or ``"pt"``.

    Returns
    -------
    matplotlib Axes
    """
    w = words(lang)
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
    return _finish(ax, w["prescribed positions and poles" if show_poles else
                         "prescribed positions"].format(n=pos.n), u, lang)


def _poles(ax, pos: Positions, u: Units) -> np.ndarray:
    """Mark the finite poles P_ij of ``pos``; their positions, in ``u``."""
    p = poles(pos)
    finite = u.convert(p.P[p.finite], "m")
    # one artist for all the marks: n positions have n (n - 1) / 2 poles, and an artist
    # each took minutes for a thousand positions; names only where they can be read
    if len(finite):
        ax.plot(*finite.T, "kx", linestyle="none")
    if len(finite) <= _POLES_NAMED:
        for (i, j), X in zip([pair for pair, f in zip(p.pairs, p.finite) if f], finite):
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


def _travel_curve(ax, sol, q_from, q_to, direction, u: Units, lang: str = "en"):
    span = np.mod(direction * (q_to - q_from), 2 * np.pi) if direction else 2 * np.pi
    d = direction or 1
    q = q_from + d * np.linspace(0.0, span, 361)
    ax.plot(*_coupler_path(sol, q, u).T, "k--", lw=0.8, label=words(lang)["coupler curve on the way"])


def motion_solution(sol: MotionSolution, *, ax=None, units: Units | Mapping[str, str] | None = None,
                    lang: str = "en"):
    """A motion-generation four-bar drawn by the engine in each prescribed position, with
    the prescribed points and the coupler curve between the first and the last, lengths in
    ``units`` (default SI).

    Returns
    -------
    matplotlib Axes
    """
    _given("sol", sol, MotionSolution, "a MotionSolution (from kinelab.synthesis: "
           "two_positions, three_positions, four_positions ...)")
    u = Units.resolve(units)
    ax = _axes(ax)
    n = len(sol.q)
    _linkage(ax, sol, sol.q, [_colour(j) for j in range(n)], u)
    for j, P in enumerate(u.convert(sol.points, "m")):
        ax.plot(*P, "s", mfc="none", color=_colour(j), ms=9)
        ax.annotate(f"P{j + 1}", P, textcoords="offset points", xytext=(6, 4), color=_colour(j))
    _travel_curve(ax, sol, sol.q[0], sol.q[-1], sol.direction, u, lang)
    return _finish(ax, words(lang)["four-bar through positions"].format(
        n=n, kind=kind_words(sol.grashof.kind, lang), state=kind_words(sol.state, lang)), u, lang)


def burmester_curves(curves: BurmesterCurves, *, ax=None, positions=None, solutions=(),
                     units: Units | Mapping[str, str] | None = None, lang: str = "en"):
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
    _given("curves", curves, BurmesterCurves, "BurmesterCurves (from "
           "kinelab.synthesis.burmester_curves)")
    if positions is not None:
        _given("positions", positions, Positions, "the four Positions (kinelab.synthesis.Positions)")
    solutions = _solutions(solutions)
    if not np.asarray(curves.valid).any():
        raise ModelError("curves: no point of the centre-point curve is valid (the positions "
                         "may not be four distinct ones); nothing to draw")
    w = words(lang)
    u = Units.resolve(units)
    ax = _axes(ax)
    center, circle = u.convert(curves.center, "m"), u.convert(curves.circle, "m")
    for k in range(2):
        c = np.where(curves.valid[k][:, None], center[k], np.nan)
        m = np.where(curves.valid[k][:, None], circle[k], np.nan)
        ax.plot(*c.T, "-", color="tab:blue", lw=1.2, label=w["centre points"] if k == 0 else None)
        ax.plot(*m.T, "-", color="tab:red", lw=1.2, label=w["circle points"] if k == 0 else None)
    # the curves run off to infinity: frame the poles, the points and the pivots shown
    # (or, without them, the middle of the curves)
    keep = [u.convert(np.array([x for s in solutions for x in (s.A0, s.B0, s.A1, s.B1)]), "m")
            .reshape(-1, 2)]
    if positions is not None:
        points = u.convert(positions.points, "m")
        keep += [points, _poles(ax, positions, u)]
        ax.plot(*points.T, "ks", mfc="none", label=w["prescribed P"])
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
    return _finish(ax, w["burmester title"], u, lang)


def structural_error(sol: FunctionSolution, *, ax=None, lang: str = "en"):
    """The structural error of a function generator over [x0, xf], with its precision points.

    Returns
    -------
    matplotlib Axes
    """
    _given("sol", sol, FunctionSolution, "a FunctionSolution (from "
           "kinelab.synthesis.function_generation)")
    w = words(lang)
    ax = _axes(ax)
    e = np.where(np.isfinite(sol.structural_error), sol.structural_error, np.nan)
    ax.plot(sol.x_samples, e, "-", color="tab:blue")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.plot(sol.x, np.zeros_like(sol.x), "o", color="tab:red", label=w["precision points"])
    ax.set_xlabel("x")
    ax.set_ylabel(w["generated error"])
    ax.set_title(w["structural error"].format(error=number(sol.max_structural_error, ".3g", lang)))
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    decimal_commas(ax.figure, lang)
    return ax


def path_solution(sol: PathSolution, *, ax=None, units: Units | Mapping[str, str] | None = None,
                  lang: str = "en"):
    """A path generator: its coupler curve, the targets, and the linkage at the first one,
    lengths in ``units`` (default SI).

    Returns
    -------
    matplotlib Axes
    """
    _given("sol", sol, PathSolution, "a PathSolution (from kinelab.synthesis.path_generation)")
    w = words(lang)
    u = Units.resolve(units)
    ax = _axes(ax)
    n = len(sol.q)
    _linkage(ax, sol, sol.q[:1], [_colour(0)], u)
    q = sol.q[0] + np.linspace(0.0, 2 * np.pi, 721)
    ax.plot(*_coupler_path(sol, q, u).T, "-", color="tab:gray", lw=1.0,
            label=w["coupler curve branch"])
    _travel_curve(ax, sol, sol.q[0], sol.q[-1], sol.direction, u, lang)
    targets = u.convert(sol.points, "m")
    ax.plot(*targets.T, "s", mfc="none", color="tab:red", ms=8, label=w["targets"])
    for j, T in enumerate(targets):
        ax.annotate(f"{j + 1}", T, textcoords="offset points", xytext=(6, 4), color="tab:red")
    ax.legend(loc="best", fontsize=8)
    return _finish(ax, w["path generator"].format(
        n=n, error=number(u.convert(sol.rms_error, "m"), ".3g", lang), unit=u.length), u, lang)


def limit_positions(design: CrankRocker | QuickReturn, *, ax=None,
                    units: Units | Mapping[str, str] | None = None, lang: str = "en"):
    """A crank-rocker or quick return drawn by the engine at its two limit positions (dead
    centres), with the crank circle and the output's travel over a turn, lengths and angles
    in ``units`` (default SI, whatever the unit of the design's own angles), the title
    naming the swing or stroke, the coefficient of velocity K (the time ratio) and the
    smallest transmission angle.

    Parameters
    ----------
    design : CrankRocker or QuickReturn
        From :func:`kinelab.synthesis.crank_rocker`, :func:`~kinelab.synthesis.offset_slider_crank`,
        :func:`~kinelab.synthesis.slotted_lever` or :func:`~kinelab.synthesis.whitworth`.

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> cr = kl.synthesis.crank_rocker(1.0, 60.0, 1.2, degrees=True)
    >>> ax = kl.plot.limit_positions(cr, units={"angle": "deg"})
    >>> "swing 60 deg" in ax.get_title()
    True
    >>> ax = kl.plot.limit_positions(cr)        # SI: radians
    >>> "swing 1.047 rad" in ax.get_title()
    True
    """
    _given("design", design, (CrankRocker, QuickReturn), "a CrankRocker or QuickReturn (from "
           "kinelab.synthesis.crank_rocker, offset_slider_crank, slotted_lever or whitworth)")
    u = Units.resolve(units)
    ax = _axes(ax)
    m = design.model
    dc = np.radians(design.dead_centres) if design.degrees else np.asarray(design.dead_centres)
    s = analyze(m, q=dc)
    turn = analyze(m, q=np.linspace(0.0, 2 * np.pi, 721), unreachable="mask", at_singular="flag")
    xy = {p: u.convert(s.position(p), "m") for p in s.point_names}
    w = words(lang)
    labels = tuple(w["limit position"].format(k=k) for k in (1, 2))
    for k, colour in enumerate(("tab:blue", "tab:orange")):
        for link in m.links:
            if link.ground or len(link.points) < 2:
                continue
            pts = np.array([xy[p][k] for p in link.points])
            ax.plot(*pts.T, "-o", color=colour, lw=2.2, ms=4,
                    label=labels[k] if link.name == "crank" else None)
    for p in m.link("ground").points:
        X = u.convert(np.array(m.point(p).xy), "m")
        ax.plot(*X, "k^", ms=9)
        ax.annotate(p, X, textcoords="offset points", xytext=(5, -12))
    # the crank pin's circle and the path of the output's pin over a whole turn
    for p, style, label in (("A", ":", w["crank circle"]),
                            (_output_pin(m), "--", w["output travel"])):
        path = np.where(turn.assembled[:, None], turn.position(p), np.nan)
        ax.plot(*u.convert(path, "m").T, style, color="0.4", lw=1.0, label=label)
    def angle(value, spec):         # the design's angle (in its call's unit) in u's
        si = np.radians(value) if design.degrees else value
        return number(float(u.convert(si, "rad")), spec, lang)
    ratio = number(design.time_ratio, ".4g", lang)
    if isinstance(design, CrankRocker):
        what = w["crank-rocker"].format(swing=angle(design.swing, ".4g"), angle=u.angle,
                                        ratio=ratio,
                                        transmission=angle(design.transmission_min, ".3g"))
    else:
        travel = (w["quick return stroke"].format(
                      stroke=number(float(u.convert(design.stroke, "m")), ".4g", lang),
                      length=u.length) if design.stroke is not None else
                  w["quick return swing"].format(swing=angle(design.swing, ".4g"), angle=u.angle))
        what = w["quick return"].format(kind=kind_words(design.kind, lang), travel=travel, ratio=ratio)
    ax.legend(loc="best", fontsize=8)
    return _finish(ax, what, u, lang)


def _output_pin(model) -> str:
    """The point whose path shows the output's travel: the rocker pin, the slider's pin,
    the lever's end or the ram."""
    for name in ("D", "B", "C"):
        if name in {p.name for p in model.points}:
            return name
    return "A"


def five_positions(positions: Positions, solutions=(), *, ax=None, samples: int = 1441,
                   units: Units | Mapping[str, str] | None = None, lang: str = "en"):
    """Five positions with their centre-point curves (of positions 1-4 and 1, 2, 3, 5),
    which meet in Burmester's points (the fixed pivots of the dyads through all five),
    and the pivots of the given linkages.

    Parameters
    ----------
    positions : Positions
        The five positions.
    solutions : sequence of MotionSolution
        Linkages from :func:`kinelab.synthesis.five_positions`, whose pivots are marked.
    samples : int
        Crank rotations sampled along each curve.

    Returns
    -------
    matplotlib Axes
    """
    _given("positions", positions, Positions, "five Positions (kinelab.synthesis.Positions)")
    if positions.n != 5:
        raise ModelError(f"positions: expected five positions, got {positions.n}; draw four with "
                         "burmester_curves, more with prescribed_positions")
    solutions = _solutions(solutions)
    samples = whole("samples", samples, 3, 10 ** 9)
    # each curve holds a few dozen floats a sample (two branches, centre and circle points)
    memory.require(2 * 400.0 * samples, f"two centre-point curves of {samples:,} samples",
                   "ask for fewer samples")
    u = Units.resolve(units)
    ax = _axes(ax)
    w = words(lang)
    prescribed_positions(positions, ax=ax, show_poles=False, units=u, lang=lang)
    sets = {"1-4": [0, 1, 2, 3], "1, 2, 3, 5": [0, 1, 2, 4]}
    for (name, idx), colour in zip(sets.items(), ("tab:blue", "tab:green")):
        sub = Positions(positions.points[idx], positions.alpha[idx])
        cur = synthesis_curves(sub, samples=samples)
        for k in range(2):
            c = u.convert(np.where(cur.valid[k][:, None], cur.center[k], np.nan), "m")
            ax.plot(*c.T, "-", color=colour, lw=1.0,
                    label=w["centre points of"].format(which=name) if k == 0 else None)
    keep = [u.convert(positions.points, "m")]
    for s in solutions:
        piv = u.convert(np.array([s.A0, s.B0]), "m")
        ax.plot(*piv.T, "^", color="tab:red", ms=9)
        ax.plot(*u.convert(np.array([s.A1, s.B1]), "m").T, "o", color="tab:red", ms=5)
        keep.append(piv)
    pts = np.vstack(keep)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = 0.3 * max((hi - lo).max(), 1e-300)
    ax.legend(loc="best", fontsize=8)
    _finish(ax, w["five positions"], u, lang)
    # the curves run off to infinity: frame the positions and the pivots, at equal scales
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    return ax
