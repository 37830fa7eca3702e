"""Dragging in the page, end to end, in Chromium: from each pointer event to the painted
frame that shows it (or a later one), over a few hundred pointer moves at 60 a second.

- ``move four-bar``: the move tool drags the crank-rocker example's coupler point P along
  its path (the linkage follows, solved one configuration at a time);
- ``move six-bar``: the same with the Stephenson six-bar example's coupler point C, and
  ``move six-bar input`` with its crank pin A;
- ``edit six-bar``: the edit tool drags the six-bar's C around a small circle: every move
  changes the design, and the server re-assembles it and sweeps its whole cycle again (361
  samples) before the page redraws it.

The page is watched from outside (a script added before its own): the time of each pointer
event as the page receives it, and the time each frame that changes the drawing is painted
(a message posted after the frame's animation callbacks) with the place the dragged point
is drawn at.  A frame answers pointer event j when the point is drawn where event j (or a
later one) put it; each event's time is the wait until the first such frame, so a move
that a newer one overtakes counts until the newer one shows.  Beside each line: the
server's time per request (the browser's resource timing, from sending the request to the
first byte of the answer), and the load average of the machine (the numbers move with it).
The move tool draws each move at once from the sweep (the page's follow.js) and the
server's solve replaces it when it comes: under each move line, the time from the move to
the server's solve drawn, by the page's own clock (``window.kinelab.answers``).

Needs Chromium (Debian's, /usr/bin/chromium, or KINELAB_CHROMIUM) and Playwright.
"""
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
PERIOD = 1 / 60          # s between two pointer moves: a mouse at 60 events a second

# Watches the page: pointer events (capture, before the page's own handlers), and each
# frame that changes the drawing, timed after it is painted.
WATCH = """
(() => {
  const bench = window.__bench = {events: [], frames: [], point: null, inFrame: false};
  performance.setResourceTimingBufferSize(100000);
  const raf = window.requestAnimationFrame.bind(window);
  // a change made in an animation callback is painted in that frame; others in the next
  window.requestAnimationFrame = (cb) => raf((t) => {
    bench.inFrame = true;
    try { cb(t); } finally { queueMicrotask(() => { bench.inFrame = false; }); }
  });
  window.addEventListener("pointermove", (e) => {
    if (e.buttons) bench.events.push([performance.now(), e.clientX, e.clientY]);
  }, true);
  const painted = (where) => {
    const ch = new MessageChannel();
    ch.port1.onmessage = () => bench.frames.push([performance.now(), where]);
    ch.port2.postMessage(0);
  };
  const watch = () => {
    const svg = document.getElementById("canvas");
    if (!svg) { setTimeout(watch, 10); return; }
    let waiting = false;
    new MutationObserver(() => {
      if (!bench.point || waiting) return;
      const read = () => {
        const c = svg.querySelector(`circle[data-point='${bench.point}']`);
        if (!c) return null;
        const r = svg.getBoundingClientRect();
        return [r.left + Number(c.getAttribute("cx")), r.top + Number(c.getAttribute("cy"))];
      };
      if (bench.inFrame) { painted(read()); return; }
      waiting = true;
      raf(() => { waiting = false; painted(read()); });
    }).observe(svg, {subtree: true, childList: true, attributes: true});
  };
  watch();
})();
"""


def chromium() -> str:
    found = os.environ.get("KINELAB_CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
    return found


def centre(page, name):
    for _ in range(100):          # a page that redraws by replacing its elements
        box = page.locator(f"#canvas circle[data-point='{name}']").bounding_box()
        if box is not None:
            return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        page.wait_for_timeout(20)
    raise RuntimeError(f"point {name} is not drawn")


def to_screen(page):
    """The drawing's map from model units to the page's pixels, from two ground pivots."""
    pts = page.evaluate("() => window.kinelab.model.points")
    (X0, Y0), (X1, Y1) = centre(page, "O2"), centre(page, "O4")
    (x0, y0), (x1, y1) = pts["O2"], pts["O4"]
    s = math.hypot(X1 - X0, Y1 - Y0) / math.hypot(x1 - x0, y1 - y0)
    return lambda x, y: (X0 + s * (x - x0), Y0 - s * (y - y0))


def open_example(page, name):
    page.select_option("#open", name)
    page.wait_for_function(f"() => (window.kinelab.source || '').startsWith('{name}') "
                           "&& window.kinelab.study && window.kinelab.config !== null",
                           timeout=120_000)
    page.wait_for_timeout(300)


def drag(page, point, targets, route):
    """Press on ``point``, move through ``targets`` (page pixels) at 60 moves a second,
    release; each event's wait for a frame that shows it, and the server's time of each
    request to ``route`` meanwhile (ms)."""
    page.evaluate(f"() => {{ window.__bench.events = []; window.__bench.frames = []; "
                  f"window.__bench.point = '{point}'; performance.clearResourceTimings(); "
                  "if (window.kinelab.answers) window.kinelab.answers.length = 0; }")
    x, y = centre(page, point)
    page.mouse.move(x, y)
    page.mouse.down()
    start = time.perf_counter()
    for k, (tx, ty) in enumerate(targets):
        wait = start + (k + 1) * PERIOD - time.perf_counter()
        if wait > 0:
            time.sleep(wait)
        page.mouse.move(tx, ty)
    page.wait_for_timeout(100)
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending", timeout=120_000)
    page.wait_for_timeout(300)
    page.mouse.up()
    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending", timeout=120_000)
    bench = page.evaluate("() => ({events: window.__bench.events, frames: window.__bench.frames, "
                          "answers: window.kinelab.answers || []})")
    server = page.evaluate(f"""() => performance.getEntriesByType("resource")
        .filter((e) => e.name.endsWith("{route}") && e.responseStart > 0)
        .map((e) => e.responseStart - e.requestStart)""")
    page.evaluate("() => { window.__bench.point = null; }")
    return waits(bench["events"], bench["frames"]), server, bench["answers"]


def waits(events, frames):
    """Each pointer event's wait (ms) until the first painted frame that draws the point
    where that event, or a later one, put it (the nearest of the events so far)."""
    out, answered, f = [], -1, 0
    shown = []                    # (painted at, the latest event answered by then)
    for t, where in frames:
        if where is None:
            continue
        sent = sum(1 for e in events if e[0] <= t)
        lo = max(answered, 0)
        if sent <= lo:
            continue
        j = min(range(lo, sent), key=lambda i: math.dist(where, events[i][1:]))
        if math.dist(where, events[j][1:]) > 3.0:       # px: not one of the pointer's places
            continue
        answered = max(answered, j)
        shown.append((t, answered))
    for j, (t, *_) in enumerate(events):
        while f < len(shown) and (shown[f][1] < j or shown[f][0] < t):
            f += 1
        if f == len(shown):
            break
        out.append(shown[f][0] - t)
    return out, len(events)


def p95(values):
    return statistics.quantiles(values, n=20)[-1] if len(values) > 1 else values[0]


def report(label, result, server, answers):
    (times, moves) = result
    line = (f"{label}: median {statistics.median(times):.1f} ms, p95 {p95(times):.1f} ms; "
            f"server {statistics.median(server):.1f} ms per request (median, p95 "
            f"{p95(server):.1f} ms; {len(server)} requests for {moves} moves, {len(times)} "
            "shown)")
    print(line, flush=True)
    if answers and label.startswith("move"):
        # the move tool draws the sweep's interpolation at once; the server's solve of a
        # move replaces it when it comes (the page's own clock, from the move's handler)
        print(f"  {label}, the server's solve drawn: median {statistics.median(answers):.1f} ms, "
              f"p95 {p95(answers):.1f} ms after the move ({len(answers)} answers drawn)", flush=True)


def main(moves: int = 240) -> None:
    from playwright.sync_api import sync_playwright

    print(f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())} "
          f"({os.cpu_count()} processors)", flush=True)
    proc = subprocess.Popen([sys.executable, "-c", "from kinelab.cli import main; main()", "serve",
                             "--port", "0"], stdout=subprocess.PIPE, text=True, cwd=ROOT)
    try:
        url = re.search(r"http://\S+", proc.stdout.readline()).group(0)
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=chromium(), args=FLAGS)
            page = browser.new_page(viewport={"width": 1300, "height": 820})
            page.add_init_script(WATCH)
            page.goto(url)
            page.wait_for_selector("body[data-ready='1']", timeout=180_000)
            for label, example, point in (("move four-bar", "crank_rocker", "P"),
                                          ("move six-bar", "stephenson6", "C"),
                                          ("move six-bar input", "stephenson6", "A")):
                open_example(page, example)
                page.check("input[name=tool][value=move]")
                screen = to_screen(page)
                study = page.evaluate("() => window.kinelab.study")
                u = study["units"]["length"]
                xs, ys = study["columns"][f"{point}.x[{u}]"], study["columns"][f"{point}.y[{u}]"]
                i0 = page.evaluate("() => window.kinelab.index")
                n = study["samples"]
                # along the point's path, a sample (1 deg) a move, onwards from where it is
                targets = [screen(xs[(i0 + k) % n], ys[(i0 + k) % n]) for k in range(1, moves + 1)]
                drag(page, point, targets[:20], "/api/drag")          # warm up
                report(label, *drag(page, point, targets, "/api/drag"))
            open_example(page, "stephenson6")
            page.check("input[name=tool][value=edit]")
            x, y = centre(page, "C")
            targets = [(x + 8 * math.sin(2 * math.pi * k / moves), y - 8 + 8 * math.cos(2 * math.pi * k / moves))
                       for k in range(1, moves + 1)]
            drag(page, "C", targets[:20], "/api/study")
            page.click("#undo")
            page.wait_for_timeout(500)
            report("edit six-bar", *drag(page, "C", targets, "/api/study"))
            browser.close()
    finally:
        proc.terminate()
        proc.wait()
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 240)
