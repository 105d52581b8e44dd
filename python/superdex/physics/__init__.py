"""superdex.physics: the engine's Python API (see API.md).

The float32 build is loaded by default; SUPERDEX_PRECISION=double selects the float64 build.
"""

from superdex._native import module as _m

Error = _m.Error
Quaternion = _m.Quaternion
TransformRT = _m.TransformRT
DynamicArrayTransformRT = _m.DynamicArrayTransformRT
DynamicArrayReal = _m.DynamicArrayReal
ActorType = _m.ActorType
JointType = _m.JointType
ColliderType = _m.ColliderType
QueryType = _m.QueryType
NumericalFaultPolicy = _m.NumericalFaultPolicy
NumericalFault = _m.NumericalFault
ContactPoint = _m.ContactPoint
SceneState = _m.SceneState
Scene = _m.Scene
Actor = _m.Actor
Shape = _m.Shape
SolverParams = _m.SolverParams
SolverStats = _m.SolverStats
ArticulatedShapeInfo = _m.ArticulatedShapeInfo
DofInfo = _m.DofInfo

initialize = _m.initialize
shutdown = _m.shutdown
is_initialized = _m.is_initialized
uses_double_precision = _m.uses_double_precision
create_scene = _m.create_scene
destroy_scene = _m.destroy_scene
create_plane_shape = _m.create_plane_shape
create_sphere_shape = _m.create_sphere_shape
create_box_shape = _m.create_box_shape
create_capsule_shape = _m.create_capsule_shape
create_tet_mesh_shape = _m.create_tet_mesh_shape
release_shape = _m.release_shape
create_tri_mesh_shape = _m.create_tri_mesh_shape
load_shape_from_file = _m.load_shape_from_file
start_recording = _m.start_recording
stop_recording = _m.stop_recording
is_recording = _m.is_recording
recorded_time = _m.recorded_time
get_debug_server = _m.get_debug_server
DebugServer = _m.DebugServer
CoordinateSpace = _m.CoordinateSpace
CoordinateSpaceAxes = _m.CoordinateSpaceAxes

from superdex.physics import debugger, paths, prefab  # noqa: E402  (submodules, after the native names)

__all__ = [name for name in dir() if not name.startswith("_")]
