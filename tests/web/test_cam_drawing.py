"""Cams on the page: the server sends each cam joint's profile in the cam's own frame (its
centre, its follower's contact point, its base circle), and the page draws it once a model
and turns it with the cam's analysed angle, a transform a frame.  The payload is checked
against kinelab's motion program (an in-line knife-edge: radius base + S(theta)) and the
analysis (the drawn cam touches its follower at every sample); the page is read back from
its own elements (the profile's transform, the browser's matrix of it) in Chromium."""
import math
import re

import numpy as np
import pytest
from starlette.testclient import TestClient

import kinelab as kl
from kinelab.io import ModelFile
from kinelab.web import create_app
from tests.web.test_api import model_of
from tests.web.test_browser import browser, page, server, state, type_in_table  # noqa: F401
from tests.web.test_gears import analysed, angle_gap, scrub_to
from tests.web.test_studio import open_example

CAM_EXAMPLES = ["cam_follower", "cam_rocker_slider"]


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url="http://127.0.0.1:8000") as c:
        yield c


def turned(xy, angle):
    """Points (N, 2) turned counterclockwise by ``angle`` (rad, scalar or (N,))."""
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1]], -1)


# -- the payload ---------------------------------------------------------------------------
def test_an_in_line_knife_edges_profile_is_at_base_plus_S(client):
    """cam_follower: the follower's foot F is 50 mm above the cam's centre O in the sketch,
    where theta = 0 and S = 0 (by hand, from the file), so the base circle is 50 mm; every
    profile point, in the cam's frame, is at radius 50 + S(theta) (kinelab's program, mm)
    and at the polar angle 90 deg - theta (the edge on +y, turned back by the cam's angle),
    to 1e-9 mm."""
    mf, model = model_of("cam_follower")
    s = client.post("/api/study", json={"model": model}).json()
    [cam] = s["drawing"]["cams"]
    assert {k: cam[k] for k in ("joint", "cam", "follower", "motion", "centre", "contact",
                                "follower_joint", "kind")} == {
        "joint": "contact", "cam": "cam", "follower": "follower", "motion": "translating",
        "centre": "O", "contact": "F", "follower_joint": "guide", "kind": "profile"}
    assert cam["base_radius"] == pytest.approx(50.0, abs=1e-12)
    theta = np.array(cam["theta"])
    assert len(theta) == 721 and theta[0] == 0 and theta[-1] == pytest.approx(2 * np.pi, abs=1e-15)
    S = kl.cams.motion(mf.mechanism.joint("contact").program, theta).S
    P = np.array(cam["profile"])
    r = 50.0 + 1000.0 * np.reshape(S, -1)                            # m -> mm
    assert np.abs(np.hypot(*P.T) - r).max() < 1e-9
    expected = np.stack([r * np.sin(theta), r * np.cos(theta)], -1)   # (0, r) turned by -theta
    assert np.abs(P - expected).max() < 1e-9
    assert np.ptp(r) == pytest.approx(20.0, abs=1e-9)                # the lift, 20 mm
    assert set(s["turns"]) == {"cam"}


@pytest.mark.parametrize("name", CAM_EXAMPLES)
def test_the_drawn_cam_touches_its_follower_at_every_sample(client, name):
    """At every sample of the sweep (5 deg apart; the profile's are 0.5 deg), the profile's
    point at the cam's angle, turned by that angle (the page's ``turns``) and carried to the
    centre, is the follower's contact point, kinelab's, to 1e-9 mm; the rocker's base circle
    is its point B's distance from O in the sketch (S = 0 there): sqrt(10**2 + 100**2)."""
    mf, model = model_of(name)
    s = client.post("/api/study", json={"model": model}).json()
    [cam] = s["drawing"]["cams"]
    q = np.radians(s["columns"][s["inputs"][0]])
    sol = kl.analyze(mf.mechanism, q)
    u = np.array(s["turns"]["cam"])
    assert np.abs(u - np.stack([np.cos(sol.angle("cam")), np.sin(sol.angle("cam"))], -1)).max() < 1e-12
    P = np.array(cam["profile"])[np.arange(len(q)) * 10]
    drawn = sol.position(cam["centre"]) * 1000 + turned(P, np.arctan2(u[:, 1], u[:, 0]))
    assert np.abs(drawn - sol.position(cam["contact"]) * 1000).max() < 1e-9
    if name == "cam_rocker_slider":
        assert cam["motion"] == "oscillating" and cam["kind"] == "pitch" and cam["contact"] == "B"
        assert cam["base_radius"] == pytest.approx(math.hypot(10, 100), abs=1e-12)


def _placed(points=None, axis=None):
    def edit(model):
        model["points"].update(points or {})
        if axis is not None:
            next(j for j in model["joints"] if j.get("name") == "guide")["axis"] = axis
    return edit


@pytest.mark.parametrize("label, edit", [
    ("offset", _placed({"F": [12, 50]})),
    ("below, sliding down", _placed({"F": [0, -50]}, [0, -1])),
    ("tilted line", _placed({"F": [30, 40]}, [0.6, 0.8])),
    ("sketched at 45 deg", _placed({"M": [30, 30]})),
])
def test_a_translating_followers_cam_touches_it_wherever_it_is_drawn(client, label, edit):
    """cam_follower with its follower offset, below the cam sliding down, on a tilted line,
    or the cam sketched at 45 deg (S not 0 there): at inputs on the profile's half-degree
    grid the drawn cam touches the follower's foot F, kinelab's, to 1e-9 mm."""
    _, model = model_of("cam_follower")
    edit(model)
    s = client.post("/api/study", json={"model": model}).json()
    [cam] = s["drawing"]["cams"]
    mf = ModelFile.from_dict(s["model"])
    q = np.radians(np.arange(0, 360, 17.5))
    sol = kl.analyze(mf.mechanism, q)
    a = sol.angle("cam")
    k = np.round(np.mod(a, 2 * np.pi) / np.radians(0.5)).astype(int)
    drawn = sol.position("O") * 1000 + turned(np.array(cam["profile"])[k], a)
    assert np.abs(drawn - sol.position("F") * 1000).max() < 1e-9


def test_a_follower_pushed_towards_the_cams_centre_gets_no_profile(client):
    _, model = model_of("cam_follower")
    _placed({"F": [0, -50]})(model)
    [cam] = client.post("/api/study", json={"model": model}).json()["drawing"]["cams"]
    assert cam["profile"] is None and "points towards the cam's centre" in cam["problem"]


def test_a_model_without_cams_sends_none(client):
    _, model = model_of("crank_rocker")
    assert client.post("/api/study", json={"model": model}).json()["drawing"]["cams"] == []


# -- the page ------------------------------------------------------------------------------
# Each cam element drawn: its class, data-cam, and for the profile its transform's numbers
# (translate X Y, scale s -s, rotate deg), its outline's vertices and the browser's own
# matrix (getCTM) applied to the vertex `at` (model units, via the view).
DRAWN = """(at) => {
  const v = window.kinelab.canvas.view;
  const m = (X, Y) => [(X - v.ox) / v.s, (v.oy - Y) / v.s];
  const out = [];
  for (const e of document.querySelectorAll("#canvas [data-layer=cams] [data-cam]")) {
    const a = (k) => +e.getAttribute(k);
    const item = {joint: e.dataset.cam, kind: e.getAttribute("class"), tag: e.localName};
    if (e.localName === "circle") Object.assign(item, {centre: m(a("cx"), a("cy")), radius: a("r") / v.s});
    if (e.localName === "line") Object.assign(item, {from: m(a("x1"), a("y1")), to: m(a("x2"), a("y2"))});
    if (e.localName === "path") {
      item.transform = e.getAttribute("transform");
      item.vertices = (e.getAttribute("d").match(/[ML]/g) || []).length;
      if (at !== null) {
        const n = e.getAttribute("d").split(/[ML]/).filter((t) => t.trim())[at].trim().split(/\\s+/).map(Number);
        const p = new DOMPoint(n[0], n[1]).matrixTransform(e.getCTM());
        item.at = m(p.x, p.y);
      }
    }
    out.push(item);
  }
  return out;
}"""
TRANSFORM = re.compile(r"translate\((\S+) (\S+)\) scale\((\S+) (\S+)\) rotate\((\S+)\)")


def drawn(pg, at=None):
    return pg.evaluate(DRAWN, at)


@pytest.mark.parametrize("name", CAM_EXAMPLES)
def test_every_cam_example_opens_and_plays(page, name):
    """Opened from the list: the profile (721 vertices), the base circle, the contact
    marked, a translating follower's line of motion; played for a while with no error on
    the page (nor in the console) nor in the status line."""
    console = []
    page.on("console", lambda m: console.append(m.text) if m.type == "error" else None)
    open_example(page, name)
    kinds = sorted(d["kind"] for d in drawn(page))
    profile = "cam-profile" if name == "cam_follower" else "cam-profile cam-pitch"
    assert kinds == sorted([profile, "cam-base", "cam-contact"] +
                           (["cam-line"] if name == "cam_follower" else [])), kinds
    assert next(d for d in drawn(page) if d["tag"] == "path")["vertices"] == 721
    start = state(page, "window.kinelab.index")
    page.click("#play")
    page.wait_for_function(f"() => window.kinelab.index !== {start}", timeout=60_000)
    page.wait_for_timeout(600)
    page.click("#play")
    page.shot(f"{name} played")
    assert not page.locator("#status.error").count(), page.inner_text("#status")
    assert not console, console


@pytest.mark.parametrize("name", CAM_EXAMPLES)
def test_the_cam_turns_with_the_input_and_touches_its_follower(page, name):
    """Scrubbed to a few inputs: the profile's transform carries it to the cam's centre at
    the view's scale, turned by the cam's angle (kinelab's at the page's input) to 1e-9
    rad; the profile's vertex at that angle, placed by the browser's own matrix, is the
    follower's contact point (kinelab's) to 1e-6 of the cam's size; the base circle sits
    on the centre, the contact mark on the contact point; the outline is never redrawn."""
    open_example(page, name)
    cam = state(page, "window.kinelab.study.drawing.cams[0]")
    outline = page.evaluate("() => document.querySelector('#canvas .cam-profile').getAttribute('d')")
    n = state(page, "window.kinelab.study.samples")
    angles = []
    for index in (0, 7, 20, n // 2, n - 3):
        scrub_to(page, index)
        sol = analysed(page)
        view = state(page, "window.kinelab.canvas.view")
        items = drawn(page, 10 * index)
        path = next(d for d in items if d["tag"] == "path")
        X, Y, sx, sy, deg = map(float, TRANSFORM.fullmatch(path["transform"]).groups())
        centre = np.reshape(sol.position(cam["centre"]), 2) * 1000          # m -> mm
        assert [(X - view["ox"]) / view["s"], (view["oy"] - Y) / view["s"]] == pytest.approx(
            centre.tolist(), abs=1e-9)
        assert (sx, sy) == (view["s"], -view["s"])
        theta = float(sol.angle("cam"))
        assert angle_gap(math.radians(deg), theta) < 1e-9, (index, deg, theta)
        contact = np.reshape(sol.position(cam["contact"]), 2) * 1000
        assert np.abs(np.array(path["at"]) - contact).max() < 1e-6 * cam["base_radius"], (index, path["at"])
        base = next(d for d in items if d["kind"] == "cam-base")
        assert base["centre"] == pytest.approx(centre.tolist(), abs=1e-9)
        assert base["radius"] == pytest.approx(cam["base_radius"], rel=1e-12)
        mark = next(d for d in items if d["kind"] == "cam-contact")
        assert mark["centre"] == pytest.approx(contact.tolist(), abs=1e-9)
        if name == "cam_follower":              # the line of motion: through F, along +y
            line = next(d for d in items if d["kind"] == "cam-line")
            assert line["from"][0] == pytest.approx(0, abs=1e-9) and line["to"][0] == pytest.approx(0, abs=1e-9)
            assert line["from"][1] < 0 < contact[1] < line["to"][1]
        angles.append(theta)
        page.shot(f"{name} {index}")
    assert np.ptp(np.unwrap(angles)) > 3            # it did turn
    assert page.evaluate("() => document.querySelector('#canvas .cam-profile').getAttribute('d')") == outline


def test_playing_changes_only_the_profiles_transform(page):
    """While the animation plays, the profile path's transform changes and its outline
    (721 vertices) is never set again: a frame turns the cam, it does not redraw it."""
    open_example(page, "cam_follower")
    page.evaluate("""() => {
      window.camChanges = {d: 0, transform: 0};
      const e = document.querySelector('#canvas .cam-profile');
      new MutationObserver((records) => { for (const r of records) window.camChanges[r.attributeName] += 1; })
        .observe(e, {attributes: true, attributeFilter: ['d', 'transform']});
      window.camElement = e;
    }""")
    frames = state(page, "window.kinelab.frames")
    page.click("#play")
    page.wait_for_function(f"() => window.kinelab.frames > {frames} + 20", timeout=60_000)
    page.click("#play")
    changes = state(page, "window.camChanges")
    assert changes["transform"] >= 20 and changes["d"] == 0, changes
    assert state(page, "document.querySelector('#canvas .cam-profile') === window.camElement")


def test_switching_models_clears_the_cam(page):
    """A cam model, then one without cams: nothing of the cam is left on the drawing; then
    the other cam example: its own cam alone (the rocker's pitch curve, its contact B)."""
    open_example(page, "cam_follower")
    assert len(drawn(page)) == 4
    open_example(page, "crank_rocker")
    assert drawn(page) == [] and state(page, "window.kinelab.study.drawing.cams") == []
    page.click("#new")
    page.wait_for_function("() => window.kinelab.study === null")
    assert drawn(page) == []
    open_example(page, "cam_rocker_slider")
    items = drawn(page)
    assert sorted(d["kind"] for d in items) == ["cam-base", "cam-contact", "cam-profile cam-pitch"]
    contact = state(page, "window.kinelab.config.points.B")
    mark = next(d for d in items if d["kind"] == "cam-contact")
    assert mark["centre"] == pytest.approx(contact, abs=1e-9)


def test_dragging_the_cam_turns_it_and_editing_the_follower_redraws_it(page):
    """The move tool drags the cam's mark M round O: the profile turns with the cam
    (kinelab's angle at the page's input, 1e-9 rad) while the page stays free of errors.
    Then the follower's foot F typed 60 mm above O in the table: the base circle the new
    sketch implies is 60 mm, and the profile's radius 60 + S(theta)."""
    open_example(page, "cam_follower")
    centre = page.locator("#canvas circle[data-point='O']").bounding_box()
    o = (centre["x"] + centre["width"] / 2, centre["y"] + centre["height"] / 2)
    box = page.locator("#canvas circle[data-point='M']").bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    r = math.hypot(x - o[0], y - o[1])
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 11):
        a = math.radians(9 * k)
        page.mouse.move(o[0] + r * math.cos(a), o[1] - r * math.sin(a))
    page.mouse.up()
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending", timeout=60_000)
    page.wait_for_timeout(200)
    page.shot("cam dragged")
    sol = analysed(page)
    assert float(sol.angle("cam")) == pytest.approx(math.radians(90), abs=math.radians(4))
    path = next(d for d in drawn(page) if d["tag"] == "path")
    deg = float(TRANSFORM.fullmatch(path["transform"]).group(5))
    assert angle_gap(math.radians(deg), float(sol.angle("cam"))) < 1e-9
    assert not page.locator("#status.error").count(), page.inner_text("#status")

    page.click("#tabs button[data-tab=table]")
    type_in_table(page, "tr[data-point=F] td[data-field=y]", 60)
    page.wait_for_function("() => window.kinelab.study && window.kinelab.study.drawing.cams.length"
                           " && Math.abs(window.kinelab.study.drawing.cams[0].base_radius - 60) < 1e-9"
                           " && !window.kinelab.busy && !window.kinelab.pending", timeout=60_000)
    page.shot("cam follower edited")
    cam = state(page, "window.kinelab.study.drawing.cams[0]")
    model = ModelFile.from_dict(state(page, "window.kinelab.model"))
    S = np.reshape(model.mechanism.joint("contact").program.svaj(np.array(cam["theta"])).S, -1)
    assert np.abs(np.hypot(*np.array(cam["profile"]).T) - (60 + 1000 * S)).max() < 1e-9
    base = next(d for d in drawn(page) if d["kind"] == "cam-base")
    assert base["radius"] == pytest.approx(60, rel=1e-12)
    assert not page.locator("#status.error").count(), page.inner_text("#status")
