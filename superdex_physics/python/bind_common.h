#pragma once
// Helpers shared by the binding files: numpy conversions and argument checks that raise
// superdex.physics.Error naming the argument, the expected dtype and shape.

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "superdex/physics/error.h"
#include "superdex/physics/real.h"
#include "superdex/physics/scene.h"
#include "superdex/physics/transform.h"
#include "superdex/physics/types.h"

namespace superdex::python {

namespace nb = nanobind;
using namespace nb::literals;
using namespace superdex::physics;

using NumpyArray = nb::ndarray<nb::numpy, real>;

// Name of the build's numpy dtype ("float32" or "float64").
inline const char* real_dtype_name() { return kUsesDoublePrecision ? "float64" : "float32"; }

// A numpy array owning a copy of `n` values laid out with `shape` (C order). Return it with
// rv_policy::automatic (a property's default, reference_internal, refuses an array with an owner;
// move or copy would make numpy copy the values a second time).
NumpyArray numpy_copy(const real* data, std::initializer_list<size_t> shape);
inline NumpyArray numpy_copy(const VecX& v) { return numpy_copy(v.data(), {static_cast<size_t>(v.size())}); }

// Reads any sequence or array of numbers as a vector; `expected` < 0 accepts any length.
VecX read_vector(nb::handle obj, std::string_view arg, long expected = -1);
// The same into `out`, which keeps its storage when the size is unchanged.
void read_vector(nb::handle obj, std::string_view arg, VecX& out, long expected = -1);
Vec3 read_vec3(nb::handle obj, std::string_view arg);
// Integer indices from a list or tuple of ints, a DynamicArrayInt, a SpanConstInt or an array of
// integral numbers; errors name `arg`. The first form keeps `out`'s storage.
void read_indices(nb::handle obj, std::string_view arg, std::vector<int>& out);
std::vector<int> read_indices(nb::handle obj, std::string_view arg);
// Points from a DynamicArrayReal3, a sequence of Real3-like values or an (n, 3) array.
std::vector<Real3> read_real3s(nb::handle obj, std::string_view arg);

// The writable, contiguous 1-D buffer of length `n` behind an out-parameter: a numpy array of
// the build's dtype or a DynamicArrayReal. Raises superdex.physics.Error otherwise.
real* out_buffer(nb::handle out, std::string_view arg, size_t n);

// Writes `values` into an out-parameter of exactly their length, raising superdex.physics.Error
// naming `arg` otherwise: reals into a numpy array of the build's dtype, a DynamicArrayReal or a
// SpanReal; transforms into a DynamicArrayTransformRT or SpanTransformRT; pairs into a
// DynamicArrayReal2, a SpanReal2 or an (n, 2) array.
void write_out(nb::handle out, std::span<const real> values, std::string_view arg);
void write_out(nb::handle out, std::span<const TransformRT> values, std::string_view arg);
void write_out(nb::handle out, std::span<const Real2> values, std::string_view arg);
// `values` into an optional out-parameter, or into a new numpy array when `out` is None; returns
// the array filled.
nb::object fill_out(nb::handle out, const VecX& values, std::string_view arg);

// An actor as seen from Python: its scene and handle. Default: no actor (an element of a new
// DynamicArrayActor).
struct Actor {
  Scene scene{SceneHandle()};
  ActorHandle handle = 0;
};

// A constraint of a scene (bind_constraint.cpp).
struct Constraint {
  Scene scene{SceneHandle()};
  ConstraintHandle handle = 0;
};

// A Python object made of dicts, lists, strings, numbers, booleans and None as JSON (numpy
// arrays through tolist()); non-finite floats are kept so that readers name the field. Errors
// name `path` (bind_json.cpp).
nlohmann::json to_json(nb::handle obj, const std::string& path);

// A Python list of the elements of `items` (for vectors of types without a DynamicArray).
template <class T>
nb::list to_list(const std::vector<T>& items) {
  nb::list l;
  for (const T& x : items) l.append(nb::cast(x));
  return l;
}

// The handle of an Actor object or an integer handle (bind_scene.cpp).
ActorHandle actor_handle_of(nb::handle obj, const std::string& arg);

/// `obj` as a bound C++ object of type T, or superdex::Error naming the argument `arg` and the
/// `expected` Python type (instead of nanobind's TypeError for a mismatched signature).
template <class T>
T& object_of(nb::handle obj, const std::string& arg, const char* expected) {
  T* p = nullptr;
  if (obj.is_none() || !nb::try_cast<T*>(obj, p) || !p)
    throw Error(arg + ": expected " + expected + ", got " + nb::inst_name(obj).c_str());
  return *p;
}

// The ShapeHandle argument `arg`, or superdex.physics.Error naming it (bind_context.cpp).
ShapeHandle shape_handle_of(nb::handle obj, const std::string& arg);

// Transform from a TransformRT or None (identity).
Transform read_transform(nb::handle obj, const std::string& arg);

// DEFAULT as a true alias of the member the C++ Default equals (`E.DEFAULT is E.NEWTON`), as
// Python's enum aliases are: nanobind would make it a member of its own, unequal to the other.
template <class E>
void add_default_alias(nb::module_& m, const char* type_name) {
  nb::object type = m.attr(type_name);
  nb::object member = nb::cast(E::Default);
  type.attr("_member_map_")["DEFAULT"] = member;
  nb::handle(reinterpret_cast<PyObject*>(&PyType_Type)).attr("__setattr__")(type, "DEFAULT", member);
}

void export_error(nb::module_& m);
void export_values(nb::module_& m);
void export_containers(nb::module_& m);
void export_handles(nb::module_& m);
void export_enums(nb::module_& m);
void export_solver_params(nb::module_& m);
// bind_recording.cpp: RecordingParams, and the Scene's recording methods (added by export_scene)
void export_recording_params(nb::module_& m);
void add_recording_methods(nb::class_<Scene>& scene);
void export_material_params(nb::module_& m);
void export_actor_params(nb::module_& m);
void export_context(nb::module_& m);
void export_constants(nb::module_& m);
void export_debug_server(nb::module_& m);
void export_debug_draw(nb::module_& m);  // before export_scene: Scene.get_debug_draw returns a DebugDraw
// bind_constraint.cpp: ConstraintType, the constraint params and Constraint (before export_scene), and
// the Scene's constraint methods (added by export_scene)
void export_constraints(nb::module_& m);
void add_constraint_methods(nb::class_<Scene>& scene);
void export_scene(nb::module_& m);
void export_actor(nb::module_& m);
void export_experimental(nb::module_& m);
void export_robotics(nb::module_& m);
void export_physics_prefab(nb::module_& m);  // bind_scene_prefab.cpp: superdex.physics.prefab (after export_actor)
void export_scene_batch(nb::module_& m);    // superdex_robotics/python: into superdex.robotics
void export_meshes(nb::module_& m);
void export_model(nb::module_& m);  // ModelData and the superdex.physics.model submodule

}  // namespace superdex::python
