"""Gear pairs on the page, in Chromium: every example with gear joints opens and plays; each
gear is drawn as its pitch circle about its axis, turning with it (a radius at the gear's
analysed angle, and ticks), a ring's ticks inwards, a rack as its pitch line whose ticks move
with its slide.  The drawing is read back from the canvas's own elements through its view
(``window.kinelab.canvas.view``: model units to pixels) and compared with kinelab's analysis
at the page's input.  Screenshots of each state go to the test's temporary folder."""
import math

import numpy as np
import pytest

import kinelab as kl
from kinelab.io import ModelFile
from tests.web.test_browser import browser, page, server, state  # noqa: F401
from tests.web.test_studio import open_example

GEAR_EXAMPLES = ["gear_train", "compound_gear_train", "planetary", "rack_and_pinion",
                 "geared_fivebar"]

# The pitch radii (mm), checked by hand from each file's comments: teeth times the module
# (2 mm) over two, or the radii given.  The gears of each joint in its order.
PITCH_RADII = {
    "gear_train": {"mesh12": {"gear1": 20, "idler": 30}, "mesh23": {"idler": 30, "gear3": 40}},
    "planetary": {"sun_planet": {"sun": 30, "planet": 20}, "planet_ring": {"planet": 20, "ring": 70}},
}
CENTRES = {"gear1": "O1", "idler": "O2", "gear3": "O3", "sun": "O", "planet": "C", "ring": "O"}

# Each drawn gear element, in model units: a pitch circle's centre and radius, a radius
# line's ends, a rack's mark (its foot on the pitch line) and its pitch line's ends.
DRAWN = """() => {
  const v = window.kinelab.canvas.view;
  const m = (X, Y) => [(X - v.ox) / v.s, (v.oy - Y) / v.s];
  const out = [];
  for (const e of document.querySelectorAll("#canvas [data-layer=gears] [data-gear]")) {
    const a = (k) => +e.getAttribute(k);
    const item = {joint: e.dataset.gear, link: e.dataset.gearLink, kind: e.getAttribute("class")};
    if (e.localName === "circle") Object.assign(item, {centre: m(a("cx"), a("cy")), radius: a("r") / v.s});
    if (e.localName === "line") Object.assign(item, {from: m(a("x1"), a("y1")), to: m(a("x2"), a("y2"))});
    if (e.localName === "path") item.ticks = (e.getAttribute("d").match(/M/g) || []).length;
    out.push(item);
  }
  return out;
}"""


def scrub_to(pg, index):
    """The scrub bar at sample `index`, and the page's configuration there come."""
    pg.fill("#scrub", str(index))
    pg.wait_for_function(f"() => window.kinelab.index === {index} && window.kinelab.config !== null "
                         "&& !window.kinelab.playing", timeout=60_000)


def analysed(pg):
    """kinelab's analysis at the page's input now (its configuration's q, in degrees)."""
    q = np.radians(state(pg, "window.kinelab.config.q"))
    model = ModelFile.from_dict(state(pg, "window.kinelab.model"))
    return kl.analyze(model.mechanism, q if len(q) > 1 else q[0])


def angle_gap(a, b):
    """The difference of two angles, rad, in [0, pi]."""
    return abs(math.remainder(a - b, 2 * math.pi))


@pytest.mark.parametrize("name", GEAR_EXAMPLES)
def test_every_gear_example_opens_and_plays(page, name):
    """Opened from the list and played: every gear pair drawn (two pitch circles, or a
    circle and a rack's pitch line), no error on the page nor in the status line."""
    open_example(page, name)
    drawn = page.evaluate(DRAWN)
    joints = [g["joint"] for g in state(page, "window.kinelab.study.drawing.gears")]
    assert joints
    for j in joints:
        kinds = sorted(d["kind"] for d in drawn if d["joint"] == j)
        pitch = [k for k in kinds if k.startswith("pitch")]
        assert len(pitch) == 2 and kinds.count("gear-mark") == 2 and kinds.count("gear-ticks") == 2, kinds
    start = state(page, "window.kinelab.index")
    page.click("#play")
    page.wait_for_function(f"() => window.kinelab.index !== {start}", timeout=60_000)
    page.wait_for_timeout(300)
    page.click("#play")
    page.shot(f"{name} played")
    assert not page.locator("#status.error").count(), page.inner_text("#status")


@pytest.mark.parametrize("name", ["planetary", "gear_train"])
def test_pitch_circles_sit_on_their_axes_and_turn_with_the_analysis(page, name):
    """At a few inputs along the scrub bar: each pitch circle's centre is its gear's axis
    and its radius the model's pitch radius, to 1e-9 mm; each radius line runs from the
    centre at the gear's angle (kinelab's, at the page's input) to 1e-9 rad, out to the
    pitch circle; the planetary's ring (internal) has its ticks inwards."""
    open_example(page, name)
    n = state(page, "window.kinelab.study.samples")
    for index in (0, 7, n // 3, n - 2):
        scrub_to(page, index)
        page.shot(f"{name} {index}")
        sol = analysed(page)
        drawn = page.evaluate(DRAWN)
        seen = set()
        for d in drawn:
            if d["joint"] not in PITCH_RADII[name]:
                continue
            link = d["link"]
            centre = sol.position(CENTRES[link]) * 1000          # m -> mm, by hand
            if d["kind"].startswith("pitch"):
                assert d["centre"] == pytest.approx(centre.tolist(), abs=1e-9), (index, d)
                assert d["radius"] == pytest.approx(PITCH_RADII[name][d["joint"]][link], abs=1e-9)
                assert d["kind"] == ("pitch ring" if link == "ring" else "pitch")
                seen.add((d["joint"], link))
            elif d["kind"] == "gear-mark":
                (x0, y0), (x1, y1) = d["from"], d["to"]
                assert [x0, y0] == pytest.approx(centre.tolist(), abs=1e-9)
                assert math.hypot(x1 - x0, y1 - y0) == pytest.approx(
                    PITCH_RADII[name][d["joint"]][link], abs=1e-9)
                theta = float(sol.angle(link))
                assert angle_gap(math.atan2(y1 - y0, x1 - x0), theta) < 1e-9, (index, link)
        assert seen == {(j, g) for j, gears in PITCH_RADII[name].items() for g in gears}
    if name == "planetary":
        # the ring's ticks point inwards (towards its centre), the planet's outwards
        inward = page.evaluate("""() => {
          const v = window.kinelab.canvas.view, out = {};
          for (const e of document.querySelectorAll("#canvas [data-layer=gears] path[data-gear=planet_ring]")) {
            const c = document.querySelector(`#canvas [data-layer=gears] circle[data-gear=planet_ring][data-gear-link=${e.dataset.gearLink}]`);
            const [X, Y] = [+c.getAttribute("cx"), +c.getAttribute("cy")], R = +c.getAttribute("r");
            const n = e.getAttribute("d").match(/-?[\\d.e+-]+/g).map(Number);
            out[e.dataset.gearLink] = Math.hypot(n[2] - X, n[3] - Y) < R;
          }
          return out;
        }""")
        assert inward == {"planet": False, "ring": True}


def test_a_racks_ticks_move_with_its_slide(page):
    """The rack and pinion scrubbed: the rack's mark (its point's foot on the pitch line)
    stays on the pitch line, 25 mm to the right of the axis through the pinion's centre,
    and moves along the slide by the slide's change (kinelab's); the pinion's radius line
    is at its angle."""
    open_example(page, "rack_and_pinion")
    marks = {}
    for index in (0, 10, 36, 70):
        scrub_to(page, index)
        sol = analysed(page)
        drawn = page.evaluate(DRAWN)
        rack = next(d for d in drawn if d["link"] == "rack" and d["kind"] == "gear-mark")
        u = np.reshape(sol.slide_axes("guide"), 2)
        o = np.reshape(sol.position("O"), 2) * 1000
        foot = np.array(rack["from"])
        assert np.dot(foot - o, [u[1], -u[0]]) == pytest.approx(25, abs=1e-9)
        marks[index] = (float(np.dot(foot, u)), float(sol.slide("guide")) * 1000)
        pinion = next(d for d in drawn if d["link"] == "pinion" and d["kind"] == "gear-mark")
        (x0, y0), (x1, y1) = pinion["from"], pinion["to"]
        assert angle_gap(math.atan2(y1 - y0, x1 - x0), float(sol.angle("pinion"))) < 1e-9
        assert rack in drawn and any(d["link"] == "rack" and d["kind"] == "gear-ticks" for d in drawn)
        page.shot(f"rack {index}")
    along0, slide0 = marks[0]
    for along, slide in marks.values():
        assert along - along0 == pytest.approx(slide - slide0, abs=1e-9)
    assert marks[70][1] - marks[0][1] > 100           # it did move: about r * 350 deg


def test_dragging_a_gears_mark_turns_the_train(page):
    """The move tool drags gear 1's mark M1 round its centre: each radius line ends where
    its gear's mark is drawn (M1, M2, M3 lie on the pitch circles, at the gears' angles),
    while the drag is drawn between samples and once the server's configuration comes."""
    open_example(page, "gear_train")
    ends = """() => {
      const out = {};
      for (const [link, mark] of [["gear1", "M1"], ["idler", "M2"], ["gear3", "M3"]]) {
        const l = document.querySelector(`#canvas [data-layer=gears] line.gear-mark[data-gear-link=${link}]`);
        const c = document.querySelector(`#canvas circle[data-point=${mark}]`);
        out[link] = Math.hypot(+l.getAttribute("x2") - +c.getAttribute("cx"), +l.getAttribute("y2") - +c.getAttribute("cy"));
      }
      return out;
    }"""
    box = page.locator("#canvas circle[data-point='O1']").bounding_box()
    o = (box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    box = page.locator("#canvas circle[data-point='M1']").bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    r = math.hypot(x - o[0], y - o[1])
    page.mouse.move(x, y)
    page.mouse.down()
    gaps = []
    for k in range(1, 13):
        a = math.radians(7 * k)
        page.mouse.move(o[0] + r * math.cos(a), o[1] - r * math.sin(a))
        gaps.append(page.evaluate(ends))      # as drawn now: predicted or solved
    page.mouse.up()
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending", timeout=60_000)
    page.wait_for_timeout(200)
    page.shot("gear train dragged")
    gaps.append(page.evaluate(ends))
    assert state(page, "window.kinelab.followGap") < 1e-9
    assert state(page, "window.kinelab.config.q[0]") == pytest.approx(84, abs=3)
    for gap in gaps:
        assert max(gap.values()) < 1e-6, gap          # px
