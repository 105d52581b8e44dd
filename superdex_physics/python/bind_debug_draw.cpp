// Debug drawing: DebugDraw (a scene's feature switches, actor flags and gather_data) and the data
// it returns, DebugDrawData with its DebugDrawLineVertices and DebugDrawSpheres. Their fields are
// read-only spans (SpanConstReal3, SpanConstReal, SpanConstColor) that keep the engine's buffers
// alive, so they stay readable after a later gather or the scene's destruction. The structs hold
// views: copy.copy, copy.deepcopy and pickling raise TypeError.

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"
#include "superdex/physics/debug_draw.h"

namespace superdex::python {

namespace {

// The Python side of the data structs: spans that own (a share of) what they view.
struct DrawLineVertices {
  SpanOf<const Real3> positions;
  SpanOf<const Color> colors;
  DebugDrawLineVertices view() const { return {{positions.data, positions.size}, {colors.data, colors.size}}; }
  bool operator==(const DrawLineVertices& o) const { return view() == o.view(); }
};

struct DrawSpheres {
  SpanOf<const Real3> positions;
  SpanOf<const real> radii;
  SpanOf<const Color> colors;
  DebugDrawSpheres view() const { return {{positions.data, positions.size}, {radii.data, radii.size}, {colors.data, colors.size}}; }
  bool operator==(const DrawSpheres& o) const { return view() == o.view(); }
};

struct DrawData {
  DrawLineVertices line_vertices;
  DrawSpheres spheres;
  bool operator==(const DrawData& o) const { return line_vertices == o.line_vertices && spheres == o.spheres; }
};

// A span field set from Python: a copy of the elements of a span of the same type, a DynamicArray,
// or anything that converts to one (lists, tuples, arrays), owned by the span.
template <class E>
SpanOf<const E> owned_span(nb::handle value) {
  SpanOf<const E>* span = nullptr;
  if (nb::try_cast(value, span, false) && span) return SpanOf<const E>::owning(std::vector<E>(span->data, span->data + span->size));
  return SpanOf<const E>::owning(nb::cast<std::vector<E>>(value));
}

// A view of `values` sharing `owner`.
template <class E>
SpanOf<const E> shared_span(const std::shared_ptr<const void>& owner, std::span<const E> values) {
  return {std::const_pointer_cast<void>(owner), values.data(), values.size()};
}

template <class S, class E>
auto span_property(SpanOf<const E> S::*member) {
  return std::make_pair([member](const S& s) { return s.*member; },
                        [member](S& s, nb::handle value) { s.*member = owned_span<E>(value); });
}

}  // namespace

void export_debug_draw(nb::module_& m) {
  {
    StructBinder<DrawLineVertices> b(m, "DebugDrawLineVertices",
                                     "A line list: vertices 2k and 2k + 1 are the ends of segment k (positions: world, m), each with a colour.");
    auto [p_get, p_set] = span_property(&DrawLineVertices::positions);
    auto [c_get, c_set] = span_property(&DrawLineVertices::colors);
    b.property("positions", p_get, p_set, "SpanConstReal3: world frame (m), two per segment.")
        .property("colors", c_get, c_set, "SpanConstColor: one per vertex.")
        .done(true, false);
  }
  {
    StructBinder<DrawSpheres> b(m, "DebugDrawSpheres", "Spheres: centres (world, m), radii (m) and colours, one each per sphere.");
    auto [p_get, p_set] = span_property(&DrawSpheres::positions);
    auto [r_get, r_set] = span_property(&DrawSpheres::radii);
    auto [c_get, c_set] = span_property(&DrawSpheres::colors);
    b.property("positions", p_get, p_set, "SpanConstReal3: centres, world frame (m).")
        .property("radii", r_get, r_set, "SpanConstReal: m.")
        .property("colors", c_get, c_set, "SpanConstColor.")
        .done(true, false);
  }
  StructBinder<DrawData>(m, "DebugDrawData",
                         "What DebugDraw.gather_data returns: line vertices and spheres in the world frame. Its spans keep the\n"
                         "engine's buffers alive: they stay readable after a later gather and after the scene's destruction.")
      .field("line_vertices", &DrawData::line_vertices)
      .field("spheres", &DrawData::spheres)
      .done(true, false);

  nb::class_<DebugDraw>(m, "DebugDraw",
                        "A scene's debug drawing, by feature: contacts, bounds, frames, centres of mass, joint axes and soft\n"
                        "surfaces as line segments and spheres (world frame, m) for the client to render. Use it on the thread\n"
                        "that uses its scene. Disabled by default, every feature off and every actor on.")
      .def("is_enabled", &DebugDraw::is_enabled, "The master switch.")
      .def("enable", &DebugDraw::enable, "enable"_a, "The master switch: while off, gather_data returns empty data; settings are kept.")
      .def("get_num_features", &DebugDraw::num_features)
      .def("find_feature", &DebugDraw::find_feature, "name"_a, "The feature's index, or -1 (names are case sensitive).")
      .def("get_feature_name", &DebugDraw::feature_name, "index"_a)
      .def("get_feature_description", &DebugDraw::feature_description, "index"_a)
      .def("is_feature_enabled", &DebugDraw::is_feature_enabled, "index"_a)
      .def("enable_feature", &DebugDraw::enable_feature, "index"_a, "enable"_a, "Remembered while the master switch is off.")
      .def("enable_actor", [](DebugDraw& d, nb::handle actor, bool enable) { d.enable_actor(actor_handle_of(actor, "enable_actor: actor"), enable); },
           "actor"_a, "enable"_a,
           "Whether the actor's primitives are drawn (all actors are by default). Disabling an articulation hides its\n"
           "links; a contact is drawn when both its actors are. Raises Error for an actor not in the scene.")
      .def("is_actor_enabled", [](const DebugDraw& d, nb::handle actor) { return d.is_actor_enabled(actor_handle_of(actor, "is_actor_enabled: actor")); },
           "actor"_a, "False when the actor, or the articulation of a link, is disabled.")
      .def("gather_data", [](DebugDraw& d) {
             const DebugDrawData data = d.gather_data();
             DrawData out;
             out.line_vertices = {shared_span(data.owner, data.line_vertices.positions), shared_span(data.owner, data.line_vertices.colors)};
             out.spheres = {shared_span(data.owner, data.spheres.positions), shared_span(data.owner, data.spheres.radii),
                            shared_span(data.owner, data.spheres.colors)};
             return out;
           },
           "The primitives of the enabled features and actors, from the current state (contacts: of the last step); empty\n"
           "while disabled.")
      .def("__repr__", [](const DebugDraw& d) { return "DebugDraw(scene=" + std::to_string(d.scene().value) + ")"; });
}

}  // namespace superdex::python
