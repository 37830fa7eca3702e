"""``kinelab cam TASK``: a disk cam from a motion program.

A click command of the main ``kinelab`` group.  It reads a TOML task file (its format is in
``docs/cams.md``), solves it with :func:`kinelab.cams.read_cam_task` and
:func:`~kinelab.cams.solve_cam_task`, writes the figures, the profile (DXF, SVG) and the SVAJ
table as one set (:func:`kinelab._files.outputs`: all of them, or none), and prints a summary
in the task's units; the group turns kinelab errors into one-line messages with exit status 2.
"""
from __future__ import annotations

import math
from pathlib import Path

import click

from kinelab.cli._main import LANG

__all__ = ["cam_command"]


def _columns(sol) -> dict:
    """The SVAJ table in the task's units: per cam angle and per second."""
    import numpy as np
    cam, u = sol.cam, sol.task.units
    osc = cam.follower.motion == "oscillating"
    k, lu = (u.scale("rad"), u.angle) if osc else (u.scale("m"), u.length)
    a, m = u.scale("rad"), u.scale("m")
    sv = cam.svaj
    s, v, acc, j = sv.in_time(sol.task.speed)
    with np.errstate(divide="ignore"):
        kappa = 1.0 / cam.profile_radius
    out = {
        f"theta [{u.angle}]": sv.theta / a,
        f"S [{lu}]": sv.S / k, f"V [{lu}/{u.angle}]": sv.V / k * a,
        f"A [{lu}/{u.angle}^2]": sv.A / k * a ** 2, f"J [{lu}/{u.angle}^3]": sv.J / k * a ** 3,
        f"v [{lu}/s]": v / k, f"a [{lu}/s^2]": acc / k, f"j [{lu}/s^3]": j / k,
        f"pressure_angle [{u.angle}]": cam.pressure_angle / a,
        f"pitch_curvature [1/{u.length}]": cam.pitch_curvature * m,
        f"profile_curvature [1/{u.length}]": kappa * m,
        f"pitch.x [{u.length}]": cam.pitch[:, 0] / m, f"pitch.y [{u.length}]": cam.pitch[:, 1] / m,
        f"profile.x [{u.length}]": cam.profile[:, 0] / m,
        f"profile.y [{u.length}]": cam.profile[:, 1] / m,
    }
    ff = sol.forces
    if ff is not None:       # forces and torques stay in SI whatever the task's units
        out["contact_moment [N m]" if osc else "contact_force [N]"] = ff.contact_force
        out["shaft_torque [N m]"] = ff.torque
    return out


def _verdict(sol, lang: str = "en") -> list[str]:
    """The jump check in one line, and the shaft torque in another."""
    from kinelab.cli._words import SAID, formatted
    said = SAID[lang]
    ff, task, u = sol.forces, sol.task, sol.task.units

    def g(v):
        return formatted(v, ".4g", lang)
    a = u.scale("rad")
    force = said["moment" if ff.motion == "oscillating" else "force"]
    unit = "N m" if ff.motion == "oscillating" else "N"
    rpm = 30 / math.pi
    if not ff.jumps:
        f, at = ff.least_force
        wc = ff.critical_speed
        if math.isinf(wc):
            upto = said["at any speed"]
        elif wc < ff.speed:      # held by the follower's inertia: lost at some lower speeds
            upto = said["not every lower"].format(
                where=said["at rest"] if wc == 0 else said["from rpm"].format(rpm=g(wc * rpm)))
        else:
            upto = said["up to"].format(rpm=g(wc * rpm), speed=g(wc / a), angle=u.angle)
        line = said["contact kept"].format(force=force, least=g(f), unit=unit, at=g(at / a),
                                           angle=u.angle, upto=upto)
    else:
        margin = task.dynamics["margin"]
        need = ff.least_preload(margin)
        line = said["jump"].format(
            force=force, at=g(ff.jump_angle / a), angle=u.angle, rpm=g(ff.speed * rpm),
            need=g(need), unit=unit,
            margin=said["for a margin"].format(margin=g(margin), unit=unit) if margin else "")
    t, at = ff.peak_torque
    mean = ff.mean_torque
    mean = 0.0 if abs(mean) <= 1e-12 * abs(t) else mean      # rounding of an exact zero
    return [line, said["shaft torque"].format(peak=g(t), at=g(at / a), angle=u.angle,
                                              mean=g(mean))]


def _summary(sol, name: str, lang: str = "en") -> list[str]:
    from kinelab.cli._words import SAID, formatted
    said = SAID[lang]
    cam, task, u = sol.cam, sol.task, sol.task.units
    m, a = u.scale("m"), u.scale("rad")
    f = cam.follower

    def g(v, spec=".4g"):
        return formatted(v, spec, lang)
    head = said["cam head"].format(name=name, motion=said[f.motion], type=said[f.type],
                                   radius=g(cam.base_radius / m, ".6g"), length=u.length)
    if sol.smallest:
        head += (said["smallest for pressure"].format(limit=g(task.pressure_angle / a),
                                                      angle=u.angle) if not f.flat else
                 said["smallest for curvature"].format(limit=g(task.min_radius / m),
                                                       length=u.length))
    lines = [head]
    phi, at = cam.largest_pressure_angle
    lines.append(said["largest pressure"].format(phi=g(phi / a), at=g(at / a), angle=u.angle))
    r, at = cam.smallest_radius
    if math.isfinite(r):
        lines.append(said["smallest radius"].format(r=g(r / m), length=u.length, at=g(at / a),
                                                    angle=u.angle))
    if f.flat:
        lines.append(said["face width"].format(width=g(cam.face_width / m), lo=g(cam.face[0] / m),
                                               hi=g(cam.face[1] / m), length=u.length))
    lines.append(said["undercut"].format(answer=said["yes" if cam.undercut.any() else "no"]))
    jumps = task.program.discontinuities
    for d in jumps:
        jump = said["jump at"].format(quantity=d.quantity, jump=g(d.jump, ".6g"),
                                      angle=g(math.degrees(d.angle), ".6g"), left=d.left + 1,
                                      right=d.right + 1)
        lines.append(said["continuity"].format(
            jump=jump + (said["infinite jerk"] if d.quantity == "A" else "")))
    if not jumps:
        lines.append(said["continuous"])
    if sol.forces is not None:
        lines += _verdict(sol, lang)
    return lines


@click.command("cam")
@click.argument("task_file", metavar="TASK", type=click.Path(dir_okay=False))
@click.option("--out", "-o", "out", default=".", show_default=True, metavar="DIR",
              help="Directory for the figures, the profile and the table.")
@LANG
def cam_command(task_file: str, out: str, lang: str) -> None:
    """Design a disk cam from the TOML task file TASK: a motion program of rise, dwell and
    return segments and a follower.

    Writes <name>_svaj.png, <name>_profile.png, <name>_pressure.png, <name>_curvature.png,
    the profile as <name>_profile.dxf and <name>_profile.svg, and the SVAJ table as
    <name>_svaj.csv, in the task's units, into --out; prints the largest pressure angle, the
    smallest radius of curvature, whether the profile is undercut and the continuity of the
    program at its joints.  With a [dynamics] table (the follower's mass, spring and preload),
    also <name>_forces.png, the contact force and shaft torque in the table, and the jump
    check: the least contact force and the largest jump-free speed, or where the follower
    leaves the cam and the preload that would hold it.  With --lang pt, the figures and the
    summary in Portuguese (decimal commas; the table keeps the decimal point).
    """
    from kinelab import cams
    from kinelab import plot as kplot
    from kinelab._files import outputs, write_csv
    from kinelab.cli._draw import _agg
    from kinelab.cli._main import said_written, stem
    from kinelab.io._text import loads, read_text

    path = Path(task_file)
    data = loads(read_text(path), "TOML", source=str(path))
    task = cams.read_cam_task(data, source=str(path), name=path.stem)
    sol = cams.solve_cam_task(task, source=str(path))
    plt = _agg()
    u = task.units
    base = stem(task_file)
    cam = sol.cam
    figures = {"svaj": kplot.cam_svaj(cam, units=u, lang=lang),
               "profile": kplot.cam_profile(cam, units=u, lang=lang),
               "pressure": kplot.cam_pressure(cam, limit=task.pressure_angle, units=u, lang=lang),
               "curvature": kplot.cam_curvature(cam, units=u, lang=lang)}
    if sol.forces is not None:
        figures["forces"] = kplot.cam_forces(sol.forces, units=u, lang=lang)
    columns = _columns(sol)
    svg = cam.to_svg(u.length)
    try:
        with outputs(out) as files:
            written = [files.write(f"{base}_{k}.png", lambda p, f=f: kplot.save(f, p))
                       for k, f in figures.items()]
            written.append(files.write(f"{base}_profile.dxf", lambda p: cam.to_dxf(p, u.length)))
            written.append(files.write(f"{base}_profile.svg", lambda p: p.write_text(svg)))
            written.append(files.write(f"{base}_svaj.csv", lambda p: write_csv(columns, p)))
    finally:
        for f in figures.values():
            plt.close(f)
    click.echo("\n".join(_summary(sol, task.name, lang)))
    said_written(written)
