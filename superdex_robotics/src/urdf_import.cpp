// URDF import: a <robot> description (links, joints, inertials, collision and visual
// geometry) turned into a BotPrefab whose articulation has the URDF's kinematics and dynamics.
//
// Mapping
//  * Links are ordered depth-first from the root link (the one that is no joint's child),
//    children in document order, so every parent comes before its children. Each URDF joint
//    becomes the joint of its child link: revolute -> Revolute (limited), continuous ->
//    Revolute (unlimited), prismatic -> Prismatic, fixed -> Hard, floating -> Free (root only),
//    planar -> error. The root link gets a joint named "world_joint" (made unique): Free by
//    default (a floating base, as humanoids and quadrupeds need), Hard with
//    UrdfImportOptions::fixed_base, and for a root link named "world" (the world's frame).
//  * A root link named "world" that carries nothing (no mass, no collision) and has a single
//    fixed or floating joint is the world itself: it is dropped, and that joint becomes the
//    root joint of its child (Hard or Free, its <origin> as parentLinkFromJoint). Any other
//    floating joint is an error. A "world" attached by a moving joint stays as a welded link.
//  * Frames: the joint <origin> is X_PJ (parentLinkFromJoint), the child link frame is the
//    joint frame (as in URDF). rpy is fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
//    The axis (default 1 0 0) is normalised; limits become the vectors axis*lower, axis*upper.
//    <limit effort> -> effortLimit; <dynamics damping friction> -> viscous / Coulomb friction.
//    <mimic joint multiplier offset> couples the joint to the one it names (a JointCoupling:
//    q = multiplier q_leader + offset, held by the step; the joint keeps its own DOF). A mimic
//    that names no joint, or joins a fixed joint, is ignored with a warning.
//  * Inertials: mass, centre of mass = inertial origin xyz, rotational inertia about the COM
//    rotated into the link frame, I_L = R I R^T (R from the inertial origin rpy). An inertia
//    that no mass distribution has (not positive definite, or principal moments breaking the
//    triangle inequality: round-off in exported files, point masses, typing errors) is
//    replaced, with a warning naming the link, by the nearest physical one
//    (superdex/physics/inertia.h: moments raised to 1e-6 of the largest, the largest lowered to
//    the sum of the other two), as the params API does.
//
// Massless links. URDF allows links without an <inertial> (or with mass 0): frames such as
// "tool0", "panda_hand_tcp" or flanges. The engine needs mass > 0 and a positive-definite
// inertia on every link. Merging such links into their parent (as Pinocchio does for every
// fixed joint) was rejected: the link names are what sensors, actuators and controllers are
// attached to (an end-effector frame is the usual target of an operational-space
// controller), so the BotPrefab keeps one link per URDF link. A massless link instead gets a
// negligible mass, kMasslessLinkMass = 1e-9 kg at its origin with an inertia of
// kMasslessLinkInertia = 1e-12 kg m^2 about each axis. A massless link may move on a joint
// only when some link it carries has mass (the intermediate frames of a hip or wrist built
// from single-axis joints), so that the joint does not move a massless body. Otherwise its mass
// and inertia come from its closed collision shape at kInertiaFromGeometryDensity (MuJoCo's
// inertiafromgeom rule), with a warning; without one the import fails naming the link and the
// joint. The Pinocchio comparison test gives Pinocchio the same negligible inertias, so it
// stays exact.
//
// Geometry. Every <collision> is imported with its <origin>: the first becomes the link's
// shape (link_from_shape), the others its extra_shapes (compound collision): <box size>,
// <sphere radius>, <cylinder radius length> as a closed 48-sided prism mesh (the exact
// cylinder up to 0.2% of its radius; a capsule would change the shape: a short wheel would
// turn into a ball), <capsule radius length> (an SDFormat extension; length is the
// cylindrical part) and <mesh filename scale> loaded with the scale baked in (a negative scale
// mirrors the mesh, its winding reversed to keep it facing outward; OBJ, STL, PLY,
// .mochi.h5; other formats such as COLLADA .dae leave the link without a collider, with a
// warning). The link's mass never comes from its shape. The first <visual> <mesh> is
// recorded as the render model (path and scale; its <origin> is ignored with a warning).
// Mesh filenames: "package://pkg/rest" is searched upward from the URDF's folder (a folder
// named pkg, or containing one), then in $ROS_PACKAGE_PATH entries and $AMENT_PREFIX_PATH
// share folders; "model://" likewise; "file://" and plain paths are absolute or relative to
// the URDF's folder. A collision mesh that cannot be found is an error; a visual one a warning.
//
// Errors are superdex::Error "<file>: line N: <joint name='j'>/<limit>: what".

#include <tinyxml2.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"
#include "superdex/physics/inertia.h"
#include "superdex/physics/link_overlaps.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"
#include "import/import_support.h"
#include "superdex/robotics/bot_prefab.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;
using physics::JointDesc;
using physics::JointType;
using physics::LinkDesc;
using physics::Mat3;
using physics::real;
using physics::ShapeGeometry;
using physics::Vec3;
using tinyxml2::XMLElement;

namespace {

// Mass (kg) and rotational inertia (kg m^2 about each axis) of links the URDF leaves massless.
constexpr double kMasslessLinkMass = 1e-9;
constexpr double kMasslessLinkInertia = 1e-12;
// Density (kg/m^3) that gives a moving link carrying no mass its mass from its collision shape.
constexpr double kInertiaFromGeometryDensity = 1000;

// Whether a collision shape encloses a volume to take mass properties from.
bool has_volume(const std::optional<ShapeGeometry>& shape) {
  if (!shape || std::holds_alternative<physics::PlaneShape>(*shape)) return false;
  if (const auto* mesh = std::get_if<physics::MeshShape>(&*shape)) return physics::is_closed(*mesh->mesh);
  return true;
}

// The pieces of the URDF the importer works from, in document order.
struct UrdfLink {
  const XMLElement* element = nullptr;
  std::string name;
  bool has_mass = false;      // an <inertial> with mass > 0 or a rotational inertia
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the COM, link frame
  double mass = 0;
  int parent_joint = -1;      // index into joints, -1 for the root
  std::vector<int> child_joints;
};

struct UrdfJoint {
  const XMLElement* element = nullptr;
  std::string name, type;
  int parent = -1, child = -1;  // indices into links
};

class UrdfImporter {
 public:
  UrdfImporter(const std::string& path, std::vector<std::string>* warnings, const UrdfImportOptions& options)
      : path_(path), dir_(fs::absolute(fs::path(path)).parent_path()), warnings_(warnings), options_(options) {}

  BotPrefab run() {
    load_document();
    read_links();
    read_joints();
    const int root = find_root();
    return build(root);
  }

 private:
  // ------------------------------------------------------------------ messages

  // "<link name='a'>/<collision>/<geometry>/<mesh>": the element and its ancestors up to the
  // nearest <link>, <joint> or <robot>.
  static std::string label(const XMLElement* e) {
    std::string out;
    for (const XMLElement* k = e; k; k = k->Parent() ? k->Parent()->ToElement() : nullptr) {
      std::string part = std::string("<") + k->Name();
      if (const char* n = k->Attribute("name")) part += " name=" + in_quotes(n);
      part += ">";
      out = out.empty() ? part : part + "/" + out;
      const std::string tag = k->Name();
      if (tag == "link" || tag == "joint" || tag == "robot") break;
    }
    return out;
  }

  [[noreturn]] void fail(const XMLElement* e, const std::string& what) const {
    throw Error(path_ + ": line " + std::to_string(e->GetLineNum()) + ": " + label(e) + ": " + what);
  }
  [[noreturn]] void fail_file(const std::string& what) const { throw Error(path_ + ": " + what); }

  void warn(const XMLElement* e, const std::string& what) const {
    if (warnings_) warnings_->push_back(path_ + ": line " + std::to_string(e->GetLineNum()) + ": " + label(e) + ": " + what);
  }

  // ------------------------------------------------------------------ attributes

  std::string required_attribute(const XMLElement* e, const char* name) const {
    const char* v = e->Attribute(name);
    if (!v) fail(e, std::string("missing required attribute '") + name + "'");
    return v;
  }

  const XMLElement* required_child(const XMLElement* e, const char* name) const {
    const XMLElement* c = e->FirstChildElement(name);
    if (!c) fail(e, std::string("missing required element <") + name + ">");
    return c;
  }

  // Whitespace-separated numbers of an attribute; `count` of them (0: any number >= 1).
  std::vector<double> numbers(const XMLElement* e, const char* name, size_t count) const {
    const std::string text = required_attribute(e, name);
    std::string bad;
    const std::optional<std::vector<double>> parsed = parse_numbers(text, &bad);
    if (!parsed) fail(e, std::string("attribute '") + name + "': malformed number '" + bad + "' in \"" + text + "\"");
    const std::vector<double>& out = *parsed;
    if (out.empty() || (count && out.size() != count))
      fail(e, std::string("attribute '") + name + "': expected " + (count ? std::to_string(count) : "at least one") +
                  " number" + (count == 1 ? "" : "s") + ", got \"" + text + "\"");
    return out;
  }
  double number(const XMLElement* e, const char* name) const { return numbers(e, name, 1)[0]; }
  Eigen::Vector3d vec3(const XMLElement* e, const char* name) const {
    const auto v = numbers(e, name, 3);
    return {v[0], v[1], v[2]};
  }
  Eigen::Vector3d vec3_or(const XMLElement* e, const char* name, const Eigen::Vector3d& fallback) const {
    return e->Attribute(name) ? vec3(e, name) : fallback;
  }
  double positive(const XMLElement* e, const char* name) const {
    const double x = number(e, name);
    if (x <= 0) fail(e, std::string("attribute '") + name + "' must be positive, got " + format_number(x));
    return x;
  }

  // ------------------------------------------------------------------ frames

  // R = Rz(yaw) Ry(pitch) Rx(roll): fixed-axis roll, then pitch, then yaw.
  static Eigen::Quaterniond rpy_to_quaternion(const Eigen::Vector3d& rpy) {
    return Eigen::Quaterniond(Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                              Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()));
  }

  // The <origin> child of `e` as a transform (identity when absent), in double precision.
  Eigen::Isometry3d origin_of(const XMLElement* e) const {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    if (const XMLElement* o = e->FirstChildElement("origin")) {
      X.linear() = rpy_to_quaternion(vec3_or(o, "rpy", Eigen::Vector3d::Zero())).toRotationMatrix();
      X.translation() = vec3_or(o, "xyz", Eigen::Vector3d::Zero());
    }
    return X;
  }

  // ------------------------------------------------------------------ document

  void load_document() {
    if (!is_existing_file(path_)) fail_file("cannot open the URDF file (does it exist?)");
    const tinyxml2::XMLError err = doc_.LoadFile(path_.c_str());
    if (err != tinyxml2::XML_SUCCESS)
      fail_file("not a valid XML file: " + std::string(doc_.ErrorStr() ? doc_.ErrorStr() : doc_.ErrorName()));
    robot_ = doc_.RootElement();
    if (!robot_ || std::string(robot_->Name()) != "robot")
      fail_file(std::string("not a URDF file: the root element is <") + (robot_ ? robot_->Name() : "") +
                ">, expected <robot>");
    // a <robot> without a name (the URDF schema requires one; some files omit it) is named
    // after its file
    const char* name = robot_->Attribute("name");
    robot_name_ = name && *name ? name : fs::path(path_).stem().string();
    if (!name || !*name) warn(robot_, "the robot has no name; naming it " + in_quotes(robot_name_) + " after its file");
  }

  void read_links() {
    for (const XMLElement* e = robot_->FirstChildElement("link"); e; e = e->NextSiblingElement("link")) {
      UrdfLink L;
      L.element = e;
      L.name = required_attribute(e, "name");
      if (L.name.empty()) fail(e, "the link name must not be empty");
      if (!link_index_.emplace(L.name, static_cast<int>(links_.size())).second)
        fail(e, "duplicate link name " + in_quotes(L.name));
      read_inertial(L);
      links_.push_back(std::move(L));
    }
    if (links_.empty()) fail(robot_, "the robot has no <link>");
  }

  void read_inertial(UrdfLink& L) const {
    const XMLElement* in = L.element->FirstChildElement("inertial");
    if (!in) return;
    const XMLElement* mass = required_child(in, "mass");
    L.mass = number(mass, "value");
    if (L.mass < 0) fail(mass, "the mass must not be negative, got " + format_number(L.mass));
    const XMLElement* ie = required_child(in, "inertia");
    const double ixx = number(ie, "ixx"), ixy = number(ie, "ixy"), ixz = number(ie, "ixz");
    const double iyy = number(ie, "iyy"), iyz = number(ie, "iyz"), izz = number(ie, "izz");
    Eigen::Matrix3d I;
    I << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
    // mass 0 with no rotational inertia: a massless frame (see the top of the file); mass 0 with
    // one (bolt's feet): the rotational inertia is kept, as Pinocchio keeps it, on the negligible mass
    if (L.mass == 0 && I.isZero()) return;
    if (L.mass == 0) L.mass = kMasslessLinkMass;
    const Eigen::Isometry3d X_LC = origin_of(in);  // the inertia frame in the link frame
    L.has_mass = true;
    L.com = X_LC.translation();
    L.inertia = X_LC.linear() * I * X_LC.linear().transpose();
    // an inertia no mass distribution has (not positive definite, principal moments breaking
    // the triangle inequality: round-off, point masses, typing errors) becomes the nearest
    // physical one, with a warning
    const Mat3 I_L = L.inertia.cast<real>();
    if (const std::optional<std::string> defect = physics::inertia_defect(I_L)) {
      L.inertia = physics::nearest_physical_inertia(I_L).cast<double>();
      const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(L.inertia).eigenvalues();
      warn(ie, "link " + in_quotes(L.name) + ": the inertia " + *defect + "; using the nearest physical inertia (principal moments " +
                   format_number(m[0]) + ", " + format_number(m[1]) + ", " + format_number(m[2]) + " kg m^2)");
    }
  }

  int link_of(const XMLElement* joint, const char* tag) const {
    const XMLElement* e = required_child(joint, tag);
    const std::string name = required_attribute(e, "link");
    const auto it = link_index_.find(name);
    if (it == link_index_.end()) fail(e, "refers to link " + in_quotes(name) + ", which is not defined");
    return it->second;
  }

  void read_joints() {
    std::set<std::string> names;
    for (const XMLElement* e = robot_->FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) {
      UrdfJoint J;
      J.element = e;
      J.name = required_attribute(e, "name");
      if (J.name.empty()) fail(e, "the joint name must not be empty");
      if (!names.insert(J.name).second) fail(e, "duplicate joint name " + in_quotes(J.name));
      J.type = required_attribute(e, "type");
      static const std::set<std::string> kKnown = {"revolute", "continuous", "prismatic", "fixed", "floating", "planar"};
      if (!kKnown.count(J.type))
        fail(e, "unknown joint type " + in_quotes(J.type) + " (expected revolute, continuous, prismatic, fixed or floating)");
      if (J.type == "planar")
        fail(e, "unsupported joint type 'planar' in joint " + in_quotes(J.name) +
                    " (SuperDex has no planar joint; model it with two prismatic and one revolute joint)");
      J.parent = link_of(e, "parent");
      J.child = link_of(e, "child");
      const int j = static_cast<int>(joints_.size());
      UrdfLink& child = links_[J.child];
      if (J.parent == J.child)
        fail(e, "the joints form a cycle: link " + in_quotes(child.name) + " is its own parent");
      if (child.parent_joint >= 0)
        fail(e, "link " + in_quotes(child.name) + " has two parents: it is the child of joint " +
                    in_quotes(joints_[child.parent_joint].name) + " and of joint " + in_quotes(J.name));
      child.parent_joint = j;
      links_[J.parent].child_joints.push_back(j);
      joints_.push_back(std::move(J));
    }
  }

  // The one link that is no joint's child; every link must be reachable from it.
  int find_root() const {
    std::vector<int> roots;
    for (size_t i = 0; i < links_.size(); ++i)
      if (links_[i].parent_joint < 0) roots.push_back(static_cast<int>(i));
    if (roots.size() > 1) {
      std::string names;
      for (int r : roots) names += (names.empty() ? "" : ", ") + in_quotes(links_[r].name);
      fail(robot_, "several root links (links that are no joint's child): " + names +
                       "; a robot must be one tree of links connected by joints");
    }
    // links not reachable from the root (or all links, without a root) lie on a cycle
    std::vector<bool> reached(links_.size(), false);
    if (!roots.empty()) {
      std::vector<int> stack{roots[0]};
      while (!stack.empty()) {
        const int l = stack.back();
        stack.pop_back();
        reached[l] = true;
        for (int j : links_[l].child_joints) stack.push_back(joints_[j].child);
      }
    }
    for (size_t i = 0; i < links_.size(); ++i) {
      if (reached[i]) continue;
      // walk up the parents until a link repeats: that loop is the cycle
      std::vector<int> seen_at(links_.size(), -1), path;
      int l = static_cast<int>(i);
      while (seen_at[l] < 0) {
        seen_at[l] = static_cast<int>(path.size());
        path.push_back(l);
        l = joints_[links_[l].parent_joint].parent;
      }
      std::string cycle;
      for (size_t k = seen_at[l]; k < path.size(); ++k) {
        const UrdfJoint& j = joints_[links_[path[k]].parent_joint];
        cycle += (cycle.empty() ? "" : ", ") + in_quotes(links_[path[k]].name) + " is the child of " +
                 in_quotes(links_[j.parent].name) + " (joint " + in_quotes(j.name) + ")";
      }
      fail(joints_[links_[l].parent_joint].element,
           std::string(roots.empty() ? "no root link: " : "") + "the joints form a cycle: " + cycle);
    }
    return roots[0];
  }

  // ------------------------------------------------------------------ mesh files

  // The file a URDF mesh filename refers to, or nullopt with the places looked at in `tried`.
  std::optional<fs::path> resolve_mesh(const std::string& filename, std::string* tried) const {
    std::vector<fs::path> candidates;
    // the rest of `filename` after a URI scheme prefix, if it has that prefix
    auto after = [&](const std::string& prefix) -> std::optional<std::string> {
      if (filename.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
      return filename.substr(prefix.size());
    };
    std::optional<std::string> rest = after("package://");
    if (!rest) rest = after("model://");
    if (rest) {
      const size_t slash = rest->find('/');
      const std::string pkg = rest->substr(0, slash);
      const std::string inside = slash == std::string::npos ? "" : rest->substr(slash + 1);
      // upward from the URDF's folder: a folder named pkg, or one that contains pkg
      for (fs::path d = dir_;; d = d.parent_path()) {
        if (d.filename() == pkg) candidates.push_back(d / inside);
        candidates.push_back(d / pkg / inside);
        if (d == d.parent_path() || d.empty()) break;
      }
      auto env_paths = [&](const char* var, const char* sub) {
        const char* v = std::getenv(var);
        if (!v) return;
        std::istringstream parts(v);
        std::string entry;
        while (std::getline(parts, entry, ':')) {
          if (entry.empty()) continue;
          const fs::path base = fs::path(entry) / sub;
          if (base.filename() == pkg) candidates.push_back(base / inside);
          candidates.push_back(base / pkg / inside);
        }
      };
      env_paths("ROS_PACKAGE_PATH", "");
      env_paths("AMENT_PREFIX_PATH", "share");
      *tried = "package " + in_quotes(pkg) + " searched upward from " + dir_.string() +
               " and in $ROS_PACKAGE_PATH and $AMENT_PREFIX_PATH";
    } else {
      fs::path p(after("file://").value_or(filename));
      if (p.is_relative()) p = dir_ / p;
      candidates.push_back(p);
      *tried = p.lexically_normal().string();
    }
    for (const fs::path& c : candidates) {
      std::error_code ec;
      if (fs::is_regular_file(c, ec)) return c.lexically_normal();
    }
    return std::nullopt;
  }

  Eigen::Vector3d mesh_scale(const XMLElement* mesh) const {
    if (!mesh->Attribute("scale")) return Eigen::Vector3d::Ones();
    const auto s = numbers(mesh, "scale", 0);
    if (s.size() != 1 && s.size() != 3)
      fail(mesh, "attribute 'scale': expected 3 numbers (or 1 for a uniform scale), got \"" +
                     std::string(mesh->Attribute("scale")) + "\"");
    const Eigen::Vector3d v = s.size() == 1 ? Eigen::Vector3d::Constant(s[0]) : Eigen::Vector3d(s[0], s[1], s[2]);
    if ((v.array() == 0).any() || !v.allFinite()) fail(mesh, "attribute 'scale' must be finite and non-zero (negative mirrors)");
    return v;
  }

  // `shape` mirrored across the planes of the axes where `sign` is -1: a mesh (scale_mesh), a
  // sphere's centre. Boxes (centred) and capsules (symmetric) stay as they are.
  static ShapeGeometry mirrored(ShapeGeometry shape, const Eigen::Vector3d& sign, const std::string& source) {
    const Vec3 s = sign.cast<real>();
    if (auto* sphere = std::get_if<physics::SphereShape>(&shape)) sphere->center = sphere->center.cwiseProduct(s);
    if (auto* mesh = std::get_if<physics::MeshShape>(&shape)) {
      physics::TriangleMesh m = *mesh->mesh;
      scale_mesh(m, s);
      return physics::make_mesh_shape(std::move(m), source);
    }
    return shape;
  }

  // The collider of a mesh file: read, scaled by `scale` (a negative component mirrors), then its
  // convex hull or the mesh itself as the options say.
  ShapeGeometry mesh_file_collider(const XMLElement* g, const fs::path& file, const Eigen::Vector3d& scale) const {
    physics::TriangleMesh m = physics::read_mesh_file(file.string());
    scale_mesh(m, scale.cast<real>());
    const std::string source = file.string() + ((scale.array() < 0).any() ? " (mirrored)" : "");
    std::string warning;
    ShapeGeometry shape = mesh_collider(std::move(m), source, options_.mesh_collision, &warning);
    if (!warning.empty()) warn(g, "collision mesh " + in_quotes(file.string()) + ": " + warning);
    return shape;
  }

  // ------------------------------------------------------------------ geometry

  // The collision shape of a <geometry>; nullopt (with a warning) for a mesh format that
  // cannot be a collider. Sets `shape_file` for meshes.
  std::optional<ShapeGeometry> collision_shape(const XMLElement* geometry, const std::string& link_name,
                                               std::string* shape_file) const {
    const XMLElement* g = geometry->FirstChildElement();
    if (!g) fail(geometry, "expected one of <box>, <sphere>, <cylinder> or <mesh>");
    const std::string kind = g->Name();
    if (kind == "box") {
      const Eigen::Vector3d size = vec3(g, "size");
      if ((size.array() <= 0).any()) fail(g, "attribute 'size' must be positive");
      return physics::BoxShape{(size / 2).cast<real>()};
    }
    if (kind == "sphere") return physics::SphereShape{Vec3::Zero(), real(positive(g, "radius"))};
    if (kind == "cylinder") {
      const double radius = positive(g, "radius"), length = positive(g, "length");
      return physics::make_mesh_shape(cylinder_mesh(radius, length),
                                      path_ + ": link " + in_quotes(link_name) + " <cylinder>");
    }
    if (kind == "capsule") return physics::CapsuleShape{real(positive(g, "radius")), real(positive(g, "length") / 2)};
    if (kind == "mesh") {
      const std::string filename = required_attribute(g, "filename");
      const Eigen::Vector3d scale = mesh_scale(g);
      std::string tried;
      const auto file = resolve_mesh(filename, &tried);
      if (!file) fail(g, "link " + in_quotes(link_name) + ": collision mesh " + in_quotes(filename) + " not found (" + tried + ")");
      // a negative scale mirrors: a .mochi.h5 shape is loaded at the scale's magnitude, then mirrored
      physics::ShapeBake bake;
      bake.scale = scale.cwiseAbs().cast<real>();
      std::string ext = file->extension().string();
      for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      const bool surface = physics::is_surface_mesh_file(file->string());
      try {
        *shape_file = file->string();
        if (surface) return mesh_file_collider(g, *file, scale);
        ShapeGeometry shape = physics::load_shape_file(file->string(), bake);
        if ((scale.array() < 0).any()) shape = mirrored(std::move(shape), scale.cwiseSign(), file->string() + " (mirrored)");
        return shape;
      } catch (const Error& e) {
        if (surface || ext == ".h5")
          fail(g, "link " + in_quotes(link_name) + ": collision mesh " + in_quotes(file->string()) + ": " + e.what());
        warn(g, "link " + in_quotes(link_name) + ": collision mesh " + in_quotes(file->string()) +
                    " is in an unsupported format (" + e.what() + "); the link has no collider");
        return std::nullopt;
      }
    }
    fail(g, "unknown geometry <" + kind + "> (expected <box>, <sphere>, <cylinder> or <mesh>)");
  }

  void read_geometry(const UrdfLink& U, LinkDesc& L) const {
    // every <collision>, each at its own origin: the first imported one is the link's shape,
    // the others collide with it as one body
    for (const XMLElement* c = U.element->FirstChildElement("collision"); c; c = c->NextSiblingElement("collision")) {
      std::string file;
      std::optional<ShapeGeometry> shape = collision_shape(required_child(c, "geometry"), U.name, &file);
      if (!shape) continue;
      const Transform X_LS = to_transform(origin_of(c));
      if (!L.shape) {
        L.shape = std::move(shape);
        L.link_from_shape = X_LS;
        L.shape_file = file;
      } else {
        L.extra_shapes.push_back({std::move(*shape), X_LS, file});
      }
    }
    for (const XMLElement* v = U.element->FirstChildElement("visual"); v; v = v->NextSiblingElement("visual")) {
      const XMLElement* geometry = v->FirstChildElement("geometry");
      const XMLElement* mesh = geometry ? geometry->FirstChildElement("mesh") : nullptr;
      if (!mesh) continue;
      const std::string filename = required_attribute(mesh, "filename");
      std::string tried;
      const auto file = resolve_mesh(filename, &tried);
      if (!file) {
        warn(mesh, "link " + in_quotes(U.name) + ": visual mesh " + in_quotes(filename) + " not found (" + tried +
                       "); the link has no render model");
        break;
      }
      L.render_model = file->string();
      L.render_model_scale = mesh_scale(mesh).cast<real>();
      if (!origin_of(v).isApprox(Eigen::Isometry3d::Identity(), 1e-12))
        warn(v, "link " + in_quotes(U.name) + ": the <origin> of the visual mesh is ignored (render models are drawn in the link frame)");
      break;
    }
  }

  // ------------------------------------------------------------------ joints

  JointDesc joint_desc(const UrdfJoint& J) const {
    const XMLElement* e = J.element;
    JointDesc d;
    d.name = J.name;
    d.parent_link_from_joint = to_transform(origin_of(e));
    if (J.type == "fixed") {
      d.type = JointType::Hard;
      return d;
    }
    if (J.type == "floating") {
      d.type = JointType::Free;
      return d;
    }
    d.type = J.type == "prismatic" ? JointType::Prismatic : JointType::Revolute;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    if (const XMLElement* a = e->FirstChildElement("axis")) {
      axis = vec3(a, "xyz");
      if (axis.norm() < 1e-12) fail(a, "the joint axis must not be zero");
      axis.normalize();
    }
    d.axis = axis.cast<real>();
    const XMLElement* limit = e->FirstChildElement("limit");
    if (J.type != "continuous") {
      if (!limit) fail(e, "a " + J.type + " joint needs a <limit> (use type=\"continuous\" for an unlimited revolute joint)");
      const double lower = limit->Attribute("lower") ? number(limit, "lower") : 0.0;
      const double upper = limit->Attribute("upper") ? number(limit, "upper") : 0.0;
      if (!limit->Attribute("lower") && !limit->Attribute("upper"))
        warn(limit, "no lower or upper limit: the joint is limited to [0, 0] (URDF defaults)");
      if (lower > upper)
        fail(limit, "the lower limit " + format_number(lower) + " exceeds the upper limit " + format_number(upper));
      d.min_limit = (axis * lower).cast<real>();
      d.max_limit = (axis * upper).cast<real>();
    }
    if (limit) {
      const double effort = number(limit, "effort");
      if (effort < 0) fail(limit, "attribute 'effort' must not be negative, got " + format_number(effort));
      d.effort_limit = real(effort);
      number(limit, "velocity");  // required by URDF; the engine has no velocity limit
    }
    if (const XMLElement* dyn = e->FirstChildElement("dynamics")) {
      if (dyn->Attribute("damping")) d.viscous_friction = real(number(dyn, "damping"));
      if (dyn->Attribute("friction")) d.coulomb_friction = real(number(dyn, "friction"));
      if (d.viscous_friction < 0 || d.coulomb_friction < 0) fail(dyn, "damping and friction must not be negative");
    }
    return d;
  }

  // Whether the rigid body a link belongs to (the link and the links welded to it by fixed
  // joints, all the way down) has mass.
  // Whether the link or a link below it has mass: the bodies a joint moves.
  bool subtree_has_mass(int l) const {
    if (links_[l].has_mass) return true;
    for (int j : links_[l].child_joints)
      if (subtree_has_mass(joints_[j].child)) return true;
    return false;
  }

  // ------------------------------------------------------------------ assembly

  BotPrefab build(int root) {
    // a "world" root that is nothing but the world: its single fixed or floating joint
    // becomes the root joint of the robot's base
    int root_joint = -1;
    {
      const UrdfLink& r = links_[root];
      if (r.name == "world" && !r.has_mass && !r.element->FirstChildElement("collision") && r.child_joints.size() == 1) {
        const UrdfJoint& j = joints_[r.child_joints[0]];
        if (j.type == "fixed" || j.type == "floating") {
          root_joint = r.child_joints[0];
          root = j.child;
        }
      }
    }
    for (const UrdfJoint& j : joints_)
      if (j.type == "floating" && &j != (root_joint >= 0 ? &joints_[root_joint] : nullptr))
        fail(j.element, "floating joint " + in_quotes(j.name) +
                            " is only supported as the robot's root joint (its parent must be a root link named "
                            "'world' that has no mass, no collision and no other joint)");

    // depth-first order from the root, children in document order
    std::vector<int> order, index_of(links_.size(), -1);
    std::vector<int> stack{root};
    while (!stack.empty()) {
      const int l = stack.back();
      stack.pop_back();
      index_of[l] = static_cast<int>(order.size());
      order.push_back(l);
      const auto& cj = links_[l].child_joints;
      for (auto it = cj.rbegin(); it != cj.rend(); ++it) stack.push_back(joints_[*it].child);
    }

    BotPrefab prefab;
    prefab.source = path_;
    prefab.base_dir = dir_.string();
    physics::ArticulationDesc& art = prefab.articulation;
    art.name = robot_name_;
    std::set<std::string> joint_names;
    for (const UrdfJoint& j : joints_) joint_names.insert(j.name);

    // the default pose: zero, except for joints whose limits exclude zero (set by start_inside_limits)
    std::vector<real> default_pose;
    bool pose_moved = false;
    for (size_t k = 0; k < order.size(); ++k) {
      const UrdfLink& U = links_[order[k]];
      LinkDesc L;
      L.name = U.name;
      JointDesc J;
      if (k == 0) {
        L.parent_link = -1;
        if (root_joint >= 0) {
          J = joint_desc(joints_[root_joint]);
        } else {
          // the joint to the world: floating unless the caller fixes the base; a root link
          // named "world" is the world's own frame, welded
          J.type = options_.fixed_base || U.name == "world" ? JointType::Hard : JointType::Free;
          J.name = "world_joint";
          for (int n = 1; joint_names.count(J.name); ++n) J.name = "world_joint_" + std::to_string(n);
        }
      } else {
        const UrdfJoint& uj = joints_[U.parent_joint];
        L.parent_link = index_of[uj.parent];
        J = joint_desc(uj);
        pose_moved |= start_inside_limits(uj, J, default_pose);
      }
      read_geometry(U, L);
      if (U.has_mass) {
        L.mass = real(U.mass);
        L.center_of_mass = U.com.cast<real>();
        const Eigen::Matrix3d& I = U.inertia;
        L.moment_of_inertia = std::array<real, 6>{real(I(0, 0)), real(I(0, 1)), real(I(0, 2)),
                                                  real(I(1, 1)), real(I(1, 2)), real(I(2, 2))};
      } else if (J.type != JointType::Hard && !subtree_has_mass(order[k])) {
        // (a root on a Hard joint never gets here; a Free root's joint is the dropped world's,
        // or the floating base's, which has no element: the link is named instead)
        const int joint = k == 0 ? root_joint : U.parent_joint;
        const XMLElement* where = joint >= 0 ? joints_[joint].element : U.element;
        // a moving link that carries no mass at all: its mass comes from its collision shape
        // at the density of water, as MuJoCo's inertiafromgeom does; without a closed shape
        // there is no rule left
        if (!has_volume(L.shape))
          fail(where, "link " + in_quotes(U.name) + " has no inertial but moves on joint " + in_quotes(J.name) +
                          ", and neither a closed collision shape nor any link it carries gives it mass (give it an <inertial> with a "
                          "positive mass, or make the joint fixed)");
        L.density = real(kInertiaFromGeometryDensity);
        warn(where, "link " + in_quotes(U.name) + " has no inertial but moves on joint " + in_quotes(J.name) +
                        ": its mass and inertia are computed from its collision shape at " +
                        std::to_string(static_cast<int>(kInertiaFromGeometryDensity)) + " kg/m^3");
      } else {
        const real I0 = real(kMasslessLinkInertia);
        L.mass = real(kMasslessLinkMass);
        L.center_of_mass = Vec3::Zero();
        L.moment_of_inertia = std::array<real, 6>{I0, 0, 0, I0, 0, I0};
      }
      art.links.push_back(std::move(L));
      art.joints.push_back(std::move(J));
    }
    if (pose_moved) art.default_pose = std::move(default_pose);
    read_mimics(art);
    prefab.sensors.resize(art.links.size());
    prefab.actuators.resize(art.links.size());
    if (options_.exclude_overlapping_links) exclude_overlaps(art);
    return prefab;
  }

  // <mimic joint multiplier offset>: the joint follows the named one, q = multiplier q_leader +
  // offset (defaults 1 and 0), as a coupling held by the step.
  void read_mimics(physics::ArticulationDesc& art) const {
    for (const UrdfJoint& J : joints_) {
      const XMLElement* m = J.element->FirstChildElement("mimic");
      if (!m) continue;
      const std::string leader = required_attribute(m, "joint");
      // robot files ship broken mimics (a leader misspelled, a joint made fixed in a reduced
      // model): the robot still loads, the joint moves on its own, and a warning says why
      auto moving = [](const std::string& type) { return type == "revolute" || type == "continuous" || type == "prismatic"; };
      const auto lj = std::find_if(joints_.begin(), joints_.end(), [&](const UrdfJoint& u) { return u.name == leader; });
      std::string why;
      if (lj == joints_.end()) why = "it refers to joint " + in_quotes(leader) + ", which is not defined";
      else if (!moving(J.type)) why = "joint " + in_quotes(J.name) + " is " + J.type;
      else if (!moving(lj->type)) why = "the joint it follows, " + in_quotes(leader) + ", is " + lj->type;
      if (!why.empty()) {
        warn(m, "<mimic> is ignored: " + why + " (only revolute, continuous and prismatic joints can follow each other)");
        continue;
      }
      physics::JointCoupling c;
      c.joint = J.name;
      c.leader = leader;
      c.ratio = real(m->Attribute("multiplier") ? number(m, "multiplier") : 1.0);
      c.offset = real(m->Attribute("offset") ? number(m, "offset") : 0.0);
      art.couplings.push_back(std::move(c));
    }
  }

  // Appends joint J's default positions to `pose`: zero, or for a revolute or prismatic joint whose
  // limits exclude zero (an arm whose elbow range is [0.33, 5.95] rad) the nearest limit, with a
  // warning, so that the robot does not start violating its limits. Returns whether it moved.
  bool start_inside_limits(const UrdfJoint& uj, const JointDesc& J, std::vector<real>& pose) const {
    const int nv = physics::joint_num_dofs(J.type);
    if ((J.type != JointType::Revolute && J.type != JointType::Prismatic) || !J.min_limit || !J.max_limit) {
      pose.insert(pose.end(), static_cast<size_t>(nv), real(0));
      return false;
    }
    const real lower = J.axis.dot(*J.min_limit), upper = J.axis.dot(*J.max_limit);
    const real q0 = std::clamp(real(0), lower, upper);
    pose.push_back(q0);
    if (q0 == 0) return false;
    warn(uj.element, "zero lies outside the joint's limits [" + format_number(lower) + ", " + format_number(upper) +
                         "]: the robot starts with the joint at " + format_number(q0));
    return true;
  }

  // Link pairs whose collision shapes already interpenetrate at the zero configuration would push
  // on each other from the first step: they are switched off, named in one warning.
  void exclude_overlaps(physics::ArticulationDesc& art) const {
    const auto overlaps = physics::overlapping_link_pairs(art, 0, path_);
    if (overlaps.empty()) return;
    std::string names;
    for (size_t k = 0; k < overlaps.size(); ++k) {
      const auto& o = overlaps[k];
      art.contact_overrides.push_back({art.links[o.link_a].name, art.links[o.link_b].name, false});
      if (k < 8) names += (k ? ", (" : "(") + in_quotes(art.links[o.link_a].name) + ", " + in_quotes(art.links[o.link_b].name) + ")";
    }
    if (overlaps.size() > 8) names += ", ...";
    warn(robot_, std::to_string(overlaps.size()) + " pair(s) of links whose collision shapes overlap at the zero configuration "
                 "do not collide with each other: " + names + " (exclude_overlapping_links=False keeps them colliding)");
  }

  std::string path_;
  fs::path dir_;
  std::vector<std::string>* warnings_;
  UrdfImportOptions options_;
  tinyxml2::XMLDocument doc_;
  const XMLElement* robot_ = nullptr;
  std::string robot_name_;
  std::vector<UrdfLink> links_;
  std::vector<UrdfJoint> joints_;
  std::map<std::string, int> link_index_;
};

}  // namespace

BotPrefab load_bot_prefab_from_urdf(const std::string& path, std::vector<std::string>* warnings, const UrdfImportOptions& options) {
  return UrdfImporter(path, warnings, options).run();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
