"""The profile as DXF (read back with ezdxf) and SVG (parsed as XML)."""
import re
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest

from kinelab.cams import Follower, MotionProgram, Segment, profile

d = np.radians


@pytest.fixture
def cam():
    p = MotionProgram([Segment("rise", 0, d(120), 0.02, "modified-trapezoid"),
                       Segment("dwell", d(120), d(200)),
                       Segment("return", d(200), d(320), 0.02, "4-5-6-7"),
                       Segment("dwell", d(320), d(360))])
    return profile(p, Follower("roller", offset=0.004, roller_radius=0.008), 0.035, samples=361)


@pytest.mark.parametrize("unit, scale, code", [("mm", 1000.0, 4), ("m", 1.0, 6), ("in", 1 / 0.0254, 1)])
def test_dxf_is_one_closed_polyline_of_the_profile_in_the_unit(cam, tmp_path, unit, scale, code):
    path = cam.to_dxf(tmp_path / "cam.dxf", unit)
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == code
    (poly,) = list(doc.modelspace())
    assert poly.dxftype() == "LWPOLYLINE" and poly.closed and poly.dxf.layer == "PROFILE"
    pts = np.array([(x, y) for x, y, *_ in poly.get_points()])
    assert pts == pytest.approx(cam.profile[:-1] * scale, rel=1e-12, abs=1e-12 * scale)


def test_svg_path_is_the_profile_in_the_unit_with_y_up(cam):
    root = ET.fromstring(cam.to_svg("mm"))
    ns = {"svg": "http://www.w3.org/2000/svg"}
    assert root.get("width").endswith("mm")
    (path,) = [p for p in root.findall("svg:path", ns) if p.get("class") == "profile"]
    data = path.get("d")
    assert data.startswith("M ") and data.endswith(" Z")
    xy = np.array(re.findall(r"(-?[0-9.]+) (-?[0-9.]+)", data), dtype=float)
    assert xy[:, 0] == pytest.approx(cam.profile[:-1, 0] * 1000, abs=1e-6)
    assert -xy[:, 1] == pytest.approx(cam.profile[:-1, 1] * 1000, abs=1e-6)
    x0, y0, w, h = map(float, root.get("viewBox").split())
    assert x0 <= xy[:, 0].min() and x0 + w >= xy[:, 0].max()
    assert y0 <= xy[:, 1].min() and y0 + h >= xy[:, 1].max()


def test_svg_in_metres_gives_a_size_svg_knows(cam):
    root = ET.fromstring(cam.to_svg("m"))
    assert root.get("width").endswith("cm")
