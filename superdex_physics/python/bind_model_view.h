#pragma once
// View<Src>: the read-only views of model data the bindings hand out (MeshDataView, ...), kept
// alive by what owns their source, and the helpers that make them.

#include <memory>
#include <optional>

#include "bind_common.h"
#include "superdex/physics/model.h"

namespace superdex::python {

// A Python object kept alive from C++; released with the GIL held.
inline std::shared_ptr<void> hold(nb::handle obj) {
  PyObject* p = obj.ptr();
  Py_INCREF(p);
  return std::shared_ptr<void>(p, [](void* q) {
    nb::gil_scoped_acquire gil;
    Py_DECREF(static_cast<PyObject*>(q));
  });
}

// A read-only view of a Src owned elsewhere (`keep` keeps it alive) or by the view itself.
template <class Src>
struct View {
  std::shared_ptr<void> keep;
  const Src* source = nullptr;
  bool owned = false;  // `source` is the view's own copy

  View(std::shared_ptr<void> k, const Src* s, bool o) : keep(std::move(k)), source(s), owned(o) {}
  // A view of a default Src (what DynamicArrayXView(n) fills with): never a null source.
  View() : View(owning(Src{})) {}

  static View owning(Src value) {
    auto p = std::make_shared<Src>(std::move(value));
    return View(p, p.get(), true);
  }
  // A view of the part `part` of an object kept alive by `keep`.
  template <class Part>
  View<Part> child(const Part& part) const {
    return View<Part>(keep, &part, false);
  }
  // The view's own, writable copy of its values.
  Src& detach() {
    if (!owned) *this = owning(*source);
    return const_cast<Src&>(*source);
  }
  bool operator==(const View& o) const { return *source == *o.source; }
};

// None, a View<T> or anything that converts to T.
template <class T>
std::optional<T> optional_of(nb::handle h) {
  if (h.is_none()) return std::nullopt;
  View<T>* v = nullptr;
  if (nb::try_cast(h, v, false) && v) return *v->source;
  return nb::cast<T>(h);
}

// A view of data shared from C++ (null: a view of an empty Src); it keeps the data alive.
template <class Src>
View<Src> shared_view(const std::shared_ptr<const Src>& p) {
  if (!p) return View<Src>();
  return View<Src>(std::const_pointer_cast<Src>(p), p.get(), false);
}

}  // namespace superdex::python
