"""The construction figures (kl.plot.tangent_construction, velocity_image, kennedy_steps):
each renders, with its numbered steps and the notes' terms, in English and Portuguese."""
from pathlib import Path

import matplotlib
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[2]


def texts(fig) -> list[str]:
    """Every text of the figure once it is drawn: titles, labels, legends, annotations."""
    from matplotlib.text import Text
    fig.canvas.draw()
    return [t.get_text() for t in fig.findobj(Text) if t.get_text()]


def steps(fig) -> list[str]:
    return [t.get_text() for t in fig.texts if (t.get_gid() or "").startswith("steps")]


@pytest.fixture(autouse=True)
def close_figures():
    yield
    import matplotlib.pyplot as plt
    plt.close("all")


def _tangents():
    t = np.linspace(0.0, 2 * np.pi / 10.0, 201)
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=0.1, rod=0.3), q=10.0 * t, qd=10.0)
    return kl.kinematics.tangent_construction(t, sol.slide("slide"), points=10)


@pytest.mark.parametrize("lang, words", [
    ("en", ["tangent", "pole P", "polar distance H", "rays from P parallel to the tangents",
            "numerical derivative"]),
    ("pt", ["tangente", "polo P", "distância polar H", "paralela", "derivada numérica",
            "diferenciação gráfica"]),
])
def test_tangent_construction_figure(lang, words):
    tc = _tangents()
    fig = kl.plot.tangent_construction(tc, lang=lang)
    shown = texts(fig)
    assert [s.split(":")[0] for s in steps(fig)] == ["1", "2", "3", "4", "5"]
    for w in words:
        assert any(w in s for s in shown), (w, shown)
    ax_c, ax_d = fig.axes[:2]
    # every tangent and every ray is drawn; the rays start at the pole
    assert len([ln for ln in ax_c.lines if (ln.get_gid() or "").startswith("tangent")]) == 10
    rays = [ln for ln in ax_d.lines if (ln.get_gid() or "").startswith("ray")]
    assert len(rays) == 10
    for ray, end in zip(rays, tc.rays):
        np.testing.assert_allclose(np.column_stack(ray.get_data()), end)
    # the pole is inside the view, to the left of the origin
    assert ax_d.get_xlim()[0] < tc.pole[0] < tc.origin[0]
    # the right-hand axis reads the derivative: the intercept's scale divided by H
    right = fig.axes[2]
    np.testing.assert_allclose(np.array(right.get_ylim()) * tc.polar_distance, ax_d.get_ylim())


def test_tangent_construction_figure_without_enough_samples_for_the_numerical_one():
    tc = kl.kinematics.tangent_construction(np.arange(6.0), np.arange(6.0) ** 2, points=2)
    fig = kl.plot.tangent_construction(tc)
    assert not any("numerical derivative" in s for s in texts(fig))


@pytest.mark.parametrize("lang, words", [
    ("en", ["velocity image by similar triangles", "triangle abp similar to ABP", "op = V_P",
            "pole o"]),
    ("pt", ["imagem de velocidades por triângulos semelhantes", "triângulo abp semelhante a ABP",
            "op = V_P", "polo o"]),
])
def test_velocity_image_figure(lang, words):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    sol = kl.analyze(fb, q=np.radians(60.0), qd=10.0)
    fig = kl.plot.velocity_image(sol, "coupler", lang=lang)
    assert [s.split(":")[0] for s in steps(fig)] == ["1", "2", "3", "4", "5"]
    assert steps(fig)[:3] == ["1: oa = V_A", "2: ob = V_B", "3: ab = V_BA"]
    shown = texts(fig)
    for w in words:
        assert any(w in s for s in shown), (w, shown)
    # the badges 1-5 are on the polygon, and the triangle abp is the image
    ax_p = fig.axes[1]
    assert sorted(t.get_text() for t in ax_p.texts if (t.get_gid() or "").startswith("badge")) \
        == ["1", "2", "3", "4", "5"]
    tri = next(p for p in ax_p.patches if p.get_gid() == "triangle P")
    vi = kl.kinematics.velocity_image(sol, "coupler")
    np.testing.assert_allclose(tri.get_xy()[:3], [vi.vertices[p] for p in ("A", "B", "P")])


def test_velocity_image_figure_in_the_file_units_and_with_more_points():
    mf = kl.io.ModelFile.read(ROOT / "examples" / "engine.toml")
    sol = kl.analyze(mf.mechanism, q=np.radians(30.0), qd=1.0)
    fig = kl.plot.velocity_image(sol, "crank", units=mf.units)
    assert fig.axes[1].get_xlabel() == f"vx [{mf.units.length}/s]"


@pytest.mark.parametrize("lang, words", [
    ("en", ["primary centres", "Kennedy's theorem", "circle diagram", "instant centres"]),
    ("pt", ["centros primários", "teorema de Kennedy", "diagrama circular",
            "centros instantâneos de rotação"]),
])
def test_kennedy_steps_figure(lang, words):
    mf = kl.io.ModelFile.read(ROOT / "examples" / "crank_rocker.toml")
    sol = kl.analyze(mf.mechanism, q=np.radians(30.0))
    fig = kl.plot.kennedy_steps(sol, units=mf.units, lang=lang)
    assert steps(fig)[1:] == ["1: O13 = (1a) O12-O23 × (1b) O14-O34",
                              "2: O24 = (2a) O12-O14 × (2b) O23-O34"]
    shown = texts(fig)
    for w in words:
        assert any(w in s for s in shown), (w, shown)
    # a row per step: the mechanism with the two numbered lines, the circle diagram
    assert len(fig.axes) == 6
    for row, number in ((1, 1), (2, 2)):
        ax_m, ax_c = fig.axes[2 * row], fig.axes[2 * row + 1]
        gids = [ln.get_gid() for ln in ax_m.lines]
        assert f"line {number}a" in gids and f"line {number}b" in gids
        assert any(t.get_text() == f"{number}a" for t in ax_m.texts)
        # the circle diagram: a side for each centre known so far
        sides = [ln.get_gid() for ln in ax_c.lines if (ln.get_gid() or "").startswith("O")]
        assert len(sides) == 4 + number
    assert len([ln for ln in fig.axes[1].lines if (ln.get_gid() or "").startswith("O")]) == 4


def test_kennedy_steps_with_a_centre_at_infinity():
    mf = kl.io.ModelFile.read(ROOT / "examples" / "slotted_link.toml")
    sol = kl.analyze(mf.mechanism, q=np.radians(60.0))
    fig = kl.plot.kennedy_steps(sol, units=mf.units, lang="pt")
    assert any("no infinito" in s for s in texts(fig))


@pytest.mark.parametrize("draw", ["tangents", "image", "kennedy"])
def test_unknown_language_is_refused(draw):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    sol = kl.analyze(fb, q=0.5, qd=1.0)
    call = {"tangents": lambda: kl.plot.tangent_construction(_tangents(), lang="fr"),
            "image": lambda: kl.plot.velocity_image(sol, "coupler", lang="fr"),
            "kennedy": lambda: kl.plot.kennedy_steps(sol, lang="fr")}[draw]
    with pytest.raises(ModelError, match=r"lang: expected one of 'en', 'pt', got 'fr'"):
        call()
