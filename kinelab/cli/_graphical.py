"""``kinelab polygons``, ``kinelab centres`` and ``kinelab differentiate``: the graphical
methods of Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*, §4.6,
as tables and figures."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import click
import numpy as np

from kinelab import io, kinematics, solvers
from kinelab.cli._analyze import MODEL, SAMPLES, configuration, with_speeds
from kinelab.cli import _constructions as steps_
from kinelab.cli._draw import FIGURE_FORMATS, _agg
from kinelab.cli._words import SAID, number
from kinelab._files import Outputs, outputs, safe_name, write_csv
from kinelab.cli._main import (CHANGE_POINTS, DEGREES, LANG, SI, VERIFY, Number, errors_from,
                               output_units, parse_inputs, read_model, report, said_written,
                               stem, sweep)
from kinelab.errors import ModelError, shown_path
from kinelab.model import Units
from kinelab.solvers._differentiate import MAX_SAMPLES, MIN_WINDOW

__all__ = ["polygons", "centres", "differentiate_command"]

AT = click.option("--at", "at", required=True, metavar="VALUE",
                  help="The input value: in the file's unit, or with a unit (30deg, 0.5rad, "
                       "12mm); comma-separated for several inputs.")
SPEED = click.option("--speed", "speed", default=None, metavar="VALUE",
                     help="Input speed, instead of the file's: in the file's unit per second, "
                          "or with a unit (60deg, 1rad, 12mm: per second).")
OUT = click.option("--out", "-o", "out", default=".", show_default=True, metavar="DIR",
                   help="Directory for the figures.")
FORMATS = click.option("--format", "formats", type=click.Choice(FIGURE_FORMATS), multiple=True,
                       default=("png",), show_default=True, help="Repeat for several formats.")


def _table(rows: list[tuple[str, ...]]) -> list[str]:
    widths = [max(len(r[k]) for r in rows) for k in range(len(rows[0]))]
    return ["  " + "  ".join(c.ljust(w) if k == 0 else c.rjust(w)
                             for k, (c, w) in enumerate(zip(r, widths))).rstrip() for r in rows]


def _vector_row(name: str, v, u: Units, si: str, lang: str = "en") -> tuple[str, ...]:
    x, y = (float(c) for c in u.convert(np.asarray(v, float), si))
    return (name, number(x, 6, lang), number(y, 6, lang), number(float(np.hypot(x, y)), 6, lang))


def _save(fig, files: Outputs, name: str, formats) -> list[Path]:
    """Write ``fig`` in each of ``formats`` as ``name.<format>``, one of ``files``."""
    from kinelab import plot as kplot
    import matplotlib.pyplot as plt
    try:
        return [files.write(f"{name}.{fmt}", lambda p: kplot.save(fig, p))
                for fmt in dict.fromkeys(formats)]
    finally:
        plt.close(fig)


@click.command()
@MODEL
@AT
@SPEED
@OUT
@FORMATS
@click.option("--velocity-scale", "velocity_scale", type=Number(positive=True),
              default=None, metavar="VALUE",
              help="Velocity per centimetre of the drawing, in the results' length unit per "
                   "second (default: a round number that fits).")
@click.option("--acceleration-scale", "acceleration_scale",
              type=Number(positive=True), default=None, metavar="VALUE",
              help="Acceleration per centimetre of the drawing, in the results' length unit "
                   "per second squared (default: a round number that fits).")
@SI
@DEGREES
@CHANGE_POINTS
@LANG
@VERIFY
@steps_.IMAGE
def polygons(model, at, speed, out, formats, velocity_scale, acceleration_scale, si, degrees,
             change_points, lang, verify_, construction):
    """Velocity and acceleration polygons of MODEL at one input: every point's velocity and
    acceleration from the pole, every side with its parts (normal, tangential, Coriolis,
    sliding), printed and drawn to scale beside the mechanism.  With --verify, every vertex,
    side and part is computed again (the other engine, the rigid-body and sliding formulas,
    Coriolis from 2 omega x v_rel) and each polygon's closure checked; the certificate is
    printed last and written as <name>_polygons_certificate.json."""
    from kinelab import plot as kplot
    _agg()
    mf = read_model(model)
    if speed is not None:
        mf = with_speeds(mf, parse_inputs(speed, mf, "--speed", rate=True))
    units = output_units(mf.units, si, degrees)
    images = steps_.check_images(mf) if construction else []
    sol = configuration(mf, at, change_points)
    with errors_from(mf, "--at"):
        vp = kinematics.velocity_polygon(sol)
        ap = kinematics.acceleration_polygon(sol)
    certificate = None
    if verify_:         # before anything is printed or drawn
        from kinelab.verify import Certificate, certify
        with errors_from(mf, "--verify"):
            parts = [certify(p, solution=sol) for p in (vp, ap)]
        certificate = Certificate(f"polygons of '{mf.mechanism.name}' at {at}",
                                  parts[0].quantities + parts[1].quantities,
                                  parts[0].notes + parts[1].notes)
    v_unit, a_unit = units.unit("m/s"), units.unit("m/s^2")

    def name(p):        # a guide's point under a slider's point A: A'
        return p.split("@")[0] + "'" if "@" in p else p
    said = SAID[lang]
    lines = [said["velocity polygon"].format(name=mf.mechanism.name, unit=v_unit)]
    rows = [("", "vx", "vy", "|v|")]
    rows += [_vector_row(f"V_{p}", v, units, "m/s", lang) for p, v in vp.vertices.items()]
    rows += [_vector_row(f"V_{name(p)}{name(r)}", s.vector, units, "m/s", lang)
             for (p, r), s in vp.sides.items()]
    lines += _table(rows)
    lines.append("")
    lines.append(said["acceleration polygon"].format(unit=a_unit))
    rows = [("", "ax", "ay", "|a|")]
    rows += [_vector_row(f"A_{p}", a, units, "m/s^2", lang) for p, a in ap.vertices.items()]
    mark = {"normal": "n", "tangential": "t", "coriolis": "c", "sliding": "s"}
    for (p, r), side in ap.sides.items():
        sub = f"{name(p)}{name(r)}"
        rows.append(_vector_row(f"A_{sub}", side.vector, units, "m/s^2", lang))
        rows += [_vector_row(f"  A^{mark[k]}_{sub}", v, units, "m/s^2", lang)
                 for k, v in side.parts.items()]
    lines += _table(rows)
    for c in vp.coincident:
        point, guide = c.split("@")
        lines.append(said["under"].format(point=point, guide=guide))
    click.echo("\n".join(lines))
    base = stem(model)
    with outputs(out) as files:
        written = _save(kplot.velocity_polygon(sol, units=units, scale=velocity_scale,
                                               lang=lang),
                        files, f"{base}_velocity_polygon", formats)
        written += _save(kplot.acceleration_polygon(sol, units=units, scale=acceleration_scale,
                                                    lang=lang),
                         files, f"{base}_acceleration_polygon", formats)
        written += steps_.write_images(mf, sol, images, files, base, formats, units, lang)
        if certificate is not None:
            written.append(files.write(f"{base}_polygons_certificate.json", certificate.to_json))
    said_written(written)
    if certificate is not None:
        report(certificate)


@click.command()
@MODEL
@AT
@OUT
@FORMATS
@click.option("--centrodes", "with_centrodes", is_flag=True,
              help="Also sweep the file's input range and draw the fixed and moving centrodes "
                   "of each link not pinned to the ground.")
@SAMPLES
@SI
@CHANGE_POINTS
@steps_.STEPS
@LANG
def centres(model, at, out, formats, with_centrodes, samples, si, change_points, steps, lang):
    """Every instant centre of MODEL at one input, found as the notes find them: primary
    centres from the joints, the others by Kennedy's theorem in the order of the circle
    diagram; printed and drawn on the mechanism beside the circle diagram."""
    from kinelab import plot as kplot
    _agg()
    mf = read_model(model)
    units = output_units(mf.units, si, False)
    sol = configuration(mf, at, change_points)
    with errors_from(mf, "--at"):
        if bool(sol.singular[0]):
            kinematics.velocity_polygon(sol)         # the singular sample's message
        kc = kinematics.kennedy_construction(sol)
    order = {s.pair: k + 1 for k, s in enumerate(kc.steps)}
    numbers = ", ".join(f"{n} {lk}" for lk, n in kc.numbers.items())
    said = SAID[lang]
    lines = [said["centres"].format(name=mf.mechanism.name, unit=units.length, numbers=numbers)]
    rows = [("", said["links"], said["found"], "x", "y")]
    for pair, c in kc.centers.items():
        how = (said["joint"].format(joint=kc.primary[pair]) if pair in kc.primary else
               f"Kennedy ({order[pair]})" if pair in order else said["velocities"])
        if bool(c.at_infinity):
            d = c.direction
            between = "; " if lang == "pt" else ", "      # a decimal comma's list: with ;
            where = (said["at infinity"], f"{said['direction']} ({number(float(d[0]), 4, lang)}"
                                          f"{between}{number(float(d[1]), 4, lang)})")
        else:
            x, y = (float(v) for v in units.convert(c.position, "m"))
            where = (number(x, 6, lang), number(y, 6, lang))
        rows.append((kc.label(pair), "-".join(pair), how, *where))
    lines += _table(rows)
    click.echo("\n".join(lines))
    base = stem(model)
    with outputs(out) as files:
        written = _save(kplot.instant_centers(sol, units=units, lang=lang), files,
                        f"{base}_centres", formats)
        if steps:
            written += steps_.write_steps(mf, sol, files, base, formats, units, lang)
        if with_centrodes:
            written += _centrodes(mf, sol, files, base, formats, samples, units, change_points,
                                  lang)
    said_written(written)


def _centrodes(mf, sol, files: Outputs, base: str, formats, samples, units,
               change_points, lang: str = "en") -> list[Path]:
    """The centrodes of each link of ``mf`` not pinned to the ground, over the file's sweep,
    at the sample nearest ``sol``'s input: one figure each, ``<base>_centrodes_<link>``."""
    from kinelab import plot as kplot
    m = mf.mechanism
    pinned = {lk for j in m.joints if j.type == "R" and m.ground.name in j.links
              for lk in j.links}
    links = [lk for lk in m.link_names if lk != m.ground.name and lk not in pinned]
    if not links:
        raise click.UsageError("--centrodes: every moving link of this mechanism is pinned to "
                               "the ground, and its centrodes are its pivot")
    swept = sweep(mf, samples, change_points=change_points)
    near = int(np.argmin(np.abs(swept.q[:, 0] - sol.q[0, 0]))) if swept.M == 1 else 0
    ok = swept.assembled & ~swept.singular
    if not ok[near]:
        near = int(np.flatnonzero(ok)[0]) if ok.any() else near
    written = []
    for lk in links:
        with errors_from(mf, "--centrodes"):
            ax = kplot.centrodes(swept, lk, near, units=units, lang=lang)
        written += _save(ax.figure, files, f"{base}_centrodes_{safe_name(lk)}", formats)
    return written


PLOTTED = 20_000     # samples a figure of derivatives draws at most (every k-th beyond):
                     # it is about 1,000 pixels wide, and matplotlib slows down past that


@click.command("differentiate")
@click.argument("data", type=click.Path(dir_okay=False))
@click.option("--x", "x_column", default=None, metavar="COLUMN",
              help="The abscissa's column, by name or number from 1 (default: the first).")
@click.option("--y", "y_column", default=None, metavar="COLUMN",
              help="The curve's column, by name or number from 1 (default: the second).")
@click.option("--window", type=click.IntRange(MIN_WINDOW, MAX_SAMPLES), default=None,
              metavar="SAMPLES",
              help="Samples per local fit (odd, at least 11), instead of the one chosen by "
                   "cross-validation.")
@click.option("--out", "-o", "out", default=".", show_default=True, metavar="DIR",
              help="Directory for the table and the figure.")
@FORMATS
@steps_.TANGENTS
@steps_.POINTS
@steps_.POLAR
@steps_.TANGENT
@LANG
def differentiate_command(data, x_column, y_column, window, out, formats, construction, points,
                          polar_distance, tangent, lang):
    """Velocity and acceleration of a measured curve: DATA is a CSV file with a header row
    (e.g. 't [s], x [mm]'), an abscissa (time or an input angle) and a displacement, evenly
    sampled or not, with noise.  Writes the derivatives with their error bands (a table and a
    figure) and prints how the smoothing was chosen."""
    from kinelab import plot as kplot
    _agg()
    steps_.check_tangents(construction, points, polar_distance, tangent)
    curve = io.read_curve(data, x=x_column, y=y_column)
    try:
        d = solvers.differentiate(curve.x, curve.y, window=window)
    except ModelError as exc:           # name the file in the message
        raise ModelError(exc.problems, source=curve.source) from None
    tc = steps_.tangents(curve, points, polar_distance, tangent) if construction else None
    xn, yn = curve.x_name or "x", curve.y_name or "y"
    xu, yu = curve.x_unit, curve.y_unit

    def unit(text):
        return f" [{text}]" if text else ""
    rate = f"{yu or '1'}/{xu or '1'}"
    columns = {f"{xn}{unit(xu)}": d.x, f"{yn}{unit(yu)}": curve.y,
               f"{yn}.smoothed{unit(yu)}": d.y,
               f"d{yn}/d{xn}{unit(rate)}": d.velocity,
               f"d{yn}/d{xn}.error{unit(rate)}": d.velocity_error,
               f"d2{yn}/d{xn}2{unit(rate + '^2' if xu else rate)}": d.acceleration,
               f"d2{yn}/d{xn}2.error{unit(rate + '^2' if xu else rate)}": d.acceleration_error}
    base = stem(data)
    k = -(-len(d.x) // PLOTTED)
    drawn = d if k == 1 else dataclasses.replace(d, **{
        f: getattr(d, f)[::k] for f in ("x", "y", "velocity", "acceleration", "velocity_error",
                                       "acceleration_error", "residual")})
    with outputs(out) as files:
        written = [files.write(f"{base}_derivatives.csv", lambda p: write_csv(columns, p))]
        fig = kplot.derivatives(drawn, x_label=f"{xn}{unit(xu)}", y_label=yn, y_unit=yu or "1",
                                x_unit=xu or "1", lang=lang)
        written += _save(fig, files, f"{base}_derivatives", formats)
        if tc is not None:
            written += steps_.write_tangents(tc, d, files, base, formats, (xn, yn, xu, yu), lang)
    said = SAID[lang]
    how = (said["window given"] if window is not None else
           said["window chosen"].format(share=number(0.7, 6, lang), gcv=d.window_gcv))
    click.echo(said["derivatives"].format(
        data=shown_path(Path(data).name), n=len(d.x), y=yn, x=xn, noise=number(d.noise, 3, lang),
        unit=yu, window=d.window, how=how,
        band=number(float(np.median(d.velocity_error)), 3, lang), rate=rate).replace(" ;", ";"))
    said_written(written)
