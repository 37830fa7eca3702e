"""Shared by the synthesis tests: poses of known four-bars, and an independent check that
a model reaches prescribed poses (it uses only kl.analyze, none of the synthesis code)."""
import numpy as np

import kinelab as kl


def wrap(a):
    return np.angle(np.exp(1j * np.asarray(a)))


def catalogue_poses(q, branch="open", **lengths):
    """Coupler point and coupler angle of a catalogue four-bar at crank angles q."""
    dims = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5, coupler_point=(1.5, 1.0))
    dims.update(lengths)
    fb = kl.mechanisms.fourbar(branch=branch, **dims)
    sol = kl.analyze(fb, q=np.asarray(q, float))
    return sol.position("P"), sol.angle("coupler")


def engine_pose_errors(model, q, points, alpha):
    """Move the model to each crank angle with the engine: (position errors, angle errors)."""
    sol = kl.analyze(model, q=np.asarray(q, float))
    P = sol.position("P")
    th = sol.angle("coupler")
    return (np.linalg.norm(P - points, axis=1),
            np.abs(wrap(th - th[0] - (np.asarray(alpha) - alpha[0]))))


def crank_lengths(pos, A0, A1):
    """|A_j - A0| over the positions of a Positions, rotating A1 about P1 here (not with
    Positions.carry)."""
    a = pos.alpha
    R = np.stack([np.stack([np.cos(a), -np.sin(a)], -1), np.stack([np.sin(a), np.cos(a)], -1)], -2)
    Aj = pos.points + np.einsum("nij,j->ni", R, np.asarray(A1) - pos.points[0])
    return np.linalg.norm(Aj - A0, axis=1)


def travel_transmission(s, samples=20001):
    """The smallest transmission angle the engine meets while the crank turns from position
    1 to the last, in the sense the solution reports (the shorter way when it reports none)."""
    d = s.direction or 1
    q = s.q[0] + d * np.linspace(0.0, np.mod(d * (s.q[-1] - s.q[0]), 2 * np.pi), samples)
    sol = kl.analyze(s.model, q=q, unreachable="mask", at_singular="flag")
    return float(np.min(kl.kinematics.transmission_angle(sol)[sol.assembled]))
