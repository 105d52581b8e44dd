"""Scene 9: robots from the MuJoCo model files people train on, each simulator reading the same
file: gymnasium-robotics' Shadow hand with its block (hand/manipulate_block.xml: 24 joints, the
block on a free joint resting in the palm) and gymnasium's humanoid (humanoid.xml: 17 joints on a
free torso) falling onto its floor. SuperDex imports the file (superdex.robotics.load_mjcf_file)
and steps its bots; MuJoCo compiles it and calls mj_step. Both at the file's time step, no
control (the hand's position servos hold their zero targets), 1 s of simulated time; the loop
only steps.

Checks: the block's height and the humanoid torso's height at the end (m).
"""

from __future__ import annotations

import importlib.util
import warnings
from pathlib import Path

from benchmarks.harness import Timer, median_of_episodes

NUMBER = 9
TITLE = "Robots from MuJoCo model files (Shadow hand with block, humanoid)"
SIMS = ("superdex", "mujoco")
MODELS = {
    "shadow hand + block": ("gymnasium_robotics", "envs/assets/hand/manipulate_block.xml", "object"),
    "humanoid": ("gymnasium", "envs/mujoco/assets/humanoid.xml", "torso"),
}


def model_path(package: str, relative: str) -> str:
    spec = importlib.util.find_spec(package)
    return str(Path(next(iter(spec.submodule_search_locations))) / relative)


def cases(opts):
    seconds = 0.02 if opts.quick else 1.0
    return [{"label": f"{name} / {sim}", "model": name, "sim": sim, "seconds": seconds, "episodes": 1 if opts.quick else 3}
            for name in MODELS for sim in SIMS]


class SuperDex:
    def __init__(self, path: str, body: str):
        import superdex.physics as sdp
        import superdex.robotics as sdr

        self.sdp = sdp
        sdp.initialize(num_worker_threads=0)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # what the importer leaves out (tendons, sensors, ...)
            model = sdr.load_mjcf_file(path)
        self.dt = model.timestep
        self.scene = sdp.create_scene("mjcf")
        self.scene.set_gravity(model.gravity)
        ctx = sdr.create_context()
        self.bots = [sdr.create_bot(self.scene, p, ctx) for p in model.bots]
        self.body = next(b.get_articulated_actor() for b, p in zip(self.bots, model.bots) if p.links[0].name == body)

    def step(self):
        self.scene.step(self.dt)

    def height(self):
        return float(self.body.get_articulated_link_transforms()[0].translation[2])

    def close(self):
        self.sdp.shutdown()


class MuJoCo:
    def __init__(self, path: str, body: str):
        import mujoco

        self.mj = mujoco
        self.model = mujoco.MjModel.from_xml_path(path)
        self.data = mujoco.MjData(self.model)
        self.dt = self.model.opt.timestep
        self.body = self.model.body(body).id

    def step(self):
        self.mj.mj_step(self.model, self.data)

    def height(self):
        return float(self.data.xpos[self.body][2])

    def close(self):
        pass


def run_case(case):
    return median_of_episodes(case, run_episode)


def run_episode(case):
    package, relative, body = MODELS[case["model"]]
    sim = {"superdex": SuperDex, "mujoco": MuJoCo}[case["sim"]](model_path(package, relative), body)
    steps = int(round(case["seconds"] / sim.dt))
    with Timer() as timer:
        for _ in range(steps):
            sim.step()
    checks = {"height_m": sim.height()}
    sim.close()
    return timer.wall, {"steps": steps, "sim_time": steps * sim.dt, "checks": checks}
