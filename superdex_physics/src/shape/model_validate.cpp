// model::validate (model.h): the rules a model must satisfy to be used, each failure a
// superdex::Error naming the field ("mesh.connectivity[12]: node 40 out of range (8 nodes)").

#include <climits>
#include <cmath>
#include <sstream>

#include "superdex/physics/error.h"
#include "superdex/physics/model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

[[noreturn]] void fail(const std::string& field, const std::string& what) { throw Error(field + ": " + what); }

std::string text(double x) {
  std::ostringstream os;
  os.precision(9);
  os << x;
  return os.str();
}

std::string at(const std::string& field, size_t i) { return field + "[" + std::to_string(i) + "]"; }

template <class V>
void require_finite(const std::string& field, const V& values) {
  for (int i = 0; i < static_cast<int>(values.size()); ++i)
    if (!std::isfinite(values[i])) fail(at(field, static_cast<size_t>(i)), "must be finite, got " + text(values[i]));
}

void require_size(const std::string& field, size_t size, size_t expected, const std::string& meaning) {
  if (size != expected) fail(field, "must have " + std::to_string(expected) + " values (" + meaning + "), got " + std::to_string(size));
}

// The segments of a polyline mesh: its connectivity's, or one between consecutive nodes when it has none.
int polyline_segments(const MeshData& m) { return m.connectivity.empty() ? std::max(0, m.num_nodes() - 1) : m.num_elements(); }

// How skinning indices of a mesh refer to the simulation mesh: up to max_index (inclusive).
struct SkinTarget {
  long long max_index = LLONG_MAX;
  std::string what = "index";  // "node" or "element"
  int count = -1;              // for messages
};

void validate_skinning(const SkinningData& s, int num_nodes, const SkinTarget& target, const std::string& f) {
  if (s.weights_per_node < 1) fail(f + ".weights_per_node", "must be >= 1, got " + std::to_string(s.weights_per_node));
  const size_t n = static_cast<size_t>(s.weights_per_node) * static_cast<size_t>(num_nodes);
  require_size(f + ".weights", s.weights.size(), n, std::to_string(s.weights_per_node) + " per node");
  require_size(f + ".indices", s.indices.size(), n, std::to_string(s.weights_per_node) + " per node");
  require_finite(f + ".weights", s.weights);
  for (size_t i = 0; i < s.indices.size(); ++i)
    if (s.indices[i] < 0 || s.indices[i] > target.max_index)
      fail(at(f + ".indices", i), target.what + " " + std::to_string(s.indices[i]) + " out of range" +
                                      (target.count >= 0 ? " (" + std::to_string(target.count) + " " + target.what + "s)" : " (must be >= 0)"));
  for (int node = 0; node < num_nodes; ++node) {
    double sum = 0;
    for (int k = 0; k < s.weights_per_node; ++k) sum += s.weights[static_cast<size_t>(node) * s.weights_per_node + k];
    if (std::abs(sum - 1.0) > 1e-5) fail(f + ".weights", "the weights of node " + std::to_string(node) + " sum to " + text(sum) + ", not 1");
  }
}

void validate_polyline(const MeshData& m, const std::string& f) {
  const int n = m.num_nodes();
  const size_t conn = m.connectivity.size();
  const bool closed = conn == 2 * static_cast<size_t>(n);
  if (closed && n < 3) fail(f + ".connectivity", "a closed polyline needs at least 3 nodes, got " + std::to_string(n));
  if (!m.connectivity.empty()) {
    if (!closed && conn != 2 * static_cast<size_t>(n - 1))
      fail(f + ".connectivity", "a polyline's segments join consecutive nodes: expected " + std::to_string(2 * (n - 1)) + " (open) or " +
                                    std::to_string(2 * n) + " (closed) values, got " + std::to_string(conn));
    for (size_t e = 0; e < conn / 2; ++e) {
      const int a = static_cast<int>(e), b = (a + 1) % n;
      if (m.connectivity[2 * e] != a || m.connectivity[2 * e + 1] != b)
        fail(at(f + ".connectivity", 2 * e), "segment " + std::to_string(e) + " must be [" + std::to_string(a) + ", " + std::to_string(b) +
                                                 "], got [" + std::to_string(m.connectivity[2 * e]) + ", " + std::to_string(m.connectivity[2 * e + 1]) + "]");
    }
  }
  const int segments = closed ? n : n - 1;
  auto node = [&](int i) { return Eigen::Vector3d(m.coordinates[3 * i], m.coordinates[3 * i + 1], m.coordinates[3 * i + 2]); };
  std::vector<Eigen::Vector3d> tangent(static_cast<size_t>(segments));
  for (int e = 0; e < segments; ++e) {
    const Eigen::Vector3d d = node((e + 1) % n) - node(e);
    if (d.norm() < 1e-6) fail(f + ".coordinates", "segment " + std::to_string(e) + " is shorter than 1e-6 m (" + text(d.norm()) + ")");
    tangent[static_cast<size_t>(e)] = d.normalized();
  }
  for (int e = 0; e + 1 < segments || (closed && e < segments); ++e) {
    const int next = (e + 1) % segments;
    if (tangent[static_cast<size_t>(e)].dot(tangent[static_cast<size_t>(next)]) < 1e-3 - 1)
      fail(f + ".coordinates", "segments " + std::to_string(e) + " and " + std::to_string(next) + " fold back onto each other");
  }
}

void validate_mesh(const MeshData& m, const std::string& f, const SkinTarget& skin_target) {
  const int npe = m.nodes_per_element;
  if (npe < 2 || npe > 4) fail(f + ".nodes_per_element", "must be 2 (polyline), 3 (triangles) or 4 (tetrahedra), got " + std::to_string(npe));
  if (m.coordinates.size() > static_cast<size_t>(INT_MAX)) fail(f + ".coordinates", "too many values");
  if (m.coordinates.size() % 3 != 0) fail(f + ".coordinates", "must hold 3 values per node, got " + std::to_string(m.coordinates.size()));
  const int n = m.num_nodes();
  if (n < npe) fail(f + ".coordinates", "must hold at least " + std::to_string(npe) + " nodes, got " + std::to_string(n));
  require_finite(f + ".coordinates", m.coordinates);
  if (m.connectivity.size() > static_cast<size_t>(INT_MAX)) fail(f + ".connectivity", "too many values");
  if (m.connectivity.size() % static_cast<size_t>(npe) != 0)
    fail(f + ".connectivity", "must hold " + std::to_string(npe) + " values per element, got " + std::to_string(m.connectivity.size()));
  for (size_t i = 0; i < m.connectivity.size(); ++i)
    if (m.connectivity[i] < 0 || m.connectivity[i] >= n)
      fail(at(f + ".connectivity", i), "node " + std::to_string(m.connectivity[i]) + " out of range (" + std::to_string(n) + " nodes)");
  if (m.skinning) validate_skinning(*m.skinning, n, skin_target, f + ".skinning");
  if (npe == 2) validate_polyline(m, f);
}

void validate_material(const PerElementSoftMaterialData& m, int elements) {
  const std::string f = "material";
  using T = SoftMaterialType;
  using P = MaterialPsdStrategy;
  const int type = static_cast<int>(m.type), psd = static_cast<int>(m.psd_strategy);
  if (type < 0 || type > 5) fail(f + ".type", "unknown material type " + std::to_string(type));
  if (psd < 0 || psd > 5) fail(f + ".psd_strategy", "unknown PSD strategy " + std::to_string(psd));
  const bool isotropic_hyperelastic = m.type == T::NeoHookean || m.type == T::StVenantKirchhoff;
  const bool supported = m.type == T::LinearElastic || m.psd_strategy == P::MaterialDefault || m.psd_strategy == P::None ||
                         m.psd_strategy == P::Projection || m.psd_strategy == P::AbsEigenProjection ||
                         (m.psd_strategy == P::Fast && isotropic_hyperelastic) ||
                         (m.psd_strategy == P::PerTermProjection && m.type == T::ActiveShapeTargetingArap);
  if (!supported) fail(f + ".psd_strategy", "strategy " + std::to_string(psd) + " is not available for material type " + std::to_string(type));
  const size_t n = static_cast<size_t>(elements);
  auto per_element = [&](const char* name, const std::vector<real>& v, size_t per, double lo, bool lo_open, double hi) {
    const std::string field = f + "." + name;
    require_size(field, v.size(), per * n, std::to_string(per) + " per element of the mesh");
    for (size_t i = 0; i < v.size(); ++i) {
      const double x = v[i];
      if (!std::isfinite(x)) fail(at(field, i), "must be finite, got " + text(x));
      if ((lo_open ? x <= lo : x < lo) || x >= hi)
        fail(at(field, i), "must be in " + std::string(lo_open ? "(" : "[") + text(lo) + ", " + text(hi) + "), got " + text(x));
    }
  };
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (m.type == T::NeoHookean || m.type == T::StVenantKirchhoff || m.type == T::LinearElastic || m.type == T::ActiveNeoHookean) {
    per_element("youngs_modulus", m.youngs_modulus, 1, 0, true, inf);
    per_element("poisson_ratio", m.poisson_ratio, 1, -1, true, 0.5);
  }
  if (m.type == T::ActiveNeoHookean) {
    per_element("aniso_alpha", m.aniso_alpha, 1, 0, false, inf);
    per_element("aniso_length", m.aniso_length, 1, 0, false, inf);
    per_element("aniso_theta", m.aniso_theta, 1, -inf, false, inf);
    per_element("aniso_phi", m.aniso_phi, 1, -inf, false, inf);
  }
  if (m.type == T::Arap || m.type == T::ActiveShapeTargetingArap) per_element("arap_stiffness", m.arap_stiffness, 1, 0, true, inf);
  if (m.type == T::ActiveShapeTargetingArap) per_element("shape_target_tensor", m.shape_target_tensor, 6, -inf, false, inf);
}

void validate_sdf(const GridSdfData& s) {
  const std::string f = "sdf";
  for (int a = 0; a < 3; ++a)
    if (s.dims[a] < 2) fail(f + ".dims", "every dimension must be at least 2, got [" + std::to_string(s.dims[0]) + ", " +
                                             std::to_string(s.dims[1]) + ", " + std::to_string(s.dims[2]) + "]");
  const double count = double(s.dims[0]) * s.dims[1] * s.dims[2];
  if (count >= INT_MAX) fail(f + ".dims", "too many samples (" + text(count) + ")");
  require_size(f + ".values", s.values.size(), static_cast<size_t>(count), "dims[0] x dims[1] x dims[2]");
  for (const auto& [name, box] : {std::pair<const char*, const Aabb*>{"bounds", &s.bounds}, {"negative_value_bounds", &s.negative_value_bounds}}) {
    require_finite(f + "." + name + ".min", box->min);
    require_finite(f + "." + name + ".max", box->max);
    if (!(box->max.array() > box->min.array()).all()) fail(f + "." + name, "max must exceed min on every axis");
  }
  if (!(s.negative_value_bounds.min.array() >= s.bounds.min.array()).all() || !(s.negative_value_bounds.max.array() <= s.bounds.max.array()).all())
    fail(f + ".negative_value_bounds", "must lie within sdf.bounds");
  require_finite(f + ".values", s.values);
  if (s.scale) {
    require_finite(f + ".scale", *s.scale);
    const Real3 a = s.scale->cwiseAbs();
    if ((a.array() < std::numeric_limits<real>::epsilon()).any()) fail(f + ".scale", "components must not be zero");
    if (a.maxCoeff() - a.minCoeff() > real(1e-6) * a.maxCoeff()) fail(f + ".scale", "must be uniform in absolute value (a grid cannot stretch)");
  }
  if (s.rotation) {
    require_finite(f + ".rotation", s.rotation->coeffs());
    if (std::abs(s.rotation->norm() - 1) > 1e-6) fail(f + ".rotation", "must be a unit quaternion, its norm is " + text(s.rotation->norm()));
  }
  if (s.translation) require_finite(f + ".translation", *s.translation);
}

}  // namespace

namespace model {

void validate(const ModelData& d) {
  const int shapes = int(d.mesh.has_value()) + int(d.box.has_value()) + int(d.plane.has_value()) + int(d.sphere.has_value());
  if (shapes != 1)
    fail("model", "must contain exactly one type of shape (mesh, box, plane or sphere), got " + std::to_string(shapes));
  if (d.mesh) validate_mesh(*d.mesh, "mesh", SkinTarget{});
  const bool polyline = d.mesh && d.mesh->nodes_per_element == 2;
  if (d.visual_mesh) {
    if (d.visual_mesh->nodes_per_element != 3)
      fail("visual_mesh.nodes_per_element", "must be 3 (triangles), got " + std::to_string(d.visual_mesh->nodes_per_element));
    SkinTarget target;
    if (d.mesh) {
      target.count = polyline ? polyline_segments(*d.mesh) : d.mesh->num_nodes();
      target.max_index = target.count - 1;
      target.what = polyline ? "element" : "node";
    } else if (d.visual_mesh->skinning) {
      fail("visual_mesh.skinning", "refers to the simulation mesh, and the model has none");
    }
    if (polyline && !d.visual_mesh->skinning) fail("visual_mesh.skinning", "is required when the simulation mesh is a polyline");
    validate_mesh(*d.visual_mesh, "visual_mesh", target);
  }
  const int nodes = d.mesh ? d.mesh->num_nodes() : 0;
  if (d.blending) {
    if (!d.mesh) fail("blending", "needs a mesh");
    for (size_t k = 0; k < d.blending->size(); ++k) {
      const BlendingData& b = (*d.blending)[k];
      const std::string f = at("blending", k);
      if (b.source_shape.empty()) fail(f + ".source_shape", "must not be empty");
      require_size(f + ".weights", b.weights.size(), 2 * static_cast<size_t>(nodes), "2 per mesh node");
      require_finite(f + ".weights", b.weights);
      require_size(f + ".indices", b.indices.size(), 2 * static_cast<size_t>(nodes), "2 per mesh node");
      for (size_t i = 0; i < b.indices.size(); ++i)
        if (b.indices[i] < 0) fail(at(f + ".indices", i), "must be >= 0, got " + std::to_string(b.indices[i]));
    }
  }
  if (d.constrained_nodes) {
    if (!d.mesh) fail("constrained_nodes", "needs a mesh");
    for (size_t i = 0; i < d.constrained_nodes->size(); ++i) {
      const int v = (*d.constrained_nodes)[i];
      if (v < 0 || v >= nodes) fail(at("constrained_nodes", i), "node " + std::to_string(v) + " out of range (" + std::to_string(nodes) + " nodes)");
    }
  }
  if (d.element_frame_axes) {
    const std::vector<real>& axes = *d.element_frame_axes;
    if (!polyline) fail("element_frame_axes", "needs a polyline mesh (nodes_per_element 2)");
    if (axes.size() % 3 != 0) fail("element_frame_axes", "must hold 3 values per element, got " + std::to_string(axes.size()));
    const int segments = polyline_segments(*d.mesh);
    require_size("element_frame_axes", axes.size(), 3 * static_cast<size_t>(segments), "3 per element");
    require_finite("element_frame_axes", axes);
    const auto& c = d.mesh->coordinates;
    const int n = d.mesh->num_nodes();
    for (int e = 0; e < segments; ++e) {
      const Eigen::Vector3d axis(axes[3 * e], axes[3 * e + 1], axes[3 * e + 2]);
      const int b = (e + 1) % n;
      const Eigen::Vector3d tangent =
          Eigen::Vector3d(c[3 * b] - c[3 * e], c[3 * b + 1] - c[3 * e + 1], c[3 * b + 2] - c[3 * e + 2]).normalized();
      const std::string f = at("element_frame_axes", 3 * static_cast<size_t>(e));
      if (std::abs(axis.norm() - 1) > 1e-3) fail(f, "the axis of element " + std::to_string(e) + " must have length 1, got " + text(axis.norm()));
      if (std::abs(axis.dot(tangent)) > 1e-3) fail(f, "the axis of element " + std::to_string(e) + " must be normal to the element");
    }
  }
  if (d.box) {
    require_finite("box.center", d.box->center);
    require_finite("box.half_extents", d.box->half_extents);
    require_finite("box.rotation", d.box->rotation.coeffs());
    for (int a = 0; a < 3; ++a)
      if (d.box->half_extents[a] < std::numeric_limits<real>::epsilon())
        fail(at("box.half_extents", static_cast<size_t>(a)), "must be positive, got " + text(d.box->half_extents[a]));
    if (std::abs(d.box->rotation.norm() - 1) > 1e-6) fail("box.rotation", "must be a unit quaternion, its norm is " + text(d.box->rotation.norm()));
  }
  if (d.plane) {
    require_finite("plane.normal", d.plane->normal);
    if (!std::isfinite(d.plane->distance)) fail("plane.distance", "must be finite");
    if (std::abs(d.plane->normal.norm() - 1) > 1e-6) fail("plane.normal", "must have length 1, got " + text(d.plane->normal.norm()));
  }
  if (d.sphere) {
    require_finite("sphere.center", d.sphere->center);
    if (!(std::isfinite(d.sphere->radius) && d.sphere->radius > 0)) fail("sphere.radius", "must be positive, got " + text(d.sphere->radius));
  }
  if (d.sdf) validate_sdf(*d.sdf);
  if (d.material) {
    if (!d.mesh) fail("material", "needs a mesh");
    validate_material(*d.material, d.mesh->num_elements());
  }
}

}  // namespace model
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
