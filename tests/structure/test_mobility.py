"""Exact mobility from the rank of the constraint Jacobian, beside the count."""
import numpy as np
import pytest
from hypothesis import given, strategies as st

from kinelab.errors import ModelError
from kinelab.model import Joint, Link, Mechanism, Point
from kinelab.structure import mobility

from .models import (bennett, closed_4r, disk_cam_flat_follower, double_wishbone, fourbar,
                     parallelogram_fivebar, rssr, sarrus, slider_crank, spherical_fourbar,
                     stewart, triangle)


@pytest.mark.parametrize("build, count, exact", [
    (sarrus, 0, 1),
    (lambda: bennett()[0], -2, 1),
    (parallelogram_fivebar, 0, 1),
    (fourbar, 1, 1),
    (triangle, 0, 0),
    (slider_crank, 1, 1),
    (disk_cam_flat_follower, 1, 1),
    (stewart, 6, 6),
    (spherical_fourbar, 1, 1),
])
def test_count_and_exact(build, count, exact):
    m = mobility(build())
    assert (m.kutzbach_gruebler, m.exact) == (count, exact)
    assert isinstance(m.kutzbach_gruebler, int) and isinstance(m.exact, int)


def test_bennett_sketch_closes():
    # the loop is closed to machine precision, so the special geometry is exact
    assert bennett()[1] < 1e-12


def test_a_4r_loop_without_bennett_conditions_is_rigid():
    # any four axes are the sketch of some 4R loop; in general position it does not move
    generic = mobility(_generic_4r())
    assert (generic.kutzbach_gruebler, generic.exact) == (-2, 0)


def _generic_4r():
    rng = np.random.default_rng(7)
    p = rng.standard_normal((4, 3))
    pts = tuple(Point(f"J{k}", *p[k]) for k in range(4))
    links = (Link("ground", ("J3", "J0"), ground=True), Link("a", ("J0", "J1")),
             Link("b", ("J1", "J2")), Link("c", ("J2", "J3")))
    pairs = [("ground", "a"), ("a", "b"), ("b", "c"), ("c", "ground")]
    joints = tuple(Joint(f"j{k}", "R", pairs[k], point=f"J{k}",
                         axis=tuple(rng.standard_normal(3))) for k in range(4))
    return Mechanism("generic 4R", pts, links, joints, space="spatial")


@pytest.mark.parametrize("angle", [0.3, 1.0, 2.0, 2.8])
def test_bennett_moves_at_every_sketch(angle):
    # a closed Bennett loop at several input angles: the special geometry is kept
    model, gap = closed_4r((1.0, np.sqrt(3.0), 1.0, np.sqrt(3.0)),
                           (np.pi / 6, np.pi / 3, np.pi / 6, np.pi / 3), theta1=angle)
    assert gap < 1e-12
    assert mobility(model).exact == 1


def test_explanations_give_the_reason():
    s = mobility(sarrus())
    assert "M = 6(6 − 1) − 5·6 = 0" in s.explanation
    assert "1 constraint equation of the 30 repeats others because the geometry is special" in s.explanation
    assert s.redundant == 1 and s.passive == 0 and s.freedoms == 1
    b = mobility(bennett()[0])
    assert "a negative count" in b.explanation
    assert "beyond those, 1 constraint equation repeats others" in b.explanation
    p = mobility(parallelogram_fivebar())
    assert p.redundant == 1 and "of the 12 repeats others" in p.explanation
    four = mobility(fourbar())
    assert "as counted: no constraint repeats another and no freedom is passive" in four.explanation


def test_rssr_coupler_spin_is_passive():
    m = mobility(rssr())
    assert (m.kutzbach_gruebler, m.freedoms, m.passive, m.exact) == (2, 2, 1, 1)
    assert "link 'coupler' can spin about the line through its points" in m.explanation


def test_a_point_off_the_spin_axis_makes_the_spin_count():
    m = mobility(rssr(with_extra_coupler_point=True))
    assert (m.passive, m.exact) == (0, 2)
    assert m.local and "link 'coupler' can move alone" in m.local[0]


def test_suspension_steering_freedom():
    # *Mecanismos*, Ex. 2.3: M = 2, wheel up and down and the knuckle's turn (steering)
    with_wheel = mobility(double_wishbone(wheel_centre=True))
    assert (with_wheel.kutzbach_gruebler, with_wheel.exact) == (2, 2)
    bare = mobility(double_wishbone(wheel_centre=False))
    assert (bare.exact, bare.passive) == (1, 1)


def test_sps_legs_spin_passively():
    m = mobility(stewart("SPS"))
    assert (m.kutzbach_gruebler, m.exact, m.passive) == (12, 6, 6)
    assert "links 'cyl0', 'rod0' together can spin" in m.explanation


def test_spherical_linkage_needs_concurrent_axes():
    m = mobility(spherical_fourbar(concurrent=False))
    assert (m.kutzbach_gruebler, m.exact, m.redundant) == (1, 0, -1)
    assert "do not all pass through one point" in m.explanation


def test_tolerance_separates_special_from_nearly_special():
    # the middle axis of one leg of the Sarrus mechanism tilted towards z by 1e-6 rad: no
    # rotation is common to both legs any more and their translations differ, so it is
    # rigid; tilted by 1e-13 rad: special to within rounding, still moving.  (A tilt
    # towards x would keep a motion: both legs would then allow rotations about x.)
    def tilted(eps):
        m = sarrus()
        joints = tuple(Joint(j.name, j.type, j.links, point=j.point,
                             axis=(0.0, 1.0, eps) if j.name == "23" else j.axis)
                       for j in m.joints)
        return Mechanism(m.name, m.points, m.links, joints, space="spatial")
    assert mobility(tilted(1e-6)).exact == 0
    assert mobility(tilted(1e-13)).exact == 1


def test_missing_geometry_is_assumed_generic_and_said():
    m = sarrus()
    joints = tuple(Joint(j.name, j.type, j.links, point=j.point) for j in m.joints)
    bare = Mechanism("RRRRRR without axes", m.points, m.links, joints, space="spatial")
    r = mobility(bare)
    assert r.exact == 0 and len(r.assumed) == 6
    assert "joint '12' gives no axis; one in general position was assumed" in r.explanation


def test_spatial_r_axis_wrong_length_is_an_error():
    m = sarrus()
    joints = (Joint("12", "R", ("1", "2"), point="A1", axis=(0.0, 1.0)),) + m.joints[1:]
    bad = Mechanism(m.name, m.points, m.links, joints, space="spatial")
    with pytest.raises(ModelError, match=r"joint '12': axis: expected 3 finite numbers"):
        mobility(bad)


def test_not_a_model():
    with pytest.raises(ModelError, match="model: expected a kinelab.model.Mechanism, got a table"):
        mobility({"links": 4})


def test_disconnected_model_is_refused():
    # the model itself refuses parts that no chain of joints joins to the ground
    m = fourbar()
    with pytest.raises(ModelError, match="'loose' are not connected to the ground"):
        Mechanism("two parts", m.points + (Point("C", 5, 5), Point("D", 6, 5)),
                  m.links + (Link("loose", ("C", "D")),), m.joints)


# -- properties over random geometry ------------------------------------------------------
coords = st.floats(-3.0, 3.0, allow_nan=False)


@given(st.lists(st.tuples(coords, coords), min_size=4, max_size=4, unique=True))
def test_random_fourbar_moves_once(xy):
    p = np.array(xy)
    d = np.linalg.norm(p[:, None] - p[None], axis=-1) + np.eye(4) * 9
    # skip sketches folded flat (three joints on a line) or with joints on top of each other
    def area(a, b, c):
        (x1, y1), (x2, y2) = b - a, c - a
        return abs(x1 * y2 - x2 * y1)
    areas = [area(p[i], p[(i + 1) % 4], p[(i + 2) % 4]) for i in range(4)]
    if d.min() < 0.2 or min(areas) < 0.1:
        return
    assert mobility(fourbar(sketch=tuple(map(tuple, p)))).exact == 1


@given(st.integers(5, 8), st.integers(0, 2**31 - 1))
def test_generic_spatial_loop_of_n_revolutes(n, seed):
    # a single loop of n R joints in general position: M = 6(n - 1) - 5n = n - 6, never < 0
    rng = np.random.default_rng(seed)
    p, u = rng.standard_normal((n, 3)), rng.standard_normal((n, 3))
    names = ["ground"] + [f"l{k}" for k in range(1, n)]
    pts = tuple(Point(f"J{k}", *p[k]) for k in range(n))
    links = tuple(Link(names[k], (f"J{(k - 1) % n}", f"J{k}"), ground=(k == 0)) for k in range(n))
    joints = tuple(Joint(f"j{k}", "R", (names[k - 1] if k else names[-1], names[k]),
                         point=f"J{(k - 1) % n}", axis=tuple(u[k])) for k in range(n))
    m = mobility(Mechanism("loop", pts, links, joints, space="spatial"))
    assert m.kutzbach_gruebler == n - 6
    assert m.exact == max(n - 6, 0)


@given(st.floats(0.2, 2.9), st.floats(0.5, 2.0), st.floats(0.5, 2.0))
def test_parallelogram_moves_at_any_angle(angle, s1, s2):
    assert mobility(parallelogram_fivebar(angle, (0.0, s1, s1 + s2))).exact == 1


# -- sketches at singular configurations -----------------------------------------------------
def test_parallelogram_drawn_flat_is_a_change_point():
    # crank 1, coupler 2, rocker 1, ground 2 with every joint on the x axis: two branches
    # (parallelogram, antiparallelogram) cross here, the Jacobian allows 2 motions
    m = mobility(fourbar(sketch=((0, 0), (1, 0), (3, 0), (2, 0))))
    assert (m.kutzbach_gruebler, m.exact, m.singular) == (1, 1, True)
    assert "at the sketch the constraint Jacobian allows 2 independent motions" in m.explanation
    assert m.explanation.splitlines()[1].startswith("Exact (rank of the constraint Jacobian near")


@pytest.mark.parametrize("sketch", [((0, 0), (1, 0), (2, 0), (3, 0)), ((0, 0), (1, 0), (2, 0), (4, 0))])
def test_fourbar_that_only_assembles_flat_cannot_move(sketch):
    # 1 + 1 + 1 = 3 and 1 + 1 + 2 = 4: the three moving links only reach as a straight line
    m = mobility(fourbar(sketch=sketch))
    assert (m.kutzbach_gruebler, m.exact, m.singular) == (1, 0, True)
    assert "cannot move" in m.explanation


def test_dead_centre_is_not_singular_for_the_whole_jacobian():
    # a slider-crank at its dead centre: the input cannot advance, but every link still
    # has one motion; the rank method is not fooled and nothing needs moving
    m = Mechanism("sc at dead centre", (Point("O2", 0, 0), Point("A", 1, 0), Point("B", 4, 0)),
                  slider_crank().links, slider_crank().joints)
    r = mobility(m)
    assert (r.exact, r.singular, r.freedoms) == (1, False, 1)


def test_sarrus_plate_moves_along_z_only():
    # a finite move of the RRRRRR mechanism keeps the plate parallel to itself above the
    # same place: its displacement is a pure Tz (*Mecanismos*, §2.2), to the closing tolerance
    from kinelab.structure._motion import moved
    from kinelab.structure._system import ConstraintSystem
    model = sarrus()
    (after, *_) = moved(ConstraintSystem.of(model))
    before = {p.name: np.array([p.x, p.y, p.z]) for p in model.points}
    shift = [np.array([p.x, p.y, p.z]) - before[p.name] for p in after.points if p.name in ("A3", "B3")]
    assert np.allclose(shift[0], shift[1], rtol=0, atol=1e-10)
    assert abs(shift[0][2]) > 1e-3 and np.allclose(shift[0][:2], 0.0, rtol=0, atol=1e-10)
    assert mobility(after).exact == 1
