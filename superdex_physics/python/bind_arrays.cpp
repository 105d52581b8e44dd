// The array helpers shared by the binding files: numbers in, and out-parameters.

#include <climits>
#include <cstring>

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_container.h"

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
  if (nb::isinstance<SpanOf<real>>(out)) {
    auto& span = nb::cast<SpanOf<real>&>(out);
    if (span.size != n) throw Error(std::string(arg) + ": expected a SpanReal of length " + std::to_string(n) + ", got length " + std::to_string(span.size));
    return span.data;
  }
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
    if (a.ndim() == 1 && n > 1 && a.stride(0) != 1) got += ", not contiguous";
    throw Error(std::string(arg) + ": expected " + expect + ", got " + got + (a.dtype() != nb::dtype<real>() ? " with another dtype" : ""));
  }
  return static_cast<real*>(a.data());
}

void write_out(nb::handle out, std::span<const real> values, std::string_view arg) {
  real* dst = out_buffer(out, arg, values.size());
  std::copy(values.begin(), values.end(), dst);
}

nb::object fill_out(nb::handle out, const VecX& values, std::string_view arg) {
  if (out.is_none()) return nb::cast(numpy_copy(values));
  write_out(out, std::span<const real>(values.data(), static_cast<size_t>(values.size())), arg);
  return nb::borrow(out);
}

namespace {

// The elements behind an out-parameter of class elements: a DynamicArray or a mutable Span of
// exactly n elements.
template <class T>
T* out_elements(nb::handle out, std::string_view arg, size_t n, const char* type_name) {
  if (nb::isinstance<std::vector<T>>(out)) {
    auto& v = nb::cast<std::vector<T>&>(out);
    if (v.size() == n) return v.data();
    throw Error(std::string(arg) + ": expected a DynamicArray" + type_name + " of length " + std::to_string(n) + ", got length " +
                std::to_string(v.size()));
  }
  if (nb::isinstance<SpanOf<T>>(out)) {
    auto& span = nb::cast<SpanOf<T>&>(out);
    if (span.size == n) return span.data;
    throw Error(std::string(arg) + ": expected a Span" + type_name + " of length " + std::to_string(n) + ", got length " +
                std::to_string(span.size));
  }
  return nullptr;
}

}  // namespace

void write_out(nb::handle out, std::span<const TransformRT> values, std::string_view arg) {
  TransformRT* dst = out_elements<TransformRT>(out, arg, values.size(), "TransformRT");
  if (!dst)
    throw Error(std::string(arg) + ": expected a DynamicArrayTransformRT or SpanTransformRT of length " + std::to_string(values.size()) +
                ", got " + nb::inst_name(out).c_str());
  std::copy(values.begin(), values.end(), dst);
}

void write_out(nb::handle out, std::span<const Real2> values, std::string_view arg) {
  if (Real2* dst = out_elements<Real2>(out, arg, values.size(), "Real2")) {
    std::copy(values.begin(), values.end(), dst);
    return;
  }
  // a writable (n, 2) array of the build's dtype
  nb::ndarray<real, nb::shape<-1, 2>, nb::c_contig> a;
  if (nb::try_cast(out, a, false) && a.shape(0) == values.size()) {
    for (size_t i = 0; i < values.size(); ++i) a(i, 0) = values[i][0], a(i, 1) = values[i][1];
    return;
  }
  throw Error(std::string(arg) + ": expected a DynamicArrayReal2, a SpanReal2 or a writable " + real_dtype_name() + " array of shape (" +
              std::to_string(values.size()) + ", 2), got " + nb::inst_name(out).c_str());
}

void read_indices(nb::handle obj, std::string_view arg, std::vector<int>& out) {
  // a list or tuple of Python ints, without a conversion to numpy
  PyObject* o = obj.ptr();
  if (PyList_Check(o) || PyTuple_Check(o)) {
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(o);
    PyObject** items = PySequence_Fast_ITEMS(o);
    out.resize(n);
    bool all_ints = true;
    for (Py_ssize_t i = 0; i < n && all_ints; ++i) {
      int overflow = 0;
      const long k = PyLong_Check(items[i]) ? PyLong_AsLongAndOverflow(items[i], &overflow) : 0;
      all_ints = PyLong_Check(items[i]) && !overflow && k >= INT_MIN && k <= INT_MAX;
      out[i] = static_cast<int>(k);
    }
    if (all_ints) return;
  }
  if (nb::isinstance<std::vector<int>>(obj)) {
    out = nb::cast<std::vector<int>&>(obj);
    return;
  }
  if (nb::isinstance<SpanOf<const int>>(obj)) {
    auto& span = nb::cast<SpanOf<const int>&>(obj);
    out.assign(span.data, span.data + span.size);
    return;
  }
  const VecX v = read_vector(obj, arg);
  out.resize(v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]) || v[i] != std::floor(v[i]) || std::abs(v[i]) > INT_MAX)
      throw Error(std::string(arg) + "[" + std::to_string(i) + "]: expected an integer index, got " + std::to_string(v[i]));
    out[i] = static_cast<int>(v[i]);
  }
}

std::vector<int> read_indices(nb::handle obj, std::string_view arg) {
  std::vector<int> out;
  read_indices(obj, arg, out);
  return out;
}

std::vector<Real3> read_real3s(nb::handle obj, std::string_view arg) {
  if (nb::isinstance<std::vector<Real3>>(obj)) return nb::cast<std::vector<Real3>&>(obj);
  std::vector<Real3> out;
  // an (n, 3) array of numbers
  nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig> a;
  if (nb::try_cast(obj, a, true)) {
    out.resize(a.shape(0));
    for (size_t i = 0; i < out.size(); ++i) out[i] = Real3(real(a(i, 0)), real(a(i, 1)), real(a(i, 2)));
    return out;
  }
  if (!nb::try_cast(obj, out, true))
    throw Error(std::string(arg) + ": expected a sequence of Real3 (or an (n, 3) array), got " + nb::inst_name(obj).c_str());
  return out;
}

Transform read_transform(nb::handle obj, const std::string& arg) {
  if (obj.is_none()) return Transform{};
  TransformRT t;
  if (!nb::try_cast(obj, t)) throw Error(arg + ": expected a TransformRT");
  if (!t.translation.allFinite()) throw Error(arg + ".translation: must be finite");
  const Quat q = t.rotation;
  if (!q.coeffs().allFinite() || q.norm() < real(1e-6)) throw Error(arg + ".rotation: must be a finite, non-zero quaternion");
  return Transform{unit_quaternion(q), t.translation};
}

}  // namespace superdex::python
