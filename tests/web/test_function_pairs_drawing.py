"""Function generation by angle pairs on the drawing, in Chromium: the fixed pivots O2, O4
and three (input, output) pairs placed by clicks, a ray's handle dragged about its pivot,
the task solved and its linkage opened: the four-bar's rocker is at each placed output angle
when its crank is at the placed input angle.  Esc cancels a pair half placed; a pair typed
wrong gets a message.  Screenshots of each state go to the test's temporary folder."""
import math

import numpy as np
import pytest

import kinelab as kl
from kinelab.io import ModelFile
from tests.web.test_browser import browser, page, server, state  # noqa: F401
from tests.web.test_synthesis_drawing import centre, drag, lines, numbers, synthesis, view

PIVOTS_MM = {"function.O2": (30.0, -40.0), "function.O4": (330.0, 10.0)}


def wrapped(a):
    return np.angle(np.exp(1j * np.asarray(a, float)))


def rays(pg, side):
    return pg.locator(f"#canvas g.target.ray.{side}").count()


def on_screen_towards(to_screen, pixel, pivot, degrees, distance=200):
    """The page's pixel `distance` pixels from `pivot` (model units) along `degrees` from +x."""
    a = math.radians(degrees)
    return to_screen(pivot[0] + distance * pixel * math.cos(a), pivot[1] + distance * pixel * math.sin(a))


def pivots_in_mm(pg):
    return {k: np.array(numbers(pg.input_value(f"[data-field='{k}']"))) * 1000 for k in PIVOTS_MM}


def test_the_pivots_and_pairs_placed_by_mouse_give_a_linkage_through_them(page):
    synthesis(page, "function-pairs")
    # the example's pairs, drawn as rays from the example's pivots
    assert rays(page, "in") == 3 and rays(page, "out") == 3
    assert page.locator("#canvas g.target.fixed").count() == 2
    to_screen, to_model, pixel = view(page)
    for key, xy in PIVOTS_MM.items():
        page.click(f"button[data-place='{key}']")
        page.mouse.click(*to_screen(*xy))
        assert page.inner_text(f"[data-hint='{key}']") == ""
    placed = pivots_in_mm(page)                                  # the task is in m
    for key, xy in PIVOTS_MM.items():
        np.testing.assert_allclose(placed[key], xy, atol=1.5 * pixel)
    assert page.text_content("#canvas g.target.fixed[data-target='function.O4']") == "O4"
    # the pairs of a crank-rocker on these pivots (ground, crank, coupler, rocker 3 : 1 : 3 :
    # 2.5), to whole degrees: the page's snap puts each ray on a whole degree
    O2, O4 = placed["function.O2"], placed["function.O4"]
    d = float(np.hypot(*(O4 - O2)))
    phi = math.degrees(math.atan2(*(O4 - O2)[::-1]))
    fb = kl.mechanisms.fourbar(ground=d, crank=d / 3, coupler=d, rocker=d * 2.5 / 3)
    inputs = [round(phi) + a for a in (40, 70, 100)]
    rocker = kl.analyze(fb, q=np.radians(np.subtract(inputs, phi))).angle("rocker")
    outputs = [round(v) for v in np.degrees(rocker) + phi]
    page.check("#snap")
    page.click("#synth-place")
    assert page.input_value("#synth-poses") == ""
    for k, (a, b) in enumerate(zip(inputs, outputs), 1):
        assert f"pair {k} of 3: click towards its input angle from O2" in page.inner_text("#synth-place-hint")
        page.mouse.click(*on_screen_towards(to_screen, pixel, O2, a))
        assert f"pair {k} of 3: click towards its output angle from O4" in page.inner_text("#synth-place-hint")
        page.mouse.click(*on_screen_towards(to_screen, pixel, O4, b))
    assert page.inner_text("#synth-place-hint") == ""
    page.shot("pairs_placed")
    assert lines(page) == [[a, b] for a, b in zip(inputs, outputs)]
    assert rays(page, "in") == 3 and rays(page, "out") == 3
    assert page.text_content("#canvas g.target.ray.out[data-target='pair 2 out']") == "2"
    # each handle drawn on its ray, at the same distance from its pivot
    for k, (a, b) in enumerate(zip(inputs, outputs), 1):
        for side, pivot, angle in (("in", O2, a), ("out", O4, b)):
            X, Y = centre(page, f"#canvas [data-target='pair {k} {side}'] circle.handle")
            x, y = np.subtract(to_model(X, Y), pivot)
            drawn = math.degrees(math.atan2(y, x))
            assert drawn == pytest.approx(math.degrees(wrapped(math.radians(angle))), abs=1.0)
            assert math.hypot(x, y) / pixel == pytest.approx(64, abs=1.5)
    # a fourth click places nothing: the three are placed
    page.mouse.click(*on_screen_towards(to_screen, pixel, O2, 0))
    assert len(lines(page)) == 3
    # a handle dragged about its pivot: the angle follows the pointer, to whole degrees with snap
    handle = centre(page, "#canvas [data-target='pair 2 in'] circle.handle")
    aim = on_screen_towards(to_screen, pixel, O2, inputs[1] + 12.4, distance=150)
    drag(page, handle, (aim[0] - handle[0], aim[1] - handle[1]))
    page.shot("pair_dragged")
    assert lines(page)[1] == [inputs[1] + 12, outputs[1]]
    assert lines(page)[0] == [inputs[0], outputs[0]] and lines(page)[2] == [inputs[2], outputs[2]]
    page.uncheck("#snap")
    handle = centre(page, "#canvas [data-target='pair 2 out'] circle.handle")
    aim = on_screen_towards(to_screen, pixel, O4, outputs[1] - 7.3, distance=150)
    drag(page, handle, (aim[0] - handle[0], aim[1] - handle[1]))
    X, Y = to_model(*aim)
    dragged = math.degrees(math.atan2(Y - O4[1], X - O4[0]))
    assert lines(page)[1][1] == pytest.approx(outputs[1] - 7.3, abs=0.05)          # the pointer's
    assert lines(page)[1][1] == pytest.approx(dragged, abs=1e-4)                  # angle, to the form's digits
    # typing puts the pairs back, and the drawing follows
    page.fill("#synth-poses", "\n".join(f"{a} {b}" for a, b in zip(inputs, outputs)))
    X, Y = centre(page, "#canvas [data-target='pair 2 in'] circle.handle")
    x, y = np.subtract(to_model(X, Y), O2)
    assert math.degrees(math.atan2(y, x)) == pytest.approx(math.degrees(wrapped(math.radians(inputs[1]))), abs=1.0)
    # solved and opened: the linkage's rocker at each placed output angle, its crank at the input
    page.click("#synth-solve")
    page.wait_for_selector("#synth-results tr[data-solution='1']", timeout=60_000)
    page.shot("pairs_solved")
    assert page.inner_text("#synth-results tr[data-solution='1'] td:nth-child(3)") == "none"
    page.click("#synth-results tr[data-solution='1'] button.open-solution")
    page.wait_for_function("() => (window.kinelab.source || '').includes('solution_1')")
    page.wait_for_function("() => window.kinelab.config !== null")
    model = state(page, "window.kinelab.model")
    assert model["units"] == {"length": "m", "angle": "deg"}
    np.testing.assert_allclose(model["points"]["O2"], O2 / 1000, rtol=0, atol=1e-9)
    np.testing.assert_allclose(model["points"]["O4"], O4 / 1000, rtol=0, atol=1e-9)
    mechanism = ModelFile.from_dict(model).mechanism                 # SI: rad
    reached = kl.analyze(mechanism, q=np.radians(inputs)).angle("rocker")
    np.testing.assert_allclose(wrapped(reached - np.radians(outputs)), 0, rtol=0, atol=1e-6)
    page.shot("pairs_opened")


def test_escape_cancels_a_pair_half_placed(page):
    synthesis(page, "function-pairs")
    to_screen, _, pixel = view(page)
    for key, (x, y) in PIVOTS_MM.items():                     # typed, in the task's m
        page.fill(f"[data-field='{key}']", f"{x / 1000}, {y / 1000}")
    O2, O4 = pivots_in_mm(page).values()
    X, Y = centre(page, "#canvas [data-target='function.O4'] circle.handle")
    np.testing.assert_allclose(X, to_screen(*O4)[0], atol=0.5)
    typed = page.input_value("#synth-poses")
    page.click("#synth-place")
    page.mouse.click(*on_screen_towards(to_screen, pixel, O2, 170))
    page.mouse.click(*on_screen_towards(to_screen, pixel, O4, 100))
    page.mouse.click(*on_screen_towards(to_screen, pixel, O2, -170))        # pair 2: its input only
    assert len(lines(page)) == 2 and len(lines(page)[1]) == 1
    # past 180 deg the input goes on turning the same way: 190, not -170
    assert lines(page)[0][0] == pytest.approx(170, abs=0.5) and lines(page)[1][0] == pytest.approx(190, abs=0.5)
    assert rays(page, "in") == 2 and rays(page, "out") == 1
    assert "pair 2 of 3: click towards its output angle" in page.inner_text("#synth-place-hint")
    page.shot("pair_half_placed")
    page.keyboard.press("Escape")
    assert page.input_value("#synth-poses") == typed
    assert page.inner_text("#synth-place-hint") == ""
    assert rays(page, "in") == 3 and rays(page, "out") == 3
    page.mouse.click(*on_screen_towards(to_screen, pixel, O4, 100))
    assert page.input_value("#synth-poses") == typed
    # a ray's drag cancelled half way: it goes back
    handle = centre(page, "#canvas [data-target='pair 1 in'] circle.handle")
    page.mouse.move(*handle)
    page.mouse.down()
    page.mouse.move(handle[0] + 30, handle[1] + 30)
    assert page.input_value("#synth-poses") != typed
    page.keyboard.press("Escape")
    page.mouse.up()
    assert page.input_value("#synth-poses") == typed
    assert state(page, "window.kinelab.canvas.dragging") is None
    # a pair deleted from the form leaves the drawing, its rays both
    page.fill("#synth-poses", "\n".join(typed.strip().splitlines()[:2]))
    assert rays(page, "in") == 2 and rays(page, "out") == 2
    assert page.locator("#canvas [data-target='pair 3 out']").count() == 0


@pytest.mark.parametrize("pairs, message", [
    ("40 87.1\n70 abc\n100 102.7", "function.pairs: expected finite numbers of shape (n, 2)"),
    ("40 87.1\n100 102.7\n70 92.2", "function.pairs: expected angles in the order the crank passes them"),
    ("40 87.1\n70 92.2\n500 102.7", "function.pairs: the crank would turn a full circle or more"),
    ("40 87.1\n70 92.2", "function.pairs: expected 3 to 100 pairs"),
])
def test_pairs_typed_wrong_get_a_message_and_the_page_goes_on(page, pairs, message):
    synthesis(page, "function-pairs")
    page.fill("#synth-poses", pairs)
    page.click("#synth-solve")
    page.wait_for_selector("#status.error", timeout=60_000)
    assert message in page.inner_text("#status")
    assert page.inner_text("#synth-results") == ""
    # the page still answers: the rays of the pairs that are numbers are drawn, and placing works
    assert rays(page, "in") >= 2
    page.click("#synth-place")
    assert "pair 1 of 3" in page.inner_text("#synth-place-hint")


def test_a_pivot_typed_wrong_gets_a_message_and_no_placing(page):
    synthesis(page, "function-pairs")
    page.fill("[data-field='function.O4']", "1, y")
    assert page.locator("#canvas g.target.fixed").count() == 1 and rays(page, "out") == 0
    page.click("#synth-place")
    assert "O2 and O4 first" in page.inner_text("#synth-place-hint")
    for typed, message in (("1, y", "function.O4: expected finite numbers of shape (2), got [1, 'y']"),
                           ("0, 0", "function.O4: expected a fixed pivot apart from O2")):
        page.fill("[data-field='function.O4']", typed)
        page.click("#synth-solve")
        page.wait_for_function("(m) => document.getElementById('status').textContent.includes(m)",
                               arg=message, timeout=60_000)
        assert page.inner_text("#synth-results") == ""
    page.fill("[data-field='function.O4']", "1, 0")
    page.click("#synth-solve")
    page.wait_for_selector("#synth-results tr[data-solution='1']", timeout=60_000)
