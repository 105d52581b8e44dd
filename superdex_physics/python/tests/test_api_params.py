"""The params and result structs: every field round-trips (attribute, keyword constructor, copy,
deepcopy, pickle, `src=` copy), nested structs are references, unknown keywords are refused, and
a bad value raises superdex.physics.Error naming the field when the struct is used."""

import copy
import math
import pickle

import numpy as np
import pytest

import superdex.physics as sdp

# every struct of the API that is plain data (fields only)
STRUCTS = [
    "ContactParams", "GridSdfParams", "BoundarySubsamplingParams", "RecenteringParams",
    "RigidActorParams", "SoftActorParams", "ArticulatedActorParams", "ArticulatedLinkParams",
    "ArticulatedJointParams", "ArticulatedJointFrictionParams", "ArticulatedCycleJointParams",
    "ArticulatedDofInfo", "ArticulatedCycleJoint", "ArticulatedSkinParams",
    "SoftMaterialParams", "NeoHookeanMaterialParams", "StVenantKirchhoffMaterialParams",
    "LinearElasticMaterialParams", "ArapMaterialParams", "ActiveAnisoArapMaterialParams",
    "ActiveNeoHookeanMaterialParams", "ActiveShapeTargetingArapMaterialParams",
    "SolverParams", "NonLinearSolverParams", "LinearSolverParams", "ExperimentalEvalParams",
    "SaturationHessianParams", "ImplicitStepParams", "SolverStats", "PerformanceStats",
    "ContactPoint", "NodeContactForce", "SdfDistances",
]

# values for optional fields (None by default) and arrays, by field name
OPTIONAL_VALUES = {
    "density": 2.5, "mass": 0.75, "inertia": 0.5,
    "center_of_mass": sdp.Real3(0.5, -0.25, 2),
    "moment_of_inertia": sdp.Real6(2, 0, 0, 3, 0, 4),
    "linear_velocity": sdp.Real3(1, 2, 3), "angular_velocity": sdp.Real3(-1, 0.5, 0),
    "min_limit": sdp.Real3(-1, 0, 0), "max_limit": sdp.Real3(1, 0, 0),
    "joint_velocities": [0.5, -0.25],
    "skin": sdp.ArticulatedSkinParams(layer="skin"),
}


def fields_of(obj):
    return list(obj.__getstate__().keys())


def changed(name, value):
    """A value of the field's type that differs from `value` and is exact in float32."""
    if value is None:
        if name == "boundary_subsampling":
            return sdp.BoundarySubsamplingParams(subsampling_density=0.5)
        return OPTIONAL_VALUES[name]
    if isinstance(value, bool):
        return not value
    if isinstance(value, int) and not hasattr(value, "name"):
        return value + 3
    if isinstance(value, float):
        return 0.5 if value != 0.5 else 0.25
    if isinstance(value, str):
        return value + "_x"
    if hasattr(type(value), "__members__"):  # an enum: another member
        return next(m for m in type(value) if m != value)
    simple = {
        sdp.Real3: sdp.Real3(0.5, -0.25, 2), sdp.Real6: sdp.Real6(1, 2, 3, 4, 5, 6), sdp.Int3: sdp.Int3(2, 3, 4),
        sdp.TransformRT: sdp.TransformRT(rotation=sdp.Quaternion(0, 1, 0, 0), translation=sdp.Real3(0.5, -0.25, 2)),
        sdp.DynamicArrayArticulatedCycleJointParams: [sdp.ArticulatedCycleJointParams(stiffness=0.5)],
        sdp.DynamicArrayArticulatedJointParams: [sdp.ArticulatedJointParams(name="j")],
        sdp.DynamicArrayArticulatedLinkParams: [sdp.ArticulatedLinkParams(name="l")],
        sdp.SpanConstInt: [3, 1, 2], sdp.SpanConstReal: [0.5, 0.25],
        sdp.SpanConstReal3: [sdp.Real3(1, 2, 3), sdp.Real3(0, 0.5, 0)],
    }
    if isinstance(value, sdp.ActorHandle):
        return sdp.ActorHandle(value.value + 7)
    for t, v in simple.items():
        if isinstance(value, t):
            return v
    if isinstance(value, sdp.ShapeHandle):
        return sdp.create_sphere_shape([0, 0, 0], 0.5)
    if hasattr(value, "__getstate__") and isinstance(value.__getstate__(), dict):  # a nested struct
        return mutated(value)
    raise AssertionError(f"{name}: no changed value for {type(value).__name__}")


def mutated(obj):
    """A copy of obj with every field changed."""
    out = type(obj)(src=obj)
    for f in fields_of(obj):
        setattr(out, f, changed(f, getattr(obj, f)))
    return out


def same(a, b):
    """Field values compare equal (spans and arrays element-wise)."""
    if hasattr(a, "tolist") and not isinstance(a, (int, float)):
        return list(a.tolist()) == list(b.tolist() if hasattr(b, "tolist") else b)
    return a == b


@pytest.fixture(autouse=True)
def _engine(engine):
    yield


@pytest.mark.parametrize("name", STRUCTS)
def test_every_field_round_trips(name):
    cls = getattr(sdp, name)
    default = cls()
    changes = {f: changed(f, getattr(default, f)) for f in fields_of(default)}
    assert changes, f"{name} has no fields"

    # attribute by attribute
    obj = cls()
    for f, v in changes.items():
        setattr(obj, f, v)
        assert same(getattr(obj, f), v), f"{name}.{f}"
    assert obj != default

    # all fields by keyword, in any order
    by_keyword = cls(**dict(reversed(list(changes.items()))))
    assert by_keyword == obj

    # copies are equal and independent
    for c in (cls(src=obj), copy.copy(obj), copy.deepcopy(obj), pickle.loads(pickle.dumps(obj))):
        assert c == obj
        first = fields_of(obj)[0]
        setattr(c, first, getattr(default, first))
        assert not same(getattr(c, first), getattr(obj, first)), f"a copy of {name} shares its {first}"

    # fields not given keep their defaults
    one = fields_of(default)[-1]
    partial = cls(**{one: changes[one]})
    for f in fields_of(default):
        assert same(getattr(partial, f), changes[one] if f == one else getattr(default, f)), f"{name}.{f}"

    assert name in repr(obj)


@pytest.mark.parametrize("name", STRUCTS)
def test_unknown_keyword_is_refused(name):
    with pytest.raises(TypeError, match="bogus_field"):
        getattr(sdp, name)(bogus_field=1)


def test_nested_structs_are_references():
    p = sdp.RigidActorParams()
    p.contact.coulomb_friction_coefficient = 0.25
    p.world_from_local.translation = sdp.Real3(1, 2, 3)
    assert p.contact.coulomb_friction_coefficient == 0.25
    assert p.world_from_local.translation == sdp.Real3(1, 2, 3)
    s = sdp.SolverParams()
    s.non_linear_solver.max_iter = 17
    assert s.non_linear_solver.max_iter == 17
    a = sdp.ArticulatedActorParams(links=[sdp.ArticulatedLinkParams(name="a")])
    a.links[0].name = "b"
    assert a.links[0].name == "b"


def test_numpy_arrays_set_vector_fields():
    p = sdp.RigidActorParams()
    p.world_from_local = sdp.TransformRT(translation=np.array([0.5, 1.5, -2.0]))
    p.center_of_mass = np.array([0.25, 0.0, 1.0], dtype=np.float32)
    p.moment_of_inertia = np.arange(1.0, 7.0)
    assert p.world_from_local.translation == sdp.Real3(0.5, 1.5, -2)
    assert np.array_equal(np.asarray(p.center_of_mass), [0.25, 0, 1])
    assert np.array_equal(np.asarray(p.moment_of_inertia), np.arange(1.0, 7.0))
    j = sdp.ArticulatedJointParams(axis=np.array([0, 0, 1]))
    assert j.axis == sdp.Real3(0, 0, 1)


def test_defaults_are_superdex_defaults():
    c = sdp.ContactParams()
    assert c.coulomb_friction_coefficient == 0.5 and c.penalty_coefficient == pytest.approx(1e9)
    n = sdp.NonLinearSolverParams()
    assert n.solver_type is sdp.NonLinearSolverType.NEWTON is sdp.NonLinearSolverType.DEFAULT
    assert n.rel_step_tol == pytest.approx(sdp.DEFAULT_REL_STEP_TOL)
    assert sdp.LinearSolverParams().max_iter == sdp.AUTO_LINEAR_SOLVER_MAX_ITER
    assert sdp.GridSdfParams().boundary_padding_dist == pytest.approx(sdp.GRID_SDF_DEFAULT_BOUNDARY_PADDING)
    assert sdp.GridSdfParams() == sdp.GRID_SDF_PARAMS_DEFAULT
    r = sdp.RigidActorParams()
    assert r.density is None and r.mass is None and r.is_static is False and r.has_gravity is True
    assert r.collider_type == sdp.ColliderType.AUTO and r.world_from_local == sdp.TRANSFORM_RT_IDENTITY
    assert sdp.SoftMaterialParams().density == sdp.DEFAULT_DENSITY


# --- bad values raise superdex.physics.Error naming the field, when the struct is used ---

def box(scene, **kw):
    return scene.create_rigid_actor(shape=sdp.create_box_shape([0.1, 0.1, 0.1]), **kw)


def tet():
    return sdp.create_tet_mesh_shape([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], [0, 1, 2, 3])


def arm_params(**joint):
    shape = sdp.create_box_shape([0.1, 0.1, 0.1])
    j1 = {"name": "j1", "type": sdp.ArticulatedJointType.REVOLUTE, "axis": [0, 0, 1], **joint}
    return sdp.ArticulatedActorParams(
        name="arm",
        links=[sdp.ArticulatedLinkParams(name="base", shape=shape),
               sdp.ArticulatedLinkParams(name="l1", parent_link=0, shape=shape)],
        joints=[sdp.ArticulatedJointParams(name="root", type=sdp.ArticulatedJointType.HARD),
                sdp.ArticulatedJointParams(**j1)],
    )


def solver(**nested):
    p = sdp.SolverParams()
    for path, value in nested.items():
        obj = p
        parts = path.split("__")
        for part in parts[:-1]:
            obj = getattr(obj, part)
        setattr(obj, parts[-1], value)
    return p


BAD = [
    # ContactParams, through the actor that uses them
    ("contact.coulomb_friction_coefficient", lambda s: box(s, contact=sdp.ContactParams(coulomb_friction_coefficient=-1))),
    ("contact.penalty_coefficient", lambda s: box(s, contact=sdp.ContactParams(penalty_coefficient=0))),
    ("contact.max_alignment_normals", lambda s: box(s, contact=sdp.ContactParams(max_alignment_normals=2))),
    ("contact.contact_stiffness", lambda s: box(s, contact=sdp.ContactParams(contact_stiffness=math.nan))),
    ("contact.obj_scale", lambda s: box(s, contact=sdp.ContactParams(obj_scale=-2))),
    # RigidActorParams
    ("mass", lambda s: box(s, mass=-1.0)),
    ("density", lambda s: box(s, density=0.0)),
    ("world_from_local.rotation", lambda s: box(s, world_from_local=sdp.TransformRT(rotation=sdp.Quaternion(0, 0, 0, 0)))),
    ("world_from_local.translation", lambda s: box(s, world_from_local=sdp.TransformRT(translation=[math.inf, 0, 0]))),
    ("linear_velocity", lambda s: box(s, is_static=True, linear_velocity=[1, 0, 0])),
    ("shape", lambda s: s.create_rigid_actor(sdp.RigidActorParams(name="no shape"))),
    ("collider_type", lambda s: box(s, collider_type=sdp.ColliderType.POINT_CLOUD)),
    # SoftActorParams and materials
    ("has_stress", lambda s: s.create_soft_actor(shape=tet(), has_gravity=False, has_inertia=False, has_stress=False)),
    ("material.neo_hookean.youngs_modulus", lambda s: s.create_soft_actor(
        shape=tet(), material=sdp.SoftMaterialParams(neo_hookean=sdp.NeoHookeanMaterialParams(youngs_modulus=-5.0)))),
    ("material.neo_hookean.poisson_ratio", lambda s: s.create_soft_actor(
        shape=tet(), material=sdp.SoftMaterialParams(neo_hookean=sdp.NeoHookeanMaterialParams(poisson_ratio=0.5)))),
    ("material.density", lambda s: s.create_soft_actor(shape=tet(), material=sdp.SoftMaterialParams(density=-1.0))),
    ("material.type", lambda s: s.create_soft_actor(shape=tet(), material=sdp.SoftMaterialParams(type=sdp.SoftMaterialType.ARAP))),
    # ArticulatedActorParams
    ("links", lambda s: s.create_articulated_actor(sdp.ArticulatedActorParams(name="empty"))),
    ("joints", lambda s: s.create_articulated_actor(sdp.ArticulatedActorParams(
        name="x", links=[sdp.ArticulatedLinkParams(shape=sdp.create_box_shape([0.1, 0.1, 0.1]))]))),
    ("joints[1].axis", lambda s: s.create_articulated_actor(arm_params(axis=[0, 0, 0]))),
    ("joints[1].limit_stiffness", lambda s: s.create_articulated_actor(arm_params(limit_stiffness=-3.0))),
    ("joints[1].friction.coulomb", lambda s: s.create_articulated_actor(
        arm_params(friction=sdp.ArticulatedJointFrictionParams(coulomb=-1.0)))),
    ("joints[1].type", lambda s: s.create_articulated_actor(arm_params(type=sdp.ArticulatedJointType.FREE))),
    # SolverParams
    ("non_linear_solver.max_iter", lambda s: s.set_solver_params(solver(non_linear_solver__max_iter=0))),
    ("non_linear_solver.abs_tol", lambda s: s.set_solver_params(solver(non_linear_solver__abs_tol=-1.0))),
    ("non_linear_solver.solver_type", lambda s: s.set_solver_params(solver(non_linear_solver__solver_type=sdp.NonLinearSolverType.BFGS))),
    ("linear_solver.solver_type", lambda s: s.set_solver_params(solver(linear_solver__solver_type=sdp.LinearSolverType.GMRES))),
    ("integration_method", lambda s: s.set_solver_params(solver(integration_method=sdp.IntegrationMethod.BDF3))),
    ("implicit_step.friction_sigma", lambda s: s.set_solver_params(solver(implicit_step__friction_sigma=0.0))),
]


@pytest.mark.parametrize("field,make", BAD, ids=[b[0] for b in BAD])
def test_bad_field_raises_error_naming_it(scene, field, make):
    with pytest.raises(sdp.Error) as e:
        make(scene)
    assert field in str(e.value)


def test_bad_values_on_actor_setters_name_the_field(scene):
    a = box(scene)
    with pytest.raises(sdp.Error, match="coulomb_friction_coefficient"):
        a.set_contact_params(sdp.ContactParams(coulomb_friction_coefficient=-0.5))
    soft = scene.create_soft_actor(shape=tet())
    with pytest.raises(sdp.Error, match="rotation_epsilon_deg"):
        soft.set_recentering_params(sdp.RecenteringParams(use_recentering=True, rotation_epsilon_deg=-1.0))
    arm = scene.create_articulated_actor(arm_params())
    with pytest.raises(sdp.Error, match="falloff_vel"):
        arm.set_articulated_joint_friction_params([sdp.ArticulatedJointFrictionParams(), sdp.ArticulatedJointFrictionParams(falloff_vel=0.0)])
    # nothing changed by a refused call
    assert a.get_contact_params() == sdp.ContactParams()
    assert arm.get_articulated_joint_friction_params().tolist() == [sdp.ArticulatedJointFrictionParams()] * 2


def test_solver_params_round_trip_through_the_scene(scene):
    p = solver(non_linear_solver__max_iter=9, non_linear_solver__abs_tol=1e-7, linear_solver__solver_type=sdp.LinearSolverType.LDLT)
    scene.set_solver_params(p)
    assert scene.get_solver_params() == p
    with pytest.raises(sdp.Error):
        scene.set_solver_params(solver(non_linear_solver__max_iter=0))
    assert scene.get_solver_params() == p  # a refused value leaves the scene's params as they were
