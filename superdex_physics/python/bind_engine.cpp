// Module functions: engine lifecycle, scenes and primitive shapes.

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/recording.h"
#include "superdex/physics/scene.h"

namespace superdex::python {

namespace {

// A shape handle as seen from Python.
struct Shape {
  ShapeHandle handle = 0;
};

real read_real(nb::handle obj, const std::string& arg) {
  double x;
  if (!nb::try_cast(obj, x)) throw Error(arg + ": expected a number");
  if (!std::isfinite(x)) throw Error(arg + ": must be finite, got " + std::to_string(x));
  return static_cast<real>(x);
}

}  // namespace

void export_engine(nb::module_& m) {
  m.def("initialize", &physics::initialize, "num_worker_threads"_a = 0,
        "Starts the engine: 0 single-threaded, -1 one worker per core, N worker threads.\n"
        "Not thread-safe: call it from one thread while no other thread uses the engine.");
  m.def("shutdown", &physics::shutdown, "Destroys every scene and shape and stops the engine.\n"
        "Not thread-safe: no other thread may be using the engine (stepping a scene, loading a file).");
  m.def("is_initialized", &physics::is_initialized);
  m.def("start_recording", &physics::start_recording, "path"_a, "frame_interval"_a = 1.0 / 60,
        "Records every live scene's steps to a JSON-lines file (docs/recording_format.md), a frame per\n"
        "frame_interval simulated seconds (0: every step).");
  m.def("stop_recording", &physics::stop_recording, "Flushes and closes the running recording.");
  m.def("is_recording", &physics::is_recording);
  m.def("recorded_time", &physics::recorded_time, "Latest simulated time (s) a recorded scene reached.");
  m.def("uses_double_precision", [] { return kUsesDoublePrecision; }, "True in the float64 build (SUPERDEX_PRECISION=double).");
  m.def("create_scene", &physics::create_scene, "name"_a = "scene",
        "A new, empty scene. Thread-safe: scenes may be created, filled and stepped from several threads,\n"
        "each scene used by one thread at a time.");
  m.def("destroy_scene", [](const Scene& s) { physics::destroy_scene(s.handle()); }, "scene"_a,
        "Destroys a scene and its actors; its handles then raise superdex.physics.Error.\n"
        "Not thread-safe for that scene: no other thread may be stepping or using it.");

  nb::class_<Shape>(m, "Shape", "A shape registered with the engine, referenced by handle.")
      .def("get_handle", [](const Shape& s) { return s.handle; })
      .def("__repr__", [](const Shape& s) { return "Shape(" + std::to_string(s.handle) + ")"; });
  m.def("create_plane_shape", [](nb::handle normal, nb::handle distance) {
          return Shape{create_shape(PlaneShape{read_vec3(normal, "create_plane_shape: normal"), read_real(distance, "create_plane_shape: distance")})};
        }, "normal"_a, "distance"_a, "Infinite plane n . x = distance (world frame when static), solid below.");
  m.def("create_sphere_shape", [](nb::handle center, nb::handle radius) {
          return Shape{create_shape(SphereShape{read_vec3(center, "create_sphere_shape: center"), read_real(radius, "create_sphere_shape: radius")})};
        }, "center"_a, "radius"_a, "Solid ball; center (m) in the body frame, radius (m).");
  m.def("create_box_shape", [](nb::handle half_extents) {
          return Shape{create_shape(BoxShape{read_vec3(half_extents, "create_box_shape: half_extents")})};
        }, "half_extents"_a, "Solid box centred at the body origin; half extents (m) along x, y, z.");
  m.def("create_capsule_shape", [](nb::handle radius, nb::handle half_length) {
          return Shape{create_shape(CapsuleShape{read_real(radius, "create_capsule_shape: radius"), read_real(half_length, "create_capsule_shape: half_length")})};
        }, "radius"_a, "half_length"_a, "Solid capsule along the body z axis: segment from -half_length to +half_length (m), radius (m).");
  m.def("create_tet_mesh_shape", [](nb::handle coordinates, nb::handle connectivity) {
          nb::object np = nb::module_::import_("numpy");
          nb::object X, T;
          try {
            X = np.attr("asarray")(coordinates, "dtype"_a = np.attr("float64"));
            T = np.attr("asarray")(connectivity);
          } catch (nb::python_error&) {
            throw Error("create_tet_mesh_shape: coordinates (N x 3) and connectivity (M x 4) must be arrays of numbers");
          }
          const auto xs = nb::cast<std::vector<size_t>>(X.attr("shape")), ts = nb::cast<std::vector<size_t>>(T.attr("shape"));
          if (xs.size() != 2 || xs[1] != 3) throw Error("create_tet_mesh_shape: coordinates must have shape (N, 3)");
          if (ts.size() != 2 || ts[1] != 4) throw Error("create_tet_mesh_shape: connectivity must have shape (M, 4)");
          if (!nb::cast<bool>(np.attr("issubdtype")(T.attr("dtype"), np.attr("integer"))))
            throw Error("create_tet_mesh_shape: connectivity must hold integers");
          const VecX flat_x = read_vector(X.attr("ravel")(), "create_tet_mesh_shape: coordinates");
          const VecX flat_t = read_vector(T.attr("ravel")(), "create_tet_mesh_shape: connectivity");
          TetMesh mesh;
          for (size_t i = 0; i < xs[0]; ++i) mesh.nodes.emplace_back(flat_x[3 * i], flat_x[3 * i + 1], flat_x[3 * i + 2]);
          for (size_t t = 0; t < ts[0]; ++t)
            mesh.tets.push_back({static_cast<int>(flat_t[4 * t]), static_cast<int>(flat_t[4 * t + 1]),
                                 static_cast<int>(flat_t[4 * t + 2]), static_cast<int>(flat_t[4 * t + 3])});
          return Shape{physics::create_tet_mesh_shape(std::move(mesh), "create_tet_mesh_shape")};
        }, "coordinates"_a, "connectivity"_a, "A tetrahedral mesh for soft actors: N x 3 node coordinates (m), M x 4 node indices.");
  m.def("release_shape", [](const Shape& s) { physics::release_shape(s.handle); }, "shape"_a);

  nb::enum_<ColliderType>(m, "ColliderType")
      .value("AUTO", ColliderType::Auto).value("NONE", ColliderType::None).value("SPHERE", ColliderType::Sphere)
      .value("BOX", ColliderType::Box).value("PLANE", ColliderType::Plane).value("MESH", ColliderType::Mesh)
      .value("SDF", ColliderType::Sdf);
}

// Exposed for bind_meshes.cpp.
nb::object shape_object(ShapeHandle handle) { return nb::cast(Shape{handle}); }

// Exposed for bind_scene.cpp.
ShapeHandle shape_handle_of(nb::handle obj, const std::string& arg) {
  Shape s;
  if (!nb::try_cast(obj, s)) throw Error(arg + ": expected a Shape from create_*_shape, got " + std::string(nb::inst_name(obj).c_str()));
  return s.handle;
}

}  // namespace superdex::python
