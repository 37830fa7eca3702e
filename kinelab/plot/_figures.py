"""Figures of a sweep: outputs against the input, K and L, coupler curves, transmission
angle, and the mechanism itself.  matplotlib is imported inside each function."""
from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from kinelab._files import atomic_write
from kinelab.errors import ModelError
from kinelab.kinematics import KinematicSolution

__all__ = ["curves", "coefficients", "coupler_curve", "transmission", "mechanism", "save",
           "input_axis"]

_QUANTITIES = {
    "link": (("angle", "angle", "rad"), ("omega", "angular velocity", "rad/s"),
             ("alpha", "angular acceleration", "rad/s²")),
    "slide": (("slide", "", "m"), ("slide_velocity", "velocity", "m/s"),
              ("slide_acceleration", "acceleration", "m/s²")),
}


def _pyplot():
    import matplotlib.pyplot as plt
    return plt


def input_axis(sol: KinematicSolution, degrees: bool = False) -> tuple[np.ndarray, str]:
    """The values to plot against and their label: the (first varying) input, else the
    sample number."""
    m = sol.mechanism
    from kinelab.kinematics import plan
    kinds = plan(m).input_kinds
    for k in range(sol.M):
        q = sol.q[:, k]
        if np.ptp(q) > 0:
            if kinds[k] == "angle":
                unit = "deg" if degrees else "rad"
                return (np.degrees(q) if degrees else q), f"{sol.input_names[k]} [{unit}]"
            return q, f"{sol.input_names[k]} [m]"
    return np.arange(sol.N), "sample"


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
                             f"'{name}'; they are {', '.join(repr(n) for n in known)}")
    return links, slides, points


def _outputs(sol, outputs):
    if outputs:
        return list(outputs)
    from kinelab.io import default_outputs
    return list(default_outputs(sol.mechanism))


def _unit(unit: str, degrees: bool) -> str:
    return unit.replace("rad", "deg") if degrees else unit


def _angle(values, degrees):
    return np.degrees(values) if degrees else values


def _series(sol, name, attr, degrees, is_angle):
    v = getattr(sol, attr)(name)
    if attr == "angle":
        ok = np.isfinite(v)
        v = v.copy()
        v[ok] = np.unwrap(v[ok])       # no jumps at +-pi
    return _angle(v, degrees) if is_angle else v


def curves(sol: KinematicSolution, outputs=None, *, degrees: bool = False, figure=None):
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
        Angles in degrees.

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
    """
    plt = _pyplot()
    links, slides, _ = _split(sol, _outputs(sol, outputs))
    groups = [(g, kind) for g, kind in ((links, "link"), (slides, "slide")) if g]
    if not groups:
        raise ModelError("outputs: curves need at least one link or slide")
    fig = figure or plt.figure(figsize=(5.5 * len(groups), 8), layout="constrained")
    axes = fig.subplots(3, len(groups), sharex=True, squeeze=False)
    x, xlabel = input_axis(sol, degrees)
    for col, (names, kind) in enumerate(groups):
        for row, (attr, label, unit) in enumerate(_QUANTITIES[kind]):
            ax = axes[row, col]
            for name in names:
                ax.plot(x, _series(sol, name, attr, degrees, kind == "link"), label=name)
            what = f"{names[0]} {label}".strip() if len(names) == 1 else (
                label or "slide") if kind == "link" else f"slide {label}".strip()
            ax.set_ylabel(f"{what} [{_unit(unit, degrees and kind == 'link')}]")
            ax.grid(True, alpha=0.3)
            if row == 0 and len(names) > 1:
                ax.legend(fontsize="small")
        axes[-1, col].set_xlabel(xlabel)
    fig.suptitle(f"{sol.mechanism.name}: position, velocity and acceleration")
    return fig


def coefficients(sol: KinematicSolution, outputs=None, *, degrees: bool = False, figure=None):
    """Velocity and acceleration coefficients K = dS/dq and L = dK/dq of chosen outputs
    against the input (one input: for several inputs, those of the first)."""
    plt = _pyplot()
    links, slides, _ = _split(sol, _outputs(sol, outputs))
    names = links + slides
    if not names:
        raise ModelError("outputs: K and L plots need at least one link or slide")
    fig = figure or plt.figure(figsize=(7, 6), layout="constrained")
    ax_k, ax_l = fig.subplots(2, 1, sharex=True)
    x, xlabel = input_axis(sol, degrees)
    in_angle = "rad" in xlabel or "deg" in xlabel
    for name in names:
        K, L = sol.K(name), sol.L(name)
        if sol.M > 1:
            K, L = K[:, 0], L[:, 0, 0]
        is_angle = name in links
        # K of an angle per input angle is dimensionless; degrees change only mixed units
        fk = (180 / math.pi) ** (int(is_angle) - int(in_angle)) if degrees else 1.0
        fl = (180 / math.pi) ** (int(is_angle) - 2 * int(in_angle)) if degrees else 1.0
        ax_k.plot(x, K * fk, label=name)
        ax_l.plot(x, L * fl, label=name)
    qu = ("deg" if degrees else "rad") if in_angle else "m"
    su = {n: (("deg" if degrees else "rad") if n in links else "m") for n in names}
    units = sorted(set(su.values()))
    ax_k.set_ylabel(f"K = dS/dq [{'|'.join(units)}/{qu}]")
    ax_l.set_ylabel(f"L = dK/dq [{'|'.join(units)}/{qu}²]")
    for ax in (ax_k, ax_l):
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="0.5", lw=0.6)
    ax_k.legend(fontsize="small")
    ax_l.set_xlabel(xlabel)
    fig.suptitle(f"{sol.mechanism.name}: velocity and acceleration coefficients")
    return fig


def coupler_curve(sol: KinematicSolution, point: str = "P", *, ax=None, sample: int | None = 0):
    """The path of a point over the sweep, with the mechanism drawn at ``sample``.

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
    ax = ax or plt.figure(figsize=(6, 6), layout="constrained").add_subplot()
    if sample is not None:
        mechanism(sol, sample, ax=ax)
    xy = sol.position(point)
    ax.plot(xy[:, 0], xy[:, 1], lw=1.3, color="black", label=f"path of {point}")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small", loc="best")
    ax.set_title(f"{sol.mechanism.name}: path of {point}")
    return ax


def transmission(sol: KinematicSolution, pairs=None, *, degrees: bool = True, ax=None):
    """Transmission angle of link pairs against the input, folded to [0, 90] deg.

    ``pairs`` defaults to the pin-jointed dyads (and slider dyads, measured from the slide's
    normal) that :func:`kinelab.io.summary` reports.
    """
    from kinelab.io._summary import _default_pairs, _transmission_values
    plt = _pyplot()
    pairs = list(pairs) if pairs else _default_pairs(sol.mechanism)
    if not pairs:
        raise ModelError("transmission: the mechanism has no pin-jointed dyad; name the links "
                         "with pairs=[('coupler', 'rocker')]")
    ax = ax or plt.figure(figsize=(7, 4), layout="constrained").add_subplot()
    x, xlabel = input_axis(sol, degrees)
    for a, b in pairs:
        mu = _transmission_values(sol, (a, b))
        ax.plot(x, np.degrees(mu) if degrees else mu, label=f"{a}-{b}")
    ax.set_ylim(0, 90 if degrees else math.pi / 2)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"transmission angle [{'deg' if degrees else 'rad'}]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    ax.set_title(f"{sol.mechanism.name}: transmission angle")
    return ax


def mechanism(sol: KinematicSolution, i: int = 0, *, ax=None, artists: dict | None = None):
    """Draw the mechanism at sample ``i``: links as bars or plates, pivots, sliders.

    With ``artists`` (a dict filled on the first call) the same artists are moved instead of
    drawn again, for animations.
    """
    plt = _pyplot()
    ax = ax or plt.figure(figsize=(6, 6), layout="constrained").add_subplot()
    m = sol.mechanism
    pos = {p: sol.position(p)[i] if not sol.single else sol.position(p) for p in sol.point_names}
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
                                                 label=link.name, zorder=2)[0]
        else:
            store[("link", link.name)].set_data(closed[:, 0], closed[:, 1])
    for k, j in enumerate(m.joints):
        if j.type != "P":
            continue
        guide = m.link(j.links[0])
        if guide.ground:      # a rail: the slider's whole travel, drawn once
            if first:
                travel = sol.position(j.point).reshape(-1, 2)
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
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    return atomic_write(path, lambda f: figure.savefig(f, format=fmt, dpi=150), binary=True)
