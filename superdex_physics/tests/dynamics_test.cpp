/// @file dynamics_test.cpp
/// Mass matrix, bias forces and forward dynamics of a branched articulation with a free root:
/// M is symmetric positive definite, equals the columns of inverse dynamics and the sum of
/// per-link J^T M_link J (and so does a single free body's, computed in closed form); gravity forces equal -sum J_com^T m g; the rate of change of
/// energy equals the power tau . v; forward dynamics satisfies M a + c = tau and the
/// pendulum's analytic acceleration; welded links add their inertia, massless welded frames nothing.

#include <Eigen/Eigenvalues>
#include <string>
#include <vector>

#include "multibody/articulation_model.h"
#include "multibody/dynamics.h"
#include "multibody/kinematics.h"
#include "core/spatial.h"
#include "superdex/physics/error.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

Transform make_transform(const Vec3& rotvec, const Vec3& p) { return {quat_exp(rotvec), p}; }

/// Free root with revolute, prismatic, spherical and revolute joints, one branch, non-diagonal
/// inertias and offset COMs. `armature` is set on every 1-DOF joint.
ArticulationDesc robot(double armature) {
  ArticulationDesc d;
  d.name = "robot";
  d.links = {make_link("root", -1, 3.0, Vec3(0.05, -0.02, 0.1), Vec3(0.2, 0.25, 0.3)),
             make_link("l1", 0, 1.2, Vec3(0, 0.2, 0.1), Vec3(0.02, 0.03, 0.04)),
             make_link("l2", 1, 0.8, Vec3(0.1, -0.1, 0), Vec3(0.01, 0.012, 0.015)),
             make_link("l3", 2, 0.5, Vec3(0, 0.05, 0.2), Vec3(0.01, 0.012, 0.008)),
             make_link("l4", 1, 0.6, Vec3(-0.1, 0, 0.15), Vec3(0.005, 0.006, 0.007))};
  d.links[1].moment_of_inertia = std::array<real, 6>{0.02, 0.003, -0.002, 0.03, 0.004, 0.04};
  d.joints = {make_joint("j0", JointType::Free),
              make_joint("j1", JointType::Revolute, Vec3(0.3, -0.5, 0.8), make_transform(Vec3(0.2, 0.4, -0.1), Vec3(0.2, 0.1, 0.3))),
              make_joint("j2", JointType::Prismatic, Vec3(1, 0.2, -0.1), make_transform(Vec3(0, -0.3, 0.2), Vec3(0, 0.4, 0))),
              make_joint("j3", JointType::Spherical, Vec3::UnitZ(), make_transform(Vec3(0.5, 0, 0), Vec3(0.1, 0.1, 0.3))),
              make_joint("j4", JointType::Revolute, Vec3(0, 1, 0), make_transform(Vec3(0, 0, 0.7), Vec3(-0.2, 0, 0.25)))};
  for (int i : {1, 2, 4}) d.joints[i].armature = armature;
  return d;
}

constexpr int kNv = 12;

VecX test_pose() {
  VecX pose(kNv);
  pose << 0.3, -0.2, 1.0, 0.4, -0.3, 0.7, 0.8, 0.25, -0.6, 0.9, 0.35, -1.1;
  return pose;
}

VecX test_velocity() {
  VecX v(kNv);
  for (int k = 0; k < kNv; ++k) v[k] = std::cos(1.3 * k + 0.2);
  return v;
}

/// Rotational inertia about the COM of link i, as a matrix in the link frame.
Mat3 inertia_of(const LinkDesc& l) {
  const auto& c = *l.moment_of_inertia;
  Mat3 I;
  I << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  return I;
}

/// Private model, state and kinematics of `desc` at the given pose and velocity.
struct PrivateArticulation {
  ArticulationModel model;
  ArticulationState state;
  ArticulationKinematics kin;
  PrivateArticulation(const ArticulationDesc& desc, const VecX& pose, const VecX& v)
      : model(build_articulation_model(desc, "robot")), state(initial_state(model)) {
    q_from_pose(model, pose.data(), false, state.q);
    state.v = v;
    update_kinematics(model, state, kin);
  }
};

class DynamicsTest : public EngineTest {
 protected:
  ActorHandle make(Scene& scene, const ArticulationDesc& desc) {
    const ActorHandle art = scene.create_articulated_actor(desc, "robot");
    scene.set_pose(art, test_pose());
    scene.set_joint_velocities(art, test_velocity());
    return art;
  }
};

TEST_F(DynamicsTest, MassMatrixIsSymmetricPositiveDefinite) {
  Scene scene = z_up_scene("dynamics");
  const ActorHandle art = make(scene, robot(0.05));
  const MatX M = scene.mass_matrix(art);
  ASSERT_EQ(M.rows(), kNv);
  EXPECT_LE((M - M.transpose()).norm(), 1e-12 * M.norm());
  Eigen::SelfAdjointEigenSolver<MatX> eig(M);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0);
}

TEST_F(DynamicsTest, MassMatrixColumnsEqualInverseDynamics) {
  const ArticulationDesc desc = robot(0);
  Scene scene = z_up_scene("dynamics");
  const MatX M = scene.mass_matrix(make(scene, desc));
  // M e_k = ID(q, v = 0, a = e_k, g = 0)
  PrivateArticulation p(desc, test_pose(), VecX::Zero(kNv));
  for (int k = 0; k < kNv; ++k) {
    const VecX col = inverse_dynamics(p.model, p.state, p.kin, VecX::Unit(kNv, k), Vec3::Zero());
    EXPECT_LE((col - M.col(k)).norm(), 1e-12 * M.norm()) << "column " << k;
  }
}

TEST_F(DynamicsTest, InverseDynamicsIsConsistentWithMassMatrixWithArmature) {
  // dynamics.h documents inverse_dynamics as tau = M(q) a + c(q, v), and M carries the armature
  const ArticulationDesc desc = robot(0.05);
  Scene scene = z_up_scene("dynamics");
  const ActorHandle art = make(scene, desc);
  const MatX M = scene.mass_matrix(art);
  const VecX c = scene.bias_forces(art);
  PrivateArticulation p(desc, test_pose(), test_velocity());
  const VecX a = test_velocity().reverse();
  const VecX tau = inverse_dynamics(p.model, p.state, p.kin, a, scene.gravity());
  EXPECT_LE((tau - (M * a + c)).norm(), 1e-10 * (M * a + c).norm());
}

TEST_F(DynamicsTest, MassMatrixEqualsSumOfLinkJacobianInertias) {
  const ArticulationDesc desc = robot(0.05);
  Scene scene = z_up_scene("dynamics");
  const ActorHandle art = make(scene, desc);
  const std::vector<ActorHandle> links = scene.nested_link_actors(art);
  const std::vector<Transform> X = scene.link_transforms(art);
  // M = sum_i m_i Jc_i^T Jc_i + Jw_i^T R I_i R^T Jw_i + armature, Jc the COM Jacobian
  MatX M_ref = MatX::Zero(kNv, kNv);
  for (size_t i = 0; i < links.size(); ++i) {
    const LinkDesc& l = desc.links[i];
    const MatXR J = scene.link_jacobian(links[i]);
    const Mat3 R = X[i].rotation.toRotationMatrix();
    const Vec3 r = R * *l.center_of_mass;
    const MatX Jw = J.bottomRows(3);
    const MatX Jc = J.topRows(3) - skew(r) * Jw;
    M_ref += *l.mass * Jc.transpose() * Jc + Jw.transpose() * (R * inertia_of(l) * R.transpose()) * Jw;
  }
  for (int k : {6, 7, 11}) M_ref(k, k) += 0.05;
  EXPECT_LE((scene.mass_matrix(art) - M_ref).norm(), 1e-12 * M_ref.norm());
}

TEST_F(DynamicsTest, SingleFreeBodyMassMatrixEqualsItsJacobianInertia) {
  // one free link (the closed form of a free body's M), offset COM and a non-diagonal inertia,
  // rotated: M = m Jc^T Jc + Jw^T R I R^T Jw, as for the tree above
  ArticulationDesc desc;
  desc.name = "body";
  desc.links = {make_link("body", -1, 2.5, Vec3(0.07, -0.03, 0.12), Vec3(0.02, 0.03, 0.04))};
  desc.links[0].moment_of_inertia = std::array<real, 6>{0.03, 0.004, -0.003, 0.025, 0.002, 0.035};
  desc.joints = {make_joint("j0", JointType::Free)};
  Scene scene = z_up_scene("free body");
  const ActorHandle art = scene.create_articulated_actor(desc, "body");
  VecX pose(6);
  pose << 0.3, -0.2, 1.0, 0.4, -0.9, 0.7;
  scene.set_pose(art, pose);
  const ActorHandle link = scene.nested_link_actors(art)[0];
  const Mat3 R = scene.link_transforms(art)[0].rotation.toRotationMatrix();
  const MatXR J = scene.link_jacobian(link);
  const Vec3 r = R * *desc.links[0].center_of_mass;
  const MatX Jw = J.bottomRows(3);
  const MatX Jc = J.topRows(3) - skew(r) * Jw;
  const MatX M_ref = *desc.links[0].mass * Jc.transpose() * Jc + Jw.transpose() * (R * inertia_of(desc.links[0]) * R.transpose()) * Jw;
  EXPECT_LE((scene.mass_matrix(art) - M_ref).norm(), 1e-12 * M_ref.norm());
}

TEST_F(DynamicsTest, GravityForcesEqualComJacobianTransposeTimesWeight) {
  const ArticulationDesc desc = robot(0);
  Scene scene = z_up_scene("dynamics");
  const ActorHandle art = make(scene, desc);
  scene.set_joint_velocities(art, VecX::Zero(kNv));
  const std::vector<ActorHandle> links = scene.nested_link_actors(art);
  const std::vector<Transform> X = scene.link_transforms(art);
  // c(q, 0) = -sum_i Jc_i^T m_i g
  VecX g_ref = VecX::Zero(kNv);
  for (size_t i = 0; i < links.size(); ++i) {
    const MatXR J = scene.link_jacobian(links[i]);
    const Vec3 r = X[i].rotation * *desc.links[i].center_of_mass;
    const MatX Jc = J.topRows(3) - skew(r) * J.bottomRows(3);
    g_ref -= Jc.transpose() * (*desc.links[i].mass * scene.gravity());
  }
  EXPECT_LE((scene.bias_forces(art) - g_ref).norm(), 1e-12 * g_ref.norm());
}

TEST_F(DynamicsTest, EnergyRateEqualsPower) {
  const ArticulationDesc desc = robot(0.05);
  Scene scene = z_up_scene("dynamics");
  const ActorHandle art = make(scene, desc);
  const ArticulationModel model = build_articulation_model(desc, "robot");
  VecX q0(model.nq);
  q_from_pose(model, test_pose().data(), false, q0);
  const VecX v0 = test_velocity();
  VecX tau(kNv);
  for (int k = 0; k < kNv; ++k) tau[k] = std::sin(0.9 * k + 1.0);
  // kinetic 0.5 v^T M v plus potential -sum m_i g . p_com_i at the state (q0 (+) h v0, v0 + h a)
  auto energy_at = [&](double h, const VecX& a) {
    VecX q = q0, pose(kNv);
    integrate_positions(model, q, v0, h);
    pose_from_q(model, q, pose.data());
    scene.set_pose(art, pose);
    const VecX v = v0 + h * a;
    scene.set_joint_velocities(art, v);
    double e = 0.5 * v.dot(scene.mass_matrix(art) * v);
    const std::vector<Transform> X = scene.link_transforms(art);
    for (size_t i = 0; i < X.size(); ++i)
      e -= *desc.links[i].mass * scene.gravity().dot(X[i] * *desc.links[i].center_of_mass);
    return e;
  };
  for (const Vec3& g : {Vec3(0, 0, 0), Vec3(0, 0, -kG)}) {
    scene.set_gravity(g);
    scene.set_pose(art, test_pose());
    scene.set_joint_velocities(art, v0);
    const VecX a = scene.forward_dynamics(art, tau);
    // central difference of the energy along the trajectory: dE/dt = tau . v
    const double h = 1e-5;
    const double rate = (energy_at(h, a) - energy_at(-h, a)) / (2 * h);
    const double power = tau.dot(v0);
    EXPECT_NEAR(rate, power, 1e-6 * (1 + std::abs(power))) << "gravity " << g.transpose();
  }
}

TEST_F(DynamicsTest, ForwardDynamicsSatisfiesEquationsOfMotion) {
  Scene scene = z_up_scene("dynamics");
  const ActorHandle art = make(scene, robot(0.05));
  VecX tau(kNv);
  for (int k = 0; k < kNv; ++k) tau[k] = 2 * std::sin(0.7 * k);
  const VecX a = scene.forward_dynamics(art, tau);
  const VecX residual = scene.mass_matrix(art) * a + scene.bias_forces(art) - tau;
  EXPECT_LE(residual.norm(), 1e-10 * (1 + tau.norm()));
}

TEST_F(DynamicsTest, PendulumForwardDynamicsMatchesAnalytic) {
  // I_pivot theta'' = tau - m g L sin(theta), COM at distance L below the pivot
  const double m = 1.5, L = 0.8, i_com = 0.02, theta = 0.7, tau = 0.9;
  Scene scene = z_up_scene("pendulum_fd");
  const ActorHandle p = scene.create_articulated_actor(
      one_dof_desc(JointType::Revolute, Vec3::UnitY(), m, Vec3(0, 0, -L), Vec3::Constant(i_com)), "pendulum");
  scene.set_pose(p, VecX::Constant(1, theta));
  scene.set_joint_velocities(p, VecX::Constant(1, 2.0));  // no Coriolis term for one DOF
  const double expected = (tau - m * kG * L * std::sin(theta)) / (i_com + m * L * L);
  EXPECT_NEAR(scene.forward_dynamics(p, VecX::Constant(1, tau))[0], expected, 1e-12);
}

TEST_F(DynamicsTest, WeldedLinkAddsItsInertiaAndOnlyItsOwnWeight) {
  // a pendulum (COM at L below the pivot) carrying a welded point-like tip at L2 below the
  // pivot: I_pivot = i + m L^2 + i2 + m2 L2^2; the static torque is (m L + m2 L2) g sin(theta),
  // or m L g sin(theta) when the tip does not feel gravity
  const double m = 1.5, L = 0.8, i_com = 0.02, m2 = 0.7, L2 = 1.1, i2 = 0.003, theta = 0.7, tau = 0.9;
  for (const bool tip_gravity : {true, false}) {
    ArticulationDesc desc = one_dof_desc(JointType::Revolute, Vec3::UnitY(), m, Vec3(0, 0, -L), Vec3::Constant(i_com));
    desc.links.push_back(make_link("tip", 1, m2, Vec3::Zero(), Vec3::Constant(i2)));
    desc.links.back().has_gravity = tip_gravity;
    desc.joints.push_back(make_joint("tip_weld", JointType::Hard, Vec3::UnitZ(), Transform{Quat::Identity(), Vec3(0, 0, -L2)}));
    Scene scene = z_up_scene("welded_tip");
    const ActorHandle p = scene.create_articulated_actor(desc, "pendulum");
    scene.set_pose(p, VecX::Constant(1, theta));
    const double inertia = i_com + m * L * L + i2 + m2 * L2 * L2;
    const double weight_torque = (m * L + (tip_gravity ? m2 * L2 : 0)) * kG * std::sin(theta);
    EXPECT_NEAR(scene.mass_matrix(p)(0, 0), inertia, 1e-12) << "tip gravity " << tip_gravity;
    EXPECT_NEAR(scene.bias_forces(p)[0], weight_torque, 1e-12) << "tip gravity " << tip_gravity;
    EXPECT_NEAR(scene.forward_dynamics(p, VecX::Constant(1, tau))[0], (tau - weight_torque) / inertia, 1e-12)
        << "tip gravity " << tip_gravity;
  }
}

TEST_F(DynamicsTest, MasslessWeldedFrameAddsNothing) {
  // a massless frame welded below a pendulum (a fingertip, a flange): the pendulum's analytic
  // inertia and weight torque are unchanged, and the frame's pose is the weld's
  const double m = 1.5, L = 0.8, i_com = 0.02, theta = 0.4;
  ArticulationDesc desc = one_dof_desc(JointType::Revolute, Vec3::UnitY(), m, Vec3(0, 0, -L), Vec3::Constant(i_com));
  LinkDesc frame;
  frame.name = "tip_frame";
  frame.parent_link = 1;
  frame.mass = 0;
  desc.links.push_back(frame);
  desc.joints.push_back(make_joint("tip_weld", JointType::Hard, Vec3::UnitZ(), Transform{Quat::Identity(), Vec3(0, 0, -1.0)}));
  Scene scene = z_up_scene("massless_frame");
  const ActorHandle p = scene.create_articulated_actor(desc, "pendulum");
  scene.set_pose(p, VecX::Constant(1, theta));
  EXPECT_NEAR(scene.mass_matrix(p)(0, 0), i_com + m * L * L, 1e-12);
  EXPECT_NEAR(scene.bias_forces(p)[0], m * L * kG * std::sin(theta), 1e-12);
  // the frame's origin: 1 m from the pivot along the pendulum, turned by theta about y
  const auto links = scene.nested_link_actors(p);
  const Vec3 pivot = scene.root_transform(links[1]).translation;
  const Vec3 expected = pivot + Vec3(-std::sin(theta), 0, -std::cos(theta));
  EXPECT_LT((scene.root_transform(links[2]).translation - expected).norm(), 1e-12);
}

TEST_F(DynamicsTest, MasslessLinkOnAMovingJointIsAnError) {
  ArticulationDesc desc = one_dof_desc(JointType::Revolute, Vec3::UnitY(), 1.0, Vec3(0, 0, -0.5), Vec3::Constant(0.01));
  desc.links[1].mass = 0;
  desc.links[1].moment_of_inertia.reset();
  Scene scene = z_up_scene("massless_moving");
  try {
    scene.create_articulated_actor(desc, "pendulum");
    ADD_FAILURE() << "a massless link on a revolute joint was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("links[1].mass: must be a positive finite number, got 0 (a massless link must hang from a Hard joint"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace superdex::physics::test
