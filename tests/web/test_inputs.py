"""A linkage of several inputs in Chromium: a five-bar, opened from the examples or drawn
link by link, given its two cranks as inputs from the page (the mobility message saying
how many it needs until it has them), each input's slider moving that input alone and the
linkage drawn where kinelab puts it at the pair, an input removed and given back, and bad
ranges and speeds refused with the reason.  Screenshots of each state go to the test's
temporary folder."""
import math
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab import kinematics
from kinelab.io import ModelFile
from tests.web.test_browser import ROOT, browser, page, point_on_screen, server, state  # noqa: F401
from tests.web.test_studio import idle, open_example, screen_map


def tool(pg, name):
    pg.check(f"input[name=tool][value={name}]")


def status(pg):
    return pg.inner_text("#status")


# The example's five-bar, drawn: cranks from P1 and P5 on the ground, couplers meeting at P3.
DRAWN = [(0, 0), (0, 100), (144.72136, 139.442719), (200, 0), (100, 0)]


def draw_five_bar(pg):
    """A five-bar drawn link by link on a new page, P1 and P5 on the ground, no input yet."""
    pg.wait_for_function("() => window.kinelab.config !== null", timeout=120_000)
    to_screen = screen_map(pg)           # the crank-rocker's: O2 at (0, 0), O4 at (300, 0)
    pg.click("#new")
    tool(pg, "link")
    pg.mouse.click(*to_screen(*DRAWN[0]))
    pg.wait_for_selector("#canvas circle[data-point=P1]", state="attached")
    for k, xy in enumerate(DRAWN[1:], 2):
        pg.mouse.click(*to_screen(*xy))                     # a new point, and the link to it
        pg.wait_for_function(f"() => window.kinelab.model.links.length === {k}")
        if k < len(DRAWN):                                  # the next link starts there
            pg.mouse.click(*point_on_screen(pg, f"P{k}"))
            pg.wait_for_selector(f"#canvas circle.pending[data-pending=P{k}]", state="attached")
    tool(pg, "ground")
    for p in ("P1", "P5"):
        pg.mouse.click(*point_on_screen(pg, p))
        pg.wait_for_function(f"() => window.kinelab.model.links[0].points.includes('{p}')")
    idle(pg)


def give_input(pg, point, count):
    """The input tool clicked on `point`; until the model has `count` inputs."""
    tool(pg, "input")
    pg.mouse.click(*point_on_screen(pg, point))
    pg.wait_for_function(f"() => (window.kinelab.model.inputs || []).length === {count}", timeout=120_000)


def until_studied(pg):
    pg.wait_for_function("() => window.kinelab.study && !window.kinelab.draft && window.kinelab.config",
                         timeout=120_000)


def drawn_five_bar_with_two_inputs(pg):
    """The drawn five-bar given its two cranks as inputs, the mobility message shown while it
    has only one; its ground pivots and its couplers' joint."""
    draw_five_bar(pg)
    give_input(pg, "P1", 1)
    pg.wait_for_selector("#status.error", timeout=120_000)
    assert "give it 2 input(s)" in status(pg)
    pg.shot("drawn_one_input")
    give_input(pg, "P5", 2)
    until_studied(pg)
    return ("P1", "P5"), "P3"


def example_five_bar(pg):
    open_example(pg, "fivebar")
    return ("O2", "O4"), "P"


FIVE_BARS = {"example": example_five_bar, "drawn": drawn_five_bar_with_two_inputs}


def test_a_drawn_five_bar_gets_two_inputs_from_the_page(page):
    """Each crank's joint with the ground an input, in the order given, with a range from
    the sketch (a full turn) and a speed of a turn a second; the second click on a joint
    that is an input already changes nothing; the table lists both, R, and the player has a
    slider for each."""
    drawn_five_bar_with_two_inputs(page)
    page.shot("drawn_two_inputs")
    model = state(page, "window.kinelab.model")
    inputs = model["inputs"]
    pivots = [next(j["name"] for j in model["joints"] if j["point"] == p and "ground" in j["links"])
              for p in ("P1", "P5")]
    assert [i["joint"] for i in inputs] == pivots
    assert all(i["speed"] == 360 for i in inputs)
    at_sketch = np.degrees(kinematics.plan(ModelFile.from_dict(model).mechanism).q_sketch)
    ranges = np.array([i["range"] for i in inputs])
    assert np.allclose(ranges, [[q, q + 360] for q in at_sketch], rtol=0, atol=1e-9), ranges
    assert not page.locator("#status.error").count()
    give_input(page, "P1", 2)                      # an input already: nothing changes
    idle(page)
    page.wait_for_timeout(200)
    assert state(page, "window.kinelab.model") == model
    page.click("#tabs button[data-tab=table]")
    rows = page.locator("#tab-table tr[data-input]")
    assert rows.count() == 2
    assert [page.inner_text(f"#tab-table tr[data-input={j}] td[data-field=kind]") for j in pivots] \
        == ["R (angle)", "R (angle)"]
    assert page.input_value(f"#tab-table tr[data-input={pivots[1]}] td[data-field=speed] input") == "360"
    assert page.locator("#input-sliders input[type=range]").count() == 2
    assert page.locator("#input-sliders").is_visible()
    # the study of both inputs plots
    assert state(page, "window.kinelab.study.inputs") == [f"{j}.q[deg]" for j in pivots]
    assert page.locator("#plot polyline, #plot path").count() >= 1


def coupler_at(model, q_deg, point):
    """Where kinelab puts `point` at the inputs `q_deg` (deg), in the model's units."""
    mf = ModelFile.from_dict(model)
    return mf.units.convert(kl.analyze(mf.mechanism, np.radians(q_deg)).position(point).reshape(2), "m")


@pytest.mark.parametrize("how", FIVE_BARS)
def test_each_inputs_slider_moves_that_input_and_the_linkage_is_drawn_there(page, how):
    """Each slider moved in turn: the other input stays, and the linkage is drawn where
    kl.analyze puts it at the pair (the couplers' joint to 1e-9 of the model's size; on
    the screen to half a pixel)."""
    pivots, coupler = FIVE_BARS[how](page)
    model = state(page, "window.kinelab.model")
    names = [i.get("name", i["joint"]) for i in model["inputs"]]
    q = [state(page, f"window.kinelab.study.columns[window.kinelab.study.inputs[{k}]][window.kinelab.index]")
         for k in range(2)]
    xy = np.array(list(model["points"].values()))
    size = float(np.max(np.ptp(xy, axis=0)))
    for k, step in ((0, 30.0), (1, 25.0), (0, -12.5)):
        q[k] += step
        page.fill(f"#input-sliders input[data-input={names[k]}]", repr(q[k]))
        page.wait_for_function(
            f"() => window.kinelab.config && window.kinelab.config.q.length === 2 && "
            f"Math.abs(window.kinelab.config.q[0] - {q[0]}) < 1e-9 && Math.abs(window.kinelab.config.q[1] - {q[1]}) < 1e-9",
            timeout=60_000)
        page.wait_for_timeout(100)
        page.shot(f"{how}_slider_{k}_{q[k]:g}")
        shown = np.array(state(page, f"window.kinelab.config.points['{coupler}']"))
        assert np.max(np.abs(shown - coupler_at(model, q, coupler))) <= 1e-9 * size
        # the drawing shows it
        pts = state(page, "window.kinelab.model.points")
        (X0, Y0), (X1, Y1) = (point_on_screen(page, p) for p in pivots)
        (x0, y0), (x1, y1) = (pts[p] for p in pivots)
        s = math.hypot(X1 - X0, Y1 - Y0) / math.hypot(x1 - x0, y1 - y0)
        at = (X0 + s * (shown[0] - x0), Y0 - s * (shown[1] - y0))
        assert math.dist(point_on_screen(page, coupler), at) < 0.75
        values = [float(v) for v in
                  (page.input_value(f"#input-sliders input[data-input={n}]") for n in names)]
        assert values == pytest.approx(q, abs=1e-9)
    assert state(page, "window.kinelab.model") == model
    assert not page.locator("#status.error").count()


@pytest.mark.parametrize("how", FIVE_BARS)
def test_an_input_removed_brings_the_mobility_message_back(page, how):
    """An input removed from the table: the drawing stays, the message says it needs two,
    the sliders go; the input given again with the tool, the linkage moves again."""
    pivots, _ = FIVE_BARS[how](page)
    page.click("#tabs button[data-tab=table]")
    second = state(page, "window.kinelab.model.inputs[1].joint")
    page.click(f"#tab-table tr[data-input={second}] td[data-field=remove] button")
    page.wait_for_function("() => window.kinelab.model.inputs.length === 1", timeout=120_000)
    page.wait_for_selector("#status.error", timeout=120_000)
    page.shot(f"{how}_input_removed")
    assert "give it 2 input(s)" in status(page)
    assert state(page, "window.kinelab.draft") and state(page, "window.kinelab.study") is None
    assert page.locator("#input-sliders").is_hidden()
    assert page.locator("#canvas .link").count() >= 4                 # the drawing stays
    assert page.locator("#tab-table tr[data-input]").count() == 1
    give_input(page, pivots[1], 2)
    until_studied(page)
    assert not page.locator("#status.error").count()
    assert page.locator("#input-sliders input[type=range]").count() == 2


@pytest.mark.parametrize("field, value, message", [
    ("range", "abc", "jO4.range: expected two numbers, start and stop, such as 0, 360; got 'abc'"),
    ("range", "abc, 90", "jO4.range start: expected a decimal number such as 12.5 or 1e3, got 'abc'"),
    ("range", "30", "jO4.range: expected two numbers, start and stop"),
    ("range", "0, 90, 180", "jO4.range: expected two numbers, start and stop"),
    ("range", "45, 45", "jO4.range: the start and the stop are the same"),
    ("range", "0, 1e999", "jO4.range stop: expected a decimal number"),
    ("speed", "1e200", "inputs[1].speed: expected at most 1e+100 rad/s"),       # refused by the server
    ("speed", "", "jO4.speed: expected a number, got an empty field"),
    ("speed", "0x10", "jO4.speed: expected a decimal number"),
])
def test_a_bad_range_or_speed_is_refused_and_the_table_put_back(page, field, value, message):
    open_example(page, "fivebar")
    page.click("#tabs button[data-tab=table]")
    selector = f"#tab-table tr[data-input=jO4] td[data-field={field}] input"
    before = page.input_value(selector)
    model = state(page, "window.kinelab.model")
    page.fill(selector, value)
    page.press(selector, "Enter")
    page.wait_for_selector("#status.error", timeout=120_000)
    page.shot(f"refused_{field}_" + "".join(c for c in value if c.isalnum()))
    assert message in status(page)
    assert page.input_value(selector) == before
    assert state(page, "window.kinelab.model") == model


def test_a_range_typed_moves_the_slider_over_it(page):
    open_example(page, "fivebar")
    page.click("#tabs button[data-tab=table]")
    selector = "#tab-table tr[data-input=jO4] td[data-field=range] input"
    page.fill(selector, "-30, 60")
    page.press(selector, "Enter")
    page.wait_for_function("() => window.kinelab.model.inputs[1].range[1] === 60 && window.kinelab.study "
                           "&& window.kinelab.study.model.inputs[1].range[1] === 60", timeout=120_000)
    idle(page)
    slider = page.locator("#input-sliders input[data-input=jO4]")
    assert (slider.get_attribute("min"), slider.get_attribute("max")) == ("-30", "60")


# -- slides -------------------------------------------------------------------------------------
def test_a_slide_as_the_one_input_of_a_slider_crank(page):
    """The input tool on the slider's point of the slider-crank (one degree of freedom): the
    slide takes the crank's place as its one input, a length, with a speed of the sketch's
    size a second; the sweep runs over the slide's reachable range."""
    open_example(page, "offset_slider_crank")
    give_input(page, "B", 1)
    page.wait_for_function("() => window.kinelab.model.inputs[0].joint === 'slide' && window.kinelab.study "
                           "&& window.kinelab.study.inputs[0] === 'slide.q[mm]'", timeout=120_000)
    idle(page)
    page.shot("slide_input")
    assert state(page, "window.kinelab.model.inputs") == [{"joint": "slide", "speed": 200}]
    page.click("#tabs button[data-tab=table]")
    assert page.inner_text("#tab-table tr[data-input=slide] td[data-field=kind]") == "P (slide)"
    assert page.locator("#input-sliders").is_hidden()           # one input: the player's own
    slide = [v for v in state(page, "window.kinelab.study.columns['slide.q[mm]']") if v is not None]
    stroke = math.sqrt(250 ** 2 - 20 ** 2) - math.sqrt(150 ** 2 - 20 ** 2)  # rod 200, crank 50, offset 20
    assert max(slide) - min(slide) == pytest.approx(stroke, rel=1e-6)


TWO_DOF_SLIDER = {
    "schema": 1, "name": "crank and slide", "units": {"length": "mm", "angle": "deg"},
    "points": {"O2": [0, 0], "A": [0, 50], "C": [100, 60], "B": [180, 20]},
    "links": [{"name": "ground", "points": ["O2"], "ground": True},
              {"name": "crank", "points": ["O2", "A"]}, {"name": "rod1", "points": ["A", "C"]},
              {"name": "rod2", "points": ["C", "B"]}, {"name": "slider", "points": ["B"]}],
    "joints": [{"type": "R", "links": ["ground", "crank"], "point": "O2"},
               {"type": "R", "links": ["crank", "rod1"], "point": "A"},
               {"type": "R", "links": ["rod1", "rod2"], "point": "C"},
               {"type": "R", "links": ["rod2", "slider"], "point": "B"},
               {"name": "slide", "type": "P", "links": ["ground", "slider"], "point": "B", "axis": 0,
                "origin": "O2"}],
    "inputs": [{"joint": "jO2", "range": [60, 120], "speed": 360},
               {"joint": "slide", "range": [180, 200], "speed": 100}],
}


def test_a_slide_given_back_as_a_second_input_moves_on_its_slider(page, tmp_path):
    """A crank and a slide driving a two-link chain: the slide removed, then given back
    with the input tool (a range from the sketch's 180 mm, half the sketch's size long);
    its slider moves the block along the guide, the crank staying, the linkage where
    kl.analyze puts it."""
    import json
    path = tmp_path / "crank_and_slide.json"
    path.write_text(json.dumps(TWO_DOF_SLIDER))
    page.set_input_files("#load", str(path))
    page.wait_for_function("() => window.kinelab.source === 'crank_and_slide.json' && window.kinelab.study "
                           "&& window.kinelab.config !== null", timeout=120_000)
    page.click("#tabs button[data-tab=table]")
    page.click("#tab-table tr[data-input=slide] td[data-field=remove] button")
    page.wait_for_selector("#status.error", timeout=120_000)
    assert "give it 2 input(s)" in status(page)
    give_input(page, "B", 2)
    until_studied(page)
    model = state(page, "window.kinelab.model")
    assert model["inputs"][1] == {"joint": "slide", "range": [180, 270], "speed": 180}
    assert page.inner_text("#tab-table tr[data-input=slide] td[data-field=kind]") == "P (slide)"
    q = [60.0, 180.0]
    for k, value in ((1, 185.0), (0, 80.0)):
        q[k] = value
        page.fill(f"#input-sliders input[data-input={['jO2', 'slide'][k]}]", repr(value))
        page.wait_for_function(
            f"() => window.kinelab.config && Math.abs(window.kinelab.config.q[0] - {q[0]}) < 1e-9 "
            f"&& Math.abs(window.kinelab.config.q[1] - {q[1]}) < 1e-9", timeout=60_000)
        page.shot(f"slide_slider_{k}")
        mf = ModelFile.from_dict(model)
        sol = kl.analyze(mf.mechanism, [math.radians(q[0]), q[1] / 1000])
        for p in ("B", "C"):
            expected = mf.units.convert(sol.position(p).reshape(2), "m")
            shown = state(page, f"window.kinelab.config.points.{p}")
            assert np.max(np.abs(np.array(shown) - expected)) <= 1e-9 * 180
    assert state(page, "window.kinelab.config.points.B") == pytest.approx([185, 20], abs=1e-9)
    # out of reach: the reason, and the linkage stays where it was
    page.fill("#input-sliders input[data-input=slide]", "200")
    page.wait_for_selector("#status.error", timeout=60_000)
    assert "cannot close at 'jO2' = 80 deg, 'slide' = 200 mm" in status(page)
    assert state(page, "window.kinelab.config.q") == pytest.approx(q, abs=1e-9)
    assert state(page, "window.kinelab.model") == model


# -- the server ---------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def client():
    from starlette.testclient import TestClient

    from kinelab.web import create_app
    with TestClient(create_app(), base_url="http://127.0.0.1:8000") as c:
        yield c


def test_the_study_gives_each_of_several_inputs_without_a_range_one_from_the_sketch(client):
    """The five-bar without its ranges: each a full turn from the sketch's angle, in the
    model's units, in the model sent back; the sweep starts at the sketch, and one sample
    asked for at a pair answers where kl.analyze puts it.  A model of one input, or of
    ranges given, keeps them as they are; a bad range is a 400 with the reason."""
    mf = ModelFile.read(Path(ROOT) / "examples" / "fivebar.toml")
    model = mf.to_dict()
    for i in model["inputs"]:
        del i["range"]
    r = client.post("/api/study", json={"model": model, "source": "fivebar.json"})
    assert r.status_code == 200, r.text
    s = r.json()
    assert [i["range"] for i in s["model"]["inputs"]] == [[90, 450], [0, 360]]
    assert s["columns"]["jO2.q[deg]"][0] == 90 and s["columns"]["jO4.q[deg]"][-1] == 360
    assert s["columns"]["P.x[mm]"][0] == pytest.approx(144.72136, abs=1e-5)
    assert s["moved"] == {} and s["unassembled"] == []
    c = client.post("/api/configuration", json={"model": model, "q": [120, 30]}).json()
    expected = mf.units.convert(kl.analyze(mf.mechanism, np.radians([120, 30])).position("P").reshape(2), "m")
    assert c["points"]["P"] == pytest.approx(expected, abs=1e-9)
    # given ranges, or one input: as they are
    given = mf.to_dict()
    assert client.post("/api/study", json={"model": given}).json()["model"]["inputs"] == given["inputs"]
    one = ModelFile.read(Path(ROOT) / "examples" / "crank_rocker.toml").to_dict()
    one["inputs"][0].pop("range", None)
    assert "range" not in client.post("/api/study", json={"model": one}).json()["model"]["inputs"][0]
    # a bad range: the reason, not a 500
    model["inputs"][1]["range"] = [0, 90, 180]
    r = client.post("/api/study", json={"model": model})
    assert r.status_code == 400 and "inputs[1].range: expected 2 numbers" in r.json()["error"]
