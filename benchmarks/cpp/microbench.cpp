/// @file microbench.cpp
/// Google Benchmark micro-benchmarks of the engine's hot kernels, on the double build:
/// kinematics, mass matrix and bias forces of revolute chains (7 and 30 DOFs), collision (one
/// box-box manifold; the whole narrow and broad phase of a settled 50-box pile), the convex
/// contact solve of an island of boxes in contact (dense, and by bodies as large islands are
/// solved) and the block Cholesky factorization of a sparse one, FEM assembly (energy, gradient and projected Hessian of Neo-Hookean tetrahedra),
/// the signed distance grid of a 1280-triangle sphere at 32^3 cells, and whole steps of the
/// 50-box pile for scale.
/// Built by `cmake --build <build dir> --target superdex_microbench`; run by benchmarks/run.py.

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "multibody/articulation_model.h"
#include "linalg/block_cholesky.h"
#include "block_problems.h"
#include "multibody/body_jacobian.h"
#include "collision/collision_detection.h"
#include "island/contact_block.h"
#include "multibody/dynamics.h"
#include "soft/fem_elasticity.h"
#include "multibody/kinematics.h"
#include "mesh_builders.h"
#include "solver/newton_solver.h"
#include "soft/reduced_soft.h"
#include "scene/scene_data.h"
#include "core/spatial.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/prefab.h"
#include "superdex/physics/scene.h"
#include "superdex/physics/sdf.h"
#include "solver/step_settings.h"

namespace sp = superdex::physics;
using sp::real;
using sp::Vec3;

namespace {

// A chain of n revolute links with alternating axes, offset COMs and full inertias.
sp::ArticulationModel chain(int n) {
  sp::ArticulationDesc d;
  d.name = "chain";
  sp::LinkDesc base;
  base.name = "base";
  base.mass = 1;
  base.moment_of_inertia = std::array<real, 6>{0.01, 0, 0, 0.01, 0, 0.01};
  d.links.push_back(base);
  sp::JointDesc weld;
  weld.name = "weld";
  weld.type = sp::JointType::Hard;
  d.joints.push_back(weld);
  for (int i = 1; i <= n; ++i) {
    sp::LinkDesc l;
    l.name = "l" + std::to_string(i);
    l.parent_link = i - 1;
    l.mass = 1.0 + 0.1 * i;
    l.center_of_mass = Vec3(0.05, 0.01, 0.1);
    l.moment_of_inertia = std::array<real, 6>{0.03, 0.001, -0.002, 0.03, 0.003, 0.02};
    d.links.push_back(l);
    sp::JointDesc j;
    j.name = "j" + std::to_string(i);
    j.type = sp::JointType::Revolute;
    j.axis = i % 3 == 0 ? Vec3::UnitX() : i % 3 == 1 ? Vec3::UnitY() : Vec3::UnitZ();
    j.parent_link_from_joint.translation = Vec3(0.0, 0.0, 0.2);
    j.armature = 0.01;
    d.joints.push_back(j);
  }
  return sp::build_articulation_model(d, "microbench");
}

sp::ArticulationState chain_state(const sp::ArticulationModel& m) {
  sp::ArticulationState s = sp::initial_state(m);
  for (int k = 0; k < m.nq; ++k) s.q[k] = 0.3 * std::sin(1.7 * k + 0.4);
  for (int k = 0; k < m.nv; ++k) s.v[k] = std::cos(0.9 * k);
  return s;
}

void BM_Kinematics(benchmark::State& st) {
  const auto model = chain(static_cast<int>(st.range(0)));
  const auto state = chain_state(model);
  sp::ArticulationKinematics kin;
  for (auto _ : st) {
    sp::update_kinematics(model, state, kin);
    benchmark::DoNotOptimize(kin.X_WL.data());
  }
}
BENCHMARK(BM_Kinematics)->Arg(7)->Arg(30);

void BM_LinkJacobian(benchmark::State& st) {
  const auto model = chain(static_cast<int>(st.range(0)));
  const auto state = chain_state(model);
  sp::ArticulationKinematics kin;
  sp::update_kinematics(model, state, kin);
  sp::MatXR J;
  for (auto _ : st) {
    sp::link_jacobian_world(model, kin, model.num_links - 1, J);
    benchmark::DoNotOptimize(J.data());
  }
}
BENCHMARK(BM_LinkJacobian)->Arg(7)->Arg(30);

void BM_MassMatrix(benchmark::State& st) {
  const auto model = chain(static_cast<int>(st.range(0)));
  const auto state = chain_state(model);
  sp::ArticulationKinematics kin;
  sp::update_kinematics(model, state, kin);
  for (auto _ : st) {
    sp::MatX M = sp::mass_matrix(model, kin);
    benchmark::DoNotOptimize(M.data());
  }
}
BENCHMARK(BM_MassMatrix)->Arg(7)->Arg(30);

void BM_BiasForces(benchmark::State& st) {
  const auto model = chain(static_cast<int>(st.range(0)));
  const auto state = chain_state(model);
  sp::ArticulationKinematics kin;
  sp::update_kinematics(model, state, kin);
  for (auto _ : st) {
    sp::VecX c = sp::bias_forces(model, state, kin, Vec3(0, 0, -9.81));
    benchmark::DoNotOptimize(c.data());
  }
}
BENCHMARK(BM_BiasForces)->Arg(7)->Arg(30);

void BM_CollideBoxBox(benchmark::State& st) {
  const sp::BoxShape a{Vec3(0.05, 0.05, 0.05)}, b{Vec3(0.05, 0.05, 0.05)};
  const sp::SpatialTransform Xa{sp::quat_exp(Vec3(0.1, -0.05, 0.2)).toRotationMatrix(), Vec3(0, 0, 0.05)};
  const sp::SpatialTransform Xb{sp::quat_exp(Vec3(-0.1, 0.15, 0.6)).toRotationMatrix(), Vec3(0.01, 0.02, 0.148)};
  std::vector<sp::ShapeContact> out;
  for (auto _ : st) {
    out.clear();
    sp::collide_box_box(a, Xa, b, Xb, real(0.01), out);
    benchmark::DoNotOptimize(out.data());
  }
  st.counters["points"] = static_cast<double>(out.size());
}
BENCHMARK(BM_CollideBoxBox);

// A settled pile of 50 boxes (as benchmark scene 4), built through the public API.
struct Pile {
  sp::Scene scene{sp::SceneHandle{}};
  Pile() {
    sp::initialize(0);
    scene = sp::create_scene("pile");
    scene.set_gravity(Vec3(0, 0, -9.81));
    sp::RigidActorParams ground;
    ground.name = "ground";
    ground.shape = sp::create_shape(sp::PlaneShape{});
    ground.is_static = true;
    scene.create_rigid_actor(ground);
    const sp::ShapeHandle box = sp::create_shape(sp::BoxShape{Vec3(0.05, 0.05, 0.05)});
    std::mt19937 rng(0);
    std::uniform_real_distribution<double> u(-0.15, 0.15);
    for (int k = 0; k < 50; ++k) {
      const int layer = k / 25, i = k % 25;
      sp::Transform X;
      X.translation = Vec3((i % 5 - 2) * 0.12 + 0.06 * layer, (i / 5 - 2) * 0.12 + 0.06 * layer, 0.1 + 0.15 * layer);
      X.rotation = sp::quat_exp(Vec3(u(rng), u(rng), u(rng)));
      sp::RigidActorParams p;
      p.name = "box" + std::to_string(k);
      p.shape = box;
      p.world_from_local = X;
      p.mass = real(1.0);
      scene.create_rigid_actor(p);
    }
    for (int k = 0; k < 500; ++k) scene.step(real(0.004));
  }
  ~Pile() { sp::shutdown(); }
};

void BM_DetectContactsPile50(benchmark::State& st) {
  Pile pile;
  const sp::SceneData& s = sp::scene_data(pile.scene.handle());
  size_t n = 0;
  for (auto _ : st) {
    const auto contacts = sp::detect_contacts(s, real(0.01), real(0.004));
    n = contacts.size();
    benchmark::DoNotOptimize(contacts.data());
  }
  st.counters["contacts"] = static_cast<double>(n);
}
BENCHMARK(BM_DetectContactsPile50)->Unit(benchmark::kMicrosecond);

void BM_StepPile50(benchmark::State& st) {
  Pile pile;
  for (auto _ : st) pile.scene.step(real(0.004));
  st.counters["contacts"] = pile.scene.solver_stats().num_contacts;
  st.counters["newton_iterations"] = pile.scene.solver_stats().total_non_linear_iters;
}
BENCHMARK(BM_StepPile50)->Unit(benchmark::kMillisecond);

// An island of `bodies` free bodies (6 DOFs each) with 4 frictional contacts per body between
// neighbours and with the ground: its convex problem, J both as compressed rows and by bodies.
struct ContactIsland {
  sp::MatX A;
  std::vector<sp::MatX> A_blocks;
  sp::VecX r;
  sp::ConstraintRows rows;
  sp::BodyJacobian J_bodies;
  sp::StepSettings params;

  explicit ContactIsland(int bodies) {
    const int n = 6 * bodies, contacts = 4 * bodies;
    std::mt19937 rng(1);
    std::normal_distribution<double> nd;
    A = sp::MatX::Zero(n, n);
    for (int b = 0; b < bodies; ++b) {
      A_blocks.push_back(sp::Mat6(sp::Mat6::Identity() * 1.0 + 0.01 * sp::Mat6::Ones()));
      A.block(6 * b, 6 * b, 6, 6) = A_blocks.back();
    }
    r.resize(n);
    for (int i = 0; i < n; ++i) r[i] = nd(rng) - (i % 6 == 2 ? 0.04 : 0.0);  // gravity's momentum on z
    std::vector<Eigen::Triplet<real>> t;
    J_bodies.reset(std::vector<int>(bodies, 6));
    for (int c = 0; c < contacts; ++c) {
      const int a = c / 4, b = (c % 4 == 0) ? -1 : (a + c % 4) % bodies;  // -1: the ground
      J_bodies.begin_block(3);
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 6; ++j) {
          const real va = static_cast<real>(nd(rng) * (j < 3 ? 1.0 : 0.05));
          t.emplace_back(3 * c + k, 6 * a + j, va);
          J_bodies.piece(a)[3 * j + k] += va;
          if (b >= 0 && b != a) {
            const real vb = static_cast<real>(-nd(rng) * (j < 3 ? 1.0 : 0.05));
            t.emplace_back(3 * c + k, 6 * b + j, vb);
            J_bodies.piece(b)[3 * j + k] += vb;
          }
        }
      J_bodies.end_block();
      sp::ContactMaterial mat;
      sp::ConstraintBlock blk = sp::frictional_contact_block(mat, real(-1e-4), real(1.0), real(1.0), real(-0.05), real(0.004), params);
      blk.row = 3 * c;
      rows.blocks.push_back(blk);
    }
    rows.J.resize(3 * contacts, n);
    rows.J.setFromTriplets(t.begin(), t.end());
  }
};

// Its solve with dense linear algebra (the path of small islands).
void BM_ContactSolveDense(benchmark::State& st) {
  const ContactIsland island(static_cast<int>(st.range(0)));
  const Eigen::LLT<sp::MatX> llt(island.A);
  int iterations = 0;
  for (auto _ : st) {
    const sp::ConvexResult res = sp::solve_convex(island.A, llt, island.r, island.rows, island.params);
    iterations = res.iterations;
    benchmark::DoNotOptimize(res.v.data());
  }
  st.counters["newton_iterations"] = iterations;
}
BENCHMARK(BM_ContactSolveDense)->Arg(4)->Arg(16)->Unit(benchmark::kMicrosecond);

// The same solve by bodies (the path of large islands: J in dense pieces per body, the Newton
// matrix factored by 6 x 6 blocks), with a new Newton system (pattern analysis included).
void BM_ContactSolveByBodies(benchmark::State& st) {
  const ContactIsland island(static_cast<int>(st.range(0)));
  int iterations = 0;
  for (auto _ : st) {
    const sp::ConvexResult res = sp::solve_convex(island.A_blocks, island.r, island.J_bodies, island.rows.blocks, island.params);
    iterations = res.iterations;
    benchmark::DoNotOptimize(res.v.data());
  }
  st.counters["newton_iterations"] = iterations;
}
BENCHMARK(BM_ContactSolveByBodies)->Arg(4)->Arg(16)->Unit(benchmark::kMicrosecond);

// The block Cholesky factorization of a rigid island's Newton matrix: `bodies` free bodies
// (6 x 6 blocks) coupled along a chain and random pairs (about 6 neighbours each), an SPD matrix
// on that pattern; the pattern analysed once, as the solver does, then factored per iteration.
void BM_BlockCholeskyFactor(benchmark::State& st) {
  std::mt19937 rng(2);
  const sp::BlockProblem p = sp::random_pattern(static_cast<int>(st.range(0)), 4, rng, 6);
  sp::BlockCholesky chol;
  chol.analyze(p.sizes, p.pairs);
  if (!sp::load(chol, p, sp::random_matrix(p, 0.1, rng)) || !chol.factor()) {
    st.SkipWithError("the random problem did not load or factor");
    return;
  }
  for (auto _ : st) {
    const bool ok = chol.factor();
    benchmark::DoNotOptimize(ok);
  }
}
BENCHMARK(BM_BlockCholeskyFactor)->Arg(18)->Arg(50)->Unit(benchmark::kMicrosecond);

// FEM assembly: energy, gradient and SPD-projected Hessian of every tetrahedron of a deformed
// block (6 tetrahedra per cell), per element.
void BM_FemTetAssembly(benchmark::State& st) {
  const auto material = sp::ElasticMaterial::from_young_poisson(sp::MaterialModel::NeoHookean, real(1e5), real(0.45), "bench");
  std::mt19937 rng(2);
  std::normal_distribution<double> nd(0.0, 0.002);
  const int cells = 6;
  const double h = 0.1 / cells;
  std::vector<sp::TetRest> rest;
  std::vector<std::array<Vec3, 4>> x;
  const int paths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
  for (int k = 0; k < cells; ++k)
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i) {
        Vec3 c[8];
        for (int v = 0; v < 8; ++v) c[v] = Vec3((i + (v & 1)) * h, (j + ((v >> 1) & 1)) * h, (k + ((v >> 2) & 1)) * h);
        for (const auto& p : paths) {
          std::array<Vec3, 4> X = {c[0], c[p[0]], c[p[1]], c[7]};
          if ((X[1] - X[0]).cross(X[2] - X[0]).dot(X[3] - X[0]) < 0) std::swap(X[1], X[2]);
          rest.push_back(sp::make_tet_rest(X[0], X[1], X[2], X[3], real(1e-12), "bench"));
          for (auto& p_ : X) p_ += Vec3(nd(rng), nd(rng), nd(rng));
          x.push_back(X);
        }
      }
  const sp::Mat3 R = sp::Mat3::Identity();
  sp::Vec12 g;
  sp::Mat12 H;
  for (auto _ : st) {
    real e = 0;
    for (size_t t = 0; t < rest.size(); ++t) e += sp::tet_energy(material, rest[t], x[t].data(), R, &g, &H, true);
    benchmark::DoNotOptimize(e);
    benchmark::DoNotOptimize(H.data());
  }
  st.SetItemsProcessed(static_cast<int64_t>(st.iterations() * rest.size()));
  st.counters["tets"] = static_cast<double>(rest.size());
}
BENCHMARK(BM_FemTetAssembly)->Unit(benchmark::kMicrosecond);

// The signed distance grid of a mesh shape, computed once per new mesh (then cached on disk):
// a 1280-triangle icosphere on a 32^3 grid with 3 cells of padding.
void BM_ComputeSdf(benchmark::State& st) {
  const sp::TriangleMesh sphere = sp::test::icosphere(3, 1.0);
  for (auto _ : st) {
    const sp::SdfGrid g = sp::compute_sdf(sphere, {32, 3}, "sphere");
    benchmark::DoNotOptimize(g.values.data());
  }
  st.counters["triangles"] = static_cast<double>(sphere.triangles.size());
}
BENCHMARK(BM_ComputeSdf)->Unit(benchmark::kMillisecond);

// The residual compliance columns of the seed's reduced duck (1168 nodes, 24 modes) for `nodes`
// surface nodes touched at once, computed afresh each iteration (what a step pays when the
// contact reaches new nodes).
void BM_ReducedResidualColumns(benchmark::State& st) {
  sp::initialize(0);
  {
    sp::Scene scene = sp::create_scene("duck");
    const std::string root = SUPERDEX_ASSETS_DIR;
    sp::prefab::add_to_scene(root + "/prefabs/duck_lamp/duck_lamp_recumbent.mochi_prefab", root, scene);
    const sp::ReducedSoftModel& model = *sp::scene_data(scene.handle()).soft_bodies.front()->reduced;
    // the free nodes highest up (where the seed's ball presses)
    std::vector<int> nodes;
    for (int v = 0; v * 3 < static_cast<int>(model.free_of_dof.size()); ++v)
      if (model.free_of_dof[3 * v] >= 0) nodes.push_back(v);
    std::sort(nodes.begin(), nodes.end(), [&](int a, int b) { return model.x_rest[3 * a + 2] > model.x_rest[3 * b + 2]; });
    nodes.resize(static_cast<size_t>(st.range(0)));
    for (auto _ : st) {
      model.residual_columns.clear();
      model.prepare_residuals(nodes);
      for (int v : nodes) benchmark::DoNotOptimize(model.residual(v).data());
    }
    st.SetItemsProcessed(static_cast<int64_t>(st.iterations() * nodes.size()));
  }
  sp::shutdown();
}
BENCHMARK(BM_ReducedResidualColumns)->Arg(1)->Arg(8)->Arg(64)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
