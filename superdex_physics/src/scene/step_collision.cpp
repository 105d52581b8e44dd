// The step's collision stages around the narrow phase (step_items.cpp): broad phase, and the
// contact lists.

#include "collision/collision_detection.h"
#include "collision/skin_contact.h"
#include "scene/step_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void find_step_contact_pairs(Step& step) {
  const Ticks k = ticks_now();
  find_contact_pairs(step.s, step.s.params.contact_margin, step.dt, step.ws.pairs);
  step.collision_ticks += ticks_now() - k;
}

void gather_contacts(Step& step) {
  const Ticks k = ticks_now();
  join_contacts(step.ws.chunk_contacts, step.ws.contacts);
  detect_skin_contacts(step.s, step.s.params.contact_margin, step.dt, step.ws.contacts);
  step.soft_contacts = detect_soft_contacts(step.s, step.s.params.contact_margin, step.dt);
  step.collision_ticks += ticks_now() - k;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
