// model::auto_correct (model.h): the in-place fixes with one obvious answer.

#include <algorithm>
#include <cmath>

#include "superdex/physics/error.h"
#include "superdex/physics/model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

bool is_unit(double norm) { return std::abs(norm - 1) <= 1e-6; }

// Scales each node's weights to sum to 1 (sums already within 1e-6 of 1 are left as they are).
void normalize_weights(SkinningData& s, const std::string& f) {
  const int k = s.weights_per_node;
  if (k <= 0) throw Error(f + ".weights_per_node: must be >= 1 to normalise the weights, got " + std::to_string(k));
  if (s.weights.size() != s.indices.size())
    throw Error(f + ".weights: " + std::to_string(s.weights.size()) + " weights for " + std::to_string(s.indices.size()) + " indices");
  if (s.weights.size() % static_cast<size_t>(k) != 0)
    throw Error(f + ".weights: " + std::to_string(s.weights.size()) + " values are not " + std::to_string(k) + " per node");
  for (size_t node = 0; node < s.weights.size() / k; ++node) {
    real* w = s.weights.data() + node * k;
    double sum = 0;
    for (int i = 0; i < k; ++i) sum += w[i];
    if (std::abs(sum) < 1e-6) throw Error(f + ".weights: the weights of node " + std::to_string(node) + " sum to 0: cannot normalise them");
    if (std::abs(sum - 1) <= 1e-6) continue;
    for (int i = 0; i < k; ++i) w[i] = static_cast<real>(w[i] / sum);
  }
}

}  // namespace

namespace model {

void auto_correct(ModelData& d) {
  if (d.mesh && d.mesh->skinning) normalize_weights(*d.mesh->skinning, "mesh.skinning");
  if (d.visual_mesh && d.visual_mesh->skinning) normalize_weights(*d.visual_mesh->skinning, "visual_mesh.skinning");
  if (d.visual_mesh && d.visual_mesh->connectivity.empty()) d.visual_mesh.reset();
  if (d.blending && d.blending->empty()) d.blending.reset();
  if (d.constrained_nodes) {
    std::vector<int>& nodes = *d.constrained_nodes;
    if (nodes.empty()) {
      d.constrained_nodes.reset();
    } else {
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    }
  }
  if (d.element_frame_axes) {
    std::vector<real>& axes = *d.element_frame_axes;
    if (axes.empty()) {
      d.element_frame_axes.reset();
    } else {
      if (axes.size() % 3 != 0) throw Error("element_frame_axes: must hold 3 values per element, got " + std::to_string(axes.size()));
      for (size_t e = 0; e < axes.size(); e += 3) {
        Eigen::Map<Real3> axis(axes.data() + e);
        if (!is_unit(axis.norm()) && axis.norm() > 0) axis.normalize();
      }
    }
  }
  if (d.box) {
    Quaternion& q = d.box->rotation;
    if (!is_unit(q.norm()) && q.norm() > 0) q.normalize();
    if (q.coeffs() == Quaternion(-1, 0, 0, 0).coeffs()) q = Quaternion::Identity();
  }
  if (d.plane && !is_unit(d.plane->normal.norm()) && d.plane->normal.norm() > 0) d.plane->normal.normalize();
  if (d.sdf) {
    GridSdfData& s = *d.sdf;
    if (s.scale && *s.scale == Real3::Ones()) s.scale.reset();
    if (s.rotation) {
      const auto c = s.rotation->coeffs();
      if (c == Quaternion::Identity().coeffs() || c == Quaternion(-1, 0, 0, 0).coeffs()) s.rotation.reset();
      else if (!is_unit(s.rotation->norm()) && s.rotation->norm() > 0) s.rotation->normalize();
    }
    if (s.translation && s.translation->isZero(0)) s.translation.reset();
  }
}

}  // namespace model
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
