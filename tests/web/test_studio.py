"""The page in Chromium while a person drags, opens, draws and types: the linkage follows a
drag in the frame of each move and the server's solve confirms it, the drawing is changed
in place, slots are drawn along their moving guides, and the page keeps its state straight
(the last model chosen, an empty new page, a link's first point, refused values).
Screenshots of each state go to the test's temporary folder."""
import math

import numpy as np
import pytest

from tests.web.test_browser import browser, page, point_on_screen, server, state  # noqa: F401


def open_example(pg, name):
    """Open an example and wait for its own study (not that of the model shown before,
    which may be the same example: the page opens with the crank-rocker)."""
    pg.evaluate("() => { window.studyBefore = window.kinelab.study; }")
    pg.select_option("#open", name)
    pg.wait_for_function(f"() => (window.kinelab.source || '').startsWith('{name}') "
                         "&& window.kinelab.study && window.kinelab.study !== window.studyBefore "
                         "&& window.kinelab.config !== null", timeout=120_000)


def idle(pg):
    pg.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending", timeout=120_000)


def screen_map(pg):
    """The drawing's map from model units to the page's pixels, from two ground pivots."""
    pts = state(pg, "window.kinelab.model.points")
    (X0, Y0), (X1, Y1) = point_on_screen(pg, "O2"), point_on_screen(pg, "O4")
    (x0, y0), (x1, y1) = pts["O2"], pts["O4"]
    s = math.hypot(X1 - X0, Y1 - Y0) / math.hypot(x1 - x0, y1 - y0)
    return lambda x, y: (X0 + s * (x - x0), Y0 - s * (y - y0))


# -- dragging ---------------------------------------------------------------------------------
COUNT_REQUESTS = """() => {
  const real = window.fetch;
  window.__drags = {sent: 0, flying: 0, most: 0};
  window.fetch = async (url, ...rest) => {
    const drag = String(url).endsWith("/api/drag");
    if (drag) { __drags.sent++; __drags.flying++; __drags.most = Math.max(__drags.most, __drags.flying); }
    try { return await real(url, ...rest); } finally { if (drag) __drags.flying--; }
  };
}"""


@pytest.mark.parametrize("point", ["C", "A"])
def test_a_six_bar_follows_each_move_at_once_and_the_server_confirms_it(page, point):
    """The move tool on the Stephenson six-bar: each move is drawn in the frame of the
    pointer event, where the sweep's K and L put the linkage (to 1e-9 of its size from the
    server's solve), with the elements drawn before changed in place; one drag request at
    a time, the newest move waiting; at the end the server's configuration, every length
    kept."""
    open_example(page, "stephenson6")
    page.evaluate(COUNT_REQUESTS)
    s = state(page, "window.kinelab.study")
    u = s["units"]["length"]
    to_screen = screen_map(page)
    i0 = state(page, "window.kinelab.index")
    xs, ys = s["columns"][f"{point}.x[{u}]"], s["columns"][f"{point}.y[{u}]"]
    page.evaluate(f"() => {{ window.__circle = document.querySelector(\"#canvas circle[data-point='{point}']\"); "
                  "window.__trace = document.querySelector('#canvas .trace'); }")
    # right after the page's own handler of each move (this one bubbles up to the window):
    # what it drew, before any answer from the server
    page.evaluate(f"""() => {{ window.__seen = [];
        window.addEventListener("pointermove", (e) => {{
          if (!e.buttons) return;
          const p = window.kinelab.predicted;
          const c = document.querySelector("#canvas circle[data-point='{point}']");
          const r = document.getElementById("canvas").getBoundingClientRect();
          window.__seen.push(p && [p.points['{point}'], r.left + +c.getAttribute('cx'), r.top + +c.getAttribute('cy')]);
        }}); }}""")
    x, y = point_on_screen(page, point)
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 41):
        j = (i0 + 3 * k) % s["samples"]
        X, Y = to_screen(xs[j] + 0.3, ys[j])        # a little off the path: the nearest place on it
        page.mouse.move(X, Y)
    idle(page)
    at_once = state(page, "window.__seen")
    page.mouse.up()
    idle(page)
    page.wait_for_function("() => window.kinelab.config && window.kinelab.config.values", timeout=60_000)
    page.shot(f"six_bar_dragged_{point}")
    drawn = [a for a in at_once if a]
    assert len(at_once) == 40 and len(drawn) == 40                # each move drawn at once
    for (px, py), cx, cy in drawn:
        assert math.dist(to_screen(px, py), (cx, cy)) < 0.01     # px
    drags = state(page, "window.__drags")
    assert drags["most"] == 1 and 1 <= drags["sent"] <= 40
    assert state(page, "window.kinelab.followGap") < 1e-9
    # the same elements, moved: the circle and the (unchanged) trace were not made again
    assert state(page, f"window.__circle === document.querySelector(\"#canvas circle[data-point='{point}']\")")
    assert state(page, "window.__trace === document.querySelector('#canvas .trace')")
    # the server's configuration, lengths kept
    c = state(page, "window.kinelab.config")
    pts = {p: np.array(v) for p, v in c["points"].items()}
    sketch = {p: np.array(v) for p, v in s["model"]["points"].items()}
    for link in s["model"]["links"]:
        ps = link["points"]
        for a, b in zip(ps, ps[1:] + ps[:1]):
            if a != b and not link.get("ground"):
                assert np.hypot(*(pts[a] - pts[b])) == pytest.approx(np.hypot(*(sketch[a] - sketch[b])), rel=1e-12)
    assert abs(c["q"][0] - s["columns"][s["inputs"][0]][i0]) > 10      # deg: it moved along
    cx, cy = point_on_screen(page, point)
    X, Y = to_screen(*c["points"][point])
    assert math.hypot(cx - X, cy - Y) < 0.5


# -- slots --------------------------------------------------------------------------------------
def screen_angle(x1, y1, x2, y2):
    return math.atan2(-(y2 - y1), x2 - x1)          # the screen's y runs down


def drawn_at(pg, name):
    """Where a point is drawn, from its circle's own numbers (a bounding box is rounded)."""
    return [float(pg.get_attribute(f"#canvas circle[data-point='{name}']", k)) for k in ("cx", "cy")]


def along(a, b):
    """The angle between two lines, rad (0 for parallel lines either way round)."""
    d = (a - b) % math.pi
    return min(d, math.pi - d)


@pytest.mark.parametrize("name, index, degrees", [("whitworth", 90, 90), ("slotted_link", 90, 45),
                                                  ("slotted_link", 540, 270)])
def test_a_slot_is_drawn_along_its_lever_as_it_turns(page, name, index, degrees):
    """Scrubbed to the crank at 90 deg (Whitworth: the lever vertical), or the slotted link's
    at 45 and 270 deg (at 90 deg its crank is where the sketch has it), the slot's guide
    line and its block lie along the lever to 1e-9 rad, not at the sketch's 26.6 deg: along
    the line from the lever's pivot O4 through the block's pin A, which slides in the slot,
    and along the lever's outline O4-C to the digits the examples give C with (Whitworth's
    C = (89.442719, 44.72136) is 5e-9 rad off the slot's axis (2, 1))."""
    open_example(page, name)
    page.fill("#scrub", str(index))
    page.wait_for_function(f"() => window.kinelab.config && Math.abs(window.kinelab.config.q[0] - {degrees}) < 1e-9",
                           timeout=60_000)
    page.wait_for_timeout(100)
    page.shot(f"{name}_at_{degrees}")
    x1, y1, x2, y2 = (float(page.get_attribute("#canvas line[data-guide=slot]", k)) for k in ("x1", "y1", "x2", "y2"))
    (X0, Y0), (X1, Y1) = ([float(v) for v in xy.split(",")]
                          for xy in page.get_attribute("#canvas [data-link=lever]", "points").split())
    lever = screen_angle(X0, Y0, X1, Y1)
    (ox, oy), (ax, ay) = drawn_at(page, "O4"), drawn_at(page, "A")
    slot = screen_angle(ox, oy, ax, ay)
    guide = screen_angle(x1, y1, x2, y2)
    assert along(guide, slot) < 1e-9
    assert along(guide, lever) < 1e-8
    block = page.get_attribute("#canvas rect[data-block=slot]", "transform")
    turned = math.radians(-float(block.removeprefix("rotate(").split()[0]))
    assert along(turned, guide) < 1e-12
    assert along(guide, math.atan2(1, 2)) > 0.1                  # not the sketch's direction
    if name == "whitworth":
        assert along(guide, math.pi / 2) < 1e-9                  # the lever is vertical
        # the ram's guide is the ground: it stays horizontal
        x1, y1, x2, y2 = (float(page.get_attribute("#canvas line[data-guide=ram_slide]", k)) for k in ("x1", "y1", "x2", "y2"))
        assert along(screen_angle(x1, y1, x2, y2), 0.0) < 1e-12


def test_a_slot_follows_its_lever_while_dragged(page):
    open_example(page, "whitworth")
    x, y = point_on_screen(page, "C")
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 16):
        page.mouse.move(x - 4 * k, y + 3 * k)
        # in the frame of the move: the guide, the lever's outline, and the slot's line O4-A
        guide, lever, slot = page.evaluate("""() => {
            const $ = (s) => document.querySelector("#canvas " + s), at = (e, k) => +e.getAttribute(k);
            const g = $("line[data-guide=slot]"), o = $("circle[data-point=O4]"), a = $("circle[data-point=A]");
            return [["x1", "y1", "x2", "y2"].map((k) => at(g, k)),
                    $("[data-link=lever]").getAttribute("points").split(" ").flatMap((p) => p.split(",").map(Number)),
                    [at(o, "cx"), at(o, "cy"), at(a, "cx"), at(a, "cy")]]; }""")
        assert along(screen_angle(*guide), screen_angle(*slot)) < 1e-9
        assert along(screen_angle(*guide), screen_angle(*lever)) < 1e-8      # C to 8 digits
    idle(page)
    page.mouse.up()
    page.shot("whitworth_dragged")


# -- page state ----------------------------------------------------------------------------------
DELAY_ANSWERS = """() => {
  const real = window.fetch, slow = {whitworth: 1200, jansen: 700};
  window.fetch = async (url, options = {}) => {
    const r = await real(url, options);
    const text = String(url) + (options.body || "");
    const wait = Object.entries(slow).find(([name]) => text.includes(name));
    if (wait) await new Promise((ok) => setTimeout(ok, wait[1]));
    return r;
  };
}"""


def test_the_model_chosen_last_is_the_one_shown(page):
    """Three models chosen from open… 50 ms apart, the first two answered last (their
    answers held back): the page stays on the last one chosen."""
    page.evaluate(DELAY_ANSWERS)
    for name in ("whitworth", "jansen", "stephenson6"):
        page.select_option("#open", name)
        page.wait_for_timeout(50)
    page.wait_for_function("() => (window.kinelab.source || '').startsWith('stephenson6') && window.kinelab.config",
                           timeout=60_000)
    page.wait_for_timeout(2500)                       # the held answers have come by now
    page.shot("chosen_last")
    assert state(page, "window.kinelab.source") == "stephenson6.toml"
    assert state(page, "window.kinelab.model.name") == "Stephenson six-bar"
    assert state(page, "window.kinelab.study.model.name") == "Stephenson six-bar"
    assert "stephenson6.toml" in page.inner_text("#title")
    assert page.locator("#canvas [data-link=link5]").count() == 1
    assert page.locator("#canvas [data-link=lever]").count() == 0
    assert not page.locator("#status.error").count()


def test_new_gives_an_empty_page(page):
    page.wait_for_function("() => window.kinelab.config !== null")
    page.click("#new")
    page.wait_for_function("() => window.kinelab.model.name === 'sketch'")
    page.wait_for_timeout(300)
    page.shot("new")
    assert page.inner_text("#title") == ""
    assert page.inner_text("#status") == "" and not page.locator("#status.error").count()
    assert page.locator("#plot > *").count() == 0
    assert page.locator("#canvas .link, #canvas .point, #canvas .trace").count() == 0
    assert page.locator("#tab-table tr[data-point]").count() == 0
    assert page.inner_text("#input-value") == ""
    # and undo brings the model back
    page.click("#undo")
    page.wait_for_function("() => (window.kinelab.source || '').startsWith('crank_rocker')")


def test_a_links_first_point_is_shown_until_escape_or_another_tool(page):
    page.wait_for_function("() => window.kinelab.config !== null")
    to_screen = screen_map(page)
    page.click("#new")
    page.check("input[name=tool][value=link]")
    page.mouse.click(*to_screen(0, 0))
    page.wait_for_selector("#canvas circle.pending[data-pending=P1]", state="attached")
    page.mouse.move(*to_screen(100, 50))
    page.wait_for_selector("#canvas line.pending-link", state="attached")
    page.shot("link_pending")
    page.keyboard.press("Escape")
    page.wait_for_selector("#canvas circle.pending", state="detached")
    assert page.locator("#canvas line.pending-link").count() == 0
    page.mouse.click(*to_screen(200, 0))          # a new first point, not a link from P1
    page.wait_for_selector("#canvas circle.pending[data-pending=P2]", state="attached")
    assert len(state(page, "window.kinelab.model.links")) == 1          # the ground only
    page.check("input[name=tool][value=point]")        # another tool: the link waits no more
    page.wait_for_selector("#canvas circle.pending", state="detached")
    page.check("input[name=tool][value=link]")
    page.mouse.click(*point_on_screen(page, "P1"))
    page.wait_for_selector("#canvas circle.pending[data-pending=P1]", state="attached")
    assert len(state(page, "window.kinelab.model.links")) == 1
    page.mouse.click(*point_on_screen(page, "P2"))     # a link from P1 to P2, as asked
    page.wait_for_function("() => window.kinelab.model.links.length === 2")
    page.shot("link_drawn")
    assert state(page, "window.kinelab.model.links[1].points") == ["P1", "P2"]
    assert page.locator("#canvas circle.pending").count() == 0


@pytest.mark.parametrize("row, value, message", [
    ("tr[data-link=rocker] td[data-field=length]", "", "rocker.length: expected a number, got an empty field"),
    ("tr[data-link=rocker] td[data-field=length]", "0x10", "rocker.length: expected a decimal number such as 12.5 or 1e3, got '0x10'"),
    ("tr[data-link=rocker] td[data-field=length]", "1_000", "got '1_000'"),
    ("tr[data-link=rocker] td[data-field=length]", "1e999", "got '1e999'"),
    ("tr[data-point=O4] td[data-field=x]", "0x10", "O4.x: expected a decimal number"),
    ("tr[data-link=rocker] td[data-field=length]", "10", "rocker"),            # refused by the server
])
def test_a_refused_value_puts_the_models_back_and_says_why(page, row, value, message):
    page.wait_for_function("() => window.kinelab.config !== null")
    page.click("#tabs button[data-tab=table]")
    field = page.locator(f"#tab-table {row} input")
    before = field.input_value()
    model = state(page, "window.kinelab.model")
    field.fill(value)
    field.press("Enter")
    page.wait_for_selector("#status.error")
    page.shot("refused_" + "".join(c for c in value if c.isalnum()))
    assert message in page.inner_text("#status")
    assert page.locator(f"#tab-table {row} input").input_value() == before
    assert state(page, "window.kinelab.model") == model


def test_a_drawn_input_turns_so_its_velocities_are_not_zero(page):
    """A crank-rocker drawn link by link: its input gets a speed of one turn a second,
    shown in the table and editable; the velocity polygon has arrows."""
    page.wait_for_function("() => window.kinelab.config !== null")
    to_screen = screen_map(page)
    page.click("#new")
    page.check("input[name=tool][value=link]")
    page.mouse.click(*to_screen(0, 0))
    page.wait_for_selector("#canvas circle[data-point=P1]", state="attached")
    for k, xy in enumerate(((0, 100), (280, 220), (300, 0)), 2):
        page.mouse.click(*to_screen(*xy))                     # a new point, and the link to it
        page.wait_for_function(f"() => window.kinelab.model.links.length === {k}")
        if k < 4:                                             # the next link starts there
            page.mouse.click(*point_on_screen(page, f"P{k}"))
            page.wait_for_selector(f"#canvas circle.pending[data-pending=P{k}]", state="attached")
    page.check("input[name=tool][value=ground]")
    for p in ("P1", "P4"):
        page.mouse.click(*point_on_screen(page, p))
        page.wait_for_function(f"() => window.kinelab.model.links[0].points.includes('{p}')")
    page.check("input[name=tool][value=input]")
    page.mouse.click(*point_on_screen(page, "P1"))
    page.wait_for_function("() => window.kinelab.study && !window.kinelab.draft && window.kinelab.config", timeout=60_000)
    page.click("#tabs button[data-tab=table]")
    speed = page.locator("#tab-table td[data-field=speed] input")
    assert speed.input_value() == "360"
    assert state(page, "window.kinelab.model.inputs[0].speed") == 360
    s = state(page, "window.kinelab.study")
    assert max(abs(v) for v in s["columns"]["link2.omega[deg/s]"] if v is not None) > 10
    speed.fill("720")
    speed.press("Enter")
    page.wait_for_function("() => window.kinelab.model.inputs[0].speed === 720")
    page.click("#tabs button[data-tab=method]")
    page.wait_for_selector("svg[data-polygon=velocity] line.absolute", state="attached", timeout=60_000)
    page.shot("drawn_input_turns")
    assert page.locator("svg[data-polygon=velocity] line.absolute").count() >= 2
