#pragma once
// Elastic rods (Cosserat rods discretized on a polyline): stretching, bending and twisting, with
// every unknown a point. Each element (a segment between two nodes) carries a material frame
// [d1 d2 t]: t along the segment, d1 towards a ghost point g kept off the segment's midpoint at
// distance L (normal to the segment), d2 = t x d1. The ghost points are nodes of the rod's soft
// body appended after the polyline's, so that the rod joins its island's convex problem like any
// soft body and its twist is the motion of its ghosts (Umetani, Schmidt and Stam 2014, "Position-
// based elastic rods", use such ghost points for the material frame).
//
// Energies (J), each 1/2 k r^2 of a strain r:
//   stretch   EA / l0 (|x_b - x_a| - l0)^2 / 2                              per element
//   ghost     k_g ((g - m) . t)^2 / 2 + k_g (|g - m| - L)^2 / 2               per element
//   bend/twist sum_i K_i (theta_i - theta0_i)^2 / (2 lbar)                    per pair of elements
// with m the segment's midpoint, theta = vee(O - O^T) / sqrt(1 + tr O) = 2 sin(phi/2) n the
// rotation O = R_e^T R_f between the frames of two consecutive elements (in e's frame), lbar the
// mean of their rest lengths and K = (EI_1, EI_2, GJ): bending about d1, about d2, twisting about t.
// Gradients are exact; Hessians are the strains' Gauss-Newton J^T K J (positive semi-definite),
// with the stretch's own exact Hessian (its tension's lateral stiffness, clamped at zero).

#include <array>
#include <vector>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using Vec9 = Eigen::Matrix<real, 9, 1>;
using Mat9 = Eigen::Matrix<real, 9, 9>;
using Vec18 = Eigen::Matrix<real, 18, 1>;
using Mat18 = Eigen::Matrix<real, 18, 18>;

struct RodElement {
  std::array<int, 3> nodes{};  // a, b and the ghost g (node indices of the rod's soft body)
  real rest_length = 0;        // l0 (m)
  real ghost_distance = 0;     // L (m)
  real ghost_stiffness = 0;    // k_g (N/m)
  real axial_stiffness = 0;    // EA / l0 (N/m)
  real spin_mass = 0;          // J l0 / L^2 (kg): the ghost's inertia relative to the midpoint
};

struct RodJoint {
  int e = 0, f = 0;            // consecutive elements (f follows e)
  real voronoi_length = 0;     // lbar (m)
  Vec3 rest_darboux = Vec3::Zero();  // theta0 (in e's frame)
};

struct RodModel {
  int num_nodes = 0;           // polyline nodes; the ghosts follow them, one per element
  bool closed = false;         // the last element joins the last node to the first
  std::vector<RodElement> elements;
  std::vector<RodJoint> joints;
  Vec3 stiffness = Vec3::Zero();  // (EI_1, EI_2, GJ) in N m^2
};

/// The material frame [d1 d2 t] of a segment a -> b with ghost point g (world, columns), and when
/// `omega_map` is given the map of the three points' velocities to the frame's angular velocity:
/// w = sum_k omega_map[k] v_k (rad/s from m/s).
Mat3 rod_element_frame(const Vec3& a, const Vec3& b, const Vec3& g, std::array<Mat3, 3>* omega_map = nullptr);

/// The same for element e of a rod whose body's node positions are x (3 per node).
Mat3 rod_element_frame(const RodModel& m, int e, const VecX& x, std::array<Mat3, 3>* omega_map = nullptr);

/// theta of two frames (in e's frame): 2 sin(phi/2) n for O = R_e^T R_f a rotation by phi about n.
Vec3 rod_darboux(const Mat3& R_e, const Mat3& R_f);

/// Energy of element e at node positions x (J; x holds every node of the rod's body, 3 per node),
/// and when asked its gradient (N) and Hessian (N/m) over (a, b, g).
real rod_element_terms(const RodModel& m, int e, const VecX& x, Vec9* gradient, Mat9* hessian);
/// The same for joint j over the nodes (a_e, b_e, g_e, a_f, b_f, g_f).
real rod_joint_terms(const RodModel& m, int j, const VecX& x, Vec18* gradient, Mat18* hessian);

/// The nodes of joint j in the order of rod_joint_terms.
std::array<int, 6> rod_joint_nodes(const RodModel& m, int j);

/// The rod's spin inertia: each element's ghost carries mu |v_g - (v_a + v_b) / 2|^2 / 2 of
/// kinetic energy (the element's spin about itself, J l0 w^2 / 2), a mass matrix mu c c^T on
/// (a, b, g) with c = (-1/2, -1/2, 1) per coordinate. It carries no momentum and no weight, so the
/// rod's centre of mass stays on its centreline. The weight of node k in it is kRodSpinWeights[k].
inline constexpr double kRodSpinWeights[3] = {-0.5, -0.5, 1.0};
/// Its momentum M_spin v (N s) for velocities v of every node of the rod's body.
VecX rod_spin_momentum(const RodModel& m, const VecX& v);

/// Total elastic energy (J).
real rod_energy(const RodModel& m, const VecX& x);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
