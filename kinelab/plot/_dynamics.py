"""Figures of dynamics results: actuator efforts, joint reactions, shaking, energy.

matplotlib is imported inside the functions, so ``import kinelab`` never needs it.  Each
function draws on a new figure (or the one given) and returns the figure.
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from kinelab.dynamics import InverseDynamics, Simulation
from kinelab.model import Units
from kinelab.plot._figures import _legend, _x_axis, plain
from kinelab.plot._words import decimal_commas, words

__all__ = ["effort_curves", "reaction_curves", "shaking_curves", "energy_curves"]


def _pyplot():
    import matplotlib.pyplot as plt     # lazy: drawing is the only thing that needs it
    return plt


def _abscissa(axes, res, degrees: bool, units, lang: str = "en") -> np.ndarray:
    """Label the x axis (shared by ``axes``) and return its values: the input of a one-input
    sweep in ``units`` (its singular positions marked on every axes), else time (or the
    sample number for a still sweep)."""
    if isinstance(res, InverseDynamics) and res.M == 1:
        u = Units.resolve(units, degrees=degrees)
        for ax in axes:
            x = _x_axis(ax, res.kinematics, u, lang)
            if ax is not axes[-1]:
                ax.set_xlabel("")
        return x
    w = words(lang)
    x, label = ((res.t, f"{w['time']} [s]") if np.ptp(res.t) > 0 else
                (np.arange(len(res.t)), w["sample"]))
    axes[-1].set_xlabel(label)
    return x


def _figure(figure, rows: int):
    plt = _pyplot()
    fig = figure if figure is not None else plt.figure(figsize=(8, 2.6 * rows + 0.6),
                                                       layout="constrained")
    return fig, fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]


def effort_curves(res: InverseDynamics | Simulation, *, degrees: bool = False,
                  units: Units | Mapping[str, str] | None = None, figure=None,
                  lang: str = "en"):
    """Each actuator's effort (torque or force, SI) against the input (in ``units``, default
    SI) or time; the axes in ``lang`` ("en" or "pt").

    Examples
    --------
    >>> from kinelab.dynamics import inverse, Loads
    >>> from kinelab.model import Mechanism, Point, Link, Joint, Input
    >>> m = Mechanism("pendulum", (Point("O", 0, 0), Point("G", 0.5, 0)),
    ...     (Link("ground", ("O",), ground=True),
    ...      Link("arm", ("O", "G"), mass=2.0, center_of_mass="G", inertia=0.01)),
    ...     (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
    >>> res = inverse(m, np.linspace(0, 2 * np.pi, 37), loads=Loads(gravity=(0, -9.81)))
    >>> from kinelab.plot._dynamics import effort_curves
    >>> fig = effort_curves(res, degrees=True)
    >>> fig.axes[0].get_ylabel(), fig.axes[0].get_xlabel()
    ('input torque [N m]', 'pivot [deg]')
    """
    w = words(lang)
    kinds = res.input_kinds
    fig, axes = _figure(figure, len(kinds))
    x = _abscissa(axes, res, degrees, units, lang)
    for ax, name, kind, y in zip(axes, res.input_names, kinds, res.input_forces.T):
        ax.plot(x, y)
        effort = "torque" if kind == "angle" else "force"
        what = w[f"input {effort}"] if len(kinds) == 1 else w[f"named {effort}"].format(name=name)
        ax.set_ylabel(plain(f"{what} [{'N m' if kind == 'angle' else 'N'}]"))
        ax.grid(True, alpha=0.3)
    _legend(axes[0], always=False)
    axes[0].set_title(plain(w["efforts title"].format(name=res.mechanism.name)))
    decimal_commas(fig, lang)
    return fig


def reaction_curves(res: InverseDynamics, joints=None, *, degrees: bool = False,
                    units: Units | Mapping[str, str] | None = None, figure=None,
                    lang: str = "en"):
    """The magnitude of each joint's reaction force (and a prismatic joint's moment), SI,
    against the input in ``units`` (default SI); the axes in ``lang``."""
    w = words(lang)
    joints = list(res.joint_names if joints is None else joints)
    fig, axes = _figure(figure, 2 if any(res.mechanism.joint(j).type == "P" for j in joints) else 1)
    x = _abscissa(axes, res, degrees, units, lang)
    for j in joints:
        axes[0].plot(x, np.hypot(*res.reactions(j).T), label=plain(j))
    axes[0].set_ylabel(f"{w['reaction']} [N]")
    _legend(axes[0], loc="best")
    axes[0].set_title(plain(w["reactions title"].format(name=res.mechanism.name)))
    if len(axes) > 1:
        for j in joints:
            if res.mechanism.joint(j).type == "P":
                axes[1].plot(x, res.reaction_moment(j), label=plain(j))
        axes[1].set_ylabel(f"{w['slide moment']} [N m]")
        _legend(axes[1], loc="best")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    decimal_commas(fig, lang)
    return fig


def shaking_curves(res: InverseDynamics, *, degrees: bool = False,
                   units: Units | Mapping[str, str] | None = None, figure=None,
                   lang: str = "en"):
    """The shaking force as a polar trace (its tip over the cycle) and the shaking moment
    (SI) against the input in ``units`` (default SI); the axes in ``lang``."""
    plt = _pyplot()
    w = words(lang)
    fig = figure if figure is not None else plt.figure(figsize=(10, 4.2), layout="constrained")
    left, right = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1, 1.6]})
    F = res.shaking_force
    left.plot(F[:, 0], F[:, 1])
    left.plot([0], [0], "k+")
    left.set_aspect("equal", adjustable="datalim")
    left.set_xlabel("Fx [N]")
    left.set_ylabel("Fy [N]")
    left.set_title(w["shaking force"])
    x = _abscissa([right], res, degrees, units, lang)
    right.plot(x, res.shaking_moment)
    right.set_ylabel(f"{w['shaking moment']} [N m]")
    _legend(right, always=False)
    for ax in (left, right):
        ax.grid(True, alpha=0.3)
    fig.suptitle(plain(res.mechanism.name))
    decimal_commas(fig, lang)
    return fig


def energy_curves(sim: Simulation, *, figure=None):
    """Kinetic, potential and mechanical energy of a simulation, the work done on it, and
    the energy balance (which should stay at the integration error)."""
    fig, axes = _figure(figure, 2)
    for label in ("kinetic_energy", "potential_energy", "energy", "actuator_work", "applied_work",
                  "dissipated"):
        y = getattr(sim, label)
        if np.any(y != 0):
            axes[0].plot(sim.t, y, label=label.replace("_", " "))
    axes[0].set_ylabel("J")
    axes[0].legend(loc="best", fontsize="small")
    axes[0].set_title(plain(f"{sim.mechanism.name}: energy"))
    axes[1].plot(sim.t, sim.energy_balance)
    axes[1].set_ylabel("balance [J]")
    axes[1].set_xlabel("t [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    return fig
