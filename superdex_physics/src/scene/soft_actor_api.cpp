// Soft actors: node displacements, positions and velocities in the actor frame, recentering,
// material, deformation gradients, surface nodes and boundary conditions.
//
// A soft body's nodes live in world coordinates (SoftState::x); its actor frame X_WL is where the
// mesh's rest nodes were placed, moved with the body's rigid motion by recentering. "Local" values
// are in that frame; displacements are local positions minus rest positions.

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "scene/actor_lookup.h"
#include "soft/fem_elasticity.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {


namespace {

void check_count(const char* what, const char* arg, size_t got, size_t expected) {
  if (got != expected)
    throw Error(std::string(what) + ": " + arg + " must hold " + std::to_string(expected) + " values (3 per node), got " + std::to_string(got));
}

void check_finite(const char* what, const char* arg, std::span<const real> v) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) throw Error(std::string(what) + ": " + arg + "[" + std::to_string(i) + "] is not finite");
}

void refuse_reduced(const SoftBody& b, const char* what) {
  if (b.reduced) throw Error(std::string(what) + ": soft actor '" + b.model.name + "' is a reduced model (its nodes follow its modes)");
}

Vec3 rest_node(const SoftBody& b, int i) { return b.model.mesh->nodes[i]; }

// After a rod's polyline nodes were set (x_before: the body's positions before): each ghost keeps
// its offset from its element's midpoint turned by the element's own turn (the smallest rotation
// of its old direction onto its new one), so that setting a bent shape bends the material frames
// with it and adds no twist; the ghost moves with the element's midpoint.
void place_rod_ghosts(SoftBody& b, const VecX& x_before) {
  if (!b.model.rod) return;
  const auto offset = [](const Vec3& a, const Vec3& c, const Vec3& g) {
    const Vec3 t = (c - a).normalized();
    const Vec3 u = g - (a + c) / 2;
    return std::pair<Vec3, Vec3>(t, u - t * u.dot(t));
  };
  for (const RodElement& e : b.model.rod->elements) {
    const Vec3 a = b.state.x.segment<3>(3 * e.nodes[0]), c = b.state.x.segment<3>(3 * e.nodes[1]);
    const Vec3 t = (c - a).normalized();
    auto [t0, u0] = offset(x_before.segment<3>(3 * e.nodes[0]), x_before.segment<3>(3 * e.nodes[1]), x_before.segment<3>(3 * e.nodes[2]));
    // an element turned end over end has no smallest rotation: its rest offset serves
    if (!(t0.dot(t) > real(-0.999)))
      std::tie(t0, u0) = offset(b.X_WL * rest_node(b, e.nodes[0]), b.X_WL * rest_node(b, e.nodes[1]), b.X_WL * rest_node(b, e.nodes[2]));
    Vec3 u = Quat::FromTwoVectors(t0, t) * u0;
    u -= t * u.dot(t);
    b.state.x.segment<3>(3 * e.nodes[2]) = (a + c) / 2 + e.ghost_distance * u.normalized();
    b.state.v.segment<3>(3 * e.nodes[2]) = (b.state.v.segment<3>(3 * e.nodes[0]) + b.state.v.segment<3>(3 * e.nodes[1])) / 2;
  }
}

// Node i's current position in the actor frame (X_LW: the inverse of the actor's root transform).
Vec3 node_local(const SoftBody& b, const Transform& X_LW, int i) { return X_LW * Vec3(b.state.x.segment<3>(3 * i)); }

// Re-applies the boundary conditions: the nodes pinned at creation, then the permanent entries,
// then the clearable ones (a later entry of a node wins).
void apply_boundary_conditions(SoftBody& b) {
  SoftModel& m = b.model;
  const std::vector<char> before = m.pinned;
  m.pinned = b.base_pinned;
  m.pin_target = b.base_pin_target;
  for (const auto* list : {&b.bc_permanent_dofs, &b.bc_dofs}) {
    const std::vector<real>& values = list == &b.bc_dofs ? b.bc_values : b.bc_permanent_values;
    for (size_t k = 0; k < list->size(); ++k) {
      const int d = (*list)[k];
      m.pinned[d / 3] = 1;
      m.pin_target[d] = values[k];
    }
  }
  if (m.pinned != before) b.pattern.reset();  // the free DOFs changed
}

}  // namespace

std::vector<real> Scene::displacements(ActorHandle h) const {
  const SoftBody& b = soft_of(scene_data(handle_), h, "get_displacements");
  const Transform X_LW = b.X_WL.inverse();
  const int n = b.user_nodes();
  std::vector<real> out(3 * n);
  for (int i = 0; i < n; ++i) {
    Eigen::Map<Vec3> d(out.data() + 3 * i);
    d = node_local(b, X_LW, i) - rest_node(b, i);
  }
  return out;
}

void Scene::set_displacements(ActorHandle h, std::span<const real> d) {
  const char* what = "set_displacements";
  SoftBody& b = soft_of(scene_data(handle_), h, what);
  refuse_reduced(b, what);
  check_count(what, "displacements", d.size(), 3 * b.user_nodes());
  check_finite(what, "displacements", d);
  const VecX x_before = b.state.x;
  for (size_t i = 0; 3 * i < d.size(); ++i)
    b.state.x.segment<3>(3 * i) = b.X_WL * Vec3(rest_node(b, static_cast<int>(i)) + Eigen::Map<const Vec3>(&d[3 * i]));
  place_rod_ghosts(b, x_before);
}

std::vector<real> Scene::node_positions_local(ActorHandle h) const {
  const SceneData& s = scene_data(handle_);
  const SoftBody& b = soft_of(const_cast<SceneData&>(s), h, "get_node_positions_local");
  require_query(s, h, QueryType::NodePositions, "get_node_positions_local");
  const Transform X_LW = b.X_WL.inverse();
  std::vector<real> out(3 * b.user_nodes());
  for (size_t i = 0; 3 * i < out.size(); ++i) {
    Eigen::Map<Vec3> p(out.data() + 3 * i);
    p = node_local(b, X_LW, static_cast<int>(i));
  }
  return out;
}

void Scene::set_node_positions_local(ActorHandle h, std::span<const real> p) {
  const char* what = "set_node_positions_local";
  SoftBody& b = soft_of(scene_data(handle_), h, what);
  refuse_reduced(b, what);
  check_count(what, "positions_local", p.size(), 3 * b.user_nodes());
  check_finite(what, "positions_local", p);
  const VecX x_before = b.state.x;
  for (size_t i = 0; 3 * i < p.size(); ++i) b.state.x.segment<3>(3 * i) = b.X_WL * Vec3(Eigen::Map<const Vec3>(&p[3 * i]));
  place_rod_ghosts(b, x_before);
}

void Scene::set_node_velocities_local(ActorHandle h, std::span<const real> v) {
  const char* what = "set_node_velocities_local";
  SoftBody& b = soft_of(scene_data(handle_), h, what);
  refuse_reduced(b, what);
  check_count(what, "velocities_local", v.size(), 3 * b.user_nodes());
  check_finite(what, "velocities_local", v);
  for (size_t i = 0; 3 * i < v.size(); ++i) b.state.v.segment<3>(3 * i) = b.X_WL.rotation * Vec3(Eigen::Map<const Vec3>(&v[3 * i]));
  place_rod_ghosts(b, b.state.x);
}

void Scene::set_zero_displacements_and_velocities(ActorHandle h) {
  const char* what = "set_zero_displacements_and_velocities";
  SoftBody& b = soft_of(scene_data(handle_), h, what);
  refuse_reduced(b, what);
  for (int i = 0; 3 * i < b.state.x.size(); ++i) b.state.x.segment<3>(3 * i) = b.X_WL * rest_node(b, i);
  b.state.v.setZero();
}

RecenteringParams Scene::recentering_params(ActorHandle h) const {
  const SceneData& s = scene_data(handle_);
  auto it = s.actors.find(h);
  if (it == s.actors.end()) throw Error("get_recentering_params: " + describe(h) + " does not exist in scene '" + s.name + "'");
  if (it->second.soft) return it->second.soft->recentering;
  RecenteringParams none;
  none.use_recentering = false;
  return none;
}

void Scene::set_recentering_params(ActorHandle h, const RecenteringParams& params) {
  SoftBody& b = soft_of(scene_data(handle_), h, "set_recentering_params");
  validate(params, "set_recentering_params: params");
  b.recentering = params;
}

SoftMaterialParams Scene::soft_material_params(ActorHandle h) const {
  return soft_of(scene_data(handle_), h, "get_soft_material_params").material_params;
}

namespace {

// The elastic material of params (validated by the caller).
ElasticMaterial elastic_material(const SoftMaterialParams& p, const std::string& where) {
  MaterialModel model = MaterialModel::NeoHookean;
  real E = p.neo_hookean.youngs_modulus, nu = p.neo_hookean.poisson_ratio;
  if (p.type == SoftMaterialType::StVenantKirchhoff) model = MaterialModel::StVK, E = p.st_venant_kirchhoff.youngs_modulus, nu = p.st_venant_kirchhoff.poisson_ratio;
  if (p.type == SoftMaterialType::LinearElastic) model = MaterialModel::Linear, E = p.linear_elastic.youngs_modulus, nu = p.linear_elastic.poisson_ratio;
  return ElasticMaterial::from_young_poisson(model, E, nu, where);
}

// Lumped node masses from each tetrahedron's density: a quarter of its mass to each node.
void lump_masses(SoftBody& b) {
  b.model.node_mass.setZero();
  for (size_t e = 0; e < b.model.tets.size(); ++e) {
    const real density = b.element_params.empty() ? b.material_params.density : b.element_params[e].density;
    for (int k = 0; k < 4; ++k) b.model.node_mass[b.model.tets[e][k]] += density * b.model.rest[e].volume / 4;
  }
  b.model.total_mass = b.model.node_mass.sum();
}

}  // namespace

void Scene::set_soft_material_params(ActorHandle h, const SoftMaterialParams& p) {
  const char* what = "set_soft_material_params";
  SoftBody& b = soft_of(scene_data(handle_), h, what);
  validate(p, std::string(what) + ": params");
  refuse_reduced(b, what);
  std::fill(b.model.material.begin(), b.model.material.end(), elastic_material(p, std::string(what) + ": params"));
  b.model.alpha = p.mass_damping_coefficient;
  b.model.beta = p.stiffness_damping_coefficient;
  const bool masses_change = p.density != b.material_params.density || !b.element_params.empty();
  b.material_params = p;
  b.element_params.clear();
  if (masses_change) lump_masses(b);
  b.step_storage = SoftStepStorage{};  // the Hessians kept from the last step belong to the old material
}

SoftMaterialParams Scene::soft_material_params_field(ActorHandle h, int element) const {
  const char* what = "get_soft_material_params_field";
  const SoftBody& b = soft_of(scene_data(handle_), h, what);
  if (element < 0 || element >= static_cast<int>(b.model.tets.size()))
    throw Error(std::string(what) + ": element_index " + std::to_string(element) + " is out of range (the actor has " +
                std::to_string(b.model.tets.size()) + " elements)");
  return b.element_params.empty() ? b.material_params : b.element_params[element];
}

void Scene::set_soft_material_params_field(ActorHandle h, const SoftMaterialParams& p, int element) {
  const char* what = "set_soft_material_params_field";
  SoftBody& b = soft_of(scene_data(handle_), h, what);
  if (element < 0 || element >= static_cast<int>(b.model.tets.size()))
    throw Error(std::string(what) + ": element_index " + std::to_string(element) + " is out of range (the actor has " +
                std::to_string(b.model.tets.size()) + " elements)");
  validate(p, std::string(what) + ": params");
  refuse_reduced(b, what);
  b.model.material[element] = elastic_material(p, std::string(what) + ": params");
  if (b.element_params.empty()) b.element_params.assign(b.model.tets.size(), b.material_params);
  const bool masses_change = p.density != b.element_params[element].density;
  b.element_params[element] = p;
  if (masses_change) lump_masses(b);
  b.step_storage = SoftStepStorage{};
}

std::vector<real> Scene::elements_deformation_gradient(ActorHandle h) const {
  const SceneData& s = scene_data(handle_);
  const SoftBody& b = soft_of(const_cast<SceneData&>(s), h, "get_elements_deformation_gradient");
  require_query(s, h, QueryType::ElementsDeformationGradient, "get_elements_deformation_gradient");
  const Transform X_LW = b.X_WL.inverse();
  std::vector<real> out;
  out.reserve(9 * b.model.tets.size());
  for (const auto& tet : b.model.tets) {
    // F = Ds Dm^-1 with both edge matrices in the actor frame
    Mat3 Ds, Dm;
    const Vec3 x0 = node_local(b, X_LW, tet[0]);
    for (int k = 0; k < 3; ++k) {
      Ds.col(k) = node_local(b, X_LW, tet[k + 1]) - x0;
      Dm.col(k) = rest_node(b, tet[k + 1]) - rest_node(b, tet[0]);
    }
    const Mat3 F = Ds * Dm.inverse();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out.push_back(F(r, c));
  }
  return out;
}

namespace {

// A skinned articulation's skin nodes (positions, or unit normals when `normals`) in the root
// joint's parent frame (its "local" frame), 3 per node.
std::vector<real> skin_nodes_local(const Articulation& a, bool normals) {
  VecX x;
  skin_positions_world(*a.skin, a.kin.X_WL, x);
  const SpatialTransform& X_WB = a.state.X_W_base;
  if (normals) {
    x = skin_normals(*a.skin, x);
    for (Eigen::Index i = 0; i < x.size(); i += 3) x.segment<3>(i) = X_WB.R.transpose() * x.segment<3>(i);
  } else {
    for (Eigen::Index i = 0; i < x.size(); i += 3) x.segment<3>(i) = X_WB.R.transpose() * (x.segment<3>(i) - X_WB.p);
  }
  return {x.data(), x.data() + x.size()};
}

}  // namespace

std::vector<real> Scene::surface_node_positions_local(ActorHandle h) const {
  const SceneData& s = scene_data(handle_);
  if (const ArticulationSkin* skin = skin_of(lookup(const_cast<SceneData&>(s), h, "get_surface_mesh_node_positions_local")); skin) {
    require_query(s, h, QueryType::SurfaceNodePositions, "get_surface_mesh_node_positions_local");
    return skin_nodes_local(*s.actors.at(h).articulation, false);
  }
  const SoftBody& b = soft_of(const_cast<SceneData&>(s), h, "get_surface_mesh_node_positions_local");
  require_query(s, h, QueryType::SurfaceNodePositions, "get_surface_mesh_node_positions_local");
  const Transform X_LW = b.X_WL.inverse();
  std::vector<real> out;
  out.reserve(3 * b.model.surface_nodes.size());
  for (int i : b.model.surface_nodes) {
    const Vec3 p = node_local(b, X_LW, i);
    out.insert(out.end(), {p.x(), p.y(), p.z()});
  }
  return out;
}

std::vector<std::pair<int, Real3>> Scene::nodes_in_volume_local(ActorHandle h, const std::variant<Aabb, Obb, Sphere>& volume,
                                                                bool boundary_only) const {
  const char* what = "query_nodes_in_volume_local";
  SceneData& s = scene_data(handle_);
  const auto inside = [&](const Real3& p) { return std::visit([&](const auto& v) { return v.contains(p); }, volume); };
  std::vector<std::pair<int, Real3>> out;
  ActorRef r = lookup(s, h, what);
  if (skin_of(r) && boundary_only) {
    // a skinned articulation's surface nodes: its skin's, in the root joint's parent frame
    require_query(s, h, QueryType::SurfaceNodePositions, what);
    const std::vector<real> x = skin_nodes_local(*r.articulation, false);
    for (size_t i = 0; 3 * i + 2 < x.size(); ++i)
      if (const Real3 p(x[3 * i], x[3 * i + 1], x[3 * i + 2]); inside(p)) out.emplace_back(static_cast<int>(i), p);
    return out;
  }
  if (!r.soft) {
    // a rigid body's nodes are its mesh shape's surface nodes, fixed in its frame
    const std::shared_ptr<const ShapeData> shape = actor_shape(r);
    if (!boundary_only || !shape || !shape->surface)
      throw Error(std::string(what) + ": " + describe(h) +
                  (boundary_only ? " has no mesh surface (primitive shapes and whole articulations have no nodes)"
                                 : " is not a soft actor: boundary_only=False needs a soft actor's nodes"));
    const std::vector<real>& c = shape->surface->coordinates;
    for (size_t i = 0; 3 * i + 2 < c.size(); ++i)
      if (const Real3 p(c[3 * i], c[3 * i + 1], c[3 * i + 2]); inside(p)) out.emplace_back(static_cast<int>(i), p);
    return out;
  }
  const SoftBody& b = *r.soft;
  require_query(s, h, boundary_only ? QueryType::SurfaceNodePositions : QueryType::NodePositions, what);
  const Transform X_LW = b.X_WL.inverse();
  auto visit = [&](int i) {
    if (const Real3 p = node_local(b, X_LW, i); inside(p)) out.emplace_back(i, p);
  };
  if (boundary_only)
    for (int i : b.model.surface_nodes) visit(i);
  else
    for (int i = 0; i < b.user_nodes(); ++i) visit(i);
  return out;
}

std::vector<real> Scene::surface_node_normals_local(ActorHandle h) const {
  const SceneData& s = scene_data(handle_);
  if (const ArticulationSkin* skin = skin_of(lookup(const_cast<SceneData&>(s), h, "get_surface_mesh_node_normals_local")); skin) {
    require_query(s, h, QueryType::SurfaceNodeNormals, "get_surface_mesh_node_normals_local");
    return skin_nodes_local(*s.actors.at(h).articulation, true);
  }
  const SoftBody& b = soft_of(const_cast<SceneData&>(s), h, "get_surface_mesh_node_normals_local");
  require_query(s, h, QueryType::SurfaceNodeNormals, "get_surface_mesh_node_normals_local");
  // area-weighted face normals summed at their nodes (the cross product's length is twice the area)
  std::map<int, Vec3> normal;
  for (const auto& f : b.model.surface_faces) {
    const Vec3 a = b.state.x.segment<3>(3 * f[0]), c1 = b.state.x.segment<3>(3 * f[1]), c2 = b.state.x.segment<3>(3 * f[2]);
    const Vec3 n = (c1 - a).cross(c2 - a);
    for (int i : f) normal[i] += n;
  }
  std::vector<real> out;
  out.reserve(3 * b.model.surface_nodes.size());
  for (int i : b.model.surface_nodes) {
    const Vec3 n = b.X_WL.rotation.inverse() * normal[i].normalized();
    out.insert(out.end(), {n.x(), n.y(), n.z()});
  }
  return out;
}

void Scene::add_boundary_condition_dofs_world(ActorHandle h, std::span<const int> dofs, std::span<const real> values, bool permanent) {
  const char* what = permanent ? "add_boundary_condition_dofs_world_permanent" : "add_boundary_condition_dofs_world";
  SoftBody& b = soft_of(scene_data(handle_), h, what);
  refuse_reduced(b, what);
  if (dofs.size() != values.size())
    throw Error(std::string(what) + ": dof_indices has " + std::to_string(dofs.size()) + " entries but dof_values_world has " +
                std::to_string(values.size()));
  const int n = 3 * b.user_nodes();
  std::map<int, int> per_node;  // a node's DOFs are set together
  for (size_t k = 0; k < dofs.size(); ++k) {
    if (dofs[k] < 0 || dofs[k] >= n)
      throw Error(std::string(what) + ": dof_indices[" + std::to_string(k) + "] = " + std::to_string(dofs[k]) + " is out of range (" +
                  std::to_string(n) + " DOFs)");
    if (!std::isfinite(values[k])) throw Error(std::string(what) + ": dof_values_world[" + std::to_string(k) + "] is not finite");
    per_node[dofs[k] / 3] |= 1 << (dofs[k] % 3);
  }
  for (const auto& [node, mask] : per_node)
    if (mask != 7)
      throw Error(std::string(what) + ": node " + std::to_string(node) + " has only some of its DOFs (" + std::to_string(3 * node) + ", " +
                  std::to_string(3 * node + 1) + ", " + std::to_string(3 * node + 2) + ") in dof_indices: a soft node's position is set whole");
  std::vector<int>& list = permanent ? b.bc_permanent_dofs : b.bc_dofs;
  std::vector<real>& vals = permanent ? b.bc_permanent_values : b.bc_values;
  list.insert(list.end(), dofs.begin(), dofs.end());
  vals.insert(vals.end(), values.begin(), values.end());
  apply_boundary_conditions(b);
}

void Scene::add_boundary_condition_nodes_world(ActorHandle h, std::span<const int> nodes, std::span<const real> positions, bool permanent) {
  const char* what = permanent ? "add_boundary_condition_nodes_world_permanent" : "add_boundary_condition_nodes_world";
  if (positions.size() != 3 * nodes.size())
    throw Error(std::string(what) + ": node_positions_world must hold 3 values per node (" + std::to_string(3 * nodes.size()) + "), got " +
                std::to_string(positions.size()));
  // checked here, so that errors name this call's arguments rather than the DOF form's
  const int num_nodes = soft_of(scene_data(handle_), h, what).user_nodes();
  std::vector<int> dofs;
  dofs.reserve(3 * nodes.size());
  for (size_t k = 0; k < nodes.size(); ++k) {
    if (nodes[k] < 0) throw Error(std::string(what) + ": node_indices[" + std::to_string(k) + "] = " + std::to_string(nodes[k]) + " is negative");
    if (nodes[k] >= num_nodes)
      throw Error(std::string(what) + ": node_indices[" + std::to_string(k) + "] = " + std::to_string(nodes[k]) + " is out of range (" +
                  std::to_string(num_nodes) + " nodes)");
    for (int c = 0; c < 3; ++c) dofs.push_back(3 * nodes[k] + c);
  }
  for (size_t k = 0; k < positions.size(); ++k)
    if (!std::isfinite(positions[k])) throw Error(std::string(what) + ": node_positions_world[" + std::to_string(k) + "] is not finite");
  add_boundary_condition_dofs_world(h, dofs, positions, permanent);
}

void Scene::clear_boundary_conditions(ActorHandle h) {
  SoftBody& b = soft_of(scene_data(handle_), h, "clear_boundary_conditions");
  b.bc_dofs.clear();
  b.bc_values.clear();
  apply_boundary_conditions(b);
}

std::vector<int> Scene::boundary_condition_dof_indices(ActorHandle h) const {
  const SoftBody& b = soft_of(scene_data(handle_), h, "get_boundary_condition_dof_indices");
  std::vector<int> out = b.bc_permanent_dofs;
  out.insert(out.end(), b.bc_dofs.begin(), b.bc_dofs.end());
  return out;
}

std::vector<real> Scene::boundary_condition_dof_values_world(ActorHandle h) const {
  const SoftBody& b = soft_of(scene_data(handle_), h, "get_boundary_condition_dof_values_world");
  std::vector<real> out = b.bc_permanent_values;
  out.insert(out.end(), b.bc_values.begin(), b.bc_values.end());
  return out;
}

void recenter_soft_body(SoftBody& b) {
  if (!b.recentering.use_recentering || b.reduced) return;
  const SoftModel& m = b.model;
  const int n = static_cast<int>(m.node_mass.size());
  // the best rigid fit of the rest nodes (frame L) to the current ones (world): centroids and the
  // rotation of the polar decomposition of their mass-weighted covariance
  Vec3 c = Vec3::Zero(), c0 = Vec3::Zero();
  for (int i = 0; i < n; ++i) c += m.node_mass[i] * b.state.x.segment<3>(3 * i), c0 += m.node_mass[i] * rest_node(b, i);
  c /= m.total_mass, c0 /= m.total_mass;
  Mat3 A = Mat3::Zero();
  for (int i = 0; i < n; ++i) A += m.node_mass[i] * (b.state.x.segment<3>(3 * i) - c) * (rest_node(b, i) - c0).transpose();
  const Mat3 R = polar_rotation(A);
  const Transform X_new{Quat(R).normalized(), c - R * c0};
  const real angle_deg = X_new.rotation.angularDistance(b.X_WL.rotation) * real(180) / real(M_PI);
  const real moved = (X_new.translation - b.X_WL.translation).norm();
  if (angle_deg > b.recentering.rotation_epsilon_deg || moved > b.recentering.translation_epsilon ||
      (b.recentering.rotation_epsilon_deg == 0 && b.recentering.translation_epsilon == 0))
    b.X_WL = X_new;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
