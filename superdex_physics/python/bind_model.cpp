// Model data (superdex/physics/model.h): the owning structs (ModelData, MeshData, ...), their
// non-owning *View classes, the primitives Box, Plane and Sphere, the enums FileFormat and
// MeshFileType, and the submodule superdex.physics.model.
//
// A view made from an owning object (MeshDataView(src=mesh)) keeps that object alive and reads
// its values whenever asked, so edits of the source show through; its arrays are SpanConst
// views. A view made field by field owns a private copy of its values. Setting a field of a view
// first gives the view its own copy of the source (the source itself is never written through a
// view).

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include <memory>
#include <optional>

#include "bind_common.h"
#include "bind_container.h"
#include "bind_model_view.h"
#include "struct_binder.h"
#include "superdex/physics/model.h"
#include "superdex/physics/params/actor_params.h"

namespace superdex::python {

namespace {

using SkinningDataView = View<SkinningData>;
using BlendingDataView = View<BlendingData>;
using MeshDataView = View<MeshData>;
using GridSdfDataView = View<GridSdfData>;
using ModelDataView = View<ModelData>;

template <class T>
SpanOf<const T> span_of(const std::shared_ptr<void>& keep, const std::vector<T>& v) {
  return SpanOf<const T>{keep, v.data(), v.size()};
}

// An array argument: a list, tuple, numpy array, DynamicArray or SpanConst of T.
template <class T>
std::vector<T> array_of(nb::handle h) {
  SpanOf<const T>* s = nullptr;
  if (nb::try_cast(h, s, false) && s) return std::vector<T>(s->data, s->data + s->size);
  return nb::cast<std::vector<T>>(h);
}

template <class T>
std::optional<T> optional_value(nb::handle h) {
  if (h.is_none()) return std::nullopt;
  return nb::cast<T>(h);
}

// Binds View<Src> as `name`: properties read from the source, construction from a Src (`src=`)
// or field by field, content equality; copies are refused (a view does not own its values).
template <class Src>
class ViewBinder {
 public:
  using V = View<Src>;

  ViewBinder(nb::handle scope, const char* name, const char* doc) : cls_(scope, name, doc), fields_(std::make_shared<Fields>()) {
    fields_->type_name = name;
  }

  // `get(const Src&, const V&)` reads the field; `set(Src&, nb::handle)` writes it.
  template <class Get, class Set>
  ViewBinder& field(const char* name, Get get, Set set, const char* doc = "") {
    cls_.def_prop_rw(
        name, [get](const V& v) { return get(*v.source, v); }, [set](V& v, nb::handle value) { set(v.detach(), value); }, doc);
    fields_->names.push_back(name);
    fields_->setters.push_back([set](V& v, nb::handle value) { set(v.detach(), value); });
    return *this;
  }

  nb::class_<V>& done() {
    std::shared_ptr<Fields> f = fields_;
    cls_.def("__init__", [f](V* self, nb::args args, nb::kwargs kwargs) {
          new (self) V(V::owning(Src{}));
          nb::handle src;
          if (args.size() == 1 && kwargs.size() == 0 && nb::isinstance<Src>(args[0])) src = args[0];
          if (args.size() == 0 && kwargs.size() == 1 && kwargs.contains("src")) src = kwargs["src"];
          if (src.is_valid()) {
            if (nb::isinstance<Src>(src)) *self = V(hold(src), &nb::cast<const Src&>(src), false);
            else if (nb::isinstance<V>(src)) *self = nb::cast<const V&>(src);
            else throw nb::type_error((f->type_name + "(): src must be a " + f->source_name + " or a " + f->type_name).c_str());
            return;
          }
          if (args.size() > 0) throw nb::type_error((f->type_name + "(): fields are keyword-only (or give src)").c_str());
          f->apply(*self, kwargs);
        })
        .def("__eq__", [](const V& a, const V& b) { return a == b; }, nb::is_operator())
        .def("__ne__", [](const V& a, const V& b) { return !(a == b); }, nb::is_operator())
        .def("__copy__", [f](const V&) -> V { throw nb::type_error((f->type_name + " is a non-owning view and cannot be copied").c_str()); })
        .def("__deepcopy__", [f](const V&, nb::handle) -> V {
               throw nb::type_error((f->type_name + " is a non-owning view and cannot be copied").c_str());
             }, nb::arg("memo"))
        .def("__repr__", [f](nb::handle self) { return f->repr(self); });
    return cls_;
  }

  ViewBinder& source_name(const char* name) {
    fields_->source_name = name;
    return *this;
  }
  nb::class_<V>& cls() { return cls_; }

 private:
  struct Fields : BinderFields<V> {
    std::string source_name = "source";
  };
  nb::class_<V> cls_;
  std::shared_ptr<Fields> fields_;
};

// Field accessors of views, by member pointer.
template <class Src, class T>
auto span_field(std::vector<T> Src::*member) {
  return std::make_pair([member](const Src& s, const View<Src>& v) { return span_of(v.keep, s.*member); },
                        [member](Src& s, nb::handle value) { s.*member = array_of<T>(value); });
}
template <class Src, class T>
auto value_field(T Src::*member) {
  return std::make_pair([member](const Src& s, const View<Src>&) { return T(s.*member); },
                        [member](Src& s, nb::handle value) { s.*member = nb::cast<T>(value); });
}
template <class Src, class T>
auto view_field(std::optional<T> Src::*member) {
  return std::make_pair(
      [member](const Src& s, const View<Src>& v) { return (s.*member) ? std::optional<View<T>>(v.child(*(s.*member))) : std::nullopt; },
      [member](Src& s, nb::handle value) { s.*member = optional_of<T>(value); });
}
template <class Src, class T>
auto optional_span_field(std::optional<std::vector<T>> Src::*member) {
  return std::make_pair(
      [member](const Src& s, const View<Src>& v) {
        return (s.*member) ? std::optional<SpanOf<const T>>(span_of(v.keep, *(s.*member))) : std::nullopt;
      },
      [member](Src& s, nb::handle value) {
        s.*member = value.is_none() ? std::nullopt : std::optional<std::vector<T>>(array_of<T>(value));
      });
}

template <class Src, class Pair>
void add(ViewBinder<Src>& b, const char* name, Pair p, const char* doc = "") {
  b.field(name, p.first, p.second, doc);
}

// The owning struct's `src=` also takes its view (a copy of the viewed values).
template <class Src>
void construct_from_view(nb::class_<Src>& c) {
  c.def("__init__", [](Src* self, const View<Src>& src) { new (self) Src(*src.source); }, nb::arg("src"));
}

// A ModelData argument given as a ModelData or a ModelDataView.
const ModelData& model_of(nb::handle h) {
  ModelDataView* v = nullptr;
  if (nb::try_cast(h, v, false) && v) return *v->source;
  ModelData* d = nullptr;
  if (nb::try_cast(h, d, false) && d) return *d;
  throw Error(std::string("data: expected a ModelData or a ModelDataView, got ") + nb::inst_name(h).c_str());
}

// Bytes of a file: bytes, bytearray, memoryview, str (UTF-8) or a sequence of one-character strings.
std::string bytes_of(nb::handle h) {
  if (PyBytes_Check(h.ptr())) return std::string(PyBytes_AS_STRING(h.ptr()), static_cast<size_t>(PyBytes_GET_SIZE(h.ptr())));
  if (PyByteArray_Check(h.ptr()))
    return std::string(PyByteArray_AS_STRING(h.ptr()), static_cast<size_t>(PyByteArray_GET_SIZE(h.ptr())));
  if (PyUnicode_Check(h.ptr())) return nb::cast<std::string>(h);
  if (PyMemoryView_Check(h.ptr())) return nb::cast<std::string>(nb::handle(h).attr("tobytes")().attr("decode")("latin-1"));
  std::string out;
  for (nb::handle item : nb::iter(h)) {
    if (PyLong_Check(item.ptr())) out.push_back(static_cast<char>(nb::cast<int>(item)));
    else out += nb::cast<std::string>(item);
  }
  return out;
}

// The per-element arrays of PerElementSoftMaterialData, in field order, with their units.
struct MaterialArray {
  const char* name;
  std::vector<real> PerElementSoftMaterialData::*member;
  const char* doc;
};
const MaterialArray kMaterialArrays[] = {
    {"youngs_modulus", &PerElementSoftMaterialData::youngs_modulus, "Pa, one per element."},
    {"poisson_ratio", &PerElementSoftMaterialData::poisson_ratio, "One per element."},
    {"aniso_alpha", &PerElementSoftMaterialData::aniso_alpha, "Pa, one per element."},
    {"aniso_length", &PerElementSoftMaterialData::aniso_length, "One per element."},
    {"aniso_theta", &PerElementSoftMaterialData::aniso_theta, "rad, one per element."},
    {"aniso_phi", &PerElementSoftMaterialData::aniso_phi, "rad, one per element."},
    {"arap_stiffness", &PerElementSoftMaterialData::arap_stiffness, "Pa, one per element."},
    {"shape_target_tensor", &PerElementSoftMaterialData::shape_target_tensor, "Six per element (upper triangle s0..s5)."},
};

void bind_structs(nb::module_& m) {
  StructBinder<SkinningData> skinning(m, "SkinningData", "Skinning of a mesh: weights_per_node (index, weight) pairs per node.");
  skinning.field("weights_per_node", &SkinningData::weights_per_node, "Weights and indices per skinned node.")
      .field("indices", &SkinningData::indices, "Size num_nodes * weights_per_node.")
      .field("weights", &SkinningData::weights, "Size num_nodes * weights_per_node; each node's sum to 1.");
  construct_from_view(skinning.cls());
  skinning.done();
  StructBinder<BlendingData> blending(m, "BlendingData", "Blending of one soft source shape within a soft skinned mesh.");
  blending.field("source_shape", &BlendingData::source_shape, "Name of the soft source shape.")
      .field("indices", &BlendingData::indices, "Size num_nodes * 2.")
      .field("weights", &BlendingData::weights, "Size num_nodes * 2.");
  construct_from_view(blending.cls());
  blending.done();
  bind_dynamic_array<BlendingData>(m, "DynamicArrayBlendingData");
  StructBinder<MeshData> mesh(m, "MeshData", "A mesh of a model: flat coordinates (m) and connectivity.");
  mesh.field("nodes_per_element", &MeshData::nodes_per_element, "2 polyline, 3 triangles, 4 tetrahedra.")
      .field("coordinates", &MeshData::coordinates, "Flat node coordinates x0, y0, z0, x1, ... (m).")
      .field("connectivity", &MeshData::connectivity, "Flat node indices, nodes_per_element per element.")
      .field("skinning", &MeshData::skinning, "Optional skinning of the nodes.");
  mesh.cls()
      .def("get_num_nodes", &MeshData::num_nodes)
      .def("get_num_elements", &MeshData::num_elements)
      .def("is_empty", &MeshData::is_empty);
  construct_from_view(mesh.cls());
  mesh.done();
  StructBinder<GridSdfData> sdf(m, "GridSdfData", "A precomputed signed-distance grid (m, negative inside); values x fastest.");
  sdf.field("dims", &GridSdfData::dims, "Samples along x, y, z.")
      .field("values", &GridSdfData::values, "dims[0] * dims[1] * dims[2] distances (m), index i + dims[0] * (j + dims[1] * k).")
      .field("bounds", &GridSdfData::bounds, "The box the samples span.")
      .field("negative_value_bounds", &GridSdfData::negative_value_bounds, "The box of the negative (inside) region.")
      .field("scale", &GridSdfData::scale, "Parent-from-grid scale (applied first).")
      .field("rotation", &GridSdfData::rotation, "Parent-from-grid rotation.")
      .field("translation", &GridSdfData::translation, "Parent-from-grid translation (m).");
  construct_from_view(sdf.cls());
  sdf.done();
  StructBinder<PerElementSoftMaterialData> material(m, "PerElementSoftMaterialData", "Per-element soft material values.");
  material.field("type", &PerElementSoftMaterialData::type).field("psd_strategy", &PerElementSoftMaterialData::psd_strategy);
  for (const MaterialArray& a : kMaterialArrays) material.field(a.name, a.member, a.doc);
  material.cls().def("get_num_elements", &PerElementSoftMaterialData::num_elements,
                     "arap_stiffness' size for the ARAP types, poisson_ratio's otherwise.");
  construct_from_view(material.cls());
  material.done();
  StructBinder<Box>(m, "Box", "An oriented box: center (m), half extents (m) along its axes, rotation.")
      .field("center", &Box::center)
      .field("half_extents", &Box::half_extents)
      .field("rotation", &Box::rotation)
      .done();
  StructBinder<Plane>(m, "Plane", "A plane: unit normal and signed distance (m) from the origin along it.")
      .field("normal", &Plane::normal)
      .field("distance", &Plane::distance)
      .done();
  StructBinder<Sphere>(m, "Sphere", "A ball: center (m) and radius (m).")
      .field("center", &Sphere::center)
      .field("radius", &Sphere::radius)
      .done();
  StructBinder<ModelData> model_data(m, "ModelData", "The contents of a model file; every part optional.");
  model_data.field("mesh", &ModelData::mesh)
      .field("visual_mesh", &ModelData::visual_mesh)
      .field("blending", &ModelData::blending)
      .field("constrained_nodes", &ModelData::constrained_nodes, "Indices of constrained mesh nodes.")
      .field("element_frame_axes", &ModelData::element_frame_axes, "Polylines: a unit axis per element, normal to it.")
      .field("box", &ModelData::box)
      .field("plane", &ModelData::plane)
      .field("sphere", &ModelData::sphere)
      .field("sdf", &ModelData::sdf)
      .field("material", &ModelData::material);
  construct_from_view(model_data.cls());
  model_data.done();
}

void bind_views(nb::module_& m) {
  {
    ViewBinder<SkinningData> b(m, "SkinningDataView", "A non-owning view of a SkinningData.");
    add(b, "weights_per_node", value_field(&SkinningData::weights_per_node));
    add(b, "indices", span_field(&SkinningData::indices));
    add(b, "weights", span_field(&SkinningData::weights));
    b.source_name("SkinningData").done();
  }
  {
    ViewBinder<BlendingData> b(m, "BlendingDataView", "A non-owning view of a BlendingData.");
    add(b, "source_shape", value_field(&BlendingData::source_shape));
    add(b, "indices", span_field(&BlendingData::indices));
    add(b, "weights", span_field(&BlendingData::weights));
    b.source_name("BlendingData").done();
    bind_dynamic_array<BlendingDataView>(m, "DynamicArrayBlendingDataView");
  }
  {
    ViewBinder<MeshData> b(m, "MeshDataView", "A non-owning view of a MeshData.");
    add(b, "nodes_per_element", value_field(&MeshData::nodes_per_element));
    add(b, "coordinates", span_field(&MeshData::coordinates));
    add(b, "connectivity", span_field(&MeshData::connectivity));
    add(b, "skinning", view_field(&MeshData::skinning));
    b.source_name("MeshData").done()
        .def("get_num_nodes", [](const MeshDataView& v) { return v.source->num_nodes(); })
        .def("get_num_elements", [](const MeshDataView& v) { return v.source->num_elements(); })
        .def("is_empty", [](const MeshDataView& v) { return v.source->is_empty(); });
  }
  {
    ViewBinder<GridSdfData> b(m, "GridSdfDataView", "A non-owning view of a GridSdfData.");
    add(b, "dims", value_field(&GridSdfData::dims));
    add(b, "values", span_field(&GridSdfData::values));
    add(b, "bounds", value_field(&GridSdfData::bounds));
    add(b, "negative_value_bounds", value_field(&GridSdfData::negative_value_bounds));
    b.field("scale", [](const GridSdfData& s, const GridSdfDataView&) { return s.scale; },
            [](GridSdfData& s, nb::handle v) { s.scale = optional_value<Real3>(v); });
    b.field("rotation", [](const GridSdfData& s, const GridSdfDataView&) { return s.rotation; },
            [](GridSdfData& s, nb::handle v) { s.rotation = optional_value<Quaternion>(v); });
    b.field("translation", [](const GridSdfData& s, const GridSdfDataView&) { return s.translation; },
            [](GridSdfData& s, nb::handle v) { s.translation = optional_value<Real3>(v); });
    b.source_name("GridSdfData").done();
  }
  {
    using D = PerElementSoftMaterialData;
    ViewBinder<D> b(m, "PerElementSoftMaterialDataView", "A non-owning view of a PerElementSoftMaterialData.");
    add(b, "type", value_field(&D::type));
    add(b, "psd_strategy", value_field(&D::psd_strategy));
    for (const MaterialArray& a : kMaterialArrays) add(b, a.name, span_field(a.member), a.doc);
    b.source_name("PerElementSoftMaterialData").done();
  }
  {
    ViewBinder<ModelData> b(m, "ModelDataView", "A non-owning view of a ModelData.");
    add(b, "mesh", view_field(&ModelData::mesh));
    add(b, "visual_mesh", view_field(&ModelData::visual_mesh));
    b.field("blending",
            [](const ModelData& s, const ModelDataView& v) -> std::optional<std::vector<BlendingDataView>> {
              if (!s.blending) return std::nullopt;
              std::vector<BlendingDataView> out;
              for (const BlendingData& item : *s.blending) out.push_back(v.child(item));
              return out;
            },
            [](ModelData& s, nb::handle value) {
              if (value.is_none()) {
                s.blending.reset();
                return;
              }
              std::vector<BlendingData> items;
              for (nb::handle item : nb::iter(value)) items.push_back(*optional_of<BlendingData>(item));
              s.blending = std::move(items);
            });
    add(b, "constrained_nodes", optional_span_field(&ModelData::constrained_nodes));
    add(b, "element_frame_axes", optional_span_field(&ModelData::element_frame_axes));
    add(b, "box", value_field(&ModelData::box));
    add(b, "plane", value_field(&ModelData::plane));
    add(b, "sphere", value_field(&ModelData::sphere));
    add(b, "sdf", view_field(&ModelData::sdf));
    add(b, "material", view_field(&ModelData::material));
    b.source_name("ModelData").done();
  }
}

void bind_model_functions(nb::module_& mm) {
  mm.def("load_from_file", &model::load_from_file, "path"_a,
         "Loads a .mochi.json, .mochi.h5, .obj, .off, .ply or .stl file, then auto_correct() and validate().");
  mm.def("load_from_file_unchecked", &model::load_from_file_unchecked, "path"_a,
         "load_from_file without auto_correct() and validate(): can load invalid models.");
  mm.def("load_from_bytes", [](nb::handle data) { return model::load_from_bytes(bytes_of(data)); }, "data"_a,
         "Loads a .mochi.h5 or .mochi.json file's bytes (told apart by the HDF5 signature), then auto_correct() and validate().");
  mm.def("load_from_bytes", [](nb::handle data, MeshFileType format) { return model::load_from_bytes(bytes_of(data), format); }, "data"_a,
         "format"_a, "Loads a file's bytes of the given type, then auto_correct() and validate().");
  mm.def("load_from_bytes_unchecked", [](nb::handle data) { return model::load_from_bytes_unchecked(bytes_of(data)); }, "data"_a);
  mm.def("load_from_bytes_unchecked",
         [](nb::handle data, MeshFileType format) { return model::load_from_bytes_unchecked(bytes_of(data), format); }, "data"_a, "format"_a,
         "load_from_bytes without auto_correct() and validate().");
  mm.def("save_to_file", [](const ModelData& data, const std::string& path, FileFormat format) { model::save_to_file(data, path, format); },
         "data"_a, "path"_a, "format"_a, "Writes the model (creating directories); an existing file is replaced.");
  mm.def("save_to_file",
         [](const ModelDataView& data, const std::string& path, FileFormat format) { model::save_to_file(*data.source, path, format); },
         "data"_a, "path"_a, "format"_a);
  mm.def("save_to_json_string", [](nb::handle data) { return model::save_to_json_string(model_of(data)); }, "data"_a,
         "The model as .mochi.json text.");
  mm.def("validate", [](nb::handle data) { model::validate(model_of(data)); }, "data"_a,
         "Raises superdex.physics.Error naming the first field that breaks a rule.");
  mm.def("auto_correct", &model::auto_correct, "data"_a, "In-place fixes: normalised weights, vectors and quaternions; empty parts dropped.");
  mm.def("bake_transform", nb::overload_cast<ModelData&, const Real3&, const Quaternion&, const Real3&>(&model::bake_transform), "data"_a,
         "scale"_a = Real3(Real3::Ones()), "rotation"_a = Quaternion(Quaternion::Identity()), "translation"_a = Real3(Real3::Zero()),
         "Applies scale, then rotation ([x, y, z, w]), then translation to the model, in place.");
  mm.def("bake_transform", nb::overload_cast<ModelData&, const Real3&, const TransformRT&>(&model::bake_transform), "data"_a,
         "scale"_a = Real3(Real3::Ones()), "transform"_a = TransformRT());
  mm.def("bake_coordinate_space_transform",
         nb::overload_cast<MeshData&, const CoordinateSpace&, const CoordinateSpace&>(&model::bake_coordinate_space_transform), "data"_a,
         "from_space"_a, "to_space"_a, "Converts the mesh from from_space's axes and units to to_space's, in place.");
  mm.def("bake_coordinate_space_transform",
         nb::overload_cast<ModelData&, const CoordinateSpace&, const CoordinateSpace&>(&model::bake_coordinate_space_transform), "data"_a,
         "from_space"_a, "to_space"_a);
  mm.def("bake_sdf", nb::overload_cast<ModelData&, const GridSdfParams&>(&model::bake_sdf), "data"_a, "params"_a = GridSdfParams(),
         "Computes data.sdf from the closed surface of the triangle or tetrahedral mesh (replacing any).");
  mm.def("flip_winding_order", nb::overload_cast<MeshData&>(&model::flip_winding_order), "data"_a,
         "Reverses every element's orientation, in place.");
  mm.def("flip_winding_order", nb::overload_cast<ModelData&>(&model::flip_winding_order), "data"_a);
}

}  // namespace

void export_model(nb::module_& m) {
  nb::enum_<FileFormat>(m, "FileFormat", nb::is_arithmetic(), "Formats model.save_to_file writes.")
      .value("JSON", FileFormat::JSON, ".mochi.json")
      .value("H5", FileFormat::H5, ".mochi.h5");
  nb::enum_<MeshFileType>(m, "MeshFileType", nb::is_arithmetic(), "What model.load_from_bytes parses.")
      .value("LEGACY", MeshFileType::Legacy, ".mochi.h5 or .mochi.json, told apart by the HDF5 signature")
      .value("PLY", MeshFileType::PLY)
      .value("OFF", MeshFileType::OFF)
      .value("STL", MeshFileType::STL)
      .value("OBJ", MeshFileType::OBJ);
  bind_structs(m);
  bind_views(m);
  nb::module_ mm = m.def_submodule("model", "Model data files: load, save, check, correct and transform ModelData.");
  bind_model_functions(mm);
}

}  // namespace superdex::python
