"""Scripts exit cleanly in every order: with or without shutdown(), with step and log callbacks,
scenes, actors, shapes, bots and Python components alive in module globals. Each script runs in
its own interpreter and must exit 0 with nothing on stderr (no crash, no leak report)."""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
SEED_EXAMPLE = REPO / "superdex_robotics/examples/advanced/example_custom_components.py"

PHYSICS_WORLD = """
import superdex.physics as sdp
sdp.initialize({threads})
scene = sdp.create_scene("s")
scene.set_gravity([0, 0, -9.81])
shape = sdp.create_sphere_shape([0, 0, 0], 0.1)
ground = scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
ball = scene.create_rigid_actor(name="ball", shape=shape, world_from_local=sdp.TransformRT(translation=[0, 0, 0.5]))
tet = sdp.create_tet_mesh_shape([0, 0, 1, 0.2, 0, 1, 0, 0.2, 1, 0, 0, 1.2], [0, 1, 2, 3])
soft = scene.create_soft_actor(name="soft", shape=tet)
seen = []
pre = scene.register_pre_step_callback("pre", lambda info: seen.append((info.scene, info.time_step_sec)))
post = scene.register_post_step_callback("post", lambda info: seen.append(ball.get_root_transform()))
sdp.set_log_callback(lambda channel, message, file, line: seen.append(message))
state = scene.capture_state()
for _ in range(5):
    scene.step(0.01)
sdp.log("a message for the Python log callback", sdp.LogChannel.WARNING)
"""

ROBOT_WORLD = """
import importlib.util
import superdex.physics as physics
import superdex.robotics as robotics
spec = importlib.util.spec_from_file_location("seed_components", {seed!r})
seed = importlib.util.module_from_spec(spec)
spec.loader.exec_module(seed)
physics.initialize(0)
scene = physics.create_scene("robots")
scene.set_gravity([0, 0, -9.81])
context = robotics.create_context()
seed.register_component_types(context)
prefab = robotics.load_bot_prefab_from_file(seed.get_default_bot_path())
bot = robotics.create_bot(scene, prefab, context)
actor = bot.get_articulated_actor()
handle = context.create_controller("MY_VELOCITY_FORCE_CONTROLLER", None, actor, "my_controller")
controller = robotics.get_python_controller(context, handle)
readings = []
scene.register_post_step_callback("obs", lambda info: readings.append(controller.get_current_observations()))
for _ in range(3):
    scene.step(0.004)
"""

ENDINGS = {
    "no_shutdown": "",
    "shutdown": "sdp.shutdown() if 'sdp' in globals() else physics.shutdown()",
    "shutdown_then_use_handles": """
(sdp if 'sdp' in globals() else physics).shutdown()
try:
    scene.step(0.01)
except Exception as e:
    assert "Error" in type(e).__name__, e
""",
    "shutdown_from_atexit": """
import atexit
atexit.register((sdp if 'sdp' in globals() else physics).shutdown)
""",
    "destroy_scene_only": "(sdp if 'sdp' in globals() else physics).destroy_scene(scene)",
}


def run_script(tmp_path, body):
    script = tmp_path / "script.py"
    script.write_text(textwrap.dedent(body))
    env = dict(os.environ)
    result = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env, timeout=300,
                            cwd=str(tmp_path))
    return result


@pytest.mark.parametrize("ending", list(ENDINGS))
@pytest.mark.parametrize("threads", [0, 2])
def test_physics_script_exits_cleanly(tmp_path, ending, threads):
    r = run_script(tmp_path, PHYSICS_WORLD.format(threads=threads) + ENDINGS[ending])
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""


@pytest.mark.parametrize("ending", ["no_shutdown", "shutdown", "destroy_scene_only"])
def test_robotics_script_exits_cleanly(tmp_path, ending):
    r = run_script(tmp_path, ROBOT_WORLD.format(seed=str(SEED_EXAMPLE)) + ENDINGS[ending])
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""


def test_a_failing_script_still_exits_without_a_crash(tmp_path):
    r = run_script(tmp_path, PHYSICS_WORLD.format(threads=0) + "raise SystemExit('stopping with scenes alive')")
    assert r.returncode == 1
    assert r.stderr.strip() == "stopping with scenes alive"
