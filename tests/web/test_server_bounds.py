"""The server against hostile requests: one request cannot exhaust it (sizes refused before
the work, memory shared by the requests in flight, the sweeps kept bounded in bytes, long
work off the event loop and within its time), it answers its own page only (Host, Origin,
Content-Type), and a client that goes away is not a fault.  Every error is JSON."""
import json
import re
import socket
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from starlette.testclient import TestClient

import kinelab as kl
from kinelab.io import ModelFile
from kinelab.model import MAX_LINKS
from kinelab.web import _api, _limits, create_app
from tests.derive.cases import four_slider_dyads
from tests.web.models import serving

ROOT = Path(__file__).resolve().parents[2]
ADDRESS = "http://127.0.0.1:8000"
MARGIN = 20.0       # s a loaded machine may take beyond what a bound promises


def chain_of_dyads() -> dict:
    """A crank driving 99 RRR dyads side by side: 200 links, the most a model may have (a
    50 KB body), and over 3,000 columns of results."""
    points, links, joints = {"O": [0.0, 0.0], "A": [0.0, 0.1]}, [], []
    for i in range((MAX_LINKS - 2) // 2):
        a = 2 * np.pi * i / 99
        points[f"G{i}"] = [np.cos(a), np.sin(a)]
        points[f"C{i}"] = [0.5 * np.cos(a) - 0.3 * np.sin(a),
                           0.05 + 0.5 * np.sin(a) + 0.3 * np.cos(a)]
        links += [{"name": f"a{i}", "points": ["A", f"C{i}"]},
                  {"name": f"b{i}", "points": [f"C{i}", f"G{i}"]}]
        joints += [{"name": f"jA{i}", "type": "R", "links": ["crank", f"a{i}"], "point": "A"},
                   {"name": f"jC{i}", "type": "R", "links": [f"a{i}", f"b{i}"], "point": f"C{i}"},
                   {"name": f"jG{i}", "type": "R", "links": ["ground", f"b{i}"], "point": f"G{i}"}]
    ground = {"name": "ground", "points": ["O"] + [f"G{i}" for i in range(99)], "ground": True}
    links = [ground, {"name": "crank", "points": ["O", "A"]}] + links
    joints.insert(0, {"name": "jO", "type": "R", "links": ["ground", "crank"], "point": "O"})
    return {"schema": 1, "name": "chain", "units": {"length": "m", "angle": "rad"},
            "points": points, "links": links, "joints": joints, "inputs": [{"joint": "jO"}]}


CHAIN = chain_of_dyads()
CRANK_ROCKER = ModelFile.read(ROOT / "examples" / "crank_rocker.toml").to_dict()


@pytest.fixture
def client():
    with TestClient(create_app(), base_url=ADDRESS) as c:
        yield c


def still_answers(client):
    r = client.post("/api/study", json={"model": CRANK_ROCKER, "samples": 37})
    assert r.status_code == 200 and r.json()["samples"] == 37


# -- sizes, before the work ---------------------------------------------------------------------
@pytest.mark.parametrize("route, extra", [("/api/study", {}), ("/api/analyze", {}),
                                          ("/api/export", {"kind": "json"}),
                                          ("/api/export", {"kind": "csv"})])
def test_samples_times_columns_past_the_bound_is_refused_fast(client, route, extra):
    assert len(json.dumps({"model": CHAIN})) < 60_000
    start = time.perf_counter()
    r = client.post(route, json={"model": CHAIN, "samples": 20_000, **extra})
    assert time.perf_counter() - start < MARGIN       # read and refused, not swept
    assert r.status_code == 413 and r.headers["content-type"] == "application/json"
    error = r.json()["error"]
    # the estimate and the limit, and what to do
    assert re.search(r"a (JSON|CSV) table of 20,000 rows x [\d,]+ columns is [\d,]+ values; "
                     r"kinelab writes at most [\d,]+ as (JSON|CSV) .*: ask for at most [\d,]+ "
                     "rows", error), error
    assert _limits.in_flight() == 0
    still_answers(client)


def test_a_sweep_past_the_memory_budget_is_refused_with_the_estimate(client):
    old = kl.memory_budget("64M")
    try:
        r = client.post("/api/study", json={"model": CHAIN, "samples": 2_000})
    finally:
        kl.memory_budget(old)
    assert r.status_code == 413
    assert re.search(r"the answer \(2,000 samples x [\d,]+ columns\) would take about [\d.]+ "
                     r"(MiB|GiB), more than the memory budget of 64 MiB", r.json()["error"])
    still_answers(client)


def test_the_estimate_of_a_sweep_bounds_what_it_takes(monkeypatch):
    """The bytes the server reserves for a study and for an analysis are at least what
    Python and numpy allocate for them at their peak (as tracemalloc counts it)."""
    import tracemalloc
    mf = ModelFile.from_dict(CHAIN)
    for call, answer in ((_api.study, "columns"), (_api.analyze, "rows")):
        estimate = _limits.sweep_cost(mf, 100, answer)[0]
        tracemalloc.start()
        try:
            base = tracemalloc.get_traced_memory()[0]
            result = call({"model": CHAIN, "samples": 100, "source": f"{answer}.json"})
            text = result if isinstance(result, str) else json.dumps(result, allow_nan=False)
            text.encode()
            peak = tracemalloc.get_traced_memory()[1] - base
        finally:
            tracemalloc.stop()
        assert peak <= estimate, (answer, peak, estimate)


def test_requests_in_flight_share_the_budget(client, monkeypatch):
    """While memory is held by requests in flight, one that needs more waits, and past the
    wait is answered 503; what is held is given back when the requests end."""
    monkeypatch.setattr(_limits, "WAIT", 0.5)
    held, release = threading.Event(), threading.Event()

    def hog():
        with _limits.request():
            _limits.require(kl.memory_budget() - 1000, "a large request", "ask for less")
            held.set()
            release.wait(60)
    other = threading.Thread(target=hog)
    other.start()
    try:
        assert held.wait(60)
        r = client.post("/api/study", json={"model": CRANK_ROCKER, "samples": 5000})
        assert r.status_code == 503 and "busy with other large requests" in r.json()["error"]
    finally:
        release.set()
        other.join(60)
    assert _limits.in_flight() == 0
    still_answers(client)


def test_the_sweeps_kept_are_bounded_in_bytes(client, monkeypatch):
    monkeypatch.setattr(_limits, "cache_bytes", lambda: 2_000_000)
    _api._PREPARED.clear()
    sizes = []
    for k in range(6):          # each sweep of the six-bar, 2,000 samples, is about 1 MB
        model = ModelFile.read(ROOT / "examples" / "stephenson6.toml").to_dict()
        r = client.post("/api/study", json={"model": model, "samples": 2000, "source": f"s{k}.toml"})
        assert r.status_code == 200
        sizes.append(_api._PREPARED.held())
        assert _api._PREPARED.held() <= 2_000_000
    assert 1 <= len(_api._PREPARED) < 6
    # a sweep larger than the whole cache is answered, not kept
    r = client.post("/api/study", json={"model": CHAIN, "samples": 400})
    assert r.status_code == 200 and _api._PREPARED.held() <= 2_000_000
    _api._PREPARED.clear()


def test_a_derivation_stops_at_the_servers_limit(client, monkeypatch):
    monkeypatch.setattr(_api, "DERIVE_SECONDS", 2.0)
    start = time.perf_counter()
    r = client.post("/api/derive", json={"model": four_slider_dyads()})
    assert time.perf_counter() - start < 2.0 + MARGIN
    assert r.status_code == 422
    assert r.json()["error"].startswith("derivation of 'four sliders': it took more than 2 s, "
                                        "the time limit;")
    still_answers(client)


# -- its own page only --------------------------------------------------------------------------
@pytest.mark.parametrize("headers, status, match", [
    ({"origin": "http://evil.example", "content-type": "text/plain"}, 403, r"^Origin: 'http://evil"),
    ({"origin": "http://evil.example"}, 403, r"is another site"),
    ({"origin": "null"}, 403, r"is another site"),
    ({"origin": "http://127.0.0.1:8001"}, 403, r"is another site"),
    ({"host": "evil.example:8000"}, 403, r"^Host: expected the address this server is at, got "
                                          r"'evil.example:8000'"),
    ({"host": "127.0.0.1.evil.example"}, 403, r"^Host:"),
    ({"content-type": "text/plain"}, 415, r"expected a JSON body \(Content-Type: application/json\), "
                                          r"got text/plain"),
    ({"content-type": "application/x-www-form-urlencoded"}, 415, r"expected a JSON body"),
    ({"content-type": "multipart/form-data; boundary=x"}, 415, r"expected a JSON body"),
    ({"content-type": ""}, 415, r"got none"),
])
def test_requests_from_elsewhere_are_refused(client, headers, status, match):
    base = {"content-type": "application/json"}
    r = client.post("/api/study", content=json.dumps({"model": CRANK_ROCKER, "samples": 5}),
                    headers={**base, **headers})
    assert r.status_code == status and r.headers["content-type"] == "application/json"
    assert re.search(match, r.json()["error"]), r.json()


@pytest.mark.parametrize("headers", [{}, {"origin": ADDRESS},
                                     {"content-type": "application/json; charset=utf-8"},
                                     {"host": "localhost:8000", "origin": "http://localhost:8000"},
                                     {"host": "[::1]:8000"}])
def test_the_page_itself_is_answered(client, headers):
    r = client.post("/api/study", content=json.dumps({"model": CRANK_ROCKER, "samples": 5}),
                    headers={"content-type": "application/json", **headers})
    assert r.status_code == 200, r.text


def test_the_page_and_its_files_need_the_right_host_too(client):
    assert client.get("/").status_code == 200
    r = client.get("/", headers={"host": "evil.example"})
    assert r.status_code == 403 and r.json()["error"].startswith("Host:")
    assert client.get("/static/app.css", headers={"host": "evil.example"}).status_code == 403


def test_a_fault_is_json_too(monkeypatch):
    monkeypatch.setattr(_api, "catalogue", lambda: 1 / 0)
    with TestClient(create_app(), base_url=ADDRESS, raise_server_exceptions=False) as c:
        r = c.get("/api/catalogue")
    assert r.status_code == 500 and r.headers["content-type"] == "application/json"
    assert r.json()["error"].startswith("internal error")


# -- a real server on loopback ------------------------------------------------------------------
@pytest.fixture(scope="module")
def server():
    """``kinelab serve --port 0`` with its log (standard error) kept: (port, log lines)."""
    with serving() as running:
        yield running


def http(port: int, method: str, path: str, body: bytes = b"", headers=None):
    """One request over a socket: (status, headers, body)."""
    import http.client
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=300)
    c.request(method, path, body=body, headers=headers or {})
    r = c.getresponse()
    out = r.status, {k.lower(): v for k, v in r.getheaders()}, r.read()
    c.close()
    return out


def post_json(port, path, data, **headers):
    return http(port, "POST", path, json.dumps(data).encode(),
                {"Content-Type": "application/json", **headers})


def test_the_served_app_refuses_and_goes_on(server):
    port, log = server
    status, headers, body = post_json(port, "/api/study", {"model": CHAIN, "samples": 20_000})
    assert status == 413 and headers["content-type"] == "application/json"
    assert "values" in json.loads(body)["error"]
    status, _, body = http(port, "POST", "/api/study", b'{"model": {}}',
                           {"Content-Type": "text/plain", "Origin": "http://evil.example"})
    assert status == 403 and json.loads(body)["error"].startswith("Origin:")
    status, _, body = http(port, "POST", "/api/study", b"{}", {"Content-Type": "text/plain"})
    assert status == 415 and "expected a JSON body" in json.loads(body)["error"]
    status, _, body = post_json(port, "/api/study", {"model": CRANK_ROCKER}, Host="evil.example")
    assert status == 403 and json.loads(body)["error"].startswith("Host:")
    status, _, body = post_json(port, "/api/study", {"model": CRANK_ROCKER, "samples": 9},
                                Origin=f"http://127.0.0.1:{port}")
    assert status == 200 and json.loads(body)["samples"] == 9


def test_a_request_the_server_cannot_read_is_answered_in_json(server):
    port, _ = server
    s = socket.create_connection(("127.0.0.1", port), timeout=30)
    s.sendall(b"NOT HTTP AT ALL\r\n\r\n")
    answer = b""
    while chunk := s.recv(65536):
        answer += chunk
    s.close()
    head, _, body = answer.partition(b"\r\n\r\n")
    assert head.startswith(b"HTTP/1.1 400") and b"content-type: application/json" in head.lower()
    assert json.loads(body)["error"].startswith("request: ")


def test_a_client_that_goes_away_mid_upload_is_not_a_fault(server):
    port, log = server
    for _ in range(3):
        s = socket.create_connection(("127.0.0.1", port), timeout=30)
        s.sendall(f"POST /api/study HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                  "Content-Type: application/json\r\nContent-Length: 100000\r\n\r\n".encode()
                  + b'{"model": ' + b" " * 5000)
        time.sleep(0.2)
        s.close()
    time.sleep(1.0)
    status, _, body = post_json(port, "/api/study", {"model": CRANK_ROCKER, "samples": 9})
    assert status == 200
    time.sleep(0.5)
    text = "".join(log)
    assert "Traceback" not in text and "Exception" not in text and "ERROR" not in text, text


def test_an_animation_stops_at_the_servers_limit(client, monkeypatch):
    from kinelab.web import _export
    monkeypatch.setattr(_export, "ANIMATION_SECONDS", 1.0)
    start = time.perf_counter()
    r = client.post("/api/export", json={"model": CHAIN, "kind": "gif", "samples": 50})
    assert time.perf_counter() - start < 1.0 + MARGIN
    assert r.status_code == 422
    assert r.json()["error"] == ("kind: the animation of 200 links took more than 1 s; make it "
                                 "with kinelab animate, which has no such limit")
    import matplotlib.pyplot as plt
    assert not plt.get_fignums()
    monkeypatch.undo()
    r = client.post("/api/export", json={"model": CRANK_ROCKER, "kind": "gif", "samples": 37})
    assert r.status_code == 200 and r.content.startswith(b"GIF8")
