/// @file broad_phase_test.cpp
/// The broad phase: a collider's world bounds enclose exactly its posed corners; its sweep bound
/// uses the bounds' corner farthest from the link origin; and the contact list, like the step's
/// contact results, comes out in the order of the contacts' links (body_a, link_a, body_b,
/// link_b), with plane contacts in their place among the others.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>

#include "collision/collision_detection.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

// The eight corners of local bounds.
std::array<Vec3, 8> corners(const Bounds& box) {
  std::array<Vec3, 8> out;
  for (int k = 0; k < 8; ++k)
    out[k] = Vec3(k & 1 ? box.max.x() : box.min.x(), k & 2 ? box.max.y() : box.min.y(), k & 4 ? box.max.z() : box.min.z());
  return out;
}

SpatialTransform random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
  return {Quat(Eigen::AngleAxis<real>(3 * u(rng), axis)).toRotationMatrix(), Vec3(u(rng), u(rng), u(rng))};
}

Bounds random_bounds(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1), size(0.01, 0.5);
  Bounds box;
  box.min = Vec3(u(rng), u(rng), u(rng));
  box.max = box.min + Vec3(size(rng), size(rng), size(rng));
  return box;
}

TEST(BroadPhase, WorldBoundsAreTheBoundsOfThePosedCorners) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Bounds local = random_bounds(rng);
    const SpatialTransform X = random_pose(rng);
    Bounds expected;
    for (const Vec3& c : corners(local)) expected.extend(X.R * c + X.p);
    const Bounds bounds = world_bounds(local, X);
    EXPECT_LT((bounds.min - expected.min).norm(), 1e-12) << "trial " << trial;
    EXPECT_LT((bounds.max - expected.max).norm(), 1e-12) << "trial " << trial;
  }
}

TEST(BroadPhase, SweepBoundIsSpeedPlusAngularSpeedTimesTheFarthestCorner) {
  std::mt19937 rng(11);
  const real dt = real(0.004);
  for (int trial = 0; trial < 50; ++trial) {
    LinkCollider col;
    col.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
    col.aabb_S = random_bounds(rng);
    col.X_LS = random_pose(rng);
    Articulation a;
    a.model.nv = 6;
    const Vec6 V = Vec6::Random();
    a.kin.V_L = {V};
    double reach = 0;
    for (const Vec3& c : corners(col.aabb_S)) reach = std::max(reach, static_cast<double>((col.X_LS.R * c + col.X_LS.p).norm()));
    const double expected = dt * (V.head<3>().norm() + V.tail<3>().norm() * reach);
    EXPECT_NEAR(collider_sweep(a, col, dt), expected, 1e-12) << "trial " << trial;
  }
}

class ContactOrderTest : public EngineTest {};

// (body_a, link_a, body_b, link_b) of a contact result or candidate
template <class C>
auto links_of(const C& c) {
  return std::make_tuple(c.body_a, c.link_a, c.body_b, c.link_b);
}

TEST_F(ContactOrderTest, ContactsComeInTheOrderOfTheirLinksPlaneContactsIncluded) {
  Scene scene = z_up_scene("order");
  // the ground first (body 0): a box's ground contact (box, 0, 0, 0) then sorts before its
  // contacts with the bodies above it, which the sweep finds before the plane's pairs
  scene.create_rigid_actor(static_params("ground", create_shape(PlaneShape{})));
  const ShapeHandle box = create_shape(BoxShape{Vec3::Constant(real(0.1))});
  const ShapeHandle ball = create_shape(SphereShape{Vec3::Zero(), real(0.08)});
  for (int column = 0; column < 3; ++column)
    for (int level = 0; level < 3; ++level) {
      Transform X;
      X.translation = Vec3(0.35 * column, 0.01 * level, 0.1 + 0.2 * level);
      scene.create_rigid_actor(rigid_params("box", level == 1 && column == 1 ? ball : box, X, real(1)));
    }
  // a two-link chain lying on the ground, across the columns: contacts on both of its links
  ArticulationDesc chain;
  chain.name = "chain";
  chain.links = {make_link("a", -1, 1, Vec3::Zero(), Vec3::Constant(real(0.01))), make_link("b", 0, 1, Vec3::Zero(), Vec3::Constant(real(0.01)))};
  chain.links[0].shape = BoxShape{Vec3(0.3, 0.05, 0.05)};
  chain.links[1].shape = BoxShape{Vec3(0.3, 0.05, 0.05)};
  Transform X_PJ;
  X_PJ.translation = Vec3(0.6, 0, 0);
  chain.joints = {make_joint("free", JointType::Free), make_joint("hinge", JointType::Revolute, Vec3::UnitY(), X_PJ)};
  const ActorHandle chain_actor = scene.create_articulated_actor(chain, "chain");
  Transform X_chain;
  X_chain.translation = Vec3(0.1, 0.4, 0.05);
  scene.set_root_transform(chain_actor, X_chain);

  const SceneData& s = scene_data(scene.handle());
  for (int step = 0; step < 40; ++step) {
    scene.step(real(0.004));
    const std::vector<Contact> candidates = detect_contacts(s, s.params.contact_margin, real(0.004));
    ASSERT_TRUE(std::is_sorted(candidates.begin(), candidates.end(), [](const Contact& x, const Contact& y) { return links_of(x) < links_of(y); }))
        << "step " << step;
    ASSERT_TRUE(std::is_sorted(s.contacts.begin(), s.contacts.end(), [](const ContactRecord& x, const ContactRecord& y) {
      return links_of(x) < links_of(y);
    })) << "step " << step;
  }
  // the order was put to the test: a body touched the ground and a body above it, and the
  // chain's second link touched something
  bool ground_then_above = false, second_link = false;
  for (size_t i = 0; i + 1 < s.contacts.size(); ++i)
    ground_then_above |= s.contacts[i].body_b == 0 && s.contacts[i + 1].body_a == s.contacts[i].body_a && s.contacts[i + 1].body_b > 0;
  for (const ContactRecord& c : s.contacts) second_link |= c.link_a == 1 || c.link_b == 1;
  EXPECT_TRUE(ground_then_above);
  EXPECT_TRUE(second_link);
}

}  // namespace
}  // namespace superdex::physics::test
