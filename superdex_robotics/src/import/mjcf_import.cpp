// MJCF import: a <mujoco> model's kinematic trees as bots (mjcf_import.h), with MuJoCo's mass
// properties, so that the joint-space mass matrix and bias forces equal MuJoCo's.
//
// Mapping
//  * Bodies are visited depth-first in document order (MuJoCo's body order); the joints of a
//    body in document order are MuJoCo's DOF order, and the links are created in that order.
//  * A body with one joint is one link on that joint. A body with several joints (a humanoid's
//    hip: three hinges) is a chain: one link per joint, the last one named after the body and
//    carrying its mass and geoms, the ones before it named "<body>/<joint>" with a negligible
//    mass (kNegligibleFraction): MuJoCo composes the joints of a body in the same order.
//    A body without joints is welded to its parent (a Hard joint named "<body>/weld").
//  * Joint frames: MuJoCo rotates a body about each joint's anchor (`pos`, body frame). The
//    joint frame is at the anchor with the body's orientation (parent_link_from_joint), and
//    the link frame sits at -pos from it (joint_from_link), so that the link frame is the body
//    frame. hinge -> Revolute, slide -> Prismatic, ball -> Spherical, free -> Free (top-level
//    bodies only: a bot of its own). `range` (degrees under compiler angle="degree") limits
//    hinge and slide joints when `limited` is true, or auto with compiler autolimits, narrowed
//    by the joint's `margin` (where MuJoCo's limit comes to rest);
//    `armature`, `damping` and `frictionloss` map to armature, viscous and Coulomb friction.
//    A joint `ref` turns (shifts) the joint frame back by ref: joint positions are MuJoCo's
//    qpos, and the bot starts at MuJoCo's qpos0 (ref) in its default pose.
//  * Mass: <inertial> (pos, orientation, mass, diaginertia or fullinertia), or, per compiler
//    inertiafromgeom, the geoms of the body whose group lies in inertiagrouprange, each of
//    `mass` or `density` (default 1000 kg/m^3) times its volume, with MuJoCo's formulas for
//    spheres, capsules, cylinders, ellipsoids and boxes and the enclosed solid of meshes.
//    compiler boundmass, boundinertia and settotalmass apply as in MuJoCo.
//  * Geoms that collide (contype or conaffinity non-zero) become the link's shapes at their
//    pose: sphere, capsule, box and plane as such, cylinders as 48-sided prisms, ellipsoids as
//    meshes, meshes (.stl, .obj, .ply through the mesh readers, MuJoCo's .msh, or inline
//    vertex/face) as their convex hull (as MuJoCo collides them) or as triangles. Link pairs
//    none of whose geoms pass MuJoCo's contype/conaffinity test do not collide; bodies that
//    hang by a joint from the world's rigid body collide with it, as in MuJoCo (only
//    parent-child pairs below the world are filtered). <contact><exclude> switches pairs off, and
//    so do pairs whose shapes already interpenetrate at the start pose (limbs drawn to meet at
//    their joint), named in a warning.
//  * Joint actuators (<motor>, <position>, <velocity>, <general> of those kinds) become IDEAL_PD
//    actuators on their joint's link (read_actuators says how).
//  * <equality><joint> (q1 = c0 + c1 q2) becomes a joint coupling (JointCoupling).
//  * <tendon><fixed> becomes a FixedTendon (length range, spring and damper); joint springs
//    (stiffness, springref) become one-joint tendons (read_tendons).
//  * Not imported, named in warnings: other actuators, spatial tendons, other equality constraints,
//    sensors, <contact><pair>, height fields.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <tuple>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <cmath>
#include <sstream>

#include "import/import_support.h"
#include "import/mjcf_document.h"
#include "import/mjcf_mesh.h"
#include "superdex/physics/convex_hull.h"
#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"
#include "superdex/physics/inertia.h"
#include "superdex/physics/link_overlaps.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/robotics/mjcf_import.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;
using physics::JointDesc;
using physics::JointType;
using physics::LinkDesc;
using physics::real;
using physics::ShapeGeometry;
using physics::Transform;
using physics::Vec3;
using tinyxml2::XMLElement;

namespace {

// Links that carry nothing (the intermediate links of a multi-joint body, massless bodies, the
// world) get this fraction of the model's smallest body mass and principal moment: negligible
// at any scale, from a fly (1e-6 kg) to a truck, yet nonzero so that every link has a valid inertia.
constexpr double kNegligibleFraction = 1e-9;

Eigen::Isometry3d translation(const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = p;
  return X;
}

// Mass, centre of mass and rotational inertia about it, in one frame.
struct Mass {
  double mass = 0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

// `parts` (each in the same frame) lumped into one body.
Mass combine(const std::vector<Mass>& parts) {
  Mass out;
  for (const Mass& p : parts) {
    out.mass += p.mass;
    out.com += p.mass * p.com;
  }
  if (out.mass <= 0) return Mass{};
  out.com /= out.mass;
  for (const Mass& p : parts) {
    const Eigen::Vector3d d = p.com - out.com;
    out.inertia += p.inertia + p.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return out;
}

// A mesh asset: its file or inline data, loaded on first use, and its collider.
struct MeshAsset {
  const XMLElement* element = nullptr;
  fs::path file;  // empty for inline vertex/face data
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  std::string inertia = "legacy";
  std::shared_ptr<const physics::TriangleMesh> mesh;
  std::optional<ShapeGeometry> collider;
};

// Where a body's link lives: bot index and link index in it.
struct LinkRef {
  int bot = 0, link = 0;
};

// A collision geom's MuJoCo contact filter bits.
struct Filter {
  int contype = 1, conaffinity = 1;
};

// What the importer keeps for a bot beside its prefab while building it.
struct BotBuild {
  std::vector<std::vector<Filter>> filters;  // per link: the contact filters of its collision geoms
  std::vector<Mass> masses;                  // per link
  std::vector<real> default_pose;            // MuJoCo's qpos0 in DOF order, the root's DOFs excluded
  std::set<std::string> link_names, actuator_names;
};

// An element found in a body, with the frame it sits in (body frame) and its class.
struct Placed {
  const XMLElement* element;
  Eigen::Isometry3d X_BF;  // the enclosing <frame>s' pose in the body frame
  std::string cls;
};

// A geom's type, sizes (MuJoCo's size, fromto resolved), mesh and pose in its body's frame.
struct GeomShape {
  std::string type, mesh;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Isometry3d X_BG = Eigen::Isometry3d::Identity();
};

// A geom as found in its body, and its shape, read once for its mass and its collider.
struct Geom {
  Placed placed;
  GeomShape shape;
};

class MjcfImporter {
 public:
  MjcfImporter(const std::string& path, std::vector<std::string>* warnings, const MjcfImportOptions& options)
      : doc_(path, warnings), options_(options) {}

  MjcfModel run() {
    const XMLElement* root = doc_.root();
    const char* model_name = root->Attribute("model");
    model_.name = model_name && *model_name ? model_name : fs::path(doc_.path()).stem().string();
    read_option();
    read_assets();
    // the world: a welded root link that carries the worldbody's geoms
    const int world = new_bot(model_.name, Transform{});
    LinkDesc wl;
    wl.name = unique_link_name(world, "world");
    JointDesc wj;
    wj.name = "world_joint";
    wj.type = JointType::Hard;
    body_link_["world"] = {world, add_link(world, std::move(wl), std::move(wj))};
    for (const XMLElement* wb = root->FirstChildElement("worldbody"); wb; wb = wb->NextSiblingElement("worldbody")) visit_world(wb);
    read_contact();
    note_unsupported();
    apply_total_mass();
    find_smallest_mass();
    for (size_t b = 0; b < model_.bots.size(); ++b) finish(static_cast<int>(b));
    read_actuators();
    read_equalities();
    read_tendons();
    // a world with nothing on it is left out
    const auto& w = model_.bots[0].articulation;
    if (w.links.size() == 1 && !w.links[0].shape && model_.bots.size() > 1) model_.bots.erase(model_.bots.begin());
    for (const auto& [what, names] : notes_) {
      std::string list;
      for (size_t k = 0; k < names.size() && k < 8; ++k) list += (k ? ", " : "") + in_quotes(names[k]);
      if (names.size() > 8) list += ", ...";
      doc_.warn(root, what + (list.empty() ? "" : ": " + list));
    }
    return std::move(model_);
  }

 private:
  // ------------------------------------------------------------------ option, assets

  void read_option() {
    for (const XMLElement* o = doc_.root()->FirstChildElement("option"); o; o = o->NextSiblingElement("option")) {
      if (const auto g = doc_.numbers(o, "gravity", "", 3)) model_.gravity = Vec3(real((*g)[0]), real((*g)[1]), real((*g)[2]));
      if (const auto t = doc_.numbers(o, "timestep", "", 1)) {
        if (!((*t)[0] > 0)) doc_.fail(o, "attribute 'timestep' must be positive");
        model_.timestep = real((*t)[0]);
      }
      // <flag gravity="disable"/> switches gravity off
      for (const XMLElement* f = o->FirstChildElement("flag"); f; f = f->NextSiblingElement("flag"))
        if (const char* g = f->Attribute("gravity"); g && std::string(g) == "disable") model_.gravity.setZero();
    }
  }

  void read_assets() {
    for (const XMLElement* a = doc_.root()->FirstChildElement("asset"); a; a = a->NextSiblingElement("asset"))
      for (const XMLElement* m = a->FirstChildElement("mesh"); m; m = m->NextSiblingElement("mesh")) {
        MeshAsset asset;
        asset.element = m;
        const char* file = doc_.attr(m, "file", "");
        const char* name = m->Attribute("name");
        if (!file && !m->Attribute("vertex")) doc_.fail(m, "a mesh needs a 'file' or inline 'vertex' data");
        std::string key = name ? name : "";
        if (file) {
          fs::path p(file);
          if (p.is_relative()) p = doc_.dir() / doc_.compiler().meshdir / p;
          asset.file = p.lexically_normal();
          if (key.empty()) key = fs::path(file).stem().string();
        }
        if (key.empty()) doc_.fail(m, "a mesh with inline data needs a 'name'");
        if (const auto s = doc_.numbers(m, "scale", "", 3)) asset.scale = Eigen::Vector3d((*s)[0], (*s)[1], (*s)[2]);
        if (const char* in = doc_.attr(m, "inertia", "")) asset.inertia = in;
        if (asset.scale.cwiseAbs().minCoeff() == 0) doc_.fail(m, "attribute 'scale' must be non-zero");
        if (m->Attribute("refpos") || m->Attribute("refquat")) doc_.warn(m, "refpos and refquat are ignored");
        if (!meshes_.emplace(key, std::move(asset)).second) doc_.fail(m, "duplicate mesh name " + in_quotes(key));
      }
  }

  // The triangles of mesh asset `name` (scale applied), read on first use.
  MeshAsset& mesh_asset(const XMLElement* geom, const std::string& name) {
    const auto it = meshes_.find(name);
    if (it == meshes_.end()) doc_.fail(geom, "refers to mesh " + in_quotes(name) + ", which is not defined in <asset>");
    MeshAsset& a = it->second;
    if (a.mesh) return a;
    physics::TriangleMesh m;
    const XMLElement* e = a.element;
    if (!a.file.empty()) {
      if (!is_existing_file(a.file.string())) doc_.fail(e, "mesh file " + in_quotes(a.file.string()) + " not found");
      std::string ext = a.file.extension().string();
      for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      try {
        m = ext == ".msh" ? read_msh_file(a.file.string()) : physics::read_mesh_file(a.file.string());
      } catch (const Error& err) {
        doc_.fail(e, std::string("mesh file: ") + err.what());
      }
    } else {
      const auto v = doc_.numbers(e, "vertex", "", 0);
      if (v->size() % 3) doc_.fail(e, "attribute 'vertex': the number of values must be a multiple of 3");
      for (size_t k = 0; k + 2 < v->size(); k += 3) m.vertices.push_back(Vec3(real((*v)[k]), real((*v)[k + 1]), real((*v)[k + 2])));
      if (const auto f = doc_.numbers(e, "face", "", 0)) {
        if (f->size() % 3) doc_.fail(e, "attribute 'face': the number of values must be a multiple of 3");
        for (size_t k = 0; k + 2 < f->size(); k += 3) {
          std::array<int, 3> t{static_cast<int>((*f)[k]), static_cast<int>((*f)[k + 1]), static_cast<int>((*f)[k + 2])};
          for (int i : t)
            if (i < 0 || i >= static_cast<int>(m.vertices.size())) doc_.fail(e, "attribute 'face' refers to a vertex that does not exist");
          m.triangles.push_back(t);
        }
      }
    }
    scale_mesh(m, a.scale.cast<real>());
    // MuJoCo uses the convex hull of a mesh given without faces
    if (m.triangles.empty()) m = physics::convex_hull(m.vertices, doc_.path() + ": mesh " + in_quotes(name));
    a.mesh = std::make_shared<const physics::TriangleMesh>(std::move(m));
    return a;
  }

  // ------------------------------------------------------------------ bodies

  // The elements of body (or frame) `e`, with <frame> children flattened into their poses.
  void collect(const XMLElement* e, const Eigen::Isometry3d& X_BF, const std::string& cls, std::vector<Placed>& geoms,
               std::vector<Placed>& bodies) const {
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if (tag == "geom") geoms.push_back({c, X_BF, cls});
      else if (tag == "body") bodies.push_back({c, X_BF, cls});
      else if (tag == "frame") collect(c, X_BF * doc_.pose(c, cls), doc_.child_class(c, cls), geoms, bodies);
      else if (tag == "replicate" || tag == "composite" || tag == "flexcomp")
        doc_.warn(c, "<" + tag + "> is not supported: its bodies and geoms are not imported");
    }
  }

  // The geoms found in a body with their shapes.
  std::vector<Geom> shapes_of(const std::vector<Placed>& placed) const {
    std::vector<Geom> out;
    for (const Placed& g : placed) out.push_back({g, geom_shape(g)});
    return out;
  }

  void visit_world(const XMLElement* wb) {
    std::vector<Placed> geoms, bodies;
    const std::string cls = doc_.child_class(wb, "");
    collect(wb, Eigen::Isometry3d::Identity(), cls, geoms, bodies);
    add_geoms({0, 0}, shapes_of(geoms), /*moving=*/false);
    for (const Placed& b : bodies) visit_body(b.element, {0, 0}, b.X_BF * doc_.pose(b.element, b.cls), b.cls, true, true);
  }

  std::string unique_link_name(int bot, const std::string& base) {
    std::string name = base;
    auto& names = builds_[bot].link_names;
    for (int n = 1; names.count(name); ++n) name = base + "_" + std::to_string(n);
    names.insert(name);
    return name;
  }

  // Adds an empty bot placed at X_WR; returns its index.
  int new_bot(const std::string& name, const Transform& X_WR) {
    BotPrefab bot;
    bot.articulation.name = name;
    bot.articulation.world_from_root = X_WR;
    model_.bots.push_back(std::move(bot));
    builds_.emplace_back();
    return static_cast<int>(model_.bots.size()) - 1;
  }

  // Adds a link to `bot` on joint `J`; returns its index.
  int add_link(int bot, LinkDesc L, JointDesc J) {
    auto& art = model_.bots[bot].articulation;
    art.links.push_back(std::move(L));
    art.joints.push_back(std::move(J));
    builds_[bot].filters.emplace_back();
    builds_[bot].masses.push_back(Mass{});
    return static_cast<int>(art.links.size()) - 1;
  }

  // `top`: a child of the world; `parent_static`: the parent is welded to the world.
  void visit_body(const XMLElement* b, LinkRef parent, const Eigen::Isometry3d& X_PB, const std::string& inherited, bool top,
                  bool parent_static) {
    const std::string cls = doc_.child_class(b, inherited);
    const int body_id = ++body_count_;
    const char* n = b->Attribute("name");
    const std::string name = n && *n ? n : "body" + std::to_string(body_id);
    std::vector<Placed> geoms, bodies;
    collect(b, Eigen::Isometry3d::Identity(), cls, geoms, bodies);
    std::vector<const XMLElement*> joints;
    for (const XMLElement* c = b->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if (tag == "joint" || tag == "freejoint") joints.push_back(c);
    }
    if (const char* g = b->Attribute("gravcomp"); g && std::atof(g) != 0) notes_["gravity compensation (gravcomp) is not imported"].push_back(name);

    LinkRef at = parent;
    Eigen::Isometry3d X_PJ_pending = X_PB;  // the next joint's frame in the current parent link
    for (size_t k = 0; k < joints.size(); ++k) {
      const XMLElement* je = joints[k];
      const bool last = k + 1 == joints.size();
      const int joint_id = joint_count_++;
      const char* jn = je->Attribute("name");
      const std::string jname = jn && *jn ? jn : "joint" + std::to_string(joint_id);
      const char* given = doc_.attr(je, "type", cls);
      const std::string type = std::string(je->Name()) == "freejoint" ? "free" : (given ? given : "hinge");
      if (type == "free") {
        if (!top || joints.size() > 1 || parent.bot != 0 || parent.link != 0)
          doc_.fail(je, "a free joint must be the only joint of a body that is a child of the world");
        const int bi = new_bot(name, to_transform(X_PB));
        LinkDesc L;
        L.name = unique_link_name(bi, name);
        JointDesc J;
        J.name = jname;
        J.type = JointType::Free;
        at = {bi, add_link(bi, std::move(L), std::move(J))};
        break;
      }
      JointDesc J;
      J.name = jname;
      read_joint(je, cls, type, J);
      const Eigen::Vector3d pos = doc_.vec3_or(je, "pos", cls, Eigen::Vector3d::Zero());
      // MuJoCo moves the body by (q - ref): the joint frame is turned (shifted) back by ref, so
      // that q means what it means in MuJoCo, and the bot starts at q = ref, MuJoCo's qpos0
      const double ref = J.type == JointType::Spherical ? 0.0 : doc_.number_or(je, "ref", cls, 0);
      const double ref_q = J.type == JointType::Revolute ? doc_.angle(ref) : ref;
      const Eigen::Vector3d axis = J.axis.cast<double>();
      Eigen::Isometry3d X_ref = Eigen::Isometry3d::Identity();
      if (J.type == JointType::Revolute) X_ref.linear() = Eigen::AngleAxisd(-ref_q, axis).toRotationMatrix();
      else if (J.type == JointType::Prismatic) X_ref.translation() = -ref_q * axis;
      J.parent_link_from_joint = to_transform(X_PJ_pending * translation(pos) * X_ref);
      LinkDesc L;
      L.name = unique_link_name(at.bot, last ? name : name + "/" + jname);
      L.parent_link = at.link;
      L.joint_from_link = (-pos).cast<real>();
      auto& pose = builds_[at.bot].default_pose;
      if (J.type == JointType::Spherical) pose.insert(pose.end(), 3, real(0));
      else pose.push_back(real(ref_q));
      at.link = add_link(at.bot, std::move(L), std::move(J));
      joint_link_[jname] = at;
      X_PJ_pending = Eigen::Isometry3d::Identity();
    }
    if (joints.empty()) {
      LinkDesc L;
      L.name = unique_link_name(at.bot, name);
      L.parent_link = at.link;
      JointDesc J;
      J.name = name + "/weld";
      J.type = JointType::Hard;
      J.parent_link_from_joint = to_transform(X_PB);
      at.link = add_link(at.bot, std::move(L), std::move(J));
    }
    body_link_[name] = at;
    const std::vector<Geom> shaped = shapes_of(geoms);
    body_mass(b, cls, shaped, at);
    const bool is_static = parent_static && joints.empty();
    add_geoms(at, shaped, !is_static);
    for (const Placed& c : bodies) visit_body(c.element, at, c.X_BF * doc_.pose(c.element, c.cls), c.cls, false, is_static);
  }

  // MuJoCo's limit (of a joint or a tendon) acts from the element's `margin` inside the range
  // [lo, hi] and comes to rest there: the range narrowed by it (unless that would empty it).
  void narrow_by_margin(const XMLElement* e, const std::string& cls, double& lo, double& hi) const {
    const double margin = doc_.number_or(e, "margin", cls, 0);
    if (margin < 0) doc_.fail(e, "margin must not be negative");
    if (lo + margin <= hi - margin) lo += margin, hi -= margin;
  }

  void read_joint(const XMLElement* je, const std::string& cls, const std::string& type, JointDesc& J) {
    if (type == "hinge") J.type = JointType::Revolute;
    else if (type == "slide") J.type = JointType::Prismatic;
    else if (type == "ball") J.type = JointType::Spherical;
    else doc_.fail(je, "unknown joint type " + in_quotes(type) + " (expected hinge, slide, ball or free)");
    Eigen::Vector3d axis = doc_.vec3_or(je, "axis", cls, Eigen::Vector3d::UnitZ());
    if (axis.norm() < 1e-12) doc_.fail(je, "the joint axis must not be zero");
    axis.normalize();
    J.axis = axis.cast<real>();
    const auto range = doc_.numbers(je, "range", cls, 2);
    const std::optional<bool> limited = doc_.boolean(je, "limited", cls);
    const bool is_limited = limited ? *limited : (doc_.compiler().autolimits && range.has_value());
    if (is_limited && J.type != JointType::Spherical) {
      if (!range) doc_.fail(je, "a limited joint needs a 'range'");
      double lo = (*range)[0], hi = (*range)[1];
      if (J.type == JointType::Revolute) lo = doc_.angle(lo), hi = doc_.angle(hi);
      if (lo > hi) doc_.fail(je, "attribute 'range': the lower limit " + format_number(lo) + " exceeds the upper limit " + format_number(hi));
      narrow_by_margin(je, cls, lo, hi);
      J.min_limit = (axis * lo).cast<real>();
      J.max_limit = (axis * hi).cast<real>();
    } else if (is_limited) {
      notes_["ball joint ranges are not imported"].push_back(J.name);
    }
    J.armature = real(doc_.number_or(je, "armature", cls, 0));
    J.viscous_friction = real(doc_.number_or(je, "damping", cls, 0));
    J.coulomb_friction = real(doc_.number_or(je, "frictionloss", cls, 0));
    if (J.armature < 0 || J.viscous_friction < 0 || J.coulomb_friction < 0)
      doc_.fail(je, "armature, damping and frictionloss must not be negative");
    // a joint spring -k (q - springref) is a one-joint tendon (read_tendons adds it); springref is
    // also where tendon springs are relaxed by default
    const double stiffness = doc_.number_or(je, "stiffness", cls, 0);
    if (stiffness < 0) doc_.fail(je, "stiffness must not be negative");
    if (J.type == JointType::Spherical) {
      if (stiffness > 0) notes_["ball joint springs are not imported"].push_back(J.name);
      return;
    }
    const double springref = doc_.number_or(je, "springref", cls, 0);
    joint_springref_[J.name] = J.type == JointType::Revolute ? doc_.angle(springref) : springref;
    if (stiffness > 0) joint_springs_.push_back({J.name, stiffness});
  }

  // ------------------------------------------------------------------ mass

  // The mass properties of `m`, or negligible ones (see kNegligibleFraction) for a massless body.
  void set_mass(LinkDesc& L, const Mass& m) const {
    if (m.mass <= 0) {
      L.mass = real(kNegligibleFraction * smallest_mass_);
      L.center_of_mass = Vec3::Zero();
      const real I0 = real(kNegligibleFraction * smallest_moment_);
      L.moment_of_inertia = std::array<real, 6>{I0, 0, 0, I0, 0, I0};
      return;
    }
    const Eigen::Matrix3d& I = m.inertia;
    L.mass = real(m.mass);
    L.center_of_mass = m.com.cast<real>();
    L.moment_of_inertia = std::array<real, 6>{real(I(0, 0)), real(I(0, 1)), real(I(0, 2)), real(I(1, 1)), real(I(1, 2)), real(I(2, 2))};
  }

  // The smallest body mass and principal moment of the model (1 kg and 1 kg m^2 when none has mass).
  void find_smallest_mass() {
    for (const BotBuild& b : builds_)
      for (const Mass& m : b.masses) {
        if (m.mass <= 0) continue;
        smallest_mass_ = std::min(smallest_mass_, m.mass);
        const double moment = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m.inertia).eigenvalues().minCoeff();
        if (moment > 0) smallest_moment_ = std::min(smallest_moment_, moment);
      }
    if (!std::isfinite(smallest_mass_)) smallest_mass_ = 1;
    if (!std::isfinite(smallest_moment_)) smallest_moment_ = 1;
  }

  // The mass properties of geom `g` (in the body frame), or nullopt when it gives none.
  std::optional<Mass> geom_mass(const Geom& geom) {
    const Placed& g = geom.placed;
    const GeomShape& s = geom.shape;
    const XMLElement* e = g.element;
    const int group = static_cast<int>(doc_.number_or(e, "group", g.cls, 0));
    const auto& c = doc_.compiler();
    if (group < c.inertia_group_min || group > c.inertia_group_max) return std::nullopt;
    if (s.type == "plane" || s.type == "hfield" || s.type == "sdf") return std::nullopt;
    double volume = 0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    Eigen::Matrix3d unit = Eigen::Matrix3d::Zero();  // inertia per unit density about com, geom frame
    const Eigen::Vector3d& z = s.size;
    constexpr double pi = EIGEN_PI;
    if (s.type == "sphere") {
      volume = 4.0 / 3 * pi * z[0] * z[0] * z[0];
      unit = Eigen::Matrix3d::Identity() * volume * 0.4 * z[0] * z[0];
    } else if (s.type == "capsule") {
      const double r = z[0], h = 2 * z[1];
      const double vc = pi * r * r * h, vs = 4.0 / 3 * pi * r * r * r;
      volume = vc + vs;
      const double ixx = vc * (3 * r * r + h * h) / 12 + vs * (0.4 * r * r + h * h / 4 + 3 * h * r / 8);
      unit.diagonal() << ixx, ixx, vc * r * r / 2 + vs * 0.4 * r * r;
    } else if (s.type == "cylinder") {
      const double r = z[0], h = 2 * z[1];
      volume = pi * r * r * h;
      const double ixx = volume * (3 * r * r + h * h) / 12;
      unit.diagonal() << ixx, ixx, volume * r * r / 2;
    } else if (s.type == "ellipsoid") {
      volume = 4.0 / 3 * pi * z[0] * z[1] * z[2];
      unit.diagonal() << volume * (z[1] * z[1] + z[2] * z[2]) / 5, volume * (z[0] * z[0] + z[2] * z[2]) / 5,
          volume * (z[0] * z[0] + z[1] * z[1]) / 5;
    } else if (s.type == "box") {
      volume = 8 * z[0] * z[1] * z[2];
      unit.diagonal() << volume * (z[1] * z[1] + z[2] * z[2]) / 3, volume * (z[0] * z[0] + z[2] * z[2]) / 3,
          volume * (z[0] * z[0] + z[1] * z[1]) / 3;
    } else if (s.type == "mesh") {
      MeshAsset& a = mesh_asset(e, s.mesh);
      physics::TriangleMesh hull;
      const physics::TriangleMesh* m = a.mesh.get();
      if (a.inertia == "convex") {
        hull = physics::convex_hull(m->vertices, doc_.path() + ": mesh " + in_quotes(s.mesh));
        m = &hull;
      } else if (a.inertia == "shell") {
        notes_["shell inertia of meshes is not supported (the enclosed solid is used)"].push_back(s.mesh);
      }
      const MeshMoments mm = mesh_moments(*m, a.inertia == "legacy");
      if (!(mm.volume > 0))
        doc_.fail(e, "mesh " + in_quotes(s.mesh) + " encloses no positive volume (" + format_number(mm.volume) +
                         " m^3): its triangles face inward or it is flat; give the geom mass=\"0\" or an <inertial> to its body");
      volume = mm.volume;
      com = mm.center;
      unit = mm.inertia;
    } else {
      doc_.fail(e, "unknown geom type " + in_quotes(s.type));
    }
    double density = doc_.number_or(e, "density", g.cls, 1000);
    if (const auto m = doc_.numbers(e, "mass", g.cls, 1)) density = volume > 0 ? (*m)[0] / volume : 0;
    if (density < 0) doc_.fail(e, "the geom's mass and density must not be negative");
    if (density == 0 || volume <= 0) return std::nullopt;
    const Eigen::Isometry3d& X = s.X_BG;
    Mass out;
    out.mass = density * volume;
    out.com = X * com;
    out.inertia = X.linear() * (density * unit) * X.linear().transpose();
    return out;
  }

  void body_mass(const XMLElement* b, const std::string& cls, const std::vector<Geom>& geoms, LinkRef at) {
    const std::string& mode = doc_.compiler().inertiafromgeom;
    const XMLElement* in = b->FirstChildElement("inertial");
    Mass m;
    if (in && mode != "true") {
      m.mass = doc_.number_or(in, "mass", cls, -1);
      if (!(m.mass >= 0)) doc_.fail(in, "missing or negative 'mass'");
      const Eigen::Isometry3d X = doc_.pose(in, cls);
      Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
      if (const auto d = doc_.numbers(in, "diaginertia", cls, 3)) {
        I.diagonal() << (*d)[0], (*d)[1], (*d)[2];
      } else if (const auto f = doc_.numbers(in, "fullinertia", cls, 6)) {
        I << (*f)[0], (*f)[3], (*f)[4], (*f)[3], (*f)[1], (*f)[5], (*f)[4], (*f)[5], (*f)[2];
      } else {
        doc_.fail(in, "needs 'diaginertia' or 'fullinertia'");
      }
      m.com = X.translation();
      m.inertia = X.linear() * I * X.linear().transpose();
    } else if (mode != "false") {
      std::vector<Mass> parts;
      for (const Geom& g : geoms)
        if (auto gm = geom_mass(g)) parts.push_back(*gm);
      m = combine(parts);
    }
    // MuJoCo's lower bounds on body mass and principal moments
    const auto& c = doc_.compiler();
    if (c.boundmass > 0 && m.mass < c.boundmass) {
      if (m.mass <= 0) m.com.setZero();
      m.mass = c.boundmass;
    }
    if (c.boundinertia > 0 && m.mass > 0) {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(m.inertia);
      const Eigen::Vector3d moments = es.eigenvalues().cwiseMax(c.boundinertia);
      m.inertia = es.eigenvectors() * moments.asDiagonal() * es.eigenvectors().transpose();
    }
    if (m.mass > 0) {
      if (const std::optional<std::string> defect = physics::inertia_defect(m.inertia.cast<real>())) {
        const std::string& name = model_.bots[at.bot].articulation.links[at.link].name;
        notes_["inertias no mass distribution has were replaced by the nearest physical ones"].push_back(name + " (" + *defect + ")");
        m.inertia = physics::nearest_physical_inertia(m.inertia.cast<real>()).cast<double>();
      }
    }
    builds_[at.bot].masses[at.link] = m;
  }

  // compiler settotalmass: every mass and inertia scaled by one factor
  void apply_total_mass() {
    const auto& target = doc_.compiler().settotalmass;
    if (!target) return;
    double total = 0;
    for (const BotBuild& b : builds_)
      for (const Mass& m : b.masses) total += m.mass;
    if (total <= 0) return;
    const double s = *target / total;
    for (BotBuild& b : builds_)
      for (Mass& m : b.masses) m.mass *= s, m.inertia *= s;
  }

  // ------------------------------------------------------------------ geoms

  // A geom's type, sizes and pose in the body frame (fromto resolved).
  GeomShape geom_shape(const Placed& g) const {
    const XMLElement* e = g.element;
    GeomShape s;
    const char* t = doc_.attr(e, "type", g.cls);
    s.type = t ? t : "sphere";
    if (const char* m = doc_.attr(e, "mesh", g.cls)) s.mesh = m;
    if (const auto z = doc_.numbers(e, "size", g.cls, 0))
      for (size_t k = 0; k < z->size() && k < 3; ++k) s.size[k] = (*z)[k];
    Eigen::Isometry3d X_FG = doc_.pose(e, g.cls);
    if (const auto ft = doc_.numbers(e, "fromto", g.cls, 6)) {
      if (s.type != "capsule" && s.type != "cylinder" && s.type != "box" && s.type != "ellipsoid")
        doc_.fail(e, "fromto is only valid for capsule, cylinder, box and ellipsoid geoms");
      const Eigen::Vector3d a((*ft)[0], (*ft)[1], (*ft)[2]), b((*ft)[3], (*ft)[4], (*ft)[5]);
      if ((b - a).norm() < 1e-12) doc_.fail(e, "attribute 'fromto': the two points coincide");
      X_FG = Eigen::Isometry3d::Identity();
      X_FG.translation() = (a + b) / 2;
      X_FG.linear() = MjcfDocument::z_to(b - a).toRotationMatrix();
      const double half = (b - a).norm() / 2;
      if (s.type == "capsule" || s.type == "cylinder") s.size[1] = half;
      else s.size[2] = half;
      if (s.type == "box" || s.type == "ellipsoid") s.size[1] = s.size[1] > 0 ? s.size[1] : s.size[0];
    }
    s.X_BG = g.X_BF * X_FG;
    auto need = [&](int n) {
      for (int k = 0; k < n; ++k)
        if (!(s.size[k] > 0)) doc_.fail(e, "a " + s.type + " geom needs " + std::to_string(n) + " positive size value(s)");
    };
    if (s.type == "sphere") need(1);
    else if (s.type == "capsule" || s.type == "cylinder") need(2);
    else if (s.type == "box" || s.type == "ellipsoid") need(3);
    else if (s.type == "mesh" && s.mesh.empty()) doc_.fail(e, "a mesh geom needs a 'mesh'");
    return s;
  }

  // The collision shape of a geom, in its frame; nullopt (with a note) when it has none.
  std::optional<ShapeGeometry> collision_shape(const Placed& g, const GeomShape& s) {
    const Eigen::Vector3d& z = s.size;
    const std::string where = doc_.path() + ": " + MjcfDocument::label(g.element);
    if (s.type == "sphere") return physics::SphereShape{Vec3::Zero(), real(z[0])};
    if (s.type == "capsule") return physics::CapsuleShape{real(z[0]), real(z[1])};
    if (s.type == "box") return physics::BoxShape{z.cast<real>()};
    if (s.type == "plane") return physics::PlaneShape{};
    if (s.type == "cylinder") return physics::make_mesh_shape(cylinder_mesh(z[0], 2 * z[1]), where + " (cylinder)");
    if (s.type == "ellipsoid") return physics::make_mesh_shape(ellipsoid_mesh(z.cast<real>()), where + " (ellipsoid)");
    if (s.type == "mesh") {
      MeshAsset& a = mesh_asset(g.element, s.mesh);
      if (!a.collider) {
        std::string warning;
        const std::string source = a.file.empty() ? doc_.path() + ": mesh " + in_quotes(s.mesh) : a.file.string();
        a.collider = mesh_collider(*a.mesh, source, options_.mesh_collision, &warning);
        if (!warning.empty()) doc_.warn(a.element, warning);
      }
      return a.collider;
    }
    notes_["geoms of type " + s.type + " are not imported"].push_back(MjcfDocument::label(g.element));
    return std::nullopt;
  }

  void add_geoms(LinkRef at, const std::vector<Geom>& geoms, bool moving) {
    LinkDesc& L = model_.bots[at.bot].articulation.links[at.link];
    for (const Geom& geom : geoms) {
      const Placed& g = geom.placed;
      const GeomShape& s = geom.shape;
      Filter f;
      f.contype = static_cast<int>(doc_.number_or(g.element, "contype", g.cls, 1));
      f.conaffinity = static_cast<int>(doc_.number_or(g.element, "conaffinity", g.cls, 1));
      if (f.contype == 0 && f.conaffinity == 0) continue;  // visual only
      if (moving && s.type == "plane") doc_.fail(g.element, "a plane geom must belong to the world or a body welded to it");
      std::optional<ShapeGeometry> shape = collision_shape(g, s);
      if (!shape) continue;
      const Transform X_LS = to_transform(s.X_BG);
      const std::string file = s.type == "mesh" ? meshes_.at(s.mesh).file.string() : "";
      if (!L.shape) {
        L.shape = std::move(shape);
        L.link_from_shape = X_LS;
        L.shape_file = file;
        if (const auto fr = doc_.numbers(g.element, "friction", g.cls, 0)) L.contact.coulomb_friction_coefficient = real((*fr)[0]);
        else L.contact.coulomb_friction_coefficient = 1;  // MuJoCo's default sliding friction
      } else {
        L.extra_shapes.push_back({std::move(*shape), X_LS, file});
      }
      builds_[at.bot].filters[at.link].push_back(f);
    }
  }

  // ------------------------------------------------------------------ contact, finishing

  void read_contact() {
    for (const XMLElement* c = doc_.root()->FirstChildElement("contact"); c; c = c->NextSiblingElement("contact")) {
      for (const XMLElement* x = c->FirstChildElement("exclude"); x; x = x->NextSiblingElement("exclude")) {
        const char* b1 = x->Attribute("body1");
        const char* b2 = x->Attribute("body2");
        if (!b1 || !b2) doc_.fail(x, "needs 'body1' and 'body2'");
        const auto i1 = body_link_.find(b1), i2 = body_link_.find(b2);
        if (i1 == body_link_.end() || i2 == body_link_.end())
          doc_.fail(x, "refers to body " + in_quotes(i1 == body_link_.end() ? b1 : b2) + ", which is not defined");
        if (i1->second.bot != i2->second.bot) {
          notes_["contact exclusions between separate free bodies are not imported"].push_back(std::string(b1) + "/" + b2);
          continue;
        }
        const auto& links = model_.bots[i1->second.bot].articulation.links;
        excluded_.insert({i1->second.bot, links[i1->second.link].name, links[i2->second.link].name});
      }
      for (const XMLElement* p = c->FirstChildElement("pair"); p; p = p->NextSiblingElement("pair"))
        notes_["explicit contact pairs are not imported (geoms collide by their contype and conaffinity)"].push_back(
            p->Attribute("name") ? p->Attribute("name") : MjcfDocument::label(p));
    }
  }

  void note_unsupported() {
    const XMLElement* root = doc_.root();
    static const std::pair<const char*, const char*> kSections[] = {
        {"sensor", "sensors are not imported"},
        {"deformable", "deformable bodies are not imported"},  {"skin", "skins are not imported"},
    };
    for (const auto& [section, what] : kSections)
      for (const XMLElement* s = root->FirstChildElement(section); s; s = s->NextSiblingElement(section))
        for (const XMLElement* e = s->FirstChildElement(); e; e = e->NextSiblingElement())
          notes_[what].push_back(name_or_kind(e));
  }

  // ------------------------------------------------------------------ actuators

  // MuJoCo's joint actuators as IDEAL_PD actuators on their joint's link (joint effort =
  // gear x actuator force, actuator length = gear x q): <motor> passes the effort command
  // through (the joint's torque or force: ctrl x gear); <position kp kv> is kp g^2 (q_cmd - q) -
  // kv g^2 v with q_cmd = ctrl / g; <velocity kv> is kv g^2 (v_cmd - v); <general> with a fixed
  // gain and no bias is a motor, with an affine bias (0, -kp, -kv) a position actuator.
  // forcerange x |gear| bounds the effort (forcelimited, or auto with autolimits). ctrlrange is
  // left to the controller that issues the commands; until one does, a position servo holds
  // MuJoCo's ctrl = 0 (within ctrlrange), as MuJoCo's does.
  void read_actuators() {
    for (const XMLElement* sec = doc_.root()->FirstChildElement("actuator"); sec; sec = sec->NextSiblingElement("actuator"))
      for (const XMLElement* e = sec->FirstChildElement(); e; e = e->NextSiblingElement()) {
        const std::string kind = e->Name();
        const std::string label = name_or_kind(e);
        const char* joint = doc_.attr(e, "joint", "");
        if (!joint) {
          notes_["actuators on tendons, sites and bodies are not imported"].push_back(label);
          continue;
        }
        const auto it = joint_link_.find(joint);
        if (it == joint_link_.end()) doc_.fail(e, "refers to joint " + in_quotes(joint) + ", which is not defined");
        const LinkRef at = it->second;
        BotPrefab& bot = model_.bots[at.bot];
        const JointDesc& J = bot.articulation.joints[at.link];
        if (J.type != JointType::Revolute && J.type != JointType::Prismatic) {
          notes_["actuators on ball joints are not imported"].push_back(label);
          continue;
        }
        const auto gears = doc_.numbers(e, "gear", "", 0);
        const double gear = gears ? (*gears)[0] : 1.0;
        double kp = 0, kd = 0;
        if (kind == "position") {
          kp = doc_.number_or(e, "kp", "", 1);
          kd = doc_.number_or(e, "kv", "", 0);
        } else if (kind == "velocity") {
          kd = doc_.number_or(e, "kv", "", 1);
        } else if (kind == "general") {
          const char* bias = doc_.attr(e, "biastype", "");
          const auto gain = doc_.numbers(e, "gainprm", "", 0);
          const auto bp = doc_.numbers(e, "biasprm", "", 0);
          const char* gain_kind = doc_.attr(e, "gaintype", "");
          const std::string gaintype = gain_kind ? gain_kind : "fixed";
          const double g0 = gain ? (*gain)[0] : 1;
          auto b = [&](size_t k) { return bp && bp->size() > k ? (*bp)[k] : 0.0; };
          if (gaintype != "fixed") {
            notes_["actuators with a non-fixed gain are not imported"].push_back(label);
            continue;
          }
          if (!bias || std::string(bias) == "none") {
            if (g0 != 1) notes_["general actuators' gains scale the effort command (give the joint effort)"].push_back(label);
          } else if (std::string(bias) == "affine" && b(0) == 0 && b(1) == -g0) {
            kp = g0;
            kd = -b(2);
          } else {
            notes_["general actuators with this bias are not imported"].push_back(label);
            continue;
          }
        } else if (kind != "motor") {
          notes_["actuators of kind <" + kind + "> are not imported"].push_back(label);
          continue;
        }
        kp *= gear * gear;
        kd *= gear * gear;
        double effort_limit = -1;
        const auto range = doc_.numbers(e, "forcerange", "", 2);
        const std::optional<bool> limited = doc_.boolean(e, "forcelimited", "");
        if (range && (limited ? *limited : doc_.compiler().autolimits)) {
          effort_limit = std::max(std::abs((*range)[0]), std::abs((*range)[1])) * std::abs(gear);
          if ((*range)[0] != -(*range)[1]) notes_["asymmetric force ranges are imported as symmetric bounds"].push_back(label);
        }
        if (kp < 0 || kd < 0) doc_.fail(e, "kp and kv must not be negative");
        std::ostringstream params;
        params.precision(17);
        params << "{\"kp\": " << kp << ", \"kd\": " << kd << ", \"effort_limit\": " << effort_limit;
        // until commanded, a servo holds MuJoCo's ctrl = 0 (clamped to ctrlrange where limited):
        // the joint target ctrl / gear
        if (kp > 0) {
          double ctrl = 0;
          const auto ctrlrange = doc_.numbers(e, "ctrlrange", "", 2);
          const std::optional<bool> ctrl_limited = doc_.boolean(e, "ctrllimited", "");
          if (ctrlrange && (ctrl_limited ? *ctrl_limited : doc_.compiler().autolimits)) ctrl = std::clamp(0.0, (*ctrlrange)[0], std::max((*ctrlrange)[0], (*ctrlrange)[1]));
          params << ", \"default_position\": " << ctrl / gear;
        }
        params << "}";
        ComponentDecl d;
        d.type = "IDEAL_PD";
        d.name = label;
        auto& names = builds_[at.bot].actuator_names;
        for (int k = 1; names.count(d.name); ++k) d.name = label + "_" + std::to_string(k);
        names.insert(d.name);
        d.params = params.str();
        bot.actuators[at.link].push_back(std::move(d));
      }
  }

  // <equality><joint joint1 joint2 polycoef="c0 c1 ..."/>: q1 = c0 + c1 q2 as a joint coupling
  // (higher polynomial terms are not imported); other equality constraints are named in a warning.
  void read_equalities() {
    for (const XMLElement* sec = doc_.root()->FirstChildElement("equality"); sec; sec = sec->NextSiblingElement("equality"))
      for (const XMLElement* e = sec->FirstChildElement(); e; e = e->NextSiblingElement()) {
        const std::string label = name_or_kind(e);
        const std::string kind = e->Name();
        if (const auto active = doc_.boolean(e, "active", ""); active && !*active) continue;
        if (kind != "joint") {
          notes_["equality constraints of kind <" + kind + "> are not imported"].push_back(label);
          continue;
        }
        const char* j1 = e->Attribute("joint1");
        const char* j2 = e->Attribute("joint2");
        if (!j1) doc_.fail(e, "missing required attribute 'joint1'");
        const auto f = joint_link_.find(j1);
        if (f == joint_link_.end()) doc_.fail(e, "refers to joint " + in_quotes(j1) + ", which is not defined");
        const auto coef = doc_.numbers(e, "polycoef", "", 0);
        auto c = [&](size_t k) { return coef && coef->size() > k ? (*coef)[k] : (k == 1 ? 1.0 : 0.0); };
        if (!j2) {
          notes_["joint equalities that fix a joint (no joint2) are not imported"].push_back(label);
          continue;
        }
        const auto l = joint_link_.find(j2);
        if (l == joint_link_.end()) doc_.fail(e, "refers to joint " + in_quotes(j2) + ", which is not defined");
        if (f->second.bot != l->second.bot) {
          notes_["joint equalities between separate bots are not imported"].push_back(label);
          continue;
        }
        if (c(2) != 0 || c(3) != 0 || c(4) != 0) notes_["joint equalities' quadratic and higher terms are not imported"].push_back(label);
        auto& art = model_.bots[f->second.bot].articulation;
        const JointType t1 = art.joints[f->second.link].type, t2 = art.joints[l->second.link].type;
        auto one_dof = [](JointType t) { return t == JointType::Revolute || t == JointType::Prismatic; };
        if (!one_dof(t1) || !one_dof(t2)) {
          notes_["joint equalities on ball joints are not imported"].push_back(label);
          continue;
        }
        art.couplings.push_back({j1, j2, real(c(1)), real(c(0))});
      }
  }

  // <tendon><fixed>: the length sum_k coef_k q_k of joints of one bot as a FixedTendon, with its
  // range (limited, or auto with autolimits), stiffness, damping and springlength (-1, the
  // default: the length at the joints' springref); joint springs as one-joint tendons named "<joint>/spring".
  // Spatial tendons, tendon friction and armature, and spring deadbands are named in warnings.
  void read_tendons() {
    for (const JointSpring& js : joint_springs_) {
      const LinkRef at = joint_link_.at(js.joint);
      physics::FixedTendon t;
      t.name = js.joint + "/spring";
      t.joints = {js.joint};
      t.coefficients = {1};
      t.stiffness = real(js.stiffness);
      t.rest_length = real(joint_springref_.at(js.joint));
      model_.bots[at.bot].articulation.fixed_tendons.push_back(std::move(t));
    }
    for (const XMLElement* sec = doc_.root()->FirstChildElement("tendon"); sec; sec = sec->NextSiblingElement("tendon"))
      for (const XMLElement* e = sec->FirstChildElement(); e; e = e->NextSiblingElement()) {
        const std::string label = name_or_kind(e);
        if (std::string(e->Name()) != "fixed") {
          notes_["spatial tendons are not imported"].push_back(label);
          continue;
        }
        physics::FixedTendon t;
        t.name = label;
        int bot = -1;
        double spring_length = 0;  // at MuJoCo's qpos_spring
        bool importable = true;
        for (const XMLElement* j = e->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
          const char* jn = j->Attribute("joint");
          if (!jn) doc_.fail(j, "missing required attribute 'joint'");
          const auto it = joint_link_.find(jn);
          if (it == joint_link_.end()) doc_.fail(j, "refers to joint " + in_quotes(jn) + ", which is not defined");
          const JointType type = model_.bots[it->second.bot].articulation.joints[it->second.link].type;
          if (type != JointType::Revolute && type != JointType::Prismatic) {
            notes_["tendons over ball joints are not imported"].push_back(label);
            importable = false;
            break;
          }
          if (bot >= 0 && bot != it->second.bot) {
            notes_["tendons across separate bots are not imported"].push_back(label);
            importable = false;
            break;
          }
          bot = it->second.bot;
          const double coef = doc_.number_or(j, "coef", "", 1);
          t.joints.push_back(jn);
          t.coefficients.push_back(real(coef));
          spring_length += coef * joint_springref_.at(jn);
        }
        if (!importable) continue;
        if (bot < 0) doc_.fail(e, "a fixed tendon needs at least one <joint>");
        const auto range = doc_.numbers(e, "range", "", 2);
        const std::optional<bool> limited = doc_.boolean(e, "limited", "");
        if (limited ? *limited : (doc_.compiler().autolimits && range.has_value())) {
          if (!range) doc_.fail(e, "a limited tendon needs a 'range'");
          if ((*range)[0] > (*range)[1])
            doc_.fail(e, "attribute 'range': the lower limit " + format_number((*range)[0]) + " exceeds the upper limit " +
                             format_number((*range)[1]));
          double lo = (*range)[0], hi = (*range)[1];
          narrow_by_margin(e, "", lo, hi);
          t.has_lower = t.has_upper = true;
          t.lower = real(lo);
          t.upper = real(hi);
        }
        t.stiffness = real(doc_.number_or(e, "stiffness", "", 0));
        t.damping = real(doc_.number_or(e, "damping", "", 0));
        if (t.stiffness < 0 || t.damping < 0) doc_.fail(e, "stiffness and damping must not be negative");
        const auto spring = doc_.numbers(e, "springlength", "", 0);
        if (spring && spring->size() > 2) doc_.fail(e, "attribute 'springlength': expected 1 or 2 numbers");
        t.rest_length = real(spring && (*spring)[0] >= 0 ? (*spring)[0] : spring_length);
        if (spring && spring->size() == 2 && (*spring)[1] != (*spring)[0])
          notes_["tendon spring deadbands are not imported (the spring pulls towards the first springlength)"].push_back(label);
        if (doc_.number_or(e, "frictionloss", "", 0) != 0) notes_["tendon friction is not imported"].push_back(label);
        if (doc_.number_or(e, "armature", "", 0) != 0) notes_["tendon armature is not imported"].push_back(label);
        model_.bots[bot].articulation.fixed_tendons.push_back(std::move(t));
      }
  }

  // An element's name, or for an unnamed one its kind and what it acts on: "<motor joint='hip'>"
  static std::string name_or_kind(const XMLElement* e) {
    if (const char* n = e->Attribute("name"); n && *n) return n;
    std::string out = std::string("<") + e->Name();
    for (const char* key : {"joint", "tendon", "site", "body", "body1", "joint1", "geom1"})
      if (const char* v = e->Attribute(key)) {
        out += std::string(" ") + key + "=" + in_quotes(v);
        break;
      }
    return out + ">";
  }

  static bool filters_pass(const std::vector<Filter>& a, const std::vector<Filter>& b) {
    for (const Filter& x : a)
      for (const Filter& y : b)
        if ((x.contype & y.conaffinity) || (y.contype & x.conaffinity)) return true;
    return false;
  }

  void finish(int bot) {
    BotPrefab& p = model_.bots[bot];
    auto& art = p.articulation;
    p.source = doc_.path();
    p.base_dir = doc_.dir().string();
    const BotBuild& build = builds_[bot];
    for (size_t l = 0; l < art.links.size(); ++l) set_mass(art.links[l], build.masses[l]);
    const auto& pose = build.default_pose;
    if (std::any_of(pose.begin(), pose.end(), [](real q) { return q != 0; })) art.default_pose = pose;
    const int n = static_cast<int>(art.links.size());
    // the rigid body (welded group) each link belongs to: its nearest ancestor on a moving joint
    std::vector<int> weld(n);
    for (int l = 0; l < n; ++l) weld[l] = (l == 0 || art.joints[l].type != JointType::Hard) ? l : weld[art.links[l].parent_link];
    // links whose rigid body hangs by a joint from the world's (the world bot's link 0 and what
    // is welded to it)
    std::vector<bool> hangs_from_world(n, false);
    for (int l = 0; l < n; ++l) {
      const int p = art.links[weld[l]].parent_link;
      hangs_from_world[l] = bot == 0 && p >= 0 && weld[p] == 0;
    }
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) {
        if (build.filters[a].empty() || build.filters[b].empty() || weld[a] == weld[b]) continue;
        const std::string &na = art.links[a].name, &nb = art.links[b].name;
        const bool excluded = excluded_.count({bot, na, nb}) || excluded_.count({bot, nb, na});
        const bool pass = !excluded && filters_pass(build.filters[a], build.filters[b]);
        // pairs the default leaves on unless filtered; bodies hanging by a joint from the
        // world's rigid body (which the default switches off) collide with it, as in MuJoCo
        if (!pass) art.contact_overrides.push_back({na, nb, false});
        else if (weld[a] == 0 && hangs_from_world[b]) art.contact_overrides.push_back({na, nb, true});
      }
    exclude_overlaps(bot, weld, hangs_from_world);
    p.sensors.resize(art.links.size());
    p.actuators.resize(art.links.size());
  }

  // Link pairs that collide and whose shapes already interpenetrate at the start pose (capsules
  // that meet at the joint between them, as models often draw limbs) would push on each other
  // from the first step, at a point their joint cannot move: they are switched off, named in one
  // warning. A link's contact with the world body's own geoms is kept unless it hangs from the
  // world by a joint (a foot that starts in the floor must still stand on it), and so is its
  // contact with a body welded to the world that it does not hang from (a table); a welded body's
  // overlaps with the links below it (an arm's base and its own arm) are switched off.
  void exclude_overlaps(int bot, const std::vector<int>& weld, const std::vector<bool>& hangs_from_world) {
    auto& art = model_.bots[bot].articulation;
    auto below = [&](int root, int l) {
      for (int x = l; x >= 0; x = art.links[x].parent_link)
        if (x == root) return true;
      return false;
    };
    // whether welded link w keeps its contact with `other` though they overlap
    auto keeps = [&](int w, int other) {
      if (bot != 0 || weld[w] != 0) return false;
      return w == 0 ? !hangs_from_world[other] : !below(w, other);
    };
    const auto overlaps = physics::overlapping_link_pairs(art, 0, doc_.path());
    for (const auto& o : overlaps) {
      const int a = o.link_a, b = o.link_b;
      if (keeps(a, b) || keeps(b, a)) continue;
      const std::string &na = art.links[a].name, &nb = art.links[b].name;
      bool found = false;
      for (auto& ov : art.contact_overrides)
        if ((ov.link_a == na && ov.link_b == nb) || (ov.link_a == nb && ov.link_b == na)) ov.enable = false, found = true;
      if (!found) art.contact_overrides.push_back({na, nb, false});
      notes_["link pairs whose shapes overlap at the start pose do not collide with each other"].push_back(na + "/" + nb);
    }
  }

  MjcfDocument doc_;
  MjcfImportOptions options_;
  MjcfModel model_;
  std::map<std::string, MeshAsset> meshes_;
  std::map<std::string, LinkRef> body_link_, joint_link_;
  std::map<std::string, double> joint_springref_;  // per hinge and slide joint: MuJoCo's qpos_spring
  struct JointSpring {
    std::string joint;
    double stiffness;
  };
  std::vector<JointSpring> joint_springs_;
  std::vector<BotBuild> builds_;  // per bot
  std::set<std::tuple<int, std::string, std::string>> excluded_;
  std::map<std::string, std::vector<std::string>> notes_;
  int body_count_ = 0, joint_count_ = 0;
  double smallest_mass_ = std::numeric_limits<double>::infinity(), smallest_moment_ = std::numeric_limits<double>::infinity();
};

}  // namespace

MjcfModel load_mjcf(const std::string& path, std::vector<std::string>* warnings, const MjcfImportOptions& options) {
  return MjcfImporter(path, warnings, options).run();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
