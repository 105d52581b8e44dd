"""Soft actor materials: the whole-actor params and per-element ones (experimental), checked
against what they must do to the elastic energy and the node masses."""

import numpy as np
import pytest

import superdex.physics as sdp
from superdex.physics import experimental

# two tetrahedra sharing the face (1, 2, 3): volumes 1/6 and 1/3 m^3
NODES = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1]
TETS = [0, 1, 2, 3, 1, 4, 2, 3]
VOLUMES = [1 / 6, 1 / 3]


def two_tets(scene, **material):
    shape = sdp.create_tet_mesh_shape(NODES, TETS)
    params = sdp.SoftMaterialParams(**material)
    a = scene.create_soft_actor(name="two", shape=shape, material=params, has_gravity=False)
    a.register_query_and_compute(sdp.QueryType.ELASTIC_ENERGY)
    return a


def deform(actor):
    """A fixed deformation of both tetrahedra (m, actor frame)."""
    d = np.zeros(15)
    d[3 * 4:3 * 4 + 3] = [0.1, -0.05, 0.2]
    d[3 * 1] = 0.05
    actor.set_displacements(d)


def neo_hookean(E, nu=0.3, density=1000.0):
    return sdp.SoftMaterialParams(type=sdp.SoftMaterialType.NEO_HOOKEAN, density=density,
                                  neo_hookean=sdp.NeoHookeanMaterialParams(youngs_modulus=E, poisson_ratio=nu))


def test_per_element_moduli_scale_each_elements_energy(scene):
    base = two_tets(scene, neo_hookean=sdp.NeoHookeanMaterialParams(youngs_modulus=1e5, poisson_ratio=0.3))
    deform(base)
    e_base = base.get_elastic_energy()
    assert e_base > 0

    # for a fixed Poisson ratio the energy density is proportional to E: doubling one element's E
    # adds that element's energy once more
    stiffer = []
    for element in (0, 1):
        a = two_tets(scene, neo_hookean=sdp.NeoHookeanMaterialParams(youngs_modulus=1e5, poisson_ratio=0.3))
        experimental.set_soft_material_params_field(actor=a, params=neo_hookean(2e5), element_index=element)
        deform(a)
        stiffer.append(a.get_elastic_energy() - e_base)
    assert all(x > 0 for x in stiffer)
    assert stiffer[0] + stiffer[1] == pytest.approx(e_base, rel=1e-4)


def test_per_element_values_round_trip_and_reset(scene):
    a = two_tets(scene)
    assert experimental.get_soft_material_params_field(a, 1) == a.get_soft_material_params()
    p = sdp.SoftMaterialParams(type=sdp.SoftMaterialType.ST_VENANT_KIRCHHOFF, density=500.0,
                               st_venant_kirchhoff=sdp.StVenantKirchhoffMaterialParams(youngs_modulus=3e5, poisson_ratio=0.25))
    experimental.set_soft_material_params_field(actor=a, params=p, element_index=1)
    assert experimental.get_soft_material_params_field(actor=a, element_index=1) == p
    assert experimental.get_soft_material_params_field(actor=a, element_index=0) == a.get_soft_material_params()
    # setting the whole actor's material resets every element
    whole = neo_hookean(4e5)
    a.set_soft_material_params(whole)
    assert experimental.get_soft_material_params_field(a, 1) == whole


def test_per_element_density_sets_the_node_masses(scene):
    a = two_tets(scene, density=1000.0)
    assert a.get_mass() == pytest.approx(1000 * sum(VOLUMES), rel=1e-5)
    experimental.set_soft_material_params_field(a, neo_hookean(1e5, density=3000.0), 1)
    assert a.get_mass() == pytest.approx(1000 * VOLUMES[0] + 3000 * VOLUMES[1], rel=1e-5)
    # the centre of mass moves towards the denser tetrahedron's nodes: lumped quarter masses
    m = np.zeros(5)
    for tet, rho, volume in ((TETS[:4], 1000.0, VOLUMES[0]), (TETS[4:], 3000.0, VOLUMES[1])):
        for n in tet:
            m[n] += rho * volume / 4
    x = np.reshape(NODES, (5, 3))
    expected_com = (m[:, None] * x).sum(0) / m.sum()
    assert np.allclose(np.asarray(a.get_rigid_center_of_mass_local()), expected_com, atol=1e-5)


def test_bad_element_or_material_is_refused(scene):
    a = two_tets(scene)
    with pytest.raises(sdp.Error, match="element_index 2 is out of range"):
        experimental.set_soft_material_params_field(a, neo_hookean(1e5), 2)
    with pytest.raises(sdp.Error, match="element_index -1"):
        experimental.get_soft_material_params_field(a, -1)
    with pytest.raises(sdp.Error, match="neo_hookean.poisson_ratio"):
        experimental.set_soft_material_params_field(a, neo_hookean(1e5, nu=0.5), 0)
    rigid = scene.create_rigid_actor(shape=sdp.create_sphere_shape([0, 0, 0], 0.1))
    with pytest.raises(sdp.Error, match="not a soft actor"):
        experimental.get_soft_material_params_field(rigid, 0)
