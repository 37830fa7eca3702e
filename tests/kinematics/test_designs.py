"""A plan's numbers for many designs of one topology at once (``Plan.designs``) are each
design's own plan's numbers: the plan built from that design's sketch alone."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.kinematics._plan import build_plan
from tests.kinematics.test_engine import CATALOGUE, _hydraulic_boom
from tests.kinematics.test_scale_free import PYSLVS

EXAMPLES = sorted(Path(__file__).parents[2].joinpath("examples").glob("*.toml"))
MODELS = {
    **CATALOGUE,
    "fivebar": lambda: kl.mechanisms.fivebar(1.0, 1.0, 1.5, 1.5, 1.0),
    "boom": _hydraulic_boom,
    **{f"pyslvs_{name}": (lambda e=e: kl.io.from_pyslvs(e, inputs=[(0, 1)])) for name, e in PYSLVS.items()},
    **{f"example_{p.stem}": (lambda p=p: kl.load(p)) for p in EXAMPLES},
}
# gear and cam joints are solved in closed form only: these have no Newton plan (method "newton")
GEARED = {f"example_{p.stem}" for p in EXAMPLES
          if 'type = "G"' in p.read_text() or 'type = "C"' in p.read_text()}


def sketches(m, D=12, seed=0):
    """D sketches of m: its own, and its points moved at random by up to 2% of its size
    (a plan reads dimensions and branches off a sketch; it need not be assembled)."""
    rng = np.random.default_rng(seed)
    xy = np.array([[p.x, p.y] for p in m.points])
    size = np.ptp(xy, axis=0).max()
    moved = xy + rng.uniform(-0.02, 0.02, (D, *xy.shape)) * size
    moved[0] = xy
    return moved


def plain(m):
    """m with no declared dimensions: its sketch alone (as a design's is)."""
    links = tuple(dataclasses.replace(link, length=None, local=None, sides=None) for link in m.links)
    joints = tuple(dataclasses.replace(j, offset=None) for j in m.joints)
    return dataclasses.replace(m, links=links, joints=joints)


@pytest.mark.parametrize("name, method", [(n, m) for m in ("auto", "newton") for n in sorted(MODELS)
                                          if m == "auto" or n not in GEARED])
def test_each_design_gets_its_own_plans_numbers(name, method):
    m = plain(MODELS[name]())
    base = build_plan(m, method=method)
    points = sketches(m)
    d = base.designs(points)
    assert d.valid.all()
    for i, xy in enumerate(points):
        own = build_plan(dataclasses.replace(m, points=tuple(
            dataclasses.replace(p, x=float(v[0]), y=float(v[1])) for p, v in zip(m.points, xy))),
            method=method)
        np.testing.assert_array_equal(own.ops_i, base.ops_i)
        # the same formulas, vectorised: to rounding
        np.testing.assert_allclose(d.ops_f[i], own.ops_f, rtol=1e-13, atol=1e-13 * own.scale)
        np.testing.assert_allclose(d.const_values[i], own.const_values, rtol=1e-14, atol=1e-14 * own.scale)
        np.testing.assert_allclose(d.q_sketch[i], own.q_sketch, rtol=0, atol=1e-13)
        np.testing.assert_allclose(d.sketch_angles[i], own.sketch_angles, rtol=0, atol=1e-13)
        assert d.scale[i] == own.scale
        if base.groups is not None:
            np.testing.assert_array_equal(own.groups[1], base.groups[1])
            np.testing.assert_allclose(d.group_f[i], own.groups[2], rtol=1e-13, atol=1e-13 * own.scale)
            np.testing.assert_allclose(d.group_x0[i], own.groups[3], rtol=1e-13, atol=1e-13 * own.scale)


def test_a_design_drawn_straight_is_not_valid():
    """A dyad drawn straight has no assembly mode: that design needs a plan of its own (and
    build_plan refuses its sketch)."""
    m = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    xy = sketches(m, D=3)
    names = m.point_names
    A, O4 = xy[1, names.index("A")], xy[1, names.index("O4")]
    xy[1, names.index("B")] = A + 0.4 * (O4 - A)          # B on the line A-O4
    d = build_plan(m).designs(xy)
    assert d.valid.tolist() == [True, False, True]
    with pytest.raises(ModelError, match="singular"):
        build_plan(dataclasses.replace(m, points=tuple(
            dataclasses.replace(p, x=float(v[0]), y=float(v[1])) for p, v in zip(m.points, xy[1]))))


def test_points_by_name_or_in_order():
    m = kl.mechanisms.slider_crank(1.0, 3.0, offset=0.2)
    xy = sketches(m, D=4)
    p = build_plan(m)
    by_order = p.designs(xy)
    by_name = p.designs({n: xy[:, i] for i, n in enumerate(m.point_names)})
    np.testing.assert_array_equal(by_order.ops_f, by_name.ops_f)
    with pytest.raises(ModelError, match=r"points: expected an array \(D, 3, 2\)"):
        p.designs(xy[:, :2])
    with pytest.raises(ModelError, match="missing 'B'"):
        p.designs({n: xy[:, i] for i, n in enumerate(m.point_names) if n != "B"})


# -- analyze_designs: each design as kl.analyze analyses it alone ------------------------------
FAMILIES = {
    "fourbar": [kl.mechanisms.fourbar(g, c, k, r, coupler_point=(0.5 * k, 0.3))
                for g, c, k, r in [(3.0, 1.0, 3.0, 2.5), (3.2, 0.9, 2.8, 2.6), (2.9, 1.1, 3.3, 2.4)]],
    "slider_crank": [kl.mechanisms.slider_crank(c, r, offset=e)
                     for c, r, e in [(1.0, 3.0, 0.2), (1.2, 3.5, -0.1), (0.8, 2.5, 0.0)]],
    "inverted_slider_crank": [kl.mechanisms.inverted_slider_crank(g, c, offset=e)
                              for g, c, e in [(2.0, 1.0, 0.3), (2.2, 0.9, 0.2), (1.9, 1.1, 0.4)]],
    "whitworth": [kl.mechanisms.whitworth(*a) for a in [(1.0, 0.5, 1.0, 2.0), (1.1, 0.6, 1.2, 2.2)]],
    "fivebar": [kl.mechanisms.fivebar(*a) for a in [(1.0, 1.0, 1.5, 1.5, 1.0), (1.1, 0.9, 1.6, 1.4, 1.05)]],
}
POSED = ["triad6", "stephenson6", "watt6", "example_crank_rocker", "example_stephenson6",
         "example_jansen", "pyslvs_stephenson_ii", "boom"]


def posed(m, n=3):
    """The mechanism sketched at n inputs near its own: designs of one set of dimensions in
    other poses (their sketches tell the plan other places for the same points)."""
    p = kl.kinematics.plan(m)
    q0 = float(p.q_sketch[0])
    step = 0.1 if p.input_kinds[0] == "angle" else 0.02 * p.scale
    return [m] + [m.at(q0 + step * (i + 1) * (1 if i % 2 else -1)) for i in range(n - 1)]


def family_cases():
    for name, designs in FAMILIES.items():
        yield pytest.param(designs, id=name)
    for name in POSED:
        yield pytest.param(posed(MODELS[name]()), id=f"posed-{name}")


def compare(designs, q, method="auto"):
    base = designs[0]
    xy = np.array([[[pt.x, pt.y] for pt in m.points] for m in designs])
    axes = {j.name: np.array([m.joint(j.name).axis for m in designs])
            for j in base.joints if j.type == "P"}
    M = len(base.inputs)
    qd = np.random.default_rng(1).normal(size=q.shape)
    got = kl.kinematics.analyze_designs(base, xy, q, qd, 0.5, axes=axes, method=method)
    assert got.designs == len(designs) and got.valid.all()
    for d, m in enumerate(designs):
        ref = kl.kinematics.analyze(m, q[d] if q.ndim > (1 if M == 1 else 2) else q, qd[d] if qd.ndim > (1 if M == 1 else 2) else qd,
                                    0.5, method=method, unreachable="mask", at_singular="flag")
        np.testing.assert_array_equal(got.by_design(got.assembled)[d], ref.assembled)
        np.testing.assert_array_equal(got.by_design(got.singular)[d], ref.singular)
        for link in base.link_names:
            for what in ("angle", "omega", "alpha", "K", "L"):
                a, b = getattr(got, what)(link)[d], getattr(ref, what)(link)
                if what == "angle":
                    a, b = np.exp(1j * a), np.exp(1j * b)
                np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9, err_msg=f"{link} {what}")
        for point in base.point_names:
            for what in ("position", "velocity", "acceleration"):
                np.testing.assert_allclose(getattr(got, what)(point)[d], getattr(ref, what)(point),
                                           rtol=1e-9, atol=1e-9 * ref.plan.scale, err_msg=f"{point} {what}")


@pytest.mark.parametrize("designs", list(family_cases()))
def test_designs_analysed_at_once_as_each_alone(designs):
    m = designs[0]
    p = kl.kinematics.plan(m)
    if len(m.inputs) > 1:
        q = p.q_sketch + np.stack(np.meshgrid(np.linspace(-0.1, 0.1, 4), np.linspace(-0.1, 0.1, 3)), -1).reshape(-1, 2)
    else:
        lo, hi = kl.kinematics.reachable_ranges(m)[0]
        q0 = p.q_sketch[0]
        q = q0 + (np.linspace(lo, hi, 37)[1:-1] - q0) * 0.9
    compare(designs, q)


@pytest.mark.parametrize("name", ["fourbar", "slider_crank"])
def test_each_design_its_own_inputs_and_the_newton_engine(name):
    designs = FAMILIES[name]
    q = np.stack([np.linspace(0.1, 6.0, 25) + 0.1 * d for d in range(len(designs))])
    compare(designs, q)
    compare(designs, q, method="newton")


# four-bars whose crank pin meets the rocker's pivot at q = 0: equal arms fold there (a
# change point), unequal ones cannot close; beside an ordinary one, in one call
FOLDING = [kl.mechanisms.fourbar(1.0, 1.0, 1.0, 1.0), kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5),
           kl.mechanisms.fourbar(1.0, 1.0, 1.2, 1.0)]
PAIRED = sorted(n for n in GEARED if len(MODELS[n]().inputs) == 1)     # gears, cams; posed at one input


@pytest.mark.parametrize("name", sorted(FAMILIES) + ["folding"] + [f"posed-{n}" for n in POSED]
                         + [f"posed-{n}" for n in PAIRED])
def test_both_forms_of_the_kernel_agree_on_designs(name):
    """The numpy form evaluates designs together (each number of an operation one value a
    sample); the kernel one after the other: the same statuses, jets and diagnostics."""
    from kinelab.kinematics import _evaluate, _interpreter
    designs = (FOLDING if name == "folding" else FAMILIES[name] if name in FAMILIES
               else posed(MODELS[name.split("-", 1)[1]]()))
    base = designs[0]
    p = kl.kinematics.plan(base)
    numbers = p.designs(np.array([[[pt.x, pt.y] for pt in m.points] for m in designs]))
    M = len(base.inputs)
    n = 20
    q = np.tile(p.q_sketch + 0.05 * np.arange(n)[:, None], (len(designs), 1)).reshape(-1, M)
    if name == "folding":
        q = np.tile(np.arange(-10, 11) * 0.05, len(designs))[:, None]     # q = 0 among them
    a = _evaluate.run_compiled(p, q, np.ones((1, M)), np.zeros((1, M)), designs=numbers)
    b = _interpreter.run(p, q, np.ones((1, M)), np.zeros((1, M)), designs=numbers)
    np.testing.assert_array_equal(a["status"], b["status"])
    failed = a["status"] != 0           # (what a failed sample's jets hold is no output)
    np.testing.assert_allclose(a["jets"][~failed], b["jets"][~failed], rtol=1e-9, atol=1e-9 * p.scale)
    np.testing.assert_allclose(a["diag"], b["diag"], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(a["fail"][failed], b["fail"][failed], rtol=1e-9, atol=1e-12 * p.scale)
    if name == "folding":           # both branches taken: folded, and stuck
        assert failed.any() and not failed.all()
    if p.groups is not None:
        for x, y in zip(a["state"], b["state"]):
            np.testing.assert_allclose(x, y, rtol=1e-9, atol=1e-9 * p.scale)
