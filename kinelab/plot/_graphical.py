"""Figures of the graphical methods: the velocity and acceleration polygons with the links'
images, the instant centres with Kennedy's circle diagram, centrodes, and the derivatives of
a measured curve (Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*,
§4.6; Badan (IFG), *Análise de aceleração*).

Polygons and mechanisms are drawn to scale: each panel is ``PANEL_CM`` centimetres square
on the page (at 100 %), and its title states how much one centimetre stands for, a round
number (1, 2, 2.5 or 5 times a power of ten) chosen so that the drawing fits.  The numbers come
from :mod:`kinelab.kinematics`; these functions only draw them.
"""
from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from kinelab.kinematics import (AccelerationPolygon, KinematicSolution, VelocityPolygon,
                                kennedy_construction)
from kinelab.kinematics import acceleration_polygon as acceleration_polygon_data
from kinelab.kinematics import centrodes as centrodes_data
from kinelab.kinematics import velocity_polygon as velocity_polygon_data
from kinelab.kinematics._polygons import sample_index
from kinelab.model import Units
from kinelab.plot._figures import plain
from kinelab.plot._words import decimal_commas, number, words
from kinelab.solvers import Derivatives

__all__ = ["velocity_polygon", "acceleration_polygon", "instant_centers", "centrodes",
           "derivatives", "drawing_scale", "PANEL_CM"]

PANEL_CM = 9.0          # side of each square panel on the page
_MARGIN_CM = 2.2        # around and between panels: titles and tick labels
_CM = 1 / 2.54          # inches per centimetre
_PART_STYLE = {         # colour and line style of each part of a side
    "normal": ("tab:blue", "--"), "tangential": ("tab:green", "--"),
    "coriolis": ("tab:red", "--"), "sliding": ("tab:purple", "--"),
}
_LEGEND_CM = 2.0        # beside the acceleration polygon: its parts' legend, off the drawing
_PART_MARK = {"normal": "n", "tangential": "t", "coriolis": "c", "sliding": "s"}


def drawing_scale(span: float, paper_cm: float = PANEL_CM) -> float:
    """The round scale (units per centimetre: 1, 2, 2.5 or 5 times a power of ten) at which
    ``span`` fits in ``paper_cm`` centimetres, with a margin of a tenth.

    Examples
    --------
    >>> kl.plot.drawing_scale(3.7)          # 3.7 m in 9 cm: 1 cm = 0.5 m
    0.5
    >>> kl.plot.drawing_scale(0.0)          # nothing to draw: 1 cm = 1
    1.0
    """
    need = 1.1 * span / paper_cm
    if not need > 0 or not math.isfinite(need):
        return 1.0
    power = 10.0 ** math.floor(math.log10(need))
    for step in (1.0, 2.0, 2.5, 5.0, 10.0):
        if step * power >= need * (1 - 1e-12):
            return float(f"{step * power:.12g}")
    return 10.0 * power


def _scale_text(scale: float, unit: str, lang: str = "en") -> str:
    return f"1 cm = {number(scale, 'g', lang)} {unit}"


def _panels(plt, count: int, legend_cm: float = 0.0):
    """A figure with ``count`` square panels of PANEL_CM side, side by side, at fixed
    places on the page (so that the scale stated holds when the figure is printed at 100 %),
    and ``legend_cm`` more on the right for a legend beside the last panel."""
    width = count * PANEL_CM + (count + 1) * _MARGIN_CM + legend_cm
    height = PANEL_CM + 2.2 * _MARGIN_CM
    fig = plt.figure(figsize=(width * _CM, height * _CM))
    axes = []
    for k in range(count):
        left = (_MARGIN_CM * (k + 1) + PANEL_CM * k) / width
        ax = fig.add_axes((left, _MARGIN_CM / height, PANEL_CM / width, PANEL_CM / height))
        ax.set_aspect("equal", adjustable="box")
        ax.grid(True, alpha=0.25)
        axes.append(ax)
    return fig, axes


def _to_scale(ax, xy: np.ndarray, scale: float) -> None:
    """Limits of a PANEL_CM panel at ``scale`` units per centimetre, centred on ``xy``."""
    xy = xy[np.isfinite(xy).all(axis=1)] if len(xy) else np.zeros((1, 2))
    mid = 0.5 * (xy.min(axis=0) + xy.max(axis=0))
    half = 0.5 * PANEL_CM * scale
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)


def _arrow(ax, start, end, *, color="black", ls="-", lw=1.6, label=None, gid=None,
           labels: list | None = None):
    """An arrow from ``start`` to ``end`` with an optional label at its middle, offset along
    the arrow's normal; with ``labels``, the label is added to that list to be placed by
    :func:`_place_labels` (once the panel's scale is set) instead."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    art = ax.annotate("", xy=end, xytext=start, annotation_clip=False,
                      arrowprops=dict(arrowstyle="-|>", color=color, lw=lw, ls=ls,
                                      shrinkA=0, shrinkB=0, mutation_scale=12))
    art.set_gid(gid)
    if label:
        d = end - start
        n = np.hypot(*d)
        normal = np.array([-d[1], d[0]]) / n if n > 0 else np.array([0.0, 1.0])
        if labels is not None:
            labels.append(_Label(label, 0.5 * (start + end), normal, dict(color=color, fontsize=8),
                                 along=d / n if n > 0 else np.zeros(2), reach=0.5 * n))
        else:
            ax.annotate(label, 0.5 * (start + end), xytext=6 * normal, textcoords="offset points",
                        color=color, fontsize=8, ha="center", va="center")
    return art


class _Label:
    """A label to place near ``xy`` (data coordinates): beside an arrow, on either side along
    its ``normal`` and shifted along it (``along``, by up to ``reach`` data units); beside a
    point (``normal`` None), in the eight directions around it."""

    def __init__(self, text, xy, normal=None, style=None, *, along=None, reach=0.0):
        self.text, self.xy, self.normal = text, np.asarray(xy, float), normal
        self.style, self.along, self.reach = style or {}, along, reach


def _place_labels(ax, labels: list) -> None:
    """Write ``labels`` on ``ax`` where none covers another: each tries its places nearest
    first (the arrow's side, then the other side, farther out, and shifted along the
    arrow; around a point, the eight directions at growing distances, with a thin leader
    line to the point when it is far) and takes the first free one; a label with no free
    place joins the label it meets first ("a, b"), which then takes a free place of its own
    if it has come to cover another.  The axes' limits must be set (the panel drawn to scale)
    before."""
    if not labels:
        return
    renderer = ax.figure.canvas.get_renderer()
    placed: list = []           # [label, annotation, box]

    def free_place(label, art, others) -> bool:
        for offset in _offsets(label, _half_size(art, renderer), ax):
            _move(art, label, offset)
            box = art.get_window_extent(renderer)
            if not any(box.overlaps(b) for _, _, b in others):
                return True
        return False
    for label in labels:
        art = ax.annotate(label.text, label.xy, xytext=(0, 0), textcoords="offset points",
                          ha="center", va="center", annotation_clip=False, **label.style)
        if free_place(label, art, placed):
            placed.append([label, art, art.get_window_extent(renderer)])
            continue
        _move(art, label, next(iter(_offsets(label, _half_size(art, renderer), ax))))
        box = art.get_window_extent(renderer)
        host = next(k for k, (_, _, b) in enumerate(placed) if box.overlaps(b))
        art.remove()
        host_label, host_art, _ = placed[host]
        host_art.set_text(f"{host_art.get_text()}, {label.text}")
        others = placed[:host] + placed[host + 1:]
        box = host_art.get_window_extent(renderer)
        if any(box.overlaps(b) for _, _, b in others):
            free_place(host_label, host_art, others)
        placed[host][2] = host_art.get_window_extent(renderer)
    _leaders(ax, placed)


def _half_size(art, renderer) -> np.ndarray:
    """Half the width and height of a text, in points."""
    box = art.get_window_extent(renderer)
    return 0.5 * np.array([box.width, box.height]) * 72.0 / art.figure.dpi


def _move(art, label: _Label, offset) -> None:
    """Put a label's centre at ``offset`` points from its anchor."""
    art.xyann = tuple(offset)


def _leaders(ax, placed) -> None:
    """A thin line from each point to its label when the label had to go far from it."""
    dpi = ax.figure.dpi
    for label, art, _ in placed:
        offset = np.asarray(art.xyann, float)
        if label.normal is None and float(np.hypot(*offset)) > 24.0:
            end = ax.transData.inverted().transform(
                ax.transData.transform(label.xy) + offset * dpi / 72.0)
            ax.plot(*np.array([label.xy, end]).T, lw=0.4, color=label.style.get("color", "0.3"),
                    zorder=1)


def _offsets(label: _Label, half: np.ndarray, ax):
    """The offsets (points) of a label's centre to try, nearest first."""
    to_points = 72.0 / ax.figure.dpi
    if label.normal is None:
        for distance in (3.0, 9.0, 16.0, 26.0, 40.0, 56.0, 76.0):
            for dx, dy in ((1, 1), (1, -1), (-1, 1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1)):
                yield np.array([dx * (half[0] + distance), dy * (half[1] + distance)])
        return
    # the normal in display space (the panels are drawn at equal scales on x and y)
    normal = np.asarray(label.normal, float)
    along = np.asarray(label.along, float)
    extent = float(np.abs(normal) @ half)      # half the label's size across the arrow
    # how far along the arrow a label may slide, in points
    x0, x1 = ax.get_xlim()
    width = ax.get_window_extent().width * to_points
    reach = label.reach * width / (x1 - x0) if x1 != x0 else 0.0
    for shift in (0.0, 0.3, -0.3, 0.6, -0.6):
        for distance in (3.0, 10.0, 18.0):
            for side in (1.0, -1.0):
                yield normal * side * (extent + distance) + along * shift * reach


def _tex(name: str) -> str:
    """A point's name in a mathtext subscript; a guide's coincident point ``A@lever`` as A′."""
    base = name.split("@")[0]
    return base + ("'" if "@" in name else "")


def _vector_label(letter: str, names, mark: str = "") -> str:
    """``$V_{AB}$`` (``$A^{n}_{AB}$`` with ``mark``) for the points ``names``; as plain
    text, ``V_a\\b``, when a name holds more than letters, digits and `` '-./``: mathtext
    would read the rest as commands, and a name comes from a file."""
    sub = "".join(_tex(n) for n in names)
    if all(c.isalnum() or c in " '-./" for c in sub):
        return f"${letter}{'^' + mark if mark else ''}_{{{sub}}}$"
    return plain(f"{letter}{mark}_{sub}")


def _mechanism_panel(ax, sol, i: int, u: Units, extra=(), lang: str = "en",
                     labels: list | None = None):
    """The mechanism at sample ``i`` to scale, its points named: their labels are added to
    ``labels`` to be placed with the others on the panel (:func:`_place_labels`), or, without
    it, placed here."""
    from kinelab.plot._figures import mechanism
    mechanism(sol, i, ax=ax, units=u)
    pos = np.array([u.convert(sol.position(p)[i] if not sol.single else sol.position(p), "m")
                    for p in sol.point_names])
    names = [_Label(plain(p), xy, style=dict(fontsize=8)) for p, xy in zip(sol.point_names, pos)]
    span_xy = np.vstack([pos, *extra]) if len(extra) else pos
    scale = drawing_scale(float(np.ptp(span_xy, axis=0).max()))
    _to_scale(ax, span_xy, scale)
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.set_title(plain(f"{sol.mechanism.name}, {_q_label(sol, i, u, lang)}\n"
                       f"{words(lang)['lengths']}: {_scale_text(scale, u.length, lang)}"),
                 fontsize=9)
    if labels is None:
        _place_labels(ax, names)
    else:
        labels[:0] = names
    return scale


def _q_label(sol: KinematicSolution, i: int, u: Units, lang: str = "en") -> str:
    parts = []
    for name, kind, v in zip(sol.input_names, sol.plan.input_kinds, sol.q[i]):
        unit = "rad" if kind == "angle" else "m"
        parts.append(f"{name} = {number(float(u.convert(v, unit)), '.4g', lang)} {u.unit(unit)}")
    return ", ".join(parts)


def _polygon_figure(sol: KinematicSolution, poly, acceleration: bool, units, scale,
                    lang: str = "en"):
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon as Patch
    u = Units.resolve(units)
    si = "m/s^2" if acceleration else "m/s"
    unit = u.unit(si).replace("^2", "²")
    letter = "A" if acceleration else "V"
    w = words(lang)
    fig, (ax_m, ax_p) = _panels(plt, 2, legend_cm=_LEGEND_CM if acceleration else 0.0)
    i = poly.sample
    _mechanism_panel(ax_m, sol, i, u, lang=lang)
    labels: list = []           # placed once the polygon's scale is set

    def conv(v):
        return np.asarray(u.convert(np.asarray(v, float), si), float)
    vertex = {name: conv(v) for name, v in {**poly.vertices, **poly.coincident}.items()}
    xy = np.vstack([np.zeros((1, 2)), *vertex.values()])
    size = float(np.ptp(xy, axis=0).max())
    scale = drawing_scale(size) if scale is None else float(scale)
    tiny = 1e-9 * max(size, 1e-300)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    link_index = {name: k for k, name in enumerate(sol.mechanism.link_names)}
    for link, image in poly.images.items():
        if len(image.points) >= 3:
            pts = np.array([vertex[p] for p in image.points])
            ax_p.add_patch(Patch(pts, closed=True, alpha=0.12, lw=0,
                                 color=colors[link_index[link] % len(colors)], gid=f"image {link}"))
    for p in sol.point_names:
        v = vertex[p]
        if np.hypot(*v) > tiny:
            _arrow(ax_p, (0.0, 0.0), v, color="black", label=_vector_label(letter, [p]), gid=f"{p}",
                   labels=labels)
    for (p, r), side in poly.sides.items():
        start, end = vertex[r], vertex[p]
        if np.hypot(*(end - start)) <= tiny:
            continue
        if not acceleration:
            if np.hypot(*start) <= tiny:     # from a point at rest: the absolute arrow itself
                continue
            _arrow(ax_p, start, end, color="tab:gray", ls="--", lw=1.2,
                   label=_vector_label(letter, [p, r]), gid=f"{p} {r}", labels=labels)
            continue
        at = start
        for part, vector in side.parts.items():
            vector = conv(vector)
            if np.hypot(*vector) <= tiny:
                continue
            color, ls = _PART_STYLE[part]
            _arrow(ax_p, at, at + vector, color=color, ls=ls, lw=1.2,
                   label=_vector_label(letter, [p, r], _PART_MARK[part]), gid=f"{p} {r} {part}",
                   labels=labels)
            at = at + vector
    ax_p.plot(0.0, 0.0, "ko", ms=4)
    pole = [_Label(f"$O_{letter}$", (0.0, 0.0))]
    groups: dict[tuple, list[str]] = {}       # vertices that coincide share one label
    for name, v in vertex.items():
        groups.setdefault(tuple(np.round(v / max(tiny, 1e-300))), []).append(name)
    for names in groups.values():
        v = vertex[names[0]]
        ax_p.plot(*v, "o", ms=3, color="black")
        pole.append(_Label(plain(" = ".join(_tex(n).lower() for n in names)), v,
                           style=dict(fontsize=9)))
    _to_scale(ax_p, xy, scale)
    _place_labels(ax_p, pole + labels)       # the vertices first: the arrows' go round them
    ax_p.set_xlabel(f"{'a' if acceleration else 'v'}x [{unit}]")
    ax_p.set_ylabel(f"{'a' if acceleration else 'v'}y [{unit}]")
    what = "acceleration" if acceleration else "velocity"
    plural = "accelerations" if acceleration else "velocities"
    ax_p.set_title(f"{w[what + ' polygon']}\n{w[plural]}: {_scale_text(scale, unit, lang)}",
                   fontsize=9)
    if acceleration:
        from matplotlib.lines import Line2D
        handles = [Line2D([], [], color=c, ls=ls, label=w[name])
                   for name, (c, ls) in _PART_STYLE.items()
                   if any(name in s.parts for s in poly.sides.values())]
        ax_p.legend(handles=handles, fontsize="x-small", loc="upper left",
                    bbox_to_anchor=(1.0, 1.0), borderaxespad=0.4, handlelength=1.5)
    decimal_commas(fig, lang)
    return fig


def velocity_polygon(sol: KinematicSolution, sample: int = 0, *,
                     units: Units | Mapping[str, str] | None = None, scale: float | None = None,
                     lang: str = "en"):
    """The mechanism at one sample beside its velocity polygon, drawn to scale.

    From the pole O_V, each point's absolute velocity V_A; between two vertices, each
    relative velocity V_BA (dashed); each link's velocity image shaded (Flores & Claro,
    §4.6.1-4.6.2).  Vertices are labelled with the points' names in lower case, as the
    notes do, and a guide's point under a slider with a prime (a′).

    Parameters
    ----------
    sol : KinematicSolution
    sample : int
        Which sample to draw (see :func:`kinelab.kinematics.velocity_polygon`).
    units : Units or mapping, optional
        ``{"length": "mm"}``: lengths and velocities in these units (default SI).
    scale : float, optional
        Velocity per centimetre of the page (default: a round number that fits).
    lang : str
        Language of the titles and legends, ``"en"`` or ``"pt"`` (decimal commas).

    Returns
    -------
    matplotlib.figure.Figure
        Two panels: the mechanism and the polygon, each PANEL_CM (9 cm) square, their
        scales in their titles.

    Raises
    ------
    ModelError, SingularityError, AssemblyError
        As :func:`kinelab.kinematics.velocity_polygon`.

    Examples
    --------
    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> fig = kl.plot.velocity_polygon(kl.analyze(sc, q=np.radians(60.0), qd=2.0))
    >>> fig.axes[1].get_title().splitlines()[1]       # V_A = 2 m/s fits in 9 cm at 0.25 m/s a cm
    'velocities: 1 cm = 0.25 m/s'
    """
    poly: VelocityPolygon = velocity_polygon_data(sol, sample)
    return _polygon_figure(sol, poly, False, units, scale, lang)


def acceleration_polygon(sol: KinematicSolution, sample: int = 0, *,
                         units: Units | Mapping[str, str] | None = None, scale: float | None = None,
                         lang: str = "en"):
    """The mechanism at one sample beside its acceleration polygon, drawn to scale.

    From the pole O_A, each point's absolute acceleration A_A; each side drawn as its parts
    head to tail: A^n_BA then A^t_BA between two points of a link, A^c then A^s (Coriolis,
    sliding) between a slider's point and its guide's point under it (Badan (IFG), *Análise
    de aceleração*); each link's acceleration image shaded.

    Parameters and returns as :func:`velocity_polygon` (``scale`` in acceleration per cm).

    Examples
    --------
    >>> sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
    >>> fig = kl.plot.acceleration_polygon(kl.analyze(sl, q=np.radians(60.0), qd=3.0))
    >>> sorted(a.get_gid() for a in fig.axes[1].texts if "@" in (a.get_gid() or ""))
    ['A A@lever coriolis', 'A A@lever sliding', 'A@lever O4 normal', 'A@lever O4 tangential']
    """
    poly: AccelerationPolygon = acceleration_polygon_data(sol, sample)
    return _polygon_figure(sol, poly, True, units, scale, lang)


def instant_centers(sol: KinematicSolution, sample: int = 0, *,
                    units: Units | Mapping[str, str] | None = None, lines: bool = True,
                    lang: str = "en"):
    """Every instant centre of one configuration on the mechanism, beside the circle
    diagram of Kennedy's construction (Flores & Claro, §4.6.3).

    Primary centres (the joints) are filled dots, secondary ones (Kennedy's theorem) open
    circles numbered in the order the construction finds them, with the two lines that fix
    each drawn thin (``lines``); a centre at infinity is an arrow along its direction,
    labelled ∞.  The circle diagram puts the links' numbers on a circle; primary centres
    are solid chords, secondary ones dashed chords with their order.

    Parameters
    ----------
    sol : KinematicSolution
    sample : int
    units : Units or mapping, optional
    lines : bool
        Draw the two lines of centres that fix each secondary centre.
    lang : str
        Language of the titles, ``"en"`` or ``"pt"`` (decimal commas).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ModelError, SingularityError, AssemblyError
        A sample out of range, singular or not assembled.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    >>> fig = kl.plot.instant_centers(kl.analyze(fb, q=np.radians(60.0)))
    >>> sorted(t.get_text() for t in fig.axes[0].texts if t.get_text().startswith("O1"))
    ['O12', 'O13 (1)', 'O14']
    """
    import matplotlib.pyplot as plt
    w = words(lang)
    i = sample_index(sol, sample)
    u = Units.resolve(units)
    kc = kennedy_construction(sol)
    fig, (ax_m, ax_c) = _panels(plt, 2)

    def at(a):
        a = np.asarray(a)
        return a if sol.single else a[i]
    pos = np.array([at(sol.position(p)) for p in sol.point_names])
    size = float(np.ptp(pos, axis=0).max())
    centre_xy, far = {}, []
    for pair, c in kc.centers.items():
        if not bool(at(c.at_infinity)):
            xy = at(c.position)
            centre_xy[pair] = xy
            if np.linalg.norm(xy - pos.mean(axis=0)) > 3 * size:
                far.append(pair)
    shown = [u.convert(xy, "m") for p, xy in centre_xy.items() if p not in far]
    labels: list = []           # the points' and the centres', placed together at the end
    _mechanism_panel(ax_m, sol, i, u, extra=[np.array(shown)] if shown else (), lang=lang,
                     labels=labels)
    order = {s.pair: k + 1 for k, s in enumerate(kc.steps)}
    for pair, c in kc.centers.items():
        label = kc.label(pair) + (f" ({order[pair]})" if pair in order else "")
        if pair in centre_xy:
            xy = u.convert(centre_xy[pair], "m")
            primary = pair in kc.primary
            ax_m.plot(*xy, "o", ms=6, color="tab:red", mfc="tab:red" if primary else "white",
                      mew=1.5, zorder=6, gid=kc.label(pair))
            labels.append(_Label(w["off the figure"].format(label=label) if pair in far else label,
                                 xy, style=dict(fontsize=8, color="tab:red")))
        else:
            d = at(c.direction)
            x0, x1 = ax_m.get_xlim()
            y0, y1 = ax_m.get_ylim()
            corner = np.array([x1 - 0.12 * (x1 - x0), y1 - 0.12 * (y1 - y0)])
            corner[1] -= 0.1 * (y1 - y0) * (len([t for t in ax_m.texts if "∞" in t.get_text()]))
            length = 0.08 * (x1 - x0)
            _arrow(ax_m, corner - length * d, corner + length * d, color="tab:red",
                   label=None, gid=kc.label(pair))
            ax_m.annotate(f"{label} ∞", corner, xytext=(-40, 0), textcoords="offset points",
                          fontsize=8, color="tab:red", ha="right", va="center")
    if lines:
        known = {p: at(c.position) for p, c in kc.centers.items() if p in centre_xy}
        for step in kc.steps:
            chosen = int(at(step.chosen))
            if chosen < 0 or step.pair not in known:
                continue
            a, b = step.pair
            for k in step.thirds[chosen]:
                ends = [q for q in (_pair(sol, a, k), _pair(sol, k, b))]
                pts = [known.get(q) for q in ends]
                pts.append(known[step.pair])
                pts = [u.convert(p, "m") for p in pts if p is not None]
                if len(pts) >= 2:
                    pts = np.array(pts)
                    ax_m.plot(pts[:, 0], pts[:, 1], lw=0.6, ls=":", color="tab:red", zorder=1)
    _place_labels(ax_m, labels)
    _circle_diagram(ax_c, kc, order, lang)
    decimal_commas(fig, lang)
    return fig


def _pair(sol, a, b):
    names = list(sol.link_names)
    return (a, b) if names.index(a) < names.index(b) else (b, a)


def _circle_diagram(ax, kc, order, lang: str = "en") -> None:
    n = len(kc.numbers)
    angle = {lk: np.pi / 2 - 2 * np.pi * (k - 1) / n for lk, k in kc.numbers.items()}
    xy = {lk: np.array([np.cos(a), np.sin(a)]) for lk, a in angle.items()}
    for pair in kc.centers:
        a, b = pair
        line = np.array([xy[a], xy[b]])
        if pair in kc.primary:
            style = dict(color="black", lw=1.6, ls="-")
        elif pair in order:
            style = dict(color="tab:red", lw=1.0, ls="--")
        else:
            style = dict(color="tab:gray", lw=0.8, ls=":")
        ax.plot(line[:, 0], line[:, 1], **style, gid=kc.label(pair))
        if pair in order:
            mid = line.mean(axis=0)
            ax.annotate(str(order[pair]), mid, fontsize=8, color="tab:red", ha="center",
                        va="center", bbox=dict(boxstyle="circle,pad=0.15", fc="white", ec="tab:red", lw=0.6))
    for lk, p in xy.items():
        ax.plot(*p, "o", ms=16, mfc="white", mec="black", zorder=3)
        ax.annotate(str(kc.numbers[lk]), p, ha="center", va="center", fontsize=9, zorder=4)
        ax.annotate(plain(lk), 1.22 * p, ha="center", va="center", fontsize=8)
    ax.set_xlim(-1.6, 1.6)
    ax.set_ylim(-1.6, 1.6)
    ax.set_axis_off()
    ax.set_title(words(lang)["circle diagram"], fontsize=9)


def centrodes(sol: KinematicSolution, link: str, sample: int = 0, *, ax=None,
              units: Units | Mapping[str, str] | None = None, lang: str = "en"):
    """The fixed centrode of ``link`` and its moving centrode placed where the link is at
    ``sample``, touching at the instant centre, with the mechanism drawn there.

    The view is the mechanism's neighbourhood (and the instant centre, when it is near):
    the centrodes are cut at its edges, where they leave it marked with an open triangle
    and a note in the legend.  Titles and legends in ``lang`` ("en" or "pt").

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    >>> sol = kl.analyze(fb, q=np.linspace(0.0, 2 * np.pi, 73))
    >>> ax = kl.plot.centrodes(sol, "coupler", 10)
    >>> [line.get_label() for line in ax.lines if not line.get_label().startswith("_")][-3:]
    ['moving centrode', 'centrodes leave the drawing here (through infinity)', 'instant centre O13']
    """
    import matplotlib.pyplot as plt
    from kinelab.plot._figures import mechanism
    i = sample_index(sol, sample)
    u = Units.resolve(units)
    c = centrodes_data(sol, link)
    ax = ax or plt.figure(figsize=(8.5, 6), layout="constrained").add_subplot()
    mechanism(sol, i, ax=ax, units=u)
    first = sol.mechanism.link(link).points[0]
    origin = np.reshape(sol.position(first), (-1, 2))[i]
    th = float(np.reshape(sol.angle(link), (-1,))[i])
    rot = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    placed = origin + c.moving @ rot.T
    # a centrode runs off to infinity (the link's centre leaving on one side and coming back
    # on the other): the view keeps to the mechanism's neighbourhood, and the centrodes are
    # cut at its edges, where they leave it marked
    w = words(lang)
    pts = np.array([np.reshape(sol.position(p), (-1, 2))[i] for p in sol.point_names])
    pts = pts[np.isfinite(pts).all(axis=1)]
    mid, size = 0.5 * (pts.min(axis=0) + pts.max(axis=0)), float(np.ptp(pts, axis=0).max())
    frame = [pts]
    if c.defined[i] and np.linalg.norm(c.fixed[i] - mid) <= 1.5 * size:
        frame.append(c.fixed[i][None, :])       # the centre where the centrodes touch
    lo, hi = np.vstack(frame).min(axis=0), np.vstack(frame).max(axis=0)
    pad = 0.25 * size
    lo, hi = lo - pad, hi + pad
    leaving = []
    for xy, style in ((c.fixed, dict(color="tab:red", label=w["fixed centrode"])),
                      (placed, dict(ls="--", color="tab:blue", label=w["moving centrode"]))):
        inside = np.isfinite(xy).all(axis=1) & np.all((xy >= lo) & (xy <= hi), axis=1)
        ax.plot(*u.convert(np.where(inside[:, None], xy, np.nan), "m").T, lw=1.5, **style)
        ends = inside & ~np.roll(inside, 1) | inside & ~np.roll(inside, -1)
        leaving.append(xy[ends & ~inside.all()])
    leaving = np.vstack(leaving)
    if len(leaving):
        ax.plot(*u.convert(leaving, "m").T, "^", ms=7, mfc="white", mec="black",
                ls="none", label=w["centrode leaves"], zorder=5)
    lo, hi = u.convert(lo, "m"), u.convert(hi, "m")
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    if c.defined[i]:
        numbers = {lk: k + 1 for k, lk in enumerate(
            [sol.mechanism.ground.name] + [x for x in sol.link_names if x != sol.mechanism.ground.name])}
        a, b = sorted((numbers[sol.mechanism.ground.name], numbers[link]))
        ax.plot(*u.convert(c.fixed[i], "m"), "o", color="black", ms=6,
                label=w["instant centre"].format(label=f"O{a}{b}"))
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.02, 1.0))
    ax.set_title(plain(w["centrodes title"].format(name=sol.mechanism.name, link=link)))
    decimal_commas(ax.figure, lang)
    return ax


def derivatives(d: Derivatives, *, x_label: str = "t [s]", y_label: str = "x",
                y_unit: str = "m", x_unit: str = "s", lang: str = "en"):
    """The measured curve and the smoothed one, then the velocity and the acceleration with
    their error bands, against the abscissa (Flores & Claro, §4.6.4).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> fig = kl.plot.derivatives(kl.solvers.differentiate(t, np.sin(2 * t)))
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['x [m]', 'dx/dt [m/s]', 'd²x/dt² [m/s²]']
    """
    import matplotlib.pyplot as plt
    w = words(lang)
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7, 7.5), layout="constrained")
    var = x_label.split(" ")[0]
    axes[0].plot(d.x, d.y + d.residual, ".", ms=2.5, color="0.55", label=w["data"])
    axes[0].plot(d.x, d.y, lw=1.4, color="black", label=w["smoothed"].format(window=d.window))
    axes[0].set_ylabel(plain(f"{y_label} [{y_unit}]"))
    axes[0].legend(fontsize="small")
    for ax, value, error, label, unit in (
            (axes[1], d.velocity, d.velocity_error, f"d{y_label}/d{var}", f"{y_unit}/{x_unit}"),
            (axes[2], d.acceleration, d.acceleration_error, f"d²{y_label}/d{var}²",
             f"{y_unit}/{x_unit}²")):
        ax.fill_between(d.x, value - error, value + error, color="tab:blue", alpha=0.25,
                        lw=0, label=w["error band"])
        ax.plot(d.x, value, lw=1.4, color="tab:blue", label=w["estimate"])
        ax.set_ylabel(plain(f"{label} [{unit}]"))
        ax.legend(fontsize="small")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(plain(x_label))
    axes[0].set_title(plain(w["derivatives title"].format(noise=number(d.noise, ".3g", lang),
                                                          unit=y_unit)))
    decimal_commas(fig, lang)
    return fig
