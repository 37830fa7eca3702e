"""Figures of a disk cam: its SVAJ diagram, its profile, its pressure angle and radius of
curvature over the cycle.  matplotlib is imported inside each function; each returns the
Figure, drawn in ``units`` (default SI) with the cam angle in ``units.angle``, its words in
``lang`` ("en" or "pt", with decimal commas)."""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from kinelab.cams import CamProfile, FollowerForces
from kinelab.errors import ModelError, describe
from kinelab.model import Units
from kinelab.plot._words import decimal_commas, number, words

__all__ = ["cam_svaj", "cam_profile", "cam_pressure", "cam_curvature", "cam_forces"]


def _check(cam) -> None:
    if not isinstance(cam, CamProfile):
        raise ModelError(f"cam: expected a CamProfile (kinelab.cams.profile), got {describe(cam)}")


def _lift_unit(cam: CamProfile, u: Units) -> tuple[float, str]:
    """Scale and unit of S: a length, or an angle for an oscillating follower."""
    if cam.follower.motion == "oscillating":
        return u.scale("rad"), u.angle
    return u.scale("m"), u.length


def cam_svaj(cam: CamProfile, *, omega: float | None = None,
             units: Units | Mapping[str, str] | None = None, lang: str = "en"):
    """S, V, A, J against the cam angle, one panel each: per cam angle, or per second at the
    cam speed ``omega`` (rad/s) when given.  Discontinuities show as vertical jumps."""
    import matplotlib.pyplot as plt
    _check(cam)
    w = words(lang)
    u = Units.resolve(units)
    k, lu = _lift_unit(cam, u)
    a = u.scale("rad")
    sv = cam.svaj
    x = sv.theta / a
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(7, 8), constrained_layout=True)
    if omega is None:
        rows = [(sv.S / k, f"S [{lu}]"), (sv.V / k * a, f"V [{lu}/{u.angle}]"),
                (sv.A / k * a ** 2, f"A [{lu}/{u.angle}^2]"),
                (sv.J / k * a ** 3, f"J [{lu}/{u.angle}^3]")]
    else:
        s, v, acc, j = sv.in_time(omega)
        rows = [(s / k, f"s [{lu}]"), (v / k, f"v [{lu}/s]"), (acc / k, f"a [{lu}/s^2]"),
                (j / k, f"j [{lu}/s^3]")]
    for ax, (y, label) in zip(axes, rows):
        ax.plot(x, y, lw=1.2)
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set_ylabel(label)
        ax.grid(True, lw=0.3)
    axes[-1].set_xlabel(f"{w['cam angle']} [{u.angle}]")
    axes[0].set_title(w["svaj title"])
    decimal_commas(fig, lang)
    return fig


def cam_profile(cam: CamProfile, *, units: Units | Mapping[str, str] | None = None,
                lang: str = "en"):
    """The cam's profile, its pitch curve (dashed), base and prime circles, to scale."""
    import matplotlib.pyplot as plt
    _check(cam)
    w = words(lang)
    u = Units.resolve(units)
    k = u.scale("m")
    fig, ax = plt.subplots(figsize=(6.5, 6.5), constrained_layout=True)
    t = np.linspace(0.0, 2 * np.pi, 361)
    ax.plot(*(cam.profile / k).T, color="k", lw=1.5, label=w["cam profile"])
    if not cam.follower.flat:
        ax.plot(*(cam.pitch / k).T, "--", color="C0", lw=1.0, label=w["pitch curve"])
    ax.plot(cam.base_radius / k * np.cos(t), cam.base_radius / k * np.sin(t), ":", color="0.5",
            lw=0.8, label=w["base circle"])
    if cam.undercut.any():
        ax.plot(*(cam.profile[cam.undercut] / k).T, "x", color="C3", ms=4, label=w["undercut"])
    ax.plot([0], [0], "+", color="k")
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.set_title(w["cam title"].format(motion=w[cam.follower.motion], type=w[cam.follower.type]))
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(True, lw=0.3)
    decimal_commas(fig, lang)
    return fig


def cam_pressure(cam: CamProfile, *, limit: float | None = None,
                 units: Units | Mapping[str, str] | None = None, lang: str = "en"):
    """The pressure angle over the cycle, with the limit (rad) when given."""
    import matplotlib.pyplot as plt
    _check(cam)
    w = words(lang)
    u = Units.resolve(units)
    a = u.scale("rad")
    fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
    ax.plot(cam.theta / a, cam.pressure_angle / a, lw=1.2, label=w["pressure angle"])
    if limit is not None:
        for s in (1, -1):
            ax.axhline(s * limit / a, color="C3", lw=0.8, ls="--",
                       label=w["limit"] if s == 1 else None)
    phi, at = cam.largest_pressure_angle
    ax.plot([at / a], [phi / a], "o", color="C1",
            label=w["largest"].format(value=number(abs(phi) / a, ".4g", lang), unit=u.angle))
    ax.set_xlabel(f"{w['cam angle']} [{u.angle}]")
    ax.set_ylabel(f"{w['pressure angle']} [{u.angle}]")
    ax.legend(fontsize=8)
    ax.grid(True, lw=0.3)
    decimal_commas(fig, lang)
    return fig


def cam_curvature(cam: CamProfile, *, units: Units | Mapping[str, str] | None = None,
                  lang: str = "en"):
    """The radius of curvature of the profile (and of the pitch curve for a roller) over the
    cycle, convex positive; straight and nearly straight parts, whose radius runs off to
    infinity, are left out beyond 5 prime radii (gaps in the curves)."""
    import matplotlib.pyplot as plt
    _check(cam)
    w = words(lang)
    u = Units.resolve(units)
    a, k = u.scale("rad"), u.scale("m")
    cap = 5 * cam.prime_radius
    fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
    x = cam.theta / a
    if cam.follower.type == "roller":
        r = cam.pitch_radius
        ax.plot(x, np.ma.masked_where(np.abs(r) > cap, r) / k, "--", lw=1.0, label=w["pitch curve"])
    r = cam.profile_radius
    ax.plot(x, np.ma.masked_where(np.abs(r) > cap, r) / k, lw=1.2, label=w["cam profile"])
    if cam.follower.type == "roller":
        ax.axhline(cam.follower.roller_radius / k, color="C3", lw=0.8, ls=":",
                   label=w["roller radius"])
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel(f"{w['cam angle']} [{u.angle}]")
    ax.set_ylabel(f"{w['radius of curvature']} [{u.length}]")
    ax.legend(fontsize=8)
    ax.grid(True, lw=0.3)
    decimal_commas(fig, lang)
    return fig


def cam_forces(forces: FollowerForces, *, units: Units | Mapping[str, str] | None = None,
               lang: str = "en"):
    """The contact force between cam and follower (the zero line drawn, where it is not above
    0 — the follower jumps — shaded) and the cam shaft's torque with its mean, over the
    cycle; forces in N, torques in N m, the cam angle in ``units.angle``."""
    import matplotlib.pyplot as plt
    if not isinstance(forces, FollowerForces):
        raise ModelError(f"forces: expected a FollowerForces (kinelab.cams.follower_forces), "
                         f"got {describe(forces)}")
    w = words(lang)
    u = Units.resolve(units)
    a = u.scale("rad")
    x = forces.theta / a
    osc = forces.motion == "oscillating"
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 6),
                                      constrained_layout=True)
    name = w["contact moment"] if osc else w["contact force"]
    top.plot(x, forces.contact_force, lw=1.2, label=name)
    top.axhline(0.0, color="k", lw=0.8)
    if forces.jumps:
        top.fill_between(x, 0, 1, where=~forces.contact, transform=top.get_xaxis_transform(),
                         color="C3", alpha=0.2, step="mid", lw=0, label=w["jump"])
    f, at = forces.least_force
    top.plot([at / a], [f], "o", color="C1",
             label=w["least"].format(value=number(f, ".4g", lang), unit="N m" if osc else "N"))
    top.set_ylabel(f"{name} [{'N m' if osc else 'N'}]")
    top.set_title(w["follower dynamics"].format(rpm=number(forces.speed * 30 / np.pi, ".4g", lang)))
    top.legend(fontsize=8)
    top.grid(True, lw=0.3)
    bottom.plot(x, forces.torque, lw=1.2, color="C2", label=w["shaft torque"])
    bottom.axhline(0.0, color="0.6", lw=0.6)
    mean = forces.mean_torque
    mean = 0.0 if abs(mean) <= 1e-12 * np.abs(forces.torque).max() else mean   # an exact 0
    bottom.axhline(mean, color="C2", lw=0.8, ls="--",
                   label=w["mean"].format(value=number(mean, ".4g", lang)))
    bottom.set_ylabel(f"{w['cam shaft torque']} [N m]")
    bottom.set_xlabel(f"{w['cam angle']} [{u.angle}]")
    bottom.legend(fontsize=8)
    bottom.grid(True, lw=0.3)
    decimal_commas(fig, lang)
    return fig
