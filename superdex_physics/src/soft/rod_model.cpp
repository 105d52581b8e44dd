// Elastic rod energies and their derivatives (rod_model.h). The strains are differentiated by
// forward-mode automatic differentiation in double precision whatever the build's precision.

#include "soft/rod_model.h"

#include <algorithm>
#include <cmath>
#include <unsupported/Eigen/AutoDiff>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

template <class T>
using V3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using M3 = Eigen::Matrix<T, 3, 3>;
template <int N>
using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;

template <class T>
M3<T> frame(const V3<T>& a, const V3<T>& b, const V3<T>& g) {
  const V3<T> d = b - a;
  const V3<T> t = d / d.norm();
  const V3<T> w = g - (a + b) * T(0.5);
  // the ghost's offset normal to the segment
  const V3<T> u = w - t * w.dot(t);
  const V3<T> d1 = u / u.norm();
  M3<T> R;
  R.col(0) = d1;
  R.col(1) = t.cross(d1);
  R.col(2) = t;
  return R;
}

template <class T>
V3<T> darboux(const M3<T>& R_e, const M3<T>& R_f) {
  using std::sqrt;
  const M3<T> O = R_e.transpose() * R_f;
  const V3<T> s(O(2, 1) - O(1, 2), O(0, 2) - O(2, 0), O(1, 0) - O(0, 1));
  return s / sqrt(T(1) + O.trace());
}

// Point k of a stencil as dual numbers: coordinate c is variable 3 k + c.
template <int N>
V3<Dual<N>> point(const VecX& x, int node, int k) {
  V3<Dual<N>> p;
  for (int c = 0; c < 3; ++c) p[c] = Dual<N>(double(x[3 * node + c]), N, 3 * k + c);
  return p;
}

// Adds k r grad(r) and k grad(r) grad(r)^T of a strain r (a dual number) to g and H.
template <int N>
void add_strain(const Dual<N>& r, double k, Eigen::Matrix<double, N, 1>& g, Eigen::Matrix<double, N, N>& H) {
  g += k * r.value() * r.derivatives();
  H += k * r.derivatives() * r.derivatives().transpose();
}

}  // namespace

Mat3 rod_element_frame(const Vec3& a, const Vec3& b, const Vec3& g, std::array<Mat3, 3>* omega_map) {
  VecX x(9);
  x << a, b, g;
  const M3<Dual<9>> R = frame<Dual<9>>(point<9>(x, 0, 0), point<9>(x, 1, 1), point<9>(x, 2, 2));
  M3<double> R0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R0(i, j) = R(i, j).value();
  if (omega_map) {
    // each coordinate's rate turns the frame by w_j with dR/dx_j R^T = [w_j]x
    for (int j = 0; j < 9; ++j) {
      M3<double> dR;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) dR(r, c) = R(r, c).derivatives()[j];
      const M3<double> W = dR * R0.transpose();
      (*omega_map)[j / 3].col(j % 3) = Vec3(real(0.5 * (W(2, 1) - W(1, 2))), real(0.5 * (W(0, 2) - W(2, 0))), real(0.5 * (W(1, 0) - W(0, 1))));
    }
  }
  return R0.cast<real>();
}

Mat3 rod_element_frame(const RodModel& m, int e, const VecX& x, std::array<Mat3, 3>* omega_map) {
  const std::array<int, 3>& n = m.elements[e].nodes;
  return rod_element_frame(x.segment<3>(3 * n[0]), x.segment<3>(3 * n[1]), x.segment<3>(3 * n[2]), omega_map);
}

Vec3 rod_darboux(const Mat3& R_e, const Mat3& R_f) {
  return darboux<double>(R_e.cast<double>(), R_f.cast<double>()).cast<real>();
}

real rod_element_terms(const RodModel& m, int e, const VecX& x, Vec9* gradient, Mat9* hessian) {
  const RodElement& el = m.elements[e];
  const V3<Dual<9>> a = point<9>(x, el.nodes[0], 0), b = point<9>(x, el.nodes[1], 1), g = point<9>(x, el.nodes[2], 2);
  Eigen::Matrix<double, 9, 1> G = Eigen::Matrix<double, 9, 1>::Zero();
  Eigen::Matrix<double, 9, 9> H = Eigen::Matrix<double, 9, 9>::Zero();
  // stretching
  const V3<Dual<9>> d = b - a;
  const Dual<9> length = d.norm();
  const Dual<9> r_s = length - double(el.rest_length);
  const double k_s = el.axial_stiffness;
  add_strain(r_s, k_s, G, H);
  // the tension's lateral stiffness k (1 - l0 / l) (I - t t^T) on (a, b), none in compression
  const double l = length.value();
  const double c = std::max(0.0, 1.0 - double(el.rest_length) / l);
  if (c > 0) {
    Eigen::Vector3d t(d[0].value() / l, d[1].value() / l, d[2].value() / l);
    const Eigen::Matrix3d K = k_s * c * (Eigen::Matrix3d::Identity() - t * t.transpose());
    H.block<3, 3>(0, 0) += K, H.block<3, 3>(3, 3) += K, H.block<3, 3>(0, 3) -= K, H.block<3, 3>(3, 0) -= K;
  }
  // the ghost: normal to the segment at distance L from its midpoint
  const V3<Dual<9>> t = d / length;
  const V3<Dual<9>> w = g - (a + b) * Dual<9>(0.5);
  const Dual<9> r_axial = w.dot(t);
  const Dual<9> r_radial = w.norm() - double(el.ghost_distance);
  add_strain(r_axial, el.ghost_stiffness, G, H);
  add_strain(r_radial, el.ghost_stiffness, G, H);
  if (gradient) *gradient = G.cast<real>();
  if (hessian) *hessian = H.cast<real>();
  const double E = 0.5 * (k_s * r_s.value() * r_s.value() +
                          el.ghost_stiffness * (r_axial.value() * r_axial.value() + r_radial.value() * r_radial.value()));
  return real(E);
}

std::array<int, 6> rod_joint_nodes(const RodModel& m, int j) {
  const RodElement& e = m.elements[m.joints[j].e];
  const RodElement& f = m.elements[m.joints[j].f];
  return {e.nodes[0], e.nodes[1], e.nodes[2], f.nodes[0], f.nodes[1], f.nodes[2]};
}

real rod_joint_terms(const RodModel& m, int j, const VecX& x, Vec18* gradient, Mat18* hessian) {
  const RodJoint& J = m.joints[j];
  const std::array<int, 6> n = rod_joint_nodes(m, j);
  const M3<Dual<18>> R_e = frame<Dual<18>>(point<18>(x, n[0], 0), point<18>(x, n[1], 1), point<18>(x, n[2], 2));
  const M3<Dual<18>> R_f = frame<Dual<18>>(point<18>(x, n[3], 3), point<18>(x, n[4], 4), point<18>(x, n[5], 5));
  const V3<Dual<18>> theta = darboux(R_e, R_f);
  Eigen::Matrix<double, 18, 1> G = Eigen::Matrix<double, 18, 1>::Zero();
  Eigen::Matrix<double, 18, 18> H = Eigen::Matrix<double, 18, 18>::Zero();
  double E = 0;
  for (int i = 0; i < 3; ++i) {
    const Dual<18> r = theta[i] - double(J.rest_darboux[i]);
    const double k = double(m.stiffness[i]) / double(J.voronoi_length);
    add_strain(r, k, G, H);
    E += 0.5 * k * r.value() * r.value();
  }
  if (gradient) *gradient = G.cast<real>();
  if (hessian) *hessian = H.cast<real>();
  return real(E);
}

VecX rod_spin_momentum(const RodModel& m, const VecX& v) {
  VecX p = VecX::Zero(v.size());
  for (const RodElement& e : m.elements) {
    Vec3 relative = Vec3::Zero();
    for (int k = 0; k < 3; ++k) relative += real(kRodSpinWeights[k]) * v.segment<3>(3 * e.nodes[k]);
    for (int k = 0; k < 3; ++k) p.segment<3>(3 * e.nodes[k]) += e.spin_mass * real(kRodSpinWeights[k]) * relative;
  }
  return p;
}

real rod_energy(const RodModel& m, const VecX& x) {
  real E = 0;
  for (int e = 0; e < static_cast<int>(m.elements.size()); ++e) E += rod_element_terms(m, e, x, nullptr, nullptr);
  for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) E += rod_joint_terms(m, j, x, nullptr, nullptr);
  return E;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
