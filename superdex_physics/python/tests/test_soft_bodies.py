"""Soft bodies (tetrahedral FEM), each solved implicitly by Newton's method.

- Cantilever: a 0.2 x 0.02 x 0.02 m beam (E = 1 MPa, nu = 0.3) clamped at one end, a small
  load F at the tip: the static tip deflection converges to Euler-Bernoulli, F L^3 / (3 E I),
  from below under refinement, and is within 5 % of it on the refined mesh. (A step of very large dt makes backward Euler the static
  equilibrium.)
- A soft cube in free fall moves like a rigid body (centre of mass 1/2 g t^2, first order in dt)
  and does not deform (uniform gravity).
- A damped beam clamped at one end under gravity, at dt = 25 ms for 10 s: finite, bounded, and
  its total energy (kinetic + gravity + elastic) never rises.
- Bad input: inverted and degenerate tetrahedra, indices out of range, unsupported materials.

Soft actors are made from SoftActorParams (conftest.soft_actor); nodes held in place are
permanent boundary conditions, and node positions are read as local positions placed by the
actor's root transform (conftest.node_positions_world).
"""

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import node_contact_forces_world, node_positions_world, soft_actor, soft_material


def box_tet_mesh(size, cells):
    """A box [0, size] split into cells (hexahedra), each into 6 positively oriented tetrahedra."""
    nx, ny, nz = cells
    xs = [np.linspace(0, size[k], cells[k] + 1) for k in range(3)]
    index = lambda i, j, k: (k * (ny + 1) + j) * (nx + 1) + i  # noqa: E731
    nodes = np.array([[xs[0][i], xs[1][j], xs[2][k]] for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)])
    tets = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                c = [index(i + a, j + b, k + d) for d in (0, 1) for b in (0, 1) for a in (0, 1)]
                # Kuhn subdivision along the main diagonal c0 -> c7
                for path in ((1, 3), (1, 5), (2, 3), (2, 6), (4, 5), (4, 6)):
                    tet = [c[0], c[path[0]], c[path[1]], c[7]]
                    p = nodes[tet]
                    if np.linalg.det(np.array([p[1] - p[0], p[2] - p[0], p[3] - p[0]])) < 0:
                        tet[1], tet[2] = tet[2], tet[1]
                    tets.append(tet)
    return nodes, np.array(tets, dtype=np.int64)


L, A = 0.2, 0.02
E, NU = 1.0e6, 0.3


def cantilever_deflection(scene, cells):
    nodes, tets = box_tet_mesh([L, A, A], cells)
    fixed = np.flatnonzero(nodes[:, 0] < 1e-9)
    tip = np.flatnonzero(nodes[:, 0] > L - 1e-9)
    # the actor frame stays the world frame: the clamped nodes' positions read exactly
    beam = soft_actor(scene, "beam", sdp.create_tet_mesh_shape(nodes, tets),
                      material=soft_material("neo_hookean", youngs_modulus=E, poisson_ratio=NU, density=1000), fixed_nodes=fixed,
                      recentering=False)
    F = 1e-3
    beam.set_external_forces_on_dofs([3 * int(i) + 2 for i in tip], [-F / len(tip)] * len(tip))
    scene.step(1e3)  # backward Euler with a huge step: the static equilibrium
    x = node_positions_world(beam)
    np.testing.assert_allclose(x[fixed], nodes[fixed], atol=1e-12)  # the clamped end did not move
    scene.destroy_actor(beam)
    return -float(np.mean(x[tip, 2] - nodes[tip, 2])) / (F * L**3 / (3 * E * A**4 / 12))


def test_cantilever_converges_to_euler_bernoulli(scene):
    """Linear tetrahedra lock in bending: the tip deflection approaches Euler-Bernoulli from
    below as the mesh is refined, the error falling faster than the element size, and the refined
    mesh (12 elements through the thickness, 1.2 mm cubes, 62k tetrahedra, 55k DOFs) is within 5 %.
    (Shear adds about 0.8 % to the beam-theory deflection at this slenderness.)"""
    scene.set_gravity([0, 0, 0])
    coarse = cantilever_deflection(scene, [20, 2, 2])
    fine = cantilever_deflection(scene, [40, 4, 4])
    assert 0.3 < coarse < fine < 1.0
    assert (1 - fine) < 0.5 * (1 - coarse)
    refined = cantilever_deflection(scene, [120, 12, 12])
    assert refined == pytest.approx(1.0, abs=0.05)


def test_free_falling_soft_cube_moves_rigidly(scene):
    nodes, tets = box_tet_mesh([0.1, 0.1, 0.1], [3, 3, 3])
    cube = soft_actor(scene, "cube", sdp.create_tet_mesh_shape(nodes, tets),
                      material=soft_material(youngs_modulus=1e5, poisson_ratio=0.45, density=500),
                      world_from_local=sdp.TransformRT(translation=[0, 0, 1]))
    cube.register_query(sdp.QueryType.ELASTIC_ENERGY)
    assert cube.get_type() == sdp.ActorType.SOFT
    assert cube.get_num_dofs() == 3 * len(nodes)
    assert cube.get_mass() == pytest.approx(500 * 0.1**3, rel=1e-6)
    dt, T = 0.01, 0.5
    for _ in range(int(T / dt)):
        scene.step(dt)
    x = node_positions_world(cube)
    drop = 1.0 + 0.05 - float(np.mean(x[:, 2]))
    # backward Euler: x_N = x0 - g dt^2 N (N + 1) / 2
    n = int(T / dt)
    assert drop == pytest.approx(9.81 * dt * dt * n * (n + 1) / 2, rel=1e-4)
    # no deformation: the node offsets from the centroid are unchanged
    np.testing.assert_allclose(x - x.mean(axis=0), nodes - nodes.mean(axis=0), atol=1e-5)
    # negligible against the kinetic energy (float32 positions leave rounding-level strain)
    kinetic = 0.5 * cube.get_mass() * (9.81 * T) ** 2
    assert cube.get_elastic_energy() <= (1e-12 if sdp.uses_double_precision() else 1e-6) * kinetic


def test_damped_beam_is_stable_at_25_ms(scene):
    nodes, tets = box_tet_mesh([L, A, A], [10, 2, 2])
    fixed = np.flatnonzero(nodes[:, 0] < 1e-9)
    rho = 1100.0
    beam = soft_actor(scene, "beam", sdp.create_tet_mesh_shape(nodes, tets),
                      material=soft_material(youngs_modulus=1e5, poisson_ratio=0.45, density=rho, stiffness_damping=0.01),
                      fixed_nodes=fixed)
    beam.register_query(sdp.QueryType.ELASTIC_ENERGY)
    mass_per_node = None
    energies = []
    for _ in range(400):
        x_prev = node_positions_world(beam)
        scene.step(0.025)
        x = node_positions_world(beam)
        assert np.all(np.isfinite(x))
        assert np.abs(x - nodes).max() < L, "no node leaves the domain"
        v = (x - x_prev) / 0.025
        if mass_per_node is None:
            # lumped masses from the mesh: rho V / 4 per tetrahedron corner
            mass_per_node = np.zeros(len(nodes))
            for t in tets:
                p = nodes[t]
                vol = np.linalg.det(np.array([p[1] - p[0], p[2] - p[0], p[3] - p[0]])) / 6
                mass_per_node[t] += rho * vol / 4
        energies.append(0.5 * np.sum(mass_per_node[:, None] * v * v) + 9.81 * np.sum(mass_per_node * x[:, 2])
                        + beam.get_elastic_energy())
    e = np.array(energies)
    # float32 positions resolve these energies to about 1e-5 of their size
    tol = 1e-9 + 1e-6 * abs(e[0]) if sdp.uses_double_precision() else 1e-4 * np.abs(e).max()
    assert np.diff(e).max() <= tol


@pytest.mark.parametrize("nodes, tets, message", [
    ([[0, 0, 0], [0, 1, 0], [1, 0, 0], [0, 0, 1]], [[0, 1, 2, 3]], "tetrahedron 0 is inverted"),
    ([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 0, 1]], [[0, 1, 2, 3]], "tetrahedron 0 is degenerate"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2, 7]], r"connectivity\[3\] = 7 is out of range \[0, 4\)"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], r"connectivity: expected 4 values per row, flat or of shape \(n, 4\), got shape \(1, 3\)"),
])
def test_bad_tet_meshes(engine, nodes, tets, message):
    with pytest.raises(sdp.Error, match=message):
        sdp.create_tet_mesh_shape(np.array(nodes, dtype=float), np.array(tets))


def test_bad_soft_materials_and_pins(scene):
    nodes, tets = box_tet_mesh([0.1, 0.1, 0.1], [1, 1, 1])
    shape = sdp.create_tet_mesh_shape(nodes, tets)
    # a material type is a SoftMaterialType; those this engine does not simulate are refused by name
    with pytest.raises(TypeError, match=r"SoftMaterialParams\(\): type: cannot be set from a value of type str"):
        sdp.SoftMaterialParams(type="Jelly")
    with pytest.raises(sdp.Error, match=r"params\.material\.type: Arap is not available yet"):
        scene.create_soft_actor(name="s", shape=shape, material=sdp.SoftMaterialParams(type=sdp.SoftMaterialType.ARAP))
    with pytest.raises(sdp.Error, match=r"params\.material\.neo_hookean\.poisson_ratio: must be in \(-1, 0\.5\), got 0\.5"):
        scene.create_soft_actor(name="s", shape=shape, material=soft_material(poisson_ratio=0.5))
    soft = scene.create_soft_actor(name="s", shape=shape)
    with pytest.raises(sdp.Error, match=r"add_boundary_condition_nodes_world_permanent: node_indices\[0\] = 99 is out of range"):
        soft.add_boundary_condition_nodes_world_permanent([99], [[0, 0, 0]])
    with pytest.raises(sdp.Error, match=r"params\.shape: must be a tetrahedral mesh"):
        scene.create_soft_actor(name="s", shape=sdp.create_sphere_shape([0, 0, 0], 1.0))


@pytest.mark.parametrize("nu", [0.45, 0.49])
def test_soft_cube_dropped_on_the_plane_rests_on_its_weight(scene, nu):
    """A soft cube (Neo-Hookean, nu = 0.45, and nearly incompressible 0.49) dropped on the ground
    comes to rest: the total contact force on it equals its weight within 1 %, the node forces add
    up to it, and its volume changes by less than 2 %."""
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    h = 0.1
    nodes, tets = box_tet_mesh([h, h, h], [4, 4, 4])
    cube = soft_actor(scene, "cube", sdp.create_tet_mesh_shape(nodes, tets),
                      material=soft_material(youngs_modulus=1e5, poisson_ratio=nu, density=500, stiffness_damping=0.01),
                      world_from_local=sdp.TransformRT(translation=[0, 0, 0.02]))
    cube.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    cube.register_query(sdp.QueryType.NODE_CONTACT_FORCES)
    for _ in range(150):
        scene.step(0.01)
    weight = cube.get_mass() * 9.81
    f = cube.get_contact_force_world()
    assert f[2] == pytest.approx(weight, rel=0.01)
    assert abs(f[0]) < 0.01 * weight and abs(f[1]) < 0.01 * weight
    np.testing.assert_allclose(node_contact_forces_world(cube, len(nodes)).sum(axis=0), f, rtol=1e-5, atol=1e-6)
    x = node_positions_world(cube)
    assert x[:, 2].min() > -1e-3, "it rests on the ground, not in it"

    def volume(p):
        return sum(np.linalg.det(np.array([p[t[1]] - p[t[0]], p[t[2]] - p[t[0]], p[t[3]] - p[t[0]]])) / 6 for t in tets)

    assert volume(x) == pytest.approx(volume(nodes), rel=0.02)


@pytest.mark.parametrize("normal_length", [1.0, 2.5])
def test_soft_cube_sticks_on_a_tilted_offset_plane(scene, normal_length):
    """A soft cube placed on a plane that is tilted by 20 degrees and moved (its shape offset 5 cm
    along its own normal, the actor turned and lifted) sticks there (friction 1 > tan 20 deg): it
    rests on the plane's surface, neither in it nor floating above, and the contact force
    carries its weight. The half-space is found in the world from the actor's pose and the
    shape's normal and offset; an error in either puts the surface elsewhere. The shape is
    {x : normal . x <= distance} whatever the normal's length: a normal 2.5 times longer with a
    distance 2.5 times larger is the same plane."""
    angle = np.radians(20.0)
    R = np.array([[1, 0, 0], [0, np.cos(angle), -np.sin(angle)], [0, np.sin(angle), np.cos(angle)]])
    t = np.array([0.1, -0.2, 0.3])
    X_plane = sdp.TransformRT(rotation=sdp.Quaternion.from_axis_angle([1, 0, 0], angle), translation=t)
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, normal_length], 0.05 * normal_length),
                             is_static=True, world_from_local=X_plane,
                             contact=sdp.ContactParams(coulomb_friction_coefficient=1.0))
    n_W = R[:, 2]
    h = 0.1
    nodes, tets = box_tet_mesh([h, h, h], [3, 3, 3])
    # the cube's bottom face 2 mm above the plane, parallel to it
    origin = t + R @ np.array([-h / 2, -h / 2, 0.05 + 0.002])
    # the cube's own friction is 1 too: the pair's is their geometric mean, 1
    cube = soft_actor(scene, "cube", sdp.create_tet_mesh_shape(nodes, tets),
                      material=soft_material(youngs_modulus=1e5, poisson_ratio=0.3, density=500, stiffness_damping=0.01),
                      world_from_local=sdp.TransformRT(rotation=sdp.Quaternion.from_axis_angle([1, 0, 0], angle),
                                                       translation=origin),
                      contact=sdp.ContactParams(coulomb_friction_coefficient=1.0))
    cube.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    for _ in range(150):
        scene.step(0.01)
    # signed distance of each node to the plane {n_W . (p - t) = 0.05}
    distance = (node_positions_world(cube) - t) @ n_W - 0.05
    assert distance.min() > -1e-3, "it rests on the plane, not in it"
    assert distance.min() < 1e-3, "it rests on the plane, not above it"
    weight = cube.get_mass() * 9.81
    np.testing.assert_allclose(cube.get_contact_force_world(), [0, 0, weight], rtol=0, atol=0.01 * weight)
    centre = node_positions_world(cube).mean(axis=0)
    start = origin + R @ np.full(3, h / 2)
    assert np.linalg.norm(centre - start) < 3e-3, "it sticks where it was put"


def test_per_element_materials_from_mochi_h5(scene, tmp_path):
    """A bar of two materials in series, their Young's moduli given per element in the .mochi.h5
    `material/` group (Linear, nu = 0), clamped at x = 0 and pulled at x = L by a uniform traction:
    each half strains uniformly (the linear elements pass this patch test exactly), so the end
    moves by F (L/2) / (E1 A) + F (L/2) / (E2 A). The file's per-element values take precedence
    over the SoftActorParams material (SuperDex's rule); set_soft_material_params then replaces
    them with uniform ones."""
    import h5py

    scene.set_gravity([0, 0, 0])
    length, side, E1, E2, F = 0.2, 0.02, 1e5, 4e5, 0.5
    nodes, tets = box_tet_mesh([length, side, side], [8, 2, 2])
    centroid_x = nodes[tets].mean(axis=1)[:, 0]
    path = tmp_path / "bar.mochi.h5"
    with h5py.File(path, "w") as f:
        f["mesh/coordinates"] = nodes
        f["mesh/connectivity"] = tets.astype(np.int32)
        f.create_group("material").attrs["type"] = "Linear"
        f["material/youngs_modulus"] = np.where(centroid_x < length / 2, E1, E2)
        f["material/poisson_ratio"] = np.zeros(len(tets))
    shape = sdp.load_shape_from_file(str(path))
    clamped = np.flatnonzero(nodes[:, 0] < 1e-9)
    end = nodes[:, 0] > length - 1e-9
    # consistent nodal loads of a uniform traction on the end face: a third of each triangle's area
    # to each of its corners (the face is split along diagonals, so corner shares differ)
    face_tris = [t for tet in tets for t in ((tet[1], tet[2], tet[3]), (tet[0], tet[3], tet[2]), (tet[0], tet[1], tet[3]), (tet[0], tet[2], tet[1]))
                 if all(end[list(t)])]
    load = np.zeros(len(nodes))
    for t in face_tris:
        a, b, c = nodes[list(t)]
        load[list(t)] += F * 0.5 * np.linalg.norm(np.cross(b - a, c - a)) / side**2 / 3

    def extension(material, replaced_by=None):
        bar = soft_actor(scene, "bar", shape, material=material, fixed_nodes=clamped)
        if replaced_by is not None:
            bar.set_soft_material_params(replaced_by)
        loaded = np.flatnonzero(load)
        bar.set_external_forces_on_dofs([3 * int(i) for i in loaded], load[loaded])
        scene.step(1e3)  # the static equilibrium
        x = node_positions_world(bar)
        scene.destroy_actor(bar)
        return float(np.mean(x[end, 0] - nodes[end, 0]))

    area = side**2
    expected = F * (length / 2) / (E1 * area) + F * (length / 2) / (E2 * area)
    tol = 1e-6 if sdp.uses_double_precision() else 2e-3
    # the material's own modulus (1 MPa) and Poisson's ratio give way to the file's
    linear = soft_material("linear", youngs_modulus=1e6, poisson_ratio=0.3, density=1000)
    assert extension(linear) == pytest.approx(expected, rel=tol)
    uniform = F * length / (E2 * area)
    uniform_material = soft_material("linear", youngs_modulus=E2, poisson_ratio=0.0, density=1000)
    assert extension(linear, replaced_by=uniform_material) == pytest.approx(uniform, rel=tol)


def test_boundary_nodes_pin_move_and_release(scene):
    """Nodes pinned at run time move where they are told within the next step and hold there; a
    linear-elastic bar (nu = 0) whose end face is moved by d along its axis carries the force
    E A d / L; released nodes (clear_boundary_conditions: the permanent ones stay) fall freely
    again. Bad indices are refused naming the argument."""
    scene.set_gravity([0, 0, 0])
    length, side, E = 0.2, 0.02, 1e5
    nodes, tets = box_tet_mesh([length, side, side], [8, 2, 2])
    bar = soft_actor(scene, "bar", sdp.create_tet_mesh_shape(nodes, tets),
                     material=soft_material("linear", youngs_modulus=E, poisson_ratio=0.0, density=1000),
                     fixed_nodes=np.flatnonzero(nodes[:, 0] < 1e-9))
    end = np.flatnonzero(nodes[:, 0] > length - 1e-9)
    fixed = np.flatnonzero(nodes[:, 0] < 1e-9)

    def held_nodes():
        dofs = np.asarray(bar.get_boundary_condition_dof_indices())
        return np.unique(dofs // 3)

    np.testing.assert_array_equal(held_nodes(), fixed)
    d = 0.002
    bar.add_boundary_condition_nodes_world(end, nodes[end] + [d, 0, 0])
    np.testing.assert_array_equal(held_nodes(), np.union1d(fixed, end))
    scene.step(1e3)  # static equilibrium with the end face moved
    x = node_positions_world(bar)
    np.testing.assert_allclose(x[end], nodes[end] + [d, 0, 0], atol=1e-6)
    # uniform strain d / L everywhere: the middle cross-section moved by d / 2
    middle = np.abs(nodes[:, 0] - length / 2) < 1e-9
    np.testing.assert_allclose(x[middle, 0] - nodes[middle, 0], d / 2, rtol=1e-3)
    # released, under gravity, the end face falls
    scene.set_gravity([0, 0, -9.81])
    bar.clear_boundary_conditions()
    np.testing.assert_array_equal(held_nodes(), fixed)
    for _ in range(5):
        scene.step(0.01)
    assert (node_positions_world(bar)[end, 2] < nodes[end, 2] - 1e-4).all()
    with pytest.raises(sdp.Error, match=r"add_boundary_condition_nodes_world: node_indices\[0\] = 999 is out of range"):
        bar.add_boundary_condition_nodes_world([999], [[0, 0, 0]])
    with pytest.raises(sdp.Error, match="add_boundary_condition_nodes_world: node_positions_world must hold 3 values per node"):
        bar.add_boundary_condition_nodes_world([0, 1], [[0, 0, 0]])
