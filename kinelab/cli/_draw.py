"""``kinelab plot`` and ``kinelab animate``."""
from __future__ import annotations

import click

from kinelab import io
from kinelab._files import output, outputs, safe_name
from kinelab.cli._analyze import MODEL, SAMPLES
from kinelab.cli._main import (CHANGE_POINTS, DEGREES, LANG, SI, errors_from, light_work, output_path,
                               output_units, read_model, said_written, stem, sweep)
from kinelab.errors import ModelError, quoted, shown, suggest

__all__ = ["plot", "animate"]

FIGURE_FORMATS = ("png", "svg", "pdf")


def _agg():
    import matplotlib
    matplotlib.use("Agg")      # files only: no window, no display needed
    import matplotlib.pyplot as plt
    return plt


def _names(text: str | None) -> list[str] | None:
    return [n.strip() for n in text.split(",") if n.strip()] if text else None


def _check_names(option: str, names: list[str] | None, known, what: str) -> None:
    """Refuse names typed in ``option`` that are not ``known`` (checked before the sweep,
    which can be long)."""
    known = dict.fromkeys(known)
    unknown = [n for n in names or () if n not in known]
    if unknown:
        raise ModelError(f"{option}: expected {what}, got {quoted(unknown)}"
                         f"{suggest(unknown[0], known)}; they are {quoted(known)}")


@click.command()
@MODEL
@click.option("--out", "-o", "out", default=".", show_default=True, metavar="DIR",
              help="Directory for the figures.")
@click.option("--format", "formats", type=click.Choice(FIGURE_FORMATS), multiple=True,
              default=("png", "svg"), show_default=True, help="Repeat for several formats.")
@click.option("--outputs", "names", default=None, metavar="NAMES",
              help="Comma-separated links, slides and points to plot (default: the file's "
                   "[outputs], else the moving links, slides and coupler points).")
@SAMPLES
@SI
@DEGREES
@CHANGE_POINTS
@LANG
def plot(model, out, formats, names, samples, si, degrees, change_points, lang):
    """Write MODEL's figures: outputs' position, velocity and acceleration against the input;
    K and L; coupler curves; transmission angle.  Axes are in the file's units (--si for m
    and rad); singular positions are marked and left out of the curves."""
    from kinelab import plot as kplot
    from kinelab.io._summary import _default_pairs
    plt = _agg()
    mf = read_model(model)
    m = mf.mechanism
    units = output_units(mf.units, si, degrees)
    chosen = _names(names) or list(mf.outputs.report) or list(io.default_outputs(m))
    base = stem(model)
    # checked before the sweep, which can be long
    _check_names("--outputs", chosen, [*m.link_names, *(j.name for j in m.joints if j.type == "P"),
                                       *m.point_names], f"links, slides or points of {shown(m.name)}")
    light_work(mf, samples)
    sol = sweep(mf, samples, change_points=change_points)
    figures = []
    with errors_from(mf, "outputs"):
        curve_names = [n for n in chosen if n in sol.link_item or n in sol.slide_item]
        if curve_names:
            figures.append(("motion", kplot.curves(sol, curve_names, units=units, lang=lang)))
            figures.append(("coefficients", kplot.coefficients(sol, curve_names, units=units,
                                                               lang=lang)))
        for p in (n for n in chosen if n in sol.point_item):
            figures.append((f"path_{safe_name(p)}",
                            kplot.coupler_curve(sol, p, units=units, lang=lang).figure))
        pairs = list(mf.outputs.transmission) or _default_pairs(m)
        if pairs:
            figures.append(("transmission",
                            kplot.transmission(sol, pairs, units=units, lang=lang).figure))
    if not figures:
        raise click.UsageError("nothing to plot: name links, slides or points with --outputs")
    written = []
    try:
        # --out is a directory: several figures, each in several formats, go in it
        with outputs(out) as files:
            for kind, fig in figures:
                for fmt in dict.fromkeys(formats):
                    written.append(files.write(f"{base}_{kind}.{fmt}",
                                               lambda p: kplot.save(fig, p)))
    finally:
        for _, fig in figures:
            plt.close(fig)
    said_written(written)


@click.command()
@MODEL
@click.option("--out", "-o", "out", default=".", show_default=True, metavar="PATH",
              help="Directory (the file is named after the model) or file name.")
@click.option("--format", "fmt", type=click.Choice(("auto", "gif", "mp4")), default="auto",
              show_default=True, help="auto: MP4 when ffmpeg is installed, else GIF.")
@click.option("--trace", default=None, metavar="POINTS",
              help="Comma-separated points whose paths are traced (default: coupler points).")
@click.option("--frames", type=click.IntRange(2, 2000), default=120, show_default=True)
@click.option("--fps", type=click.IntRange(1, 120), default=30, show_default=True)
@click.option("--centres", "centers", is_flag=True,
              help="Overlay the instant centres (O12, O13, ...) in each frame.")
@click.option("--velocities", is_flag=True,
              help="Overlay each moving point's velocity as an arrow, at one stated scale.")
@SAMPLES
@SI
@CHANGE_POINTS
@LANG
def animate(model, out, fmt, trace, frames, fps, centers, velocities, samples, si, change_points,
            lang):
    """Write an animation of MODEL moving through its sweep, with its coupler curves traced
    (and, on request, its instant centres and velocities); axes in the file's length unit
    (--si for m)."""
    from kinelab import plot as kplot
    _agg()
    mf = read_model(model)
    units = output_units(mf.units, si, False)
    if fmt == "auto":
        fmt = "mp4" if kplot.can_write_mp4() else "gif"
    _check_names("--trace", _names(trace), mf.mechanism.point_names,
                 f"points of {shown(mf.mechanism.name)}")
    light_work(mf, samples)
    sol = sweep(mf, samples, change_points=change_points)

    def write(path):
        with errors_from(mf, "--trace" if trace else ""):
            kplot.animate(sol, path, trace=_names(trace), frames=frames, fps=fps, units=units,
                          centers=centers, velocities=velocities, lang=lang)
    said_written([output(output_path(out, stem(model), fmt), write)])
