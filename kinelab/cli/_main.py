"""What the ``kinelab`` commands share: reading a model file, naming outputs, sweeping with a
progress bar, options and their checks.  The group itself is in ``_group.py``."""
from __future__ import annotations

import contextlib
import math
import os
import re
import sys
from pathlib import Path

import click
import numpy as np

from kinelab import _compiled, kinematics
from kinelab._files import safe_name
from kinelab.errors import ModelError, quoted, shown, shown_path
from kinelab.io import ModelFile
from kinelab.io._text import NUMBER, PLAIN_NUMBER, number
from kinelab.io._modelfile import errors_from
from kinelab.cli._group import main
from kinelab.kinematics import KinematicSolution
from kinelab.model import ANGLE_UNITS, LENGTH_UNITS, Units, range_problem, rate_problem

__all__ = ["main", "read_model", "errors_from", "sweep", "output_path", "parse_inputs", "stem",
           "SI", "DEGREES", "VERIFY", "report", "said_written", "certificate_path", "output_units",
           "Number", "about", "light_work", "LANG"]


def read_model(path: str) -> ModelFile:
    return ModelFile.read(path)


@contextlib.contextmanager
def about(path: str | os.PathLike | None, fields: tuple[str, ...] = ()):
    """Name ``path``, a file the command read, in the errors raised inside that name no file
    (``designs.csv: designs: missing column(s) ...``): every such error, or (``fields``)
    those whose problems are all about these fields of it; nothing when ``path`` is None."""
    try:
        yield
    except ModelError as exc:
        if path is None or exc.source is not None or fields and not all(
                p.partition(":")[0] in fields for p in exc.problems):
            raise
        raise ModelError(exc.problems, source=str(path)) from None


SI = click.option("--si", is_flag=True,
                  help="Results in SI (m, rad) instead of the file's units.")
DEGREES = click.option("--degrees", is_flag=True,
                       help="Angles in degrees, whatever the file's unit (with --si: metres "
                            "and degrees).")


LANG = click.option(
    "--lang", type=click.Choice(("en", "pt")), default="en", show_default=True,
    help="Language of the figures' titles, axes and legends and of the printed summary: en, "
         "or pt (Portuguese, with decimal commas; tables keep the decimal point).")


VERIFY = click.option(
    "--verify", "verify_", is_flag=True,
    help="Compute every reported number again by independent routes and print the certificate "
         "last: each quantity, its routes, their largest disagreement and its bound, and the "
         "verdict 'verified: N quantities, largest disagreement E' (exit status 0) or 'NOT "
         "verified: ...' (exit status 1); with the outputs, <name>_certificate.json.")


def certificate_path(written: Path) -> Path:
    """Where the certificate of a table goes: ``<name>_certificate.json`` beside it."""
    return written.with_name(f"{written.stem}_certificate.json")


def said_written(paths) -> None:
    """Say which files a command wrote, one line each."""
    for path in paths:
        click.echo(f"wrote {shown_path(path)}")


def report(certificate) -> None:
    """Print a certificate (written already, with the command's other outputs) with its
    verdict last, and end with exit status 1 when it failed."""
    click.echo("\n".join(certificate.lines()))
    if not certificate.passed:
        click.get_current_context().exit(1)


CHANGE_POINTS = click.option(
    "--change-points", "change_points", type=click.Choice(("smooth", "switch")), default="smooth",
    show_default=True,
    help="Where two assembly modes meet and the input goes on (a parallelogram at 180 deg): go "
         "on along the branch whose K and L continue, or switch to the other one.")


def output_units(file_units: Units, si: bool, degrees: bool) -> Units:
    """The units results are shown in: the file's, SI with ``--si``, and degrees for angles
    with ``--degrees``."""
    u = Units() if si else file_units
    return Units(u.length, "deg") if degrees else u


# a sweep of this many samples shows a progress bar on a terminal (Newton groups: BAR_FROM_NEWTON)
BAR_FROM = 20000
BAR_FROM_NEWTON = 200


def light_work(mf: ModelFile, samples: int | None = None) -> None:
    """Run the rest of the command's analyses as light work (``_compiled.light_work``) when
    the file's plan is closed-form and its sweep shows no progress bar: they take
    milliseconds on the kernel's numpy form, less than loading the compiled kernel does
    (numba's start-up).  Newton groups and larger sweeps load it as before."""
    with errors_from(mf):
        p = kinematics.plan(mf.mechanism)
    light = not p.uses_newton and mf.sample_count(samples) < BAR_FROM
    click.get_current_context().with_resource(_compiled.light_work(light))


def sweep(mf: ModelFile, samples: int | None = None, *, progress: bool | None = None,
          change_points: str = "smooth") -> KinematicSolution:
    """Analyse the file's sweep; on a terminal, in chunks with a progress bar; through
    change points as ``change_points`` says (see ``analyze(at_change_point=...)``)."""
    m = mf.mechanism
    q, qd, qdd = mf.sample_inputs(samples)
    if progress is None:
        progress = sys.stderr.isatty()
    with errors_from(mf):
        p = kinematics.plan(m)
    big = len(q) >= (BAR_FROM_NEWTON if p.uses_newton else BAR_FROM)
    if not (progress and big):
        return mf.analyze(samples, at_change_point=change_points)
    with errors_from(mf, "inputs"):
        return analyze_in_chunks(m, q, qd, qdd, chunks=50, label=f"analysing {m.name}",
                                 at_change_point=change_points)


def analyze_in_chunks(m, q, qd, qdd, *, chunks: int, label: str = "",
                      at_change_point: str = "smooth") -> KinematicSolution:
    """``analyze`` over ``q`` in ``chunks`` pieces (a progress bar on stderr when a label is
    given), each continuing where the last ended, joined into one solution."""
    parts = []
    bounds = np.linspace(0, len(q), chunks + 1).astype(int)
    pieces = [(a, b) for a, b in zip(bounds[:-1], bounds[1:]) if b > a]
    bar = click.progressbar(length=len(q), label=label, file=sys.stderr) if label else None
    try:
        if bar is not None:
            bar.__enter__()
        for a, b in pieces:
            parts.append(kinematics.analyze(m, q[a:b], qd[a:b], qdd[a:b], at_singular="flag",
                                            start=parts[-1] if parts else None,
                                            at_change_point=at_change_point))
            if bar is not None:
                bar.update(b - a)
    finally:
        if bar is not None:
            bar.__exit__(None, None, None)
    return KinematicSolution.concatenate(parts)


def stem(model: str) -> str:
    """A model file's name without its suffix, made safe (:func:`safe_name`): what its
    outputs are named after."""
    return safe_name(Path(model).stem)


def output_path(out: str | None, stem: str, suffix: str) -> Path:
    """``out`` itself when it names a file with ``suffix``'s kind, else ``out/stem.suffix``."""
    if out is None:
        return Path(f"{stem}.{suffix}")
    path = Path(out)
    if path.suffix and not out.endswith(("/", "\\")) and not path.is_dir():
        return path
    return path / f"{stem}.{suffix}"


_VALUE = re.compile(rf"[ \t]*({NUMBER})[ \t]*([a-z]*)[ \t]*")     # 30, 30deg, 0.5 rad


class Number(click.ParamType):
    """An option's number, written as every file and option writes one
    (:data:`kinelab.io._text.NUMBER`: ``1000``, ``-0.5``, ``1.5e3``), finite, and above 0
    when ``positive``."""

    name = "number"

    def __init__(self, *, positive: bool = False):
        self.positive = positive

    def convert(self, value, param, ctx):
        if isinstance(value, float):         # a default
            return value
        v = number(value) if isinstance(value, str) else None
        if v is None or not math.isfinite(v) or (self.positive and v <= 0):
            kind = "a finite number above 0" if self.positive else "a finite number"
            self.fail(f"expected {kind} in {PLAIN_NUMBER}, got {shown(str(value))}", param, ctx)
        return v


def parse_inputs(text: str, mf: ModelFile, option: str = "--at", *, rate: bool = False) -> np.ndarray:
    """Input values typed by a person, ``30``, ``30deg``, ``0.5rad``, ``12mm`` or ``30,60``,
    in SI; a bare number is in the file's unit.  The same for rates (``rate``: ``--speed
    60deg`` is 60 deg/s): errors name ``option``.  Values are refused past the sizes a model
    takes (an angle within MAX_TURNS turns of 0, a rate of at most MAX_RATE)."""
    with errors_from(mf):
        kinds = kinematics.plan(mf.mechanism).input_kinds
    parts = text.split(",")
    if len(parts) != len(kinds):
        raise ModelError(f"{option}: expected {len(kinds)} value(s) separated by commas (one per "
                         f"input: {quoted(mf.mechanism.input_names)}), got {shown(text)}")
    out = []
    for part, kind in zip(parts, kinds):
        match = _VALUE.fullmatch(part)
        unit = match.group(2) if match else ""
        units = ANGLE_UNITS if kind == "angle" else LENGTH_UNITS
        default = mf.units.angle_scale if kind == "angle" else mf.units.length_scale
        if not match or (unit and unit not in units):
            raise ModelError(f"{option}: expected a number in {PLAIN_NUMBER}, optionally "
                             f"followed by one of {', '.join(units)}, got {shown(part.strip())}")
        v = float(match.group(1)) * (units[unit] if unit else default)
        si = "rad" if kind == "angle" else "m"
        why = ("expected a finite number" if not math.isfinite(v) else
               rate_problem(v, f"{si}/s") if rate else
               range_problem(v, v, angle=kind == "angle"))
        if why:
            raise ModelError(f"{option}: {why}, got {shown(part.strip())}")
        out.append(v)
    return np.array(out) if len(out) > 1 else np.array(out[0])
