"""Figures of the graphical methods: what is drawn is the analysis' data, at the scale the
title states, on panels of the stated size."""
import re

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import kinelab as kl  # noqa: E402
from kinelab.errors import SingularityError  # noqa: E402

K = kl.kinematics


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def stated_scale(ax):
    """(value per cm, unit) from the panel's title: '... 1 cm = 0.5 m/s'."""
    match = re.search(r"1 cm = ([0-9.e+-]+) (\S+)$", ax.get_title())
    return float(match.group(1)), match.group(2)


def panel_cm(ax):
    fig = ax.figure
    w, h = fig.get_size_inches()
    box = ax.get_position()
    return box.width * w * 2.54, box.height * h * 2.54


def arrows(ax):
    """{gid: (start, end)} of the arrows drawn with a gid."""
    return {a.get_gid(): (np.array(a.xyann), np.array(a.xy)) for a in ax.texts
            if a.get_gid() and getattr(a, "arrow_patch", None) is not None}


@pytest.mark.parametrize("units, factor", [(None, 1.0), ({"length": "mm"}, 1000.0)])
def test_velocity_polygon_figure_draws_the_data_to_scale(units, factor):
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
                     q=np.radians(40.0), qd=5.0)
    fig = kl.plot.velocity_polygon(sol, units=units)
    ax_m, ax_p = fig.axes
    vp = K.velocity_polygon(sol)
    drawn = arrows(ax_p)
    for p, v in vp.vertices.items():
        if np.linalg.norm(v) > 0:
            start, end = drawn[p]
            np.testing.assert_allclose(start, 0.0, atol=1e-12)
            np.testing.assert_allclose(end, v * factor, rtol=1e-12, atol=1e-9)
    for (p, r), side in vp.sides.items():
        if (p, r) == ("A", "O2") or (p, r) == ("B", "O4"):
            assert f"{p} {r}" not in drawn       # from a point at rest: the absolute arrow
            continue
        start, end = drawn[f"{p} {r}"]
        np.testing.assert_allclose(end - start, side.vector * factor, rtol=1e-12, atol=1e-9)
    for ax in (ax_m, ax_p):
        scale, unit = stated_scale(ax)
        w, h = panel_cm(ax)
        assert w == pytest.approx(kl.plot.PANEL_CM) and h == pytest.approx(kl.plot.PANEL_CM)
        assert np.ptp(ax.get_xlim()) == pytest.approx(kl.plot.PANEL_CM * scale, rel=1e-12)
        assert np.ptp(ax.get_ylim()) == pytest.approx(kl.plot.PANEL_CM * scale, rel=1e-12)
        # every vertex (or point) fits in its panel
    assert stated_scale(ax_p)[1] == ("m/s" if units is None else "mm/s")
    for v in vp.vertices.values():
        x0, x1 = ax_p.get_xlim()
        assert x0 <= v[0] * factor <= x1


def test_acceleration_polygon_figure_draws_every_part_head_to_tail():
    sol = kl.analyze(kl.mechanisms.slotted_link(crank=1.0, distance=2.0), q=np.radians(70.0),
                     qd=3.0, qdd=1.0)
    fig = kl.plot.acceleration_polygon(sol, scale=2.0)
    ap = K.acceleration_polygon(sol)
    drawn = arrows(fig.axes[1])
    assert stated_scale(fig.axes[1]) == (2.0, "m/s²")
    for (p, r), parts in ap.parts.items():
        at = ap.vertex(r)
        for name, vector in parts.items():
            start, end = drawn[f"{p} {r} {name}"]
            np.testing.assert_allclose(start, at, atol=1e-12)
            np.testing.assert_allclose(end - start, vector, atol=1e-12)
            at = end
        np.testing.assert_allclose(at, ap.vertex(p), atol=1e-12)
    labels = {t.get_text() for t in fig.axes[1].texts}
    assert {"$A^c_{AA'}$", "$A^s_{AA'}$", "$A^n_{AO2}$", "$A^t_{AO2}$"} <= labels


def test_instant_centres_figure():
    sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0, offset=0.3), q=1.0)
    fig = kl.plot.instant_centers(sol)
    kc = K.kennedy_construction(sol)
    ax_m, ax_c = fig.axes
    markers = {line.get_gid(): np.array([line.get_xdata()[0], line.get_ydata()[0]])
               for line in ax_m.lines if line.get_gid()}
    for pair, c in kc.centers.items():
        label = kc.label(pair)
        if c.at_infinity:
            start, end = arrows(ax_m)[label]
            d = (end - start) / np.linalg.norm(end - start)
            assert abs(d[0] * c.direction[1] - d[1] * c.direction[0]) < 1e-12
        else:
            np.testing.assert_allclose(markers[label], c.position, atol=1e-12)
    # the circle diagram: one chord per centre, primary ones solid, the others dashed
    chords = {line.get_gid(): line.get_linestyle() for line in ax_c.lines if line.get_gid()}
    assert len(chords) == 6
    assert {chords[kc.label(p)] for p in kc.primary} == {"-"}
    assert {chords[kc.label(s.pair)] for s in kc.steps} == {"--"}


def test_centrodes_figure():
    sol = kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), q=np.linspace(0.0, 2 * np.pi, 73))
    ax = kl.plot.centrodes(sol, "coupler", 10)
    c = K.centrodes(sol, "coupler")
    lines = {line.get_label(): line for line in ax.lines}
    drawn = lines["fixed centrode"].get_xydata()
    kept = np.isfinite(drawn).all(axis=1)
    np.testing.assert_allclose(drawn[kept], c.fixed[kept], atol=1e-12)
    # cut at the drawing's edges: what is kept is inside the view, what is cut outside it
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()

    def inside(xy):
        return (xy[:, 0] >= x0) & (xy[:, 0] <= x1) & (xy[:, 1] >= y0) & (xy[:, 1] <= y1)
    assert kept.any() and inside(drawn[kept]).all() and not inside(c.fixed[~kept]).any()
    leaves = lines["centrodes leave the drawing here (through infinity)"].get_xydata()
    assert len(leaves) >= 2 and inside(leaves).all()
    moving = lines["moving centrode"].get_xydata()
    np.testing.assert_allclose(moving[10], c.fixed[10], atol=1e-12)     # they touch at the centre


def test_derivatives_figure():
    t = np.linspace(0.0, 1.0, 101)
    d = kl.solvers.differentiate(t, np.sin(2 * t))
    fig = kl.plot.derivatives(d, y_label="s", y_unit="mm")
    assert [ax.get_ylabel() for ax in fig.axes] == ["s [mm]", "ds/dt [mm/s]", "d²s/dt² [mm/s²]"]
    np.testing.assert_array_equal(fig.axes[1].lines[0].get_ydata(), d.velocity)


def test_singular_sample_draws_nothing():
    sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 1.0), q=np.array([0.3, np.pi / 2]),
                     at_singular="flag")
    for draw in (kl.plot.velocity_polygon, kl.plot.acceleration_polygon, kl.plot.instant_centers):
        with pytest.raises(SingularityError):
            draw(sol, 1)
    assert not plt.get_fignums()


@pytest.mark.parametrize("span, expected", [(3.7, 0.5), (9.0, 2.0), (20.0, 2.5), (0.004, 0.0005)])
def test_drawing_scale(span, expected):
    assert kl.plot.drawing_scale(span) == expected
    assert span <= kl.plot.PANEL_CM * expected
