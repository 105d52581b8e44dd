// Volume, mass properties and validation of shapes (meshes: mesh_properties.cpp).

#include <cmath>
#include <numbers>
#include <sstream>

#include "shape/mesh_properties.h"
#include "superdex/physics/error.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {
constexpr real kPi = std::numbers::pi_v<real>;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// the deduction guide C++20 makes implicit; clang before 17 (the fuzz build) still needs it
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

bool finite(const Vec3& v) { return v.allFinite(); }
}  // namespace

real shape_volume(const ShapeGeometry& shape) {
  return std::visit(
      Overloaded{[](const PlaneShape&) -> real {
                   throw Error("a plane is unbounded: it has no volume or mass (make it static)");
                 },
                 [](const SphereShape& s) -> real { return 4 * kPi * s.radius * s.radius * s.radius / 3; },
                 [](const BoxShape& b) -> real { return 8 * b.half_extents.prod(); },
                 [](const CapsuleShape& c) -> real {
                   const real r2 = c.radius * c.radius;
                   return kPi * r2 * (2 * c.half_length) + 4 * kPi * r2 * c.radius / 3;
                 },
                 [](const MeshShape& m) -> real { return mesh_volume(m); }},
      shape);
}

MassProperties shape_mass_properties(const ShapeGeometry& shape, real density) {
  // meshes integrate volume, centre of mass and inertia in one pass
  if (const auto* mesh = std::get_if<MeshShape>(&shape)) return mesh_mass_properties(*mesh, density);
  MassProperties mp;
  mp.mass = density * shape_volume(shape);
  std::visit(Overloaded{[](const PlaneShape&) {},
                        [&](const SphereShape& s) {
                          mp.center_of_mass = s.center;
                          mp.inertia_about_com = Mat3::Identity() * (real(0.4) * mp.mass * s.radius * s.radius);
                        },
                        [&](const BoxShape& b) {
                          const Vec3 e = 2 * b.half_extents;
                          const Vec3 sq = e.cwiseProduct(e);
                          mp.inertia_about_com = (Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()) * (mp.mass / 12)).asDiagonal();
                        },
                        [&](const CapsuleShape& c) {
                          // cylinder plus two hemispheres, each hemisphere's COM offset 3r/8 from its base
                          const real r = c.radius, h = 2 * c.half_length, r2 = r * r;
                          const real m_cyl = density * kPi * r2 * h;
                          const real m_hemi = density * 2 * kPi * r2 * r / 3;
                          const real izz = m_cyl * r2 / 2 + 2 * m_hemi * (real(0.4) * r2);
                          const real d = c.half_length + 3 * r / 8;
                          const real i_hemi_com = real(0.4) * m_hemi * r2 - m_hemi * (3 * r / 8) * (3 * r / 8);
                          const real ixx = m_cyl * (3 * r2 + h * h) / 12 + 2 * (i_hemi_com + m_hemi * d * d);
                          mp.inertia_about_com = Vec3(ixx, ixx, izz).asDiagonal();
                        },
                        [](const MeshShape&) {}},
             shape);
  return mp;
}

void validate_shape(const ShapeGeometry& shape, const std::string& where) {
  auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  auto positive = [&](real x, const char* field) {
    if (!std::isfinite(x) || x <= 0) {
      std::ostringstream os;
      os << field << " must be a positive finite number, got " << x;
      fail(os.str());
    }
  };
  std::visit(Overloaded{[&](const PlaneShape& p) {
                          if (!finite(p.normal) || !std::isfinite(p.distance)) fail("plane normal and distance must be finite");
                          if (p.normal.norm() < real(1e-9)) fail("plane normal must be non-zero");
                        },
                        [&](const SphereShape& s) {
                          positive(s.radius, "sphere radius");
                          if (!finite(s.center)) fail("sphere center must be finite");
                        },
                        [&](const BoxShape& b) {
                          for (int k = 0; k < 3; ++k) positive(b.half_extents[k], "box halfExtents");
                        },
                        [&](const CapsuleShape& c) {
                          positive(c.radius, "capsule radius");
                          if (!std::isfinite(c.half_length) || c.half_length < 0)
                            fail("capsule halfLength must be a finite number >= 0");
                        },
                        [&](const MeshShape& m) { validate_mesh_shape(m, where); }},
             shape);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
