"""Tolerance studies: each drawn design against the engine, the spread against the linear
sensitivities (central differences of the engine), and the figures."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError

NOMINAL = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)


def test_each_drawn_design_against_the_engine():
    study = kl.sweep.tolerance("fourbar", NOMINAL, {"crank": 0.01, "ground": 0.02}, n=6, seed=2)
    q = study.q
    nominal = kl.analyze(kl.mechanisms.fourbar(**NOMINAL), q).angle("rocker")
    for i, row in study.designs.iterrows():
        drawn = kl.analyze(kl.mechanisms.fourbar(**row.to_dict()), q).angle("rocker")
        assert np.allclose(study.errors[i], kl.solvers.wrap_angle(drawn - nominal), atol=1e-10)
    assert (study.designs["coupler"] == 3.0).all()
    assert study.designs["crank"].between(0.99, 1.01).all() and study.designs["crank"].std() > 0.004


def test_spread_matches_the_linear_sensitivities():
    tol = {"ground": 1e-5, "crank": 1e-5, "coupler": 2e-5, "rocker": 1e-5}
    study = kl.sweep.tolerance("fourbar", NOMINAL, tol, n=4000, seed=5)
    h = 1e-6
    variance = 0.0
    for name, t in tol.items():
        up, down = dict(NOMINAL), dict(NOMINAL)
        up[name] += h
        down[name] -= h
        d = (kl.analyze(kl.mechanisms.fourbar(**up), study.q).angle("rocker")
             - kl.analyze(kl.mechanisms.fourbar(**down), study.q).angle("rocker")) / (2 * h)
        variance = variance + (d * t) ** 2 / 3.0          # uniform on +-t: variance t^2 / 3
    # 4000 draws: the sample standard deviation is within a few % of the true one
    assert np.allclose(study.errors.std(axis=0), np.sqrt(variance), rtol=0.06)


def test_a_slide_output_and_the_figures(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    study = kl.sweep.tolerance("slider_crank", dict(crank=1.0, rod=3.0), {"crank": 1e-3},
                               n=50, distribution="normal")
    assert study.unit == "m" and np.allclose(study.errors[:, 0], study.designs["crank"] - 1.0, atol=1e-12)
    ax = kl.plot.tolerance_band(study)
    assert ax.get_ylabel() == "slide error [m]"
    ax = kl.plot.error_histogram(kl.sweep.tolerance("fourbar", NOMINAL, {"crank": 1e-3}, n=50),
                                 degrees=True)
    assert ax.get_xlabel() == "largest |rocker error| over the cycle [deg]"


@pytest.mark.parametrize("kwargs, message", [
    (dict(tolerances={"crank_length": 1e-3}), r"tolerances: unknown parameter 'crank_length'"),
    (dict(tolerances={"crank": -1.0}), r"tolerances: crank: expected a tolerance >= 0"),
    (dict(tolerances={"crank": 1e-3}, distribution="gauss"), r"distribution: expected one of 'uniform', 'normal'"),
])
def test_bad_tolerance_input(kwargs, message):
    with pytest.raises(ModelError, match=message):
        kl.sweep.tolerance("fourbar", NOMINAL, **kwargs)
