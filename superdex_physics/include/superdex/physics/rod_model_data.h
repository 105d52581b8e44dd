#pragma once
/// @file rod_model_data.h
/// Rod models (SuperDex's experimental generate_tubular_rod_model_data): a polyline with a frame
/// axis per element, and a tube around it for display.

#include <vector>

#include "superdex/physics/model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// The model of a rod along `nodes` (m): a polyline mesh (element e joins node e to node e + 1;
/// with is_closed_loop one more joins the last node to the first), element_frame_axes (one per
/// element, made unit and normal to its element), and a visual mesh: a tube of `radius` (m) with
/// num_cross_section_segments (>= 3) vertices around each node, capped at the ends of an open rod,
/// each vertex skinned to the elements meeting at its node. Throws superdex::Error naming the
/// argument for bad input.
ModelData generate_tubular_rod_model_data(const std::vector<Real3>& nodes, const std::vector<Real3>& element_frame_axes, real radius,
                                          int num_cross_section_segments, bool is_closed_loop);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
