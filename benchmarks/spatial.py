"""Throughput of kinelab.spatial over 10^6 poses: RRR forward and inverse kinematics and
6-SPS leg lengths.  Prints poses per second; asserts nothing about speed."""
from __future__ import annotations

import time

import numpy as np
from scipy.spatial.transform import Rotation

import kinelab.spatial as sp

N = 1_000_000


def rate(label: str, run, repeat: int = 3) -> None:
    best = np.inf
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    print(f"{label:<44} {N / best:>14,.0f} poses/s   ({best:.3f} s for {N:,})")


def main() -> None:
    rng = np.random.default_rng(0)
    robot = sp.rrr(1.0, 1.0)
    theta = rng.uniform(-np.pi, np.pi, (N, 3))
    points = robot.forward(theta)
    # Keep the reachable points off the base axis (a singular point raises).
    points = points[np.hypot(points[:, 0], points[:, 1]) > 1e-9]

    ring = np.radians([-15, 15, 105, 135, 225, 255]), np.radians([-45, 45, 75, 165, 195, 285])
    base = np.c_[np.cos(ring[0]), np.sin(ring[0]), np.zeros(6)]
    top = 0.5 * np.c_[np.cos(ring[1]), np.sin(ring[1]), np.zeros(6)]
    position = np.array([0.0, 0.0, 1.0]) + rng.uniform(-0.2, 0.2, (N, 3))
    rotation = Rotation.from_rotvec(rng.uniform(-0.3, 0.3, (N, 3)))

    print(f"kinelab.spatial benchmark, N = {N:,} poses, best of 3")
    rate("RRR forward kinematics", lambda: robot.forward(theta))
    rate("RRR inverse kinematics (all 4 branches)", lambda: robot.inverse(points))
    rate("RRR inverse kinematics (one branch)", lambda: robot.inverse(points, branch="front-up"))
    rate("6-SPS leg lengths", lambda: sp.stewart_leg_lengths(base, top, position, rotation))


if __name__ == "__main__":
    main()
