#pragma once
// Contacts left out of an island's first solve because they cannot act in it, and admitted to a
// second solve when its result says otherwise. A contact block acts only once its normal velocity
// falls below its target by less than friction's reach (vn < vhat + mu |vt|, block_response), and
// a speculative contact's target lies beyond half its gap's closing speed: a contact whose gap
// the motion leaves half open is inactive, and leaving it out changes nothing but the cost.

#include "island/island_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// A soft contact too far apart to close within the step at the current speeds: it is left out of
// the first solve, and joins a second one only if that solve's velocities would close (half) its
// gap. Most speculative contacts of a soft surface are such.
inline bool soft_contact_deferred(const SoftContact& c) { return c.phi > c.sweep; }

// Flags the island's rigid contacts that take part in its first solve (w.contact_takes_part):
// all but those (with params.defer_separating_contacts) that both the bodies' current velocities
// and their free motion keep clear (half their gap open, friction's reach included). Needs the
// island's link Jacobians reset (reset_link_jacobians).
void select_rigid_contacts(const IslandInputs& in, IslandWorkspace& w);

// Admits the deferred rigid contacts that the solution `out` would make act (their gap closing
// faster than their target allows, friction's reach included); returns how many. The links'
// velocities at LinkMotion::Solution must be those of `out` (forgotten since the last solve:
// forget_link_velocities), as for admit_closing_soft_contacts.
int admit_closing_rigid_contacts(const IslandInputs& in, const IslandSolution& out, IslandWorkspace& w);

// Admits the deferred soft contacts not yet `admitted` whose gap the island's solution would close
// by more than half (half the gap its contact block would let close before acting); returns how
// many.
int admit_closing_soft_contacts(const IslandInputs& in, const IslandSolution& out, IslandWorkspace& w, std::vector<char>& admitted);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
