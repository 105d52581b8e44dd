// Linear-blend skins of articulations (articulation_skin.h).

#include "multibody/articulation_skin.h"

#include "shape/shape_data.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::shared_ptr<ArticulationSkin> build_articulation_skin(const ArticulatedSkinParams& params, std::shared_ptr<const ShapeData> shape,
                                                          const ArticulationModel& model, const std::vector<SpatialTransform>& X_BL_rest,
                                                          const std::string& where) {
  const std::optional<MeshData>& mesh = shape->model->mesh;
  if (!mesh || mesh->nodes_per_element != 3 || mesh->num_elements() == 0)
    throw Error(where + ": a skin must be a triangle mesh (its nodes bound to the links by skinning weights)");
  if (!mesh->skinning || mesh->skinning->weights_per_node <= 0)
    throw Error(where + ": the mesh has no skinning data (mesh.skinning: per node, weights over link indices); a plain triangle mesh cannot be a skin");
  auto skin = std::make_shared<ArticulationSkin>();
  skin->params = params;
  // the skin keeps its shape's data, not a handle: a handle counts in the engine's registry, which
  // a scene's destruction at shutdown must not touch
  skin->params.shape = ShapeHandle();
  skin->mesh = std::make_shared<const MeshData>(*mesh);
  skin->shape = std::move(shape);
  skin->material = contact_material(params.contact);
  const int n = mesh->num_nodes(), k = mesh->skinning->weights_per_node;
  for (int e = 0; e < mesh->num_elements(); ++e)
    skin->faces.push_back({mesh->connectivity[3 * e], mesh->connectivity[3 * e + 1], mesh->connectivity[3 * e + 2]});
  skin->first.push_back(0);
  for (int i = 0; i < n; ++i) {
    const Vec3 p_B(mesh->coordinates[3 * i], mesh->coordinates[3 * i + 1], mesh->coordinates[3 * i + 2]);
    int best = -1;
    real best_weight = 0;
    for (int j = 0; j < k; ++j) {
      const int link = mesh->skinning->indices[i * k + j];
      const real w = mesh->skinning->weights[i * k + j];
      if (w == 0) continue;
      if (link < 0 || link >= model.num_links)
        throw Error(where + ": mesh.skinning.indices[" + std::to_string(i * k + j) + "]: link " + std::to_string(link) +
                    " out of range (the articulation has " + std::to_string(model.num_links) + " links)");
      skin->influences.push_back({link, w, X_BL_rest[link].R.transpose() * (p_B - X_BL_rest[link].p)});
      if (w > best_weight) best = link, best_weight = w;
    }
    if (best < 0) throw Error(where + ": mesh.skinning: node " + std::to_string(i) + " has no positive weight");
    skin->main_link.push_back(best);
    skin->first.push_back(static_cast<int>(skin->influences.size()));
  }
  return skin;
}

Vec3 skin_node_world(const ArticulationSkin& skin, const std::vector<SpatialTransform>& X_WL, int i) {
  Vec3 x = Vec3::Zero();
  for (int j = skin.first[i]; j < skin.first[i + 1]; ++j) {
    const SkinInfluence& f = skin.influences[j];
    x += f.weight * (X_WL[f.link].R * f.p_L + X_WL[f.link].p);
  }
  return x;
}

void skin_positions_world(const ArticulationSkin& skin, const std::vector<SpatialTransform>& X_WL, VecX& x_W) {
  x_W.resize(3 * skin.num_nodes());
  for (int i = 0; i < skin.num_nodes(); ++i) x_W.segment<3>(3 * i) = skin_node_world(skin, X_WL, i);
}

VecX skin_normals(const ArticulationSkin& skin, const VecX& x_W) {
  VecX n = VecX::Zero(x_W.size());
  // the cross product's length is twice the face's area: area-weighted sums
  for (const auto& f : skin.faces) {
    const Vec3 a = x_W.segment<3>(3 * f[0]);
    const Vec3 face = (x_W.segment<3>(3 * f[1]) - a).cross(x_W.segment<3>(3 * f[2]) - a);
    for (int i : f) n.segment<3>(3 * i) += face;
  }
  for (Eigen::Index i = 0; i < n.size(); i += 3) {
    const real len = n.segment<3>(i).norm();
    if (len > 0) n.segment<3>(i) /= len;
  }
  return n;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
