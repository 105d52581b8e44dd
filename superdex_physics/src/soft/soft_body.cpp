// Soft bodies: building from a tet mesh, and the implicit Newton step (soft_body.h).

#include "soft/soft_body.h"
#include "shape/tet_mesh_surface.h"

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <map>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <type_traits>

#include "soft/reduced_soft.h"
#include "scene/scene_data.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Positions of the four nodes of tetrahedron t.
void gather(const std::array<int, 4>& tet, const VecX& x, Vec3* out) {
  for (int k = 0; k < 4; ++k) out[k] = x.segment<3>(3 * tet[k]);
}

// Per-tetrahedron fixed rotations: the polar rotation at x0 for the corotated model.
std::vector<Mat3> rotations(const SoftBody& b, const VecX& x0) {
  std::vector<Mat3> R(b.model.tets.size(), Mat3::Identity());
  for (size_t t = 0; t < b.model.tets.size(); ++t) {
    if (b.model.material[t].model != MaterialModel::Corotated) continue;
    Vec3 xs[4];
    gather(b.model.tets[t], x0, xs);
    R[t] = polar_rotation(deformation_gradient(b.model.rest[t], xs));
  }
  return R;
}

// Computes element(t, out) for every tetrahedron and hands each result to scatter(t, out) in
// tetrahedron order, so that sums come out the same either way: on the engine's worker threads
// into `buffer` (one T per tetrahedron, kept by the caller across calls) when it has any, else
// one tetrahedron at a time, without the buffer unless `keep` asks for every result in it.
template <class T, class Element, class Scatter>
void for_each_tet(size_t count, std::vector<T>& buffer, Element&& element, Scatter&& scatter, bool keep = false) {
  EngineData& e = engine_data();
  const bool parallel = e.arena && count > 512;
  if (parallel || keep) {
    buffer.resize(count);
    if (parallel) {
      e.arena->execute([&] {
        oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<size_t>(0, count, 256), [&](const oneapi::tbb::blocked_range<size_t>& r) {
          for (size_t t = r.begin(); t < r.end(); ++t) element(t, buffer[t]);
        });
      });
    } else {
      for (size_t t = 0; t < count; ++t) element(t, buffer[t]);
    }
    for (size_t t = 0; t < count; ++t) scatter(t, buffer[t]);
  } else {
    T local;
    for (size_t t = 0; t < count; ++t) {
      element(t, local);
      scatter(t, local);
    }
  }
}

// Elastic energy at positions x (J).
real elastic_energy(const SoftBody& b, const VecX& x, const std::vector<Mat3>& R) {
  std::vector<real> buffer;
  real total = 0;
  for_each_tet(
      b.model.tets.size(), buffer,
      [&](size_t t, real& energy) {
        Vec3 xs[4];
        gather(b.model.tets[t], x, xs);
        energy = tet_energy(b.model.material[t], b.model.rest[t], xs, R[t], nullptr, nullptr, false);
      },
      [&](size_t, const real& energy) { total += energy; });
  if (b.model.rod) total += rod_energy(*b.model.rod, x);
  return total;
}

// Gradient of the elastic energy at positions x (N), into grad (3N).
void elastic_gradient(const SoftBody& b, const VecX& x, const std::vector<Mat3>& R, std::vector<Vec12>& buffer, VecX& grad) {
  grad.setZero(x.size());
  for_each_tet(
      b.model.tets.size(), buffer,
      [&](size_t t, Vec12& g) {
        Vec3 xs[4];
        gather(b.model.tets[t], x, xs);
        tet_derivatives(b.model.material[t], b.model.rest[t], xs, R[t], &g, nullptr, false);
      },
      [&](size_t t, const Vec12& g) {
        for (int i = 0; i < 4; ++i) grad.segment<3>(3 * b.model.tets[t][i]) += g.segment<3>(3 * i);
      });
  if (!b.model.rod) return;
  const RodModel& rod = *b.model.rod;
  Vec9 g9;
  for (int e = 0; e < static_cast<int>(rod.elements.size()); ++e) {
    rod_element_terms(rod, e, x, &g9, nullptr);
    for (int i = 0; i < 3; ++i) grad.segment<3>(3 * rod.elements[e].nodes[i]) += g9.segment<3>(3 * i);
  }
  Vec18 g18;
  for (int j = 0; j < static_cast<int>(rod.joints.size()); ++j) {
    rod_joint_terms(rod, j, x, &g18, nullptr);
    const std::array<int, 6> nodes = rod_joint_nodes(rod, j);
    for (int i = 0; i < 6; ++i) grad.segment<3>(3 * nodes[i]) += g18.segment<3>(3 * i);
  }
}

}  // namespace

std::unique_ptr<SoftBody> build_soft_body(const std::string& name, std::shared_ptr<const TetMesh> mesh,
                                          const SoftMaterial& material, const Transform& X_WL,
                                          const std::vector<int>& fixed_nodes, const std::string& where) {
  auto body = std::make_unique<SoftBody>();
  SoftModel& m = body->model;
  m.name = name;
  m.mesh = mesh;
  m.tets = mesh->tets;
  const int n = static_cast<int>(mesh->nodes.size());
  if (!std::isfinite(material.density) || material.density <= 0) throw Error(where + ": material.density must be positive");
  if (!(material.damping_alpha >= 0) || !(material.damping_beta >= 0))
    throw Error(where + ": material damping must be >= 0");
  m.alpha = material.damping_alpha;
  m.beta = material.damping_beta;
  const MaterialModel model = material_model_from_name(material.type, where + ": material.type");
  // per-element parameters: the caller's, else the mesh file's, else the defaults
  auto parameter = [&](const std::optional<real>& given, const std::vector<real>& per_element, real fallback, size_t t) {
    if (given) return *given;
    if (per_element.empty()) return fallback;
    return per_element.size() == 1 ? per_element[0] : per_element[t];
  };
  for (const auto* values : {&mesh->youngs_modulus, &mesh->poisson_ratio})
    if (values->size() > 1 && values->size() != mesh->tets.size())
      throw Error(where + ": the mesh has " + std::to_string(values->size()) + " per-element material values for " +
                  std::to_string(mesh->tets.size()) + " tetrahedra");
  // world rest positions, rest data and lumped masses
  body->state.x.resize(3 * n);
  for (int i = 0; i < n; ++i) body->state.x.segment<3>(3 * i) = X_WL * mesh->nodes[i];
  body->state.v = VecX::Zero(3 * n);
  body->state.tau_external = VecX::Zero(3 * n);
  m.node_mass = VecX::Zero(n);
  for (size_t t = 0; t < m.tets.size(); ++t) {
    Vec3 xs[4];
    gather(m.tets[t], body->state.x, xs);
    m.rest.push_back(make_tet_rest(xs[0], xs[1], xs[2], xs[3], 0, where + ": tetrahedron " + std::to_string(t)));
    m.material.push_back(ElasticMaterial::from_young_poisson(
        model, parameter(material.youngs_modulus, mesh->youngs_modulus, real(1e5), t),
        parameter(material.poisson_ratio, mesh->poisson_ratio, real(0.3), t),
        mesh->youngs_modulus.size() > 1 && !material.youngs_modulus ? where + ": tetrahedron " + std::to_string(t) + " material"
                                                                     : where + ": material"));
    for (int k = 0; k < 4; ++k) m.node_mass[m.tets[t][k]] += material.density * m.rest.back().volume / 4;
  }
  for (int i = 0; i < n; ++i)
    if (m.node_mass[i] <= 0) throw Error(where + ": node " + std::to_string(i) + " belongs to no tetrahedron");
  m.total_mass = m.node_mass.sum();
  // surface: faces that belong to one tetrahedron only
  const std::vector<std::array<int, 3>> boundary = tet_boundary_faces(m.tets);
  std::vector<char> on_surface(n, 0);
  for (const auto& face : boundary) {
    m.surface_faces.push_back(face);
    for (int i : face) on_surface[i] = 1;
  }
  for (int i = 0; i < n; ++i)
    if (on_surface[i]) m.surface_nodes.push_back(i);
  m.pinned.assign(n, 0);
  m.pin_target = body->state.x;
  for (size_t k = 0; k < fixed_nodes.size(); ++k) {
    if (fixed_nodes[k] < 0 || fixed_nodes[k] >= n)
      throw Error(where + ": fixed_nodes[" + std::to_string(k) + "] = " + std::to_string(fixed_nodes[k]) + " is out of range (" +
                  std::to_string(n) + " nodes)");
    m.pinned[fixed_nodes[k]] = 1;
  }
  if (material.reduced_modes > 0) {
    body->reduced = build_reduced_model(m, body->state.x, material.reduced_modes, where);
    body->state.q = body->state.qd = VecX::Zero(material.reduced_modes);
    body->state.u_c = VecX::Zero(3 * n);
  }
  return body;
}

real soft_elastic_energy(const SoftBody& b, const VecX& x) { return elastic_energy(b, x, rotations(b, b.state.x)); }

int SoftPattern::slot(int row, int col) const {
  const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[col];
  const int* end = H.innerIndexPtr() + H.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  return it != end && *it == row ? static_cast<int>(it - H.innerIndexPtr()) : -1;
}

namespace {

// The pattern of every coupling between free DOFs through a tetrahedron, its value slots per
// tetrahedron, and the symbolic factorization.
std::unique_ptr<SoftPattern> build_pattern(const SoftModel& m) {
  auto p = std::make_unique<SoftPattern>();
  const int n = 3 * static_cast<int>(m.pinned.size());
  p->free_of_dof.assign(n, -1);
  for (int d = 0; d < n; ++d)
    if (!m.pinned[d / 3]) p->free_of_dof[d] = p->num_free++, p->dof_of_free.push_back(d);
  std::vector<Eigen::Triplet<real>> entries;
  for (int f = 0; f < p->num_free; ++f) entries.emplace_back(f, f, real(1));
  // a rod's stencils: each element's three nodes, each joint's six
  std::vector<std::vector<int>> stencils;
  if (m.rod) {
    for (const RodElement& e : m.rod->elements) stencils.push_back({e.nodes.begin(), e.nodes.end()});
    for (int j = 0; j < static_cast<int>(m.rod->joints.size()); ++j) {
      const std::array<int, 6> nodes = rod_joint_nodes(*m.rod, j);
      stencils.push_back({nodes.begin(), nodes.end()});
    }
  }
  for (const std::vector<int>& nodes : stencils)
    for (int i : nodes)
      for (int j : nodes)
        for (int a = 0; a < 3; ++a)
          for (int c = 0; c < 3; ++c) {
            const int r = p->free_of_dof[3 * i + a], col = p->free_of_dof[3 * j + c];
            if (r >= 0 && col >= 0) entries.emplace_back(r, col, real(1));
          }
  for (const auto& tet : m.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int a = 0; a < 3; ++a)
          for (int c = 0; c < 3; ++c) {
            const int r = p->free_of_dof[3 * tet[i] + a], col = p->free_of_dof[3 * tet[j] + c];
            if (r >= 0 && col >= 0) entries.emplace_back(r, col, real(1));
          }
  p->H.resize(p->num_free, p->num_free);
  p->H.setFromTriplets(entries.begin(), entries.end());
  p->H.makeCompressed();
  p->tet_slots.assign(144 * m.tets.size(), -1);
  for (size_t t = 0; t < m.tets.size(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int a = 0; a < 3; ++a)
          for (int c = 0; c < 3; ++c) {
            const int r = p->free_of_dof[3 * m.tets[t][i] + a], col = p->free_of_dof[3 * m.tets[t][j] + c];
            if (r >= 0 && col >= 0) p->tet_slots[144 * t + 12 * (3 * i + a) + 3 * j + c] = p->slot(r, col);
          }
  for (const std::vector<int>& nodes : stencils) {
    const int n = 3 * static_cast<int>(nodes.size());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int r = p->free_of_dof[3 * nodes[i / 3] + i % 3], col = p->free_of_dof[3 * nodes[j / 3] + j % 3];
        p->rod_slots.push_back(r >= 0 && col >= 0 ? p->slot(r, col) : -1);
      }
  }
  std::fill(p->H.valuePtr(), p->H.valuePtr() + p->H.nonZeros(), real(0));
  p->cholesky.analyze(p->H);
  return p;
}

// Adds scale * H, the Hessian of tetrahedron t, into the values of a matrix with the pattern's
// structure (pinned DOFs left out).
void scatter_hessian(const SoftPattern& p, size_t t, real scale, const Mat12& H, real* values) {
  const int* slots = p.tet_slots.data() + 144 * t;
  for (int k = 0; k < 144; ++k)
    if (slots[k] >= 0) values[slots[k]] += scale * H(k / 12, k % 12);
}

// Adds scale * the Hessian of a rod at positions x into the values of a matrix with the pattern's
// structure.
void add_rod_hessian(const RodModel& rod, const SoftPattern& p, const VecX& x, real scale, real* values) {
  const int* slots = p.rod_slots.data();
  Mat9 H9;
  for (int e = 0; e < static_cast<int>(rod.elements.size()); ++e, slots += 81) {
    rod_element_terms(rod, e, x, nullptr, &H9);
    for (int k = 0; k < 81; ++k)
      if (slots[k] >= 0) values[slots[k]] += scale * H9(k / 9, k % 9);
  }
  Mat18 H18;
  for (int j = 0; j < static_cast<int>(rod.joints.size()); ++j, slots += 324) {
    rod_joint_terms(rod, j, x, nullptr, &H18);
    for (int k = 0; k < 324; ++k)
      if (slots[k] >= 0) values[slots[k]] += scale * H18(k / 18, k % 18);
  }
}

}  // namespace

SoftStep::SoftStep(SoftBody& b, const Vec3& g_W, real dt_, real reuse_strain)
    : body(b),
      pattern(*(b.pattern ? b.pattern : (b.pattern = build_pattern(b.model))).get()),
      dt(dt_),
      x0(b.state.x),
      reuse_strain_(reuse_strain),
      storage_(b.step_storage),
      factorizations_at_start_(pattern.cholesky.factorizations()) {
  const SoftModel& m = b.model;
  const int nf = pattern.num_free;
  R_ = rotations(b, x0);
  v_pinned = VecX::Zero(x0.size());
  for (int d = 0; d < x0.size(); ++d)
    if (pattern.free_of_dof[d] < 0) v_pinned[d] = (m.pin_target[d] - x0[d]) / dt;
  v0.resize(nf);
  mass.resize(nf);
  r.resize(nf);
  if (m.rod) {
    rod_K0_.assign(pattern.H.nonZeros(), real(0));
    add_rod_hessian(*m.rod, pattern, x0, dt * dt, rod_K0_.data());
  }
  // a rod's spin inertia: its momentum at the start, and its coupling to the pinned DOFs' motion
  VecX spin_start, spin_pinned;
  if (m.rod) spin_start = rod_spin_momentum(*m.rod, b.state.v), spin_pinned = rod_spin_momentum(*m.rod, v_pinned);
  for (int f = 0; f < nf; ++f) {
    const int d = pattern.dof_of_free[f];
    v0[f] = b.state.v[d];
    mass[f] = m.node_mass[d / 3];
    r[f] = mass[f] * v0[f] + dt * (mass[f] * g_W[d % 3] + b.state.tau_external[d]);
    if (m.rod) r[f] += spin_start[d] - (1 + dt * m.alpha) * spin_pinned[d];
    // in single precision the Newton matrix's diagonal at a ghost is raised by 1e-5 of its
    // stiffness: rounded to float, that stiffness (many times the ghost's inertia over dt^2)
    // would otherwise leave the matrix indefinite. Only the Newton direction changes, not the
    // problem it solves (its gradient keeps the true inertia).
    if constexpr (std::is_same_v<real, float>)
      if (m.rod && d / 3 >= m.rod->num_nodes) newton_shift_.emplace_back(pattern.slot(f, f), real(1e-5) * rod_K0_[pattern.slot(f, f)]);
  }
  // A = M + dt (alpha M + beta K(x0)), with K(x0) kept for the first Newton iteration, and the
  // element Hessians at x0 with their deformation gradients for the iterations that reuse them
  K0_.assign(pattern.H.nonZeros(), real(0));
  std::vector<Mat3>& F0 = storage_.F0;
  F0.resize(m.tets.size());
  for_each_tet(
      m.tets.size(), storage_.H0,
      [&](size_t t, Mat12& H) {
        Vec3 xs[4];
        gather(m.tets[t], x0, xs);
        F0[t] = deformation_gradient(m.rest[t], xs);
        tet_derivatives_at(m.material[t], m.rest[t], F0[t], R_[t], nullptr, &H, true);
      },
      [&](size_t t, const Mat12& H) { scatter_hessian(pattern, t, dt * dt, H, K0_.data()); }, true);
  element_hessians_ = static_cast<int>(m.tets.size());
  A = pattern.H;
  if (m.beta > 0) {
    Eigen::Map<VecX>(A.valuePtr(), A.nonZeros()) = (m.beta / dt) * Eigen::Map<const VecX>(K0_.data(), A.nonZeros());
    if (m.rod) Eigen::Map<VecX>(A.valuePtr(), A.nonZeros()) += (m.beta / dt) * Eigen::Map<const VecX>(rod_K0_.data(), A.nonZeros());
  }
  for (int f = 0; f < nf; ++f) A.valuePtr()[pattern.slot(f, f)] += (1 + dt * m.alpha) * mass[f];
  if (m.rod) {
    // the spin inertia's mu c c^T blocks; their diagonal also joins the lumped mass per DOF
    const int* slots = pattern.rod_slots.data();
    for (const RodElement& e : m.rod->elements) {
      for (int k = 0; k < 81; ++k) {
        const int i = k / 9, j = k % 9;
        if (i % 3 != j % 3 || slots[k] < 0) continue;
        const real value = e.spin_mass * real(kRodSpinWeights[i / 3] * kRodSpinWeights[j / 3]);
        A.valuePtr()[slots[k]] += (1 + dt * m.alpha) * value;
        if (i == j) mass[pattern.free_of_dof[3 * e.nodes[i / 3] + i % 3]] += value;
      }
      slots += 81;
    }
  }
}

void SoftStep::start_hessian(Eigen::SparseMatrix<real>& K) const {
  std::copy(K0_.begin(), K0_.end(), K.valuePtr());
  for (size_t k = 0; k < rod_K0_.size(); ++k) K.valuePtr()[k] += rod_K0_[k];
  for (const auto& [slot, shift] : newton_shift_) K.valuePtr()[slot] += shift;
}

VecX SoftStep::full_velocity(const VecX& v_free) const {
  VecX v = v_pinned;
  for (int f = 0; f < pattern.num_free; ++f) v[pattern.dof_of_free[f]] = v_free[f];
  return v;
}

void SoftStep::add_gradient(const Eigen::Ref<const VecX>& v_free, Eigen::Ref<VecX> g) const {
  elastic_gradient(body, x0 + dt * full_velocity(v_free), R_, storage_.gradients, storage_.grad);
  for (int f = 0; f < pattern.num_free; ++f) g[f] += dt * storage_.grad[pattern.dof_of_free[f]];
}

void SoftStep::hessian(const Eigen::Ref<const VecX>& v_free, Eigen::SparseMatrix<real>& K) const {
  const SoftModel& m = body.model;
  const VecX x = x0 + dt * full_velocity(v_free);
  std::copy(K0_.begin(), K0_.end(), K.valuePtr());
  // the elements deformed beyond the reuse strain since x0 (or not finite) replace their
  // Hessian at x0 by the one at x; the others keep it
  std::vector<int>& changed = storage_.changed;
  std::vector<Mat3>& changed_F = storage_.changed_F;
  changed.clear();
  changed_F.clear();
  for (size_t t = 0; t < m.tets.size(); ++t) {
    Vec3 xs[4];
    gather(m.tets[t], x, xs);
    const Mat3 F = deformation_gradient(m.rest[t], xs);
    if (!((F - storage_.F0[t]).cwiseAbs().maxCoeff() <= reuse_strain_)) {
      changed.push_back(static_cast<int>(t));
      changed_F.push_back(F);
    }
  }
  for_each_tet(
      changed.size(), storage_.hessians,
      [&](size_t i, Mat12& H) {
        const int t = changed[i];
        tet_derivatives_at(m.material[t], m.rest[t], changed_F[i], R_[t], nullptr, &H, true);
        H -= storage_.H0[t];
      },
      [&](size_t i, const Mat12& H) { scatter_hessian(pattern, changed[i], dt * dt, H, K.valuePtr()); });
  element_hessians_ += static_cast<int>(changed.size());
  if (m.rod) add_rod_hessian(*m.rod, pattern, x, dt * dt, K.valuePtr());
  for (const auto& [slot, shift] : newton_shift_) K.valuePtr()[slot] += shift;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
