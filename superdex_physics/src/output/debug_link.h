#pragma once
// The step's hooks into the debug server (superdex/physics/debug_server.h): wait while the page
// holds the simulation paused, restore the initial state on request, keep real time, and send
// frames to the page.

#include "scene/scene_data.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// At the start of Scene::step: blocks while paused; restores the scene's first state on request.
void debug_before_step(Scene& scene);
// At the end of Scene::step: reports progress, paces real-time play and sends a frame when due.
void debug_after_step(Scene& scene, const SceneData& s);
// Scene::update_debugger: reports progress and sends a frame when the pages want one.
void debug_update(const SceneData& s);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
