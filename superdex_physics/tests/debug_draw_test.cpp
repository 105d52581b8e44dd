/// @file debug_draw_test.cpp
/// DebugDraw through the public C++ API: a 0.2 m cube resting on the plane z = 0 gives contact
/// spheres on the plane inside its footprint; its bounds are 12 edges at the analytic box; the
/// master switch, feature indices and actor flags behave as debug_draw.h says; and gathered data
/// stays readable after a later gather and after the scene is destroyed.

#include <algorithm>

#include "superdex/physics/debug_draw.h"
#include "superdex/physics/error.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

constexpr real kHalf = real(0.1);

class DebugDrawTest : public EngineTest {
 protected:
  void SetUp() override {
    EngineTest::SetUp();
    scene_ = z_up_scene("debug_draw");
  }
  // A cube centred at (0.3, -0.2, kHalf + 1 mm) above the ground plane, settled for 0.5 s.
  void make_resting_box() {
    scene_.create_rigid_actor(static_params("ground", create_shape(PlaneShape{})));
    Transform X_WB;
    X_WB.translation = Vec3(real(0.3), real(-0.2), kHalf + real(1e-3));
    box_ = scene_.create_rigid_actor(rigid_params("box", create_shape(BoxShape{Vec3::Constant(kHalf)}), X_WB, real(2)));
    for (int n = 0; n < 50; ++n) scene_.step(0.01);
  }
  // The draw with only `feature` on, enabled.
  DebugDraw only(const std::string& feature) {
    DebugDraw draw = scene_.debug_draw();
    draw.enable(true);
    for (int i = 0; i < draw.num_features(); ++i) draw.enable_feature(i, draw.feature_name(i) == feature);
    return draw;
  }
  Scene scene_{SceneHandle()};  // made once the engine runs (SetUp)
  ActorHandle box_;
};

TEST_F(DebugDrawTest, ContactSpheresLieOnTheGroundUnderTheBox) {
  make_resting_box();
  const DebugDrawData data = only("contact_points").gather_data();
  ASSERT_GE(data.spheres.positions.size(), 4u);
  EXPECT_EQ(data.spheres.radii.size(), data.spheres.positions.size());
  EXPECT_TRUE(data.line_vertices.positions.empty());
  for (const Real3& p : data.spheres.positions) {
    EXPECT_LT(std::abs(p.z()), 2e-3);
    EXPECT_LE(std::abs(p.x() - 0.3), kHalf + 1e-3);
    EXPECT_LE(std::abs(p.y() + 0.2), kHalf + 1e-3);
  }
}

TEST_F(DebugDrawTest, AabbIsTwelveEdgesOfTheAnalyticBox) {
  make_resting_box();
  const DebugDrawData data = only("actor_aabbs").gather_data();  // the plane is unbounded: skipped
  ASSERT_EQ(data.line_vertices.positions.size(), 24u);
  const Aabb box = scene_.aabb_world(box_);
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (const Real3& p : data.line_vertices.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  EXPECT_TRUE(lo.isApprox(box.min)) << lo.transpose();
  EXPECT_TRUE(hi.isApprox(box.max)) << hi.transpose();
  EXPECT_NEAR(hi.x() - lo.x(), 2 * kHalf, 2e-3);  // the resting box stays upright
}

TEST_F(DebugDrawTest, SwitchesAndIndices) {
  make_resting_box();
  DebugDraw draw = scene_.debug_draw();
  EXPECT_FALSE(draw.is_enabled());
  const int aabbs = draw.find_feature("actor_aabbs");
  ASSERT_GE(aabbs, 0);
  EXPECT_EQ(draw.find_feature("Actor_Aabbs"), -1);
  draw.enable_feature(aabbs, true);
  EXPECT_TRUE(draw.gather_data().line_vertices.positions.empty());  // master off
  draw.enable(true);
  EXPECT_EQ(draw.gather_data().line_vertices.positions.size(), 24u);
  draw.enable_actor(box_, false);
  EXPECT_FALSE(draw.is_actor_enabled(box_));
  EXPECT_TRUE(draw.gather_data().line_vertices.positions.empty());
  EXPECT_THROW(draw.feature_name(draw.num_features()), Error);
  EXPECT_THROW(draw.enable_feature(-1, true), Error);
  EXPECT_THROW(draw.enable_actor(ActorHandle(next_handle()), false), Error);
}

TEST_F(DebugDrawTest, DataOutlivesLaterGathersAndTheScene) {
  make_resting_box();
  DebugDraw draw = only("actor_aabbs");
  const DebugDrawData first = draw.gather_data();
  const std::vector<Real3> before(first.line_vertices.positions.begin(), first.line_vertices.positions.end());
  Transform X_WB;
  X_WB.translation = Vec3(5, 5, 5);
  scene_.set_root_transform(box_, X_WB);
  const DebugDrawData second = draw.gather_data();
  EXPECT_FALSE(first == second);
  destroy_scene(scene_.handle());
  EXPECT_TRUE(std::equal(before.begin(), before.end(), first.line_vertices.positions.begin(), first.line_vertices.positions.end()));
  EXPECT_THROW(draw.gather_data(), Error);
}

}  // namespace
}  // namespace superdex::physics::test
