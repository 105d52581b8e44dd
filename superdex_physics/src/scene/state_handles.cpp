// Captured states by handle, as bytes and as a JSON snapshot; the single-island switch; the list of
// every actor.

#include <algorithm>

#include <fstream>

#include <nlohmann/json.hpp>

#include "scene/scene_data.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

StateHandle Scene::capture_state() {
  SceneData& s = scene_data(handle_);
  const StateHandle h = next_handle();
  s.states[h] = state_bytes(s);
  return h;
}

void Scene::restore_state(StateHandle state, bool release) {
  SceneData& s = scene_data(handle_);
  auto it = s.states.find(state);
  if (it == s.states.end())
    throw Error("restore_state: state " + std::to_string(state.value) + " is not a state captured in scene '" + s.name +
                "' (never captured, or released)");
  // released even when the restore fails
  std::vector<std::uint8_t> bytes = release ? std::move(it->second) : it->second;
  if (release) s.states.erase(it);
  restore_state_bytes(s, bytes);
}

void Scene::release_state(StateHandle state) { scene_data(handle_).states.erase(state); }

void Scene::release_all_states() { scene_data(handle_).states.clear(); }

bool Scene::is_equal_state(StateHandle a, StateHandle b) const {
  const SceneData& s = scene_data(handle_);
  auto ia = s.states.find(a), ib = s.states.find(b);
  return ia != s.states.end() && ib != s.states.end() && ia->second == ib->second;
}

void Scene::capture_state_to_bytes(std::vector<std::uint8_t>& out) const {
  const std::vector<std::uint8_t> bytes = state_bytes(scene_data(handle_));
  out.insert(out.end(), bytes.begin(), bytes.end());
}

void Scene::restore_state_from_bytes(std::span<const std::uint8_t> bytes) { restore_state_bytes(scene_data(handle_), bytes); }

void Scene::capture_state_to_file(const std::string& path) const {
  const SceneData& s = scene_data(handle_);
  nlohmann::json j;
  j["scene"] = s.name;
  j["time"] = s.time;
  j["lastTimeStep"] = s.last_time_step;
  auto vector = [](const auto& v) {
    nlohmann::json a = nlohmann::json::array();
    for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(static_cast<double>(v[i]));
    return a;
  };
  nlohmann::json actors = nlohmann::json::array();
  for (const auto& a : s.articulations) {
    nlohmann::json e;
    e["handle"] = a->handle.value;
    e["name"] = a->model.name;
    e["q"] = vector(a->state.q);
    e["v"] = vector(a->state.v);
    e["externalForces"] = vector(a->state.tau_external);
    actors.push_back(std::move(e));
  }
  for (const auto& b : s.soft_bodies) {
    nlohmann::json e;
    e["handle"] = b->handle.value;
    e["name"] = b->model.name;
    e["rootRotation"] = vector(b->X_WL.rotation.coeffs());
    e["rootTranslation"] = vector(b->X_WL.translation);
    e["nodePositionsWorld"] = vector(b->state.x);
    e["nodeVelocitiesWorld"] = vector(b->state.v);
    actors.push_back(std::move(e));
  }
  j["actors"] = std::move(actors);
  std::ofstream f(path);
  if (!f) throw Error("capture_state_to_file: cannot write '" + path + "'");
  f << j.dump(2) << "\n";
  if (!f) throw Error("capture_state_to_file: writing '" + path + "' failed");
}

void Scene::set_force_single_island(bool force) { scene_data(handle_).force_single_island = force; }
bool Scene::force_single_island() const { return scene_data(handle_).force_single_island; }

std::vector<ActorHandle> Scene::all_actors() const {
  const SceneData& s = scene_data(handle_);
  std::vector<ActorHandle> out;
  for (const auto& a : s.articulations) {
    out.push_back(a->handle);
    if (!a->is_rigid)
      for (ActorHandle l : a->link_handles) out.push_back(l);
  }
  for (const auto& b : s.soft_bodies) out.push_back(b->handle);
  // handles come from one increasing counter, and an articulation's links right after it
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
