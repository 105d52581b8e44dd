#pragma once
// The step's hook into a running recording (superdex/physics/recording.h).

#include "scene/scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Writes the scene's state as a frame when a recording runs and its frame interval has passed.
void record_step(const SceneData& scene);
// Writes the scene's state as a frame now when a recording runs, unless that frame would repeat
// the scene's last one.
void record_current_frame(const SceneData& scene);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
