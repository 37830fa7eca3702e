"""``kinelab dynamics``: actuator efforts, joint reactions and shaking over a model's sweep.

It reads the model file, sweeps its inputs as ``kinelab analyze`` does, calls
:func:`kinelab.dynamics.inverse` with the file's ``[dynamics]`` section and writes a CSV
table and figures; every computation lives in :mod:`kinelab.dynamics`.
"""
from __future__ import annotations

from pathlib import Path

import click
import numpy as np

from kinelab._files import outputs, safe_name
from kinelab.cli._main import (DEGREES, LANG, SI, VERIFY, certificate_path, errors_from,
                               output_units, read_model, report, said_written, stem)
from kinelab.io import ModelFile
from kinelab.io._modelfile import MAX_SAMPLES, sweep_times
from kinelab.model import Units
from kinelab.errors import ModelError, describe, shown_path
from kinelab.cli._words import SAID, number

__all__ = ["dynamics_command", "run", "times", "MAX_VALUES"]

MAX_VALUES = 5_000_000
"""The most values (samples x columns) of the table ``kinelab dynamics`` writes: the inverse
dynamics, the CSV text and the figures of a table this large take about 20 s on a slow,
loaded machine (250,000 samples of the engine example's 20 columns; ``benchmarks/tables.py``
prints the rates)."""


times = sweep_times
"""Time along a one-input sweep at constant speed (zero otherwise), s."""


def run(mf: ModelFile, out: str | Path = ".", *, samples: int | None = None,
        units: Units | None = None, gravity: tuple[float, float] | None = None,
        plots: bool = True, verify: bool = False, name: str | None = None, lang: str = "en"):
    """Sweep, solve and write ``<name>_dynamics.csv`` and the figures (the inputs in
    ``units``, default the file's; forces and energies in SI; the figures' text in
    ``lang``) into ``out``, all or none of them, ``<name>`` being ``name`` (the command
    gives the model file's stem), by default the model's name made safe
    (:func:`safe_name`); with ``verify``, the result's certificate too, as
    ``<name>_dynamics_certificate.json``.  Returns the result, the paths written (the
    certificate's last) and the certificate."""
    from kinelab.dynamics._inverse import table_width   # not needed by times (kinelab check)

    units = mf.units if units is None else units
    m = mf.mechanism
    rows, width = mf.sample_count(samples), table_width(m)
    if rows * width > MAX_VALUES:
        raise ModelError(f"{'--samples' if samples is not None else 'inputs.samples'}: a table of "
                         f"{rows:,} samples x {width} columns is {rows * width:,} values; kinelab "
                         f"dynamics writes at most {MAX_VALUES:,} (about 20 s): ask for at most "
                         f"{MAX_VALUES // width:,} samples",
                         source=None if samples is not None else mf.source)
    res = mf.inverse_dynamics(samples, gravity=gravity)     # the browser app's forces too
    certificate = None
    if verify:          # before anything is written: a model the routes refuse writes nothing
        from kinelab.verify import certify
        loads, masses = mf.dynamics_setup(gravity)
        certificate = certify(res, loads=loads, masses=masses)
    name = safe_name(m.name) if name is None else name
    with outputs(out) as files:
        written = [files.write(f"{name}_dynamics.csv", lambda p: res.to_csv(p, units=units))]
        if plots:
            from kinelab.cli._draw import _agg
            from kinelab.plot import _dynamics as figs
            from kinelab.plot import save
            plt = _agg()
            figures = (("efforts", figs.effort_curves), ("reactions", figs.reaction_curves),
                       ("shaking", figs.shaking_curves))
            for suffix, draw in figures[:1] if res.reactions_refused else figures:
                fig = draw(res, units=units, lang=lang)
                try:
                    written.append(files.write(f"{name}_{suffix}.png", lambda p: save(fig, p)))
                finally:
                    plt.close(fig)
        if certificate is not None:
            written.append(files.write(certificate_path(written[0]).name, certificate.to_json))
    return res, written, certificate


def _gravity(text: str | None):
    if text is None:
        return None
    try:
        g = tuple(float(v) for v in text.split(","))
    except ValueError:
        g = ()
    if len(g) != 2:
        raise click.BadParameter(f"expected GX,GY in m/s^2 (e.g. 0,-9.81), got {describe(text)}")
    return g


@click.command("dynamics")
@click.argument("model", type=click.Path(exists=True, dir_okay=False))
@click.option("--out", "-o", default=".", metavar="DIR", show_default=True,
              help="Directory for the table and the figures.")
@click.option("--samples", type=click.IntRange(2, MAX_SAMPLES), default=None,
              help="Samples per input, instead of the file's.")
@SI
@DEGREES
@click.option("--gravity", default=None, metavar="GX,GY",
              help="Gravity in m/s^2, instead of the file's (e.g. 0,-9.81).")
@click.option("--no-plots", is_flag=True, help="Write the table only.")
@LANG
@VERIFY
def dynamics_command(model, out, samples, si, degrees, gravity, no_plots, lang, verify_):
    """Actuator efforts, joint reactions and shaking force of MODEL over its inputs' sweep.

    Writes <name>_dynamics.csv (efforts, energies, reactions, shaking force and moment)
    and, unless --no-plots, <name>_efforts.png, <name>_reactions.png, <name>_shaking.png,
    all of them or none; <name> is the model file's name without its suffix.  A model
    with a cam joint driving an oscillating follower gets its efforts and energies only
    (its contact point is not declared), and says so.
    The links need mass data; loads come from the file's [dynamics] section.  The inputs'
    positions and rates are in the file's units (--si for m and rad); forces are in N,
    torques in N m, energies in J and powers in W.  With --verify, the efforts, energies,
    reactions and shaking are computed again by independent routes (power balance,
    Newton-Euler, each link's balance, the whole mechanism's momentum) and the certificate
    is printed last and written as <name>_dynamics_certificate.json.
    """
    g = _gravity(gravity)
    mf = read_model(model)
    units = output_units(mf.units, si, degrees)
    with errors_from(mf):
        res, written, certificate = run(mf, out, samples=samples, units=units, gravity=g,
                                        plots=not no_plots, verify=verify_, name=stem(model),
                                        lang=lang)
    said = SAID[lang]

    def num(v):
        return number(v, 6, lang)
    for name, kind, col in zip(res.input_names, res.input_kinds, res.input_forces.T):
        unit = "N m" if kind == "angle" else "N"
        ok = np.isfinite(col)
        if not ok.any():
            click.echo(said["undefined"].format(name=name))
            continue
        peak = np.max(np.abs(col[ok]))
        rms = peak * np.sqrt(np.mean((col[ok] / peak) ** 2)) if peak > 0 else 0.0  # no overflow
        click.echo(said["effort"].format(name=name, peak=num(peak), rms=num(rms), unit=unit))
    if res.reactions_refused:       # the efforts only (an oscillating cam follower)
        click.echo(res.reactions_refused)
    else:
        F = np.hypot(*res.shaking_force.T)
        click.echo(said["shaking"].format(force=num(np.nanmax(F)),
                                          moment=num(np.nanmax(np.abs(res.shaking_moment)))))
    if res.singular.any():
        click.echo(said["singular"].format(count=int(res.singular.sum())))
    said_written(written)
    if certificate is not None:
        report(certificate)

