"""A cam's profile for drawings and cutting: SVG (a closed path) and DXF (a closed
LWPOLYLINE, through ezdxf), in a length unit of the model files'."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from kinelab.errors import ModelError, expected_one_of
from kinelab.model import LENGTH_UNITS

__all__ = ["profile_svg", "write_dxf"]


def _points(cam, unit: str) -> np.ndarray:
    """The profile's distinct points (the last sample repeats the first), in ``unit``."""
    if unit not in LENGTH_UNITS:
        raise ModelError(f"unit: {expected_one_of(unit, LENGTH_UNITS)}")
    xy = np.asarray(cam.profile, dtype=float) / LENGTH_UNITS[unit]
    if len(xy) > 1 and np.allclose(xy[0], xy[-1], rtol=0, atol=1e-12 * np.abs(xy).max()):
        xy = xy[:-1]
    return xy


def profile_svg(cam, unit: str = "mm") -> str:
    """The profile of ``cam`` (a :class:`~kinelab.cams.CamProfile`) as an SVG document: one
    closed path, drawn to scale in ``unit`` (y up, the cam's centre marked by a small cross).

    Examples
    --------
    >>> from kinelab.cams import MotionProgram, Segment, Follower, profile
    >>> p = MotionProgram([Segment("rise", 0, np.pi, 0.01, "cycloidal"),
    ...                    Segment("return", np.pi, 2 * np.pi, 0.01, "cycloidal")])
    >>> svg = profile(p, Follower("knife-edge"), 0.03, samples=9).to_svg("mm")
    >>> svg.count("<path"), 'width="' in svg
    (2, True)
    """
    xy = _points(cam, unit)
    ext = float(np.abs(xy).max())
    margin = 0.05 * ext
    lo = -ext - margin
    size = 2 * (ext + margin)
    shown, k = (unit, 1.0) if unit != "m" else ("cm", 100.0)   # SVG has no metre
    d = "M " + " L ".join(f"{x:.6f} {-y:.6f}" for x, y in xy) + " Z"
    c = 0.03 * ext
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n'
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{size * k:.4f}{shown}" '
            f'height="{size * k:.4f}{shown}" viewBox="{lo:.6f} {lo:.6f} {size:.6f} {size:.6f}">\n'
            f'  <title>cam profile ({unit})</title>\n'
            f'  <style>path {{ fill: none; stroke: black; stroke-width: {0.002 * size:.6f}; }}</style>\n'
            f'  <path class="profile" d="{d}"/>\n'
            f'  <path class="centre" d="M {-c:.6f} 0 L {c:.6f} 0 M 0 {-c:.6f} L 0 {c:.6f}"/>\n'
            '</svg>\n')


def write_dxf(cam, path: str | os.PathLike, unit: str = "mm") -> Path:
    """Write the profile of ``cam`` as a DXF drawing at ``path`` (atomically): a closed
    LWPOLYLINE on the layer PROFILE, its drawing units ``unit``."""
    import ezdxf
    from ezdxf import units as dxf_units

    from kinelab._files import atomic_write

    xy = _points(cam, unit)
    doc = ezdxf.new("R2010")
    doc.units = {"m": dxf_units.M, "cm": dxf_units.CM, "mm": dxf_units.MM, "in": dxf_units.IN}[unit]
    doc.layers.add("PROFILE")
    doc.modelspace().add_lwpolyline([(float(x), float(y)) for x, y in xy], format="xy",
                                    close=True, dxfattribs={"layer": "PROFILE"})
    return atomic_write(path, lambda f: doc.write(f))
