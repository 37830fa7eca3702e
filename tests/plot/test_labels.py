"""Every figure the commands draw, for every example, says what it shows: its titles, axes,
legends, tick labels and annotations in the model's (or task's) units and in the language
asked for (``--lang en|pt``: in Portuguese no English word, decimal commas); and the labels
that used to pile up or be cut are placed where they can be read."""
from __future__ import annotations

import re
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.io import ModelFile
from kinelab.plot._words import WORDS, decimal_commas, number
from tests.synthesis.test_cli import CRANK_ROCKER, LOG10_TASK, NOTES_6_5, NOTES_6_7

matplotlib.use("Agg")

EX = Path(__file__).resolve().parents[2] / "examples"
EXAMPLES = sorted(EX.glob("*.toml"))

# English words that must not be in a Portuguese figure (names from the files apart)
ENGLISH = ["angle", "velocity", "velocities", "acceleration", "accelerations", "position",
           "positions", "path", "polygon", "centre", "centres", "center", "centrode",
           "centrodes", "transmission", "force", "reaction", "reactions", "shaking",
           "moment", "swing", "stroke", "time ratio", "limit", "circle", "travel", "derivatives",
           "smoothed", "data", "estimate", "error", "band", "sample", "lengths", "images",
           "diagram", "the", "of", "and", "through", "fixed", "moving", "input", "efforts",
           "coefficients", "precision", "targets", "points", "curve", "curves", "leave",
           "primary", "tangential", "sliding", "figure", "branch", "valid", "four-bar"]


@pytest.fixture
def drawn(monkeypatch):
    """The figures the command draws, as it closes them: for each, its texts and its
    placed labels' boxes (drawn first, so that the tick labels are laid out)."""
    figures = []
    close = plt.close

    def closing(fig=None):
        if isinstance(fig, matplotlib.figure.Figure):
            fig.canvas.draw()
            figures.append(Drawn(fig))
        return close(fig)
    monkeypatch.setattr(plt, "close", closing)
    return figures


class Drawn:
    """What a figure shows, read from it before it is closed."""

    def __init__(self, fig):
        renderer = fig.canvas.get_renderer()
        self.width, self.height = fig.bbox.width, fig.bbox.height
        self.texts = texts(fig)
        self.axes = []
        for ax in fig.axes:
            labels = [(t.get_text(), t.get_window_extent(renderer)) for t in ax.texts
                      if t.get_text().strip() and t.get_visible()]
            legend = ax.get_legend()
            self.axes.append(dict(
                title=ax.get_title(), xlabel=ax.get_xlabel(), ylabel=ax.get_ylabel(),
                labels=labels, box=ax.get_window_extent(renderer),
                legend=legend.get_window_extent(renderer) if legend else None,
                xlabel_box=ax.xaxis.label.get_window_extent(renderer),
                lines={line.get_label(): line.get_xydata() for line in ax.lines},
                xlim=ax.get_xlim(), ylim=ax.get_ylim()))


def texts(fig) -> list[str]:
    """Every text of ``fig``: titles, axis labels, legends, tick labels, annotations."""
    out = [t.get_text() for t in fig.texts]
    if fig._suptitle is not None:
        out.append(fig._suptitle.get_text())
    for ax in fig.axes:
        out += [ax.get_title(loc) for loc in ("left", "center", "right")]
        out += [ax.get_xlabel(), ax.get_ylabel()]
        out += [t.get_text() for t in (*ax.get_xticklabels(), *ax.get_yticklabels())]
        out += [ax.xaxis.get_offset_text().get_text(), ax.yaxis.get_offset_text().get_text()]
        out += [t.get_text() for t in ax.texts]
        if ax.get_legend() is not None:
            out += [t.get_text() for t in ax.get_legend().get_texts()]
    return [t for t in out if t.strip()]


def run(*args):
    result = CliRunner().invoke(main, [str(a) for a in args])
    assert result.exit_code == 0, result.output
    return result.output


def names_of(path: Path) -> list[str]:
    """The names a model file gives (the model's, its links', points', joints', inputs'):
    kept as they are in every language."""
    m = ModelFile.read(path).mechanism
    names = [m.name, *m.link_names, *m.point_names, *(j.name for j in m.joints),
             *m.input_names]
    return sorted(set(names), key=len, reverse=True)


def without(text: str, names) -> str:
    for name in names:
        text = text.replace(name, " ")
    return text


def english_words(text: str) -> list[str]:
    return [w for w in ENGLISH if re.search(rf"(?<![\w-]){re.escape(w)}(?![\w-])", text,
                                             re.IGNORECASE)]


def assert_portuguese(figures, names=()):
    assert figures
    for fig in figures:
        for text in fig.texts:
            rest = without(text, names)
            assert not english_words(rest), (text, english_words(rest))
            assert not re.search(r"\d\.\d", rest), text          # decimal commas


def assert_units(figures, path: Path):
    """No text names a unit other than the file's: degrees for an angle in degrees, the
    file's length unit for lengths."""
    units = ModelFile.read(path).units
    names = names_of(path)
    for fig in figures:
        for text in fig.texts:
            rest = without(text, names)
            if units.angle == "deg":
                assert not re.search(r"(?<![\w/])rad\b", rest), text
            if units.length != "m":
                assert not re.search(r"\[m\]|\[m/s", rest), text


def overlapping(labels) -> list[tuple[str, str]]:
    return [(a, b) for k, (a, box_a) in enumerate(labels) for b, box_b in labels[k + 1:]
            if box_a.overlaps(box_b)]


def at_value(path: Path) -> str:
    """An input value where every example assembles and is regular: 30 (deg) past the
    start of each input's range."""
    mf = ModelFile.read(path)
    q = np.atleast_1d(mf.sample_inputs(12)[0][1])
    return ",".join(f"{v}rad" for v in q)


# -- every figure of every example, in both languages ----------------------------------------

@pytest.mark.parametrize("lang", ["en", "pt"])
@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_plot_figures(path, lang, drawn, tmp_path):
    run("plot", path, "--samples", "37", "--format", "png", "--lang", lang, "--out", tmp_path)
    units = ModelFile.read(path).units
    w = WORDS[lang]
    assert drawn
    for fig in drawn:
        for ax in fig.axes:
            if ax["xlabel"] and "[" in ax["xlabel"] and not ax["xlabel"].startswith(("x ", "y ")):
                assert ax["xlabel"].endswith(f"[{units.angle}]") or \
                    ax["xlabel"].endswith(f"[{units.length}]"), ax["xlabel"]
    ylabels = [ax["ylabel"] for fig in drawn for ax in fig.axes]
    assert f"{w['transmission angle']} [{units.angle}]" in ylabels or \
        not any("transmission" in t or "transmiss" in t for f in drawn for t in f.texts)
    assert_units(drawn, path)
    if lang == "pt":
        assert_portuguese(drawn, names_of(path))


@pytest.mark.parametrize("lang", ["en", "pt"])
@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_polygon_and_centre_figures(path, lang, drawn, tmp_path):
    at = at_value(path)
    run("polygons", path, "--at", at, "--lang", lang, "--out", tmp_path)
    run("centres", path, "--at", at, "--lang", lang, "--out", tmp_path)
    assert len(drawn) == 3
    units = ModelFile.read(path).units
    velocity, acceleration, centres = drawn
    v_unit = units.unit("m/s")
    a_unit = units.unit("m/s^2").replace("^2", "²")
    assert velocity.axes[1]["xlabel"] == f"vx [{v_unit}]"
    assert f"1 cm = " in velocity.axes[1]["title"] and velocity.axes[1]["title"].endswith(v_unit)
    assert acceleration.axes[1]["ylabel"] == f"ay [{a_unit}]"
    assert acceleration.axes[1]["title"].endswith(a_unit)
    assert centres.axes[0]["xlabel"] == f"x [{units.length}]"
    # the labels of the mechanism, the polygons and the centres cover none of the others
    for ax in (*velocity.axes[:2], *acceleration.axes[:2], centres.axes[0]):
            assert not overlapping(ax["labels"]), (path.stem, overlapping(ax["labels"]))
    # the parts' legend is beside the acceleration polygon, not on it
    legend = acceleration.axes[1]["legend"]
    assert legend is None or not legend.overlaps(acceleration.axes[1]["box"])
    assert_units(drawn, path)
    polygon_title = velocity.axes[1]["title"]
    if lang == "pt":
        assert polygon_title.startswith("polígono de velocidades")
        assert acceleration.axes[1]["title"].startswith("polígono de acelerações")
        assert centres.axes[1]["title"].startswith("diagrama circular")
        assert_portuguese(drawn, names_of(path))
    else:
        assert polygon_title.startswith("velocity polygon")


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_animation(lang, drawn, tmp_path):
    path = EX / "jansen.toml"       # the most links: the longest legend
    run("animate", path, "--samples", "9", "--frames", "2", "--format", "gif", "--velocities",
        "--centres", "--lang", lang, "--out", tmp_path)
    (fig,) = drawn
    ax = fig.axes[0]
    # the legend is below the drawing, inside the figure: it covers nothing of the mechanism
    assert ax["legend"] is not None and not ax["legend"].overlaps(ax["box"])
    assert ax["legend"].y0 >= 0 and ax["legend"].y1 < ax["box"].y0
    assert not ax["legend"].overlaps(ax["xlabel_box"])
    assert_units(drawn, path)
    if lang == "pt":
        assert_portuguese(drawn, names_of(path))
        assert any(t.startswith("velocidades: 1 cm = ") and "," in t for t in fig.texts)


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_dynamics_figures(lang, drawn, tmp_path):
    path = EX / "engine.toml"
    out = run("dynamics", path, "--samples", "37", "--lang", lang, "--out", tmp_path)
    efforts, reactions, shaking = drawn
    torque = "input torque" if lang == "en" else "torque na entrada"
    assert efforts.axes[0]["ylabel"] == f"{torque} [N m]"
    crank = "crank angle" if lang == "en" else "ângulo da manivela (crank angle)"
    assert efforts.axes[0]["xlabel"] == f"{crank} [deg]"          # the input, its unit
    for fig in drawn:        # nothing cut at the figure's edges
        for ax in fig.axes:
            box = ax["xlabel_box"]
            if ax["xlabel"]:
                assert box.x0 >= 0 and box.y0 >= 0 and box.x1 <= fig.width, ax["xlabel"]
    assert_units(drawn, path)
    if lang == "pt":
        assert_portuguese(drawn, names_of(path))
        assert re.search(r"\|esforço\| máximo \d+,\d+ N m", out)
        assert not re.search(r"\d\.\d", out.split("wrote")[0])
        # the table keeps the decimal point
        table = (tmp_path / "engine_dynamics.csv").read_text()
        row = table.splitlines()[1].split(",")
        assert len(row) == len(table.splitlines()[0].split(",")) and [float(v) for v in row]


def test_dynamics_files_are_named_after_the_model_file(tmp_path):
    text = (EX / "engine.toml").read_text().replace('name = "engine"', 'name = "my engine"', 1)
    path = tmp_path / "v8.toml"
    path.write_text(text)
    run("dynamics", path, "--samples", "9", "--out", tmp_path / "out")
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [
        "v8_dynamics.csv", "v8_efforts.png", "v8_reactions.png", "v8_shaking.png"]


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_differentiate_figure(lang, drawn, tmp_path):
    t = np.linspace(0.0, 1.0, 41)
    data = tmp_path / "cam.csv"
    data.write_text("t [s],s [mm]\n" + "\n".join(f"{a:.6f},{np.sin(3 * a):.6f}" for a in t))
    run("differentiate", data, "--lang", lang, "--out", tmp_path)
    (fig,) = drawn
    assert [ax["ylabel"] for ax in fig.axes] == ["s [mm]", "ds/dt [mm/s]", "d²s/dt² [mm/s²]"]
    if lang == "pt":
        assert_portuguese(drawn)


TASKS = {"crank-rocker": CRANK_ROCKER, "three positions": NOTES_6_5,
         "four positions": NOTES_6_7, "function": LOG10_TASK}


@pytest.mark.parametrize("lang", ["en", "pt"])
@pytest.mark.parametrize("task", TASKS, ids=list(TASKS))
def test_synthesis_figures(task, lang, drawn, tmp_path):
    path = tmp_path / "task.toml"
    path.write_text(TASKS[task])
    run("synth", path, "--lang", lang, "--out", tmp_path / "out")
    assert drawn
    units = kl.io.load_task(path).units
    for fig in drawn:
        for ax in fig.axes:
            if ax["xlabel"].startswith("x ["):
                assert ax["xlabel"] == f"x [{units.length}]"
    if units.angle == "deg":
        assert not any(re.search(r"(?<![\w/])rad\b", t) for f in drawn for t in f.texts)
    if lang == "pt":
        assert_portuguese(drawn, ["A0", "B0", "P"])


# -- each mislabel fixed ---------------------------------------------------------------------

def test_synth_titles_a_crank_rocker_in_the_tasks_degrees(drawn, tmp_path):
    """Its swing was titled in radians ("swing 0.785 rad") for a task in degrees."""
    path = tmp_path / "task.toml"
    path.write_text(CRANK_ROCKER)
    run("synth", path, "--out", tmp_path / "out")
    (fig,) = drawn
    title = fig.axes[0]["title"]
    assert "swing 45 deg" in title and "min transmission" in title and "rad" not in title
    mu = float(re.search(r"min transmission ([\d.]+) deg", title).group(1))
    assert 10 < mu < 90
    run("synth", path, "--out", tmp_path / "si", "--si")
    assert "swing 0.7854 rad" in drawn[-1].axes[0]["title"]


def test_dynamics_torque_axis_says_torque():
    """Its torque axis was labelled with the input's name, "crank angle [N m]"."""
    res = ModelFile.read(EX / "engine.toml").inverse_dynamics(19)
    fig = kl.plot.effort_curves(res, degrees=True)
    assert fig.axes[0].get_ylabel() == "input torque [N m]"
    assert fig.axes[0].get_xlabel() == "crank angle [deg]"
    assert fig.get_layout_engine() is not None        # constrained: the x label is not cut
    plt.close(fig)


def test_acceleration_polygon_labels_do_not_pile_up_at_the_pole():
    """Short parts near the pole had their labels drawn on top of one another."""
    sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
    fig = kl.plot.acceleration_polygon(kl.analyze(sl, q=np.radians(60.0), qd=3.0))
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    labels = [(t.get_text(), t.get_window_extent(renderer)) for t in fig.axes[1].texts
              if t.get_text().strip()]
    assert len(labels) >= 6 and not overlapping(labels)
    every = ", ".join(t for t, _ in labels)
    for part in ("$A^n_{A'O4}$", "$A^t_{A'O4}$", "$A^c_{AA'}$", "$A^s_{AA'}$"):
        assert part in every
    plt.close(fig)


def test_centre_labels_do_not_overlap():
    """"O24 (2)" and "O12" were written over each other at a four-bar's crank pin."""
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    for q in np.radians([0.0, 60.0, 150.0, 270.0]):
        fig = kl.plot.instant_centers(kl.analyze(fb, q=q))
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        labels = [(t.get_text(), t.get_window_extent(renderer)) for t in fig.axes[0].texts
                  if t.get_text().strip()]
        assert not overlapping(labels)
        every = ", ".join(t for t, _ in labels)
        assert "O12" in every and "O24 (2)" in every and "O13 (1)" in every
        plt.close(fig)


def test_centrodes_keep_to_the_drawing():
    """Centrodes ran off to infinity and swamped the figure: they are cut at its edges."""
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    sol = kl.analyze(fb, q=np.linspace(0.0, 2 * np.pi, 145))
    ax = kl.plot.centrodes(sol, "coupler", 20)
    pts = np.array([sol.position(p)[20] for p in sol.point_names])
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    size = np.ptp(pts, axis=0).max()
    assert x1 - x0 < 2.5 * size and y1 - y0 < 2.5 * size     # the mechanism fills the view
    for line in ax.lines:
        xy = line.get_xydata()
        xy = xy[np.isfinite(xy).all(axis=1)]
        assert ((xy[:, 0] >= x0) & (xy[:, 0] <= x1) & (xy[:, 1] >= y0) & (xy[:, 1] <= y1)).all()
    notes = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "centrodes leave the drawing here (through infinity)" in notes
    plt.close(ax.figure)


def test_animation_legend_covers_nothing(tmp_path, drawn):
    run("animate", EX / "crank_rocker.toml", "--samples", "9", "--frames", "2", "--format",
        "gif", "--out", tmp_path)
    ax = drawn[0].axes[0]
    assert not ax["legend"].overlaps(ax["box"])


# -- the words and the numbers ---------------------------------------------------------------

def test_both_languages_have_every_word():
    assert WORDS["en"].keys() == WORDS["pt"].keys()
    for key, text in WORDS["en"].items():
        # the same fields, filled by name: in the order each language puts its words
        assert sorted(re.findall(r"\{\w+\}", text)) == sorted(re.findall(r"\{\w+\}",
                                                                          WORDS["pt"][key])), key


def test_decimal_commas_in_tick_labels():
    fig, ax = plt.subplots()
    ax.plot([0.0, 1.0], [0.0, 0.5])
    decimal_commas(fig, "pt")
    fig.canvas.draw()
    ticks = [t.get_text() for t in ax.get_yticklabels()]
    assert "0,5" in ticks and not any("." in t for t in ticks)
    plt.close(fig)
    assert number(0.25, "g", "pt") == "0,25" and number(0.25, "g", "en") == "0.25"


@pytest.mark.parametrize("lang", [None, "fr", 1])
def test_a_language_not_known_is_refused(lang):
    sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=np.linspace(0, np.pi, 5))
    with pytest.raises(kl.errors.ModelError, match=r"^lang: expected 'en' or 'pt', got "):
        kl.plot.curves(sol, ["slide"], lang=lang)


def test_lang_option_refuses_other_languages(tmp_path):
    result = CliRunner().invoke(main, ["plot", str(EX / "crank_rocker.toml"), "--lang", "fr",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 2 and "--lang" in result.output


# -- the summaries the drawing commands print ------------------------------------------------

def test_polygons_and_centres_print_in_portuguese_with_decimal_commas(tmp_path):
    path = EX / "slotted_link.toml"
    polygons = run("polygons", path, "--at", "60", "--lang", "pt", "--out", tmp_path)
    assert polygons.startswith("slotted link (Erthal): polígono de velocidades [mm/s]")
    assert "polígono de acelerações [mm/s^2]" in polygons
    assert "  V_A      -272,07    157,08  314,159" in polygons
    centres = run("centres", path, "--at", "60", "--lang", "pt", "--out", tmp_path)
    assert "centros instantâneos de rotação [mm]" in centres
    assert "no infinito  direção (-0,3273; 0,9449)" in centres
    for out in (polygons, centres):
        table = out.split("wrote")[0]
        assert not re.search(r"\d\.\d", table)
        assert not english_words(without(table, names_of(path) + ["Kennedy"]))
    english = run("centres", path, "--at", "60", "--out", tmp_path)
    assert "at infinity  direction (-0.3273, 0.9449)" in english


def test_differentiate_prints_in_portuguese(tmp_path):
    t = np.linspace(0.0, 1.0, 41)
    data = tmp_path / "cam.csv"
    data.write_text("t [s],s [mm]\n" + "\n".join(f"{a:.6f},{np.sin(3 * a):.6f}" for a in t))
    out = run("differentiate", data, "--lang", "pt", "--out", tmp_path)
    assert out.startswith("cam.csv: 41 amostras de s em função de t; ruído cerca de ")
    assert "validação cruzada generalizada" in out and "0,7 das " in out
    assert not re.search(r"\d\.\d", out.split("wrote")[0].replace("cam.csv", ""))
    table = (tmp_path / "cam_derivatives.csv").read_text().splitlines()
    assert [float(v) for v in table[1].split(",")]      # the table keeps the decimal point


def test_synth_prints_in_portuguese_with_decimal_commas(tmp_path):
    path = tmp_path / "task.toml"
    path.write_text(NOTES_6_5)
    out = run("synth", path, "--lang", "pt", "--out", tmp_path / "pt")
    assert out.startswith("task: geração de movimento, 1 mecanismo(s)")
    assert "A1 (3,5477; -1,6546) B1 (0,9941; 3,2382) m" in out
    assert "ângulo de transmissão mín. 0,779 rad (atende ao limite de 0,524 rad)" in out
    assert out.rstrip().endswith("manivela-balancim, válido\nescreveu 4 arquivo(s) em "
                                 f"{tmp_path / 'pt'}")
    assert not re.search(r"\d\.\d", out)
    english = run("synth", path, "--out", tmp_path / "en")
    assert "A1 (3.5477, -1.6546) B1 (0.9941, 3.2382) m, min transmission 0.779 rad (meets the " \
           "0.524 rad limit), crank-rocker, valid" in english
    # the files are the same in both languages but for the figures' words
    assert (tmp_path / "pt" / "summary.json").read_text() == \
        (tmp_path / "en" / "summary.json").read_text()


def test_the_crank_is_named_in_portuguese_on_the_x_axis(drawn, tmp_path):
    run("plot", EX / "crank_rocker.toml", "--samples", "37", "--format", "png", "--lang", "pt",
        "--out", tmp_path)
    motion = drawn[0]
    assert motion.axes[-1]["xlabel"] == "ângulo da manivela (crank angle) [deg]"
    assert motion.axes[0]["ylabel"] == "ângulo [deg]"      # of several links, named in the legend
    sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=np.linspace(0, np.pi, 7))
    fig = kl.plot.curves(sol, ["slide"], lang="pt", degrees=True)
    assert fig.axes[-1].get_xlabel() == "ângulo de entrada (jO2) [deg]"
    plt.close(fig)
