"""The debugger page in a real browser (playwright-core driving Debian's chromium, headless),
attached to the seed example as a user runs it, and replaying a recording of it:

- live: the seed scene loads in the page, the 3D canvas is not blank, the actor tree lists the
  arm's links, a chart shows the force sensor's signal, pause stops simulated time, step advances
  exactly one step, play resumes; closing the page makes `is_attached()` false, so the seed's
  loop ends and the script exits cleanly;
- replay (`python -m superdex view FILE`): the page holds as many frames as the file, the ball's
  pose at frame k equals the recorded one, and the ball's render model (.glb) is drawn.

The node scripts (superdex_debugger/tests/*.mjs) print one JSON object of measurements; the
assertions are here. SUPERDEX_UPDATE_SCREENSHOTS=1 writes the screenshots to docs/.
"""

import json
import os
import queue
import shutil
import signal
import subprocess
import sys
import threading
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
EXAMPLE = REPO / "superdex_robotics" / "examples" / "advanced" / "example_custom_components.py"
UI = REPO / "superdex_debugger"
LINKS = ["base_link", "link_1", "link_2", "ball"]
# tools/sanitize.sh runs the suite with the sanitized engine, many times slower: waits are longer
SLOW = 5 if os.environ.get("SUPERDEX_SANITIZED") == "1" else 1


@pytest.fixture(scope="module", autouse=True)
def browser_tools():
    missing = [what for what, ok in [("node", shutil.which("node")), ("chromium", shutil.which("chromium")),
                                     ("the built page", (UI / "dist" / "index.html").is_file()),
                                     ("playwright-core", (UI / "node_modules" / "playwright-core").is_dir())] if not ok]
    assert not missing, f"missing {', '.join(missing)}: run tools/bootstrap.sh and the build (tools/dev.sh test does both)"


def screenshot_path(tmp_path, name):
    return REPO / "docs" / name if os.environ.get("SUPERDEX_UPDATE_SCREENSHOTS") == "1" else tmp_path / name


def headless_env(**extra):
    env = {k: v for k, v in os.environ.items() if not k.startswith("SUPERDEX_DEBUGGER_")}
    env.update(SUPERDEX_DEBUGGER_BROWSER="0", **extra)
    return env


def start_and_read_url(cmd, env, marker):
    """Starts `cmd`; returns the process, the URL from the stdout line containing `marker`, and a
    queue receiving its further stdout lines."""
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=REPO)
    lines = queue.Queue()
    threading.Thread(target=lambda: [lines.put(l) for l in proc.stdout], daemon=True).start()
    while True:
        try:
            line = lines.get(timeout=300 * SLOW)
        except queue.Empty:
            proc.kill()
            pytest.fail(f"{cmd} printed no URL")
        if marker in line:
            url = next(word for word in line.split() if word.startswith("http://127.0.0.1:"))
            return proc, url, lines


def run_node(script, *args):
    # the browser does not load the sanitizer runtimes preloaded into the Python processes
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    result = subprocess.run(["node", str(UI / "tests" / script), *map(str, args)], capture_output=True, text=True,
                            timeout=600 * SLOW, cwd=UI, env=env)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout.strip().splitlines()[-1])


def test_the_page_attaches_to_the_seed_example_and_controls_it(tmp_path):
    # the seed waits for the page up to SUPERDEX_DEBUGGER_WAIT (a browser starting on a busy machine)
    proc, url, _ = start_and_read_url([sys.executable, str(EXAMPLE)], headless_env(SUPERDEX_DEBUGGER_WAIT=str(120 * SLOW)),
                                      "superdex.debugger: open")
    try:
        shot = screenshot_path(tmp_path, "debugger_live.png")
        # --settle: a pause takes effect after the step in flight (one seed step: milliseconds, or
        # seconds under the sanitizers), waited for before the single-step check
        r = run_node("live.mjs", url, "--screenshot", shot, "--links", ",".join(LINKS), "--signal", "force_sensor",
                     "--timeout", 120 * SLOW, "--settle", 0.3 if SLOW == 1 else 8)
        # closing the page ends the seed's `while debugger.is_attached()` loop
        _, stderr = proc.communicate(timeout=120 * SLOW)
    finally:
        if proc.poll() is None:
            proc.kill()
    details = json.dumps({k: v for k, v in r.items() if k not in ("signalNames",)}, indent=1)
    assert r["connected"] and r["sessionMode"] == "live", details
    assert r["canvasNonBlank"], details
    assert r["treeHasLinks"], details
    assert r["signalPlotted"] and "force_sensor" in r["signalName"], details
    # the step in flight when the pause arrived may end; none after it
    assert r["pauseHolds"] and r["stepPaused"] - r["stepAtPause"] <= 1, details
    assert r["stepAdvancesOne"] and r["stepAfter"] == r["stepBefore"] + 1, details
    assert r["playResumes"] and r["tPlay1"] > r["tPlay0"], details
    assert not r.get("pageErrors"), details
    assert shot.stat().st_size > 10_000
    assert proc.returncode == 0, stderr
    assert stderr == "", stderr


def test_a_recording_of_the_seed_example_replays_frame_for_frame(tmp_path):
    recording = tmp_path / "seed.jsonl"
    env = headless_env(SUPERDEX_DEBUGGER_RECORD=str(recording), SUPERDEX_DEBUGGER_DURATION="0.6",
                       SUPERDEX_DEBUGGER_FRAME_INTERVAL="0.02")
    subprocess.run([sys.executable, str(EXAMPLE)], env=env, check=True, capture_output=True, timeout=900 * SLOW, cwd=REPO)
    lines = [json.loads(l) for l in recording.read_text().splitlines()]
    frames = [l for l in lines if l["type"] == "frame"]
    (arm,) = [l for l in lines if l["type"] == "actor" and l["name"] == "example_bot_2dof"]
    ball = arm["links"][3]["handle"]
    assert len(frames) >= 25

    proc, url, _ = start_and_read_url([sys.executable, "-m", "superdex", "view", str(recording), "--no-browser"],
                                      headless_env(), "superdex view: replaying")
    try:
        shot = screenshot_path(tmp_path, "debugger_replay.png")
        r = run_node("replay.mjs", url, recording, "--link-handle", ball, "--screenshot", shot)
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=30)
    details = json.dumps({k: v for k, v in r.items() if k != "actorNames"}, indent=1)
    assert r["replayEnded"] and r["sessionMode"] == "replay", details
    assert r["frameCount"] == len(frames) == r["endFrames"], details
    assert r["linkHandle"] == ball and r["linksMatch"] and r["maxAbsDiff"] == 0, details
    assert set(LINKS) <= set(r["actorNames"]), details
    # the ball's render model (a .glb embedded in the recording) is drawn in its place
    assert r["renderModelsDeclared"] == 1 and r["renderModelCount"] == 1, details
    assert r["canvasNonBlank"], details
    assert proc.returncode == 0


def record_and_replay(tmp_path, example, seconds):
    """Runs a physics example headless for `seconds`, recording it, then replays the recording in
    the page: (the recording's lines, replay.mjs's report, that report as text for messages)."""
    recording = tmp_path / f"{example}.jsonl"
    env = headless_env(SUPERDEX_DEBUGGER_RECORD=str(recording), SUPERDEX_DEBUGGER_FRAME_INTERVAL="0.02")
    script = REPO / "superdex_physics" / "examples" / f"{example}.py"
    subprocess.run([sys.executable, str(script), "--seconds", str(seconds), "--debugger"], env=env, check=True, capture_output=True,
                   timeout=900 * SLOW, cwd=REPO)
    lines = [json.loads(l) for l in recording.read_text().splitlines()]
    proc, url, _ = start_and_read_url([sys.executable, "-m", "superdex", "view", str(recording), "--no-browser"],
                                      headless_env(), "superdex view: replaying")
    try:
        r = run_node("replay.mjs", url, recording)
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=30)
    return lines, r, json.dumps({k: v for k, v in r.items() if k != "actorNames"}, indent=1)


def test_a_replay_shows_an_actor_destroyed_during_the_run_up_to_its_last_frame(tmp_path):
    """The constraints example destroys its upper box before 0.5 s: replayed, the page draws the
    box at the first frame and not at the last."""
    lines, r, details = record_and_replay(tmp_path, "constraints_double_pendulum", 0.5)
    (upper,) = [l["handle"] for l in lines if l["type"] == "actor" and l.get("name") == "upper"]
    assert any(l["type"] == "destroy" and l["handle"] == upper for l in lines)
    assert r["replayEnded"], details
    assert upper in r["shownActorsFirst"], details
    assert upper not in r["shownActorsLast"], details
    assert r["upAxis"] == "FLU", details  # the example's gravity is -z


def test_a_scene_with_gravity_down_y_is_shown_y_up(tmp_path):
    """SuperDex's default gravity is (0, -9.8, 0): the skinned pendulum example keeps it, and the
    replayed page shows its scene Y up (RUB), its skin among the drawn actors."""
    lines, r, details = record_and_replay(tmp_path, "skinned_double_pendulum", 0.3)
    (skin,) = [l["handle"] for l in lines if l["type"] == "actor" and l.get("name") == "skinned_pendulum/skin"]
    assert r["upAxis"] == "RUB", details
    assert skin in r["shownActorsFirst"], details
    assert r["canvasNonBlank"], details


RECORD_A_BALL = """
import sys
import superdex.physics as sdp
sdp.initialize()
scene = sdp.create_scene("recorded")
scene.set_gravity([0, 0, -9.81])  # Z-up, as the page shows it
scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1))
sdp.start_recording(sys.argv[1], 0.0)
for _ in range(20):
    scene.step(0.01)
sdp.stop_recording()
sdp.shutdown()
"""


def ignore_sigint():
    # as a shell starts a background job (`cmd &` in a script): SIGINT ignored
    signal.signal(signal.SIGINT, signal.SIG_IGN)


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_superdex_view_stops_on_a_signal_even_started_with_sigint_ignored(tmp_path, stop):
    recording = tmp_path / "ball.jsonl"
    subprocess.run([sys.executable, "-c", RECORD_A_BALL, str(recording)], check=True, capture_output=True,
                   timeout=300 * SLOW, cwd=REPO)
    cmd = [sys.executable, "-m", "superdex", "view", str(recording), "--no-browser", "--port", "0"]
    proc = subprocess.Popen(cmd, env=headless_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=REPO,
                            preexec_fn=ignore_sigint)
    try:
        line = proc.stdout.readline()
        assert "superdex view: replaying" in line, line + proc.stderr.read()
        proc.send_signal(stop)
        assert proc.wait(timeout=30 * SLOW) == 0
    finally:
        proc.kill()
        proc.wait()


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_a_stop_signal_only_sets_the_flag_wherever_it_arrives(stop):
    # A signal can arrive between any two bytecodes, also before the serving loop's try: the
    # handler must not raise there (it did, and the process then died of an uncaught interrupt)
    from superdex import cli

    saved = {sig: signal.getsignal(sig) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        flag = cli._stop_on_signals()
        assert flag == [False]
        signal.raise_signal(stop)
        assert flag == [True]
    finally:
        for sig, handler in saved.items():
            signal.signal(sig, handler)
