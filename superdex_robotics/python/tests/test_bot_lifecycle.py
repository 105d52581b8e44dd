"""10,000 create/destroy cycles of a bot with Python components leak nothing.

The resident set size after the cycles stays within 5 % of its value after a warm-up, and
every Python component object the framework created has been released (weak references die).
Under AddressSanitizer (SUPERDEX_SANITIZED=1, tools/sanitize.sh) the resident size is not
compared: ASan keeps freed memory in its quarantine (256 MB) before reusing it, so the process
grows until the quarantine is full whatever the engine does; leaks there are LeakSanitizer's to
find (the C++ memory-cycles test).
"""

import gc
import os
import weakref
from pathlib import Path

import superdex.robotics as sdr
from robotics_helpers import EXAMPLE_BOT, scene  # noqa: F401
from superdex.physics.paths import resolve_asset

CYCLES = 10_000
WARMUP = 1_000


def rss_bytes() -> int:
    # second field of /proc/self/statm: resident pages
    pages = int(Path("/proc/self/statm").read_text().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE")


class Sensor:
    def __init__(self, actor, param_args):
        self.actor = actor
        self.buffer = bytearray(1024)  # some memory per component, so leaks would show

    def reset(self):
        pass


class Servo(Sensor):
    pass


def test_create_destroy_cycles_keep_memory_flat(scene):
    ctx = sdr.create_context()
    sdr.register_python_sensor(ctx, "MY_CONTACT_FORCE_SENSOR", Sensor)
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", Servo)
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    refs = []
    baseline = None
    for cycle in range(CYCLES):
        bot = sdr.create_bot(scene, prefab, ctx)
        if cycle % 500 == 0:
            refs.append(weakref.ref(sdr.get_python_sensor(ctx, bot.get_sensor_handles()[0])))
        scene.step(0.004)
        sdr.destroy_bot(scene, bot)
        del bot
        if cycle == WARMUP:
            gc.collect()
            baseline = rss_bytes()
    gc.collect()
    final = rss_bytes()
    if os.environ.get("SUPERDEX_SANITIZED") != "1":
        assert final <= baseline * 1.05, f"RSS grew from {baseline / 2**20:.1f} MiB to {final / 2**20:.1f} MiB"
    assert all(r() is None for r in refs), "Python components were released"
    assert scene.get_num_actors() == 0
