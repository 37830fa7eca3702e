"""The certificate of synthesis: each linkage analysed again at every task point, against
the task and what the synthesis reported; fails when a reported number is wrong."""
import dataclasses

import numpy as np
import pytest

import kinelab as kl
from kinelab import synthesis

NOTES_6_7 = synthesis.Positions(np.array([[0, 0], [5, 8], [10, 15], [18, 20]]) / 100.0,
                                np.radians([0.0, 10.0, 20.0, 30.0]))


def test_four_positions_are_reached():
    sols = synthesis.four_positions(NOTES_6_7, a0x=-0.20195, b0x=-0.29167)
    cert = kl.verify.certify_solutions(sols, "§6.7")
    assert cert.passed, str(cert)
    reached = cert.quantity("position reached").comparisons[0]
    assert reached.samples >= 4 * len([s for s in sols if s.valid])
    for s in sols:
        one = kl.verify.certify(s)
        assert one.passed and one["position error"][0] == ("synthesis",
                                                            "re-analysis at every task point")


def test_three_positions_of_the_notes():
    pos = synthesis.Positions(np.array([[1.0, 1.0], [2.0, 0.5], [3.0, 1.5]]),
                              np.array([0.0, 0.0, np.pi / 4]))
    s = synthesis.three_positions(pos, A0=np.array([5.0, 0.0]), B0=np.array([0.0, 0.0]))
    cert = kl.verify.certify(s)
    assert cert.passed, str(cert)
    # a wrong pivot in the report fails, named
    bad = dataclasses.replace(s, A1=s.A1 + 1e-6)
    verdict = kl.verify.certify(bad).verdict()
    assert verdict.startswith("NOT verified: ") and \
        "pivots by re-analysis at the first task point" in verdict


def test_a_wrong_reported_error_fails():
    s = synthesis.three_positions(
        synthesis.Positions(np.array([[1.0, 1.0], [2.0, 0.5], [3.0, 1.5]]),
                            np.array([0.0, 0.0, np.pi / 4])),
        A0=np.array([5.0, 0.0]), B0=np.array([0.0, 0.0]))
    errors = s.position_errors.copy()
    errors[2] = 1e-3
    cert = kl.verify.certify(dataclasses.replace(s, position_errors=errors))
    assert [q.name for q in cert.quantities if not q.passed] == ["position error"]


def test_function_generation_needs_and_meets_its_function():
    s = synthesis.function_generation(np.log10, (1.0, 2.0), (90.0, 150.0), (0.0, 90.0),
                                      degrees=True)
    cert = kl.verify.certify(s, function=np.log10)
    assert cert.passed, str(cert)
    assert cert.quantity("function reached").comparisons[0].samples == 3
    # against another function the structural error is not the one reported
    assert not kl.verify.certify(s, function=lambda x: np.log10(x) * 1.001).passed
    with pytest.raises(kl.errors.ModelError, match="function: expected the prescribed function"):
        kl.verify.certify(s)


def test_path_generation():
    targets = np.array([[0, 0], [0.25, 0.02], [0.5, 0.03], [0.75, 0.02], [1, 0]])
    sols = synthesis.path_generation(targets, runs=2, maxiter=10, seed=3)
    cert = kl.verify.certify_solutions(sols, "path")
    assert cert.passed, str(cert)
    assert cert["path error"][1] <= 1e-12


@pytest.mark.parametrize("design", [
    lambda: synthesis.crank_rocker(0.1, 45.0, 1.25, degrees=True),
    lambda: synthesis.offset_slider_crank(0.1, 1.4),
    lambda: synthesis.slotted_lever(1.6, 0.2),
    lambda: synthesis.whitworth(1.6, 0.03, 0.1)], ids=["crank-rocker", "offset slider-crank",
                                                      "slotted lever", "whitworth"])
def test_crank_rockers_and_quick_returns(design):
    s = design()
    requested = {"time_ratio": s.time_ratio}
    cert = kl.verify.certify(s, requested=requested)
    assert cert.passed, str(cert)
    assert cert["dead centre"][1] <= 1e-9
    # asked for another time ratio, the linkage does not meet it
    assert not kl.verify.certify(s, requested={"time_ratio": s.time_ratio + 1e-6}).passed
