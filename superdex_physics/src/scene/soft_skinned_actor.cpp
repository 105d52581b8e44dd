// Soft-skinned actors (Scene::create_soft_skinned_actor): a skeleton articulation and soft bodies
// whose constrained nodes are tied to its links.

#include <algorithm>

#include "scene/actor_lookup.h"
#include "superdex/physics/params/constraint_params.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The index of the link named `name`, or an error naming the field.
int link_named(const Articulation& a, const std::string& name, const std::string& where) {
  const auto& names = a.model.link_names;
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw Error(where + ": no link named '" + name + "' in the skeleton");
  return static_cast<int>(it - names.begin());
}

// The link each constrained node of a soft shape ties to: `attach` for all when it is a link, else
// the link of the node's largest skinning weight.
std::vector<int> node_links(const ShapeData& shape, const std::vector<int>& nodes, int attach, int num_links, const std::string& where) {
  if (attach >= 0) return std::vector<int>(nodes.size(), attach);
  const std::optional<SkinningData>& skinning = shape.model->mesh->skinning;
  if (!skinning || skinning->weights_per_node <= 0)
    throw Error(where + ": no soft_attach_links name its link and its mesh has no skinning weights to choose one");
  std::vector<int> out;
  for (int n : nodes) {
    const int k = skinning->weights_per_node;
    const auto first = skinning->weights.begin() + n * k;
    const int best = skinning->indices[n * k + static_cast<int>(std::max_element(first, first + k) - first)];
    if (best < 0 || best >= num_links)
      throw Error(where + ": mesh.skinning: node " + std::to_string(n) + " is bound to link " + std::to_string(best) + ", out of range (" +
                  std::to_string(num_links) + " links)");
    out.push_back(best);
  }
  return out;
}

}  // namespace

ActorHandle Scene::create_soft_skinned_actor(const SoftSkinnedActorParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string where = "create_soft_skinned_actor('" + p.skeleton_params.name + "'): params";
  validate(p, where);
  // the soft bodies' shapes and constrained nodes are checked before anything is created
  std::vector<std::shared_ptr<const ShapeData>> shapes;
  for (size_t i = 0; i < p.soft_params.size(); ++i) {
    const std::string sw = where + ".soft_params[" + std::to_string(i) + "].shape";
    shapes.push_back(shape_data(p.soft_params[i].shape, sw));
    const auto& nodes = shapes.back()->model->constrained_nodes;
    if (!nodes || nodes->empty()) throw Error(sw + ": has no constrained nodes (constrainedNodes) to tie to the skeleton's links");
  }
  ArticulatedActorParams skeleton = p.skeleton_params;
  // without colliding links, the soft bodies are the actor's only surface
  if (!p.enable_colliding_links)
    for (ArticulatedLinkParams& l : skeleton.links) l.collider_type = ColliderType::None;
  const ActorHandle h = create_articulated_actor(skeleton);
  try {
    Articulation& a = *lookup(s, h, "create_soft_skinned_actor").articulation;
    const SpatialTransform X_WB = a.state.X_W_base;
    for (size_t i = 0; i < p.soft_params.size(); ++i) {
      const std::string sw = where + ".soft_params[" + std::to_string(i) + "]";
      SoftActorParams sp = p.soft_params[i];
      sp.has_gravity = sp.has_gravity || p.has_gravity;
      sp.has_inertia = sp.has_inertia || p.has_inertia;
      sp.has_stress = sp.has_stress || p.has_stress;
      // authored, like the skeleton, in the root joint's parent frame
      const Transform X_WB_t{Quat(X_WB.R).normalized(), X_WB.p};
      sp.world_from_local = X_WB_t * sp.world_from_local;
      const ActorHandle soft = create_soft_actor(sp);
      a.nested_softs.push_back(soft);
      SoftBody& body = *s.actors.at(soft).soft;
      body.skeleton = h;
      int attach = -1;
      if (!p.soft_attach_links.empty()) {
        const size_t k = p.soft_attach_links.size() == 1 ? 0 : i;
        attach = link_named(a, p.soft_attach_links[k], where + ".soft_attach_links[" + std::to_string(k) + "]");
      }
      const std::vector<int>& nodes = *shapes[i]->model->constrained_nodes;
      const std::vector<int> links = node_links(*shapes[i], nodes, attach, a.model.num_links, sw + ".shape");
      for (size_t j = 0; j < nodes.size(); ++j) {
        DeformableNodeToRigidConstraintParams tie;
        tie.rigid_actor = a.link_handles[links[j]];
        tie.deformable_actor = soft;
        tie.deformable_node_index = nodes[j];
        tie.fix_to_deformable_pos = true;
        const ConstraintHandle c = create_deformable_node_to_rigid_constraint(tie);
        s.constraints.at(c).owner = h;  // the actor's own: destroyed with it, not alone
      }
      // a soft body and the links it is tied to do not touch
      for (int link : std::set<int>(links.begin(), links.end()))
        enable_actor_contact_symmetric(soft, a.link_handles[link], false, IncludeNestedActors::No);
    }
  } catch (...) {
    destroy_actor(h);
    throw;
  }
  return h;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
