"""Time from an edit in the page to the redrawn linkage and paths (the browser's clock):
a drag of a six-bar's joint re-assembles and re-sweeps 361 samples on the server, sends
the columns the page redraws, and redraws; beside it, the server's own share (the same
request from Python), and the same sweep with every column (what the page asks for once the
drag ends).

Needs Chromium (Debian's, /usr/bin/chromium) and Playwright; prints best and median of
each, in ms.
"""
import json
import statistics
import subprocess
import sys
import time
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def main(repeats: int = 30) -> None:
    from playwright.sync_api import sync_playwright
    from starlette.testclient import TestClient

    from kinelab.io import ModelFile
    from kinelab.web import create_app

    model = ModelFile.read(ROOT / "examples" / "stephenson6.toml").to_dict()
    client = TestClient(create_app(), base_url="http://127.0.0.1:8000")
    def server_share(columns, tag):
        times = []
        for k in range(repeats):
            body = {"model": json.loads(json.dumps(model)), "samples": 361, "source": f"{tag}{k}"}
            if columns is not None:
                body["columns"] = columns
            t0 = time.perf_counter()
            client.post("/api/study", json=body)
            times.append(1e3 * (time.perf_counter() - t0))
        return times

    # what a drag asks for (the points, the inputs and the plotted column), and every column
    server = server_share(["coupler-rocker.transmission[deg]", "jO2.q[deg]"], "drag")
    every = server_share(None, "every")
    proc = subprocess.Popen([sys.executable, "-c", "from kinelab.cli import main; main()", "serve",
                             "--port", "0", str(ROOT / "examples" / "stephenson6.toml")],
                            stdout=subprocess.PIPE, text=True)
    try:
        url = re.search(r"http://\S+", proc.stdout.readline()).group(0)
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=FLAGS)
            page = browser.new_page(viewport={"width": 1300, "height": 820})
            page.goto(url)
            page.wait_for_selector("body[data-ready='1']", timeout=180_000)
            results = {}
            for tool in ("edit",):
                page.check(f"input[name=tool][value={tool}]")
                times, fetched = [], []
                name = page.evaluate("() => Object.keys(window.kinelab.model.points).find("
                                     "p => !window.kinelab.study.drawing.ground_points.includes(p))")
                for k in range(repeats):
                    page.wait_for_function("() => window.kinelab.config !== null")
                    box = None
                    for _ in range(20):          # the drawing is redrawn when an answer comes
                        box = page.locator(f"#canvas circle[data-point='{name}']").bounding_box()
                        if box is not None:
                            break
                        page.wait_for_timeout(20)
                    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
                    page.mouse.move(x, y)
                    page.mouse.down()
                    page.mouse.move(x + (2 if k % 2 else -2), y + 1)
                    page.wait_for_function("() => !window.kinelab.busy && !window.kinelab.pending")
                    page.mouse.up()
                    times.append(page.evaluate("() => window.kinelab.lastUpdateMs"))
                    fetched.append(page.evaluate("() => window.kinelab.lastDragStudyMs"))
                results[tool] = times
                results["fetch"] = fetched
                results["redraw"] = [t - f for t, f in zip(times, fetched)]
            browser.close()
    finally:
        proc.terminate()
        proc.wait()
    print(f"{'six-bar (Stephenson), 361 samples':40s} {'best ms':>9s} {'median ms':>10s}")
    for label, t in [("edit drag, page end to end", results["edit"]),
                     ("  of which the request and its JSON", results["fetch"]),
                     ("  of which the redraw", results["redraw"]),
                     ("server share of it (same request)", server),
                     ("server, every column of the sweep", every)]:
        print(f"{label:40s} {min(t):9.1f} {statistics.median(t):10.1f}")


if __name__ == "__main__":
    main()
