// Coordinate conventions (coordinate_space.h): the direction each axis points to, decoded from
// the packed axes value, and the signed permutation between two conventions.

#include "superdex/physics/coordinate_space.h"

#include <cmath>

#include "superdex/physics/error.h"

namespace superdex::physics {

namespace {

using A = CoordinateSpaceAxes;

// Right, Left, Up, Down, Forward, Backward: the physical direction as a vector of the reference
// frame (right, up, forward).
Eigen::Vector3d direction_vector(int direction) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  v[direction / 2] = direction % 2 == 0 ? 1.0 : -1.0;
  return v;
}

// Columns: where this space's x, y and z axes point in the reference frame (right, up, forward).
Eigen::Matrix3d axes_matrix(CoordinateSpaceAxes axes) {
  const unsigned value = static_cast<unsigned>(axes);
  Eigen::Matrix3d m;
  for (int axis = 0; axis < 3; ++axis) m.col(axis) = direction_vector(static_cast<int>((value >> (3 * axis)) & 7u));
  return m;
}

bool axes_valid(CoordinateSpaceAxes axes) {
  const unsigned value = static_cast<unsigned>(axes);
  if (value >> 9) return false;
  bool line_used[3] = {false, false, false};
  for (int axis = 0; axis < 3; ++axis) {
    const unsigned direction = (value >> (3 * axis)) & 7u;
    if (direction >= 6 || line_used[direction / 2]) return false;
    line_used[direction / 2] = true;
  }
  return true;
}

void validate_named(const CoordinateSpace& space, const std::string& name) {
  if (!axes_valid(space.axes))
    throw Error(name + ".axes: " + std::to_string(static_cast<unsigned>(space.axes)) +
                " is not a coordinate convention: the x, y and z axes must point along three different lines (e.g. FLU)");
  if (!(std::isfinite(space.units_per_meter) && space.units_per_meter > 0))
    throw Error(name + ".units_per_meter: must be a positive finite number, got " + std::to_string(space.units_per_meter));
}

}  // namespace

const CoordinateSpaceAxes kAllCoordinateSpaceAxes[48] = {
    A::RUF, A::RUB, A::RDF, A::RDB, A::LUF, A::LUB, A::LDF, A::LDB, A::RFU, A::RFD, A::RBU, A::RBD,
    A::LFU, A::LFD, A::LBU, A::LBD, A::URF, A::URB, A::ULF, A::ULB, A::DRF, A::DRB, A::DLF, A::DLB,
    A::UFR, A::UFL, A::UBR, A::UBL, A::DFR, A::DFL, A::DBR, A::DBL, A::FRU, A::FRD, A::FLU, A::FLD,
    A::BRU, A::BRD, A::BLU, A::BLD, A::FUR, A::FUL, A::FDR, A::FDL, A::BUR, A::BUL, A::BDR, A::BDL,
};

const char* coordinate_space_axes_name(CoordinateSpaceAxes axes) {
  static const char* const kLetters = "RLUDFB";
  static char names[48][4];
  static const bool filled = [] {
    for (int i = 0; i < 48; ++i) {
      const unsigned value = static_cast<unsigned>(kAllCoordinateSpaceAxes[i]);
      for (int axis = 0; axis < 3; ++axis) names[i][axis] = kLetters[(value >> (3 * axis)) & 7u];
      names[i][3] = '\0';
    }
    return true;
  }();
  (void)filled;
  for (int i = 0; i < 48; ++i)
    if (kAllCoordinateSpaceAxes[i] == axes) return names[i];
  return nullptr;
}

void CoordinateSpace::validate() const { validate_named(*this, "CoordinateSpace"); }

Eigen::Vector3d CoordinateSpace::right() const { return axes_matrix(axes).transpose() * direction_vector(0); }
Eigen::Vector3d CoordinateSpace::up() const { return axes_matrix(axes).transpose() * direction_vector(2); }
Eigen::Vector3d CoordinateSpace::forward() const { return axes_matrix(axes).transpose() * direction_vector(4); }

Eigen::Matrix3d coordinate_space_rotation(const CoordinateSpace& from, const CoordinateSpace& to) {
  validate_named(from, "from_space");
  validate_named(to, "to_space");
  // p_reference = M_from p_from and p_to = M_to^T p_reference (M orthogonal)
  return axes_matrix(to.axes).transpose() * axes_matrix(from.axes);
}

}  // namespace superdex::physics
