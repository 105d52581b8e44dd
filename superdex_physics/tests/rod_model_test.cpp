/// @file rod_model_test.cpp
/// The elastic rod's energies (soft/rod_model.h) against independent checks: gradients are the
/// central finite differences of the energy at perturbed configurations; at rest (every strain
/// zero) the Gauss-Newton Hessians equal the finite differences of the gradient; the element
/// frame's angular-velocity map matches the frame's finite-difference rotation rate; the energy
/// of a uniformly bent rod is EI kappa^2 L / 2 and of a uniformly twisted one GJ tau^2 L / 2.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>

#include "soft/rod_model.h"

namespace superdex::physics {
namespace {

// A rod on a polyline of nodes (one ghost per element at distance L along its frame axis), its
// rest state the given configuration.
struct TestRod {
  RodModel model;
  VecX x;  // polyline nodes then ghosts
};

TestRod make_rod(const std::vector<Vec3>& nodes, const Vec3& axis, const Vec3& stiffness, double EA = 50.0) {
  TestRod r;
  const int n = static_cast<int>(nodes.size()), ne = n - 1;
  r.model.num_nodes = n;
  r.model.stiffness = stiffness;
  r.x.resize(3 * (n + ne));
  for (int i = 0; i < n; ++i) r.x.segment<3>(3 * i) = nodes[i];
  for (int e = 0; e < ne; ++e) {
    RodElement el;
    el.nodes = {e, e + 1, n + e};
    el.rest_length = (nodes[e + 1] - nodes[e]).norm();
    el.ghost_distance = 0.3;
    el.axial_stiffness = EA / el.rest_length;
    el.ghost_stiffness = EA / el.ghost_distance;
    const Vec3 t = (nodes[e + 1] - nodes[e]).normalized();
    const Vec3 u = (axis - t * axis.dot(t)).normalized();
    r.x.segment<3>(3 * (n + e)) = (nodes[e] + nodes[e + 1]) / 2 + el.ghost_distance * u;
    r.model.elements.push_back(el);
  }
  for (int e = 0; e + 1 < ne; ++e) {
    RodJoint j;
    j.e = e;
    j.f = e + 1;
    j.voronoi_length = (r.model.elements[e].rest_length + r.model.elements[e + 1].rest_length) / 2;
    const auto frame = [&](int k) {
      const RodElement& el = r.model.elements[k];
      return rod_element_frame(r.x.segment<3>(3 * el.nodes[0]), r.x.segment<3>(3 * el.nodes[1]), r.x.segment<3>(3 * el.nodes[2]));
    };
    j.rest_darboux = rod_darboux(frame(e), frame(e + 1));
    r.model.joints.push_back(j);
  }
  return r;
}

TestRod kinked_rod() {
  return make_rod({Vec3(0, 0, 0), Vec3(1, 0.1, 0), Vec3(1.8, 0.5, 0.3)}, Vec3(0, 0, 1), Vec3(2.0, 3.0, 1.5));
}

VecX perturbed(const VecX& x, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  VecX y = x;
  for (int i = 0; i < y.size(); ++i) y[i] += u(rng);
  return y;
}

// Energy of element k (or joint k) at x.
double term_energy(const RodModel& m, bool joint, int k, const VecX& x) {
  return joint ? rod_joint_terms(m, k, x, nullptr, nullptr) : rod_element_terms(m, k, x, nullptr, nullptr);
}

std::vector<int> stencil(const RodModel& m, bool joint, int k) {
  if (joint) {
    const auto n = rod_joint_nodes(m, k);
    return {n.begin(), n.end()};
  }
  return {m.elements[k].nodes.begin(), m.elements[k].nodes.end()};
}

// The term's gradient and Hessian scattered over all of x's coordinates (a joint's shared node
// gets the sum of its two slots).
VecX global_gradient(const RodModel& m, bool joint, int k, const VecX& x) {
  VecX g_s;
  if (joint) {
    Vec18 g;
    rod_joint_terms(m, k, x, &g, nullptr);
    g_s = g;
  } else {
    Vec9 g;
    rod_element_terms(m, k, x, &g, nullptr);
    g_s = g;
  }
  const std::vector<int> nodes = stencil(m, joint, k);
  VecX out = VecX::Zero(x.size());
  for (size_t s = 0; s < nodes.size(); ++s) out.segment<3>(3 * nodes[s]) += g_s.segment<3>(3 * s);
  return out;
}

MatX global_hessian(const RodModel& m, bool joint, int k, const VecX& x) {
  MatX H_s;
  if (joint) {
    Mat18 H;
    rod_joint_terms(m, k, x, nullptr, &H);
    H_s = H;
  } else {
    Mat9 H;
    rod_element_terms(m, k, x, nullptr, &H);
    H_s = H;
  }
  const std::vector<int> nodes = stencil(m, joint, k);
  MatX out = MatX::Zero(x.size(), x.size());
  for (size_t s = 0; s < nodes.size(); ++s)
    for (size_t t = 0; t < nodes.size(); ++t) out.block<3, 3>(3 * nodes[s], 3 * nodes[t]) += H_s.block<3, 3>(3 * s, 3 * t);
  return out;
}

int term_count(const RodModel& m, bool joint) {
  return joint ? static_cast<int>(m.joints.size()) : static_cast<int>(m.elements.size());
}

TEST(RodModel, GradientsAreTheEnergysFiniteDifferences) {
  const TestRod r = kinked_rod();
  const double h = 1e-6;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const VecX x = perturbed(r.x, 0.05, seed);
    for (bool joint : {false, true})
      for (int k = 0; k < term_count(r.model, joint); ++k) {
        const VecX exact = global_gradient(r.model, joint, k, x);
        VecX fd(x.size());
        for (int i = 0; i < x.size(); ++i) {
          VecX xp = x, xm = x;
          xp[i] += h;
          xm[i] -= h;
          fd[i] = (term_energy(r.model, joint, k, xp) - term_energy(r.model, joint, k, xm)) / (2 * h);
        }
        EXPECT_LE((exact - fd).norm(), 1e-6 * std::max(1.0, fd.norm())) << (joint ? "joint " : "element ") << k << " seed " << seed;
      }
  }
}

TEST(RodModel, AtRestTheHessiansAreTheGradientsFiniteDifferences) {
  // every strain is zero at the rest configuration, where Gauss-Newton is the exact Hessian
  const TestRod r = kinked_rod();
  const double h = 1e-6;
  for (bool joint : {false, true})
    for (int k = 0; k < term_count(r.model, joint); ++k) {
      const MatX H = global_hessian(r.model, joint, k, r.x);
      MatX fd(r.x.size(), r.x.size());
      for (int i = 0; i < r.x.size(); ++i) {
        VecX xp = r.x, xm = r.x;
        xp[i] += h;
        xm[i] -= h;
        fd.col(i) = (global_gradient(r.model, joint, k, xp) - global_gradient(r.model, joint, k, xm)) / (2 * h);
      }
      EXPECT_LE((H - fd).norm(), 1e-5 * fd.norm()) << (joint ? "joint " : "element ") << k;
      EXPECT_LE((H - H.transpose()).norm(), 1e-12 * H.norm());
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<MatX>(H).eigenvalues().minCoeff(), -1e-9 * H.norm());
    }
}

TEST(RodModel, RigidMotionsStoreNoEnergyAndHaveNoStiffness) {
  const TestRod r = kinked_rod();
  const Mat3 R = Eigen::AngleAxis<double>(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  VecX moved = r.x;
  for (int i = 0; i < moved.size() / 3; ++i) moved.segment<3>(3 * i) = R * r.x.segment<3>(3 * i) + Vec3(0.3, -2, 5);
  EXPECT_LE(rod_energy(r.model, moved), 1e-20);
  // translations are in every term's Hessian's null space
  for (bool joint : {false, true})
    for (int k = 0; k < term_count(r.model, joint); ++k) {
      const MatX H = global_hessian(r.model, joint, k, moved);
      for (int c = 0; c < 3; ++c) {
        VecX t = VecX::Zero(moved.size());
        for (int i = 0; i < moved.size() / 3; ++i) t[3 * i + c] = 1;
        EXPECT_LE((H * t).norm(), 1e-9 * H.norm());
      }
    }
}

TEST(RodModel, FrameAngularVelocityMapMatchesTheFramesRotationRate) {
  const Vec3 a(0.1, -0.2, 0.3), b(1.0, 0.4, -0.1), g(0.6, 0.2, 0.7);
  std::array<Mat3, 3> omega_map;
  const Mat3 R = rod_element_frame(a, b, g, &omega_map);
  EXPECT_LE((R.transpose() * R - Mat3::Identity()).norm(), 1e-12);
  const Vec3 va(0.3, -1.0, 0.2), vb(-0.5, 0.1, 0.4), vg(0.2, 0.6, -0.9);
  const double h = 1e-6;
  const Mat3 Rp = rod_element_frame(a + h * va, b + h * vb, g + h * vg), Rm = rod_element_frame(a - h * va, b - h * vb, g - h * vg);
  const Mat3 W = (Rp - Rm) / (2 * h) * R.transpose();
  const Vec3 w_fd(W(2, 1), W(0, 2), W(1, 0));
  const Vec3 w = omega_map[0] * va + omega_map[1] * vb + omega_map[2] * vg;
  EXPECT_LE((w - w_fd).norm(), 1e-6 * w_fd.norm());
}

TEST(RodModel, UniformBendingAndTwistingStoreTheirAnalyticEnergies) {
  // an arc of curvature kappa in the plane normal to the frame axis (Z): bending about d1, the
  // first flexural stiffness, E = EI_1 kappa^2 L / 2 over the joints' total length
  const int n = 41;
  const double kappa = 0.8, L = 1.0;
  std::vector<Vec3> straight, arc;
  for (int i = 0; i < n; ++i) {
    const double s = L * i / (n - 1);
    straight.push_back(Vec3(s, 0, 0));
    arc.push_back(Vec3(std::sin(kappa * s) / kappa, (1 - std::cos(kappa * s)) / kappa, 0));
  }
  const Vec3 K(2.0, 3.0, 1.5);
  TestRod r = make_rod(straight, Vec3(0, 0, 1), K);
  TestRod bent = make_rod(arc, Vec3(0, 0, 1), K);
  // the straight rod's energy at the bent configuration (ghosts at their bent places)
  const double joints_length = L * (n - 2) / (n - 1);
  const double E_bend = rod_energy(r.model, bent.x);
  EXPECT_NEAR(E_bend, K[0] * kappa * kappa * joints_length / 2, 1e-3 * E_bend);
  // twisted: each ghost turned by tau s about the straight axis (X)
  const double tau = 0.6;
  VecX twisted = r.x;
  for (int e = 0; e < n - 1; ++e) {
    const double s = L * (e + 0.5) / (n - 1), c = std::cos(tau * s), sn = std::sin(tau * s);
    const Vec3 m = (straight[e] + straight[e + 1]) / 2;
    const double d = r.model.elements[e].ghost_distance;
    twisted.segment<3>(3 * (n + e)) = m + d * Vec3(0, -sn, c);
  }
  const double E_twist = rod_energy(r.model, twisted);
  EXPECT_NEAR(E_twist, K[2] * tau * tau * joints_length / 2, 1e-3 * E_twist);
}

}  // namespace
}  // namespace superdex::physics
