"""Grashof's criterion and Barker's classes, checked against the motion itself.

The class comes from the lengths alone; what each link does comes from analysing the
four-bar over two turns of its crank (unwrapped angles counted in turns), on the branches
kinelab follows through change points.  A link the crank cannot drive fully is checked from
the other pivot: the rocker turns fully relative to the ground exactly when the mirrored
four-bar (crank and rocker swapped) can be driven by it through a whole turn.
"""
import math
import warnings

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import AssemblyError, ModelError
from tests.kinematics.checks import closure_residual, wrap

TWO_TURNS = np.linspace(0.0, 4 * math.pi, 2881)      # 0.25 degree steps


def turns(sol, link):
    """(net turns, turns spanned) of a link's angle over the samples."""
    u = np.unwrap(sol.angle(link))
    return (u[-1] - u[0]) / (2 * math.pi), (u.max() - u.min()) / (2 * math.pi)


def regular(sol):
    """The samples away from change points: exactly at one (flagged singular) a folded dyad
    is placed to about sqrt(eps) only."""
    ok = ~sol.singular
    assert ok.mean() > 0.99
    return ok


def sweep(lengths, branch="open"):
    fb = kl.mechanisms.fourbar(*lengths, branch=branch)
    sol = kl.analyze(fb, q=TWO_TURNS)
    assert closure_residual(sol) < 1e-9 * max(lengths)
    return sol


def can_turn_fully(lengths):
    """Whether the crank of fourbar(*lengths) can be driven through two whole turns."""
    try:
        sweep(lengths)
        return True
    except AssemblyError:
        return False


# (ground, crank, coupler, rocker): kind, Barker's code, form, crank turns, rocker turns;
# worked by hand from s, l, p, q
CLASSES = [
    ((3.0, 1.0, 3.0, 2.5), "crank-rocker", "GCRR", None, True, False),     # 1 + 3 < 3 + 2.5
    ((1.0, 3.0, 3.0, 2.5), "double-crank", "GCCC", None, True, True),
    ((3.0, 2.5, 1.0, 3.0), "double-rocker", "GRCR", None, False, False),
    ((3.0, 2.5, 3.0, 1.0), "rocker-crank", "GRRC", None, False, True),
    ((1.0, 2.0, 1.0, 1.5), "triple-rocker", "RRR2", None, False, False),    # 1 + 2 > 1 + 1.5
    ((2.0, 3.0, 4.0, 5.0), "change-point", "CCC", None, True, True),        # 2 + 5 = 3 + 4
    ((4.0, 2.0, 3.0, 5.0), "change-point", "CRR", None, True, False),
    ((3.0, 4.0, 2.0, 5.0), "change-point", "RCR", None, False, False),
    ((3.0, 4.0, 5.0, 2.0), "change-point", "RRC", None, False, True),
    ((100, 60, 100, 60), "change-point", "S2X", "parallelogram", True, True),
    ((60, 100, 60, 100), "change-point", "S2X", "parallelogram", True, True),
    ((1.0, 1.0, 2.0, 2.0), "change-point", "S2X", "kite", True, True),
    ((2.0, 2.0, 1.0, 1.0), "change-point", "S2X", "kite", False, True),
    ((1.0, 2.0, 2.0, 1.0), "change-point", "S2X", "kite", True, True),
    ((2.0, 1.0, 1.0, 2.0), "change-point", "S2X", "kite", True, False),
    ((1.0, 1.0, 1.0, 1.0), "change-point", "S3X", "rhombus", True, True),
]


@pytest.mark.parametrize("lengths, kind, barker, form, crank, rocker", CLASSES,
                         ids=[str(c[0]) for c in CLASSES])
def test_classes_worked_by_hand(lengths, kind, barker, form, crank, rocker):
    g = kl.mechanisms.grashof(*lengths)
    assert (g.kind, g.barker, g.form, g.crank_rotates, g.rocker_rotates) == (kind, barker, form, crank, rocker)
    assert g.grashof == (kind != "triple-rocker")


@pytest.mark.parametrize("lengths", [c[0] for c in CLASSES], ids=[str(c[0]) for c in CLASSES])
def test_what_turns_fully_is_what_the_motion_does(lengths):
    g = kl.mechanisms.grashof(*lengths)
    ground, crank, coupler, rocker = lengths
    assert can_turn_fully(lengths) == g.crank_rotates
    assert can_turn_fully((ground, rocker, coupler, crank)) == g.rocker_rotates
    if g.crank_rotates:
        # driven by its crank, on each mode: the rocker goes round on some mode when it
        # turns fully, and never spans a whole turn otherwise
        spans = [turns(sweep(lengths, b), "rocker")[1] for b in ("open", "crossed")]
        if g.rocker_rotates:
            assert max(spans) > 1.0 - 1e-9
        else:
            assert max(spans) < 1.0


@pytest.mark.parametrize("lengths", [(100, 60, 100, 60), (60, 100, 60, 100), (5.0, 2.0, 5.0, 2.0),
                                     (2.0, 5.0, 2.0, 5.0), (1.0, 1.0, 1.0, 1.0)])
def test_parallelogram_and_rhombus_are_the_parallelogram_on_open(lengths):
    sol = sweep(lengths, "open")
    ok = regular(sol)
    assert np.max(np.abs(wrap(sol.angle("rocker") - TWO_TURNS)[ok])) < 1e-9     # at the crank's angle
    assert np.max(np.abs(wrap(sol.angle("coupler") - sol.angle("coupler")[1])[ok])) < 1e-9


@pytest.mark.parametrize("lengths, rocker_turns, coupler_turns", [
    ((100, 60, 100, 60), -2.0, None), ((5.0, 2.0, 5.0, 2.0), -2.0, None),   # longer pair grounded
    ((60, 100, 60, 100), 2.0, 4.0), ((2.0, 5.0, 2.0, 5.0), 2.0, 4.0),        # shorter pair grounded
])
def test_parallelogram_is_the_antiparallelogram_on_crossed(lengths, rocker_turns, coupler_turns):
    sol = sweep(lengths, "crossed")
    ground, crank = lengths[:2]
    # not the parallelogram: B away from A + (ground, 0) except near the change points
    apart = np.linalg.norm(sol.position("B") - sol.position("A") - [ground, 0.0], axis=1)
    away = np.min(np.abs(TWO_TURNS[:, None] - [c.q for c in sol.change_points]), axis=1) > 0.05
    assert np.all(apart[away] > 1e-3 * ground)
    net, _ = turns(sol, "rocker")
    assert net == pytest.approx(rocker_turns, abs=1e-9)
    net, span = turns(sol, "coupler")
    if coupler_turns is None:
        assert span < 1.0                                                      # it rocks
    else:
        assert net == pytest.approx(coupler_turns, abs=1e-9)


@pytest.mark.parametrize("lengths", [(1.0, 1.0, 1.0, 1.0), (2.0, 1.0, 1.0, 2.0), (1.0, 2.0, 2.0, 1.0),
                                     (5.0, 2.0, 2.0, 5.0), (2.0, 5.0, 5.0, 2.0)])
def test_rhombus_and_kite_grounded_at_the_rocker_fold_on_crossed(lengths):
    sol = sweep(lengths, "crossed")
    ok = regular(sol)
    assert np.max(np.linalg.norm(sol.position("B")[ok], axis=1)) < 1e-9 * max(lengths)   # B on O2
    rocker = sol.angle("rocker")[ok]
    assert np.max(np.abs(wrap(rocker - rocker[0]))) < 1e-9                              # still
    together = wrap(sol.angle("coupler") - sol.angle("crank"))[ok]
    assert np.max(np.abs(wrap(together - together[0]))) < 1e-9


@pytest.mark.parametrize("lengths, rocker_net", [((2.0, 1.0, 1.0, 2.0), None), ((5.0, 2.0, 2.0, 5.0), None),
                                                 ((1.0, 2.0, 2.0, 1.0), 4.0), ((2.0, 5.0, 5.0, 2.0), 4.0)])
def test_kite_grounded_at_the_rocker_on_open(lengths, rocker_net):
    net, span = turns(sweep(lengths, "open"), "rocker")
    if rocker_net is None:
        assert span < 1.0                       # the longer pair grounded: it rocks
    else:
        assert net == pytest.approx(rocker_net, abs=1e-9)     # twice per turn of the crank


@pytest.mark.parametrize("lengths", [(1.0, 1.0, 2.0, 2.0), (2.0, 2.0, 5.0, 5.0), (3.0, 3.0, 4.0, 4.0)])
@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_kite_grounded_at_the_crank_turns_its_rocker_once_per_two_crank_turns(lengths, branch):
    net, _ = turns(sweep(lengths, branch), "rocker")
    assert abs(net) == pytest.approx(1.0, abs=1e-9)
    ground, crank, coupler, rocker = lengths
    assert not can_turn_fully((coupler, rocker, ground, crank))   # the longer pair grounded


def test_ties_within_rtol():
    g = kl.mechanisms.grashof(100, 60, 100, 60 * (1 + 1e-14))
    assert (g.form, g.barker, g.rocker_rotates) == ("parallelogram", "S2X", True)
    g = kl.mechanisms.grashof(100, 60, 100, 60 * (1 + 1e-6))    # s = 60, the crank: 160 < 160.00006
    assert (g.form, g.kind, g.barker, g.rocker_rotates) == (None, "crank-rocker", "GCRR", False)


def test_bad_lengths_are_named():
    with pytest.raises(ModelError, match=r"^crank: expected a positive length \(m\), got -1$"):
        kl.mechanisms.grashof(1.0, -1, 1.0, 1.0)


@pytest.mark.parametrize("lengths, options, message", [
    ((10**400, 1, 3, 2.5), {}, r"^ground: expected a positive length \(m\), got a whole number of 401 digits$"),
    ((True, 1, 3, 2.5), {}, r"^ground: expected a positive length \(m\), got true$"),
    ((3, "1", 3, 2.5), {}, r"^crank: expected a positive length \(m\), got '1'$"),
    ((3, 1, 3, 2e9), {}, r"^rocker: expected a length from 1e-09 m to 1e\+09 m, got 2e\+09 m$"),
    ((3, 1, 3, 2.5), {"rtol": "a"}, r"^rtol: expected a number from 0 to 0.01, got 'a'$"),
    ((3, 1, 3, 2.5), {"rtol": None}, r"^rtol: expected a number from 0 to 0.01, got None$"),
    ((3, 1, 3, 2.5), {"rtol": np.nan}, r"^rtol: expected a number from 0 to 0.01, got nan$"),
    ((3, 1, 3, 2.5), {"rtol": -1}, r"^rtol: expected a number from 0 to 0.01, got -1$"),
    ((3, 1, 3, 2.5), {"rtol": 1}, r"^rtol: expected a number from 0 to 0.01, got 1$"),
])
def test_bad_arguments_of_grashof_are_named(lengths, options, message):
    with pytest.raises(ModelError, match=message):
        kl.mechanisms.grashof(*lengths, **options)


@pytest.mark.parametrize("lengths, options, message", [
    ((10**400, 1, 3, 2.5), {}, r"^ground: expected real numbers \(lengths, m\), got a whole number of 401 digits$"),
    (("a", 1, 3, 2.5), {}, r"^ground: expected real numbers \(lengths, m\), got 'a'$"),
    (("1", 1, 3, 2.5), {}, r"^ground: expected real numbers \(lengths, m\), got '1'$"),
    ((3, [True], 3, 2.5), {}, r"^crank: expected real numbers \(lengths, m\), got \[true\]$"),
    (([[1, 2], [3]], 1, 3, 2.5), {}, r"^ground: expected real numbers \(lengths, m\), got \[\[1, 2\], \[3\]\]$"),
    (([1, 2], [1, 2, 3], 3, 2.5), {}, r"^ground, crank, coupler, rocker: expected arrays of shapes "
                                      r"that broadcast together, got ground \(2,\), crank \(3,\), "),
    ((3, 1, 3, 2.5), {"rtol": 1e308}, r"^rtol: expected a number from 0 to 0.01, got 1e\+308$"),
])
def test_bad_arguments_of_grashof_kinds_are_named(lengths, options, message):
    with pytest.raises(ModelError, match=message):
        kl.mechanisms.grashof_kinds(*lengths, **options)


def test_grashof_kinds_marks_lengths_out_of_range_without_overflow():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        kinds = kl.mechanisms.grashof_kinds([3.0, np.nan, 2e9, 1e308, -1.0], 1.0, 3.0, 2.5)
    assert kinds.tolist() == ["crank-rocker", None, None, None, None]


def test_a_large_rtol_does_not_turn_a_crank_rocker_into_a_change_point():
    assert kl.mechanisms.grashof(3.0, 1.0, 3.0, 2.5, rtol=0.01).kind == "crank-rocker"
