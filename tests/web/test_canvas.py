"""The canvas as a designer uses it, in Chromium: the wheel zooms about the pointer, a drag
pans, *fit* brings the linkage back, the grid's step follows the zoom and *snap* puts
points on it, a selection is deleted and undone, the units shown change every number shown,
and a link's length is typed on the drawing.  The view never changes the model's numbers.  Screenshots of each state go to the test's temporary folder."""
import math

import pytest

from tests.web.test_browser import browser, page, point_on_screen, server, state  # noqa: F401
from tests.web.test_studio import open_example


def wait_at(pg, name, at, timeout=60_000):
    """Until point `name` is drawn at `at` (screen pixels, to half a pixel)."""
    pg.wait_for_function(
        f"""() => {{ const c = document.querySelector("#canvas circle[data-point='{name}']");
            const r = document.getElementById("canvas").getBoundingClientRect();
            return c && Math.hypot(r.left + +c.getAttribute('cx') - {at[0]},
                                   r.top + +c.getAttribute('cy') - {at[1]}) < 0.5; }}""",
        timeout=timeout)


def tool(pg, name):
    pg.check(f"input[name=tool][value={name}]")


def test_the_wheel_zooms_about_the_pointer_and_the_model_stays(page):
    """A wheel turned with the pointer on O2: O2 stays under the pointer, B moves away from
    it by the zoom's factor, and the model (and its sweep) are the same numbers."""
    open_example(page, "crank_rocker")
    model = state(page, "window.kinelab.model")
    o2, b = point_on_screen(page, "O2"), point_on_screen(page, "B")
    page.mouse.move(*o2)
    page.mouse.wheel(0, -300)
    k = math.exp(300 * 0.0015)
    wait_at(page, "B", (o2[0] + k * (b[0] - o2[0]), o2[1] + k * (b[1] - o2[1])))
    page.shot("zoomed")
    o2z, bz = point_on_screen(page, "O2"), point_on_screen(page, "B")
    assert math.dist(o2z, o2) < 0.5
    assert math.dist(bz, o2z) / math.dist(b, o2) == pytest.approx(k, rel=1e-3)
    assert state(page, "window.kinelab.model") == model
    # out again: smaller than before
    page.mouse.wheel(0, 600)
    wait_at(page, "B", (o2[0] + (b[0] - o2[0]) / k, o2[1] + (b[1] - o2[1]) / k))
    assert math.dist(point_on_screen(page, "B"), o2) < math.dist(b, o2)
    assert state(page, "window.kinelab.model") == model


def test_two_fingers_pinch_zoom_about_their_middle_and_the_model_stays(page):
    """Two touch pointers drawn apart to twice their distance, away from the linkage: the
    drawing grows twice about their middle, which stays put; the model is the same."""
    open_example(page, "crank_rocker")
    model = state(page, "window.kinelab.model")
    o2, b = point_on_screen(page, "O2"), point_on_screen(page, "B")
    box = page.locator("#canvas").bounding_box()
    mid = (box["x"] + 60, box["y"] + box["height"] - 60)
    page.evaluate("""([mx, my]) => {
      const svg = document.getElementById("canvas");
      const send = (kind, id, x, y) => svg.dispatchEvent(new PointerEvent(kind, {
        pointerId: id, pointerType: "touch", isPrimary: id === 1, clientX: x, clientY: y,
        bubbles: true, cancelable: true}));
      send("pointerdown", 1, mx - 20, my);
      send("pointerdown", 2, mx + 20, my);
      for (let k = 1; k <= 10; k++) {            // each finger 20 px further out, in steps
        send("pointermove", 1, mx - 20 - 2 * k, my);
        send("pointermove", 2, mx + 20 + 2 * k, my);
      }
      send("pointerup", 1, mx - 40, my);
      send("pointerup", 2, mx + 40, my);
    }""", list(mid))
    # each step about the fingers' middle, which stays at mid: the zoom is 2 about mid
    expect = lambda p: (mid[0] + 2 * (p[0] - mid[0]), mid[1] + 2 * (p[1] - mid[1]))  # noqa: E731
    wait_at(page, "O2", expect(o2))
    wait_at(page, "B", expect(b))
    page.shot("pinched")
    assert state(page, "window.kinelab.model") == model


@pytest.mark.parametrize("how", ["pan tool", "middle button"])
def test_a_drag_pans_and_fit_brings_the_linkage_back(page, how):
    open_example(page, "crank_rocker")
    model = state(page, "window.kinelab.model")
    names = list(model["points"])
    before = {p: point_on_screen(page, p) for p in names}
    box = page.locator("#canvas").bounding_box()
    start = (box["x"] + 40, box["y"] + box["height"] - 40)      # away from the linkage
    if how == "pan tool":
        tool(page, "pan")
    page.mouse.move(*start)
    page.mouse.down(button="left" if how == "pan tool" else "middle")
    for k in range(1, 11):
        page.mouse.move(start[0] + 6 * k, start[1] - 4 * k)
    page.mouse.up(button="left" if how == "pan tool" else "middle")
    wait_at(page, "B", (before["B"][0] + 60, before["B"][1] - 40))
    page.shot("panned")
    for p in names:
        x, y = point_on_screen(page, p)
        assert (x - before[p][0], y - before[p][1]) == pytest.approx((60, -40), abs=0.5)
    assert state(page, "window.kinelab.model") == model
    page.click("#fit")
    wait_at(page, "B", before["B"])
    for p in names:
        assert point_on_screen(page, p) == pytest.approx(before[p], abs=0.5)


def grid_step(pg):
    return float(pg.get_attribute("#canvas", "data-grid-step"))


def one_two_five(step):
    m = step / 10 ** math.floor(math.log10(step) + 1e-12)
    return any(abs(m - k) < 1e-9 for k in (1, 2, 5))


def on_grid(v, step):
    return abs(v / step - round(v / step)) < 1e-9


def test_the_grid_follows_the_zoom_in_one_two_five_steps(page):
    open_example(page, "crank_rocker")
    step = grid_step(page)
    assert one_two_five(step)
    assert page.locator("#canvas [data-layer=grid] line").count() > 4
    page.mouse.move(*point_on_screen(page, "O2"))
    for _ in range(3):
        page.mouse.wheel(0, -400)
        page.wait_for_timeout(100)
    page.wait_for_function(f"() => +document.getElementById('canvas').dataset.gridStep < {step}")
    page.shot("grid zoomed")
    assert one_two_five(grid_step(page)) and grid_step(page) < step
    page.uncheck("#grid")
    assert page.locator("#canvas [data-layer=grid] line").count() == 0


def test_snap_puts_new_points_on_the_grid_and_on_other_points(page):
    """A new drawing with *snap*: two points placed anywhere land on grid crossings; a link
    from near the first point (not on it) starts at it, no point added."""
    page.click("#new")
    page.check("#snap")
    tool(page, "point")
    box = page.locator("#canvas").bounding_box()
    page.mouse.click(box["x"] + 201.3, box["y"] + 157.7)
    page.wait_for_function("() => Object.keys(window.kinelab.model.points).length === 1")
    step = grid_step(page)
    tool(page, "link")
    p1 = state(page, "window.kinelab.model.points.P1")
    assert all(on_grid(v, step) for v in p1)
    x, y = point_on_screen(page, "P1")
    page.mouse.click(x + 6, y - 5)                      # near P1: the link starts at P1
    page.mouse.click(box["x"] + 330.4, box["y"] + 251.1)
    page.wait_for_function("() => window.kinelab.model.links.length === 2")
    page.shot("snapped link")
    m = state(page, "window.kinelab.model")
    assert sorted(m["points"]) == ["P1", "P2"]
    assert m["links"][1]["points"] == ["P1", "P2"]
    assert all(on_grid(v, step) for v in m["points"]["P2"])


def test_snap_puts_a_new_point_on_a_links_line(page):
    """With *snap*, a point placed a few pixels off a link's line (away from its ends and
    from the grid's crossings) lands on the line."""
    page.click("#new")
    page.check("#snap")
    tool(page, "point")
    box = page.locator("#canvas").bounding_box()
    page.mouse.click(box["x"] + 120.3, box["y"] + 300.7)
    page.wait_for_function("() => Object.keys(window.kinelab.model.points).length === 1")
    tool(page, "link")                                  # from P1 to a new point P2
    page.mouse.click(*point_on_screen(page, "P1"))
    page.mouse.click(box["x"] + 420.4, box["y"] + 141.1)
    page.wait_for_function("() => window.kinelab.model.links.some((l) => l.points.length === 2)")
    tool(page, "point")
    (ax, ay), (bx, by) = point_on_screen(page, "P1"), point_on_screen(page, "P2")
    n = math.hypot(bx - ax, by - ay)
    # 0.37 of the way along P1 P2, 4 px to its side
    page.mouse.click(ax + 0.37 * (bx - ax) - 4 * (by - ay) / n, ay + 0.37 * (by - ay) + 4 * (bx - ax) / n)
    page.wait_for_function("() => Object.keys(window.kinelab.model.points).length === 3")
    page.shot("snapped to a line")
    m = state(page, "window.kinelab.model")
    (new,) = set(m["points"]) - {"P1", "P2"}
    p, a, b = (m["points"][k] for k in (new, "P1", "P2"))
    cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
    ab = math.dist(a, b)
    assert abs(cross) / ab < 1e-6 * ab, (p, a, b)      # on the line P1 P2 (as the page rounds)
    along = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / ab ** 2
    assert along == pytest.approx(0.37, abs=0.02)


def test_an_edit_drag_with_snap_leaves_the_point_on_the_grid(page):
    open_example(page, "crank_rocker")
    page.check("#snap")
    tool(page, "edit")
    step = grid_step(page)
    x, y = point_on_screen(page, "B")
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(x + 3.3 * k, y + 2.1 * k)
    page.mouse.up()
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending && !window.kinelab.narrowed",
                           timeout=120_000)
    page.wait_for_timeout(300)
    page.shot("snapped drag")
    b = state(page, "window.kinelab.model.points.B")
    assert all(on_grid(v, step) for v in b), (b, step)


def test_a_deleted_link_is_gone_and_undo_restores_it(page):
    """The coupler selected and deleted: the four-bar that is left has two moving links and
    one input, which the server refuses with its reason; the drawing stays to be fixed, and
    undo brings the coupler back."""
    open_example(page, "crank_rocker")
    before = state(page, "window.kinelab.model")
    tool(page, "select")
    a, b = point_on_screen(page, "A"), point_on_screen(page, "B")
    page.mouse.click((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
    assert page.text_content("#selection") == "selected: link coupler"
    assert page.locator("#canvas [data-link=coupler].selected").count() == 1
    page.shot("selected")
    page.keyboard.press("Delete")
    try:
        page.wait_for_function("() => !window.kinelab.model.links.some((l) => l.name === 'coupler')",
                               timeout=120_000)
    except Exception:
        pytest.fail("the coupler is still there; selected, focus, status: " + repr(state(
            page, "[window.kinelab.selected, document.activeElement.tagName, "
                  "document.getElementById('status').textContent]")))
    page.wait_for_function("() => document.getElementById('status').classList.contains('error')",
                           timeout=120_000)
    page.shot("deleted")
    m = state(page, "window.kinelab.model")
    assert not any(j for j in m["joints"] if "coupler" in j["links"])
    assert page.text_content("#status").strip()
    page.click("#undo")
    page.wait_for_function("() => window.kinelab.study && window.kinelab.model.links.some((l) => l.name === 'coupler')",
                           timeout=120_000)
    assert state(page, "window.kinelab.model") == before


def test_a_point_clicked_again_selects_its_joint_then_its_input(page):
    open_example(page, "crank_rocker")
    m = state(page, "window.kinelab.model")
    tool(page, "select")
    x, y = point_on_screen(page, "O2")
    joint = next(j["name"] for j in m["joints"] if j["point"] == "O2")
    seen = []
    for _ in range(3):
        page.mouse.click(x, y)
        seen.append(page.text_content("#selection"))
    assert seen == ["selected: point O2", f"selected: joint {joint}",
                    f"selected: input {m['inputs'][0].get('name', joint)}"]
    page.click("#delete")
    page.wait_for_function("() => !(window.kinelab.model.inputs || []).length", timeout=120_000)
    page.shot("input deleted")
    page.keyboard.press("Control+z")
    page.wait_for_function("() => window.kinelab.study && (window.kinelab.model.inputs || []).length === 1",
                           timeout=120_000)


def open_in_metres(pg, tmp_path):
    """The crank-rocker as kinelab holds it, in m and rad (crank 0.1 m), loaded as a file."""
    import json

    import kinelab as kl
    d = kl.load("examples/crank_rocker.toml").to_dict()
    path = tmp_path / "crank_rocker_m.json"
    path.write_text(json.dumps({**d, "schema": 1, "units": {"length": "m", "angle": "rad"}}))
    pg.set_input_files("#load", str(path))
    pg.wait_for_function("() => window.kinelab.source === 'crank_rocker_m.json' && window.kinelab.study "
                         "&& window.kinelab.config !== null", timeout=120_000)


def test_the_unit_switch_shows_a_model_in_metres_in_millimetres(page, tmp_path):
    open_in_metres(page, tmp_path)
    model = state(page, "window.kinelab.model")
    page.select_option("#plot-y", "A.y[m]")
    page.click("#tabs button[data-tab=table]")
    crank = "#tab-table tr[data-link=crank] td[data-field=length] input"
    assert page.input_value(crank) == "0.1"
    assert page.text_content("#canvas [data-dim=crank]") == "0.1 m"
    page.select_option("#unit-length", "mm")
    page.select_option("#unit-angle", "deg")
    page.shot("in mm")
    assert page.input_value(crank) == "100"
    assert page.input_value("#tab-table tr[data-point=A] td[data-field=y] input") == "100"
    assert page.text_content("#canvas [data-dim=crank]") == "100 mm"
    assert page.text_content("#canvas [data-dim=input]").endswith(" deg")
    assert page.text_content("#plot-ylabel") == "A.y[mm]"
    assert "(mm)" in page.text_content("#tab-table")
    assert state(page, "window.kinelab.model") == model
    # a length typed in mm goes into the model in m
    page.fill(crank, "120")
    page.press(crank, "Enter")
    page.wait_for_function("() => window.kinelab.study && window.kinelab.model.links"
                           ".find((l) => l.name === 'crank').length === 0.12", timeout=120_000)
    assert state(page, "window.kinelab.model.units") == {"length": "m", "angle": "rad"}
    page.select_option("#unit-length", "in")
    assert float(page.input_value(crank)) == pytest.approx(120 / 25.4, rel=1e-11)


def test_a_dimension_double_clicked_is_typed_in_place(page):
    """The crank's length typed on the drawing re-assembles the linkage as the table's edit
    does; a coupler too long to close is refused with the reason, the model kept; the input's
    angle typed moves the linkage there."""
    open_example(page, "crank_rocker")
    assert page.text_content("#canvas [data-dim=crank]") == "100 mm"
    page.dblclick("#canvas [data-dim=crank]")
    assert page.input_value("#dim-edit") == "100"
    page.fill("#dim-edit", "110")
    page.press("#dim-edit", "Enter")
    page.wait_for_function("() => window.kinelab.study && window.kinelab.model.links"
                           ".find((l) => l.name === 'crank').length === 110", timeout=120_000)
    page.wait_for_function("() => document.querySelector('#canvas [data-dim=crank]').textContent === '110 mm'",
                           timeout=30_000)
    page.shot("crank typed")
    before = state(page, "window.kinelab.model")
    page.dblclick("#canvas [data-dim=coupler]")
    page.fill("#dim-edit", "5000")
    page.press("#dim-edit", "Enter")
    page.wait_for_function("() => document.getElementById('status').classList.contains('error')",
                           timeout=120_000)
    assert state(page, "window.kinelab.model") == before
    assert page.locator("#dim-edit").count() == 0
    page.dblclick("#canvas [data-dim=input]")
    page.fill("#dim-edit", "90")
    page.press("#dim-edit", "Enter")
    page.wait_for_function("() => window.kinelab.config && Math.abs(window.kinelab.config.q[0] - 90) < 1e-9",
                           timeout=120_000)
    a = state(page, "window.kinelab.config.points.A")
    assert a == pytest.approx([0, 110], abs=1e-9)
    page.shot("input typed")


def test_space_held_pans_and_pressed_alone_plays(page):
    open_example(page, "crank_rocker")
    model = state(page, "window.kinelab.model")
    b = point_on_screen(page, "B")
    box = page.locator("#canvas").bounding_box()
    start = (box["x"] + 40, box["y"] + box["height"] - 40)
    page.mouse.move(*start)
    page.keyboard.down(" ")
    page.mouse.down()
    page.mouse.move(start[0] - 30, start[1] + 20, steps=5)
    page.mouse.up()
    page.keyboard.up(" ")
    wait_at(page, "B", (b[0] - 30, b[1] + 20))
    assert not state(page, "window.kinelab.playing")
    assert state(page, "window.kinelab.model") == model
    page.keyboard.press(" ")
    assert state(page, "window.kinelab.playing")
    page.keyboard.press(" ")
    assert not state(page, "window.kinelab.playing")


def test_the_drawing_exported_leaves_the_grid_out(page, tmp_path):
    open_example(page, "crank_rocker")
    assert page.locator("#canvas [data-layer=grid] line").count() > 0
    with page.expect_download() as d:
        page.select_option("#export", "drawing-svg")
    path = tmp_path / "drawing.svg"
    d.value.save_as(path)
    text = path.read_text()
    assert 'data-link="coupler"' in text and 'data-dim="crank"' in text
    assert 'data-layer="grid"' not in text
