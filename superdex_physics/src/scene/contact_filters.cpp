// The scene's contact filters: named contact layers and per-actor rules (collision_broad.cpp
// applies them).

#include <algorithm>

#include "scene/scene_data.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

int contact_layer_index(SceneData& s, const std::string& name, const std::string& where) {
  for (size_t i = 0; i < s.layer_names.size(); ++i)
    if (s.layer_names[i] == name) {
      s.layer_registered[i] = 1;
      return static_cast<int>(i);
    }
  if (s.layer_names.size() >= 64) throw Error(where + ": a scene has at most 64 contact layers; '" + name + "' would be the 65th");
  s.layer_names.push_back(name);
  s.layer_registered.push_back(1);
  return static_cast<int>(s.layer_names.size() - 1);
}

namespace {

int existing_layer(const SceneData& s, const std::string& name) {
  for (size_t i = 0; i < s.layer_names.size(); ++i)
    if (s.layer_names[i] == name) return static_cast<int>(i);
  return -1;
}

void require_name(const std::string& name, const char* what, const char* arg) {
  if (name.empty()) throw Error(std::string(what) + ": " + arg + " must be a non-empty layer name");
}

void set_layer_bit(SceneData& s, int a, int b, bool enable) {
  const std::uint64_t bit = std::uint64_t(1) << b;
  if (enable) s.layer_masks[a] |= bit;
  else s.layer_masks[a] &= ~bit;
}

}  // namespace

void Scene::enable_layer_contact_asymmetric(const std::string& layer_a, const std::string& layer_b, bool enable) {
  const char* what = "enable_layer_contact_asymmetric";
  require_name(layer_a, what, "layer_a");
  require_name(layer_b, what, "layer_b");
  SceneData& s = scene_data(handle_);
  const int a = contact_layer_index(s, layer_a, what), b = contact_layer_index(s, layer_b, what);
  set_layer_bit(s, a, b, enable);
}

void Scene::enable_layer_contact_symmetric(const std::string& layer_a, const std::string& layer_b, bool enable) {
  const char* what = "enable_layer_contact_symmetric";
  require_name(layer_a, what, "layer_a");
  require_name(layer_b, what, "layer_b");
  SceneData& s = scene_data(handle_);
  const int a = contact_layer_index(s, layer_a, what), b = contact_layer_index(s, layer_b, what);
  set_layer_bit(s, a, b, enable);
  set_layer_bit(s, b, a, enable);
}

bool Scene::is_layer_contact_enabled(const std::string& layer_a, const std::string& layer_b) const {
  const SceneData& s = scene_data(handle_);
  const int a = existing_layer(s, layer_a), b = existing_layer(s, layer_b);
  if (a < 0 || b < 0) return true;  // unknown layers have every contact enabled
  return (s.layer_masks[a] >> b) & 1;
}

int Scene::num_contact_layers() const {
  const SceneData& s = scene_data(handle_);
  return static_cast<int>(std::count(s.layer_registered.begin(), s.layer_registered.end(), 1));
}

std::vector<std::string> Scene::contact_layer_names() const {
  const SceneData& s = scene_data(handle_);
  std::vector<std::string> out;
  for (size_t i = 0; i < s.layer_names.size(); ++i)
    if (s.layer_registered[i]) out.push_back(s.layer_names[i]);
  return out;
}

std::string Scene::contact_layer(ActorHandle actor) const {
  const SceneData& s = scene_data(handle_);
  auto it = s.actors.find(actor);
  if (it == s.actors.end()) throw Error("get_contact_layer: actor " + std::to_string(actor) + " does not exist in scene '" + s.name + "'");
  const ActorRef& r = it->second;
  if (r.soft) return r.soft->layer;
  return r.articulation->links[std::max(r.link, 0)].layer;
}

void Scene::set_contact_layer(ActorHandle actor, const std::string& layer) {
  SceneData& s = scene_data(handle_);
  auto it = s.actors.find(actor);
  if (it == s.actors.end()) throw Error("set_contact_layer: actor " + std::to_string(actor) + " does not exist in scene '" + s.name + "'");
  const int index = contact_layer_index(s, layer, "set_contact_layer: layer");
  const ActorRef& r = it->second;
  if (r.soft) {
    r.soft->layer = layer;
    r.soft->layer_index = index;
    return;
  }
  // a link actor sets its own link's layer; a whole actor every link's
  Articulation& a = *r.articulation;
  for (int l = 0; l < a.model.num_links; ++l) {
    if (r.link >= 0 && l != r.link) continue;
    a.links[l].layer = layer;
    for (LinkCollider& c : a.model.colliders)
      if (c.link == l) c.layer = index;
  }
}

void Scene::enable_actor_contact_asymmetric(ActorHandle colliding, ActorHandle collider, bool enable, IncludeNestedActors nested) {
  SceneData& s = scene_data(handle_);
  for (ActorHandle h : {colliding, collider})
    if (!s.actors.count(h))
      throw Error("enable_actor_contact_asymmetric: actor " + std::to_string(h) + " does not exist in scene '" + s.name + "'");
  s.actor_contact[{colliding, collider}] = {enable, nested == IncludeNestedActors::Yes};
}

void Scene::enable_actor_contact_symmetric(ActorHandle a, ActorHandle b, bool enable, IncludeNestedActors nested) {
  SceneData& s = scene_data(handle_);
  for (ActorHandle h : {a, b})
    if (!s.actors.count(h)) throw Error("enable_actor_contact_symmetric: actor " + std::to_string(h) + " does not exist in scene '" + s.name + "'");
  s.actor_contact[{a, b}] = {enable, nested == IncludeNestedActors::Yes};
  s.actor_contact[{b, a}] = {enable, nested == IncludeNestedActors::Yes};
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
