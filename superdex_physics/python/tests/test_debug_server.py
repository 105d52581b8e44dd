"""The debug server (docs/debugger_protocol.md) driven as the page drives it, over HTTP and a
WebSocket, against a scene stepping on another thread:

- security: the token is required on every request and on the WebSocket, foreign origins and
  hosts are refused, nothing outside the UI folder is served (`..`, encoded `..`, symbolic links);
- the scene is described, then frames arrive with link poses and named signals;
- pause stops simulated time (scene.step blocks), step advances exactly one step, play resumes
  in real time (simulated time keeps pace with the wall clock), restore returns to the first state;
- random bytes, malformed and oversized messages leave the simulation stepping and the server
  serving; closing the page ends `has_connection()` and releases a paused simulation;
- replay sends every line of a recording, then `end` with the number of frames;
- stopping the server while a step is inside it (pacing, building or sending a frame, gated)
  leaves that step to finish safely.
"""

import contextlib
import json
import os
import random
import socket
import threading
import time
import urllib.error
import urllib.request

import pytest
from websockets.exceptions import InvalidStatus
from websockets.sync.client import connect

import superdex.physics as sdp


@pytest.fixture
def ui_dir(tmp_path):
    ui = tmp_path / "ui"
    (ui / "assets").mkdir(parents=True)
    (ui / "index.html").write_text("<!doctype html><title>debugger</title>")
    (ui / "assets" / "app.js").write_text("console.log('app')")
    (tmp_path / "secret.txt").write_text("secret")
    os.symlink(tmp_path / "secret.txt", ui / "link_out.txt")
    return ui


@pytest.fixture
def server(ui_dir):
    srv = sdp.get_debug_server()
    srv.set_ui_directory(str(ui_dir))
    srv.start()
    yield srv
    srv.stop()


def http_get(url, headers=None):
    try:
        with urllib.request.urlopen(urllib.request.Request(url, headers=headers or {}), timeout=5) as r:
            return r.status, r.read(), r.headers
    except urllib.error.HTTPError as e:
        return e.code, b"", e.headers


def raw_get(port, path, host=None):
    """The status code of a request sent byte for byte (no client-side path normalisation)."""
    with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
        s.sendall(f"GET {path} HTTP/1.1\r\nHost: {host or f'127.0.0.1:{port}'}\r\nConnection: close\r\n\r\n".encode())
        data = b""
        while chunk := s.recv(4096):
            data += chunk
    return int(data.split(b" ", 2)[1])


def ws_url(srv):
    return srv.get_url().replace("http://", "ws://") + "ws"


def token_of(srv):
    return srv.get_url().rstrip("/").rsplit("/", 1)[1]


def wait_for(predicate, timeout=10.0):
    """Polls `predicate` until it holds (True) or `timeout` seconds passed (False)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.02)
    return False


class Page:
    """A WebSocket client reading the server's lines on a thread, as the page does."""

    def __init__(self, srv, origin=None):
        self.stack = contextlib.ExitStack()
        self.ws = self.stack.enter_context(connect(ws_url(srv), origin=origin, open_timeout=5, max_size=None))
        self.lines = []
        self.lock = threading.Lock()
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        try:
            while True:
                message = self.ws.recv()
                lines = [json.loads(l) for l in message.split("\n") if l]
                with self.lock:
                    self.lines.extend(lines)
                # frames are acknowledged, as the page does (flow control)
                if any(l.get("type") == "frame" for l in lines):
                    self.ws.send('{"type": "ack"}')
        except Exception:
            pass

    def of_type(self, kind):
        with self.lock:
            return [l for l in self.lines if l.get("type") == kind]

    wait_for = staticmethod(wait_for)

    def control(self, action):
        self.ws.send(json.dumps({"type": "control", "action": action}))

    def latest_status(self):
        statuses = self.of_type("status")
        return statuses[-1] if statuses else None

    def close(self):
        self.stack.close()
        self.thread.join(timeout=5)


class SteppingScene:
    """A pendulum-free scene: a ball resting on the ground, stepped on a thread as a user's loop."""

    def __init__(self, dt=0.01):
        sdp.initialize()
        self.scene = sdp.create_scene("served")
        self.scene.set_gravity([0, 0, -9.81])
        self.scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
        self.ball = self.scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1),
                                                  world_from_local=sdp.TransformRT(translation=[0, 0, 0.5]))
        self.dt = dt
        self.steps = 0
        self.error = None
        self.running = True
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        try:
            while self.running:
                self.scene.step(self.dt)
                self.steps += 1
        except Exception as e:  # reported by the test
            self.error = e

    def stop(self):
        self.running = False
        self.thread.join(timeout=10)
        assert not self.thread.is_alive(), "the stepping thread did not finish"
        sdp.shutdown()


@pytest.fixture
def stepping():
    s = SteppingScene()
    yield s
    sdp.get_debug_server().stop()  # releases a paused step
    s.stop()
    assert s.error is None


def test_every_request_needs_the_token_a_local_host_and_no_foreign_origin(server):
    port, token = server.get_port(), token_of(server)
    status, body, headers = http_get(server.get_url())
    assert status == 200 and b"debugger" in body and headers["Content-Type"].startswith("text/html")
    status, body, headers = http_get(server.get_url() + "assets/app.js")
    assert status == 200 and headers["Content-Type"].startswith("text/javascript")
    assert http_get(f"http://127.0.0.1:{port}/")[0] == 403
    assert http_get(f"http://127.0.0.1:{port}/assets/app.js")[0] == 403
    assert http_get(f"http://127.0.0.1:{port}/{'0' * 32}/")[0] == 403
    assert http_get(f"http://127.0.0.1:{port}/{token[:-1]}/")[0] == 403
    assert http_get(server.get_url(), {"Origin": "http://evil.example"})[0] == 403
    assert http_get(server.get_url(), {"Origin": f"http://127.0.0.1:{port + 1}"})[0] == 403
    assert http_get(server.get_url(), {"Origin": f"http://127.0.0.1:{port}"})[0] == 200
    # DNS rebinding: a page of another name that resolves to 127.0.0.1
    assert raw_get(port, f"/{token}/", host=f"evil.example:{port}") == 403
    assert raw_get(port, f"/{token}/", host=f"localhost:{port}") == 200


def test_nothing_outside_the_ui_folder_is_served(server):
    port, token = server.get_port(), token_of(server)
    for path in ["../secret.txt", "assets/../../secret.txt", "%2e%2e/secret.txt", "..%2fsecret.txt", "assets%2f..%2f..%2fsecret.txt",
                 "link_out.txt", "..\\secret.txt", "%00index.html", "missing.js", "assets/"]:
        assert raw_get(port, f"/{token}/{path}") == 404, path
    assert raw_get(port, f"/{token}/assets/app.js") == 200


def test_the_websocket_needs_the_token_and_a_local_origin(server):
    port = server.get_port()
    with pytest.raises(InvalidStatus) as refused:
        connect(f"ws://127.0.0.1:{port}/{'f' * 32}/ws", open_timeout=5)
    assert refused.value.response.status_code == 403
    with pytest.raises(InvalidStatus) as refused:
        connect(ws_url(server), origin="http://evil.example", open_timeout=5)
    assert refused.value.response.status_code == 403
    page = Page(server, origin=f"http://localhost:{port}")
    assert page.wait_for(lambda: page.of_type("session"))
    session = page.of_type("session")[0]
    assert session["mode"] == "live" and session["version"] == 1 and session["axes"] == "FLU"
    assert server.has_connection()
    page.close()
    assert page.wait_for(lambda: not server.has_connection())
    # a Y-up page for pages that connect afterwards
    server.set_coordinate_space(sdp.CoordinateSpace(axes=sdp.CoordinateSpaceAxes.RUB))
    try:
        page = Page(server)
        assert page.wait_for(lambda: page.of_type("session"))
        assert page.of_type("session")[0]["axes"] == "RUB"
        assert server.get_coordinate_space().axes == sdp.CoordinateSpaceAxes.RUB
        page.close()
    finally:
        server.set_coordinate_space(sdp.CoordinateSpace())


def test_a_page_sees_the_scene_and_controls_the_simulation(server, stepping):
    page = Page(server)
    assert page.wait_for(lambda: len(page.of_type("frame")) >= 5)
    (actor,) = [a for a in page.of_type("actor") if a["name"] == "ball"]
    ball_link = str(actor["links"][0]["handle"])
    # the ball falls from 0.5 m (in real time once the page is attached) and comes to rest
    def resting():
        f = page.of_type("frame")[-1]
        return f["t"] > 0.6 and abs(f["links"][ball_link][2] - 0.1) < 0.01

    assert page.wait_for(resting, timeout=20)
    frame = page.of_type("frame")[-1]
    assert frame["links"][ball_link][2] == pytest.approx(0.1, abs=0.01)  # resting on the ground
    assert frame["signals"]["ball.contact_force"][2] == pytest.approx(actor["links"][0]["mass"] * 9.81, rel=0.02)

    # playing in real time: simulated time keeps pace with the wall clock
    assert page.wait_for(lambda: page.latest_status() and page.latest_status()["state"] == "playing")
    t0, w0 = stepping.scene.get_total_simulation_time(), time.monotonic()
    time.sleep(1.0)
    t1, w1 = stepping.scene.get_total_simulation_time(), time.monotonic()
    assert (t1 - t0) == pytest.approx(w1 - w0, rel=0.1)

    # pause: scene.step blocks, simulated time stops
    page.control("pause")
    assert page.wait_for(lambda: page.latest_status()["state"] == "paused")
    time.sleep(0.1)
    steps_paused = stepping.steps
    time.sleep(0.5)
    assert stepping.steps == steps_paused
    assert server.is_paused()

    # step: exactly one more step
    t_before = stepping.scene.get_total_simulation_time()
    page.control("step")
    assert page.wait_for(lambda: stepping.steps == steps_paused + 1)
    time.sleep(0.3)
    assert stepping.steps == steps_paused + 1
    assert stepping.scene.get_total_simulation_time() == pytest.approx(t_before + stepping.dt, abs=1e-6)
    assert page.wait_for(lambda: page.latest_status()["step"] == page.of_type("frame")[-1]["step"])

    # restore: back to the first state, paused
    page.control("restore")
    assert page.wait_for(lambda: page.of_type("frame")[-1]["t"] < 0.05)
    assert stepping.steps == steps_paused + 1
    assert page.of_type("frame")[-1]["links"][ball_link][2] == pytest.approx(0.5, abs=0.01)

    # play again, then as fast as possible
    page.control("play")
    assert page.wait_for(lambda: stepping.steps > steps_paused + 20)
    page.control("fast")
    steps_fast, w_fast = stepping.steps, time.monotonic()
    time.sleep(0.5)
    assert (stepping.steps - steps_fast) * stepping.dt > 2 * (time.monotonic() - w_fast)
    page.close()


def test_each_page_that_attaches_is_described_the_scene_once(server, stepping):
    """A page that attaches while the scene steps gets each actor's description once, before
    the frames that move it, however the attach falls between two steps."""
    for _ in range(30):
        page = Page(server)
        assert page.wait_for(lambda: len(page.of_type("frame")) >= 3)
        lines = [l for l in page.lines if l["type"] in ("actor", "frame")]
        assert [l["name"] for l in lines if l["type"] == "actor"] == ["ground", "ball"]
        assert lines[0]["type"] == "actor"
        page.close()
        assert page.wait_for(lambda: not server.has_connection())


def test_closing_the_page_releases_a_paused_simulation(server, stepping):
    page = Page(server)
    assert page.wait_for(lambda: page.of_type("frame"))
    page.control("pause")
    assert page.wait_for(lambda: server.is_paused())
    page.close()
    assert page.wait_for(lambda: not server.has_connection())
    steps = stepping.steps
    assert page.wait_for(lambda: stepping.steps > steps + 10)


def test_garbage_on_the_websocket_leaves_the_simulation_running(server, stepping):
    rng = random.Random(7)
    page = Page(server)
    assert page.wait_for(lambda: page.of_type("frame"))
    # malformed control messages and binary frames are dropped; the connection stays
    for message in ["", "{", "null", "[1,2]", '{"type":"control"}', '{"type":"control","action":42}',
                    '{"type":"control","action":"explode"}', '{"type":7}', "\u00ff" * 100]:
        page.ws.send(message)
    for _ in range(20):
        page.ws.send(bytes(rng.getrandbits(8) for _ in range(rng.randint(1, 2000))))
    frames = len(page.of_type("frame"))
    assert page.wait_for(lambda: len(page.of_type("frame")) > frames + 5)
    assert not server.is_paused()
    # an oversized message ends that connection only
    page.ws.send("x" * 200_000)
    assert page.wait_for(lambda: not server.has_connection())
    # raw random bytes after the upgrade, and instead of HTTP
    for attempt in range(10):
        with socket.create_connection(("127.0.0.1", server.get_port()), timeout=5) as s:
            if attempt % 2 == 0:
                key = "dGhlIHNhbXBsZSBub25jZQ=="
                s.sendall((f"GET /{token_of(server)}/ws HTTP/1.1\r\nHost: 127.0.0.1:{server.get_port()}\r\nUpgrade: websocket\r\n"
                           f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n").encode())
                s.recv(4096)
            s.sendall(bytes(rng.getrandbits(8) for _ in range(5000)))
            time.sleep(0.05)
    steps = stepping.steps
    assert page.wait_for(lambda: stepping.steps > steps + 10)
    assert stepping.error is None
    # and the server still serves pages
    assert http_get(server.get_url())[0] == 200
    fresh = Page(server)
    assert fresh.wait_for(lambda: fresh.of_type("frame"))
    fresh.close()


def test_replay_sends_the_recording_then_end(tmp_path, ui_dir):
    recording = tmp_path / "run.jsonl"
    sdp.initialize()
    scene = sdp.create_scene("recorded")
    scene.set_gravity([0, 0, -9.81])
    scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1))
    sdp.start_recording(str(recording), 0.0)
    for _ in range(150):
        scene.step(0.01)
    sdp.stop_recording()
    sdp.shutdown()
    lines = [json.loads(l) for l in recording.read_text().splitlines()]
    srv = sdp.get_debug_server()
    srv.set_ui_directory(str(ui_dir))
    srv.start_replay(str(recording))
    try:
        page = Page(srv)
        assert page.wait_for(lambda: page.of_type("end"))
        (session,) = page.of_type("session")
        assert session["mode"] == "replay" and session["source"] == "run.jsonl"
        received = [l for l in page.lines if l["type"] not in ("session", "end")]
        assert received == lines
        assert page.of_type("end")[0]["frames"] == sum(l["type"] == "frame" for l in lines) == 150
        page.close()
    finally:
        srv.stop()


def test_bad_use_is_refused_with_clear_errors(tmp_path, ui_dir):
    srv = sdp.get_debug_server()
    srv.set_ui_directory(str(tmp_path / "nowhere"))
    with pytest.raises(sdp.Error, match="not built"):
        srv.start()
    srv.set_ui_directory(str(ui_dir))
    not_a_recording = tmp_path / "notes.txt"
    not_a_recording.write_text("hello\n")
    with pytest.raises(sdp.Error, match="notes.txt"):
        srv.start_replay(str(not_a_recording))
    with pytest.raises(sdp.Error, match="cannot read"):
        srv.start_replay(str(tmp_path / "missing.jsonl"))
    with pytest.raises(sdp.Error, match="port"):
        srv.start(70000)
    port = srv.start()
    try:
        with pytest.raises(sdp.Error, match="already started"):
            srv.start()
        with pytest.raises(sdp.Error, match="before start"):
            srv.set_ui_directory(str(ui_dir))
        assert srv.get_port() == port and srv.has_started()
    finally:
        srv.stop()
    assert not srv.has_started() and srv.get_port() == 0 and srv.get_url() == ""


def test_a_flood_of_connections_leaves_the_server_answering(server, stepping):
    """Hundreds of idle or half-open connections, and many short-lived WebSocket pages, neither
    stop the simulation nor the server from answering a real page."""
    port = server.get_port()
    idle = []
    for i in range(300):
        s = socket.create_connection(("127.0.0.1", port), timeout=5)
        if i % 3 == 0:
            s.sendall(b"GET /")  # a request line that never ends
        idle.append(s)
    for _ in range(30):
        with connect(ws_url(server), open_timeout=5) as ws:
            ws.send('{"type":"control","action":"play"}')
    steps = stepping.steps
    assert http_get(server.get_url())[0] == 200
    page = Page(server)
    assert page.wait_for(lambda: len(page.of_type("frame")) >= 3)
    assert page.wait_for(lambda: stepping.steps > steps + 10)
    page.close()
    for s in idle:
        s.close()
    assert stepping.error is None


def test_stopping_the_server_while_a_step_is_inside_it_is_safe(ui_dir):
    """The server is started and stopped again and again while a scene steps as fast as it can
    with a page attached: each stop falls while the step is pacing, building a frame, sending
    it or waiting at the gate. The step keeps what it uses alive until it leaves (a step that
    used the server's state after stop freed it crashed the process)."""
    scene = SteppingScene(dt=0.001)
    server = sdp.get_debug_server()
    server.set_ui_directory(str(ui_dir))
    try:
        for cycle in range(40):
            server.start()
            page = Page(server)
            assert page.wait_for(lambda: page.of_type("frame"))
            # in turn: real-time play (pacing), as fast as possible (frames), paused (the gate)
            page.control(["play", "fast", "pause"][cycle % 3])
            time.sleep(0.002 * (cycle % 7))
            server.stop()
            page.close()
            assert scene.error is None
        steps = scene.steps
        assert wait_for(lambda: scene.steps > steps + 10)
    finally:
        server.stop()
        scene.stop()
    assert scene.error is None
