#pragma once
// An MJCF document as the importer reads it: the XML with every <include> expanded, the
// <default> classes resolved into per-element attribute sets, the <compiler> settings, and
// attribute access that falls back on an element's class as MuJoCo does.

#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/real.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// <compiler> settings the importer uses (MuJoCo's defaults).
struct MjcfCompiler {
  bool degrees = true;             ///< angle="degree": euler, axisangle and hinge ranges in degrees
  std::string eulerseq = "xyz";    ///< lower case: axes that move with the frame; upper case: fixed axes
  std::filesystem::path meshdir;   ///< where mesh files are looked for (relative to the model's folder)
  bool autolimits = true;          ///< a joint with a range is limited unless it says otherwise
  std::string inertiafromgeom = "auto";  ///< "auto" (bodies without <inertial>), "true" or "false"
  int inertia_group_min = 0, inertia_group_max = 5;  ///< geoms of these groups give bodies mass
  double boundmass = 0, boundinertia = 0;            ///< lower bounds on body masses and moments
  bool balanceinertia = false;
  std::optional<double> settotalmass;  ///< scale every mass so that they sum to this (kg)
};

class MjcfDocument {
 public:
  using Element = tinyxml2::XMLElement;

  MjcfDocument(const std::string& path, std::vector<std::string>* warnings);

  const std::string& path() const { return path_; }
  const std::filesystem::path& dir() const { return dir_; }
  const Element* root() const { return root_; }
  const MjcfCompiler& compiler() const { return compiler_; }

  /// The value of attribute `name` of `e`: its own, else its class's default for elements of its
  /// kind (class: its `class` attribute, else `childclass`, else "main"). nullptr when unset.
  const char* attr(const Element* e, const char* name, const std::string& childclass) const;

  /// Numbers of an attribute (own or default), `count` of them (0: any number >= 1); nullopt when unset.
  std::optional<std::vector<double>> numbers(const Element* e, const char* name, const std::string& childclass, size_t count) const;
  double number_or(const Element* e, const char* name, const std::string& childclass, double fallback) const;
  Eigen::Vector3d vec3_or(const Element* e, const char* name, const std::string& childclass, const Eigen::Vector3d& fallback) const;
  /// "true"/"false" (MuJoCo's "auto" gives nullopt), or nullopt when unset.
  std::optional<bool> boolean(const Element* e, const char* name, const std::string& childclass) const;

  /// The frame given by pos and one of quat, axisangle, euler, xyaxes, zaxis (identity when absent).
  Eigen::Isometry3d pose(const Element* e, const std::string& childclass) const;
  /// The rotation given by quat, axisangle, euler, xyaxes or zaxis (identity when absent).
  Eigen::Quaterniond orientation(const Element* e, const std::string& childclass) const;
  /// The minimal rotation taking +z to `v`.
  static Eigen::Quaterniond z_to(const Eigen::Vector3d& v);
  /// An angle attribute value in radians.
  double angle(double value) const { return compiler_.degrees ? value * EIGEN_PI / 180 : value; }

  /// The class an element's children use: its `childclass`, else the inherited one.
  std::string child_class(const Element* e, const std::string& inherited) const;

  [[noreturn]] void fail(const Element* e, const std::string& what) const;
  [[noreturn]] void fail_file(const std::string& what) const;
  void warn(const Element* e, const std::string& what) const;

  /// "<body name='a'>/<geom>": the element and its ancestors up to the nearest <body> or <worldbody>.
  static std::string label(const Element* e);

 private:
  void expand_includes(tinyxml2::XMLElement* top, const std::filesystem::path& dir);
  void read_defaults(const Element* def, const std::string& parent_class);
  void read_compiler();

  std::string path_;
  std::filesystem::path dir_;
  std::vector<std::string>* warnings_;
  tinyxml2::XMLDocument doc_;
  Element* root_ = nullptr;
  MjcfCompiler compiler_;
  // class -> element kind ("geom", "joint", ...) -> attribute -> value, parents' values included
  std::map<std::string, std::map<std::string, std::map<std::string, std::string>>> defaults_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
