// Rod models with a tubular visual mesh (rod_model_data.h).

#include "superdex/physics/rod_model_data.h"

#include <cmath>
#include <numbers>
#include <string>

#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

ModelData generate_tubular_rod_model_data(const std::vector<Real3>& nodes, const std::vector<Real3>& element_frame_axes, real radius,
                                          int num_cross_section_segments, bool is_closed_loop) {
  const std::string what = "generate_tubular_rod_model_data";
  const int n = static_cast<int>(nodes.size());
  const int segments = num_cross_section_segments;
  if (n < 2 || (is_closed_loop && n < 3))
    throw Error(what + ": nodes: a rod needs at least " + std::string(is_closed_loop ? "3 nodes in a closed loop" : "2 nodes") + ", got " +
                std::to_string(n));
  const int ne = is_closed_loop ? n : n - 1;
  if (static_cast<int>(element_frame_axes.size()) != ne)
    throw Error(what + ": element_frame_axes: expected one axis per element (" + std::to_string(ne) + "), got " +
                std::to_string(element_frame_axes.size()));
  if (!(std::isfinite(radius) && radius > 0)) throw Error(what + ": radius must be a positive finite number (m), got " + std::to_string(radius));
  if (segments < 3) throw Error(what + ": num_cross_section_segments must be >= 3, got " + std::to_string(segments));
  for (int i = 0; i < n; ++i)
    if (!nodes[i].allFinite()) throw Error(what + ": nodes[" + std::to_string(i) + "] is not finite");
  // each element's tangent and its axis made unit and normal to it
  std::vector<Vec3> t(ne), d1(ne);
  for (int e = 0; e < ne; ++e) {
    const Vec3 d = nodes[(e + 1) % n] - nodes[e];
    if (!(d.norm() > 0)) throw Error(what + ": nodes " + std::to_string(e) + " and " + std::to_string((e + 1) % n) + " coincide");
    t[e] = d.normalized();
    const Vec3 u = element_frame_axes[e] - t[e] * element_frame_axes[e].dot(t[e]);
    if (!(u.allFinite() && u.norm() > real(1e-6) * std::max(real(1), element_frame_axes[e].norm())))
      throw Error(what + ": element_frame_axes[" + std::to_string(e) + "] is zero, not finite or along its element");
    d1[e] = u.normalized();
  }
  ModelData model;
  MeshData line;
  line.nodes_per_element = 2;
  for (const Real3& p : nodes) line.coordinates.insert(line.coordinates.end(), {p.x(), p.y(), p.z()});
  for (int e = 0; e < ne; ++e) line.connectivity.insert(line.connectivity.end(), {e, (e + 1) % n});
  model.mesh = std::move(line);
  std::vector<real> axes;
  for (const Vec3& a : d1) axes.insert(axes.end(), {a.x(), a.y(), a.z()});
  model.element_frame_axes = std::move(axes);
  // the elements meeting at node i (one at an open rod's ends)
  auto adjacent = [&](int i) -> std::pair<int, int> {
    if (is_closed_loop) return {(i + ne - 1) % ne, i};
    if (i == 0) return {0, 0};
    if (i == n - 1) return {ne - 1, ne - 1};
    return {i - 1, i};
  };
  MeshData tube;
  tube.nodes_per_element = 3;
  SkinningData skin;
  skin.weights_per_node = 2;
  auto add_vertex = [&](const Vec3& p, std::pair<int, int> elements) {
    tube.coordinates.insert(tube.coordinates.end(), {p.x(), p.y(), p.z()});
    skin.indices.insert(skin.indices.end(), {elements.first, elements.second});
    skin.weights.insert(skin.weights.end(), {real(0.5), real(0.5)});
  };
  // a ring of vertices around each node, normal to the mean of its elements' tangents
  constexpr real two_pi = 2 * std::numbers::pi_v<real>;
  for (int i = 0; i < n; ++i) {
    const auto [e, f] = adjacent(i);
    const Vec3 tangent = (t[e] + t[f]).normalized();
    Vec3 axis = d1[e] + d1[f];
    axis = (axis - tangent * axis.dot(tangent)).normalized();
    const Vec3 other = tangent.cross(axis);
    for (int k = 0; k < segments; ++k) {
      const real phi = two_pi * k / segments;
      add_vertex(nodes[i] + radius * (std::cos(phi) * axis + std::sin(phi) * other), {e, f});
    }
  }
  // the tube's sides, counter-clockwise seen from outside
  auto ring = [&](int i, int k) { return i * segments + k % segments; };
  for (int i = 0; i < ne; ++i) {
    const int j = (i + 1) % n;
    for (int k = 0; k < segments; ++k) {
      tube.connectivity.insert(tube.connectivity.end(), {ring(i, k), ring(j, k + 1), ring(j, k)});
      tube.connectivity.insert(tube.connectivity.end(), {ring(i, k), ring(i, k + 1), ring(j, k + 1)});
    }
  }
  // an open rod's caps
  if (!is_closed_loop) {
    const int start = n * segments;
    add_vertex(nodes[0], adjacent(0));
    const int end = start + 1;
    add_vertex(nodes[n - 1], adjacent(n - 1));
    for (int k = 0; k < segments; ++k) {
      tube.connectivity.insert(tube.connectivity.end(), {start, ring(0, k + 1), ring(0, k)});
      tube.connectivity.insert(tube.connectivity.end(), {end, ring(n - 1, k), ring(n - 1, k + 1)});
    }
  }
  tube.skinning = std::move(skin);
  model.visual_mesh = std::move(tube);
  return model;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
