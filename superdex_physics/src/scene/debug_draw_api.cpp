// The DebugDraw handle (superdex/physics/debug_draw.h): the scene's feature switches, actor
// flags and the gather into buffers that are shared with the data handed out.

#include <algorithm>

#include "output/debug_draw_features.h"
#include "scene/actor_lookup.h"
#include "superdex/physics/debug_draw.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

template <class T>
bool same_values(std::span<const T> a, std::span<const T> b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end());
}

// The feature at `index`, or superdex::Error naming the call, the argument and the valid range.
int checked_feature(int index, const char* what) {
  if (index < 0 || index >= kNumDebugDrawFeatures)
    throw Error(std::string(what) + ": index " + std::to_string(index) + " is out of range [0, " + std::to_string(kNumDebugDrawFeatures) +
                ") (DebugDraw.get_num_features())");
  return index;
}

}  // namespace

bool DebugDrawSpheres::operator==(const DebugDrawSpheres& o) const {
  return same_values(positions, o.positions) && same_values(radii, o.radii) && same_values(colors, o.colors);
}

bool DebugDrawLineVertices::operator==(const DebugDrawLineVertices& o) const {
  return same_values(positions, o.positions) && same_values(colors, o.colors);
}

bool DebugDraw::is_enabled() const { return scene_data(scene_).debug_draw.settings.enabled; }

void DebugDraw::enable(bool enable) { scene_data(scene_).debug_draw.settings.enabled = enable; }

int DebugDraw::num_features() const {
  scene_data(scene_);  // a destroyed scene's handle is refused like every other call's
  return kNumDebugDrawFeatures;
}

int DebugDraw::find_feature(const std::string& name) const {
  scene_data(scene_);
  for (int i = 0; i < kNumDebugDrawFeatures; ++i)
    if (name == kDebugDrawFeatures[i].name) return i;
  return -1;
}

std::string DebugDraw::feature_name(int index) const {
  scene_data(scene_);
  return kDebugDrawFeatures[checked_feature(index, "get_feature_name")].name;
}

std::string DebugDraw::feature_description(int index) const {
  scene_data(scene_);
  return kDebugDrawFeatures[checked_feature(index, "get_feature_description")].description;
}

bool DebugDraw::is_feature_enabled(int index) const {
  return scene_data(scene_).debug_draw.settings.features[checked_feature(index, "is_feature_enabled")];
}

void DebugDraw::enable_feature(int index, bool enable) {
  scene_data(scene_).debug_draw.settings.features[checked_feature(index, "enable_feature")] = enable;
}

void DebugDraw::enable_actor(ActorHandle actor, bool enable) {
  SceneData& s = scene_data(scene_);
  lookup(s, actor, "enable_actor");
  if (enable) s.debug_draw.settings.disabled_actors.erase(actor);
  else s.debug_draw.settings.disabled_actors.insert(actor);
}

bool DebugDraw::is_actor_enabled(ActorHandle actor) const {
  SceneData& s = scene_data(scene_);
  const ActorRef r = lookup(s, actor, "is_actor_enabled");
  const auto& disabled = s.debug_draw.settings.disabled_actors;
  // a link is drawn only when its articulation is
  return !disabled.count(actor) && !(is_link_actor(r) && disabled.count(r.articulation->handle));
}

DebugDrawData DebugDraw::gather_data() {
  SceneData& s = scene_data(scene_);
  DebugDrawState& state = s.debug_draw;
  // the buffers handed out last time are written again only when no one holds them any more
  if (!state.buffers || state.buffers.use_count() > 1) state.buffers = std::make_shared<DebugDrawBuffers>();
  DebugDrawBuffers& b = *state.buffers;
  gather_debug_draw(s, state.settings, b);
  DebugDrawData data;
  data.line_vertices = {b.line_positions, b.line_colors};
  data.spheres = {b.sphere_positions, b.sphere_radii, b.sphere_colors};
  data.owner = state.buffers;
  return data;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
