// Error, enums, and the array helpers shared by the binding files.

#include <cstring>

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "superdex/physics/articulation_desc.h"
#include "superdex/physics/scene.h"

namespace superdex::python {

NumpyArray numpy_copy(const real* data, std::initializer_list<size_t> shape) {
  size_t n = 1;
  for (size_t s : shape) n *= s;
  auto* copy = new std::vector<real>(data, data + n);
  nb::capsule owner(copy, [](void* p) noexcept { delete static_cast<std::vector<real>*>(p); });
  return NumpyArray(copy->data(), shape.size(), shape.begin(), owner);
}

namespace {

// The common cases without a numpy conversion: a 1-D contiguous float64 or float32 array, or a
// list or tuple of Python numbers. False when obj is none of these (the general path decides).
bool read_vector_fast(nb::handle obj, VecX& out) {
  nb::ndarray<const double, nb::ndim<1>, nb::c_contig> d;
  if (nb::try_cast(obj, d, false)) {
    out = Eigen::Map<const Eigen::VectorXd>(d.data(), static_cast<Eigen::Index>(d.shape(0))).cast<real>();
    return true;
  }
  nb::ndarray<const float, nb::ndim<1>, nb::c_contig> f;
  if (nb::try_cast(obj, f, false)) {
    out = Eigen::Map<const Eigen::VectorXf>(f.data(), static_cast<Eigen::Index>(f.shape(0))).cast<real>();
    return true;
  }
  PyObject* o = obj.ptr();
  if (!PyList_Check(o) && !PyTuple_Check(o)) return false;
  const Py_ssize_t n = PySequence_Fast_GET_SIZE(o);
  PyObject** items = PySequence_Fast_ITEMS(o);
  out.resize(n);
  for (Py_ssize_t i = 0; i < n; ++i) {
    if (!PyFloat_Check(items[i]) && !PyLong_Check(items[i])) return false;
    const double x = PyFloat_AsDouble(items[i]);
    if (x == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();  // an int too large for a double: the general path reports it
      return false;
    }
    out[i] = static_cast<real>(x);
  }
  return true;
}

}  // namespace

VecX read_vector(nb::handle obj, std::string_view arg, long expected) {
  VecX out;
  read_vector(obj, arg, out, expected);
  return out;
}

void read_vector(nb::handle obj, std::string_view arg, VecX& out, long expected) {
  if (read_vector_fast(obj, out)) {
    if (expected >= 0 && out.size() != expected)
      throw Error(std::string(arg) + ": expected " + std::to_string(expected) + " values, got " + std::to_string(out.size()));
    return;
  }
  nb::object arr;
  try {
    // imported once and never released (a static object would be destroyed after the interpreter)
    static const nb::handle np = nb::module_::import_("numpy").release();
    arr = np.attr("ascontiguousarray")(obj, "dtype"_a = np.attr("float64"));
  } catch (nb::python_error&) {
    throw Error(std::string(arg) + ": expected a sequence of numbers");
  }
  auto a = nb::cast<nb::ndarray<const double, nb::c_contig>>(arr);
  if (a.ndim() > 1) throw Error(std::string(arg) + ": expected a 1-D sequence of numbers, got " + std::to_string(a.ndim()) + " dimensions");
  const long n = a.ndim() == 0 ? 1 : static_cast<long>(a.shape(0));
  if (expected >= 0 && n != expected)
    throw Error(std::string(arg) + ": expected " + std::to_string(expected) + " values, got " + std::to_string(n));
  out.resize(n);
  for (long i = 0; i < n; ++i) out[i] = static_cast<real>(a.data()[i]);
}

Vec3 read_vec3(nb::handle obj, std::string_view arg) { return read_vector(obj, arg, 3); }

real* out_buffer(nb::handle out, std::string_view arg, size_t n) {
  // the common case first: a writable contiguous array of the right dtype and length
  nb::ndarray<real, nb::ndim<1>, nb::c_contig> fast;
  if (nb::try_cast(out, fast, false) && fast.shape(0) == n) return fast.data();
  if (nb::isinstance<std::vector<real>>(out)) {
    auto& d = nb::cast<std::vector<real>&>(out);
    if (d.size() != n)
      throw Error(std::string(arg) + ": expected a DynamicArrayReal of length " + std::to_string(n) + ", got length " + std::to_string(d.size()));
    return d.data();
  }
  const std::string expect = "a writable, contiguous numpy array of dtype " + std::string(real_dtype_name()) +
                             " and shape (" + std::to_string(n) + ",)";
  // read-only arrays do not convert to a writable ndarray: name that defect first
  if (nb::hasattr(out, "flags") && nb::hasattr(out.attr("flags"), "writeable") &&
      !nb::cast<bool>(out.attr("flags").attr("writeable")))
    throw Error(std::string(arg) + ": expected " + expect + ", got a read-only array");
  nb::ndarray<> a;
  if (!nb::try_cast(out, a, false)) throw Error(std::string(arg) + ": expected " + expect + ", got " + nb::inst_name(out).c_str());
  if (a.dtype() != nb::dtype<real>() || a.ndim() != 1 || a.shape(0) != n || (n > 1 && a.stride(0) != 1)) {
    std::string got = "ndim " + std::to_string(a.ndim());
    if (a.ndim() == 1) got = "shape (" + std::to_string(a.shape(0)) + ",)";
    throw Error(std::string(arg) + ": expected " + expect + ", got " + got + (a.dtype() != nb::dtype<real>() ? " with another dtype" : ""));
  }
  return static_cast<real*>(a.data());
}

Transform read_transform(nb::handle obj, const std::string& arg) {
  if (obj.is_none()) return Transform{};
  TransformRT t;
  if (!nb::try_cast(obj, t)) throw Error(arg + ": expected a TransformRT");
  if (!t.translation.allFinite()) throw Error(arg + ".translation: must be finite");
  const Quat q = t.rotation;
  if (!q.coeffs().allFinite() || q.norm() < real(1e-6)) throw Error(arg + ".rotation: must be a finite, non-zero quaternion");
  return Transform{q.normalized(), t.translation};
}

void export_types(nb::module_& m) {
  nb::exception<superdex::Error> error_type(m, "Error", PyExc_RuntimeError);
  // Messages quote file contents, which need not be UTF-8 (a malformed file's bytes): decode
  // them with replacement characters instead of failing with a UnicodeDecodeError. Translators
  // registered later are tried first, so this one replaces nanobind's default for Error.
  nb::register_exception_translator(
      [](const std::exception_ptr& p, void* type) {
        try {
          std::rethrow_exception(p);
        } catch (const superdex::Error& e) {
          const char* what = e.what();
          PyObject* message = PyUnicode_DecodeUTF8(what, static_cast<Py_ssize_t>(std::strlen(what)), "replace");
          PyErr_SetObject(static_cast<PyObject*>(type), message);
          Py_XDECREF(message);
        }
      },
      error_type.ptr());

  nb::enum_<ActorType>(m, "ActorType")
      .value("RIGID", ActorType::Rigid).value("SOFT", ActorType::Soft)
      .value("ARTICULATED", ActorType::Articulated).value("LINK", ActorType::Link);
  nb::enum_<JointType>(m, "JointType")
      .value("HARD", JointType::Hard).value("FREE", JointType::Free).value("REVOLUTE", JointType::Revolute)
      .value("PRISMATIC", JointType::Prismatic).value("SPHERICAL", JointType::Spherical);
  nb::enum_<NumericalFaultPolicy>(m, "NumericalFaultPolicy",
                                  "What scene.step does when a body's next state is not finite or the solver does not converge.")
      .value("RAISE", NumericalFaultPolicy::Raise,
             "raise superdex.physics.Error naming the actor and quantity; the scene keeps its last good state (default)")
      .value("WARN_AND_CLAMP", NumericalFaultPolicy::WarnAndClamp,
             "warn (RuntimeWarning) and keep going: a faulty island's bodies keep their last good positions with zero "
             "velocity; an unconverged but finite result is kept");
  nb::class_<NumericalFault>(m, "NumericalFault", "A numerical fault that the last step clamped.")
      .def_ro("actor", &NumericalFault::actor, "handle of the rigid, articulated or soft actor")
      .def_ro("quantity", &NumericalFault::quantity, "\"positions\", \"velocities\", \"contact forces\", \"node positions\", ... or \"convergence\"")
      .def_ro("message", &NumericalFault::message)
      .def("__repr__", [](const NumericalFault& f) { return "NumericalFault(" + f.message + ")"; });
}

}  // namespace superdex::python
