// The handle types: Handle and its typed kinds (SceneHandle, ActorHandle, ShapeHandle, ...), each a
// 64-bit id, 0 invalid; sortable and hashable. ShapeHandle counts references: a Python ShapeHandle
// holds one, released when it is garbage collected.

#include <nanobind/stl/string.h>

#include "bind_common.h"

namespace superdex::python {

namespace {

template <class H>
void add_handle_methods(nb::class_<H>& c, const char* name) {
  c.def("__init__", [](H* self) { new (self) H(); })
      .def("__init__", [](H* self, std::int64_t value) { new (self) H(value); }, "value"_a)
      .def_prop_rw("value", [](const H& h) { return static_cast<std::int64_t>(h); }, [](H& h, std::int64_t v) { h = H(v); },
                   "The raw 64-bit id (0: invalid).")
      .def("is_valid", [](const H& h) { return static_cast<std::int64_t>(h) != 0; })
      .def("get_hash", [](const H& h) { return static_cast<std::int64_t>(h); })
      .def("__eq__", [](const H& a, const H& b) { return static_cast<std::int64_t>(a) == static_cast<std::int64_t>(b); }, nb::is_operator())
      .def("__ne__", [](const H& a, const H& b) { return static_cast<std::int64_t>(a) != static_cast<std::int64_t>(b); }, nb::is_operator())
      .def("__lt__", [](const H& a, const H& b) { return static_cast<std::int64_t>(a) < static_cast<std::int64_t>(b); }, nb::is_operator())
      .def("__hash__", [](const H& h) { return std::hash<std::int64_t>()(static_cast<std::int64_t>(h)); })
      .def("__repr__", [name](const H& h) { return std::string(name) + "(" + std::to_string(static_cast<std::int64_t>(h)) + ")"; })
      .def("__copy__", [](const H& h) { return H(h); })
      .def("__deepcopy__", [](const H& h, nb::handle) { return H(h); }, "memo"_a)
      .def("__getstate__", [](const H& h) { return static_cast<std::int64_t>(h); })
      .def("__setstate__", [](H& self, std::int64_t v) { new (&self) H(v); });
}

template <class Tag>
void bind_typed(nb::module_& m, const char* name, const char* doc) {
  nb::class_<Handle<Tag>> c(m, name, doc);
  add_handle_methods(c, name);
}

}  // namespace

void export_handles(nb::module_& m) {
  bind_typed<struct AnyTag>(m, "Handle", "A 64-bit id of something the engine keeps; 0 is invalid.");
  bind_typed<SceneTag>(m, "SceneHandle", "Names a scene.");
  bind_typed<ActorTag>(m, "ActorHandle", "Names an actor of a scene.");
  bind_typed<CallbackTag>(m, "CallbackHandle", "Names a step callback of a scene.");
  bind_typed<StateTag>(m, "StateHandle", "Names a state captured by Scene.capture_state.");
  bind_typed<QueryTag>(m, "QueryHandle", "Names a query registered on an actor or a constraint.");
  bind_typed<ConstraintTag>(m, "ConstraintHandle", "Names a constraint of a scene.");

  // a counted reference: a copy (params.shape = handle) takes a reference, and garbage collection
  // of the Python object drops one; release_shape() releases the shape at once
  nb::class_<ShapeHandle> shape(m, "ShapeHandle",
                                "A counted reference to a shape. The shape is released when its last ShapeHandle is garbage "
                                "collected, or at once by release_shape(); actors keep the data of the shape they were made from.");
  shape.def("__init__", [](ShapeHandle* self) { new (self) ShapeHandle(); })
      .def("__init__", [](ShapeHandle* self, std::int64_t value) { new (self) ShapeHandle(value); }, "value"_a)
      .def_prop_rw("value", &ShapeHandle::value, &ShapeHandle::set_value, "The raw 64-bit id (0: invalid).")
      .def("is_valid", &ShapeHandle::is_valid)
      .def("get_hash", &ShapeHandle::value)
      .def("__eq__", [](const ShapeHandle& a, const ShapeHandle& b) { return a == b; }, nb::is_operator())
      .def("__ne__", [](const ShapeHandle& a, const ShapeHandle& b) { return !(a == b); }, nb::is_operator())
      .def("__lt__", [](const ShapeHandle& a, const ShapeHandle& b) { return a.value() < b.value(); }, nb::is_operator())
      .def("__hash__", [](const ShapeHandle& h) { return std::hash<std::int64_t>()(h.value()); })
      .def("__repr__", [](const ShapeHandle& h) { return "ShapeHandle(" + std::to_string(h.value()) + ")"; })
      .def("__copy__", [](const ShapeHandle& h) { return ShapeHandle(h); })
      .def("__deepcopy__", [](const ShapeHandle& h, nb::handle) { return ShapeHandle(h); }, "memo"_a)
      // within a process: unpickling takes a new reference to the shape, if it still lives
      .def("__getstate__", &ShapeHandle::value)
      .def("__setstate__", [](ShapeHandle& self, std::int64_t v) { new (&self) ShapeHandle(v); });
}

}  // namespace superdex::python
