"""What a connected debugger page costs the simulation: wall time per step with no page, and with a
page attached (frames built, sent at up to 60 Hz and acknowledged by a client in another process,
as a browser is), stepping as fast as possible so that every cost shows.

    uv run python benchmarks/debugger_overhead.py [--seconds 3] [--repeats 3]

Scenes: a stack of rigid boxes (cheap steps: the worst case for the relative overhead) and the
seed example's duck lamp on the ground (1168 soft nodes per frame)."""

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

import superdex.physics as sdp

REPO = Path(__file__).resolve().parents[1]
DUCK = REPO / "assets" / "prefabs" / "duck_lamp" / "duck_lamp_recumbent_full.mochi_prefab"


def boxes(scene):
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    for i in range(20):
        scene.create_rigid_actor(name=f"box_{i}", shape=sdp.create_box_shape([0.1, 0.1, 0.1]), mass=1.0,
                                 world_from_local=sdp.TransformRT(translation=[0.3 * (i % 5), 0.3 * (i // 5), 0.1]))


def duck(scene):
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    sdp.prefab.add_to_scene(str(DUCK), str(REPO / "assets"), scene)


PAGE = """
import json, sys
from websockets.sync.client import connect
frames = sent = 0
with connect(sys.argv[1], max_size=None) as ws:
    ws.send(json.dumps({"type": "control", "action": "fast"}))
    try:
        while True:
            message = ws.recv()
            sent += len(message)
            if '"type":"frame"' in message:
                frames += 1
                ws.send('{"type":"ack"}')
    except Exception:
        pass
print(frames, sent)
"""


def start_page(url):
    """A page in another process (as a browser is): takes every message, acknowledges frames."""
    return subprocess.Popen([sys.executable, "-c", PAGE, url], stdout=subprocess.PIPE, text=True)


def steps_per_second(build, seconds, dt, attached):
    sdp.initialize()
    scene = sdp.create_scene("bench")
    scene.set_gravity([0, 0, -9.81])
    build(scene)
    for _ in range(20):  # settle, warm caches
        scene.step(dt)
    page = None
    server = sdp.get_debug_server()
    if attached:
        server.start()
        page = start_page(server.get_url().replace("http://", "ws://") + "ws")
        while not server.has_connection():
            time.sleep(0.01)
        time.sleep(0.5)  # the page asks for "fast"
        scene.step(dt)
    steps, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        scene.step(dt)
        steps += 1
    rate = steps / (time.perf_counter() - start)
    info = (0, 0)
    if attached:
        server.stop()
        frames, sent = page.communicate(timeout=30)[0].split()
        info = (int(frames), int(sent))
    sdp.shutdown()
    return rate, info


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    print(f"{'scene':<8} {'steps/s alone':>14} {'with page':>10} {'overhead':>9} {'frames/s':>9} {'kB/frame':>9}")
    for name, build, dt in [("boxes", boxes, 0.004), ("duck", duck, 0.004)]:
        # alternated runs, medians: the machine's noise is of the same order as the effect
        alones, pages = [], []
        for _ in range(args.repeats):
            alones.append(steps_per_second(build, args.seconds, dt, False)[0])
            pages.append(steps_per_second(build, args.seconds, dt, True))
        alone = statistics.median(alones)
        with_page = statistics.median(p[0] for p in pages)
        frames = statistics.median(p[1][0] for p in pages)
        sent = statistics.median(p[1][1] for p in pages)
        print(f"{name:<8} {alone:>14.1f} {with_page:>10.1f} {100 * (1 - with_page / alone):>8.1f}% "
              f"{frames / args.seconds:>9.1f} {sent / max(frames, 1) / 1000:>9.1f}")


if __name__ == "__main__":
    main()
