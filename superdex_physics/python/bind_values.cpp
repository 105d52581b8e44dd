// Value types: Real2, Real3, Real4, Real6, Int2, Int3, Quaternion, TransformRT, Color and the
// volumes (Aabb, Obb; Sphere, Box and Plane are bound with the model types). Each converts implicitly from a sequence or numpy array
// of the right length, reads and writes by index, converts to numpy (np.array(v)) and lists,
// compares exactly, pickles and copies.

#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_text.h"
#include "superdex/physics/log.h"
#include "superdex/physics/types.h"

namespace superdex::python {

namespace {

size_t checked_index(long i, size_t n) {
  if (i < 0) i += static_cast<long>(n);
  if (i < 0 || static_cast<size_t>(i) >= n) throw nb::index_error("index out of range");
  return static_cast<size_t>(i);
}

// Reads exactly N numbers from a sequence or array into v.
template <class V>
void read_exact(nb::handle src, V& v, const char* type_name) {
  using S = typename V::Scalar;
  constexpr int N = V::RowsAtCompileTime;
  if (PyList_Check(src.ptr()) || PyTuple_Check(src.ptr())) {
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(src.ptr());
    if (n != N) throw nb::type_error((std::string(type_name) + ": expected " + std::to_string(N) + " values, got " + std::to_string(n)).c_str());
    PyObject** items = PySequence_Fast_ITEMS(src.ptr());
    for (int i = 0; i < N; ++i) v[i] = nb::cast<S>(nb::handle(items[i]));
    return;
  }
  const size_t n = nb::len(src);
  if (n != N) throw nb::type_error((std::string(type_name) + ": expected " + std::to_string(N) + " values, got " + std::to_string(n)).c_str());
  for (int i = 0; i < N; ++i) v[i] = nb::cast<S>(src[i]);
}

// np.array(v): a copy in the build's scalar type, converted to `dtype` when one is asked for.
template <class S>
nb::object numpy_of(const S* data, size_t n, nb::handle dtype) {
  auto* copy = new std::vector<S>(data, data + n);
  nb::capsule owner(copy, [](void* p) noexcept { delete static_cast<std::vector<S>*>(p); });
  const size_t shape[1] = {n};
  nb::object a = nb::cast(nb::ndarray<nb::numpy, S>(copy->data(), 1, shape, owner), nb::rv_policy::automatic);
  if (!dtype.is_none()) a = a.attr("astype")(dtype);
  return a;
}

template <class V>
nb::list list_of(const V& v) {
  nb::list l;
  for (int i = 0; i < static_cast<int>(v.size()); ++i) l.append(v[i]);
  return l;
}

// The members every fixed-size vector type shares; arithmetic is added for real vectors.
template <class V>
nb::class_<V> bind_fixed_vector(nb::module_& m, const char* name, const char* doc) {
  using S = typename V::Scalar;
  constexpr int N = V::RowsAtCompileTime;
  nb::class_<V> c(m, name, doc);
  c.def("__init__", [](V* self) { new (self) V(V::Zero()); })
      .def("__init__", [name](V* self, nb::handle values) {
             V v;
             read_exact(values, v, name);
             new (self) V(v);
           }, "values"_a)
      .def("__len__", [](const V&) { return N; })
      .def("__getitem__", [](const V& v, long i) { return v[checked_index(i, N)]; })
      .def("__setitem__", [](V& v, long i, S x) { v[checked_index(i, N)] = x; })
      .def("__iter__", [](const V& v) { return nb::iter(list_of(v)); })
      .def("__eq__", [](const V& a, const V& b) { return a == b; }, nb::is_operator())
      .def("__ne__", [](const V& a, const V& b) { return a != b; }, nb::is_operator())
      .def("__hash__", [](const V& v) {
             nb::tuple t = nb::tuple(list_of(v));
             return nb::hash(t);
           })
      .def("tolist", [](const V& v) { return list_of(v); })
      .def("__array__", [](const V& v, nb::handle dtype, nb::handle) { return numpy_of(v.data(), N, dtype); },
           "dtype"_a.none() = nb::none(), "copy"_a.none() = nb::none())
      .def("__str__", [](const V& v) { return vector_text(v); })
      .def("__repr__", [name](const V& v) {
             const std::string s = vector_text(v);
             return std::string(name) + "(" + s.substr(1, s.size() - 2) + ")";
           })
      .def("__copy__", [](const V& v) { return V(v); })
      .def("__deepcopy__", [](const V& v, nb::handle) { return V(v); }, "memo"_a)
      .def("__getstate__", [](const V& v) { return nb::tuple(list_of(v)); })
      .def("__setstate__", [name](V& self, nb::tuple state) {
             V v;
             read_exact(state, v, name);
             new (&self) V(v);
           });
  // sequences and arrays of N numbers convert implicitly (a list passed where a Real3 is expected)
  nb::implicitly_convertible<std::array<S, N>, V>();
  return c;
}

// Element-wise arithmetic with vectors of the same type and with scalars, both ways, in place too.
template <class V>
void add_arithmetic(nb::class_<V>& c) {
  using S = typename V::Scalar;
  c.def("__add__", [](const V& a, const V& b) { return V(a + b); }, nb::is_operator())
      .def("__add__", [](const V& a, S s) { return V(a.array() + s); }, nb::is_operator())
      .def("__radd__", [](const V& a, S s) { return V(s + a.array()); }, nb::is_operator())
      .def("__sub__", [](const V& a, const V& b) { return V(a - b); }, nb::is_operator())
      .def("__sub__", [](const V& a, S s) { return V(a.array() - s); }, nb::is_operator())
      .def("__rsub__", [](const V& a, S s) { return V(s - a.array()); }, nb::is_operator())
      .def("__mul__", [](const V& a, const V& b) { return V(a.cwiseProduct(b)); }, nb::is_operator())
      .def("__mul__", [](const V& a, S s) { return V(a * s); }, nb::is_operator())
      .def("__rmul__", [](const V& a, S s) { return V(s * a); }, nb::is_operator())
      .def("__truediv__", [](const V& a, const V& b) { return V(a.cwiseQuotient(b)); }, nb::is_operator())
      .def("__truediv__", [](const V& a, S s) { return V(a / s); }, nb::is_operator())
      .def("__rtruediv__", [](const V& a, S s) { return V(s / a.array()); }, nb::is_operator())
      .def("__neg__", [](const V& a) { return V(-a); }, nb::is_operator())
      .def("__iadd__", [](V& a, const V& b) -> V& { a += b; return a; }, nb::is_operator(), nb::rv_policy::none)
      .def("__iadd__", [](V& a, S s) -> V& { a.array() += s; return a; }, nb::is_operator(), nb::rv_policy::none)
      .def("__isub__", [](V& a, const V& b) -> V& { a -= b; return a; }, nb::is_operator(), nb::rv_policy::none)
      .def("__isub__", [](V& a, S s) -> V& { a.array() -= s; return a; }, nb::is_operator(), nb::rv_policy::none)
      .def("__imul__", [](V& a, const V& b) -> V& { a = a.cwiseProduct(b).eval(); return a; }, nb::is_operator(), nb::rv_policy::none)
      .def("__imul__", [](V& a, S s) -> V& { a *= s; return a; }, nb::is_operator(), nb::rv_policy::none)
      .def("__itruediv__", [](V& a, const V& b) -> V& { a = a.cwiseQuotient(b).eval(); return a; }, nb::is_operator(), nb::rv_policy::none)
      .def("__itruediv__", [](V& a, S s) -> V& { a /= s; return a; }, nb::is_operator(), nb::rv_policy::none)
      .def("dot", [](const V& a, const V& b) { return a.dot(b); }, "other"_a)
      .def("norm", [](const V& a) { return a.norm(); }, "Euclidean length.");
}

Quaternion quaternion_of(const Real4& v) { return Quaternion(v[3], v[0], v[1], v[2]); }

// Warns (log channel Warning) when a transform is built from a rotation that is not a unit
// quaternion: it is kept as given, and transforms points scaled by its squared norm.
void warn_if_not_unit(const Quaternion& q, const char* where) {
  const real n = q.norm();
  if (std::abs(n - 1) > real(1e-3))
    physics::log_warning(std::string(where) + ": rotation " + vector_text(q.coeffs()) + " is not a unit quaternion (norm " +
                         number_text(n) + ")");
}

// One channel of a Color, or superdex.physics.Error naming it.
std::uint8_t color_channel(long value, const char* name) {
  if (value < 0 || value > 255) throw Error(std::string("Color: ") + name + " must be in [0, 255], got " + std::to_string(value));
  return static_cast<std::uint8_t>(value);
}

nb::list color_list(const Color& c) {
  nb::list l;
  for (int v : {c.r, c.g, c.b, c.a}) l.append(v);
  return l;
}

std::string transform_text(const TransformRT& t) {
  nlohmann::json j;
  j["rotation"] = vector_json(t.rotation.coeffs());
  j["translation"] = vector_json(t.translation);
  return j.dump();
}

}  // namespace

void export_values(nb::module_& m) {
  auto real2 = bind_fixed_vector<Real2>(m, "Real2", "Two reals.");
  add_arithmetic(real2);
  real2.def("__init__", [](Real2* self, real x, real y) { new (self) Real2(x, y); }, "x"_a, "y"_a);
  auto real3 = bind_fixed_vector<Real3>(m, "Real3", "Three reals: a point or vector (m, m/s, N, ... as the API says).");
  add_arithmetic(real3);
  real3.def("__init__", [](Real3* self, real x, real y, real z) { new (self) Real3(x, y, z); }, "x"_a, "y"_a, "z"_a)
      .def("cross", [](const Real3& a, const Real3& b) { return Real3(a.cross(b)); }, "other"_a);
  auto real4 = bind_fixed_vector<Real4>(m, "Real4", "Four reals.");
  add_arithmetic(real4);
  real4.def("__init__", [](Real4* self, real x, real y, real z, real w) { new (self) Real4(x, y, z, w); }, "x"_a, "y"_a, "z"_a, "w"_a);
  auto real6 = bind_fixed_vector<Real6>(m, "Real6", "Six reals (a symmetric 3 x 3 matrix as xx, xy, xz, yy, yz, zz).");
  add_arithmetic(real6);
  real6.def("__init__", [](Real6* self, real a, real b, real c, real d, real e, real f) {
          new (self) Real6();
          *self << a, b, c, d, e, f;
        }, "v0"_a, "v1"_a, "v2"_a, "v3"_a, "v4"_a, "v5"_a);
  bind_fixed_vector<Int2>(m, "Int2", "Two integers.")
      .def("__init__", [](Int2* self, int x, int y) { new (self) Int2(x, y); }, "x"_a, "y"_a);
  bind_fixed_vector<Int3>(m, "Int3", "Three integers (grid dimensions).")
      .def("__init__", [](Int3* self, int x, int y, int z) { new (self) Int3(x, y, z); }, "x"_a, "y"_a, "z"_a);

  nb::class_<Quaternion>(m, "Quaternion", "A rotation as a quaternion; indexed x, y, z, w. Default: the identity.")
      .def("__init__", [](Quaternion* self) { new (self) Quaternion(Quaternion::Identity()); })
      .def("__init__", [](Quaternion* self, real x, real y, real z, real w) { new (self) Quaternion(w, x, y, z); },
           "x"_a, "y"_a, "z"_a, "w"_a)
      .def("__init__", [](Quaternion* self, nb::handle values) {
             Real4 v;
             read_exact(values, v, "Quaternion");
             new (self) Quaternion(quaternion_of(v));
           }, "values"_a)
      .def_static("identity", [] { return Quaternion(Quaternion::Identity()); })
      .def_static("zero", [] { return Quaternion(0, 0, 0, 0); })
      .def_static("from_axis_angle", [](const Real3& axis, real angle) {
             if (!axis.allFinite() || axis.norm() == 0) throw Error("Quaternion.from_axis_angle: axis must be a finite, non-zero vector");
             return Quaternion(Eigen::AngleAxis<real>(angle, axis.normalized()));
           }, "axis"_a, "angle"_a, "Rotation of `angle` (rad) about `axis` (any length).")
      .def_static("from_rotation_vector", [](const Real3& v) {
             const real angle = v.norm();
             if (angle == 0) return Quaternion(Quaternion::Identity());
             return Quaternion(Eigen::AngleAxis<real>(angle, v / angle));
           }, "rotation_vector"_a, "Rotation about v / |v| by |v| (rad).")
      .def_static("rotation_x", [](real a) { return Quaternion(Eigen::AngleAxis<real>(a, Real3::UnitX())); }, "angle"_a)
      .def_static("rotation_y", [](real a) { return Quaternion(Eigen::AngleAxis<real>(a, Real3::UnitY())); }, "angle"_a)
      .def_static("rotation_z", [](real a) { return Quaternion(Eigen::AngleAxis<real>(a, Real3::UnitZ())); }, "angle"_a)
      .def("to_rotation_vector", [](const Quaternion& q) {
             const Eigen::AngleAxis<real> aa(q.normalized());
             return Real3(aa.angle() * aa.axis());
           }, "The rotation vector (axis times angle, rad) of the normalised rotation.")
      .def("conjugate", [](const Quaternion& q) { return Quaternion(q.conjugate()); })
      .def("inverse", [](const Quaternion& q) { return Quaternion(q.inverse()); })
      .def("norm", [](const Quaternion& q) { return q.norm(); })
      .def("rotate", [](const Quaternion& q, const Real3& v) { return Real3(q * v); }, "vector"_a,
           "The vector rotated by this (unit) rotation.")
      .def("__len__", [](const Quaternion&) { return 4; })
      .def("__getitem__", [](const Quaternion& q, long i) { return q.coeffs()[checked_index(i, 4)]; })
      .def("__setitem__", [](Quaternion& q, long i, real x) { q.coeffs()[checked_index(i, 4)] = x; })
      .def("__iter__", [](const Quaternion& q) { return nb::iter(list_of(Real4(q.coeffs()))); })
      .def("tolist", [](const Quaternion& q) { return list_of(Real4(q.coeffs())); })
      .def("__array__", [](const Quaternion& q, nb::handle dtype, nb::handle) { return numpy_of(q.coeffs().data(), 4, dtype); },
           "dtype"_a.none() = nb::none(), "copy"_a.none() = nb::none())
      .def("__eq__", [](const Quaternion& a, const Quaternion& b) { return a.coeffs() == b.coeffs(); }, nb::is_operator())
      .def("__ne__", [](const Quaternion& a, const Quaternion& b) { return a.coeffs() != b.coeffs(); }, nb::is_operator())
      .def("__hash__", [](const Quaternion& q) { return nb::hash(nb::tuple(list_of(Real4(q.coeffs())))); })
      .def("__add__", [](const Quaternion& a, const Quaternion& b) { return Quaternion(Real4(a.coeffs() + b.coeffs())); }, nb::is_operator())
      .def("__sub__", [](const Quaternion& a, const Quaternion& b) { return Quaternion(Real4(a.coeffs() - b.coeffs())); }, nb::is_operator())
      .def("__neg__", [](const Quaternion& a) { return Quaternion(Real4(-a.coeffs())); }, nb::is_operator())
      .def("__mul__", [](const Quaternion& a, const Quaternion& b) { return Quaternion(a * b); }, nb::is_operator(),
           "Hamilton product: the rotation b, then a.")
      .def("__mul__", [](const Quaternion& a, real s) { return Quaternion(Real4(a.coeffs() * s)); }, nb::is_operator())
      .def("__mul__", [](const Quaternion& a, const Real3& v) { return Real3(a * v); }, nb::is_operator())
      .def("__rmul__", [](const Quaternion& a, real s) { return Quaternion(Real4(s * a.coeffs())); }, nb::is_operator())
      .def("__truediv__", [](const Quaternion& a, real s) { return Quaternion(Real4(a.coeffs() / s)); }, nb::is_operator())
      .def("__str__", [](const Quaternion& q) { return vector_text(q.coeffs()); })
      .def("__repr__", [](const Quaternion& q) {
             const std::string s = vector_text(q.coeffs());
             return "Quaternion(" + s.substr(1, s.size() - 2) + ")";
           })
      .def("__copy__", [](const Quaternion& q) { return Quaternion(q); })
      .def("__deepcopy__", [](const Quaternion& q, nb::handle) { return Quaternion(q); }, "memo"_a)
      .def("__getstate__", [](const Quaternion& q) { return nb::tuple(list_of(Real4(q.coeffs()))); })
      .def("__setstate__", [](Quaternion& self, nb::tuple state) {
             Real4 v;
             read_exact(state, v, "Quaternion");
             new (&self) Quaternion(quaternion_of(v));
           });
  nb::implicitly_convertible<std::array<real, 4>, Quaternion>();

  m.def("normalize", [](const Real2& v) { return Real2(v.normalized()); }, "v"_a);
  m.def("normalize", [](const Real3& v) { return Real3(v.normalized()); }, "v"_a);
  m.def("normalize", [](const Quaternion& q) { return Quaternion(q.normalized()); }, "q"_a,
        "The vector or quaternion divided by its length (unchanged when zero).");

  nb::class_<TransformRT>(m, "TransformRT", "A rigid transform X_AB: p_A = rotation * p_B + translation (m).")
      .def("__init__", [](TransformRT* self, const Quaternion& rotation, const Real3& translation) {
             warn_if_not_unit(rotation, "TransformRT");
             new (self) TransformRT{rotation, translation};
           }, "rotation"_a = Quaternion(Quaternion::Identity()), "translation"_a = Real3(Real3::Zero()))
      .def("__init__", [](TransformRT* self, const Real3& translation) { new (self) TransformRT{Quaternion::Identity(), translation}; },
           "translation"_a)
      .def_static("identity", [] { return TransformRT{}; })
      .def_rw("rotation", &TransformRT::rotation)
      .def_rw("translation", &TransformRT::translation)
      .def("inverse", [](const TransformRT& X) { return X.inverse(); }, "X_BA from X_AB.")
      .def("__mul__", [](const TransformRT& a, const TransformRT& b) { return compose(a, b); }, nb::is_operator(),
           "Composition: X_AB * X_BC = X_AC.")
      .def("__mul__", [](const TransformRT& a, const Real3& p) { return Real3(a * p); }, nb::is_operator(),
           "The point p_B mapped into frame A.")
      .def("__imul__", [](TransformRT& a, const TransformRT& b) -> TransformRT& {
             a = compose(a, b);
             return a;
           }, nb::is_operator(), nb::rv_policy::none)
      .def("__eq__", [](const TransformRT& a, const TransformRT& b) { return a == b; }, nb::is_operator())
      .def("__ne__", [](const TransformRT& a, const TransformRT& b) { return !(a == b); }, nb::is_operator())
      .def("__str__", &transform_text)
      .def("__repr__", [](const TransformRT& t) { return "TransformRT(" + transform_text(t) + ")"; })
      .def("__copy__", [](const TransformRT& t) { return TransformRT(t); })
      .def("__deepcopy__", [](const TransformRT& t, nb::handle) { return TransformRT(t); }, "memo"_a)
      .def("__getstate__", [](const TransformRT& t) { return nb::make_tuple(t.rotation, t.translation); })
      .def("__setstate__", [](TransformRT& self, nb::tuple s) {
             new (&self) TransformRT{nb::cast<Quaternion>(s[0]), nb::cast<Real3>(s[1])};
           });

  nb::class_<Color>(m, "Color", "An RGBA colour, 8 bits a channel (0 to 255); default: opaque white. Indexed r, g, b, a.")
      .def("__init__", [](Color* self, long r, long g, long b, long a) {
             new (self) Color{color_channel(r, "r"), color_channel(g, "g"), color_channel(b, "b"), color_channel(a, "a")};
           }, "r"_a = 255, "g"_a = 255, "b"_a = 255, "a"_a = 255)
      .def_prop_rw("r", [](const Color& c) { return int(c.r); }, [](Color& c, long v) { c.r = color_channel(v, "r"); })
      .def_prop_rw("g", [](const Color& c) { return int(c.g); }, [](Color& c, long v) { c.g = color_channel(v, "g"); })
      .def_prop_rw("b", [](const Color& c) { return int(c.b); }, [](Color& c, long v) { c.b = color_channel(v, "b"); })
      .def_prop_rw("a", [](const Color& c) { return int(c.a); }, [](Color& c, long v) { c.a = color_channel(v, "a"); })
      .def("__len__", [](const Color&) { return 4; })
      .def("__getitem__", [](const Color& c, long i) { return int((&c.r)[checked_index(i, 4)]); })
      .def("__iter__", [](const Color& c) { return nb::iter(color_list(c)); })
      .def("tolist", &color_list)
      .def("__array__", [](const Color& c, nb::handle dtype, nb::handle) { return numpy_of(&c.r, 4, dtype); },
           "dtype"_a.none() = nb::none(), "copy"_a.none() = nb::none())
      .def("__eq__", [](const Color& a, const Color& b) { return a == b; }, nb::is_operator())
      .def("__ne__", [](const Color& a, const Color& b) { return !(a == b); }, nb::is_operator())
      .def("__hash__", [](const Color& c) { return nb::hash(nb::tuple(color_list(c))); })
      .def("__repr__", [](const Color& c) {
             return "Color(" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) + ", " + std::to_string(c.a) + ")";
           })
      .def("__copy__", [](const Color& c) { return Color(c); })
      .def("__deepcopy__", [](const Color& c, nb::handle) { return Color(c); }, "memo"_a)
      .def("__getstate__", [](const Color& c) { return nb::tuple(color_list(c)); })
      .def("__setstate__", [](Color& self, nb::tuple s) {
             new (&self) Color{color_channel(nb::cast<long>(s[0]), "r"), color_channel(nb::cast<long>(s[1]), "g"),
                               color_channel(nb::cast<long>(s[2]), "b"), color_channel(nb::cast<long>(s[3]), "a")};
           });

  nb::class_<Aabb>(m, "Aabb", "An axis-aligned box [min, max] (m), in the frame the API names.")
      .def("__init__", [](Aabb* self, const Real3& min, const Real3& max) { new (self) Aabb{min, max}; },
           "min"_a = Real3(Real3::Zero()), "max"_a = Real3(Real3::Zero()))
      .def_rw("min", &Aabb::min)
      .def_rw("max", &Aabb::max)
      .def("get_center", &Aabb::center)
      .def("get_size", &Aabb::size)
      .def("contains", &Aabb::contains, "point"_a)
      .def("__eq__", [](const Aabb& a, const Aabb& b) { return a == b; }, nb::is_operator())
      .def("__ne__", [](const Aabb& a, const Aabb& b) { return !(a == b); }, nb::is_operator())
      .def("__str__", [](const Aabb& a) {
             nlohmann::json j;
             j["min"] = vector_json(a.min);
             j["max"] = vector_json(a.max);
             return j.dump();
           })
      .def("__repr__", [](const Aabb& a) { return "Aabb(min=" + vector_text(a.min) + ", max=" + vector_text(a.max) + ")"; })
      .def("__copy__", [](const Aabb& a) { return Aabb(a); })
      .def("__deepcopy__", [](const Aabb& a, nb::handle) { return Aabb(a); }, "memo"_a)
      .def("__getstate__", [](const Aabb& a) { return nb::make_tuple(a.min, a.max); })
      .def("__setstate__", [](Aabb& self, nb::tuple s) { new (&self) Aabb{nb::cast<Real3>(s[0]), nb::cast<Real3>(s[1])}; });
  nb::class_<Obb>(m, "Obb", "An oriented box: transform places its centre and axes in the parent frame; half extents (m).")
      .def(nb::init<>())
      .def("__init__", [](Obb* self, const TransformRT& transform, const Real3& half_extents) { new (self) Obb{transform, half_extents}; },
           "transform"_a, "half_extents"_a)
      .def("get_center", &Obb::center)
      .def("get_half_extents", [](const Obb& o) { return o.half_extents; })
      .def("get_size", &Obb::size)
      .def("contains", &Obb::contains, "point"_a)
      .def("__repr__", [](const Obb& o) { return "Obb(center=" + vector_text(o.center()) + ", half_extents=" + vector_text(o.half_extents) + ")"; })
      .def("__str__", [](const Obb& o) { return "Obb(center=" + vector_text(o.center()) + ", half_extents=" + vector_text(o.half_extents) + ")"; });
}

}  // namespace superdex::python
