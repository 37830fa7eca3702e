"""The page in a real browser (Debian's Chromium, headless, driven by Playwright), acting as
a person does: open, drag, type, switch the branch, play, export.  Screenshots of each
state go to the test's temporary folder."""
import json
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from tests.web.models import assert_same_model

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM_FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update",
                  "--disable-sync"]


def chromium() -> str | None:
    found = os.environ.get("KINELAB_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")
    return found if found and Path(found).exists() else None


@pytest.fixture(scope="module")
def browser():
    path = chromium()
    if path is None:
        if os.environ.get("CI"):
            pytest.fail("no Chromium: .ci/run installs Debian's chromium; the browser tests must run in CI")
        pytest.skip("no Chromium found (apt-get install chromium, or set KINELAB_CHROMIUM)")
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=path, args=CHROMIUM_FLAGS)
        yield b
        b.close()


@pytest.fixture(scope="module")
def server():
    """``kinelab serve --port 0``: the command itself, on loopback, its address read from
    what it prints."""
    command = [sys.executable, "-c", "from kinelab.cli import main; main()", "serve", "--port", "0"]
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            cwd=ROOT)
    try:
        line = proc.stdout.readline()
        match = re.search(r"serving at (http://127\.0\.0\.1:\d+/)", line)
        assert match, line + proc.stdout.read() if proc.poll() is not None else line
        yield match.group(1)
    finally:
        proc.terminate()
        proc.wait(timeout=20)


@pytest.fixture
def page(browser, server, tmp_path):
    context = browser.new_context(viewport={"width": 1300, "height": 820}, accept_downloads=True)
    pg = context.new_page()
    pg.requests = []
    pg.errors = []
    pg.on("request", lambda r: pg.requests.append(r.url))
    pg.on("pageerror", lambda e: pg.errors.append(str(e)))
    pg.goto(server)
    pg.wait_for_selector("body[data-ready='1']", timeout=180_000)
    pg.shot = lambda name: pg.screenshot(path=str(tmp_path / f"{name}.png"))
    yield pg
    assert not pg.errors, pg.errors
    context.close()


def state(pg, expression):
    return pg.evaluate(f"() => {expression}")


def point_on_screen(pg, name):
    box = pg.locator(f"#canvas circle[data-point='{name}']").bounding_box()
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


def test_the_page_loads_everything_from_the_server_itself(page, server):
    page.shot("loaded")
    assert page.locator("#canvas .link").count() >= 4
    assert page.locator("#canvas .trace").count() == 1
    assert "crank_rocker.toml" in page.inner_text("#title")
    assert page.requests and all(u.startswith(server) or u.startswith(("data:", "blob:"))
                                 for u in page.requests), page.requests
    assert all(u.startswith("http://127.0.0.1:") for u in page.requests if u.startswith("http"))


def lengths(points):
    d = lambda a, b: math.dist(points[a], points[b])      # noqa: E731
    return {"crank": d("O2", "A"), "coupler": d("A", "B"), "rocker": d("O4", "B"),
            "AP": d("A", "P"), "BP": d("B", "P")}


def test_dragging_a_point_moves_the_linkage_and_keeps_its_lengths(page):
    page.wait_for_function("() => window.kinelab.config !== null")
    before = state(page, "window.kinelab.config.points")
    x, y = point_on_screen(page, "B")
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 11):
        page.mouse.move(x - 12 * k, y + 9 * k)
    page.mouse.up()
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending")
    page.wait_for_timeout(200)
    page.shot("dragged")
    after = state(page, "window.kinelab.config.points")
    assert math.dist(before["B"], after["B"]) > 5        # mm: it moved
    for name, length in lengths(before).items():
        assert lengths(after)[name] == pytest.approx(length, rel=1e-12), name
    assert lengths(after)["coupler"] == pytest.approx(300, rel=1e-12)
    # the drawing shows it
    cx, cy = point_on_screen(page, "B")
    assert math.hypot(cx - x, cy - y) > 5


def test_editing_a_joint_changes_the_coupler_curve(page):
    page.check("input[name=tool][value=edit]")
    trace = page.get_attribute("#canvas .trace", "points")
    x, y = point_on_screen(page, "O4")
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(x + 4 * k, y - 2 * k)
    page.mouse.up()
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending")
    page.shot("edited")
    assert page.get_attribute("#canvas .trace", "points") != trace
    model = state(page, "window.kinelab.model")
    O4 = model["points"]["O4"]
    assert O4 != [300.0, 0.0]
    ground = next(link for link in model["links"] if link["name"] == "ground")
    assert ground["length"] == pytest.approx(math.hypot(*O4), rel=1e-12)
    page.click("#undo")
    page.wait_for_function("() => window.kinelab.model.points.O4[0] === 300")


def test_typing_a_length_re_assembles_the_linkage(page):
    page.click("#tabs button[data-tab=table]")
    field = page.locator("#tab-table tr[data-link=rocker] td[data-field=length] input")
    field.fill("270")
    field.press("Enter")
    page.wait_for_function("() => window.kinelab.model.links[3].length === 270")
    page.wait_for_timeout(300)
    page.shot("typed")
    s = state(page, "window.kinelab.study")
    B = np.array([s["columns"]["B.x[mm]"], s["columns"]["B.y[mm]"]]).T
    assert np.allclose(np.hypot(*(B - [300.0, 0.0]).T), 270, rtol=1e-12, atol=0)


def test_switching_the_branch(page):
    page.click("#tabs button[data-tab=table]")
    y_before = state(page, "window.kinelab.model.points.B[1]")
    page.click("#tab-table button[data-step]")
    page.wait_for_function(f"() => window.kinelab.model.points.B[1] * {y_before} < 0")
    page.shot("switched")
    pts = state(page, "window.kinelab.model.points")
    assert math.dist(pts["A"], pts["B"]) == pytest.approx(300, rel=1e-12)
    assert math.dist(pts["O4"], pts["B"]) == pytest.approx(250, rel=1e-12)


def test_the_plot_cursor_follows_the_animation_and_a_click_moves_the_linkage(page):
    page.click("#play")
    page.wait_for_function("() => window.kinelab.frames > 10")
    page.click("#play")
    page.shot("played")
    index = state(page, "window.kinelab.index")
    assert index > 0
    assert page.get_attribute("#plot-cursor", "data-index") == str(index)
    s = state(page, "window.kinelab.study")
    # the cursor is where the plot puts that sample's input
    box = page.locator("#plot").bounding_box()
    page.mouse.click(box["x"] + box["width"] * 0.75, box["y"] + box["height"] / 2)
    page.wait_for_function(f"() => window.kinelab.index !== {index}")
    picked = state(page, "window.kinelab.index")
    assert page.get_attribute("#plot-cursor", "data-index") == str(picked)
    q = s["columns"][s["inputs"][0]][picked]
    assert 200 < q < 340          # three quarters along an axis from 0 to 360 deg
    assert "deg" in page.text_content("#plot-xlabel") and "[" in page.text_content("#plot-ylabel")


def test_the_exported_csv_is_kinelab_analyze(page, tmp_path):
    from click.testing import CliRunner

    from kinelab.cli import main
    with page.expect_download() as download:
        page.select_option("#export", "csv")
    path = tmp_path / "page.csv"
    download.value.save_as(path)
    r = CliRunner().invoke(main, ["analyze", str(ROOT / "examples" / "crank_rocker.toml"), "--out",
                                  str(tmp_path / "cli.csv"), "-q"])
    assert r.exit_code == 0, r.output
    page_rows = np.genfromtxt(path, delimiter=",", names=True)
    cli_rows = np.genfromtxt(tmp_path / "cli.csv", delimiter=",", names=True)
    assert page_rows.dtype.names == cli_rows.dtype.names
    for name in cli_rows.dtype.names:
        assert np.allclose(page_rows[name], cli_rows[name], rtol=1e-12, atol=1e-12, equal_nan=True), name


def test_the_derivation_is_typeset(page):
    page.click("#tabs button[data-tab=derivation]")
    page.click("#derive")
    page.wait_for_selector("#derivation math", timeout=120_000)
    page.shot("derivation")
    assert page.locator("#derivation math").count() >= 6
    box = page.locator("#derivation math").first.bounding_box()
    assert box["height"] > 10         # laid out as maths, not as raw text


def test_a_refused_drag_keeps_the_last_good_configuration(page):
    page.click("#tabs button[data-tab=table]")
    field = page.locator("#tab-table tr[data-link=rocker] td[data-field=length] input")
    field.fill("10")
    field.press("Enter")
    page.wait_for_selector("#status.error")
    page.shot("refused")
    assert "rocker" in page.inner_text("#status")
    assert state(page, "window.kinelab.model.links[3].length") == 250
    # the table shows the model's value again, not the one refused
    assert page.locator("#tab-table tr[data-link=rocker] td[data-field=length] input").input_value() == "250"


def test_lengths_and_pivots_typed_in_the_table_re_assemble_at_the_crank_angle(page):
    """A coupler of 100 mm closes at the drawn crank angle (90 deg: A stays at (0, 100));
    one of 10 mm does not (A is 316.228 mm from O4, coupler and rocker reach 240 to 260 mm)
    and is refused, the table keeping 100; a pivot moved in the table keeps the lengths."""
    page.click("#tabs button[data-tab=table]")

    def cell(row, field):
        return page.locator(f"#tab-table tr[{row}] td[data-field={field}] input")
    cell("data-link=coupler", "length").fill("100")
    cell("data-link=coupler", "length").press("Enter")
    page.wait_for_function("() => window.kinelab.model.links[2].length === 100 && !window.kinelab.busy")
    points = state(page, "window.kinelab.model.points")
    assert points["A"] == [0, 100]
    assert math.dist(points["A"], points["B"]) == pytest.approx(100, rel=1e-12)
    assert math.dist(points["O4"], points["B"]) == pytest.approx(250, rel=1e-12)
    cell("data-link=coupler", "length").fill("10")
    cell("data-link=coupler", "length").press("Enter")
    page.wait_for_selector("#status.error")
    page.shot("refused coupler")
    text = page.inner_text("#status")
    assert "misses by 56.2278 mm" in text and "\n" not in text.strip()
    assert state(page, "window.kinelab.model.links[2].length") == 100
    assert cell("data-link=coupler", "length").input_value() == "100"
    cell("data-point=O4", "x").fill("320")
    cell("data-point=O4", "x").press("Enter")
    page.wait_for_function("() => window.kinelab.model.points.O4[0] === 320 && !window.kinelab.busy")
    page.shot("pivot moved")
    after = state(page, "window.kinelab.model.points")
    assert after["A"] == [0, 100]
    for a, b, length in (("A", "B", 100), ("O4", "B", 250)):
        assert math.dist(after[a], after[b]) == pytest.approx(length, rel=1e-12)


def test_synthesize_a_crank_rocker_and_open_it(page, tmp_path):
    from click.testing import CliRunner

    from kinelab.cli import main
    from kinelab.io import ModelFile
    page.click("#tabs button[data-tab=synthesis]")
    page.select_option("#synth-kind", "crank-rocker")
    page.fill("[data-field='crank_rocker.swing']", "40")
    page.fill("[data-field='crank_rocker.time_ratio']", "1.2")
    page.click("#synth-solve")
    page.wait_for_selector("#synth-results tr[data-solution='1']", timeout=60_000)
    page.shot("synthesized")
    row = page.inner_text("#synth-results tr[data-solution='1']")
    assert "crank-rocker" in row and "swing 40 deg" in row and "time ratio 1.2" in row
    # the same task through kinelab synth
    task = tmp_path / "task.toml"
    task.write_text('task = "crank-rocker"\nunits = { length = "mm", angle = "deg" }\n'
                    '[crank_rocker]\nground = 100\nswing = 40\ntime_ratio = 1.2\n')
    r = CliRunner().invoke(main, ["synth", str(task), "--out", str(tmp_path / "out"), "--no-figures"])
    assert r.exit_code == 0, r.output
    written = ModelFile.read(tmp_path / "out" / "solution_1.toml")
    page.click("#synth-results tr[data-solution='1'] button.open-solution")
    page.wait_for_function("() => (window.kinelab.source || '').includes('solution_1')")
    page.wait_for_function("() => window.kinelab.config !== null")
    page.shot("opened")
    assert_same_model(ModelFile.from_dict(state(page, "window.kinelab.model")), written)
    assert page.locator("#canvas .link").count() >= 4
    # drawn and swept as any model: the rocker swings 40 deg over the cycle (361 samples)
    s = state(page, "window.kinelab.study")
    rocker = np.unwrap(np.radians(s["columns"]["rocker.angle[deg]"]))
    assert np.degrees(rocker.max() - rocker.min()) == pytest.approx(40.0, abs=0.05)
    # and it moves: the animation plays
    page.click("#play")
    page.wait_for_function("() => window.kinelab.frames > 5")
    page.click("#play")
    assert state(page, "window.kinelab.index") > 0


def polygon_lines(pg, kind):
    return pg.evaluate(f"""() => [...document.querySelectorAll("svg[data-polygon={kind}] line")]
        .map((l) => [l.dataset.side, +l.getAttribute("x1"), +l.getAttribute("y1"),
                     +l.getAttribute("x2"), +l.getAttribute("y2")])""")


def test_the_polygons_show_and_follow_the_input(page):
    page.click("#tabs button[data-tab=method]")
    page.wait_for_selector("svg[data-polygon=acceleration] line", state="attached")
    page.shot("polygons")
    config = state(page, "window.kinelab.config")
    velocity = polygon_lines(page, "velocity")
    # an arrow from the pole for every moving point, a side V_BA for the coupler
    assert {"A", "B", "P"} <= {side for side, *_ in velocity}
    assert "B A" in {side for side, *_ in velocity}
    text = page.inner_text("#polygons")
    assert "velocity polygon (mm/s, from the pole OV)" in text
    # the arrows are drawn to one scale: their screen lengths are in the ratio of |V|
    v = config["polygons"]["velocity"]["vertices"]
    length = {side: math.hypot(x2 - x1, y2 - y1) for side, x1, y1, x2, y2 in velocity}
    assert length["B"] / length["A"] == pytest.approx(math.hypot(*v["B"]) / math.hypot(*v["A"]), rel=1e-3)
    parts = {side.split()[-1] for side, *_ in polygon_lines(page, "acceleration") if " " in side}
    assert parts == {"normal", "tangential"}
    # the input moves: the polygons change with it
    page.fill("#scrub", "90")
    page.wait_for_function(f"() => window.kinelab.config && window.kinelab.config.q[0] !== {config['q'][0]}")
    page.wait_for_timeout(100)
    page.shot("polygons_moved")
    assert polygon_lines(page, "velocity") != velocity
    moved = state(page, "window.kinelab.config")
    v = moved["polygons"]["velocity"]["vertices"]
    length = {side: math.hypot(x2 - x1, y2 - y1) for side, x1, y1, x2, y2 in polygon_lines(page, "velocity")}
    assert length["B"] / length["A"] == pytest.approx(math.hypot(*v["B"]) / math.hypot(*v["A"]), rel=1e-3)


def test_the_acceleration_polygon_of_a_slotted_link_shows_coriolis(page):
    page.select_option("#open", "slotted_link")
    page.wait_for_function("() => (window.kinelab.source || '').includes('slotted_link')")
    page.click("#tabs button[data-tab=method]")
    page.fill("#scrub", "60")             # the crank at 60 deg: the lever turns, the slider slides
    page.wait_for_function("""() => [...document.querySelectorAll("svg[data-polygon=acceleration] line")]
        .some((l) => (l.dataset.side || '').endsWith('coriolis'))""")
    page.shot("coriolis")
    assert "AcAA@lever" in page.text_content("svg[data-polygon=acceleration]")   # A^c_{A A@lever}


def model_to_screen(pg):
    """The drawing's map from model units to the page's pixels, read off two ground pivots
    of the crank-rocker example (O2 at (0, 0), O4 at (300, 0) mm)."""
    (x0, y0), (x1, _) = point_on_screen(pg, "O2"), point_on_screen(pg, "O4")
    scale = (x1 - x0) / 300.0
    return lambda x, y: (x0 + scale * x, y0 - scale * y)


def test_three_poses_placed_on_the_drawing_are_synthesized_and_inserted(page):
    from kinelab.io import ModelFile
    page.wait_for_function("() => window.kinelab.config !== null")
    page.click("#tabs button[data-tab=synthesis]")
    page.select_option("#synth-kind", "three")
    to_screen = model_to_screen(page)
    page.click("#synth-place")
    assert page.input_value("#synth-length") == "mm" and page.input_value("#synth-angle") == "deg"
    aimed = [(100, 100, 0), (200, 50, 0), (300, 150, 45)]        # mm, deg: the notes' task x 100
    for x, y, angle in aimed:
        X, Y = to_screen(x, y)
        page.mouse.move(X, Y)
        page.mouse.down()
        for k in range(1, 7):                  # the drag gives the angle
            page.mouse.move(X + 10 * k * math.cos(math.radians(angle)),
                            Y - 10 * k * math.sin(math.radians(angle)))
        page.mouse.up()
    page.wait_for_selector("#canvas g.pose[data-pose='3']", state="attached")
    page.shot("poses_placed")
    assert page.locator("#canvas g.pose").count() == 3
    poses = np.array([[float(v) for v in line.split()]
                      for line in page.input_value("#synth-poses").strip().splitlines()])
    assert poses.shape == (3, 3)
    # where the mouse went, to a pixel; the angles to the drag's pixel rounding
    pixel = 1.0 / ((point_on_screen(page, "O4")[0] - point_on_screen(page, "O2")[0]) / 300.0)
    np.testing.assert_allclose(poses[:, :2], np.array(aimed)[:, :2], atol=1.5 * pixel)
    np.testing.assert_allclose(poses[:, 2], np.array(aimed)[:, 2], atol=2.0)
    # editable in the form afterwards: the arrow follows the typed angle
    lines = page.input_value("#synth-poses").strip().splitlines()
    x3, y3, _ = lines[2].split()
    lines[2] = f"{x3} {y3} 45"
    page.fill("#synth-poses", "\n".join(lines))
    poses[2, 2] = 45.0
    page.fill("[data-field='pivots.A0']", "500, 0")
    page.fill("[data-field='pivots.B0']", "0, 0")
    page.click("#synth-solve")
    page.wait_for_selector("#synth-results tr[data-solution='1']", timeout=60_000)
    page.click("#synth-results tr[data-solution='1'] button.open-solution")
    page.wait_for_function("() => (window.kinelab.source || '').includes('solution_1')")
    page.wait_for_function("() => window.kinelab.config !== null")
    page.shot("poses_inserted")
    # the model the page holds, moved by kinelab through the three poses (SI once read)
    m = ModelFile.from_dict(state(page, "window.kinelab.model")).mechanism
    points, angles = poses[:, :2] / 1000.0, np.radians(poses[:, 2])
    sol = kl.synthesis.three_positions(points, angles, (0.5, 0.0), (0.0, 0.0))
    s = kl.analyze(m, q=sol.q)
    np.testing.assert_allclose(s.position("P"), points, rtol=0, atol=1e-9)
    turned = np.unwrap(s.angle("coupler")) - np.unwrap(angles)
    np.testing.assert_allclose(turned - turned[0], 0.0, atol=1e-9)


def type_in_table(pg, selector, value):
    field = pg.locator(f"#tab-table {selector} input")
    field.fill(str(value))
    field.press("Enter")


def test_a_slider_crank_drawn_from_scratch_is_kinelabs_slider_crank(page):
    """Points, links (R joints where they meet), a slider on a guide (P joint), the ground and
    the input, all drawn; the exact coordinates and lengths typed in the table.  The sweep the
    page shows is that of ``kl.mechanisms.slider_crank`` with the same lengths."""
    page.wait_for_function("() => window.kinelab.config !== null")
    to_screen = model_to_screen(page)
    page.click("#new")
    page.wait_for_function("() => window.kinelab.model.name === 'sketch'")
    crank, rod = 100.0, 300.0
    O2, A, B = (0.0, 0.0), (0.0, crank), (math.sqrt(rod**2 - crank**2), 0.0)
    page.check("input[name=tool][value=link]")
    for k, xy in enumerate((O2, A), 1):
        page.mouse.click(*to_screen(*xy))
        page.wait_for_selector(f"#canvas circle[data-point=P{k}]", state="attached")
    page.mouse.click(*point_on_screen(page, "P2"))
    page.mouse.click(*to_screen(*B))
    page.wait_for_function("() => window.kinelab.model.links.length === 3")
    page.check("input[name=tool][value=slider]")
    X, Y = point_on_screen(page, "P3")
    page.mouse.move(X, Y)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(X + 12 * k, Y)
    page.mouse.up()
    page.wait_for_function("() => window.kinelab.model.joints.some((j) => j.type === 'P')")
    page.check("input[name=tool][value=ground]")
    page.mouse.click(*point_on_screen(page, "P1"))
    page.check("input[name=tool][value=input]")
    page.mouse.click(*point_on_screen(page, "P1"))
    page.wait_for_function("() => window.kinelab.study !== null && !window.kinelab.draft")
    page.shot("slider_crank_drawn")
    model = state(page, "window.kinelab.model")
    assert [j["type"] for j in model["joints"]].count("P") == 1
    assert [j["type"] for j in model["joints"]].count("R") == 3
    slide = next(j for j in model["joints"] if j["type"] == "P")
    assert slide["links"][0] == "ground" and slide["point"] == "P3"
    assert slide["axis"] == [1, 0]                       # a horizontal drag
    assert page.locator("#canvas rect.joint.P").count() == 1
    # exact values typed in the table: coordinates first, then the lengths
    page.click("#tabs button[data-tab=table]")
    for point, axis, v in (("P1", "x", O2[0]), ("P1", "y", O2[1]), ("P3", "y", B[1])):
        type_in_table(page, f"tr[data-point={point}] td[data-field={axis}]", v)
        page.wait_for_function(f"() => window.kinelab.model.points.{point}[{'xy'.index(axis)}] === {v}")
    for link, length in (("link1", crank), ("link2", rod)):
        type_in_table(page, f"tr[data-link={link}] td[data-field=length]", length)
        page.wait_for_function(f"() => window.kinelab.model.links.find((l) => l.name === '{link}').length === {length}")
    page.wait_for_function("() => !window.kinelab.draft && window.kinelab.study.model.links[1].length === 100")
    page.shot("slider_crank_typed")
    s = state(page, "window.kinelab.study")
    # the input drawn turns once a second (360 deg/s), shown in the table
    assert s["model"]["inputs"][0]["speed"] == 360
    assert page.input_value("#tab-table td[data-field=speed] input") == "360"
    q = np.radians(s["columns"][s["inputs"][0]])
    sc = kl.analyze(kl.mechanisms.slider_crank(crank / 1000, rod / 1000), q=q, qd=2 * np.pi)
    for mine, theirs in (("P2", "A"), ("P3", "B")):
        drawn = np.array([s["columns"][f"{mine}.x[mm]"], s["columns"][f"{mine}.y[mm]"]]).T
        np.testing.assert_allclose(drawn, 1000 * sc.position(theirs), rtol=0, atol=1e-9)
    np.testing.assert_allclose(np.radians(s["columns"]["link2.angle[deg]"]), sc.angle("rod"), rtol=0, atol=1e-12)
    np.testing.assert_allclose(s["columns"]["link2.omega[deg/s]"], np.degrees(sc.omega("rod")), rtol=1e-9, atol=1e-9)


def test_a_guide_turned_in_the_table_carries_the_slider_along_it(page):
    page.select_option("#open", "offset_slider_crank")
    page.wait_for_function("() => (window.kinelab.source || '').includes('offset_slider_crank')")
    page.click("#tabs button[data-tab=table]")
    type_in_table(page, "tr[data-joint=slide] td[data-field=axis]", 10)
    page.wait_for_function("""() => { const a = window.kinelab.model.joints.find((j) => j.name === 'slide').axis;
                                      return Math.abs(Math.atan2(a[1], a[0]) * 180 / Math.PI - 10) < 1e-9; }""")
    page.shot("guide_turned")
    s = state(page, "window.kinelab.study")
    B0 = np.array(s["model"]["points"]["B"])
    B = np.array([s["columns"]["B.x[mm]"], s["columns"]["B.y[mm]"]]).T
    A = np.array([s["columns"]["A.x[mm]"], s["columns"]["A.y[mm]"]]).T
    along = np.array([np.cos(np.radians(10)), np.sin(np.radians(10))])
    across = along[0] * (B - B0)[:, 1] - along[1] * (B - B0)[:, 0]
    np.testing.assert_allclose(across, 0.0, atol=1e-9)                        # on the guide
    assert np.ptp((B - B0) @ along) > 90                                     # and sliding
    np.testing.assert_allclose(np.hypot(*(B - A).T), 200.0, rtol=1e-12)


def columns_xy(study, point):
    u = study["units"]["length"]
    return np.array([study["columns"][f"{point}.x[{u}]"], study["columns"][f"{point}.y[{u}]"]]).T


def test_typing_the_sides_of_a_coupler_point_places_it_by_the_law_of_cosines(page):
    """The example's coupler point P (given by its local place) typed in the table as 200 mm
    from A and 150 mm from B, right of A -> B: over the whole sweep P is where the law of
    cosines puts it."""
    page.click("#tabs button[data-tab=table]")
    row = "tr[data-of-link=coupler][data-link-point=P]"
    assert page.input_value(f"#tab-table {row} td[data-field=from1] select") == "A"
    assert page.input_value(f"#tab-table {row} td[data-field=from2] select") == "B"
    type_in_table(page, f"{row} td[data-field=distance1]", 200)
    page.wait_for_function("() => ((window.kinelab.model.links[2].sides || {}).P || {}).A === 200")
    type_in_table(page, f"{row} td[data-field=distance2]", 150)
    page.wait_for_function("() => window.kinelab.model.links[2].sides.P.B === 150")
    page.select_option(f"#tab-table {row} td[data-field=side] select", "right")
    page.wait_for_function("() => window.kinelab.model.links[2].sides.P.side === 'right'")
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending")
    page.shot("sides_typed")
    coupler = state(page, "window.kinelab.model.links[2]")
    assert coupler["sides"] == {"P": {"A": 200, "B": 150, "side": "right"}}
    assert "P" not in coupler.get("local", {})          # one way per point
    s = state(page, "window.kinelab.study")
    A, B, P = (columns_xy(s, p) for p in "ABP")
    # the law of cosines, by hand: along = (200² - 150² + 300²) / (2 x 300) = 179.1667 mm from
    # A towards B, and 88.878 mm = sqrt(200² - 179.1667²) to the right of A -> B
    along = (200**2 - 150**2 + 300**2) / (2 * 300)
    right = math.sqrt(200**2 - along**2)
    assert (along, right) == pytest.approx((179.16666666666666, 88.87803), rel=1e-6)
    e = (B - A) / 300.0
    np.testing.assert_allclose(np.hypot(*(B - A).T), 300.0, rtol=1e-12)
    np.testing.assert_allclose(P, A + along * e - right * np.stack([-e[:, 1], e[:, 0]], -1),
                               rtol=0, atol=1e-9)
    page.wait_for_function(f"() => document.querySelector('#tab-table {row} .now-sides').textContent === '200, 150'")


def test_dragging_a_point_given_by_its_sides_keeps_them_measured(page):
    """With the edit tool, P (given by its sides, typed in the table) dragged away: its sides
    become its new distances from A and B, and the linkage keeps them over the sweep."""
    page.wait_for_function("() => window.kinelab.config !== null")
    page.click("#tabs button[data-tab=table]")
    type_in_table(page, "tr[data-of-link=coupler][data-link-point=P] td[data-field=distance1]", 180)
    page.wait_for_function("() => ((window.kinelab.model.links[2].sides || {}).P || {}).A === 180")
    page.wait_for_function("() => window.kinelab.config !== null")     # drawn where it is now
    page.check("input[name=tool][value=edit]")
    x, y = point_on_screen(page, "P")
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(x + 6 * k, y + 4 * k)      # down and to the right: towards A -> B
    page.mouse.up()
    page.wait_for_function("() => window.kinelab.model.links[2].sides.P.A !== 180")
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending")
    # the drag's narrowed sweep is followed by the whole one once the drag has ended
    page.wait_for_function("() => 'A.x[mm]' in window.kinelab.study.columns"
                           " && window.kinelab.study.model === window.kinelab.model")
    page.shot("sides_dragged")
    sides = state(page, "window.kinelab.model.links[2].sides.P")
    pts = state(page, "window.kinelab.model.points")
    assert sides["side"] == "left"
    assert sides["A"] == pytest.approx(math.dist(pts["A"], pts["P"]), rel=1e-9)
    assert sides["B"] == pytest.approx(math.dist(pts["B"], pts["P"]), rel=1e-9)
    assert abs(sides["A"] - 180) > 1                                     # mm: it moved
    s = state(page, "window.kinelab.study")
    A, B, P = (columns_xy(s, p) for p in "ABP")
    np.testing.assert_allclose(np.hypot(*(P - A).T), sides["A"], rtol=1e-12)
    np.testing.assert_allclose(np.hypot(*(P - B).T), sides["B"], rtol=1e-12)
