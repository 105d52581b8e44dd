// A rod drawn as a tube (rod_display.h).

#include "output/rod_display.h"

#include <cmath>
#include <numbers>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The cross-section's radius from the model: each element's spin mass is J l0 / L^2, its mass
// rho A l0.
real display_radius(const SoftBody& b) {
  const RodModel& rod = *b.model.rod;
  real J = 0, length = 0;
  for (const RodElement& e : rod.elements) {
    J += e.spin_mass * e.ghost_distance * e.ghost_distance;
    length += e.rest_length;
  }
  const real rho_A = b.model.total_mass / length;
  return std::sqrt(2 * (J / length) / rho_A);
}

}  // namespace

void rod_display_vertices(const SoftBody& b, VecX& out) {
  const RodModel& rod = *b.model.rod;
  const int n = rod.num_nodes, ne = static_cast<int>(rod.elements.size());
  const real radius = display_radius(b);
  std::vector<Mat3> R(ne);
  for (int e = 0; e < ne; ++e) R[e] = rod_element_frame(rod, e, b.state.x);
  out.resize(3 * (n * kRodDisplaySegments + (rod.closed ? 0 : 2)));
  constexpr real two_pi = 2 * std::numbers::pi_v<real>;
  for (int i = 0; i < n; ++i) {
    // the elements meeting at the node: their mean tangent and axis
    const int e = rod.closed ? (i + ne - 1) % ne : std::max(0, i - 1), f = rod.closed ? i % ne : std::min(i, ne - 1);
    const Vec3 t = (R[e].col(2) + R[f].col(2)).normalized();
    Vec3 d1 = R[e].col(0) + R[f].col(0);
    d1 = (d1 - t * d1.dot(t)).normalized();
    const Vec3 d2 = t.cross(d1);
    const Vec3 x = b.state.x.segment<3>(3 * i);
    for (int k = 0; k < kRodDisplaySegments; ++k) {
      const real phi = two_pi * k / kRodDisplaySegments;
      out.segment<3>(3 * (i * kRodDisplaySegments + k)) = x + radius * (std::cos(phi) * d1 + std::sin(phi) * d2);
    }
  }
  if (!rod.closed) {
    out.segment<3>(3 * n * kRodDisplaySegments) = b.state.x.segment<3>(0);
    out.segment<3>(3 * (n * kRodDisplaySegments + 1)) = b.state.x.segment<3>(3 * (n - 1));
  }
}

std::vector<std::array<int, 3>> rod_display_faces(const SoftBody& b) {
  const RodModel& rod = *b.model.rod;
  const int n = rod.num_nodes, ne = static_cast<int>(rod.elements.size()), S = kRodDisplaySegments;
  auto ring = [S](int i, int k) { return i * S + k % S; };
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i < ne; ++i) {
    const int j = (i + 1) % n;
    for (int k = 0; k < S; ++k) {
      faces.push_back({ring(i, k), ring(j, k + 1), ring(j, k)});
      faces.push_back({ring(i, k), ring(i, k + 1), ring(j, k + 1)});
    }
  }
  if (!rod.closed) {
    const int start = n * S, end = start + 1;
    for (int k = 0; k < S; ++k) {
      faces.push_back({start, ring(0, k + 1), ring(0, k)});
      faces.push_back({end, ring(n - 1, k), ring(n - 1, k + 1)});
    }
  }
  return faces;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
