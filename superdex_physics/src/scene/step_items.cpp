// The step's parallel preparation: together on the worker threads, the soft bodies' parts of the
// problem (the costliest items, first), the dynamics terms of every articulation and the narrow
// phase, each item timed.

#include <algorithm>
#include <functional>

#include "collision/collision_detection.h"
#include "multibody/articulation_step.h"
#include "scene/step_stages.h"
#include "superdex/physics/engine.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void prepare_step_items(Step& step) {
  SceneData& s = step.s;
  StepWorkspace& ws = step.ws;
  const real dt = step.dt;
  const size_t n = s.articulations.size();
  const ContactPairs& pairs = ws.pairs;
  const size_t num_soft = s.soft_bodies.size();
  std::vector<std::unique_ptr<SoftStep>>& soft_steps = step.soft_steps;
  soft_steps.resize(num_soft);
  std::vector<int>& soft_free = ws.soft_free;
  soft_free.assign(num_soft, 0);
  for (size_t k = 0; k < num_soft; ++k)
    for (char pinned : s.soft_bodies[k]->model.pinned) soft_free[k] += pinned ? 0 : 3;
  std::vector<ArticulationTerms>& terms = ws.terms;
  terms.resize(n);
  std::vector<std::vector<Contact>>& chunk_contacts = ws.chunk_contacts;
  chunk_contacts.resize(pairs.num_chunks());
  for (auto& chunk : chunk_contacts) chunk.clear();
  // the articulations by groups of a few (each costs about a microsecond: one item each would
  // pass the threads' shared item counter back and forth as often)
  constexpr size_t kBodiesPerItem = 8;
  const size_t body_items = (n + kBodiesPerItem - 1) / kBodiesPerItem;
  // each item's time (the soft bodies' are not reported)
  std::vector<Ticks>& item_ticks = ws.item_ticks;
  item_ticks.assign(num_soft + body_items + pairs.num_chunks(), 0);
  const auto prepare = [&](size_t i) {
    if (i < num_soft) {
      if (soft_free[i] > 0 && !s.soft_bodies[i]->reduced) soft_steps[i] = std::make_unique<SoftStep>(*s.soft_bodies[i], s.soft_bodies[i]->has_gravity ? s.gravity : Vec3::Zero(), dt, s.params.soft_hessian_reuse_strain);
      return;
    }
    const Ticks t = ticks_now();
    if (i < num_soft + body_items) {
      const size_t first = (i - num_soft) * kBodiesPerItem;
      for (size_t b = first; b < std::min(n, first + kBodiesPerItem); ++b)
        articulation_terms(*s.articulations[b], s.gravity, dt, s.params, terms[b]);
    } else {
      const size_t c = i - num_soft - body_items;
      collide_pairs(s, pairs, c, chunk_contacts[c]);
    }
    item_ticks[i] = ticks_now() - t;
  };
  // by reference: a std::function holds a reference without allocating (the lambda is too large)
  run_on_worker_threads(item_ticks.size(), std::cref(prepare));
  for (size_t i = num_soft; i < item_ticks.size(); ++i) (i < num_soft + body_items ? step.kinematics_ticks : step.collision_ticks) += item_ticks[i];
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
