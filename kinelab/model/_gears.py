"""Gear pairs as joints of a planar model: what a ``G`` joint says and what it must satisfy.

A gear joint ``G`` joins two links ``(a, b)`` that turn on a third, the *carrier* ``c`` (the
ground for a train of fixed axes, the arm of an epicyclic train).  Its pitch circles roll on
each other without slipping, so that, relative to the carrier,

- an external pair turns its gears opposite ways:
  ``(theta_a - theta_c) r_a = -(theta_b - theta_c) r_b``;
- an internal pair (a gear inside a ring) turns them the same way:
  ``(theta_a - theta_c) r_a = +(theta_b - theta_c) r_b``;
- a rack and pinion (``a`` the pinion, ``b`` the rack, sliding on the carrier in a prismatic
  joint) moves the rack by the pinion's pitch radius per radian:
  ``s_b - s_b0 = r_a ((theta_a - theta_c) - (theta_a0 - theta_c0))``, ``s`` the rack's slide
  along its joint's axis.  Convention: a pinion turning counter-clockwise drives the rack
  along ``+axis`` (its pitch line lies to the right of the axis through the pinion's centre);
  reverse the axis to reverse the sense.

The relation is linear in the angles: the sketch fixes its constant (each gear's angle at the
sketch is its phase), and ``theta_b = theta_c + k (theta_a - theta_c) + const`` with
``k = -r_a / r_b`` (external) or ``+r_a / r_b`` (internal).
"""
from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from kinelab.errors import describe, shown
from kinelab.model._values import is_real, length_problem

__all__ = ["GEAR_MESHES", "GearMesh", "gear_mesh", "gear_problems", "GEAR_FIELDS"]

GEAR_MESHES = ("external", "internal", "rack")
"""The kinds of gear pair a ``G`` joint can be."""

GEAR_FIELDS = ("mesh", "ratio", "radii", "teeth", "radius", "carrier")
"""The fields of a joint that only a gear joint ``G`` has."""


@dataclass(frozen=True)
class GearMesh:
    """A gear joint resolved against its model.

    Attributes
    ----------
    joint : str
    mesh : {'external', 'internal', 'rack'}
    a, b : str
        The two gears (``a`` the pinion and ``b`` the rack of a rack and pinion).
    carrier : str
        The link that carries both axes.
    k : float
        Spur pairs: ``theta_b - theta_c = k (theta_a - theta_c) + const``, ``k = -r_a/r_b``
        (external) or ``+r_a/r_b`` (internal).  Rack: the pinion's pitch radius (m), the rack's
        advance per radian of the pinion relative to the carrier.
    centre_a, centre_b : str or None
        The points where ``a`` and ``b`` turn on the carrier (``centre_b`` is None for a rack).
    slide : str or None
        A rack's prismatic joint on the carrier.
    """

    joint: str
    mesh: str
    a: str
    b: str
    carrier: str
    k: float
    centre_a: str
    centre_b: str | None
    slide: str | None

    @property
    def ratio(self) -> float:
        """Spur pairs: the gear ratio ``r_b / r_a`` (= ``N_b / N_a``), positive."""
        return 1.0 / abs(self.k)


def _hinge(m, link: str, carrier: str, kind: str = "R"):
    """R: a revolute joint of ``link`` at a point the carrier also carries (on the carrier
    itself, or on a shaft coaxial with it there).  P: the prismatic joint (carrier, link)."""
    held = set(m.link(carrier).points)
    for j in m.joints:
        if j.type != kind or not isinstance(j.links, (tuple, list)) or link not in j.links:
            continue
        if kind == "R" and isinstance(j.point, str) and j.point in held:
            return j
        if kind == "P" and tuple(j.links) == (carrier, link):
            return j
    return None


def _whole(v: Any) -> bool:
    return (isinstance(v, numbers.Integral) and not isinstance(v, bool)) or (
        is_real(v) and float(v).is_integer())


def gear_problems(m, j, links: Mapping[str, Any]) -> list[str]:
    """Every problem of gear joint ``j`` of mechanism ``m`` (its links already checked to be
    two different declared links), each a one-line message naming the field."""
    out: list[str] = []
    where = f"joint {shown(j.name)}"
    a, b = j.links
    mesh = "external" if j.mesh is None else j.mesh
    if not isinstance(mesh, str) or mesh not in GEAR_MESHES:
        return [f"{where}: mesh: expected one of 'external', 'internal', 'rack', got "
                f"{describe(j.mesh)}"]
    given = [f for f in ("ratio", "radii", "teeth") if getattr(j, f) is not None]
    if mesh == "rack":
        for f in given:
            out.append(f"{where}: {f}: a rack and pinion is set by radius (the pinion's pitch "
                       f"radius, m), not by {f}; remove {f}")
        if j.radius is None:
            out.append(f"{where}: radius: a rack and pinion needs the pinion's pitch radius "
                       "(radius = ..., m)")
        elif not is_real(j.radius) or float(j.radius) <= 0:
            out.append(f"{where}: radius: expected a positive length (m), got {describe(j.radius)}")
        elif why := length_problem(float(j.radius)):
            out.append(f"{where}: radius: {why}, got {float(j.radius):g} m")
    else:
        if j.radius is not None:
            out.append(f"{where}: radius: only a rack and pinion (mesh = 'rack') has one; give "
                       "radii = [r_a, r_b] for a spur pair")
        if not given:
            out.append(f"{where}: ratio: an {mesh} gear pair needs its ratio: give one of ratio "
                       "(N_b / N_a), radii = [r_a, r_b] (m) or teeth = [N_a, N_b]")
        elif len(given) > 1:
            out.append(f"{where}: {' and '.join(given)}: give only one of ratio, radii and teeth")
        elif j.ratio is not None:
            if not is_real(j.ratio) or float(j.ratio) <= 0 or not 1e-6 <= float(j.ratio) <= 1e6:
                out.append(f"{where}: ratio: expected a positive number from 1e-06 to 1e+06 "
                           f"(N_b / N_a, the teeth of {shown(b)} over those of {shown(a)}), got "
                           f"{describe(j.ratio)}")
        elif j.radii is not None:
            r = j.radii
            if (not isinstance(r, (tuple, list)) or len(r) != 2 or not all(map(is_real, r))
                    or min(float(x) for x in r) <= 0):
                out.append(f"{where}: radii: expected two positive pitch radii [r_a, r_b] (m), "
                           f"got {describe(r)}")
            elif why := next(filter(None, (length_problem(float(x)) for x in r)), None):
                out.append(f"{where}: radii: {why}, got {describe(r)}")
        else:
            t = j.teeth
            if not isinstance(t, (tuple, list)) or len(t) != 2 or not all(map(_whole, t)):
                out.append(f"{where}: teeth: expected two whole numbers of teeth [N_a, N_b], got "
                           f"{describe(t)}")
            elif min(t) <= 0:
                out.append(f"{where}: teeth: expected positive numbers of teeth, got "
                           f"{describe(t)}; a gear has at least one tooth")
            elif max(t) > 1e6:
                out.append(f"{where}: teeth: expected at most 1e+06 teeth, got {describe(t)}")
        if not out and mesh == "internal" and _spur_ratio(j) == 1.0:
            out.append(f"{where}: mesh: an internal pair needs a ring larger than its pinion, "
                       "but the ratio is 1; make it external or change the sizes")
    carrier = j.carrier if j.carrier is not None else m.ground.name
    if not isinstance(carrier, str) or carrier not in links:
        out.append(f"{where}: carrier: expected a declared link (the link carrying both gears' "
                   f"axes; the ground by default), got {describe(j.carrier)}")
        return out
    if carrier in (a, b):
        out.append(f"{where}: carrier: the carrier {shown(carrier)} cannot be one of the gears; "
                   "name the link that carries both axes (the ground, or the arm)")
        return out
    ha = _hinge(m, a, carrier)
    if ha is None:
        out.append(f"{where}: links: gear {shown(a)} must turn on the carrier {shown(carrier)} "
                   f"(an R joint of {shown(a)} at a point {shown(carrier)} carries); add an R "
                   f"joint between {shown(a)} and {shown(carrier)} at its centre")
    if mesh == "rack":
        if _hinge(m, b, carrier, "P") is None:
            out.append(f"{where}: links: the rack {shown(b)} must slide on the carrier "
                       f"{shown(carrier)}; add a P joint with links = [{shown(carrier)}, "
                       f"{shown(b)}]")
    else:
        hb = _hinge(m, b, carrier)
        if hb is None:
            out.append(f"{where}: links: gear {shown(b)} must turn on the carrier "
                       f"{shown(carrier)} (an R joint of {shown(b)} at a point {shown(carrier)} "
                       f"carries); add an R joint between {shown(b)} and {shown(carrier)} at its "
                       "centre")
        elif ha is not None and isinstance(ha.point, str) and isinstance(hb.point, str):
            try:
                pa, pb = m.point(ha.point), m.point(hb.point)
                if math.dist(pa.xy, pb.xy) <= 1e-12:
                    out.append(f"{where}: the centres {shown(ha.point)} and {shown(hb.point)} of "
                               "the two gears are at one place in the sketch; gears in mesh turn "
                               "about different centres")
            except Exception:   # an undeclared point: reported by the joint's own check
                pass
    return out


def _spur_ratio(j) -> float:
    """N_b / N_a of a checked spur gear joint."""
    if j.ratio is not None:
        return float(j.ratio)
    if j.radii is not None:
        return float(j.radii[1]) / float(j.radii[0])
    return float(j.teeth[1]) / float(j.teeth[0])


def gear_mesh(m, j) -> GearMesh:
    """The gear joint ``j`` of a checked mechanism ``m``, resolved: its carrier, ``k``, the
    centres of its gears (and a rack's prismatic joint)."""
    a, b = j.links
    mesh = j.mesh or "external"
    carrier = j.carrier if j.carrier is not None else m.ground.name
    ca = _hinge(m, a, carrier).point
    if mesh == "rack":
        return GearMesh(j.name, mesh, a, b, carrier, float(j.radius), ca, None,
                        _hinge(m, b, carrier, "P").name)
    k = 1.0 / _spur_ratio(j)
    return GearMesh(j.name, mesh, a, b, carrier, -k if mesh == "external" else k, ca,
                    _hinge(m, b, carrier).point, None)
