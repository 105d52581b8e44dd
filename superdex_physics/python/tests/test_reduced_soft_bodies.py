"""Reduced soft bodies (material "reducedModes": r): linear elasticity about the rest shape in the
r lowest vibration modes plus the static correction, checked against an independent linear
finite-element model assembled here with numpy (isotropic linear elasticity, lumped masses).

Reduced models are this engine's addition, outside SuperDex's SoftActorParams: they are made
from prefab files (a soft actor entry with its material's "reducedModes" and "fixedNodes"), as
the bundled duck prefab is. Each test writes its mesh (.mochi.h5) and prefab next to it.

- Static response to gravity: the full linear FEM one, K^-1 M g, whatever r.
- Vibration: the period of a released cantilever is that of the lowest eigenmode of K and M.
- Contact: pressed by a ball, the body's shape is K^-1 (M g + f) with f the contact forces the
  engine reports, no node is inside the ball, and the forces carry the ball's load.
- State capture and restore replays bitwise; bad input is refused with the field named.
"""

import json
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link, node_contact_forces_world, node_positions_world
from superdex.physics.prefab import add_to_scene
from test_soft_bodies import box_tet_mesh

E, NU, RHO = 1.0e6, 0.3, 1000.0
SIZE, CELLS = [0.2, 0.02, 0.02], [10, 2, 2]


def linear_fem(nodes, tets, youngs, nu, density):
    """Stiffness (3N x 3N) of linear isotropic elasticity on linear tetrahedra, and lumped node masses."""
    mu, lam = youngs / (2 * (1 + nu)), youngs * nu / ((1 + nu) * (1 - 2 * nu))
    C = np.zeros((6, 6))
    C[:3, :3] = lam
    C[np.arange(3), np.arange(3)] += 2 * mu
    C[np.arange(3, 6), np.arange(3, 6)] = mu
    K = np.zeros((3 * len(nodes), 3 * len(nodes)))
    mass = np.zeros(len(nodes))
    for tet in tets:
        p = nodes[tet]
        Dm = (p[1:] - p[0]).T
        volume = np.linalg.det(Dm) / 6
        grads = np.vstack([-np.linalg.inv(Dm).sum(0), np.linalg.inv(Dm)])  # shape function gradients (4 x 3)
        B = np.zeros((6, 12))
        for a, (gx, gy, gz) in enumerate(grads):
            B[:, 3 * a:3 * a + 3] = [[gx, 0, 0], [0, gy, 0], [0, 0, gz], [gy, gx, 0], [0, gz, gy], [gz, 0, gx]]
        dofs = (3 * tet[:, None] + np.arange(3)).ravel()
        K[np.ix_(dofs, dofs)] += volume * B.T @ C @ B
        mass[tet] += density * volume / 4
    return K, mass


def static_displacement(K, free_dofs, load):
    u = np.zeros(K.shape[0])
    u[free_dofs] = np.linalg.solve(K[np.ix_(free_dofs, free_dofs)], load[free_dofs])
    return u.reshape(-1, 3)


def ball_slider(scene, translation, radius, ball_mass, push):
    """A ball on a vertical slider welded at `translation` (world), pushed down with `push` (N)."""
    links = [link("base", mass=1.0, moment_of_inertia=[1e-3, 0, 0, 1e-3, 0, 1e-3]),
             link("ball", parent=0, mass=ball_mass, moment_of_inertia=[1e-6, 0, 0, 1e-6, 0, 1e-6],
                  shape=sdp.create_sphere_shape([0, 0, 0], radius))]
    joints = [joint("weld", "hard", at=translation),
              joint("slide", "prismatic", axis=[0, 0, 1])]
    slider = articulation(scene, "slider", links, joints)
    slider.set_external_forces_on_dofs([0], [-push])
    return slider


def material(modes, damping=0.0):
    return {"type": "NeoHookean", "youngsModulus": E, "poissonRatio": NU, "density": RHO, "damping": damping, "reducedModes": modes}


def soft_prefab(folder, name, nodes, tets, material, fixed_nodes=None):
    """Writes `name`.mochi.h5 (the tet mesh) and `name`.mochi_prefab (one soft actor with this
    material and these pinned nodes) into `folder`; returns the prefab's path."""
    import h5py

    with h5py.File(folder / f"{name}.mochi.h5", "w") as f:
        f["mesh/coordinates"] = np.asarray(nodes, dtype=np.float64)
        f["mesh/connectivity"] = np.asarray(tets, dtype=np.int32)
    entry = {"name": name, "shape": f"./{name}.mochi.h5", "material": material}
    if fixed_nodes is not None:
        entry["fixedNodes"] = [int(i) for i in fixed_nodes]
    path = folder / f"{name}.mochi_prefab"
    path.write_text(json.dumps({"actors": {"soft": [entry]}}))
    return path


def reduced_actor(scene, folder, name, nodes, tets, material, fixed_nodes=None):
    """The soft actor of soft_prefab(...), added to the scene, its node positions readable."""
    path = soft_prefab(folder, name, nodes, tets, material, fixed_nodes)
    actor = add_to_scene(path, folder, scene).actors[0]
    actor.register_query_and_compute(sdp.QueryType.NODE_POSITIONS)
    return actor


def cantilever(scene, folder, modes, damping=0.0, size=SIZE, cells=CELLS):
    nodes, tets = box_tet_mesh(size, cells)
    clamped = np.flatnonzero(nodes[:, 0] < 1e-9)
    beam = reduced_actor(scene, folder, "beam", nodes, tets, material(modes, damping), clamped)
    free = np.repeat(nodes[:, 0] > 1e-9, 3)
    return beam, nodes, tets, free


@pytest.mark.parametrize("modes", [1, 8])
def test_static_sag_is_the_full_linear_fem_one(scene, tmp_path, modes):
    beam, nodes, tets, free = cantilever(scene, tmp_path, modes)
    scene.step(1e3)  # implicit Euler with a huge step: the static equilibrium
    K, mass = linear_fem(nodes, tets, E, NU, RHO)
    u_ref = static_displacement(K, free, (mass[:, None] * np.array([0, 0, -9.81])).ravel())
    u = node_positions_world(beam) - nodes
    assert np.abs(u_ref).max() > 1e-4  # a visible sag (m)
    np.testing.assert_allclose(u, u_ref, atol=2e-3 * np.abs(u_ref).max())


def test_released_cantilever_swings_at_the_lowest_eigenfrequency(scene, tmp_path):
    # a flat beam: its lowest mode, bending in z, makes nearly all of the sag (the next one that
    # the sag holds, 6 times faster, makes 1.6 % of it), so the tip crosses zero at its period
    size = [0.2, 0.04, 0.01]
    beam, nodes, tets, free = cantilever(scene, tmp_path, 6, size=size, cells=[10, 4, 1])
    K, mass = linear_fem(nodes, tets, E, NU, RHO)
    # the lowest eigenfrequency of K u = w^2 M u on the free DOFs
    s = 1 / np.sqrt(np.repeat(mass, 3)[free])
    omega = np.sqrt(np.linalg.eigvalsh(s[:, None] * K[np.ix_(free, free)] * s[None, :])[0])
    period = 2 * np.pi / omega
    # sag under gravity, then release with gravity off: the beam swings about its rest shape
    scene.step(1e3)
    scene.set_gravity([0, 0, 0])
    tip = np.flatnonzero(nodes[:, 0] > size[0] - 1e-9)
    dt = period / 400
    z = []
    for _ in range(1200):  # three periods
        scene.step(dt)
        z.append(float(node_positions_world(beam)[tip, 2].mean() - nodes[tip, 2].mean()))
    z = np.array(z)
    # upward zero crossings, interpolated
    up = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))
    times = (up + z[up] / (z[up] - z[up + 1])) * dt
    assert len(times) >= 2
    assert np.mean(np.diff(times)) == pytest.approx(period, rel=0.01)
    # implicit Euler dissipates, slowly at 400 steps per period: the swing keeps most of its size
    assert 0.5 * abs(z[0]) < np.abs(z[-400:]).max() < abs(z[0]) * 1.001


def test_pressed_block_takes_the_linear_fem_shape_of_its_contact_forces(scene, tmp_path):
    nodes, tets = box_tet_mesh([0.06, 0.06, 0.03], [4, 4, 2])
    nodes = nodes - [0.03, 0.03, 0]
    bottom = np.flatnonzero(nodes[:, 2] < 1e-9)
    block = reduced_actor(scene, tmp_path, "block", nodes, tets,
                          {"youngsModulus": 5e4, "poissonRatio": 0.4, "density": 1000, "damping": 0.01, "reducedModes": 12},
                          bottom)
    block.register_query(sdp.QueryType.NODE_CONTACT_FORCES)
    radius, push, ball_mass = 0.012, 0.5, 0.05
    slider = ball_slider(scene, [0.004, -0.003, 0.03 + radius + 0.002], radius, ball_mass, push)
    for _ in range(400):
        scene.step(0.004)
    x = node_positions_world(block)
    f = node_contact_forces_world(block, len(nodes))
    # the contact forces carry the push and the ball's weight
    assert f[:, 2].sum() == pytest.approx(-(push + 9.81 * ball_mass), rel=0.02)
    # the shape is the linear FEM response to gravity and those forces
    K, mass = linear_fem(nodes, tets, 5e4, 0.4, 1000)
    load = (f + mass[:, None] * np.array([0, 0, -9.81])).ravel()
    u_ref = static_displacement(K, np.repeat(nodes[:, 2] > 1e-9, 3), load)
    assert np.abs(u_ref).max() > 2e-4  # a visible dent (m)
    np.testing.assert_allclose(x - nodes, u_ref, atol=5e-3 * np.abs(u_ref).max())
    # and no node is inside the ball
    centre = np.asarray(slider.get_articulated_link_transforms()[1].translation, dtype=np.float64)
    assert np.linalg.norm(x - centre, axis=1).min() > radius - 1e-4


def test_capture_and_restore_replay_bitwise(scene, tmp_path):
    beam, *_ = cantilever(scene, tmp_path, 4, damping=0.01)
    for _ in range(20):
        scene.step(0.01)
    state = scene.capture_state()
    for _ in range(30):
        scene.step(0.01)
    after = np.array(beam.get_node_positions_local())
    frame = beam.get_root_transform()
    scene.restore_state(state, release_immediately=True)
    for _ in range(30):
        scene.step(0.01)
    np.testing.assert_array_equal(np.array(beam.get_node_positions_local()), after)
    assert beam.get_root_transform() == frame


def test_bad_reduced_models_are_refused(scene, tmp_path):
    nodes, tets = box_tet_mesh([0.1, 0.02, 0.02], [4, 1, 1])
    clamped = np.flatnonzero(nodes[:, 0] < 1e-9)

    def add(name, material, fixed_nodes=None):
        return reduced_actor(scene, tmp_path, name, nodes, tets, material, fixed_nodes)

    with pytest.raises(sdp.Error, match="reducedModes needs pinned nodes"):
        add("free", material(4))
    free_dofs = 3 * (len(nodes) - len(clamped))
    with pytest.raises(sdp.Error, match=f"reducedModes must be between 1 and {free_dofs - 1}"):
        add("many", material(free_dofs), clamped)
    for bad in (-1, 2.5, "4"):
        with pytest.raises(sdp.Error, match="reducedModes"):
            add("bad", material(bad), clamped)
    beam = add("beam", material(4), clamped)
    with pytest.raises(sdp.Error, match="reduced"):
        beam.add_boundary_condition_nodes_world([int(len(nodes) - 1)], [[0.1, 0.02, 0.02]])
    # nor can SoftActorParams make one: SuperDex's materials have no reduced models
    with pytest.raises(TypeError, match="unexpected keyword argument 'reduced_modes'"):
        sdp.SoftMaterialParams(reduced_modes=4)


DUCKS = Path(__file__).resolve().parents[3] / "assets" / "prefabs" / "duck_lamp"


def pressed_duck(prefab):
    """The duck prefab settled on the ground, then pressed by a ball on a vertical slider with 0.5 N:
    its node positions at the start, settled, and pressed."""
    sdp.initialize(num_worker_threads=0)
    try:
        scene = sdp.create_scene("duck")
        scene.set_gravity([0, 0, -9.81])
        scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
        duck = sdp.prefab.add_to_scene(str(DUCKS / prefab), "/duck", scene).actors[0]
        duck.register_query_and_compute(sdp.QueryType.NODE_POSITIONS)
        start = node_positions_world(duck)
        for _ in range(50):
            scene.step(0.004)
        rest = node_positions_world(duck)
        ball_slider(scene, [-0.30, 0, rest[:, 2].max() + 0.016], 0.015, 0.05, 0.5)
        for _ in range(200):
            scene.step(0.004)
        return start, rest, node_positions_world(duck)
    finally:
        sdp.shutdown()


def test_reduced_duck_sags_and_dents_like_the_full_one():
    """The seed's prefab (reduced, 24 modes) against its full nonlinear twin: the same sag under
    gravity (the static correction makes it the linear one, and the strains are small), and the
    same shape under the pressing ball, to 15 % of the largest displacement."""
    start, rest_full, pressed_full = pressed_duck("duck_lamp_recumbent_full.mochi_prefab")
    _, rest_reduced, pressed_reduced = pressed_duck("duck_lamp_recumbent.mochi_prefab")
    sag = np.linalg.norm(rest_full - start, axis=1).max()
    assert sag > 5e-4  # (m)
    assert np.linalg.norm(rest_full - rest_reduced, axis=1).max() < 0.02 * sag
    moved = np.linalg.norm(pressed_full - rest_full, axis=1).max()
    assert moved > 3e-4  # a dent (m)
    assert np.linalg.norm(pressed_full - pressed_reduced, axis=1).max() < 0.15 * moved
