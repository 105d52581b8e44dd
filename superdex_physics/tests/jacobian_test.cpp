/// @file jacobian_test.cpp
/// Scene::link_jacobian against central finite differences of the link poses: for every DOF
/// k the positions are advanced along the unit velocity e_k by +-eps (integrate_positions),
/// and the link origin displacement / (2 eps) and the rotation-vector log of the relative
/// rotation / (2 eps) must equal the linear and angular Jacobian columns.

#include <vector>

#include "multibody/articulation_model.h"
#include "multibody/kinematics.h"
#include "core/spatial.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

Transform make_transform(const Vec3& rotvec, const Vec3& p) { return {quat_exp(rotvec), p}; }

/// Free root and a branched chain of revolute, prismatic, spherical and revolute joints with
/// arbitrary axes, joint placements and COMs.
ArticulationDesc branched_chain() {
  ArticulationDesc d;
  d.name = "chain";
  d.world_from_root = make_transform(Vec3(0.1, -0.2, 0.3), Vec3(0.5, -0.4, 0.2));
  d.links = {make_link("root", -1, 2.0, Vec3(0.1, 0, 0.05), Vec3(0.1, 0.2, 0.15)),
             make_link("l1", 0, 1.0, Vec3(0, 0.2, 0.1), Vec3(0.02, 0.03, 0.04)),
             make_link("l2", 1, 0.7, Vec3(0.1, -0.1, 0), Vec3(0.01, 0.01, 0.015)),
             make_link("l3", 2, 0.5, Vec3(0, 0, 0.2), Vec3(0.01, 0.012, 0.008)),
             make_link("l4", 3, 0.3, Vec3(0.15, 0.05, 0), Vec3(0.004, 0.005, 0.006)),
             make_link("l5", 1, 0.4, Vec3(-0.1, 0, 0.1), Vec3(0.005, 0.004, 0.006))};
  d.joints = {make_joint("j0", JointType::Free, Vec3::UnitZ(), make_transform(Vec3(-0.2, 0.1, 0.05), Vec3(0.1, 0, 0))),
              make_joint("j1", JointType::Revolute, Vec3(0.3, -0.5, 0.8), make_transform(Vec3(0.2, 0.4, -0.1), Vec3(0.2, 0.1, 0.3))),
              make_joint("j2", JointType::Prismatic, Vec3(1, 0.2, -0.1), make_transform(Vec3(0, -0.3, 0.2), Vec3(0, 0.4, 0))),
              make_joint("j3", JointType::Spherical, Vec3::UnitZ(), make_transform(Vec3(0.5, 0, 0), Vec3(0.1, 0.1, 0.3))),
              make_joint("j4", JointType::Revolute, Vec3(0, 1, 0), make_transform(Vec3(0, 0, 0.7), Vec3(0, 0, 0.25))),
              make_joint("j5", JointType::Prismatic, Vec3(0, 0, 1), make_transform(Vec3(0.1, 0.1, 0.1), Vec3(-0.2, 0, 0)))};
  return d;
}

/// A fixed, non-special pose: root position and rotation vector, then the other joints.
VecX test_pose(int nv) {
  VecX pose(nv);
  pose << 0.3, -0.2, 1.0, 0.4, -0.3, 0.7,  // free root
      0.8,                                   // revolute j1
      0.25,                                  // prismatic j2
      -0.6, 0.9, 0.35,                       // spherical j3
      -1.1,                                  // revolute j4
      0.15;                                  // prismatic j5
  return pose;
}

class JacobianTest : public EngineTest {};

TEST_F(JacobianTest, MatchesFiniteDifferencesOfLinkPoses) {
  const ArticulationDesc desc = branched_chain();
  Scene scene = create_scene("jacobian");
  const ActorHandle art = scene.create_articulated_actor(desc, "chain");
  const int nv = scene.num_dofs(art);
  ASSERT_EQ(nv, 13);
  // the same model, privately, to move positions along a velocity direction
  const ArticulationModel model = build_articulation_model(desc, "chain");
  const VecX pose0 = test_pose(nv);
  VecX q0(model.nq);
  q_from_pose(model, pose0.data(), false, q0);

  scene.set_pose(art, pose0);
  const std::vector<ActorHandle> links = scene.nested_link_actors(art);
  std::vector<MatXR> J;
  for (ActorHandle l : links) J.push_back(scene.link_jacobian(l));

  // link poses after moving along e_k for a signed time h
  auto poses_after = [&](int k, double h) {
    VecX q = q0, pose(nv);
    integrate_positions(model, q, VecX::Unit(nv, k), h);
    pose_from_q(model, q, pose.data());
    scene.set_pose(art, pose);
    return scene.link_transforms(art);
  };
  const double eps = 1e-6;
  for (int k = 0; k < nv; ++k) {
    const std::vector<Transform> plus = poses_after(k, eps), minus = poses_after(k, -eps);
    for (size_t i = 0; i < links.size(); ++i) {
      Vec6 fd;
      fd.head<3>() = (plus[i].translation - minus[i].translation) / (2 * eps);
      // world-axes angular velocity: R(+eps) = exp(2 eps w) R(-eps)
      fd.tail<3>() = quat_log(plus[i].rotation * minus[i].rotation.conjugate()) / (2 * eps);
      const Vec6 col = J[i].col(k);
      EXPECT_LE((fd - col).norm(), 1e-6 * std::max(1.0, col.norm())) << "link " << i << " dof " << k << "\nfd  " << fd.transpose() << "\nJac " << col.transpose();
    }
  }
}

TEST_F(JacobianTest, NonAncestorColumnsAreZeroAndRootHandleGivesLinkZero) {
  Scene scene = create_scene("jacobian_structure");
  const ActorHandle art = scene.create_articulated_actor(branched_chain(), "chain");
  scene.set_pose(art, test_pose(scene.num_dofs(art)));
  const std::vector<ActorHandle> links = scene.nested_link_actors(art);
  // link 5 hangs off link 1: DOFs of j2 (7), j3 (8..10) and j4 (11) do not move it
  const MatXR J5 = scene.link_jacobian(links[5]);
  EXPECT_EQ(J5.middleCols(7, 5).norm(), 0);
  // link 2 is not moved by j3, j4, j5
  EXPECT_EQ(scene.link_jacobian(links[2]).rightCols(5).norm(), 0);
  // the articulation handle refers to its root link
  EXPECT_TRUE(scene.link_jacobian(art).isApprox(scene.link_jacobian(links[0])));
}

TEST_F(JacobianTest, MapsJointVelocitiesToReportedLinkVelocity) {
  const ArticulationDesc desc = branched_chain();
  Scene scene = create_scene("jacobian_velocity");
  const ActorHandle art = scene.create_articulated_actor(desc, "chain");
  const int nv = scene.num_dofs(art);
  scene.set_pose(art, test_pose(nv));
  VecX v(nv);
  for (int k = 0; k < nv; ++k) v[k] = std::sin(1.7 * k + 0.3);
  scene.set_joint_velocities(art, v);
  // J v is the (linear, angular) world velocity of each link origin; Scene::velocity reports
  // its centre of mass's: v_origin + w x (R com_L)
  const std::vector<ActorHandle> links = scene.nested_link_actors(art);
  for (size_t i = 0; i < links.size(); ++i) {
    Vec6 expected = scene.link_jacobian(links[i]) * v;
    const Vec3 r_W = scene.link_transform(art, static_cast<int>(i)).rotation * *desc.links[i].center_of_mass;
    expected.head<3>() += expected.tail<3>().cross(r_W);
    EXPECT_LE((scene.velocity(links[i]) - expected).norm(), 1e-12 * (1 + expected.norm())) << "link " << i;
  }
}

}  // namespace
}  // namespace superdex::physics::test
