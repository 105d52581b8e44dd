#pragma once
/// @file link_overlaps.h
/// Links of one articulation whose collision shapes already interpenetrate at its default
/// pose. Robot descriptions often give neighbouring links overlapping collision meshes (a
/// wrist shell around the next link's motor); left to collide, such pairs push on each other
/// from the first step. Importers switch them off as contact overrides.

#include <vector>

#include "superdex/physics/articulation_desc.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Two links (indices into ArticulationDesc::links, link_a < link_b) and how deep their shapes
/// interpenetrate (m, > 0).
struct LinkOverlap {
  int link_a = 0, link_b = 0;
  real depth = 0;
};

/// The pairs of links of `desc` that touch (by default: not on one rigid body, not on two bodies
/// joined by a joint, not both welded to the world; or switched on by a contact override) and whose collision shapes
/// interpenetrate by more than `tolerance` (m) with every joint at the description's default
/// pose, in increasing (link_a, link_b) order. Pairs whose overlap cannot be measured (an open
/// mesh against another mesh) are left out. Throws superdex::Error for an invalid description,
/// naming `source`.
std::vector<LinkOverlap> overlapping_link_pairs(const ArticulationDesc& desc, real tolerance, const std::string& source);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
