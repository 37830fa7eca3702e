"""The forces tab, long work's progress and its cancel, in a real browser (as in
test_browser.py): the input torque the page shows is ``kinelab dynamics`` of the model it
saves; masses typed in the tab reach the model file; a derivation shows its progress and a
click on *cancel* stops the server's work; a matrix wider than the tab scrolls."""
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from kinelab.cli import main
from tests.web.test_browser import browser, page, server, state  # noqa: F401 -- fixtures

ROOT = Path(__file__).resolve().parents[2]
LONG = 180_000      # ms a loaded machine may take for a sweep, a derivation, a download


# the forces shown are of the model shown
FORCES_NOW = ("() => window.kinelab.dynamics && window.kinelab.dynamicsOf === window.kinelab.model"
              " && !window.kinelab.busy")


def open_example(pg, name):
    pg.evaluate("() => { window.studyBefore = window.kinelab.study; }")
    pg.select_option("#open", name)
    pg.wait_for_function(f"() => (window.kinelab.source || '').includes('{name}') "
                         "&& window.kinelab.study && window.kinelab.study !== window.studyBefore "
                         "&& !window.kinelab.draft", timeout=LONG)


def open_forces(pg):
    pg.click("#tabs button[data-tab=forces]")
    pg.wait_for_function(FORCES_NOW, timeout=LONG)


def saved(pg, tmp_path, name="saved.toml") -> Path:
    """The model file the page's *save .toml* writes."""
    with pg.expect_download(timeout=LONG) as download:
        pg.click("#save-toml")
    path = tmp_path / name
    download.value.save_as(path)
    return path


def kinelab_dynamics(path: Path, tmp_path) -> np.ndarray:
    out = tmp_path / "cli"
    r = CliRunner().invoke(main, ["dynamics", str(path), "--out", str(out), "--no-plots"])
    assert r.exit_code == 0, r.output
    return next(out.glob("*_dynamics.csv"))


def test_the_input_torque_is_kinelab_dynamics_of_the_saved_model(page, tmp_path):
    open_example(page, "engine")
    open_forces(page)
    page.fill("#scrub", "40")
    page.wait_for_function("() => window.kinelab.index === 40")
    page.wait_for_selector("#canvas g.forces path[data-force=effort]", state="attached")
    page.shot("forces")
    answer = state(page, "window.kinelab.dynamics")
    table = np.genfromtxt(kinelab_dynamics(saved(page, tmp_path), tmp_path), delimiter=",",
                          names=True)
    torque = np.array(answer["columns"]["crank_angle.torque[N*m]"], float)
    np.testing.assert_allclose(torque, table["crank_angletorqueNm"], rtol=0, atol=1e-9)
    # the value listed and the arrow drawn at the configuration shown are that sample's
    shown = float(page.get_attribute("#forces-now tr[data-effort] td[data-value]", "data-value"))
    assert shown == pytest.approx(table["crank_angletorqueNm"][40], abs=1e-9)
    arc = float(page.get_attribute("#canvas g.forces path[data-force=effort]", "data-value"))
    assert arc == pytest.approx(shown, abs=1e-9)
    assert "τ" in page.text_content("#canvas g.forces")
    # a reaction arrow at each joint, the shaking force at the ground pivot
    drawn = page.eval_on_selector_all("#canvas g.forces line[data-force]",
                                      "ls => ls.map((l) => [l.dataset.force, +l.dataset.value])")
    assert {name for name, _ in drawn} == {"jO2", "jA", "jB", "slide", "shaking"}
    jA = dict(drawn)["jA"]
    assert jA == pytest.approx(np.hypot(table["jAreactionxN"][40], table["jAreactionyN"][40]),
                               rel=1e-9)
    # the plot is the torque against the crank angle, its cursor at the sample shown
    assert page.input_value("#forces-y") == "crank_angle.torque[N*m]"
    assert page.get_attribute("#forces-plot #plot-cursor", "data-index") == "40"


def test_the_forces_table_downloads_as_the_commands_csv(page, tmp_path):
    open_example(page, "engine")
    open_forces(page)
    with page.expect_download(timeout=LONG) as download:
        page.click("#forces-csv")
    assert download.value.suggested_filename == "engine_dynamics.csv"
    path = tmp_path / "page.csv"
    download.value.save_as(path)
    assert path.read_bytes() == kinelab_dynamics(ROOT / "examples" / "engine.toml",
                                                 tmp_path).read_bytes()


def type_in(pg, selector, value):
    field = pg.locator(f"#tab-forces {selector}")
    field.fill(str(value))
    field.press("Enter")


def test_masses_and_loads_typed_in_the_forces_tab(page, tmp_path):
    """The crank-rocker example has no masses: the tab says so; masses, centres of mass (new
    points at the middle of each link), inertias, gravity and a force typed in the tab make
    a model whose forces are again kinelab dynamics' of the file the page saves.  A value
    the loader refuses is said in the page and leaves the model as it was."""
    open_example(page, "crank_rocker")
    page.click("#tabs button[data-tab=forces]")
    page.wait_for_selector("#forces-message.error", timeout=LONG)
    assert "link 'crank': mass: missing" in page.inner_text("#forces-message")
    for link, mass, inertia in (("crank", 0.5, 800.0), ("coupler", 1.5, 12000.0),
                                ("rocker", 1.0, 6000.0)):
        row = f"tr[data-link={link}]"
        type_in(page, f"{row} td[data-field=mass] input", mass)
        page.wait_for_function(f"() => window.kinelab.model.links.find((l) => l.name === '{link}').mass === {mass}",
                               timeout=LONG)
        page.select_option(f"#tab-forces {row} td[data-field=center_of_mass] select", "+ new point")
        page.wait_for_function(f"() => window.kinelab.model.links.find((l) => l.name === '{link}').center_of_mass === 'G_{link}'",
                               timeout=LONG)
        type_in(page, f"{row} td[data-field=inertia] input", inertia)
        page.wait_for_function(f"() => window.kinelab.model.links.find((l) => l.name === '{link}').inertia === {inertia}",
                               timeout=LONG)
    page.click("#forces-standard-gravity")
    page.wait_for_function("() => (window.kinelab.model.dynamics || {}).gravity", timeout=LONG)
    page.click("#forces-add-force")
    page.wait_for_selector("#tab-forces tr[data-force='0']", timeout=LONG)
    type_in(page, "tr[data-force='0'] td[data-field=fx] input", "-20 * cos(q)")
    page.wait_for_function("() => window.kinelab.model.dynamics.forces[0].fx === '-20 * cos(q)'",
                           timeout=LONG)
    page.wait_for_function(FORCES_NOW, timeout=LONG)
    assert len(state(page, "window.kinelab.dynamics.loads.forces")) == 1
    assert page.inner_text("#forces-message") == ""
    page.shot("forces_typed")
    model = state(page, "window.kinelab.model")
    coupler = next(link for link in model["links"] if link["name"] == "coupler")
    assert coupler["center_of_mass"] == "G_coupler" and coupler["local"]["G_coupler"] == [150, 0]
    answer = state(page, "window.kinelab.dynamics")
    table = np.genfromtxt(kinelab_dynamics(saved(page, tmp_path), tmp_path), delimiter=",",
                          names=True)
    np.testing.assert_allclose(np.array(answer["columns"]["crank_angle.torque[N*m]"], float),
                               table["crank_angletorqueNm"], rtol=0, atol=1e-9)
    # a value the loader refuses: said in the page, the model kept
    type_in(page, "tr[data-link=crank] td[data-field=mass] input", -3)
    page.wait_for_selector("#forces-message.error", timeout=LONG)
    assert "mass" in page.inner_text("#forces-message")
    assert state(page, "window.kinelab.model.links[1].mass") == 0.5
    assert page.input_value("#tab-forces tr[data-link=crank] td[data-field=mass] input") == "0.5"


def progress_of_server(pg) -> list[dict]:
    """What the server says it is working on (its jobs, each listed until its work ends)."""
    return pg.evaluate("""async () => (await (await fetch('/api/progress', {method: 'POST',
        headers: {'Content-Type': 'application/json'}, body: '{}'})).json()).jobs""")


def test_a_derivation_shows_its_progress_and_cancel_stops_the_servers_work(page):
    open_example(page, "stephenson6")
    page.click("#tabs button[data-tab=derivation]")
    page.click("#derive")
    job = page.wait_for_selector("#progress .job[data-path='/api/derive']", timeout=LONG)
    assert "deriving" in job.inner_text()
    # the seconds go on, and the server's steps show with the fraction done
    page.wait_for_function("() => parseFloat(document.querySelector("
                           "\"#progress .job[data-path='/api/derive'] .elapsed\").textContent) >= 1.5",
                           timeout=LONG)
    page.wait_for_selector("#progress .job[data-path='/api/derive'] progress:not([hidden])",
                           timeout=LONG)
    page.shot("deriving")
    assert page.inner_text("#progress .job .stage").strip()
    running = [j for j in progress_of_server(page) if j["what"] == "/api/derive"]
    assert len(running) == 1 and running[0]["state"] == "running"
    page.click("#progress .job[data-path='/api/derive'] button.cancel")
    page.wait_for_selector("#progress .job", state="detached", timeout=LONG)
    assert re.match(r"deriving: cancelled after [\d.]+ s", page.inner_text("#status"))
    # the server stopped the work: its job is listed until the work has ended
    page.wait_for_function("""async () => (await (await fetch('/api/progress', {method: 'POST',
        headers: {'Content-Type': 'application/json'}, body: '{}'})).json()).jobs.length === 0""",
                           timeout=LONG, polling=200)
    page.shot("cancelled")
    assert page.locator("#derivation math").count() == 0
    # and the page goes on: a quick request answered, no progress shown for it
    page.fill("#scrub", "30")
    page.wait_for_function("() => window.kinelab.config && window.kinelab.index === 30", timeout=LONG)


def test_a_matrix_wider_than_the_tab_scrolls_sideways(browser, server):  # noqa: F811
    context = browser.new_context(viewport={"width": 760, "height": 700})
    pg = context.new_page()
    try:
        pg.goto(server)
        pg.wait_for_selector("body[data-ready='1']", timeout=LONG)
        pg.click("#tabs button[data-tab=derivation]")
        pg.click("#derive")
        pg.wait_for_selector("#derivation math", timeout=LONG)
        boxes = pg.evaluate("""() => [...document.querySelectorAll('#derivation > div')]
            .filter((d) => d.querySelector('math')).map((d) => ({scroll: d.scrollWidth,
                width: d.clientWidth, math: d.querySelector('math').getBoundingClientRect().width}))""")
        wide = [b for b in boxes if b["scroll"] > b["width"] + 1]
        assert wide, boxes            # the tab is narrow: some matrix is wider
        for b in wide:                # the whole of it can be scrolled to, none cut off
            assert b["math"] == pytest.approx(b["scroll"], abs=1.5), b
        assert pg.evaluate("""() => { const d = [...document.querySelectorAll('#derivation > div')]
            .find((d) => d.scrollWidth > d.clientWidth + 1); d.scrollLeft = 1e6; return d.scrollLeft > 0; }""")
    finally:
        context.close()


def point_on_screen(pg, name):
    box = pg.locator(f"#canvas circle[data-point='{name}']").bounding_box()
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


def test_a_centre_of_mass_and_a_force_placed_on_the_drawing(page):
    """*place* beside a link, then a click half way along the crank: its centre of mass is a
    new point there, in the crank's own frame (50 mm along O2 -> A, to a pixel); *+ force at
    a point of the drawing*, then a click on B: a force at B, to be typed."""
    page.wait_for_function("() => window.kinelab.config !== null", timeout=LONG)
    page.click("#tabs button[data-tab=forces]")
    page.wait_for_selector("#forces-message.error", timeout=LONG)
    (x0, y0), (x1, y1) = point_on_screen(page, "O2"), point_on_screen(page, "A")
    pixel = 100.0 / np.hypot(x1 - x0, y1 - y0)           # mm: the crank is 100 mm
    page.click("#tab-forces tr[data-link=crank] button.place")
    assert "centre of mass of crank" in page.inner_text("#forces-place-hint")
    page.mouse.click((x0 + x1) / 2, (y0 + y1) / 2)
    page.wait_for_function("() => window.kinelab.model.links[1].center_of_mass === 'G_crank'",
                           timeout=LONG)
    crank = state(page, "window.kinelab.model.links[1]")
    assert crank["points"] == ["O2", "A", "G_crank"]
    np.testing.assert_allclose(crank["local"]["G_crank"], [50.0, 0.0], atol=1.5 * pixel)
    assert page.inner_text("#forces-place-hint") == ""
    page.click("#forces-place-force")
    page.mouse.click(*point_on_screen(page, "B"))
    page.wait_for_function("() => ((window.kinelab.model.dynamics || {}).forces || []).length === 1",
                           timeout=LONG)
    assert state(page, "window.kinelab.model.dynamics.forces[0]") == {"point": "B", "fx": 0, "fy": 0}
    assert page.locator("#tab-forces tr[data-force='0']").count() == 1
    # the press went to the forces tab, not to the drawing's tool: nothing was dragged
    assert state(page, "window.kinelab.model.points.B") == state(page, "window.kinelab.study.model.points.B")
