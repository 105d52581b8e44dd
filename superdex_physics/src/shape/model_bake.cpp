// Transforms baked into model data (model.h): bake_transform, the coordinate-space conversion
// (a signed permutation and a unit scale) and flip_winding_order.
//
// Every map here is p' = L p + t with L = R S (R a rotation or, for coordinate spaces, a signed
// permutation; S diagonal). Points take L, directions normal to something (frame axes, plane
// normals) take L^-T, and the oriented primitives are rebuilt so that they describe the same set.

#include <algorithm>
#include <cmath>

#include "superdex/physics/error.h"
#include "superdex/physics/model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using Mat3d = Eigen::Matrix3d;
using Vec3d = Eigen::Vector3d;

// p' = linear * p + translation, with linear = rotation * diag(scale), computed in double.
struct Affine {
  Mat3d rotation = Mat3d::Identity();  // orthogonal (det +-1)
  Vec3d scale = Vec3d::Ones();
  Vec3d translation = Vec3d::Zero();

  Mat3d linear() const { return rotation * scale.asDiagonal(); }
  Mat3d inverse_transpose() const { return rotation * scale.cwiseInverse().asDiagonal(); }
  double determinant() const { return rotation.determinant() * scale.prod(); }
  bool uniform() const {
    const Vec3d a = scale.cwiseAbs();
    return a.maxCoeff() - a.minCoeff() <= 1e-12 * a.maxCoeff();
  }
  // The orthogonal part of the map when |scale| is uniform: rotation * sign(scale).
  Mat3d orthogonal() const { return rotation * scale.cwiseSign().asDiagonal(); }
  Vec3d point(const Vec3d& p) const { return linear() * p + translation; }
  // A unit vector normal to a surface, transformed by the inverse transpose; a uniform |scale|
  // leaves the orthogonal part, which keeps the length (and is exact for a change of axes).
  Vec3d normal(const Vec3d& n) const {
    if (uniform()) return orthogonal() * n;
    return (inverse_transpose() * n).normalized();
  }
};

Vec3d vec(const Real3& v) { return v.cast<double>(); }
Real3 real3(const Vec3d& v) { return v.cast<real>(); }

// A proper rotation R' with R' (h .* u) covering the same box as orthogonal * Q (h .* u) for u in
// [-1, 1]^3: a box is symmetric under reflections of its own axes, so an improper map is made
// proper by reflecting the box's x axis.
Quaternion proper_rotation(const Mat3d& orthogonal_times_q) {
  Mat3d m = orthogonal_times_q;
  if (m.determinant() < 0) m.col(0) = -m.col(0);
  return Quaternion(Eigen::Quaterniond(m).normalized().cast<real>());
}

void transform_coordinates(std::vector<real>& c, const Affine& a) {
  const Mat3d L = a.linear();
  for (size_t i = 0; i + 2 < c.size(); i += 3) {
    const Vec3d p = L * Vec3d(c[i], c[i + 1], c[i + 2]) + a.translation;
    c[i] = static_cast<real>(p.x()), c[i + 1] = static_cast<real>(p.y()), c[i + 2] = static_cast<real>(p.z());
  }
}

void transform_mesh(MeshData& m, const Affine& a) {
  transform_coordinates(m.coordinates, a);
  if (a.determinant() < 0) model::flip_winding_order(m);
}

// Fibre directions (theta, phi) and shape-target tensors of the material, rotated with the model.
void transform_material(PerElementSoftMaterialData& m, const Affine& a) {
  const bool fibres = !m.aniso_theta.empty() || !m.aniso_phi.empty();
  const bool tensors = std::any_of(m.shape_target_tensor.begin(), m.shape_target_tensor.end(), [](real x) { return x != 0; });
  if (!fibres && !tensors) return;
  if (!a.uniform())
    throw Error(std::string("material.") + (fibres ? "aniso_theta" : "shape_target_tensor") +
                ": per-element directions cannot take a non-uniform scale");
  const Mat3d Q = a.orthogonal();
  if (m.aniso_theta.size() != m.aniso_phi.size())
    throw Error("material.aniso_phi: must have as many values as material.aniso_theta to be transformed");
  for (size_t e = 0; e < m.aniso_theta.size(); ++e) {
    const double theta = m.aniso_theta[e], phi = m.aniso_phi[e];
    const Vec3d d = Q * Vec3d(std::cos(phi) * std::cos(theta), std::sin(phi), std::cos(phi) * std::sin(theta));
    m.aniso_theta[e] = static_cast<real>(std::atan2(d.z(), d.x()));
    m.aniso_phi[e] = static_cast<real>(std::asin(std::clamp(d.y(), -1.0, 1.0)));
  }
  for (size_t e = 0; e + 5 < m.shape_target_tensor.size(); e += 6) {
    real* s = m.shape_target_tensor.data() + e;
    Mat3d X;
    X << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
    const Mat3d Y = Q * X * Q.transpose();
    const double upper[6] = {Y(0, 0), Y(0, 1), Y(0, 2), Y(1, 1), Y(1, 2), Y(2, 2)};
    for (int k = 0; k < 6; ++k) s[k] = static_cast<real>(upper[k]);
  }
}

// The grid's placement composed with the map (|scale| uniform): p = T + R (S .* g).
void transform_sdf(GridSdfData& s, const Affine& a) {
  const Mat3d R = s.rotation ? Mat3d(s.rotation->cast<double>().normalized().toRotationMatrix()) : Mat3d::Identity();
  Vec3d S = s.scale ? vec(*s.scale) : Vec3d::Ones();
  const Vec3d T = s.translation ? vec(*s.translation) : Vec3d::Zero();
  Mat3d Rn = a.orthogonal() * R;
  if (Rn.determinant() < 0) {  // keep the rotation proper: mirror the grid's x axis through its scale
    Rn.col(0) = -Rn.col(0);
    S.x() = -S.x();
  }
  s.scale = real3(std::abs(a.scale.x()) * S);
  s.rotation = Quaternion(Eigen::Quaterniond(Rn).normalized().cast<real>());
  s.translation = real3(a.point(T));
  if (*s.scale == Real3::Ones()) s.scale.reset();
  if (s.rotation->coeffs() == Quaternion::Identity().coeffs()) s.rotation.reset();
  if (s.translation->isZero(0)) s.translation.reset();
}

void transform_model(ModelData& d, const Affine& a) {
  const bool uniform = a.uniform();
  if (d.sphere && !uniform) throw Error("sphere: cannot take a non-uniform scale (it would become an ellipsoid)");
  if (d.box && !uniform && d.box->rotation.coeffs() != Quaternion::Identity().coeffs() &&
      d.box->rotation.coeffs() != Quaternion(-1, 0, 0, 0).coeffs())
    throw Error("box: a rotated box cannot take a non-uniform scale");
  if (d.material) transform_material(*d.material, a);

  if (d.mesh) transform_mesh(*d.mesh, a);
  if (d.visual_mesh) transform_mesh(*d.visual_mesh, a);
  if (d.element_frame_axes) {
    std::vector<real>& axes = *d.element_frame_axes;
    for (size_t i = 0; i + 2 < axes.size(); i += 3) {
      const Vec3d v = a.normal(Vec3d(axes[i], axes[i + 1], axes[i + 2]));
      axes[i] = static_cast<real>(v.x()), axes[i + 1] = static_cast<real>(v.y()), axes[i + 2] = static_cast<real>(v.z());
    }
  }
  if (d.box) {
    Box& b = *d.box;
    const Mat3d Q = b.rotation.cast<double>().normalized().toRotationMatrix();
    b.center = real3(a.point(vec(b.center)));
    b.half_extents = real3(a.scale.cwiseAbs().cwiseProduct(vec(b.half_extents)));
    b.rotation = proper_rotation(a.orthogonal() * Q);
  }
  if (d.plane) {
    Plane& p = *d.plane;
    const Vec3d n = vec(p.normal);
    const Vec3d n2 = a.normal(n);
    // uniform: d' = |s| d + n'.t (exact for a pure change of axes); else through a point of the plane
    p.distance = static_cast<real>(uniform ? std::abs(a.scale.x()) * p.distance * n.norm() + n2.dot(a.translation)
                                           : n2.dot(a.point(n * (double(p.distance) / n.squaredNorm()))));
    p.normal = real3(n2);
  }
  if (d.sphere) {
    d.sphere->center = real3(a.point(vec(d.sphere->center)));
    d.sphere->radius = static_cast<real>(std::abs(a.scale.x()) * d.sphere->radius);
  }
  if (d.sdf) {
    if (uniform) transform_sdf(*d.sdf, a);
    else d.sdf.reset();  // a grid cannot stretch: recomputed where it is needed
  }
}

Affine bake_affine(const Real3& scale, const Quaternion& rotation, const Real3& translation) {
  if (!scale.allFinite() || (scale.cwiseAbs().array() < std::numeric_limits<real>::epsilon()).any())
    throw Error("bake_transform: scale must be finite and non-zero on every axis");
  if (!rotation.coeffs().allFinite() || rotation.norm() < real(1e-12)) throw Error("bake_transform: rotation must be a finite, non-zero quaternion");
  if (!translation.allFinite()) throw Error("bake_transform: translation must be finite");
  Affine a;
  a.rotation = rotation.cast<double>().normalized().toRotationMatrix();
  a.scale = vec(scale);
  a.translation = vec(translation);
  return a;
}

Affine space_affine(const CoordinateSpace& from, const CoordinateSpace& to) {
  Affine a;
  a.rotation = coordinate_space_rotation(from, to);
  a.scale = Vec3d::Constant(to.units_per_meter / from.units_per_meter);
  return a;
}

}  // namespace

namespace model {

void bake_transform(ModelData& data, const Real3& scale, const Quaternion& rotation, const Real3& translation) {
  const Affine a = bake_affine(scale, rotation, translation);
  if (a.rotation.isIdentity(0) && a.scale == Vec3d::Ones() && a.translation.isZero(0)) return;
  transform_model(data, a);
}

void bake_transform(ModelData& data, const Real3& scale, const TransformRT& transform) {
  bake_transform(data, scale, transform.rotation, transform.translation);
}

void bake_coordinate_space_transform(MeshData& data, const CoordinateSpace& from_space, const CoordinateSpace& to_space) {
  transform_mesh(data, space_affine(from_space, to_space));
}

void bake_coordinate_space_transform(ModelData& data, const CoordinateSpace& from_space, const CoordinateSpace& to_space) {
  transform_model(data, space_affine(from_space, to_space));
}

void flip_winding_order(MeshData& data) {
  const int k = data.nodes_per_element;
  if (k < 3) return;
  for (size_t e = 0; e + static_cast<size_t>(k) <= data.connectivity.size(); e += static_cast<size_t>(k))
    std::swap(data.connectivity[e], data.connectivity[e + 1]);
}

void flip_winding_order(ModelData& data) {
  if (data.mesh) flip_winding_order(*data.mesh);
  if (data.visual_mesh) flip_winding_order(*data.visual_mesh);
}

}  // namespace model
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
