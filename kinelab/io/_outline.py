"""Link outlines and pivot holes, for drawings and cutting: SVG and DXF.

Each moving link becomes a plate: the rounded hull of its points (the convex hull grown by
half the link width, so a binary link is a slot-ended bar), with a hole at every point
(pivots, pins, coupler points).  A link that guides a slider gets a slot along the slide; a
slider block is a rectangle along its slide.  Outlines are closed polylines whose segments
are straight or circular (the DXF "bulge" of each vertex), so SVG and DXF draw the same shapes.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np

from kinelab._files import atomic_write
from kinelab.errors import ModelError, check_choice, describe, quoted, shown, suggest
from kinelab.io._modelfile import LENGTH_UNITS
from kinelab.kinematics import KinematicSolution
from kinelab.model import Mechanism, is_real, length_problem
from kinelab.solvers._arguments import flag

__all__ = ["Outline", "outlines", "to_svg", "to_dxf"]


@dataclass(frozen=True)
class Outline:
    """One part: closed polylines and circles, in metres.

    Attributes
    ----------
    link : str
    boundary : ndarray, shape (n, 3)
        The plate's outline: x, y and the bulge of the segment from this vertex to the next
        (0 straight, tan(angle / 4) for an arc turning CCW through ``angle``).
    holes : ndarray, shape (h, 3)
        x, y and diameter of each hole.
    slots : tuple of ndarray, shape (m, 3)
        Closed outlines cut out of the plate (slots for sliders).
    """

    link: str
    boundary: np.ndarray
    holes: np.ndarray
    slots: tuple[np.ndarray, ...] = ()


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _hull(points: np.ndarray) -> np.ndarray:
    """Convex hull, CCW (Andrew's monotone chain); collinear points dropped."""
    pts = np.unique(points.round(15), axis=0)
    if len(pts) <= 2:
        return pts

    def half(seq):
        out = []
        for p in seq:
            while len(out) >= 2 and _cross(out[-1] - out[-2], p - out[-2]) <= 1e-18:
                out.pop()
            out.append(p)
        return out
    lower, upper = half(pts), half(pts[::-1])
    hull = np.array(lower[:-1] + upper[:-1])
    return hull if len(hull) >= 2 else pts[[0, -1]]


def _rounded(points: np.ndarray, r: float) -> np.ndarray:
    """The hull of ``points`` grown by ``r``: straight sides and an arc at every corner."""
    hull = _hull(points)
    if len(hull) == 1:                     # a single point: a circle, as two half arcs
        c = hull[0]
        return np.array([[c[0] + r, c[1], 1.0], [c[0] - r, c[1], 1.0]])
    out = []
    n = len(hull)
    for i in range(n):
        a, b = hull[i], hull[(i + 1) % n]
        d = (b - a) / np.linalg.norm(b - a)
        normal = np.array([d[1], -d[0]])            # outward for a CCW hull
        c = hull[(i + 2) % n]
        d2 = (c - b) / np.linalg.norm(c - b)
        normal2 = np.array([d2[1], -d2[0]])
        turn = math.atan2(_cross(normal, normal2), normal @ normal2) % (2 * math.pi)
        out.append([*(a + r * normal), 0.0])
        out.append([*(b + r * normal), math.tan(turn / 4)])
    return np.array(out)


def _slot(a: np.ndarray, b: np.ndarray, width: float) -> np.ndarray:
    return _rounded(np.array([a, b]), width / 2)


def _rectangle(c: np.ndarray, u: np.ndarray, length: float, width: float) -> np.ndarray:
    v = np.array([-u[1], u[0]])
    corners = [c - u * length / 2 - v * width / 2, c + u * length / 2 - v * width / 2,
               c + u * length / 2 + v * width / 2, c - u * length / 2 + v * width / 2]
    return np.array([[*p, 0.0] for p in corners])


def _size(m: Mechanism) -> float:
    lengths = [math.dist(m.point(link.points[0]).xy, m.point(link.points[1]).xy)
               for link in m.links if not link.ground and len(link.points) >= 2]
    return float(np.median(lengths)) if lengths else 1.0


def outlines(model: Mechanism, *, width: float | None = None, hole: float | None = None,
             ground: bool = False, sol=None) -> list[Outline]:
    """The parts of a planar mechanism at its sketch, each in the plane's coordinates.

    Parameters
    ----------
    model : Mechanism
    width : float, optional
        Width of the bars, m (default: 15 % of the median link length).
    hole : float, optional
        Hole (and slot) diameter, m (default: 40 % of the width).
    ground : bool
        Include the ground link (a plate through its pivots).
    sol : KinematicSolution, optional
        A sweep: slots then span the slide's whole travel; without it, the guide's own extent.
    """
    if not isinstance(model, Mechanism) or model.space != "planar":
        raise ModelError("model: expected a planar kinelab Mechanism")
    flag("ground", ground)
    if sol is not None and not isinstance(sol, KinematicSolution):
        raise ModelError(f"sol: expected a KinematicSolution of the model (a sweep of its inputs) "
                         f"or None, got {describe(sol)}")
    w = width if width is not None else 0.15 * _size(model)
    d = hole if hole is not None else (0.4 * w if is_real(w) else None)
    if not (is_real(w) and is_real(d) and 0 < d < w):
        raise ModelError(f"width, hole: expected 0 < hole < width, got width {describe(w)} m and "
                         f"hole {describe(d)} m")
    for name, value in (("width", w), ("hole", d)):
        why = length_problem(float(value))      # a drawing's numbers stay finite
        if why:
            raise ModelError(f"{name}: {why}, got {float(value):g} m")
    xy = {p.name: np.array(p.xy) for p in model.points}
    parts = []
    for link in model.links:
        if link.ground and not ground:
            continue
        pts = np.array([xy[p] for p in link.points])
        slides = [j for j in model.joints if j.type == "P" and j.links[1] == link.name]
        if len(link.points) == 1 and slides:
            u = np.asarray(slides[0].axis, float) / math.hypot(*slides[0].axis)
            boundary = _rectangle(pts[0], u, 2.0 * w, w)
        else:
            boundary = _rounded(pts, w / 2)
        slots = []
        for j in model.joints:
            if j.type != "P" or j.links[0] != link.name:
                continue
            u = np.asarray(j.axis, float) / math.hypot(*j.axis)
            p0 = xy[j.point]
            if sol is not None:
                s = np.asarray(sol.slide(j.name))
                origin = xy[j.origin or link.points[0]]
                s0 = float(u @ (p0 - origin))
                travel = s[np.isfinite(s)] - s0
                lo, hi = float(travel.min()), float(travel.max())
            else:
                proj = (pts - p0) @ u
                lo, hi = float(proj.min()), float(proj.max())
            if hi - lo > 1e-12:
                slots.append(_slot(p0 + lo * u, p0 + hi * u, d))
        holes = np.array([[*xy[p], d] for p in link.points])
        parts.append(Outline(link.name, boundary, holes, tuple(slots)))
    if not parts:
        raise ModelError("model: it has no moving link to draw")
    return parts


def _layout(parts: list[Outline], layout: str, gap: float) -> list[tuple[Outline, np.ndarray, float]]:
    """(part, translation, rotation) placing each part: as assembled, or laid flat in a row."""
    if layout == "assembly":
        return [(p, np.zeros(2), 0.0) for p in parts]
    placed, x = [], 0.0
    for p in parts:
        h = p.holes[:, :2]
        angle = -math.atan2(*(h[1] - h[0])[::-1]) if len(h) >= 2 else 0.0
        R = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
        b = _extent(p.boundary) @ R.T
        shift = np.array([x - b[:, 0].min(), -b[:, 1].min()])
        placed.append((p, shift, angle))
        x += np.ptp(b[:, 0]) + gap
    return placed


_OPTIONS = ("width", "hole", "ground", "sol")     # outlines' keywords


def _placed(model, unit: str, layout: str, options) -> tuple[float, list]:
    """The drawing's unit scale and its outlines placed as ``layout`` asks (two hole
    diameters apart when laid out as parts)."""
    k = _check_unit(unit)
    check_choice("layout", layout, ("parts", "assembly"))
    for key in options:
        if key not in _OPTIONS:
            raise ModelError(f"{shown(key)}: unknown option{suggest(key, _OPTIONS)}; the options of "
                             f"a drawing are unit, layout, {quoted(_OPTIONS)}")
    parts = outlines(model, **options)
    return k, _layout(parts, layout, 2.0 * float(np.max(parts[0].holes[:, 2])))


def _extent(poly: np.ndarray) -> np.ndarray:
    """Points that bound a bulged polyline (vertices and arc mid-points are enough here)."""
    out = [poly[:, :2]]
    n = len(poly)
    for i in range(n):
        if poly[i, 2]:
            a, b = poly[i, :2], poly[(i + 1) % n, :2]
            chord = b - a
            normal = np.array([chord[1], -chord[0]])
            sag = poly[i, 2] * np.linalg.norm(chord) / 2      # bulge = tan(arc angle / 4)
            out.append(((a + b) / 2 + normal / np.linalg.norm(normal) * sag)[None])
    return np.vstack(out)


def _transform(poly: np.ndarray, shift: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    xy = poly[:, :2] @ np.array([[c, -s], [s, c]]).T + shift
    return np.column_stack([xy, poly[:, 2:]])


def _check_unit(unit: str) -> float:
    check_choice("unit", unit, LENGTH_UNITS)
    return LENGTH_UNITS[unit]


def _path(poly: np.ndarray, k: float) -> str:
    """SVG path data of a bulged polyline (y flipped: SVG's y points down)."""
    n = len(poly)
    parts = [f"M {poly[0, 0] / k:.6f} {-poly[0, 1] / k:.6f}"]
    for i in range(n):
        a, b, bulge = poly[i, :2], poly[(i + 1) % n, :2], poly[i, 2]
        end = f"{b[0] / k:.6f} {-b[1] / k:.6f}"
        if bulge == 0:
            parts.append(f"L {end}")
        else:
            theta = 4 * math.atan(bulge)
            r = np.linalg.norm(b - a) / (2 * abs(math.sin(theta / 2))) / k
            large = int(abs(theta) > math.pi)
            sweep = 0 if theta > 0 else 1        # CCW in the plane is clockwise on screen
            parts.append(f"A {r:.6f} {r:.6f} 0 {large} {sweep} {end}")
    return " ".join(parts) + " Z"


def to_svg(model: Mechanism, path: str | os.PathLike, *, unit: str = "mm",
           layout: Literal["parts", "assembly"] = "parts", **options) -> Path:
    """Write the links' outlines and holes as SVG, one group per link, sized in ``unit``.

    ``layout="parts"`` lays each link flat, in a row (for cutting); ``"assembly"`` draws them
    where the sketch puts them.  Other options go to :func:`outlines` (``width``, ``hole``,
    ``ground``, ``sol``).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> fb = kl.mechanisms.fourbar(0.3, 0.1, 0.3, 0.25)
    >>> path = kl.io.to_svg(fb, pathlib.Path(tempfile.mkdtemp()) / "fb.svg")
    >>> path.read_text().count('class="hole"')          # two holes in each of three links
    6
    """
    k, placed = _placed(model, unit, layout, options)
    body = []
    everything = []
    for part, shift, angle in placed:
        boundary = _transform(part.boundary, shift, angle)
        holes = _transform(part.holes, shift, angle)
        everything += [_extent(boundary)]
        items = [f'    <path class="outline" d="{_path(boundary, k)}"/>']
        items += [f'    <path class="slot" d="{_path(_transform(s, shift, angle), k)}"/>'
                  for s in part.slots]
        items += [f'    <circle class="hole" cx="{h[0] / k:.6f}" cy="{-h[1] / k:.6f}" r="{h[2] / 2 / k:.6f}"/>'
                  for h in holes]
        body.append(f'  <g id="{_xml(part.link)}">\n' + "\n".join(items) + "\n  </g>")
    ext = np.vstack(everything) / k
    margin = 0.05 * float(np.ptp(ext, axis=0).max())
    x0, x1 = ext[:, 0].min() - margin, ext[:, 0].max() + margin
    y0, y1 = -ext[:, 1].max() - margin, -ext[:, 1].min() + margin
    svg = (f'<?xml version="1.0" encoding="UTF-8"?>\n'
           f'<svg xmlns="http://www.w3.org/2000/svg" width="{x1 - x0:.4f}{unit}" '
           f'height="{y1 - y0:.4f}{unit}" viewBox="{x0:.6f} {y0:.6f} {x1 - x0:.6f} {y1 - y0:.6f}">\n'
           f'  <title>{_xml(model.name)}: link outlines ({unit})</title>\n'
           '  <style>path, circle { fill: none; stroke: black; stroke-width: '
           f'{0.002 * (x1 - x0):.4f}; }}</style>\n' + "\n".join(body) + "\n</svg>\n")
    return atomic_write(path, lambda f: f.write(svg))


def _xml(text: str) -> str:
    return (str(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;"))


def to_dxf(model: Mechanism, path: str | os.PathLike, *, unit: str = "mm",
           layout: Literal["parts", "assembly"] = "parts", **options) -> Path:
    """Write the links' outlines (closed polylines) and holes (circles) as DXF, in ``unit``;
    layers OUTLINE, SLOTS and HOLES.  Options as :func:`to_svg`.

    Examples
    --------
    >>> import tempfile, pathlib, ezdxf
    >>> sc = kl.mechanisms.slider_crank(0.05, 0.2)
    >>> path = kl.io.to_dxf(sc, pathlib.Path(tempfile.mkdtemp()) / "sc.dxf")
    >>> sorted(e.dxftype() for e in ezdxf.readfile(path).modelspace())
    ['CIRCLE', 'CIRCLE', 'CIRCLE', 'CIRCLE', 'CIRCLE', 'LWPOLYLINE', 'LWPOLYLINE', 'LWPOLYLINE']
    """
    import ezdxf
    from ezdxf import units as dxf_units

    k, placed = _placed(model, unit, layout, options)
    doc = ezdxf.new("R2010")
    doc.units = {"m": dxf_units.M, "cm": dxf_units.CM, "mm": dxf_units.MM, "in": dxf_units.IN}[unit]
    for layer in ("OUTLINE", "SLOTS", "HOLES"):
        doc.layers.add(layer)
    msp = doc.modelspace()
    for part, shift, angle in placed:
        boundary = _transform(part.boundary, shift, angle)
        msp.add_lwpolyline([(x / k, y / k, b) for x, y, b in boundary], format="xyb", close=True,
                           dxfattribs={"layer": "OUTLINE"})
        for s in part.slots:
            s = _transform(s, shift, angle)
            msp.add_lwpolyline([(x / k, y / k, b) for x, y, b in s], format="xyb", close=True,
                               dxfattribs={"layer": "SLOTS"})
        for h in _transform(part.holes, shift, angle):
            msp.add_circle((h[0] / k, h[1] / k), h[2] / 2 / k, dxfattribs={"layer": "HOLES"})
    return atomic_write(path, lambda f: doc.write(f))
