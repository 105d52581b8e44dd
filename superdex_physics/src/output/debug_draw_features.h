#pragma once
// Debug drawing's features, per-scene settings and output buffers (the public side is
// superdex/physics/debug_draw.h). The feature table is fixed (the model); what a scene draws
// (DebugDrawSettings) and what it drew last (DebugDrawBuffers) live in its SceneData.

#include <array>
#include <memory>
#include <set>
#include <vector>

#include "superdex/physics/handles.h"
#include "superdex/physics/types.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct SceneData;

// The features, in the order of their public indices.
enum class DebugDrawFeature { ContactPoints, ContactNormals, ContactForces, ActorAabbs, ActorFrames, CentersOfMass, JointAxes, SoftSurfaceEdges };
inline constexpr int kNumDebugDrawFeatures = 8;

struct DebugDrawFeatureInfo {
  const char* name;         // what find_feature takes
  const char* description;  // one line: what is drawn, and how it is scaled and coloured
};
// The table, indexed by DebugDrawFeature.
extern const std::array<DebugDrawFeatureInfo, kNumDebugDrawFeatures> kDebugDrawFeatures;

// What a scene draws: all off by default, every actor on.
struct DebugDrawSettings {
  bool enabled = false;                                // the master switch
  std::array<bool, kNumDebugDrawFeatures> features{};  // by DebugDrawFeature
  std::set<ActorHandle> disabled_actors;               // handles never reused: stale ones are harmless
};

// The primitives of one gather (world frame, m). Line vertices come in pairs.
struct DebugDrawBuffers {
  std::vector<Real3> line_positions;
  std::vector<Color> line_colors;
  std::vector<Real3> sphere_positions;
  std::vector<real> sphere_radii;
  std::vector<Color> sphere_colors;
};

// A scene's debug drawing. `buffers` is shared with the DebugDrawData handed out: a gather
// writes into it only when nobody else holds it, else into new buffers, so that handed-out views
// never change under their reader.
struct DebugDrawState {
  DebugDrawSettings settings;
  std::shared_ptr<DebugDrawBuffers> buffers;
};

// Fills `out` (cleared first) with the primitives of the enabled features and actors of `s`,
// from its current state and the contacts of its last step.
void gather_debug_draw(const SceneData& s, const DebugDrawSettings& settings, DebugDrawBuffers& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
