"""What a sweep stores: only the coordinates it solves; the ground's and the inputs' are read
back the same."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.kinematics import KinematicSolution
from kinelab.kinematics._kernel import BLOCK

Q = np.linspace(0.1, 2 * np.pi + 0.1, 9)


def coupler_fourbar():
    return kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))


def test_ground_and_input_coordinates_are_not_stored_per_sample():
    sol = kl.analyze(coupler_fourbar(), q=Q, qd=2.0, qdd=0.5)
    # the ground's angle, the pivots O2, O4 and the crank's angle (six coordinates) are
    # not repeated per sample
    assert sol.stored_jets.shape == (9, sol.jets.shape[1] - 6, 3)
    np.testing.assert_allclose(sol.angle("crank"), np.angle(np.exp(1j * Q)), rtol=0, atol=1e-14)
    np.testing.assert_array_equal(sol.K("crank"), np.ones(9))
    np.testing.assert_array_equal(sol.L("crank"), np.zeros(9))
    np.testing.assert_array_equal(sol.omega("crank"), np.full(9, 2.0))
    np.testing.assert_array_equal(sol.alpha("crank"), np.full(9, 0.5))
    np.testing.assert_array_equal(sol.position("O4"), np.tile([3.0, 0.0], (9, 1)))
    np.testing.assert_array_equal(sol.angle("ground"), np.zeros(9))
    for name in ("O2", "O4"):
        np.testing.assert_array_equal(sol.K(name), np.zeros((9, 2)))
        np.testing.assert_array_equal(sol.L(name), np.zeros((9, 2)))
        np.testing.assert_array_equal(sol.velocity(name), np.zeros((9, 2)))
        np.testing.assert_array_equal(sol.acceleration(name), np.zeros((9, 2)))


def test_jets_built_on_demand_agree_with_every_accessor():
    sol = kl.analyze(coupler_fourbar(), q=Q, qd=2.0, qdd=0.5)
    for link, i in sol.link_item.items():
        np.testing.assert_array_equal(sol.jets[:, i], np.stack([sol.angle(link), sol.K(link),
                                                                  sol.L(link)], axis=-1))
        np.testing.assert_array_equal(sol.rates[:, i], np.stack([sol.omega(link), sol.alpha(link)],
                                                                   axis=-1))
    for point, i in sol.point_item.items():
        np.testing.assert_array_equal(sol.jets[:, i:i + 2, 0], sol.position(point))
        np.testing.assert_array_equal(sol.jets[:, i:i + 2, 1], sol.K(point))
        np.testing.assert_array_equal(sol.rates[:, i:i + 2, 1], sol.acceleration(point))
    cols = sol.columns()
    np.testing.assert_array_equal(cols["O4.x[m]"], np.full(9, 3.0))
    np.testing.assert_array_equal(cols["ground.alpha[rad/s^2]"], np.zeros(9))


def test_ground_coordinates_follow_the_nan_rules():
    """Where the loops do not close every value is NaN; at a singular sample K, L and the
    rates are NaN and positions are kept: for the ground's coordinates as for the others."""
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)   # non-Grashof
    _, limit = kl.kinematics.reachable_ranges(fb)[0]
    sol = kl.analyze(fb, q=[0.0, limit, 3.0], qd=1.0, unreachable="mask")
    np.testing.assert_array_equal(sol.singular, [False, True, False])
    np.testing.assert_array_equal(sol.assembled, [True, True, False])
    np.testing.assert_array_equal(sol.position("O4")[:2], [[1.0, 0.0], [1.0, 0.0]])
    assert np.isnan(sol.position("O4")[2]).all() and np.isnan(sol.angle("ground")[2])
    assert np.isnan(sol.K("O4")[1]).all() and np.isnan(sol.velocity("O4")[1]).all()
    assert np.isnan(sol.omega("ground")[1]) and np.isnan(sol.L("ground")[1])
    assert np.isnan(sol.K("crank")[1]) and np.isnan(sol.omega("crank")[1])
    assert np.isnan(sol.angle("crank")[2]) and sol.angle("crank")[1] == limit
    np.testing.assert_array_equal(sol.K("O4")[0], [0.0, 0.0])
    np.testing.assert_array_equal(np.isnan(sol.jets[:, sol.point_item["O4"], 0]),
                                  np.isnan(sol.jets[:, sol.point_item["B"], 0]))


@pytest.mark.parametrize("make", [coupler_fourbar, kl.mechanisms.triad6])
def test_pieces_concatenate_to_the_whole_sweep(make):
    m = make()
    whole = kl.analyze(m, q=Q, qd=1.5)
    first = kl.analyze(m, q=Q[:4], qd=1.5)
    joined = KinematicSolution.concatenate([first, kl.analyze(m, q=Q[4:], qd=1.5, start=first)])
    np.testing.assert_allclose(joined.jets, whole.jets, rtol=0, atol=1e-12)
    np.testing.assert_allclose(joined.rates, whole.rates, rtol=0, atol=1e-11)
    np.testing.assert_array_equal(joined.singular, whole.singular)


@pytest.mark.parametrize("make, q", [
    (lambda: kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5),
     np.linspace(-3.0, 3.0, 23)),                       # non-Grashof: some samples do not close
    (kl.mechanisms.stephenson6, np.linspace(0.0, 2 * np.pi, 23)),
    (lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0),
     np.column_stack([np.linspace(0.0, 6.0, 23), np.linspace(2.0, 4.0, 23)])),
    (lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.5), np.linspace(0.0, 2 * np.pi, 23)),
    (lambda: kl.mechanisms.slotted_link(1.0, 2.0), np.linspace(0.0, 2 * np.pi, 23)),
    (lambda: kl.mechanisms.whitworth(1.0, 0.5, 3.0, 2.0), np.linspace(0.0, 2 * np.pi, 23)),
])
def test_samples_swept_together_are_those_analysed_alone(make, q):
    """A sweep evaluates its samples side by side in blocks; a sample that fails (or is
    singular) beside others does not change them."""
    m = make()
    sweep = kl.analyze(m, q=q, qd=1.5, qdd=-0.5, unreachable="mask")
    assert sweep.assembled.any()
    for i in range(len(q)):
        alone = kl.analyze(m, q=q[i:i + 1], qd=1.5, qdd=-0.5, unreachable="mask")
        assert alone.assembled[0] == sweep.assembled[i]
        np.testing.assert_allclose(alone.stored_jets[0], sweep.stored_jets[i], rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(alone.stored_rates[0], sweep.stored_rates[i], rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(alone.det_J[0], sweep.det_J[i], rtol=1e-13, atol=1e-13)


def test_the_first_sample_that_does_not_close_is_reported_from_within_a_block():
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    q = np.linspace(0.5, 5.5, 23)
    bad = np.flatnonzero(~kl.analyze(fb, q=q, unreachable="mask").assembled)
    assert bad.size and bad[0] % BLOCK != 0               # inside a block, not at its start
    with pytest.raises(kl.errors.AssemblyError) as swept:
        kl.analyze(fb, q=q)
    with pytest.raises(kl.errors.AssemblyError) as alone:
        kl.analyze(fb, q=q[bad[0]])
    assert swept.value.gap == alone.value.gap > 0
    assert swept.value.loop == alone.value.loop


def test_the_solution_keeps_its_own_inputs():
    """The crank's angle and rates are read back from q, qd and qdd: changing the arrays
    passed in afterwards must not change the solution."""
    q, qd, qdd = Q.copy(), np.full(9, 2.0), np.linspace(0.0, 1.0, 9)
    sol = kl.analyze(coupler_fourbar(), q=q, qd=qd, qdd=qdd)
    angle, omega, alpha = sol.angle("crank").copy(), sol.omega("crank").copy(), sol.alpha("crank").copy()
    q += 1.0
    qd *= 3.0
    qdd[:] = -7.0
    np.testing.assert_array_equal(sol.angle("crank"), angle)
    np.testing.assert_array_equal(sol.omega("crank"), omega)
    np.testing.assert_array_equal(sol.alpha("crank"), alpha)
    assert sol.q.flags.writeable and sol.qd.flags.writeable


@pytest.mark.parametrize("first, then", [("newton", "auto"), ("auto", "newton")])
def test_a_start_from_another_method_is_refused(first, then):
    """The two methods solve different Newton groups: one's state cannot start the other."""
    t6 = kl.mechanisms.triad6()
    earlier = kl.analyze(t6, q=Q[:3], method=first)
    with pytest.raises(kl.errors.ModelError, match="another method"):
        kl.analyze(t6, q=Q[3:], method=then, start=earlier)
    kl.analyze(t6, q=Q[3:], method=first, start=earlier)          # the same method continues


def test_slide_axis_turns_with_its_guide():
    """In Erthal's slotted link the slot runs along the lever from O4 through A, and the
    slide is B = |A - O4|: the axis is (A - O4) / B at every sample."""
    sol = kl.analyze(kl.mechanisms.slotted_link(1.0, 2.0), q=Q)
    along = sol.position("A") - sol.position("O4")
    np.testing.assert_allclose(sol.slide_axes("slot"), along / sol.slide("slot")[:, None],
                               rtol=0, atol=1e-14)
    with pytest.raises(kl.errors.ModelError, match="prismatic joint"):
        sol.slide_axes("jA")


def test_slide_axes_follow_the_shape_rule():
    """One configuration: no sample axis, like every other accessor; the value is the
    sweep's row at that input."""
    sl = kl.mechanisms.slotted_link(1.0, 2.0)
    sweep = kl.analyze(sl, q=Q, qd=2.0, qdd=-1.0)
    one = kl.analyze(sl, q=Q[7], qd=2.0, qdd=-1.0)
    assert one.slide_axes("slot").shape == (2,) and sweep.slide_axes("slot").shape == (len(Q), 2)
    np.testing.assert_array_equal(one.slide_axes("slot"), sweep.slide_axes("slot")[7])
    # a caller inside the package: the parts of the pin's acceleration
    parts, parts_n = one.acceleration_components("A"), sweep.acceleration_components("A")
    for name in ("origin", "tangential", "normal", "coriolis", "sliding"):
        assert getattr(parts, name).shape == (2,)
        np.testing.assert_array_equal(getattr(parts, name), getattr(parts_n, name)[7])


def by_items(sol, name, kinds):
    """A link's, point's or slide's (value, K, L, rate, second rate) read from ``item_jets``
    and ``item_rates``, the general gather, shaped as the accessors shape them."""
    tables = {"l": (sol.link_item, 1), "p": (sol.point_item, 2), "s": (sol.slide_item, 1)}
    i, w = next((t[0][name], t[1]) for kind, t in tables.items() if kind in kinds and name in t[0])
    jets, rates = sol.item_jets(list(range(i, i + w))), sol.item_rates(list(range(i, i + w)))
    N, M = sol.N, sol.M
    parts = [jets[:, :, 0], jets[:, :, 1:1 + M], jets[:, :, 1 + M:].reshape(N, w, M, M),
             rates[:, :, 0], rates[:, :, 1]]
    parts = [p if w > 1 else p[:, 0] for p in parts]
    parts[1] = parts[1][..., 0] if M == 1 else parts[1]
    parts[2] = parts[2][..., 0, 0] if M == 1 else parts[2]
    return [p[0] if sol.single else p for p in parts]


ACCESSORS = {"l": ("angle", "K", "L", "omega", "alpha"),
             "p": ("position", "K", "L", "velocity", "acceleration"),
             "s": ("slide", "K", "L", "slide_velocity", "slide_acceleration")}


def non_grashof():
    return kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)


@pytest.mark.parametrize("make, q", [
    (coupler_fourbar, Q),
    (coupler_fourbar, 0.7),
    (coupler_fourbar, [-7.0, -3.2, 3.3, 9.0, 20.0]),                    # wrapped angles
    (non_grashof, "limits"),                                            # masked, singular
    (non_grashof, 3.0),
    (lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.5), Q),
    (lambda: kl.mechanisms.whitworth(1.0, 0.5, 1.0, 2.0), Q),
    (kl.mechanisms.stephenson6, Q),
    (kl.mechanisms.triad6, Q[:4]),
    (lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0), [[1.2, 1.3], [1.6, 1.5], [2.0, 1.9]]),
    (lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0), [1.2, 1.3]),
], ids=["fourbar", "one sample", "turns", "masked and singular", "one masked", "slider-crank",
        "whitworth", "stephenson6", "triad6", "fivebar", "fivebar one sample"])
def test_every_accessor_is_the_general_gather(make, q):
    """The accessors read stored items as views, turn an input into its link's angle, rates,
    K and L, and gather fixed points once: to the bit what item_jets and item_rates give,
    NaN rules and shapes included; and what they gather they hand out as copies."""
    m = make()
    M = len(m.inputs)
    if isinstance(q, str):                  # either end of the reach, and beyond
        lo, hi = kl.kinematics.reachable_ranges(m)[0]
        q = [0.0, hi, 3.0, lo, 1.0]
    qd, qdd = (2.0, 0.5) if M == 1 else (np.array([2.0, -1.0]), np.array([0.5, 0.25]))
    sol = kl.analyze(m, q=q, qd=qd, qdd=qdd, unreachable="mask", at_singular="flag")
    if make is non_grashof and sol.N > 1:
        assert sol.singular.any() and not sol.assembled.all()
    names = [(n, "l") for n in sol.link_names] + [(n, "p") for n in sol.point_names] + \
        [(n, "s") for n in sol.slide_names]
    for name, kind in names:
        expected = by_items(sol, name, kind)
        got = [getattr(sol, a)(name) for a in ACCESSORS[kind]]
        for a, x, y in zip(ACCESSORS[kind], got, expected):
            assert type(x) is type(y) and np.shape(x) == np.shape(y), (name, a)
            np.testing.assert_array_equal(x, y, err_msg=f"{name}.{a}")
        for a in ACCESSORS[kind]:                 # what one caller changes, no other sees
            x = getattr(sol, a)(name)
            if isinstance(x, np.ndarray) and x.base is not None and not np.shares_memory(
                    x, sol.stored_jets) and not np.shares_memory(x, sol.stored_rates):
                x[...] = 1234.5
        for a, y in zip(ACCESSORS[kind], expected):
            np.testing.assert_array_equal(getattr(sol, a)(name), y, err_msg=f"{name}.{a}")


def test_designs_accessors_are_the_general_gather():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    r = np.array([1.0, 1.2, 1.4])
    xy = np.array([[[0, 0], [0, c], [np.sqrt(9 - c * c), 0]] for c in r])
    sol = kl.kinematics.analyze_designs(sc, xy, q=np.radians([0.0, 90.0, 400.0]), qd=2.0)
    for link in sol.link_names:
        np.testing.assert_array_equal(sol.angle(link), sol.by_design(sol.item_jets([sol.link_item[link]])[:, 0, 0]))
        np.testing.assert_array_equal(sol.omega(link), sol.by_design(sol.item_rates([sol.link_item[link]])[:, 0, 0]))
    for point in sol.point_names:
        i = sol.point_item[point]
        np.testing.assert_array_equal(sol.position(point), sol.by_design(sol.item_jets([i, i + 1])[:, :, 0]))


def test_a_solution_made_quickly_has_every_field():
    """analyze builds its solution without the dataclass's __init__: every field is set."""
    import dataclasses
    sol = kl.analyze(coupler_fourbar(), q=Q, qd=2.0)
    assert {f.name for f in dataclasses.fields(KinematicSolution)} <= set(vars(sol))


@pytest.mark.parametrize("q", [0.7, np.float64(0.7), [0.7], np.array([0.7, 2.0, -7.0]),
                               np.linspace(0.0, 12.0, 40)[::3], [1, 2, 3], np.float32(0.5)])
def test_inputs_checked_quickly_or_not_give_the_same_numbers(q):
    """One input swept at constant rates takes a quicker check: its numbers are those of the
    same inputs given in another form (which takes the general checks)."""
    fb = coupler_fourbar()
    a = kl.analyze(fb, q, 2.0, 0.5)
    as_list = np.asarray(q, float).tolist()
    b = kl.analyze(fb, as_list, np.array(2.0), np.array(0.5))
    assert a.q.shape == b.q.shape and a.qd.shape == b.qd.shape and a.qd.strides == b.qd.strides
    assert not a.qd.flags.writeable and not b.qd.flags.writeable or a.N == 1
    for name in ("B", "P"):
        np.testing.assert_array_equal(a.position(name), b.position(name))
        np.testing.assert_array_equal(a.acceleration(name), b.acceleration(name))
    np.testing.assert_array_equal(a.q, b.q)
    assert a.single == b.single
