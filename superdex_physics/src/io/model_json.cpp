// The .mochi.json model format (docs/model_formats.md): camelCase keys, optional parts written only
// when present, reals as the shortest decimal that reads back to the same value in this build's
// precision. Reading names the source and the JSON path of every defect.

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "io/model_io.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace model_io {

namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

// ---------------------------------------------------------------- writing

// The double whose shortest decimal form is the shortest one that reads back as x in `real`.
double json_number(real x) {
  if constexpr (std::is_same_v<real, float>) {
    if (!std::isfinite(x)) return x;
    char buffer[32];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);
    *r.ptr = '\0';
    const double shortest = std::strtod(buffer, nullptr);
    // reading decimal -> double -> float rounds twice: keep the exact value where that differs
    return static_cast<float>(shortest) == x ? shortest : static_cast<double>(x);
  } else {
    return x;
  }
}

OrderedJson reals(const std::vector<real>& v) {
  OrderedJson a = OrderedJson::array();
  for (real x : v) a.push_back(json_number(x));
  return a;
}

template <class V>
OrderedJson vector_json(const V& v) {
  OrderedJson a = OrderedJson::array();
  for (int i = 0; i < static_cast<int>(v.size()); ++i) a.push_back(json_number(v[i]));
  return a;
}

OrderedJson quaternion_json(const Quaternion& q) {
  return OrderedJson::array({json_number(q.x()), json_number(q.y()), json_number(q.z()), json_number(q.w())});
}

OrderedJson aabb_json(const Aabb& b) { return OrderedJson{{"min", vector_json(b.min)}, {"max", vector_json(b.max)}}; }

OrderedJson mesh_json(const MeshData& m) {
  OrderedJson j{{"nodesPerElement", m.nodes_per_element}, {"coordinates", reals(m.coordinates)}, {"connectivity", m.connectivity}};
  if (m.skinning)
    j["skinning"] = {{"weightsPerNode", m.skinning->weights_per_node}, {"indices", m.skinning->indices}, {"weights", reals(m.skinning->weights)}};
  return j;
}

OrderedJson material_json(const PerElementSoftMaterialData& m) {
  return {{"type", material_type_text(m.type)},
          {"psdStrategy", psd_strategy_text(m.psd_strategy)},
          {"youngsModulus", reals(m.youngs_modulus)},
          {"poissonRatio", reals(m.poisson_ratio)},
          {"anisoAlpha", reals(m.aniso_alpha)},
          {"anisoLength", reals(m.aniso_length)},
          {"anisoTheta", reals(m.aniso_theta)},
          {"anisoPhi", reals(m.aniso_phi)},
          {"arapStiffness", reals(m.arap_stiffness)},
          {"shapeTargetTensor", reals(m.shape_target_tensor)}};
}

// ---------------------------------------------------------------- reading

// Reads values out of the parsed document; every error names the source and the JSON path.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw Error(source_ + ": " + (path.empty() ? "/" : path) + ": " + what);
  }

  // The member `key` of object `j`, or nullptr when absent or null.
  const Json* member(const Json& j, const std::string& path, const char* key) const {
    if (!j.is_object()) fail(path, std::string("expected an object, got ") + j.type_name());
    const auto it = j.find(key);
    return it == j.end() || it->is_null() ? nullptr : &*it;
  }

  double number(const Json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, std::string("expected a number, got ") + j.type_name());
    return j.get<double>();
  }

  real real_value(const Json& j, const std::string& path) const { return static_cast<real>(number(j, path)); }

  int integer(const Json& j, const std::string& path) const {
    const double x = number(j, path);
    if (x != std::floor(x) || x < -2147483648.0 || x > 2147483647.0) fail(path, "expected an integer, got " + j.dump());
    return static_cast<int>(x);
  }

  std::string text(const Json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, std::string("expected a string, got ") + j.type_name());
    return j.get<std::string>();
  }

  const Json& array(const Json& j, const std::string& path, long expected_size = -1) const {
    if (!j.is_array()) fail(path, std::string("expected an array, got ") + j.type_name());
    if (expected_size >= 0 && static_cast<long>(j.size()) != expected_size)
      fail(path, "expected " + std::to_string(expected_size) + " values, got " + std::to_string(j.size()));
    return j;
  }

  std::vector<real> reals(const Json& j, const std::string& path) const {
    std::vector<real> out;
    out.reserve(array(j, path).size());
    for (size_t i = 0; i < j.size(); ++i) out.push_back(real_value(j[i], path + "/" + std::to_string(i)));
    return out;
  }

  std::vector<int> ints(const Json& j, const std::string& path) const {
    std::vector<int> out;
    out.reserve(array(j, path).size());
    for (size_t i = 0; i < j.size(); ++i) out.push_back(integer(j[i], path + "/" + std::to_string(i)));
    return out;
  }

  template <class V>
  V fixed(const Json& j, const std::string& path) const {
    V v;
    array(j, path, v.size());
    for (int i = 0; i < static_cast<int>(v.size()); ++i) {
      const std::string p = path + "/" + std::to_string(i);
      if constexpr (std::is_same_v<typename V::Scalar, int>) v[i] = integer(j[i], p);
      else v[i] = real_value(j[i], p);
    }
    return v;
  }

  Quaternion quaternion(const Json& j, const std::string& path) const {
    const Real4 c = fixed<Real4>(j, path);
    return Quaternion(c[3], c[0], c[1], c[2]);
  }

  Aabb aabb(const Json& j, const std::string& path) const {
    Aabb b;
    if (const Json* v = member(j, path, "min")) b.min = fixed<Real3>(*v, path + "/min");
    if (const Json* v = member(j, path, "max")) b.max = fixed<Real3>(*v, path + "/max");
    return b;
  }

  // Reads the member `key` of `j` with `read(value, path)` into `out` when present.
  template <class T, class F>
  void optional(const Json& j, const std::string& path, const char* key, T& out, F read) const {
    if (const Json* v = member(j, path, key)) out = read(*v, path + "/" + key);
  }

 private:
  std::string source_;
};

MeshData read_mesh(const Reader& r, const Json& j, const std::string& path) {
  MeshData m;
  r.optional(j, path, "nodesPerElement", m.nodes_per_element, [&](const Json& v, const std::string& p) { return r.integer(v, p); });
  r.optional(j, path, "coordinates", m.coordinates, [&](const Json& v, const std::string& p) { return r.reals(v, p); });
  r.optional(j, path, "connectivity", m.connectivity, [&](const Json& v, const std::string& p) { return r.ints(v, p); });
  r.optional(j, path, "skinning", m.skinning, [&](const Json& v, const std::string& p) {
    SkinningData s;
    r.optional(v, p, "weightsPerNode", s.weights_per_node, [&](const Json& w, const std::string& q) { return r.integer(w, q); });
    r.optional(v, p, "indices", s.indices, [&](const Json& w, const std::string& q) { return r.ints(w, q); });
    r.optional(v, p, "weights", s.weights, [&](const Json& w, const std::string& q) { return r.reals(w, q); });
    return s;
  });
  return m;
}

template <class E>
E enum_value(const Reader& r, const Json& j, const std::string& path, std::optional<E> (*parse)(std::string_view), int count) {
  if (j.is_number()) {
    const int v = r.integer(j, path);
    if (v < 0 || v >= count) r.fail(path, "enum value " + std::to_string(v) + " out of range [0, " + std::to_string(count) + ")");
    return static_cast<E>(v);
  }
  const std::string name = r.text(j, path);
  const std::optional<E> e = parse(name);
  if (!e) r.fail(path, "unknown name '" + name + "'");
  return *e;
}

PerElementSoftMaterialData read_material(const Reader& r, const Json& j, const std::string& path) {
  PerElementSoftMaterialData m;
  r.optional(j, path, "type", m.type, [&](const Json& v, const std::string& p) {
    return enum_value<SoftMaterialType>(r, v, p, parse_material_type, kNumMaterialTypes);
  });
  r.optional(j, path, "psdStrategy", m.psd_strategy, [&](const Json& v, const std::string& p) {
    return enum_value<MaterialPsdStrategy>(r, v, p, parse_psd_strategy, kNumPsdStrategies);
  });
  const std::pair<const char*, std::vector<real>*> arrays[] = {
      {"youngsModulus", &m.youngs_modulus}, {"poissonRatio", &m.poisson_ratio}, {"anisoAlpha", &m.aniso_alpha},
      {"anisoLength", &m.aniso_length},     {"anisoTheta", &m.aniso_theta},     {"anisoPhi", &m.aniso_phi},
      {"arapStiffness", &m.arap_stiffness}, {"shapeTargetTensor", &m.shape_target_tensor}};
  for (const auto& [key, out] : arrays) r.optional(j, path, key, *out, [&](const Json& v, const std::string& p) { return r.reals(v, p); });
  return m;
}

GridSdfData read_sdf(const Reader& r, const Json& j, const std::string& path) {
  GridSdfData s;
  r.optional(j, path, "dims", s.dims, [&](const Json& v, const std::string& p) { return r.fixed<Int3>(v, p); });
  r.optional(j, path, "values", s.values, [&](const Json& v, const std::string& p) { return r.reals(v, p); });
  r.optional(j, path, "bounds", s.bounds, [&](const Json& v, const std::string& p) { return r.aabb(v, p); });
  r.optional(j, path, "negativeValueBounds", s.negative_value_bounds, [&](const Json& v, const std::string& p) { return r.aabb(v, p); });
  r.optional(j, path, "scale", s.scale, [&](const Json& v, const std::string& p) { return r.fixed<Real3>(v, p); });
  r.optional(j, path, "rotation", s.rotation, [&](const Json& v, const std::string& p) { return r.quaternion(v, p); });
  r.optional(j, path, "translation", s.translation, [&](const Json& v, const std::string& p) { return r.fixed<Real3>(v, p); });
  return s;
}

// The flat format older tools wrote (recognised by a top-level "coordinates").
ModelData read_deprecated(const Reader& r, const Json& j) {
  ModelData data;
  MeshData mesh;
  mesh.nodes_per_element = 4;
  r.optional(j, "", "element_size", mesh.nodes_per_element, [&](const Json& v, const std::string& p) { return r.integer(v, p); });
  if (mesh.nodes_per_element != 3 && mesh.nodes_per_element != 4)
    r.fail("/element_size", "must be 3 or 4, got " + std::to_string(mesh.nodes_per_element));
  if (const Json* c = r.member(j, "", "coordinates")) mesh.coordinates = r.reals(*c, "/coordinates");
  if (const Json* c = r.member(j, "", "connectivity")) mesh.connectivity = r.ints(*c, "/connectivity");
  if (mesh.coordinates.empty() || mesh.coordinates.size() % 3 != 0)
    r.fail("/coordinates", "expected a non-empty multiple of 3 values, got " + std::to_string(mesh.coordinates.size()));
  if (mesh.connectivity.empty() || mesh.connectivity.size() % static_cast<size_t>(mesh.nodes_per_element) != 0)
    r.fail("/connectivity", "expected a non-empty multiple of " + std::to_string(mesh.nodes_per_element) + " values, got " +
                                std::to_string(mesh.connectivity.size()));
  if (const Json* w = r.member(j, "", "weights")) {
    SkinningData s;
    s.weights = r.reals(*w, "/weights");
    if (const Json* i = r.member(j, "", "indices")) s.indices = r.ints(*i, "/indices");
    s.weights_per_node = mesh.num_nodes() > 0 ? static_cast<int>(s.indices.size()) / mesh.num_nodes() : 0;
    mesh.skinning = std::move(s);
  }
  data.mesh = std::move(mesh);
  if (const Json* b = r.member(j, "", "blending_data")) {
    std::vector<BlendingData> blending;
    for (size_t k = 0; k < r.array(*b, "/blending_data").size(); ++k) {
      const std::string p = "/blending_data/" + std::to_string(k);
      BlendingData bd;
      r.optional((*b)[k], p, "bone_subset", bd.source_shape, [&](const Json& v, const std::string& q) { return r.text(v, q); });
      r.optional((*b)[k], p, "weights", bd.weights, [&](const Json& v, const std::string& q) { return r.reals(v, q); });
      r.optional((*b)[k], p, "indices", bd.indices, [&](const Json& v, const std::string& q) { return r.ints(v, q); });
      blending.push_back(std::move(bd));
    }
    data.blending = std::move(blending);
  }
  if (const Json* vc = r.member(j, "", "visual_coordinates")) {
    MeshData visual;
    visual.nodes_per_element = 3;
    visual.coordinates = r.reals(*vc, "/visual_coordinates");
    if (const Json* c = r.member(j, "", "visual_connectivity")) visual.connectivity = r.ints(*c, "/visual_connectivity");
    SkinningData s;
    s.weights_per_node = 4;
    if (const Json* w = r.member(j, "", "embedding_weights")) s.weights = r.reals(*w, "/embedding_weights");
    if (const Json* i = r.member(j, "", "embedding_indices")) s.indices = r.ints(*i, "/embedding_indices");
    visual.skinning = std::move(s);
    data.visual_mesh = std::move(visual);
  }
  if (const Json* c = r.member(j, "", "constrained_nodes")) data.constrained_nodes = r.ints(*c, "/constrained_nodes");
  return data;
}

}  // namespace

std::string write_json(const ModelData& d) {
  OrderedJson j = OrderedJson::object();
  if (d.mesh) j["mesh"] = mesh_json(*d.mesh);
  if (d.visual_mesh) j["visualMesh"] = mesh_json(*d.visual_mesh);
  if (d.blending) {
    OrderedJson a = OrderedJson::array();
    for (const BlendingData& b : *d.blending) a.push_back({{"sourceShape", b.source_shape}, {"indices", b.indices}, {"weights", reals(b.weights)}});
    j["blending"] = std::move(a);
  }
  if (d.constrained_nodes) j["constrainedNodes"] = *d.constrained_nodes;
  if (d.element_frame_axes) j["elementFrameAxes"] = reals(*d.element_frame_axes);
  if (d.box) j["box"] = {{"center", vector_json(d.box->center)}, {"halfExtents", vector_json(d.box->half_extents)}, {"rotation", quaternion_json(d.box->rotation)}};
  if (d.plane) j["plane"] = {{"normal", vector_json(d.plane->normal)}, {"distance", json_number(d.plane->distance)}};
  if (d.sphere) j["sphere"] = {{"center", vector_json(d.sphere->center)}, {"radius", json_number(d.sphere->radius)}};
  if (d.sdf) {
    const GridSdfData& s = *d.sdf;
    OrderedJson g{{"dims", {s.dims[0], s.dims[1], s.dims[2]}}, {"values", reals(s.values)}, {"bounds", aabb_json(s.bounds)},
                  {"negativeValueBounds", aabb_json(s.negative_value_bounds)}};
    if (s.scale) g["scale"] = vector_json(*s.scale);
    if (s.rotation) g["rotation"] = quaternion_json(*s.rotation);
    if (s.translation) g["translation"] = vector_json(*s.translation);
    j["sdf"] = std::move(g);
  }
  if (d.material) j["material"] = material_json(*d.material);
  return j.dump(2) + "\n";
}

ModelData read_json(std::string_view text, const std::string& source) {
  Json j;
  try {
    j = Json::parse(text.begin(), text.end());
  } catch (const Json::parse_error& e) {
    throw Error(source + ": not valid JSON: " + e.what());
  }
  const Reader r(source);
  if (!j.is_object()) r.fail("", std::string("expected a JSON object, got ") + j.type_name());
  if (j.contains("coordinates")) return read_deprecated(r, j);
  ModelData d;
  r.optional(j, "", "mesh", d.mesh, [&](const Json& v, const std::string& p) { return read_mesh(r, v, p); });
  r.optional(j, "", "visualMesh", d.visual_mesh, [&](const Json& v, const std::string& p) { return read_mesh(r, v, p); });
  r.optional(j, "", "blending", d.blending, [&](const Json& v, const std::string& p) {
    std::vector<BlendingData> out;
    for (size_t k = 0; k < r.array(v, p).size(); ++k) {
      const std::string q = p + "/" + std::to_string(k);
      BlendingData b;
      r.optional(v[k], q, "sourceShape", b.source_shape, [&](const Json& w, const std::string& s) { return r.text(w, s); });
      r.optional(v[k], q, "indices", b.indices, [&](const Json& w, const std::string& s) { return r.ints(w, s); });
      r.optional(v[k], q, "weights", b.weights, [&](const Json& w, const std::string& s) { return r.reals(w, s); });
      out.push_back(std::move(b));
    }
    return out;
  });
  r.optional(j, "", "constrainedNodes", d.constrained_nodes, [&](const Json& v, const std::string& p) { return r.ints(v, p); });
  r.optional(j, "", "elementFrameAxes", d.element_frame_axes, [&](const Json& v, const std::string& p) { return r.reals(v, p); });
  r.optional(j, "", "box", d.box, [&](const Json& v, const std::string& p) {
    Box b;
    r.optional(v, p, "center", b.center, [&](const Json& w, const std::string& q) { return r.fixed<Real3>(w, q); });
    r.optional(v, p, "halfExtents", b.half_extents, [&](const Json& w, const std::string& q) { return r.fixed<Real3>(w, q); });
    r.optional(v, p, "rotation", b.rotation, [&](const Json& w, const std::string& q) { return r.quaternion(w, q); });
    return b;
  });
  r.optional(j, "", "plane", d.plane, [&](const Json& v, const std::string& p) {
    Plane pl;
    r.optional(v, p, "normal", pl.normal, [&](const Json& w, const std::string& q) { return r.fixed<Real3>(w, q); });
    r.optional(v, p, "distance", pl.distance, [&](const Json& w, const std::string& q) { return r.real_value(w, q); });
    return pl;
  });
  r.optional(j, "", "sphere", d.sphere, [&](const Json& v, const std::string& p) {
    Sphere s;
    r.optional(v, p, "center", s.center, [&](const Json& w, const std::string& q) { return r.fixed<Real3>(w, q); });
    r.optional(v, p, "radius", s.radius, [&](const Json& w, const std::string& q) { return r.real_value(w, q); });
    return s;
  });
  r.optional(j, "", "sdf", d.sdf, [&](const Json& v, const std::string& p) { return read_sdf(r, v, p); });
  r.optional(j, "", "material", d.material, [&](const Json& v, const std::string& p) { return read_material(r, v, p); });
  return d;
}

}  // namespace model_io
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
