"""Shared fixtures: an initialized engine per test, and small builders of actor params structs and
of files (a cube OBJ)."""

import numpy as np
import pytest

import superdex.physics as sdp


@pytest.fixture
def engine():
    """Initializes the engine for one test and shuts it down afterwards."""
    sdp.initialize(num_worker_threads=0)
    yield sdp
    if sdp.is_initialized():
        sdp.shutdown()


@pytest.fixture
def scene(engine):
    """A Z-up scene (the engine's default gravity is SuperDex's (0, -9.8, 0))."""
    s = sdp.create_scene("test")
    s.set_gravity([0, 0, -9.81])
    return s


@pytest.fixture
def log_messages():
    """The engine's log messages (channel, message) while the test runs."""
    messages = []
    sdp.set_log_callback(lambda channel, message, file, line: messages.append((channel, message)))
    yield messages
    sdp.set_log_callback(None)


def real_dtype():
    return np.float64 if sdp.uses_double_precision() else np.float32


def transform(translation=(0, 0, 0), rotation=None):
    """A TransformRT from a translation (m) and an optional Quaternion (x, y, z, w)."""
    return sdp.TransformRT(rotation=rotation if rotation is not None else sdp.Quaternion(0, 0, 0, 1),
                           translation=[float(x) for x in translation])


def contact(mu=0.5, **fields):
    """ContactParams with Coulomb friction `mu` and any other fields by their names."""
    return sdp.ContactParams(coulomb_friction_coefficient=mu, **fields)


def link(name, parent=-1, **fields):
    """An ArticulatedLinkParams: `parent` is the parent link's index (-1 for the root); the other
    fields by their names (mass, center_of_mass, moment_of_inertia, shape, contact, ...)."""
    return sdp.ArticulatedLinkParams(name=name, parent_link=parent, **fields)


def joint(name, type, at=None, **fields):
    """An ArticulatedJointParams of `type` (an ArticulatedJointType or its name, any case) whose
    frame is `at` (a translation, m) in its parent link's frame; other fields by their names."""
    if isinstance(type, str):
        type = getattr(sdp.ArticulatedJointType, type.upper())
    if at is not None:
        fields["parent_link_from_joint"] = transform(at)
    return sdp.ArticulatedJointParams(name=name, type=type, **fields)


def articulation(scene, name, links, joints, **fields):
    """An articulated actor from lists of link and joint params (fields: world_from_root,
    joint_velocities, cycles)."""
    return scene.create_articulated_actor(sdp.ArticulatedActorParams(name=name, links=links, joints=joints, **fields))


def two_link_arm(scene, name="arm", **joint_extra):
    """A welded base and two revolute links about Y, each 0.5 m long with 1 kg at its tip;
    joint_extra: fields of both revolute joints (min_limit, max_limit, friction, ...)."""
    links = [
        link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        link("l1", parent=0, mass=1.0, center_of_mass=[0.5, 0, 0], moment_of_inertia=[0.001, 0, 0, 0.001, 0, 0.001]),
        link("l2", parent=1, mass=1.0, center_of_mass=[0.5, 0, 0], moment_of_inertia=[0.001, 0, 0, 0.001, 0, 0.001]),
    ]
    joints = [
        joint("weld", "hard", at=[0, 0, 1]),
        joint("j1", "revolute", axis=[0, 1, 0], **joint_extra),
        joint("j2", "revolute", at=[0.5, 0, 0], axis=[0, 1, 0], **joint_extra),
    ]
    return articulation(scene, name, links, joints)


SOFT_MODELS = {
    "neo_hookean": ("NEO_HOOKEAN", "neo_hookean"),
    "linear": ("LINEAR_ELASTIC", "linear_elastic"),
    "stvk": ("ST_VENANT_KIRCHHOFF", "st_venant_kirchhoff"),
}


def soft_material(model="neo_hookean", youngs_modulus=1e5, poisson_ratio=0.3, density=1000.0, stiffness_damping=0.0,
                  mass_damping=0.0):
    """SoftMaterialParams of one model ("neo_hookean", "linear" or "stvk"): Young's modulus (Pa),
    Poisson's ratio, density (kg/m^3), Rayleigh stiffness-proportional (s) and mass-proportional
    (1/s) damping."""
    type_name, field = SOFT_MODELS[model]
    material = sdp.SoftMaterialParams(type=getattr(sdp.SoftMaterialType, type_name), density=density,
                                      stiffness_damping_coefficient=stiffness_damping, mass_damping_coefficient=mass_damping)
    elastic = getattr(material, field)  # by reference: setting it sets the material's
    elastic.youngs_modulus = youngs_modulus
    elastic.poisson_ratio = poisson_ratio
    return material


def soft_actor(scene, name, shape, material=None, world_from_local=None, fixed_nodes=None, recentering=True, **fields):
    """A soft actor (SoftActorParams; fields by their names) whose NODE_POSITIONS query is
    registered (node_positions_world reads it); `fixed_nodes` are held where they start by
    permanent boundary conditions. recentering=False keeps the actor frame where it was created
    (SuperDex's default moves it with the body), so that with an identity frame the local node
    positions are the world ones exactly."""
    params = sdp.SoftActorParams(name=name, shape=shape, material=material if material is not None else soft_material(),
                                 **fields)
    if world_from_local is not None:
        params.world_from_local = world_from_local
    actor = scene.create_soft_actor(params)
    if not recentering:
        actor.set_recentering_params(sdp.RecenteringParams(use_recentering=False))
    actor.register_query_and_compute(sdp.QueryType.NODE_POSITIONS)
    if fixed_nodes is not None and len(fixed_nodes) > 0:
        fixed = np.asarray(fixed_nodes, dtype=np.int64)
        actor.add_boundary_condition_nodes_world_permanent(fixed, node_positions_world(actor)[fixed])
    return actor


def node_positions_world(soft):
    """(n, 3) world positions of a soft actor's nodes (float64): its local node positions (its
    NODE_POSITIONS query) placed by its root transform."""
    from contact_helpers import rotation_matrix

    local = np.asarray(soft.get_node_positions_local(), dtype=np.float64).reshape(-1, 3)
    X = soft.get_root_transform()
    return local @ rotation_matrix(np.asarray(X.rotation, dtype=np.float64)).T + np.asarray(X.translation, dtype=np.float64)


def node_contact_forces_world(soft, num_nodes):
    """(n, 3) contact forces on a soft actor's nodes (N, world; its NODE_CONTACT_FORCES query),
    zero for nodes without contact."""
    forces = np.zeros((num_nodes, 3))
    for f in soft.get_node_contact_forces_world():
        forces[f.index] += np.asarray(f.force, dtype=np.float64)
    return forces


def cube_obj(path, h=0.1):
    """Writes a closed cube of half extent h (m), centred at the origin, as an OBJ file."""
    v = [(x, y, z) for z in (-h, h) for y in (-h, h) for x in (-h, h)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines = [f"v {a} {b} {c}" for a, b, c in v]
    for a, b, c, d in quads:
        lines += [f"f {a + 1} {b + 1} {c + 1}", f"f {a + 1} {c + 1} {d + 1}"]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path


def unit_sphere_triangles(asset_path):
    """The vertices (n, 3) and triangles (m, 3) of a unit-sphere triangle mesh asset, checked to be a
    closed, consistently outward surface on the sphere whose volume is just under the sphere's."""
    import math

    from superdex.physics.paths import resolve_asset

    mesh = sdp.model.load_from_file(str(resolve_asset(asset_path))).mesh
    assert mesh.nodes_per_element == 3
    x = np.array(mesh.coordinates, dtype=float).reshape(-1, 3)
    t = np.array(mesh.connectivity).reshape(-1, 3)
    np.testing.assert_allclose(np.linalg.norm(x, axis=1), 1.0, atol=1e-6)
    # closed: every edge is shared by exactly two triangles, in opposite directions
    edges = {}
    for a, b, c in t:
        for e in ((a, b), (b, c), (c, a)):
            edges[e] = edges.get(e, 0) + 1
    assert all(n == 1 and edges.get((e[1], e[0])) == 1 for e, n in edges.items())
    # outward, and within 1 % under the sphere's volume
    volume = np.einsum("ij,ij->i", x[t[:, 0]], np.cross(x[t[:, 1]], x[t[:, 2]])).sum() / 6
    assert 0.99 * 4 / 3 * math.pi < volume < 4 / 3 * math.pi
    return x, t
