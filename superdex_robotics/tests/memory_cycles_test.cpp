/// @file memory_cycles_test.cpp
/// Memory over many episodes: create a scene, load the example bot and a rigid prefab from their
/// files, step 100 times, destroy; 10,000 such cycles keep the process's resident memory flat
/// (within 5 % between the end of a 1,000-cycle warm-up and the end of the run). The C++ twin of
/// superdex_robotics/python/tests/test_memory_cycles.py, without Python in the way.
///
/// tools/dev.sh sanitize runs it under LeakSanitizer (detect_leaks=1): a block still allocated at
/// exit and no longer referenced fails the run even when it is too small to move the RSS.
/// SUPERDEX_MEMORY_CYCLES sets the number of cycles (default 10,000) for quick local runs.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "superdex/physics/engine.h"
#include "superdex/physics/prefab.h"
#include "superdex/physics/scene.h"
#include "superdex/robotics/bot_prefab.h"
#include "superdex/robotics/context.h"

#ifndef SUPERDEX_ASSETS_DIR
#error "SUPERDEX_ASSETS_DIR must name the repository's assets/ folder"
#endif

namespace superdex::robotics::test {
namespace {

namespace fs = std::filesystem;
using physics::real;
using physics::Vec3;
using physics::VecX;

constexpr int kSteps = 100;
constexpr int kWarmUpCycles = 1000;

int cycles() {
  const char* v = std::getenv("SUPERDEX_MEMORY_CYCLES");
  return v && *v ? std::max(kWarmUpCycles + 1000, std::atoi(v)) : 10000;
}

// resident memory of this process (KiB), from /proc/self/status
long rss_kib() {
  std::ifstream status("/proc/self/status");
  std::string key;
  long value = 0;
  while (status >> key) {
    if (key == "VmRSS:" && status >> value) return value;
    status.ignore(1 << 20, '\n');
  }
  return -1;
}

// The example bot's component types, in C++: a sensor that reads its link's contact force
// through a registered query, and a servo with a constant small effort.
class ForceSensor : public SensorComponent {
 public:
  explicit ForceSensor(const ComponentArgs& a) : scene_(a.scene), actor_(a.actor) {
    scene_.register_query(actor_, physics::QueryType::TotalContactForce);
  }
  void reset() override { force_.setZero(); }
  void update(const Tick&) override { force_ = scene_.contact_force(actor_); }
  VecX signal() const override { return force_; }

 private:
  physics::Scene scene_;
  physics::ActorHandle actor_;
  Vec3 force_ = Vec3::Zero();
};

class ConstantServo : public ActuatorComponent {
 public:
  void reset() override {}
  real compute_effort(const Tick&, const DofCommand&) override { return real(0.01); }
};

TEST(MemoryCyclesTest, TenThousandEpisodesKeepMemoryFlat) {
  const std::string bot_file = SUPERDEX_ASSETS_DIR "/bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot";
  const fs::path dir = fs::temp_directory_path() / ("superdex_memory_cycles_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path prefab = dir / "table.mochi_prefab";
  std::ofstream(prefab) << R"({"actors": {"rigid": [
    {"name": "ground", "shape": {"plane": {"normal": [0, 0, 1], "distance": 0}}, "isStatic": true},
    {"name": "box", "shape": {"box": {"halfExtents": [0.05, 0.05, 0.05]}}, "mass": 0.5, "translation": [-0.3, 0, 0.05]}]}})";

  physics::initialize(0);
  // one episode; every warning is an error here (a warning per episode would itself grow memory)
  auto episode = [&] {
    physics::Scene scene = physics::create_scene("episode");
    scene.set_gravity(Vec3(0, 0, -9.81));
    Context ctx;
    ctx.register_type(ComponentKind::Sensor, "MY_CONTACT_FORCE_SENSOR",
                      [](const ComponentArgs& a) { return std::make_unique<ForceSensor>(a); });
    ctx.register_type(ComponentKind::Actuator, "MY_VELOCITY_SERVO_ACTUATOR",
                      [](const ComponentArgs&) { return std::make_unique<ConstantServo>(); });
    std::vector<std::string> warnings;
    const BotHandle bot = ctx.create_bot(scene, load_bot_prefab(bot_file, &warnings), &warnings);
    physics::prefab::PrefabParams params;
    params.name = "table";
    physics::prefab::add_to_scene(prefab.string(), dir.string(), scene, params, &warnings);
    ASSERT_TRUE(warnings.empty()) << warnings.front();
    for (int i = 0; i < kSteps; ++i) scene.step(real(0.01));
    ASSERT_NEAR(scene.total_simulation_time(), kSteps * 0.01, 1e-6);
    ctx.destroy_bot(bot);
    physics::destroy_scene(scene.handle());
  };

  const int total = cycles();
  for (int k = 0; k < kWarmUpCycles; ++k) ASSERT_NO_FATAL_FAILURE(episode());
  const long start = rss_kib();
  ASSERT_GT(start, 0) << "no /proc/self/status";
  std::vector<long> samples;
  for (int k = kWarmUpCycles; k < total; ++k) {
    ASSERT_NO_FATAL_FAILURE(episode());
    if ((k + 1) % 1000 == 0) samples.push_back(rss_kib());
  }
  physics::shutdown();
  fs::remove_all(dir);

  std::string trace;
  for (long s : samples) trace += std::to_string(s) + " ";
#if defined(__SANITIZE_ADDRESS__)
#define SUPERDEX_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SUPERDEX_TEST_UNDER_ASAN 1
#endif
#endif
#if defined(SUPERDEX_TEST_UNDER_ASAN)
  // ASan holds freed blocks in a quarantine of bounded size, which fills over the first thousand
  // episodes: growth is measured from the first sample on
  const long baseline = samples.front();
#else
  const long baseline = start;
#endif
  EXPECT_LE(samples.back(), baseline * 1.05) << "RSS grew from " << baseline << " KiB over " << total - kWarmUpCycles
                                          << " episodes: " << trace;
}

}  // namespace
}  // namespace superdex::robotics::test
