#pragma once
// A skin of an articulation (ArticulatedSkinParams): a triangle surface whose nodes follow the
// links by linear-blend skinning, x_W = sum_k w_k X_WL_k p_L_k, with p_L_k the node's rest
// position in link k's frame. Its nodes probe other actors' colliders (skin_contact.h).

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "multibody/articulation_model.h"
#include "superdex/physics/model.h"
#include "superdex/physics/params/actor_params.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ShapeData;

// One link moving a skin node: its weight and the node's rest position in the link frame (m).
struct SkinInfluence {
  int link = 0;
  real weight = 0;
  Vec3 p_L = Vec3::Zero();
};

struct ArticulationSkin {
  ArticulatedSkinParams params;               // as given, without the shape handle (`shape` holds its data)
  std::shared_ptr<const ShapeData> shape;
  std::shared_ptr<const MeshData> mesh;       // the skin's triangles, node order of the skinning
  std::vector<std::array<int, 3>> faces;
  std::vector<int> first;                     // node i's influences: [first[i], first[i + 1])
  std::vector<SkinInfluence> influences;
  std::vector<int> main_link;                 // per node: the link of its largest weight
  ContactMaterial material;
  int layer_index = 0;                        // SceneData::layer_names
  ActorHandle display;                        // the id the debugger draws it under

  int num_nodes() const { return static_cast<int>(main_link.size()); }
};

// The skin of `params` for an articulation `model`: the shape must be a triangle mesh with
// skinning data over link indices; X_BL_rest are the links' rest poses in the root joint's parent
// frame (every joint at zero). Errors name `where` (e.g. "...params.skin.shape").
std::shared_ptr<ArticulationSkin> build_articulation_skin(const ArticulatedSkinParams& params, std::shared_ptr<const ShapeData> shape,
                                                          const ArticulationModel& model, const std::vector<SpatialTransform>& X_BL_rest,
                                                          const std::string& where);

// The world position of node `i` with the links at X_WL.
Vec3 skin_node_world(const ArticulationSkin& skin, const std::vector<SpatialTransform>& X_WL, int i);
// Every node's world position (3 per node) into `x_W`.
void skin_positions_world(const ArticulationSkin& skin, const std::vector<SpatialTransform>& X_WL, VecX& x_W);
// Unit node normals at world positions x_W (area-weighted face normals), 3 per node.
VecX skin_normals(const ArticulationSkin& skin, const VecX& x_W);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
