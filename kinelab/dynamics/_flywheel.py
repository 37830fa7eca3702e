"""Flywheel sizing from the torque curve of a machine cycle."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.model import MAX_RATE, is_real, real_array

__all__ = ["flywheel", "Flywheel"]


@dataclass(frozen=True)
class Flywheel:
    """A flywheel that keeps the speed fluctuation of a cycle within a given coefficient.

    Attributes
    ----------
    theta : ndarray, shape (N,)
        Crank angle over one cycle, rad.
    torque : ndarray, shape (N,)
        Torque the crank needs at each angle, N m.
    mean_torque : float
        Its average over the cycle, N m: what a steady motor supplies.
    energy : ndarray, shape (N,)
        ``integral of (mean_torque - torque) d theta`` from the start of the cycle, J: the
        energy the flywheel stores; the speed is highest where it peaks.
    energy_fluctuation : float
        ``max(energy) - min(energy)``, J.
    theta_fastest, theta_slowest : float
        Crank angles of the highest and lowest speed, rad.
    speed : float
        Mean crank speed, rad/s.
    fluctuation : float
        Coefficient of speed fluctuation ``(w_max - w_min) / w_mean``.
    inertia : float
        Moment of inertia the flywheel needs, ``energy_fluctuation / (fluctuation speed^2)``,
        kg m^2 (exact for ``w_mean = (w_max + w_min) / 2``; the links' own varying inertia
        is neglected beside it).
    """

    theta: np.ndarray
    torque: np.ndarray
    mean_torque: float
    energy: np.ndarray
    energy_fluctuation: float
    theta_fastest: float
    theta_slowest: float
    speed: float
    fluctuation: float
    inertia: float

    def __repr__(self) -> str:
        return (f"Flywheel(inertia={self.inertia:.6g} kg m^2, mean torque {self.mean_torque:.6g} N m, "
                f"energy fluctuation {self.energy_fluctuation:.6g} J)")


def flywheel(theta: ArrayLike, torque: ArrayLike, *, speed: float, fluctuation: float) -> Flywheel:
    """Size a flywheel from the torque a machine needs over one cycle.

    A motor supplying the mean torque gives the shaft, between two crank angles, the energy
    ``E = integral (T_mean - T) d theta``; a flywheel of inertia I turns that into speed,
    ``1/2 I (w_max^2 - w_min^2) = E_max - E_min``.  With the coefficient of fluctuation
    ``C_s = (w_max - w_min) / w_mean`` and ``w_mean = (w_max + w_min) / 2`` this gives
    ``I = (E_max - E_min) / (C_s w_mean^2)``.  The integral is by the trapezoidal rule.

    Parameters
    ----------
    theta : array_like, shape (N,)
        Crank angles covering exactly one cycle, increasing (2 pi for most machines, 4 pi
        for a four-stroke engine), rad.
    torque : array_like, shape (N,)
        Torque the crank needs at those angles (the input torque of
        :func:`kinelab.dynamics.inverse` at constant speed), N m.
    speed : float
        Mean crank speed, rad/s.
    fluctuation : float
        Allowed coefficient of speed fluctuation ``(w_max - w_min) / w_mean``, above 0 and
        below 2 (where the crank would stop), e.g. 0.002 for an alternator, 0.2 for a
        crusher.

    Returns
    -------
    Flywheel

    Examples
    --------
    A torque ``T0 + A sin(2 theta)`` stores and returns ``A`` joules each half turn:

    >>> theta = np.linspace(0.0, 2 * np.pi, 3601)
    >>> fw = flywheel(theta, 10 + 4 * np.sin(2 * theta), speed=100.0, fluctuation=0.02)
    >>> round(fw.mean_torque, 9), round(fw.energy_fluctuation, 5), round(fw.inertia, 6)
    (10.0, 4.0, 0.02)
    """
    th, tq = real_array(theta), real_array(torque)
    if th is None or tq is None:
        raise ModelError(f"theta, torque: expected arrays of real numbers, got {describe(theta)} "
                         f"and {describe(torque)}")
    problems = []
    if th.ndim != 1 or th.shape != tq.shape or th.size < 3:
        problems.append(f"theta, torque: expected two arrays of the same shape (N,), N >= 3, got "
                        f"{th.shape} and {tq.shape}")
    elif not (np.all(np.isfinite(th)) and np.all(np.isfinite(tq))):
        problems.append("theta, torque: expected finite numbers (a singular sample gives NaN "
                        "torques; sweep around it)")
    elif np.any(np.diff(th) <= 0):
        problems.append("theta: expected increasing crank angles over one cycle")
    if not (is_real(speed) and 0 < speed <= MAX_RATE):
        problems.append(f"speed: expected a positive number of rad/s up to {MAX_RATE:g}, got "
                        f"{describe(speed)}")
    # (w_max - w_min) / w_mean with w_mean = (w_max + w_min) / 2 reaches 2 where w_min = 0
    if not (is_real(fluctuation) and 0 < fluctuation < 2):
        problems.append(f"fluctuation: expected a positive number below 2 (the coefficient of "
                        f"speed fluctuation (w_max - w_min) / w_mean, 2 when the crank stops), "
                        f"got {describe(fluctuation)}")
    if problems:
        raise ModelError(problems)
    span = th[-1] - th[0]
    from scipy.integrate import cumulative_trapezoid
    work = cumulative_trapezoid(tq, th, initial=0.0)
    mean = work[-1] / span
    energy = mean * (th - th[0]) - work
    i_max, i_min = int(np.argmax(energy)), int(np.argmin(energy))
    de = float(energy[i_max] - energy[i_min])
    return Flywheel(theta=th, torque=tq, mean_torque=float(mean), energy=energy,
                    energy_fluctuation=de, theta_fastest=float(th[i_max]),
                    theta_slowest=float(th[i_min]), speed=float(speed),
                    fluctuation=float(fluctuation), inertia=de / (fluctuation * speed ** 2))
