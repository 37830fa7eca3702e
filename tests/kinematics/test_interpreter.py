"""The numpy evaluator of solution plans (``_interpreter.run``) against the compiled kernel
(``_evaluate.run_compiled``), output by output.

Both run the same plan with the same formulas; they differ in rounding only: the kernel
contracts ``a * b + c`` into fused multiply-adds, numpy does not, and the two libraries'
sin, cos and atan2 may differ in the last bit.  Near a singular configuration of measure s
(the sine that ``KinematicSolution.singularity`` reports) rounding of relative size eps
reaches a position with a factor of about 1/s, K with 1/s**2 and L with 1/s**3 (see
``SINGULAR_TOL`` in ``_analyze``); at an exact limit position the position is the square
root of a rounding.  So every output is compared to ``1e-12`` of its unit (1 rad, or the
mechanism's size in m) times that factor, with 1/s at least 1 and at most 1/sqrt(eps); K
and L also to 1e-12 of their own size times 1/s**2.  The Jacobian of a Newton group mixes
metres and radians, and K and L are solved with its factorisation at the iterate before the
last: in Newton plans they carry the mechanism's size (and its square) as a further factor.

Newton plans follow the samples by continuation.  Where a sweep reaches a limit position,
Newton's steps there are rounding divided by a vanishing det J, so where continuation
stops, and the branch it takes if the sweep comes back, are decided by rounding: those
sweeps are compared up to their first failing sample, and their end state to the accuracy
of a limit position.
"""
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl
from kinelab.kinematics import _evaluate, _interpreter
from kinelab.kinematics import _codes as k
from kinelab.kinematics._analyze import SINGULAR_TOL, _branch_map, plan
from tests.kinematics.test_engine import CATALOGUE
from tests.kinematics.checks import wrap
from tests.kinematics.test_engine import _hydraulic_boom, _with_input

REL = 1e-12                          # rounding, relative to an output's unit
SQRT_EPS = math.sqrt(np.finfo(float).eps)
EXAMPLES = sorted(Path(__file__).parents[2].joinpath("examples").glob("*.toml"))
TWO_TURNS = np.radians(np.arange(0.0, 721.0, 1.0))
WATT6_SHORT = {"O2-A": 3.0, "C-D": 1.0, "O6-D": 2.0}     # both of its dyads fail somewhere


def prp_yoke():
    """A crank whose line meets a level line (a PRP dyad: two slider blocks pinned together);
    the two lines are exactly parallel at q = 0."""
    return kl.model.Mechanism.from_dict({
        "name": "yoke", "points": {"O2": [0, 0], "O3": [0, 1], "A": [0.5, 0.5], "P": [1, 1]},
        "links": [{"name": "ground", "points": ["O2", "O3"], "ground": True},
                  {"name": "crank", "points": ["O2", "A"]},
                  {"name": "s1", "points": ["P"]}, {"name": "s2", "points": ["P"]}],
        "joints": [{"name": "jO2", "type": "R", "links": ["ground", "crank"], "point": "O2"},
                   {"name": "along", "type": "P", "links": ["crank", "s1"], "point": "P", "axis": [1, 1]},
                   {"name": "level", "type": "P", "links": ["ground", "s2"], "point": "P",
                    "axis": [1, 0], "origin": "O3"},
                   {"name": "jP", "type": "R", "links": ["s1", "s2"], "point": "P"}],
        "inputs": [{"joint": "jO2"}]})


def double_parallelogram():
    return kl.load(Path(__file__).with_name("double_parallelogram.toml"))


def piston_driven():
    return _with_input(kl.mechanisms.slider_crank(1.0, 3.0, 0.2), kl.model.Input(joint="slide"))


def relative_angle_driven():
    return _with_input(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), kl.model.Input(joint="jB"))


def coupler_angle_driven():
    return _with_input(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), kl.model.Input(links=("ground", "coupler")))


# mechanisms, and the sweeps they turn through (None: inside their reach, from the sketch)
TURNING = {
    **CATALOGUE,
    "inverted_negative": lambda: kl.mechanisms.inverted_slider_crank(2.0, 1.0, offset=0.3, branch="negative"),
    "watt6_crossed": lambda: kl.mechanisms.watt6(lengths={}, branch=("crossed", "crossed")),
    "stephenson6_mixed": lambda: kl.mechanisms.stephenson6(lengths={}, branch=("open", "crossed")),
    **{f"example_{p.stem}": (lambda p=p: kl.load(p)) for p in EXAMPLES
       if p.stem not in ("fivebar", "planetary")},
}
# gear and cam joints are solved in closed form only: these have no Newton plan (method "newton")
GEARED = {f"example_{p.stem}" for p in EXAMPLES
          if 'type = "G"' in p.read_text() or 'type = "C"' in p.read_text()}
INSIDE = {"prp_yoke": prp_yoke, "piston": piston_driven, "relative_angle": relative_angle_driven,
          "coupler_angle": coupler_angle_driven, "boom": _hydraulic_boom}
FIVEBAR_Q = np.stack(np.meshgrid(np.linspace(1.2, 2.0, 12), np.linspace(1.3, 1.9, 10)), -1).reshape(-1, 2)
TWO_INPUTS = {"fivebar_up": lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0),
              "fivebar_down": lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0, branch="down"),
              "example_fivebar": lambda: kl.load(EXAMPLES[[p.stem for p in EXAMPLES].index("fivebar")]),
              "example_planetary": lambda: kl.load(EXAMPLES[[p.stem for p in EXAMPLES].index("planetary")])}


def inside(m, samples=181):
    """A sweep over the interval of the mechanism's reach that holds its sketch, away from
    its ends."""
    q0 = plan(m).q_sketch[0]
    lo, hi = next(r for r in kl.kinematics.reachable_ranges(m) if r[0] <= q0 <= r[1])
    return lo + (hi - lo) * np.linspace(0.02, 0.98, samples)


# --------------------------------------------------------------------------------------
# the comparison
# --------------------------------------------------------------------------------------
def both(p, q, qd=None, qdd=None, **kw):
    """Both evaluators on the same arguments (rates: one random row unless given)."""
    q = np.ascontiguousarray(np.reshape(np.asarray(q, float), (len(q), -1)))
    M = q.shape[1]
    rng = np.random.default_rng(len(q))
    qd = rng.normal(size=(1, M)) if qd is None else qd
    qdd = rng.normal(size=(1, M)) if qdd is None else qdd
    return (_evaluate.run_compiled(p, q, qd, qdd, **kw), _interpreter.run(p, q, qd, qdd, **kw), q, qd, qdd)


def units(p, stored):
    """Unit of each stored item (1 rad, or the mechanism's size in m) and of each input."""
    item = np.where(stored < p.n_angles, 1.0, p.scale)
    inp = np.array([1.0 if kind == "angle" else p.scale for kind in p.input_kinds])
    return item, inp


def conditioning(measure):
    """1/s, at least 1 and at most 1/sqrt(eps) (see the module docstring)."""
    return 1.0 / np.clip(measure, SQRT_EPS, 1.0)


def assert_same(p, a, b, q, qd, qdd, stored=None, upto=None, ops_f=None):
    """Every output of the kernel (a) and of numpy (b), to rounding amplified by the
    conditioning; ``upto``: compare only the samples before it."""
    stored = p.stored_items if stored is None else stored
    ops_f = p.ops_f if ops_f is None else ops_f
    n = len(q) if upto is None else upto
    sa, sb = a["status"][:n], b["status"][:n]
    np.testing.assert_array_equal(sb, sa)
    ok = sa == k.ST_OK
    c = conditioning(a["diag"][:n, 1])[ok]
    # K and L are compared where both are finite; not finite (a folded dyad, an exact
    # singularity) in both alike, but where a singular sample's rounding decides
    fa, fb = np.isfinite(a["jets"][:n][ok]), np.isfinite(b["jets"][:n][ok])
    flagged = a["diag"][:n, 1][ok] < SINGULAR_TOL
    assert np.array_equal(fa[~flagged], fb[~flagged])
    finite = fa.all((1, 2)) & fb.all((1, 2))
    iu, inp = units(p, stored)
    M = q.shape[1]
    ja, jb = a["jets"][:n][ok], b["jets"][:n][ok]
    # values: angles compared across their wrap at +-pi
    angle = stored < p.n_angles
    dv = np.abs(ja[..., 0] - jb[..., 0])
    dv[:, angle] = np.abs(wrap(ja[:, angle, 0] - jb[:, angle, 0]))
    assert np.all(dv <= REL * iu * c[:, None]), f"values differ by {np.max(dv / (iu * c[:, None])):.2e}"
    # Near a limit position rounding reaches them
    # relative to their own size, by about 1/s**2.  The Jacobian of a Newton group mixes
    # metres and radians, its condition about the mechanism's size: K and L of Newton plans
    # carry that factor (and its square), with the last Newton step in their Jacobian
    newton = max(1.0, p.scale) if p.groups is not None else 1.0
    uK = iu[:, None] / inp[None, :] * newton
    uL = iu[:, None, None] / (inp[None, :, None] * inp[None, None, :]) * newton ** 2
    rows = np.flatnonzero(ok)[finite]
    ja_u, jb_u = a["jets"][rows], b["jets"][rows]
    Ka, Kb = ja_u[..., 1:1 + M], jb_u[..., 1:1 + M]
    La = ja_u[..., 1 + M:].reshape(len(rows), len(stored), M, M)
    Lb = jb_u[..., 1 + M:].reshape(len(rows), len(stored), M, M)
    cu = c[finite]
    tK = REL * (uK * cu[:, None, None] ** 2 + np.abs(Ka) * cu[:, None, None] ** 2)
    tL = REL * (uL * cu[:, None, None, None] ** 3 + np.abs(La) * cu[:, None, None, None] ** 2)
    assert np.all(np.abs(Ka - Kb) <= tK), f"K differs by {np.max(np.abs(Ka - Kb) / tK):.2e} x tol"
    assert np.all(np.abs(La - Lb) <= tL), f"L differs by {np.max(np.abs(La - Lb) / tL):.2e} x tol"
    # rates: S' = K q', S'' = K q'' + q'^T L q', with the tolerances of K and L
    wd = np.abs(qd[rows] if len(qd) > 1 else qd[:1])[:, None, :]
    wdd = np.abs(qdd[rows] if len(qdd) > 1 else qdd[:1])[:, None, :]
    tv = np.sum(tK * wd, -1)
    ta = np.sum(tK * wdd, -1) + np.sum(tL * wd[..., :, None] * wd[..., None, :], (-2, -1))
    ra, rb = a["rates"][rows], b["rates"][rows]
    assert np.all(np.abs(ra[..., 0] - rb[..., 0]) <= tv + REL * np.abs(ra[..., 0]))
    assert np.all(np.abs(ra[..., 1] - rb[..., 1]) <= ta + REL * np.abs(ra[..., 1]))
    # det J and the singularity measure (of a Newton group: of its Jacobian at the iterate
    # before the last, which differs from the solution by up to 1e-13 of the size)
    det_a, det_b = a["diag"][:n][ok, 0], b["diag"][:n][ok, 0]
    size = np.max(np.abs(det_a), initial=0.0)
    assert np.all(np.abs(det_a - det_b) <= REL * newton * size * c)
    assert np.all(np.abs(a["diag"][:n][ok, 1] - b["diag"][:n][ok, 1]) <= REL * newton * c)
    # where a sample fails: the operation, and by how much (m) it misses
    bad = ~ok
    np.testing.assert_array_equal(b["fail"][:n][bad, 1], a["fail"][:n][bad, 1])
    np.testing.assert_array_equal(b["diag"][:n][bad], 0.0)
    gap_a, gap_b = a["fail"][:n][bad, 0], b["fail"][:n][bad, 0]
    assert np.all(np.abs(gap_a - gap_b) <= REL * p.scale)      # the failed group's gap


def assert_same_state(p, a, b, at_limit=False):
    """The continuation's end state: to rounding where the run ended on an assembled
    sample; at a limit position, where continuation stopped is decided by rounding of
    Newton's steps (about 1e-9 rad here), and the state is its square root."""
    (qa, xa), (qb, xb) = a["state"], b["state"]
    if not at_limit:
        c = conditioning(a["diag"][-1, 1])
        np.testing.assert_allclose(qb, qa, rtol=0, atol=REL * c)
        np.testing.assert_allclose(xb, xa, rtol=0, atol=REL * p.scale * c)
    else:
        np.testing.assert_allclose(qb, qa, rtol=0, atol=1e-7)
        np.testing.assert_allclose(xb, xa, rtol=0, atol=math.sqrt(1e-7) * p.scale)


def check(m, q, method="auto", qd=None, qdd=None, **kw):
    p = plan(m, method=method)
    a, b, q2, qd2, qdd2 = both(p, q, qd, qdd, **kw)
    assert_same(p, a, b, q2, qd2, qdd2, stored=kw.get("stored"))
    if p.groups is not None:
        assert_same_state(p, a, b)
    return p, a, b


# --------------------------------------------------------------------------------------
# every plan
# --------------------------------------------------------------------------------------
@pytest.mark.parametrize("name, method", [(n, m) for m in ("auto", "newton") for n in TURNING
                                          if m == "auto" or n not in GEARED])
def test_turning_mechanisms(name, method):
    check(TURNING[name](), TWO_TURNS if method == "auto" else TWO_TURNS[::3], method)


@pytest.mark.parametrize("method", ["auto", "newton"])
@pytest.mark.parametrize("name", list(INSIDE))
def test_other_inputs_and_groups(name, method):
    m = INSIDE[name]()
    check(m, inside(m) if name != "prp_yoke" else np.linspace(0.1, 3.0, 181), method)


@pytest.mark.parametrize("name, method", [(n, m) for m in ("auto", "newton") for n in TWO_INPUTS
                                          if m == "auto" or n not in GEARED])
def test_two_inputs_with_rates_per_sample(name, method):
    rng = np.random.default_rng(3)
    qd, qdd = rng.normal(size=FIVEBAR_Q.shape), rng.normal(size=FIVEBAR_Q.shape)
    check(TWO_INPUTS[name](), FIVEBAR_Q, method, qd, qdd)
    check(TWO_INPUTS[name](), FIVEBAR_Q, method)          # one row of rates for all


def test_rates_per_sample_with_one_input():
    rng = np.random.default_rng(4)
    qd, qdd = rng.normal(size=(len(TWO_TURNS), 1)), rng.normal(size=(len(TWO_TURNS), 1))
    for m in (TURNING["fourbar"](), TURNING["whitworth"]()):
        check(m, TWO_TURNS, qd=qd, qdd=qdd)
    check(TURNING["triad6"](), TWO_TURNS[:200], qd=qd[:200], qdd=qdd[:200])


def test_every_operation_and_constraint_kind_is_compared():
    """The mechanisms above exercise every operation of the kernel and every kind of
    Newton-group equation."""
    ops, kinds = set(), set()
    for make in (*TURNING.values(), *INSIDE.values(), *TWO_INPUTS.values(), double_parallelogram):
        m = make()
        geared = any(j.type in ("G", "C") for j in m.joints)
        for method in ("auto", "newton") if make is not double_parallelogram and not geared else ("auto",):
            p = plan(m, method=method)
            ops |= set(p.ops_i[:, 0].tolist())
            if p.groups is not None:
                kinds |= set(p.groups[1][:, 0].tolist())
    assert ops == {v for name, v in vars(k).items() if name.startswith("OP_")}
    assert kinds == {v for name, v in vars(k).items() if name.startswith("C_")}


def test_nothing_stored():
    nothing = np.empty(0, np.int64)
    for m, q in ((TURNING["watt6"](), TWO_TURNS), (kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5), TWO_TURNS),
                 (TURNING["triad6"](), TWO_TURNS[:300])):
        p, a, b = check(m, q, stored=nothing)
        assert b["jets"].shape == (len(q), 0, 3) and b["rates"].shape == (len(q), 0, 2)


def test_many_samples_in_chunks():
    """More samples than the evaluator takes at a time, in random order."""
    rng = np.random.default_rng(5)
    q = rng.uniform(-10.0, 10.0, 3 * _interpreter._CHUNK + 17)
    check(TURNING["stephenson6"](), q, qd=rng.normal(size=(len(q), 1)), qdd=rng.normal(size=(len(q), 1)))
    check(kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5), q)


# --------------------------------------------------------------------------------------
# change points, singular samples, unreachable samples
# --------------------------------------------------------------------------------------
CHANGE_POINTS = {
    "parallelogram": lambda: kl.mechanisms.fourbar(100, 60, 100, 60),
    "antiparallelogram": lambda: kl.mechanisms.fourbar(100, 60, 100, 60, branch="crossed"),
    "fourbar_4_2_3_5": lambda: kl.mechanisms.fourbar(4, 2, 3, 5),
    "kite": lambda: kl.mechanisms.fourbar(1, 1, 2, 2),
    "slider_crank_1_1": lambda: kl.mechanisms.slider_crank(1, 1),
    "slotted_link_1_1": lambda: kl.mechanisms.slotted_link(1, 1),
    # a binary link placed through two hinges (its second hinge a redundant joint): well
    # conditioned on the branch where that joint holds, which the change points keep
    "double_parallelogram": double_parallelogram,
}


@pytest.mark.parametrize("name", list(CHANGE_POINTS))
def test_change_points_on_each_branch(name):
    """Each sample with the plan parameters of its branch, as ``_run_branches`` runs them,
    over two turns that pass the change points exactly (every degree)."""
    m = CHANGE_POINTS[name]()
    p = plan(m)
    bmap = _branch_map(p, 1, "smooth")
    assert bmap is not None
    q = np.radians(np.arange(-360.0, 721.0, 0.5))
    index, tables = bmap.variants(q)
    assert len(np.unique(index)) >= 2
    singular = 0
    for v in np.unique(index):
        rows = index == v
        a, b, q2, qd, qdd = both(p, q[rows], ops_f=tables[v])
        assert_same(p, a, b, q2, qd, qdd)
        singular += int(np.sum(a["diag"][:, 1] < SINGULAR_TOL))
    assert singular > 0              # samples at (or next to) change points were compared


def rows_of(out, rows):
    """The per-sample outputs of an evaluator at ``rows`` only."""
    return {key: a[rows] for key, a in out.items() if key != "state"}


@pytest.mark.parametrize("lengths, branch", [
    ((100, 60, 100, 60), "open"), ((100, 60, 100, 60), "crossed"), ((2, 1, 2, 1), "open"),
    ((2, 1, 2, 1), "crossed"), ((4.0, 2.0, 3.0, 5.0), "open"), ((1, 1, 2, 2), "open")])
def test_newton_through_change_points(lengths, branch):
    """Continuation through change points: a sample exactly at one, where Newton's method
    cannot converge, is placed from both sides (the kernel's _place_between writes det J = 0
    there) or, where rounding decides that the two sides do not meet, reported unconverged;
    either way the sweep goes on beyond it on its branch, and both forms agree on every
    other sample.  Which of the two happens at the change point itself is rounding: not
    asserted."""
    m = kl.mechanisms.fourbar(*lengths, branch=branch)
    p = plan(m, method="newton")
    at = np.array([c.q for c in kl.kinematics.change_points(m, 0.0, 4 * math.pi)])
    at_change_point = np.any(np.abs(TWO_TURNS[:, None] - at[None, :]) < 1e-9, axis=1)
    a, b, q, qd, qdd = both(p, TWO_TURNS)
    for out in (a, b):
        assert np.all(out["status"][~at_change_point] == k.ST_OK)
        assert set(out["status"][at_change_point].tolist()) <= {k.ST_OK, k.ST_NO_CONVERGENCE}
        placed = (out["status"] == k.ST_OK) & (out["diag"][:, 1] == 0.0)
        assert not np.any(placed & ~at_change_point)
    away = ~at_change_point
    assert_same(p, rows_of(a, away), rows_of(b, away), q[away], qd, qdd)


@pytest.mark.parametrize("make, q", [
    (lambda: kl.mechanisms.fourbar(100, 60, 100, 60), [0.0, math.pi, 2 * math.pi, 1.0]),
    (lambda: kl.mechanisms.slider_crank(1, 1), [math.pi / 2, -math.pi / 2, 0.3]),
    (lambda: kl.mechanisms.slotted_link(1, 1), [math.pi, -math.pi, 3 * math.pi, 0.2]),
    (lambda: kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5), [math.acos(-0.3125), -math.acos(-0.3125), 0.0]),
    (lambda: kl.mechanisms.slider_crank(3, 1), [math.asin(1 / 3), math.pi - math.asin(1 / 3), 0.1]),
], ids=["change-points", "rod-across-slide", "pin-through-pivot", "fourbar-limits", "slider-limits"])
def test_samples_at_singular_configurations(make, q):
    """Samples exactly at singular configurations, on the sketch's branch: a straight dyad,
    a folded one, a limit position."""
    p, a, b = check(make(), np.array(q))
    assert np.any(a["diag"][:, 1] < 1e-7)


def test_kite_folds_where_its_crank_pin_reaches_the_rocker_pivot():
    """kite (1, 1, 2, 2): A reaches O4 at q = 0; the dyad folds (the kernel's _rrr_folded)."""
    m = kl.mechanisms.fourbar(1, 1, 2, 2)
    p, a, b = check(m, np.array([0.0, 2 * math.pi, 0.5]))
    assert a["status"][0] == k.ST_OK and a["diag"][0, 1] == 0.0
    assert np.isnan(b["jets"][0, :, 1]).any()           # K undefined there, in both


@pytest.mark.parametrize("make", [lambda: kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5),
                                  lambda: kl.mechanisms.slider_crank(3, 1),
                                  lambda: kl.mechanisms.inverted_slider_crank(2.0, 1.0, offset=1.5),
                                  lambda: kl.mechanisms.watt6(lengths={"O2-A": 3.0}),
                                  lambda: kl.mechanisms.watt6(lengths=WATT6_SHORT),
                                  lambda: kl.mechanisms.fourbar(2.0, 1.5, 1.0, 3.0)],
                         ids=["non-grashof", "crank-outreaches-rod", "offset-beyond-pin", "watt6-first-dyad",
                              "watt6-second-dyad", "triple-rocker"])
def test_sweeps_that_leave_the_reach(make):
    """Closed forms: every sample on its own; the failed group and its gap (m)."""
    p, a, b = check(make(), TWO_TURNS)
    assert np.any(a["status"] == k.ST_NO_ASSEMBLY) and np.any(a["status"] == k.ST_OK)


@pytest.mark.parametrize("make, direction", [(lambda: kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5), 1.0),
                                             (lambda: kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5), -1.0),
                                             (lambda: kl.mechanisms.watt6(lengths={"O2-A": 3.0}), 1.0),
                                             (_hydraulic_boom, -1.0), (relative_angle_driven, 1.0)],
                         ids=["non-grashof-up", "non-grashof-down", "watt6", "boom", "relative-angle"])
def test_newton_sweeps_that_leave_the_reach(make, direction):
    """Continuation from the sketch out of the reach: to the first failing sample (the
    samples after it start from a limit position, see the module docstring)."""
    m = make()
    p = plan(m, method="newton")
    q0 = float(p.q_sketch[0])
    q = q0 + direction * np.linspace(0.0, 4.0 * (math.pi if p.input_kinds[0] == "angle" else p.scale), 401)
    status = _evaluate.run_compiled(p, q[:, None], np.zeros((1, 1)), np.zeros((1, 1)))["status"]
    first = int(np.argmax(status != k.ST_OK))
    assert 0 < first and status[first] == k.ST_NO_CONVERGENCE
    a, b, q2, qd, qdd = both(p, q[:first + 1])
    assert_same(p, a, b, q2, qd, qdd)
    assert_same_state(p, a, b, at_limit=True)       # where continuation stopped


def test_gap_of_the_failed_group():
    """watt6 whose crank cannot reach: the first dyad A-B-O4 misses by |A - O4| minus the
    reach of its arms (the triangle inequality), at every sample that fails there."""
    m = kl.mechanisms.watt6(lengths=WATT6_SHORT)
    p = plan(m)
    b = _interpreter.run(p, TWO_TURNS[:, None], np.zeros((1, 1)), np.zeros((1, 1)))
    first, second = p.steps[2].op, p.steps[3].op
    assert set(b["fail"][b["status"] != k.ST_OK, 1].tolist()) == {first, second}
    bad = (b["status"] == k.ST_NO_ASSEMBLY) & (b["fail"][:, 1] == first)
    xy = {pt.name: np.array(pt.xy) for pt in m.points}
    lb, lc = (float(np.hypot(*(xy[u] - xy[v]))) for u, v in (("A", "B"), ("B", "O4")))
    r = float(np.hypot(*(xy["A"] - xy["O2"])))
    A = xy["O2"] + r * np.stack([np.cos(TWO_TURNS[bad]), np.sin(TWO_TURNS[bad])], -1)
    D = np.hypot(*(xy["O4"] - A).T)
    np.testing.assert_allclose(b["fail"][bad, 0], np.maximum(D - (lb + lc), abs(lb - lc) - D),
                               rtol=0, atol=1e-12 * p.scale)


def test_kernel_gap_is_of_the_failed_group():
    """The gap a failing sample reports is its failed group's, not one of the operations
    after it (which run on numbers another sample left)."""
    m = kl.mechanisms.watt6(lengths=WATT6_SHORT)
    p = plan(m)
    q = TWO_TURNS[:, None]
    a = _evaluate.run_compiled(p, q, np.zeros((1, 1)), np.zeros((1, 1)))
    b = _interpreter.run(p, q, np.zeros((1, 1)), np.zeros((1, 1)))
    bad = a["status"] != k.ST_OK
    np.testing.assert_allclose(a["fail"][bad, 0], b["fail"][bad, 0], rtol=0, atol=1e-12)


def test_parallel_lines_give_no_point():
    """Two lines exactly parallel (q = 0 for the yoke): both leave their intersection NaN,
    flagged singular; every other output the same."""
    m = prp_yoke()
    p = plan(m)
    q = np.array([0.3, 0.4, 0.5, 0.6, 0.0, 0.7, 0.0])
    a, b, q2, qd, qdd = both(p, q)
    np.testing.assert_array_equal(b["status"], a["status"])
    at = q == 0.0
    np.testing.assert_array_equal(a["diag"][at], 0.0)
    np.testing.assert_array_equal(b["diag"][at], 0.0)
    P = p.item_slot[p.point_item["P"]]
    assert np.isnan(b["jets"][at, P]).all() and np.isnan(a["jets"][at, P]).all()
    from_P = [p.point_item["P"], p.point_item["P"] + 1, *p.slide_item.values()]   # the slides too
    keep = ~np.isin(p.stored_items, from_P)
    np.testing.assert_allclose(b["jets"][at][:, keep, 0], a["jets"][at][:, keep, 0], rtol=0, atol=1e-15)
    rest = ~at
    sub = lambda o: {key: v[rest] for key, v in o.items()}     # noqa: E731
    assert_same(p, sub(a), sub(b), q2[rest], qd, qdd)


def test_kernel_parallel_lines_do_not_depend_on_other_samples():
    """Two lines exactly parallel place no point: NaN, whatever sample ran before."""
    p = plan(prp_yoke())
    zero = np.zeros((1, 1))
    P = p.item_slot[p.point_item["P"]]
    alone = _evaluate.run_compiled(p, np.array([[0.0]]), zero, zero)["jets"][0, P, 0]
    after = _evaluate.run_compiled(p, np.array([[0.3], [0.4], [0.5], [0.6], [0.0]]), zero, zero)["jets"][4, P, 0]
    assert alone == after or (np.isnan(alone) and np.isnan(after))


# --------------------------------------------------------------------------------------
# continuing from a state, random geometries
# --------------------------------------------------------------------------------------
def test_start_continues_a_sweep():
    """A Newton sweep in two pieces, the second from where the first ended: numpy from its
    own state as the kernel from its own, and as numpy in one piece."""
    p = plan(kl.mechanisms.triad6())
    q = np.linspace(0.0, 4 * np.pi, 400)[:, None]
    zero = np.zeros((1, 1))
    a1, b1, *_ = both(p, q[:150], zero, zero)
    assert_same_state(p, a1, b1)
    a2 = _evaluate.run_compiled(p, q[150:], zero, zero, start=a1["state"])
    b2 = _interpreter.run(p, q[150:], zero, zero, start=b1["state"])
    assert_same(p, a2, b2, q[150:], zero, zero)
    assert_same_state(p, a2, b2)
    whole = _interpreter.run(p, q, zero, zero)
    np.testing.assert_allclose(b2["jets"], whole["jets"][150:], rtol=0, atol=1e-12 * p.scale)
    # from a state and input given by hand (another mechanism's sketch): as the kernel
    a3, b3, *_ = both(p, q[:20], zero, zero, start=(np.array([0.3]), p.groups[3]))
    assert_same(p, a3, b3, q[:20], zero, zero)
    assert_same_state(p, a3, b3)


@st.composite
def fourbars(draw):
    lengths = [draw(st.floats(0.2, 4.0)) for _ in range(4)]
    branch = draw(st.sampled_from(["open", "crossed"]))
    cp = (draw(st.floats(-1.0, 2.0)), draw(st.floats(-1.0, 1.0)))
    try:
        return kl.mechanisms.fourbar(*lengths, coupler_point=cp, branch=branch)
    except kl.errors.ModelError:       # no assembly at any crank angle
        return draw(st.nothing())


@given(fourbars())
def test_random_fourbars(fb):
    """Any four-bar (Grashof or not), over two turns: where it assembles, where not."""
    check(fb, TWO_TURNS[::2])


@given(st.floats(0.2, 3.0), st.floats(0.2, 3.0), st.floats(-1.0, 1.0), st.sampled_from(["right", "left"]))
def test_random_slider_cranks(crank, rod, offset, branch):
    try:
        sc = kl.mechanisms.slider_crank(crank, rod, offset=offset, branch=branch)
    except kl.errors.ModelError:
        return
    check(sc, TWO_TURNS[::2])


# --------------------------------------------------------------------------------------
# the public API with the numpy evaluator in place of the kernel
# --------------------------------------------------------------------------------------
@pytest.fixture
def numpy_only(monkeypatch):
    """Run ``kl.analyze`` (and what it calls) with the numpy evaluator."""
    def swap():
        monkeypatch.setattr("kinelab.kinematics._analyze._run", _interpreter.run)
        monkeypatch.setattr("kinelab.kinematics._branches.run", _interpreter.run)
    return swap


def assert_solutions_equal(s1, s2):
    np.testing.assert_array_equal(s2.assembled, s1.assembled)
    np.testing.assert_array_equal(s2.singular, s1.singular)
    ok = s1.assembled
    for name in s1.mechanism.link_names:
        np.testing.assert_allclose(wrap(s2.angle(name)[ok] - s1.angle(name)[ok]), 0.0, atol=1e-11)
        np.testing.assert_allclose(s2.omega(name), s1.omega(name), rtol=1e-9, atol=1e-10)
        np.testing.assert_allclose(s2.alpha(name), s1.alpha(name), rtol=1e-9, atol=1e-9)
    for name in s1.mechanism.point_names:
        np.testing.assert_allclose(s2.position(name), s1.position(name), rtol=0, atol=1e-11)
        np.testing.assert_allclose(s2.acceleration(name), s1.acceleration(name), rtol=1e-9, atol=1e-9)
    # located by Newton's method on the dyad's arm, to about 1e-12
    assert [(c.step, c.followed) for c in s2.change_points] == [(c.step, c.followed) for c in s1.change_points]
    np.testing.assert_allclose([c.q for c in s2.change_points], [c.q for c in s1.change_points],
                               rtol=0, atol=1e-10)


@pytest.mark.parametrize("make, q, options", [
    (TURNING["fourbar"], TWO_TURNS, {}),
    (CHANGE_POINTS["parallelogram"], TWO_TURNS, {}),
    (CHANGE_POINTS["fourbar_4_2_3_5"], TWO_TURNS, {"at_change_point": "switch"}),
    (CHANGE_POINTS["slotted_link_1_1"], TWO_TURNS, {}),
    (TURNING["whitworth"], TWO_TURNS, {}),
    (TURNING["triad6"], TWO_TURNS[::4], {}),
    (TURNING["fourbar"], TWO_TURNS[::4], {"method": "newton"}),
    (lambda: kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5), TWO_TURNS, {"unreachable": "mask"}),
    (TWO_INPUTS["fivebar_up"], FIVEBAR_Q, {}),
], ids=["fourbar", "parallelogram", "switch", "slotted-through-pivot", "whitworth", "triad6", "newton",
        "mask", "fivebar"])
def test_analyze_with_the_numpy_evaluator(numpy_only, make, q, options):
    m = make()
    s1 = kl.analyze(m, q, qd=1.5, qdd=-0.5, **options)
    numpy_only()
    s2 = kl.analyze(make(), q, qd=1.5, qdd=-0.5, **options)
    assert_solutions_equal(s1, s2)


def test_analyze_errors_and_searches_with_the_numpy_evaluator(numpy_only):
    fb = kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5)
    t6 = kl.mechanisms.triad6()
    q = np.linspace(0.0, 4 * np.pi, 400)
    with pytest.raises(kl.errors.AssemblyError) as e1:
        kl.analyze(fb, TWO_TURNS)
    first = kl.analyze(t6, q[:150])
    second = kl.analyze(t6, q[150:], start=first)
    status = kl.kinematics.assembly_status(fb, TWO_TURNS)
    ranges = kl.kinematics.reachable_ranges(kl.mechanisms.slider_crank(3, 1))
    cps = kl.kinematics.change_points(CHANGE_POINTS["kite"](), 0.0, 4 * np.pi)
    numpy_only()
    fb, t6 = kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5), kl.mechanisms.triad6()
    with pytest.raises(kl.errors.AssemblyError) as e2:
        kl.analyze(fb, TWO_TURNS)
    assert str(e2.value) == str(e1.value)
    first2 = kl.analyze(t6, q[:150])
    assert_solutions_equal(second, kl.analyze(t6, q[150:], start=first2))
    status2 = kl.kinematics.assembly_status(fb, TWO_TURNS)
    np.testing.assert_array_equal(status2.assembled, status.assembled)
    np.testing.assert_array_equal(status2.singular, status.singular)
    np.testing.assert_allclose(kl.kinematics.reachable_ranges(kl.mechanisms.slider_crank(3, 1)), ranges,
                               rtol=0, atol=1e-12)
    cps2 = kl.kinematics.change_points(CHANGE_POINTS["kite"](), 0.0, 4 * np.pi)
    assert [c.step for c in cps2] == [c.step for c in cps]
    np.testing.assert_allclose([c.q for c in cps2], [c.q for c in cps], rtol=0, atol=1e-12)
