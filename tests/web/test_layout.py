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
