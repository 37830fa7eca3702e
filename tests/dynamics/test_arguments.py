"""Arguments of the dynamics room: each bad one is a ModelError naming it; a motion too long
for its budget of evaluations is refused at once, with the estimate."""
import numpy as np
import pytest

from kinelab.dynamics import (LinkMass, Loads, MassProperties, Spring, flywheel, inverse,
                              simulate)
from kinelab.dynamics import _forward
from kinelab.errors import ModelError
from tests.dynamics.models import pendulum

g = (0.0, -9.81)
BIG = 10 ** 400


@pytest.mark.parametrize("make, message", [
    (lambda: Loads(springs=5), r"^springs: expected a sequence of kinelab\.dynamics\.Spring, got 5$"),
    (lambda: Loads(dampers="ab"), r"^dampers: expected a sequence of kinelab\.dynamics\.Damper, got 'ab'$"),
    (lambda: Loads(springs=[Spring(("O", "G"), stiffness=1.0, free_length=0.5), 3]),
     r"^springs\[1\]: expected a kinelab\.dynamics\.Spring, got 3$"),
    (lambda: MassProperties(links=5), r"^links: expected a sequence of kinelab\.dynamics\.LinkMass, got 5$"),
    (lambda: MassProperties(links=["x"]), r"^links\[0\]: expected a kinelab\.dynamics\.LinkMass, got 'x'$"),
    (lambda: MassProperties(points=[LinkMass("arm", 1.0, "G", 0.1)]),
     r"^points\[0\]: expected a kinelab\.dynamics\.PointMass, got "),
])
def test_sequences_of_loads_and_masses(make, message):
    with pytest.raises(ModelError, match=message):
        make()


THETA = np.linspace(0.0, 2 * np.pi, 50)


@pytest.mark.parametrize("kw, message", [
    (dict(speed=BIG), r"speed: expected a positive number of rad/s up to 1e\+100, got a whole "
                      r"number of 401 digits"),
    (dict(fluctuation=5), r"fluctuation: expected a positive number below 2 \(the coefficient "
                          r"of speed fluctuation .*got 5$"),
    (dict(fluctuation=2.0), r"fluctuation: .*got 2\.0$"),
    (dict(fluctuation=0), r"fluctuation: .*got 0$"),
    (dict(theta=[0.0, 1.0, BIG], torque=[1.0, 2.0, 3.0]),
     r"theta, torque: expected arrays of real numbers, got \[0\.0, 1\.0, a whole number of 401 digits\]"),
])
def test_flywheel_arguments(kw, message):
    kw = {"theta": THETA, "torque": 1 + np.sin(THETA), "speed": 10.0, "fluctuation": 0.1, **kw}
    with pytest.raises(ModelError, match=message):
        flywheel(**kw)


def test_flywheel_fluctuation_just_below_two_still_sizes_a_flywheel():
    fw = flywheel(THETA, 1 + np.sin(THETA), speed=10.0, fluctuation=1.9)
    assert 0 < fw.inertia < flywheel(THETA, 1 + np.sin(THETA), speed=10.0, fluctuation=0.1).inertia


@pytest.mark.parametrize("kw, message", [
    (dict(q=[]), r"^q: expected at least one configuration, got none"),
    (dict(q=0.1, reactions="x"), r"^reactions: expected True or False, got 'x'$"),
    (dict(q=0.1, t=BIG), r"^t: expected a time \(s\) or one per sample, shape \(\) or \(1,\), got "
                         r"a whole number of 401 digits$"),
])
def test_inverse_arguments(kw, message):
    with pytest.raises(ModelError, match=message):
        inverse(pendulum(), **kw)


def test_an_exception_in_a_callable_law_names_the_law():
    def law(t, q, qd):
        return 1 / 0
    with pytest.raises(ModelError, match=r"^inputs\['pivot'\]: the callable raised "
                       r"ZeroDivisionError: division by zero at t = 0 s; fix the function") as info:
        simulate(pendulum(), (0.0, 1.0), 0.3, inputs={"pivot": law}, loads=Loads(gravity=g))
    assert isinstance(info.value.__cause__, ZeroDivisionError)


@pytest.mark.parametrize("kw, message", [
    (dict(t_span=(0.0, BIG)), r"^t_span: expected finite start < end, got \(0\.0, a whole number"),
    (dict(t_span="ab"), r"^t_span: expected \(start, end\) in s, got 'ab'"),
    (dict(q0=BIG), r"^q0: expected real numbers, got a whole number of 401 digits$"),
    (dict(qd0="fast"), r"^qd0: expected real numbers, got 'fast'$"),
    (dict(t_eval=[[0.0, 0.5], [0.7, 1.0]]), r"^t_eval: expected output times in s, shape \(N,\)"),
    (dict(rtol=1.0), r"^rtol: expected a positive number below 1 .*got 1\.0$"),
    (dict(rtol=BIG), r"^rtol: expected a positive number below 1 .*got a whole number"),
    (dict(atol=BIG), r"^atol: expected a positive number, got a whole number"),
    (dict(max_step=BIG), r"^max_step: expected a positive number"),
    (dict(threads=10 ** 6), r"^threads: expected a positive whole number up to 1024"),
])
def test_simulate_arguments(kw, message):
    kw = {"t_span": (0.0, 1.0), "q0": 0.3, **kw}
    with pytest.raises(ModelError, match=message):
        simulate(pendulum(), loads=Loads(gravity=g), **kw)


@pytest.fixture
def small_trial(monkeypatch):
    """A trial of 200 evaluations, so that the tests of the estimate stay short."""
    monkeypatch.setattr(_forward, "TRIAL_EVALUATIONS", 200)


@pytest.mark.parametrize("method", ["DOP853", "RK45"])
@pytest.mark.parametrize("t_span, about", [
    ((0.0, 1e6), r"about [\d.]+e\+0[5-9]"), ((0.0, 1e308), "more than 1e308")])
def test_a_span_beyond_the_budget_is_refused_with_its_estimate(small_trial, method, t_span, about):
    with pytest.raises(ModelError, match=(
            r"^t_span: the motion of 'pendulum' from 0 to 1e\+\d+ s would take " + about
            + r" evaluations of the equations of motion \(the first 200 reached t = [\d.e+-]+ s\), "
            r"more than max_evaluations = 5,000; shorten t_span")):
        simulate(pendulum(), t_span, 0.3, loads=Loads(gravity=g), t_eval=list(t_span),
                 method=method, max_evaluations=5_000)


def test_the_default_budget_in_python_refuses_what_would_take_long(small_trial, monkeypatch):
    monkeypatch.setattr(_forward, "MAX_EVALUATIONS_PYTHON", 1_000)
    with pytest.raises(ModelError, match=r"more than max_evaluations = 1,000 \(the default with "
                       r"the right-hand side in Python\)"):
        simulate(pendulum(), (0.0, 100.0), 0.3, loads=Loads(gravity=g), method="RK45")


def test_a_run_beyond_the_trial_but_within_the_budget_is_computed_in_full(small_trial,
                                                                          monkeypatch):
    """The trial is thrown away: the run equals the same run without a trial."""
    kw = dict(loads=Loads(gravity=g), method="RK45", t_eval=[0.0, 1.0, 2.0])
    sim = simulate(pendulum(), (0.0, 2.0), 0.3, **kw)
    assert sim.status == "finished" and sim.nfev > 200
    monkeypatch.setattr(_forward, "TRIAL_EVALUATIONS", 10 ** 6)
    ref = simulate(pendulum(), (0.0, 2.0), 0.3, **kw)
    assert sim.nfev == ref.nfev and np.array_equal(sim.q, ref.q)
