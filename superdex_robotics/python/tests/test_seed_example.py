"""The seed example (superdex_robotics/examples/advanced/example_custom_components.py), run headless
as a user would run it, for 12 simulated seconds (3.5 s, one press, when SUPERDEX_SANITIZED=1:
tools/sanitize.sh runs the suite with the sanitized engine, many times slower): SUPERDEX_DEBUGGER_RECORD makes
`debugger.attach()` record every step to a file, SUPERDEX_DEBUGGER_DURATION ends the loop.
The recording (docs/recording_format.md) is the evidence:

- exit code 0, nothing on stderr, every recorded number finite (frames every 10 ms);
- in free space (before the first contact) the ball tracks the moving circle target with RMS
  error under 5 mm (the target is the seed's circle, computed here independently);
- the ball presses on the duck once per 3 s period, and the contact force on it exceeds the
  controller's 0.5 N entry threshold each time; from 0.3 s after that until the ball lifts off,
  the force stays within 0.5 +- 0.1 N, and it lifts off when the target has risen above it by
  the 5 mm exit margin;
- in the same run, in-process: the sensor's reading after each step equals the total contact
  force the solver applied to the ball in that step (the recording's contact list) to 1e-6 N.
"""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[3]
EXAMPLE = REPO / "superdex_robotics" / "examples" / "advanced" / "example_custom_components.py"
SANITIZED = os.environ.get("SUPERDEX_SANITIZED") == "1"
DURATION = 3.5 if SANITIZED else 12.0
PERIOD = 3.0
PRESSES = 1 if SANITIZED else 4


def circle_target(t):
    theta = 2 * math.pi / PERIOD * t
    return np.array([-0.3 + 0.08 * math.cos(theta), 0.15 + 0.08 * math.sin(theta)])


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    recording = tmp_path_factory.mktemp("seed") / "run.jsonl"
    env = dict(os.environ, SUPERDEX_DEBUGGER_RECORD=str(recording), SUPERDEX_DEBUGGER_DURATION=str(DURATION),
               SUPERDEX_DEBUGGER_FRAME_INTERVAL="0.01")
    proc = subprocess.run([sys.executable, str(EXAMPLE)], env=env, capture_output=True, text=True, timeout=1800 * (5 if SANITIZED else 1))
    lines = []
    with open(recording) as f:
        for line in f:
            entry = json.loads(line)
            if entry.get("type") == "frame":
                # node positions: checked for finiteness here, then dropped to keep memory small
                entry["soft_finite"] = all(math.isfinite(v) for x in entry.pop("soft").values() for v in x)
            lines.append(entry)
    return proc, lines


def ball_handle(lines):
    (arm,) = [l for l in lines if l["type"] == "actor" and l["name"] == "example_bot_2dof"]
    return arm["links"][3]["handle"]


def test_runs_cleanly_and_records_finite_numbers(run):
    proc, lines = run
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert "recording to" in proc.stdout
    assert lines[0]["type"] == "header" and lines[0]["format"] == "superdex-recording" and lines[0]["version"] == 1
    frames = [l for l in lines if l["type"] == "frame"]
    # a frame once 10 ms passed: every third 4 ms step
    times = np.array([f["t"] for f in frames])
    assert np.diff(times).max() == pytest.approx(0.012, abs=1e-6)
    assert times[-1] == pytest.approx(DURATION, abs=0.012)
    for f in frames:
        for pose in f["links"].values():
            assert all(math.isfinite(v) for v in pose)
        assert f["soft_finite"]
        for c in f["contacts"]:
            assert all(math.isfinite(v) for v in c["f"])


def ball_track(lines):
    handle = str(ball_handle(lines))
    frames = [l for l in lines if l["type"] == "frame"]
    t = np.array([f["t"] for f in frames])
    xz = np.array([[f["links"][handle][0], f["links"][handle][2]] for f in frames])
    fz = np.array([-sum(c["f"][2] for c in f["contacts"] if c["b"] == int(handle)) +
                   sum(c["f"][2] for c in f["contacts"] if c["a"] == int(handle)) for f in frames])
    return t, xz, fz


def test_free_space_tracking(run):
    t, xz, fz = ball_track(run[1])
    first_contact = t[np.argmax(fz > 0)]
    free = t < first_contact - 0.05
    error = np.linalg.norm(xz[free] - np.array([circle_target(ti) for ti in t[free]]), axis=1)
    assert first_contact > 1.0
    assert np.sqrt(np.mean(error**2)) < 5e-3


def presses(t, fz):
    """Contact episodes of the ball as (first contact, force-mode entry, lift-off) frame indices:
    a press starts with contact after at least 1 s without any, force mode is entered when the
    force first exceeds the 0.5 N threshold, and the press ends at the first frame without contact
    after that."""
    out = []
    i = 1
    while i < len(t):
        if fz[i] > 0 and fz[i - 1] <= 0 and (not out or t[i] - t[out[-1][2]] > 1.0):
            entry = i + int(np.argmax(fz[i:] > 0.5))
            end = entry + int(np.argmax(fz[entry:] <= 0))
            out.append((i, entry, end))
            i = end
        i += 1
    return out


def test_presses_on_the_duck_every_period(run):
    t, xz, fz = ball_track(run[1])
    found = presses(t, fz)
    assert len(found) == PRESSES
    np.testing.assert_allclose(np.diff([t[start] for start, _, _ in found]), PERIOD, atol=0.1)
    for start, entry, end in found:
        assert fz[entry] > 0.5 and t[entry] - t[start] < 0.2, "the press exceeds the force-mode entry threshold"


def regulated_window(t, xz, entry):
    """Frames of a press from 0.3 s after force-mode entry until force mode is left, and the frame
    where it is left: when the rising target is above the ball by the 5 mm exit margin (the
    controller's rule), one frame of slack for the recording's sampling."""
    target_z = np.array([circle_target(ti)[1] for ti in t])
    rising = np.flatnonzero((target_z > xz[:, 1] + 0.005) & (np.arange(len(t)) >= entry))
    exit_frame = int(rising[0])
    window = np.arange(entry, exit_frame - 1)
    return window[t[window] >= t[entry] + 0.3], exit_frame


def test_force_is_regulated_while_pressing(run):
    """Each press: from 0.3 s after the force first exceeds the 0.5 N threshold (force mode
    entered) until the target has risen above the ball by the 5 mm exit margin, f_z stays within
    0.5 +- 0.1 N, and contact lasts that long (force mode is left by the margin, not by losing
    contact); the ball lifts off right after."""
    t, xz, fz = ball_track(run[1])
    for start, entry, end in presses(t, fz):
        regulated, exit_frame = regulated_window(t, xz, entry)
        assert len(regulated) > 10, "force mode lasts beyond the transient"
        assert np.abs(fz[regulated] - 0.5).max() <= 0.1
        assert exit_frame <= end, "contact held until the exit margin was reached"
        assert t[end] - t[exit_frame] < 0.1, "the ball lifts off once force mode is left"


def test_sensor_reads_the_contact_force_the_solver_applied(monkeypatch, tmp_path):
    """In-process through the first press: after each step, the sensor's compute_signal() equals the
    sum of the forces of the solver's contact records on the ball in that step. After main()'s
    destroy_bot and shutdown no component object is alive and the engine holds nothing."""
    import gc
    import importlib.util
    import weakref

    import superdex.physics as sdp

    spec = importlib.util.spec_from_file_location("seed_example", EXAMPLE)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    monkeypatch.setenv("SUPERDEX_DEBUGGER_RECORD", str(tmp_path / "run.jsonl"))
    monkeypatch.setenv("SUPERDEX_DEBUGGER_DURATION", "2.3")
    compared = []
    original = example.MyContactForceSensor.compute_signal

    def compute_signal(self):
        reading = original(self)
        # every contact record of this link: its force is on actor_a from actor_b
        link = self.actor.get_handle()
        points = self.actor.get_contact_points_world()
        applied = np.zeros(3)
        for p in points:
            assert link in (p.actor_a, p.actor_b)
            applied += np.asarray(p.force, dtype=np.float64) * (1.0 if p.actor_a == link else -1.0)
        compared.append((reading.astype(np.float64), applied))
        return reading

    original_init = example.MyContactForceSensor.__init__

    def init(self, actor, param_args):
        original_init(self, actor, param_args)
        actor.register_query(sdp.QueryType.CONTACT_POINTS)

    # every component object the example makes, watched through weak references
    components = []
    for cls in (example.MyVelocityForceController, example.MyContactForceSensor, example.MyVelocityServoActuator):
        made = init if cls is example.MyContactForceSensor else cls.__init__

        def watched(self, *args, _made=made):
            _made(self, *args)
            components.append(weakref.ref(self))

        monkeypatch.setattr(cls, "__init__", watched)
    monkeypatch.setattr(example.MyContactForceSensor, "compute_signal", compute_signal)
    example.main()
    gc.collect()
    assert len(components) == 4, "a controller, a sensor and two servos were made"
    assert [ref() for ref in components] == [None] * 4, "destroy_bot and shutdown released every component"
    assert not sdp.is_initialized()
    assert len(compared) == round(2.3 * example.CONTROL_RATE_HZ)
    readings = np.array([c[0] for c in compared])
    applied = np.array([c[1] for c in compared])
    assert np.abs(readings[:, 2]).max() > 0.5, "the run includes a press"
    np.testing.assert_allclose(readings, applied, rtol=0, atol=1e-6)
