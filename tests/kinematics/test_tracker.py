"""A tracker answers one configuration at a time exactly as analyze does: the same numbers,
the same branches, the same errors; its configurations close their loops."""
import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab import _compiled
from kinelab.errors import AssemblyError, KinelabError, ModelError, SingularityError
from tests.kinematics.checks import closure_residual
from tests.kinematics.test_engine import CATALOGUE

FOURBAR = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5, coupler_point=(1.5, 1.0))


def same_solution(a, b):
    """Every value, rate, K and L of two one-sample solutions agree to rounding."""
    assert a.single and b.single
    for link in a.link_names:
        for get in (a.angle, a.omega, a.alpha, a.K, a.L):
            other = getattr(b, get.__name__)
            assert np.allclose(get(link), other(link), rtol=1e-14, atol=1e-14), (get.__name__, link)
    for point in a.point_names:
        for get in ("position", "velocity", "acceleration", "K", "L"):
            assert np.allclose(getattr(a, get)(point), getattr(b, get)(point), rtol=1e-14,
                               atol=1e-14), (get, point)
    for slide in a.slide_names:
        assert np.allclose(a.slide(slide), b.slide(slide), rtol=1e-14, atol=1e-14)
    assert a.det_J[0] == pytest.approx(b.det_J[0], rel=1e-14)
    assert a.singularity[0] == pytest.approx(b.singularity[0], rel=1e-14)


@pytest.mark.parametrize("m", [kl.mechanisms.fourbar(**FOURBAR),
                               kl.mechanisms.slider_crank(crank=1.0, rod=3.0, offset=0.2),
                               kl.mechanisms.stephenson6(),
                               kl.mechanisms.whitworth(crank=1.0, distance=0.5, lever=1.0, rod=2.0)],
                         ids=["fourbar", "slider-crank", "stephenson6", "whitworth"])
def test_one_configuration_is_analyze_s(m):
    track = kl.kinematics.Tracker(m)
    for q in np.linspace(0.05, 2 * math.pi, 13).tolist():
        sol = track(q, 7.0, -3.0)
        same_solution(sol, kl.analyze(m, q, 7.0, -3.0))
        assert closure_residual(sol) < 1e-12
        xy = track.positions(q)
        assert xy.shape == (len(track.point_names), 2)
        for name, row in zip(track.point_names, xy):
            assert np.array_equal(row, sol.position(name))


def test_numbers_of_any_kind_and_sweeps():
    fb = kl.mechanisms.fourbar(**FOURBAR)
    track = kl.kinematics.Tracker(fb)
    ref = kl.analyze(fb, 0.7, 2.0, 1.0)
    for q, qd, qdd in [(0.7, 2, 1), (np.float64(0.7), 2.0, np.array(1.0)), (np.array(0.7), 2.0, 1.0)]:
        same_solution(track(q, qd, qdd), ref)
    q = np.linspace(0.0, 2 * math.pi, 50)
    sweep = track(q, 2.0)
    assert np.array_equal(sweep.position("P"), kl.analyze(fb, q, 2.0).position("P"))
    xy = track.positions(q)
    assert xy.shape == (50, len(track.point_names), 2)
    assert np.array_equal(xy[:, track.point_names.index("B")], sweep.position("B"))


def test_solutions_do_not_share_memory():
    """Each answer is its own: a later call does not change an earlier one."""
    track = kl.kinematics.Tracker(kl.mechanisms.fourbar(**FOURBAR))
    first, xy = track(0.3), track.positions(0.3)
    kept, kept_xy = first.position("B").copy(), xy.copy()
    track(2.0), track.positions(2.0)
    assert np.array_equal(first.position("B"), kept) and np.array_equal(xy, kept_xy)


@pytest.mark.parametrize("followed", ["smooth", "switch"])
def test_change_points_follow_analyze(followed):
    """A parallelogram: both sides of each change point, on the branch analyze takes."""
    fb = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    track = kl.kinematics.Tracker(fb, at_change_point=followed)
    for q in [0.5, 3.0, 3.3, 6.0, 6.4, 9.5, -0.4, -3.3]:
        same_solution(track(q, 1.0), kl.analyze(fb, q, 1.0, at_change_point=followed))
        assert np.array_equal(track.positions(q),
                              np.array([kl.analyze(fb, q, at_change_point=followed).position(p)
                                        for p in track.point_names]))


def test_unreachable_and_singular_as_analyze():
    rocker = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    track = kl.kinematics.Tracker(rocker)
    with pytest.raises(AssemblyError, match="reachable q is"):
        track(2.0)
    with pytest.raises(AssemblyError, match="reachable q is"):
        track.positions(2.0)
    masked = kl.kinematics.Tracker(rocker, unreachable="mask")
    assert np.isnan(masked.positions(2.0)).all()
    assert not masked(2.0).assembled[0]
    parallelogram = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    with pytest.raises(SingularityError):
        kl.kinematics.Tracker(parallelogram)(math.pi)          # a change point
    flagged = kl.kinematics.Tracker(parallelogram, at_singular="flag")(math.pi, 1.0)
    assert flagged.singular[0] and np.isnan(flagged.velocity("B")).all()
    xy = kl.kinematics.Tracker(parallelogram).positions(math.pi)   # positions exist there
    assert np.allclose(xy, [[0, 0], [-60, 0], [40, 0], [100, 0]], atol=1e-9)


def test_bad_input_is_named():
    track = kl.kinematics.Tracker(kl.mechanisms.fourbar(**FOURBAR))
    for bad in (float("nan"), "x", [[0.1]], True):
        with pytest.raises(ModelError, match="q"):
            track(bad)
        with pytest.raises(ModelError, match="q"):
            track.positions(bad)
    with pytest.raises(ModelError, match="qd"):
        track(0.1, float("inf"))
    with pytest.raises(ModelError, match="at_change_point"):
        kl.kinematics.Tracker(kl.mechanisms.fourbar(**FOURBAR), at_change_point="jump")


def test_two_inputs():
    five = kl.mechanisms.fivebar(3.0, 1.0, 2.5, 2.5, 1.0)
    track = kl.kinematics.Tracker(five)
    q = np.array([1.2, 1.9])
    same_solution(track(q, np.array([1.0, -2.0])), kl.analyze(five, q, np.array([1.0, -2.0])))
    assert closure_residual(track(q)) < 1e-12


def test_newton_groups_go_on_from_the_previous_call():
    """A drag of a triad in small steps stays on the branch it is on, as one sweep does."""
    triad = kl.mechanisms.triad6()
    track = kl.kinematics.Tracker(triad)
    q = np.linspace(float(kl.kinematics.plan(triad).q_sketch[0]), 1.0, 40)
    sweep = kl.analyze(triad, q)
    for i, qi in enumerate(q.tolist()):
        sol = track(qi)
        assert closure_residual(sol) < 1e-10
        for p in sol.point_names:
            assert np.allclose(sol.position(p), sweep.position(p)[i], atol=1e-10)
    assert np.allclose(track.positions(float(q[-1])),
                       [sweep.position(p)[-1] for p in track.point_names], atol=1e-10)


# --------------------------------------------------------------------------------------
# the quick path (one input given as numbers, the compiled one-sample kernel) against
# analyze, to the bit; and the tracker under the kernel's numpy form
# --------------------------------------------------------------------------------------
EXAMPLES = sorted(Path(__file__).parents[2].joinpath("examples").glob("*.toml"))
CASES = {**{name: make for name, make in CATALOGUE.items()},
         "parallelogram": lambda: kl.mechanisms.fourbar(100, 60, 100, 60),
         "non_grashof": lambda: kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5),
         **{path.stem: (lambda path=path: kl.load(path)) for path in EXAMPLES}}
QUICK_Q = [0.05, 0.7, 1.9, 2.0, 3.0, math.pi, -2.5, 6.4, 9.5, 40.0]


def outputs(sol):
    """Every number a solution answers with, by accessor and name (one sample)."""
    out = {"q": sol.q, "qd": sol.qd, "qdd": sol.qdd, "det_J": sol.det_J,
           "singularity": sol.singularity, "singular": sol.singular, "assembled": sol.assembled,
           "N": sol.N, "M": sol.M, "single": sol.single,
           "change_points": [(c.q, c.step) for c in sol.change_points]}
    for link in sol.link_names:
        for get in ("angle", "omega", "alpha", "K", "L"):
            out[get, link] = getattr(sol, get)(link)
    for point in sol.point_names:
        for get in ("position", "velocity", "acceleration", "K", "L"):
            out[get, point] = getattr(sol, get)(point)
    for slide in sol.slide_names:
        for get in ("slide", "slide_velocity", "slide_acceleration", "K", "L"):
            out[get, slide] = getattr(sol, get)(slide)
    return out


def assert_identical(a, b):
    """The same outputs, to the bit, of the same types and shapes (NaN equal to NaN)."""
    oa, ob = outputs(a), outputs(b)
    assert oa.keys() == ob.keys()
    for key, x in oa.items():
        y = ob[key]
        assert type(x) is type(y), key
        if isinstance(x, (np.ndarray, np.floating)):
            assert np.shape(x) == np.shape(y) and np.asarray(x).dtype == np.asarray(y).dtype, key
            assert np.array_equal(x, y, equal_nan=True), (key, x, y)
        else:
            assert x == y, key


def answer_or_error(call):
    try:
        return call(), None
    except KinelabError as e:
        return None, (type(e), str(e))


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("options", [{}, {"at_singular": "flag", "unreachable": "mask"}],
                         ids=["raise", "flag"])
def test_tracker_is_analyze_to_the_bit(name, options):
    """At every input value (reachable or not, singular or not) the tracker answers with
    analyze's numbers, flags and errors, to the bit, and its positions are the solution's."""
    m = CASES[name]()
    track = kl.kinematics.Tracker(m, **options)
    M = len(m.inputs)
    newton = kl.kinematics.plan(m).groups is not None
    for q in QUICK_Q:
        qs = q if M == 1 else np.array([q, 0.5 * q + 1.0])
        qd, qdd = (7.0, -3.0) if M == 1 else (np.array([7.0, 1.0]), np.array([-3.0, 2.0]))
        mine, my_error = answer_or_error(lambda: track(qs, qd, qdd))
        theirs, error = answer_or_error(lambda: kl.analyze(m, qs, qd, qdd, **options))
        assert my_error == error, (name, q)
        if mine is not None:
            assert_identical(mine, theirs)
            if M == 1 and theirs.assembled[0]:
                xy = track.positions(qs)
                for row, point in zip(xy, track.point_names):
                    if newton:     # on from the call just made: the same point to rounding
                        assert np.allclose(row, theirs.position(point), rtol=0, atol=1e-9)
                    else:
                        assert np.array_equal(row, theirs.position(point)), (name, q, point)
        if newton:
            track = kl.kinematics.Tracker(m, **options)    # Newton groups go on from a call


@pytest.mark.parametrize("q", [float("nan"), float("inf"), -float("inf"), 1e300, np.float64("nan")])
def test_bad_numbers_named_as_analyze_names_them(q):
    fb = kl.mechanisms.fourbar(**FOURBAR)
    track = kl.kinematics.Tracker(fb)
    for args in [(q, 1.0, 0.0), (0.5, q, 0.0), (0.5, 1.0, q)]:
        with pytest.raises(ModelError) as mine:
            track(*args)
        with pytest.raises(ModelError) as theirs:
            kl.analyze(fb, *args)
        assert str(mine.value) == str(theirs.value)
    with pytest.raises(ModelError) as mine:
        track.positions(q)
    with pytest.raises(ModelError) as theirs:
        kl.analyze(fb, q)
    assert str(mine.value) == str(theirs.value)


@pytest.fixture
def compiled_mode():
    """The compiled kernel, whatever KINELAB_KERNEL says (the quick path is its own)."""
    before = _compiled.mode()
    _compiled.set_mode("compiled")
    yield
    _compiled.set_mode(before)


def test_numpy_numbers_take_the_quick_path(compiled_mode):
    fb = kl.mechanisms.fourbar(**FOURBAR)
    track = kl.kinematics.Tracker(fb)
    sol = track(np.float64(0.7), np.float64(2.0), 1.0)
    assert type(sol).__name__ == "_OneConfiguration"
    assert_identical(sol, kl.analyze(fb, 0.7, 2.0, 1.0))


def test_answers_of_the_quick_path_behave_as_analyze_s():
    """A tracker's answer is a KinematicSolution like any other: export, concatenation, a
    certificate."""
    fb = kl.mechanisms.fourbar(**FOURBAR)
    track = kl.kinematics.Tracker(fb)
    sol, ref = track(0.7, 2.0, 1.0), kl.analyze(fb, 0.7, 2.0, 1.0)
    assert isinstance(sol, kl.kinematics.KinematicSolution)
    assert repr(sol) == repr(ref)
    for key, column in ref.columns().items():
        assert np.array_equal(sol.columns()[key], column, equal_nan=True), key
    both = kl.kinematics.KinematicSolution.concatenate([sol, track(0.8, 2.0, 1.0)])
    assert np.array_equal(both.angle("rocker"), kl.analyze(fb, [0.7, 0.8], 2.0, 1.0).angle("rocker"))
    assert kl.verify.certify(sol).passed
    replaced = dataclasses.replace(sol, certificate=None)
    assert_identical(replaced, ref)


def test_tracker_on_the_numpy_form(monkeypatch):
    """While the compiled kernel is not ready (or with KINELAB_KERNEL=numpy) a tracker
    answers through analyze on the kernel's numpy form: its numbers, to the bit, and the
    compiled ones to rounding."""
    cases = {name: CASES[name] for name in ("fourbar", "stephenson6", "slider_crank",
                                            "parallelogram", "jansen", "fivebar")}
    compiled = {name: kl.kinematics.Tracker(make())(0.7 if name != "fivebar" else
                                                    np.array([0.7, 1.4]), 2.0 if name != "fivebar"
                                                    else np.array([2.0, 1.0]))
                for name, make in cases.items()}
    monkeypatch.setattr(_compiled, "ready", lambda entry: False)
    for name, make in cases.items():
        m = make()
        q, qd = (0.7, 2.0) if name != "fivebar" else (np.array([0.7, 1.4]), np.array([2.0, 1.0]))
        sol = kl.kinematics.Tracker(m)(q, qd)
        assert type(sol) is kl.kinematics.KinematicSolution
        assert_identical(sol, kl.analyze(m, q, qd))
        for key, value in outputs(sol).items():
            if isinstance(value, np.ndarray) and value.dtype == float:
                assert np.allclose(value, outputs(compiled[name])[key], rtol=1e-12,
                                   atol=1e-12 * kl.kinematics.plan(m).scale), (name, key)


@pytest.mark.parametrize("name", [n for n, make in CASES.items() if len(make().inputs) == 1])
@pytest.mark.parametrize("options", [{}, {"at_singular": "flag", "unreachable": "mask"}],
                         ids=["raise", "flag"])
def test_small_sweeps_in_one_call_are_the_general_path_to_the_bit(name, options):
    """analyze runs a small sweep of one input given as a float array in one call of the
    kernel (checks, outputs and counts included): its numbers, flags and errors are those
    of the same inputs given as a list, which take the general path (the mechanisms of
    one input: a sweep of several inputs is a table of them, taken by another path)."""
    m = CASES[name]()
    q = np.array(QUICK_Q + [-7.0, 12.5, 1e3])
    mine, my_error = answer_or_error(lambda: kl.analyze(m, q, 7.0, -3.0, **options))
    theirs, error = answer_or_error(lambda: kl.analyze(m, q.tolist(), 7.0, -3.0, **options))
    assert my_error == error
    if mine is not None:
        assert_identical(mine, theirs)
        for name_ in ("jets", "rates"):
            assert np.array_equal(getattr(mine, name_), getattr(theirs, name_), equal_nan=True)


def test_driven_angles_compiled_are_wrap_angle_to_the_bit(compiled_mode):
    """The angle of a link turned by an input, compiled (solution accessors), is
    solvers.wrap_angle of the input, to the bit, within a turn and far beyond."""
    from kinelab.kinematics import _kernel
    from kinelab.solvers._angles import wrapped_angles

    assert _compiled.ready("driven_angles")
    rng = np.random.default_rng(3)
    edges = [math.pi, -math.pi, 3 * math.pi, -3 * math.pi, 2 * math.pi, -2 * math.pi, 4 * math.pi,
             -4 * math.pi, 0.0, -0.0, 1e-300, np.nextafter(math.pi, 4.0), np.nextafter(-math.pi, 0.0),
             np.nextafter(-math.pi, -4.0), np.nextafter(3 * math.pi, 0.0), 1e17, float("nan")]
    for a in (rng.uniform(-5 * math.pi, 5 * math.pi, 100_000), rng.uniform(-1e7, 1e7, 10_000),
              np.array(edges)):
        q = np.ascontiguousarray(np.stack([a, a[::-1]], axis=1))
        for m in (0, 1):
            for sign in (1.0, -1.0):
                got = _kernel.driven_angles(q, m, sign, np.empty(len(a)))
                want = wrapped_angles(q[:, m] * sign)
                assert np.array_equal(got.view(np.int64)[~np.isnan(want)],
                                      want.view(np.int64)[~np.isnan(want)])
                assert np.array_equal(np.isnan(got), np.isnan(want))


@pytest.mark.parametrize("name", ["fourbar", "stephenson6", "slider_crank", "non_grashof"])
def test_sweeps_of_thousands_in_one_call_are_the_general_path_to_the_bit(name):
    """Up to the size where a sweep takes threads, in result memory of the pool (1 MiB and
    over): the same numbers as the general path's."""
    m = CASES[name]()
    q = np.linspace(-7.0, 7.0, 5000)
    mine = kl.analyze(m, q, 7.0, -3.0, unreachable="mask", at_singular="flag")
    theirs = kl.analyze(m, q.tolist(), 7.0, -3.0, unreachable="mask", at_singular="flag")
    assert mine.stored_jets.nbytes + mine.stored_rates.nbytes >= 1 << 20 or name != "stephenson6"
    for field in ("q", "stored_jets", "stored_rates", "det_J", "singularity", "singular",
                  "assembled"):
        assert np.array_equal(getattr(mine, field), getattr(theirs, field), equal_nan=True), field
    for link in mine.link_names:
        assert np.array_equal(mine.angle(link), theirs.angle(link), equal_nan=True)
        assert np.array_equal(mine.alpha(link), theirs.alpha(link), equal_nan=True)


_NUMPY_FORM = """
import json, sys
import numpy as np
import kinelab as kl
from kinelab import _compiled
assert _compiled.mode() == "numpy"
out = {}
for path in sys.argv[1:]:
    m = kl.mechanisms.stephenson6() if path == "stephenson6" else kl.load(path)
    track = kl.kinematics.Tracker(m)
    rows = []
    for q in (0.3, 1.1, 2.5):
        q = float(q) if len(m.inputs) == 1 else np.array([q, q + 1.0])
        a, b = track(q, 2.0, 0.5), kl.analyze(m, q, 2.0, 0.5)
        same = all(np.array_equal(getattr(a, g)(n), getattr(b, g)(n), equal_nan=True)
                   for n in a.point_names for g in ("position", "velocity", "acceleration", "K", "L"))
        rows.append([same, [np.asarray(a.acceleration(n)).tolist() for n in a.point_names]])
    out[path] = rows
print(json.dumps(out))
"""


def test_tracker_with_the_kernel_set_to_numpy():
    """KINELAB_KERNEL=numpy: a tracker answers as analyze does there, to the bit, and as the
    compiled kernel does, to rounding."""
    import json
    import os
    import subprocess
    import sys

    names = ["stephenson6"] + [str(p) for p in EXAMPLES if p.stem in ("crank_rocker", "jansen",
                                                                       "fivebar", "slotted_link")]
    done = subprocess.run([sys.executable, "-c", _NUMPY_FORM, *names], capture_output=True,
                          text=True, env={**os.environ, "KINELAB_KERNEL": "numpy"}, timeout=600)
    assert done.returncode == 0, done.stderr
    got = json.loads(done.stdout.strip().splitlines()[-1])
    for name in names:
        m = kl.mechanisms.stephenson6() if name == "stephenson6" else kl.load(name)
        track = kl.kinematics.Tracker(m)
        scale = kl.kinematics.plan(m).scale
        for q, (same, accelerations) in zip((0.3, 1.1, 2.5), got[name]):
            assert same, (name, q)
            q = float(q) if len(m.inputs) == 1 else np.array([q, q + 1.0])
            sol = track(q, 2.0, 0.5)
            for point, a in zip(sol.point_names, accelerations):
                assert np.allclose(a, sol.acceleration(point), rtol=1e-9, atol=1e-9 * scale), \
                    (name, q, point)
