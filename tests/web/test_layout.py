"""The page from a phone's 390 pixels to a 4K screen, in Chromium: nothing wider than the
window (no sideways scrolling), the drawing at least as wide as the window less its margins
on a phone and beside the panels on a wide screen, every tab reachable.  Screenshots of each
size go to the test's temporary folder."""
import pytest

from tests.web.test_browser import browser, page, server, state  # noqa: F401
from tests.web.test_studio import open_example

SIZES = {"phone": (390, 844), "tablet": (820, 1180), "laptop": (1300, 820), "4K": (3840, 2160)}


def box(pg, selector):
    return pg.locator(selector).bounding_box()


@pytest.mark.parametrize("size", SIZES)
def test_the_page_fits_the_window_from_a_phone_to_4k(page, size):
    width, height = SIZES[size]
    page.set_viewport_size({"width": width, "height": height})
    open_example(page, "crank_rocker")
    page.shot(f"layout {size}")
    assert state(page, "document.documentElement.scrollWidth") <= width
    canvas, tabs = box(page, "#canvas"), box(page, "#tabs")
    if width <= 700:        # one column: the drawing across the window, the panels below it
        assert canvas["width"] >= width - 20 and canvas["height"] >= 300
        assert tabs["y"] >= canvas["y"] + canvas["height"]
    else:                   # the drawing beside the panels
        assert tabs["x"] >= canvas["x"] + canvas["width"] - 1
        assert canvas["width"] >= 0.5 * width
    for name in ("plot", "table", "method", "synthesis", "forces"):
        button = page.locator(f"#tabs button[data-tab={name}]")
        button.scroll_into_view_if_needed()
        button.click()
        assert page.locator(f"#tab-{name}").is_visible()
        assert state(page, "document.documentElement.scrollWidth") <= width, name


def overlaps(boxes):
    """The pairs of boxes (x, y, width, height, text) that overlap by more than a pixel."""
    found = []
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            w = min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0])
            h = min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1])
            if w > 1 and h > 1:
                found.append((a[4], b[4]))
    return found


def at_the_sketch_and_half_a_turn_on(pg):
    """The page shown at its first sample, then half its samples on: each yielded in turn."""
    yield "sketch"
    pg.evaluate("() => window.kinelab.setIndex(Math.floor(window.kinelab.study.samples / 2))")
    pg.wait_for_timeout(500)
    yield "half a turn on"


@pytest.mark.parametrize("example", ["crank_rocker", "stephenson6", "whitworth"])
def test_labels_of_points_and_instant_centres_do_not_overlap(page, example):
    """Every point's name and every instant centre's label drawn where no other label is
    (their boxes as Chromium lays the text out), at the sketch and half a turn on."""
    open_example(page, example)
    if not page.locator("#show-centres").is_checked():
        page.check("#show-centres")
    page.wait_for_function("() => document.querySelectorAll('#canvas text.centre-label').length > 0",
                           timeout=120_000)
    for _ in at_the_sketch_and_half_a_turn_on(page):
        boxes = page.evaluate("""() => [...document.querySelectorAll(
            '#canvas text.label, #canvas text.centre-label')].map((t) => {
                const b = t.getBBox(); return [b.x, b.y, b.width, b.height, t.textContent]; })""")
        assert len(boxes) > 4
        assert not overlaps(boxes), overlaps(boxes)
    page.shot(f"labels {example}")


@pytest.mark.parametrize("size", ["phone", "laptop"])
@pytest.mark.parametrize("example", ["crank_rocker", "stephenson6", "whitworth", "slotted_link",
                                     "fivebar", "engine", "jansen"])
def test_labels_of_points_keep_off_the_dimensions(page, example, size):
    """The dimensions on the drawing (each link's length, the input's angle) are placed
    first; no point's name is drawn over one (their boxes on the screen, turned as drawn)."""
    width, height = SIZES[size]
    page.set_viewport_size({"width": width, "height": height})
    open_example(page, example)
    assert page.locator("#dims").is_checked()
    page.wait_for_function("() => document.querySelectorAll('#canvas text.dim').length > 2",
                           timeout=120_000)
    for index in at_the_sketch_and_half_a_turn_on(page):
        labels, dims = ([b + [f"{kind} {t}"] for *b, t in page.evaluate(f"""() => [...document
            .querySelectorAll('#canvas text.{kind}')].map((t) => {{
                const b = t.getBoundingClientRect();
                return [b.x, b.y, b.width, b.height, t.textContent]; }})""")]
                        for kind in ("label", "dim"))
        assert len(dims) > 2 and len(labels) > 3
        crossing = [(a, b) for a, b in overlaps(labels + dims)
                    if a.startswith("label") != b.startswith("label")]
        page.shot(f"dimensions {example} {size} {index}")
        assert not crossing, crossing
