#pragma once
// The working storage of one scene's step (Scene::step_dynamics), kept in the scene across
// steps: every list is cleared or resized before use and keeps its capacity, so that a step
// like the last one (the same bodies, islands and contact counts) allocates almost nothing.

#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "multibody/articulation_step.h"
#include "collision/collision_detection.h"
#include "island/island_solver.h"
#include "island/islands.h"
#include "scene/bdf2_step.h"
#include "soft/soft_body.h"
#include "soft/soft_contact.h"
#include "solver/sparse_newton_system.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// A soft contact result's place in the order of the results: its links (body_a, link_a, body_b,
// link_b), then its island and its index among the island's soft contacts.
struct SoftContactRecordKey {
  std::array<int, 4> links;
  int island = 0, index = 0;
};

struct StepWorkspace {
  ContactPairs pairs;                                  // broad phase
  std::vector<std::vector<Contact>> chunk_contacts;    // narrow phase, per chunk of pairs
  std::vector<Ticks> item_ticks;                       // time per item of the parallel preparation (step_ticks.h)
  std::vector<Contact> contacts;                       // the chunks' contacts, joined
  std::vector<int> soft_free;                          // free DOFs per soft body
  std::vector<int> num_dofs;                           // DOFs per articulation
  std::vector<ArticulationTerms> terms;                // per articulation
  std::vector<ConstraintTerms> constraint_terms;       // per scene constraint, in handle order: this step's rows
  std::vector<std::array<int, 2>> constraint_bodies;   // per scene constraint: the island nodes it joins (build_islands; -1: none)
  std::vector<Island> islands;
  IslandScratch island_scratch;
  std::vector<SparseNewtonSystem*> sparse_cache;  // per island: its Newton system when sparse
  std::vector<double> island_size;                     // per island: its cost estimate
  std::vector<IslandSolution> solutions;               // per island
  std::vector<VecX> q_next, v_next, efforts_next;      // per articulation: the next state
  std::vector<ArticulationKinematics> kin_next;        // per articulation: the next state's kinematics
  std::vector<SoftContactRecordKey> soft_record_keys;  // the soft contact results' order
  std::vector<std::pair<int, int>> record_places;      // per contact: its island and index there
  Bdf2History bdf2;                                    // the last two steps' states (integration_method BDF2)
  Bdf2History bdf2_start;                              // a BDF2 step's start state (its storage kept)
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
