#pragma once
// Looking actors up by handle for the actor API, with errors that name the call and the actor.

#include <string>
#include <utility>

#include "scene/scene_data.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

inline std::string describe(ActorHandle h) { return "actor " + std::to_string(h); }

inline ActorRef lookup(SceneData& s, ActorHandle h, const char* what) {
  auto it = s.actors.find(h);
  if (it == s.actors.end())
    throw Error(std::string(what) + ": " + describe(h) + " does not exist in scene '" + s.name + "' (destroyed, or never created here)");
  return it->second;
}

// The shape an actor was made from: a soft actor's, a rigid actor's or a link's; null for a whole
// articulation or a link without one.
inline std::shared_ptr<const ShapeData> actor_shape(const ActorRef& r) {
  if (r.soft) return r.soft->shape;
  if (r.link >= 0 || r.articulation->is_rigid) return r.articulation->links[std::max(r.link, 0)].shape;
  return nullptr;
}

inline bool is_link_actor(const ActorRef& r) { return r.link >= 0 && !r.articulation->is_rigid; }

inline void refuse_soft(const ActorRef& r, ActorHandle h, const char* what) {
  if (r.soft) throw Error(std::string(what) + ": " + describe(h) + " is a soft actor ('" + r.soft->model.name + "')");
}

// The articulation behind a rigid or articulated actor; link and soft actors are refused.
inline Articulation& whole(SceneData& s, ActorHandle h, const char* what) {
  ActorRef r = lookup(s, h, what);
  refuse_soft(r, h, what);
  if (is_link_actor(r))
    throw Error(std::string(what) + ": " + describe(h) + " is a link actor; call it on its articulation (" +
                describe(r.articulation->handle) + ")");
  return *r.articulation;
}

// The articulation behind an articulated actor; rigid, link and soft actors are refused.
inline Articulation& articulated(SceneData& s, ActorHandle h, const char* what) {
  Articulation& a = whole(s, h, what);
  if (a.is_rigid) throw Error(std::string(what) + ": " + describe(h) + " is a rigid actor, not an articulated one");
  return a;
}

// The articulation and link index of a link actor, or link 0 of a rigid or articulated actor.
inline std::pair<Articulation*, int> link_of(SceneData& s, ActorHandle h, const char* what) {
  ActorRef r = lookup(s, h, what);
  refuse_soft(r, h, what);
  return {r.articulation, r.link < 0 ? 0 : r.link};
}

// The skin of an articulated actor that has one (ArticulatedActorParams::skin), else null.
inline const ArticulationSkin* skin_of(const ActorRef& r) {
  return !r.soft && r.link < 0 && r.articulation->skin ? r.articulation->skin.get() : nullptr;
}

// The soft body behind a soft actor; others are refused.
inline SoftBody& soft_of(SceneData& s, ActorHandle h, const char* what) {
  ActorRef r = lookup(s, h, what);
  if (!r.soft) throw Error(std::string(what) + ": " + describe(h) + " is not a soft actor");
  return *r.soft;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
