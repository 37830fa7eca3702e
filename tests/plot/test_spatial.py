"""3-D figures: the spherical four-bar drawn on its sphere."""
import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import kinelab as kl  # noqa: E402
from kinelab.errors import AssemblyError, ModelError  # noqa: E402

M = kl.spatial.SphericalFourBar(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9)


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_links_are_arcs_between_their_axes(branch):
    ax = kl.plot.spherical_fourbar(M, 0.7, branch=branch)
    assert ax.name == "3d"
    sol = M.analyze(0.7, branch=branch)
    lines = {ln.get_label(): np.array(ln.get_data_3d()).T for ln in ax.lines}
    assert {"ground", "crank", "coupler", "rocker", "axis O2", "axis A", "axis B",
            "axis O4"} <= set(lines)
    ends = {"ground": (sol.u_O2, sol.u_O4), "crank": (sol.u_O2, sol.u_A),
            "coupler": (sol.u_A, sol.u_B), "rocker": (sol.u_B, sol.u_O4)}
    for link, (a, b) in ends.items():
        arc = lines[link]
        np.testing.assert_allclose(np.linalg.norm(arc, axis=1), 1.0, rtol=0, atol=1e-12)
        np.testing.assert_allclose(arc[0], a, rtol=0, atol=1e-12)
        np.testing.assert_allclose(arc[-1], b, rtol=0, atol=1e-12)
        # on one great circle: every point in the plane of the two axes
        normal = np.cross(a, b)
        assert np.abs(arc @ normal).max() < 1e-12
    assert ax.get_title() == f"θ2 = 40.1°, {branch}"


def test_draws_into_given_axes_and_saves(tmp_path):
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    assert kl.plot.spherical_fourbar(M, 0.0, ax=ax, wireframe=False) is ax
    kl.plot.save(fig, tmp_path / "sphere.png")
    assert (tmp_path / "sphere.png").stat().st_size > 1000


def test_refuses_bad_arguments():
    with pytest.raises(ModelError, match=r"fourbar: expected a kinelab.spatial.SphericalFourBar"):
        kl.plot.spherical_fourbar("four-bar", 0.0)
    with pytest.raises(ModelError, match=r"theta2: expected one angle"):
        kl.plot.spherical_fourbar(M, [0.0, 1.0])
    with pytest.raises(ModelError, match=r"branch: expected one of 'open', 'crossed'"):
        kl.plot.spherical_fourbar(M, 0.0, branch="up")
    far = kl.spatial.SphericalFourBar(alpha1=1.0, alpha2=0.9, alpha3=0.8, alpha4=0.3)
    with pytest.raises(AssemblyError, match=r"cannot close at θ2 = 0 rad"):
        kl.plot.spherical_fourbar(far, 0.0)
