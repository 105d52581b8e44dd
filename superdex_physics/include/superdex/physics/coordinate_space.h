#pragma once
/// @file coordinate_space.h
/// Coordinate conventions of other tools and engines: which physical direction (right, left, up,
/// down, forward, backward) each coordinate axis points to, and the length unit. The engine's own
/// convention is FLU in metres (x forward, y left, z up). Models made for another convention are
/// converted with model::bake_coordinate_space_transform (model.h).

#include <cstdint>
#include <string>

#include <Eigen/Core>

namespace superdex::physics {

/// Where the x, y and z axes point, named by the three directions in axis order: FLU is x
/// forward, y left, z up. The value packs the directions Right=0, Left=1, Up=2, Down=3, Forward=4,
/// Backward=5 as x | y << 3 | z << 6 (SuperDex's values).
enum class CoordinateSpaceAxes : std::uint16_t {
  RUF = 272, RUB = 336, RDF = 280, RDB = 344, LUF = 273, LUB = 337, LDF = 281, LDB = 345,
  RFU = 160, RFD = 224, RBU = 168, RBD = 232, LFU = 161, LFD = 225, LBU = 169, LBD = 233,
  URF = 258, URB = 322, ULF = 266, ULB = 330, DRF = 259, DRB = 323, DLF = 267, DLB = 331,
  UFR = 34, UFL = 98, UBR = 42, UBL = 106, DFR = 35, DFL = 99, DBR = 43, DBL = 107,
  FRU = 132, FRD = 196, FLU = 140, FLD = 204, BRU = 133, BRD = 197, BLU = 141, BLD = 205,
  FUR = 20, FUL = 84, FDR = 28, FDL = 92, BUR = 21, BUL = 85, BDR = 29, BDL = 93,
  Default = FLU,
};

/// The 48 valid conventions in SuperDex's order (for bindings and tests).
extern const CoordinateSpaceAxes kAllCoordinateSpaceAxes[48];
/// "FLU", "RUB", ...; nullptr for a value that is not one of the 48.
const char* coordinate_space_axes_name(CoordinateSpaceAxes axes);

/// A coordinate convention: axis directions and how many length units make a metre (100 for
/// centimetres). units_per_meter is a double in both precisions.
struct CoordinateSpace {
  CoordinateSpaceAxes axes = CoordinateSpaceAxes::Default;
  double units_per_meter = 1.0;

  /// Throws superdex::Error when the axes do not name three different axis lines or
  /// units_per_meter is not a positive finite number.
  void validate() const;

  /// x forward, y left, z up; metres (the engine's convention; also ROS's).
  static CoordinateSpace engine_default() { return {CoordinateSpaceAxes::FLU, 1.0}; }
  /// x forward, y right, z up; centimetres.
  static CoordinateSpace unreal() { return {CoordinateSpaceAxes::FRU, 100.0}; }
  /// x right, y up, z forward; metres.
  static CoordinateSpace unity() { return {CoordinateSpaceAxes::RUF, 1.0}; }
  /// x right, y up, z backward; metres.
  static CoordinateSpace open_gl() { return {CoordinateSpaceAxes::RUB, 1.0}; }
  /// x right, y up, z backward; metres.
  static CoordinateSpace filament() { return {CoordinateSpaceAxes::RUB, 1.0}; }
  /// x forward, y left, z up; metres.
  static CoordinateSpace ros() { return {CoordinateSpaceAxes::FLU, 1.0}; }

  /// The unit vector pointing right (up, forward) in this space's coordinates: +-1 on one axis.
  /// The axes must be valid.
  Eigen::Vector3d right() const;
  Eigen::Vector3d up() const;
  Eigen::Vector3d forward() const;

  bool operator==(const CoordinateSpace&) const = default;
};

/// The signed permutation A with p_to = A p_from for directions given in `from`'s and `to`'s axes
/// (entries 0 and +-1: exact). Lengths also scale by to.units_per_meter / from.units_per_meter.
/// Both spaces are validated first (superdex::Error naming `from_space` or `to_space`).
Eigen::Matrix3d coordinate_space_rotation(const CoordinateSpace& from, const CoordinateSpace& to);

}  // namespace superdex::physics
