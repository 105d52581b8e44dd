"""One scene description, three simulators: SuperDex (its Python API), MuJoCo (an MJCF string) and
PyBullet (URDF text for articulations, API calls for free bodies).

A description is plain data:

    scene = {
        "dt": 0.004, "gravity": [0, 0, -9.81],
        "ground": {"friction": 0.5} or None,                  # the plane z = 0
        "bodies": [{"name", "shape", "mass", "position", "rotation" (x, y, z, w),
                    "friction", "static": bool}],               # rigid bodies (free or static)
        "articulations": [{"name", "links", "joints", "world_from_root": {"translation", "rotation"}}],
    }

Articulations use the link and joint dicts of the .superdex_bot format (FORMATS.md), the fields
that all three simulators can express: link mass, centerOfMass, momentOfInertia [Ixx, Ixy, Ixz,
Iyy, Iyz, Izz] about the COM in link axes, shape (sphere, box or capsule with center and
rotation; capsules along their local z), contact.coulombFrictionCoefficient; joint type (Hard,
Revolute, Prismatic, Free), axis, parentLinkFromJoint, minLimit/maxLimit, friction.viscous,
inertia (armature). Shapes are {"sphere": {"radius"}}, {"box": {"halfExtents"}} or
{"capsule": {"radius", "halfLength"}}, each with optional "center" and "rotation".

What each simulator cannot express the same way is handled here once:
- Friction combination: SuperDex combines two surfaces by their geometric mean, MuJoCo by the maximum,
  Bullet by the product. With one coefficient mu for every surface, SuperDex and MuJoCo get mu
  and PyBullet gets sqrt(mu) per surface, so every pair has mu.
- Bullet's default linear and angular damping of every body (0.04) is switched off, and so are
  the velocity motors PyBullet puts on every joint.
- Self-collision: SuperDex and MuJoCo collide the links of one articulation except parent and
  child; PyBullet is told the same (URDF_USE_SELF_COLLISION_EXCLUDE_PARENT).
- Bullet has no joint armature: a description with armature loads into PyBullet without it
  (reported by `pybullet_differences`).
"""

from __future__ import annotations

import json
import math
import os
import tempfile

import numpy as np

# ---------------------------------------------------------------- small geometry helpers


def quat_xyzw_to_matrix(q):
    x, y, z, w = np.asarray(q, dtype=np.float64) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def matrix_to_quat_xyzw(R):
    R = np.asarray(R, dtype=np.float64)
    t = np.trace(R)
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        q = [(R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s, 0.25 * s]
    elif R[0, 0] > R[1, 1] and R[0, 0] > R[2, 2]:
        s = math.sqrt(1.0 + R[0, 0] - R[1, 1] - R[2, 2]) * 2
        q = [0.25 * s, (R[0, 1] + R[1, 0]) / s, (R[0, 2] + R[2, 0]) / s, (R[2, 1] - R[1, 2]) / s]
    elif R[1, 1] > R[2, 2]:
        s = math.sqrt(1.0 + R[1, 1] - R[0, 0] - R[2, 2]) * 2
        q = [(R[0, 1] + R[1, 0]) / s, 0.25 * s, (R[1, 2] + R[2, 1]) / s, (R[0, 2] - R[2, 0]) / s]
    else:
        s = math.sqrt(1.0 + R[2, 2] - R[0, 0] - R[1, 1]) * 2
        q = [(R[0, 2] + R[2, 0]) / s, (R[1, 2] + R[2, 1]) / s, 0.25 * s, (R[1, 0] - R[0, 1]) / s]
    q = np.array(q)
    return q / np.linalg.norm(q)


def rpy_to_quat_xyzw(r, p, y):
    """URDF roll-pitch-yaw (fixed axes X, Y, Z: R = Rz(y) Ry(p) Rx(r)) as a quaternion."""
    cr, sr, cp, sp, cy, sy = math.cos(r / 2), math.sin(r / 2), math.cos(p / 2), math.sin(p / 2), math.cos(y / 2), math.sin(y / 2)
    return np.array([sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy])


def quat_xyzw_to_rpy(q):
    R = quat_xyzw_to_matrix(q)
    pitch = math.asin(max(-1.0, min(1.0, -R[2, 0])))
    if abs(R[2, 0]) < 1 - 1e-9:
        roll = math.atan2(R[2, 1], R[2, 2])
        yaw = math.atan2(R[1, 0], R[0, 0])
    else:  # gimbal lock: put everything in yaw
        roll = 0.0
        yaw = math.atan2(-R[0, 1], R[1, 1])
    return roll, pitch, yaw


def fmt(v):
    return " ".join(repr(float(x)) for x in v)


def wxyz(q):
    x, y, z, w = q
    return [w, x, y, z]


def shape_kind(shape):
    (kind,) = [k for k in ("sphere", "box", "capsule") if k in shape]
    return kind, shape[kind]


def shape_pose(shape):
    """(center, rotation xyzw) of a shape in its link frame; spheres put "center" inside."""
    kind, s = shape_kind(shape)
    center = s.get("center", shape.get("center", [0, 0, 0]))
    rotation = s.get("rotation", shape.get("rotation", [0, 0, 0, 1]))
    return list(center), list(rotation)


def link_friction(link, default=0.5):
    return float(link.get("contact", {}).get("coulombFrictionCoefficient", default))


def joint_limit(joint, key):
    """The scalar limit along the joint axis from a 3-vector minLimit/maxLimit (or a scalar)."""
    v = joint.get(key)
    if v is None:
        return None
    if isinstance(v, (int, float)):
        return float(v)
    axis = np.asarray(joint["axis"], dtype=np.float64)
    return float(np.dot(np.asarray(v, dtype=np.float64), axis / np.linalg.norm(axis)))


def inertia_matrix(link):
    i = link.get("momentOfInertia", [0, 0, 0, 0, 0, 0])
    return np.array([[i[0], i[1], i[2]], [i[1], i[3], i[4]], [i[2], i[4], i[5]]], dtype=np.float64)


# ---------------------------------------------------------------- SuperDex


def superdex_articulation(scene, sdp, name, links, joints, world_from_root=None, default_pose=None):
    """An articulated actor from link and joint dicts in the .superdex_bot format (FORMATS.md).

    SuperDex's ArticulatedLinkParams carry a shape in the link frame only, while these dicts place
    their shapes with a center and rotation in it: the dicts are written as a bot file and built by
    superdex.robotics (create_bot, no components), which keeps each shape's pose as the file says."""
    import superdex.robotics as sdr

    doc = {"name": name, "links": links, "joints": joints}
    if default_pose is not None:
        doc["defaultPose"] = [float(x) for x in default_pose]
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, f"{name}.superdex_bot")
        with open(path, "w") as f:
            json.dump(doc, f)
        prefab = sdr.load_bot_prefab_from_file(path)
    if world_from_root is not None:
        prefab.world_from_root = world_from_root
    # the context only keeps the bot's (empty) component lists: the actor stays with the scene
    return sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()


def node_positions_world(actor):
    """(n, 3) world positions (m) of a SuperDex soft actor's nodes: its local node positions
    placed by its frame. Needs the actor's NODE_POSITIONS query (registered before the last step)."""
    local = np.asarray(actor.get_node_positions_local(), dtype=np.float64).reshape(-1, 3)
    X_WL = actor.get_root_transform()
    return local @ quat_xyzw_to_matrix(np.asarray(X_WL.rotation, dtype=np.float64)).T + np.asarray(X_WL.translation, dtype=np.float64)


def build_superdex(scene_desc, sdp, scene=None, name="bench", offset=(0.0, 0.0, 0.0)):
    """Adds the description to a SuperDex scene (created when None). Returns (scene, actors by name).
    `offset` translates everything (independent copies side by side)."""
    if scene is None:
        scene = sdp.create_scene(name)
        scene.set_gravity(list(scene_desc.get("gravity", [0, 0, -9.81])))
    off = np.asarray(offset, dtype=np.float64)
    actors = {}
    ground = scene_desc.get("ground")
    if ground is not None and not np.any(off):
        actors["ground"] = scene.create_rigid_actor(
            name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True,
            contact=sdp.ContactParams(coulomb_friction_coefficient=ground["friction"]))
    for b in scene_desc.get("bodies", []):
        kind, s = shape_kind(b["shape"])
        shape = (sdp.create_box_shape(s["halfExtents"]) if kind == "box" else
                 sdp.create_sphere_shape([0, 0, 0], s["radius"]) if kind == "sphere" else
                 sdp.create_capsule_shape(s["radius"], s["halfLength"]))
        xf = sdp.TransformRT(rotation=sdp.Quaternion(*b.get("rotation", [0, 0, 0, 1])),
                             translation=list(np.asarray(b["position"], dtype=np.float64) + off))
        static = b.get("static", False)
        params = sdp.RigidActorParams(name=b["name"], shape=shape, is_static=static, world_from_local=xf,
                                      contact=sdp.ContactParams(coulomb_friction_coefficient=b.get("friction", 0.5)))
        if not static:
            params.mass = b["mass"]
        actors[b["name"]] = scene.create_rigid_actor(params)
    for a in scene_desc.get("articulations", []):
        root = a.get("world_from_root", {})
        xf = sdp.TransformRT(rotation=sdp.Quaternion(*root.get("rotation", [0, 0, 0, 1])),
                             translation=list(np.asarray(root.get("translation", [0, 0, 0]), dtype=np.float64) + off))
        actors[a["name"]] = superdex_articulation(scene, sdp, a["name"], a["links"], a["joints"], world_from_root=xf,
                                                  default_pose=a.get("default_pose"))
    return scene, actors


# ---------------------------------------------------------------- MuJoCo (MJCF)


def _mjcf_geom(shape, friction, name):
    kind, s = shape_kind(shape)
    center, rotation = shape_pose(shape)
    size = ({"sphere": lambda: [s["radius"]], "box": lambda: s["halfExtents"],
             "capsule": lambda: [s["radius"], s["halfLength"]]})[kind]()
    return (f'<geom name="{name}" type="{kind}" size="{fmt(size)}" pos="{fmt(center)}" quat="{fmt(wxyz(rotation))}" '
            f'friction="{friction!r} 0.005 0.0001"/>')


def _mjcf_articulation(a, indent="    "):
    links, joints = a["links"], a["joints"]
    children = {i: [] for i in range(len(links))}
    for i, link in enumerate(links):
        if "parentLink" in link:
            children[link["parentLink"]].append(i)
    root = a.get("world_from_root", {})

    def body(i, depth):
        link, joint = links[i], joints[i]
        pad = indent + "  " * depth
        X = joint.get("parentLinkFromJoint", {})
        pos = X.get("translation", [0, 0, 0])
        rot = X.get("rotation", [0, 0, 0, 1])
        if i == 0:  # the root joint's parent frame is world_from_root
            R0 = quat_xyzw_to_matrix(root.get("rotation", [0, 0, 0, 1]))
            pos = R0 @ np.asarray(pos, dtype=np.float64) + np.asarray(root.get("translation", [0, 0, 0]), dtype=np.float64)
            rot = matrix_to_quat_xyzw(R0 @ quat_xyzw_to_matrix(rot))
        out = [f'{pad}<body name="{a["name"]}/{link["name"]}" pos="{fmt(pos)}" quat="{fmt(wxyz(rot))}">']
        t = joint["type"]
        if t in ("Revolute", "Prismatic"):
            lo, hi = joint_limit(joint, "minLimit"), joint_limit(joint, "maxLimit")
            attrs = f'type="{"hinge" if t == "Revolute" else "slide"}" axis="{fmt(joint["axis"])}"'
            if lo is not None or hi is not None:
                attrs += f' limited="true" range="{lo if lo is not None else -1e9!r} {hi if hi is not None else 1e9!r}"'
            damping = joint.get("friction", {}).get("viscous", 0.0)
            attrs += f' damping="{damping!r}" armature="{float(joint.get("inertia", 0.0))!r}"'
            out.append(f'{pad}  <joint name="{a["name"]}/{joint["name"]}" {attrs}/>')
        elif t == "Free":
            out.append(f'{pad}  <freejoint name="{a["name"]}/{joint["name"]}"/>')
        elif t != "Hard":
            raise ValueError(f"joint type {t} is not generated for MuJoCo")
        mass = float(link.get("mass", 0.0))
        if mass > 0:
            I = inertia_matrix(link)
            full = [I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2]]
            out.append(f'{pad}  <inertial pos="{fmt(link.get("centerOfMass", [0, 0, 0]))}" mass="{mass!r}" fullinertia="{fmt(full)}"/>')
        if "shape" in link:
            out.append(pad + "  " + _mjcf_geom(link["shape"], link_friction(link), f'{a["name"]}/{link["name"]}'))
        for c in children[i]:
            out.extend(body(c, depth + 1))
        out.append(f"{pad}</body>")
        return out

    return "\n".join(body(0, 0))


def to_mjcf(scene_desc, actuators="", extra_worldbody="", option_extra=""):
    """The description as an MJCF string. MuJoCo's defaults are kept (Newton solver, pyramidal
    cones, its soft-contact parameters) except the integrator: implicitfast, MuJoCo's
    recommendation, which treats joint damping and actuator velocity gains implicitly."""
    g = scene_desc.get("gravity", [0, 0, -9.81])
    parts = []
    ground = scene_desc.get("ground")
    if ground is not None:
        parts.append(f'    <geom name="ground" type="plane" size="0 0 1" friction="{ground["friction"]!r} 0.005 0.0001"/>')
    for b in scene_desc.get("bodies", []):
        rot = b.get("rotation", [0, 0, 0, 1])
        geom = _mjcf_geom(b["shape"], float(b.get("friction", 0.5)), b["name"])
        if b.get("static", False):
            parts.append(f'    <body name="{b["name"]}" pos="{fmt(b["position"])}" quat="{fmt(wxyz(rot))}">{geom}</body>')
        else:
            massed = geom[:-2] + f' mass="{float(b["mass"])!r}"/>'
            parts.append(f'    <body name="{b["name"]}" pos="{fmt(b["position"])}" quat="{fmt(wxyz(rot))}"><freejoint/>'
                         f'{massed}</body>')
    excludes = []
    for a in scene_desc.get("articulations", []):
        parts.append(_mjcf_articulation(a))
        # MuJoCo filters parent-child contacts except when the parent is welded to the world
        # (it counts as the world then): exclude every parent-child pair explicitly
        for link in a["links"]:
            if "parentLink" in link:
                parent = a["links"][link["parentLink"]]["name"]
                excludes.append(f'    <exclude body1="{a["name"]}/{parent}" body2="{a["name"]}/{link["name"]}"/>')
    contact = f"  <contact>\n{chr(10).join(excludes)}\n  </contact>" if excludes else ""
    return f"""<mujoco model="{scene_desc.get("name", "bench")}">
  <compiler angle="radian" inertiafromgeom="auto" boundmass="0" boundinertia="0"/>
  <option timestep="{scene_desc["dt"]!r}" gravity="{fmt(g)}" integrator="implicitfast" {option_extra}/>
  <worldbody>
{chr(10).join(parts)}
{extra_worldbody}
  </worldbody>
{contact}
{actuators}
</mujoco>"""


# ---------------------------------------------------------------- PyBullet (URDF + API)


def _urdf_geometry(shape):
    kind, s = shape_kind(shape)
    if kind == "sphere":
        return f'<sphere radius="{s["radius"]!r}"/>'
    if kind == "box":
        return f'<box size="{fmt(2 * np.asarray(s["halfExtents"], dtype=np.float64))}"/>'
    return f'<capsule radius="{s["radius"]!r}" length="{2 * s["halfLength"]!r}"/>'


def to_urdf(a, friction_scale=math.sqrt):
    """URDF text of one articulation (its root joint must be Hard: the base is fixed by loadURDF).
    Link friction is written as friction_scale(mu) (Bullet multiplies the two surfaces')."""
    links, joints = a["links"], a["joints"]
    if joints[0]["type"] != "Hard":
        raise ValueError("PyBullet articulations are generated with a fixed (Hard) root")
    out = [f'<robot name="{a["name"]}">']
    for link in links:
        mass = float(link.get("mass", 0.0))
        I = inertia_matrix(link)
        out.append(f'  <link name="{link["name"]}">')
        out.append(f'    <inertial><origin xyz="{fmt(link.get("centerOfMass", [0, 0, 0]))}" rpy="0 0 0"/><mass value="{mass!r}"/>'
                   f'<inertia ixx="{float(I[0, 0])!r}" ixy="{float(I[0, 1])!r}" ixz="{float(I[0, 2])!r}" iyy="{float(I[1, 1])!r}" iyz="{float(I[1, 2])!r}" izz="{float(I[2, 2])!r}"/></inertial>')
        if "shape" in link:
            center, rotation = shape_pose(link["shape"])
            out.append(f'    <collision><origin xyz="{fmt(center)}" rpy="{fmt(quat_xyzw_to_rpy(rotation))}"/>'
                       f'<geometry>{_urdf_geometry(link["shape"])}</geometry></collision>')
            out.append(f'    <contact><lateral_friction value="{friction_scale(link_friction(link))!r}"/></contact>')
        out.append("  </link>")
    for i, (link, joint) in enumerate(zip(links, joints)):
        if i == 0:
            continue
        parent = links[link["parentLink"]]["name"]
        X = joint.get("parentLinkFromJoint", {})
        t = {"Hard": "fixed", "Revolute": "revolute", "Prismatic": "prismatic"}[joint["type"]]
        lo, hi = joint_limit(joint, "minLimit"), joint_limit(joint, "maxLimit")
        if t == "revolute" and lo is None and hi is None:
            t = "continuous"
        body = (f'    <parent link="{parent}"/><child link="{link["name"]}"/>'
                f'<origin xyz="{fmt(X.get("translation", [0, 0, 0]))}" rpy="{fmt(quat_xyzw_to_rpy(X.get("rotation", [0, 0, 0, 1])))}"/>')
        if t != "fixed":
            body += f'<axis xyz="{fmt(joint["axis"])}"/>'
            body += f'<dynamics damping="{float(joint.get("friction", {}).get("viscous", 0.0))!r}" friction="0"/>'
            if t in ("revolute", "prismatic"):
                body += (f'<limit lower="{lo if lo is not None else -1e9!r}" upper="{hi if hi is not None else 1e9!r}" '
                         f'effort="1e9" velocity="1e9"/>')
        out.append(f'  <joint name="{joint["name"]}" type="{t}">\n{body}\n  </joint>')
    out.append("</robot>")
    return "\n".join(out)


def pybullet_differences(scene_desc):
    """What PyBullet cannot model of this description, as text (empty when nothing)."""
    notes = []
    for a in scene_desc.get("articulations", []):
        if any(float(j.get("inertia", 0.0)) for j in a["joints"]):
            notes.append(f"{a['name']}: no joint armature in Bullet")
    return "; ".join(notes)


def build_pybullet(scene_desc, p, client):
    """Loads the description into a DIRECT PyBullet client. Returns {name: body id}; articulation
    joints get (index by joint name) in ids['<name>/joints']."""
    p.setGravity(*scene_desc.get("gravity", [0, 0, -9.81]), physicsClientId=client)
    p.setTimeStep(scene_desc["dt"], physicsClientId=client)
    ids = {}
    ground = scene_desc.get("ground")
    if ground is not None:
        plane = p.createCollisionShape(p.GEOM_PLANE, physicsClientId=client)
        gid = p.createMultiBody(0, plane, physicsClientId=client)
        p.changeDynamics(gid, -1, lateralFriction=math.sqrt(ground["friction"]), physicsClientId=client)
        ids["ground"] = gid
    for b in scene_desc.get("bodies", []):
        kind, s = shape_kind(b["shape"])
        if kind == "box":
            cs = p.createCollisionShape(p.GEOM_BOX, halfExtents=s["halfExtents"], physicsClientId=client)
        elif kind == "sphere":
            cs = p.createCollisionShape(p.GEOM_SPHERE, radius=s["radius"], physicsClientId=client)
        else:
            cs = p.createCollisionShape(p.GEOM_CAPSULE, radius=s["radius"], height=2 * s["halfLength"], physicsClientId=client)
        mass = 0.0 if b.get("static", False) else float(b["mass"])
        bid = p.createMultiBody(mass, cs, basePosition=list(b["position"]), baseOrientation=list(b.get("rotation", [0, 0, 0, 1])),
                                physicsClientId=client)
        p.changeDynamics(bid, -1, lateralFriction=math.sqrt(float(b.get("friction", 0.5))), linearDamping=0.0, angularDamping=0.0,
                         physicsClientId=client)
        ids[b["name"]] = bid
    for a in scene_desc.get("articulations", []):
        text = to_urdf(a)
        fd, path = tempfile.mkstemp(suffix=".urdf", text=True)
        with os.fdopen(fd, "w") as f:
            f.write(text)
        root = a.get("world_from_root", {})
        bid = p.loadURDF(path, basePosition=list(root.get("translation", [0, 0, 0])),
                         baseOrientation=list(root.get("rotation", [0, 0, 0, 1])), useFixedBase=True,
                         flags=p.URDF_USE_INERTIA_FROM_FILE | p.URDF_USE_SELF_COLLISION | p.URDF_USE_SELF_COLLISION_EXCLUDE_PARENT,
                         physicsClientId=client)
        os.unlink(path)
        n = p.getNumJoints(bid, physicsClientId=client)
        joint_index = {}
        for j in range(-1, n):
            p.changeDynamics(bid, j, linearDamping=0.0, angularDamping=0.0, physicsClientId=client)
        for j in range(n):
            info = p.getJointInfo(bid, j, physicsClientId=client)
            joint_index[info[1].decode()] = j
            if info[2] != p.JOINT_FIXED:
                # PyBullet's default velocity motor on every joint: off
                p.setJointMotorControl2(bid, j, p.VELOCITY_CONTROL, force=0.0, physicsClientId=client)
        ids[a["name"]] = bid
        ids[a["name"] + "/joints"] = joint_index
        if a.get("default_pose") is not None:
            movable = [j for j in a["joints"][1:] if j["type"] != "Hard"]
            for joint, q in zip(movable, a["default_pose"]):
                p.resetJointState(bid, joint_index[joint["name"]], q, 0.0, physicsClientId=client)
    return ids


def mujoco_set_default_pose(model, data, scene_desc, mujoco):
    for a in scene_desc.get("articulations", []):
        if a.get("default_pose") is None:
            continue
        movable = [j for j in a["joints"][1:] if j["type"] != "Hard"]
        for joint, q in zip(movable, a["default_pose"]):
            data.qpos[model.joint(f'{a["name"]}/{joint["name"]}').qposadr[0]] = q
    mujoco.mj_forward(model, data)
