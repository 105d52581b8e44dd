// Separation of two oriented boxes by the separating axis theorem (Gottschalk, Lin and Manocha's
// OBB test; Ericson, Real-Time Collision Detection, 4.4.1): the midphase that spares the narrow
// phase the pairs whose world bounds overlap but whose shapes' own boxes stay apart.

#include <algorithm>
#include <cmath>

#include "collision/collision_geometry.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

bool boxes_apart(const Bounds& a_S, const SpatialTransform& X_WA, const Bounds& b_S, const SpatialTransform& X_WB, real gap) {
  const Vec3 ha = (a_S.max - a_S.min) / 2, hb = (b_S.max - b_S.min) / 2;
  // b's axes and centre in a's box frame
  const Mat3 R = X_WA.R.transpose() * X_WB.R;
  const Vec3 c_a = X_WA.R * ((a_S.min + a_S.max) / 2) + X_WA.p;
  const Vec3 c_b = X_WB.R * ((b_S.min + b_S.max) / 2) + X_WB.p;
  const Vec3 t = X_WA.R.transpose() * (c_b - c_a);
  // |R| grown by a little, so that nearly parallel edges (a cross product near zero) cannot
  // report a separation that round-off made
  const Mat3 abs_R = R.cwiseAbs().array() + real(1e-6);
  for (int i = 0; i < 3; ++i)
    if (std::abs(t[i]) > ha[i] + hb.dot(abs_R.row(i)) + gap) return true;
  for (int j = 0; j < 3; ++j)
    if (std::abs(t.dot(R.col(j))) > ha.dot(abs_R.col(j)) + hb[j] + gap) return true;
  // the axes a_i x b_j, of length sin(angle): the gap scales with it
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const real length = std::sqrt(std::max(real(0), 1 - R(i, j) * R(i, j)));
      const real ra = ha[i1] * abs_R(i2, j) + ha[i2] * abs_R(i1, j);
      const real rb = hb[j1] * abs_R(i, j2) + hb[j2] * abs_R(i, j1);
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb + gap * length) return true;
    }
  }
  return false;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
