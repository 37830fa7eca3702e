"""``kinelab sweep`` and ``kinelab atlas``: studies over many designs, on this machine or a
Dask cluster (``--scheduler ADDRESS``).

Design tables come from a CSV or Parquet file (one column per parameter, SI: m, rad) or
from ranges (``--sobol 4096 --range crank=0.5:1.5 ...``).  Results are Parquet (or CSV),
one row per design, every column naming its unit.
"""
from __future__ import annotations

from pathlib import Path

import click
import numpy as np

from kinelab import sweep as sw
from kinelab.sweep._family import DesignOffModel
from kinelab._files import atomic_write, output
from kinelab.cli._main import Number, about
from kinelab.errors import ModelError, describe, shown_path
from kinelab.io._csv import read_table
from kinelab.io._text import PLAIN_NUMBER, number
from kinelab.solvers._arguments import MAX_SEED
from kinelab.sweep._run import MAX_SAMPLES

__all__ = ["sweep_command", "atlas_command"]

_PROBLEMS_SHOWN = 20
_MOST = 10 ** 9      # designs, designs in a chunk, nearest designs: beyond any memory
_ANGLES = ("transmission_min", "transmission_max", "reachable_from", "reachable_to")


def _read_table(path: str, what: str):
    """A table of numbers from a CSV or a Parquet file, as a DataFrame; ``what`` its rows
    are: designs (an empty cell is a design's missing value, NaN) or points."""
    import pandas

    if Path(path).suffix.lower() in (".parquet", ".pq"):
        return sw.read_parquet(path, "a table")
    missing = np.nan if what == "designs" else None
    names, values = read_table(path, what=what, missing=missing)
    return pandas.DataFrame(values, columns=names)


def _range(text: str):
    name, sep, spec = text.partition("=")
    parts = spec.split(":")
    if not sep or not name or len(parts) not in (2, 3):
        raise ModelError(f"--range: expected NAME=LOW:HIGH (or NAME=LOW:HIGH:COUNT for --grid), "
                         f"got {describe(text)}")
    values = [number(v) for v in parts]
    if None in values or not all(np.isfinite(values)):     # nan, inf, and 1e400 (read as inf)
        raise ModelError(f"--range: expected finite numbers in NAME=LOW:HIGH[:COUNT], in "
                         f"{PLAIN_NUMBER}, got {describe(text)}")
    return name.strip(), values


def designs_from(table: str | None, sobol: int | None, random: int | None, grid: bool,
                 ranges: tuple[str, ...], seed: int):
    """The design table of a command: a file, or generated from ``--range`` options."""
    chosen = [x for x in (table is not None, sobol is not None, random is not None, grid) if x]
    if len(chosen) != 1:
        raise ModelError("designs: give exactly one of a DESIGNS file, --sobol N, --random N or "
                         "--grid (with --range NAME=LOW:HIGH for each varied parameter)")
    if table is not None:
        if ranges:
            raise ModelError("--range: only with --sobol, --random or --grid, not with a DESIGNS file")
        return _read_table(table, "designs")
    parsed = dict(_range(r) for r in ranges)
    if grid:
        axes = {}
        for name, v in parsed.items():
            if len(v) != 3 or v[2] != int(v[2]) or v[2] < 1:
                raise ModelError(f"--range {describe(name)}: --grid needs NAME=LOW:HIGH:COUNT with a "
                                 "whole COUNT >= 1")
            axes[name] = (v[0], v[1], int(v[2]))
        return sw.grid(**axes)      # refuses a grid beyond the memory budget before building it
    bounds = {name: tuple(v[:2]) for name, v in parsed.items()}
    return (sw.sobol(sobol, seed=seed, **bounds) if sobol is not None
            else sw.random(random, seed=seed, **bounds))


_WRITES = {"sweep": (".parquet", ".csv"), "atlas": (".parquet",)}


def _check_out(path: str, command: str) -> Path:
    """The output path, refused (before any work) unless its suffix is one the command writes."""
    accepted = _WRITES[command]
    p = Path(path)
    if p.suffix.lower() not in accepted:
        raise ModelError(f"--out: expected a file name ending in {' or '.join(accepted)}, got "
                         f"{shown_path(path)}")
    return p


def _family_of(spec: str, branch: str | None, output: str | None):
    options = {} if branch is None else {"branch": branch}
    if spec in sw.CATALOGUE:
        return sw.family(spec, output=output, **options)
    if not Path(spec).suffix.lower() in (".toml", ".json"):
        raise ModelError(f"FAMILY: expected a catalogue kind ({', '.join(sw.CATALOGUE)}) or a "
                         f"model file (.toml or .json), got {describe(spec)}")
    from kinelab.io import load
    model = load(spec)
    with about(spec):
        return sw.family(model, output=output, **options)


def _labelled(df, degrees: bool, output_is_slide: bool):
    """Columns named with their units (angles in rad, or deg with --degrees)."""
    unit = "deg" if degrees else "rad"
    out = df.copy()
    names = {}
    for c in df.columns:
        if c in _ANGLES or (c == "swing" and not output_is_slide):
            if degrees:
                out[c] = np.degrees(df[c])
            names[c] = f"{c}[{unit}]"
        elif c == "swing":
            names[c] = "swing[m]"
        elif c == "peak_torque":
            names[c] = "peak_torque[N m]"
    return out.rename(columns=names)


def _with_designs(designs, metrics, unit):
    """The designs' own columns (m; kg and kg m^2 for masses and inertias: ``unit`` of a
    column's name), then their metrics: each row traced to its design."""
    import pandas

    d = pandas.DataFrame(designs)
    d = d.rename(columns={c: f"{c}[{unit(c)}]" for c in d.columns}).set_index(metrics.index)
    return pandas.concat([d, metrics], axis=1)


def _write(df, path: Path) -> None:
    if path.suffix.lower() == ".csv":      # else .parquet (checked by _check_out)
        atomic_write(path, lambda f: df.to_csv(f, index=False))
    else:
        sw.write_parquet(df, path)


def _report_problems(df) -> None:
    problems = df.attrs.get("problems", {})
    for label, message in list(problems.items())[:_PROBLEMS_SHOWN]:
        click.echo(f"kinelab: warning: design {label}: {message}", err=True)
    if len(problems) > _PROBLEMS_SHOWN:
        click.echo(f"kinelab: warning: ... and {len(problems) - _PROBLEMS_SHOWN} more designs "
                   "that could not be analysed", err=True)


DESIGNS_OPTIONS = [
    click.option("--sobol", type=click.IntRange(1, _MOST), default=None, metavar="N",
                 help="N designs of a scrambled Sobol sequence in the --range bounds (a power "
                      "of 2 keeps the sequence balanced)."),
    click.option("--random", "random_n", type=click.IntRange(1, _MOST), default=None, metavar="N",
                 help="N designs drawn uniformly in the --range bounds."),
    click.option("--grid", is_flag=True, help="Every combination of --range NAME=LOW:HIGH:COUNT."),
    click.option("--range", "ranges", multiple=True, metavar="NAME=LOW:HIGH[:COUNT]",
                 help="Bounds of a parameter (m or rad), repeated for each one varied."),
    click.option("--seed", type=click.IntRange(0, MAX_SEED), default=0, show_default=True,
                 help="Seed of --sobol and --random."),
    click.option("--scheduler", default=None, metavar="ADDRESS",
                 help="Run on the Dask cluster of this scheduler (tcp://host:8786)."),
    click.option("--chunk-size", type=click.IntRange(1, _MOST), default=None,
                 help="Designs per chunk (default: what fits in 32 MiB)."),
    click.option("--samples", type=click.IntRange(4, MAX_SAMPLES), default=72, show_default=True,
                 help=f"Input samples over a full turn (at most {MAX_SAMPLES:,})."),
]


def _designs_options(f):
    for option in reversed(DESIGNS_OPTIONS):
        f = option(f)
    return f


@click.command("sweep")
@click.argument("family_spec", metavar="FAMILY")
@click.argument("table", metavar="[DESIGNS]", required=False)
@_designs_options
@click.option("--metrics", default=None, metavar="NAMES",
              help="Comma-separated: " + ", ".join(sw.METRICS) + " (default: the family's "
                   "standard ones).")
@click.option("--branch", default=None,
              help="Assembly mode of a catalogue family (fourbar: open or crossed ...).")
@click.option("--output", "output_name", default=None,
              help="Link or prismatic joint whose swing and time ratio are measured.")
@click.option("--speed", type=Number(), default=1.0, show_default=True,
              help="Input speed for peak_torque, rad/s (at most 1e100 in size).")
@click.option("--degrees", is_flag=True, help="Angles in degrees in the table.")
@click.option("--out", "-o", "out", default="sweep.parquet", show_default=True, metavar="PATH",
              help="Result table: .parquet or .csv.")
def sweep_command(family_spec, table, sobol, random_n, grid, ranges, seed, scheduler, chunk_size,
                  samples, metrics, branch, output_name, speed, degrees, out):
    """Metrics of every design of FAMILY (a catalogue kind such as fourbar, or a model file)
    over a turn of its input, one row per design of DESIGNS (CSV or Parquet) or of --sobol,
    --random or --grid; on a Dask cluster with --scheduler."""
    import time

    path = _check_out(out, "sweep")
    fam = _family_of(family_spec, branch, output_name)
    designs = designs_from(table, sobol, random_n, grid, ranges, seed)
    names = None if metrics is None else tuple(m.strip() for m in metrics.split(",") if m.strip())
    start = time.perf_counter()
    model_file = None if family_spec in sw.CATALOGUE else family_spec
    with about(table, ("designs", "metrics")), about(model_file, ("family",)):
        try:
            df = sw.run(fam, designs, samples=samples, metrics=names, client=scheduler,
                        chunk_size=chunk_size, speed=speed)
        except DesignOffModel as exc:
            raise ModelError(f"designs: the design {exc.design} moves points off the places the "
                             f"file declares ({exc.detail}); vary (--range, DESIGNS columns) only "
                             "points that no declaration fixes, or remove that declaration (a "
                             "link's local place or sides, a joint's offset) from the file and run "
                             f"kinelab check {shown_path(family_spec)}",
                             source=family_spec) from None
    seconds = time.perf_counter() - start
    table = _with_designs(designs, _labelled(df, degrees, fam.output_is_slide), fam.unit)
    output(path, lambda p: _write(table, p))
    _report_problems(df)
    assembles = f", {int(df['assembles'].sum()):,} assemble over the turn" if "assembles" in df else ""
    click.echo(f"{len(df):,} designs in {seconds:.3g} s{assembles}; wrote {shown_path(path)}")


@click.group("atlas")
def atlas_command():
    """Atlases of four-bar coupler curves: build one, find the designs nearest a path."""


@atlas_command.command("build")
@click.argument("table", metavar="[DESIGNS]", required=False)
@_designs_options
@click.option("--branch", default="open", show_default=True, help="Assembly mode: open or crossed.")
@click.option("--out", "-o", "out", default="atlas.parquet", show_default=True, metavar="PATH",
              help="The atlas: .parquet.")
def atlas_build(table, sobol, random_n, grid, ranges, seed, scheduler, chunk_size, samples,
                branch, out):
    """Build an atlas from four-bar designs (columns ground, crank, coupler, rocker,
    coupler_point_along, coupler_point_perpendicular, m)."""
    path = _check_out(out, "atlas")
    sw.family("fourbar", branch=branch)       # the branch checked before the designs are made
    designs = designs_from(table, sobol, random_n, grid, ranges, seed)
    with about(table, ("designs", "metrics")):
        a = sw.atlas(designs, branch=branch, samples=samples, client=scheduler,
                     chunk_size=chunk_size)
    output(path, a.to_parquet)
    click.echo(f"{len(a):,} of {len(designs):,} designs turn their crank fully; wrote {shown_path(path)}")


@atlas_command.command("find")
@click.argument("atlas_path", metavar="ATLAS")
@click.argument("path_file", metavar="PATH")
@click.option("-k", "k", type=click.IntRange(1, _MOST), default=5, show_default=True,
              help="How many designs.")
@click.option("--refine", is_flag=True,
              help="Polish the nearest designs into linkages through the path (path synthesis).")
def atlas_find(atlas_path, path_file, k, refine):
    """The designs of ATLAS whose coupler curves are nearest in shape to the closed path in
    PATH (a CSV of x, y points in order, m)."""
    a = sw.Atlas.from_parquet(atlas_path)
    if not len(a):
        raise ModelError("it holds no design that turns its crank fully; build it from more or "
                         "other designs", source=atlas_path)
    points = _read_table(path_file, "points").to_numpy()[:, :2]
    with about(path_file):      # what is wrong now is the path's
        near = a.nearest(points, k)
        sols = a.refine(points, k=min(k, 3)) if refine else None   # refused before any output
        if sols is not None and not len(sols):
            raise ModelError(f"refine: {sols.reason}")
    click.echo(near.to_string(float_format=lambda v: f"{v:.6g}"))
    if sols is not None:
        best = sols[0]
        size = float(np.hypot(*np.ptp(points, axis=0)))
        limit = (f"meets the {np.degrees(best.transmission_limit):.3g} deg limit"
                 if best.meets_transmission_limit else
                 f"below the {np.degrees(best.transmission_limit):.3g} deg limit")
        share = 100 * best.max_error / size
        click.echo(f"refined: A0 = ({best.A0[0]:.6g}, {best.A0[1]:.6g}) m, B0 = ({best.B0[0]:.6g}, "
                   f"{best.B0[1]:.6g}) m; its coupler curve passes within {best.max_error:.3g} m "
                   f"of all {len(points)} points of {shown_path(path_file)} (the largest "
                   f"distance, {share:.3g} % of the path's size), min transmission "
                   f"{np.degrees(best.min_transmission_angle):.3g} deg ({limit}), {best.state}")
