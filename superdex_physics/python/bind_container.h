#pragma once
// The container types: DynamicArray<T> (an owning, resizable array: std::vector<T>) and the
// span views Span<T> / SpanConst<T> over contiguous elements. Elements of class type are handed
// out by reference from DynamicArray and mutable spans (so `arr[0].translation = ...` changes the
// array), by value from const spans; numbers are always values. Numeric arrays convert to numpy
// (np.array(a)); an array of Real3 becomes an (n, 3) array, an array of Color an (n, 4) uint8 one.

#include <nanobind/nanobind.h>
#include <nanobind/make_iterator.h>
#include <nanobind/ndarray.h>

#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "superdex/physics/error.h"
#include "superdex/physics/types.h"

namespace superdex::python {

namespace nb = nanobind;
using namespace physics;

/// A view of `size` contiguous elements; `owner` keeps them alive when the view owns a copy
/// (results the engine hands out), null when a Python object is kept alive instead (a span made
/// from a DynamicArray).
template <class T>
struct SpanOf {
  std::shared_ptr<void> owner;
  T* data = nullptr;
  size_t size = 0;

  static SpanOf owning(std::vector<std::remove_const_t<T>> values) {
    auto v = std::make_shared<std::vector<std::remove_const_t<T>>>(std::move(values));
    return SpanOf{v, v->data(), v->size()};
  }
};

namespace container_detail {

size_t wrap_index(long i, size_t n);

// How elements convert to numpy: scalars as 1-D arrays, fixed-size vectors as (n, N).
template <class T>
struct NumpyShape {
  static constexpr bool numeric = std::is_arithmetic_v<T> && !std::is_same_v<T, bool>;
  static constexpr size_t cols = 0;
  using Scalar = T;
};
template <class S, int N>
struct NumpyShape<Eigen::Matrix<S, N, 1>> {
  static constexpr bool numeric = true;
  static constexpr size_t cols = N;
  using Scalar = S;
};

// colours as (n, 4) arrays of uint8 (r, g, b, a)
template <>
struct NumpyShape<Color> {
  static constexpr bool numeric = true;
  static constexpr size_t cols = 4;
  using Scalar = std::uint8_t;
};

template <class T>
nb::object to_numpy(const T* data, size_t n, nb::handle owner, nb::handle dtype, nb::handle copy, bool writable) {
  using NS = NumpyShape<std::remove_const_t<T>>;
  using S = typename NS::Scalar;
  size_t shape[2] = {n, NS::cols};
  nb::object a;
  if (writable) a = nb::cast(nb::ndarray<nb::numpy, S>(const_cast<S*>(reinterpret_cast<const S*>(data)), NS::cols ? 2 : 1, shape, owner),
                             nb::rv_policy::reference);
  else a = nb::cast(nb::ndarray<nb::numpy, const S>(reinterpret_cast<const S*>(data), NS::cols ? 2 : 1, shape, owner),
                    nb::rv_policy::reference);
  if (!dtype.is_none()) a = a.attr("astype")(dtype);
  else if (!copy.is_none() && nb::cast<bool>(copy)) a = a.attr("copy")();
  return a;
}

// str() of one element: numbers as Python prints them, other elements by their own str().
template <class T>
std::string element_text(const T& x) {
  return nb::cast<std::string>(nb::str(nb::cast(x)));
}

template <class E, class Seq>
std::string sequence_text(const Seq& items, size_t n) {
  std::string s = "[";
  for (size_t i = 0; i < n; ++i) s += (i ? ", " : "") + element_text(E(items[i]));
  return s + "]";
}

}  // namespace container_detail

/// Binds std::vector<T> as `name` (a DynamicArray).
template <class T>
nb::class_<std::vector<T>> bind_dynamic_array(nb::handle scope, const char* name) {
  using Vec = std::vector<T>;
  using namespace container_detail;
  constexpr bool by_reference = std::is_class_v<T> && !std::is_same_v<T, std::string>;
  nb::class_<Vec> c(scope, name, "An owning, resizable array.");
  c.def(nb::init<>())
      .def("__init__", [](Vec* self, long size, const T& value) {
             if (size < 0) throw Error(std::string("size must be >= 0, got ") + std::to_string(size));
             new (self) Vec(static_cast<size_t>(size), value);
           }, nb::arg("size"), nb::arg("value") = T())
      .def("__init__", [](Vec* self, const Vec& other) { new (self) Vec(other); }, nb::arg("sequence"))
      .def("__init__", [](Vec* self, nb::iterable items) {
             new (self) Vec();
             for (nb::handle h : items) self->push_back(nb::cast<T>(h));
           }, nb::arg("sequence"))
      .def("__len__", [](const Vec& v) { return v.size(); })
      .def("__bool__", [](const Vec& v) { return !v.empty(); })
      .def("__setitem__", [](Vec& v, long i, const T& x) { v[wrap_index(i, v.size())] = x; })
      .def("append", [](Vec& v, const T& x) { v.push_back(x); }, nb::arg("value"))
      .def("extend", [](Vec& v, nb::iterable items) {
             Vec added;
             for (nb::handle h : items) added.push_back(nb::cast<T>(h));
             v.insert(v.end(), added.begin(), added.end());
           }, nb::arg("values"))
      .def("clear", [](Vec& v) { v.clear(); })
      .def("empty", [](const Vec& v) { return v.empty(); })
      .def("size", [](const Vec& v) { return v.size(); })
      .def("reserve", [](Vec& v, size_t n) { v.reserve(n); }, nb::arg("capacity"))
      .def("capacity", [](const Vec& v) { return v.capacity(); })
      .def("resize", [](Vec& v, size_t n, const T& value) { v.resize(n, value); }, nb::arg("size"), nb::arg("value") = T())
      .def("tolist", [](const Vec& v) {
             nb::list l;
             for (size_t i = 0; i < v.size(); ++i) l.append(nb::cast(T(v[i]), nb::rv_policy::move));
             return l;
           })
      .def("__str__", [](const Vec& v) { return sequence_text<T>(v, v.size()); })
      .def("__repr__", [name](const Vec& v) { return std::string(name) + "(" + sequence_text<T>(v, v.size()) + ")"; })
      .def("__copy__", [](const Vec& v) { return Vec(v); })
      .def("__deepcopy__", [](const Vec& v, nb::handle) { return Vec(v); }, nb::arg("memo"))
      .def("__getstate__", [](const Vec& v) {
             nb::list l;
             for (size_t i = 0; i < v.size(); ++i) l.append(nb::cast(T(v[i]), nb::rv_policy::move));
             return l;
           })
      .def("__setstate__", [](Vec& self, nb::list items) {
             new (&self) Vec();
             for (nb::handle h : items) self.push_back(nb::cast<T>(h));
           });
  if constexpr (by_reference) {
    c.def("__getitem__", [](Vec& v, long i) -> T& { return v[wrap_index(i, v.size())]; }, nb::rv_policy::reference_internal)
        .def("__iter__", [](Vec& v) { return nb::make_iterator<nb::rv_policy::reference_internal>(nb::type<Vec>(), "iterator", v.begin(), v.end()); },
             nb::keep_alive<0, 1>());
  } else {
    c.def("__getitem__", [](const Vec& v, long i) { return T(v[wrap_index(i, v.size())]); })
        .def("__iter__", [](const Vec& v) {
               nb::list l;
               for (size_t i = 0; i < v.size(); ++i) l.append(nb::cast(T(v[i])));
               return nb::iter(l);
             });
  }
  if constexpr (requires(const T& a, const T& b) { a == b; }) {
    c.def("__eq__", [](const Vec& a, const Vec& b) { return a == b; }, nb::is_operator())
        .def("__ne__", [](const Vec& a, const Vec& b) { return !(a == b); }, nb::is_operator());
  }
  if constexpr (NumpyShape<T>::numeric) {
    c.def("__array__", [](nb::handle self, nb::handle dtype, nb::handle copy) {
           Vec& v = nb::cast<Vec&>(self);
           return to_numpy(v.data(), v.size(), self, dtype, copy, true);
         }, nb::arg("dtype").none() = nb::none(), nb::arg("copy").none() = nb::none());
  }
  // lists, tuples and arrays convert implicitly where a DynamicArray is expected
  nb::implicitly_convertible<nb::list, Vec>();
  nb::implicitly_convertible<nb::tuple, Vec>();
  if constexpr (NumpyShape<T>::numeric) nb::implicitly_convertible<nb::ndarray<>, Vec>();
  return c;
}

/// Binds SpanOf<T> (mutable: `name` is SpanX) or SpanOf<const T> (SpanConstX). A span can be made
/// from a DynamicArray of the same element type, which it keeps alive.
template <class T>
nb::class_<SpanOf<T>> bind_span(nb::handle scope, const char* name) {
  using Span = SpanOf<T>;
  using E = std::remove_const_t<T>;
  using Vec = std::vector<E>;
  using namespace container_detail;
  constexpr bool is_const = std::is_const_v<T>;
  constexpr bool by_reference = std::is_class_v<E> && !std::is_same_v<E, std::string> && !is_const;
  nb::class_<Span> c(scope, name, is_const ? "A read-only view of contiguous elements." : "A view of contiguous elements.");
  c.def("__init__", [](Span* self, Vec& v) { new (self) Span{nullptr, v.data(), v.size()}; }, nb::arg("array"), nb::keep_alive<1, 2>())
      .def("__len__", [](const Span& s) { return s.size; })
      .def("__bool__", [](const Span& s) { return s.size > 0; })
      .def("size", [](const Span& s) { return s.size; })
      .def("empty", [](const Span& s) { return s.size == 0; })
      .def("tolist", [](const Span& s) {
             nb::list l;
             for (size_t i = 0; i < s.size; ++i) l.append(nb::cast(E(s.data[i]), nb::rv_policy::move));
             return l;
           })
      .def("__str__", [](const Span& s) { return sequence_text<E>(s.data, s.size); })
      .def("__repr__", [name](const Span& s) { return std::string(name) + "(" + sequence_text<E>(s.data, s.size) + ")"; })
      // a span pickles as a list of its elements (what it views does not travel)
      .def("__reduce__", [](const Span& s) {
        nb::list l;
        for (size_t i = 0; i < s.size; ++i) l.append(nb::cast(E(s.data[i]), nb::rv_policy::move));
        return nb::make_tuple(nb::module_::import_("builtins").attr("list"), nb::make_tuple(l));
      })
      .def("__copy__", [](const Span& s) { return Vec(s.data, s.data + s.size); })
      .def("__deepcopy__", [](const Span& s, nb::handle) { return Vec(s.data, s.data + s.size); }, nb::arg("memo"));
  if constexpr (by_reference) {
    c.def("__getitem__", [](Span& s, long i) -> E& { return s.data[wrap_index(i, s.size)]; }, nb::rv_policy::reference_internal)
        .def("__iter__", [](Span& s) { return nb::make_iterator<nb::rv_policy::reference_internal>(nb::type<Span>(), "iterator", s.data, s.data + s.size); },
             nb::keep_alive<0, 1>());
  } else {
    c.def("__getitem__", [](const Span& s, long i) { return E(s.data[wrap_index(i, s.size)]); })
        .def("__iter__", [](const Span& s) {
               nb::list l;
               for (size_t i = 0; i < s.size; ++i) l.append(nb::cast(E(s.data[i]), nb::rv_policy::move));
               return nb::iter(l);
             });
  }
  if constexpr (!is_const) {
    c.def("__setitem__", [](Span& s, long i, const E& x) { s.data[wrap_index(i, s.size)] = x; });
  }
  // a span converts to a DynamicArray of its element type where one is expected (when bound)
  if (nb::type<Vec>().is_valid()) nb::implicitly_convertible<Span, Vec>();
  if constexpr (NumpyShape<E>::numeric) {
    c.def("__array__", [](nb::handle self, nb::handle dtype, nb::handle copy) {
           Span& s = nb::cast<Span&>(self);
           return to_numpy(s.data, s.size, self, dtype, copy, !is_const);
         }, nb::arg("dtype").none() = nb::none(), nb::arg("copy").none() = nb::none());
  }
  return c;
}

}  // namespace superdex::python
