"""Recordings (docs/recording_format.md): a header, each scene and actor once, then frames with
link poses, soft node positions and contacts; destroyed actors are announced; the debugger's
headless mode records for a set simulated duration."""

import json
import time

import numpy as np
import pytest

import superdex.physics as sdp


def read(path):
    return [json.loads(line) for line in open(path)]


def test_recording_of_a_ball_falling_on_the_ground(scene, tmp_path):
    path = tmp_path / "run.jsonl"
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    ball = scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), is_static=False, mass=1.0,
                                    world_from_local=sdp.TransformRT(translation=[0, 0, 0.5]))
    sdp.start_recording(str(path), 0.0)
    with pytest.raises(sdp.Error, match="already running"):
        sdp.start_recording(str(tmp_path / "other.jsonl"), 0.0)
    positions = []
    for _ in range(50):
        scene.step(0.01)
        positions.append(np.array(ball.get_root_transform().translation, dtype=float))
    scene.destroy_actor(ball)
    scene.step(0.01)
    sdp.stop_recording()
    assert not sdp.is_recording()
    lines = read(path)
    assert lines[0] == {"type": "header", "format": "superdex-recording", "version": 1, "units": "m, s, kg, N",
                        "frameInterval": 0.0}
    assert lines[1]["type"] == "scene" and lines[1]["gravity"] == [0.0, 0.0, -9.81]
    actors = {l["name"]: l for l in lines if l["type"] == "actor"}
    assert actors["ground"]["kind"] == "static"
    assert actors["ball"]["kind"] == "rigid"
    assert actors["ball"]["links"][0]["colliders"][0]["shape"] == {"sphere": {"radius": 0.1, "center": [0.0, 0.0, 0.0]}}
    frames = [l for l in lines if l["type"] == "frame"]
    assert len(frames) == 51
    handle = str(actors["ball"]["links"][0]["handle"])
    recorded = np.array([f["links"][handle][:3] for f in frames[:50]])
    np.testing.assert_allclose(recorded, positions, rtol=1e-6, atol=1e-7)
    # resting on the ground at the end: contacts carry its weight
    assert sum(c["f"][2] for c in frames[49]["contacts"]) == pytest.approx(9.81, rel=1e-3)
    destroyed = [l for l in lines if l["type"] == "destroy"]
    assert [d["handle"] for d in destroyed] == [actors["ball"]["handle"]]
    assert handle not in frames[50]["links"]


def test_frame_interval_decimates(scene, tmp_path):
    path = tmp_path / "run.jsonl"
    scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), is_static=False, mass=1.0)
    sdp.start_recording(str(path), 0.05)
    for _ in range(100):
        scene.step(0.01)
    sdp.stop_recording()
    times = [l["t"] for l in read(path) if l["type"] == "frame"]
    np.testing.assert_allclose(np.diff(times), 0.05, atol=1e-9)
    with pytest.raises(sdp.Error, match="frame_interval must be >= 0"):
        sdp.start_recording(str(path), -1.0)
    with pytest.raises(sdp.Error, match="cannot write"):
        sdp.start_recording(str(tmp_path / "missing" / "run.jsonl"), 0.0)


def test_debugger_records_headless_for_a_duration(scene, tmp_path, monkeypatch, capsys):
    path = tmp_path / "run.jsonl"
    monkeypatch.setenv("SUPERDEX_DEBUGGER_RECORD", str(path))
    monkeypatch.setenv("SUPERDEX_DEBUGGER_DURATION", "0.5")
    monkeypatch.setenv("SUPERDEX_DEBUGGER_FRAME_INTERVAL", "0.1")
    scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), is_static=False, mass=1.0)
    assert sdp.debugger.attach()
    steps = 0
    while sdp.debugger.is_attached():
        scene.step(0.01)
        steps += 1
    assert steps == 50
    assert not sdp.is_recording()
    assert "recording to" in capsys.readouterr().out
    assert [round(l["t"], 6) for l in read(path) if l["type"] == "frame"] == [0.01, 0.11, 0.21, 0.31, 0.41]


def test_a_duration_counts_simulated_steps_across_restores(scene, tmp_path, monkeypatch):
    """A script that restores a captured state every 0.2 s (its clock goes back) still ends after
    0.5 s of simulation, and the recording has a frame right after each restore (the replay's
    new epoch)."""
    path = tmp_path / "run.jsonl"
    monkeypatch.setenv("SUPERDEX_DEBUGGER_RECORD", str(path))
    monkeypatch.setenv("SUPERDEX_DEBUGGER_DURATION", "0.5")
    monkeypatch.setenv("SUPERDEX_DEBUGGER_FRAME_INTERVAL", "0.1")
    scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), is_static=False, mass=1.0)
    start = scene.capture_state()
    assert sdp.debugger.attach()
    steps = 0
    while sdp.debugger.is_attached():
        if steps and steps % 20 == 0:
            scene.restore_state(start, release_immediately=False)
        scene.step(0.01)
        steps += 1
    assert steps == 50
    times = [round(l["t"], 6) for l in read(path) if l["type"] == "frame"]
    assert times == [0.01, 0.11, 0.01, 0.11, 0.01]  # the last 0.1 s run ends at t = 0.1


def test_update_debugger_records_a_scene_that_is_not_stepped(scene, tmp_path):
    """Scene.update_debugger writes the scene's current state as a frame without stepping it,
    and only when it changed since the scene's last frame; stepped frames go on as before."""
    path = tmp_path / "run.jsonl"
    ball = scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), is_static=False, mass=1.0,
                                    world_from_local=sdp.TransformRT(translation=[0, 0, 0.5]))
    scene.update_debugger()  # no recording, no page: nothing to do
    sdp.start_recording(str(path), 0.0)
    scene.update_debugger()
    scene.update_debugger()  # the same state: no second frame
    ball.set_root_transform(sdp.TransformRT(translation=[0.3, 0, 0.5]))
    scene.update_debugger()
    scene.step(0.01)
    scene.update_debugger()  # the step's own frame shows this state already
    sdp.stop_recording()
    frames = [l for l in read(path) if l["type"] == "frame"]
    assert [(f["t"], f["step"]) for f in frames] == [(0.0, 0), (0.0, 0), (pytest.approx(0.01), 1)]
    # the ball where it was put, then where it was moved to, then a step later
    x = [next(iter(f["links"].values()))[0] for f in frames]
    assert x[0] == 0 and x[1] == pytest.approx(0.3) and x[2] == pytest.approx(0.3)
    assert sdp.recorded_time() == 0 and not sdp.is_recording()
    assert [l["name"] for l in read(path) if l["type"] == "actor"] == ["ball"]  # described once


def test_a_duration_without_steps_runs_on_the_wall_clock(scene, tmp_path, monkeypatch):
    """A script that only shows its scene through update_debugger (an IK loop) simulates nothing:
    headless, it ends once the duration has passed on the wall clock after its first frame."""
    path = tmp_path / "run.jsonl"
    monkeypatch.setenv("SUPERDEX_DEBUGGER_RECORD", str(path))
    monkeypatch.setenv("SUPERDEX_DEBUGGER_DURATION", "0.3")
    scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), is_static=False, mass=1.0)
    assert sdp.debugger.attach()
    time.sleep(0.35)
    assert sdp.debugger.is_attached()  # no frame yet: a slow setup is not cut short
    start = time.monotonic()
    shown = 0
    while sdp.debugger.is_attached():
        scene.update_debugger()
        shown += 1
        time.sleep(0.01)
    assert 0.3 <= time.monotonic() - start < 1.0
    assert shown > 5 and not sdp.is_recording()
    assert len([l for l in read(path) if l["type"] == "frame"]) == 1  # nothing changed after the first


def test_debugger_without_a_page_prints_the_url_and_gives_up(engine, monkeypatch, capsys, tmp_path):
    monkeypatch.delenv("SUPERDEX_DEBUGGER_RECORD", raising=False)
    monkeypatch.delenv("SUPERDEX_DEBUGGER_DURATION", raising=False)
    monkeypatch.setenv("SUPERDEX_DEBUGGER_BROWSER", "0")
    (tmp_path / "index.html").write_text("<!doctype html>")
    monkeypatch.setenv("SUPERDEX_DEBUGGER_UI", str(tmp_path))
    assert not sdp.debugger.attach(timeout_seconds=0.3)
    assert not sdp.debugger.is_attached()
    assert not sdp.get_debug_server().has_started()
    out, err = capsys.readouterr()
    assert "open http://127.0.0.1:" in out and "no page connected within 0.3 s" in err
    monkeypatch.setenv("SUPERDEX_DEBUGGER_DURATION", "soon")
    with pytest.raises(sdp.Error, match="SUPERDEX_DEBUGGER_DURATION: expected a number of seconds"):
        sdp.debugger.attach()


def test_recording_stops_safely_while_other_threads_step(engine, tmp_path):
    """Scenes stepped on two Python threads record into the running recording while the main
    thread stops and restarts it again and again (as a headless script's detach does while its
    worker scenes still step): every step either records or not, nothing is torn."""
    import threading

    scenes = []
    for k in range(2):
        s = sdp.create_scene(f"worker {k}")
        s.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), is_static=False, mass=1.0)
        scenes.append(s)
    stop = threading.Event()

    def work(s):
        while not stop.is_set():
            s.step(0.001)

    threads = [threading.Thread(target=work, args=(s,)) for s in scenes]
    for t in threads:
        t.start()
    try:
        for k in range(40):
            sdp.start_recording(str(tmp_path / f"run{k}.jsonl"), 0.0)
            time.sleep(0.002)
            assert sdp.recorded_frames() >= 0
            sdp.stop_recording()
    finally:
        stop.set()
        for t in threads:
            t.join()
    # each file is whole: a header, then complete JSON lines
    for k in range(40):
        lines = read(tmp_path / f"run{k}.jsonl")
        assert lines[0]["type"] == "header"
