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


@pytest.mark.parametrize("method", ["DOP853", "RK45"])      # compiled, and in Python
@pytest.mark.parametrize("t_span, about", [
    ((0.0, 1e6), r"about [\d.]+e\+0[6-9]"), ((0.0, 1e308), "more than 1e308")])
def test_a_span_beyond_the_budget_is_refused_with_its_estimate(method, t_span, about):
    """At 2000 evaluations the run has gone a few tens of seconds of the span: at that pace
    the whole span takes far more than the budget, and it stops there."""
    with pytest.raises(ModelError, match=(
            r"^t_span: the motion of 'pendulum' from 0 to 1e\+\d+ s would take " + about
            + r" evaluations of the equations of motion \(the first [\d,]+ reached t = [\d.e+-]+ "
            r"s\), more than max_evaluations = 5,000; shorten t_span")):
        simulate(pendulum(), t_span, 0.3, loads=Loads(gravity=g), t_eval=list(t_span),
                 method=method, max_evaluations=5_000)


def test_the_default_budget_in_python_refuses_what_would_take_long(monkeypatch):
    monkeypatch.setattr(_forward, "MAX_EVALUATIONS_PYTHON", 3_000)
    with pytest.raises(ModelError, match=r"more than max_evaluations = 3,000 \(the default with "
                       r"the right-hand side in Python\)"):
        simulate(pendulum(), (0.0, 1e4), 0.3, loads=Loads(gravity=g), method="RK45")


@pytest.mark.parametrize("method", ["DOP853", "RK45"])
def test_a_run_at_a_pace_within_its_budget_goes_on_unchanged(method):
    """The pace is checked, nothing is redone: a run past 2000 evaluations whose budget
    suffices equals the same run with an ample budget, and one short of its budget stops
    with the budget's own message (its first 2000 evaluations reach 7.3 s of the 40, so
    that the pace alone would need 11,000 evaluations: more than the run takes, less than
    ten times its budget)."""
    kw = dict(loads=Loads(gravity=g), method=method, t_eval=[0.0, 20.0, 40.0])
    ref = simulate(pendulum(), (0.0, 40.0), 0.3, **kw)
    assert ref.status == "finished" and ref.nfev > 2_000
    sim = simulate(pendulum(), (0.0, 40.0), 0.3, max_evaluations=2 * ref.nfev, **kw)
    assert sim.nfev == ref.nfev and np.array_equal(sim.q, ref.q)
    with pytest.raises(ModelError, match=r"max_evaluations") as info:
        simulate(pendulum(), (0.0, 40.0), 0.3, max_evaluations=ref.nfev // 2, **kw)
    assert "would take" not in str(info.value)        # ran out of budget; not refused early
