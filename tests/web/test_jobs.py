"""Long work shows how far it has come and can be stopped: each request is a job (the id in
its body), ``/api/progress`` says what it is doing, ``/api/cancel`` or closing the request
stops the work itself (the thread that ran it is free again), and long work never keeps
short requests waiting."""
import json
import re
import socket
import sys
import threading
import time
import traceback
from pathlib import Path

import pytest
from starlette.testclient import TestClient

from kinelab.io import ModelFile
from kinelab.web import _apart, _app, create_app
from tests.web.models import serving

ROOT = Path(__file__).resolve().parents[2]
ADDRESS = "http://127.0.0.1:8000"
MARGIN = 30.0       # s a loaded machine may take beyond what a bound promises
SIX_BAR = ModelFile.read(ROOT / "examples" / "stephenson6.toml").to_dict()
CRANK_ROCKER = ModelFile.read(ROOT / "examples" / "crank_rocker.toml").to_dict()


@pytest.fixture
def client():
    with TestClient(create_app(), base_url=ADDRESS) as c:
        yield c


def wait_for(condition, seconds=MARGIN, every=0.05):
    """The first true value of ``condition()`` within ``seconds`` (else the test fails)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        value = condition()
        if value:
            return value
        time.sleep(every)
    pytest.fail(f"not within {seconds} s")


def in_background(call):
    out = {}
    t = threading.Thread(target=lambda: out.update(answer=call()), daemon=True)
    t.start()
    return t, out


def alive(pid: int) -> bool:
    import os
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


def test_a_derivation_shows_its_progress_and_a_cancel_stops_its_work(client):
    worker, out = in_background(lambda: client.post(
        "/api/derive", json={"model": SIX_BAR, "job": "derive-1"}))
    # running, with what it is doing and how far it has come
    seen = wait_for(lambda: (lambda p: p if p.get("fraction") else None)(
        client.post("/api/progress", json={"job": "derive-1"}).json()))
    assert seen["state"] == "running" and seen["what"] == "/api/derive"
    assert seen["label"] and 0 < seen["fraction"] < 1 and seen["seconds"] > 0
    listed = client.post("/api/progress", json={}).json()["jobs"]
    assert [j["job"] for j in listed] == ["derive-1"]
    # the work is in a worker process, not in the server's threads
    [pid] = _apart.workers()["busy"]
    asked = time.monotonic()
    r = client.post("/api/cancel", json={"job": "derive-1"})
    assert r.status_code == 200 and r.json() == {"job": "derive-1", "cancelled": True}
    worker.join(MARGIN)
    assert not worker.is_alive()
    answer = out["answer"]
    assert answer.status_code == 422
    assert re.fullmatch(r"/api/derive: cancelled after [\d.]+ s, as asked", answer.json()["error"])
    assert time.monotonic() - asked < MARGIN
    # the work has ended: no job listed, its worker process ended
    wait_for(lambda: not client.post("/api/progress", json={}).json()["jobs"])
    assert not alive(pid) and pid not in _apart.workers()["busy"] + _apart.workers()["idle"]
    assert client.post("/api/progress", json={"job": "derive-1"}).json() == {
        "job": "derive-1", "state": "not running"}
    # and the server goes on
    r = client.post("/api/analyze", json={"model": CRANK_ROCKER, "samples": 5})
    assert r.status_code == 200


def working_on(function: str) -> list[int]:
    """The threads whose stack is in ``function`` of the web app's API now."""
    return [t for t, frame in sys._current_frames().items()
            if any(f.name == function and "kinelab/web/_api.py" in f.filename.replace("\\", "/")
                   for f in traceback.extract_stack(frame))]


def test_a_sweep_is_stopped_in_its_thread(client, monkeypatch):
    """A study whose sweep would go on for ever (Python work in one of the server's
    threads): cancelled, the thread stops where it is, ends the work and is free again."""
    from kinelab.web import _api
    started, ended = threading.Event(), threading.Event()

    def endless(mf, samples):
        started.set()
        try:
            while True:
                pass
        finally:
            ended.set()
    monkeypatch.setattr(_api, "_sweep", endless)
    worker, out = in_background(lambda: client.post(
        "/api/study", json={"model": CRANK_ROCKER, "samples": 77, "source": "endless.toml",
                            "job": "big"}))
    assert started.wait(MARGIN)
    assert working_on("study")
    assert client.post("/api/progress", json={"job": "big"}).json()["state"] == "running"
    assert client.post("/api/cancel", json={"job": "big"}).json()["cancelled"] is True
    assert ended.wait(MARGIN)
    worker.join(MARGIN)
    assert not worker.is_alive()
    assert out["answer"].status_code == 422
    assert out["answer"].json()["error"].startswith("/api/study: cancelled after")
    wait_for(lambda: not client.post("/api/progress", json={}).json()["jobs"])
    assert not working_on("study")
    monkeypatch.undo()
    r = client.post("/api/study", json={"model": CRANK_ROCKER, "samples": 9})
    assert r.status_code == 200 and r.json()["samples"] == 9


def test_where_no_worker_process_can_start_long_work_runs_in_a_thread(client, monkeypatch):
    """A derivation where worker processes cannot start (a script without the main guard
    a new process needs): answered all the same, from one of the server's threads, and
    the server's log says why, once."""
    class NoProcess:
        def __init__(self):
            raise _apart.Unavailable("a worker process cannot start here (a test)")
    monkeypatch.setattr(_apart, "_Worker", NoProcess)
    monkeypatch.setattr(_apart, "_idle", [])
    monkeypatch.setattr(_apart, "_broken", [])
    r = client.post("/api/derive", json={"model": CRANK_ROCKER})
    assert r.status_code == 200 and r.json()["sections"]
    assert _apart._broken == ["a worker process cannot start here (a test)"]
    r = client.post("/api/derive", json={"model": CRANK_ROCKER, "lang": "pt"})
    assert r.status_code == 200 and r.json()["lang"] == "pt"


def test_a_job_cancelled_before_its_request_arrives_never_runs(client):
    assert client.post("/api/cancel", json={"job": "early"}).json() == {"job": "early",
                                                                         "cancelled": False}
    r = client.post("/api/derive", json={"model": SIX_BAR, "job": "early"})
    assert r.status_code == 422 and "cancelled" in r.json()["error"]


@pytest.mark.parametrize("job", ["", "has space", "x" * 65, 12, ["a"], "ä"])
def test_a_job_id_must_be_a_short_plain_name(client, job):
    for route, body in (("/api/analyze", {"model": CRANK_ROCKER, "samples": 5, "job": job}),
                        ("/api/cancel", {"job": job}), ("/api/progress", {"job": job})):
        r = client.post(route, json=body)
        assert r.status_code == 400, (route, r.text)
        assert r.json()["error"].startswith("job: expected an id of 1 to 64 letters, digits")


def test_one_id_is_one_request_at_a_time(client):
    worker, out = in_background(lambda: client.post(
        "/api/derive", json={"model": SIX_BAR, "job": "twice"}))
    wait_for(lambda: client.post("/api/progress", json={"job": "twice"}).json()["state"] == "running")
    r = client.post("/api/analyze", json={"model": CRANK_ROCKER, "samples": 5, "job": "twice"})
    assert r.status_code == 400 and "is already running" in r.json()["error"]
    client.post("/api/cancel", json={"job": "twice"})
    worker.join(MARGIN)
    assert out["answer"].status_code == 422


def test_progress_and_cancel_refuse_what_is_not_json(client):
    r = client.post("/api/cancel", content=b'{"job": "a"}', headers={"content-type": "text/plain"})
    assert r.status_code == 415
    r = client.post("/api/progress", content=b"[1, 2", headers={"content-type": "application/json"})
    assert r.status_code == 400 and r.json()["error"].startswith("body: expected a JSON object")


def test_an_animation_reports_its_frames(client):
    worker, out = in_background(lambda: client.post(
        "/api/export", json={"model": CRANK_ROCKER, "kind": "gif", "job": "gif-1"}))
    seen = wait_for(lambda: (lambda p: p if p.get("label", "").startswith("frame") else None)(
        client.post("/api/progress", json={"job": "gif-1"}).json()), every=0.02)
    assert re.fullmatch(r"frame \d+ of 60", seen["label"]) and 0.1 <= seen["fraction"] <= 1
    worker.join(MARGIN * 4)
    assert out["answer"].status_code == 200 and out["answer"].content.startswith(b"GIF8")


# -- a real server ----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def server():
    """``kinelab serve --port 0`` with its log (standard error) kept: (port, log lines)."""
    with serving() as running:
        yield running


def post(port, path, data, timeout=600):
    import http.client
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout)
    c.request("POST", path, body=json.dumps(data).encode(),
              headers={"Content-Type": "application/json"})
    r = c.getresponse()
    out = r.status, json.loads(r.read() or b"null")
    c.close()
    return out


def listed(port) -> list[dict]:
    return post(port, "/api/progress", {})[1]["jobs"]


def test_closing_the_request_stops_the_work(server):
    port, log = server
    body = json.dumps({"model": SIX_BAR, "job": "closed-1"}).encode()
    s = socket.create_connection(("127.0.0.1", port), timeout=60)
    s.sendall(f"POST /api/derive HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: "
              f"application/json\r\nContent-Length: {len(body)}\r\n\r\n".encode() + body)
    wait_for(lambda: any(j["job"] == "closed-1" and j["state"] == "running" for j in listed(port)))
    closed = time.monotonic()
    s.close()
    wait_for(lambda: not any(j["job"] == "closed-1" for j in listed(port)))
    assert time.monotonic() - closed < MARGIN
    time.sleep(0.5)
    text = "".join(log)
    assert "Traceback" not in text and "ERROR" not in text, text


def test_long_work_does_not_keep_short_requests_waiting(server):
    """More derivations than the long workers, and a request that sweeps a linkage (and one
    that asks for their progress) all the while: each short one is answered about as fast
    as alone, not after the derivations (seconds each)."""
    port, _ = server
    short = {"model": CRANK_ROCKER, "samples": 361}

    def timed(path, data):
        start = time.perf_counter()
        status, _ = post(port, path, data)
        assert status == 200
        return time.perf_counter() - start
    alone = min(timed("/api/analyze", short) for _ in range(3))
    jobs = [f"long-{k}" for k in range(_app.LONG_WORKERS + 2)]
    threads = [threading.Thread(target=post, args=(port, "/api/derive", {"model": SIX_BAR, "job": j}),
                                daemon=True) for j in jobs]
    for t in threads:
        t.start()
    wait_for(lambda: sum(j["state"] == "running" for j in listed(port)) == _app.LONG_WORKERS)
    assert any(j["state"] == "waiting" for j in listed(port))      # the rest queue for a long worker
    during, asked = [], []
    while len(during) < 5 and any(j["state"] == "running" for j in listed(port)):
        during.append(timed("/api/analyze", short))
        asked.append(timed("/api/progress", {}))
    for j in jobs:
        post(port, "/api/cancel", {"job": j})
    for t in threads:
        t.join(MARGIN)
    assert during, "the derivations ended before a short request could be timed"
    # the interpreter is shared with the derivations (so up to about twice as long), never
    # queued behind them; the margin is for a loaded machine
    assert max(during) < 3 * alone + 1.0, (alone, during)
    assert max(asked) < 1.0, asked
    wait_for(lambda: not listed(port))
