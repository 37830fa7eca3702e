"""Figures of a sweep: outputs against the input, K and L, coupler curves, transmission
angle, and the mechanism itself.  matplotlib is imported inside each function.

Every function draws in the units it is given (``units=``, default SI; ``degrees=True`` for
angles in degrees), converted by :class:`kinelab.model.Units`, and names them on its axes.
Values at singular samples (``sol.singular``: det J = 0) are left out, leaving gaps, and
the singular positions are marked.
"""
from __future__ import annotations

import functools
import math
import numbers
import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from kinelab._files import atomic_write
from kinelab.errors import ModelError, describe, quoted, shown
from kinelab._files import file_path
from kinelab.kinematics import KinematicSolution
from kinelab.kinematics._solution import takes_solution
from kinelab.kinematics._columns import INPUT_SI_UNITS
from kinelab.model import Units
from kinelab.plot._words import decimal_commas, words

__all__ = ["curves", "coefficients", "coupler_curve", "transmission", "mechanism", "save",
           "input_axis"]

_QUANTITIES = {     # (accessor, word, SI unit) of each row (words: kinelab.plot._words)
    "link": (("angle", "angle", "rad"), ("omega", "angular velocity", "rad/s"),
             ("alpha", "angular acceleration", "rad/s^2")),
    "slide": (("slide", "slide", "m"), ("slide_velocity", "velocity", "m/s"),
              ("slide_acceleration", "acceleration", "m/s^2")),
}
SINGULAR_LABEL = "singular (det J = 0)"


def takes_sweep(function):
    """``function`` with its first argument checked to be a KinematicSolution with at least
    one sample (:func:`~kinelab.kinematics._solution.takes_solution`, and an empty sweep
    named)."""
    @takes_solution
    @functools.wraps(function)
    def checked(sol, *args, **kwargs):
        if sol.N == 0:
            raise ModelError("sol: the solution has no samples; analyze at least one input value")
        return function(sol, *args, **kwargs)
    return checked


def sample_of(sol: KinematicSolution, i: object, name: str) -> int:
    """The sample ``i`` of ``sol`` (negative counts from the end) as an index."""
    n = 1 if sol.single else sol.N
    if isinstance(i, (bool, np.bool_)) or not isinstance(i, numbers.Integral) or not -n <= i < n:
        span = "0 (one configuration)" if n == 1 else f"a whole number from 0 to {n - 1} (or -{n} to -1 from the end)"
        raise ModelError(f"{name}: expected {span}, the index of a sample, got {describe(i)}")
    return int(i) % n


def _pyplot():
    import matplotlib.pyplot as plt
    return plt


def plain(text: str) -> str:
    """``text`` shown as it is by matplotlib, never read as mathtext: a figure's text that
    holds a name (of a model, point, link, joint, input or column) comes from a file, and
    mathtext would read ``$...$`` in it as commands (and fail on ``\\frac{``).

    Examples
    --------
    >>> print(plain("crank-rocker: path of $x$"))
    crank-rocker: path of \\$x\\$
    """
    return text.replace("$", r"\$")


def _fitted(label: str, width: int = 34) -> str:
    """An axis label longer than ``width`` characters with its unit on a line of its own,
    so that it fits beside the axes of a figure of several rows.

    Examples
    --------
    >>> print(_fitted("aceleração angular de lever [deg/s²]"))
    aceleração angular de lever
    [deg/s²]
    """
    head, bracket, unit = label.rpartition(" [")
    return f"{head}\n[{unit}" if len(label) > width and bracket else label


def _label(units: Units, si_unit: str) -> str:
    """An axis label's unit: ``deg/s²``."""
    return units.unit(si_unit).replace("^2", "²")


@takes_sweep
def input_axis(sol: KinematicSolution, degrees: bool = False, *,
               units: Units | Mapping[str, str] | None = None) -> tuple[np.ndarray, str]:
    """The values to plot against and their label: the (first varying) input in ``units``
    (default SI), else the sample number.

    Examples
    --------
    >>> sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=[0.0, np.pi])
    >>> x, label = kl.plot.input_axis(sol, units={"angle": "deg"})
    >>> x, label
    (array([  0., 180.]), 'jO2 [deg]')
    """
    x, label, _ = _input(sol, Units.resolve(units, degrees=degrees))
    return x, label


def _input(sol: KinematicSolution, u: Units, lang: str = "en") -> tuple[np.ndarray, str, str]:
    """:func:`input_axis` (the sample number's label in ``lang``) and the unit of its values
    ('' for the sample number)."""
    for k, kind in enumerate(sol.plan.input_kinds):
        q = sol.q[:, k]
        if np.ptp(q) > 0:
            unit = u.unit(INPUT_SI_UNITS[kind])
            role = ("input slide" if kind != "angle" else
                    "input crank" if np.ptp(q) >= 2 * math.pi - 1e-9 else "input angle")
            name = words(lang)[role].format(name=sol.input_names[k])
            return u.convert(q, INPUT_SI_UNITS[kind]), f"{name} [{unit}]", unit
    return np.arange(sol.N), words(lang)["sample"], ""


def _x_axis(ax, sol: KinematicSolution, u: Units, lang: str = "en") -> np.ndarray:
    """Label ``ax``'s x axis with the input, mark the singular positions; the x values."""
    x, label, unit = _input(sol, u, lang)
    ax.set_xlabel(plain(label))
    if np.ptp(x) > 0:
        ax.set_xlim(np.min(x), np.max(x))      # the sweep, edge to edge
    _turn_ticks(ax.xaxis, x, unit)
    _mark_singular(ax, sol, x)
    return x


def _turn_ticks(axis, values, unit: str) -> None:
    """Degrees over a full turn or more: ticks on multiples of 90 (0, 90, ..., 360)."""
    v = np.asarray(values)[np.isfinite(values)]
    if unit == "deg" and v.size and np.ptp(v) >= 360.0 - 1e-6:
        from matplotlib.ticker import MultipleLocator
        axis.set_major_locator(MultipleLocator(90.0 * math.ceil(np.ptp(v) / 720.0)))


def _regular(sol: KinematicSolution, values) -> np.ndarray:
    """``values`` (N, ...) with NaN at the singular samples: no line is drawn through them."""
    mask = np.asarray(sol.singular).reshape((-1,) + (1,) * (np.ndim(values) - 1))
    return np.where(mask, np.nan, values)


def _singular_samples(sol: KinematicSolution) -> list[int]:
    """One sample (the middle one) of each run of singular samples."""
    from kinelab.io._summary import _runs
    return _runs(np.asarray(sol.singular)) if not sol.single else []


def _mark_singular(ax, sol: KinematicSolution, x) -> None:
    """Thin vertical lines at the singular positions of a sweep plotted against ``x``,
    labelled once in the legend."""
    for k, i in enumerate(_singular_samples(sol)):
        ax.axvline(x[i], color="tab:red", lw=0.7, ls=":", zorder=1,
                   label=SINGULAR_LABEL if k == 0 else None)


def _split(sol: KinematicSolution, outputs):
    links, slides, points = [], [], []
    for name in outputs:
        if name in sol.slide_item:
            slides.append(name)
        elif name in sol.link_item:
            links.append(name)
        elif name in sol.point_item:
            points.append(name)
        else:
            known = list(sol.link_item) + list(sol.slide_item) + list(sol.point_item)
            raise ModelError(f"outputs: expected links, slides or points of the mechanism, got "
                             f"{shown(name)}; they are {', '.join(repr(n) for n in known)}")
    return links, slides, points


def _outputs(sol, outputs):
    if isinstance(outputs, str):
        return [outputs]        # one name
    if outputs is not None and not isinstance(outputs, (list, tuple)):
        raise ModelError(f"outputs: expected names of links, slides or points, got "
                         f"{describe(outputs)}")
    if outputs:
        return list(outputs)
    from kinelab.io import default_outputs
    return list(default_outputs(sol.mechanism))


def _series(sol, name, attr, si_unit, units: Units):
    v = _regular(sol, getattr(sol, attr)(name))
    if attr == "angle":
        ok = np.isfinite(v)
        v[ok] = np.unwrap(v[ok])       # no jumps at +-pi
    return units.convert(v, si_unit)


def _legend(ax, always: bool = True, **kwargs) -> None:
    """The legend of ``ax``, the singular positions last; with ``always=False`` only when
    there are singular positions to name."""
    handles, labels = ax.get_legend_handles_labels()
    if not (always and labels) and SINGULAR_LABEL not in labels:
        return
    order = sorted(range(len(labels)), key=lambda i: labels[i] == SINGULAR_LABEL)
    ax.legend([handles[i] for i in order], [labels[i] for i in order], fontsize="small", **kwargs)


@takes_sweep
def curves(sol: KinematicSolution, outputs=None, *, degrees: bool = False,
           units: Units | Mapping[str, str] | None = None, figure=None, lang: str = "en"):
    """Position, velocity and acceleration of chosen outputs against the input.

    One column per kind of output (link angles, slides), three rows: position, velocity,
    acceleration.  Points are drawn by :func:`coupler_curve`.

    Parameters
    ----------
    sol : KinematicSolution
        A sweep.
    outputs : list of str, optional
        Links and slides (default: those :func:`kinelab.io.default_outputs` picks).
    degrees : bool
        Angles in degrees: shorthand for ``units={"angle": "deg"}``.
    units : Units or mapping, optional
        ``{"length": "mm", "angle": "deg"}``; default SI.
    lang : str
        Language of the titles, axes and legends: ``"en"`` or ``"pt"`` (with decimal
        commas in the tick labels).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib; matplotlib.use("Agg")
    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> fig = kl.plot.curves(kl.analyze(sc, q=np.linspace(0, 2 * np.pi, 73), qd=1.0), ["rod", "slide"])
    >>> [ax.get_ylabel() for ax in fig.axes][:2]
    ['rod angle [rad]', 'slide [m]']
    >>> fig = kl.plot.curves(kl.analyze(sc, q=np.linspace(0, 2 * np.pi, 73), qd=1.0), ["slide"],
    ...                      units={"length": "mm", "angle": "deg"})
    >>> ax = fig.axes[-1]
    >>> fig.axes[0].get_ylabel(), ax.get_xlabel(), float(ax.get_xlim()[1])   # a full turn, edge to edge
    ('slide [mm]', 'jO2 [deg]', 360.0)
    >>> [float(t) for t in ax.get_xticks() if 0 <= t <= 360]
    [0.0, 90.0, 180.0, 270.0, 360.0]
    """
    plt = _pyplot()
    w = words(lang)
    u = Units.resolve(units, degrees=degrees)
    links, slides, _ = _split(sol, _outputs(sol, outputs))
    groups = [(g, kind) for g, kind in ((links, "link"), (slides, "slide")) if g]
    if not groups:
        raise ModelError("outputs: curves need at least one link or slide")
    fig = figure or plt.figure(figsize=(5.5 * len(groups), 8), layout="constrained")
    axes = fig.subplots(3, len(groups), sharex=True, squeeze=False)
    for col, (names, kind) in enumerate(groups):
        for row, (attr, label, si) in enumerate(_QUANTITIES[kind]):
            ax = axes[row, col]
            x = _x_axis(ax, sol, u, lang)
            for name in names:
                y = _series(sol, name, attr, si, u)
                ax.plot(x, y, label=plain(name))
                if row == 0:
                    _turn_ticks(ax.yaxis, y, u.unit(si))
            what = (w[f"named {label}"].format(name=names[0]) if len(names) == 1 else
                    w[label] if kind == "link" else w[f"slide {label}" if row else "slide"])
            ax.set_ylabel(_fitted(plain(f"{what} [{_label(u, si)}]")))
            ax.grid(True, alpha=0.3)
            if row == 0:            # names the curves and the singular positions for the column
                _legend(ax, always=len(names) > 1)
        for ax in axes[:-1, col]:
            ax.set_xlabel("")       # shared: the bottom row names it
    fig.suptitle(plain(w["motion title"].format(name=sol.mechanism.name)))
    decimal_commas(fig, lang)
    return fig


@takes_sweep
def coefficients(sol: KinematicSolution, outputs=None, *, degrees: bool = False,
                 units: Units | Mapping[str, str] | None = None, figure=None,
                 lang: str = "en"):
    """Velocity and acceleration coefficients K = dS/dq and L = dK/dq of chosen outputs
    against the input (one input: for several inputs, those of the first), in ``units``
    (default SI): K in output unit per input unit, L per input unit squared.

    Examples
    --------
    >>> import matplotlib; matplotlib.use("Agg")
    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> fig = kl.plot.coefficients(kl.analyze(sc, q=np.linspace(0, 2 * np.pi, 73)), ["slide"],
    ...                            units={"length": "mm", "angle": "deg"})
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['K = dS/dq [mm/deg]', 'L = dK/dq [mm/deg²]']
    """
    plt = _pyplot()
    w = words(lang)
    u = Units.resolve(units, degrees=degrees)
    links, slides, _ = _split(sol, _outputs(sol, outputs))
    names = links + slides
    if not names:
        raise ModelError("outputs: K and L plots need at least one link or slide")
    fig = figure or plt.figure(figsize=(7, 6), layout="constrained")
    ax_k, ax_l = fig.subplots(2, 1, sharex=True)
    qu = INPUT_SI_UNITS[sol.plan.input_kinds[0]]
    k_units, l_units = [], []
    for ax in (ax_k, ax_l):
        x = _x_axis(ax, sol, u, lang)
    for name in names:
        K, L = sol.K(name), sol.L(name)
        if sol.M > 1:
            K, L = K[:, 0], L[:, 0, 0]
        su = "rad" if name in links else "m"
        k_units.append(f"{su}/{qu}")
        l_units.append(f"{su}/{qu}^2")
        ax_k.plot(x, u.convert(_regular(sol, K), k_units[-1]), label=plain(name))
        ax_l.plot(x, u.convert(_regular(sol, L), l_units[-1]), label=plain(name))
    ax_k.set_ylabel(_fitted(f"{w['K label']} [{' | '.join(sorted({_label(u, k) for k in k_units}))}]"))
    ax_l.set_ylabel(_fitted(f"{w['L label']} [{' | '.join(sorted({_label(u, k) for k in l_units}))}]"))
    for ax in (ax_k, ax_l):
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="0.5", lw=0.6)
    _legend(ax_k)
    ax_k.set_xlabel("")
    fig.suptitle(plain(w["coefficients title"].format(name=sol.mechanism.name)))
    decimal_commas(fig, lang)
    return fig


@takes_sweep
def coupler_curve(sol: KinematicSolution, point: str = "P", *, ax=None, sample: int | None = 0,
                  units: Units | Mapping[str, str] | None = None, lang: str = "en"):
    """The path of a point over the sweep, with the mechanism drawn at ``sample``, lengths
    in ``units`` (default SI).  The path leaves out the singular samples, which are marked.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import matplotlib; matplotlib.use("Agg")
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> ax = kl.plot.coupler_curve(kl.analyze(fb, q=np.linspace(0, 2 * np.pi, 91)), "P")
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('x [m]', 'y [m]')
    """
    plt = _pyplot()
    w = words(lang)
    u = Units.resolve(units)
    ax = ax or plt.figure(figsize=(6, 6), layout="constrained").add_subplot()
    if sample is not None:
        mechanism(sol, sample_of(sol, sample, "sample"), ax=ax, units=u)
    xy = u.convert(sol.position(point), "m")
    ax.plot(*_regular(sol, xy).T, lw=1.3, color="black", label=plain(w["path of"].format(point=point)))
    singular = _singular_samples(sol)
    if singular:
        ax.plot(*xy[singular].T, "x", color="tab:red", ms=8, mew=1.5, label=SINGULAR_LABEL)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.grid(True, alpha=0.3)
    _legend(ax, loc="best")
    ax.set_title(plain(w["path title"].format(name=sol.mechanism.name, point=point)))
    decimal_commas(ax.figure, lang)
    return ax


@takes_sweep
def transmission(sol: KinematicSolution, pairs=None, *, degrees: bool | None = None,
                 units: Units | Mapping[str, str] | None = None, ax=None, lang: str = "en"):
    """Transmission angle of link pairs against the input, folded to [0, 90] deg.

    ``pairs`` defaults to the pin-jointed dyads (and slider dyads, measured from the slide's
    normal) that :func:`kinelab.io.summary` reports.  Angles are in degrees unless ``units``
    (or ``degrees=False``) say otherwise.

    Examples
    --------
    >>> import matplotlib; matplotlib.use("Agg")
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    >>> ax = kl.plot.transmission(kl.analyze(fb, q=np.linspace(0, 2 * np.pi, 37)))
    >>> ax.get_ylabel(), [float(v) for v in ax.get_ylim()]
    ('transmission angle [deg]', [0.0, 90.0])
    """
    from kinelab.io._summary import _default_pairs, _transmission_values
    plt = _pyplot()
    w = words(lang)
    u = Units.resolve(units, degrees=units is None if degrees is None else degrees)
    pairs = list(pairs) if pairs else _default_pairs(sol.mechanism)
    if not pairs:
        raise ModelError("transmission: the mechanism has no pin-jointed dyad; name the links "
                         "with pairs=[('coupler', 'rocker')]")
    ax = ax or plt.figure(figsize=(7, 4), layout="constrained").add_subplot()
    x = _x_axis(ax, sol, u, lang)
    for a, b in pairs:
        mu = _regular(sol, _transmission_values(sol, (a, b)))
        ax.plot(x, u.convert(mu, "rad"), label=plain(f"{a}-{b}"))
    ax.set_ylim(0, u.convert(math.pi / 2, "rad"))
    ax.set_ylabel(f"{w['transmission angle']} [{u.angle}]")
    ax.grid(True, alpha=0.3)
    _legend(ax)
    ax.set_title(plain(w["transmission title"].format(name=sol.mechanism.name)))
    decimal_commas(ax.figure, lang)
    return ax


@takes_sweep
def mechanism(sol: KinematicSolution, i: int = 0, *, ax=None, artists: dict | None = None,
              units: Units | Mapping[str, str] | None = None):
    """Draw the mechanism at sample ``i``: links as bars or plates, pivots, sliders, with
    lengths in ``units`` (default SI).

    With ``artists`` (a dict filled on the first call) the same artists are moved instead of
    drawn again, for animations.
    """
    plt = _pyplot()
    i = sample_of(sol, i, "i")
    u = Units.resolve(units)
    ax = ax or plt.figure(figsize=(6, 6), layout="constrained").add_subplot()
    m = sol.mechanism

    def position(p):
        return u.convert(sol.position(p), "m")
    pos = {p: position(p)[i] if not sol.single else position(p) for p in sol.point_names}
    first = artists is None or not artists
    store = artists if artists is not None else {}
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, link in enumerate(m.links):
        xy = np.array([pos[p] for p in link.points])
        if link.ground:
            if first:
                for p in link.points:
                    store[("pivot", p)] = ax.plot(*pos[p], marker="^", ms=11, color="0.35",
                                                  zorder=3)[0]
            continue
        if len(link.points) == 1:
            if first:
                store[("link", link.name)] = ax.plot(*xy[0], marker="s", ms=13, mfc="none",
                                                     mew=2, color=colors[k % len(colors)], zorder=4)[0]
            else:
                store[("link", link.name)].set_data([xy[0, 0]], [xy[0, 1]])
            continue
        closed = np.vstack([xy, xy[:1]]) if len(xy) > 2 else xy
        if first:
            store[("link", link.name)] = ax.plot(closed[:, 0], closed[:, 1], lw=4, alpha=0.85,
                                                 solid_capstyle="round", color=colors[k % len(colors)],
                                                 label=plain(link.name), zorder=2)[0]
        else:
            store[("link", link.name)].set_data(closed[:, 0], closed[:, 1])
    for k, j in enumerate(m.joints):
        if j.type != "P":
            continue
        guide = m.link(j.links[0])
        if guide.ground:      # a rail: the slider's whole travel, drawn once
            if first:
                travel = position(j.point).reshape(-1, 2)
                travel = travel[np.isfinite(travel).all(axis=1)]
                ends = travel[[np.argmin(travel @ np.asarray(j.axis)), np.argmax(travel @ np.asarray(j.axis))]]
                ax.plot(ends[:, 0], ends[:, 1], lw=1.2, color="0.55", zorder=1)
            continue
        # a slot along a moving guide, from its first point to the slider
        seg = np.array([pos[guide.points[0]], pos[j.point]])
        i_guide = m.link_names.index(guide.name)
        if first:
            store[("slot", j.name)] = ax.plot(seg[:, 0], seg[:, 1], lw=1.5, ls="--", zorder=1,
                                              color=colors[i_guide % len(colors)])[0]
        else:
            store[("slot", j.name)].set_data(seg[:, 0], seg[:, 1])
    pins = [p for p in sol.point_names if len(m.links_carrying(p)) > 1]
    pxy = np.array([pos[p] for p in pins]) if pins else np.zeros((0, 2))
    if first:
        store["pins"] = ax.plot(pxy[:, 0], pxy[:, 1], "o", ms=5, mfc="white", mec="black",
                                zorder=5)[0]
        ax.set_aspect("equal", adjustable="datalim")
    else:
        store["pins"].set_data(pxy[:, 0], pxy[:, 1])
    return ax


def save(figure, path: str | os.PathLike) -> Path:
    """Save a figure (PNG, SVG or any matplotlib format, by suffix) atomically."""
    from matplotlib.figure import Figure

    if not isinstance(figure, Figure):
        raise ModelError(f"figure: expected a matplotlib Figure (ax.figure for the axes of a "
                         f"plot), got {describe(figure)}")
    path = file_path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    formats = figure.canvas.get_supported_filetypes()
    if fmt not in formats:
        raise ModelError(f"path: expected a file name ending in one of "
                         f"{quoted(sorted('.' + f for f in formats))}, got {shown(path.name)}")
    return atomic_write(path, lambda f: figure.savefig(f, format=fmt, dpi=150), binary=True)
