"""The constructions step by step for ``kinelab polygons --construction``, ``kinelab centres
--steps`` and ``kinelab differentiate --construction``: their options and the figures and
tables they write (Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*,
§4.6.2-4.6.4).  The commands themselves live in :mod:`kinelab.cli._graphical`."""
from __future__ import annotations

from pathlib import Path

import click

from kinelab._files import Outputs, safe_name, write_csv
from kinelab.cli._main import Number, errors_from

__all__ = ["IMAGE", "STEPS", "TANGENTS", "POINTS", "POLAR", "TANGENT",
           "check_images", "write_images", "write_steps", "check_tangents", "write_tangents"]

IMAGE = click.option("--construction", "construction", is_flag=True,
                     help="Also draw the velocity image of each moving link with three or more "
                          "points by similar triangles, step by step: oa, ob, ab, the triangle "
                          "abc similar to ABC, oc (<name>_velocity_image_<link>).")
STEPS = click.option("--steps", "steps", is_flag=True,
                     help="Also draw Kennedy's construction step by step: the primary centres, "
                          "then each secondary one on two numbered lines of known centres, "
                          "with the circle diagram (<name>_kennedy_steps).")
TANGENTS = click.option("--construction", "construction", is_flag=True,
                        help="Also differentiate by the notes' construction: tangents at chosen "
                             "points, a pole at the polar distance H, rays parallel to the "
                             "tangents and their intercepts (<name>_construction.csv and a "
                             "figure beside the numerical derivative).")
POINTS = click.option("--points", "points", type=click.IntRange(1, None), default=None,
                      metavar="N", help="With --construction: tangents at N points (default 12).")
POLAR = click.option("--polar-distance", "polar_distance", type=Number(positive=True),
                     default=None, metavar="H",
                     help="With --construction: the polar distance, in the abscissa's unit "
                          "(default: twice the interval between the chosen points).")
TANGENT = click.option("--tangent", "tangent", type=click.Choice(("chord", "fitted")),
                       default=None,
                       help="With --construction: the tangent's slope from the chord between "
                            "neighbouring samples (the notes', default) or from the fitted "
                            "curve.")


def _save(fig, files: Outputs, name: str, formats) -> list[Path]:
    from kinelab.cli._graphical import _save as save
    return save(fig, files, name, formats)


def check_images(mf) -> list[str]:
    """The moving links of ``mf`` with three or more points; refuses a model with none."""
    m = mf.mechanism
    links = [lk.name for lk in m.links if not lk.ground and len(lk.points) >= 3]
    if not links:
        raise click.UsageError("--construction: expected a moving link with three or more "
                               "points (the triangle ABC of a velocity image); this model's "
                               "moving links have two or fewer")
    return links


def write_images(mf, sol, links, files: Outputs, base: str, formats, units, lang) -> list[Path]:
    from kinelab import plot as kplot
    written = []
    for link in links:
        with errors_from(mf, "--construction"):
            fig = kplot.velocity_image(sol, link, units=units, lang=lang)
        written += _save(fig, files, f"{base}_velocity_image_{safe_name(link)}", formats)
    return written


def write_steps(mf, sol, files: Outputs, base: str, formats, units, lang) -> list[Path]:
    from kinelab import plot as kplot
    with errors_from(mf, "--steps"):
        fig = kplot.kennedy_steps(sol, units=units, lang=lang)
    return _save(fig, files, f"{base}_kennedy_steps", formats)


def check_tangents(construction, points, polar_distance, tangent) -> None:
    """The construction's options only with --construction."""
    if construction:
        return
    for name, value in (("--points", points), ("--polar-distance", polar_distance),
                        ("--tangent", tangent)):
        if value is not None:
            raise click.UsageError(f"{name}: only with --construction (the graphical "
                                   "differentiation by tangents)")


def tangents(curve, points, polar_distance, tangent):
    """The construction of ``curve`` (its errors naming the file)."""
    from kinelab import kinematics
    from kinelab.errors import ModelError
    try:
        return kinematics.tangent_construction(curve.x, curve.y, points=points,
                                               polar_distance=polar_distance,
                                               method=tangent or "chord")
    except ModelError as exc:
        raise ModelError([p.replace("points:", "--points:", 1).replace("polar_distance:",
                                                                         "--polar-distance:", 1)
                          for p in exc.problems], source=curve.source) from None


def write_tangents(tc, d, files: Outputs, base: str, formats, names, lang) -> list[Path]:
    """The construction's table and figure; ``names`` = (x name, y name, x unit, y unit)."""
    from kinelab import plot as kplot
    xn, yn, xu, yu = names

    def unit(text):
        return f" [{text}]" if text else ""
    rate = f"{yu or '1'}/{xu or '1'}"
    columns = {f"{xn}{unit(xu)}": tc.points[:, 0], f"{yn}{unit(yu)}": tc.points[:, 1],
               f"slope{unit(rate)}": tc.slope, f"intercept{unit(yu)}": tc.intercepts,
               f"d{yn}/d{xn}{unit(rate)}": tc.derivative}
    written = [files.write(f"{base}_construction.csv", lambda p: write_csv(columns, p))]
    fig = kplot.tangent_construction(tc, numerical=d, x_label=xn, y_label=yn, x_unit=xu or "1",
                                     y_unit=yu or "1", lang=lang)
    written += _save(fig, files, f"{base}_construction", formats)
    return written
