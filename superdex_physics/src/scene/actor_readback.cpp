// Creation parameters read back from live actors (scene.h "Creation parameters read back"): what
// would create each actor again as it is now. Prefab export (io/prefab_export.cpp) is built on
// these; they read the records an actor keeps of its creation (LinkRecord, SoftBody's params,
// the articulation's description) and replace what setters have changed since.

#include <algorithm>

#include "scene/actor_lookup.h"
#include "soft/reduced_soft.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

Real6 inertia_entries(const Mat3& I) { return (Real6() << I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)).finished(); }

// The index of a layer name among the scene's layers (0, the default "", when unknown).
int layer_index_of(const SceneData& s, const std::string& name) {
  for (size_t i = 0; i < s.layer_names.size(); ++i)
    if (s.layer_names[i] == name) return static_cast<int>(i);
  return 0;
}

// The base placement X_WR that puts the root link where it is now with the root joint at its zero
// position. While the base and the root joint have not moved since creation, the description's
// own transform (the quaternion as given, bit for bit).
Transform root_placement(const Articulation& a) {
  const JointModel& root = a.model.joints[0];
  Transform given = a.model.desc.world_from_root;
  given.rotation.normalize();
  const SpatialTransform X_given = SpatialTransform::from(given);
  const bool base_unmoved = X_given.R == a.state.X_W_base.R && X_given.p == a.state.X_W_base.p;
  if (root.type != JointType::Free && base_unmoved) return given;
  if (root.type == JointType::Free && base_unmoved) {
    const auto q = a.state.q.segment<7>(root.q_offset);
    if (q.head<6>().isZero(0) && q[6] == 1) return given;
  }
  // X_WR = X_WL0 (X_PJ0 T(p_JL0))^-1
  const SpatialTransform X_RL0 = root.X_PJ * SpatialTransform{Mat3::Identity(), root.p_JL};
  const SpatialTransform X_WR = a.kin.X_WL[0] * X_RL0.inverse();
  return Transform{Quat(X_WR.R).normalized(), X_WR.p};
}

}  // namespace

std::vector<ActorContactRule> Scene::actor_contact_rules() const {
  const SceneData& s = scene_data(handle_);
  std::vector<ActorContactRule> out;
  for (const auto& [pair, rule] : s.actor_contact) {
    if (!s.actors.count(pair.first) || !s.actors.count(pair.second)) continue;
    out.push_back({pair.first, pair.second, rule.enabled, rule.nested ? IncludeNestedActors::Yes : IncludeNestedActors::No});
  }
  return out;
}

bool Scene::has_gravity(ActorHandle h) const {
  ActorRef r = lookup(scene_data(handle_), h, "has_gravity");
  if (r.soft) return r.soft->has_gravity;
  const ArticulationModel& m = r.articulation->model;
  if (r.link >= 0) return m.has_gravity[r.link] != 0;
  return std::any_of(m.has_gravity.begin(), m.has_gravity.end(), [](char g) { return g != 0; });
}

RigidActorParams Scene::rigid_actor_params(ActorHandle h) const {
  const char* what = "rigid_actor_params";
  SceneData& s = scene_data(handle_);
  ActorRef r = lookup(s, h, what);
  refuse_soft(r, h, what);
  if (!r.articulation->is_rigid)
    throw Error(std::string(what) + ": " + describe(h) + (r.link >= 0 ? " is a link actor: read its articulation (articulation_desc)"
                                                                       : " is an articulated actor (articulation_desc)"));
  const Articulation& a = *r.articulation;
  const LinkRecord& rec = a.links[0];
  RigidActorParams p;
  p.name = a.model.name;
  p.layer = rec.layer;
  if (rec.shape) p.shape = add_shape_reference_to(rec.shape);
  p.world_from_local = root_transform(h);
  p.collider_type = rec.collider_type;
  p.is_static = a.is_static;
  p.contact = rec.contact;
  p.has_gravity = a.model.has_gravity[0] != 0;
  if (!a.is_static) {
    const SpatialInertia& I = a.model.inertia[0];
    p.mass = I.mass;
    p.center_of_mass = I.com;
    p.moment_of_inertia = rec.declared_inertia ? *rec.declared_inertia : inertia_entries(I.inertia_com);
    if (rec.density > 0) p.density = rec.density;
    const Vec6 V = velocity(h);
    if (!V.head<3>().isZero(0)) p.linear_velocity = Real3(V.head<3>());
    if (!V.tail<3>().isZero(0)) p.angular_velocity = Real3(V.tail<3>());
  }
  return p;
}

SoftActorParams Scene::soft_actor_params(ActorHandle h) const {
  const SoftBody& b = soft_of(scene_data(handle_), h, "soft_actor_params");
  if (!b.model.material.empty() && b.model.material.front().model == MaterialModel::Corotated)
    throw Error("soft_actor_params: " + describe(h) + " ('" + b.model.name +
                "') has a Corotated material, which SoftMaterialParams cannot express (NeoHookean, StVenantKirchhoff or LinearElastic)");
  SoftActorParams p;
  p.name = b.model.name;
  p.layer = b.layer;
  p.world_from_local = b.X_WL;
  if (b.shape) p.shape = add_shape_reference_to(b.shape);
  p.material = b.material_params;
  p.contact = b.contact_params;
  p.has_gravity = b.has_gravity;
  return p;
}

std::vector<int> Scene::soft_fixed_nodes(ActorHandle h) const {
  const SoftBody& b = soft_of(scene_data(handle_), h, "soft_fixed_nodes");
  std::vector<int> out;
  for (size_t i = 0; i < b.base_pinned.size(); ++i)
    if (b.base_pinned[i]) out.push_back(static_cast<int>(i));
  return out;
}

int Scene::soft_reduced_modes(ActorHandle h) const {
  const SoftBody& b = soft_of(scene_data(handle_), h, "soft_reduced_modes");
  return b.reduced ? b.reduced->num_modes() : 0;
}

ArticulationDesc Scene::articulation_desc(ActorHandle h) const {
  const char* what = "articulation_desc";
  SceneData& s = scene_data(handle_);
  const Articulation& a = articulated(s, h, what);
  ArticulationDesc d = a.model.desc;
  d.world_from_root = root_placement(a);
  for (int i = 0; i < a.model.num_links; ++i) {
    LinkDesc& l = d.links[i];
    const LinkRecord& rec = a.links[i];
    // links made from params: the shape as given, where the description holds the same collider
    // (a Box or Sphere collider made from another shape stays the box or sphere in use)
    const bool fitted = rec.collider_type == ColliderType::Box || rec.collider_type == ColliderType::Sphere;
    if (rec.shape && rec.shape->geometry && !(fitted && l.shape)) {
      l.shape = *rec.shape->geometry;
      l.shape_scale = Vec3::Ones();
      l.link_from_shape = Transform{};
      l.collider_type = collider_type_name(rec.collider_type);
    }
    const SpatialInertia& I = a.model.inertia[i];
    l.mass = I.mass;
    l.center_of_mass = I.com;
    const Real6 c = rec.declared_inertia ? *rec.declared_inertia : inertia_entries(I.inertia_com);
    l.moment_of_inertia = std::array<real, 6>{c[0], c[1], c[2], c[3], c[4], c[5]};
    if (rec.density > 0) l.density = rec.density;
    l.contact = rec.contact;
    l.layer = layer_index_of(s, rec.layer);
    l.has_gravity = a.model.has_gravity[i] != 0;
    JointDesc& j = d.joints[i];
    const JointModel& jm = a.model.joints[i];
    j.coulomb_friction = jm.coulomb;
    j.viscous_friction = jm.viscous;
    j.armature = jm.armature;
  }
  return d;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
