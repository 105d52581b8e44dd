#pragma once
// Binds a plain C++ struct as a Python class in SuperDex's style: every field readable and
// writable by name, a constructor taking any fields by keyword with the rest at their C++
// defaults, `src=` copy construction (also positional), exact equality, copy.copy and
// copy.deepcopy, pickling (copies refused for structs of views), and a repr listing the fields.
// Nested structs and arrays are returned by reference, so `params.contact.penalty_coefficient = x`
// changes `params`. A struct deriving from a bound struct (StructBinder<Derived, Base>) is a Python
// subclass of it whose constructor takes the base's keywords first, then its own.

#include <nanobind/nanobind.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include <functional>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <string>
#include <vector>

namespace superdex::python {

namespace nb = nanobind;

/// The named fields of a bound class, each with a setter taking any Python value: what keyword
/// construction, pickling and repr need (shared by StructBinder and the view binders).
template <class Obj>
struct BinderFields {
  std::string type_name;
  std::vector<std::string> names;
  std::vector<std::function<void(Obj&, nb::handle)>> setters;

  size_t index(const std::string& n) const {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == n) return i;
    return names.size();
  }
  /// Sets the fields given by keyword.
  void apply(Obj& self, nb::kwargs kwargs) const {
    for (auto [key, value] : kwargs) {
      const std::string k = nb::cast<std::string>(key);
      const size_t i = index(k);
      if (i == names.size()) throw nb::type_error((type_name + "(): unexpected keyword argument '" + k + "'").c_str());
      try {
        setters[i](self, value);
      } catch (const nb::cast_error&) {
        // nanobind's bare std::bad_cast would name neither the field nor the value
        throw nb::type_error((type_name + "(): " + k + ": cannot be set from a value of type " +
                              nb::inst_name(value).c_str()).c_str());
      }
    }
  }
  /// "Type(field=repr, ...)".
  std::string repr(nb::handle self) const {
    std::string s = type_name + "(";
    for (size_t i = 0; i < names.size(); ++i) {
      if (i) s += ", ";
      s += names[i] + "=" + nb::cast<std::string>(nb::repr(self.attr(names[i].c_str())));
    }
    return s + ")";
  }
};

/// The fields of each struct bound with StructBinder, kept so that a derived struct's binder
/// can take them over (one registry per type and build).
template <class T>
std::shared_ptr<BinderFields<T>>& bound_fields() {
  static std::shared_ptr<BinderFields<T>> fields;
  return fields;
}

/// `Base = void`: a plain struct; otherwise T derives from the bound struct Base.
template <class T, class Base = void>
class StructBinder {
 public:
  using Setter = std::function<void(T&, nb::handle)>;
  using Class = std::conditional_t<std::is_void_v<Base>, nb::class_<T>, nb::class_<T, std::conditional_t<std::is_void_v<Base>, T, Base>>>;

  StructBinder(nb::handle scope, const char* name, const char* doc)
      : cls_(scope, name, doc), fields_(std::make_shared<Fields>()) {
    fields_->type_name = name;
    bound_fields<T>() = fields_;
    if constexpr (!std::is_void_v<Base>) {
      // the base's fields, set on the base part of T
      const std::shared_ptr<BinderFields<Base>> base = bound_fields<Base>();
      if (!base) throw std::logic_error(std::string(name) + ": its base struct must be bound first");
      for (size_t i = 0; i < base->names.size(); ++i) {
        fields_->names.push_back(base->names[i]);
        fields_->setters.push_back([set = base->setters[i]](T& t, nb::handle v) { set(static_cast<Base&>(t), v); });
      }
    }
  }

  /// A read-write field. Python values convert as for a function argument (implicitly from
  /// lists where the field is a Real3, a DynamicArray, ...).
  template <class F>
  StructBinder& field(const char* name, F T::*member, const char* doc = "") {
    cls_.def_rw(name, member, doc);
    fields_->names.push_back(name);
    fields_->setters.push_back([member](T& t, nb::handle v) { t.*member = nb::cast<F>(v); });
    return *this;
  }

  /// A field read and written through accessors (a validated or derived value).
  template <class Get, class Set>
  StructBinder& property(const char* name, Get get, Set set, const char* doc = "") {
    cls_.def_prop_rw(name, get, set, doc);
    fields_->names.push_back(name);
    fields_->setters.push_back([set](T& t, nb::handle v) {
      using Arg = std::decay_t<typename FirstArgOf<decltype(&Set::operator())>::type>;
      set(t, nb::cast<Arg>(v));
    });
    return *this;
  }

  /// A std::vector field read as a read-only span of the struct's elements (SpanConstX, which
  /// keeps the struct alive) and written from any array-like of elements (needs bind_container.h).
  template <class E>
  StructBinder& span_field(const char* name, std::vector<E> T::*member, const char* doc = "") {
    cls_.def_prop_rw(
        name, [member](const T& t) { return SpanOf<const E>{nullptr, (t.*member).data(), (t.*member).size()}; },
        [member](T& t, const std::vector<E>& v) { t.*member = v; }, nb::for_getter(nb::keep_alive<0, 1>()), doc);
    fields_->names.push_back(name);
    fields_->setters.push_back([member](T& t, nb::handle v) { t.*member = nb::cast<std::vector<E>>(v); });
    return *this;
  }

  Class& cls() { return cls_; }

  /// Adds the constructor, equality (when `comparable`: T has ==; otherwise a base's is inherited), copies and pickling (when `copyable`;
  /// otherwise copy.copy, copy.deepcopy and pickling raise TypeError: a struct of views) and repr.
  Class& done(bool comparable = true, bool copyable = true) {
    std::shared_ptr<Fields> f = fields_;
    // `src=` first: the keyword form would take `src` for an unknown field
    if (copyable) cls_.def("__init__", [](T* self, const T& src) { new (self) T(src); }, nb::arg("src"));
    cls_.def("__init__", [f](T* self, nb::kwargs kwargs) {
          // built aside, so that a rejected keyword leaves no half-made instance behind
          T t;
          f->apply(t, kwargs);
          new (self) T(std::move(t));
        })
        .def("__repr__", [f](nb::handle self) { return f->repr(self); });
    if (copyable) {
      cls_.def("__copy__", [](const T& t) { return T(t); })
          .def("__deepcopy__", [](const T& t, nb::handle) { return T(t); }, nb::arg("memo"))
          .def("__getstate__", [f](nb::handle self) {
            nb::dict state;
            for (const std::string& n : f->names) state[n.c_str()] = self.attr(n.c_str());
            return state;
          })
          .def("__setstate__", [f](T& self, nb::dict state) {
            new (&self) T();
            for (auto [key, value] : state) f->setters[f->index(nb::cast<std::string>(key))](self, value);
          });
    } else {
      const std::string name = f->type_name;
      const auto refuse = [name] { throw nb::type_error((name + " holds views of buffers and cannot be copied").c_str()); };
      cls_.def("__copy__", [refuse](const T&) { refuse(); })
          .def("__deepcopy__", [refuse](const T&, nb::handle) { refuse(); }, nb::arg("memo"))
          .def("__reduce__", [refuse](const T&) { refuse(); });
    }
    if constexpr (requires(const T& a, const T& b) { a == b; }) {
      if (comparable) {
        cls_.def("__eq__", [](const T& a, const T& b) { return a == b; }, nb::is_operator())
            .def("__ne__", [](const T& a, const T& b) { return !(a == b); }, nb::is_operator());
      }
    }
    return cls_;
  }

 private:
  template <class M>
  struct FirstArgOf;
  template <class C, class R, class A0, class A1>
  struct FirstArgOf<R (C::*)(A0, A1) const> {
    using type = A1;
  };

  using Fields = BinderFields<T>;
  Class cls_;
  std::shared_ptr<Fields> fields_;
};

}  // namespace superdex::python
