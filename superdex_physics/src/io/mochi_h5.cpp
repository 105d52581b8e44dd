// Reading and writing the groups of a `.mochi.h5` file (FORMATS.md), with checks that name the
// file, the group/dataset/attribute and the defect.

#include "superdex/physics/mochi_h5.h"

#include <cmath>
#include <sstream>

#include "core/crash_isolation.h"
#include "io/h5_file.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using h5::Numbers;
using h5::Reader;

std::string dims_text(const std::vector<hsize_t>& dims) {
  if (dims.empty()) return "a scalar";
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + "]";
}

std::string vec_text(const Vec3& v) {
  std::ostringstream os;
  os << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return os.str();
}

// Throws naming the first NaN or infinity; `position` renders a flat index for the message.
template <class Position>
void require_finite(const Reader& r, const std::string& where, const std::vector<double>& values, Position position) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) r.fail(where, std::string(std::isnan(values[i]) ? "NaN" : "infinite value") + " at " + position(i));
}

// An index stored in the file (read as a double), as text; a value beyond the range of long long
// (a uint64 dataset) is printed as a number rather than converted, which would be undefined.
std::string index_text(double v) {
  if (v >= -9.2e18 && v <= 9.2e18) return std::to_string(static_cast<long long>(v));
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string flat_position(size_t i) { return "index " + std::to_string(i); }

// A numeric attribute of exactly `n` finite values.
std::vector<double> attribute_values(const Reader& r, const std::string& group, const std::string& name, size_t n) {
  const Numbers a = r.attribute(group, name);
  const std::string where = group + "/" + name;
  if (a.values.size() != n)
    r.fail(where, "wrong shape: expected " + std::to_string(n) + (n == 1 ? " value" : " values") + ", got " + std::to_string(a.values.size()));
  require_finite(r, where, a.values, flat_position);
  return a.values;
}

Vec3 vec3_attribute(const Reader& r, const std::string& group, const std::string& name) {
  const auto v = attribute_values(r, group, name, 3);
  return Vec3(static_cast<real>(v[0]), static_cast<real>(v[1]), static_cast<real>(v[2]));
}

MochiMesh read_mesh(const Reader& r, const std::string& g) {
  r.require_group(g);
  MochiMesh m;
  const std::string cpath = g + "/coordinates", epath = g + "/connectivity";
  const Numbers c = r.dataset(cpath, false);
  if (c.dims.size() != 2) r.fail(cpath, "wrong rank: expected a 2-D dataset N x 3, got " + dims_text(c.dims));
  if (c.dims[1] != 3) r.fail(cpath, "wrong shape: expected N x 3, got " + dims_text(c.dims));
  if (c.dims[0] == 0) r.fail(cpath, "empty mesh: no nodes");
  require_finite(r, cpath, c.values, [](size_t i) { return "row " + std::to_string(i / 3) + ", column " + std::to_string(i % 3); });
  m.coordinates.resize(c.dims[0]);
  for (size_t i = 0; i < m.coordinates.size(); ++i)
    m.coordinates[i] = Eigen::Vector3d(c.values[3 * i], c.values[3 * i + 1], c.values[3 * i + 2]).cast<real>();

  const Numbers e = r.dataset(epath, true);
  const std::string expected = "M x 2 (a rod's polyline), M x 3 (triangles) or M x 4 (tetrahedra)";
  if (e.dims.size() != 2) r.fail(epath, "wrong rank: expected a 2-D dataset " + expected + ", got " + dims_text(e.dims));
  if (e.dims[1] < 2 || e.dims[1] > 4) r.fail(epath, "wrong shape: expected " + expected + ", got " + dims_text(e.dims));
  if (e.dims[0] == 0) r.fail(epath, "empty mesh: no elements");
  m.nodes_per_element = static_cast<int>(e.dims[1]);
  const double n = static_cast<double>(m.coordinates.size());
  m.connectivity.resize(e.values.size());
  for (size_t i = 0; i < e.values.size(); ++i) {
    if (!(e.values[i] >= 0 && e.values[i] < n))
      r.fail(epath, "index " + index_text(e.values[i]) + " at row " + std::to_string(i / e.dims[1]) +
                        " out of range: the mesh has " + std::to_string(m.coordinates.size()) + " nodes");
    m.connectivity[i] = static_cast<int>(e.values[i]);
  }

  const std::string npath = g + "/constrained_nodes";
  if (r.has(npath)) {
    const Numbers cn = r.dataset(npath, true);
    if (cn.dims.size() > 2 || (cn.dims.size() == 2 && cn.dims[1] != 1))
      r.fail(npath, "wrong shape: expected a list of node indices, got " + dims_text(cn.dims));
    for (size_t i = 0; i < cn.values.size(); ++i) {
      if (!(cn.values[i] >= 0 && cn.values[i] < n))
        r.fail(npath, "node " + index_text(cn.values[i]) + " at index " + std::to_string(i) +
                          " out of range: the mesh has " + std::to_string(m.coordinates.size()) + " nodes");
      m.constrained_nodes.push_back(static_cast<int>(cn.values[i]));
    }
  }
  return m;
}

MochiSdf read_sdf(const Reader& r) {
  r.require_group("sdf");
  MochiSdf s;
  const Numbers g = r.dataset("sdf/grid", false);
  if (g.dims.size() != 3) r.fail("sdf/grid", "wrong rank: expected a 3-D dataset [nx, ny, nz], got " + dims_text(g.dims));
  for (hsize_t d : g.dims)
    if (d < 2) r.fail("sdf/grid", "wrong shape: every dimension must be at least 2, got " + dims_text(g.dims));
  const size_t nx = g.dims[0], ny = g.dims[1], nz = g.dims[2];
  // the file is C order (z fastest); SdfGrid is x fastest
  require_finite(r, "sdf/grid", g.values, [&](size_t f) {
    std::ostringstream os;
    os << "[" << f / (ny * nz) << ", " << (f / nz) % ny << ", " << f % nz << "]";
    return os.str();
  });
  s.grid.size = {static_cast<int>(nx), static_cast<int>(ny), static_cast<int>(nz)};
  s.grid.values.resize(g.values.size());
  for (size_t i = 0; i < nx; ++i)
    for (size_t j = 0; j < ny; ++j)
      for (size_t k = 0; k < nz; ++k) s.grid.values[i + nx * (j + ny * k)] = static_cast<real>(g.values[(i * ny + j) * nz + k]);
  // attributes on the grid dataset (SuperDex's layout, model::save_to_file) or on the group
  const std::string at = r.has_attribute("sdf/grid", "grid_min") ? "sdf/grid" : "sdf";
  s.grid.grid_min = vec3_attribute(r, at, "grid_min");
  s.grid.grid_max = vec3_attribute(r, at, "grid_max");
  if (!(s.grid.grid_min.array() < s.grid.grid_max.array()).all())
    r.fail(at, "grid_min must be < grid_max on every axis, got grid_min " + vec_text(s.grid.grid_min) + " and grid_max " +
                      vec_text(s.grid.grid_max));
  if (r.has_attribute(at, "scale")) {
    const Numbers a = r.attribute(at, "scale");
    if (a.values.size() != 1 && a.values.size() != 3) r.fail("sdf/scale", "wrong shape: expected 1 or 3 values, got " + std::to_string(a.values.size()));
    require_finite(r, "sdf/scale", a.values, flat_position);
    const Vec3 scale = a.values.size() == 1 ? Vec3::Constant(static_cast<real>(a.values[0]))
                                            : Vec3(static_cast<real>(a.values[0]), static_cast<real>(a.values[1]), static_cast<real>(a.values[2]));
    if ((scale.array() <= 0).any()) r.fail("sdf/scale", "must be positive, got " + vec_text(scale));
    s.scale = scale;
  }
  if (r.has_attribute(at, "rotation")) {
    const auto q = attribute_values(r, at, "rotation", 4);
    const Quat rot(static_cast<real>(q[3]), static_cast<real>(q[0]), static_cast<real>(q[1]), static_cast<real>(q[2]));
    if (rot.norm() < real(1e-6)) r.fail("sdf/rotation", "must be a non-zero quaternion [x, y, z, w]");
    s.rotation = rot.normalized();
  }
  if (r.has_attribute(at, "translation")) s.translation = vec3_attribute(r, at, "translation");
  return s;
}

// A per-element material dataset: a list of finite values (or one for all elements).
std::vector<real> material_values(const Reader& r, const std::string& path) {
  std::vector<real> out;
  if (!r.has(path)) return out;
  const Numbers d = r.dataset(path, false);
  if (d.dims.size() > 2 || (d.dims.size() == 2 && d.dims[1] != 1))
    r.fail(path, "wrong shape: expected one value per element, got " + dims_text(d.dims));
  require_finite(r, path, d.values, flat_position);
  for (double x : d.values) out.push_back(static_cast<real>(x));
  return out;
}

MochiMaterial read_material(const Reader& r, const std::optional<MochiMesh>& mesh) {
  r.require_group("material");
  MochiMaterial m;
  m.type = r.string_attribute("material", "type");
  m.youngs_modulus = material_values(r, "material/youngs_modulus");
  m.poisson_ratio = material_values(r, "material/poisson_ratio");
  for (real e : m.youngs_modulus)
    if (e <= 0) r.fail("material/youngs_modulus", "must be positive, got " + std::to_string(e));
  for (real nu : m.poisson_ratio)
    if (nu <= -1 || nu >= real(0.5)) r.fail("material/poisson_ratio", "must lie in (-1, 0.5), got " + std::to_string(nu));
  if (mesh) {
    const size_t elements = static_cast<size_t>(mesh->num_elements());
    for (const auto* v : {&m.youngs_modulus, &m.poisson_ratio}) {
      const char* name = v == &m.youngs_modulus ? "material/youngs_modulus" : "material/poisson_ratio";
      if (v->size() > 1 && v->size() != elements)
        r.fail(name, "expected one value per element (" + std::to_string(elements) + ") or one for all, got " + std::to_string(v->size()));
    }
  }
  return m;
}

// Reads every group present, checking each; HDF5 lock held by the caller.
MochiH5 read_checked(const std::string& path) {
  const Reader r(path);
  MochiH5 out;
  if (r.has("mesh")) out.mesh = read_mesh(r, "mesh");
  if (r.has("visual_mesh")) out.visual_mesh = read_mesh(r, "visual_mesh");
  if (r.has("sdf")) out.sdf = read_sdf(r);
  if (r.has("material")) out.material = read_material(r, out.mesh);
  if (r.has("box")) {
    r.require_group("box");
    const Vec3 h = vec3_attribute(r, "box", "half_extents");
    if ((h.array() <= 0).any()) r.fail("box/half_extents", "must be positive, got " + vec_text(h));
    out.box = BoxShape{h};
  }
  if (r.has("sphere")) {
    r.require_group("sphere");
    SphereShape s;
    s.radius = static_cast<real>(attribute_values(r, "sphere", "radius", 1)[0]);
    if (s.radius <= 0) r.fail("sphere/radius", "must be positive, got " + std::to_string(s.radius));
    if (r.has_attribute("sphere", "center")) s.center = vec3_attribute(r, "sphere", "center");
    out.sphere = s;
  }
  if (r.has("plane")) {
    r.require_group("plane");
    PlaneShape p;
    p.normal = vec3_attribute(r, "plane", "normal");
    if (p.normal.norm() < real(1e-9)) r.fail("plane/normal", "must be non-zero");
    p.distance = static_cast<real>(attribute_values(r, "plane", "distance", 1)[0]);
    const real len = p.normal.norm();
    p.normal /= len;
    p.distance /= len;
    out.plane = p;
  }
  return out;
}

}  // namespace

MochiH5 read_mochi_h5(const std::string& path) {
  auto guard = h5::lock();
  // HDF5 itself can crash on a corrupt file (fuzz/regressions/mochi_h5/): try it in a child first
  try_in_child_process(path, [&] { (void)read_checked(path); }, "the HDF5 library");
  return read_checked(path);
}

namespace {

void write_mesh(h5::Writer& w, const std::string& g, const MochiMesh& m) {
  w.group(g);
  std::vector<double> c;
  c.reserve(3 * m.coordinates.size());
  for (const Vec3& p : m.coordinates) c.insert(c.end(), {double(p.x()), double(p.y()), double(p.z())});
  w.dataset(g + "/coordinates", {m.coordinates.size(), 3}, c);
  const hsize_t k = static_cast<hsize_t>(m.nodes_per_element);
  w.dataset(g + "/connectivity", {k > 0 ? m.connectivity.size() / k : 0, k}, m.connectivity);
  if (!m.constrained_nodes.empty()) w.dataset(g + "/constrained_nodes", {m.constrained_nodes.size()}, m.constrained_nodes);
}

std::vector<double> doubles(const Vec3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }

}  // namespace

void write_mochi_h5(const std::string& path, const MochiH5& data) {
  auto guard = h5::lock();
  h5::Writer w(path);
  if (data.mesh) write_mesh(w, "mesh", *data.mesh);
  if (data.visual_mesh) write_mesh(w, "visual_mesh", *data.visual_mesh);
  if (data.sdf) {
    const SdfGrid& g = data.sdf->grid;
    w.group("sdf");
    const size_t nx = static_cast<size_t>(g.size[0]), ny = static_cast<size_t>(g.size[1]), nz = static_cast<size_t>(g.size[2]);
    std::vector<double> values(nx * ny * nz, 0.0);
    for (size_t i = 0; i < nx; ++i)
      for (size_t j = 0; j < ny; ++j)
        for (size_t k = 0; k < nz; ++k) {
          const size_t src = i + nx * (j + ny * k);
          values[(i * ny + j) * nz + k] = src < g.values.size() ? double(g.values[src]) : 0.0;
        }
    w.dataset("sdf/grid", {nx, ny, nz}, values);
    w.attribute("sdf", "grid_min", doubles(g.grid_min));
    w.attribute("sdf", "grid_max", doubles(g.grid_max));
    if (data.sdf->scale) w.attribute("sdf", "scale", doubles(*data.sdf->scale));
    if (data.sdf->rotation) {
      const Quat& q = *data.sdf->rotation;
      w.attribute("sdf", "rotation", {double(q.x()), double(q.y()), double(q.z()), double(q.w())});
    }
    if (data.sdf->translation) w.attribute("sdf", "translation", doubles(*data.sdf->translation));
  }
  if (data.material) {
    w.group("material");
    w.string_attribute("material", "type", data.material->type);
    auto list = [](const std::vector<real>& v) { return std::vector<double>(v.begin(), v.end()); };
    if (!data.material->youngs_modulus.empty())
      w.dataset("material/youngs_modulus", {data.material->youngs_modulus.size()}, list(data.material->youngs_modulus));
    if (!data.material->poisson_ratio.empty())
      w.dataset("material/poisson_ratio", {data.material->poisson_ratio.size()}, list(data.material->poisson_ratio));
  }
  if (data.box) {
    w.group("box");
    w.attribute("box", "half_extents", doubles(data.box->half_extents));
  }
  if (data.sphere) {
    w.group("sphere");
    w.attribute("sphere", "radius", {double(data.sphere->radius)});
    if (!data.sphere->center.isZero()) w.attribute("sphere", "center", doubles(data.sphere->center));
  }
  if (data.plane) {
    w.group("plane");
    w.attribute("plane", "normal", doubles(data.plane->normal));
    w.attribute("plane", "distance", {double(data.plane->distance)});
  }
  w.close();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
