// The .mochi.h5 model layout (docs/model_formats.md): groups mesh/, visual_mesh/, sdf/, material/, box/,
// sphere/ and plane/. Reals are stored in the build's precision, integers as int32. Reading takes
// every variant earlier files used (sdf/ attributes on the group, a scalar scale, skinning/ or
// embedding/, legacy material names) and checks only what reading needs: validate() checks the rest.

#include <cmath>
#include <limits>

#include "core/crash_isolation.h"
#include "io/h5_file.h"
#include "io/model_io.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace model_io {

namespace {

using h5::Numbers;
using h5::Reader;

std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + "]";
}

std::vector<real> reals_of(const Numbers& n) { return std::vector<real>(n.values.begin(), n.values.end()); }

std::vector<int> ints_of(const Reader& r, const std::string& path, const Numbers& n) {
  std::vector<int> out;
  out.reserve(n.values.size());
  for (double v : n.values) {
    if (!(v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max()))
      r.fail(path, "value " + std::to_string(v) + " does not fit a 32-bit integer");
    out.push_back(static_cast<int>(v));
  }
  return out;
}

// A dataset of rank 2 with `columns` columns (0: any), or of rank 1 when `columns` is 1.
Numbers table(const Reader& r, const std::string& path, bool integers, hsize_t columns) {
  Numbers n = r.dataset(path, integers);
  const bool ok = (n.dims.size() == 2 && (columns == 0 || n.dims[1] == columns)) || (n.dims.size() == 1 && columns == 1);
  if (!ok)
    r.fail(path, "wrong shape: expected " + std::string(columns == 0 ? "N x k" : "N x " + std::to_string(columns)) + ", got " + shape_text(n.dims));
  return n;
}

std::vector<real> attribute_reals(const Reader& r, const std::string& object, const std::string& name, size_t count) {
  const Numbers a = r.attribute(object, name);
  if (a.values.size() != count)
    r.fail(object + "/" + name, "wrong shape: expected " + std::to_string(count) + " values, got " + std::to_string(a.values.size()));
  return reals_of(a);
}

Real3 attribute_real3(const Reader& r, const std::string& object, const std::string& name) {
  const std::vector<real> v = attribute_reals(r, object, name, 3);
  return Real3(v[0], v[1], v[2]);
}

Quaternion attribute_quaternion(const Reader& r, const std::string& object, const std::string& name) {
  const std::vector<real> v = attribute_reals(r, object, name, 4);
  return Quaternion(v[3], v[0], v[1], v[2]);
}

SkinningData read_skinning(const Reader& r, const std::string& g) {
  SkinningData s;
  if (r.has(g + "/weights")) {
    const Numbers w = table(r, g + "/weights", false, 0);
    s.weights_per_node = w.dims.size() == 2 ? static_cast<int>(w.dims[1]) : 1;
    s.weights = reals_of(w);
  }
  if (r.has(g + "/indices")) {
    const Numbers i = table(r, g + "/indices", true, 0);
    if (!r.has(g + "/weights")) s.weights_per_node = i.dims.size() == 2 ? static_cast<int>(i.dims[1]) : 1;
    s.indices = ints_of(r, g + "/indices", i);
  }
  return s;
}

// mesh/ or visual_mesh/; `skin_groups` are the names the skinning group may have, preferred first.
MeshData read_mesh(const Reader& r, const std::string& g, std::initializer_list<const char*> skin_groups) {
  MeshData m;
  const Numbers c = table(r, g + "/coordinates", false, 3);
  m.coordinates = reals_of(c);
  if (r.has(g + "/connectivity")) {
    const Numbers e = table(r, g + "/connectivity", true, 0);
    m.nodes_per_element = e.dims.size() == 2 ? static_cast<int>(e.dims[1]) : 1;
    m.connectivity = ints_of(r, g + "/connectivity", e);
  } else {
    m.nodes_per_element = 2;  // a polyline through the nodes in order
  }
  for (const char* name : skin_groups)
    if (r.has(g + "/" + name)) {
      m.skinning = read_skinning(r, g + "/" + name);
      break;
    }
  return m;
}

GridSdfData read_sdf(const Reader& r) {
  GridSdfData s;
  const Numbers grid = r.dataset("sdf/grid", false);
  if (grid.dims.size() != 3) r.fail("sdf/grid", "wrong rank: expected a 3-D dataset [nx, ny, nz], got " + shape_text(grid.dims));
  const size_t nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
  s.dims = Int3(static_cast<int>(nx), static_cast<int>(ny), static_cast<int>(nz));
  // the file is C order (z fastest), GridSdfData x fastest
  s.values.resize(grid.values.size());
  for (size_t i = 0; i < nx; ++i)
    for (size_t j = 0; j < ny; ++j)
      for (size_t k = 0; k < nz; ++k) s.values[i + nx * (j + ny * k)] = static_cast<real>(grid.values[(i * ny + j) * nz + k]);
  // attributes on the grid dataset; files written before kept them on the group
  const std::string at = r.has_attribute("sdf/grid", "grid_min") ? "sdf/grid" : "sdf";
  s.bounds.min = attribute_real3(r, at, "grid_min");
  s.bounds.max = attribute_real3(r, at, "grid_max");
  s.negative_value_bounds = s.bounds;
  if (r.has_attribute(at, "collider_min")) s.negative_value_bounds.min = attribute_real3(r, at, "collider_min");
  if (r.has_attribute(at, "collider_max")) s.negative_value_bounds.max = attribute_real3(r, at, "collider_max");
  if (r.has_attribute(at, "scale")) {
    const Numbers a = r.attribute(at, "scale");
    if (a.values.size() == 1) s.scale = Real3::Constant(static_cast<real>(a.values[0]));
    else s.scale = attribute_real3(r, at, "scale");
  }
  if (r.has_attribute(at, "rotation")) s.rotation = attribute_quaternion(r, at, "rotation");
  if (r.has_attribute(at, "translation")) s.translation = attribute_real3(r, at, "translation");
  return s;
}

PerElementSoftMaterialData read_material(const Reader& r) {
  PerElementSoftMaterialData m;
  const std::string g = "material";
  r.require_group(g);
  if (r.has_attribute(g, "type")) {
    const std::string name = r.string_attribute(g, "type");
    const auto t = parse_material_type(name);
    if (!t) r.fail(g + "/type", "unknown material type '" + name + "'");
    m.type = *t;
  } else if (r.has_attribute(g, "material_type")) {  // legacy: a name or an integer code
    std::optional<SoftMaterialType> t;
    try {
      t = parse_material_type(r.string_attribute(g, "material_type"));
    } catch (const Error&) {
      const Numbers code = r.attribute(g, "material_type");
      if (code.values.size() == 1 && code.values[0] >= 0 && code.values[0] < kNumMaterialTypes && code.values[0] == std::floor(code.values[0]))
        t = static_cast<SoftMaterialType>(static_cast<int>(code.values[0]));
    }
    if (!t) r.fail(g + "/material_type", "unknown material type");
    m.type = *t;
  }
  if (r.has_attribute(g, "psd_strategy")) {
    std::string name;
    try {
      name = r.string_attribute(g, "psd_strategy");
    } catch (const Error&) {
      r.fail(g + "/psd_strategy", "must be a name such as 'Projection' (integer codes are not supported)");
    }
    const auto s = parse_psd_strategy(name);
    if (!s) r.fail(g + "/psd_strategy", "unknown PSD strategy '" + name + "'");
    m.psd_strategy = *s;
  }
  auto values = [&](std::initializer_list<const char*> names, hsize_t columns) {
    for (const char* name : names)
      if (r.has(g + "/" + name)) return reals_of(table(r, g + "/" + name, false, columns));
    return std::vector<real>{};
  };
  m.youngs_modulus = values({"youngs_modulus"}, 1);
  m.poisson_ratio = values({"poisson_ratio"}, 1);
  m.aniso_alpha = values({"aniso_alpha"}, 1);
  m.aniso_length = values({"aniso_length"}, 1);
  m.aniso_theta = values({"aniso_theta"}, 1);
  m.aniso_phi = values({"aniso_phi"}, 1);
  m.arap_stiffness = values({"arap_stiffness", "mu"}, 1);
  m.shape_target_tensor = values({"shape_target_tensor", "shape_targets"}, 6);
  return m;
}

ModelData read_checked(const std::string& path) {
  const Reader r(path);
  ModelData d;
  if (r.has("mesh")) {
    r.require_group("mesh");
    d.mesh = read_mesh(r, "mesh", {"skinning", "embedding"});
    if (r.has("mesh/blending")) {
      std::vector<BlendingData> blending;
      for (const std::string& name : r.members("mesh/blending")) {
        const std::string g = "mesh/blending/" + name;
        BlendingData b;
        b.source_shape = name;
        if (r.has(g + "/weights")) b.weights = reals_of(table(r, g + "/weights", false, 2));
        if (r.has(g + "/indices")) b.indices = ints_of(r, g + "/indices", table(r, g + "/indices", true, 2));
        blending.push_back(std::move(b));
      }
      d.blending = std::move(blending);
    }
    if (r.has("mesh/constrained_nodes"))
      d.constrained_nodes = ints_of(r, "mesh/constrained_nodes", table(r, "mesh/constrained_nodes", true, 1));
    if (r.has("mesh/element_frame_axes")) d.element_frame_axes = reals_of(table(r, "mesh/element_frame_axes", false, 3));
  }
  // a visual_mesh/ group without coordinates carries nothing
  if (r.has("visual_mesh") && r.has("visual_mesh/coordinates")) d.visual_mesh = read_mesh(r, "visual_mesh", {"embedding", "skinning"});
  if (r.has("sdf")) d.sdf = read_sdf(r);
  if (r.has("material")) d.material = read_material(r);
  if (r.has("box")) {
    r.require_group("box");
    Box b;
    if (r.has_attribute("box", "center")) b.center = attribute_real3(r, "box", "center");
    b.half_extents = attribute_real3(r, "box", "half_extents");
    if (r.has_attribute("box", "rotation")) b.rotation = attribute_quaternion(r, "box", "rotation");
    d.box = b;
  }
  if (r.has("sphere")) {
    r.require_group("sphere");
    Sphere s;
    if (r.has_attribute("sphere", "center")) s.center = attribute_real3(r, "sphere", "center");
    s.radius = attribute_reals(r, "sphere", "radius", 1)[0];
    d.sphere = s;
  }
  if (r.has("plane")) {
    r.require_group("plane");
    Plane p;
    p.normal = attribute_real3(r, "plane", "normal");
    p.distance = attribute_reals(r, "plane", "distance", 1)[0];
    d.plane = p;
  }
  return d;
}

// ---------------------------------------------------------------- writing

[[noreturn]] void write_fail(const std::string& path, const std::string& field, const std::string& what) {
  throw Error(path + ": cannot write " + field + ": " + what);
}

// The number of rows of a flat array of `columns` values per row.
hsize_t rows(const std::string& path, const std::string& field, size_t size, int columns) {
  if (columns <= 0) write_fail(path, field, "needs a positive number of values per row, got " + std::to_string(columns));
  if (size % static_cast<size_t>(columns) != 0)
    write_fail(path, field, std::to_string(size) + " values are not a multiple of " + std::to_string(columns));
  return size / static_cast<size_t>(columns);
}

// Attributes of reals in the build's precision.
[[maybe_unused]] void real_attribute(h5::Writer& w, const std::string& object, const std::string& name, const std::vector<float>& values) {
  w.attribute_f32(object, name, values);
}
[[maybe_unused]] void real_attribute(h5::Writer& w, const std::string& object, const std::string& name, const std::vector<double>& values) {
  w.attribute(object, name, values);
}

std::vector<real> vector_values(const Real3& v) { return {v.x(), v.y(), v.z()}; }
std::vector<real> quaternion_values(const Quaternion& q) { return {q.x(), q.y(), q.z(), q.w()}; }

void write_skinning(h5::Writer& w, const std::string& path, const std::string& g, const std::string& field, const SkinningData& s) {
  w.group(g);
  const int k = s.weights_per_node;
  w.dataset(g + "/weights", {rows(path, field + ".weights", s.weights.size(), k), static_cast<hsize_t>(k)}, s.weights);
  w.dataset(g + "/indices", {rows(path, field + ".indices", s.indices.size(), k), static_cast<hsize_t>(k)}, s.indices);
}

void write_mesh(h5::Writer& w, const std::string& path, const std::string& g, const std::string& field, const MeshData& m,
                const char* skin_group) {
  w.group(g);
  w.dataset(g + "/coordinates", {rows(path, field + ".coordinates", m.coordinates.size(), 3), 3}, m.coordinates);
  if (!m.connectivity.empty()) {
    const int k = m.nodes_per_element;
    w.dataset(g + "/connectivity", {rows(path, field + ".connectivity", m.connectivity.size(), k), static_cast<hsize_t>(k)}, m.connectivity);
  }
  if (m.skinning) write_skinning(w, path, g + "/" + skin_group, field + ".skinning", *m.skinning);
}

void write_sdf(h5::Writer& w, const std::string& path, const GridSdfData& s) {
  if ((s.dims.array() < 0).any()) write_fail(path, "sdf.dims", "negative dimension");
  const size_t nx = static_cast<size_t>(s.dims[0]), ny = static_cast<size_t>(s.dims[1]), nz = static_cast<size_t>(s.dims[2]);
  if (nx * ny * nz != s.values.size())
    write_fail(path, "sdf.values", std::to_string(s.values.size()) + " values for dims " + std::to_string(nx) + " x " + std::to_string(ny) +
                                       " x " + std::to_string(nz));
  std::vector<real> c_order(s.values.size());
  for (size_t i = 0; i < nx; ++i)
    for (size_t j = 0; j < ny; ++j)
      for (size_t k = 0; k < nz; ++k) c_order[(i * ny + j) * nz + k] = s.values[i + nx * (j + ny * k)];
  w.group("sdf");
  w.dataset("sdf/grid", {nx, ny, nz}, c_order);
  real_attribute(w, "sdf/grid", "grid_min", vector_values(s.bounds.min));
  real_attribute(w, "sdf/grid", "grid_max", vector_values(s.bounds.max));
  real_attribute(w, "sdf/grid", "collider_min", vector_values(s.negative_value_bounds.min));
  real_attribute(w, "sdf/grid", "collider_max", vector_values(s.negative_value_bounds.max));
  if (s.scale) real_attribute(w, "sdf/grid", "scale", vector_values(*s.scale));
  if (s.rotation) real_attribute(w, "sdf/grid", "rotation", quaternion_values(*s.rotation));
  if (s.translation) real_attribute(w, "sdf/grid", "translation", vector_values(*s.translation));
}

void write_material(h5::Writer& w, const std::string& path, const PerElementSoftMaterialData& m) {
  w.group("material");
  w.string_attribute("material", "type", material_type_text(m.type));
  w.string_attribute("material", "psd_strategy", psd_strategy_text(m.psd_strategy));
  const std::pair<const char*, const std::vector<real>*> per_element[] = {
      {"youngs_modulus", &m.youngs_modulus}, {"poisson_ratio", &m.poisson_ratio}, {"aniso_alpha", &m.aniso_alpha},
      {"aniso_length", &m.aniso_length},     {"aniso_theta", &m.aniso_theta},     {"aniso_phi", &m.aniso_phi},
      {"arap_stiffness", &m.arap_stiffness}};
  for (const auto& [name, v] : per_element)
    if (!v->empty()) w.dataset(std::string("material/") + name, {v->size()}, *v);
  if (!m.shape_target_tensor.empty())
    w.dataset("material/shape_target_tensor", {rows(path, "material.shape_target_tensor", m.shape_target_tensor.size(), 6), 6},
              m.shape_target_tensor);
}

}  // namespace

ModelData read_h5(const std::string& path) {
  auto guard = h5::lock();
  // HDF5 itself can crash on a corrupt file: try it in a child process first
  try_in_child_process(path, [&] { (void)read_checked(path); }, "the HDF5 library");
  return read_checked(path);
}

void write_h5(const std::string& path, const ModelData& d) {
  auto guard = h5::lock();
  h5::Writer w(path);
  if (d.mesh) {
    write_mesh(w, path, "mesh", "mesh", *d.mesh, "skinning");
    if (d.blending && !d.blending->empty()) {
      w.group("mesh/blending", true);
      for (size_t k = 0; k < d.blending->size(); ++k) {
        const BlendingData& b = (*d.blending)[k];
        const std::string field = "blending[" + std::to_string(k) + "]";
        if (b.source_shape.empty() || b.source_shape.find('/') != std::string::npos || b.source_shape == ".")
          write_fail(path, field + ".source_shape", "'" + b.source_shape + "' cannot name an HDF5 group");
        const std::string g = "mesh/blending/" + b.source_shape;
        w.group(g);
        w.dataset(g + "/weights", {rows(path, field + ".weights", b.weights.size(), 2), 2}, b.weights);
        w.dataset(g + "/indices", {rows(path, field + ".indices", b.indices.size(), 2), 2}, b.indices);
      }
    }
    if (d.constrained_nodes && !d.constrained_nodes->empty())
      w.dataset("mesh/constrained_nodes", {d.constrained_nodes->size()}, *d.constrained_nodes);
    if (d.element_frame_axes && !d.element_frame_axes->empty())
      w.dataset("mesh/element_frame_axes", {rows(path, "element_frame_axes", d.element_frame_axes->size(), 3), 3}, *d.element_frame_axes);
  } else if ((d.blending && !d.blending->empty()) || (d.constrained_nodes && !d.constrained_nodes->empty()) ||
             (d.element_frame_axes && !d.element_frame_axes->empty())) {
    write_fail(path, "the model", "blending, constrained_nodes and element_frame_axes are stored with the mesh, and there is none");
  }
  if (d.visual_mesh) write_mesh(w, path, "visual_mesh", "visual_mesh", *d.visual_mesh, "embedding");
  if (d.sdf) write_sdf(w, path, *d.sdf);
  if (d.material) write_material(w, path, *d.material);
  if (d.box) {
    w.group("box");
    real_attribute(w, "box", "center", vector_values(d.box->center));
    real_attribute(w, "box", "half_extents", vector_values(d.box->half_extents));
    real_attribute(w, "box", "rotation", quaternion_values(d.box->rotation));
  }
  if (d.sphere) {
    w.group("sphere");
    real_attribute(w, "sphere", "center", vector_values(d.sphere->center));
    real_attribute(w, "sphere", "radius", std::vector<real>{d.sphere->radius});
  }
  if (d.plane) {
    w.group("plane");
    real_attribute(w, "plane", "normal", vector_values(d.plane->normal));
    real_attribute(w, "plane", "distance", std::vector<real>{d.plane->distance});
  }
  w.close();
}

}  // namespace model_io
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
