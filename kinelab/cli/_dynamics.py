"""``kinelab dynamics``: actuator efforts, joint reactions and shaking over a model's sweep.

A click command for the main ``kinelab`` group to register (``main.add_command(dynamics)``).
It reads the model, sweeps its inputs, calls :func:`kinelab.dynamics.inverse` and writes a
CSV table and figures; every computation lives in :mod:`kinelab.dynamics`.
"""
from __future__ import annotations

import math
from pathlib import Path

import click
import numpy as np

from kinelab import dynamics, kinematics
from kinelab.errors import KinelabError, ModelError
from kinelab.model import Mechanism

__all__ = ["dynamics_command", "sweep_inputs", "run"]


def _load(path: str) -> Mechanism:
    try:
        from kinelab.io import load  # lazy: model files are the io room's business
    except ImportError:
        raise click.ClickException(
            "reading model files needs kinelab.io.load, which this installation does not have "
            "yet; call kinelab.dynamics.inverse(model, ...) from Python instead") from None
    return load(path)


def sweep_inputs(m: Mechanism, samples: int):
    """q, qd, qdd and t over the model's input ranges, all inputs moving together.

    Each input runs over its ``range`` at its ``speed`` and ``acceleration``; a single angle
    input without a range covers one turn, or the interval where it assembles.  Time is
    the crank's ``(q - q[0]) / speed`` for one input at constant speed, else zero.
    """
    M = len(m.inputs)
    kinds = ["slide" if (i.joint is not None and m.joint(i.joint).type == "P") else "angle"
             for i in m.inputs]
    cols = []
    for k, (inp, kind) in enumerate(zip(m.inputs, kinds)):
        if inp.range is not None:
            lo, hi = inp.range
        elif kind == "angle" and M == 1:
            reach = kinematics.reachable_ranges(m)
            lo, hi = reach[0]
            if hi - lo >= 2 * math.pi - 1e-9:
                lo, hi = 0.0, 2 * math.pi
            else:   # stay off the limit positions, where the forces are infinite
                pad = 1e-3 * (hi - lo)
                lo, hi = lo + pad, hi - pad
        else:
            raise ModelError(f"inputs[{k}] ('{inp.label}'): range: the sweep needs a range for this "
                             "input; give one in the model file")
        cols.append(np.linspace(lo, hi, samples))
    q = np.stack(cols, axis=-1)
    qd = np.broadcast_to([i.speed for i in m.inputs], q.shape).copy()
    qdd = np.broadcast_to([i.acceleration for i in m.inputs], q.shape).copy()
    t = np.zeros(samples)
    if M == 1 and m.inputs[0].speed != 0 and m.inputs[0].acceleration == 0:
        t = (q[:, 0] - q[0, 0]) / m.inputs[0].speed
    return q, qd, qdd, t


def run(m: Mechanism, out: str | Path = ".", *, samples: int = 361, degrees: bool = False,
        gravity: tuple[float, float] | None = None, plots: bool = True):
    """Sweep, solve and write ``<name>_dynamics.csv`` and the figures; returns the result and
    the paths written."""
    from kinelab._files import atomic_write

    setup = dynamics.DynamicsSetup.from_model(m)
    loads = setup.loads
    if gravity is not None:
        loads = dynamics.Loads(gravity=gravity, forces=loads.forces, torques=loads.torques,
                               springs=loads.springs, dampers=loads.dampers)
    q, qd, qdd, t = sweep_inputs(m, samples)
    M = q.shape[1]
    squeeze = (lambda a: a[:, 0]) if M == 1 else (lambda a: a)
    res = dynamics.inverse(m, squeeze(q), squeeze(qd), squeeze(qdd), loads=loads,
                           masses=setup.masses(m), t=t)
    out = Path(out)
    written = [out / f"{m.name}_dynamics.csv"]
    res.to_csv(written[0], degrees=degrees)
    if plots:
        from kinelab.plot import _dynamics as figs
        for suffix, draw in (("efforts", figs.effort_curves), ("reactions", figs.reaction_curves),
                             ("shaking", figs.shaking_curves)):
            fig = draw(res, degrees=degrees)
            path = out / f"{m.name}_{suffix}.png"
            atomic_write(path, lambda f, fig=fig: fig.savefig(f, format="png", dpi=120), binary=True)
            fig.clf()
            import matplotlib.pyplot as plt
            plt.close(fig)
            written.append(path)
    return res, written


def _gravity(text: str | None):
    if text is None:
        return None
    try:
        g = tuple(float(v) for v in text.split(","))
    except ValueError:
        g = ()
    if len(g) != 2:
        raise click.BadParameter(f"expected GX,GY in m/s^2 (e.g. 0,-9.81), got {text!r}")
    return g


@click.command("dynamics")
@click.argument("model", type=click.Path(exists=True, dir_okay=False))
@click.option("--out", "-o", default=".", metavar="DIR", show_default=True,
              help="Directory for the table and the figures.")
@click.option("--samples", type=click.IntRange(2, 10_000_000), default=361, show_default=True,
              help="Samples over the inputs' ranges.")
@click.option("--degrees", is_flag=True, help="Angles in degrees in the table and the figures.")
@click.option("--gravity", default=None, metavar="GX,GY",
              help="Gravity in m/s^2, instead of the file's (e.g. 0,-9.81).")
@click.option("--no-plots", is_flag=True, help="Write the table only.")
def dynamics_command(model, out, samples, degrees, gravity, no_plots):
    """Actuator efforts, joint reactions and shaking force of MODEL over its inputs' sweep.

    Writes <name>_dynamics.csv (efforts, energies, reactions, shaking force and moment)
    and, unless --no-plots, <name>_efforts.png, <name>_reactions.png, <name>_shaking.png.
    The links need mass data; loads come from the file's [dynamics] section.
    """
    g = _gravity(gravity)
    try:
        m = _load(model)
        res, written = run(m, out, samples=samples, degrees=degrees, gravity=g, plots=not no_plots)
    except KinelabError as exc:
        raise click.ClickException(str(exc)) from None
    for name, kind, col in zip(res.input_names, res.input_kinds, res.input_forces.T):
        unit = "N m" if kind == "angle" else "N"
        ok = np.isfinite(col)
        click.echo(f"{name}: peak |effort| {np.max(np.abs(col[ok])):.6g} {unit}, "
                   f"rms {np.sqrt(np.mean(col[ok] ** 2)):.6g} {unit}")
    F = np.hypot(*res.shaking_force.T)
    click.echo(f"shaking force: peak {np.nanmax(F):.6g} N; shaking moment: peak "
               f"{np.nanmax(np.abs(res.shaking_moment)):.6g} N m")
    if res.singular.any():
        click.echo(f"{int(res.singular.sum())} singular sample(s): forces undefined there (NaN)")
    for path in written:
        click.echo(f"wrote {path}")
