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
