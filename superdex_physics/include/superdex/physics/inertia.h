#pragma once
/// @file inertia.h
/// Whether a rotational inertia describes a physical mass distribution, and the nearest one that
/// does: what the params API simulates when given an invalid inertia and what the URDF importer
/// gives a link whose <inertia> is not physical (each with a warning).

#include <optional>
#include <string>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Why a rotational inertia (kg m^2, about the centre of mass) is not physical: not positive
/// definite, or principal moments violating the triangle inequality. Empty when it is physical.
std::optional<std::string> inertia_defect(const Mat3& I);

/// The physical inertia nearest I in its principal axes: moments raised to at least 1e-6 of the
/// largest (or 1e-9 kg m^2 when none is positive), then the largest lowered to the sum of the
/// other two where it exceeds it.
Mat3 nearest_physical_inertia(const Mat3& I);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
