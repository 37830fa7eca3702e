"""``kinelab export`` and ``kinelab import``: drawings and other tools' formats."""
from __future__ import annotations

import math
import re
from pathlib import Path

import click

from kinelab import io
from kinelab.cli._analyze import MODEL
from kinelab._files import atomic_write, output
from kinelab.cli._main import (Number, errors_from, output_path, read_model, said_written, stem,
                               sweep)
from kinelab.errors import ModelError, shown, shown_path
from kinelab.io._text import read_text

__all__ = ["export", "import_"]

TARGETS = ("svg", "dxf", "pyslvs", "toml", "json")
UNITS = click.Choice(list(io.LENGTH_UNITS))


@click.command()
@MODEL
@click.option("--to", "target", type=click.Choice(TARGETS), required=True,
              help="svg/dxf: link outlines and holes; pyslvs: a Pyslvs expression; "
                   "toml/json: the model file, in --unit.")
@click.option("--out", "-o", "out", default=".", show_default=True, metavar="PATH",
              help="Directory (the file is named after the model) or file name.")
@click.option("--unit", type=UNITS, default=None,
              help="Length unit of the output and of --width and --hole (default: the "
                   "model file's).")
@click.option("--layout", type=click.Choice(("parts", "assembly")), default="parts",
              show_default=True, help="svg/dxf: links laid flat in a row, or as assembled.")
@click.option("--width", type=Number(positive=True), default=None,
              help="svg/dxf: bar width (default: 15 % of the median link length).")
@click.option("--hole", type=Number(positive=True), default=None,
              help="svg/dxf: hole diameter (default: 40 % of the width).")
@click.option("--ground", is_flag=True, help="svg/dxf: draw the ground link too.")
def export(model, target, out, unit, layout, width, hole, ground):
    """Export MODEL: link outlines (SVG, DXF) for drawings and cutting, a Pyslvs expression,
    or the model file in other units or as JSON."""
    mf = read_model(model)
    m = mf.mechanism
    unit = unit or mf.units.length
    scale = io.LENGTH_UNITS[unit]
    path = output_path(out, stem(model), target)
    if target in ("svg", "dxf"):
        sol = sweep(mf, 181)          # slots span the sliders' travel
        outline = io.to_svg if target == "svg" else io.to_dxf

        def write(p):
            with errors_from(mf):
                outline(m, p, unit=unit, layout=layout, ground=ground, sol=sol,
                        width=None if width is None else width * scale,
                        hole=None if hole is None else hole * scale)
    elif target == "pyslvs":
        with errors_from(mf):
            text = io.to_pyslvs(m, length=unit)

        def write(p):
            atomic_write(p, lambda f: f.write(text))
    else:
        import dataclasses
        converted = dataclasses.replace(mf, units=io.Units(unit, mf.units.angle))

        def write(p):
            io.save(converted, p)
    said_written([output(path, write)])


@click.command("import")
@click.argument("source", type=click.Path(dir_okay=False))
@click.option("--out", "-o", "out", required=True, metavar="MODEL",
              help="The kinelab model file to write (.toml or .json).")
@click.option("--from", "fmt", type=click.Choice(("auto", "pyslvs", "linkage2d")), default="auto",
              show_default=True, help="auto: linkage2d for .json files, else a Pyslvs expression.")
@click.option("--unit", type=UNITS, default="mm", show_default=True,
              help="Pyslvs: the unit of the expression's coordinates; also the model file's.")
@click.option("--inputs", default=None, metavar="PAIRS",
              help="Pyslvs input pairs 'pivot,driven;...' (joint numbers), e.g. '0,1'.")
@click.option("--input", "input_joint", default=None, metavar="JOINT",
              help="linkage2d: the joint (name or id) that drives it.")
def import_(source, out, fmt, unit, inputs, input_joint):
    """Convert SOURCE, a Pyslvs mechanism expression or a linkage2d JSON file, into a kinelab
    model file (the assembly of the drawing is kept).  A Pyslvs expression has no speeds: its
    inputs get 600 deg/s (100 rpm) for an angle and 100 mm/s for a slide, as the written
    file's description says."""
    path = Path(source)
    description = ""
    if fmt == "auto":
        fmt = "linkage2d" if path.suffix.lower() == ".json" else "pyslvs"
    if fmt == "linkage2d":
        m = io.from_linkage2d_json(path, input=input_joint)
    else:
        text = read_text(path)
        pairs = None
        if inputs:
            pairs = [tuple(int(v) if _JOINT.fullmatch(v) else -1 for v in p.split(","))
                     for p in inputs.split(";")]
            if any(-1 in p for p in pairs):
                raise ModelError(f"--inputs: expected pairs of joint numbers (ASCII digits) like "
                                 f"'0,1;4,3', got {shown(inputs)}")
        try:
            m = io.from_pyslvs(text, inputs=pairs, length=unit, name=path.stem)
        except ModelError as exc:
            raise ModelError(exc.problems, source=path.name) from None
        description = _speed_note(path.name, unit)
    if m.inputs:        # what kinelab check would refuse is said now, and nothing is written
        from kinelab.io._imported import planned
        planned(m, path.name, pyslvs=fmt == "pyslvs")
    imported = io.ModelFile(mechanism=m, units=io.Units(unit, "deg"), description=description)
    written = output(out, lambda p: io.save(imported, p))
    click.echo(f"wrote {shown_path(written)}: {len(m.links)} links, {len(m.joints)} joints, inputs "
               f"{', '.join(m.input_names) or 'none (add one under [[inputs]])'}")


_JOINT = re.compile(r"[ \t]*[0-9]{1,9}[ \t]*")      # a Pyslvs joint's number


def _speed_note(source: str, unit: str) -> str:
    """What an imported Pyslvs model's file says about the input speeds it was given."""
    turn = io.IMPORT_SPEEDS["angle"]
    slide = io.IMPORT_SPEEDS["slide"] / io.LENGTH_UNITS[unit]
    return (f"Imported from the Pyslvs expression {source}, which has no speeds: each input "
            f"was given kinelab's default, {math.degrees(turn):.6g} deg/s "
            f"({turn * 60 / (2 * math.pi):.6g} rpm) for an angle, {slide:.6g} {unit}/s for a "
            "slide; set your own with speed under [[inputs]] (or kinelab analyze --speed).")
