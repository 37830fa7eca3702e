"""Each metric of a four-bar study against an independent computation: Grashof's
inequality, the law of cosines, the engine's limit positions and reachable ranges."""
import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinelab as kl

LINKS = ("ground", "crank", "coupler", "rocker")
length = st.floats(0.2, 5.0)


def table(n, seed=3, lo=0.3, hi=3.0):
    return kl.sweep.random(n, seed=seed, **{k: (lo, hi) for k in LINKS})


@given(st.tuples(length, length, length, length))
def test_grashof_by_the_inequality(lengths):
    g, c, b, r = lengths
    kind = kl.sweep.run("fourbar", {"ground": [g], "crank": [c], "coupler": [b], "rocker": [r]},
                        metrics=("grashof",))["grashof"][0]
    assert kind == kl.mechanisms.grashof(g, c, b, r).kind
    s, l_ = min(lengths), max(lengths)
    p_q = sum(lengths) - s - l_
    if abs((s + l_) - p_q) > 1e-9 * sum(lengths):       # away from change points
        shortest = LINKS[int(np.argmin(lengths))]
        expected = ("triple-rocker" if s + l_ > p_q else
                    {"ground": "double-crank", "crank": "crank-rocker",
                     "coupler": "double-rocker", "rocker": "rocker-crank"}[shortest])
        assert kind == expected


def test_grashof_kinds_at_change_points_and_equal_pairs():
    cases = [(2, 1, 2, 1), (1, 1, 1, 1), (1, 1, 2, 2), (3, 1, 2, 2), (2, 1, 3, 2.0000001)]
    kinds = kl.mechanisms.grashof_kinds(*np.array(cases, float).T)
    assert kinds.tolist() == [kl.mechanisms.grashof(*c).kind for c in cases]
    assert kl.mechanisms.grashof_kinds([1.0, -1.0, np.nan], 1, 1, 1).tolist() == ["change-point", None, None]


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_transmission_against_engine_and_law_of_cosines(branch):
    t = table(40, seed=5)
    fam = kl.sweep.family("fourbar", branch=branch)
    df = kl.sweep.run(fam, t, samples=72, metrics=("assembles", "transmission_min", "transmission_max"))
    q = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    checked = 0
    for (_, row), (_, res) in zip(t.iterrows(), df.iterrows()):
        try:
            fb = kl.mechanisms.fourbar(*row[list(LINKS)], branch=branch)
        except kl.errors.ModelError:        # assembles nowhere
            assert not res["assembles"]
            continue
        assert bool(res["assembles"]) == bool(kl.kinematics.assembly_status(fb, q).assembled.all())
        if not res["assembles"]:
            assert math.isnan(res["transmission_min"]) and math.isnan(res["transmission_max"])
            continue
        sol = kl.analyze(kl.mechanisms.fourbar(*row[list(LINKS)], branch=branch), q)
        mu = kl.kinematics.transmission_angle(sol)
        assert res["transmission_min"] == pytest.approx(mu.min(), abs=1e-10)   # closed form vs engine
        assert res["transmission_max"] == pytest.approx(mu.max(), abs=1e-10)
        # the extremes of mu are at q = 0 and pi (|O4 A| = |ground - crank|, ground + crank)
        g, c, b, r = row[list(LINKS)]
        ends = np.arccos([(b * b + r * r - (g - c) ** 2) / (2 * b * r),
                          (b * b + r * r - (g + c) ** 2) / (2 * b * r)])
        assert res["transmission_min"] == pytest.approx(np.minimum(ends, np.pi - ends).min(), abs=1e-12)
        assert 0 < res["transmission_min"] <= res["transmission_max"] <= np.pi / 2
        checked += 1
    assert checked >= 5


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_time_ratio_and_swing_at_the_engines_limit_positions(branch):
    t = table(60, seed=11)
    df = kl.sweep.run(kl.sweep.family("fourbar", branch=branch), t,
                      metrics=("grashof", "assembles", "time_ratio", "swing"))
    crank_rockers = df.index[df["grashof"] == "crank-rocker"]
    assert len(crank_rockers) >= 3
    for i in crank_rockers:
        fb = kl.mechanisms.fourbar(*t.loc[i, list(LINKS)], branch=branch)
        tr = kl.kinematics.time_ratio(fb, "rocker")           # bisection on the engine's K
        assert df.loc[i, "time_ratio"] == pytest.approx(tr.ratio, rel=1e-9)
        rocker = kl.analyze(fb, q=tr.dead_centres).angle("rocker")
        swing = abs(kl.solvers.wrap_angle(rocker[1] - rocker[0]))
        assert df.loc[i, "swing"] == pytest.approx(swing, abs=1e-9)
    turning = df.index[df["grashof"] == "double-crank"]
    assert (df.loc[turning, "swing"] == 2 * np.pi).all() and df.loc[turning, "time_ratio"].isna().all()
    assert df.loc[~df["assembles"], ["time_ratio", "swing"]].isna().all().all()


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_time_ratio_and_swing_of_crank_rockers_at_the_limit_positions_in_closed_form(branch):
    """The rocker reverses where crank and coupler are in line: O2B = coupler + crank
    (extended) and coupler - crank (folded); the triangle O2 O4 B gives the angle of O2B
    at O2 and of O4B at O4 in both.  The crank turns pi + and pi - their difference between
    them; the rocker swings the difference of its two angles (either branch: mirror images)."""
    rng = np.random.default_rng(5)
    g, c, b, r = rng.uniform(2.0, 3.0, 300), rng.uniform(0.3, 0.9, 300), *rng.uniform(2.0, 3.0, (2, 300))
    df = kl.sweep.run(kl.sweep.family("fourbar", branch=branch),
                      {"ground": g, "crank": c, "coupler": b, "rocker": r},
                      metrics=("grashof", "time_ratio", "swing"), progress=False)
    rocker = df["grashof"].to_numpy() == "crank-rocker"
    assert rocker.sum() >= 200
    at_o2, at_o4 = [], []
    for o2b in (b + c, b - c):
        at_o2.append(np.arccos((g * g + o2b * o2b - r * r) / (2 * g * o2b)))
        at_o4.append(np.arccos((g * g + r * r - o2b * o2b) / (2 * g * r)))
    alpha = np.abs(at_o2[1] - at_o2[0])
    ratio = (np.pi + alpha) / (np.pi - alpha)
    swing = np.abs(at_o4[1] - at_o4[0])
    np.testing.assert_allclose(df["time_ratio"].to_numpy()[rocker], ratio[rocker], rtol=1e-10)
    np.testing.assert_allclose(df["swing"].to_numpy()[rocker], swing[rocker], rtol=1e-10)


def test_generic_dead_centres_against_the_engine():
    """The engine path (one analysis per design) finds the slider's reversals by regula falsi."""
    designs = {"crank": [1.0, 0.5, 0.8], "rod": [3.0, 2.0, 2.5], "offset": [0.0, 0.3, -0.6]}
    df = kl.sweep.run("slider_crank", designs, metrics=("assembles", "time_ratio", "swing"))
    for i in range(3):
        r, l_, e = designs["crank"][i], designs["rod"][i], designs["offset"][i]
        sc = kl.mechanisms.slider_crank(r, l_, e)
        assert df["time_ratio"][i] == pytest.approx(kl.kinematics.time_ratio(sc, "slide").ratio, rel=1e-9)
        stroke = math.sqrt((l_ + r) ** 2 - e * e) - math.sqrt((l_ - r) ** 2 - e * e)
        assert df["swing"][i] == pytest.approx(stroke, abs=1e-10)


def test_reachable_range_against_the_engine():
    t = table(30, seed=2)
    df = kl.sweep.run("fourbar", t, metrics=("assembles", "reachable"))
    some = df.index[~df["assembles"] & df["reachable_from"].notna()]
    assert len(some) >= 3
    for i in some:
        ranges = kl.kinematics.reachable_ranges(kl.mechanisms.fourbar(*t.loc[i, list(LINKS)]))
        lo, hi = df.loc[i, ["reachable_from", "reachable_to"]]
        widths = [b - a for a, b in ranges]
        assert hi - lo == pytest.approx(max(widths), abs=1e-9)
        assert any(abs(math.remainder(lo - a, 2 * math.pi)) < 1e-9 for a, _ in ranges)
    full = df.index[df["assembles"]]
    assert np.allclose(df.loc[full, "reachable_to"] - df.loc[full, "reachable_from"], 2 * np.pi)


def test_user_metric_sees_the_engines_kinematics():
    t = table(12, seed=7)

    def coupler_K_peak(batch):
        return np.max(np.abs(batch.K("coupler")), axis=1)      # NaN where it does not assemble

    def mean_px(batch):
        return np.mean(batch.position("P")[..., 0], axis=1)
    t["coupler_point_along"], t["coupler_point_perpendicular"] = 0.4, 0.3
    df = kl.sweep.run("fourbar", t, metrics={"assembles": "assembles", "kpeak": coupler_K_peak,
                                              "px": mean_px})
    q = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    for i in df.index[df["assembles"]]:
        fb = kl.mechanisms.fourbar(*t.loc[i, list(LINKS)], coupler_point=(0.4, 0.3))
        sol = kl.analyze(fb, q)
        assert df.loc[i, "kpeak"] == pytest.approx(np.abs(sol.K("coupler")).max(), rel=1e-10)
        assert df.loc[i, "px"] == pytest.approx(sol.position("P")[:, 0].mean(), abs=1e-12)


def test_peak_torque_of_a_family_with_masses():
    engine = kl.load("examples/engine.toml")
    fam = kl.sweep.family(engine, output="slide")
    df = kl.sweep.run(fam, {"A.y": [0.05, 0.06]}, metrics=("peak_torque", "swing"), speed=30.0)
    q = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    moved = fam.build({"A.y": 0.06})
    assert moved.point("A").y == 0.06
    tau = kl.dynamics.inverse(moved, q, qd=30.0).input_forces
    assert df["peak_torque"][1] == pytest.approx(np.abs(tau).max(), rel=1e-12)
    assert df["swing"][1] == pytest.approx(2 * 0.06, abs=1e-10)         # crank 60 mm: stroke 120 mm
    assert df["peak_torque"][1] > df["peak_torque"][0]


def test_peak_torque_of_many_designs_at_once_is_each_designs_own():
    # the designs' analyses in one call, their centres of mass where each design puts them:
    # every design's torque as kl.dynamics.inverse gives it for that design alone
    engine = kl.load("examples/engine.toml")
    fam = kl.sweep.family(engine, output="slide")
    rng = np.random.default_rng(3)
    rows = {"A.y": rng.uniform(0.04, 0.07, 12), "G3.x": rng.uniform(0.03, 0.09, 12),
            "G2.y": rng.uniform(0.0, 0.02, 12)}
    rows["A.x"] = np.zeros(12)
    rows["A.x"][5] = 0.15           # crank 250 mm, rod 201 mm: not at every crank angle
    rows["A.y"][5] = 0.2
    df = kl.sweep.run(fam, rows, metrics=("peak_torque",), speed=40.0, progress=False)
    q = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    for d in range(12):
        if d == 5:
            assert np.isnan(df["peak_torque"][d])
            continue
        design = fam.build({c: v[d] for c, v in rows.items()})
        tau = kl.dynamics.inverse(design, q, qd=40.0, reactions=False).input_forces
        assert df["peak_torque"][d] == pytest.approx(np.abs(tau).max(), rel=1e-11)


def test_masses_and_inertias_per_design():
    # a counterweight study: the crank's mass and inertia as columns beside a point; each
    # design's peak torque is that of the model with those masses, and a mass the model
    # would refuse is that row's problem
    engine = kl.load("examples/engine.toml")
    fam = kl.sweep.family(engine, output="slide")
    assert {"crank.mass", "crank.inertia", "rod.mass", "rod.inertia", "slider.mass"} <= set(fam.parameters)
    assert fam.defaults["crank.inertia"] == pytest.approx(0.004)     # 4000 kg mm^2 in the file
    assert (fam.unit("crank.mass"), fam.unit("rod.inertia"), fam.unit("A.y")) == ("kg", "kg m^2", "m")
    rows = {"crank.mass": np.array([1.0, 3.0, 9.0, -2.0]), "crank.inertia": np.array([0.001, 0.004, 0.02, 0.004]),
            "slider.mass": np.array([0.8, 0.5, 2.0, 0.8]), "A.y": np.array([0.05, 0.055, 0.06, 0.05])}
    df = kl.sweep.run(fam, rows, metrics=("peak_torque",), speed=40.0, progress=False)
    q = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    for d in range(3):
        design = fam.build({c: v[d] for c, v in rows.items()})
        assert design.link("crank").mass == rows["crank.mass"][d]
        tau = kl.dynamics.inverse(design, q, qd=40.0, reactions=False).input_forces
        assert df["peak_torque"][d] == pytest.approx(np.abs(tau).max(), rel=1e-11)
    assert np.isnan(df["peak_torque"][3])
    assert "mass" in df.attrs["problems"][3]


def test_descriptors_are_invariant_and_tell_curves_apart():
    t = np.linspace(0, 2 * np.pi, 90, endpoint=False)
    ellipse = np.column_stack([2 * np.cos(t), np.sin(t)])
    shifted = np.roll(ellipse, 17, axis=0) * 3.0 + [1.0, -2.0]
    a, b = kl.sweep.descriptors(np.stack([ellipse, shifted]))
    # the curves are resampled along chords from their first sample: from another start the
    # chords differ by O(h^2), h = 2 pi / 90, times the curvature: a few 1e-6 here
    assert np.abs(a - b).max() < 1e-4
    assert np.allclose(kl.sweep.descriptors(ellipse * 7.0 + 3.0), a, atol=1e-12)   # same start
    circle = np.column_stack([np.cos(t), np.sin(t)])
    c = kl.sweep.descriptors(circle)
    assert c[0] == pytest.approx(1.0, abs=1e-12) and np.linalg.norm(a - c) > 0.1


def _engine_time_ratio(fb):
    """The engine's time ratio and swing, NaN where it says they are not defined."""
    try:
        tr = kl.kinematics.time_ratio(fb, "rocker")
    except (kl.errors.SingularityError, kl.errors.AssemblyError, kl.errors.ModelError):
        return math.nan, math.nan
    rocker = kl.analyze(fb, q=tr.dead_centres).angle("rocker")
    return tr.ratio, abs(kl.solvers.wrap_angle(rocker[1] - rocker[0]))


def change_point_designs(n=40, seed=8):
    """Change-point four-bars (s + l = p + q in floats, or to rounding), crank shortest and
    ground, coupler or rocker longest, with a few plain crank-rockers among them."""
    rng = np.random.default_rng(seed)
    rows = [(2.0, 1.0, 2.0, 3.0), (2.853353864439476, 1.1688947331595825, 4.797067308933343,
                                   3.1126081776534495), (3.0, 1.0, 3.0, 1.0), (3.0, 1.0, 3.0, 2.5)]
    for _ in range(n):
        a = rng.uniform(0.5, 1.5)
        g, b = rng.uniform(a + 0.5, 5.0, 2)
        rows.append((g, a, b, a + b - g) if a + b - g > a else (g, a, b, g + 0.3))
    return {k: [r[i] for r in rows] for i, k in enumerate(LINKS)}


@pytest.mark.parametrize("samples", [72, 73])
def test_change_points_of_a_model_files_four_bars_against_the_engine(samples):
    """The same change-point four-bars as a model's family (its points as columns, through
    the kernel's path): no time ratio or swing where the engine's time_ratio has none, at an
    even number of samples (the change points at samples) and an odd one (between them)."""
    d = change_point_designs()
    mechs = [kl.mechanisms.fourbar(*(d[k][i] for k in LINKS)) for i in range(len(d["ground"]))]
    base = dataclasses.replace(mechs[0], parameters={})
    cols = {f"{p}.{c}": [getattr(m.point(p), c) for m in mechs] for p in ("A", "B", "O4") for c in "xy"}
    df = kl.sweep.run(kl.sweep.family(base, output="rocker"), cols, samples=samples,
                      metrics=("time_ratio", "swing"), progress=False)
    for i, fb in enumerate(mechs):
        ratio, swing = _engine_time_ratio(fb)
        if math.isnan(ratio):
            assert math.isnan(df["time_ratio"][i]) and math.isnan(df["swing"][i]), i
        else:
            assert df["time_ratio"][i] == pytest.approx(ratio, rel=1e-9), i
            assert df["swing"][i] == pytest.approx(swing, abs=1e-9), i


def test_change_points_against_the_engine():
    """A change point is singular (the engine's measure, the transmission angle's sine, below
    SINGULAR_TOL): the sweep assembles where the engine does, and gives no time ratio or
    swing where the engine's time_ratio says they are not defined."""
    d = change_point_designs()
    df = kl.sweep.run("fourbar", d, metrics=("grashof", "assembles", "reachable", "time_ratio", "swing"))
    q = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    singular = 0
    for i in df.index:
        fb = kl.mechanisms.fourbar(*(d[k][i] for k in LINKS))
        status = kl.kinematics.assembly_status(fb, q)
        assert bool(df["assembles"][i]) == bool(status.assembled.all()), i
        if df["assembles"][i]:
            assert df["reachable_to"][i] - df["reachable_from"][i] == 2 * np.pi
        ratio, swing = _engine_time_ratio(fb)
        singular += math.isnan(ratio)
        if math.isnan(ratio):
            assert math.isnan(df["time_ratio"][i]) and math.isnan(df["swing"][i]), i
        else:
            assert df["time_ratio"][i] == pytest.approx(ratio, rel=1e-9)
            assert df["swing"][i] == pytest.approx(swing, abs=1e-9)
    assert singular >= 10 and df["time_ratio"].notna().sum() >= 3
