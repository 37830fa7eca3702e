"""The integration's tolerances mean the same at every size: the PR robot of *Mecanismos*
§5.6 (a block sliding on a rail, an arm turning on it) scaled by s, with its moments of
inertia by s**2 and gravity by s, moves through the same angles and through slides s times
as long, at the same times (its equations of motion are the same in units of its size).
With atol in metres for the slide, a robot 0.1 mm across was integrated with a tolerance a
thousand times looser, relative to its size, than one a metre across."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.dynamics import Loads
from tests.dynamics.models import pr_robot
from tests.kinematics.scaling import scaled

T = np.linspace(0.0, 1.0, 11)


def run(m, s, method):
    return kl.dynamics.simulate(m, (0.0, 1.0), [0.2 * s, 0.3], [0.5 * s, 0.0], method=method,
                                loads=Loads(gravity=(0.0, -9.81 * s)), t_eval=T)


@pytest.mark.parametrize("method", ["DOP853", "RK45"])
@pytest.mark.parametrize("s", [1e-4, 1e-2, 1e2, 1e4])
def test_a_scaled_robot_moves_the_same(s, method):
    m = pr_robot()
    ref, got = run(m, 1.0, method), run(scaled(m, s), s, method)
    # the same steps to rounding: a few hundred machine epsilons (the rtol, 1e-10, is what
    # an unscaled tolerance on the slide would have shown)
    np.testing.assert_allclose(got.q[:, 0] / s, ref.q[:, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(got.q[:, 1], ref.q[:, 1], rtol=0, atol=1e-12)
