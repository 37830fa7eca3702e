"""The synthesis task on the drawing, in Chromium: the pivots of a three-position task and
the points of a path placed by clicks and dragged, a placed pose dragged (its angle kept),
Esc cancelling a placing.  The form holds what the mouse did, in the task's units; the
drawing shows it.  Screenshots of each state go to the test's temporary folder."""
import numpy as np
import pytest

from tests.web.test_browser import browser, page, point_on_screen, server, state  # noqa: F401

POSES_MM = "100 100 0\n200 50 0\n300 150 45"        # the notes' three positions x 100


def view(pg):
    """The drawing's map from model units to the page's pixels and back, and a pixel's size
    in model units (the crank-rocker example, in mm)."""
    left, top, s, ox, oy = pg.evaluate("""() => {
        const r = document.getElementById("canvas").getBoundingClientRect(), v = window.kinelab.canvas.view;
        return [r.left, r.top, v.s, v.ox, v.oy]; }""")
    to_screen = lambda x, y: (left + ox + s * x, top + oy - s * y)          # noqa: E731
    to_model = lambda X, Y: ((X - left - ox) / s, (oy - (Y - top)) / s)     # noqa: E731
    return to_screen, to_model, 1.0 / s


def synthesis(pg, kind):
    pg.wait_for_function("() => window.kinelab.config !== null")
    pg.click("#tabs button[data-tab=synthesis]")
    pg.select_option("#synth-kind", kind)
    assert state(pg, "window.kinelab.model.units.length") == "mm"


def numbers(text):
    return [float(v) for v in text.replace(",", " ").split()]


def lines(pg):
    return [numbers(line) for line in pg.input_value("#synth-poses").strip().splitlines()]


def drag(pg, start, by, steps=8):
    x, y = start
    pg.mouse.move(x, y)
    pg.mouse.down()
    for k in range(1, steps + 1):
        pg.mouse.move(x + by[0] * k / steps, y + by[1] * k / steps)
    pg.mouse.up()


def centre(pg, selector):
    box = pg.locator(selector).bounding_box()
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


def test_the_pivots_of_three_positions_are_placed_and_dragged_on_the_drawing(page):
    """A0 and B0 placed by clicks, B0 then dragged: the fields hold where the mouse went
    (to a pixel), and the linkage solved and opened has its fixed pivots there."""
    synthesis(page, "three")
    page.select_option("#synth-length", "mm")
    page.fill("#synth-poses", POSES_MM)
    to_screen, to_model, pixel = view(page)
    aimed = {"pivots.A0": (260, -80), "pivots.B0": (-40, 20)}           # mm
    for key, xy in aimed.items():
        page.click(f"button[data-place='{key}']")
        assert "click its place" in page.inner_text(f"[data-hint='{key}']")
        page.mouse.click(*to_screen(*xy))
        assert page.inner_text(f"[data-hint='{key}']") == ""
    page.wait_for_selector("#canvas g.target.fixed[data-target='pivots.B0']", state="attached")
    page.shot("pivots_placed")
    for key, xy in aimed.items():
        np.testing.assert_allclose(numbers(page.input_value(f"[data-field='{key}']")), xy, atol=1.5 * pixel)
    assert page.locator("#canvas g.target.fixed").count() == 2
    assert page.text_content("#canvas g.target[data-target='pivots.A0']") == "A0"
    # dragged by its mark: the field follows the mouse
    before = numbers(page.input_value("[data-field='pivots.B0']"))
    drag(page, centre(page, "#canvas [data-target='pivots.B0'] circle.handle"), (40, -30))
    after = numbers(page.input_value("[data-field='pivots.B0']"))
    np.testing.assert_allclose(np.subtract(after, before), (40 * pixel, 30 * pixel), atol=1.5 * pixel)
    X, Y = centre(page, "#canvas [data-target='pivots.B0'] circle.handle")
    np.testing.assert_allclose(to_model(X, Y), after, atol=1.5 * pixel)
    page.shot("pivot_dragged")
    a0, b0 = (numbers(page.input_value(f"[data-field='{k}']")) for k in ("pivots.A0", "pivots.B0"))
    page.click("#synth-solve")
    page.wait_for_selector("#synth-results tr[data-solution='1']", timeout=60_000)
    page.click("#synth-results tr[data-solution='1'] button.open-solution")
    page.wait_for_function("() => (window.kinelab.source || '').includes('solution_1')")
    page.wait_for_function("() => window.kinelab.config !== null")
    page.shot("pivots_solved")
    model = state(page, "window.kinelab.model")
    assert model["units"]["length"] == "mm"
    ground = next(link for link in model["links"] if link.get("ground"))
    assert ground["points"] == ["O2", "O4"]
    np.testing.assert_allclose(model["points"]["O2"], a0, rtol=0, atol=1e-6)
    np.testing.assert_allclose(model["points"]["O4"], b0, rtol=0, atol=1e-6)


def test_the_points_of_a_path_are_placed_drawn_and_dragged(page):
    synthesis(page, "path")
    assert page.locator("#canvas g.target.point").count() == 5       # the example's, in m: drawn too
    to_screen, to_model, pixel = view(page)
    aimed = [(0, 150), (80, 200), (160, 220), (240, 200), (320, 150)]   # mm
    page.fill("#synth-place-count", "5")
    page.click("#synth-place")
    assert page.input_value("#synth-length") == "mm"
    assert page.input_value("#synth-poses") == ""
    for k, xy in enumerate(aimed, 1):
        assert f"point {k} of 5" in page.inner_text("#synth-place-hint")
        page.mouse.click(*to_screen(*xy))
    assert page.inner_text("#synth-place-hint") == ""
    page.shot("path_placed")
    placed = lines(page)
    np.testing.assert_allclose(placed, aimed, atol=1.5 * pixel)
    assert page.locator("#canvas g.target.point").count() == 5
    assert page.locator("#canvas polyline.target-path").count() == 1
    assert [page.text_content(f"#canvas g.target[data-target='point {k}']") for k in range(1, 6)] == list("12345")
    for k, xy in enumerate(placed, 1):            # each drawn where the form has it
        X, Y = centre(page, f"#canvas [data-target='point {k}'] circle.handle")
        np.testing.assert_allclose(to_model(X, Y), xy, atol=1.5 * pixel)
    # a sixth click places nothing: the five are placed
    page.mouse.click(*to_screen(400, 100))
    assert lines(page) == placed
    # point 3 dragged: it alone moves, by the mouse's move
    drag(page, centre(page, "#canvas [data-target='point 3'] circle.handle"), (-25, 45))
    page.shot("path_point_dragged")
    moved = lines(page)
    assert moved[:2] == placed[:2] and moved[3:] == placed[3:]
    np.testing.assert_allclose(np.subtract(moved[2], placed[2]), (-25 * pixel, -45 * pixel), atol=1.5 * pixel)
    X, Y = centre(page, "#canvas [data-target='point 3'] circle.handle")
    np.testing.assert_allclose(to_model(X, Y), moved[2], atol=1.5 * pixel)
    # the task solved as typed: the points the form holds
    page.fill("[data-field='search.maxiter']", "5")
    page.click("#synth-solve")
    page.wait_for_selector("#synth-results tr[data-solution='1']", timeout=120_000)


def test_a_placed_pose_is_dragged_by_its_point_and_keeps_its_angle(page):
    synthesis(page, "three")
    to_screen, to_model, pixel = view(page)
    page.click("#synth-place")
    for x, y, angle in ((100, 100, 0), (200, 50, 0), (300, 150, 45)):
        X, Y = to_screen(x, y)
        drag(page, (X, Y), (60 * np.cos(np.radians(angle)), -60 * np.sin(np.radians(angle))), steps=6)
    page.wait_for_selector("#canvas g.pose[data-pose='3']", state="attached")
    text = page.input_value("#synth-poses").strip().splitlines()
    placed = lines(page)
    assert len(placed) == 3
    np.testing.assert_allclose(np.array(placed)[:, 2], (0, 0, 45), atol=2.0)
    line = page.locator("#canvas g.pose[data-pose='3'] line")
    ends = [float(line.get_attribute(k)) for k in ("x1", "y1", "x2", "y2")]
    drag(page, centre(page, "#canvas g.pose[data-pose='3'] circle.handle"), (-50, 35))
    page.shot("pose_dragged")
    after = page.input_value("#synth-poses").strip().splitlines()
    assert after[:2] == text[:2]
    moved = numbers(after[2])
    assert after[2].split()[2] == text[2].split()[2]                     # the angle's very text
    np.testing.assert_allclose(np.subtract(moved[:2], placed[2][:2]), (-50 * pixel, -35 * pixel), atol=1.5 * pixel)
    # the arrow moved with its point, its direction kept
    moved_ends = [float(line.get_attribute(k)) for k in ("x1", "y1", "x2", "y2")]
    np.testing.assert_allclose(np.subtract(moved_ends[2:], moved_ends[:2]), np.subtract(ends[2:], ends[:2]), atol=1e-6)
    np.testing.assert_allclose(np.subtract(moved_ends[:2], ends[:2]), (-50, 35), atol=1.5)
    assert page.locator("#canvas g.pose").count() == 3


def test_escape_cancels_a_placing_and_another_tab_or_task_stops_it(page):
    synthesis(page, "path")
    to_screen, _, _ = view(page)
    typed = page.input_value("#synth-poses")
    page.click("#synth-place")
    page.mouse.click(*to_screen(50, 50))
    page.mouse.click(*to_screen(150, 80))
    assert len(lines(page)) == 2
    page.shot("path_before_escape")
    page.keyboard.press("Escape")
    page.shot("path_escaped")
    # the form as before the placing: its points and its units
    assert page.input_value("#synth-poses") == typed
    assert page.input_value("#synth-length") == "m"
    assert page.inner_text("#synth-place-hint") == ""
    assert page.locator("#canvas g.target.point").count() == 5
    page.mouse.click(*to_screen(250, 80))
    assert page.input_value("#synth-poses") == typed
    # a pivot's placing, cancelled
    page.select_option("#synth-kind", "three")
    page.click("button[data-place='pivots.A0']")
    page.keyboard.press("Escape")
    assert page.inner_text("[data-hint='pivots.A0']") == ""
    page.mouse.click(*to_screen(100, -50))
    assert page.input_value("[data-field='pivots.A0']") == "5, 0"
    # a drag cancelled half way: the pivot goes back
    page.fill("[data-field='pivots.B0']", "0.1, 0.05")
    page.select_option("#synth-length", "m")
    start = centre(page, "#canvas [data-target='pivots.B0'] circle.handle")
    page.mouse.move(*start)
    page.mouse.down()
    page.mouse.move(start[0] + 40, start[1] + 40)
    assert page.input_value("[data-field='pivots.B0']") != "0.1, 0.05"
    page.keyboard.press("Escape")
    page.mouse.move(start[0] + 60, start[1] + 60)
    page.mouse.up()
    assert page.input_value("[data-field='pivots.B0']") == "0.1, 0.05"
    # another tab, or another task, stops a placing; what was placed stays
    page.click("#synth-place")
    page.mouse.click(*to_screen(100, 100))
    page.click("#tabs button[data-tab=plot]")
    page.click("#tabs button[data-tab=synthesis]")
    assert page.inner_text("#synth-place-hint") == ""
    page.mouse.click(*to_screen(200, 100))
    assert len(lines(page)) == 1
    page.click("button[data-place='pivots.A1']")
    page.select_option("#synth-kind", "path")
    page.mouse.click(*to_screen(200, 100))
    assert page.locator("#canvas g.target.point").count() == 5
    page.shot("placing_stopped")
    # the linkage's own points move again as before
    assert state(page, "window.kinelab.canvas.dragging") is None


@pytest.mark.parametrize("field, text, message", [
    ("function.expression", "log10(", "function.expression: cannot parse"),
    ("function.x_range", "2, 2", "function.x_range: expected two different numbers"),
    ("function.points", "1", "function.points: expected a whole number from 2 to 100"),
    ("function.ground", "x", "function.ground: expected a positive number, got 'x'"),
])
def test_a_function_task_typed_wrong_says_which_field_and_why(page, field, text, message):
    synthesis(page, "function")
    page.fill(f"[data-field='{field}']", text)
    page.click("#synth-solve")
    page.wait_for_selector("#status.error", timeout=60_000)
    assert message in page.inner_text("#status")
    assert page.inner_text("#synth-results") == ""
