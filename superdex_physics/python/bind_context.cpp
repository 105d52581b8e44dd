// Module functions of the engine context: initialize and shutdown, threads, the log, scenes,
// primitive and tetrahedral shapes and their registry, and the recording switches.

#include <nanobind/stl/string.h>

#include <frameobject.h>

#include "bind_common.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/log.h"
#include "superdex/physics/recording.h"
#include "superdex/physics/scene.h"

namespace superdex::python {

namespace {

real read_real(nb::handle obj, const std::string& arg) {
  double x;
  if (!nb::try_cast(obj, x)) throw Error(arg + ": expected a number, got " + std::string(nb::inst_name(obj).c_str()));
  if (!std::isfinite(x)) throw Error(arg + ": must be finite, got " + std::to_string(x));
  return static_cast<real>(x);
}

// The Python log callback: called with the GIL from whatever thread logs. At interpreter exit it
// is dropped (the module's atexit hook) before Python goes away.
struct PythonLogCallback {
  nb::object fn;
  ~PythonLogCallback() {
    if (!Py_IsInitialized()) {
      fn.release();  // the interpreter is gone: leave its object alone
      return;
    }
    nb::gil_scoped_acquire gil;
    fn.reset();
  }
};

void set_python_log_callback(nb::handle fn) {
  if (fn.is_none()) {
    physics::set_log_callback(nullptr);
    return;
  }
  if (!PyCallable_Check(fn.ptr())) throw Error("set_log_callback: callback must be callable (channel, message, file, line) or None");
  auto holder = std::make_shared<PythonLogCallback>(PythonLogCallback{nb::borrow(fn)});
  physics::set_log_callback([holder](LogChannel channel, std::string_view message, std::string_view file, int line) {
    if (!Py_IsInitialized()) return;
    nb::gil_scoped_acquire gil;
    try {
      holder->fn(channel, nb::str(message.data(), message.size()), nb::str(file.data(), file.size()), line);
    } catch (nb::python_error& e) {
      e.discard_as_unraisable("superdex log callback");
    }
  });
}

// The file and line of the Python code calling into the module.
std::pair<std::string, int> caller_location() {
  PyFrameObject* frame = PyEval_GetFrame();
  if (!frame) return {"", 0};
  PyCodeObject* code = PyFrame_GetCode(frame);
  std::string file = nb::cast<std::string>(nb::handle(code->co_filename));
  const int line = PyFrame_GetLineNumber(frame);
  Py_DECREF(code);
  return {file, line};
}

Aabb shape_aabb(const ShapeHandle& shape) {
  const ShapeGeometry g = physics::shape_geometry(shape);
  const real inf = std::numeric_limits<real>::infinity();
  if (auto* p = std::get_if<PlaneShape>(&g)) {
    // the solid half-space below the plane: bounded only along an axis-aligned normal
    Aabb b{Real3::Constant(-inf), Real3::Constant(inf)};
    const Vec3 n = p->normal.normalized();
    for (int k = 0; k < 3; ++k)
      if (std::abs(std::abs(n[k]) - 1) < real(1e-6)) (n[k] > 0 ? b.max[k] : b.min[k]) = n[k] > 0 ? p->distance : -p->distance;
    return b;
  }
  const auto [lo, hi] = shape_bounds(g);
  return Aabb{lo, hi};
}

}  // namespace

void export_context(nb::module_& m) {
  m.def("initialize", &physics::initialize, "num_worker_threads"_a = 0,
        "Starts the engine: 0 single-threaded, -1 one worker per core, N worker threads. Raises superdex.physics.Error\n"
        "when already initialized (call shutdown() first). Not thread-safe.");
  m.def("shutdown", &physics::shutdown, "Destroys every scene and shape and stops the engine. Not thread-safe.");
  m.def("is_initialized", &physics::is_initialized);
  m.def("get_num_threads", &physics::num_threads, "Worker threads initialize() was asked for, or 0 when single-threaded.");
  m.def("set_is_single_threaded", &physics::set_single_threaded, "is_single_threaded"_a,
        "New work runs on the calling thread (True) or on the worker threads again (False).");
  m.def("is_single_threaded", &physics::is_single_threaded);
  m.def("uses_double_precision", [] { return kUsesDoublePrecision; }, "True in the float64 build (SUPERDEX_PRECISION=double).");
  m.def("uses_hdf5", [] { return true; }, "True: .mochi.h5 model files and HDF5 recordings are available.");
  m.def("is_debug", [] {
#ifdef NDEBUG
    return false;
#else
    return true;
#endif
  }, "Whether the native library is a debug build.");

  m.def("set_log_callback", &set_python_log_callback, "callback"_a.none(),
        "callback(channel, message, file, line) receives every message of an enabled channel; None restores the default\n"
        "printer (Verbose and Info to stdout, Warning and Error to stderr). Called from the thread that logs.");
  m.def("enable_log_channel", &physics::enable_log_channel, "channel"_a, "enable"_a, "Verbose is disabled by default.");
  m.def("is_log_channel_enabled", &physics::is_log_channel_enabled, "channel"_a);
  m.def("log", [](const std::string& message, LogChannel channel) {
          const auto [file, line] = caller_location();
          physics::log(channel, message, file, line);
        }, "message"_a, "channel"_a = LogChannel::Info, "Logs a message from Python (its file and line are the caller's).");

  m.def("start_recording", &physics::start_recording, "path"_a, "frame_interval"_a = 1.0 / 60,
        "Records every live scene's steps to a JSON-lines file (docs/recording_format.md), a frame per\n"
        "frame_interval simulated seconds (0: every step).");
  m.def("stop_recording", &physics::stop_recording, "Flushes and closes the running recording.");
  m.def("is_recording", &physics::is_recording);
  m.def("recorded_frames", &physics::recorded_frames, "How many frames the running recording has written (0 when none runs).");
  m.def("recorded_time", &physics::recorded_time, "The most simulated time (s) a recorded scene has run since the recording started (the sum of its step sizes).");

  m.def("create_scene", &physics::create_scene, "name"_a,
        "A new, empty scene. Scenes may be created, filled and stepped from several threads, each used by one thread at a time.");
  m.def("destroy_scene", [](nb::handle scene) {
          if (scene.is_none()) return;
          const Scene& s = object_of<Scene>(scene, "destroy_scene: scene", "a superdex.physics.Scene or None");
          if (physics::scene_exists(s.handle())) physics::destroy_scene(s.handle());
        }, "scene"_a.none(), "Destroys a scene and its actors at once; no effect for None or a destroyed scene.");
  m.def("get_scene", [](SceneHandle h) -> nb::object {
          if (!physics::scene_exists(h)) return nb::none();
          return nb::cast(Scene(h));
        }, "handle"_a, "The scene with this handle, or None.");
  m.def("is_valid_scene", [](nb::handle scene) {
          if (scene.is_none()) return false;
          const Scene& s = object_of<Scene>(scene, "is_valid_scene: scene", "a superdex.physics.Scene or None");
          return physics::scene_exists(s.handle());
        }, "scene"_a.none());

  m.def("create_plane_shape", [](const Real3& normal, nb::handle distance) {
          return create_shape(PlaneShape{normal, read_real(distance, "create_plane_shape: distance")});
        }, "normal"_a, "distance"_a, "The half-space {x : n . x <= distance} (n = normal / |normal|), solid below the plane.");
  m.def("create_sphere_shape", [](const Real3& center, nb::handle radius) {
          return create_shape(SphereShape{center, read_real(radius, "create_sphere_shape: radius")});
        }, "center"_a, "radius"_a, "A solid ball; center (m) in the shape frame, radius (m).");
  m.def("create_box_shape", [](const Real3& half_extents) { return create_shape(BoxShape{half_extents}); }, "half_extents"_a,
        "A solid box centred at the shape origin; half extents (m) along x, y, z (this engine's addition).");
  m.def("create_capsule_shape", [](nb::handle radius, nb::handle half_length) {
          return create_shape(CapsuleShape{read_real(radius, "create_capsule_shape: radius"),
                                           read_real(half_length, "create_capsule_shape: half_length")});
        }, "radius"_a, "half_length"_a,
        "A solid capsule along the shape's z axis: segment from -half_length to +half_length (m), radius (m) (this engine's addition).");
  m.def("release_shape", [](nb::handle shape) {
          if (shape.is_none()) return;
          physics::release_shape(object_of<ShapeHandle>(shape, "release_shape: shape", "a superdex.physics.ShapeHandle or None"));
        }, "shape"_a.none(), "Releases a shape at once (actors made from it keep its data); no effect for None or a released shape.");
  m.def("get_num_shapes", &physics::num_shapes, "The number of live (unreleased) shapes.");
  m.def("get_shape_aabb", &shape_aabb, "shape"_a, "The shape's bounds in its frame (m).");
  m.def("enable_file_cache", &physics::enable_file_cache, "enable"_a,
        "Keeps the data of shapes loaded from files after their release, so that loading the same file with the same bake\n"
        "is fast; disabling it empties the cache.");
  m.def("is_file_cache_enabled", &physics::is_file_cache_enabled);
  m.def("clear_file_cache", &physics::clear_file_cache);
  m.def("clear_file_from_cache", &physics::clear_file_from_cache, "file_path"_a, "Every bake of the file (exact path).");

  // At interpreter exit, before Python tears its objects down, the engine lets go of every Python
  // object it holds (step callbacks, the log callback): a script may exit without shutdown() with
  // scenes and callbacks alive. Registered at import, so the user's own exit handlers run first.
  nb::module_::import_("atexit").attr("register")(nb::cpp_function([] {
    physics::set_log_callback(nullptr);
    if (physics::is_initialized()) physics::shutdown();
  }));
}

// Exposed for bind_scene.cpp.
ShapeHandle shape_handle_of(nb::handle obj, const std::string& arg) {
  return object_of<ShapeHandle>(obj, arg, "a superdex.physics.ShapeHandle");
}

}  // namespace superdex::python
