"""Scene 9: robots people bring, each simulator reading the same model file.

- From MuJoCo model files: gymnasium-robotics' Shadow hand with its block (hand/manipulate_block.xml:
  24 joints, the block on a free joint resting in the palm) and gymnasium's humanoid
  (humanoid.xml: 17 joints on a free torso) falling onto its floor. SuperDex imports the file
  (superdex.robotics.load_mjcf_file); MuJoCo compiles it. No control (the hand's position servos
  hold their zero targets), at the file's time step.
- From example-robot-data URDFs: the G1 humanoid (g1_29dof_rev_1_0.urdf, 29 joints, convex
  hulls of its meshes) on a free base, dropped standing from a 0.8 m pelvis height onto a ground
  plane, no control; the Allegro hand (allegro_right_hand.urdf) welded palm up with a 5 cm, 100 g
  cube on its palm, its 16 joints driven towards a grasp (stiffness 20 N m/rad, damping
  0.5 N m s/rad: SuperDex's implicit joint drives, MuJoCo's position actuators with kp 20 and
  kv 0.5). SuperDex imports the URDF (superdex.robotics.load_bot_prefab_from_urdf_file); MuJoCo
  reads the same file through MjSpec (its meshes found by name, visual geoms discarded), with the
  free joint, the floor, the cube and the actuators added in code. 2 ms steps.

1 s of simulated time; the loop only steps. Checks: the height at the end (m) of the block, the
humanoid's torso, the G1's pelvis and the cube.
"""

from __future__ import annotations

import importlib.util
import math
import re
import warnings
from pathlib import Path

from benchmarks.harness import Timer, median_of_episodes

NUMBER = 9
TITLE = "Robots people bring (Shadow hand with block, humanoid, G1 falling, Allegro with a cube)"
SIMS = ("superdex", "mujoco")
MODELS = {
    "shadow hand + block": ("gymnasium_robotics", "envs/assets/hand/manipulate_block.xml", "object"),
    "humanoid": ("gymnasium", "envs/mujoco/assets/humanoid.xml", "torso"),
    "G1 falling": ("urdf", "g1_description/urdf/g1_29dof_rev_1_0.urdf", "pelvis"),
    "Allegro + cube": ("urdf", "allegro_hand_description/urdf/allegro_right_hand.urdf", "cube"),
}
URDF_DT = 0.002
G1_HEIGHT = 0.8  # m: the pelvis's height at the start, the feet just above the ground
CUBE_HALF, CUBE_MASS, CUBE_START = 0.025, 0.1, (0.045, 0.0, 0.0111 + 0.025 + 0.0005)  # m, kg, m (world)
# the Allegro's joint targets (rad): index, middle, ring curled; the thumb turned in
GRASP = [0.0, 1.0, 1.0, 1.0] * 3 + [1.3, 0.3, 0.5, 0.5]
KP, KD = 20.0, 0.5


def model_path(package: str, relative: str) -> str:
    if package == "urdf":
        from superdex.robot_files import example_robot_data_file

        return str(example_robot_data_file("robots/" + relative))
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
        self.scene = sdp.create_scene("robots")
        ctx = sdr.create_context()
        if path.endswith(".urdf"):
            self.dt = URDF_DT
            self.scene.set_gravity([0, 0, -9.81])
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # mesh repairs and the importer's notes
                prefab = sdr.load_bot_prefab_from_urdf_file(path, fixed_base=body == "cube")
            if body == "pelvis":
                self.scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
                robot = sdr.create_bot(self.scene, prefab, ctx).get_articulated_actor()
                pose = [0.0] * robot.get_num_dofs()
                pose[2] = G1_HEIGHT
                robot.set_articulated_pose_from_joints(pose)
                self.height = lambda: float(robot.get_articulated_link_transforms()[0].translation[2])
            else:
                # palm up: the palm's normal (+x) onto the world's +z
                prefab.world_from_root = sdp.TransformRT(rotation=sdp.Quaternion.from_axis_angle([0, 1, 0], -math.pi / 2))
                hand = sdr.create_bot(self.scene, prefab, ctx).get_articulated_actor()
                cube = self.scene.create_rigid_actor(name="cube", shape=sdp.create_box_shape(half_extents=[CUBE_HALF] * 3), mass=CUBE_MASS,
                                                     world_from_local=sdp.TransformRT(translation=list(CUBE_START)),
                                                     contact=sdp.ContactParams(coulomb_friction_coefficient=1.0))
                for dof, target in enumerate(GRASP):
                    hand.set_joint_drive(dof, stiffness=KP, damping=KD, target_position=target)
                self.height = lambda: float(cube.get_root_transform().translation[2])
            return
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # what the importer leaves out (tendons, sensors, ...)
            model = sdr.load_mjcf_file(path)
        self.dt = model.timestep
        self.scene.set_gravity(model.gravity)
        self.bots = [sdr.create_bot(self.scene, p, ctx) for p in model.bots]
        self.body = next(b.get_articulated_actor() for b, p in zip(self.bots, model.bots) if p.links[0].name == body)
        self.height = lambda: float(self.body.get_articulated_link_transforms()[0].translation[2])

    def step(self):
        self.scene.step(self.dt)

    def close(self):
        self.sdp.shutdown()


def mujoco_urdf_spec(mujoco, path: str):
    """The URDF as an MjSpec: meshes looked up by file name in the robot's meshes/ folder, visual
    geoms discarded, inertias that break the triangle inequality balanced (MuJoCo's own repair, as
    SuperDex's importer repairs them)."""
    text = Path(path).read_text()
    meshdir = Path(path).parent.parent / "meshes"
    text = re.sub(r'filename="[^"]*/([^/"]+)"', r'filename="\1"', text)
    text = re.sub(r"(<robot[^>]*>)", r'\1<mujoco><compiler meshdir="' + str(meshdir) + r'" discardvisual="true" balanceinertia="true"/></mujoco>', text, count=1)
    return mujoco.MjSpec.from_string(text)


class MuJoCo:
    def __init__(self, path: str, body: str):
        import mujoco

        self.mj = mujoco
        if path.endswith(".urdf"):
            spec = mujoco_urdf_spec(mujoco, path)
            spec.option.timestep = URDF_DT
            root = spec.worldbody.first_body()
            if body == "pelvis":
                root.add_freejoint()
                spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1])
            else:
                # palm up (w, x, y, z): -90 degrees about y
                root.quat = [math.cos(-math.pi / 4), 0.0, math.sin(-math.pi / 4), 0.0]
                cube = spec.worldbody.add_body(name="cube", pos=list(CUBE_START))
                cube.add_freejoint()
                cube.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[CUBE_HALF] * 3, mass=CUBE_MASS, friction=[1.0, 0.005, 0.0001])
                for joint in spec.joints:
                    if joint.type == mujoco.mjtJoint.mjJNT_HINGE:
                        spec.add_actuator(target=joint.name, trntype=mujoco.mjtTrn.mjTRN_JOINT,
                                          gaintype=mujoco.mjtGain.mjGAIN_FIXED, gainprm=[KP] + [0] * 9,
                                          biastype=mujoco.mjtBias.mjBIAS_AFFINE, biasprm=[0, -KP, -KD] + [0] * 7)
            self.model = spec.compile()
            self.data = mujoco.MjData(self.model)
            if body == "pelvis":
                self.data.qpos[2] = G1_HEIGHT
            else:
                self.data.ctrl[:] = GRASP
            self.dt = self.model.opt.timestep
            self.body = self.model.body(body).id
            return
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
